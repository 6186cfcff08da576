"""MDO, MDF, MDS, MRAT, MAAT, MRHD and MAHD through `logixst run --trace`, bit by bit.

Behaviour (docs/decisions/0077-drive-instructions.md, SPEC 9.32): a virtual axis has no drive
and is refused with error 38 (Illegal Axis Data Type) in the executing scan; a drive axis is
the servo model. MDO enables its drive (DriveEnableStatus, AxisStatus bit 1) with nothing
wired to the output: the drive message takes one planner update, as for MSO, and DN comes
with the drive enable; MDF turns the drive off, again at the next update.
MDS needs ramp attributes the servo model does not have: error 86 at once. Tuning and hookup
tests are drive services the model does not carry out: error 12 at the next update.

Timing (motion_trace.py): scan k starts at t = k ms, the planner updates at 0, 2, 4 ... ms
before the scan starting then; a request made in scan k completes at the next update, i.e.
in the row of the first even millisecond after k. Error numbers: stdlib/motion_errors.toml
(4 Servo On State Error, 7 Shutdown State, 12 Servo Message Failure, 13 Parameter Out Of
Range with EXERR = zero-based faceplate operand index, 38, 86).
"""

from __future__ import annotations

HEAD = """VAR
  D, E : AXIS_SERVO := (PositionLoopBandwidth := 20.0);
  V : AXIS_VIRTUAL;
  c1, c2, c3, c4, c5, c6 : MOTION_INSTRUCTION;
  k : DINT;
END_VAR
"""


def prog(body: str) -> str:
    return HEAD + body + "\nk := k + 1;\n"


def test_mdo_enables_the_drive_and_mdf_turns_it_off(mp) -> None:
    body = """IF k = 1 THEN MDO(D, c1, 5.0, volts); END_IF;
IF k = 11 THEN MDF(D, c2); END_IF;"""
    watch = [
        "D.DriveEnableStatus", "D.ServoActionStatus", "D.AxisStatus", "D.ActualPosition",
        "c1.EN", "c1.DN", "c1.ER", "c2.EN", "c2.DN",
    ]  # fmt: skip
    tr = mp.trace(prog(body), watch, scans=20)
    assert tr.at(0.0, "D.DriveEnableStatus") == 0 and tr.at(0.0, "c1.EN") == 0
    # scan 1: EN; the drive enable and DN come together with the update at 2 ms
    assert tr.at(0.001, "c1.EN") == 1 and tr.at(0.001, "c1.DN") == 0
    assert tr.at(0.001, "D.DriveEnableStatus") == 0
    assert tr.at(0.002, "c1.DN") == 1 and tr.at(0.002, "c1.ER") == 0
    assert tr.at(0.002, "D.DriveEnableStatus") == 1
    # the drive stays enabled across the updates at 2, 4 ... 10 ms; the loop stays open:
    # AxisStatus = DriveEnableStatus (bit 1) = 2, ServoActionStatus (bit 0) off
    for t in (0.002, 0.004, 0.006, 0.008, 0.010):
        assert tr.at(t, "D.DriveEnableStatus") == 1, t
        assert tr.at(t, "D.AxisStatus") == 2, t
        assert tr.at(t, "D.ServoActionStatus") == 0, t
        # nothing is wired to the drive output: the axis does not move
        assert tr.at(t, "D.ActualPosition") == 0, t
    # MDF in scan 11: drive off and DN with the update at 12 ms, and it stays off
    assert tr.at(0.011, "D.DriveEnableStatus") == 1 and tr.at(0.011, "c2.DN") == 0
    assert tr.at(0.011, "c2.EN") == 1
    assert tr.at(0.012, "c2.DN") == 1
    for t in (0.012, 0.014, 0.019):
        assert tr.at(t, "D.DriveEnableStatus") == 0 and tr.at(t, "D.AxisStatus") == 0, t


