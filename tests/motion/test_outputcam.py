"""Output cam core (interpreter/motion/outputcam.py) against hand-computed switch instants.

The axis moves at constant velocity in every test, so positions are x(t) = x0 + v t and
the instant of a switch at cam position y is t = (y - x0) / v (cam = axis when CamArm =
AxisArm). Expected values are worked out in the comments (SPEC 9.27 formulas).
"""

from __future__ import annotations

import numpy as np
import pytest

from interpreter.motion.outputcam import (
    COMPLETE,
    ENDED,
    LOCKED,
    PENDING_STARTED,
    ArmRequest,
    OutputCamSet,
)
from interpreter.motion.outputcam_tables import (
    DisarmType,
    OutputCamExecutionMode,
    OutputCamExecutionSchedule,
    PositionReference,
    check_compensation,
    check_output_cam,
    columns_from_records,
    error_code,
)

ONCE = OutputCamExecutionMode.ONCE
CONT = OutputCamExecutionMode.CONTINUOUS
PERSIST = OutputCamExecutionMode.PERSISTENT
IMM = OutputCamExecutionSchedule.IMMEDIATE
PEND = OutputCamExecutionSchedule.PENDING
FWD = OutputCamExecutionSchedule.FORWARD_ONLY
REV = OutputCamExecutionSchedule.REVERSE_ONLY
BI = OutputCamExecutionSchedule.BIDIRECTIONAL
DT = 0.001
US = 1e-6


def cam(*elements: dict, start: float = 0.0, end: float = 100.0):
    cols = columns_from_records(list(elements), "OUTPUT_CAM")
    return check_output_cam(cols, start, end)


def comp(**by_bit: dict):
    recs = [by_bit.get(f"b{i}", {}) for i in range(1 + max(int(k[1:]) for k in by_bit))]
    return check_compensation(columns_from_records(recs, "OUTPUT_COMPENSATION"))


def window(bit=0, left=10.0, right=20.0, latch=1, unlatch=1, **more) -> dict:
    return {"OutputBit": bit, "LatchType": latch, "UnlatchType": unlatch, "Left": left,
            "Right": right, **more}  # fmt: skip


def request(elements, handle=1, mode=ONCE, sched=IMM, start=0.0, end=100.0, axis_arm=0.0,
            cam_arm=0.0, ref=PositionReference.ACTUAL) -> ArmRequest:  # fmt: skip
    return ArmRequest(handle, elements, start, end, mode, sched, axis_arm, cam_arm, ref)


class Axis:
    """One axis moving at piecewise constant velocity, updated every DT."""

    def __init__(self, x0: float = 0.0, v: float = 100.0) -> None:
        self.x = x0
        self._v = v
        self.n = 0
        self._base = (x0, 0)  # positions from the last velocity change, not accumulated

    @property
    def v(self) -> float:
        return self._v

    @v.setter
    def v(self, value: float) -> None:
        self._v = value
        self._base = (self.x, self.n)

    def position(self, n: int) -> float:
        x, n0 = self._base
        return x + self._v * (n - n0) * DT

    def run(self, s: OutputCamSet, seconds: float, unwind: float = 0.0):
        edges, events = [], []
        for _ in range(round(seconds / DT)):
            t0 = self.n * DT
            x1 = self.position(self.n + 1)
            if unwind:
                x1 %= unwind
            start = np.array([[self.x], [self.x]])
            end = np.array([[x1], [x1]])
            step = s.update(t0, DT, start, end, unwind=np.array([unwind]))
            edges += [(e.bit, e.time, e.value) for e in step.edges]
            events += [(e.handle, e.kind, e.time) for e in step.events]
            self.x = x1
            self.n += 1
        return edges, events


def times(edges, bit=0):
    return [(round(t, 9), v) for b, t, v in edges if b == bit]


def assert_edges(edges, expected, bit=0):
    got = [(t, v) for b, t, v in edges if b == bit]
    assert [v for _, v in got] == [v for _, v in expected], got
    for (t, _), (te, _) in zip(got, expected, strict=True):
        assert t == pytest.approx(te, abs=US), got


