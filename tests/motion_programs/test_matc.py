"""MATC through the VM: every behaviour of the seed (MATC-motion-axis-time-cam.txt), SPEC 5
and 9.22/9.23, checked on `--trace` output against closed forms.

Profiles used (points Master, Slave; linear segments unless said otherwise):
- LIN: (0, 0) (1, 10): P(x) = 10 x, span 1 s, net 10 -> slave speed 10 DS / TS units/s.
- TRI: (0, 0) (0.5, 5) (1, 0): up 10/s then down 10/s, net 0.
A cam executed in the scan at t = 0 starts at the update at t0 = 2 ms (SPEC 9.3). Positions
are compared with the continuous closed form at the row's time; the planner samples every
2 ms, so the tolerance is one coarse update of travel (speed * 0.002) plus float32 rounding.
"""

from __future__ import annotations

import pytest
from motion_trace import CUP, ramp

T0 = 0.002  # start update of an instruction executed in scan 0
F32 = 1e-4  # float32 rounding of positions below ~100 units

HEAD = """VAR
  lin : CAM_PROFILE[2] := [(Master := 0.0, Slave := 0.0, SegmentType := 0),
                           (Master := 1.0, Slave := 10.0, SegmentType := 0)];
  tri : CAM_PROFILE[3] := [(Master := 0.0, Slave := 0.0, SegmentType := 0),
                           (Master := 0.5, Slave := 5.0, SegmentType := 0),
                           (Master := 1.0, Slave := 0.0, SegmentType := 0)];
  A, B : AXIS_VIRTUAL := (MaximumSpeed := 1000.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0);
  c1, c2, c3, c4 : MOTION_INSTRUCTION;
  k : DINT;
"""


def prog(decls: str, body: str) -> str:
    return HEAD + decls + "END_VAR\n" + body + "\nk := k + 1;\n"


def test_same_direction_distance_and_time_scaling_once(mp) -> None:
    # DS = 2, TS = 2: contribution 2 * (P(t/2) - P(0)) = 10 t for 0 <= t <= 2 s, then held at 20
    src = prog(
        "",
        "IF k = 0 THEN MATC(A, c1, 0, lin, 2.0, 2.0, once, immediate, 0.0, none, timedrivenmode); END_IF;",
    )
    tr = mp.trace(
        src,
        [
            "A.CommandPosition",
            "A.ActualPosition",
            "c1.EN",
            "c1.DN",
            "c1.IP",
            "c1.PC",
            "c1.ER",
            "A.TimeCamStatus",
        ],
        scans=2100,
    )
    tr.check("A.CommandPosition", lambda t: ramp(t, T0, T0 + 2.0, 10.0), 10.0 * CUP + F32)
    tr.check("A.ActualPosition", lambda t: ramp(t, T0, T0 + 2.0, 10.0), 10.0 * CUP + F32)  # virtual
    # SPEC 9.22: DN, IP and TimeCamStatus in the executing scan
    assert [
        tr.at(0.0, n) for n in ("c1.EN", "c1.DN", "c1.IP", "c1.PC", "c1.ER", "A.TimeCamStatus")
    ] == [1, 1, 1, 0, 0, 1]
    # Once: cam time reaches span * TS = 2 s at the update 2.002: PC set, IP and TimeCamStatus cleared
    assert (tr.at(2.001, "c1.IP"), tr.at(2.001, "c1.PC"), tr.at(2.001, "A.TimeCamStatus")) == (
        1,
        0,
        1,
    )
    assert (tr.at(2.002, "c1.IP"), tr.at(2.002, "c1.PC"), tr.at(2.002, "A.TimeCamStatus")) == (
        0,
        1,
        0,
    )
    assert tr.at(2.099, "A.CommandPosition") == 20.0  # the axis holds


def test_opposite_direction_subtracts_the_profile(mp) -> None:
    src = prog(
        "",
        "IF k = 0 THEN MATC(A, c1, 1, lin, 1.0, 1.0, once, immediate, 0.0, none, timedrivenmode); END_IF;",
    )
    tr = mp.trace(src, ["A.CommandPosition"], scans=1200)
    tr.check("A.CommandPosition", lambda t: -ramp(t, T0, T0 + 1.0, 10.0), 10.0 * CUP + F32)


