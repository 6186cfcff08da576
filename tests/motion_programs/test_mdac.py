"""MDAC and master-driven motion through the VM (MDAC-master-driven-axis-control.txt, SPEC 5,
9.24): motion types, master reference, pending master, AC bit, All conflicts, links broken
by stops, errors 93/94/95/96, lock position and lock direction of master-driven cams.

Master jog used below: MAJ forward 10 units/s, accel 1000 units/s^2, executed at t = 0, so it
starts at the update t0 = 2 ms, reaches speed after 10 ms having covered 0.05 units:
    m(t) = 500 (t - t0)^2 for t <= 0.012, else 0.05 + 10 (t - 0.012).
A master-driven slave runs its profile against master distance d = m(t) - m(start).
"""

from __future__ import annotations

import math

import pytest
from motion_trace import CUP

F32 = 1e-4
HEAD = """VAR
  big : CAM_PROFILE[2] := [(Master := 0.0, Slave := 0.0, SegmentType := 0),
                           (Master := 100.0, Slave := 200.0, SegmentType := 0)];
  M, M2, S, T : AXIS_VIRTUAL := (MaximumSpeed := 1000.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0);
  c1, c2, c3, c4, c5, cj, cj2 : MOTION_INSTRUCTION;
  k : DINT;
"""
JOG_M = "MAJ(M, cj, forward, 10.0, unitspersec, 1000.0, unitspersec2, 1000.0, unitspersec2, trapezoidal, 0.0, 0.0, unitspersec3, disabled, programmed, 0.0, none);"


def prog(decls: str, body: str) -> str:
    return HEAD + decls + "END_VAR\n" + body + "\nk := k + 1;\n"


def m(t: float) -> float:
    t0 = 0.002
    if t <= t0:
        return 0.0
    if t <= 0.012:
        return 500.0 * (t - t0) ** 2
    return 0.05 + 10.0 * (t - 0.012)


def md_move(
    axis: str, ctl: str, dist: float, speed: float, accel: float, lock: str = "none"
) -> str:
    return (
        f"MAM({axis}, {ctl}, incremental, {dist}, {speed}, unitspermasterunit, {accel}, unitspermasterunit2, "
        f"{accel}, unitspermasterunit2, trapezoidal, 0.0, 0.0, unitspermasterunit3, disabled, programmed, 0.0, {lock}, 0, 0);"
    )


def test_master_driven_move_follows_master_distance_and_sets_ac(mp) -> None:
    # MDAC Move; MAM incremental 20 at 2 units per master unit, accel/decel 4 per master unit^2,
    # executed at 0.1 s -> starts at 0.102 with d = m(t) - m(0.102):
    #   s(d) = 2 d^2 (d <= 0.5); 0.5 + 2 (d - 0.5) (d <= 10); 19.5 + 2 e - 2 e^2, e = d - 10 (d <= 10.5)
    # 10.5 master units at 10 units/s: complete at 0.102 + 1.05 = 1.152 (PC)
    body = f"""IF k = 0 THEN {JOG_M} MDAC(S, M, c1, move, command); END_IF;
IF k = 100 THEN {md_move("S", "c2", 20.0, 2.0, 4.0)} END_IF;"""

    def s(t: float) -> float:
        d = max(0.0, m(t) - m(0.102))
        if d <= 0.5:
            return 2.0 * d * d
        if d <= 10.0:
            return 0.5 + 2.0 * (d - 0.5)
        e = min(d, 10.5) - 10.0
        return 19.5 + 2.0 * e - 2.0 * e * e

    tr = mp.trace(
        prog("", body),
        [
            "S.CommandPosition",
            "S.CommandVelocity",
            "c1.DN",
            "c1.IP",
            "c1.AC",
            "c2.IP",
            "c2.PC",
            "S.CoordinatedMotionStatus",
        ],
        scans=1300,
    )
    tr.check("S.CommandPosition", s, 20.0 * CUP + F32)
    assert abs(tr.at(0.6, "S.CommandVelocity") - 20.0) < 1e-3  # 2 units/mu x 10 mu/s
    assert [tr.at(0.0, n) for n in ("c1.DN", "c1.IP", "c1.AC", "S.CoordinatedMotionStatus")] == [
        1,
        1,
        0,
        1,
    ]
    # seed: AC set when a master-driven move goes IP on the slave; the MDAC's IP unchanged
    assert (tr.at(0.101, "c1.AC"), tr.at(0.102, "c1.AC"), tr.at(0.102, "c1.IP")) == (0, 1, 1)
    assert (tr.at(1.151, "c2.PC"), tr.at(1.152, "c2.PC"), tr.at(1.152, "c2.IP")) == (0, 1, 0)
    assert (tr.at(1.152, "c1.AC"), tr.at(1.152, "c1.IP")) == (0, 1)  # link stays, no motion


