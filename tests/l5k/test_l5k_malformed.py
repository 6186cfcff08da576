"""Malformed .L5K input: one-line diagnostics at the place in the file, never a traceback."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest

from interpreter.cli import main
from interpreter.runtime import loader

FIX = Path(__file__).parent / "fixtures"

GOOD = """IE_VER := 2.20;
CONTROLLER C (ProcessorType := "1756-L83E")
\tTAG
\t\tA : DINT := 1;
\t\tB : DINT := 2;
\tEND_TAG
\tPROGRAM P (MAIN := "R")
\t\tROUTINE R
\t\t\tN: ADD(A,B,B);
\t\tEND_ROUTINE
\tEND_PROGRAM
\tTASK T (Type := CONTINUOUS)
\t\tP;
\tEND_TASK
END_CONTROLLER
"""


def check(
    capsys: pytest.CaptureFixture[str], tmp_path: Path, text: str | bytes
) -> tuple[int, list[dict[str, Any]], str]:
    path = tmp_path / "x.L5K"
    if isinstance(text, bytes):
        path.write_bytes(text)
    else:
        path.write_text(text)
    capsys.readouterr()
    code = main(["check", str(path), "--format", "json"])
    cap = capsys.readouterr()
    assert "Traceback" not in cap.err
    return code, (json.loads(cap.out) if cap.out.strip() else []), cap.err


def codes(diags: list[dict[str, Any]]) -> list[tuple[str, int, int]]:
    return [(d["code"], d["line"], d["column"]) for d in diags]


def test_the_base_text_is_clean(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    assert check(capsys, tmp_path, GOOD)[:2] == (0, [])


def test_truncated_file_is_reported_where_it_ends(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    cut = GOOD[: GOOD.index("\t\tEND_ROUTINE")]  # ends after the rung on line 9
    code, diags, _ = check(capsys, tmp_path, cut)
    assert code == 1
    assert codes(diags) == [("S008", 10, 1)]  # the end of the file: line 10, column 1
    assert diags[0]["message"] == (
        "ROUTINE opened at line 8 is not closed: the file ends before END_ROUTINE"
    )


def test_wrong_end_keyword(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    text = GOOD.replace("\t\tEND_ROUTINE\n", "")
    code, diags, _ = check(capsys, tmp_path, text)
    assert code == 1 and codes(diags) == [("S008", 10, 2)]
    assert "END_PROGRAM where END_ROUTINE was expected" in diags[0]["message"]


def test_text_that_is_not_an_export(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    code, diags, _ = check(capsys, tmp_path, "hello world\n")
    assert code == 1 and codes(diags) == [("S008", 1, 1)]
    assert "not a Studio 5000 L5K export" in diags[0]["message"]


def test_l5x_content_in_an_l5k_file(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    text = '<?xml version="1.0"?>\n<RSLogix5000Content/>\n'
    code, diags, _ = check(capsys, tmp_path, text)
    assert code == 1 and codes(diags) == [("S008", 1, 1)]


def test_unclosed_string(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    # `\tPROGRAM P (MAIN := "R)`: no '"' follows anywhere (strings may span lines)
    text = GOOD.replace('(MAIN := "R")', '(MAIN := "R)')
    code, diags, _ = check(capsys, tmp_path, text)
    assert code == 1 and codes(diags) == [("S008", 7, 21)]  # the opening quote
    assert diags[0]["message"] == "string is not closed"


def test_unclosed_header_comment(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    code, diags, _ = check(capsys, tmp_path, "(*****\n  Import-Export\n" + GOOD)
    assert code == 1 and codes(diags) == [("S008", 1, 1)]
    assert "'(*'" in diags[0]["message"]


def test_a_bad_tag_is_skipped_and_reading_goes_on(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    text = GOOD.replace("\t\tA : DINT := 1;\n", "\t\tBad DINT := 5;\n\t\tA : DINT := 1;\n")
    code, diags, _ = check(capsys, tmp_path, text)
    assert code == 1 and codes(diags) == [("S008", 4, 7)]  # at 'DINT' after `\t\tBad `
    assert diags[0]["message"] == "expected ':' after the tag name 'Bad', found 'DINT'"


def test_a_bad_member_and_a_nameless_program(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    text = GOOD.replace(
        "\tTAG\n",
        "\tDATATYPE U (FamilyType := NoFamily)\n\t\tDINT;\n\t\tDINT Ok;\n\tEND_DATATYPE\n\tTAG\n",
        1,
    ).replace("\tTASK T", '\tPROGRAM (MAIN := "R")\n\tEND_PROGRAM\n\tTASK T')
    code, diags, _ = check(capsys, tmp_path, text)
    assert code == 1
    # `\t\tDINT;`: the member name is missing where the ';' stands (column 7); the program
    # header has no name before its attribute list (line 16, column 10)
    assert codes(diags) == [("S008", 4, 7), ("S008", 16, 10)]
    assert "expected a member name" in diags[0]["message"]
    assert "expected a program name" in diags[1]["message"]


def test_text_after_the_controller(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    code, diags, _ = check(capsys, tmp_path, GOOD + "\nEXTRA\n")
    assert code == 1 and codes(diags) == [("S008", 17, 1)]


def test_unknown_blocks_are_skipped(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    text = GOOD.replace(
        "END_CONTROLLER", 'FUTURE_BLOCK (X := "END_CONTROLLER")\n\tEND_FUTURE_BLOCK\nEND_CONTROLLER'
    )
    assert check(capsys, tmp_path, text)[:2] == (0, [])


def test_empty_and_binary_files_are_input_errors(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    code, diags, err = check(capsys, tmp_path, "  \n")
    assert code == 2 and diags == [] and "empty" in err
    code, diags, err = check(capsys, tmp_path, b"IE_VER\x00\x01\x02")
    assert code == 2 and diags == [] and "binary" in err


def test_size_limit(
    capsys: pytest.CaptureFixture[str], tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(loader, "MAX_PROJECT_BYTES", 100)
    code, diags, err = check(capsys, tmp_path, GOOD)
    assert (
        code == 2
        and diags == []
        and "too large" in err
        and "the limit is" in err
        and len(err.strip().splitlines()) == 1
    )


def test_run_of_a_malformed_export_exits_1(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    path = tmp_path / "cut.L5K"
    path.write_text(GOOD[:200])
    capsys.readouterr()
    assert main(["run", str(path), "--scans", "1"]) == 1
    err = capsys.readouterr().err
    assert "S008" in err and "Traceback" not in err


def test_a_project_is_given_alone(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    st = tmp_path / "a.st"
    st.write_text("VAR x : DINT; END_VAR\nx := 1;\n")
    capsys.readouterr()
    assert main(["run", str(FIX / "st_project.L5K"), str(st)]) == 2
    assert "an .L5X or .L5K file is a whole project" in capsys.readouterr().err


def test_a_tag_named_like_an_end_keyword(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    # only the END_ keywords of blocks end blocks: END_POS is an ordinary tag name
    text = GOOD.replace("\t\tB : DINT := 2;\n", "\t\tB : DINT := 2;\n\t\tEND_POS : DINT := 3;\n")
    text = text.replace("N: ADD(A,B,B);", "N: ADD(A,END_POS,B);")
    path = tmp_path / "end.L5K"
    path.write_text(text)
    capsys.readouterr()
    assert main(["run", str(path), "--scans", "2", "--json", "--watch", "B"]) == 0
    assert json.loads(capsys.readouterr().out)["tags"] == {"B": 1 + 3}  # B := A + END_POS


def test_blocks_among_tag_statements_are_skipped(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    # a tag-based alarm's block after its tag: not a tag statement, the next tag still reads
    block = '\t\tALARM_CONDITION HI (Input := "A > 5", Severity := 500)\n\t\tEND_ALARM_CONDITION\n'
    text = GOOD.replace("\t\tB : DINT := 2;\n", block + "\t\tB : DINT := 2;\n")
    path = tmp_path / "alarm.L5K"
    path.write_text(text)
    capsys.readouterr()
    assert main(["run", str(path), "--scans", "1", "--json", "--watch", "B"]) == 0
    assert json.loads(capsys.readouterr().out)["tags"] == {"B": 1 + 2}  # ADD(A,B,B) once


def test_unknown_statement_is_reported_and_skipped(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    text = GOOD.replace("\tTASK T", "\tSOMETHING := [1,2];\n\tTASK T")
    code, diags, _ = check(capsys, tmp_path, text)
    assert code == 1 and codes(diags) == [("S008", 12, 2)]
    assert diags[0]["message"] == "unknown statement 'SOMETHING' skipped"
