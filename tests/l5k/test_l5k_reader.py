"""Every section kind of an .L5K export: what is read into the project model and how it runs."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest

from interpreter.cli import main
from interpreter.syntax import nodes as n
from interpreter.syntax.l5k import read_l5k

FIX = Path(__file__).parent / "fixtures"
SECTIONS = FIX / "sections.L5K"


def read(path: Path):  # type: ignore[no-untyped-def]
    project, diags = read_l5k(path.read_bytes(), str(path))
    assert project is not None, diags
    return project, diags


def test_sections_are_read_into_the_project_model() -> None:
    p, diags = read(SECTIONS)
    assert diags == []
    assert (p.controller, p.revision) == ("Plant", "35.00")  # the header's `v35.00`
    types = {t.name: t for t in p.types}
    assert list(types) == ["Flags", "Text12"]
    # BIT members become BOOL members; their hidden SINT host is not a member of its own
    flags = [(m.names[0][0], m.type.name, m.type.dims) for m in types["Flags"].members]
    assert flags == [
        ("Ready", "BOOL", []),
        ("Alarm", "BOOL", []),
        ("Level", "REAL", []),
        ("Hold", "TIMER", []),
        ("Log", "DINT", [(0, 3)]),
    ]
    # MODULE blocks give the modules' places: Local, a backplane slot, a network node
    assert p.modules == {"LOCAL": "Local", "LOCAL:3": "DI1", "DRIVE1": "Drive1"}
    (aoi,) = p.aois
    assert aoi.name == "Ramp"
    assert [(a.name, a.usage, a.required) for a in aoi.params] == [
        ("EnableIn", "Input", False),
        ("EnableOut", "Output", False),
        ("Target", "Input", True),
        ("Step", "Input", False),
        ("Value", "Output", True),
    ]
    assert [d.names[0][0] for d in aoi.locals] == ["Steps"]
    assert [(r.name, r.language, len(r.rungs)) for r in aoi.routines] == [("Logic", "rll", 2)]
    assert aoi.routines[0].rungs[0].comment == "Move Value toward Target by Step"
    tags = [d.names[0][0] for d in p.tags]
    assert tags[:4] == ["F1", "Name", "Msg", "Counts"] and "Alm" in tags
    assert [(a.name, a.target) for a in p.aliases] == [("Level", "F1.Level")]
    assert p.coarse_update_us == 4000.0 and p.axis_groups == {"AXIS1": "Group1"}
    progs = {x.name: x for x in p.programs}
    assert list(progs) == ["Main", "Slow", "Off"]
    main_prog = progs["Main"]
    assert main_prog.main == "Logic" and not main_prog.disabled
    assert [(r.name, r.language) for r in main_prog.routines] == [("Logic", "rll"), ("Calc", "st")]
    logic = main_prog.routines[0]
    # 5 rungs written, the one marked D (deleted by pending edits) is left out; numbers
    # count every rung as Studio numbers them
    assert [r.number for r in logic.rungs] == [0, 2, 3, 4]
    assert logic.rungs[0].comment == "Count the scans.\nA second line; with a semicolon"
    assert [(t.name, t.type, t.rate_ms, t.priority, t.inhibited) for t in p.tasks] == [
        ("MainTask", "CONTINUOUS", 10.0, 10, False),
        ("Every5", "PERIODIC", 5.0, 8, False),
        ("Held", "PERIODIC", 1.0, 7, True),
    ]
    assert [t.programs[0][0] for t in p.tasks] == ["Main", "Slow", "Off"]


def test_tag_data_becomes_initial_values() -> None:
    p, _ = read(SECTIONS)
    inits = {d.names[0][0]: d.init for d in p.tags}
    name = inits["Name"]  # a string-family type: [LEN,'text'] is its text
    assert isinstance(name, n.Literal) and name.value == b"Pump1"
    counts = inits["Counts"]
    assert isinstance(counts, n.ArrayInit)
    assert [i.value for i in counts.items if isinstance(i, n.Literal)] == [1, 2, 3]
    alarm = inits["Alm"]  # ALARM_DIGITAL: its configuration is the attribute list
    assert isinstance(alarm, n.StructInit)
    got = {m: i.value for m, _, i in alarm.members if isinstance(i, n.Literal)}
    # numbers, true/false and DT# times are members (DT#1970-01-01-00:00:00.000000Z is
    # 0 microseconds since the epoch, decision 0045); the message keeps its default
    assert got == {
        "Severity": 750,
        "MinDurationPRE": 0,
        "Condition": 1,
        "AckRequired": 0,
        "ProgTime": 0,
    }


def test_sections_project_runs(capsys: pytest.CaptureFixture[str]) -> None:
    watch = [
        "F1.Ready",
        "F1.Alarm",
        "F1.Level",
        "F1.Hold.PRE",
        "F1.Log[0]",
        "F1.Log[3]",
        "Name",
        "Msg",
        "Timers[1].PRE",
        "Forced",
        "Level",
        "Alm.Severity",
        "Axis1.ConversionConstant",
        "Program:Main.Scans",
        "Total",
        "Lamp",
        "Copy",
        "RampOut",
        "R1.Value",
        "Program:Slow.Ticks",
        "Program:Off.Ticks",
    ]
    capsys.readouterr()
    argv = ["run", str(SECTIONS), "--scans", "10", "--json"]
    code = main(argv + [a for w in watch for a in ("--watch", w)])
    out = capsys.readouterr()
    assert code == 0, out.err
    tags: dict[str, Any] = json.loads(out.out)["tags"]
    assert tags == {
        "F1.Ready": True,  # host SINT 9 = 2#1001: bit 0 (Ready) and bit 3 (Alarm) set
        "F1.Alarm": True,
        "F1.Level": 2.5,
        "F1.Hold.PRE": 1000,  # nested TIMER [0,1000,0]
        "F1.Log[0]": 1,  # 16#0000_0001, the array continued on the next line
        "F1.Log[3]": 4,
        "Name": "Pump1",
        "Msg": "hi",
        "Timers[1].PRE": 200,
        "Forced": 5,  # the value before `, TagForceData := ...`
        "Level": 2.5,  # alias of F1.Level
        "Alm.Severity": 750,
        "Axis1.ConversionConstant": 1000.0,
        # ADD(Scans,1,Scans) every scan; the D rung MOV(999,Scans) is deleted, never runs
        "Program:Main.Scans": 10,
        # Calc's original logic adds Counts[0] = 1 a scan; the pending edit (12345) waits
        "Total": 10,
        "Lamp": True,  # XIC(F1.Ready)OTE(Lamp)
        "Copy": 5,  # MOV(Counts[2]) then ADD Counts[1]: 3 + 2, on a rung written on 3 lines
        # Ramp adds Step (DefaultData "0.5") while Value < Target 10.0: 10 calls -> 5.0
        "RampOut": 5.0,
        "R1.Value": 5.0,
        "Program:Slow.Ticks": 2,  # periodic 5 ms over scans at t = 0..9 ms: t = 0 and 5
        "Program:Off.Ticks": 0,  # its task is inhibited
    }


def test_protected_content_is_reported_not_read(capsys: pytest.CaptureFixture[str]) -> None:
    capsys.readouterr()
    path = FIX / "protected_aoi.L5K"
    assert main(["check", str(path), "--format", "json"]) == 0  # U: warnings (SPEC 9.32)
    diags = json.loads(capsys.readouterr().out)
    assert [(d["code"], d["line"], d["column"]) for d in diags] == [
        ("U302", 5, 2),
        ("U302", 23, 3),
    ]
    assert diags[0]["message"] == (
        "add-on instruction 'Sealed' is protected (encoded); its content cannot be read"
    )
    assert (
        diags[1]["message"] == "routine 'Hidden' is protected (encoded); its content cannot be read"
    )


def test_positions_and_context_point_into_the_l5k_file(
    capsys: pytest.CaptureFixture[str],
) -> None:
    capsys.readouterr()
    path = FIX / "st_errors.L5K"
    assert main(["check", str(path), "--format", "json"]) == 1
    diags = json.loads(capsys.readouterr().out)
    # Line 13 is `\t\t\t'  Missing := 2;`: the ST text starts after the quote in column 5,
    # two spaces later Missing spans columns 7..13.
    e101 = next(d for d in diags if d["code"] == "E101")
    assert (e101["line"], e101["column"], e101["endColumn"]) == (13, 7, 14)
    assert e101["message"].endswith("(program Line1, routine Main, line 1)")
    # Line 14 `\t\t\t'Count := (Count + ;`: the ';' is character 19 of the text -> column 23
    s001 = next(d for d in diags if d["code"] == "S001")
    assert (s001["line"], s001["column"]) == (14, 23)
    assert s001["message"].endswith("(program Line1, routine Main, line 2)")


def test_rung_written_on_several_lines_keeps_file_positions(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    path = tmp_path / "wrapped.L5K"
    path.write_text(
        "IE_VER := 2.20;\n"
        "CONTROLLER C\n"
        "\tTAG\n"
        "\t\tA : DINT := 0;\n"
        "\tEND_TAG\n"
        '\tPROGRAM P (MAIN := "R")\n'
        "\t\tROUTINE R\n"
        "\t\t\tN: MOV(1,A)\n"
        "\t\t\t   ADD(A,Nope,A);\n"
        "\t\tEND_ROUTINE\n"
        "\tEND_PROGRAM\n"
        "\tTASK T (Type := CONTINUOUS)\n"
        "\t\tP;\n"
        "\tEND_TASK\n"
        "END_CONTROLLER\n"
    )
    capsys.readouterr()
    assert main(["check", str(path), "--format", "json"]) == 1
    (d,) = json.loads(capsys.readouterr().out)
    # `\t\t\t   ADD(A,Nope,A);`: 3 tabs and 3 spaces, ADD( at columns 7..10, A, -> Nope at 13
    assert (d["code"], d["line"], d["column"], d["endColumn"]) == ("E101", 9, 13, 17)
    assert d["message"] == "undefined tag 'Nope' (program P, routine R, rung 0)"
