"""MAM, MAJ, MAS, MGS, MSO/MSF/MAFR and MCCP through the VM, against hand formulas.

Move formulas (rest to rest, distance D, speed V, accel A, decel Dc, reaching V):
  trapezoid: T = D/V + V/(2A) + V/(2Dc)
  S-curve with jerk J: each ramp lasts V/A + A/J and covers V/2 of that time's travel, so
  T = D/V + (V/A + A/J)/2 + (V/Dc + Dc/J)/2; % of Time p gives J = A²/V (200/p - 1).
A move executed in the scan at 0 starts at the update t0 = 2 ms; it completes (PC) at the
first update at or after t0 + T.
"""

from __future__ import annotations

import pytest
from motion_trace import CUP

T0 = 0.002
F32 = 1e-4
HEAD = """VAR
  X, Y : AXIS_VIRTUAL := (MaximumSpeed := 20.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0);
  c1, c2, c3, c4, c5, c6 : MOTION_INSTRUCTION;
  k : DINT;
"""


def prog(decls: str, body: str) -> str:
    return HEAD + decls + "END_VAR\n" + body + "\nk := k + 1;\n"


def mam(
    axis: str,
    ctl: str,
    pos: float,
    v: float,
    a: float,
    d: float,
    shape: str = "trapezoidal",
    ja: float = 0.0,
    jd: float = 0.0,
    ju: str = "unitspersec3",
    su: str = "unitspersec",
    au: str = "unitspersec2",
    mtype: str = "absolute",
    ev: str = "0",
    cd: str = "0",
) -> str:
    return (
        f"MAM({axis}, {ctl}, {mtype}, {pos}, {v}, {su}, {a}, {au}, {d}, {au}, {shape}, {ja}, {jd}, {ju}, "
        f"disabled, programmed, 0.0, none, {ev}, {cd});"
    )


def pc_time(tr, ctl: str) -> float:  # noqa: ANN001
    return tr.first(f"{ctl}.PC", lambda v: v == 1)


def assert_completes(tr, ctl: str, t_end: float) -> None:  # noqa: ANN001
    t = pc_time(tr, ctl)
    assert t_end - 1e-9 <= t <= t_end + CUP + 1e-9, (t, t_end)


def test_trapezoid_end_position_duration_and_bits(mp) -> None:
    # D 10, V 5, A 100, Dc 50: T = 2 + 0.025 + 0.05 = 2.075 s; accel 0.05 s (0.125 units),
    # decel 0.1 s (0.25 units)
    src = prog("", f"IF k = 0 THEN {mam('X', 'c1', 10.0, 5.0, 100.0, 50.0)} END_IF;")
    tr = mp.trace(
        src,
        [
            "X.CommandPosition",
            "X.CommandVelocity",
            "c1.DN",
            "c1.IP",
            "c1.PC",
            "c1.ACCEL",
            "c1.DECEL",
            "X.MoveStatus",
            "X.AccelStatus",
            "X.DecelStatus",
        ],
        scans=2200,
    )

    def p(t: float) -> float:
        u = min(max(t - T0, 0.0), 2.075)
        if u <= 0.05:
            return 50.0 * u * u
        if u <= 1.975:
            return 0.125 + 5.0 * (u - 0.05)
        r = 2.075 - u
        return 10.0 - 25.0 * r * r

    tr.check("X.CommandPosition", p, 5.0 * CUP + F32)
    assert_completes(tr, "c1", T0 + 2.075)
    assert tr.col("X.CommandPosition")[-1] == 10.0
    assert [tr.at(0.0, n) for n in ("c1.DN", "c1.IP", "c1.PC", "X.MoveStatus")] == [1, 1, 0, 0]
    assert [tr.at(0.03, n) for n in ("c1.ACCEL", "c1.DECEL", "X.MoveStatus", "X.AccelStatus")] == [
        1,
        0,
        1,
        1,
    ]
    assert [tr.at(1.0, n) for n in ("c1.ACCEL", "c1.DECEL", "X.CommandVelocity")] == [0, 0, 5.0]
    assert [tr.at(2.02, n) for n in ("c1.ACCEL", "c1.DECEL", "X.DecelStatus")] == [0, 1, 1]
    assert [tr.at(2.099, n) for n in ("c1.IP", "c1.PC", "X.MoveStatus", "c1.DECEL")] == [0, 1, 0, 0]


