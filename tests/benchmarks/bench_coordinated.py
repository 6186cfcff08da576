"""Coordinated motion benchmark (issue 12): a 1,000-move MCLM/MCCM path in a 3-axis
coordinate system at 1 ms coarse update, and 16 coordinate systems running at once.

Run as a script (`python tests/benchmarks/bench_coordinated.py`). Prints simulated time
over wall time (x real time) measured in one run:
- core: MotionGroup.update with the path set; moves are queued whenever the one-deep queue
  has room, as a program would (lines and arcs alternate, blending with termination 2);
- program: the same path through `logixst run` of an ST program (1 ms scans: planner
  update, tags written back, the scan that queues the next move);
- 16 systems: 16 coordinate systems of 3 axes in one group, each on its own path.
"""

from __future__ import annotations

import math
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))  # run from anywhere

from interpreter.motion import EventKind, MotionGroup  # noqa: E402
from interpreter.motion.path_geometry import Segment, circle, line  # noqa: E402
from interpreter.motion.profiles import Limits  # noqa: E402

CUP = 0.001
MOVES = 1000
PROGRAM_MOVES = 200
LIMITS = Limits(50.0, 500.0, 500.0)


def _segment(k: int, start: np.ndarray) -> Segment:
    """Move k of the path: a square-ish zig-zag of lines with a half circle every fourth
    move (via point above the chord), climbing slowly in Z."""
    if k % 4 == 3:
        end = start + np.array([10.0, 0.0, 0.5])
        via = start + np.array([5.0, 5.0, 0.25])
        seg = circle(start, end, via, 0, 0, 3)
        assert isinstance(seg, Segment), seg
        return seg
    step = ((10.0, 0.0, 0.5), (0.0, 10.0, 0.5), (0.0, -10.0, 0.5))[k % 4]
    return line(start, start + np.array(step))


def _run_core(n_systems: int, moves: int) -> tuple[float, float, int]:
    """(simulated seconds, wall seconds, completed moves)."""
    g = MotionGroup(CUP)
    systems = []
    for c in range(n_systems):
        axes = [g.add_axis(f"s{c}a{i}") for i in range(3)]
        systems.append(g.add_coordinate_system(axes))
    queued = [0] * n_systems
    done = 0
    room = True  # a move completed: the queues may have room (a program queues on PC)
    t0 = time.perf_counter()
    while done < n_systems * moves:
        if room:
            for c, cs in enumerate(systems):
                st = g.paths.systems[cs]
                while queued[c] < moves and ((st.lead is not None) + len(st.queue)) < 2:
                    start = g.path_start_point(cs)
                    r = g.start_path(cs, _segment(queued[c], start), LIMITS, 2, 0.5, 0, False)
                    assert r.ok, r
                    queued[c] += 1
        room = False
        for ev in g.update():
            if ev.kind is EventKind.COMPLETE or ev.kind is EventKind.IN_PROCESS:
                done += ev.kind is EventKind.COMPLETE
                room = True
    wall = time.perf_counter() - t0
    return g.time, wall, done


