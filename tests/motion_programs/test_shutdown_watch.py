"""MASD/MASR, MGSD/MGSR, MGSP, MAW/MDW and MCSV through `logixst run`, against hand values.

Timing (motion_trace.py): scan k starts at t = k ms, the planner updates at 0, 2, 4 ... ms
before the scan starting then, and an instruction executed in scan k takes effect at the
next update, where its own clock is 0. A trace row shows the values at the end of its scan.

Jog used below (speed 10, accel 1000, started in scan 0, so at the update t0 = 2 ms): the
accel phase lasts 10/1000 = 0.01 s and covers 1000 * 0.01**2 / 2 = 0.05; after that the
axis gains 10 per second. At an update with own clock c >= 0.01 the position is
0.05 + 10 * (c - 0.01).
"""

from __future__ import annotations

from motion_trace import CUP

F32 = 1e-4
HEAD = """VAR
  X, Y : AXIS_VIRTUAL := (MaximumSpeed := 20.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0);
  c1, c2, c3, c4, c5, c6 : MOTION_INSTRUCTION;
  k : DINT;
"""


def prog(decls: str, body: str) -> str:
    return HEAD + decls + "END_VAR\n" + body + "\nk := k + 1;\n"


def jog(axis: str, ctl: str, direction: str = "forward", speed: float = 10.0) -> str:
    return (
        f"MAJ({axis}, {ctl}, {direction}, {speed}, unitspersec, 1000.0, unitspersec2, 1000.0, "
        f"unitspersec2, trapezoidal, 0.0, 0.0, unitspersec3, disabled, programmed, 0.0, none);"
    )


def mam(axis: str, ctl: str, pos: float, v: float = 5.0, a: float = 100.0) -> str:
    return (
        f"MAM({axis}, {ctl}, absolute, {pos}, {v}, unitspersec, {a}, unitspersec2, {a}, "
        f"unitspersec2, trapezoidal, 0.0, 0.0, unitspersec3, disabled, programmed, 0.0, none, 0, 0);"
    )


def test_masd_stops_a_virtual_axis_at_once_and_refuses_motion_until_masr(mp) -> None:
    body = f"""IF k = 0 THEN {jog("X", "c1")} END_IF;
IF k = 100 THEN MASD(X, c2); END_IF;
IF k = 150 THEN {mam("X", "c3", 5.0)} END_IF;
IF k = 200 THEN MASR(X, c4); END_IF;
IF k = 250 THEN {mam("X", "c5", 5.0)} END_IF;"""
    watch = [
        "X.CommandPosition", "X.CommandVelocity", "X.ShutdownStatus", "X.JogStatus",
        "X.AxisStatus", "c1.IP", "c1.PC", "c2.DN", "c3.ER", "c3.ERR", "c4.DN", "c5.DN",
        "c5.ER",
    ]  # fmt: skip
    tr = mp.trace(prog("", body), watch, scans=300)
    # before the shutdown: jogging; position at the update 0.1 (clock 0.098) = 0.05 + 0.88
    assert tr.at(0.099, "X.JogStatus") == 1
    assert abs(tr.at(0.1, "X.CommandPosition") - 0.93) < F32
    # MASD: a virtual axis completes in the executing scan and shows ShutdownStatus at once
    assert tr.at(0.1, "c2.DN") == 1
    assert tr.at(0.1, "X.ShutdownStatus") == 1
    assert tr.at(0.099, "X.ShutdownStatus") == 0
    # the motion ends at the next update without a ramp: the position stays at 0.93
    assert tr.at(0.102, "X.CommandVelocity") == 0
    assert tr.at(0.102, "X.JogStatus") == 0
    assert abs(tr.at(0.149, "X.CommandPosition") - 0.93) < F32
    # the jog was ended, not completed: IP cleared, no PC
    assert tr.at(0.101, "c1.IP") == 1
    assert tr.at(0.102, "c1.IP") == 0 and tr.at(0.102, "c1.PC") == 0
    # AxisStatus: ServoActionStatus (bit 0, always on for a virtual axis) + ShutdownStatus (bit 2)
    assert tr.at(0.12, "X.AxisStatus") == 1 + 4
    # a move on a shut-down axis is refused with error 7 (shutdown state)
    assert tr.at(0.15, "c3.ER") == 1 and tr.at(0.15, "c3.ERR") == 7
    # MASR: completes at once on a virtual axis, the axis is ready again and moves
    assert tr.at(0.2, "c4.DN") == 1
    assert tr.at(0.2, "X.ShutdownStatus") == 0
    assert tr.at(0.25, "c5.DN") == 1 and tr.at(0.25, "c5.ER") == 0
    assert tr.at(0.299, "X.CommandPosition") > 0.93


