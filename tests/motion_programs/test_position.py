"""MRP (redefine position) and MAH (home axis) through the VM, against hand formulas.

Both take effect at the next planner update (SPEC 9.3): an instruction executed in the scan
at t is applied at the start of the update after it, before that update's motion step.
Jog used below: MAJ forward 10 units/s, accel 100 units/s^2 from the update 0.002, so
    x(t) = 50 (t - 0.002)^2 for t <= 0.102, else 0.5 + 10 (t - 0.102).
A trace row at t shows the latest update at or before t: expectations use upd(t).
"""

from __future__ import annotations

import math
from collections.abc import Callable

from motion_trace import CUP

F32 = 1e-4
HEAD = """VAR
  X, Y : AXIS_VIRTUAL := (MaximumSpeed := 1000.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0,
                          HomePosition := 25.0);
  c1, c2, c3, c4, c5 : MOTION_INSTRUCTION;
  k : DINT;
"""


def prog(decls: str, body: str) -> str:
    return HEAD + decls + "END_VAR\n" + body + "\nk := k + 1;\n"


def upd(t: float) -> float:
    return math.floor(t / CUP + 1e-9) * CUP


def at_update(f: Callable[[float], float]) -> Callable[[float], float]:
    return lambda t: f(upd(t))


def jog(axis: str, ctl: str) -> str:
    return (
        f"MAJ({axis}, {ctl}, forward, 10.0, unitspersec, 100.0, unitspersec2, 100.0, unitspersec2, "
        "trapezoidal, 0.0, 0.0, unitspersec3, disabled, programmed, 0.0, none);"
    )


def x(t: float) -> float:
    if t <= 0.002:
        return 0.0
    if t <= 0.102:
        return 50.0 * (t - 0.002) ** 2
    return 0.5 + 10.0 * (t - 0.102)


# ------------------------------------------------------------------ MRP
def test_mrp_then_absolute_move_reaches_the_target_in_the_new_frame(mp) -> None:
    # X at rest at 0; MRP Absolute Actual 100 at t = 0 -> X = 100 from the update 0.002 (DN
    # after that update). MAM Absolute 110 at t = 0.01 (update 0.012): D = 10, V 10, A = Dc
    # = 100: T = D/V + V/2A + V/2Dc = 1 + 0.05 + 0.05 = 1.1 -> PC at 1.112, X = 110.
    move = (
        "MAM(X, c2, absolute, 110.0, 10.0, unitspersec, 100.0, unitspersec2, 100.0, unitspersec2, "
        "trapezoidal, 0.0, 0.0, unitspersec3, disabled, programmed, 0.0, none, 0, 0);"
    )
    body = f"""IF k = 0 THEN MRP(X, c1, absolute, actual, 100.0); END_IF;
IF k = 10 THEN {move} END_IF;"""
    tr = mp.trace(
        prog("", body),
        ["X.ActualPosition", "X.CommandPosition", "c1.DN", "c1.IP", "c2.PC"],
        scans=1200,
    )
    assert (tr.at(0.001, "X.CommandPosition"), tr.at(0.002, "X.CommandPosition")) == (0.0, 100.0)
    assert tr.at(0.002, "X.ActualPosition") == 100.0
    # the request needs a coarse update: DN after it, no IP
    assert (tr.at(0.0, "c1.DN"), tr.at(0.002, "c1.DN"), tr.at(0.002, "c1.IP")) == (0, 1, 0)
    assert (tr.at(1.111, "c2.PC"), tr.at(1.112, "c2.PC")) == (0, 1)
    assert abs(tr.at(1.112, "X.CommandPosition") - 110.0) < F32