def test_reverse_and_unchanged_first_time_defaults(mp) -> None:
    # seed: Reverse the first time -> Opposite; Unchanged the first time -> Same
    src = prog(
        "",
        """IF k = 0 THEN
  MATC(A, c1, 2, lin, 1.0, 1.0, once, immediate, 0.0, none, timedrivenmode);
  MATC(B, c2, 3, lin, 1.0, 1.0, once, immediate, 0.0, none, timedrivenmode);
END_IF;""",
    )
    tr = mp.trace(src, ["A.CommandPosition", "B.CommandPosition"], scans=600)
    tr.check("A.CommandPosition", lambda t: -ramp(t, T0, 2.0, 10.0), 10.0 * CUP + F32)
    tr.check("B.CommandPosition", lambda t: ramp(t, T0, 2.0, 10.0), 10.0 * CUP + F32)


def test_reverse_and_unchanged_refer_to_the_last_cam_even_if_completed(mp) -> None:
    # four Once cams of LIN with TS = 0.1 (0.1 s, net 10 each), one every 200 ms:
    # Opposite -> -10; Reverse (of Opposite) = Same -> 0; Unchanged (Same) -> +10;
    # Reverse (of Same) = Opposite -> 0
    src = prog(
        "",
        """IF k = 0 THEN MATC(A, c1, 1, lin, 1.0, 0.1, once, immediate, 0.0, none, timedrivenmode); END_IF;
IF k = 200 THEN MATC(A, c2, 2, lin, 1.0, 0.1, once, immediate, 0.0, none, timedrivenmode); END_IF;
IF k = 400 THEN MATC(A, c3, 3, lin, 1.0, 0.1, once, immediate, 0.0, none, timedrivenmode); END_IF;
IF k = 600 THEN MATC(A, c4, 2, lin, 1.0, 0.1, once, immediate, 0.0, none, timedrivenmode); END_IF;""",
    )
    tr = mp.trace(src, ["A.CommandPosition", "c1.PC", "c4.PC"], scans=800)
    got = [tr.at(t, "A.CommandPosition") for t in (0.15, 0.35, 0.55, 0.75)]
    assert got == pytest.approx([-10.0, 0.0, 10.0, 0.0], abs=F32)
    # midway through the third cam (started at update 0.402): +10 * 0.05 from 0
    assert abs(tr.at(0.452, "A.CommandPosition") - 5.0) < F32
    assert tr.at(0.15, "c1.PC") == 1 and tr.at(0.75, "c4.PC") == 1


def test_continuous_unwinds_time_and_repeats(mp) -> None:
    # TRI continuous: a triangle wave of period 1 s between 0 and 5 (net 0 per pass)
    def wave(t: float) -> float:
        x = (t - T0) % 1.0 if t >= T0 else 0.0
        return 10.0 * x if x <= 0.5 else 10.0 * (1.0 - x)

    src = prog(
        "",
        "IF k = 0 THEN MATC(A, c1, 0, tri, 1.0, 1.0, continuous, immediate, 0.0, none, timedrivenmode); END_IF;",
    )
    tr = mp.trace(src, ["A.CommandPosition", "c1.IP", "c1.PC"], scans=2600)
    tr.check("A.CommandPosition", wave, 10.0 * CUP + F32)
    assert set(tr.col("c1.IP")) == {1.0} and set(tr.col("c1.PC")) == {0.0}


def test_continuous_adds_the_net_change_each_pass(mp) -> None:
    # LIN continuous, TS = 0.5: 10 units per 0.5 s pass, passes add up: 20 (t - t0)
    src = prog(
        "",
        "IF k = 0 THEN MATC(A, c1, 0, lin, 1.0, 0.5, continuous, immediate, 0.0, none, timedrivenmode); END_IF;",
    )
    tr = mp.trace(src, ["A.CommandPosition"], scans=2600)
    tr.check("A.CommandPosition", lambda t: ramp(t, T0, 10.0, 20.0), 20.0 * CUP + 5 * F32)


