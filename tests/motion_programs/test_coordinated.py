"""MCLM, MCCM and MCS through `logixst run`, against closed forms (issue 12).

Timing as everywhere (motion_trace.py): a move executed in the scan at 0 starts at the
update t0 = 2 ms and completes (PC) at the first update at or after t0 + T.
Vector profile along the path (length L, speed V, accel = decel A, reaching V):
  trapezoid: T = L/V + V/A (each ramp V/A long, covering V^2/(2A));
  S-curve at 100 % of Time: J = A^2/V, each ramp lasts V/A + A/J = 2V/A (the doubled
  ramp) and covers V^2/A, so T = L/V + 2V/A.
"""

from __future__ import annotations

import math

import pytest
from motion_trace import CUP

T0 = 0.002
F32 = 2e-4
HEAD = """VAR
  X, Y, Z : AXIS_VIRTUAL := (MaximumSpeed := 100.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0);
  XY : COORDINATE_SYSTEM := (Axes := [X, Y], MaximumSpeed := 20.0, MaximumAccel := 1000.0,
                             MaximumDecel := 1000.0, MaximumAccelJerk := 8000.0, MaximumDecelJerk := 8000.0);
  c1, c2, c3, c4 : MOTION_INSTRUCTION;
  p1 : REAL[2] := [30.0, 40.0];
  p2 : REAL[2] := [60.0, 80.0];
  p3 : REAL[2] := [90.0, 120.0];
  ctr : REAL[2] := [10.0, 0.0];
  k : DINT;
"""


def prog(decls: str, body: str) -> str:
    return HEAD + decls + "END_VAR\n" + body + "\nk := k + 1;\n"


def mclm(
    ctl: str,
    pos: str,
    v: float = 10.0,
    a: float = 100.0,
    d: float = 100.0,
    *,
    tt: int | str = 1,
    shape: str = "trapezoidal",
    ja: float = 100.0,
    jd: float = 100.0,
    ju: str = "%oftime",
    su: str = "unitspersec",
    au: str = "unitspersec2",
    mtype: str = "0",
    merge: str = "disabled",
    ct: float = 0.0,
    cs: str = "XY",
    ms: str = "programmed",
) -> str:
    return (
        f"MCLM({cs}, {ctl}, {mtype}, {pos}, {v}, {su}, {a}, {au}, {d}, {au}, {shape}, {ja}, {jd}, "
        f"{ju}, {tt}, {merge}, {ms}, {ct}, 0, none, 0, 0);"
    )


def mccm(
    ctl: str,
    pos: str,
    ctype: int | str,
    aux: str,
    direction: int | str,
    v: float = 10.0,
    a: float = 100.0,
    *,
    tt: int | str = 1,
    mtype: int | str = 0,
) -> str:
    return (
        f"MCCM(XY, {ctl}, {mtype}, {pos}, {ctype}, {aux}, {direction}, {v}, unitspersec, {a}, "
        f"unitspersec2, {a}, unitspersec2, trapezoidal, 100.0, 100.0, %oftime, {tt}, disabled, "
        "programmed, 0.0, 0, none, 0, 0);"
    )


def once(stmt: str) -> str:
    return f"IF k = 0 THEN {stmt} END_IF;"


def pc_time(tr, ctl: str) -> float:  # noqa: ANN001
    return tr.first(f"{ctl}.PC", lambda v: v == 1)


def assert_completes(tr, ctl: str, t_end: float) -> None:  # noqa: ANN001
    t = pc_time(tr, ctl)
    assert t_end - 1e-9 <= t <= t_end + CUP + 1e-9, (t, t_end)


