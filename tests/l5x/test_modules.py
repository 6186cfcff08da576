"""Module I/O tags from an export's <Modules> section (docs/decisions/0052-module-io-tags.md)."""

from __future__ import annotations

from pathlib import Path

import pytest
from test_project import run  # the same run-and-read-tags helper (tests/l5x is on sys.path)

from interpreter.cli import main
from interpreter.runtime.loader import load
from interpreter.semantics.project import build_project
from interpreter.semantics.types import ArrayType, StructType
from interpreter.syntax.l5x import read_l5x

FIX = Path(__file__).parent / "fixtures"
MODULES = FIX / "module_io.L5X"


def read(path: Path = MODULES):  # type: ignore[no-untyped-def]
    project, diags = read_l5x(path.read_bytes(), str(path))
    assert project is not None and diags == []
    return project


def test_module_tags_are_named_as_studio_names_them() -> None:
    project = read()
    names = [d.names[0][0] for d in project.tags if ":" in d.names[0][0]]
    # Slot modules of the controller's chassis take Local:<slot>; the adapter on Ethernet
    # its own name; the POINT module in slot 1 behind it Rack3:1 with its suffix I1. The
    # controller (no Communications) has none; Rack3_Input (slot 2) has only L5K data.
    assert names == [
        "Local:1:C",
        "Local:1:I",
        "Local:2:I",
        "Local:2:O",
        "Rack3:I",
        "Rack3:O",
        "Rack3:1:I1",
    ]
    assert project.modules == {
        "LOCAL:1": "DigitalIn",
        "LOCAL:2": "AnalogOut",
        "RACK3": "Rack3",
        "RACK3:1": "Rack3_Counter",
        "RACK3:2": "Rack3_Input",
    }


def test_module_types_come_from_the_decorated_structures() -> None:
    model, diags = build_project(read())
    assert diags == []
    t = model.tags["LOCAL:2:I"].type
    assert isinstance(t, StructType) and t.name == "AB:1756_OF4_Float:I:0"
    assert [(m, str(mt)) for m, mt in t.members] == [
        ("ChannelFaults", "INT"),
        ("Ch0Fault", "BOOL"),
        ("Ch1Fault", "BOOL"),
        ("Status", "AB:1756_OF4_Status:I:0"),
        ("Ch", "AB:1756_OF4_Channel:I:0[2]"),
        ("CSTTimestamp", "LINT"),
    ]
    ch = t.members[4][1]
    assert isinstance(ch, ArrayType) and isinstance(ch.elem, StructType)
    assert [m for m, _ in ch.elem.members] == ["Data", "InHold"]
    # the AOI parameter of a module-defined type resolves to the same structure
    assert model.types.get("AB:1756_DI:I:0") is model.tags["LOCAL:1:I"].type


def test_members_are_merged_over_modules_of_one_type(tmp_path: Path) -> None:
    # Two modules show the same type name with different members: the type has both.
    text = MODULES.read_text()
    extra = text.replace(
        '<DataValueMember Name="Counts" DataType="DINT" Radix="Decimal" Value="1234"/>',
        '<DataValueMember Name="Counts" DataType="DINT" Radix="Decimal" Value="1234"/>'
        '<DataValueMember Name="Rate" DataType="REAL" Radix="Float" Value="0.5"/>',
    )
    extra = extra.replace(
        '<Structure DataType="AB:1756_DI:I:0">', '<Structure DataType="AB:1734_VHSC:I:0">', 1
    )
    path = tmp_path / "merged.L5X"
    path.write_text(extra)
    model, _ = build_project(read(path))
    t = model.types.get("AB:1734_VHSC:I:0")
    assert isinstance(t, StructType)
    assert [m for m, _ in t.members] == ["Fault", "Data", "Counts", "Rate"]


def test_project_with_modules_checks_clean(capsys: pytest.CaptureFixture[str]) -> None:
    capsys.readouterr()
    assert main(["check", str(MODULES)]) == 0
    assert capsys.readouterr().out.strip() == "0 error(s), 0 warning(s)"


