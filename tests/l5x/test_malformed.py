"""Malformed or hostile exports give one-line diagnostics and exit codes, never a traceback."""

from __future__ import annotations

import json
import time
from pathlib import Path

import pytest

from interpreter.cli import main

FIX = Path(__file__).parent / "fixtures"


def check(capsys: pytest.CaptureFixture[str], name: str) -> tuple[int, list[dict], str]:
    capsys.readouterr()
    code = main(["check", str(FIX / name), "--format", "json"])
    cap = capsys.readouterr()
    return code, (json.loads(cap.out) if cap.out.strip() else []), cap.err


def test_billion_laughs_is_refused_before_any_expansion(capsys: pytest.CaptureFixture[str]) -> None:
    start = time.monotonic()
    code, diags, _ = check(capsys, "billion_laughs.L5X")
    assert time.monotonic() - start < 5
    assert code == 1
    assert [(d["code"], d["line"]) for d in diags] == [("S007", 2)]  # the DOCTYPE line
    assert "DOCTYPE" in diags[0]["message"]


def test_external_entity_is_refused(capsys: pytest.CaptureFixture[str]) -> None:
    code, diags, _ = check(capsys, "external_entity.L5X")
    assert code == 1 and [d["code"] for d in diags] == ["S007"]
    assert "passwd" not in json.dumps(diags)


def test_truncated_export(capsys: pytest.CaptureFixture[str]) -> None:
    code, diags, _ = check(capsys, "truncated.L5X")
    assert code == 1
    assert [d["code"] for d in diags] == ["S007"]
    assert "malformed XML" in diags[0]["message"]
    assert diags[0]["line"] >= 10  # at the cut, not at the top of the file


def test_text_file_with_l5x_suffix(capsys: pytest.CaptureFixture[str]) -> None:
    code, diags, _ = check(capsys, "not_xml.L5X")
    assert code == 1
    assert [(d["code"], d["line"], d["column"]) for d in diags] == [("S007", 1, 1)]


def test_empty_file_is_an_input_error(capsys: pytest.CaptureFixture[str]) -> None:
    code, diags, err = check(capsys, "empty.L5X")
    assert code == 2 and diags == []
    assert "empty" in err and "Traceback" not in err


def test_wrong_root_element(capsys: pytest.CaptureFixture[str]) -> None:
    code, diags, _ = check(capsys, "wrong_root.L5X")
    assert code == 1 and [d["code"] for d in diags] == ["S007"]
    assert "RSLogix5000Content" in diags[0]["message"] and diags[0]["line"] == 2


def test_missing_attributes(capsys: pytest.CaptureFixture[str]) -> None:
    code, diags, _ = check(capsys, "missing_attributes.L5X")
    assert code == 1
    assert [(d["code"], d["line"]) for d in diags] == [("S007", 5), ("S007", 6)]
    assert "no Name" in diags[0]["message"] and "no DataType" in diags[1]["message"]


def test_unknown_data_type_is_a_verification_error(capsys: pytest.CaptureFixture[str]) -> None:
    code, diags, _ = check(capsys, "unknown_type.L5X")
    assert code == 1
    assert [(d["code"], d["line"]) for d in diags] == [("E119", 5)]
    assert "NO_SUCH_TYPE" in diags[0]["message"]


def test_fbd_sfc_and_protected_routines_are_not_supported(
    capsys: pytest.CaptureFixture[str],
) -> None:
    # U diagnostics are warnings (SPEC 9.32): the check passes. JSRs to the three routines
    # resolve (a protected routine is still a routine), so there is no E124.
    code, diags, _ = check(capsys, "unsupported.L5X")
    assert code == 0
    assert [(d["code"], d["line"], d["severity"]) for d in diags] == [
        ("U301", 15, "warning"),
        ("U301", 20, "warning"),
        ("U302", 23, "warning"),
    ]


def test_unsupported_routines_run_as_nothing_and_are_reported_once(
    capsys: pytest.CaptureFixture[str],
) -> None:
    # Main is `n := n + 1; JSR(Blend); JSR(Steps); JSR(Secret);` each scan: 3 scans give n = 3
    # and the three JSRs to routines that are not simulated do nothing (SPEC 9.32).
    capsys.readouterr()
    code = main(["run", str(FIX / "unsupported.L5X"), "--scans", "3", "--json", "--watch", "n"])
    report = json.loads(capsys.readouterr().out)
    assert code == 0
    assert report["tags"] == {"n": 3}
    assert [(u["code"], u["line"], u["column"]) for u in report["unsupported"]] == [
        ("U301", 15, 1),
        ("U301", 20, 1),
        ("U302", 23, 1),
    ]
    assert set(report["unsupported"][0]) == {"code", "message", "file", "line", "column"}