def test_trapezoid_line_duration_end_point_and_bits(mp) -> None:
    # L = |(30, 40)| = 50, V 10, A 100: T = 5 + 0.1 = 5.1 s; the ramps last 0.1 s
    tr = mp.trace(
        prog("", once(mclm("c1", "p1"))),
        [
            "X.CommandPosition", "Y.CommandPosition", "XY.VectorCommandVelocity", "c1.DN",
            "c1.IP", "c1.AC", "c1.PC", "c1.ACCEL", "c1.DECEL", "XY.MoveStatus",
            "XY.AccelStatus", "XY.DecelStatus", "XY.MotionStatus", "X.CoordinatedMotionStatus",
            "XY.CommandPosToleranceStatus", "XY.CommandPosition[0]", "XY.ReadyStatus",
            "XY.CoordinateSystemStatus",
        ],
        scans=5300,
    )  # fmt: skip
    # virtual axes are always ready; ReadyStatus is bit 1, MotionStatus bit 2 of the word
    assert tr.at(0.0, "XY.ReadyStatus") == 1
    assert tr.at(0.05, "XY.CoordinateSystemStatus") == 2 + 4
    assert_completes(tr, "c1", T0 + 5.1)
    assert tr.col("X.CommandPosition")[-1] == 30.0
    assert tr.col("Y.CommandPosition")[-1] == 40.0
    assert tr.col("XY.CommandPosition[0]")[-1] == 30.0
    # the path is the line: y = 4/3 x everywhere
    for x, y in zip(tr.col("X.CommandPosition"), tr.col("Y.CommandPosition"), strict=True):
        assert y == pytest.approx(4.0 / 3.0 * x, abs=F32)
    # executing scan: DN and IP; the move goes active at the first update
    assert [tr.at(0.0, n) for n in ("c1.DN", "c1.IP", "c1.PC")] == [1, 1, 0]
    at = {n: tr.at(0.05, n) for n in ("c1.AC", "c1.ACCEL", "XY.AccelStatus", "XY.MoveStatus")}
    assert at == {"c1.AC": 1, "c1.ACCEL": 1, "XY.AccelStatus": 1, "XY.MoveStatus": 1}
    assert tr.at(0.05, "X.CoordinatedMotionStatus") == 1
    assert tr.at(0.05, "XY.MotionStatus") == 1
    # cruise at 10 units/s: 6 units/s on X, 8 on Y
    assert tr.at(2.0, "XY.VectorCommandVelocity") == pytest.approx(10.0, abs=1e-4)
    assert [tr.at(5.05, n) for n in ("c1.DECEL", "XY.DecelStatus")] == [1, 1]
    end = [tr.at(5.2, n) for n in ("c1.IP", "c1.AC", "c1.PC", "XY.MoveStatus")]
    assert end == [0, 0, 1, 0]
    assert tr.at(5.2, "X.CoordinatedMotionStatus") == 0
    assert tr.at(5.2, "XY.CommandPosToleranceStatus") == 1  # kept after the move


def test_s_curve_at_100_percent_of_time_doubles_the_ramps(mp) -> None:
    # J = A^2/V = 1000: ramps 2V/A = 0.2 s each: T = 5 + 0.2 = 5.2 s; the first jerk phase
    # (V/A = 0.1 s) gives s = J t^3 / 6
    tr = mp.trace(
        prog("", once(mclm("c1", "p1", shape="s-curve"))),
        ["X.CommandPosition", "Y.CommandPosition", "c1.PC"],
        scans=5400,
    )
    assert_completes(tr, "c1", T0 + 5.2)
    t = 0.05
    s = 1000.0 * t**3 / 6.0
    assert tr.at(T0 + t, "X.CommandPosition") == pytest.approx(0.6 * s, abs=F32)
    assert tr.at(T0 + t, "Y.CommandPosition") == pytest.approx(0.8 * s, abs=F32)
    assert tr.col("X.CommandPosition")[-1] == 30.0


