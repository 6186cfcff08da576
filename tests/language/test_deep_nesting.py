"""Deeply nested programs through the real command (`python -m interpreter.cli`, as the
`logixst` script runs it): long sums, NOT chains, nested branches and parentheses must run,
and what is beyond the limits must be refused in one line, never with a traceback."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def logixst(tmp_path: Path, name: str, text: str, *args: str) -> subprocess.CompletedProcess[str]:
    path = tmp_path / name
    path.write_text(text)
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    return subprocess.run(
        [sys.executable, "-m", "interpreter.cli", args[0], str(path), *args[1:]],
        capture_output=True,
        text=True,
        env=env,
        check=False,
        timeout=120,
    )


def watched(done: subprocess.CompletedProcess[str]) -> dict:
    assert done.returncode == 0, done.stderr[-2000:]
    assert "Traceback" not in done.stderr
    return json.loads(done.stdout)["tags"]  # type: ignore[no-any-return]


def test_a_sum_of_400_terms_runs(tmp_path: Path) -> None:
    # x := a + a + ... + a with 400 terms and a = 3: 400 x 3 = 1200. The left-deep AST is 400
    # levels deep (beyond Python's default recursion limit in the checker) and its generated
    # expression would nest 400 parentheses (Python's parser stops at 200).
    text = "VAR x : DINT; a : DINT := 3; END_VAR\nx := " + " + ".join(["a"] * 400) + ";\n"
    assert watched(
        logixst(tmp_path, "sum.st", text, "run", "--scans", "1", "--json", "--watch", "x")
    ) == {"x": 1200}


def test_a_long_not_chain_runs(tmp_path: Path) -> None:
    # 3,001 NOTs applied to FALSE: an odd count gives TRUE
    text = "VAR x : BOOL; a : BOOL; END_VAR\nx := " + "NOT " * 3001 + "a;\n"
    assert watched(
        logixst(tmp_path, "nots.st", text, "run", "--scans", "1", "--json", "--watch", "x")
    ) == {"x": True}


def test_branches_nested_500_deep_run(tmp_path: Path) -> None:
    # [[[...XIC(a)...]]]OTE(b): each branch has one leg, so b follows a
    text = "VAR a : BOOL := 1; b : BOOL; END_VAR\n" + "[" * 500 + "XIC(a)" + "]" * 500 + "OTE(b);\n"
    assert watched(
        logixst(tmp_path, "deep.rll", text, "run", "--scans", "1", "--json", "--watch", "b")
    ) == {"b": True}


def test_cpt_with_2000_nested_parentheses_runs(tmp_path: Path) -> None:
    # parentheses leave no AST level, but the text is 2,000 levels deep: 7 - 2 = 5
    text = (
        "VAR x : DINT; a : DINT := 7; END_VAR\nCPT(x," + "(" * 2000 + "a - 2" + ")" * 2000 + ");\n"
    )
    assert watched(
        logixst(tmp_path, "cpt.rll", text, "run", "--scans", "1", "--json", "--watch", "x")
    ) == {"x": 5}


def test_blocks_too_deep_for_the_vm_are_refused_in_one_line(tmp_path: Path) -> None:
    # 150 nested IFs: the 65th is beyond the 64-block limit (docs/limits.md), refused by the
    # verification that `check` runs too, at its place: line 1 is the VAR line, so IF number
    # 65 is on line 66
    text = "VAR x : BOOL; END_VAR\n" + "IF x THEN\n" * 150 + "x := 1;\n" + "END_IF;\n" * 150
    done = logixst(tmp_path, "ifs.st", text, "run", "--scans", "1")
    assert done.returncode == 1
    assert "Traceback" not in done.stderr
    assert done.stderr.strip().splitlines() == [
        f"{tmp_path / 'ifs.st'}:66:1: error E132 statement blocks nested 65 deep: the limit is 64"
    ]


def test_beyond_the_expression_depth_limit_is_one_diagnostic(tmp_path: Path) -> None:
    # 40,000 unary minus signs: the AST is 40,001 levels deep; the limit pass measures it
    # without recursion and reports the node at depth 5,001. `x := ` takes columns 1-5, so
    # the minus sign at depth k is at column 5 + k: depth 5,001 is column 5,006.
    text = "VAR x : DINT; a : DINT; END_VAR\nx := " + "-" * 40000 + "a;\n"
    done = logixst(tmp_path, "neg.st", text, "check")
    assert done.returncode == 1
    assert done.stdout.strip().splitlines() == [
        f"{tmp_path / 'neg.st'}:2:5006: error E132 expression nested more than 5,000 operations"
        " deep: the limit is 5,000 (split it with intermediate tags)",
        "1 error(s), 0 warning(s)",
    ]
