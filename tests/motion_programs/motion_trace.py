"""Helpers for the motion program tests: run ST motion programs through `logixst run --trace` and read the trace back.

Timing used by every test (SPEC 9.1-9.3): scan k starts at t = k ms (1 ms scans), the planner
updates at t = 0, 2, 4, ... ms before the scan starting then, and an instruction executed
in scan k takes effect at the next update (its own clock is 0 there). A trace row shows the
values at the end of its scan, i.e. after the latest update at or before the row's time.
"""

from __future__ import annotations

import csv
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path

import pytest

from interpreter.cli import main

CUP = 0.002  # default coarse update period, s
SCAN = 0.001  # default scan period, s


@dataclass
class Trace:
    names: list[str]
    rows: list[list[float]]
    code: int
    err: str

    def col(self, name: str) -> list[float]:
        j = self.names.index(name)
        return [r[j] for r in self.rows]

    def time(self) -> list[float]:
        return self.col("time")

    def at(self, t: float, name: str) -> float:
        """Value of `name` in the row of the scan starting at t seconds."""
        k = round(t / self.rows[1][0]) if len(self.rows) > 1 else 0
        assert abs(self.rows[k][0] - t) < 1e-9, (t, self.rows[k][0])
        return self.rows[k][self.names.index(name)]

    def first(self, name: str, pred: Callable[[float], bool]) -> float:
        """Time of the first row where pred(value) holds."""
        for r in self.rows:
            if pred(r[self.names.index(name)]):
                return r[0]
        raise AssertionError(f"{name} never satisfied the condition")

    def check(
        self,
        name: str,
        expected: Callable[[float], float],
        tol: float,
        t0: float = 0.0,
        t1: float = math.inf,
    ) -> None:
        """Every row with t0 <= time <= t1 is within tol of expected(time)."""
        j = self.names.index(name)
        worst = 0.0
        for r in self.rows:
            if t0 - 1e-9 <= r[0] <= t1 + 1e-9:
                err = abs(r[j] - expected(r[0]))
                assert err <= tol, (
                    f"{name} at t={r[0]}: {r[j]} vs expected {expected(r[0])} (tol {tol})"
                )
                worst = max(worst, err)


class Runner:
    def __init__(self, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
        self.tmp = tmp_path
        self.capsys = capsys

    def trace(
        self,
        src: str,
        watch: Sequence[str],
        scans: int,
        args: Sequence[str] = (),
        name: str = "prog.st",
    ) -> Trace:
        prog = self.tmp / name
        prog.write_text(src)
        out = self.tmp / "trace.csv"
        argv = ["run", str(prog), "--scans", str(scans), "--trace", str(out), "--json", *args]
        for w in watch:
            argv += ["--watch", w]
        self.capsys.readouterr()
        code = main(argv)
        cap = self.capsys.readouterr()
        assert "Traceback" not in cap.err
        assert code == 0, (code, cap.err, cap.out[:2000])
        with out.open() as fh:
            rows = list(csv.reader(fh))
        return Trace(rows[0], [[float(x) for x in r] for r in rows[1:]], code, cap.err)

    def run(self, src: str, argv: Sequence[str] = ()) -> tuple[int, str, str]:
        prog = self.tmp / "prog.st"
        prog.write_text(src)
        self.capsys.readouterr()
        code = main(["run", str(prog), *argv])
        cap = self.capsys.readouterr()
        return code, cap.out, cap.err


def ramp(t: float, t0: float, t1: float, rate: float) -> float:
    """rate * (t - t0) clipped to [t0, t1]: a constant-velocity stretch."""
    return rate * (min(max(t, t0), t1) - t0)