def _program(moves: int) -> str:
    """An ST program queueing the same kind of path from the scan: a move whenever the
    system's queue has room (MovePendingQueueFullStatus clear, the control tags free)."""
    return f"""VAR
  X, Y, Z : AXIS_VIRTUAL := (MaximumSpeed := 1000.0, MaximumAccel := 10000.0, MaximumDecel := 10000.0);
  CS : COORDINATE_SYSTEM := (Axes := [X, Y, Z], MaximumSpeed := 50.0, MaximumAccel := 500.0,
                             MaximumDecel := 500.0, CommandTolerance := 0.5);
  lin : MOTION_INSTRUCTION[2];
  arc : MOTION_INSTRUCTION[2];
  d, via : REAL[3];
  k, j : DINT;
END_VAR
IF k < {moves} AND NOT CS.MovePendingQueueFullStatus THEN
  j := k MOD 2;
  IF k MOD 4 = 3 THEN
    d[0] := 10.0; d[1] := 0.0; d[2] := 0.5;
    via[0] := 5.0; via[1] := 5.0; via[2] := 0.25;
    MCCM(CS, arc[j], 1, d, 0, via, 0, 50.0, unitspersec, 500.0, unitspersec2, 500.0, unitspersec2, trapezoidal, 100.0, 100.0, %oftime, 2, disabled, programmed, 0.0, 0.0, none, 0, 0);
  ELSE
    d[0] := 0.0; d[1] := 0.0; d[2] := 0.5;
    IF k MOD 4 = 0 THEN d[0] := 10.0; ELSIF k MOD 4 = 1 THEN d[1] := 10.0; ELSE d[1] := -10.0; END_IF;
    MCLM(CS, lin[j], 1, d, 50.0, unitspersec, 500.0, unitspersec2, 500.0, unitspersec2, trapezoidal, 100.0, 100.0, %oftime, 2, disabled, programmed, 0.0, 0.0, none, 0, 0);
  END_IF;
  k := k + 1;
END_IF;
"""


def _run_program(moves: int, seconds: float) -> tuple[float, float]:
    from interpreter.cli import main

    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "path.st"
        path.write_text(_program(moves))
        argv = ["run", str(path), "--duration", str(seconds), "--coarse-update", "1"]
        argv += ["--json", "--watch", "k", "--watch", "Z.CommandPosition"]
        t0 = time.perf_counter()
        code = main(argv)
        wall = time.perf_counter() - t0
        assert code == 0
    return seconds, wall


def _idle_update_seconds(n_axes: int, updates: int = 5000) -> float:
    """Per-update cost of a group whose axes do nothing (the fixed cost of the planner)."""
    g = MotionGroup(CUP)
    for i in range(n_axes):
        g.add_axis(f"a{i}")
    for _ in range(100):
        g.update()
    t0 = time.perf_counter()
    for _ in range(updates):
        g.update()
    return (time.perf_counter() - t0) / updates


def main() -> None:
    idle3 = _idle_update_seconds(3)
    idle48 = _idle_update_seconds(48)
    print(
        f"idle group update (no motion): 3 axes {idle3 * 1e6:.1f} us, 48 axes {idle48 * 1e6:.1f} us"
    )
    sim, wall, done = _run_core(1, MOVES)
    assert done == MOVES
    per = wall / (sim / CUP)
    print(f"core, 1 system, {MOVES} moves: {sim:.1f} s simulated in {wall:.2f} s")
    print(f"  {sim / wall:.0f}x real time ({per * 1e6:.1f} us per update, of which the")
    print(f"  path moves add {(per - idle3) * 1e6:.1f} us to the idle group's {idle3 * 1e6:.1f})")
    sim16, wall16, done16 = _run_core(16, MOVES // 10)
    assert done16 == 16 * (MOVES // 10)
    per16 = wall16 / (sim16 / CUP)
    print(f"core, 16 systems x {MOVES // 10} moves: {sim16:.1f} s simulated in {wall16:.2f} s")
    print(f"  {sim16 / wall16:.0f}x real time ({per16 * 1e6:.1f} us per update; the paths add")
    print(f"  {(per16 - idle48) * 1e6:.1f} us to the idle 48-axis group's {idle48 * 1e6:.1f})")
    # the program: the first PROGRAM_MOVES moves of the path (the whole run scans too)
    seconds = math.ceil(sim * PROGRAM_MOVES / MOVES) + 1.0
    psim, pwall = _run_program(PROGRAM_MOVES, seconds)
    print(f"program, {PROGRAM_MOVES} moves (logixst run, 1 ms scans and coarse update):")
    print(f"  {psim:.0f} s simulated in {pwall:.2f} s: {psim / pwall:.1f}x real time")


if __name__ == "__main__":
    main()
