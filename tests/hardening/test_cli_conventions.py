"""Issue 14, CLI conventions and option ranges, through the real entry point.

Bounds: every case finishes within its `timeout` (seconds, wall) under the 2 GB address-space
limit of harness.logixst; the refusals come before anything is read, so 20 s is generous.
"""

from __future__ import annotations

import argparse
import json
import tomllib
from pathlib import Path

import pytest

from interpreter.cli import build_parser
from tests.hardening.harness import ROOT, logixst

PROGRAM = "VAR\n  n : DINT;\nEND_VAR\nn := n + 1;\n"


@pytest.fixture
def prog(tmp_path: Path) -> Path:
    p = tmp_path / "p.st"
    p.write_text(PROGRAM)
    return p


@pytest.mark.parametrize(
    "argv", [["--help"], ["run", "--help"], ["check", "--help"], ["lsp", "--help"]]
)
def test_help_exits_0(argv: list[str]) -> None:
    r = logixst(*argv, timeout=20)
    assert r.code == 0 and r.out.startswith("usage: logixst") and r.err == ""


def test_every_option_has_help_text() -> None:
    parser = build_parser()
    subs = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    for name, sub in subs.choices.items():
        assert sub.description, name
        for action in sub._actions:
            assert action.help and action.help != argparse.SUPPRESS, (name, action.dest)


def test_version_is_the_distribution_version() -> None:
    expected = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["version"]
    r = logixst("--version", timeout=20)
    assert (r.code, r.out.strip()) == (0, f"logixst {expected}")


@pytest.mark.parametrize("command", ["run", "check"])
def test_missing_file_has_one_wording(command: str, tmp_path: Path) -> None:
    r = logixst(command, tmp_path / "nope.st", timeout=20)
    assert r.code == 2
    line = r.one_line_error()
    assert line == f"logixst: error: {tmp_path / 'nope.st'}: no such file or directory"


def test_check_of_a_directory_without_program_files_is_a_usage_error(tmp_path: Path) -> None:
    (tmp_path / "notes.txt").write_text("not a program\n")
    r = logixst("check", tmp_path, timeout=20)
    assert r.code == 2 and r.out == ""
    r.one_line_error(str(tmp_path), "no .st, .rll, .L5X or .L5K files")


@pytest.mark.parametrize(
    ("flags", "message"),
    [
        # 1e300 s / 1 ms = 1e303 scans, beyond the 10,000,000-scan limit
        (
            ["--duration", "1e300"],
            "--duration 1e+300 s at a 1 ms scan period is too many scans (the limit is 10,000,000)",
        ),
        (
            ["--scans", "99999999999999999999"],
            "--scans 99999999999999999999 is outside 0..10,000,000",
        ),
        (["--scans", "10000001"], "--scans 10000001 is outside 0..10,000,000"),
        (["--scan-period", "1e-300"], "--scan-period 1e-300 ms is outside 0.1..2,000,000 ms"),
        (["--scan-period", "2000001"], "--scan-period 2e+06 ms is outside 0.1..2,000,000 ms"),
        (["--coarse-update", "0.000001"], "--coarse-update 1e-06 ms is outside 1..32 ms"),
        (["--coarse-update", "0.5"], "--coarse-update 0.5 ms is outside 1..32 ms"),
        (["--coarse-update", "33"], "--coarse-update 33 ms is outside 1..32 ms"),
        # 20 s at 0.1 ms = 200,000 scans is fine; 2,000 s at 0.1 ms = 20,000,000 is not
        (["--duration", "2000", "--scan-period", "0.1"], "the limit is 10,000,000"),
    ],
)
def test_option_ranges(prog: Path, flags: list[str], message: str) -> None:
    r = logixst("run", prog, *flags, timeout=20)
    assert r.code == 2 and r.out == ""
    r.one_line_error(message)


@pytest.mark.parametrize(
    "flags", [["--coarse-update", "1"], ["--coarse-update", "32"], ["--scans", "0"]]
)
def test_range_ends_are_accepted(prog: Path, flags: list[str]) -> None:
    r = logixst("run", prog, "--json", *flags, timeout=60)
    assert r.code == 0, r.err


