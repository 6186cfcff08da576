"""MAOC and MDOC through `logixst run` (SPEC 5, 9.26, 9.27; decisions 0108, 0112, 0113).

Motion used (hand-derived, coarse update 1 ms, scan 1 ms, virtual axis A):
- forward jog: MAJ(forward, 100 u/s, accel/decel 1e5) executed in scan 0 starts at the
  update t = 1 ms; the ramp to 100 u/s takes 1 ms and covers 100 * 0.001 / 2 = 0.05, so for
  t >= 2 ms x(t) = 100 (t - 0.001) - 0.05 = 100 t - 0.15, i.e. tf(x) = (x + 0.15) / 100.
- reverse jog: MAJ(reverse, 100 u/s) executed in scan 600 applies at the update 0.601
  (x = 59.95 with v = +100); +100 -> -100 at 1e5 takes 2 ms and its displacement
  100 * 0.002 - 1e5 * 0.002^2 / 2 = 0, so for t >= 0.603 x(t) = 59.95 - 100 (t - 0.603),
  i.e. tr(x) = 0.603 + (59.95 - x) / 100.
- reverse from rest: MAJ(reverse) in scan 0: x(t) = -(100 t - 0.15).
An MAOC executed in scan 0 applies at the update 1 ms, whose interval starts at t = 0
(x = 0): with Immediate, cam position = CamArm + (x - 0). Switch instants are read from
`--watch outw@edges` / `outw.N@edges` (exact instants, decision 0113) and must be within
1 µs of the closed form.
"""

from __future__ import annotations

import json

import pytest

US = 1e-6  # edge time tolerance: 1 µs

HEAD = """VAR
  A : AXIS_VIRTUAL := (MaximumSpeed := 1000.0, MaximumAccel := 100000.0, MaximumDecel := 100000.0);
  jog, rev, arm, arm2, dis, stp : MOTION_INSTRUCTION;
  comp : OUTPUT_COMPENSATION[4];
  outw, inw : DINT;
  k : DINT;
"""
JOG = (
    "MAJ(A, jog, forward, 100.0, unitspersec, 100000.0, unitspersec2, 100000.0, unitspersec2, "
    "trapezoidal, 0.0, 0.0, unitspersec3, disabled, programmed, 0.0, none);"
)
REV = JOG.replace("jog, forward", "rev, reverse")


def tf(x: float) -> float:
    return (x + 0.15) / 100.0


def tr(x: float) -> float:
    return 0.603 + (59.95 - x) / 100.0


def tneg(x: float) -> float:  # reverse jog from rest, x < 0
    return (-x + 0.15) / 100.0


def el(bit=0, latch=1, unlatch=1, left=10.0, right=20.0, **more) -> str:
    fields = {"OutputBit": bit, "LatchType": latch, "UnlatchType": unlatch}
    fields.update({"Left": left, "Right": right, **more})
    return "(" + ", ".join(f"{k} := {v}" for k, v in fields.items()) + ")"


def cam_decl(name: str, *elements: str) -> str:
    return f"  {name} : OUTPUT_CAM[{len(elements)}] := [{', '.join(elements)}];\n"


def maoc(
    ctl="arm", cam="cam", start=0.0, end=100.0, mode="continuous", sched="immediate",
    axis_arm=0.0, cam_arm=0.0, ref="actual", target=0, out="outw",
) -> str:  # fmt: skip
    return (
        f"MAOC(A, {target}, {ctl}, {out}, inw, {cam}, {start}, {end}, comp, {mode}, {sched}, "
        f"{axis_arm}, {cam_arm}, {ref});"
    )


def head(decls: str) -> str:
    """HEAD, without its default compensation array when decls declare their own."""
    return HEAD.replace("  comp : OUTPUT_COMPENSATION[4];\n", "") if "comp :" in decls else HEAD


def run(mp, decls: str, at: dict[int, str], watch: list[str], scans: int) -> dict:
    """Run HEAD + decls; `at` maps a scan number to statements executed in that scan."""
    body = "".join(f"IF k = {k} THEN {s} END_IF;\n" for k, s in sorted(at.items()))
    src = head(decls) + decls + "END_VAR\n" + body + "k := k + 1;\n"
    argv = ["--scans", str(scans), "--coarse-update", "1", "--json"]
    for w in watch:
        argv += ["--watch", w]
    code, out, err = mp.run(src, argv)
    assert code == 0 and "Traceback" not in err, (code, err, out[:2000])
    return json.loads(out)["tags"]


def assert_edges(got: list, expected: list[tuple[float, int]]) -> None:
    assert len(got) == len(expected), (got, expected)
    for (t, v), (te, ve) in zip(got, expected, strict=True):
        assert v == ve and abs(t - te) <= US, (got, expected)


# ----------------------------------------------------------------- latch / unlatch types
def test_position_window_and_control_bits(mp) -> None:
    tags = run(
        mp,
        cam_decl("cam", el()),
        {0: JOG + maoc()},
        ["outw.0@edges", "arm.DN", "arm.IP", "arm.PC", "arm.ER", "A.OutputCamStatus",
         "A.OutputCamLockStatus", "outw"],
        300,
    )  # fmt: skip
    # window [10, 20] of a [0, 100] cam: on at x = 10, off at x = 20
    assert_edges(tags["outw.0@edges"], [(tf(10), 1), (tf(20), 0)])
    assert [tags[n] for n in ("arm.DN", "arm.IP", "arm.PC", "arm.ER")] == [True, True, False, False]
    assert (tags["A.OutputCamStatus"], tags["A.OutputCamLockStatus"], tags["outw"]) == (1, 1, 0)