def test_inputs_read_their_exported_values(capsys: pytest.CaptureFixture[str]) -> None:
    tags = run(
        capsys,
        MODULES,
        1,
        "InWord",
        "Local:2:O.Ch0Data",
        "Echo",
        "Rack3:O.Data[0]",
        "Rack3:O.Data[3]",
        "Counts",
        "Counter.Ones",
        "Lamp",
        "Slot1Bits",
        "Local:1:C.COSOnOffEn",
        "Local:2:I.Status.Ch0HoldInitValue",
    )
    assert tags == {
        "InWord": 40,  # Local:1:I.Data = 2#10_1000 = 32 + 8
        "Local:2:O.Ch0Data": 12.5,  # bit 3 of 40 is set, so Main writes 12.5
        "Echo": 1.75,  # Local:2:I.Ch[1].Data + Local:2:O.Ch1Data = -2.25 + 4.0
        "Rack3:O.Data[0]": 6,  # Rack3:I.Data[1] = 2#101 = 5, plus 1
        "Rack3:O.Data[3]": -128,  # OTL of bit 7 of a SINT (2#1000_0000 as a signed byte)
        "Counts": 1234,  # Rack3:1:I1.Counts
        "Counter.Ones": 2,  # the AOI counts bits 3 and 5 of its InOut Card, both set in 40
        "Lamp": True,  # bit 5 set and Local:2:I.Status.CalFault = 0
        "Slot1Bits": 40,  # an alias for Local:1:I.Data
        "Local:1:C.COSOnOffEn": 0xFFFF,  # config data: 16 ones
        "Local:2:I.Status.Ch0HoldInitValue": True,
    }


def test_set_changes_module_inputs(capsys: pytest.CaptureFixture[str]) -> None:
    tags = run(
        capsys,
        MODULES,
        1,
        "InWord",
        "Local:2:O.Ch0Data",
        "Counter.Ones",
        "Lamp",
        extra=("--set", "Local:1:I.Data=0", "--set", "Local:1:I.Data.5=1"),
    )
    # Data = 0 then bit 5 = 1: Data = 32, bit 3 clear so Ch0Data keeps its exported 0.0
    assert tags == {"InWord": 32, "Local:2:O.Ch0Data": 0.0, "Counter.Ones": 1, "Lamp": True}


def test_watch_shows_module_structures(capsys: pytest.CaptureFixture[str]) -> None:
    tags = run(capsys, MODULES, 1, "Rack3:O", "Local:2:I.Ch")
    assert tags == {
        "Rack3:O": {"Data": [6, 0, 0, -128]},
        "Local:2:I.Ch": [{"Data": 1.5, "InHold": False}, {"Data": -2.25, "InHold": True}],
    }
    capsys.readouterr()
    assert (
        main(
            [
                "run",
                str(MODULES),
                "--scans",
                "1",
                "--watch",
                "Local:2:O.Ch0Data",
                "--watch",
                "Rack3:1:I1.Counts",
            ]
        )
        == 0
    )
    lines = capsys.readouterr().out.splitlines()
    assert lines == ["Local:2:O.Ch0Data  12.5", "Rack3:1:I1.Counts  1234"]