def test_motion_type_decides_which_motions_are_master_driven(mp) -> None:
    # MDAC Jog does not cover MAM or MATC: master-driven MAM/MATC find no link -> error 93
    body = f"""IF k = 0 THEN
  MDAC(S, M, c1, jog, command);
  {md_move("S", "c2", 20.0, 2.0, 4.0)}
  MATC(S, c3, 0, big, 1.0, 1.0, once, immediate, 0.0, none, masterdrivenmode);
  MDAC(T, M, c4, timecam, command);
  MATC(T, c5, 0, big, 1.0, 1.0, once, immediate, 0.0, none, masterdrivenmode);
END_IF;"""
    tr = mp.trace(
        prog("", body), ["c1.DN", "c2.ER", "c2.ERR", "c3.ER", "c3.ERR", "c5.ER", "c5.DN"], scans=2
    )
    assert [
        tr.at(0.0, n) for n in ("c1.DN", "c2.ER", "c2.ERR", "c3.ER", "c3.ERR", "c5.ER", "c5.DN")
    ] == [1, 1, 93, 1, 93, 0, 1]


def test_master_reference_actual_or_command(mp) -> None:
    # D is a drive axis (servo model: first-order lag, tau = 1/(2 pi 20 Hz)); S follows its
    # command, T its actual position, U a virtual master's "actual" (= command for a virtual
    # axis). Slave jogs at 1 unit per master unit start before the masters move (at rest, so
    # both references agree at the start). In steady state at 10 units/s the drive lags by
    #   e = v cup q / (1 - q), q = exp(-cup / tau)  (0100: exact for a held command)
    decls = "  D : AXIS_CIP_DRIVE := (MaximumSpeed := 1000.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0);\n  co, cd, cu : MOTION_INSTRUCTION;\n"
    jog = "MAJ({0}, {1}, forward, 1.0, unitspermasterunit, 1000.0, unitspermasterunit2, 1000.0, unitspermasterunit2, trapezoidal, 0.0, 0.0, unitspermasterunit3, disabled, programmed, 0.0, none);"
    body = f"""IF k = 0 THEN
  MSO(D, co);
  MDAC(S, D, c1, jog, command); MDAC(T, D, c2, jog, actual); MDAC(M2, M, c3, jog, actual);
  {jog.format("S", "c4")} {jog.format("T", "c5")} {jog.format("M2", "cj2")}
END_IF;
IF k = 20 THEN
  MAJ(D, cd, forward, 10.0, unitspersec, 1000.0, unitspersec2, 1000.0, unitspersec2, trapezoidal, 0.0, 0.0, unitspersec3, disabled, programmed, 0.0, none);
  {JOG_M}
END_IF;"""
    tr = mp.trace(
        prog(decls, body),
        [
            "D.CommandPosition",
            "D.ActualPosition",
            "D.PositionError",
            "S.CommandPosition",
            "T.CommandPosition",
            "M.CommandPosition",
            "M2.CommandPosition",
            "co.DN",
        ],
        scans=600,
    )
    tau = 1.0 / (2.0 * math.pi * 20.0)
    q = math.exp(-CUP / tau)
    lag = 10.0 * CUP * q / (1.0 - q)  # 0.06998 units
    assert tr.at(0.599, "D.PositionError") == pytest.approx(lag, rel=1e-3)
    # the slave jog ramps to 1 unit/mu over 0.001 master units (0.0005 units of slave travel)
    for t in (0.3, 0.45, 0.599):
        assert tr.at(t, "S.CommandPosition") == pytest.approx(
            tr.at(t, "D.CommandPosition") - 0.0005, abs=1e-3
        )
        assert tr.at(t, "T.CommandPosition") == pytest.approx(
            tr.at(t, "D.ActualPosition") - 0.0005, abs=1e-3
        )
        assert tr.at(t, "M2.CommandPosition") == pytest.approx(
            tr.at(t, "M.CommandPosition") - 0.0005, abs=1e-3
        )
    assert tr.at(0.599, "S.CommandPosition") - tr.at(0.599, "T.CommandPosition") == pytest.approx(
        lag, rel=1e-2
    )