def test_masd_on_a_drive_axis_opens_the_loop_and_mso_is_refused_until_masr(mp) -> None:
    decls = "  D : AXIS_CIP_DRIVE := (MaximumSpeed := 20.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0);\n"
    body = """IF k = 0 THEN MSO(D, c1); END_IF;
IF k = 10 THEN MASD(D, c2); END_IF;
IF k = 20 THEN MSO(D, c3); END_IF;
IF k = 30 THEN MASR(D, c4); END_IF;
IF k = 40 THEN MSO(D, c5); END_IF;"""
    watch = [
        "D.ServoActionStatus", "D.ShutdownStatus", "c2.DN", "c3.ER", "c3.ERR", "c4.DN",
        "c5.DN", "D.DriveEnableStatus",
    ]  # fmt: skip
    tr = mp.trace(prog(decls, body), watch, scans=50)
    assert tr.at(0.009, "D.ServoActionStatus") == 1
    # a drive axis: the shutdown takes the drive message of one coarse update (DN at 0.012)
    assert tr.at(0.01, "D.ShutdownStatus") == 1
    assert tr.at(0.01, "c2.DN") == 0 and tr.at(0.012, "c2.DN") == 1
    assert tr.at(0.012, "D.ServoActionStatus") == 0 and tr.at(0.012, "D.DriveEnableStatus") == 0
    # servo on is refused while shut down
    assert tr.at(0.02, "c3.ER") == 1 and tr.at(0.02, "c3.ERR") == 7
    # the reset leaves the loop open; MSO then closes it again
    assert tr.at(0.032, "c4.DN") == 1 and tr.at(0.032, "D.ShutdownStatus") == 0
    assert tr.at(0.039, "D.ServoActionStatus") == 0
    assert tr.at(0.042, "c5.DN") == 1 and tr.at(0.042, "D.ServoActionStatus") == 1


def test_mgsd_and_mgsr_act_on_every_axis_of_the_group(mp) -> None:
    decls = "  G : MOTION_GROUP;\n  c7 : MOTION_INSTRUCTION;\n"
    body = f"""IF k = 0 THEN MGSD(G, c1); END_IF;
IF k = 10 THEN {mam("Y", "c2", 1.0)} END_IF;
IF k = 20 THEN MGSR(G, c3); END_IF;
IF k = 30 THEN {mam("Y", "c4", 1.0)} END_IF;"""
    watch = [
        "X.ShutdownStatus", "Y.ShutdownStatus", "c1.DN", "c2.ER", "c2.ERR", "c3.DN", "c4.DN",
    ]  # fmt: skip
    tr = mp.trace(prog(decls, body), watch, scans=40)
    # only virtual axes in the group: the group request completes in the executing scan
    assert tr.at(0.0, "c1.DN") == 1
    assert tr.at(0.0, "X.ShutdownStatus") == 1 and tr.at(0.0, "Y.ShutdownStatus") == 1
    assert tr.at(0.01, "c2.ER") == 1 and tr.at(0.01, "c2.ERR") == 7
    assert tr.at(0.02, "c3.DN") == 1
    assert tr.at(0.02, "X.ShutdownStatus") == 0 and tr.at(0.02, "Y.ShutdownStatus") == 0
    assert tr.at(0.03, "c4.DN") == 1