def test_immediate_matc_while_time_camming_is_error_23(mp) -> None:
    src = prog(
        "",
        """IF k = 0 THEN MATC(A, c1, 0, lin, 1.0, 1.0, continuous, immediate, 0.0, none, timedrivenmode); END_IF;
IF k = 10 THEN MATC(A, c2, 0, tri, 1.0, 1.0, once, immediate, 0.0, none, timedrivenmode); END_IF;""",
    )
    tr = mp.trace(
        src, ["A.CommandPosition", "c1.IP", "c2.ER", "c2.ERR", "c2.DN", "c2.IP", "c2.EN"], scans=300
    )
    assert [tr.at(0.01, n) for n in ("c2.EN", "c2.ER", "c2.ERR", "c2.DN", "c2.IP")] == [
        1,
        1,
        23,
        0,
        0,
    ]
    assert tr.at(0.299, "c1.IP") == 1  # the running cam is not disturbed
    tr.check("A.CommandPosition", lambda t: ramp(t, T0, 10.0, 10.0), 10.0 * CUP + F32)


def test_pending_cams_blend_accelerate_run_decelerate(mp) -> None:
    # c1: LIN Once (0 -> 10 in 1 s, 10 units/s); c2 pending: HALF continuous (0 -> 5 in 0.5 s,
    # 10 units/s); c3 pending at 1.2 s: DEC, P(x) = 10 x - 5 x^2 on [0, 1] (speed 10 -> 0),
    # calculated by MCCP from 3 cubic points with start slope 10 and end slope 0 (a clamped
    # cubic spline reproduces a quadratic exactly).
    # Hand-over at the end of the active pass, leftover time carried: no stall, no jump.
    #   t in [t0, 1.502]: 10 (t - t0)         (c1 until 1.002, then c2 passes of 0.5 s)
    #   t in [1.502, 2.502]: 15 + 10 x - 5 x^2, x = t - 1.502;  then 20
    decls = """  half : CAM_PROFILE[2] := [(Master := 0.0, Slave := 0.0, SegmentType := 0),
                            (Master := 0.5, Slave := 5.0, SegmentType := 0)];
  dec : CAM_PROFILE[3];
  decpts : CAM[3] := [(Master := 0.0, Slave := 0.0, SegmentType := 1),
                      (Master := 0.5, Slave := 3.75, SegmentType := 1),
                      (Master := 1.0, Slave := 5.0, SegmentType := 1)];
  cc : MOTION_INSTRUCTION;
"""
    body = """IF k = 0 THEN
  MCCP(cc, decpts, 3, 10.0, 0.0, dec);
  MATC(A, c1, 0, lin, 1.0, 1.0, once, immediate, 0.0, none, timedrivenmode);
END_IF;
IF k = 10 THEN MATC(A, c2, 0, half, 1.0, 1.0, continuous, pending, 0.0, none, timedrivenmode); END_IF;
IF k = 1200 THEN MATC(A, c3, 0, dec, 1.0, 1.0, once, pending, 0.0, none, timedrivenmode); END_IF;"""

    def pos(t: float) -> float:
        if t <= 1.502:
            return ramp(t, T0, 1.502, 10.0)
        x = min(t, 2.502) - 1.502
        return 15.0 + 10.0 * x - 5.0 * x * x

    tr = mp.trace(
        prog(decls, body),
        [
            "A.CommandPosition",
            "A.CommandVelocity",
            "A.TimeCamStatus",
            "A.TimeCamPendingStatus",
            "c1.IP",
            "c1.PC",
            "c2.DN",
            "c2.IP",
            "c2.PC",
            "c3.IP",
            "c3.PC",
            "cc.DN",
        ],
        scans=2700,
    )
    tr.check("A.CommandPosition", pos, 10.0 * CUP + F32)
    assert tr.at(0.0, "cc.DN") == 1  # MCCP completes in its scan (SPEC 9.21)
    # pending: DN and IP at once, TimeCamPendingStatus set immediately
    assert (tr.at(0.009, "A.TimeCamPendingStatus"), tr.at(0.010, "A.TimeCamPendingStatus")) == (
        0,
        1,
    )
    assert (tr.at(0.010, "c2.DN"), tr.at(0.010, "c2.IP")) == (1, 1)
    # hand-over from the Once cam at 1.002: its PC set, pending status cleared
    assert [tr.at(1.001, n) for n in ("c1.IP", "c1.PC", "A.TimeCamPendingStatus")] == [1, 0, 1]
    assert [
        tr.at(1.002, n) for n in ("c1.IP", "c1.PC", "A.TimeCamPendingStatus", "A.TimeCamStatus")
    ] == [0, 1, 0, 1]
    assert tr.at(1.2, "A.TimeCamPendingStatus") == 1
    # hand-over from the Continuous cam at 1.502: its IP cleared, no PC
    assert [tr.at(1.501, n) for n in ("c2.IP", "c3.IP")] == [1, 1]
    assert [tr.at(1.502, n) for n in ("c2.IP", "c2.PC", "A.TimeCamPendingStatus")] == [0, 0, 0]
    # speed stays 10 through both hand-overs, then falls linearly to 0
    assert abs(tr.at(1.002, "A.CommandVelocity") - 10.0) < 1e-3
    assert abs(tr.at(1.502, "A.CommandVelocity") - 10.0) < 1e-3
    assert abs(tr.at(2.002, "A.CommandVelocity") - 5.0) < 1e-3  # 10 - 10 x at x = 0.5
    assert [tr.at(2.502, n) for n in ("c3.IP", "c3.PC", "A.TimeCamStatus")] == [0, 1, 0]
    assert tr.at(2.699, "A.CommandPosition") == 20.0