def test_mrp_relative_during_a_jog_shifts_the_frame_without_disturbing_the_motion(mp) -> None:
    # MRP Relative Command -50 at t = 0.3 (update 0.302): X(t) = x(t) - 50 from then on, the
    # velocity stays 10 (no spike in CommandVelocity or AverageVelocity)
    body = f"""IF k = 0 THEN {jog("X", "c1")} END_IF;
IF k = 300 THEN MRP(X, c2, relative, command, -50.0); END_IF;"""
    tr = mp.trace(
        prog("", body),
        ["X.CommandPosition", "X.CommandVelocity", "X.AverageVelocity", "c1.IP"],
        scans=600,
    )
    tr.check("X.CommandPosition", at_update(lambda t: x(t) - (50.0 if t >= 0.302 else 0.0)), F32)
    assert abs(tr.at(0.302, "X.CommandVelocity") - 10.0) < 1e-4
    # AverageVelocity over 0.25 s of steady travel: 10 units/s, across the redefinition
    assert abs(tr.at(0.4, "X.AverageVelocity") - 10.0) < 1e-3
    assert tr.at(0.599, "c1.IP") == 1


def test_mrp_of_a_master_leaves_its_gear_slave_undisturbed(mp) -> None:
    # Y geared 1:1 to X from the start; MRP Absolute Command 1000 on X at t = 0.3: X jumps,
    # Y keeps following X's travel, y(t) = x(t)
    body = f"""IF k = 0 THEN {jog("X", "c1")}
  MAG(Y, X, c2, same, 1.0, 1, 1, command, real, disabled, 0.0, unitspersec2); END_IF;
IF k = 300 THEN MRP(X, c3, absolute, command, 1000.0); END_IF;"""
    tr = mp.trace(prog("", body), ["X.CommandPosition", "Y.CommandPosition"], scans=500)
    tr.check("Y.CommandPosition", at_update(x), F32)
    # x(0.3) = 2.48 is replaced by 1000 at the update 0.302, then one step of 0.02
    assert abs(tr.at(0.302, "X.CommandPosition") - 1000.02) < F32


def test_mrp_actual_on_a_drive_keeps_the_following_error(mp) -> None:
    # drive D (servo model: first-order lag, tau = 1/(2 pi 20 Hz)) jogging at 10 units/s in
    # steady state lags by e = v cup q / (1 - q), q = exp(-cup / tau) (decision 0100).
    # MRP Absolute Actual 0 at t = 0.5: actual := 0 and command := e at the update 0.502,
    # then both advance 10 x 0.002: ActualPosition(0.502) = 0.02, PositionError stays e.
    decls = "  D : AXIS_CIP_DRIVE := (MaximumSpeed := 1000.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0);\n"
    body = f"""IF k = 0 THEN MSO(D, c1); END_IF;
IF k = 2 THEN {jog("D", "c2")} END_IF;
IF k = 500 THEN MRP(D, c3, absolute, actual, 0.0); END_IF;"""
    tr = mp.trace(prog(decls, body), ["D.ActualPosition", "D.PositionError"], scans=600)
    tau = 1.0 / (2.0 * math.pi * 20.0)
    q = math.exp(-CUP / tau)
    e = 10.0 * CUP * q / (1.0 - q)
    assert abs(tr.at(0.5, "D.PositionError") - e) < 1e-3
    assert abs(tr.at(0.502, "D.PositionError") - e) < 1e-3
    assert abs(tr.at(0.502, "D.ActualPosition") - 0.02) < 1e-3


def test_mrp_enumerations_are_checked_before_running(mp) -> None:
    # Type and PositionSelect are immediate enumerations (0..1): a bad number is a check
    # error (E109) at its column, the program does not run
    body = """IF k = 0 THEN
  MRP(X, c1, 2, actual, 1.0);
  MRP(X, c2, absolute, 5, 1.0);
END_IF;"""
    code, _, err = mp.run(prog("", body))
    assert code != 0
    assert "prog.st:8:14: error E109 2 is not a value of MRP Type" in err
    assert "prog.st:9:24: error E109 5 is not a value of MRP PositionSelect" in err