def arm(s, el, check=None, compensation=None, axis=0, target=0, **kw):
    r = s.arm(axis, target, request(el, **kw), compensation)
    assert r.armed
    return r


# -- position latch/unlatch, narrow window -------------------------------------------------
def test_position_window_switches_at_exact_instants() -> None:
    s = OutputCamSet()
    el, chk = cam(window(left=10.0, right=20.0))
    assert chk.ok
    arm(s, el)
    edges, _ = Axis(0.0, 100.0).run(s, 0.5)
    # x = 100 t: on at x = 10 -> t = 0.1, off when leaving x = 20 -> t = 0.2
    assert_edges(edges, [(0.1, True), (0.2, False)])
    assert s.targets[(0, 0)].output == 0


def test_narrow_window_inside_one_update_is_switched_on_and_off_once_per_pass() -> None:
    # v = 2000 u/s, 2 u per 1 ms update; window [10.3, 10.9] is 0.6 u wide (< 2 u).
    # Continuous over [0, 100]: a pass takes 100 / 2000 = 0.05 s.
    # on at 10.3 / 2000 = 5.15 ms, off at 10.9 / 2000 = 5.45 ms, then + 50 ms per pass.
    s = OutputCamSet()
    el, _ = cam(window(left=10.3, right=10.9))
    arm(s, el, mode=CONT)
    edges, _ = Axis(0.0, 2000.0).run(s, 0.12)
    exp = []
    for k in range(3):
        exp += [(0.00515 + 0.05 * k, True), (0.00545 + 0.05 * k, False)]
    assert_edges(edges, exp)


def test_zero_width_window_reports_both_edges_at_the_same_instant() -> None:
    # LatchDelay 0.002, UnlatchDelay 0.004 at v = 100: lo = 10 - 0.2 = 9.8,
    # hi = 10.1 - 0.4 = 9.7 < lo -> width raised to the minimum (0): on and off at 9.8
    s = OutputCamSet()
    el, _ = cam(window(left=10.0, right=10.1))
    c, _ = comp(b0={"LatchDelay": 0.002, "UnlatchDelay": 0.004})
    arm(s, el, compensation=c)
    edges, _ = Axis(0.0, 100.0).run(s, 0.2)
    assert_edges(edges, [(0.098, True), (0.098, False)])


def test_minimum_width_widens_a_collapsed_window() -> None:
    # same as above with min_width 0.5: window [9.8, 10.3] -> on 0.098 s, off 0.103 s
    s = OutputCamSet(min_width=0.5)
    el, _ = cam(window(left=10.0, right=10.1))
    c, _ = comp(b0={"LatchDelay": 0.002, "UnlatchDelay": 0.004})
    arm(s, el, compensation=c)
    edges, _ = Axis(0.0, 100.0).run(s, 0.2)
    assert_edges(edges, [(0.098, True), (0.103, False)])


# -- compensation arithmetic ---------------------------------------------------------------
def test_offset_and_delays_forward() -> None:
    # Left + Offset - v*LatchDelay = 20 + 2 - 100*0.01 = 21 -> t = 0.21
    # Right + Offset - v*UnlatchDelay = 30 + 2 - 100*0.02 = 30 -> leaves at t = 0.30
    s = OutputCamSet()
    el, _ = cam(window(left=20.0, right=30.0))
    c, _ = comp(b0={"Offset": 2.0, "LatchDelay": 0.01, "UnlatchDelay": 0.02})
    arm(s, el, compensation=c)
    edges, _ = Axis(0.0, 100.0).run(s, 0.5)
    assert_edges(edges, [(0.21, True), (0.30, False)])


def test_offset_and_delays_mirrored_in_reverse() -> None:
    # v = -100 from x = 50 (cam arm 50): latch edge is Right: 30 + 2 - (-100)(0.01) = 33
    # -> t = (50 - 33) / 100 = 0.17; unlatch edge Left: 20 + 2 + 100*0.02 = 24 -> t = 0.26
    s = OutputCamSet()
    el, _ = cam(window(left=20.0, right=30.0))
    c, _ = comp(b0={"Offset": 2.0, "LatchDelay": 0.01, "UnlatchDelay": 0.02})
    arm(s, el, compensation=c, axis_arm=50.0, cam_arm=50.0)
    edges, _ = Axis(50.0, -100.0).run(s, 0.4)
    assert_edges(edges, [(0.17, True), (0.26, False)])


