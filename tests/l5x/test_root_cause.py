"""One root cause, one diagnostic (decision 0054).

A tag whose declared type is unknown is reported once, where it is declared; the tag still
exists, and its uses (members, elements, bits, operands, block calls) are not reported
again. The same holds for a UDT member or an AOI parameter of an unknown type, and for the
operands of an instruction the checker does not know. Each test has a clean twin: the same
project with the type (or instruction) known checks without a diagnostic, so the uses below
are valid Logix once the type exists.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from interpreter.cli import main
from interpreter.runtime.loader import load

HEAD = """<?xml version="1.0" encoding="UTF-8" standalone="yes"?>
<RSLogix5000Content SchemaRevision="1.0" SoftwareRevision="33.01" TargetName="Root" TargetType="Controller">
<Controller Use="Target" Name="Root" ProcessorType="1756-L83E" MajorRev="33" MinorRev="11">
<DataTypes>
<DataType Name="Holder" Family="NoFamily" Class="User"><Members>
<Member Name="Inner" DataType="{inner}" Dimension="0" Radix="NullType" Hidden="false"/>
<Member Name="Count" DataType="DINT" Dimension="0" Radix="Decimal" Hidden="false"/>
</Members></DataType>
{extra_type}</DataTypes>
<AddOnInstructionDefinitions>
<AddOnInstructionDefinition Name="UsesIt" Revision="1.0">
<Parameters>
<Parameter Name="EnableIn" TagType="Base" DataType="BOOL" Usage="Input" Required="false" Visible="false"/>
<Parameter Name="EnableOut" TagType="Base" DataType="BOOL" Usage="Output" Required="false" Visible="false"/>
<Parameter Name="Thing" TagType="Base" DataType="{param}" Usage="InOut" Required="true" Visible="true"/>
<Parameter Name="Out" TagType="Base" DataType="DINT" Usage="Output" Required="true" Visible="true"/>
</Parameters>
<Routines>
<Routine Name="Logic" Type="ST"><STContent>
<Line Number="0"><![CDATA[Out := Thing.Level + Thing.Bits.3;]]></Line>
</STContent></Routine>
</Routines>
</AddOnInstructionDefinition>
</AddOnInstructionDefinitions>
<Tags>
<Tag Name="Box" TagType="Base" DataType="{tag}" Dimensions="4"/>
<Tag Name="One" TagType="Base" DataType="{tag}"/>
<Tag Name="Hold" TagType="Base" DataType="Holder"/>
<Tag Name="Call" TagType="Base" DataType="UsesIt"/>
<Tag Name="n" TagType="Base" DataType="DINT"/>
<Tag Name="r" TagType="Base" DataType="REAL"/>
<Tag Name="b" TagType="Base" DataType="BOOL"/>
</Tags>
<Programs>
<Program Name="Main" MainRoutineName="Logic">
<Routines>
<Routine Name="Logic" Type="ST"><STContent>
<Line Number="0"><![CDATA[n := Box[2].Level + One.Level;]]></Line>
<Line Number="1"><![CDATA[b := One.Bits.3 AND Box[n].Bits.[n];]]></Line>
<Line Number="2"><![CDATA[r := Hold.Inner.Level * 2.0; Hold.Count := Hold.Inner.Bits;]]></Line>
<Line Number="3"><![CDATA[IF b THEN n := One.Level; COP(Box[0], One, 1); END_IF;]]></Line>
<Line Number="4"><![CDATA[UsesIt(Call, One, n); UsesIt(Call, Hold.Inner, n);]]></Line>
</STContent></Routine>
<Routine Name="Rungs" Type="RLL"><RLLContent>
<Rung Number="0" Type="N"><Text><![CDATA[XIC(One.Bits.3)ADD(One.Level,Box[1].Level,n)OTE(b);]]></Text></Rung>
<Rung Number="1" Type="N"><Text><![CDATA[{ins}(One,Once,All,n)OTE(b);]]></Text></Rung>
</RLLContent></Routine>
</Routines>
</Program>
</Programs>
</Controller>
</RSLogix5000Content>
"""

# The known twin of the unknown type: the members the code above uses.
KNOWN = """<DataType Name="Gauge" Family="NoFamily" Class="User"><Members>
<Member Name="Level" DataType="DINT" Dimension="0" Radix="Decimal" Hidden="false"/>
<Member Name="Bits" DataType="DINT" Dimension="0" Radix="Decimal" Hidden="false"/>
</Members></DataType>
"""


def check(tmp_path: Path, **fill: str) -> list[tuple[str, int, str]]:
    values = {"inner": "Gauge", "param": "Gauge", "tag": "Gauge", "extra_type": KNOWN}
    values["ins"] = "XIO"  # replaced below where the test wants an unknown instruction
    values.update(fill)
    text = HEAD.format(**values)
    if values["ins"] == "XIO":  # the twin's rung: a known instruction, valid operands
        text = text.replace("XIO(One,Once,All,n)", "XIO(b)")
    path = tmp_path / "root.L5X"
    path.write_text(text)
    return [(d.code, d.span.line, d.message) for d in load([path]).diagnostics]


def test_clean_twin(tmp_path: Path) -> None:
    assert check(tmp_path) == []


def test_unknown_tag_type_is_reported_once_per_declaration(tmp_path: Path) -> None:
    found = check(tmp_path, tag="Gadget")
    # Box (line 30) and One (line 31) only: no E101/E102/E105/E110/E121 at the 14 uses
    assert [(c, line) for c, line, _ in found] == [("E119", 30), ("E119", 31)]
    assert found[0][2] == "unknown data type 'GADGET'"


def test_unknown_member_type_is_reported_once(tmp_path: Path) -> None:
    found = check(tmp_path, inner="Widget")
    assert [(c, line) for c, line, _ in found] == [("E119", 6)]


def test_unknown_parameter_type_is_reported_once(tmp_path: Path) -> None:
    # the parameter still exists: the calls keep their operand count, the Logic routine its
    # names, and any argument is accepted for it
    found = check(tmp_path, param="Widget")
    assert [(c, line) for c, line, _ in found] == [("E119", 19)]


def test_operands_of_an_unknown_instruction_are_not_reported(tmp_path: Path) -> None:
    # Once and All may be enumeration values of the unknown instruction: no E101/E108
    found = check(tmp_path, ins="FROB")
    assert [(c, line) for c, line, _ in found] == [("E103", 50)]


def test_undefined_tag_in_an_unknown_instruction_is_still_reported_inside_members(
    tmp_path: Path,
) -> None:
    # a member path is always a tag, whatever the instruction: its root is checked
    found = check(tmp_path, ins="FROB")
    assert all(code != "E101" for code, _, _ in found)
    path = tmp_path / "member.L5X"
    text = HEAD.format(inner="Gauge", param="Gauge", tag="Gauge", extra_type=KNOWN, ins="FROB")
    path.write_text(text.replace("FROB(One,Once,All,n)", "FROB(Nowhere.Level,Once)"))
    codes = [d.code for d in load([path]).diagnostics]
    assert codes == ["E103", "E101"]


ALIASES = """<?xml version="1.0" encoding="UTF-8" standalone="yes"?>
<RSLogix5000Content SchemaRevision="1.0" SoftwareRevision="33.01" TargetName="A" TargetType="Controller">
<Controller Use="Target" Name="A" ProcessorType="1756-L83E" MajorRev="33" MinorRev="11">
<Tags>
<Tag Name="Word" TagType="Base" DataType="DINT"/>
<Tag Name="n" TagType="Base" DataType="DINT"/>
<Tag Name="Start" TagType="Alias" AliasFor="{start}"/>
<Tag Name="Lost" TagType="Alias" AliasFor="{lost}"/>
</Tags>
<Programs><Program Name="Main" MainRoutineName="Logic"><Routines>
<Routine Name="Logic" Type="RLL"><RLLContent>
<Rung Number="0" Type="N"><Text><![CDATA[XIC(Start)XIO(Lost)ADD(n,1,n);]]></Text></Rung>
<Rung Number="1" Type="N"><Text><![CDATA[XIC(Start)OTE(Lost);]]></Text></Rung>
<Rung Number="2" Type="N"><Text><![CDATA[XIC(Lost)OTL(Start);]]></Text></Rung>
</RLLContent></Routine>
</Routines></Program></Programs>
<Tasks><Task Name="T" Type="CONTINUOUS" Priority="10" Watchdog="500">
<ScheduledPrograms><ScheduledProgram Name="Main"/></ScheduledPrograms></Task></Tasks>
</Controller>
</RSLogix5000Content>
"""


def test_an_alias_without_a_base_is_reported_once(tmp_path: Path) -> None:
    # Start is a bit of Word (the clean twin); Lost names a tag that does not exist: one E101
    # at the alias, none at its three uses
    path = tmp_path / "alias.L5X"
    path.write_text(ALIASES.format(start="Word.0", lost="Word.1"))
    assert [d.code for d in load([path]).diagnostics] == []
    path.write_text(ALIASES.format(start="Word.0", lost="Nowhere.1"))
    found = [(d.code, d.span.line) for d in load([path]).diagnostics]
    assert found == [("E101", 8)]


def test_an_alias_of_missing_module_data_runs_without_its_uses(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # Lost aliases a module input the export does not describe: one U305 at the alias; the
    # instructions using it do not execute and pass the rung condition on. Rung 0: Start
    # (Word.0) is 0, so ADD does not run and n stays 0; rung 2: XIC(Lost) passes the true
    # rung on to OTL(Start), so Word.0 is set: Word = 1.
    path = tmp_path / "module_alias.L5X"
    path.write_text(ALIASES.format(start="Word.0", lost="Local:3:I.Data.4"))
    found = [(d.code, d.span.line) for d in load([path]).diagnostics]
    assert found == [("U305", 8)]
    assert run_tags(capsys, path, "n", "Word") == {"n": 0, "Word": 1}


def run_tags(capsys: pytest.CaptureFixture[str], path: Path, *watch: str) -> dict[str, object]:
    argv = ["run", str(path), "--scans", "1", "--json"]
    for w in watch:
        argv += ["--watch", w]
    capsys.readouterr()
    code = main(argv)
    out = capsys.readouterr().out
    assert code == 0, out
    return json.loads(out)["tags"]  # type: ignore[no-any-return]
