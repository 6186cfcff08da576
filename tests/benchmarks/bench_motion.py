"""Motion core benchmark: N axes running continuous cubic time cams at 1 ms coarse update.

Run as a script (`python tests/benchmarks/bench_motion.py`) or with pytest pointed at this
file. Prints the per-update cost for 1, 8, 32 and 128 axes and their ratios, measured in
one run (absolute times vary between machines; the ratios are what to compare).
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))  # run from anywhere

from interpreter.motion import (  # noqa: E402
    ExecutionMode,
    MotionGroup,
    calculate_cam_profile,
)

CUP = 0.001


def _group(n_axes: int) -> MotionGroup:
    g = MotionGroup(CUP)
    # a smooth cyclic cam (rise and return, cubic spline) and a second shape for variety
    x = np.linspace(0.0, 1.0, 9)
    profiles = [
        calculate_cam_profile(x, 10.0 * np.sin(np.pi * x) ** 2, [1] * 9),
        calculate_cam_profile(x, 5.0 * x + np.sin(2 * np.pi * x), [1] * 9, 5.0, 5.0),
    ]
    for i in range(n_axes):
        a = g.add_axis(f"ax{i}")
        r = g.start_time_cam(
            a, profiles[i % 2], time_scaling=0.5 + 0.01 * i,
            execution_mode=ExecutionMode.CONTINUOUS,
        )  # fmt: skip
        assert r.ok
    g.update()
    return g


def per_update_seconds(n_axes: int, updates: int) -> float:
    g = _group(n_axes)
    t0 = time.perf_counter()
    for _ in range(updates):
        g.update()
    return (time.perf_counter() - t0) / updates


def main() -> dict[str, float]:
    results: dict[str, float] = {}
    sim_seconds = 60.0
    updates = round(sim_seconds / CUP)
    g = _group(32)
    t0 = time.perf_counter()
    for _ in range(updates):
        g.update()
    wall = time.perf_counter() - t0
    results["wall_32_axes_60s"] = wall
    print(
        f"32 axes, {sim_seconds:.0f} s simulated at {CUP * 1e3:.0f} ms: {wall:.2f} s wall "
        f"({'OK' if wall < 10 else 'TOO SLOW'}, budget 10 s)"
    )
    base = None
    for n in (1, 8, 32, 128):
        cost = per_update_seconds(n, 5000)
        results[f"per_update_{n}"] = cost
        base = base or cost
        print(f"{n:4d} axes: {cost * 1e6:8.1f} us/update  ratio to 1 axis {cost / base:5.2f}")
    return results


def test_bench_motion() -> None:
    r = main()
    assert r["wall_32_axes_60s"] < 10.0


if __name__ == "__main__":
    main()