def test_duration_unlatch_uses_compensated_duration() -> None:
    # latch at 20 - 100*0.01 = 19 -> t = 0.19; Duration + LatchDelay - UnlatchDelay =
    # 0.05 + 0.01 - 0.02 = 0.04 -> off at 0.23
    s = OutputCamSet()
    el, _ = cam(window(left=20.0, right=30.0, unlatch=2, Duration=0.05))
    c, _ = comp(b0={"LatchDelay": 0.01, "UnlatchDelay": 0.02})
    arm(s, el, compensation=c)
    edges, _ = Axis(0.0, 100.0).run(s, 0.5)
    assert_edges(edges, [(0.19, True), (0.23, False)])


# -- enable latch/unlatch types -------------------------------------------------------------
def test_enable_latch_and_unlatch_follow_input_edges() -> None:
    # Enable/Enable on Input bit 3: the words are sampled per update, so edges fall at
    # the start of the update after the input changed.
    s = OutputCamSet()
    el, chk = cam(window(latch=2, unlatch=3, EnableType=0, EnableBit=3))
    assert chk.ok
    arm(s, el)
    ax = Axis(0.0, 100.0)
    ax.run(s, 0.01)  # input off: nothing
    s.targets[(0, 0)].input = 1 << 3
    e1, _ = ax.run(s, 0.01)  # rises at the update at t = 0.010
    s.targets[(0, 0)].input = 0
    e2, _ = ax.run(s, 0.01)  # falls at t = 0.020
    assert_edges(e1 + e2, [(0.010, True), (0.020, False)])


def test_inverted_input_enable_and_position_and_enable() -> None:
    # Position and Enable latch with Inverted Input bit 0: input 1 -> not enabled, so
    # entering [10, 20] at t = 0.1 does not latch; input cleared at the update at
    # t = 0.15 (x = 15, inside) -> latches at 0.15; Position and Enable unlatch -> leaves
    # at x = 20, t = 0.2
    s = OutputCamSet()
    el, _ = cam(window(latch=3, unlatch=4, EnableType=1, EnableBit=0))
    arm(s, el)
    s.targets[(0, 0)].input = 1
    ax = Axis(0.0, 100.0)
    e1, _ = ax.run(s, 0.15)
    s.targets[(0, 0)].input = 0
    e2, _ = ax.run(s, 0.1)
    assert_edges(e1 + e2, [(0.15, True), (0.2, False)])


def test_duration_and_enable_ends_early_when_enable_drops() -> None:
    # latch Position at 10 (t 0.1), Duration 1 s, Output-word bit 5 enable; the program
    # clears Output bit 5 before the update at t = 0.12 -> reset at 0.12
    s = OutputCamSet()
    el, _ = cam(window(unlatch=5, Duration=1.0, EnableType=2, EnableBit=5))
    arm(s, el)
    s.targets[(0, 0)].output = 1 << 5
    ax = Axis(0.0, 100.0)
    e1, _ = ax.run(s, 0.12)
    s.targets[(0, 0)].output &= ~(1 << 5)
    e2, _ = ax.run(s, 0.05)
    assert_edges(e1 + e2, [(0.1, True), (0.12, False)])


def test_inactive_latch_and_unlatch_leave_the_bit() -> None:
    s = OutputCamSet()
    el, _ = cam(window(latch=0, unlatch=1), window(bit=1, latch=1, unlatch=0))
    arm(s, el)
    edges, _ = Axis(0.0, 100.0).run(s, 0.5)
    # bit 0 never latches; bit 1 latches at 0.1 and is never reset
    assert times(edges, 0) == []
    assert_edges(edges, [(0.1, True)], bit=1)


# -- modes ----------------------------------------------------------------------------------
def test_inverted_mode() -> None:
    s = OutputCamSet()
    el, _ = cam(window())
    c, _ = comp(b0={"Mode": 1})
    s.targets.clear()
    arm(s, el, compensation=c)
    s.targets[(0, 0)].output = 1  # bit on before the window
    edges, _ = Axis(0.0, 100.0).run(s, 0.5)
    assert_edges(edges, [(0.1, False), (0.2, True)])


