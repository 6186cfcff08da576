"""Operand acceptance as Studio applies it (decision 0054), each with the evidence's shape.

Every case is a minimal export written by hand after a real export that Studio verified
(named in the decision); it must check clean and, where it runs, give the value worked out
by hand. Each has a twin that stays an error, so the rule is not looser than Logix.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from interpreter.runtime.loader import load
from tests.l5x.cli_run import run

HEAD = """<?xml version="1.0" encoding="UTF-8" standalone="yes"?>
<RSLogix5000Content SchemaRevision="1.0" SoftwareRevision="20.04" TargetName="Rules" TargetType="Controller">
<Controller Use="Target" Name="Rules" ProcessorType="1756-L73" MajorRev="20" MinorRev="14">
<Tags>
<Tag Name="n" TagType="Base" DataType="INT"><Data Format="Decorated"><DataValue DataType="INT" Value="3"/></Data></Tag>
<Tag Name="s8" TagType="Base" DataType="SINT"><Data Format="Decorated"><DataValue DataType="SINT" Value="2"/></Data></Tag>
<Tag Name="d" TagType="Base" DataType="DINT"><Data Format="Decorated"><DataValue DataType="DINT" Value="7"/></Data></Tag>
<Tag Name="r" TagType="Base" DataType="REAL"/>
<Tag Name="b" TagType="Base" DataType="BOOL"/>
<Tag Name="src" TagType="Base" DataType="DINT" Dimensions="5"><Data Format="Decorated">
<Array DataType="DINT" Dimensions="5"><Element Index="[0]" Value="1"/><Element Index="[1]" Value="2"/>
<Element Index="[2]" Value="3"/><Element Index="[3]" Value="4"/><Element Index="[4]" Value="5"/></Array></Data></Tag>
<Tag Name="dst" TagType="Base" DataType="DINT" Dimensions="5"/>
<Tag Name="f" TagType="Base" DataType="REAL" Dimensions="5"/>
<Tag Name="txt" TagType="Base" DataType="STRING"/>
<Tag Name="txt2" TagType="Base" DataType="STRING"/>
<Tag Name="ctl" TagType="Base" DataType="CONTROL"/>
{tags}</Tags>
<Programs>
<Program Name="Main" MainRoutineName="Logic">
<Routines>
<Routine Name="Logic" Type="RLL"><RLLContent>
{rungs}</RLLContent></Routine>
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

TRUE_FALSE_TAGS = (
    '<Tag Name="True" TagType="Base" DataType="BOOL"/>\n'
    '<Tag Name="False" TagType="Base" DataType="BOOL">'
    '<Data Format="Decorated"><DataValue DataType="BOOL" Value="1"/></Data></Tag>\n'
)


def export(tmp_path: Path, *rungs: str, tags: str = "") -> Path:
    body = "".join(
        f'<Rung Number="{k}" Type="N"><Text><![CDATA[{r}]]></Text></Rung>\n'
        for k, r in enumerate(rungs)
    )
    path = tmp_path / "rules.L5X"
    path.write_text(HEAD.format(tags=tags, rungs=body))
    return path


def codes(path: Path) -> list[str]:
    return [d.code for d in load([path]).diagnostics]