@pytest.mark.parametrize(
    ("ja", "ju", "j", "t_total"),
    [
        # J = 4000 (A²/J = 2.5 <= V: A is reached): ramps 0.05 + 0.025 s: T = 2 + 0.075
        (4000.0, "unitspersec3", 4000.0, 2.075),
        # 100 % of Time: J = A²/V = 2000, ramps 0.05 + 0.05 = 0.1 s (a pure S): T = 2.1
        (100.0, "%oftime", 2000.0, 2.1),
        # 50 % of Maximum jerk (MaximumAccelJerk = MaximumDecelJerk = 8000): as the first case
        (50.0, "%ofmaximum", 4000.0, 2.075),
        # J = 1000: A²/J = 10 > V, A is never reached: each ramp takes 2 sqrt(V/J) = 0.141421 s
        (1000.0, "unitspersec3", 1000.0, 2.0 + 2.0 * (5.0 / 1000.0) ** 0.5),
    ],
)
def test_s_curve_duration_and_jerk_units(mp, ja: float, ju: str, j: float, t_total: float) -> None:
    decls = "  Z : AXIS_VIRTUAL := (MaximumSpeed := 20.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0, MaximumAccelJerk := 8000.0, MaximumDecelJerk := 8000.0);\n"
    src = prog(
        decls,
        f"IF k = 0 THEN {mam('Z', 'c1', 10.0, 5.0, 100.0, 100.0, 's-curve', ja, ja, ju)} END_IF;",
    )
    tr = mp.trace(src, ["Z.CommandPosition", "c1.PC"], scans=2300)
    assert_completes(tr, "c1", T0 + t_total)
    # first jerk phase (t <= A/J after the start, 0.025 s at most here): p = J t^3 / 6
    t = 0.02
    assert tr.at(T0 + t, "Z.CommandPosition") == pytest.approx(j * t**3 / 6.0, abs=F32)
    # the middle of the move is the middle of the distance (symmetric ramps)
    mid = T0 + t_total / 2.0
    mid_row = round(mid / 0.002) * 0.002  # an update instant
    assert tr.at(mid_row, "Z.CommandPosition") == pytest.approx(
        5.0 + 5.0 * (mid_row - mid), abs=1e-3
    )
    assert tr.col("Z.CommandPosition")[-1] == 10.0


def test_percent_of_maximum_speed_and_accel(mp) -> None:
    # 50 % of MaximumSpeed 20 = 10 units/s; 10 % of MaximumAccel/Decel 1000 = 100:
    # D 10: T = 1 + 0.05 + 0.05 = 1.1 s
    src = prog(
        "",
        "IF k = 0 THEN "
        + mam("X", "c1", 10.0, 50.0, 10.0, 10.0, su="%ofmaximum", au="%ofmaximum")
        + " END_IF;",
    )
    tr = mp.trace(src, ["X.CommandVelocity", "c1.PC"], scans=1200)
    assert tr.at(0.5, "X.CommandVelocity") == pytest.approx(10.0)
    assert_completes(tr, "c1", T0 + 1.1)


def test_time_based_move_lasts_the_programmed_time(mp) -> None:
    # Seconds: move 10 units in 2 s with 0.5 s accel and 0.5 s decel:
    # V = D / (T - Ta/2 - Td/2) = 10 / 1.5; the midpoint is reached at T/2
    src = prog(
        "",
        "IF k = 0 THEN "
        + mam("X", "c1", 10.0, 2.0, 0.5, 0.5, su="seconds", au="seconds", mtype="incremental")
        + " END_IF;",
    )
    tr = mp.trace(src, ["X.CommandPosition", "X.CommandVelocity", "c1.PC"], scans=2100)
    assert_completes(tr, "c1", T0 + 2.0)
    assert tr.at(T0 + 1.0, "X.CommandPosition") == pytest.approx(5.0, abs=F32)
    assert tr.at(T0 + 1.0, "X.CommandVelocity") == pytest.approx(10.0 / 1.5, abs=1e-4)