def test_trace_shows_the_status_words_and_the_output_bit(mp) -> None:
    tr_ = mp.trace(
        HEAD + cam_decl("cam", el()) + "END_VAR\n"
        f"IF k = 0 THEN {JOG} {maoc()} END_IF;\nk := k + 1;\n",
        ["arm.DN", "arm.IP", "A.OutputCamStatus", "A.OutputCamLockStatus", "outw"],
        scans=250,
        args=["--coarse-update", "1"],
    )
    # SPEC 9.27 / decision 0112: DN, IP and OutputCamStatus in the executing scan; the lock
    # (and the cam position) from the update that applies it
    assert [tr_.at(0.0, n) for n in ("arm.DN", "arm.IP", "A.OutputCamStatus")] == [1, 1, 1]
    assert tr_.at(0.0, "A.OutputCamLockStatus") == 0
    assert tr_.at(0.001, "A.OutputCamLockStatus") == 1
    # edge at tf(10) = 0.1015 s lies in the update 0.102: the row of 0.101 still shows 0
    assert (tr_.at(0.101, "outw"), tr_.at(0.102, "outw")) == (0, 1)
    assert (tr_.at(0.201, "outw"), tr_.at(0.202, "outw")) == (1, 0)


def test_inactive_latch_leaves_a_bit_set_by_the_program(mp) -> None:
    # bit 0 is set by the program; an Inactive latch never sets, so Position unlatch has
    # nothing of its own to reset (outputs are written only at switches, decision 0108)
    tags = run(
        mp,
        cam_decl("cam", el(latch=0), el(bit=1, unlatch=0)),
        {0: "outw := 1; " + JOG + maoc()},
        ["outw@edges", "outw"],
        300,
    )
    # bit 1: Position latch at 10, Inactive unlatch: stays on
    assert tags["outw@edges"] == [[pytest.approx(tf(10), abs=US), 1, 1]]
    assert tags["outw"] == 3


ENABLE_SCANS = {50: "inw := 8;", 80: "inw := 0;"}  # Input bit 3 on in scans 50..79


@pytest.mark.parametrize(
    ("element", "expected"),
    [
        # Enable latch / Enable unlatch: the enable edges fall at the start of the update
        # after the scan that wrote the Input word, i.e. at 0.050 and 0.080
        (el(latch=2, unlatch=3, EnableBit=3), [(0.050, 1), (0.080, 0)]),
        # Position and Enable latch: window [2, 20] (x = 2 at 0.0215) but enabled at 0.050
        (el(latch=3, unlatch=1, left=2.0, EnableBit=3), [(0.050, 1), (tf(20), 0)]),
        # Position and Enable unlatch: window [2, 20]; the enable drops first (0.080)
        (el(latch=1, unlatch=4, left=2.0, EnableBit=3), [(tf(2), 1), (0.080, 0)]),
        # Duration: on at x = 2, off 0.03 s later
        (el(latch=1, unlatch=2, left=2.0, Duration=0.03), [(tf(2), 1), (tf(2) + 0.03, 0)]),
        # Duration and Enable: 0.1 s would end at 0.1215, the enable drops at 0.080 first
        (
            el(latch=1, unlatch=5, left=2.0, Duration=0.1, EnableBit=3),
            [(tf(2), 1), (0.080, 0)],
        ),
    ],
)
def test_latch_and_unlatch_types(mp, element: str, expected) -> None:
    tags = run(
        mp, cam_decl("cam", element), {0: JOG + maoc(), **ENABLE_SCANS}, ["outw.0@edges"], 250
    )
    assert_edges(tags["outw.0@edges"], expected)


def test_inverted_input_enable_follows_the_inverse_of_the_bit(mp) -> None:
    # Enable latch / Enable unlatch on Inverted Input bit 3: the enable is on from the
    # start (Input 0) -- nothing switches at arming (decision 0108) --, goes off at 0.050
    # (unlatch: the element was never on, no edge), comes on at 0.080: the bit is set
    tags = run(
        mp,
        cam_decl("cam", el(latch=2, unlatch=3, EnableType=1, EnableBit=3)),
        {0: JOG + maoc(), **ENABLE_SCANS},
        ["outw.0@edges"],
        200,
    )
    assert_edges(tags["outw.0@edges"], [(0.080, 1)])


def test_output_enable_type_reads_the_output_word(mp) -> None:
    # the element (bit 1) is enabled by Output bit 5, which the program sets in scan 50
    # and clears in scan 90 (edges at the start of the next update)
    tags = run(
        mp,
        cam_decl("cam", el(bit=1, latch=2, unlatch=3, EnableType=2, EnableBit=5)),
        {0: JOG + maoc(), 50: "outw.5 := 1;", 90: "outw.5 := 0;"},
        ["outw.1@edges", "outw"],
        200,
    )
    assert_edges(tags["outw.1@edges"], [(0.050, 1), (0.090, 0)])
    assert tags["outw"] == 0


# ----------------------------------------------------------------- output modes
def _comp(mode: int, cycle: float = 0.0, duty: float = 0.0) -> str:
    return (
        f"  comp : OUTPUT_COMPENSATION[1] := [(Mode := {mode}, CycleTime := {cycle}, "
        f"DutyCycle := {duty})];\n"
    )


def test_inverted_mode(mp) -> None:
    # Inverted: the bit is set when the element turns inactive (x = 20); entering writes 0,
    # which the word already holds (no edge)
    decls = cam_decl("cam", el()) + _comp(1)
    tags = run(mp, decls, {0: JOG + maoc()},
               ["outw.0@edges"], 300)  # fmt: skip
    assert_edges(tags["outw.0@edges"], [(tf(20), 1)])