def test_s_curve_jerk_in_units_and_percent_of_maximum(mp) -> None:
    # 50 % of MaximumAccelJerk 8000 = 4000 units/s^3 = A^2/V * (200/p - 1) with p = 40 %:
    # ramps V/A + A/J = 0.1 + 0.025 s: T = 5 + 0.125 = 5.125 s (both programs)
    for ja, ju in ((50.0, "%ofmaximum"), (4000.0, "unitspersec3"), (40.0, "%oftime")):
        tr = mp.trace(
            prog("", once(mclm("c1", "p1", shape="s-curve", ja=ja, jd=ja, ju=ju))),
            ["c1.PC"],
            scans=5300,
        )
        assert_completes(tr, "c1", T0 + 5.125)


def test_percent_of_maximum_speed_and_accel(mp) -> None:
    # 50 % of the system's MaximumSpeed 20 = 10; 10 % of MaximumAccel/Decel 1000 = 100:
    # T = 5.1 s as with units
    src = prog("", once(mclm("c1", "p1", 50.0, 10.0, 10.0, su="%ofmaximum", au="%ofmaximum")))
    tr = mp.trace(src, ["XY.VectorCommandVelocity", "c1.PC"], scans=5200)
    assert tr.at(2.0, "XY.VectorCommandVelocity") == pytest.approx(10.0, abs=1e-4)
    assert_completes(tr, "c1", T0 + 5.1)


def test_incremental_move_starts_from_the_queued_end_point(mp) -> None:
    # two incremental moves of (30, 40) queued in one scan end at (60, 80)
    body = once(mclm("c1", "p1", mtype="1") + mclm("c2", "p1", mtype="1"))
    tr = mp.trace(prog("", body), ["X.CommandPosition", "Y.CommandPosition", "c2.PC"], scans=10500)
    assert_completes(tr, "c2", T0 + 2 * 5.1)
    assert tr.col("X.CommandPosition")[-1] == 60.0
    assert tr.col("Y.CommandPosition")[-1] == 80.0


def test_full_circle_about_a_centre_traces_the_circle(mp) -> None:
    # 2D Center with end = start: a full circle of radius 10 about (10, 0) from (0, 0), CCW:
    # L = 20 pi, T = L/V + V/A = 2 pi + 0.1 s; a quarter of the way (s = L/4 after
    # V/A + (5 pi - V^2/(2A))/V s) the point is the bottom (10, -10); every point is at
    # radius 10
    decls = "  here : REAL[2];\n"
    tr = mp.trace(
        prog(decls, once(mccm("c1", "here", 1, "ctr", 1))),
        ["X.CommandPosition", "Y.CommandPosition", "c1.PC", "c1.ER"],
        scans=6500,
    )
    assert tr.col("c1.ER")[0] == 0
    assert_completes(tr, "c1", T0 + 2 * math.pi + 0.1)
    for x, y in zip(tr.col("X.CommandPosition"), tr.col("Y.CommandPosition"), strict=True):
        assert math.hypot(x - 10.0, y) == pytest.approx(10.0, abs=F32)
    # CCW from (0, 0) about (10, 0): the first quarter goes through (10, -10)
    t_quarter = T0 + 0.1 + (5.0 * math.pi - 0.5) / 10.0
    row = round(t_quarter / CUP) * CUP
    assert tr.at(row, "X.CommandPosition") == pytest.approx(10.0, abs=0.03)
    assert tr.at(row, "Y.CommandPosition") == pytest.approx(-10.0, abs=1e-3)
    assert tr.col("X.CommandPosition")[-1] == pytest.approx(0.0, abs=1e-6)
    assert tr.col("Y.CommandPosition")[-1] == pytest.approx(0.0, abs=1e-6)


