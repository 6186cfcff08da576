"""Motion benchmark: N axes running continuous cubic time cams at 1 ms coarse update.

Run as a script (`python tests/benchmarks/bench_motion.py`) or with pytest pointed at this
file. Prints the per-update cost for 1, 8, 32 and 128 axes and their ratios, measured in
one run (absolute times vary between machines; the ratios are what to compare): first the
numpy core alone (MotionGroup.update), then whole programs (an ST program with one MATC
per axis on the Controller, 1 ms scans: planner update, axis tags written back, scan).
"""

from __future__ import annotations

import sys
import tempfile
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


def _program(n_axes: int) -> str:
    """The same cams as _group() as an ST program: 9-point cubic profile, one MATC per axis."""
    pts = ", ".join(
        f"(Master := {k / 8}, Slave := {10.0 * np.sin(np.pi * k / 8) ** 2:.9f}, SegmentType := 1)"
        for k in range(9)
    )
    axes = ", ".join(f"A{i}" for i in range(n_axes))
    ctls = ", ".join(f"c{i}" for i in range(n_axes))
    cams = "\n".join(
        f"  MATC(A{i}, c{i}, 0, prof, 1.0, {0.5 + 0.01 * i}, continuous, immediate, 0.0, none, 0);"
        for i in range(n_axes)
    )
    return (
        f"VAR\n  prof : CAM_PROFILE[9] := [{pts}];\n  {axes} : AXIS_VIRTUAL;\n"
        f"  {ctls} : MOTION_INSTRUCTION;\nEND_VAR\nIF S:FS THEN\n{cams}\nEND_IF;\n"
    )


def per_scan_seconds(n_axes: int, scans: int) -> float:
    """Wall time of one 1 ms scan with its planner update, through the Controller."""
    from interpreter.runtime.controller import Controller
    from interpreter.runtime.loader import load

    with tempfile.TemporaryDirectory() as d:
        p = Path(d) / f"cams{n_axes}.st"
        p.write_text(_program(n_axes))
        ctl = Controller(load([p]), scan_period_ms=1.0, coarse_update_ms=CUP * 1e3)
    ctl.prescan()
    for _ in range(10):
        assert ctl.scan()
    t0 = time.perf_counter()
    for _ in range(scans):
        ctl.scan()
    return (time.perf_counter() - t0) / scans


def whole_command_seconds(n_axes: int = 32, sim_seconds: float = 60.0) -> tuple[float, float]:
    """(wall, CPU) seconds of the whole `logixst run` command on the n-axis cam program
    for sim_seconds at 1 ms coarse update and 1 ms scans, start-up included. CPU time
    (user + system of the child process) is the steadier figure on a shared machine."""
    import os
    import resource
    import subprocess

    root = Path(__file__).resolve().parents[2]
    with tempfile.TemporaryDirectory() as d:
        p = Path(d) / f"cams{n_axes}.st"
        p.write_text(_program(n_axes))
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        t0 = time.perf_counter()
        subprocess.run(
            [sys.executable, "-m", "interpreter.cli", "run", str(p),
             "--duration", str(sim_seconds), "--coarse-update", str(CUP * 1e3)],
            check=True, capture_output=True, cwd=root,
            env={**os.environ, "PYTHONPATH": str(root)},
        )  # fmt: skip
        wall = time.perf_counter() - t0
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu


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
    wall_cmd, cpu_cmd = whole_command_seconds(32, sim_seconds)
    results["command_32_axes_60s_wall"] = wall_cmd
    results["command_32_axes_60s_cpu"] = cpu_cmd
    print(
        f"logixst run, 32 axes, {sim_seconds:.0f} s: {wall_cmd:.2f} s wall, {cpu_cmd:.2f} s CPU "
        f"({sim_seconds / cpu_cmd:.1f}x real time by CPU; goal 20x)"
    )
    print("whole program (Controller: update + tag write-back + scan), 1 ms scans:")
    base = None
    for n in (1, 8, 32, 128):
        cost = per_scan_seconds(n, 3000)
        results[f"per_scan_{n}"] = cost
        base = base or cost
        print(f"{n:4d} axes: {cost * 1e6:8.1f} us/scan    ratio to 1 axis {cost / base:5.2f}")
    return results


def test_bench_motion() -> None:
    r = main()
    assert r["wall_32_axes_60s"] < 10.0


if __name__ == "__main__":
    main()
