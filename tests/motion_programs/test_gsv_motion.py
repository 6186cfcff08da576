"""GSV/SSV of the motion object classes (AXIS, MOTIONGROUP, COORDINATESYSTEM) through
`logixst run`, and the U303 warnings of attributes logixst does not simulate.

The attribute table is catalog data (stdlib/system_objects.toml): a motion object's
attributes are the members of its tag, so GSV reads the tag named as InstanceName and SSV
writes it.
"""

from __future__ import annotations

import json

from motion_trace import CUP

from interpreter.cli import main
from interpreter.instructions.ladder_system import gsv
from interpreter.semantics.types import INT
from interpreter.vm.context import ExecContext
from interpreter.vm.refs import Ref
from stdlib import catalog

HEAD = """VAR
  X : AXIS_VIRTUAL := (MaximumSpeed := 20.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0);
  G : MOTION_GROUP;
  c1, c2 : MOTION_INSTRUCTION;
  k : DINT;
"""


def test_gsv_reads_axis_and_group_attributes_and_ssv_sets_a_limit(mp) -> None:
    # jog at 10/s (accel 1000): at the update 0.02 (clock 0.018) X is at
    # 0.05 + 10 * (0.018 - 0.01) = 0.13, moving at 10
    src = (
        HEAD
        + """  pos, vel, acc, newmax, maxv : REAL;
  cup, servo : DINT;
END_VAR
IF k = 0 THEN
  MAJ(X, c1, forward, 10.0, unitspersec, 1000.0, unitspersec2, 1000.0, unitspersec2,
      trapezoidal, 0.0, 0.0, unitspersec3, disabled, programmed, 0.0, none);
END_IF;
GSV(Axis, X, ActualPosition, pos);
GSV(Axis, X, CommandVelocity, vel);
GSV(Axis, X, ServoActionStatus, servo);
GSV(MotionGroup, G, CoarseUpdatePeriod, cup);
newmax := 50.0;
IF k = 30 THEN SSV(Axis, X, MaximumAcceleration, newmax); END_IF;
GSV(Axis, X, MaximumAcceleration, maxv);
GSV(Axis, X, MaximumAccel, acc);
k := k + 1;
"""
    )
    tr = mp.trace(src, ["pos", "vel", "servo", "cup", "maxv", "acc", "X.MaximumAccel"], scans=40)
    assert abs(tr.at(0.02, "pos") - 0.13) < 1e-4
    assert tr.at(0.02, "vel") == 10.0
    assert tr.at(0.02, "servo") == 1  # a virtual axis is always under servo control
    assert tr.at(0.0, "cup") == round(CUP * 1e6)  # the group's period in µs
    # MaximumAcceleration is the GSV name of the MaximumAccel member
    assert tr.at(0.029, "maxv") == 1000.0
    assert tr.at(0.03, "maxv") == 50.0 and tr.at(0.03, "acc") == 50.0
    assert tr.at(0.03, "X.MaximumAccel") == 50.0


def test_gsv_coordinate_system_tolerance_by_its_attribute_name(mp) -> None:
    src = (
        HEAD
        + """  CS : COORDINATE_SYSTEM := (CommandTolerance := 0.25);
  tol, newtol, tol2 : REAL;
END_VAR
GSV(CoordinateSystem, CS, CommandPositionTolerance, tol);
newtol := 0.5;
IF k = 1 THEN SSV(CoordinateSystem, CS, CommandPositionTolerance, newtol); END_IF;
GSV(CoordinateSystem, CS, CommandTolerance, tol2);
k := k + 1;
"""
    )
    tr = mp.trace(src, ["tol", "tol2"], scans=3)
    assert tr.at(0.0, "tol") == 0.25
    assert tr.at(0.001, "tol2") == 0.5


def test_unsimulated_attributes_are_u303_not_errors(mp) -> None:
    src = (
        HEAD
        + """  rev, entry, slice : INT;
END_VAR
GSV(ControllerDevice, , ProductRev, rev);
GSV(Controller, , TimeSlice, slice);
GSV(Task, THIS, DateTime, entry);
"""
    )
    prog = mp.tmp / "u.st"
    prog.write_text(src)
    mp.capsys.readouterr()
    main(["check", str(prog), "--format", "json"])
    diags = json.loads(mp.capsys.readouterr().out)
    diags = diags if isinstance(diags, list) else diags["diagnostics"]
    assert [d["code"] for d in diags] == ["U303", "U303", "U303"], diags
    assert "ProductRev cannot be read" in diags[0]["message"]
    assert "TimeSlice cannot be read" in diags[1]["message"]
    # DateTime belongs to WallClockTime, not Task
    assert "not an attribute logixst knows for class Task" in diags[2]["message"]


