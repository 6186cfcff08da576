"""The motion part of the catalog is complete: every instruction of the Logix motion
reference (MOTION-RM002), the members real exports read on axes, coordinate systems and
motion groups, and the GSV/SSV object classes real projects use.

The lists below are typed from the reference manuals' tables of contents and from the
members seen in public exports (tests/l5x, /work/l5x-corpus), not generated from the catalog.
"""

from __future__ import annotations

import pytest

from stdlib import catalog

MOTION_INSTRUCTIONS = {
    # motion state
    "MSO", "MSF", "MASD", "MASR", "MDO", "MDF", "MDS", "MAFR",
    # motion move
    "MAS", "MAH", "MAJ", "MAM", "MAG", "MCD", "MRP", "MCCP", "MCSV", "MAPC", "MATC", "MDAC",
    # motion group
    "MGS", "MGSD", "MGSR", "MGSP",
    # motion event
    "MAW", "MDW", "MAR", "MDR", "MAOC", "MDOC",
    # motion configuration
    "MAAT", "MRAT", "MAHD", "MRHD",
    # multi-axis coordinated motion
    "MCS", "MCLM", "MCCM", "MCCD", "MCT", "MCTP", "MCSD", "MCSR", "MDCC", "MCPM", "MCTO",
    "MCTPO",
}  # fmt: skip


@pytest.mark.parametrize("name", sorted(MOTION_INSTRUCTIONS))
def test_motion_instruction_is_in_the_catalog_for_both_languages(name: str) -> None:
    cat = catalog()
    for lang in ("st", "rll"):
        ins = cat.instruction(name, lang)
        assert ins is not None, f"{name} missing for {lang}"
    ins = cat.instruction(name, "st")
    assert ins is not None
    # every motion instruction starts a process tracked by a MOTION_INSTRUCTION structure
    assert any(op.types == ("MOTION_INSTRUCTION",) for op in ins.operands), name
    assert ins.transitional, f"{name}: motion instructions run on the rung's rising edge"


# (instruction, operand names in Studio's order)
SIGNATURES = [
    ("MASD", ["Axis", "MotionControl"]),
    ("MGSP", ["Group", "MotionControl"]),
    ("MAW", ["Axis", "MotionControl", "TriggerCondition", "Position"]),
    ("MCSV", ["MotionControl", "CamProfile", "MasterValue", "SlaveValue", "SlopeValue", "SlopeDerivative"]),
    ("MDCC", ["SlaveSystem", "MasterAxis", "MotionControl", "MasterReference", "NominalMasterVelocity"]),
    ("MCPM", ["CoordinateSystem", "MotionControl", "Path", "Length", "Dynamics", "LockPosition", "LockDirection"]),
    ("MCTO", ["CartesianSystem", "RobotSystem", "MotionControl", "WorkFrame", "ToolFrame"]),
    ("MCCD", ["CoordinateSystem", "MotionControl", "MotionType", "ChangeSpeed", "Speed", "SpeedUnits",
              "ChangeAccel", "AccelRate", "AccelUnits", "ChangeDecel", "DecelRate", "DecelUnits",
              "ChangeAccelJerk", "AccelJerk", "ChangeDecelJerk", "DecelJerk", "JerkUnits", "Scope"]),
]  # fmt: skip


@pytest.mark.parametrize(("name", "operands"), SIGNATURES, ids=[s[0] for s in SIGNATURES])
def test_operand_order_follows_studio(name: str, operands: list[str]) -> None:
    ins = catalog().instruction(name, "st")
    assert ins is not None
    assert [op.name for op in ins.operands] == operands


def test_enumerated_operands_are_immediate_with_documented_numbers() -> None:
    cat = catalog()
    maw = cat.instruction("MAW", "rll")
    assert maw is not None
    trig = maw.operands[2]
    assert trig.format == "immediate" and trig.enum is not None
    values = {v.text: v.value for v in cat.enum(trig.enum).values}
    assert values == {"Forward": 0, "Reverse": 1}


AXIS_MEMBERS = [
    # status words and bits read by the Rockwell sample projects and public exports
    "PositionLockStatus", "ServoActionStatus", "DriveEnableStatus", "ShutdownStatus",
    "AxisHomedStatus", "EnableInputStatus", "AbsoluteReferenceStatus", "Registration1Time",
    "WatchEventArmedStatus", "WatchEventStatus", "WatchPosition", "StrobeActualPosition",
    "StrobeCommandPosition", "CIPAxisState", "CIPAxisFaults", "ModuleFaults",
    "AttributeErrorCode", "PhysicalAxisFault", "GuardFault", "VelocityFeedback",
    "TorqueReference", "DCBusVoltage", "PositionLockTolerance", "InterpolationTime",
]  # fmt: skip