def test_mgsp_latches_every_axis_position_of_the_latest_update(mp) -> None:
    decls = "  G : MOTION_GROUP;\n"
    body = f"""IF k = 0 THEN {jog("X", "c1")} {jog("Y", "c2", "reverse", 5.0)} END_IF;
IF k = 50 THEN MGSP(G, c3); END_IF;"""
    watch = [
        "X.StrobeActualPosition", "X.StrobeCommandPosition", "Y.StrobeActualPosition",
        "Y.StrobeCommandPosition", "X.CommandPosition", "c3.DN",
    ]  # fmt: skip
    tr = mp.trace(prog(decls, body), watch, scans=80)
    assert tr.at(0.049, "X.StrobeActualPosition") == 0
    assert tr.at(0.05, "c3.DN") == 1
    # X at the update 0.05 (clock 0.048): 0.05 + 10 * (0.048 - 0.01) = 0.43
    # Y (speed 5 reverse): ramp 0.005 s covering 0.0125, then 5/s: -(0.0125 + 5 * 0.043)
    for name, value in (("X", 0.43), ("Y", -0.2275)):
        for attr in ("StrobeActualPosition", "StrobeCommandPosition"):
            assert abs(tr.at(0.05, f"{name}.{attr}") - value) < F32, (name, attr)
            # the strobe keeps its value while the axis moves on
            assert abs(tr.at(0.079, f"{name}.{attr}") - value) < F32, (name, attr)
    assert tr.at(0.079, "X.CommandPosition") > 0.6


def test_maw_forward_fires_at_the_first_update_past_the_position(mp) -> None:
    # MAM to 10 at 5/s, accel 100, started at the update 0.002: the ramp lasts 0.05 s and
    # covers 0.125; the position reaches 2.0 at clock 0.05 + (2 - 0.125)/5 = 0.425, i.e.
    # t = 0.427. At the update 0.426 (clock 0.424) the axis is at 1.995, at 0.428 at 2.005.
    body = f"""IF k = 0 THEN MAW(X, c1, forward, 2.0); {mam("X", "c2", 10.0)} END_IF;"""
    watch = [
        "c1.DN", "c1.IP", "c1.PC", "X.WatchEventArmedStatus", "X.WatchEventStatus",
        "X.WatchPosition", "X.AxisEvent", "X.WatchTime", "X.ActualPosition",
    ]  # fmt: skip
    tr = mp.trace(prog("", body), watch, scans=500)
    assert tr.at(0.0, "c1.DN") == 1 and tr.at(0.0, "c1.IP") == 1
    assert tr.at(0.0, "X.WatchEventArmedStatus") == 1 and tr.at(0.0, "X.WatchEventStatus") == 0
    assert tr.at(0.0, "X.WatchPosition") == 2.0
    assert tr.at(0.0, "X.AxisEvent") == 1  # WatchEventArmedStatus is bit 0
    assert tr.at(0.427, "c1.PC") == 0 and tr.at(0.427, "c1.IP") == 1
    assert abs(tr.at(0.427, "X.ActualPosition") - 1.995) < F32
    assert tr.first("c1.PC", lambda v: v == 1) == 0.428
    assert tr.at(0.428, "c1.IP") == 0
    assert tr.at(0.428, "X.WatchEventStatus") == 1
    assert tr.at(0.428, "X.WatchEventArmedStatus") == 0
    assert tr.at(0.428, "X.AxisEvent") == 2  # WatchEventStatus is bit 1
    assert tr.at(0.428, "X.WatchTime") == 428000  # CST of that update, µs


def test_maw_reverse_waits_for_a_crossing_in_its_direction_and_mdw_disarms(mp) -> None:
    # forward jog from 0: the reverse watch at 0.5 is passed forward at about t = 0.057 and
    # never backwards, so it stays armed until MDW at scan 100
    body = f"""IF k = 0 THEN MAW(X, c1, reverse, 0.5); {jog("X", "c2")} END_IF;
IF k = 100 THEN MDW(X, c3); END_IF;"""
    watch = [
        "c1.IP", "c1.PC", "c3.DN", "X.WatchEventArmedStatus", "X.WatchEventStatus",
        "X.ActualPosition",
    ]  # fmt: skip
    tr = mp.trace(prog("", body), watch, scans=120)
    assert tr.at(0.099, "X.ActualPosition") > 0.5
    assert tr.at(0.099, "c1.IP") == 1 and tr.at(0.099, "X.WatchEventArmedStatus") == 1
    assert all(v == 0 for v in tr.col("c1.PC"))
    # MDW completes at once and clears the watch bits; the MAW leaves IP at the next update
    assert tr.at(0.1, "c3.DN") == 1
    assert tr.at(0.1, "X.WatchEventArmedStatus") == 0 and tr.at(0.1, "X.WatchEventStatus") == 0
    assert tr.at(0.1 + CUP, "c1.IP") == 0