def test_pulsed_and_inverted_pulsed_modes() -> None:
    # window [10, 20] active 0.1..0.2 s; CycleTime 0.04, DutyCycle 25 % -> on 0.01 s:
    # pulses on at 0.10, 0.14, 0.18; off at 0.11, 0.15, 0.19; reset at 0.2 (already off)
    s = OutputCamSet()
    el, _ = cam(window(), window(bit=1))
    c, chk = comp(b0={"Mode": 2, "CycleTime": 0.04, "DutyCycle": 25},
                  b1={"Mode": 3, "CycleTime": 0.04, "DutyCycle": 25})  # fmt: skip
    assert chk.ok
    arm(s, el, compensation=c)
    s.targets[(0, 0)].output = 0b10  # inverted-and-pulsed bit rests on
    edges, _ = Axis(0.0, 100.0).run(s, 0.5)
    on_off = [(0.10, True), (0.11, False), (0.14, True), (0.15, False), (0.18, True),
              (0.19, False)]  # fmt: skip
    assert_edges(edges, on_off)
    # bit 1 is the inverse while active; the set at the window end (0.2) finds it already
    # on (off-duty since 0.19), so no extra edge
    assert_edges(edges, [(t, not v) for t, v in on_off], bit=1)


# -- execution modes ------------------------------------------------------------------------
def test_once_completes_when_leaving_the_range() -> None:
    # cam range [0, 100], v = 100: leaves at x = 100, t = 1.0 -> PC; a window past that
    # never switches again
    s = OutputCamSet()
    el, _ = cam(window())
    arm(s, el)
    edges, events = Axis(0.0, 100.0).run(s, 2.5)
    assert_edges(edges, [(0.1, True), (0.2, False)])
    assert [(h, k) for h, k, _ in events] == [(1, LOCKED), (1, COMPLETE)]
    assert events[1][2] == pytest.approx(1.0, abs=US)
    assert s.status_words(0)["OutputCamStatus"] == 0


def test_continuous_wraps_the_cam_range() -> None:
    # range [50, 150] (span 100), cam arm 50 at axis 0: cam = 50 + x; window [60, 70]
    # -> x in [10, 20] + 100 k: on at 0.1, 1.1, 2.1 s; off at 0.2, 1.2, 2.2 s
    s = OutputCamSet()
    el, _ = cam(window(left=60.0, right=70.0), start=50.0, end=150.0)
    arm(s, el, mode=CONT, start=50.0, end=150.0, cam_arm=50.0)
    edges, _ = Axis(0.0, 100.0).run(s, 2.5)
    exp = [(x, v) for k in range(3) for x, v in ((0.1 + k, True), (0.2 + k, False))]
    assert_edges(edges, exp)


def test_continuous_on_a_rotary_axis_that_unwinds() -> None:
    # axis unwinds at 360, cam range [0, 360]: window [350, 370]... clamp: Right 370 is past
    # the end -> 360 with ERR 36; window [350, 360] on at 3.5 s, off when leaving 360 = wrap
    # instant 3.6 s (the wrap leaves the window), then again + 3.6 s.
    s = OutputCamSet()
    el, chk = cam(window(left=350.0, right=370.0), end=360.0)
    assert (chk.error, chk.segment) == (error_code("Illegal Output Cam"), 0)
    arm(s, el, mode=CONT, end=360.0)
    edges, _ = Axis(0.0, 100.0).run(s, 7.3, unwind=360.0)
    assert_edges(edges, [(3.5, True), (3.6, False), (7.1, True), (7.2, False)])


