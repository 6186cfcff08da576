"""Issue 14: non-finite REALs in `--json` and `--trace` (docs/decisions/0132).

Parsed with a strict parser: json.loads with parse_constant raising, so the bare tokens
`Infinity`, `-Infinity` and `NaN` that Python writes by default fail the test.
Bound: one scan of a five-line program, 60 s wall, 2 GB address space (harness.logixst).
"""

from __future__ import annotations

import csv
import json
import math
from pathlib import Path
from typing import Any

from tests.hardening.harness import logixst

# 3.0E38 * 10.0 = 3.0E39, beyond the float32 maximum 3.4028235E38: +infinity;
# its negation -infinity; infinity - infinity is NaN (IEEE 754).
SOURCE = """VAR
  big : REAL := 3.0E38;
  pinf, ninf, nan : REAL;
  l : LREAL;
  arr : REAL[2];
  s : STRING;
END_VAR
pinf := big * 10.0;
ninf := -pinf;
nan := pinf - pinf;
l := pinf;
arr[1] := nan;
s := 'NaN';
"""


def strict(text: str) -> Any:
    def refuse(token: str) -> None:
        raise ValueError(f"non-JSON constant {token}")

    return json.loads(text, parse_constant=refuse)


def test_json_report_is_strict(tmp_path: Path) -> None:
    p = tmp_path / "inf.st"
    p.write_text(SOURCE)
    r = logixst("run", p, "--scans", "1", "--json", timeout=60)
    assert r.code == 0, r.err
    tags = strict(r.out)["tags"]
    assert tags["pinf"] == "Infinity" and tags["ninf"] == "-Infinity" and tags["nan"] == "NaN"
    assert tags["l"] == "Infinity"
    assert tags["big"] == 3.0000000054977558e38  # float32 nearest to 3.0E38, still a number


def test_structures_and_arrays_are_strict(tmp_path: Path) -> None:
    p = tmp_path / "inf.st"
    p.write_text(SOURCE)
    r = logixst("run", p, "--scans", "1", "--json", "--watch", "arr", "--watch", "s", timeout=60)
    assert r.code == 0, r.err
    assert strict(r.out)["tags"] == {"arr": [0.0, "NaN"], "s": "NaN"}


def test_trace_cells(tmp_path: Path) -> None:
    p = tmp_path / "inf.st"
    p.write_text(SOURCE)
    trace = tmp_path / "t.csv"
    r = logixst(
        "run", p, "--scans", "1", "--trace", trace, "--watch", "pinf", "--watch", "ninf",
        "--watch", "nan", "--watch", "arr", timeout=60,
    )  # fmt: skip
    assert r.code == 0, r.err
    rows = list(csv.reader(trace.open()))
    assert rows[0] == ["time", "pinf", "ninf", "nan", "arr"]
    assert rows[1][1:4] == ["Infinity", "-Infinity", "NaN"]
    assert strict(rows[1][4]) == [0.0, "NaN"]
    # the texts read back as the values they stand for
    assert float(rows[1][1]) == math.inf and float(rows[1][2]) == -math.inf
    assert math.isnan(float(rows[1][3]))
