"""Add-On Instruction instances keep their own scan-to-scan state (decision 0024).

A transitional ladder instruction (all motion instructions) inside an AOI's ladder Logic
routine remembers the rung it saw last; in Logix that memory belongs to the instance's
backing tag, so two instances called in the same scan with different rungs are independent.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from interpreter.instructions import registry
from interpreter.runtime.controller import Controller, WatchError, to_json_value
from interpreter.runtime.loader import load_project

HEAD = """<?xml version="1.0" encoding="UTF-8" standalone="yes"?>
<RSLogix5000Content SchemaRevision="1.0" SoftwareRevision="33.01" TargetName="Cell" TargetType="Controller">
<Controller Use="Target" Name="Cell" ProcessorType="1756-L83E" MajorRev="33" MinorRev="11">
"""


def rung(number: int, text: str) -> str:
    return f'<Rung Number="{number}" Type="N"><Text><![CDATA[{text}]]></Text></Rung>\n'


def project(
    logic: list[str], main: list[str], program_tags: str, ctl_tags: str = "", params: str = ""
) -> str:
    """One AOI `Mover` (Input Go, InOut Ax, local MOTION_INSTRUCTION MC) with a ladder Logic
    routine, and a ladder Main routine in MainProgram."""
    return (
        HEAD
        + f"""<AddOnInstructionDefinitions>
<AddOnInstructionDefinition Name="Mover" Revision="1.0">
<Parameters>
<Parameter Name="EnableIn" TagType="Base" DataType="BOOL" Usage="Input" Required="false" Visible="false"/>
<Parameter Name="EnableOut" TagType="Base" DataType="BOOL" Usage="Output" Required="false" Visible="false"/>
<Parameter Name="Go" TagType="Base" DataType="BOOL" Usage="Input" Required="true" Visible="true"/>
<Parameter Name="Ax" TagType="Base" DataType="AXIS_VIRTUAL" Usage="InOut" Required="true" Visible="true"/>
{params}</Parameters>
<LocalTags>
<LocalTag Name="MC" DataType="MOTION_INSTRUCTION"/>
</LocalTags>
<Routines>
<Routine Name="Logic" Type="RLL"><RLLContent>
{"".join(rung(i, t) for i, t in enumerate(logic))}</RLLContent></Routine>
</Routines>
</AddOnInstructionDefinition>
</AddOnInstructionDefinitions>
<Tags>
<Tag Name="Group1" TagType="Base" DataType="MOTION_GROUP">
<Data Format="MotionGroup"><MotionGroupParameters CoarseUpdatePeriod="1000"/></Data>
</Tag>
{ctl_tags}</Tags>
<Programs>
<Program Name="MainProgram" MainRoutineName="Main">
<Tags>
{program_tags}</Tags>
<Routines>
<Routine Name="Main" Type="RLL"><RLLContent>
{"".join(rung(i, t) for i, t in enumerate(main))}</RLLContent></Routine>
</Routines>
</Program>
</Programs>
<Tasks>
<Task Name="MainTask" Type="CONTINUOUS"><ScheduledPrograms><ScheduledProgram Name="MainProgram"/></ScheduledPrograms></Task>
</Tasks>
</Controller>
</RSLogix5000Content>
"""
    )


def axis(name: str) -> str:
    return (
        f'<Tag Name="{name}" TagType="Base" DataType="AXIS_VIRTUAL"><Data Format="Axis">'
        '<AxisParameters MotionGroup="Group1" MaximumSpeed="100.0" MaximumAcceleration="1000.0" '
        'MaximumDeceleration="1000.0"/></Data></Tag>\n'
    )


def tag(name: str, dtype: str) -> str:
    return f'<Tag Name="{name}" TagType="Base" DataType="{dtype}"/>\n'


AXES = axis("Ax1") + axis("Ax2")
INSTANCES = tag("M1", "Mover") + tag("M2", "Mover") + tag("GoA", "BOOL") + tag("GoB", "BOOL")
MAIN = ["Mover(M1,GoA,Ax1);", "Mover(M2,GoB,Ax2);"]


def controller(tmp_path: Path, text: str) -> Controller:
    path = tmp_path / "cell.L5X"
    path.write_text(text)
    loaded = load_project(path)
    errors = [d for d in loaded.diagnostics if not d.code.startswith("W")]
    assert not errors, errors
    ctl = Controller(loaded)
    assert ctl.prescan(), ctl.major_fault
    return ctl


def test_transitional_edge_is_per_instance(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """The transitional-call contract (HELPERS.md) holds for each instance on its own."""
    calls: list[tuple[str, bool]] = []
    registry.load_all()  # the real modules register first; this stand-in then wins
    ctl_ref: list[Controller] = []

    def mso(ctx: object, rung: bool, ax: list, mc: list) -> None:
        which = "A" if ax is ctl_ref[0].reference("Ax1")[0]() else "B"
        calls.append((which, rung))

    monkeypatch.setitem(registry.IMPLEMENTATIONS, "MSO@rll", mso)
    ctl = controller(tmp_path, project(["XIC(Go)MSO(Ax,MC);"], MAIN, INSTANCES, AXES))
    ctl_ref.append(ctl)
    go_a = [1, 1, 1, 0, 1]
    go_b = [0, 0, 1, 1, 0]
    for a, b in zip(go_a, go_b, strict=True):
        ctl.reference("Program:MainProgram.GoA")[2](a)
        ctl.reference("Program:MainProgram.GoB")[2](b)
        assert ctl.scan(), ctl.major_fault
    # Worked per scan (A is called before B; prescan cleared both edges):
    #   scan 0: A rises -> (A, True);  B false -> (B, False)
    #   scan 1: A stays true -> no call; B false -> (B, False)
    #   scan 2: A stays true -> no call; B rises -> (B, True)
    #   scan 3: A false -> (A, False); B stays true -> no call
    #   scan 4: A rises again -> (A, True); B false -> (B, False)
    # One edge shared by both instances would have let A "rise" again in scans 1 and 2,
    # because B's false rung cleared the bit in between.
    assert calls == [
        ("A", True),
        ("B", False),
        ("B", False),
        ("B", True),
        ("A", False),
        ("A", True),
        ("B", False),
    ]


def test_two_instances_move_their_own_axes(tmp_path: Path) -> None:
    """Real MAM: an incremental move of 10 runs once per rising edge of each instance's Go."""
    logic = [
        "XIC(Go)MAM(Ax,MC,1,10.0,100.0,Units per sec,1000.0,Units per sec2,1000.0,Units per sec2,"
        "Trapezoidal,0.0,0.0,Units per sec3,Disabled,Programmed,0.0,None,0,0);"
    ]
    # GoB rises at scan 50 (K counts scans from 0; GoB = K >= 50); GoA is true from the start.
    main = ["OTL(GoA);", "GEQ(K,50)OTE(GoB);", *MAIN, "ADD(K,1,K);"]
    ctl = controller(tmp_path, project(logic, main, INSTANCES + tag("K", "DINT"), AXES))
    for _ in range(400):
        assert ctl.scan(), ctl.major_fault
    # Each axis makes one move of 10 units: a triangle at 1000 u/s2 reaches exactly 100 u/s
    # after 0.1 s and 5 units, then brakes for 0.1 s and 5 units: 0.2 s in all, over by
    # scan ~250 for Ax2, which starts at scan 50. Executing MAM again while Go stays true (a
    # shared edge cleared by the other instance's false rung) would keep adding 10-unit moves.
    assert ctl.reference("Ax1.CommandPosition")[0]() == pytest.approx(10.0, abs=1e-6)
    assert ctl.reference("Ax2.CommandPosition")[0]() == pytest.approx(10.0, abs=1e-6)