def test_pulsed_mode(mp) -> None:
    # Pulsed, CycleTime 10 ms, DutyCycle 30 %: while x is in [10, 19.5] (0.1015 .. 0.1965
    # s) on at 0.1015 + 0.01 k, off 3 ms later, k = 0..9; the exit falls between pulses
    tags = run(mp, cam_decl("cam", el(right=19.5)) + _comp(2, 0.01, 30.0), {0: JOG + maoc()},
               ["outw.0@edges"], 300)  # fmt: skip
    expected = []
    for k in range(10):
        expected += [(tf(10) + 0.01 * k, 1), (tf(10) + 0.01 * k + 0.003, 0)]
    assert_edges(tags["outw.0@edges"], expected)


def test_inverted_and_pulsed_mode(mp) -> None:
    # the complement of Pulsed: off during each 3 ms pulse, on between; the bit is 0 when
    # the window is entered, so the first edge is the end of the first pulse (0.1045); the
    # exit (0.1965) sets the bit, which is already on
    tags = run(mp, cam_decl("cam", el(right=19.5)) + _comp(3, 0.01, 30.0), {0: JOG + maoc()},
               ["outw.0@edges"], 300)  # fmt: skip
    expected = [(tf(10) + 0.003, 1)]
    for k in range(1, 10):
        expected += [(tf(10) + 0.01 * k, 0), (tf(10) + 0.01 * k + 0.003, 1)]
    assert_edges(tags["outw.0@edges"], expected)


# ----------------------------------------------------------------- compensation
def test_offset_and_delays_forward(mp) -> None:
    # Offset 2, LatchDelay 10 ms, UnlatchDelay 5 ms at v = 100:
    # latch at Left + Offset - v LatchDelay = 10 + 2 - 1 = 11,
    # unlatch at Right + Offset - v UnlatchDelay = 20 + 2 - 0.5 = 21.5
    decls = cam_decl("cam", el()) + (
        "  comp : OUTPUT_COMPENSATION[1] := [(Offset := 2.0, LatchDelay := 0.01, "
        "UnlatchDelay := 0.005)];\n"
    )
    tags = run(mp, decls, {0: JOG + maoc()}, ["outw.0@edges"], 300)
    assert_edges(tags["outw.0@edges"], [(tf(11), 1), (tf(21.5), 0)])


def test_offset_and_delays_mirrored_in_reverse(mp) -> None:
    # reverse at v = -100, window [-20, -10] of a [-50, 0] cam, Offset 2:
    # latch at Right + Offset - v LatchDelay = -10 + 2 + 1 = -7,
    # unlatch at Left + Offset - v UnlatchDelay = -20 + 2 + 0.5 = -17.5
    decls = cam_decl("cam", el(left=-20.0, right=-10.0)) + (
        "  comp : OUTPUT_COMPENSATION[1] := [(Offset := 2.0, LatchDelay := 0.01, "
        "UnlatchDelay := 0.005)];\n"
    )
    at = {0: JOG.replace("jog, forward", "jog, reverse") + maoc(start=-50.0, end=0.0)}
    tags = run(mp, decls, at, ["outw.0@edges"], 300)
    assert_edges(tags["outw.0@edges"], [(tneg(-7), 1), (tneg(-17.5), 0)])


def test_duration_is_compensated_by_both_delays(mp) -> None:
    # Duration 30 ms, LatchDelay 10 ms, UnlatchDelay 5 ms: latch at 10 - 1 = 9, off
    # Duration + LatchDelay - UnlatchDelay = 35 ms later
    decls = cam_decl("cam", el(unlatch=2, Duration=0.03)) + (
        "  comp : OUTPUT_COMPENSATION[1] := [(LatchDelay := 0.01, UnlatchDelay := 0.005)];\n"
    )
    tags = run(mp, decls, {0: JOG + maoc()}, ["outw.0@edges"], 300)
    assert_edges(tags["outw.0@edges"], [(tf(9), 1), (tf(9) + 0.035, 0)])


def test_compensation_change_takes_effect_at_once(mp) -> None:
    # Offset 0 -> 5 written in scan 50 (x = 4.85): the window becomes [15, 25]
    tags = run(mp, cam_decl("cam", el()), {0: JOG + maoc(), 50: "comp[0].Offset := 5.0;"},
               ["outw.0@edges"], 300)  # fmt: skip
    assert_edges(tags["outw.0@edges"], [(tf(15), 1), (tf(25), 0)])


# ----------------------------------------------------------------- execution modes
def test_once_completes_when_the_cam_leaves_its_range(mp) -> None:
    tr_ = mp.trace(
        HEAD + cam_decl("cam", el()) + "END_VAR\n"
        f"IF k = 0 THEN {JOG} {maoc(end=50.0, mode='once')} END_IF;\nk := k + 1;\n",
        ["arm.IP", "arm.PC", "A.OutputCamStatus", "A.OutputCamLockStatus"],
        scans=700,
        args=["--coarse-update", "1"],
    )
    # x passes 50 at tf(50) = 0.5015 (update 0.502): PC set, IP and the words cleared
    before = [tr_.at(0.501, n) for n in ("arm.IP", "arm.PC", "A.OutputCamStatus")]
    after = [tr_.at(0.502, n) for n in ("arm.IP", "arm.PC", "A.OutputCamStatus")]
    assert (before, after) == ([1, 0, 1], [0, 1, 0])
    assert tr_.at(0.502, "A.OutputCamLockStatus") == 0


def test_continuous_wraps_the_range(mp) -> None:
    # [0, 50] continuous: the window [10, 20] comes back every 50 units (0.5 s)
    tags = run(mp, cam_decl("cam", el()), {0: JOG + maoc(end=50.0)}, ["outw.0@edges"], 1600)
    expected = []
    for k in range(3):
        expected += [(tf(10 + 50 * k), 1), (tf(20 + 50 * k), 0)]
    assert_edges(tags["outw.0@edges"], expected)


