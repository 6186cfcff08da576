"""Running an L5X project: scopes, JSR reachability, tasks, AOIs, data, aliases, --tags."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest

from interpreter.cli import main

FIX = Path(__file__).parent / "fixtures"
PROJECT = FIX / "st_project.L5X"


def run(
    capsys: pytest.CaptureFixture[str],
    path: Path,
    scans: int,
    *watch: str,
    extra: tuple[str, ...] = (),
) -> dict[str, Any]:
    argv = ["run", str(path), "--scans", str(scans), "--json", *extra]
    for w in watch:
        argv += ["--watch", w]
    capsys.readouterr()
    code = main(argv)
    out = capsys.readouterr()
    assert code == 0, (code, out.err, out.out)
    return json.loads(out.out)["tags"]  # type: ignore[no-any-return]


def test_project_checks_clean(capsys: pytest.CaptureFixture[str]) -> None:
    capsys.readouterr()
    assert main(["check", str(PROJECT)]) == 0
    assert capsys.readouterr().out.strip() == "0 error(s), 0 warning(s)"


def test_exported_data_becomes_initial_values(capsys: pytest.CaptureFixture[str]) -> None:
    tags = run(
        capsys,
        PROJECT,
        0,
        "Speed",
        "Shared",
        "Program:MainProgram.Shared",
        "V1.Open",
        "V1.Fault",
        "V1.Count",
        "V1.Hist[1]",
        "Label",
        "Table[1,1]",
        "Program:MainProgram.Sc.Gain",
    )
    assert tags == {
        "Speed": 7,  # decorated DataValue
        "Shared": 16,  # Radix Hex 16#0000_0010
        "Program:MainProgram.Shared": 100,
        "V1.Open": True,
        "V1.Fault": False,  # BIT members over the hidden SINT
        "V1.Count": 3,
        "V1.Hist[1]": 20,  # ArrayMember elements
        "Label": "abc",  # <Data Format="String">
        "Table[1,1]": 4,  # L5K [1,2,3,4] for DINT[2,2]: row-major, [1,1] is the 4th
        "Program:MainProgram.Sc.Gain": 2.0,  # the AOI parameter's default
    }


def test_scopes_jsr_tasks_and_aoi(capsys: pytest.CaptureFixture[str]) -> None:
    tags = run(
        capsys,
        PROJECT,
        25,
        "Speed",
        "Shared",
        "Program:MainProgram.Shared",
        "Program:Fast.Runs",
        "Ticks",
        "Program:MainProgram.Result",
        "Program:MainProgram.Counted",
        "Program:MainProgram.Sc.Out",
        "Program:MainProgram.Sc.EnableOut",
    )
    # MainTask (continuous) runs MainProgram every scan: Main adds 1 to the program's own
    # Shared (shadowing the controller tag) and JSRs Sub, which adds 2 to Speed. The
    # routine Unused and the unscheduled program Idle never run (they would zero Speed).
    assert tags["Speed"] == 7 + 2 * 25
    assert tags["Program:MainProgram.Shared"] == 100 + 25
    assert tags["Shared"] == 16
    # Every10 (periodic, 10 ms) is due at t = 0, 10, 20 within scans at t = 0..24 ms.
    assert tags["Program:Fast.Runs"] == 3 and tags["Ticks"] == 3
    # Gained(Sc, 1.5, Result, Counted): Out = In * Gain = 1.5 * 2.0; Total is InOut and gains
    # (N - Calls) + 1 a call, where the alias parameter N is the local Calls: +1, not +2.
    assert tags["Program:MainProgram.Result"] == 3.0
    assert tags["Program:MainProgram.Sc.Out"] == 3.0
    assert tags["Program:MainProgram.Counted"] == 25
    assert tags["Program:MainProgram.Sc.EnableOut"] is True


def test_aliases_share_storage(capsys: pytest.CaptureFixture[str]) -> None:
    tags = run(capsys, PROJECT, 3, "SpeedAlias", "CountAlias", "Speed", "V1.Hist[2]")
    assert tags["SpeedAlias"] == tags["Speed"] == 7 + 2 * 3
    assert tags["CountAlias"] == tags["V1.Hist[2]"] == 30


def test_set_a_program_tag(capsys: pytest.CaptureFixture[str]) -> None:
    tags = run(
        capsys,
        PROJECT,
        1,
        "Program:MainProgram.Shared",
        extra=("--set", "Program:MainProgram.Shared=5"),
    )
    assert tags["Program:MainProgram.Shared"] == 6


def test_aoi_local_tags_are_hidden_outside(capsys: pytest.CaptureFixture[str]) -> None:
    capsys.readouterr()
    code = main(["run", str(PROJECT), "--scans", "1", "--watch", "Program:MainProgram.Sc.Calls"])
    assert code == 2
    assert "no member 'Calls'" in capsys.readouterr().err


def test_default_watch_lists_program_tags_qualified(capsys: pytest.CaptureFixture[str]) -> None:
    capsys.readouterr()
    assert main(["run", str(PROJECT), "--scans", "1"]) == 0
    out = capsys.readouterr().out
    assert "Program:Fast.Runs" in out and "Program:MainProgram.Shared" in out


def test_tags_file_supplies_controller_tags_and_types(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    st = tmp_path / "bare.st"
    st.write_text("Speed := Speed + V1.Count;\nV1.Fault := TRUE;\n")
    tags = run(capsys, st, 2, "Speed", "V1.Fault", extra=("--tags", str(PROJECT)))
    assert tags == {"Speed": 7 + 3 + 3, "V1.Fault": True}


def test_tags_file_gives_no_program_tags(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    st = tmp_path / "bare.st"
    st.write_text("Result := 1.0;\n")
    capsys.readouterr()
    assert main(["check", str(st), "--tags", str(PROJECT)]) == 1
    assert "E101" in capsys.readouterr().out


def test_tags_must_be_an_l5x(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    st = tmp_path / "bare.st"
    st.write_text("VAR x : DINT; END_VAR\nx := 1;\n")
    capsys.readouterr()
    assert main(["run", str(st), "--tags", str(st)]) == 2


def test_members_named_like_reserved_words(capsys: pytest.CaptureFixture[str]) -> None:
    # Studio exports hold UDT members called AND, MOD, NOT, Array (fanno/l5x-emulator v37):
    # after '.', a reserved word is a member name, in ladder operands and in ST alike.
    path = FIX / "keyword_members.L5X"
    capsys.readouterr()
    assert main(["check", str(path)]) == 0
    assert capsys.readouterr().out.strip() == "0 error(s), 0 warning(s)"
    tags = run(capsys, path, 1, "Kw.AND", "Kw.MOD", "Kw.Array[1]", "Kw.NOT")
    # 3 AND 5 = 2#011 AND 2#101 = 1; 7 MOD 4 = 3; Array[1] := MOD = 3; NOT := 1 + 3 * 3 = 10
    assert tags == {"Kw.AND": 1, "Kw.MOD": 3, "Kw.Array[1]": 3, "Kw.NOT": 10}


def test_program_parameter_references(capsys: pytest.CaptureFixture[str]) -> None:
    # `\Program.Parameter` (Huiscode/L5x v35 export: `XIC(\CM_HMI.HMI.Machine.Use.Bool[126])`)
    # names another program's tag, in ladder and in ST.
    path = FIX / "program_parameters.L5X"
    capsys.readouterr()
    assert main(["check", str(path)]) == 0
    assert capsys.readouterr().out.strip() == "0 error(s), 0 warning(s)"
    tags = run(capsys, path, 1, "Program:Source.Level", "Program:User.Sum", "Program:User.Scaled")
    # Source runs first: Level = 5; then User: Sum = 5 + 2 = 7, Scaled = 5 * 10 = 50
    assert tags == {"Program:Source.Level": 5, "Program:User.Sum": 7, "Program:User.Scaled": 50}