def test_pending_cam_preloaded_without_an_active_cam_waits(mp) -> None:
    # a pending MATC with no cam running does not move the axis; the next immediate cam
    # (executed at 0.1 s, starts at 0.102) runs its pass, then the preloaded cam takes over
    src = prog(
        "",
        """IF k = 0 THEN MATC(A, c1, 1, lin, 1.0, 1.0, once, pending, 0.0, none, timedrivenmode); END_IF;
IF k = 100 THEN MATC(A, c2, 0, lin, 1.0, 1.0, once, immediate, 0.0, none, timedrivenmode); END_IF;""",
    )
    tr = mp.trace(
        src,
        [
            "A.CommandPosition",
            "A.TimeCamStatus",
            "A.TimeCamPendingStatus",
            "c1.IP",
            "c1.PC",
            "c2.PC",
        ],
        scans=2300,
    )

    def pos(t: float) -> float:  # +10/s from 0.102 to 1.102, then -10/s (Opposite) to 2.102
        return ramp(t, 0.102, 1.102, 10.0) - ramp(t, 1.102, 2.102, 10.0)

    tr.check("A.CommandPosition", pos, 10.0 * CUP + F32)
    assert [tr.at(0.05, n) for n in ("A.TimeCamStatus", "A.TimeCamPendingStatus", "c1.IP")] == [
        0,
        1,
        1,
    ]
    assert [tr.at(1.102, n) for n in ("c2.PC", "A.TimeCamPendingStatus", "A.TimeCamStatus")] == [
        1,
        0,
        1,
    ]
    assert [tr.at(2.102, n) for n in ("c1.PC", "c1.IP", "A.TimeCamStatus")] == [1, 0, 0]


def test_uncalculated_profile_is_error_32(mp) -> None:
    # Status 0 (never calculated) and 1 (being calculated) are both "not calculated" (SPEC 9.23)
    src = prog(
        "  raw, busy : CAM_PROFILE[4];\n",
        """IF k = 0 THEN
  busy[0].Status := 1;
  MATC(A, c1, 0, raw, 1.0, 1.0, once, immediate, 0.0, none, timedrivenmode);
  MATC(B, c2, 0, busy, 1.0, 1.0, once, immediate, 0.0, none, timedrivenmode);
END_IF;""",
    )
    tr = mp.trace(
        src,
        [
            "c1.ER",
            "c1.ERR",
            "c2.ER",
            "c2.ERR",
            "raw[0].Status",
            "busy[0].Status",
            "A.CommandPosition",
        ],
        scans=20,
    )
    assert [
        tr.at(0.0, n)
        for n in ("c1.ER", "c1.ERR", "c2.ER", "c2.ERR", "raw[0].Status", "busy[0].Status")
    ] == [1, 32, 1, 32, 0, 1]
    assert tr.at(0.019, "A.CommandPosition") == 0.0


