"""Verification resolves each name in the scope of the routine that uses it.

The checker caches tag lookups per scope (Checker in semantics/checker.py); this test fails
if a cached resolution leaks from one program (or AOI) into another: the same tag name has a
different type, or does not exist, in each scope below.
"""

from __future__ import annotations

import re
from pathlib import Path

from interpreter.runtime.loader import load

# Controller: X is a DINT, Only a BOOL. Program PA: X is a TIMER, Loc a BOOL. Program PB: X is
# a BOOL. Program PC: no tag of its own, so X is the controller's DINT and Loc is undefined.
# AOI Bump: its local X is a REAL and controller tags are not visible inside it; AOI Bump2:
# its local X is a BOOL.
AOI = """<AddOnInstructionDefinition Name="{name}" Revision="1.0">
<Parameters>
<Parameter Name="EnableIn" TagType="Base" DataType="BOOL" Usage="Input" Required="false" Visible="false"/>
<Parameter Name="EnableOut" TagType="Base" DataType="BOOL" Usage="Output" Required="false" Visible="false"/>
<Parameter Name="Flag" TagType="Base" DataType="BOOL" Usage="Output" Required="false" Visible="true"/>
</Parameters>
<LocalTags>
<LocalTag Name="X" DataType="{local}"/>
</LocalTags>
<Routines>
<Routine Name="Logic" Type="RLL">
<RLLContent>
{rungs}</RLLContent>
</Routine>
</Routines>
</AddOnInstructionDefinition>
"""
RUNGS = [
    '<Rung Number="0" Type="N"><Text><![CDATA[XIC(X)OTE(Flag);]]></Text></Rung>\n',
    '<Rung Number="1" Type="N"><Text><![CDATA[XIC(Only)OTE(Flag);]]></Text></Rung>\n',
]

HEAD = (
    """<?xml version="1.0" encoding="UTF-8" standalone="yes"?>
<RSLogix5000Content SchemaRevision="1.0" SoftwareRevision="33.01" TargetName="Scopes" TargetType="Controller">
<Controller Use="Target" Name="Scopes" ProcessorType="1756-L83E" MajorRev="33" MinorRev="11">
<AddOnInstructionDefinitions>
"""
    + AOI.format(name="Bump", local="REAL", rungs=RUNGS[0] + RUNGS[1])
    + AOI.format(name="Bump2", local="BOOL", rungs=RUNGS[0])
    + """</AddOnInstructionDefinitions>
<Tags>
<Tag Name="X" TagType="Base" DataType="DINT"/>
<Tag Name="Only" TagType="Base" DataType="BOOL"/>
</Tags>
<Programs>
"""
)

PROGRAM = """<Program Name="{name}" MainRoutineName="Main">
<Tags>{tags}</Tags>
<Routines>
<Routine Name="Main" Type="RLL">
<RLLContent>
<Rung Number="0" Type="N"><Text><![CDATA[XIC(X)XIC(Loc)OTE(Only);]]></Text></Rung>
<Rung Number="1" Type="N"><Text><![CDATA[TON(X,?,?);]]></Text></Rung>
</RLLContent>
</Routine>
</Routines>
</Program>
"""

TAIL = """</Programs>
</Controller>
</RSLogix5000Content>
"""

SCOPES = {
    "PA": '<Tag Name="X" TagType="Base" DataType="TIMER"/><Tag Name="Loc" TagType="Base" DataType="BOOL"/>',
    "PB": '<Tag Name="X" TagType="Base" DataType="BOOL"/>',
    "PC": "",
}


def test_same_name_in_several_programs_gets_each_programs_diagnostics(tmp_path: Path) -> None:
    # checked twice over, in both orders, so every scope is also entered after every other one
    order = list(SCOPES.items()) + list(reversed(SCOPES.items()))
    body = "".join(
        PROGRAM.format(name=f"{name}{k}", tags=tags) for k, (name, tags) in enumerate(order)
    )
    path = tmp_path / "scopes.L5X"
    path.write_text(HEAD + body + TAIL)
    loaded = load([path])
    # the name suggestion is beside the point here (it draws on every program's tags)
    found = sorted(
        (d.code, re.sub(r" \(did you mean '\w+'\?\)", "", d.message)) for d in loaded.diagnostics
    )
    expected = []
    for k, (name, _) in enumerate(order):
        where = f" (program {name}{k}, routine Main, rung "
        if name == "PA":  # X is a TIMER: not a bit for XIC, right for TON; Loc is its own BOOL
            expected.append(
                ("E105", "XIC operand DataBit does not accept TIMER (accepts BOOL)" + where + "0)")
            )
        elif name == "PB":  # X is a BOOL: right for XIC, not a timer; Loc is not declared here
            expected.append(("E101", "undefined tag 'Loc'" + where + "0)"))
            expected.append(
                ("E105", "TON operand Timer does not accept BOOL (accepts TIMER)" + where + "1)")
            )
        else:  # X is the controller's DINT: wrong for both; no Loc either
            expected.append(
                ("E105", "XIC operand DataBit does not accept DINT (accepts BOOL)" + where + "0)")
            )
            expected.append(("E101", "undefined tag 'Loc'" + where + "0)"))
            expected.append(
                ("E105", "TON operand Timer does not accept DINT (accepts TIMER)" + where + "1)")
            )
    # inside Bump, X is its REAL local and the controller's Only does not exist (reported once:
    # a definition is checked once, however many programs use its name); Bump2's X is a BOOL
    where = " (add-on instruction Bump, routine Logic, rung "
    expected.append(
        ("E105", "XIC operand DataBit does not accept REAL (accepts BOOL)" + where + "0)")
    )
    expected.append(("E101", "undefined tag 'Only'" + where + "1)"))
    assert found == sorted(expected)