def test_persistent_stops_outside_the_range_and_rearms_on_return(mp) -> None:
    # forward through [10, 20], out past 50 (0.5015), back in at 50 in reverse (tr(50) =
    # 0.7025): in reverse the latch edge is Right (20), the unlatch edge Left (10)
    at = {0: JOG + maoc(end=50.0, mode="persistent"), 600: REV}
    src_tags = run(mp, cam_decl("cam", el()), at,
                   ["outw.0@edges", "A.OutputCamStatus", "arm.IP", "arm.PC"], 1300)  # fmt: skip
    assert_edges(src_tags["outw.0@edges"], [(tf(10), 1), (tf(20), 0), (tr(20), 1), (tr(10), 0)])
    assert (src_tags["A.OutputCamStatus"], src_tags["arm.IP"], src_tags["arm.PC"]) == (
        1,
        True,
        False,
    )


def test_persistent_lock_status_while_outside(mp) -> None:
    tr_ = mp.trace(
        HEAD + cam_decl("cam", el()) + "END_VAR\n"
        f"IF k = 0 THEN {JOG} {maoc(end=50.0, mode='persistent')} END_IF;\n"
        f"IF k = 600 THEN {REV} END_IF;\nk := k + 1;\n",
        ["A.OutputCamStatus", "A.OutputCamLockStatus"],
        scans=800,
        args=["--coarse-update", "1"],
    )
    # out at tf(50) = 0.5015, back at tr(50) = 0.7025: Lock off in between, Status stays
    assert [tr_.at(t, "A.OutputCamLockStatus") for t in (0.501, 0.502, 0.702, 0.703)] == [
        1,
        0,
        0,
        1,
    ]
    assert set(tr_.col("A.OutputCamStatus")) == {1.0}


# ----------------------------------------------------------------- schedules
def test_forward_only_locks_at_the_axis_arm_position(mp) -> None:
    # AxisArm 30, CamArm 0: cam = x - 30, window [10, 20] -> x in [40, 50]
    tags = run(mp, cam_decl("cam", el()),
               {0: JOG + maoc(end=50.0, mode="once", sched="forwardonly", axis_arm=30.0)},
               ["outw.0@edges", "arm.PC"], 700)  # fmt: skip
    assert_edges(tags["outw.0@edges"], [(tf(40), 1), (tf(50), 0)])


def test_reverse_only_ignores_forward_travel(mp) -> None:
    # AxisArm 40, CamArm 50: passed forward at 0.4015 (ignored), in reverse at tr(40):
    # cam = 50 + (x - 40); window [10, 20] -> x in [0, 10], latched at x = 10 (Right)
    at = {0: JOG + maoc(end=50.0, sched="reverseonly", axis_arm=40.0, cam_arm=50.0), 600: REV}
    tags = run(mp, cam_decl("cam", el()), at, ["outw.0@edges"], 1300)
    assert_edges(tags["outw.0@edges"], [(tr(10), 1), (tr(0), 0)])


def test_bidirectional_locks_in_reverse_too(mp) -> None:
    # reverse from rest; AxisArm -30, CamArm 0 on a [-50, 0] cam: cam = x + 30, window
    # [-20, -10] -> x in [-50, -40]; reverse: latch at x = -40, unlatch at -50
    at = {
        0: JOG.replace("jog, forward", "jog, reverse")
        + maoc(start=-50.0, end=0.0, sched="Bi-directional", axis_arm=-30.0)
    }
    tags = run(mp, cam_decl("cam", el(left=-20.0, right=-10.0)), at, ["outw.0@edges"], 600)
    assert_edges(tags["outw.0@edges"], [(tneg(-40), 1), (tneg(-50), 0)])


def test_pending_cam_takes_over_at_the_range_end(mp) -> None:
    # cam 1: once on [0, 50], window [10, 20] on bit 0; cam 2 pending from scan 100:
    # [0, 50], window [5, 15] on bit 1, starting at CamArm 0 when cam 1 passes 50 (x = 50)
    decls = cam_decl("cam", el()) + cam_decl("cam2", el(bit=1, left=5.0, right=15.0))
    at = {
        0: JOG + maoc(end=50.0, mode="once"),
        100: maoc(ctl="arm2", cam="cam2", end=50.0, mode="once", sched="pending"),
    }
    tags = run(mp, decls, at, ["outw@edges", "arm.PC", "arm2.IP", "arm2.DN"], 800)
    got = tags["outw@edges"]
    expected = [(tf(10), 0, 1), (tf(20), 0, 0), (tf(55), 1, 1), (tf(65), 1, 0)]
    assert len(got) == len(expected)
    for (t, b, v), (te, be, ve) in zip(got, expected, strict=True):
        assert (b, v) == (be, ve) and abs(t - te) <= US
    assert (tags["arm.PC"], tags["arm2.DN"], tags["arm2.IP"]) == (True, True, True)


def test_pending_and_transition_status_words(mp) -> None:
    decls = cam_decl("cam", el()) + cam_decl("cam2", el(bit=1, left=5.0, right=15.0))
    src = (
        HEAD + decls + "END_VAR\n"
        f"IF k = 0 THEN {JOG} {maoc(end=50.0, mode='once')} END_IF;\n"
        f"IF k = 100 THEN {maoc(ctl='arm2', cam='cam2', end=50.0, mode='once', sched='pending')} END_IF;\n"
        "k := k + 1;\n"
    )
    tr_ = mp.trace(src, ["A.OutputCamPendingStatus", "A.OutputCamTransitionStatus", "arm.PC"],
                   scans=600, args=["--coarse-update", "1"])  # fmt: skip
    # pending from its executing scan until the hand-over in the update 0.502 (x = 50 at
    # 0.5015); transition for that update only
    pend = [tr_.at(t, "A.OutputCamPendingStatus") for t in (0.099, 0.1, 0.501, 0.502)]
    trans = [tr_.at(t, "A.OutputCamTransitionStatus") for t in (0.501, 0.502, 0.503)]
    assert (pend, trans) == ([0, 1, 1, 0], [0, 1, 0])
    assert (tr_.at(0.501, "arm.PC"), tr_.at(0.502, "arm.PC")) == (0, 1)