def test_radius_arc_quarter_circle(mp) -> None:
    # from (0, 0) to (10, 10) with radius +10 CW: centre (10, 0)... the short arc, a quarter
    # circle: L = 5 pi; CW seen from +Z passes left of the chord, i.e. through x < y points
    decls = "  q : REAL[2] := [10.0, 10.0];\n"
    tr = mp.trace(
        prog(decls, once(mccm("c1", "q", 2, "10.0", 0))),
        ["X.CommandPosition", "Y.CommandPosition", "c1.PC", "c1.ER"],
        scans=1800,
    )
    assert_completes(tr, "c1", T0 + 5.0 * math.pi / 10.0 + 0.1)
    for x, y in zip(tr.col("X.CommandPosition"), tr.col("Y.CommandPosition"), strict=True):
        assert math.hypot(x - 10.0, y) == pytest.approx(10.0, abs=F32)
        assert y >= x - F32
    assert (tr.col("X.CommandPosition")[-1], tr.col("Y.CommandPosition")[-1]) == (10.0, 10.0)


def _vector_speed_at_junction(mp, tt: int, ct: float = 0.0) -> list[float]:  # noqa: ANN001
    """Two collinear (tangent) moves (0,0)->(30,40)->(60,80) queued at once with the given
    termination type of the first; vector speeds from the first cruise to the second's."""
    body = once(mclm("c1", "p1", tt=tt, ct=ct) + mclm("c2", "p2"))
    tr = mp.trace(prog("", body), ["XY.VectorCommandVelocity", "c1.PC", "c2.PC"], scans=10400)
    assert tr.col("c2.PC")[-1] == 1
    return [
        v
        for t, v in zip(tr.time(), tr.col("XY.VectorCommandVelocity"), strict=True)
        if 1.0 <= t <= 9.0
    ]


def test_command_tolerance_blend_keeps_the_vector_speed_up(mp) -> None:
    # termination 2 with the system's CommandTolerance 0.1: the blend starts 0.1 units before
    # the end, where the first move decelerates through sqrt(2 A 0.1) = 4.47 units/s; the
    # second accelerates at the same rate, so the sum holds there and never reaches zero.
    # The blend starts at the first update past that point: up to A * CUP = 0.2 slower.
    low = min(_vector_speed_at_junction(mp, 2))
    v_ct = math.sqrt(2 * 100.0 * 0.1)
    assert v_ct - 100.0 * CUP - 1e-4 <= low <= v_ct + 1e-4


@pytest.mark.parametrize("tt", [3, 4, 5])
def test_no_decel_blends_from_the_decel_point(mp, tt: int) -> None:
    # 3 (No Decel) starts the next move where the first starts to decelerate: with equal
    # accel and decel the two ramps add up to the cruise speed, 10 units/s throughout;
    # 4 and 5 (Follow Contour) blend the same way here (decision 0124)
    low = min(_vector_speed_at_junction(mp, tt))
    assert 10.0 - 100.0 * CUP - 1e-4 <= low <= 10.0 + 1e-4


def test_programmed_command_tolerance_uses_the_operand(mp) -> None:
    # 6 with the operand's CommandTolerance 0.2 (not the system's 0.1): the blend starts at
    # sqrt(2 A 0.2) = 6.32 units/s
    low = min(_vector_speed_at_junction(mp, 6, ct=0.2))
    v_ct = math.sqrt(2 * 100.0 * 0.2)
    assert v_ct - 100.0 * CUP - 1e-4 <= low <= v_ct + 1e-4


@pytest.mark.parametrize("tt", [0, 1])
def test_settling_terminations_stop_between_moves(mp, tt: int) -> None:
    assert min(_vector_speed_at_junction(mp, tt)) == 0.0