def test_mdo_operand_and_state_errors(mp) -> None:
    body = """IF k = 0 THEN
  MDO(V, c1, 5.0, volts);
  MDO(D, c2, 10.5, volts);
  MDO(D, c3, -101, percent);
  MDO(E, c4, 100, percent);
  MSO(D, c5);
END_IF;
IF k = 4 THEN MDO(D, c6, 1.0, volts); END_IF;"""
    watch = [
        "c1.ER", "c1.ERR", "c2.ER", "c2.ERR", "c2.EXERR", "c3.ERR", "c3.EXERR", "c4.DN",
        "c4.ER", "c5.DN", "c6.ER", "c6.ERR", "D.DriveEnableStatus", "E.DriveEnableStatus",
    ]  # fmt: skip
    tr = mp.trace(prog(body), watch, scans=8)
    # a virtual axis has no drive: error 38 in the executing scan
    assert tr.at(0.0, "c1.ER") == 1 and tr.at(0.0, "c1.ERR") == 38
    # 10.5 V is beyond the +-10 V of the analog output: error 13 on operand 2 (DriveOutput)
    assert tr.at(0.0, "c2.ERR") == 13 and tr.at(0.0, "c2.EXERR") == 2
    # -101 percent is beyond the output range too (the limit holds in both directions)
    assert tr.at(0.0, "c3.ERR") == 13 and tr.at(0.0, "c3.EXERR") == 2
    # 100 percent is the whole output range: accepted, done at the next update (0.002)
    assert tr.at(0.0, "E.DriveEnableStatus") == 0 and tr.at(0.0, "c4.DN") == 0
    assert tr.at(0.002, "c4.DN") == 1 and tr.at(0.002, "c4.ER") == 0
    assert tr.at(0.002, "E.DriveEnableStatus") == 1
    # D's loop was closed by MSO (DN at 0.002): MDO needs Axis Ready, error 4
    assert tr.at(0.002, "c5.DN") == 1
    assert tr.at(0.004, "c6.ER") == 1 and tr.at(0.004, "c6.ERR") == 4
    # D's drive is enabled by the servo loop, not by the refused MDO
    assert tr.at(0.004, "D.DriveEnableStatus") == 1


def test_mso_msf_and_shutdown_end_direct_drive(mp) -> None:
    body = """IF k = 0 THEN MDO(D, c1, 1.0, volts); MDO(E, c2, 1.0, volts); END_IF;
IF k = 3 THEN MSO(D, c3); MASD(E, c4); END_IF;
IF k = 7 THEN MSF(D, c5); END_IF;"""
    watch = [
        "D.DriveEnableStatus", "D.ServoActionStatus", "E.DriveEnableStatus",
        "E.ShutdownStatus", "c3.DN", "c4.DN", "c5.DN",
    ]  # fmt: skip
    tr = mp.trace(prog(body), watch, scans=14)
    assert tr.at(0.002, "D.DriveEnableStatus") == 1 and tr.at(0.002, "E.DriveEnableStatus") == 1
    # MSO closes D's loop at the update at 4 ms: the drive stays on throughout, now with
    # the servo loop
    assert tr.at(0.003, "D.DriveEnableStatus") == 1 and tr.at(0.003, "D.ServoActionStatus") == 0
    assert tr.at(0.004, "c3.DN") == 1 and tr.at(0.004, "D.ServoActionStatus") == 1
    assert tr.at(0.004, "D.DriveEnableStatus") == 1
    # MASD ends E's direct drive: shut down at once, drive off with the update at 4 ms
    assert tr.at(0.003, "E.ShutdownStatus") == 1 and tr.at(0.003, "E.DriveEnableStatus") == 1
    assert tr.at(0.004, "E.DriveEnableStatus") == 0 and tr.at(0.006, "E.DriveEnableStatus") == 0
    # MSF in scan 7: loop open and drive off from the update at 8 ms on, not held by MDO
    assert tr.at(0.008, "c5.DN") == 1
    for t in (0.008, 0.010, 0.013):
        assert tr.at(t, "D.DriveEnableStatus") == 0 and tr.at(t, "D.ServoActionStatus") == 0


