"""Issue 14: literals, declarations, nesting, motion configuration and compile size, through
the real entry point. Each limit is reported by `check` (exit 1) and by `run` (exit 1, same
diagnostic, nothing runs) at file:line:col, and the program just inside it runs.

Bounds: every case is held to the 2 GB address space of harness.logixst and to the wall
time given as `timeout` (the slowest, a 10,000-element rung, compiles in about 5 s alone on
this machine; the bound allows for a busy machine).
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from tests.hardening.harness import logixst

DECL = "VAR\n  x : DINT;\n  y : LINT;\n  s : STRING;\n  b : BOOL;\n  o : BOOL;\nEND_VAR\n"


def both(path: Path, *extra: str | Path, timeout: float = 60) -> tuple[str, str]:
    """`check` and `run` of the same files: both exit 1 with the same diagnostic lines."""
    c = logixst("check", path, *extra, timeout=timeout)
    r = logixst("run", path, *extra, "--scans", "1", timeout=timeout)
    assert c.code == 1 and r.code == 1, (c.err, r.err)
    assert "Traceback" not in c.err + r.err
    diag_lines = c.out.strip().splitlines()[:-1]  # the last line is the summary
    assert r.err.strip().splitlines() == diag_lines
    assert r.out == ""
    return c.out, r.err


def write(tmp_path: Path, name: str, text: str) -> Path:
    p = tmp_path / name
    p.write_text(text)
    return p


# ---- literals
def test_a_100000_digit_literal(tmp_path: Path) -> None:
    p = write(tmp_path, "huge.st", DECL + "x := " + "9" * 100_000 + ";\n")
    out, _ = both(p)
    # line 8 (after the 7-line VAR block), column 6 after `x := `
    assert out.splitlines()[0] == (
        f"{p}:8:6: error E133 numeric literal of 100,000 characters: the limit is 1,000"
    )


@pytest.mark.parametrize(
    ("literal", "message"),
    [
        # 22 hex digits = 88 bits: wider than any Logix integer (LINT/ULINT are 64 bits)
        (
            "16#FFFFFFFFFFFFFFFFFFFFFF",
            "integer literal 16#FFFFFFFFFFFFFFFFFFFFFF does not fit in 64 bits (LINT/ULINT)",
        ),
        # 29 digits > 2**63 - 1 = 9223372036854775807 (the largest LINT)
        (
            "99999999999999999999999999999",
            "integer literal 99999999999999999999999999999 is out of range: the largest is 9223372036854775807 (LINT)",
        ),
        # 2**64 = 18446744073709551616 is one past the largest ULINT
        (
            "18446744073709551616UL",
            "integer literal 18446744073709551616UL is out of range: the largest is 18446744073709551615 (ULINT)",
        ),
    ],
)
def test_out_of_range_integer_literals(tmp_path: Path, literal: str, message: str) -> None:
    p = write(tmp_path, "lit.st", DECL + f"y := {literal};\n")
    out, _ = both(p)
    assert out.splitlines()[0] == f"{p}:8:6: error E133 {message}"


def test_literals_at_the_ends_of_lint_and_ulint_run(tmp_path: Path) -> None:
    src = DECL.replace("y : LINT;", "y : LINT;\n  u : ULINT;") + (
        "y := 9223372036854775807;\nu := 18446744073709551615UL;\n"
    )
    p = write(tmp_path, "ends.st", src)
    r = logixst("run", p, "--scans", "1", "--json", "--watch", "y", "--watch", "u", timeout=60)
    assert r.code == 0, r.err
    assert json.loads(r.out)["tags"] == {"y": 2**63 - 1, "u": 2**64 - 1}


def test_a_104_character_string_literal(tmp_path: Path) -> None:
    p = write(tmp_path, "str.st", DECL + "s := '" + "a" * 104 + "';\n")
    out, _ = both(p)
    assert out.splitlines()[0] == (
        f"{p}:8:6: error E133 string literal of 104 characters: a STRING holds 82"
    )


def test_an_82_character_string_literal_fits(tmp_path: Path) -> None:
    p = write(tmp_path, "str.st", DECL + "s := '" + "a" * 82 + "';\n")
    r = logixst("run", p, "--scans", "1", "--json", "--watch", "s", timeout=60)
    assert r.code == 0, r.err
    assert json.loads(r.out)["tags"] == {"s": "a" * 82}


# ---- declarations and storage
@pytest.mark.parametrize(
    ("decl", "col", "count"),
    [
        ("a : DINT[1000000000];", 7, "1,000,000,000"),
        # ARRAY[0..2000000000] holds 2,000,000,001 elements; the type starts at column 7
        ("a : ARRAY[0..2000000000] OF REAL;", 31, "2,000,000,001"),
        ("a : DINT[1000,1000,1000];", 7, "1,000,000,000"),
    ],
)
def test_huge_arrays(tmp_path: Path, decl: str, col: int, count: str) -> None:
    p = write(tmp_path, "arr.st", f"VAR\n  {decl}\nEND_VAR\n")
    out, _ = both(p, timeout=30)  # nothing is allocated: far below the 2 GB bound
    assert out.splitlines()[0] == (
        f"{p}:2:{col}: error E132 array of {count} elements: the limit is 2,000,000 per array"
    )


def test_total_tag_storage(tmp_path: Path) -> None:
    # 1,500,000 + 1,500,000 DINTs = 3,000,000 values; 20,000 STRINGs of 83 values each
    # (LEN + 82 characters) add 1,660,000: 4,660,000 > 4,000,000 at tag c
    src = "VAR\n  a : DINT[1500000];\n  b : DINT[1500000];\n  c : STRING[20000];\nEND_VAR\n"
    p = write(tmp_path, "tot.st", src)
    out, _ = both(p, timeout=30)
    assert out.splitlines()[0] == (
        f"{p}:4:3: error E132 tag 'c' takes the program's storage to 4,660,000 values: "
        "the limit is 4,000,000 for all tags together"
    )


# ---- nesting: the same limit in check and run
def test_120_nested_ifs(tmp_path: Path) -> None:
    p = write(tmp_path, "ifs.st", DECL + "IF b THEN\n" * 120 + "x := 1;\n" + "END_IF;\n" * 120)
    out, _ = both(p)
    # the 65th IF is on line 7 + 65 = 72
    assert out.splitlines()[0] == (
        f"{p}:72:1: error E132 statement blocks nested 65 deep: the limit is 64"
    )


def test_64_nested_blocks_with_16_loops_run(tmp_path: Path) -> None:
    # 8 FOR + 1 WHILE + 7 REPEAT = 16 loops, 24 IF + 24 CASE: 64 blocks; x counts once
    decl = "VAR\n  x : DINT;\n  b : BOOL := 1;\n  i : DINT[8];\nEND_VAR\n"
    body = (
        "".join(f"FOR i[{k}] := 0 TO 0 DO\n" for k in range(8))
        + "IF b THEN\n" * 24
        + "CASE x OF 0:\n" * 24
        + "WHILE b DO\nb := 0;\n"
        + "REPEAT\n" * 7
        + "x := x + 1;\n"
        + "UNTIL TRUE END_REPEAT;\n" * 7
        + "END_WHILE;\n"
        + "END_CASE;\n" * 24
        + "END_IF;\n" * 24
        + "END_FOR;\n" * 8
    )
    p = write(tmp_path, "mix.st", decl + body)
    r = logixst("run", p, "--scans", "1", "--json", "--watch", "x", timeout=60)
    assert r.code == 0, r.err
    assert json.loads(r.out)["tags"] == {"x": 1}


def test_17_nested_loops(tmp_path: Path) -> None:
    decl = "VAR\n  x : DINT;\n  i : DINT[17];\nEND_VAR\n"
    body = (
        "".join(f"FOR i[{k}] := 0 TO 0 DO\n" for k in range(17)) + "x := 1;\n" + "END_FOR;\n" * 17
    )
    p = write(tmp_path, "loops.st", decl + body)
    out, _ = both(p)
    # the 17th FOR is on line 4 + 17 = 21
    assert out.splitlines()[0] == f"{p}:21:1: error E132 loops nested 17 deep: the limit is 16"


def test_flat_sum_of_20000_terms(tmp_path: Path) -> None:
    p = write(tmp_path, "sum.st", DECL + "x := " + " + ".join(["x"] * 20_000) + ";\n")
    out, _ = both(p, timeout=90)
    line = out.splitlines()[0]
    assert line.startswith(f"{p}:8:") and line.endswith(
        "error E132 expression nested more than 5,000 operations deep: the limit is 5,000 "
        "(split it with intermediate tags)"
    )


def test_sum_of_5000_terms_runs(tmp_path: Path) -> None:
    # x := 1 + 1 + ... (5,000 ones) = 5,000; 4,999 additions, within the 5,000 limit
    p = write(tmp_path, "sum.st", DECL + "x := " + " + ".join(["1"] * 5_000) + ";\n")
    r = logixst("run", p, "--scans", "1", "--json", "--watch", "x", timeout=90)
    assert r.code == 0, r.err
    assert json.loads(r.out)["tags"] == {"x": 5000}


# ---- ladder size: linear compile or a limit
LADDER_TAGS = "VAR\n  b : BOOL := 1;\n  o : BOOL;\n  d : DINT;\nEND_VAR\n"


@pytest.mark.parametrize(
    ("rung", "message"),
    [
        ("XIC(b)" * 16_000 + "OTE(o);", "rung of more than 10,000 instructions and branches"),
        ("[" + ",".join(["XIC(b)"] * 125_000) + "]OTE(o);", "rung of more than 10,000"),
        ("ADD(d,1,d)" * 100_000 + ";", "rung of more than 10,000"),
        (
            "[XIC(b)," * 10_000 + "XIC(b)" + "]" * 10_000 + "OTE(o);",
            "branches nested 1001 deep: the limit is 1000",
        ),
    ],
    ids=["16k-series", "125k-parallel", "100k-ADD", "10k-nested"],
)
def test_oversized_rungs(tmp_path: Path, rung: str, message: str) -> None:
    tags = write(tmp_path, "tags.st", LADDER_TAGS)
    p = write(tmp_path, "main.rll", rung + "\n")
    c = logixst("check", p, tags, timeout=60)
    r = logixst("run", p, tags, "--scans", "1", timeout=60)
    assert c.code == r.code == 1, (c.err, r.err)
    assert f"{p}:1:" in c.out and message in c.out
    assert r.err.strip().splitlines() == c.out.strip().splitlines()[:-1]


@pytest.mark.parametrize(
    ("rung", "expected"),
    [
        # 9,999 contacts on b (TRUE) in series: o is TRUE
        ("XIC(b)" * 9_999 + "OTE(o);", {"o": True, "d": 0}),
        # 1 branch + 9,998 legs + OTE = 10,000 elements: o is TRUE
        ("[" + ",".join(["XIC(b)"] * 9_998) + "]OTE(o);", {"o": True, "d": 0}),
        # 9,999 ADDs in one rung, one scan: d = 9,999
        ("ADD(d,1,d)" * 9_999 + ";", {"o": False, "d": 9_999}),
        # 1,000 nested branches (the limit), each with a second leg: o follows b
        ("[XIC(b)," * 999 + "XIC(b)" + "]" * 999 + "OTE(o);", {"o": True, "d": 0}),
    ],
    ids=["series", "parallel", "ADD", "nested"],
)
def test_rungs_at_the_limit_compile_in_seconds(tmp_path: Path, rung: str, expected: dict) -> None:
    tags = write(tmp_path, "tags.st", LADDER_TAGS)
    p = write(tmp_path, "main.rll", rung + "\n")
    r = logixst(
        "run", p, tags, "--scans", "1", "--json", "--watch", "o", "--watch", "d", timeout=60
    )
    assert r.code == 0, r.err
    assert json.loads(r.out)["tags"] == expected
    assert r.seconds < 60


# ---- motion configuration
def test_motion_configuration_values(tmp_path: Path) -> None:
    src = (
        "VAR\n"
        "  grp : MOTION_GROUP := (CoarseUpdatePeriod := 500);\n"
        "  X : AXIS_VIRTUAL := (MaximumSpeed := -100.0, MaximumAccel := 1.0E999);\n"
        "  Y : AXIS_VIRTUAL := (MaximumDecel := -1.0, MaximumAccelJerk := -2.0, PositionUnwind := -1.0);\n"
        "  XY : COORDINATE_SYSTEM := (Axes := [X, Y], MaximumSpeed := -1.0);\n"
        "END_VAR\n"
    )
    p = write(tmp_path, "mc.st", src)
    out, _ = both(p)
    codes = [line.split(": error ")[1] for line in out.splitlines()[:-1]]
    assert codes == [
        "E118 MOTION_GROUP.CoarseUpdatePeriod must be 1000 to 32000 microseconds, not 500",
        "E118 AXIS_VIRTUAL.MaximumSpeed must be a finite number >= 0 (0: not configured), not -100",
        # 1.0E999 is beyond any float: +infinity
        "E118 AXIS_VIRTUAL.MaximumAccel must be a finite number >= 0 (0: not configured), not inf",
        "E118 AXIS_VIRTUAL.MaximumDecel must be a finite number >= 0 (0: not configured), not -1",
        "E118 AXIS_VIRTUAL.MaximumAccelJerk must be a finite number >= 0 (0: not configured), not -2",
        "E118 AXIS_VIRTUAL.PositionUnwind must be a finite number >= 0 (0: linear, no unwind), not -1",
        "E118 COORDINATE_SYSTEM.MaximumSpeed must be a finite number >= 0 (0: not configured), not -1",
    ]
    assert out.splitlines()[1].startswith(f"{p}:3:40: ")


# ---- a large straight-line ST file
def test_one_megabyte_of_straight_line_st(tmp_path: Path) -> None:
    # 16,000 statements of about 63 bytes (1.02 MB). acc[0] is the target of every 100th
    # statement (i = 0, 100, ..., 15,900: 160 of them), each adding rate * 0.001 + offset[0]
    # = 2.0 * 0.001 + 0 = 0.002: 160 * 0.002 = 0.32, within float32 rounding of the 160
    # additions (each at most half an ulp of 0.32, 1.5e-8: under 1e-5 in all)
    decl = "VAR\n  acc : REAL[100];\n  offset : REAL[50];\n  rate : REAL := 2.0;\nEND_VAR\n"
    lines = "".join(
        f"acc[{i % 100}] := acc[{i % 100}] + rate * 0.001 + offset[{i % 50}];   // step {i:05d}\n"
        for i in range(16_000)
    )
    p = write(tmp_path, "big.st", decl + lines)
    assert p.stat().st_size > 1_000_000
    r = logixst("run", p, "--scans", "1", "--json", "--watch", "acc[0]", timeout=120)
    assert r.code == 0, r.err
    assert abs(json.loads(r.out)["tags"]["acc[0]"] - 0.32) < 1e-5


def test_routine_statement_limit(tmp_path: Path) -> None:
    # 50,001 statements: the 50,001st (line 7 + 50,001 = 50,008) crosses the 50,000 limit
    p = write(tmp_path, "many.st", DECL + "x := 1;\n" * 50_001)
    out, _ = both(p, timeout=90)
    assert out.splitlines()[0] == (
        f"{p}:50008:1: error E132 routine of more than 50,000 statements: the limit is 50,000 "
        "(split it into several routines)"
    )
