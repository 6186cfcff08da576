"""Constructs Studio accepted in the exports added to the corpus in session 6 (decision 0160).

Each case is a minimal export written by hand with the shape of the real one (named in the
comment); it must check without an E or S diagnostic and run, giving the value worked out by
hand. Where the rule has an edge, a twin shows the edge still holds.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from interpreter.runtime.loader import load
from interpreter.syntax import nodes as n
from interpreter.syntax.l5x import read_l5x
from interpreter.syntax.st_parser import parse_st
from tests.l5x.cli_run import run

HEAD = """<?xml version="1.0" encoding="UTF-8" standalone="yes"?>
<RSLogix5000Content SchemaRevision="1.0" SoftwareRevision="35.00" TargetName="More" TargetType="Controller">
<Controller Use="Target" Name="More" ProcessorType="1756-L83E" MajorRev="35" MinorRev="11">
<Tags>
<Tag Name="Var" TagType="Base" DataType="REAL"/>
<Tag Name="mask" TagType="Base" DataType="UDINT" Radix="Hex"><Data Format="Decorated">
<DataValue DataType="UDINT" Radix="Hex" Value="16#ffff_0000"/></Data></Tag>
<Tag Name="all" TagType="Base" DataType="ULINT" Radix="Hex"><Data Format="Decorated">
<DataValue DataType="ULINT" Radix="Hex" Value="16#ffff_ffff_ffff_ffff"/></Data></Tag>
<Tag Name="low" TagType="Base" DataType="UDINT"/>
{tags}</Tags>
<Programs>
<Program Name="Main" MainRoutineName="Logic">
<Tags>
<Tag Name="PID" TagType="Base" DataType="PID"/>
<Tag Name="pv" TagType="Base" DataType="REAL"/>
<Tag Name="cv" TagType="Base" DataType="REAL"/>
<Tag Name="ct" TagType="Base" DataType="DINT"/>
<Tag Name="dn" TagType="Base" DataType="DINT"/>
</Tags>
<Routines>
<Routine Name="Logic" Type="ST"><STContent>
{lines}</STContent></Routine>
</Routines>
</Program>
</Programs>
<Tasks>
<Task Name="T" Type="CONTINUOUS" Priority="10" Watchdog="500">
<ScheduledPrograms><ScheduledProgram Name="Main"/></ScheduledPrograms>
</Task>
</Tasks>
</Controller>
</RSLogix5000Content>
"""


def export(tmp_path: Path, *lines: str, tags: str = "") -> Path:
    body = "".join(
        f'<Line Number="{k}"><![CDATA[{line}]]></Line>\n' for k, line in enumerate(lines)
    )
    path = tmp_path / "more.L5X"
    path.write_text(HEAD.format(tags=tags, lines=body))
    return path


def diagnostics(path: Path) -> list[str]:
    return [f"{d.code} {d.message}" for d in load([path]).diagnostics]


# ------------------------------------------------------------ VAR and END_VAR are tag names
def test_a_tag_named_var_in_structured_text(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # JeremyMedders/LogixLibraries Array_R_AOI (v35): a local tag `Var`, `Var := 0.0;`
    path = export(tmp_path, "Var := 1.5;", "Var := Var * 2.0 + var;")
    assert diagnostics(path) == []
    # 1.5 then 1.5 * 2.0 + 1.5 = 4.5
    assert run(path, capsys, "Var") == {"Var": 4.5}


def test_var_still_opens_a_declaration_block_in_a_st_file() -> None:
    routine, diags = parse_st("VAR var_input : DINT; END_VAR var_input := 2;", "v.st")
    assert diags == []
    assert [name for d in routine.decls for name, _ in d.names] == ["var_input"]
    assert len(routine.body) == 1
    # VAR followed by a name on the next line still opens a block
    routine, diags = parse_st("VAR\n  a : DINT;\nEND_VAR\na := 1;", "v.st")
    assert diags == [] and len(routine.decls) == 1 and len(routine.body) == 1


# ------------------------------------------------------------ radix values of unsigned tags
def test_hex_values_of_unsigned_tags_are_their_unsigned_pattern(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # LogixLibraries N_UDINT_AOI (v35): a UDINT parameter HI_MASK of Value="16#ffff_0000"
    path = export(tmp_path, "low := mask AND 16#0001_0000;")
    assert diagnostics(path) == []
    tags = run(path, capsys, "mask", "all", "low")
    # 16#ffff_0000 = 65535 * 65536 = 4294901760; all 64 bits set = 2**64 - 1; bit 16 is set
    assert tags == {"mask": 4294901760, "all": 2**64 - 1, "low": 65536}


def test_a_pattern_wider_than_the_tag_is_still_refused(tmp_path: Path) -> None:
    tag = (
        '<Tag Name="small" TagType="Base" DataType="USINT" Radix="Hex"><Data Format="Decorated">'
        '<DataValue DataType="USINT" Radix="Hex" Value="16#1ff"/></Data></Tag>\n'
    )
    path = export(tmp_path, "low := 1;", tags=tag)
    assert diagnostics(path) == ["E118 16#1ff does not fit a USINT"]


# ------------------------------------------------------------ PID(PID, ...) in ST
def test_pid_called_on_a_tag_named_pid(tmp_path: Path) -> None:
    # LogixLibraries Op_PID_AOI (v35): a local tag `PID` of type PID and
    # `PID(PID, Inp_PV, Inp_Tieback, Inp_CV, 0, Inp_Inhold, Inp_InholdValue);`
    path = export(tmp_path, "PID(PID, pv, 0, cv, 0, 0, 0);")
    assert diagnostics(path) == []


def test_a_pid_tag_of_another_name_is_still_an_instance_called_by_name(tmp_path: Path) -> None:
    # the IEC form (decision 0126) stays for a tag whose name is not the instruction's
    tag = '<Tag Name="loop1" TagType="Base" DataType="PID"/>\n'
    path = export(tmp_path, "loop1(pv, 0, cv, 0, 0, 0);", tags=tag)
    assert [d.split()[0] for d in diagnostics(path)] == ["E130"] * 6


# ------------------------------------------------------------ GSV TimeSynchronize
def test_time_synchronize_clock_type_and_domain_number(tmp_path: Path) -> None:
    # LogixLibraries Sys_PrecisionTime_AOI (v35): GSV(TimeSynchronize, , ClockType, ...)
    path = export(
        tmp_path,
        "GSV(TimeSynchronize, , ClockType, ct);",
        "GSV(TimeSynchronize, , DomainNumber, dn);",
    )
    # known attributes, not simulated: U303, never E108
    assert [d.split()[0] for d in diagnostics(path)] == ["U303", "U303"]


# ------------------------------------------------------------ ProductDefinedTypes, IOTags
SDK_EXPORT = """<?xml version="1.0" encoding="UTF-8" standalone="yes"?>
<RSLogix5000Content SchemaRevision="1.0" SoftwareRevision="32.02" TargetName="Sdk" TargetType="Controller" ContainsContext="true" ExportOptions="References NoRawData L5KData DecoratedData Context ProductDefinedTypes IOTags">
<Controller Use="Target" Name="Sdk" ProcessorType="1756-L83E" MajorRev="32" MinorRev="11">
<DataTypes>
<DataType Name="TIMER" Family="NoFamily" Class="{timer_class}">
<Members>
<Member Name="PRE" DataType="DINT" Dimension="0" Radix="Decimal" Hidden="false"/>
<Member Name="ACC" DataType="DINT" Dimension="0" Radix="Decimal" Hidden="false"/>
</Members>
</DataType>
<DataType Name="AB:ETHERNET_MODULE_DINT_8Bytes:I:0" Family="NoFamily" Class="IO">
<Members>
<Member Name="Data" DataType="DINT" Dimension="2" Radix="Decimal" Hidden="false"/>
</Members>
</DataType>
</DataTypes>
<Modules>
<Module Name="Scale" CatalogNumber="ETHERNET-MODULE" Vendor="1" ProductType="0" ProductCode="0" Major="1" Minor="1" ParentModule="Local" ParentModPortId="2" Inhibited="false" MajorFault="false">
<Communications CommMethod="536870913">
<Connections>
<Connection Name="Exclusive Owner" RPI="50000" Type="Input">
<InputTag ExternalAccess="Read/Write">
<Data Format="Decorated">
<Structure DataType="AB:ETHERNET_MODULE_DINT_8Bytes:I:0">
<ArrayMember Name="Data" DataType="DINT" Dimensions="2" Radix="Decimal">
<Element Index="[0]" Value="12"/><Element Index="[1]" Value="-3"/>
</ArrayMember>
</Structure>
</Data>
</InputTag>
</Connection>
</Connections>
</Communications>
</Module>
</Modules>
<Tags>
<Tag Name="Scale:I" TagType="Base" DataType="AB:ETHERNET_MODULE_DINT_8Bytes:I:0" IO="true">
<Data Format="Decorated">
<Structure DataType="AB:ETHERNET_MODULE_DINT_8Bytes:I:0">
<ArrayMember Name="Data" DataType="DINT" Dimensions="2" Radix="Decimal">
<Element Index="[0]" Value="12"/><Element Index="[1]" Value="-3"/>
</ArrayMember>
</Structure>
</Data>
</Tag>
<Tag Name="t" TagType="Base" DataType="TIMER"/>
<Tag Name="d" TagType="Base" DataType="DINT"/>
</Tags>
<Programs>
<Program Name="Main" MainRoutineName="Logic">
<Routines>
<Routine Name="Logic" Type="ST"><STContent>
<Line Number="0"><![CDATA[t.PRE := 5; d := Scale:I.Data[0] + Scale:I.Data[1];]]></Line>
</STContent></Routine>
</Routines>
</Program>
</Programs>
<Tasks>
<Task Name="T" Type="CONTINUOUS" Priority="10" Watchdog="500">
<ScheduledPrograms><ScheduledProgram Name="Main"/></ScheduledPrograms>
</Task>
</Tasks>
</Controller>
</RSLogix5000Content>
"""


def test_product_defined_types_and_io_tags_of_an_sdk_export(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # tnunnink/LogixConverter Test.L5X (v32, ExportOptions ProductDefinedTypes IOTags): the
    # DataTypes section describes TIMER and the module types, the Tags section repeats the
    # module tags; the built-in TIMER and the module's own tag stand, with no E117
    path = tmp_path / "sdk.L5X"
    path.write_text(SDK_EXPORT.format(timer_class="ProductDefined"))
    assert diagnostics(path) == []
    tags = run(path, capsys, "t", "d")
    # the built-in TIMER (PRE, ACC, EN, TT, DN); d = 12 + -3 = 9
    assert tags == {"t": {"PRE": 5, "ACC": 0, "EN": 0, "TT": 0, "DN": 0}, "d": 9}


def test_a_user_type_named_like_a_built_in_is_still_refused(tmp_path: Path) -> None:
    path = tmp_path / "sdk.L5X"
    path.write_text(SDK_EXPORT.format(timer_class="User"))
    assert "E117 type 'TIMER' is already defined" in diagnostics(path)


# ------------------------------------------------------------ #region, TRUE/FALSE tags
def test_region_lines_and_tags_named_true_and_false(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # W-P-I/FunctionBlocks (v33): `#region Macros / keywords`, then `TRUE:=1; FALSE:=0;` on
    # local BOOL tags TRUE and FALSE, and `#endregion`, indented or not
    tags = (
        '<Tag Name="TRUE" TagType="Base" DataType="BOOL"/>\n'
        '<Tag Name="FALSE" TagType="Base" DataType="BOOL"/>\n'
    )
    path = export(
        tmp_path,
        "#region Macros / keywords",
        "\tTRUE:=1;",
        "\tFALSE:=0;",
        "\t#region nested",
        "\tlow := 3;",
        "\t#endregion",
        "#endregion",
        "IF TRUE AND NOT FALSE THEN Var := 2.5; END_IF;",
        tags=tags,
    )
    assert diagnostics(path) == []
    # TRUE and FALSE hold 1 and 0, the condition holds: Var = 2.5, low = 3
    assert run(path, capsys, "TRUE", "FALSE", "Var", "low") == {
        "TRUE": 1,
        "FALSE": 0,
        "Var": 2.5,
        "low": 3,
    }


def test_true_and_false_read_the_tags_of_those_names(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # as in ladder (decision 0054): where the project declares tags TRUE and FALSE, the words
    # read the tags; here they hold the opposite of the literals, so the condition fails
    tags = (
        '<Tag Name="TRUE" TagType="Base" DataType="BOOL"/>\n'
        '<Tag Name="FALSE" TagType="Base" DataType="BOOL"><Data Format="Decorated">'
        '<DataValue DataType="BOOL" Value="1"/></Data></Tag>\n'
    )
    path = export(tmp_path, "low := 1;", "IF TRUE OR NOT FALSE THEN low := 2; END_IF;", tags=tags)
    assert diagnostics(path) == []
    # TRUE is 0 and FALSE is 1: 0 OR NOT 1 is false, low stays 1
    assert run(path, capsys, "low") == {"low": 1}


def test_a_hash_that_opens_no_region_is_still_refused(tmp_path: Path) -> None:
    path = export(tmp_path, "#regional := 1;")
    assert [d.split()[0] for d in diagnostics(path)][:1] == ["S004"]


# ------------------------------------------------------------ GSV AddOnInstructionDefinition
def test_gsv_of_the_add_on_instruction_definition(tmp_path: Path) -> None:
    # W-P-I ISA88 AOIs (v33): GSV(AddOnInstructionDefinition,THIS,Vendor,Name) in their logic;
    # here the class with an instance name, as a program may use it
    tags = '<Tag Name="edited" TagType="Base" DataType="LINT"/>\n'
    path = export(
        tmp_path, "GSV(AddOnInstructionDefinition, Valve, LastEditDate, edited);", tags=tags
    )
    assert [d.split()[0] for d in diagnostics(path)] == ["U303"]


# ------------------------------------------------------------ a program export's references
PROGRAM_EXPORT = """<?xml version="1.0" encoding="UTF-8" standalone="yes"?>
<RSLogix5000Content SchemaRevision="1.0" SoftwareRevision="33.00" TargetName="Caller" TargetType="Program" ContainsContext="true" ExportOptions="References NoRawData L5KData DecoratedData Context Dependencies ForceProtectedEncoding AllProjDocTrans">
<Controller Use="Context" Name="Plant">
<Programs Use="Context">
<Program Use="Target" Name="Caller" MainRoutineName="Main">
<Tags>
<Tag Name="reset" TagType="Base" DataType="BOOL"/>
<Tag Name="mi" TagType="Base" DataType="MOTION_INSTRUCTION">
<Data Format="Decorated">
<Structure DataType="MOTION_INSTRUCTION">
<DataValueMember Name="FLAGS" DataType="DINT" Radix="Decimal" Value="0"/>
<DataValueMember Name="EN" DataType="BOOL" Value="0"/>
<DataValueMember Name="TrackingMaster" DataType="BOOL" Value="{tracking}"/>
<DataValueMember Name="CalculatedDataAvailable" DataType="BOOL" Value="0"/>
<DataValueMember Name="ERR" DataType="INT" Radix="Decimal" Value="0"/>
</Structure>
</Data>
</Tag>
</Tags>
<Routines>
<Routine Name="Main" Type="RLL">
<RLLContent>
<Rung Number="0" Type="N"><Text><![CDATA[XIC(\\Model.Cmd.Clear)OTE(reset);]]></Text></Rung>
</RLLContent>
</Routine>
</Routines>
</Program>
<Program Use="Context" Name="Model">
<Tags Use="Context">
<Tag Use="Reference" Name="Cmd">
</Tag>
</Tags>
</Program>
</Programs>
</Controller>
</RSLogix5000Content>
"""


def test_a_referenced_tag_of_another_program_is_outside_the_export(tmp_path: Path) -> None:
    # W-P-I EventCaller_Program (v33): the context lists `<Tag Use="Reference" Name=...>` with
    # no DataType for another program's tag the rungs use: no S007; the use names a tag that
    # lives outside the file (E101), as every reference outside a partial export does.
    # MOTION_INSTRUCTION data carries TrackingMaster and CalculatedDataAvailable at 0 (v33):
    # members logixst does not model, dropped at their default.
    path = tmp_path / "caller.L5X"
    path.write_text(PROGRAM_EXPORT.format(tracking="0"))
    assert diagnostics(path) == [
        "E101 undefined tag 'Program:Model.Cmd' (program Caller, routine Main, rung 0)"
    ]


def test_only_an_unmodelled_member_at_its_default_is_dropped(tmp_path: Path) -> None:
    # a value other than the default is kept in the tag's data, for the checker to refuse
    kept = {}
    for tracking in ("0", "1"):
        path = tmp_path / f"caller{tracking}.L5X"
        path.write_text(PROGRAM_EXPORT.format(tracking=tracking))
        project, _ = read_l5x(path.read_bytes(), str(path))
        assert project is not None
        (mi,) = [t for p in project.programs for t in p.tags if t.names[0][0] == "mi"]
        assert isinstance(mi.init, n.StructInit)
        kept[tracking] = [name for name, _, _ in mi.init.members]
    assert kept == {"0": ["FLAGS", "EN", "ERR"], "1": ["FLAGS", "EN", "TrackingMaster", "ERR"]}