def test_new_master_is_taken_at_the_next_slave_motion_start(mp) -> None:
    # masters M (10 units/s) and M2 (20 units/s); S moves at 1 unit per master unit.
    # MDAC to M2 at 0.2 s is pending: the running move keeps M (S at 10 units/s, c2 IP but not
    # AC); the next MAM on S (0.3 s) takes M2: S at 20 units/s, c2 AC, c1's link replaced.
    jog2 = JOG_M.replace("MAJ(M, cj, forward, 10.0", "MAJ(M2, cj2, forward, 20.0")
    body = f"""IF k = 0 THEN {JOG_M} {jog2} MDAC(S, M, c1, move, command); END_IF;
IF k = 50 THEN {md_move("S", "c3", 1000.0, 1.0, 1000.0)} END_IF;
IF k = 200 THEN MDAC(S, M2, c2, move, command); END_IF;
IF k = 300 THEN {md_move("S", "c4", 1000.0, 1.0, 1000.0)} END_IF;"""
    tr = mp.trace(
        prog("", body), ["S.CommandVelocity", "c1.IP", "c1.AC", "c2.IP", "c2.AC"], scans=400
    )
    assert tr.at(0.25, "S.CommandVelocity") == pytest.approx(10.0, abs=1e-3)
    assert [tr.at(0.25, n) for n in ("c1.IP", "c1.AC", "c2.IP", "c2.AC")] == [1, 1, 1, 0]
    assert tr.at(0.35, "S.CommandVelocity") == pytest.approx(20.0, abs=1e-3)
    assert [tr.at(0.35, n) for n in ("c1.IP", "c1.AC", "c2.IP", "c2.AC")] == [0, 0, 1, 1]


def test_all_conflicts_are_error_96_until_the_link_is_broken(mp) -> None:
    # seed: All and a specific motion type cannot be assigned to one slave at the same time;
    # MAS All on the slave breaks the link, after which All is accepted
    body = """IF k = 0 THEN
  MDAC(S, M, c1, move, command); MDAC(S, M2, c2, all, command);
  MDAC(T, M, c3, all, command); MDAC(T, M2, c4, jog, command);
END_IF;
IF k = 10 THEN MAS(S, cj, all, no, 0.0, unitspersec2, no, 0.0, unitspersec3); END_IF;
IF k = 20 THEN MDAC(S, M2, c5, all, command); END_IF;"""
    tr = mp.trace(
        prog("", body),
        [
            "c1.IP",
            "c2.ER",
            "c2.ERR",
            "c3.IP",
            "c4.ER",
            "c4.ERR",
            "c5.DN",
            "c5.IP",
            "S.CoordinatedMotionStatus",
        ],
        scans=30,
    )
    assert [tr.at(0.0, n) for n in ("c1.IP", "c2.ER", "c2.ERR", "c3.IP", "c4.ER", "c4.ERR")] == [
        1,
        1,
        96,
        1,
        1,
        96,
    ]
    assert (
        tr.at(0.011, "c1.IP"),
        tr.at(0.012, "c1.IP"),
        tr.at(0.012, "S.CoordinatedMotionStatus"),
    ) == (1, 0, 0)
    assert (tr.at(0.02, "c5.DN"), tr.at(0.02, "c5.IP")) == (1, 1)


def test_links_broken_by_mas_all_and_mgs_on_the_slave_only(mp) -> None:
    # MAS Move on the slave and MAS All on the master leave the link (seed action tables);
    # MAS All on the slave breaks it (IP cleared); MGS breaks the links of its axes
    decls = "  grp : MOTION_GROUP;\n  cg : MOTION_INSTRUCTION;\n"
    body = """IF k = 0 THEN MDAC(S, M, c1, all, command); MDAC(T, M2, c2, all, command); END_IF;
IF k = 10 THEN MAS(S, c3, move, no, 0.0, unitspersec2, no, 0.0, unitspersec3); END_IF;
IF k = 20 THEN MAS(M, c4, all, no, 0.0, unitspersec2, no, 0.0, unitspersec3); END_IF;
IF k = 30 THEN MAS(S, c5, all, no, 0.0, unitspersec2, no, 0.0, unitspersec3); END_IF;
IF k = 40 THEN MGS(grp, cg, programmed); END_IF;"""
    tr = mp.trace(
        prog(decls, body), ["c1.IP", "c2.IP", "c3.PC", "c4.PC", "cg.DN", "cg.PC"], scans=50
    )
    assert [tr.at(t, "c1.IP") for t in (0.029, 0.031, 0.032)] == [1, 1, 0]
    assert (tr.at(0.029, "c3.PC"), tr.at(0.029, "c4.PC")) == (1, 1)  # the stops completed
    assert [tr.at(t, "c2.IP") for t in (0.041, 0.042)] == [1, 0]
    assert (tr.at(0.04, "cg.DN"), tr.at(0.042, "cg.PC")) == (1, 1)


