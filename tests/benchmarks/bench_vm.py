"""VM benchmark: one DINT/REAL arithmetic loop as ST on the Controller vs the same in plain Python.

Run as a script (`python tests/benchmarks/bench_vm.py [ITERATIONS]`) or with pytest pointed
at this file. Both versions run in the same process, one after the other, best of 5, so
the ratio holds up on a noisy machine even when the absolute times do not. Target
(docs/performance.md): ST at most 10x slower than plain Python.

The plain Python version uses Python ints and doubles. It does not wrap DINTs or round to
float32, so the ratio includes the cost of Logix semantics. A third timing ("python+logix")
adds the same wrap and float32 helpers by hand, to show how much of the gap they explain.
"""

from __future__ import annotations

import sys
import tempfile
import time
from array import array
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))  # run from anywhere

from interpreter.runtime.controller import Controller  # noqa: E402
from interpreter.runtime.loader import load  # noqa: E402

TARGET_RATIO = 10.0

ST_SOURCE = """VAR
  i, acc, n : DINT;
  x, y : REAL;
END_VAR
acc := 0;
x := 0.0;
y := 0.0;
FOR i := 1 TO n DO
  acc := acc + (i * 3) MOD 7;
  x := x * 0.5 + 1.25;
  y := y + x / 4.0;
  IF acc > 1000000 THEN
    acc := acc - 1000000;
  END_IF;
END_FOR;
"""


def plain(n: int) -> tuple[int, float]:
    acc, x, y = 0, 0.0, 0.0
    for i in range(1, n + 1):
        acc = acc + (i * 3) % 7
        x = x * 0.5 + 1.25
        y = y + x / 4.0
        if acc > 1000000:
            acc = acc - 1000000
    return acc, y


_BUF = array("f", [0.0])


def _f32(v: float) -> float:
    _BUF[0] = v  # storing into a float32 array rounds to single precision
    return _BUF[0]


def _wrap32(v: int) -> int:
    return ((v + 0x80000000) & 0xFFFFFFFF) - 0x80000000


def plain_logix(n: int) -> tuple[int, float]:
    acc, x, y = 0, 0.0, 0.0
    for i in range(1, n + 1):
        acc = _wrap32(acc + _wrap32(i * 3) % 7)
        x = _f32(_f32(x * 0.5) + 1.25)
        y = _f32(y + _f32(x / 4.0))
        if acc > 1000000:
            acc = _wrap32(acc - 1000000)
    return acc, y


def best_of(fn, repeat: int = 5) -> float:  # type: ignore[no-untyped-def]
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def bench(n: int = 200_000) -> dict[str, float]:
    with tempfile.TemporaryDirectory() as d:
        path = Path(d) / "loop.st"
        path.write_text(ST_SOURCE)
        loaded = load([path])
    assert not loaded.diagnostics, loaded.diagnostics
    ctl = Controller(loaded, watchdog=100 * n)
    ctl.prescan()
    _, _, set_n = ctl.reference("n")
    set_n(n)
    get_acc, _, _ = ctl.reference("acc")
    get_y, _, _ = ctl.reference("y")

    def st_scan() -> None:
        assert ctl.scan()

    t_st = best_of(st_scan)
    t_py = best_of(lambda: plain(n))
    t_pl = best_of(lambda: plain_logix(n))
    acc, y = plain(n)
    assert get_acc() == acc
    assert abs(get_y() - y) <= 1e-6 * abs(y)  # float32 vs double: same value to ~7 digits
    return {
        "n": n,
        "st": t_st,
        "python": t_py,
        "python_logix": t_pl,
        "ratio": t_st / t_py,
        "ratio_logix": t_st / t_pl,
    }


def report(r: dict[str, float]) -> str:
    verdict = "meets" if r["ratio"] <= TARGET_RATIO else "misses"
    return (
        f"{r['n']:.0f} loop iterations, best of 5\n"
        f"  ST on the Controller : {r['st'] * 1e3:8.1f} ms ({r['st'] / r['n'] * 1e9:6.0f} ns/iteration)\n"
        f"  plain Python         : {r['python'] * 1e3:8.1f} ms ({r['python'] / r['n'] * 1e9:6.0f} ns/iteration)\n"
        f"  Python + wrap/float32: {r['python_logix'] * 1e3:8.1f} ms\n"
        f"  ratio ST / Python = {r['ratio']:.2f}x ({verdict} the {TARGET_RATIO:.0f}x target); "
        f"ST / Python+wrap/float32 = {r['ratio_logix']:.2f}x"
    )


def test_vm_benchmark() -> None:
    print("\n" + report(bench()))


if __name__ == "__main__":
    print(report(bench(int(sys.argv[1]) if len(sys.argv) > 1 else 200_000)))