def test_event_distances_give_the_time_to_each_point(mp) -> None:
    # D 10, V 5, A = Dc = 100 (accel 0.05 s covering 0.125): 1 unit before the end (9.0) is
    # reached at 0.05 + (9 - 0.125)/5 = 1.825 s, 5 units before the end at 1.025 s
    decls = "  ev : REAL[2] := [1.0, 5.0];\n  cd : REAL[2];\n"
    src = prog(
        decls,
        "IF k = 0 THEN " + mam("X", "c1", 10.0, 5.0, 100.0, 100.0, ev="ev", cd="cd") + " END_IF;",
    )
    tr = mp.trace(src, ["cd[0]", "cd[1]"], scans=5)
    assert tr.at(0.004, "cd[0]") == pytest.approx(1.825, abs=1e-6)
    assert tr.at(0.004, "cd[1]") == pytest.approx(1.025, abs=1e-6)


def test_jog_then_stop_with_percent_decel(mp) -> None:
    # MAJ 10 units/s, accel 100: ramp 0.1 s (0.5 units) from 0.002. MAS Jog at 0.5 s (applied
    # at 0.502) with 5 % of MaximumDecel 1000 = 50: 0.2 s and 1 unit to rest.
    #   p(0.502) = 0.5 + 10 (0.502 - 0.102) = 4.5, at rest at 0.702 at 5.5
    body = """IF k = 0 THEN MAJ(X, c1, forward, 10.0, unitspersec, 100.0, unitspersec2, 100.0, unitspersec2, trapezoidal, 0.0, 0.0, unitspersec3, disabled, programmed, 0.0, none); END_IF;
IF k = 500 THEN MAS(X, c2, jog, yes, 5.0, %ofmaximum, no, 0.0, unitspersec3); END_IF;"""
    tr = mp.trace(
        prog("", body),
        [
            "X.CommandPosition",
            "c1.IP",
            "c1.PC",
            "c2.IP",
            "c2.PC",
            "c2.DECEL",
            "X.JogStatus",
            "X.StoppingStatus",
        ],
        scans=800,
    )

    def p(t: float) -> float:
        u = t - T0
        if u <= 0.1:
            return 50.0 * max(u, 0.0) ** 2
        if t <= 0.502:
            return 0.5 + 10.0 * (u - 0.1)
        r = max(0.702 - t, 0.0)
        return 5.5 - 25.0 * r * r

    tr.check("X.CommandPosition", p, 10.0 * CUP + F32)
    assert [tr.at(0.501, n) for n in ("c1.IP", "X.JogStatus", "c2.IP")] == [1, 1, 1]
    assert [
        tr.at(0.6, n) for n in ("c1.IP", "c1.PC", "X.JogStatus", "X.StoppingStatus", "c2.DECEL")
    ] == [0, 0, 0, 1, 1]
    assert [tr.at(0.702, n) for n in ("c2.IP", "c2.PC", "X.StoppingStatus", "c2.DECEL")] == [
        0,
        1,
        0,
        0,
    ]