@pytest.mark.parametrize("option", ["--trace", "--plot"])
def test_trace_and_plot_never_overwrite_an_input(prog: Path, option: str) -> None:
    before = prog.read_bytes()
    # the same file under another spelling of its path
    other = prog.parent / "." / prog.name
    r = logixst("run", prog, "--scans", "1", option, other, timeout=20)
    assert r.code == 2
    r.one_line_error(option, "would overwrite the input file")
    assert prog.read_bytes() == before


def test_trace_never_overwrites_the_tags_export(prog: Path, tmp_path: Path) -> None:
    export = ROOT / "samples" / "mixer.L5X"
    copy = tmp_path / "tags.L5X"
    copy.write_bytes(export.read_bytes())
    r = logixst("run", prog, "--tags", copy, "--trace", copy, timeout=20)
    assert r.code == 2
    r.one_line_error("--trace", "would overwrite the input file")
    assert copy.read_bytes() == export.read_bytes()


# ---- system flags in --watch and --set (SPEC 9.17)
def test_watch_first_scan_flag_in_st(prog: Path) -> None:
    r = logixst(
        "run", prog, "--scans", "2", "--watch", "S:FS", "--trace", prog.parent / "t.csv", timeout=60
    )
    assert r.code == 0, r.err
    # S:FS is set during the first scan only; the trace holds end-of-scan values (SPEC 9.2)
    rows = (prog.parent / "t.csv").read_text().splitlines()
    assert rows == ["time,S:FS", "0.0,1", "0.001,0"]


def test_watch_arithmetic_flag_of_an_st_program_is_a_clear_error(prog: Path) -> None:
    r = logixst("run", prog, "--watch", "S:N", timeout=20)
    assert r.code == 2
    r.one_line_error("--watch 'S:N' is available in ladder only", "no ladder routine")


def test_watch_arithmetic_flags_of_a_ladder_program(tmp_path: Path) -> None:
    decl = tmp_path / "tags.st"
    decl.write_text("VAR\n  a : DINT := 1;\n  d : DINT;\nEND_VAR\n")
    rll = tmp_path / "main.rll"
    rll.write_text("SUB(a,5,d);\n")  # 1 - 5 = -4: S:N set, S:Z clear
    r = logixst(
        "run",
        rll,
        decl,
        "--scans",
        "1",
        "--json",
        "--watch",
        "S:N",
        "--watch",
        "S:Z",
        "--watch",
        "d",
        timeout=60,
    )
    assert r.code == 0, r.err
    assert json.loads(r.out)["tags"] == {"S:N": True, "S:Z": False, "d": -4}


@pytest.mark.parametrize("suffix", [".st", ".rll"])
def test_set_of_a_system_flag_is_refused(tmp_path: Path, suffix: str) -> None:
    decl = tmp_path / "tags.st"
    decl.write_text("VAR\n  b : BOOL;\nEND_VAR\n")
    files = [decl]
    if suffix == ".rll":
        files.append(tmp_path / "main.rll")
        files[-1].write_text("XIC(S:FS)OTE(b);\n")
    r = logixst("run", *files, "--set", "S:FS=1", timeout=20)
    assert r.code == 2
    r.one_line_error("--set 'S:FS' is a status flag the controller sets")


def test_sample_headers_work_from_a_fresh_clone() -> None:
    # the plot extra is installed from the clone (the package is not on an index) and plots
    # go to the working directory, never into the tracked docs/img/
    for sample in sorted((ROOT / "samples").iterdir()):
        text = sample.read_text(encoding="utf-8", errors="replace")
        assert "pip install logixst[" not in text, sample.name
        assert "--plot docs/" not in text, sample.name


@pytest.mark.parametrize(
    ("value", "message"),
    [
        # 88 bits: no Logix integer holds it, as E133 says of the same literal in a program
        (
            "16#FFFFFFFFFFFFFFFFFFFFFF",
            "--set: integer literal 16#FFFFFFFFFFFFFFFFFFFFFF does not fit in 64 bits (LINT/ULINT)",
        ),
        ("9" * 5000, "--set: numeric literal of 5,000 characters: the limit is 1,000"),
        # 1e999 is +infinity: outside a DINT (-2**31 .. 2**31 - 1)
        ("1e999", "--set 'n' is DINT: inf is outside -2147483648..2147483647"),
    ],
    ids=["88-bit", "5000-digits", "infinite"],
)
def test_set_of_out_of_range_literals(prog: Path, value: str, message: str) -> None:
    r = logixst("run", prog, "--set", f"n={value}", timeout=20)
    assert r.code == 2
    r.one_line_error(message)