def test_units_and_lock_direction_errors(mp) -> None:
    # 94: speed in units/s (time driven) with accel per master unit^2; 95: a time-driven move
    # with a lock direction (lock directions belong to master-driven motion)
    body = """IF k = 0 THEN
  MAM(S, c1, incremental, 5.0, 10.0, unitspersec, 100.0, unitspermasterunit2, 100.0, unitspersec2, trapezoidal, 0.0, 0.0, unitspersec3, disabled, programmed, 0.0, none, 0, 0);
  MAM(S, c2, incremental, 5.0, 10.0, unitspersec, 100.0, unitspersec2, 100.0, unitspersec2, trapezoidal, 0.0, 0.0, unitspersec3, disabled, programmed, 0.0, immediateforwardonly, 0, 0);
END_IF;"""
    tr = mp.trace(prog("", body), ["c1.ER", "c1.ERR", "c2.ER", "c2.ERR"], scans=2)
    assert [tr.at(0.0, n) for n in ("c1.ER", "c1.ERR", "c2.ER", "c2.ERR")] == [1, 94, 1, 95]


def test_motion_type_and_master_reference_as_text_or_number(mp) -> None:
    # SPEC 9.24: MDAC(S, M, c, 3, 1) is MDAC(S, M, c, timecam, command): same slave motion
    body = f"""IF k = 0 THEN
  {JOG_M}
  MDAC(S, M, c1, 3, 1); MDAC(T, M, c2, timecam, command);
  MATC(S, c3, 0, big, 1.0, 1.0, continuous, immediate, 0.0, none, masterdrivenmode);
  MATC(T, c4, 0, big, 1.0, 1.0, continuous, immediate, 0.0, none, 1);
END_IF;"""
    tr = mp.trace(prog("", body), ["S.CommandPosition", "T.CommandPosition"], scans=300)
    # the cams start at 0.002 with the master: slave = 2 m(t)
    tr.check("S.CommandPosition", lambda t: 2.0 * m(t), 20.0 * CUP + F32)
    assert tr.col("S.CommandPosition") == tr.col("T.CommandPosition")


def test_master_reference_change_of_a_moving_slave_is_an_error(mp) -> None:
    decls = "  D : AXIS_CIP_DRIVE := (MaximumSpeed := 1000.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0);\n"
    body = f"""IF k = 0 THEN MSO(D, cj2); MDAC(S, D, c1, move, command); END_IF;
IF k = 10 THEN {md_move("S", "c2", 1.0, 1.0, 100.0)} END_IF;
IF k = 20 THEN MDAC(S, D, c3, move, actual); END_IF;"""
    tr = mp.trace(prog(decls, body), ["c3.ER", "c3.ERR", "c1.IP"], scans=25)
    # the slave's move is in process (waiting for master travel): the new reference is refused
    assert (tr.at(0.02, "c3.ER"), tr.at(0.02, "c3.ERR"), tr.at(0.024, "c1.IP")) == (1, 105, 1)


def test_lock_position_forward_starts_the_cam_when_the_master_crosses_it(mp) -> None:
    # BIG (slope 2) master driven, Position Forward at 5: the slave waits until m = 5
    # (m(t) = 5 at t = 0.012 + 4.95/10 = 0.507), then s = 2 (m - 5); TimeCamLockStatus follows
    body = f"""IF k = 0 THEN
  {JOG_M} MDAC(S, M, c1, timecam, command);
  MATC(S, c2, 0, big, 1.0, 1.0, once, immediate, 5.0, positionforward, masterdrivenmode);
END_IF;"""
    tr = mp.trace(
        prog("", body), ["S.CommandPosition", "S.TimeCamLockStatus", "S.TimeCamStatus"], scans=900
    )
    tr.check("S.CommandPosition", lambda t: 2.0 * max(0.0, m(t) - 5.0), 20.0 * CUP + F32)
    assert (tr.at(0.4, "S.TimeCamStatus"), tr.at(0.4, "S.TimeCamLockStatus")) == (1, 0)
    assert tr.at(0.6, "S.TimeCamLockStatus") == 1