# ----------------------------------------------------------------- narrow window
NARROW = cam_decl("cam", el(left=3.06, right=3.11))


def test_narrow_window_switches_once_per_pass_within_a_microsecond(mp) -> None:
    # [0, 10] continuous, window [3.06, 3.11]: 0.05 units wide, half of the 0.1 units the
    # axis travels per coarse update; one pass per 0.1 s: on at tf(3.06 + 10 k) = 0.0321 +
    # 0.1 k, off at tf(3.11 + 10 k) = 0.0326 + 0.1 k, both inside the update ending 0.033
    tags = run(mp, NARROW, {0: JOG + maoc(end=10.0)}, ["outw.0@edges", "outw"], 1000)
    expected = []
    for k in range(10):
        expected += [(tf(3.06 + 10 * k), 1), (tf(3.11 + 10 * k), 0)]
    assert_edges(tags["outw.0@edges"], expected)


# ----------------------------------------------------------------- array checks
@pytest.mark.parametrize(
    ("element", "exerr"),
    [
        (el(bit=32), 1),  # OutputBit outside 0..31: skipped
        (el(latch=7), 2),  # LatchType: Inactive used
        (el(unlatch=9), 3),  # UnlatchType: Inactive used
        (el(left=20.0, right=10.0), 4),  # Left >= Right with a position type: skipped
        (el(left=-5.0), 5),  # Left < CamStart: CamStart used
        (el(right=150.0), 6),  # Right > CamEnd: CamEnd used
        (el(unlatch=2, Duration=0.0), 8),  # Duration <= 0: skipped
        (el(latch=2, unlatch=3, EnableType=5), 9),  # EnableType: skipped
        (el(latch=2, unlatch=3, EnableBit=40), 10),  # EnableBit: skipped
        (el(latch=0, unlatch=2, Duration=0.1), 11),  # Inactive latch with Duration unlatch
    ],
)
def test_output_cam_array_checks(mp, element: str, exerr: int) -> None:
    # element 1 is the bad one: ERR 36, SEGMENT 1; element 0 still runs (DN, IP)
    tags = run(mp, cam_decl("cam", el(bit=2), element), {0: JOG + maoc()},
               ["arm.ER", "arm.ERR", "arm.EXERR", "arm.SEGMENT", "arm.DN", "arm.IP",
                "outw.2@edges"], 250)  # fmt: skip
    got = [tags[n] for n in ("arm.ER", "arm.ERR", "arm.EXERR", "arm.SEGMENT", "arm.DN", "arm.IP")]
    assert got == [True, 36, exerr, 1, True, True]
    assert_edges(tags["outw.2@edges"], [(tf(10), 1), (tf(20), 0)])


def test_substituted_left_and_right_switch_at_the_range_ends(mp) -> None:
    # cam range [5, 100] with CamArm 5: cam = x + 5. Element 0 Left -5 -> CamStart 5: the
    # cam starts inside it (nothing switches at arming), off at cam 20 = x 15; element 1
    # (bit 1) Right 150 -> CamEnd 100: on at cam 30 (x 25), off when the cam reaches 100
    # (x = 95, the end of the range; continuous: the window ends at the wrap)
    tags = run(mp, cam_decl("cam", el(left=-5.0), el(bit=1, left=30.0, right=150.0)),
               {0: JOG + maoc(start=5.0, cam_arm=5.0)}, ["outw.1@edges", "arm.SEGMENT"],
               1000)  # fmt: skip
    assert tags["arm.SEGMENT"] == 0
    assert_edges(tags["outw.1@edges"], [(tf(25), 1), (tf(95), 0)])


@pytest.mark.parametrize(
    ("comp", "exerr", "segment"),
    [
        ("[(Mode := 0), (Mode := 9)]", 1, 1),
        ("[(Mode := 0), (Mode := 2, CycleTime := 0.01, DutyCycle := 150.0)]", 2, 1),
        ("[(Mode := 0), (Mode := 0), (Mode := 3, CycleTime := 0.0, DutyCycle := 50.0)]", 3, 2),
    ],
)
def test_output_compensation_array_checks(mp, comp: str, exerr: int, segment: int) -> None:
    n = comp.count("(")
    decls = cam_decl("cam", el()) + f"  comp : OUTPUT_COMPENSATION[{n}] := {comp};\n"
    tags = run(mp, decls, {0: JOG + maoc()},
               ["arm.ER", "arm.ERR", "arm.EXERR", "arm.SEGMENT", "arm.IP"], 5)  # fmt: skip
    got = [tags[n] for n in ("arm.ER", "arm.ERR", "arm.EXERR", "arm.SEGMENT", "arm.IP")]
    assert got == [True, 37, exerr, segment, True]


def test_compensation_array_longer_than_32(mp) -> None:
    decls = cam_decl("cam", el()) + "  comp : OUTPUT_COMPENSATION[33];\n"
    tags = run(mp, decls, {0: JOG + maoc()}, ["arm.ERR", "arm.EXERR", "arm.SEGMENT"], 5)
    assert [tags[n] for n in ("arm.ERR", "arm.EXERR", "arm.SEGMENT")] == [37, 4, 32]


def test_output_cam_error_reported_before_compensation_error(mp) -> None:
    decls = (
        cam_decl("cam", el(), el(bit=40)) + "  comp : OUTPUT_COMPENSATION[1] := [(Mode := 9)];\n"
    )
    tags = run(mp, decls, {0: JOG + maoc()}, ["arm.ERR", "arm.SEGMENT"], 5)
    assert (tags["arm.ERR"], tags["arm.SEGMENT"]) == (36, 1)