def test_persistent_disarms_outside_and_rearms_on_return() -> None:
    # range [0, 30]; forward to x = 40 (0.4 s) then back at -100: re-enters at 30 (t 0.5),
    # window [10, 20] mirrored: on at 20 (t 0.6), off leaving 10 (t 0.7)
    s = OutputCamSet()
    el, _ = cam(window(), end=30.0)
    arm(s, el, mode=PERSIST, end=30.0)
    ax = Axis(0.0, 100.0)
    e1, _ = ax.run(s, 0.4)
    w = s.status_words(0)
    assert (w["OutputCamStatus"], w["OutputCamLockStatus"]) == (1, 0)  # out of range
    ax.v = -100.0
    e2, _ = ax.run(s, 0.35)  # back to x = 5, inside the range
    assert_edges(e1 + e2, [(0.1, True), (0.2, False), (0.6, True), (0.7, False)])
    assert s.status_words(0)["OutputCamLockStatus"] == 1


# -- schedules ------------------------------------------------------------------------------
@pytest.mark.parametrize(("sched", "v", "x0", "lock_t"), [
    (FWD, 100.0, 0.0, 0.5), (REV, -100.0, 100.0, 0.5), (BI, -100.0, 100.0, 0.5),
    (BI, 100.0, 0.0, 0.5)])  # fmt: skip
def test_directional_arming_locks_at_the_axis_arm_position(sched, v, x0, lock_t) -> None:
    # AxisArm 50, CamArm 40: cam = 40 + (x - 50); forward: window [60, 70] -> x in
    # [70, 80] -> t 0.7 .. 0.8. Reverse from 100: cam = 40 - 100 (t - 0.5) reaches the
    # window's mirrored latch edge 70? no: cam only falls from 40 -> window [10, 20]
    # reached at cam 20 (t = 0.5 + 0.2) and left at 10 (t = 0.8).
    s = OutputCamSet()
    el, _ = cam(window(left=60.0, right=70.0) if v > 0 else window())
    arm(s, el, sched=sched, axis_arm=50.0, cam_arm=40.0)
    assert s.status_words(0)["OutputCamStatus"] == 1
    edges, events = Axis(x0, v).run(s, 1.0)
    assert events[0][1] == LOCKED and events[0][2] == pytest.approx(lock_t, abs=US)
    assert_edges(edges, [(0.7, True), (0.8, False)])


def test_forward_only_ignores_reverse_travel() -> None:
    s = OutputCamSet()
    el, _ = cam(window())
    arm(s, el, sched=FWD, axis_arm=50.0, cam_arm=0.0)
    _, events = Axis(100.0, -100.0).run(s, 1.0)
    assert events == []
    w = s.status_words(0)
    assert (w["OutputCamStatus"], w["OutputCamLockStatus"]) == (1, 0)


def test_pending_cam_takes_over_at_the_range_end() -> None:
    # first cam Once over [0, 50] from x = 0 ends at t = 0.5; the pending cam (range
    # [0, 100], cam arm 0) starts there: its window [10, 20] -> x in [60, 70] -> 0.6..0.7
    s = OutputCamSet()
    el1, _ = cam(window(bit=1), end=50.0)
    el2, _ = cam(window())
    arm(s, el1, end=50.0)
    ax = Axis(0.0, 100.0)
    e0, _ = ax.run(s, 0.1)
    arm(s, el2, handle=2, sched=PEND)
    w = s.status_words(0)
    assert (w["OutputCamPendingStatus"], w["OutputCamLockStatus"]) == (1, 1)
    edges, events = ax.run(s, 0.9)
    kinds = [(h, k) for h, k, _ in events]
    assert kinds == [(1, COMPLETE), (2, PENDING_STARTED)]
    assert events[0][2] == pytest.approx(0.5, abs=US)
    # the first cam's bit 1 window [10, 20]: on at 0.1 (first run), off at 0.2
    assert_edges(e0 + edges, [(0.1, True), (0.2, False)], bit=1)
    assert_edges(edges, [(0.6, True), (0.7, False)])
    assert s.status_words(0)["OutputCamPendingStatus"] == 0


def test_immediate_supersedes_and_directional_refused_while_locked() -> None:
    s = OutputCamSet()
    el, _ = cam(window())
    arm(s, el)
    ax = Axis(0.0, 100.0)
    ax.run(s, 0.01)
    r = s.arm(0, 0, request(el, handle=2, sched=FWD, axis_arm=50.0))
    assert (r.armed, r.error) == (False, error_code("Illegal Dynamic Change"))
    arm(s, el, handle=3)
    _, events = ax.run(s, 0.01)
    assert (1, ENDED) in [(h, k) for h, k, _ in events]
    r = s.arm(0, 8, request(el))
    assert (r.armed, r.error) == (False, error_code("Illegal Execution Target"))