def test_immediate_forward_only_follows_forward_travel_only(mp) -> None:
    # master moves (MAM, 100 units/s, 1000 units/s^2): to 10 (done by 0.202), back to 4
    # (0.302..0.457), on to 12 (0.602..0.781). Slave: BIG forward-only from the start:
    # s = 2 * (furthest master distance reached) -> 20, holds 20 while the master backs up
    # (TimeCamLockStatus false), resumes when the master passes 10 again -> 24
    mv = "MAM(M, {0}, absolute, {1}, 100.0, unitspersec, 1000.0, unitspersec2, 1000.0, unitspersec2, trapezoidal, 0.0, 0.0, unitspersec3, disabled, programmed, 0.0, none, 0, 0);"
    body = f"""IF k = 0 THEN
  {mv.format("c3", 10.0)} MDAC(S, M, c1, timecam, command);
  MATC(S, c2, 0, big, 1.0, 1.0, once, immediate, 0.0, immediateforwardonly, masterdrivenmode);
END_IF;
IF k = 300 THEN {mv.format("c4", 4.0)} END_IF;
IF k = 600 THEN {mv.format("c5", 12.0)} END_IF;"""
    tr = mp.trace(
        prog("", body), ["M.CommandPosition", "S.CommandPosition", "S.TimeCamLockStatus"], scans=900
    )
    got = [
        (
            tr.at(t, "M.CommandPosition"),
            tr.at(t, "S.CommandPosition"),
            tr.at(t, "S.TimeCamLockStatus"),
        )
        for t in (0.25, 0.5, 0.85)
    ]
    assert got == [
        pytest.approx((10.0, 20.0, 1)),
        pytest.approx((4.0, 20.0, 0)),
        pytest.approx((12.0, 24.0, 1)),
    ]
    assert max(tr.col("S.CommandPosition")[:600]) == pytest.approx(20.0)  # never followed back


def test_master_driven_jog_with_a_position_lock(mp) -> None:
    # MAJ at 0.5 unit per master unit (accel 1000 per mu^2: at speed after 0.0005 mu), Position
    # Forward lock at 5: nothing until m = 5 (t = 0.507), then s = 0.5 (m - 5) - 0.000125;
    # JogLockStatus set once following
    jog = (
        "MAJ(S, c2, forward, 0.5, unitspermasterunit, 1000.0, unitspermasterunit2, 1000.0, unitspermasterunit2,"
        " trapezoidal, 0.0, 0.0, unitspermasterunit3, disabled, programmed, 5.0, positionforward);"
    )
    body = f"IF k = 0 THEN {JOG_M} MDAC(S, M, c1, jog, command); {jog} END_IF;"
    tr = mp.trace(
        prog("", body), ["S.CommandPosition", "S.JogLockStatus", "S.JogStatus", "c2.IP"], scans=900
    )
    tr.check(
        "S.CommandPosition", lambda t: max(0.0, 0.5 * (m(t) - 5.0) - 0.000125), 5.0 * CUP + F32
    )
    assert [tr.at(0.4, n) for n in ("S.JogStatus", "S.JogLockStatus", "c2.IP")] == [1, 0, 1]
    assert tr.at(0.6, "S.JogLockStatus") == 1


def test_out_of_range_operands_are_error_13_with_the_operand_index(mp) -> None:
    # MDAC faceplate: SlaveAxis 0, MasterAxis 1, MotionControl 2, MotionType 3, MasterReference 4
    body = """IF k = 0 THEN
  mt := 9; mr := 5;
  MDAC(S, M, c1, mt, command);
  MDAC(T, M, c2, move, mr);
END_IF;"""
    tr = mp.trace(
        prog("  mt, mr : DINT;\n", body),
        ["c1.ER", "c1.ERR", "c1.EXERR", "c2.ERR", "c2.EXERR", "c1.IP"],
        scans=2,
    )
    assert [
        tr.at(0.0, n) for n in ("c1.ER", "c1.ERR", "c1.EXERR", "c2.ERR", "c2.EXERR", "c1.IP")
    ] == [1, 13, 3, 13, 4, 0]