def test_mds_is_refused_by_the_position_loop_drive(mp) -> None:
    body = """IF k = 0 THEN
  MDS(D, c1, 10.0, 0);
  MDS(V, c2, 10.0, 0);
  MASD(E, c4);
END_IF;
IF k = 1 THEN MDS(E, c5, 50.0, 1); END_IF;"""
    watch = [
        "c1.EN", "c1.ER", "c1.ERR", "c1.DN", "c2.ERR", "c5.ERR", "D.DirectControlStatus", "D.DirectVelocityControlStatus", "D.DriveEnableStatus",
        "D.ActualVelocity",
    ]  # fmt: skip
    tr = mp.trace(prog(body), watch, scans=6)
    # the servo model has no ramp attributes for direct velocity control: 86 at once
    assert tr.at(0.0, "c1.EN") == 1 and tr.at(0.0, "c1.ER") == 1 and tr.at(0.0, "c1.ERR") == 86
    assert tr.at(0.005, "c1.DN") == 0
    assert tr.at(0.0, "c2.ERR") == 38
    # a shut-down axis: error 7 comes first
    assert tr.at(0.001, "c5.ERR") == 7
    # nothing changed on the axis
    for name in ("DirectControlStatus", "DirectVelocityControlStatus", "DriveEnableStatus"):
        assert tr.at(0.005, f"D.{name}") == 0, name
    assert tr.at(0.005, "D.ActualVelocity") == 0


def test_tuning_and_hookup_requests_fail_at_the_next_update(mp) -> None:
    body = """IF k = 1 THEN
  MRAT(D, c1);
  MRHD(D, c2, 0);
  MAAT(D, c3);
  MAHD(D, c4, 1, 0);
  MRAT(V, c5);
END_IF;"""
    watch = [
        "c1.EN", "c1.ER", "c1.ERR", "c1.IP", "c2.ER", "c2.ERR", "c3.ER", "c3.ERR",
        "c4.ER", "c4.ERR", "c4.EXERR", "c5.ERR", "D.DriveEnableStatus",
    ]  # fmt: skip
    tr = mp.trace(prog(body), watch, scans=6)
    # scan 1: enabled, no answer yet
    assert tr.at(0.001, "c1.EN") == 1 and tr.at(0.001, "c1.ER") == 0
    assert tr.at(0.001, "c1.IP") == 0
    # update at 2 ms: the drive did not carry out the service: error 12, EXERR 0
    for c in ("c1", "c2", "c3", "c4"):
        assert tr.at(0.002, f"{c}.ER") == 1 and tr.at(0.002, f"{c}.ERR") == 12, c
    assert tr.at(0.002, "c4.EXERR") == 0
    assert tr.at(0.005, "c1.EN") == 1  # ST: EN stays until the next execution
    assert tr.at(0.001, "c5.ERR") == 38
    assert tr.at(0.005, "D.DriveEnableStatus") == 0


def test_tuning_and_hookup_state_and_operand_errors(mp) -> None:
    body = """IF k = 0 THEN MSO(D, c1); MASD(E, c2); END_IF;
IF k = 3 THEN
  MRAT(D, c3);
  MRHD(D, c4, 2);
  MAAT(E, c5);
  MAHD(E, c6, 0, 1);
END_IF;"""
    watch = ["c3.ERR", "c4.ERR", "c4.EXERR", "c5.ERR", "c5.EXERR", "c6.ERR", "c6.EXERR"]
    tr = mp.trace(prog(body), watch, scans=6)
    # MRAT moves the motor itself: with the loop closed (MSO done at 2 ms) it is error 4
    assert tr.at(0.003, "c3.ERR") == 4
    # so is the hookup test (marker test, 2)
    assert tr.at(0.003, "c4.ERR") == 4 and tr.at(0.003, "c4.EXERR") == 0
    # a shut-down axis: 12 with EXERR 12 (object mode conflict), at once
    assert tr.at(0.003, "c5.ERR") == 12 and tr.at(0.003, "c5.EXERR") == 12
    assert tr.at(0.003, "c6.ERR") == 12 and tr.at(0.003, "c6.EXERR") == 12


LADDER = """VAR
  D : AXIS_SERVO;
  V : AXIS_VIRTUAL;
  on, off, tune, tv : MOTION_INSTRUCTION;
  go, stop : BOOL;
  k : DINT;
END_VAR
XIC(go)MDO(D,on,50,Percent)MRAT(D,tune)MRHD(V,tv,Marker);
XIC(stop)MDF(D,off);
ADD(k,1,k);
GEQ(k,10)LES(k,20)OTE(go);
GEQ(k,30)OTE(stop);
"""