@pytest.mark.parametrize(
    ("call", "err", "exerr"),
    [
        (maoc(target=8), 35, 0),  # execution target outside 0..7
        (maoc(start=50.0, end=50.0), 13, 7),  # CamStart >= CamEnd
        (maoc(cam_arm=120.0), 13, 12),  # CamArm outside the range
    ],
)
def test_refusals(mp, call: str, err: int, exerr: int) -> None:
    tags = run(mp, cam_decl("cam", el()), {0: call},
               ["arm.ER", "arm.ERR", "arm.EXERR", "arm.DN", "arm.IP"], 5)  # fmt: skip
    got = [tags[n] for n in ("arm.ER", "arm.ERR", "arm.EXERR", "arm.DN", "arm.IP")]
    assert got == [True, err, exerr, False, False]


def test_directional_arm_while_locked_is_an_illegal_dynamic_change(mp) -> None:
    tags = run(mp, cam_decl("cam", el()),
               {0: JOG + maoc(), 10: maoc(ctl="arm2", sched="forwardonly", axis_arm=50.0)},
               ["arm2.ER", "arm2.ERR", "arm.IP"], 20)  # fmt: skip
    assert (tags["arm2.ER"], tags["arm2.ERR"], tags["arm.IP"]) == (True, 23, True)


# ----------------------------------------------------------------- MDOC and stops
def test_mdoc_specific_and_all(mp) -> None:
    # targets 0 and 1 run the same window on bits 0 and 1 of different words; MDOC Specific
    # on target 1 in scan 150 (x = 14.85, inside the window: bit 1 keeps its 1), MDOC All
    # in scan 400 ends target 0 (which switched at 10 and 20 and would again at 110)
    decls = cam_decl("cam", el()) + cam_decl("cam2", el(bit=1)) + "  out2 : DINT;\n"
    at = {
        0: JOG + maoc(end=100.0) + maoc(ctl="arm2", cam="cam2", target=1, out="out2"),
        150: "MDOC(A, 1, dis, specific);",
        400: "MDOC(A, 5, stp, all);",
    }
    tags = run(mp, decls, at, ["outw.0@edges", "out2.1@edges", "out2", "arm.IP", "arm.PC",
                               "arm2.IP", "arm2.PC", "dis.DN", "stp.DN", "A.OutputCamStatus"],
               1300)  # fmt: skip
    assert_edges(tags["outw.0@edges"], [(tf(10), 1), (tf(20), 0)])
    assert_edges(tags["out2.1@edges"], [(tf(10), 1)])
    assert tags["out2"] == 2  # outputs keep their last state
    assert [tags[n] for n in ("arm.IP", "arm.PC", "arm2.IP", "arm2.PC")] == [False] * 4
    assert (tags["dis.DN"], tags["stp.DN"], tags["A.OutputCamStatus"]) == (True, True, 0)


def test_mdoc_status_word_clears_in_its_scan(mp) -> None:
    src = (
        HEAD + cam_decl("cam", el()) + "END_VAR\n"
        f"IF k = 0 THEN {JOG} {maoc()} {maoc(ctl='arm2', target=3)} END_IF;\n"
        "IF k = 50 THEN MDOC(A, 3, dis, specific); END_IF;\nk := k + 1;\n"
    )
    tr_ = mp.trace(src, ["A.OutputCamStatus", "arm2.IP", "dis.ER"], scans=60,
                   args=["--coarse-update", "1"])  # fmt: skip
    # targets 0 and 3: 0b1001; MDOC Specific 3 leaves 0b0001 in its scan, the MAOC's IP
    # clears at the next update
    assert [tr_.at(t, "A.OutputCamStatus") for t in (0.049, 0.05)] == [9, 1]
    assert [tr_.at(t, "arm2.IP") for t in (0.05, 0.051)] == [1, 0]


def test_mdoc_bad_disarm_type_and_target(mp) -> None:
    tags = run(mp, "", {0: "MDOC(A, 9, dis, specific); MDOC(A, 0, stp, all);"},
               ["dis.ER", "dis.ERR", "stp.DN", "stp.ER"], 3)  # fmt: skip
    assert [tags[n] for n in ("dis.ER", "dis.ERR", "stp.DN", "stp.ER")] == [True, 35, True, False]


def test_a_stop_does_not_disarm_output_cams(mp) -> None:
    # MAS in scan 150 (x = 14.85, inside [10, 20]): the axis stops at once-ish (decel 1e5),
    # the cam stays armed and the bit stays on
    at = {0: JOG + maoc(), 150: "MAS(A, stp, all, no, 0.0, unitspersec2, no, 0.0, unitspersec3);"}
    tags = run(mp, cam_decl("cam", el()), at,
               ["outw", "A.OutputCamStatus", "arm.IP", "A.OutputCamLockStatus"], 300)  # fmt: skip
    assert [tags[n] for n in ("outw", "A.OutputCamStatus", "arm.IP")] == [1, 1, True]


# ----------------------------------------------------------------- ladder
LADDER = """VAR
  A : AXIS_VIRTUAL := (MaximumSpeed := 1000.0, MaximumAccel := 100000.0, MaximumDecel := 100000.0);
  jog, arm : MOTION_INSTRUCTION;
  cam : OUTPUT_CAM[1] := [(OutputBit := 4, LatchType := 1, UnlatchType := 1, Left := 10.0, Right := 20.0)];
  comp : OUTPUT_COMPENSATION[5] := [(Offset := 0.0), (Offset := 0.0), (Offset := 0.0), (Offset := 0.0), (LatchDelay := 0.01)];
  outw, inw : DINT;
  go : BOOL;
  k : DINT;
END_VAR
XIC(go)MAJ(A,jog,Forward,100.0,Units per sec,100000.0,Units per sec2,100000.0,Units per sec2,Trapezoidal,0.0,0.0,Units per sec3,Disabled,Programmed,0.0,None)MAOC(A,0,arm,outw,inw,cam,0.0,100.0,comp,Once,Immediate,0.0,0.0,Actual);
ADD(k,1,k);
GEQ(k,10)OTE(go);
"""


