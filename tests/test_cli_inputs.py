"""`logixst run` on bad or unusual input: one clear line on stderr, the SPEC 6 exit code, no traceback.

Exit codes (SPEC 6): 0 ran, 1 verification errors, 2 usage or input-file error, 3 major fault.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from interpreter.cli import main

GOOD = """VAR
  n : DINT;
  x : REAL;
END_VAR
n := n + 1;
x := x + 0.5;
"""


@pytest.fixture
def good(tmp_path: Path) -> Path:
    p = tmp_path / "good.st"
    p.write_text(GOOD)
    return p


def run_main(capsys: pytest.CaptureFixture[str], *argv: str) -> tuple[int, str, str]:
    code = main(["run", *argv])
    out, err = capsys.readouterr()
    return code, out, err


def assert_one_line_error(err: str, *fragments: str) -> None:
    assert "Traceback" not in err
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert lines[0].startswith("logixst: error: "), err
    for f in fragments:
        assert f in lines[0], (f, err)


def run_cli(*argv: str, cwd: Path | None = None) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "interpreter.cli", *argv],
        capture_output=True,
        text=True,
        timeout=120,
        cwd=cwd,
    )


# ------------------------------------------------------------------ input files
def test_missing_file(tmp_path: Path) -> None:
    r = run_cli("run", str(tmp_path / "nope.st"))
    assert r.returncode == 2
    assert_one_line_error(r.stderr, "nope.st", "no such file")
    assert r.stdout == ""


def test_missing_file_with_other_suffix_is_reported_as_missing(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    code, _, err = run_main(capsys, str(tmp_path / "nope.txt"))
    assert code == 2
    assert_one_line_error(err, "no such file")


def test_directory(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    code, out, err = run_main(capsys, str(tmp_path))
    assert code == 2
    assert_one_line_error(err, str(tmp_path), "is a directory")
    assert out == ""


def test_binary_file(tmp_path: Path) -> None:
    p = tmp_path / "blob.st"
    p.write_bytes(bytes(range(256)) * 4)
    r = run_cli("run", str(p))
    assert r.returncode == 2
    assert_one_line_error(r.stderr, "blob.st", "binary")


def test_unsupported_suffix(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    p = tmp_path / "prog.txt"
    p.write_text(GOOD)
    code, _, err = run_main(capsys, str(p))
    assert code == 2
    assert_one_line_error(err, "prog.txt", "unsupported file type")


@pytest.mark.parametrize("content", [b"", b"  \n\t\n"])
def test_empty_file(capsys: pytest.CaptureFixture[str], tmp_path: Path, content: bytes) -> None:
    # An empty or whitespace-only file is almost always a wrong path or a failed export.
    p = tmp_path / "empty.st"
    p.write_bytes(content)
    code, out, err = run_main(capsys, str(p), "--scans", "3")
    assert code == 2
    assert_one_line_error(err, "empty.st", "empty")
    assert out == ""


def test_invalid_utf8_in_a_comment_is_read_as_latin1(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    # Exports from Windows tools often carry cp1252 bytes (degree sign, micro sign) in comments.
    p = tmp_path / "latin.st"
    p.write_bytes(b"VAR n : DINT; END_VAR\n// setpoint 20 \xb0C, \xb5m, \xff\xfe\nn := n + 1;\n")
    code, out, err = run_main(capsys, str(p), "--scans", "2", "--watch", "n")
    assert code == 0, err
    assert "Traceback" not in err
    assert out.split() == ["n", "2"]


def test_invalid_utf8_in_code_is_a_syntax_diagnostic(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    p = tmp_path / "bad.st"
    p.write_bytes(b"VAR n : DINT; END_VAR\nn := n \xff 1;\n")
    code, out, err = run_main(capsys, str(p))
    assert code == 1
    assert "Traceback" not in err
    # One diagnostic per line; the first names the stray byte (decoded as latin-1).
    lines = err.strip().splitlines()
    assert lines[0] == f"{p}:2:8: error S004 unexpected character 'ÿ'"
    assert all(line.startswith(f"{p}:") for line in lines)


def test_bom_is_skipped(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    p = tmp_path / "bom.st"
    p.write_bytes(b"\xef\xbb\xbf" + GOOD.encode())
    code, out, err = run_main(capsys, str(p), "--scans", "4", "--watch", "n")
    assert (code, err) == (0, "")
    assert out.split() == ["n", "4"]


def test_no_program_given(capsys: pytest.CaptureFixture[str]) -> None:
    code, _, err = run_main(capsys)
    assert code == 2
    assert_one_line_error(err, "PROGRAM")


# ------------------------------------------------------------------ flags
@pytest.mark.parametrize(
    ("flags", "fragment"),
    [
        (["--scan-period", "0"], "--scan-period"),
        (["--scan-period", "-1"], "--scan-period"),
        (["--scan-period", "nan"], "--scan-period"),
        (["--scan-period", "fast"], "--scan-period"),
        (["--scans", "-1"], "--scans"),
        (["--scans", "ten"], "--scans"),
        (["--duration", "-0.5"], "--duration"),
        (["--duration", "inf"], "--duration"),
        (["--duration", "1", "--scans", "5"], "not allowed"),
        # 1e308 s x 1000 / 1 ms overflows a float to inf: no scan count, refused (was a traceback)
        (["--duration", "1e308"], "--duration 1e+308 s"),
        # a subnormal period is below the 0.1 ms floor (docs/limits.md), refused by its range
        (["--scan-period", "5e-324"], "--scan-period 4.94066e-324 ms is outside 0.1..2,000,000 ms"),
        (["--watchdog", "0"], "--watchdog"),
        (["--set", "n"], "TAG=VALUE"),
        (["--set", "n=abc"], "not an ST literal"),
        (["--set", "nosuch=1"], "nosuch"),
        (["--watch", "nosuch"], "nosuch"),
        (["--watch", "n.99"], "n.99"),
        (["--watch", "n["], "n["),
        (["--frobnicate"], "--frobnicate"),
    ],
)
def test_bad_flags(
    capsys: pytest.CaptureFixture[str], good: Path, flags: list[str], fragment: str
) -> None:
    code, out, err = run_main(capsys, str(good), *flags)
    assert code == 2
    assert_one_line_error(err, fragment)
    assert out == ""


def test_unknown_watch_tag_through_the_real_entry_point(good: Path) -> None:
    r = run_cli("run", str(good), "--watch", "Missing")
    assert r.returncode == 2
    assert_one_line_error(r.stderr, "Missing", "undefined tag")


def test_unwritable_trace(capsys: pytest.CaptureFixture[str], good: Path, tmp_path: Path) -> None:
    code, _, err = run_main(
        capsys,
        str(good),
        "--scans",
        "1",
        "--watch",
        "n",
        "--trace",
        str(tmp_path / "no" / "dir" / "t.csv"),
    )
    assert code == 2
    assert_one_line_error(err, "cannot write trace")


def test_unknown_subcommand(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["frob"]) == 2
    assert_one_line_error(capsys.readouterr().err, "frob")


# ------------------------------------------------------------------ the other exit codes, for contrast
def test_verification_error_exit_1(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    p = tmp_path / "undef.st"
    p.write_text("VAR n : DINT; END_VAR\nn := m + 1;\n")
    code, out, err = run_main(capsys, str(p))
    assert code == 1
    assert err.strip() == f"{p}:2:6: error E101 undefined tag 'm'"
    assert out == ""


def test_major_fault_exit_3(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    p = tmp_path / "fault.st"
    p.write_text("VAR a : DINT[3]; i : DINT := 3; END_VAR\na[i] := 1;\n")
    code, _, err = run_main(capsys, str(p), "--watch", "i")
    assert code == 3
    assert "Traceback" not in err
    assert err.strip() == f"{p}:2:1: major fault type 4 code 20: array subscript out of range"


# ------------------------------------------------------------------ size
def test_one_megabyte_program(tmp_path: Path) -> None:
    # Realistic Logix tag names are long; 20 of them, ~5,600 assignment lines, 1 MB in all.
    names = [f"Line{k}_Conveyor_Section_Infeed_Motor_Speed_Reference" for k in range(20)]
    lines = ["VAR", *(f"  {nm} : DINT;" for nm in names), "END_VAR"]
    size, i = 0, 0
    while size < 1_000_000:
        line = f"{names[i % 20]} := {names[(i + 7) % 20]} + {i % 100}; // keep the infeed ahead of the discharge"
        lines.append(line)
        size += len(line) + 1
        i += 1
    p = tmp_path / "big.st"
    p.write_text("\n".join(lines) + "\n")
    assert p.stat().st_size >= 1_000_000
    r = run_cli("run", str(p), "--scans", "1", "--watch", names[0], "--json")
    assert r.returncode == 0, r.stderr[-2000:]
    assert r.stderr == ""
    assert '"scans": 1' in r.stdout