def test_unsimulated_gsv_leaves_the_destination_unchanged() -> None:
    cat = catalog()
    cls = cat.enum("GSV_ClassName").lookup("ControllerDevice")
    attr = cat.enum("GSV_AttributeName").lookup("ProductRev")
    assert cls is not None and attr is not None
    cell = [7]
    gsv(ExecContext(), True, cls.value, 0, attr.value, Ref(cell, 0, INT))
    assert cell == [7]


def _check(mp, src: str) -> list[dict]:  # type: ignore[no-untyped-def]
    prog = mp.tmp / "c.st"
    prog.write_text(src)
    mp.capsys.readouterr()
    main(["check", str(prog), "--format", "json"])
    diags = json.loads(mp.capsys.readouterr().out)
    return diags if isinstance(diags, list) else diags["diagnostics"]  # type: ignore[no-any-return]


def test_cip_axis_fault_bits_and_motion_status_words_are_read_only_members(mp) -> None:
    # W-P-I/FunctionBlocks Servo_Object (v33) tests each CIP axis fault by name
    # (Axis.MotorOvercurrentFault ... ExternalInputFault) and the words MotionAlarmStatus /
    # MotionFaultStatus; its program reads ConverterOutputStatus. On a healthy simulated
    # axis all of them read 0 (nothing raises a drive fault); CIPAxisFaults is 64 bits wide.
    src = """VAR
  A : AXIS_CIP_DRIVE;
  any : BOOL; words : DINT; all : LINT;
END_VAR
any := A.MotorOvercurrentFault OR A.ConverterACSinglePhaseLossFault OR A.BusPowerBlownFuseFault
  OR A.FeedbackDataLossULFault OR A.SensorFault OR A.ExternalInputFault OR A.ConverterOutputStatus;
words := A.MotionAlarmStatus + A.MotionFaultStatus + A.CIPAxisIOStatusRA;
all := A.CIPAxisFaults;
"""
    tr = mp.trace(src, ["any", "words", "all"], scans=2)
    assert (tr.at(0.0, "any"), tr.at(0.0, "words"), tr.at(0.0, "all")) == (0, 0, 0)
    # they are status: the program cannot write them
    bad = src.replace("all := A.CIPAxisFaults;", "A.MotorOvercurrentFault := 1;")
    assert [d["code"] for d in _check(mp, bad)] == ["E120"]


def test_axis_jerk_limits_by_their_gsv_names_and_drive_attributes_as_u303(mp) -> None:
    # W-P-I/FunctionBlocks PF527_V4 (v33): SSV(Axis, Axis, MaximumAccelerationJerk, r) and
    # GSV of the motor nameplate and gearbox; Servo_Object: SSV(Axis, ..., InhibitAxis, d)
    # and GSV AxisFaultBits / ModuleFaultBits / MotionFaultBits.
    src = """VAR
  X : AXIS_VIRTUAL := (MaximumAccelJerk := 300.0);
  j, jd, r : REAL; f, m, mf, inh, lt : DINT; k : DINT;
END_VAR
GSV(Axis, X, MaximumAccelerationJerk, j);
r := 1250.0;
IF k = 1 THEN SSV(Axis, X, MaximumDecelerationJerk, r); END_IF;
GSV(Axis, X, MaximumDecelerationJerk, jd);
GSV(Axis, X, AxisFaultBits, f);
GSV(Axis, X, ModuleFaultBits, m);
k := k + 1;
"""
    tr = mp.trace(src, ["j", "jd", "X.MaximumDecelJerk", "f", "m"], scans=3)
    # the GSV names read and write the MaximumAccelJerk / MaximumDecelJerk members
    assert tr.at(0.0, "j") == 300.0
    assert tr.at(0.0, "jd") == 0.0 and tr.at(0.001, "jd") == 1250.0
    assert tr.at(0.001, "X.MaximumDecelJerk") == 1250.0
    # AxisFaultBits / ModuleFaultBits are the AxisFault / ModuleFaults words: 0 when healthy
    assert (tr.at(0.0, "f"), tr.at(0.0, "m")) == (0, 0)
    cat = catalog()
    assert cat.system_attribute("Axis", "AxisFaultBits").member == "AxisFault"  # type: ignore[union-attr]
    assert cat.system_attribute("Axis", "ModuleFaultBits").member == "ModuleFaults"  # type: ignore[union-attr]
    # drive attributes the simulator does not model: U303 warnings, not errors
    extra = src.replace(
        "k := k + 1;",
        "GSV(Axis, X, RotaryMotorRatedSpeed, r); GSV(Axis, X, LoadType, lt);\n"
        "GSV(Axis, X, MotionFaultBits, mf); inh := 1; SSV(Axis, X, InhibitAxis, inh);\n"
        "SSV(Axis, X, MaximumFrequency, r); k := k + 1;",
    )
    assert [d["code"] for d in _check(mp, extra)] == ["U303"] * 5
    # a name that is no Axis attribute stays an error
    bad = src.replace("k := k + 1;", "GSV(Axis, X, MotorRatedSpeedy, r); k := k + 1;")
    assert [d["code"] for d in _check(mp, bad)] == ["E108"]