def test_maoc_in_a_ladder_rung(mp) -> None:
    # go from scan 10: jog and cam (bit 4 is compensated by comp[4]) from the update 0.011 (interval start 0.010, x = 0);
    # x(t) = 100 (t - 0.011) - 0.05. LatchDelay 10 ms: latch at 10 - 1 = 9 -> t = 0.1015,
    # unlatch at 20 -> t = 0.2115; Once on [0, 100]: PC at x = 100, t = 1.0115
    prog = mp.tmp / "prog.rll"
    prog.write_text(LADDER)
    from interpreter.cli import main

    mp.capsys.readouterr()
    code = main(["run", str(prog), "--scans", "1100", "--coarse-update", "1", "--json",
                 "--watch", "outw.4@edges", "--watch", "arm.PC", "--watch", "arm.EN"])  # fmt: skip
    out = mp.capsys.readouterr().out
    assert code == 0
    tags = json.loads(out)["tags"]
    assert_edges(tags["outw.4@edges"], [(0.1015, 1), (0.2115, 0)])
    assert (tags["arm.PC"], tags["arm.EN"]) == (True, True)


# ----------------------------------------------------------------- sub-tick edges (0113)


def test_trace_cells_hold_the_edges_of_the_scan(mp) -> None:
    prog = mp.tmp / "prog.st"
    prog.write_text(head(NARROW) + NARROW + "END_VAR\n"
                    f"IF k = 0 THEN {JOG} {maoc(end=10.0)} END_IF;\nk := k + 1;\n")  # fmt: skip
    out = mp.tmp / "t.csv"
    from interpreter.cli import main

    mp.capsys.readouterr()
    code = main(["run", str(prog), "--scans", "250", "--coarse-update", "1", "--trace", str(out),
                 "--watch", "outw", "--watch", "outw.0@edges", "--watch", "OUTW@Edges"])  # fmt: skip
    assert code == 0
    import csv

    rows = list(csv.reader(out.open()))
    assert rows[0] == ["time", "outw", "outw.0@edges", "OUTW@Edges"]
    cells = {r[0]: (r[2], r[3]) for r in rows[1:] if r[2]}
    # tf(3.06) = 0.0321 and tf(3.11) = 0.0326: both in the update 0.033, shown in the row
    # of the scan 0.033; the word itself never shows the pulse
    assert list(cells) == ["0.033", "0.133", "0.233"]
    assert {r[1] for r in rows[1:]} == {"0"}
    bit, both = cells["0.033"]
    # TIME:VALUE per edge (TIME:BIT:VALUE for the word); Left/Right are REAL, so the
    # instants are those of the float32 window edges, within 1 µs of the closed form
    assert [c.rsplit(":", 1)[1] for c in bit.split()] == ["1", "0"]
    for cell, te in zip(bit.split(), (tf(3.06), tf(3.11)), strict=True):
        assert abs(float(cell.split(":")[0]) - te) <= US and len(cell.split(":")[0]) == 11
    assert [c.split(":", 1)[1] for c in both.split()] == ["0:1", "0:0"]


def test_edges_of_a_real_tag_is_a_usage_error(mp) -> None:
    code, _, err = mp.run(head("") + "  r : REAL;\nEND_VAR\nk := k + 1;\n",
                          ["--scans", "2", "--watch", "r@edges"])  # fmt: skip
    assert code == 2 and "@edges" in err and "Traceback" not in err


def test_plot_draws_an_edges_lane(mp, tmp_path) -> None:
    png = tmp_path / "oc.png"
    code, _, err = mp.run(
        head(NARROW) + NARROW + "END_VAR\n"
        f"IF k = 0 THEN {JOG} {maoc(end=10.0)} END_IF;\nk := k + 1;\n",
        ["--scans", "300", "--coarse-update", "1", "--plot", str(png), "--watch",
         "A.ActualPosition", "--watch", "outw.0", "--watch", "outw.0@edges"],
    )  # fmt: skip
    assert code == 0, err
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


# ----------------------------------------------------------------- rotary axes (0115)
ROTARY = HEAD.replace(
    "A : AXIS_VIRTUAL := (", "A : AXIS_VIRTUAL := (RotaryAxis := 1, PositionUnwind := 360.0, "
)


def run_rotary(mp, decls: str, at: dict[int, str], watch: list[str], scans: int) -> dict:
    body = "".join(f"IF k = {k} THEN {s} END_IF;\n" for k, s in sorted(at.items()))
    src = ROTARY + decls + "END_VAR\n" + body + "k := k + 1;\n"
    argv = ["--scans", str(scans), "--coarse-update", "1", "--json"]
    for w in watch:
        argv += ["--watch", w]
    code, out, err = mp.run(src, argv)
    assert code == 0 and "Traceback" not in err, (code, err, out[:2000])
    return json.loads(out)["tags"]


def test_rotary_window_across_the_unwind(mp) -> None:
    # A unwinds at 360 (positions in [0, 360)); the unwrapped travel is 100 t - 0.15.
    # Continuous cam [0, 360]; bit 0 is on over [350, 360] and [0, 10]: on at the unwrapped
    # 350 (t = 3.5015) and off at 370 (3.7015), again at 710 / 730; the two elements hand
    # over at the wrap without switching the bit (decision 0114)
    decls = cam_decl("cam", el(left=350.0, right=360.0), el(left=0.0, right=10.0))
    tags = run_rotary(mp, decls, {0: JOG + maoc(end=360.0)},
                      ["outw.0@edges", "A.ActualPosition"], 7400)  # fmt: skip
    assert_edges(tags["outw.0@edges"], [(tf(350), 1), (tf(370), 0), (tf(710), 1), (tf(730), 0)])
    assert 0.0 <= tags["A.ActualPosition"] < 360.0