def test_servo_on_off_drive_axis_versus_virtual(mp) -> None:
    # drive axis: motion before MSO is error 5 (servo off); MSO completes at the next update;
    # actual lags command while moving and settles; MSF completes at the next update and
    # motion is refused again. Virtual axis: MSO/MSF complete in their scan, no effect.
    decls = "  D : AXIS_CIP_DRIVE := (MaximumSpeed := 20.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0);\n  c7, c8 : MOTION_INSTRUCTION;\n"
    body = f"""IF k = 0 THEN {mam("D", "c1", 10.0, 10.0, 100.0, 100.0)} MSO(D, c2); MSO(X, c3); END_IF;
IF k = 10 THEN {mam("D", "c4", 5.0, 10.0, 100.0, 100.0)} END_IF;
IF k = 1000 THEN MSF(D, c5); MSF(X, c6); MAFR(D, c7); END_IF;
IF k = 1010 THEN {mam("D", "c8", 0.0, 10.0, 100.0, 100.0)} END_IF;"""
    tr = mp.trace(
        prog(decls, body),
        [
            "c1.ER",
            "c1.ERR",
            "c2.DN",
            "c3.DN",
            "D.ServoActionStatus",
            "D.DriveEnableStatus",
            "D.CommandPosition",
            "D.ActualPosition",
            "X.ServoActionStatus",
            "c5.DN",
            "c6.DN",
            "c7.DN",
            "c8.ERR",
            "c4.PC",
        ],
        scans=1100,
    )
    assert (tr.at(0.0, "c1.ER"), tr.at(0.0, "c1.ERR")) == (1, 5)
    assert (tr.at(0.0, "c2.DN"), tr.at(0.0, "D.ServoActionStatus"), tr.at(0.0, "c3.DN")) == (
        0,
        0,
        1,
    )
    assert (
        tr.at(0.002, "c2.DN"),
        tr.at(0.002, "D.ServoActionStatus"),
        tr.at(0.002, "D.DriveEnableStatus"),
    ) == (1, 1, 1)
    assert (
        tr.at(0.3, "D.ActualPosition") < tr.at(0.3, "D.CommandPosition") - 0.01
    )  # following error
    assert tr.at(0.999, "D.ActualPosition") == pytest.approx(5.0, abs=1e-4)  # settled
    assert (
        tr.at(1.0, "c5.DN"),
        tr.at(1.0, "c6.DN"),
        tr.at(1.002, "c5.DN"),
        tr.at(1.002, "c7.DN"),
    ) == (0, 1, 1, 1)
    assert (tr.at(1.002, "D.ServoActionStatus"), tr.at(1.002, "X.ServoActionStatus")) == (0, 1)
    assert tr.at(1.01, "c8.ERR") == 5


def test_mccp_status_and_errors(mp) -> None:
    # Status 0 before MCCP, 2 after (in its scan), 3 while a cam uses it; recalculating a
    # profile in use is 31; bad cams: Length 1 or beyond the array 26, profile array too
    # short 27, segment type 28, master order 29
    decls = """  pts : CAM[3] := [(Master := 0.0, Slave := 0.0, SegmentType := 1), (Master := 1.0, Slave := 2.0, SegmentType := 1),
                   (Master := 2.0, Slave := 0.0, SegmentType := 1)];
  badt : CAM[2] := [(Master := 0.0, Slave := 0.0, SegmentType := 2), (Master := 1.0, Slave := 1.0, SegmentType := 0)];
  bado : CAM[2] := [(Master := 1.0, Slave := 0.0, SegmentType := 0), (Master := 1.0, Slave := 1.0, SegmentType := 0)];
  prof : CAM_PROFILE[3];
  small : CAM_PROFILE[2];
  e1, e2, e3, e4, e5 : MOTION_INSTRUCTION;
"""
    body = """IF k = 5 THEN MCCP(c1, pts, 3, 0.0, 0.0, prof); END_IF;
IF k = 10 THEN MATC(X, c2, 0, prof, 1.0, 1.0, once, immediate, 0.0, none, timedrivenmode); END_IF;
IF k = 12 THEN MCCP(c3, pts, 3, 0.0, 0.0, prof);
  MCCP(e1, pts, 1, 0.0, 0.0, small); MCCP(e2, pts, 4, 0.0, 0.0, small); MCCP(e3, pts, 3, 0.0, 0.0, small);
  MCCP(e4, badt, 2, 0.0, 0.0, small); MCCP(e5, bado, 2, 0.0, 0.0, small);
END_IF;"""
    tr = mp.trace(
        prog(decls, body),
        ["prof[0].Status", "prof[1].Status", "prof[2].Status", "c1.DN", "c3.ERR"]
        + [f"e{i}.ERR" for i in range(1, 6)]
        + ["X.CommandPosition"],
        scans=2100,
    )
    assert [tr.at(t, "prof[0].Status") for t in (0.004, 0.005, 0.009, 0.01, 2.099)] == [
        0,
        2,
        2,
        3,
        2,
    ]
    assert (
        tr.at(0.005, "prof[1].Status"),
        tr.at(0.005, "prof[2].Status"),
        tr.at(0.005, "c1.DN"),
    ) == (2, 2, 1)
    assert tr.at(0.012, "c3.ERR") == 31
    assert [tr.at(0.012, f"e{i}.ERR") for i in range(1, 6)] == [26, 26, 27, 28, 29]
    # the cubic spline passes through the points: 2 at master 1 s (cam started at 0.012)
    assert tr.at(1.012, "X.CommandPosition") == pytest.approx(2.0, abs=F32)


