"""Run a small program through `logixst run` and read the per-scan trace."""

from __future__ import annotations

import contextlib
import csv
import io
import json
from pathlib import Path
from typing import Any

from interpreter.cli import main


def trace(
    tmp_path: Path,
    source: str,
    suffix: str,
    scans: int,
    watch: list[str],
    period_ms: float = 1.0,
    files: dict[str, str] | None = None,
    expect_code: int = 0,
) -> tuple[list[dict[str, str]], dict[str, Any]]:
    """(one row per scan: watched value texts, the JSON report) of `scans` scans of `source`;
    `files` are further routine files (name -> text), callable by their stem."""
    prog = tmp_path / f"prog{suffix}"
    prog.write_text(source)
    paths = [str(prog)]
    for name, text in (files or {}).items():
        (tmp_path / name).write_text(text)
        paths.append(str(tmp_path / name))
    out_csv = tmp_path / "trace.csv"
    report = tmp_path / "report.json"
    argv = ["run", *paths, "--scans", str(scans), "--scan-period", str(period_ms)]
    argv += ["--json", "--trace", str(out_csv)]
    for w in watch:
        argv += ["--watch", w]
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        code = main(argv)
    assert code == expect_code, buf.getvalue()
    report.write_text(buf.getvalue())
    rows = []
    if out_csv.exists():
        with out_csv.open() as f:
            rows = list(csv.DictReader(f))
    return rows, json.loads(buf.getvalue())


def run_each_scan(
    tmp_path: Path, decl: str, body: str, scans: int, watch: list[str], period_ms: float
) -> list[dict[str, str]]:
    """Trace rows of an ST program that runs `body` each scan after `n := n + 1` (n = 1 on
    the first scan); the program must check clean."""
    src = f"VAR n : DINT; {decl} END_VAR\nn := n + 1;\n{body}\n"
    rows, report = trace(tmp_path, src, ".st", scans, watch, period_ms=period_ms)
    assert report["diagnostics"] == []
    return rows


def column(rows: list[dict[str, str]], name: str) -> list[float]:
    return [float(r[name]) for r in rows]


def int_column(rows: list[dict[str, str]], name: str) -> list[int]:
    return [int(r[name]) for r in rows]