def test_profile_status_counts_the_cams_using_it(mp) -> None:
    # 2 calculated; +1 per running cam (A, B); an erroring MATC (23) does not count; a pending
    # cam counts when it takes over; -1 when a cam completes: back to 2.
    # (time scalings 0.25 / 0.5 are exact in a REAL, so the passes end on update instants)
    src = prog(
        "",
        """IF k = 0 THEN MATC(A, c1, 0, lin, 1.0, 0.25, once, immediate, 0.0, none, timedrivenmode); END_IF;
IF k = 5 THEN MATC(B, c2, 0, lin, 1.0, 0.5, once, immediate, 0.0, none, timedrivenmode); END_IF;
IF k = 6 THEN MATC(B, c3, 0, lin, 1.0, 0.5, once, immediate, 0.0, none, timedrivenmode); END_IF;
IF k = 7 THEN MATC(B, c4, 0, lin, 1.0, 0.25, once, pending, 0.0, none, timedrivenmode); END_IF;""",
    )
    tr = mp.trace(src, ["lin[0].Status", "c3.ERR"], scans=800)
    st = lambda t: tr.at(t, "lin[0].Status")  # noqa: E731
    assert tr.at(0.006, "c3.ERR") == 23
    # A runs 0.002..0.252; B's first cam 0.006..0.506, then its pending cam 0.506..0.756
    times = (0.0, 0.004, 0.005, 0.251, 0.252, 0.505, 0.506, 0.755, 0.756)
    assert [st(t) for t in times] == [3, 3, 4, 4, 3, 3, 3, 3, 2]


def test_bad_operands_set_err_13_with_the_operand_index(mp) -> None:
    # EXERR = faceplate index: Direction 2, DistanceScaling 4, TimeScaling 5, LockDirection 9
    decls = "  dir, ld : DINT;\n  ds, ts : REAL;\n"
    body = """IF k = 0 THEN
  dir := 7; ld := 9; ds := 1.0e39; ts := 0.0;
  MATC(A, c1, dir, lin, 1.0, 1.0, once, immediate, 0.0, none, timedrivenmode);
  MATC(A, c2, 0, lin, ds, 1.0, once, immediate, 0.0, none, timedrivenmode);
  MATC(A, c3, 0, lin, 1.0, ts, once, immediate, 0.0, none, timedrivenmode);
  MATC(A, c4, 0, lin, 1.0, 1.0, once, immediate, 0.0, ld, masterdrivenmode);
END_IF;"""
    tr = mp.trace(
        prog(decls, body),
        [f"c{i}.{m}" for i in range(1, 5) for m in ("ER", "ERR", "EXERR", "DN")],
        scans=3,
    )
    got = [
        (
            tr.at(0.0, f"c{i}.ER"),
            tr.at(0.0, f"c{i}.ERR"),
            tr.at(0.0, f"c{i}.EXERR"),
            tr.at(0.0, f"c{i}.DN"),
        )
        for i in range(1, 5)
    ]
    assert got == [(1, 13, 2, 0), (1, 13, 4, 0), (1, 13, 5, 0), (1, 13, 9, 0)]


def test_lock_direction_conflicts_are_error_95(mp) -> None:
    # time driven with a lock direction (seed: only master-driven cams lock) and a pending
    # cam with a Position lock: LOCK_DIRECTION_CONFLICT
    src = prog(
        "",
        """IF k = 0 THEN
  MATC(A, c1, 0, lin, 1.0, 1.0, once, immediate, 0.0, immediateforwardonly, timedrivenmode);
  MATC(B, c2, 0, lin, 1.0, 1.0, once, pending, 5.0, positionforward, masterdrivenmode);
END_IF;""",
    )
    tr = mp.trace(src, ["c1.ERR", "c2.ERR", "c1.ER", "c2.ER"], scans=2)
    assert [tr.at(0.0, n) for n in ("c1.ER", "c1.ERR", "c2.ER", "c2.ERR")] == [1, 95, 1, 95]


def test_master_driven_cam_without_mdac_is_error_93(mp) -> None:
    src = prog(
        "",
        "IF k = 0 THEN MATC(A, c1, 0, lin, 1.0, 1.0, once, immediate, 0.0, none, masterdrivenmode); END_IF;",
    )
    tr = mp.trace(src, ["c1.ER", "c1.ERR"], scans=2)
    assert (tr.at(0.0, "c1.ER"), tr.at(0.0, "c1.ERR")) == (1, 93)