# -- MDOC -----------------------------------------------------------------------------------
def test_mdoc_disarms_and_outputs_keep_their_state() -> None:
    s = OutputCamSet()
    el, _ = cam(window())
    arm(s, el, target=0)
    arm(s, el, handle=2, target=3)
    ax = Axis(0.0, 100.0)
    ax.run(s, 0.15)  # inside the window: bit 0 on in both targets
    assert s.status_words(0)["OutputCamStatus"] == 0b1001
    assert s.disarm(0, 3, DisarmType.SPECIFIC) == [2]
    assert s.status_words(0)["OutputCamStatus"] == 0b0001
    ax.run(s, 0.2)
    assert s.targets[(0, 3)].output == 1  # kept on after the disarm
    assert s.targets[(0, 0)].output == 0  # still armed: reset leaving the window
    arm(s, el, handle=5, axis=1, target=0)
    assert s.disarm(0, 0, DisarmType.ALL) == [1]  # All: every target of axis 0 only
    assert s.status_words(0)["OutputCamStatus"] == 0
    assert s.status_words(1)["OutputCamStatus"] == 1


# -- exact motion, reference, transition ----------------------------------------------------
def test_exact_inverse_of_an_accelerating_axis_gives_exact_edges() -> None:
    # x = a t^2 / 2, a = 1000 u/s^2, no delays. Window [10.2, 10.5]:
    # on at sqrt(2 * 10.2 / 1000) = 0.1428285686 s, off at sqrt(0.021) = 0.1449137675 s
    # (linear interpolation inside the 1 ms update would be off by up to ~1e-6 s here)
    a = 1000.0
    s = OutputCamSet()
    el, _ = cam(window(left=10.2, right=10.5))
    arm(s, el)
    edges = []
    for n in range(200):
        t0 = n * DT
        x0, x1 = a * t0**2 / 2, a * (t0 + DT) ** 2 / 2

        def inverse(d, x0=x0, t0=t0):
            return np.sqrt(2 * (x0 + d) / a) - t0

        step = s.update(t0, DT, np.array([[x0], [x0]]), np.array([[x1], [x1]]),
                        time_of={(0, 0): inverse})  # fmt: skip
        edges += [(e.bit, e.time, e.value) for e in step.edges]
    got = [t for _, t, _ in edges]
    assert got == pytest.approx([0.1428285686, 0.1449137675], abs=1e-9)


def test_reference_selects_actual_or_command_position() -> None:
    # command = 100 t, actual = 100 t - 1 (1 u behind). Forward only, AxisArm 0, CamArm 0:
    # cam = position of the chosen reference. Window [10, 20]: command reaches 10 at
    # t = 0.1, actual at t = 0.11; off 0.1 s later.
    for ref, on_t in ((PositionReference.COMMAND, 0.1), (PositionReference.ACTUAL, 0.11)):
        s = OutputCamSet()
        el, _ = cam(window())
        arm(s, el, ref=ref, sched=FWD)
        edges = []
        for n in range(300):
            t0 = n * DT
            cmd0, cmd1 = 100 * t0, 100 * (t0 + DT)
            step = s.update(t0, DT, np.array([[cmd0 - 1], [cmd0]]),
                            np.array([[cmd1 - 1], [cmd1]]))  # fmt: skip
            edges += [(e.bit, e.time, e.value) for e in step.edges]
        assert_edges(edges, [(on_t, True), (on_t + 0.1, False)])