# ------------------------------------------------------------------ MAH
def test_active_immediate_homing_ends_motion_and_sets_home_position(mp) -> None:
    # virtual axis, default HomeMode Active, HomeSequence Immediate, HomePosition 25.
    # MAH at t = 0.2 (update 0.202): the jog ends (IP cleared, no PC), X = 25 and holds;
    # MAH: DN and IP at execution, PC (IP cleared) and AxisHomedStatus at the update.
    body = f"IF k = 0 THEN {jog('X', 'c1')} END_IF;\nIF k = 200 THEN MAH(X, c2); END_IF;"
    names = ["X.CommandPosition", "c1.IP", "c1.PC", "c2.DN", "c2.IP", "c2.PC"]
    tr = mp.trace(prog("", body), [*names, "X.AxisHomedStatus", "X.JogStatus"], scans=300)
    assert (tr.at(0.2, "c2.DN"), tr.at(0.2, "c2.IP"), tr.at(0.2, "c2.PC")) == (1, 1, 0)
    assert [tr.at(0.202, n) for n in names] == [25.0, 0, 0, 1, 0, 1]
    assert (tr.at(0.2, "X.AxisHomedStatus"), tr.at(0.202, "X.AxisHomedStatus")) == (0, 1)
    assert (tr.at(0.299, "X.CommandPosition"), tr.at(0.299, "X.JogStatus")) == (25.0, 0)


def test_passive_immediate_homing_keeps_the_motion(mp) -> None:
    # HomeMode Passive: the position becomes 25 at the update 0.202 (before its step), the
    # jog goes on: X(t) = 25 + x(t) - x(0.2) from then on
    decls = "  P : AXIS_VIRTUAL := (MaximumSpeed := 1000.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0, HomeMode := 0, HomePosition := 25.0);\n"
    body = f"IF k = 0 THEN {jog('P', 'c1')} END_IF;\nIF k = 200 THEN MAH(P, c2); END_IF;"
    tr = mp.trace(prog(decls, body), ["P.CommandPosition", "c1.IP", "c2.PC"], scans=300)
    tr.check(
        "P.CommandPosition",
        at_update(lambda t: 25.0 + x(t) - x(0.2) if t >= 0.202 else x(t)),
        F32,
    )
    assert (tr.at(0.299, "c1.IP"), tr.at(0.202, "c2.PC")) == (1, 1)


def test_homing_configurations_the_simulated_axes_cannot_run(mp) -> None:
    # error table: 41 Illegal Homing Configuration (virtual axis, non-immediate sequence;
    # active marker homing needs marker feedback the simulated drive lacks), 84 Drive Digital
    # Input Not Assigned (home switch), 5 Servo Off State (active homing, servo off)
    decls = """  V : AXIS_VIRTUAL := (HomeSequence := 2);
  SW : AXIS_CIP_DRIVE := (HomeSequence := 1);
  MK, OFF : AXIS_CIP_DRIVE;
  m1 : MOTION_INSTRUCTION;
"""
    body = """IF k = 0 THEN MSO(MK, m1); END_IF;
IF k = 4 THEN
  MAH(V, c1); MAH(SW, c2); MAH(OFF, c4);
  MK.HomeSequence := 2; MAH(MK, c3);
END_IF;"""
    names = ["c1.ERR", "c2.ERR", "c3.ERR", "c4.ERR", "c1.ER", "c4.ER"]
    tr = mp.trace(prog(decls, body), names, scans=6)
    assert [tr.at(0.004, n) for n in names] == [41, 84, 41, 5, 1, 1]


def test_passive_marker_homing_waits_until_stopped(mp) -> None:
    # passive homing on the marker: no marker ever comes on the simulated drive, so the
    # request stays in process (HomingStatus) without moving the axis, until MAS Home ends
    # it (IP cleared, no PC); the axis is not homed
    decls = "  D : AXIS_CIP_DRIVE := (HomeMode := 0, HomeSequence := 2, MaximumDecel := 1000.0);\n"
    body = """IF k = 0 THEN MAH(D, c1); END_IF;
IF k = 100 THEN MAS(D, c2, home, no, 0.0, unitspersec2, no, 0.0, unitspersec3); END_IF;"""
    names = ["c1.IP", "c1.PC", "D.HomingStatus", "D.AxisHomedStatus", "c2.PC"]
    tr = mp.trace(prog(decls, body), names, scans=200)
    assert [tr.at(0.098, n) for n in names] == [1, 0, 1, 0, 0]
    assert [tr.at(0.102, n) for n in names] == [0, 0, 0, 0, 1]