def test_drive_instructions_in_ladder_are_transitional(mp) -> None:
    # go is true in the scans 10..19 (set at the end of scan 9), stop from scan 30 on
    watch = [
        "on.EN", "on.DN", "tune.EN", "tune.ER", "tune.ERR", "tv.EN", "tv.ER", "tv.ERR",
        "D.DriveEnableStatus", "off.EN", "off.DN",
    ]  # fmt: skip
    tr = mp.trace(LADDER, watch, scans=40, name="prog.rll")
    # scan 10: MDO executes once; drive enable and DN with the update at 12 ms
    assert [tr.at(t, "on.EN") for t in (0.009, 0.010, 0.019)] == [0, 1, 1]
    assert tr.at(0.011, "D.DriveEnableStatus") == 0 and tr.at(0.011, "on.DN") == 0
    assert tr.at(0.012, "on.DN") == 1 and tr.at(0.012, "D.DriveEnableStatus") == 1
    # MRAT on the same axis (loop open): no answer from the drive, error 12 at 12 ms; the
    # rung staying true does not send it again
    assert tr.at(0.011, "tune.ER") == 0
    assert tr.at(0.012, "tune.ER") == 1 and tr.at(0.012, "tune.ERR") == 12
    assert set(tr.col("tune.ERR")[12:20]) == {12.0}
    # MRHD on a virtual axis: error 38 in the executing scan
    assert tr.at(0.010, "tv.ER") == 1 and tr.at(0.010, "tv.ERR") == 38
    # rung false from scan 20: EN cleared because DN or ER is set; DN and ER stay
    assert [tr.at(0.020, n) for n in ("on.EN", "on.DN", "tune.EN", "tune.ER", "tv.EN")] == [
        0,
        1,
        0,
        1,
        0,
    ]
    # the drive stays enabled until MDF in scan 30; drive off and DN at the update at 32 ms
    assert tr.at(0.031, "D.DriveEnableStatus") == 1 and tr.at(0.030, "off.EN") == 1
    assert tr.at(0.031, "off.DN") == 0
    assert tr.at(0.032, "off.DN") == 1 and tr.at(0.032, "D.DriveEnableStatus") == 0


def test_a_request_that_ends_direct_drive_wins_over_a_pending_mdo(mp) -> None:
    # MDO in scan 0 sends its drive message (answered at the update at 2 ms); MSF in scan 1
    # reaches the drive after it, so at 2 ms the drive is off although MDO is done
    body = """IF k = 0 THEN MDO(D, c1, 3.0, volts); END_IF;
IF k = 1 THEN MSF(D, c2); END_IF;"""
    tr = mp.trace(prog(body), ["c1.DN", "c2.DN", "D.DriveEnableStatus"], scans=6)
    assert tr.at(0.002, "c1.DN") == 1 and tr.at(0.002, "c2.DN") == 1
    for t in (0.002, 0.004, 0.005):
        assert tr.at(t, "D.DriveEnableStatus") == 0, t
    # and these instructions are simulated: no U304 warning
    assert "U304" not in tr.err


def test_group_shutdown_ends_direct_drive(mp) -> None:
    src = """VAR
  G : MOTION_GROUP;
  D : AXIS_SERVO;
  c1, c2 : MOTION_INSTRUCTION;
  k : DINT;
END_VAR
IF k = 0 THEN MDO(D, c1, 1.0, volts); END_IF;
IF k = 5 THEN MGSD(G, c2); END_IF;
k := k + 1;
"""
    tr = mp.trace(src, ["c1.DN", "c2.DN", "D.DriveEnableStatus", "D.ShutdownStatus"], scans=10)
    assert tr.at(0.002, "D.DriveEnableStatus") == 1 and tr.at(0.005, "D.DriveEnableStatus") == 1
    # MGSD in scan 5: shut down at once; a drive axis in the group: DN and drive off at 6 ms
    assert tr.at(0.005, "D.ShutdownStatus") == 1 and tr.at(0.005, "c2.DN") == 0
    assert tr.at(0.006, "c2.DN") == 1
    for t in (0.006, 0.008, 0.009):
        assert tr.at(t, "D.DriveEnableStatus") == 0, t