def test_move_transition_and_pending_status(mp) -> None:
    body = once(mclm("c1", "p1", tt=2) + mclm("c2", "p2"))
    tr = mp.trace(
        prog("", body),
        [
            "XY.MovePendingStatus", "XY.MovePendingQueueFullStatus", "XY.MoveTransitionStatus",
            "c1.AC", "c2.AC", "c2.IP", "c1.PC", "c1.IP", "XY.VectorCommandVelocity",
        ],
        scans=5200,
    )  # fmt: skip
    assert tr.at(1.0, "XY.MovePendingStatus") == 1
    assert tr.at(1.0, "XY.MovePendingQueueFullStatus") == 1
    assert [tr.at(1.0, n) for n in ("c1.AC", "c2.AC", "c2.IP")] == [1, 0, 1]
    # the blend starts 0.1 units before the end of the first move: 0.1 + (50 - 0.05)... at
    # t0 + 5.1 - sqrt(2 * 0.1 / A) = 5.057 s; it lasts until the first move's end (5.102)
    t_blend = T0 + 5.1 - math.sqrt(2 * 0.1 / 100.0)
    mid = round((t_blend + T0 + 5.1) / 2 / 0.001) * 0.001
    # both are active while they blend (AC clears with PC, seed); the moves are collinear, so
    # the axes stay on the path and MoveTransitionStatus stays clear (MCCM seed; a corner
    # blend sets it: tests/spec/test_spec_motion.py)
    assert [tr.at(mid, n) for n in ("XY.MoveTransitionStatus", "c2.AC", "c1.AC")] == [0, 1, 1]
    assert tr.at(mid, "XY.MovePendingStatus") == 0
    assert tr.at(5.15, "XY.MoveTransitionStatus") == 0
    assert [tr.at(5.15, n) for n in ("c1.PC", "c1.AC", "c1.IP")] == [1, 0, 0]


def test_a_third_move_while_one_is_queued_is_error_43(mp) -> None:
    body = once(mclm("c1", "p1") + mclm("c2", "p2") + mclm("c3", "p3"))
    tr = mp.trace(prog("", body), ["c3.ER", "c3.ERR", "c3.DN", "c2.DN", "c2.ER"], scans=3)
    assert [tr.at(0.0, n) for n in ("c3.ER", "c3.ERR", "c3.DN")] == [1, 43, 0]
    assert [tr.at(0.0, n) for n in ("c2.DN", "c2.ER")] == [1, 0]


def test_merge_coordinated_replaces_the_queue(mp) -> None:
    # a merging move while one runs and one waits: no error 43; the other two end (IP
    # cleared, no PC) and the system goes to p3
    body = once(mclm("c1", "p1") + mclm("c2", "p2")) + (
        f"IF k = 1000 THEN {mclm('c3', 'p3', merge='coordinatedmotion')} END_IF;"
    )
    tr = mp.trace(
        prog("", body),
        ["c1.IP", "c1.PC", "c2.IP", "c2.PC", "c3.ER", "c3.PC", "X.CommandPosition"],
        scans=16000,
    )
    end = {n: tr.col(n)[-1] for n in ("c1.IP", "c1.PC", "c2.IP", "c2.PC", "c3.ER", "c3.PC")}
    assert end == {"c1.IP": 0, "c1.PC": 0, "c2.IP": 0, "c2.PC": 0, "c3.ER": 0, "c3.PC": 1}
    assert tr.col("X.CommandPosition")[-1] == 90.0


def test_mcs_stops_within_the_decel_distance(mp) -> None:
    # cruising at 10 units/s, MCS at t = 2 s with DecelRate 50: v^2 / (2 d) = 1 unit; the
    # stop applies at the next update (one update of travel, 0.02, before it)
    body = once(mclm("c1", "p2")) + (
        "IF k = 2000 THEN MCS(XY, c2, 2, yes, 50.0, unitspersec2, no, 0.0, unitspersec3); END_IF;"
    )
    tr = mp.trace(
        prog("", body),
        [
            "X.CommandPosition", "Y.CommandPosition", "c1.IP", "c1.PC", "c2.IP", "c2.PC",
            "c2.DN", "XY.StoppingStatus", "XY.MoveStatus", "XY.VectorCommandVelocity",
        ],
        scans=3000,
    )  # fmt: skip
    at_mcs = math.hypot(tr.at(2.0, "X.CommandPosition"), tr.at(2.0, "Y.CommandPosition"))
    final = math.hypot(tr.col("X.CommandPosition")[-1], tr.col("Y.CommandPosition")[-1])
    assert 1.0 - F32 <= final - at_mcs <= 1.0 + 10.0 * CUP + F32
    assert [tr.at(2.0, n) for n in ("c2.DN", "c2.IP")] == [1, 1]
    assert [tr.at(2.1, n) for n in ("XY.StoppingStatus", "XY.MoveStatus", "c1.IP")] == [1, 0, 0]
    # at rest after 0.2 s: MCS completes, the move ended without PC
    assert [tr.at(2.3, n) for n in ("c2.PC", "c2.IP", "XY.StoppingStatus", "c1.PC")] == [
        1,
        0,
        0,
        0,
    ]
    assert tr.at(2.3, "XY.VectorCommandVelocity") == 0.0


