"""Alias tags reach their base tag's storage (decision 0044; fixtures aliases*.L5X).

Every expected value is worked by hand from the fixture's data and logic in the comments.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest

from interpreter.cli import main

FIX = Path(__file__).parent / "fixtures"
ALIASES = FIX / "aliases.L5X"
BROKEN = FIX / "aliases_broken.L5X"


def run(
    capsys: pytest.CaptureFixture[str], path: Path, scans: int, *watch: str, extra: tuple = ()
) -> dict[str, Any]:
    argv = ["run", str(path), "--scans", str(scans), "--json", *extra]
    for w in watch:
        argv += ["--watch", w]
    capsys.readouterr()
    code = main(argv)
    out = capsys.readouterr()
    assert code == 0, (code, out.err, out.out)
    return json.loads(out.out)["tags"]  # type: ignore[no-any-return]


def check(capsys: pytest.CaptureFixture[str], path: Path) -> tuple[int, list[dict[str, Any]]]:
    capsys.readouterr()
    code = main(["check", str(path), "--format", "json"])
    out = capsys.readouterr().out
    return code, json.loads(out)


def test_every_kind_of_alias_checks_clean(capsys: pytest.CaptureFixture[str]) -> None:
    code, diags = check(capsys, ALIASES)
    assert diags == []
    assert code == 0


def test_reads_and_writes_through_aliases_reach_the_base(
    capsys: pytest.CaptureFixture[str],
) -> None:
    alias_and_base = [
        ("Cmd2", "M1.Cmd"),  # Cmd2 -> Drive.Cmd -> M1.Cmd (declared before Drive and M1)
        ("MotorCmd", "M1.Cmd"),
        ("Drive.Cmd", "M1.Cmd"),
        ("Drive.Speed", "M1.Speed"),
        ("Program:Main.PCount", "Program:Main.Count"),  # program alias of a program tag
        ("Program:Main.PWord", "Word"),  # program alias of a controller tag
        ("Program:Main.PRun", "RunBit"),  # program alias of a controller alias
        ("InData", "Local:1:I.Data"),  # module I/O word
        ("FlagBit", "M1.Flags[2].1"),
        ("Cmd2Bit", "M1.Cmd.4"),
        ("StartPB", "Local:1:I.Data.3"),
        ("Lamp", "Local:2:O.Data.0"),
    ]
    watch = [w for pair in alias_and_base for w in pair]
    extra = ("Mirror", "Word", "Local:2:O.Data", "Sum", "RunBit", "M1.Flags[2]")
    tags = run(capsys, ALIASES, 3, *watch, *extra)
    for alias, base in alias_and_base:
        assert tags[alias] == tags[base], (alias, base)
    # M1.Cmd starts at 13, `Cmd2 := Cmd2 + 1` each scan: 16 after 3 scans
    assert tags["M1.Cmd"] == 16
    # bit 4 of 16 (2#1_0000) is set; Mirror copied Cmd2Bit in the same scan
    assert tags["Cmd2Bit"] is True and tags["Mirror"] is True
    # `Drive.Speed := Drive.Speed * 2.0` from 1.5: 1.5 * 2^3 = 12.0
    assert tags["M1.Speed"] == 12.0
    # Word = 4 has bit 2 set, so RunBit (Word.2) and PRun are true and Count counts every scan
    assert tags["RunBit"] is True and tags["Program:Main.Count"] == 3
    # `PWord.0 := TRUE` sets bit 0 of Word: 4 + 1 = 5
    assert tags["Word"] == 5
    # Local:1:I.Data = 2#1000 has bit 3 set: StartPB is true and Lamp sets Local:2:O.Data.0
    assert tags["InData"] == 8 and tags["StartPB"] is True
    assert tags["Local:2:O.Data"] == 1 and tags["Lamp"] is True
    # `FlagBit := TRUE` sets bit 1 of M1.Flags[2]: 4 + 2 = 6
    assert tags["M1.Flags[2]"] == 6 and tags["FlagBit"] is True
    # ladder: XIC(StartPB) XIC(RunBit) ADD(MotorCmd, 100, Sum) after the ST of scan 3: 16 + 100
    assert tags["Sum"] == 116


def test_alias_parameters_of_an_add_on_instruction(capsys: pytest.CaptureFixture[str]) -> None:
    # Fill: IF Step (alias of Cfg.Cmd) = 0 THEN Step := 10; Level (alias of Acc) += Cfg.Cmd;
    # Full (alias of Status.0) := Level >= 20; Out := Status. Ready is Flags.2, Flags = 4.
    watch = ("Tank.Level", "Tank.Full", "Tank.Step", "Tank.Out", "Tank.Ready")
    tags = run(capsys, ALIASES, 0, *watch)
    # before any scan: the local defaults, seen through the aliases (4 = 2#100: bit 2 set)
    assert tags == {
        "Tank.Level": 0,
        "Tank.Full": False,
        "Tank.Step": 0,
        "Tank.Out": 0,
        "Tank.Ready": True,
    }
    tags = run(capsys, ALIASES, 1, *watch)
    # Step was 0, so 10; Level = 0 + 10 = 10 < 20: Full and Status stay 0
    assert tags == {
        "Tank.Level": 10,
        "Tank.Full": False,
        "Tank.Step": 10,
        "Tank.Out": 0,
        "Tank.Ready": True,
    }
    tags = run(capsys, ALIASES, 2, *watch)
    # Level = 20 >= 20 sets Full, bit 0 of Status: Out = 1
    assert tags == {
        "Tank.Level": 20,
        "Tank.Full": True,
        "Tank.Step": 10,
        "Tank.Out": 1,
        "Tank.Ready": True,
    }


def test_an_alias_parameter_set_from_outside_reaches_the_local_tag(
    capsys: pytest.CaptureFixture[str],
) -> None:
    # --set Tank.Step=5 writes Cfg.Cmd through the alias: Level grows 5 a scan,
    # 3 scans give 15 < 20 (Full false), 4 scans give 20 (Full true)
    watch = ("Tank.Level", "Tank.Full", "Tank.Step")
    tags = run(capsys, ALIASES, 3, *watch, extra=("--set", "Tank.Step=5"))
    assert tags == {"Tank.Level": 15, "Tank.Full": False, "Tank.Step": 5}
    tags = run(capsys, ALIASES, 4, *watch, extra=("--set", "Tank.Step=5"))
    assert tags == {"Tank.Level": 20, "Tank.Full": True, "Tank.Step": 5}


def test_required_alias_parameters_are_call_operands_in_declared_order(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    # Fill(Tank, 1.25, LevelCopy): Rate (alias of Cfg.Speed, declared before Copy) gets 1.25,
    # the logic doubles Cfg.Speed: 2.5; Copy (alias of Acc) hands Level out: 10 per scan
    tags = run(capsys, ALIASES, 2, "Tank.Rate", "LevelCopy", "Tank.Level")
    assert tags == {"Tank.Rate": 2.5, "LevelCopy": 20, "Tank.Level": 20}
    # the operands are checked as any AOI's: one missing is E104
    text = ALIASES.read_text().replace("Fill(Tank, 1.25, LevelCopy);", "Fill(Tank, 1.25);")
    path = tmp_path / "short.L5X"
    path.write_text(text)
    _, diags = check(capsys, path)
    assert [d["code"] for d in diags] == ["E104"]


def test_set_through_an_alias_writes_the_base(capsys: pytest.CaptureFixture[str]) -> None:
    # StartPB is Local:1:I.Data.3: clearing it leaves Data = 8 - 8 = 0, so Lamp stays off and
    # the ladder rung XIC(StartPB) is false (Sum keeps 0)
    tags = run(
        capsys, ALIASES, 1, "InData", "Lamp", "Sum", "Local:1:I.Data", extra=("--set", "StartPB=0")
    )
    assert tags == {"InData": 0, "Lamp": False, "Sum": 0, "Local:1:I.Data": 0}


def test_check_types_an_alias_as_its_base(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    text = ALIASES.read_text().replace(
        "<![CDATA[Mirror := Cmd2Bit;]]>",
        "<![CDATA[Mirror := StartPB.1; Drive.Nope := 1; Cmd2 := InData + Drive;]]>",
    )
    path = tmp_path / "typed.L5X"
    path.write_text(text)
    code, diags = check(capsys, path)
    got = [(d["code"], d["message"].split(" (program")[0]) for d in diags]
    assert got == [
        ("E121", "bit access needs an integer, not BOOL"),  # StartPB is one bit
        ("E102", "'Motor' has no member 'Nope'"),  # Drive is M1, a Motor
        ("E121", "'+' cannot be applied to Motor"),
    ]
    assert code != 0


def test_an_alias_without_a_base_is_one_diagnostic_at_its_declaration(
    capsys: pytest.CaptureFixture[str],
) -> None:
    _, diags = check(capsys, BROKEN)
    got = [(d["line"], d["code"], d["message"]) for d in diags]
    assert got == [
        (10, "E101", "alias 'Ghost' for 'Nowhere.X': 'Nowhere' is not a declared tag"),
        (
            11,
            "E101",
            "alias 'LoopA' for 'LoopB': the aliases form a cycle (LoopA -> LoopB -> LoopA) "
            "with no base tag",
        ),
        (
            12,
            "E101",
            "alias 'LoopB' for 'LoopA.2': the aliases form a cycle (LoopA -> LoopB -> LoopA) "
            "with no base tag",
        ),
        (13, "E101", "alias 'Via' for 'LoopB': alias 'LoopB' has no base tag"),
        (14, "E122", "alias 'BadBit' for 'Word.40': bit 40 is outside 0..31 of DINT"),
        (
            15,
            "E110",
            "alias 'BadIdx' for 'Arr[i]': an alias names a fixed element: subscripts are numbers",
        ),
        (16, "E122", "alias 'OutIdx' for 'Arr[4]': subscript 4 is outside 0..3"),
        (17, "E102", "alias 'BadMember' for 'Word.Foo': DINT has no member 'Foo'"),
        (18, "U305", diags[8]["message"]),
        (19, "E117", "tag 'Word' is already declared at line 7"),
    ]
    # a module I/O base whose module is not in the export: not simulated, not an error
    assert diags[8]["message"].startswith("alias 'NoModule' for 'Local:5:I.Data.0': 'Local:5:I'")
    assert diags[8]["message"].endswith("; it is not simulated")


def test_tags_option_brings_the_exports_controller_aliases(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    # --tags declares controller tags only (no AOI instances): the fixture without Tank
    export = tmp_path / "tags.L5X"
    export.write_text(
        "".join(
            line
            for line in ALIASES.read_text().splitlines(keepends=True)
            if 'Name="Tank"' not in line
        )
    )
    routine = tmp_path / "uses.st"
    routine.write_text("Cmd2 := Cmd2 + 1;\nLamp := StartPB AND RunBit;\nDrive.Speed := 2.5;\n")
    tags = run(
        capsys,
        routine,
        2,
        "Cmd2",
        "M1.Cmd",
        "Local:2:O.Data",
        "M1.Speed",
        extra=("--tags", str(export)),
    )
    # M1.Cmd 13 + 2 scans = 15; StartPB (Local:1:I.Data.3) and RunBit (Word.2) are set, so
    # Lamp sets bit 0 of Local:2:O.Data; Drive is M1
    assert tags == {"Cmd2": 15, "M1.Cmd": 15, "Local:2:O.Data": 1, "M1.Speed": 2.5}