def test_edge_members_are_hidden(tmp_path: Path) -> None:
    ctl = controller(tmp_path, project(["XIC(Go)MSO(Ax,MC);"], MAIN, INSTANCES, AXES))
    getter, t, _ = ctl.reference("Program:MainProgram.M1")
    assert set(to_json_value(getter(), t)) == {"EnableIn", "EnableOut", "Go"}  # type: ignore[arg-type]
    with pytest.raises(WatchError):
        ctl.reference("Program:MainProgram.M1.__Edge0")


def test_ladder_caller_prescans_the_aoi_logic(tmp_path: Path) -> None:
    """Prescan of a ladder rung calling an AOI prescans the AOI's Logic routine, as an ST call
    does: its OTE clears the instance's output Q, exported as 1."""
    q = '<Parameter Name="Q" TagType="Base" DataType="BOOL" Usage="Output" Required="false" Visible="true"/>\n'
    m1 = (
        '<Tag Name="M1" TagType="Base" DataType="Mover"><Data Format="Decorated"><Structure DataType="Mover">'
        '<DataValueMember Name="Q" DataType="BOOL" Value="1"/></Structure></Data></Tag>\n'
    )
    ctl = controller(
        tmp_path, project(["XIC(Go)OTE(Q);"], MAIN[:1], m1 + tag("GoA", "BOOL"), AXES, q)
    )
    assert ctl.reference("Program:MainProgram.M1.Q")[0]() == 0