def test_mcsv_evaluates_a_calculated_profile(mp) -> None:
    # One cubic segment from (0, 0) to (10, 20) with slopes 0 at both ends is the Hermite
    # curve p = 20 (3 s^2 - 2 s^3), s = u/10: p' = 20 (6 s - 6 s^2)/10, p'' = 20 (6 - 12 s)/100.
    # At u = 2.5 (s = 0.25): p = 3.125, p' = 2.25, p'' = 0.6.
    decls = """  pts : CAM[2] := [(Master := 0.0, Slave := 0.0, SegmentType := 1), (Master := 10.0, Slave := 20.0, SegmentType := 1)];
  prof, none2 : CAM_PROFILE[2];
  s, d1, d2, s2, d12, d22 : REAL;
"""
    body = """IF k = 0 THEN MCCP(c1, pts, 2, 0.0, 0.0, prof); END_IF;
IF k = 1 THEN MCSV(c2, prof, 2.5, s, d1, d2); END_IF;
IF k = 2 THEN MCSV(c3, prof, 12.0, s2, d12, d22); END_IF;
IF k = 3 THEN MCSV(c4, none2, 1.0, s2, d12, d22); END_IF;"""
    watch = ["c2.DN", "s", "d1", "d2", "c3.ER", "c3.ERR", "c3.EXERR", "c4.ER", "c4.ERR", "s2"]
    tr = mp.trace(prog(decls, body), watch, scans=5)
    assert tr.at(0.001, "c2.DN") == 1
    assert abs(tr.at(0.001, "s") - 3.125) < F32
    assert abs(tr.at(0.001, "d1") - 2.25) < F32
    assert abs(tr.at(0.001, "d2") - 0.6) < F32
    # outside the profile's master range: error 13 on MasterValue (faceplate index 2)
    assert tr.at(0.002, "c3.ER") == 1 and tr.at(0.002, "c3.ERR") == 13
    assert tr.at(0.002, "c3.EXERR") == 2
    # a profile never calculated: error 32, outputs untouched
    assert tr.at(0.003, "c4.ER") == 1 and tr.at(0.003, "c4.ERR") == 32
    assert tr.at(0.003, "s2") == 0


def test_mar_arms_and_waits_for_an_input_nothing_drives_and_mdr_disarms(mp) -> None:
    # Studio's 7-operand form (input 2) and the older form without InputNumber (input 1)
    body = """IF k = 0 THEN MAR(X, c1, positive_edge, disabled, 0.0, 0.0, 2); MAR(X, c2, negative_edge, enabled, 1.0, 5.0); END_IF;
IF k = 10 THEN MDR(X, c3, 2); END_IF;
IF k = 12 THEN MAR(X, c4, positive_edge, enabled, 5.0, 1.0, 1); MDR(X, c5, 3); END_IF;"""
    watch = [
        "c1.DN", "c1.IP", "c1.PC", "c2.IP", "c3.DN", "X.RegEvent1ArmedStatus",
        "X.RegEvent2ArmedStatus", "X.RegEvent2Status", "X.AxisEvent", "c4.ER", "c4.ERR",
        "c4.EXERR", "c5.ER", "c5.EXERR",
    ]  # fmt: skip
    tr = mp.trace(prog("", body), watch, scans=20)
    assert tr.at(0.0, "c1.DN") == 1 and tr.at(0.0, "c1.IP") == 1
    # RegEvent1ArmedStatus is bit 2 of AxisEvent, RegEvent2ArmedStatus bit 4
    assert tr.at(0.0, "X.AxisEvent") == 4 + 16
    assert tr.at(0.0, "X.RegEvent1ArmedStatus") == 1 and tr.at(0.0, "X.RegEvent2ArmedStatus") == 1
    # no edge reaches the simulated inputs: still armed, no PC
    assert tr.at(0.009, "c1.IP") == 1 and tr.at(0.009, "c2.IP") == 1
    assert all(v == 0 for v in tr.col("c1.PC"))
    # MDR on input 2: done at once, bits cleared at once, the MAR leaves IP at the next update
    assert tr.at(0.01, "c3.DN") == 1
    assert tr.at(0.01, "X.RegEvent2ArmedStatus") == 0 and tr.at(0.01, "X.RegEvent2Status") == 0
    assert tr.at(0.01 + CUP, "c1.IP") == 0
    assert tr.at(0.01 + CUP, "c2.IP") == 1  # input 1 is still armed
    # a window whose maximum is not above its minimum: ERR 13 on MaximumPosition (index 5)
    assert tr.at(0.012, "c4.ER") == 1 and tr.at(0.012, "c4.ERR") == 13
    assert tr.at(0.012, "c4.EXERR") == 5
    # there are only registration inputs 1 and 2 (MDR InputNumber is operand 2)
    assert tr.at(0.012, "c5.ER") == 1 and tr.at(0.012, "c5.EXERR") == 2