def test_run_of_a_malformed_export_exits_1_with_diagnostics(
    capsys: pytest.CaptureFixture[str],
) -> None:
    capsys.readouterr()
    code = main(["run", str(FIX / "truncated.L5X"), "--scans", "1"])
    err = capsys.readouterr().err
    assert code == 1
    assert "S007" in err and "Traceback" not in err


def test_st_positions_are_file_positions_with_studio_line_numbers(
    capsys: pytest.CaptureFixture[str],
) -> None:
    code, diags, _ = check(capsys, "st_errors.L5X")
    assert code == 1
    # Line 16 of the file holds ST line 1 `  Missing := 2;` whose CDATA content starts in
    # column 10 (after `<![CDATA[`); two spaces later is column 12.
    e101 = next(d for d in diags if d["code"] == "E101")
    assert (e101["line"], e101["column"], e101["endColumn"]) == (16, 12, 19)
    assert "(program Line1, routine Main, line 1)" in e101["message"]
    # Line 19 `Count := (Count + ;`: the ';' is character 19 of the content -> column 28.
    s001 = next(d for d in diags if d["code"] == "S001")
    assert (s001["line"], s001["column"]) == (19, 28)
    assert "line 2)" in s001["message"]


def test_other_files_with_an_l5x_are_refused(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    st = tmp_path / "a.st"
    st.write_text("VAR x : DINT; END_VAR\nx := 1;\n")
    capsys.readouterr()
    code = main(["run", str(FIX / "st_project.L5X"), str(st)])
    assert code == 2
    assert "whole project" in capsys.readouterr().err


def test_run_of_an_export_without_programs_scans_nothing(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    # An Add-On Instruction export (or a controller with no programs) used to crash `run`
    # looking up a main routine that does not exist. With no program there is nothing to
    # scan: the 3 scans run empty, and the one controller tag keeps its initial value 7.
    p = tmp_path / "no_programs.L5X"
    p.write_text(
        '<?xml version="1.0" encoding="UTF-8" standalone="yes"?>\n'
        '<RSLogix5000Content SchemaRevision="1.0" SoftwareRevision="32.00" TargetName="T" TargetType="Controller">\n'
        '<Controller Use="Target" Name="T">\n'
        '<Tags><Tag Name="K" TagType="Base" DataType="DINT"><Data Format="Decorated">\n'
        '<DataValue DataType="DINT" Radix="Decimal" Value="7"/></Data></Tag></Tags>\n'
        "</Controller>\n"
        "</RSLogix5000Content>\n"
    )
    capsys.readouterr()
    code = main(["run", str(p), "--scans", "3", "--json"])
    cap = capsys.readouterr()
    assert code == 0, cap.err
    assert json.loads(cap.out) == {
        "time": 0.003,
        "scans": 3,
        "tags": {"K": 7},
        "faults": [],
        "diagnostics": [],
        "unsupported": [],
    }


@pytest.mark.parametrize("encoding", ["x", "utf-32", "punycode", "rot13"])
def test_unreadable_declared_encoding(
    capsys: pytest.CaptureFixture[str], tmp_path: Path, encoding: str
) -> None:
    # expat hands encodings it does not know itself to Python's codecs, which raised
    # LookupError/ValueError out of the reader (a traceback). Now S007 at the encoding's value:
    # `<?xml version="1.0" encoding="` is 30 characters, so the value starts in column 31.
    p = tmp_path / "enc.L5X"
    p.write_text(
        f'<?xml version="1.0" encoding="{encoding}"?>\n'
        '<RSLogix5000Content SchemaRevision="1.0"><Controller Name="T"/></RSLogix5000Content>\n'
    )
    capsys.readouterr()
    code = main(["check", str(p), "--format", "json"])
    diags = json.loads(capsys.readouterr().out)
    assert code == 1
    assert [(d["code"], d["line"], d["column"]) for d in diags] == [("S007", 1, 31)]
    assert f"'{encoding}'" in diags[0]["message"]
