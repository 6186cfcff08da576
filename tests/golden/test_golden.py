"""Golden traces: tests/golden/<name>/{program.st, manifest.toml, expected.csv}.

manifest.toml: `scans`, `scan_period` (ms), `watch` (list of tag references) and an optional
`[inputs]` table `scan = { tag = value, ... }` applied just before that scan runs (scan 0 is
the first normal scan). Rows are compared per scan: time and integers/BOOLs exactly, REALs
with a relative tolerance of 1e-6. `pytest --regen-golden` rewrites expected.csv (review every
value by hand before committing).
"""

from __future__ import annotations

import csv
import math
import tomllib
from pathlib import Path

import pytest

from interpreter.cli import _csv_value, parse_set_value
from interpreter.diagnostics import has_errors
from interpreter.runtime.controller import Controller
from interpreter.runtime.loader import load

HERE = Path(__file__).parent
CASES = sorted(p.name for p in HERE.iterdir() if (p / "manifest.toml").is_file())


def _input_value(v: object) -> object:
    if isinstance(v, bool):
        return 1 if v else 0
    if isinstance(v, str):
        return parse_set_value(v)
    return v


def simulate(case: Path) -> list[list[str]]:
    """Header and one row per scan, as strings, like `logixst run --trace`."""
    manifest = tomllib.loads((case / "manifest.toml").read_text())
    loaded = load([case / "program.st"])
    assert not has_errors(loaded.diagnostics), [d.text() for d in loaded.diagnostics]
    period = float(manifest.get("scan_period", 1.0))
    ctl = Controller(loaded, scan_period_ms=period)
    watches = [(w, *ctl.reference(w)) for w in manifest["watch"]]
    inputs = {int(k): v for k, v in manifest.get("inputs", {}).items()}
    rows = [["time", *manifest["watch"]]]
    ctl.prescan()
    for k in range(int(manifest["scans"])):
        for tag, value in inputs.get(k, {}).items():
            ctl.reference(tag)[2](_input_value(value))
        assert ctl.scan(), ctl.faults()
        rows.append(
            [repr(k * period / 1000.0)] + [str(_csv_value(g(), t)) for _, g, t, _ in watches]
        )
    return rows


def _same(a: str, b: str) -> bool:
    if a == b:
        return True
    try:
        x, y = float(a), float(b)
    except ValueError:
        return False
    if math.isnan(x) and math.isnan(y):
        return True
    return math.isclose(x, y, rel_tol=1e-6, abs_tol=1e-12)


@pytest.mark.parametrize("name", CASES)
def test_golden(name: str, request: pytest.FixtureRequest) -> None:
    case = HERE / name
    got = simulate(case)
    expected_path = case / "expected.csv"
    if request.config.getoption("--regen-golden"):
        with expected_path.open("w", newline="") as fh:
            csv.writer(fh, lineterminator="\n").writerows(got)
        pytest.skip(f"regenerated {expected_path}")
    expected = list(csv.reader(expected_path.open()))
    assert got[0] == expected[0], "header"
    assert len(got) == len(expected), "number of scans"
    for k, (g, e) in enumerate(zip(got[1:], expected[1:], strict=True)):
        bad = [
            (col, gv, ev)
            for col, gv, ev in zip(expected[0], g, e, strict=True)
            if not _same(gv, ev)
        ]
        assert not bad, f"scan {k}: (column, got, expected) {bad}"


def test_at_least_three_goldens() -> None:
    assert len(CASES) >= 3


def test_comparison_tolerance() -> None:
    assert _same("0.30000001192092896", "0.3000000119")  # REAL within 1e-6 relative
    assert not _same("1.0000001192092896", "1.0000021")  # 2e-6 relative: a real difference
    assert not _same("3", "4")
    assert _same("nan", "nan")
    assert not _same("1", "true")