def test_mcs_on_a_system_at_rest_completes(mp) -> None:
    body = once("MCS(XY, c2, all, no, 0.0, unitspersec2, no, 0.0, unitspersec3);")
    tr = mp.trace(prog("", body), ["c2.DN", "c2.PC", "c2.ER"], scans=5)
    assert [tr.at(0.004, n) for n in ("c2.DN", "c2.PC", "c2.ER")] == [1, 1, 0]


@pytest.mark.parametrize(
    ("stmt", "exerr"),
    [
        (mclm("c1", "p1", mtype="bad"), 2),
        (mclm("c1", "short"), 3),
        (mclm("c1", "p1", v=-1.0), 4),
        (mclm("c1", "p1", a=0.0), 6),
        (mclm("c1", "p1", d=0.0), 8),
        (mclm("c1", "p1", tt="bad"), 14),
        (mclm("c1", "p1", tt=6, ct=-1.0), 17),
    ],
)
def test_mclm_parameter_errors(mp, stmt: str, exerr: int) -> None:
    decls = "  short : REAL[1];\n  bad : DINT := 9;\n"  # enumerations out of range: from a tag
    tr = mp.trace(prog(decls, once(stmt)), ["c1.ER", "c1.ERR", "c1.EXERR"], 2)
    assert [tr.at(0.0, n) for n in ("c1.ER", "c1.ERR", "c1.EXERR")] == [1, 13, exerr]


@pytest.mark.parametrize(
    ("stmt", "exerr"),
    [
        # the seed's table: 2 Move Type, 3 Position, 4 Circle Type, 5 Via/Center,
        # 6 Direction, 7 Speed, 9 Accel, 11 Decel; TerminationType is operand 17
        (mccm("c1", "p1", 1, "ctr", 0, mtype="bad"), 2),
        (mccm("c1", "short", 1, "ctr", 0), 3),
        (mccm("c1", "p1", "bad", "ctr", 0), 4),
        (mccm("c1", "p1", 1, "short", 0), 5),
        (mccm("c1", "p1", 1, "ctr", "bad"), 6),
        (mccm("c1", "p1", 1, "ctr", 0, v=-1.0), 7),
        (mccm("c1", "p1", 1, "ctr", 0, a=0.0), 9),
        (mccm("c1", "p1", 1, "ctr", 0, tt="bad"), 17),
    ],
)
def test_mccm_parameter_errors(mp, stmt: str, exerr: int) -> None:
    decls = "  short : REAL[1];\n  bad : DINT := 9;\n"  # enumerations out of range: from a tag
    tr = mp.trace(prog(decls, once(stmt)), ["c1.ER", "c1.ERR", "c1.EXERR"], 2)
    assert [tr.at(0.0, n) for n in ("c1.ER", "c1.ERR", "c1.EXERR")] == [1, 13, exerr]