def test_time_cam_superimposes_on_a_jog_and_mas_all_ends_it_without_pc(mp) -> None:
    # jog 5 units/s (accel 1000: at speed after 5 ms) plus LIN continuous (10 units/s); MAS All
    # at 0.5 s (applied at 0.502) with decel 1000 from 15 units/s: IP and TimeCamStatus cleared,
    # no PC for the cam; the stop completes (PC) after 15 ms
    body = """IF k = 0 THEN
  MAJ(A, c1, forward, 5.0, unitspersec, 1000.0, unitspersec2, 1000.0, unitspersec2, trapezoidal, 0.0, 0.0, unitspersec3, disabled, programmed, 0.0, none);
  MATC(A, c2, 0, lin, 1.0, 1.0, continuous, immediate, 0.0, none, timedrivenmode);
END_IF;
IF k = 500 THEN MAS(A, c3, all, yes, 1000.0, unitspersec2, no, 0.0, unitspersec3); END_IF;"""
    tr = mp.trace(
        prog("", body),
        [
            "A.CommandPosition",
            "A.CommandVelocity",
            "c1.IP",
            "c2.IP",
            "c2.PC",
            "A.TimeCamStatus",
            "c3.IP",
            "c3.PC",
            "A.StoppingStatus",
        ],
        scans=600,
    )
    # before the stop: jog ramp 0 -> 5 over 5 ms (covers 0.0125) then 5/s, plus the cam's 10/s
    tr.check(
        "A.CommandPosition",
        lambda t: ramp(t, T0, 0.502, 10.0) + ramp(t, T0 + 0.0025, 0.502, 5.0),
        15.0 * CUP + F32,
        0.0,
        0.501,
    )
    assert [tr.at(0.501, n) for n in ("c1.IP", "c2.IP", "A.TimeCamStatus")] == [1, 1, 1]
    assert [
        tr.at(0.502, n)
        for n in ("c1.IP", "c2.IP", "c2.PC", "A.TimeCamStatus", "c3.IP", "A.StoppingStatus")
    ] == [0, 0, 0, 0, 1, 1]
    # 15 units/s at 1000 units/s^2: 15 ms and 0.1125 units to rest
    p_stop = tr.at(0.502, "A.CommandPosition")
    assert abs(tr.at(0.599, "A.CommandPosition") - (p_stop + 0.1125)) < 1e-3
    assert (tr.at(0.516, "c3.PC"), tr.at(0.518, "c3.PC"), tr.at(0.518, "c3.IP")) == (0, 1, 0)


def test_initialised_profile_is_calculated_as_mccp_with_zero_slopes(mp) -> None:
    # SPEC 2.1: the same cubic points as a CAM_PROFILE initialiser and through MCCP with
    # start/end slope 0 drive two axes identically; Status 2 at load, before any scan
    decls = """  init : CAM_PROFILE[4] := [(Master := 0.0, Slave := 0.0, SegmentType := 1), (Master := 0.3, Slave := 4.0, SegmentType := 1),
                            (Master := 0.7, Slave := 1.0, SegmentType := 1), (Master := 1.0, Slave := 6.0, SegmentType := 1)];
  pts : CAM[4] := [(Master := 0.0, Slave := 0.0, SegmentType := 1), (Master := 0.3, Slave := 4.0, SegmentType := 1),
                   (Master := 0.7, Slave := 1.0, SegmentType := 1), (Master := 1.0, Slave := 6.0, SegmentType := 1)];
  calc : CAM_PROFILE[4];
  cc : MOTION_INSTRUCTION;
"""
    body = """IF k = 0 THEN
  MCCP(cc, pts, 4, 0.0, 0.0, calc);
  MATC(A, c1, 0, init, 1.0, 1.0, once, immediate, 0.0, none, timedrivenmode);
  MATC(B, c2, 0, calc, 1.0, 1.0, once, immediate, 0.0, none, timedrivenmode);
END_IF;"""
    tr = mp.trace(
        prog(decls, body), ["init[0].Status", "A.CommandPosition", "B.CommandPosition"], scans=1100
    )
    assert tr.col("A.CommandPosition") == tr.col("B.CommandPosition")
    # the spline passes through the points: 4 at 0.3 s, 1 at 0.7 s, 6 at the end (start 0.002)
    assert [tr.at(t, "A.CommandPosition") for t in (0.302, 0.702, 1.099)] == pytest.approx(
        [4.0, 1.0, 6.0], abs=F32
    )
    assert tr.at(1.099, "init[0].Status") == 2
