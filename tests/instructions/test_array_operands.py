"""Whole-array operands of a program routine (COP on array tags) read and write the live
tag storage in every scan: the routine makes each such array reference once, when it is
translated (codegen.Translator with the controller's tags), not at each execution."""

from __future__ import annotations

from pathlib import Path

from interpreter.runtime.controller import Controller
from interpreter.runtime.loader import load

PROGRAM = """VAR
  a, b, c : DINT[3];
  k : DINT;
END_VAR
k := k + 1;
b[0] := k; b[1] := 10 * k; b[2] := 100 * k;
COP(b, a, 3);
a[1] := a[1] + 1;
COP(a, c, 3);
"""


def test_whole_array_operands_follow_the_tags_scan_after_scan(tmp_path: Path) -> None:
    p = tmp_path / "arrays.st"
    p.write_text(PROGRAM)
    ctl = Controller(load([p]))
    assert ctl.prescan()
    for k in (1, 2, 3):
        assert ctl.scan()
        # scan k: b = [k, 10k, 100k] copied into a, a[1] incremented, a copied into c
        got = [ctl.reference(f"c[{i}]")[0]() for i in range(3)]
        assert got == [k, 10 * k + 1, 100 * k]