def test_transition_status_marks_the_update_of_a_hand_over() -> None:
    # Continuous cam over [0, 50] with a pending cam: hand-over at the first wrap
    # (x = 50, t = 0.5, inside the update [0.499, 0.5]... the update ending at 0.5 reaches
    # 50 exactly, the cam only moves beyond it in the next update [0.5, 0.501])
    s = OutputCamSet()
    el, _ = cam(window(), end=50.0)
    arm(s, el, mode=CONT, end=50.0)
    arm(s, el, handle=2, sched=PEND)
    ax = Axis(0.0, 100.0)
    seen = []
    for _ in range(600):
        _, events = ax.run(s, DT)
        seen.append(s.status_words(0)["OutputCamTransitionStatus"])
        if events and events[0][1] == PENDING_STARTED:
            assert events[0][2] == pytest.approx(0.5, abs=US)
    assert seen.count(1) == 1 and seen.index(1) == 500
    # the continuous cam ended without PC
    assert s.status_words(0)["OutputCamPendingStatus"] == 0


def test_continuous_in_reverse_wraps_to_the_end() -> None:
    # range [0, 100], cam arm 100 at axis 100, v = -100: cam = x until 0, then wraps to 100.
    # window [10, 20] mirrored: on at 20 (t 0.8), off leaving 10 (t 0.9), again + 1 s
    s = OutputCamSet()
    el, _ = cam(window())
    arm(s, el, mode=CONT, axis_arm=100.0, cam_arm=100.0)
    edges, _ = Axis(100.0, -100.0).run(s, 2.0)
    assert_edges(edges, [(0.8, True), (0.9, False), (1.8, True), (1.9, False)])


def test_batched_quiet_pass_matches_the_exact_path() -> None:
    # 8 axes x 8 targets of random windows (some enable-gated, some Once, one reversing
    # axis): the one-pass numpy precheck may only skip cams in which nothing switches, so
    # edges and events must equal the per-cam evaluation of every cam.
    rng = np.random.default_rng(7)

    def build(batch: bool) -> OutputCamSet:
        s = OutputCamSet(batch=batch)
        r = np.random.default_rng(3)
        for a in range(8):
            for tg in range(8):
                left = r.uniform(0, 330, 16)
                recs = [window(bit=i, left=float(lf), right=float(lf) + 12.0,
                               latch=3 if i % 5 == 0 else 1, unlatch=1, EnableBit=i)
                        for i, lf in enumerate(left)]  # fmt: skip
                el, _ = cam(*recs, end=360.0)
                c, _ = comp(b0={"Offset": 1.0, "LatchDelay": 0.002, "UnlatchDelay": 0.001})
                mode = ONCE if tg == 7 else CONT
                arm(s, el, compensation=c, axis=a, target=tg, handle=a * 8 + tg, mode=mode,
                    end=360.0)  # fmt: skip
        return s

    fast, exact = build(True), build(False)
    x = np.zeros((2, 8))
    speed = np.linspace(150.0, 900.0, 8)
    speed[3] = -400.0
    out = {True: [], False: []}
    for n in range(800):
        x1 = x + speed * DT + rng.normal(0, 1e-4, 8)  # velocity jitter moves the edges
        for s in (fast, exact):
            if n == 400:
                for t in s.targets.values():
                    t.input = 0x5555
            step = s.update(n * DT, DT, x, x1)
            out[s.batch] += [(e.axis, e.target, e.bit, round(e.time, 12), e.value)
                             for e in step.edges]  # fmt: skip
            out[s.batch] += [(e.handle, e.kind, round(e.time, 12)) for e in step.events]
        x = x1
    assert len(out[True]) > 300
    assert out[True] == out[False]


def test_refusals_and_array_errors_in_the_arm_result() -> None:
    s = OutputCamSet()
    el, chk = cam(window(bit=40), window())  # element 0 skipped: ERR 36, SEGMENT 0
    # CamStart >= CamEnd -> ERR 13, EXERR 7 (CamEndPosition is operand 7 counting from 0)
    r = s.arm(0, 0, request(el, start=50.0, end=50.0))
    assert (r.armed, r.error, r.exerr) == (False, error_code("Parameter Out Of Range"), 7)
    # CamArm outside the range -> ERR 13, EXERR 12
    r = s.arm(0, 0, request(el, cam_arm=101.0))
    assert (r.armed, r.error, r.exerr) == (False, error_code("Parameter Out Of Range"), 12)
    r = s.arm(0, 0, request(el), check=chk)
    assert (r.armed, r.error, r.exerr, r.segment) == (True, error_code("Illegal Output Cam"), 1, 0)
    edges, _ = Axis(0.0, 100.0).run(s, 0.3)
    assert_edges(edges, [(0.1, True), (0.2, False)])  # the good element still runs