def test_group_stop_fast_disable_and_links(mp) -> None:
    # jogs start at 0.006 (D reaches 10 units/s at 0.106). MGS Fast Disable at 0.2 (applied
    # 0.202): every axis decelerates at its MaximumDecel (X: 10 units/s at 1000 -> 10 ms;
    # D: 10 units/s at 100 -> 0.1 s); PC when the last axis is at rest (0.202 + 0.1);
    # the drive is disabled then. The jogs end (IP cleared, no PC).
    decls = (
        "  grp : MOTION_GROUP := (CoarseUpdatePeriod := 2000);\n"
        "  D : AXIS_CIP_DRIVE := (MaximumSpeed := 20.0, MaximumAccel := 100.0, MaximumDecel := 100.0);\n"
        "  cg : MOTION_INSTRUCTION;\n"
    )
    jog = "MAJ({0}, {1}, forward, 10.0, unitspersec, 100.0, unitspersec2, 100.0, unitspersec2, trapezoidal, 0.0, 0.0, unitspersec3, disabled, programmed, 0.0, none);"
    body = f"""IF k = 0 THEN MSO(D, c3); END_IF;
IF k = 5 THEN {jog.format("X", "c1")} {jog.format("D", "c2")} END_IF;
IF k = 200 THEN MGS(grp, cg, 2); END_IF;"""
    tr = mp.trace(
        prog(decls, body),
        [
            "X.CommandVelocity",
            "D.CommandVelocity",
            "cg.DN",
            "cg.IP",
            "cg.PC",
            "c1.IP",
            "c2.IP",
            "c2.PC",
            "D.ServoActionStatus",
        ],
        scans=400,
    )
    assert [tr.at(0.2, n) for n in ("cg.DN", "cg.IP", "cg.PC")] == [1, 1, 0]
    assert tr.at(0.212, "X.CommandVelocity") == 0.0 and tr.at(0.212, "D.CommandVelocity") > 0.0
    assert [tr.at(0.202, n) for n in ("c1.IP", "c2.IP", "c2.PC")] == [0, 0, 0]
    assert_completes(tr, "cg", 0.302)
    t_pc = pc_time(tr, "cg")
    # disabled at the update that brings the last axis to rest
    assert (
        tr.at(t_pc - 0.001, "D.ServoActionStatus") == 1 and tr.at(t_pc, "D.ServoActionStatus") == 0
    )


def test_move_errors_17_33_54_and_zero_speed_dwell(mp) -> None:
    # rotary move types on a linear axis: 17; master offset moves without a position cam: 33;
    # MAS with the configured decel on an axis whose MaximumDecel is 0: 54.
    # A move at speed 0 stays in process without moving (dwell).
    decls = "  Z : AXIS_VIRTUAL;\n"
    body = f"""IF k = 0 THEN
  {mam("X", "c1", 10.0, 5.0, 100.0, 100.0, mtype="2")}
  {mam("X", "c2", 10.0, 5.0, 100.0, 100.0, mtype="5")}
  MAS(Z, c3, all, no, 0.0, unitspersec2, no, 0.0, unitspersec3);
  {mam("Y", "c4", 10.0, 0.0, 100.0, 100.0)}
END_IF;"""
    tr = mp.trace(
        prog(decls, body),
        ["c1.ERR", "c2.ERR", "c3.ERR", "c4.IP", "c4.PC", "Y.CommandPosition"],
        scans=200,
    )
    assert [tr.at(0.0, n) for n in ("c1.ERR", "c2.ERR", "c3.ERR")] == [17, 33, 54]
    assert [tr.at(0.199, n) for n in ("c4.IP", "c4.PC", "Y.CommandPosition")] == [1, 0, 0.0]