# ------------------------------------------------------------ integers where numbers are taken
def test_int_and_sint_lengths_for_cop_and_fll(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # ModbusMaster (COP Length an INT), FLEX_HART_Commands (COP, SINT), DTOS_PAD (FLL, SINT)
    path = export(tmp_path, "COP(src[0],dst[0],n);", "FLL(2.5,f[0],s8);")
    assert codes(path) == []
    tags = run(path, capsys, "dst", "f")
    # n = 3 elements copied; s8 = 2 elements filled
    assert tags == {"dst": [1, 2, 3, 0, 0], "f": [2.5, 2.5, 0.0, 0.0, 0.0]}


def test_a_real_length_is_still_refused(tmp_path: Path) -> None:
    assert codes(export(tmp_path, "COP(src[0],dst[0],r);")) == ["E105"]


def test_bool_for_a_number_is_still_refused(tmp_path: Path) -> None:
    assert codes(export(tmp_path, "COP(src[0],dst[0],b);")) == ["E105"]


def test_constant_fsc_condition(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # Plc_emulator (v37): FSC(FileMisc.FAC,?,?,ALL,0). A constant 0 never finds a match, so
    # FSC runs to the end of the 5 elements: DN set, FD clear, POS at LEN = 5.
    path = export(tmp_path, "FSC(ctl,5,0,ALL,0);")
    assert codes(path) == []
    tags = run(path, capsys, "ctl.DN", "ctl.FD", "ctl.POS")
    assert tags == {"ctl.DN": True, "ctl.FD": False, "ctl.POS": 5}


def test_a_computed_integer_is_not_a_condition(tmp_path: Path) -> None:
    assert codes(export(tmp_path, "CMP(d+1)OTE(b);")) == ["E105"]


# ------------------------------------------------------------ immediate DTOS source
def test_immediate_dtos_source(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # SD168700 (machine program): DTOS(97,ASCII_Scratchpad)
    path = export(tmp_path, "DTOS(97,txt);")
    assert codes(path) == []
    assert run(path, capsys, "txt") == {"txt": "97"}


def test_dtos_still_writes_a_string(tmp_path: Path) -> None:
    assert codes(export(tmp_path, "DTOS(97,d);")) == ["E105"]


# ------------------------------------------------------------ MOV of strings
def test_mov_of_a_string_literal_and_a_string_tag(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # Plc_emulator (v37): MOVE('500',ASCIIConversions.STOD_Source); Cooker_1_AutoLogic:
    # MOV(Cooker1_Recipe.Name,Drop_Tub_Current_Recipe), both STRING
    path = export(tmp_path, "MOV('500',txt)MOVE(txt,txt2);")
    assert codes(path) == []
    assert run(path, capsys, "txt", "txt2") == {"txt": "500", "txt2": "500"}


@pytest.mark.parametrize("rung", ["MOV('500',d);", "MOV(d,txt);", "MOV(txt,r);"])
def test_mov_does_not_mix_strings_and_numbers(tmp_path: Path, rung: str) -> None:
    assert codes(export(tmp_path, rung)) == ["E116"]


# ------------------------------------------------------------ TRUE and FALSE as tag names
def test_tags_named_true_and_false(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # Random_AOI_Test (v20): tags True and False, and the rung [OTE(True) ,OTU(False) ]
    path = export(
        tmp_path, "[OTE(True) ,OTU(False) ];", "XIC(True)XIO(False)OTE(b);", tags=TRUE_FALSE_TAGS
    )
    assert codes(path) == []
    # rung 0 writes True := 1 and unlatches False (exported as 1); rung 1 sees both, so b is
    # set; --watch names them as tags too
    assert run(path, capsys, "True", "False", "b") == {"True": True, "False": False, "b": True}


def test_without_such_tags_true_is_not_a_tag(tmp_path: Path) -> None:
    assert codes(export(tmp_path, "OTE(True);")) == ["E106"]


def test_integer_tags_for_mam_position_and_speed(st) -> None:  # noqa: ANN001
    # ST_Motion_Example (Rockwell sample): MAM with DINT tags as Position and Speed. Logix
    # converts them: pos = 10, spd = 5, A = Dc = 100 give T = 10/5 + 5/200 + 5/200 = 2.05 s,
    # so after 2,200 scans of 1 ms the move is complete at 10.0.
    src = """VAR
  X : AXIS_VIRTUAL := (MaximumSpeed := 20.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0);
  c1 : MOTION_INSTRUCTION;
  k : DINT;
  pos : DINT := 10;
  spd : DINT := 5;
END_VAR
IF k = 0 THEN
  MAM(X, c1, absolute, pos, spd, unitspersec, 100.0, unitspersec2, 100.0, unitspersec2,
      trapezoidal, 0.0, 0.0, unitspersec3, disabled, programmed, 0.0, none, 0, 0);
END_IF;
k := k + 1;
"""
    assert json.loads(st.check(src).out) == []
    tags = st.tags(src, "X.CommandPosition", "c1.PC", scans=2200)
    assert tags == {"X.CommandPosition": pytest.approx(10.0, abs=1e-4), "c1.PC": True}
    bad = src.replace("spd : DINT := 5;", "spd : BOOL;")
    assert [d["code"] for d in json.loads(st.check(bad).out)] == ["E105"]


# ------------------------------------------------------------ module references
MODULE_AOI = """<?xml version="1.0" encoding="UTF-8" standalone="yes"?>
<RSLogix5000Content SchemaRevision="1.0" SoftwareRevision="35.01" TargetName="M" TargetType="Controller">
<Controller Use="Target" Name="M" ProcessorType="1756-L83E" MajorRev="35" MinorRev="11">
<AddOnInstructionDefinitions>
<AddOnInstructionDefinition Name="IO_Status" Revision="1.0">
<Parameters>
<Parameter Name="EnableIn" TagType="Base" DataType="BOOL" Usage="Input" Required="false" Visible="false"/>
<Parameter Name="EnableOut" TagType="Base" DataType="BOOL" Usage="Output" Required="false" Visible="false"/>
<Parameter Name="Module_In" TagType="Base" DataType="MODULE" Usage="InOut" Required="true" Visible="true"/>
<Parameter Name="Faulted" TagType="Base" DataType="BOOL" Usage="Output" Required="false" Visible="true"/>
</Parameters>
<Routines><Routine Name="Logic" Type="RLL"><RLLContent>
<Rung Number="0" Type="N"><Text><![CDATA[NOP();]]></Text></Rung>
</RLLContent></Routine></Routines>
</AddOnInstructionDefinition>
</AddOnInstructionDefinitions>
<Tags>
<Tag Name="Rack1" TagType="Base" DataType="IO_Status"/>
<Tag Name="Other" TagType="Base" DataType="IO_Status"/>
<Tag Name="n" TagType="Base" DataType="DINT"/>
</Tags>
<Programs><Program Name="Main" MainRoutineName="Logic"><Routines>
<Routine Name="Logic" Type="RLL"><RLLContent>
<Rung Number="0" Type="N"><Text><![CDATA[{rung}]]></Text></Rung>
</RLLContent></Routine>
</Routines></Program></Programs>
</Controller>
</RSLogix5000Content>
"""


@pytest.mark.parametrize(
    ("rung", "expected"),
    [
        # Master_Main_Program (v35): IO_Module_Status(ENET_ECP100_A_0,ENET_ECP100_A_0,...): the
        # MODULE InOut names the module, here also the name of the instance tag
        ("IO_Status(Rack1,Rack1);", []),
        ("IO_Status(Other,Drive7);", []),  # a module that is no tag at all
        ("IO_Status(Other,n.0);", ["E105"]),  # a bit is not a module
    ],
)
def test_module_inout_takes_a_module_name(tmp_path: Path, rung: str, expected: list[str]) -> None:
    path = tmp_path / "module.L5X"
    path.write_text(MODULE_AOI.format(rung=rung))
    assert codes(path) == expected


# ------------------------------------------------------------ status flags as outputs
def test_status_flag_written_by_a_rung(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # Random_AOI_Test's A_Uniform_RNG (v20): OTU(S:V) clears the overflow flag. Here
    # 2147483647 + 1 overflows a DINT (S:V set, seen by rung 1), rung 2 clears it, rung 3
    # sees it clear and sets bit 0 of dst[0]; ADD stores the wrapped -2147483648.
    path = export(
        tmp_path,
        "ADD(2147483647,1,d);",
        "XIC(S:V)OTE(b);",
        "OTU(S:V);",
        "XIO(S:V)OTL(dst[0].0);",
    )
    assert codes(path) == []
    tags = run(path, capsys, "b", "d", "dst[0]")
    assert tags == {"b": True, "d": -2147483648, "dst[0]": 1}


def test_true_follows_the_tags_when_the_rung_is_read_again(tmp_path: Path) -> None:
    # the language server keeps parsed rungs between reads (ParseMemo): the same rung, at the
    # same place, checked with and then without the tags must give what a fresh read gives
    from interpreter.semantics.checker import check_program
    from interpreter.semantics.project import build_project
    from interpreter.syntax.l5x import ParseMemo, read_l5x

    with_tags = export(tmp_path, "XIC(True)OTE(b);", tags=TRUE_FALSE_TAGS).read_text()
    # the same lines, the tags renamed: the rung keeps its position, so the memo returns it
    without = with_tags.replace('Name="True"', 'Name="Tx"').replace('Name="False"', 'Name="Fx"')
    memo = ParseMemo()
    seen = []
    rungs = []
    for text in (with_tags, without, with_tags):
        project, _ = read_l5x(text.encode(), "rules.L5X", memo)  # rotates the memo itself
        assert project is not None
        rungs.append(project.programs[0].routines[0].rungs[0])
        model, _ = build_project(project)
        seen.append([d.code for d in check_program(model).diags])
    assert rungs[0] is rungs[1] is rungs[2]  # the memo handed back the same rung each time
    # with the tags: clean; without: XIC of the literal TRUE is not a tag (E106)
    assert seen == [[], ["E106"], []]