def test_mccm_geometry_error_is_reported(mp) -> None:
    # via point on the line from (0, 0) to (30, 40): collinear, error 44
    decls = "  via : REAL[2] := [15.0, 20.0];\n"
    tr = mp.trace(prog(decls, once(mccm("c1", "p1", 0, "via", 0))), ["c1.ER", "c1.ERR", "c1.DN"], 2)
    assert [tr.at(0.0, n) for n in ("c1.ER", "c1.ERR", "c1.DN")] == [1, 44, 0]


MAJ_X = (
    "MAJ(X, c4, forward, 1.0, unitspersec, 100.0, unitspersec2, 100.0, unitspersec2, "
    "trapezoidal, 0.0, 0.0, unitspersec3, disabled, programmed, 0.0, none);"
)


def test_merge_disabled_superimposes_single_axis_motion(mp) -> None:
    # a jog of X at 1 unit/s (ramp 0.01 s) runs under the MCLM to (30, 40): X carries both,
    # so X - 3/4 Y is the jog alone: 0.005 + (t - t0 - 0.01) once at speed
    body = once(MAJ_X + mclm("c1", "p1"))
    tr = mp.trace(prog("", body), ["X.CommandPosition", "Y.CommandPosition", "c4.IP"], 3000)
    for t in (1.0, 2.0, 2.9):
        jog = 0.005 + (t - T0 - 0.01)
        x, y = tr.at(t, "X.CommandPosition"), tr.at(t, "Y.CommandPosition")
        assert x - 0.75 * y == pytest.approx(jog, abs=F32)
    assert tr.at(2.9, "c4.IP") == 1


def test_merge_all_motion_ends_the_jog(mp) -> None:
    body = once(MAJ_X) + f"IF k = 500 THEN {mclm('c1', 'p1', merge='allmotion')} END_IF;"
    tr = mp.trace(prog("", body), ["c4.IP", "c1.PC", "X.CommandPosition"], 6000)
    assert tr.at(0.4, "c4.IP") == 1
    assert tr.at(0.6, "c4.IP") == 0
    assert tr.col("c1.PC")[-1] == 1
    assert tr.col("X.CommandPosition")[-1] == 30.0  # the absolute end point, jog ended


def test_event_distance_gives_the_time_to_the_point(mp) -> None:
    # L 50, V 10, A 100: 5 units before the end (s = 45) is reached at
    # 0.1 + (45 - 0.5) / 10 = 4.55 s after the start; 1 unit before: 4.95 s
    decls = "  ev : REAL[2] := [5.0, 1.0];\n  cd : REAL[2];\n"
    stmt = mclm("c1", "p1").replace("0, none, 0, 0);", "0, none, ev, cd);")
    tr = mp.trace(prog(decls, once(stmt)), ["cd[0]", "cd[1]"], 5)
    assert tr.at(0.004, "cd[0]") == pytest.approx(4.55, abs=1e-6)
    assert tr.at(0.004, "cd[1]") == pytest.approx(4.95, abs=1e-6)


@pytest.mark.parametrize(("ms", "speed"), [("programmed", 20.0), ("current", 10.0)])
def test_merge_speed_programmed_or_current(mp, ms: str, speed: float) -> None:
    # cruising at 10 towards p2, a merging move along the same line to p3 at 20 units/s:
    # Programmed speeds up to 20, Current keeps the 10 the system has
    body = once(mclm("c1", "p2")) + (
        f"IF k = 1000 THEN {mclm('c2', 'p3', v=20.0, merge='coordinatedmotion', ms=ms)} END_IF;"
    )
    tr = mp.trace(prog("", body), ["XY.VectorCommandVelocity", "c1.IP", "c2.IP"], 2500)
    assert tr.at(2.0, "XY.VectorCommandVelocity") == pytest.approx(speed, abs=1e-4)
    assert [tr.at(2.0, n) for n in ("c1.IP", "c2.IP")] == [0, 1]