def test_rotary_forward_only_arms_once_per_revolution_position(mp) -> None:
    # Forward only at AxisArm 90 on the rotary axis, armed in scan 1000 (x = 99.85, just past
    # 90): it locks at the next pass of 90, the unwrapped 450 (t = 4.5015), with CamArm 0:
    # window [10, 20] -> unwrapped 460 .. 470; Once on [0, 100]
    tags = run_rotary(mp, cam_decl("cam", el()),
                      {0: JOG, 1000: maoc(end=100.0, mode="once", sched="forwardonly",
                                          axis_arm=90.0)},
                      ["outw.0@edges", "arm.PC"], 5600)  # fmt: skip
    assert_edges(tags["outw.0@edges"], [(tf(460), 1), (tf(470), 0)])
    assert tags["arm.PC"] is True  # cam 100 passed at the unwrapped 550 (t = 5.5015)


# ----------------------------------------------------------------- checker (catalog rules)
def test_checker_knows_the_operand_rules_from_the_catalog(mp) -> None:
    # ExecutionMode/ExecutionSchedule/Reference and DisarmType are immediate enumerations
    # (E107 for a tag, E108 for an unknown text); Axis must be an axis (E113); OutputCam and
    # OutputCompensation take their own array types (E105); Output must be a tag (E106)
    src = head("") + cam_decl("cam", el()) + "  r : REAL;\n  m : DINT;\nEND_VAR\n" + "\n".join([
        "IF k = 0 THEN",
        "MAOC(A, 0, arm, outw, inw, cam, 0.0, 100.0, comp, persistent, forwardonly, 0.0, 0.0, command);",
        "MAOC(A, 0, arm2, outw, inw, cam, 0.0, 100.0, comp, once, Bi-directional, 0.0, 0.0, actual);",
        "MAOC(A, 0, arm, outw, inw, cam, 0.0, 100.0, comp, m, pending, 0.0, 0.0, actual);",
        "MAOC(A, 0, arm, outw, inw, cam, 0.0, 100.0, comp, sometimes, pending, 0.0, 0.0, actual);",
        "MAOC(r, 0, arm, outw, inw, cam, 0.0, 100.0, comp, once, pending, 0.0, 0.0, actual);",
        "MAOC(A, 0, arm, outw, inw, comp, 0.0, 100.0, cam, once, pending, 0.0, 0.0, actual);",
        "MAOC(A, 0, arm, 5, inw, cam, 0.0, 100.0, comp, once, pending, 0.0, 0.0, actual);",
        "MDOC(A, 0, dis, specific); MDOC(A, 0, stp, all); MDOC(A, 0, dis, m);",
        "END_IF;",
    ]) + "\n"  # fmt: skip
    prog = mp.tmp / "chk.st"
    prog.write_text(src)
    from interpreter.cli import main

    mp.capsys.readouterr()
    code = main(["check", str(prog), "--format", "json"])
    diags = json.loads(mp.capsys.readouterr().out)
    errors = sorted((d["line"], d["code"]) for d in diags if d["severity"] == "error")
    first = src.count("\n", 0, src.index("IF k = 0")) + 1  # line of IF k = 0
    assert code == 1
    assert errors == [
        (first + 3, "E107"), (first + 4, "E108"), (first + 5, "E113"),
        (first + 6, "E105"), (first + 6, "E105"), (first + 7, "E106"), (first + 8, "E107"),
    ]  # fmt: skip


def test_reference_command_and_actual_on_a_drive_axis(mp) -> None:
    # a drive axis (servo model lag) jogged like A: its command position is 100 t - 0.15
    # (MSO and the jog in scan 0), its actual position lags behind. Reference Command
    # switches at the closed form of the command; Reference Actual later, by the lag
    decls = (
        "  D : AXIS_CIP_DRIVE := (MaximumSpeed := 1000.0, MaximumAccel := 100000.0, "
        "MaximumDecel := 100000.0, PositionLoopBandwidth := 20.0);\n  so : MOTION_INSTRUCTION;\n"
        "  out2 : DINT;\n" + cam_decl("cam", el())
    )
    jog = JOG.replace("MAJ(A,", "MAJ(D,")
    at = {0: "MSO(D, so); " + jog
          + maoc(ref="command").replace("MAOC(A,", "MAOC(D,")
          + maoc(ctl="arm2", target=1, out="out2").replace("MAOC(A,", "MAOC(D,")}  # fmt: skip
    tags = run(mp, decls, at, ["outw.0@edges", "out2.0@edges"], 300)
    assert_edges(tags["outw.0@edges"], [(tf(10), 1), (tf(20), 0)])
    # first-order lag, tau = 1 / (2 pi 20) = 8 ms: at steady speed actual trails command by
    # v tau = 0.8 units, i.e. the actual crosses each level about 8 ms later
    actual = tags["out2.0@edges"]
    assert [v for _, v in actual] == [1, 0]
    for (t, _), te in zip(actual, (tf(10), tf(20)), strict=True):
        assert 0.007 < t - te < 0.009, actual


def test_inverted_output_enable_type(mp) -> None:
    # Inverted Output bit 5: enabled while outw.5 = 0 -- on from the start (nothing switches
    # at arming), off at 0.050 (the element was never on: no edge), on again at 0.090: set
    tags = run(
        mp,
        cam_decl("cam", el(bit=1, latch=2, unlatch=3, EnableType=3, EnableBit=5)),
        {0: JOG + maoc(), 50: "outw.5 := 1;", 90: "outw.5 := 0;"},
        ["outw.1@edges", "outw"],
        200,
    )
    assert_edges(tags["outw.1@edges"], [(0.090, 1)])
    assert tags["outw"] == 2