def test_mgs_with_a_programmed_hard_shutdown_leaves_the_axis_shut_down(mp) -> None:
    # ProgrammedStopMode 4 (Hard Shutdown): MGS Programmed shuts the axis down at once
    decls = "  G : MOTION_GROUP;\n  Z : AXIS_VIRTUAL := (ProgrammedStopMode := 4);\n"
    body = f"""IF k = 0 THEN {jog("Z", "c1")} END_IF;
IF k = 20 THEN MGS(G, c2, programmed); END_IF;
IF k = 30 THEN {mam("Z", "c3", 1.0)} END_IF;"""
    tr = mp.trace(prog(decls, body), ["Z.ShutdownStatus", "Z.CommandVelocity", "c3.ERR"], 40)
    assert tr.at(0.019, "Z.ShutdownStatus") == 0
    assert tr.at(0.022, "Z.ShutdownStatus") == 1 and tr.at(0.022, "Z.CommandVelocity") == 0
    assert tr.at(0.03, "c3.ERR") == 7


def test_mcsd_and_mcsr_shut_down_the_axes_of_a_coordinate_system(mp) -> None:
    decls = "  CS : COORDINATE_SYSTEM := (Axes := [X, Y]);\n  Z : AXIS_VIRTUAL;\n"
    body = f"""IF k = 0 THEN MCSD(CS, c1); END_IF;
IF k = 5 THEN {mam("X", "c2", 1.0)} {mam("Z", "c3", 1.0)} END_IF;
IF k = 10 THEN MCSR(CS, c4); END_IF;"""
    watch = [
        "c1.DN", "X.ShutdownStatus", "Y.ShutdownStatus", "Z.ShutdownStatus",
        "CS.ShutdownStatus", "CS.CoordinateSystemStatus", "c2.ERR", "c3.DN", "c4.DN",
    ]  # fmt: skip
    tr = mp.trace(prog(decls, body), watch, scans=12)
    assert tr.at(0.0, "c1.DN") == 1  # virtual axes only: done in the executing scan
    assert [tr.at(0.0, f"{a}.ShutdownStatus") for a in ("X", "Y", "Z")] == [1, 1, 0]
    assert tr.at(0.0, "CS.ShutdownStatus") == 1
    assert tr.at(0.0, "CS.CoordinateSystemStatus") == 1  # ShutdownStatus is bit 0
    assert tr.at(0.005, "c2.ERR") == 7  # an axis of the system refuses motion
    assert tr.at(0.005, "c3.DN") == 1  # an axis outside the system is not affected
    assert tr.at(0.01, "c4.DN") == 1
    assert tr.at(0.01, "X.ShutdownStatus") == 0 and tr.at(0.01, "CS.ShutdownStatus") == 0
    assert tr.at(0.01, "CS.CoordinateSystemStatus") == 0


def test_a_shut_down_axis_refuses_gearing_and_active_homing(mp) -> None:
    # After MASD (scan 0, done in that scan) the axis is in the shutdown state: MAG with it
    # as slave and an Active MAH (the default HomeMode of a virtual axis is Active) are
    # refused with error 7 in the scan they execute.
    body = """IF k = 0 THEN MASD(X, c1); END_IF;
IF k = 10 THEN MAG(X, Y, c2, same, 1.0, 1, 1, command, real, disabled, 0.0, unitspersec2); END_IF;
IF k = 20 THEN MAH(X, c3); END_IF;"""
    tr = mp.trace(prog("", body), ["c1.DN", "c2.ER", "c2.ERR", "c3.ER", "c3.ERR"], scans=30)
    assert tr.at(0.0, "c1.DN") == 1
    assert (tr.at(0.01, "c2.ER"), tr.at(0.01, "c2.ERR")) == (1, 7)
    assert (tr.at(0.02, "c3.ER"), tr.at(0.02, "c3.ERR")) == (1, 7)