LADDER = """VAR
  X, Y : AXIS_VIRTUAL;
  XY : COORDINATE_SYSTEM := (Axes := [X, Y], MaximumSpeed := 20.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0);
  arc : MOTION_INSTRUCTION;
  inc, ctr : REAL[2] := [20.0, 0.0];
  k : DINT;
END_VAR
EQU(k,0)MOV(10.0,ctr[0])MOV(0.0,ctr[1]);
EQU(k,1)MCCM(XY,arc,Incremental,inc[0],Center,ctr[0],CW,10,Units per sec,100,Units per sec2,100,Units per sec2,Trapezoidal,100.0,100.0,% of Time,No Settle,Disabled,Programmed,0,0,None,0,0);
ADD(k,1,k);
"""


def test_ladder_mccm_incremental_half_circle(mp) -> None:
    # executed in scan 1 (start at the update 0.002): from (0, 0) by (20, 0) about the
    # centre (0, 0) + (10, 0), clockwise: a half circle over the top through (10, 10),
    # L = 10 pi, T = pi + 0.1 s; halfway (T/2 after the start) it is at the top
    tr = mp.trace(
        LADDER, ["X.CommandPosition", "Y.CommandPosition", "arc.PC", "arc.ER"], 3400,
        name="prog.rll",
    )  # fmt: skip
    assert tr.col("arc.ER")[-1] == 0
    assert_completes(tr, "arc", T0 + math.pi + 0.1)
    top = T0 + (math.pi + 0.1) / 2.0
    row = round(top / CUP) * CUP
    assert tr.at(row, "X.CommandPosition") == pytest.approx(10.0, abs=0.02)
    assert tr.at(row, "Y.CommandPosition") == pytest.approx(10.0, abs=1e-3)
    for x, y in zip(tr.col("X.CommandPosition"), tr.col("Y.CommandPosition"), strict=True):
        assert math.hypot(x - 10.0, y) == pytest.approx(10.0, abs=F32)
        assert y >= -F32
    assert (tr.col("X.CommandPosition")[-1], tr.col("Y.CommandPosition")[-1]) == (20.0, 0.0)


def test_merge_decel_jerk_in_percent_of_time_uses_the_speed_change(mp) -> None:
    # at 30 units/s a merging S-curve move at V = 10 with 100 % of Time: the decel jerk comes
    # from max(V, |V0 - V|) = 20 (SPEC 9.28): J = A^2/20 = 500 (not A^2/V = 1000). From 30 to
    # 10 (dv 20 = A^2/J): jerk up for A/J = 0.2 s (dv 10), jerk down for 0.2 s: at 10 after
    # 0.4 s; 0.3 s in, dv = 10 + (A 0.1 - J 0.1^2 / 2) = 17.5, so the speed is 12.5
    body = once(mclm("c1", "p3", v=30.0, a=1000.0, d=1000.0)) + (
        "IF k = 1000 THEN "
        + mclm("c2", "p3", v=10.0, shape="s-curve", merge="coordinatedmotion")
        + " END_IF;"
    )
    tr = mp.trace(prog("", body), ["XY.VectorCommandVelocity", "c2.ER"], 1600)
    assert tr.at(0.9, "XY.VectorCommandVelocity") == pytest.approx(30.0, abs=1e-4)
    t_merge = 1.002
    assert tr.at(t_merge + 0.3, "XY.VectorCommandVelocity") == pytest.approx(12.5, abs=1e-3)
    assert tr.at(t_merge + 0.4, "XY.VectorCommandVelocity") == pytest.approx(10.0, abs=1e-4)


def test_a_system_naming_an_axis_twice_is_error_13(mp) -> None:
    decls = "  XX : COORDINATE_SYSTEM := (Axes := [X, X]);\n"
    tr = mp.trace(prog(decls, once(mclm("c1", "p1", cs="XX"))), ["c1.ER", "c1.ERR", "c1.EXERR"], 2)
    assert [tr.at(0.0, n) for n in ("c1.ER", "c1.ERR", "c1.EXERR")] == [1, 13, 0]