def test_pending_refused_during_a_transition() -> None:
    s = OutputCamSet()
    el, _ = cam(window(), end=50.0)
    arm(s, el, mode=CONT, end=50.0)
    arm(s, el, handle=2, sched=PEND)
    ax = Axis(0.0, 100.0)
    while not s.status_words(0)["OutputCamTransitionStatus"]:
        ax.run(s, DT)
    r = s.arm(0, 0, request(el, handle=3, sched=PEND))
    assert (r.armed, r.error) == (False, error_code("Illegal Dynamic Change"))
    ax.run(s, DT)  # transition over: a pending MAOC is accepted again
    assert s.arm(0, 0, request(el, handle=4, sched=PEND)).armed


@pytest.mark.parametrize("windows_only", [False, True])
def test_quiet_intervals_match_the_exact_path_with_every_kind_of_element(windows_only) -> None:
    # decision 0114: a cam may only be skipped while its travel stays inside its quiet
    # interval. Every latch/unlatch type, durations, pulsed and inverted bits, delays,
    # persistent and once ranges, enable words the "program" toggles, velocity changes and
    # reversals: the skipping pass must give exactly the edges and events of evaluating
    # every cam every update. windows_only: Position/Position windows without delays (the
    # bisection path), narrow and wide, with offsets and inverted bits.
    def build(batch: bool) -> OutputCamSet:
        s = OutputCamSet(batch=batch)
        r = np.random.default_rng(11)
        for a in range(4):
            for tg in range(4):
                recs = []
                for i in range(12):
                    left = float(r.uniform(0, 300))
                    recs.append(window(
                        bit=i, left=left, right=left + float(r.uniform(0.05, 30.0)),
                        latch=1 if windows_only else int(r.integers(0, 4)),
                        unlatch=1 if windows_only else int(r.integers(0, 6)),
                        Duration=float(r.uniform(0.001, 0.05)), EnableType=int(r.integers(0, 4)),
                        EnableBit=int(r.integers(0, 32)),
                    ))  # fmt: skip
                el, _ = cam(*recs, end=360.0)
                c, _ = (
                    comp(b2={"Mode": 1}, b4={"Offset": 3.0})
                    if windows_only
                    else comp(
                        b1={"Mode": 2, "CycleTime": 0.007, "DutyCycle": 40.0},
                        b2={"Mode": 1},
                        b3={"Mode": 3, "CycleTime": 0.011, "DutyCycle": 25.0},
                        b4={"Offset": 3.0, "LatchDelay": 0.004, "UnlatchDelay": 0.002},
                        b5={"LatchDelay": 0.01},
                    )
                )
                mode = (ONCE, CONT, PERSIST, CONT)[tg]
                arm(s, el, compensation=c, axis=a, target=tg, handle=a * 4 + tg + 1,
                    mode=mode, end=360.0)  # fmt: skip
        return s

    fast, exact = build(True), build(False)
    rng = np.random.default_rng(5)
    x = np.zeros((2, 4))
    speed = np.array([120.0, 333.0, -250.0, 60.0])
    out: dict[bool, list] = {True: [], False: []}
    for n in range(3000):
        if n % 700 == 350:
            speed = -speed  # reversals (persistent cams leave and come back)
        if n % 97 == 0:
            speed = speed * rng.uniform(0.8, 1.25, 4)  # velocity changes move the windows
        x1 = x + speed * DT
        words = int(rng.integers(0, 2**31)) if n % 41 == 0 else None
        for s in (fast, exact):
            if words is not None:  # the program writes the Input and Output words
                for t in s.targets.values():
                    t.input = words
                    t.output ^= words & 0x0F0F0000
            step = s.update(n * DT, DT, x, x1)
            out[s.batch] += [(e.axis, e.target, e.bit, round(e.time, 12), e.value)
                             for e in step.edges]  # fmt: skip
            out[s.batch] += [(e.handle, e.kind, round(e.time, 12)) for e in step.events]
        x = x1
    assert len(out[True]) > 500
    assert out[True] == out[False]
