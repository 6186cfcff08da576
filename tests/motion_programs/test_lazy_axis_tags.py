"""Axis attributes are written to the tags lazily (decision 0104): the members the program,
a --watch or a --trace reads are there when they are read; the others are not rebuilt.

Motion used (SPEC 9.3, 2 ms coarse update, 1 ms scans): MAJ forward at 10 units/s with
accel 1000 executed in scan 0 starts at the update t = 0.002; it reaches speed after
10 / 1000 = 0.01 s having covered 10^2 / (2 * 1000) = 0.05, so for t >= 0.012
p(t) = 0.05 + 10 (t - 0.012). A scan reads the state of the latest update at or before
its start: at t = 0.1, p = 0.05 + 10 * 0.088 = 0.93 and v = 10 (virtual: actual = command).
"""

from __future__ import annotations

from pathlib import Path

import pytest

from interpreter.runtime.controller import Controller
from interpreter.runtime.loader import load, load_project

JOG = (
    "MAJ(A, c, forward, 10.0, unitspersec, 1000.0, unitspersec2, 1000.0, unitspersec2, "
    "trapezoidal, 0.0, 0.0, unitspersec3, disabled, programmed, 0.0, none);"
)

SRC = f"""VAR
  A : AXIS_VIRTUAL;
  c : MOTION_INSTRUCTION;
  k : DINT;
  pos, vel : REAL;
END_VAR
IF k = 0 THEN {JOG} END_IF;
pos := A.ActualPosition;
GSV(Axis, A, CommandVelocity, vel);
k := k + 1;
"""


def _controller(tmp_path: Path, src: str) -> Controller:
    p = tmp_path / "lazy.st"
    p.write_text(src)
    ctl = Controller(load([p]))
    assert ctl.prescan()
    return ctl


def _run_to(ctl: Controller, t: float) -> None:
    while ctl.scans * ctl.ctx.scan_period_ms < t * 1000.0 + 0.5:
        assert ctl.scan()


def test_members_the_program_reads_are_current(tmp_path: Path) -> None:
    ctl = _controller(tmp_path, SRC)
    pos, vel = ctl.reference("pos")[0], ctl.reference("vel")[0]
    _run_to(ctl, 0.1)  # the scan starting at t = 0.1 has run
    assert pos() == pytest.approx(0.93, abs=1e-5)  # member access in ST
    assert vel() == pytest.approx(10.0, abs=1e-5)  # GSV attribute name


def test_members_nobody_reads_are_not_rebuilt(tmp_path: Path) -> None:
    ctl = _controller(tmp_path, SRC)
    _run_to(ctl, 0.1)
    (slot,) = [t.slot for t in ctl.model.tags.values() if t.name == "A"]
    axis = ctl.T[slot]
    ix = ctl.ctx.motion.groups[0].axes[0].layout.index  # type: ignore[union-attr]
    assert axis[ix["ACTUALPOSITION"]] == pytest.approx(0.93, abs=1e-5)  # read by the program
    assert axis[ix["ACTUALVELOCITY"]] == 0.0  # nobody reads it: still the initial value
    # a watch added now demands it: written at once with the present state (constant speed)
    get = ctl.reference("A.ActualVelocity")[0]
    assert get() == pytest.approx(10.0, abs=1e-5)
    # t = 0.004: accelerating at 1000 units/s^2
    ctl2 = _controller(tmp_path, SRC)
    acc2 = ctl2.reference("A.CommandAcceleration")[0]
    _run_to(ctl2, 0.004)
    assert acc2() == pytest.approx(1000.0)


L5X = """<?xml version="1.0" encoding="UTF-8" standalone="yes"?>
<RSLogix5000Content SchemaRevision="1.0" SoftwareRevision="33.01" TargetName="Cell" TargetType="Controller">
<Controller Use="Target" Name="Cell" ProcessorType="1756-L83E" MajorRev="33" MinorRev="11">
<Tags>
<Tag Name="Group1" TagType="Base" DataType="MOTION_GROUP">
<Data Format="MotionGroup"><MotionGroupParameters CoarseUpdatePeriod="1000"/></Data>
</Tag>
<Tag Name="Ax1" TagType="Base" DataType="AXIS_VIRTUAL"><Data Format="Axis">
<AxisParameters MotionGroup="Group1" MaximumSpeed="100.0" MaximumAcceleration="1000.0"
 MaximumDeceleration="1000.0"/></Data></Tag>
<Tag Name="P" TagType="Alias" AliasFor="Ax1.CommandPosition"/>
</Tags>
<Programs><Program Name="MainProgram" MainRoutineName="Main"><Tags>
<Tag Name="K" TagType="Base" DataType="DINT"/>
<Tag Name="X" TagType="Base" DataType="REAL"/>
<Tag Name="MC" TagType="Base" DataType="MOTION_INSTRUCTION"/>
</Tags><Routines><Routine Name="Main" Type="RLL"><RLLContent>
<Rung Number="0" Type="N"><Text><![CDATA[EQU(K,0)MAM(Ax1,MC,1,10.0,100.0,Units per sec,1000.0,Units per sec2,1000.0,Units per sec2,Trapezoidal,0.0,0.0,Units per sec3,Disabled,Programmed,0.0,None,0,0);]]></Text></Rung>
<Rung Number="1" Type="N"><Text><![CDATA[MOV(P,X);]]></Text></Rung>
<Rung Number="2" Type="N"><Text><![CDATA[ADD(K,1,K);]]></Text></Rung>
</RLLContent></Routine></Routines></Program></Programs>
<Tasks><Task Name="MainTask" Type="CONTINUOUS"><ScheduledPrograms>
<ScheduledProgram Name="MainProgram"/></ScheduledPrograms></Task></Tasks>
</Controller>
</RSLogix5000Content>
"""


def test_alias_of_an_axis_member_is_written(tmp_path: Path) -> None:
    # The program reads Ax1.CommandPosition only through the alias P. An incremental MAM
    # of 10 at 1000 units/s^2 with speed 100 is a triangle: 0.1 s up to 100 units/s
    # (5 units), 0.1 s down (5 units), done 0.2 s after it starts (1 ms updates); by
    # scan 400 X holds 10.
    path = tmp_path / "cell.L5X"
    path.write_text(L5X)
    loaded = load_project(path)
    assert not [d for d in loaded.diagnostics if not d.code.startswith("W")]
    ctl = Controller(loaded)
    assert ctl.prescan()
    x = ctl.reference("Program:MainProgram.X")[0]
    for _ in range(400):
        assert ctl.scan(), ctl.major_fault
    assert x() == pytest.approx(10.0, abs=1e-6)