@pytest.mark.parametrize(
    "type_name",
    ["AXIS_CIP_DRIVE", "AXIS_VIRTUAL", "AXIS_SERVO", "AXIS_SERVO_DRIVE", "AXIS_GENERIC",
     "AXIS_GENERIC_DRIVE", "AXIS_CONSUMED"],
)  # fmt: skip
def test_axis_types_have_the_members_projects_read(type_name: str) -> None:
    td = catalog().type(type_name)
    assert td is not None, type_name
    names = {m.name for m in td.members}
    missing = [m for m in AXIS_MEMBERS if m not in names]
    assert missing == []


def test_coordinate_system_and_group_members() -> None:
    cat = catalog()
    cs = cat.type("COORDINATE_SYSTEM")
    assert cs is not None
    members = {m.name: m for m in cs.members}
    # ActualPosition/CommandPosition are per-coordinate arrays (the samples index them)
    assert members["ActualPosition"].type.startswith("REAL[")
    assert members["CommandPosition"].type.startswith("REAL[")
    for bit in ("ShutdownStatus", "ReadyStatus", "MoveStatus", "StoppingStatus"):
        assert bit in members
    mg = cat.type("MOTION_GROUP")
    assert mg is not None
    assert {"CoarseUpdatePeriod", "GroupFault", "GroupSynced"} <= {m.name for m in mg.members}
    for t in ("PATH_DATA", "DYNAMICS_DATA"):  # MCPM's structures
        assert cat.type(t) is not None


GSV_CLASSES = {
    "ControllerDevice", "Controller", "CoordinateSystem", "Axis", "MotionGroup", "Program",
    "Task", "Routine", "Module", "Message", "CST", "WallClockTime", "DF1", "FaultLog",
    "SerialPort", "Redundancy", "TimeSynchronize", "Safety",
}  # fmt: skip

# (class, attribute) pairs seen in public exports
GSV_PAIRS = [
    ("ControllerDevice", "ProductRev"), ("ControllerDevice", "SerialNumber"),
    ("Controller", "ControllerLogTotalEntryCount"), ("Module", "EntryStatus"),
    ("Module", "ForceStatus"), ("Axis", "HomeMode"), ("Axis", "InterpolationTime"),
    ("Axis", "ActualPosition"), ("Axis", "PositionLockStatus"), ("Axis", "MaximumAcceleration"),
    ("CoordinateSystem", "CommandPositionTolerance"), ("Safety", "SafetySignatureExists"),
    ("Task", "LastScanTime"), ("Program", "MajorFaultRecord"), ("FaultLog", "MinorFaultBits"),
    ("WallClockTime", "LocalDateTime"), ("CST", "CurrentValue"), ("MotionGroup", "CoarseUpdatePeriod"),
]  # fmt: skip


def test_gsv_classes_and_attributes_are_catalog_data() -> None:
    cat = catalog()
    classes = {v.text.upper() for v in cat.enum("GSV_ClassName").values}
    assert {c.upper() for c in GSV_CLASSES} <= classes
    attributes = {v.text.upper() for v in cat.enum("GSV_AttributeName").values}
    for cls, attr in GSV_PAIRS:
        assert cat.system_attribute(cls, attr) is not None, (cls, attr)
        assert attr.upper() in attributes


def test_simulated_is_a_subset_of_access() -> None:
    for cls in catalog().system_classes.values():
        for a in cls.attributes:
            assert a.simulated <= a.access, (cls.name, a.name)
            assert a.access, (cls.name, a.name)


def test_system_object_attribute_types_are_known_types() -> None:
    from interpreter.semantics.types import TypeTable

    table = TypeTable()
    for cls in catalog().system_classes.values():
        assert cls.doc, cls.name
        assert cls.instance in ("none", "name", "tag"), cls.name
        for a in cls.attributes:
            base, _, dims = a.type.partition("[")
            assert table.get(base) is not None, (cls.name, a.name, a.type)
            assert not dims or dims.rstrip("]").isdigit(), (cls.name, a.name, a.type)
            assert a.doc, (cls.name, a.name)