def test_tags_option_brings_module_tags(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # --tags takes controller tags and UDTs; the AOI-typed tag is left out of this copy
    # because controller_scope does not declare add-on instruction types.
    shared = tmp_path / "shared.L5X"
    shared.write_text(
        "".join(
            line
            for line in MODULES.read_text().splitlines(keepends=True)
            if 'DataType="CountOn"' not in line
        )
    )
    st = tmp_path / "io.st"
    st.write_text("VAR Bits : DINT; END_VAR\nBits := Local:1:I.Data AND 16#F;\n")
    tags = run(capsys, st, 1, "Bits", extra=("--tags", str(shared)))
    assert tags == {"Bits": 8}  # 2#10_1000 AND 2#1111


def test_module_tags_without_data_get_one_diagnostic_per_module(tmp_path: Path) -> None:
    # Rack3_Input (Rack3:2) has only L5K data and xPLC28 is not in <Modules> at all: Studio
    # knows both from the module profiles, which the export does not hold. Each module is
    # reported once (U306, decision 0056), however many of its tags and members are used,
    # and nothing cascades at the uses (members, bits, operands).
    text = MODULES.read_text().replace(
        "Counts := Rack3:1:I1.Counts;",
        "Counts := Rack3:2:I.Data + xPLC28:O.Pt08.Data; Counts := Rack3:2:I.Data.3"
        " + xPLC28:I.Pt00.Data + xPLC28:O.Pt08.Data;",
    )
    path = tmp_path / "missing.L5X"
    path.write_text(text)
    found = [(d.code, d.span.line, d.span.col, d.message) for d in load([path]).diagnostics]
    assert found == [
        (
            "U306",
            237,
            20,
            "module I/O tag 'Rack3:2:I': the data of module 'Rack3_Input' is not in the export"
            " (no Decorated data); it is not simulated (program MainProgram, routine Main, line 4)",
        ),
        (
            "U306",
            237,
            37,
            "module I/O tag 'xPLC28:O': its module is not in the export; it is not simulated"
            " (program MainProgram, routine Main, line 4)",
        ),
    ]


def test_uses_of_module_tags_without_data_do_not_execute(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # SPEC 9.32: what uses a tag that is not simulated does not execute. The ST assignment
    # and the IF on xPLC28:I are skipped, so Counts keeps its exported 0 (instead of 1234
    # from Rack3:1:I1); on the rung, XIC(Rack3:2:I.Data.0) passes the rung condition on, so
    # the rung still latches Rack3:O.Data[3].7 (-128 as a signed byte, as in the unchanged run)
    text = (
        MODULES.read_text()
        .replace(
            "Counts := Rack3:1:I1.Counts;",
            "Counts [:=] Rack3:2:I.Data; IF xPLC28:I.Fault THEN Counts := 5; END_IF;",
        )
        .replace("XIC(Rack3:I.Data[1].2)OTL(", "XIC(Rack3:I.Data[1].2)XIC(Rack3:2:I.Data.0)OTL(")
        .replace("OTL(Rack3:O.Data[3].7);", "OTL(Rack3:O.Data[3].7)OTE(xPLC28:O.Pt00.Data);")
    )  # the non-retentive [:=] and the OTE are also left out of the prescan
    path = tmp_path / "skip.L5X"
    path.write_text(text)
    # one U306 per module (Rack3:2 in ST and on the rung, xPLC28), nothing else
    assert [d.code for d in load([path]).diagnostics] == ["U306", "U306"]
    tags = run(capsys, path, 1, "Counts", "Rack3:O.Data[3]", "InWord")
    assert tags == {"Counts": 0, "Rack3:O.Data[3]": -128, "InWord": 40}


MISSING_TYPE = """<?xml version="1.0" encoding="UTF-8" standalone="yes"?>
<RSLogix5000Content SchemaRevision="1.0" SoftwareRevision="34.01" TargetName="T" TargetType="Controller">
<Controller Use="Target" Name="T" ProcessorType="5069-L320ER" MajorRev="34" MinorRev="11">
<DataTypes>
<DataType Name="Station" Family="NoFamily" Class="User"><Members>
<Member Name="Inputs" DataType="AB:5000_DI16:I:0" Dimension="0" Radix="NullType" Hidden="false"/>
<Member Name="Count" DataType="DINT" Dimension="0" Radix="Decimal" Hidden="false"/>
</Members></DataType>
</DataTypes>
<Tags>
<Tag Name="St" TagType="Base" DataType="Station"/>
<Tag Name="Copies" TagType="Base" DataType="AB:5000_DI16:I:0" Dimensions="2"/>
<Tag Name="n" TagType="Base" DataType="DINT"><Data Format="Decorated"><DataValue DataType="DINT" Value="7"/></Data></Tag>
</Tags>
<Programs><Program Name="Main" MainRoutineName="Logic"><Routines>
<Routine Name="Logic" Type="ST"><STContent>
<Line Number="0"><![CDATA[St.Count := St.Inputs.Pt00.Data + Copies[1].Pt03.Data; n := n + 1;]]></Line>
</STContent></Routine>
</Routines></Program></Programs>
<Tasks><Task Name="T" Type="CONTINUOUS" Priority="10" Watchdog="500">
<ScheduledPrograms><ScheduledProgram Name="Main"/></ScheduledPrograms></Task></Tasks>
</Controller>
</RSLogix5000Content>
"""


def test_module_defined_type_missing_is_reported_once(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # AB:5000_DI16:I:0 is used by a UDT member and an array tag, and no module of the file
    # shows its layout: one U306 (at its first declaration), none at the second or the uses
    path = tmp_path / "missing_type.L5X"
    path.write_text(MISSING_TYPE)
    found = [(d.code, d.span.line) for d in load([path]).diagnostics]
    assert found == [("U306", 6)]
    # the assignment that reads them does not execute; the next statement does: n = 7 + 1
    assert run(capsys, path, 1, "St.Count", "n") == {"St.Count": 0, "n": 8}
