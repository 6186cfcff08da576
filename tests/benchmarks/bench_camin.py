"""PLCopen camming benchmark (issue 13): 32 slaves, each coupled to one master through
MC_CamIn, 60 s simulated at a 1 ms coarse update. Goal >= 20x real time, minimum 10x.

Run as a script (`python tests/benchmarks/bench_camin.py [seconds]`; default 60 simulated
seconds). Prints the real-time factor (simulated / wall seconds) of
- the core alone: MotionGroup.update with the master jogging and 32 position cam couplings;
- the whole program through the Controller: a 1 ms coarse update with 1 ms scans (every scan
  calls the 32 MC_CamIn blocks, as a PLCopen program does) and with 4 ms scans.
Each figure is given against wall time and against the CPU time of this process.
"""

from __future__ import annotations

import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))  # run from anywhere

from interpreter.motion import MotionGroup, calculate_cam_profile  # noqa: E402
from interpreter.motion.poscam import CamLaw  # noqa: E402

CUP = 0.001
SLAVES = 32
X = np.linspace(0.0, 360.0, 13)
Y = 50.0 * np.sin(np.radians(X)) ** 2  # a rise-and-return cam per master revolution


def core_factor(sim_seconds: float) -> tuple[float, float]:
    g = MotionGroup(CUP)
    m = g.add_axis("master")
    profile = calculate_cam_profile(X, Y, [1] * len(X))
    for i in range(SLAVES):
        s = g.add_axis(f"s{i}")
        law = CamLaw(profile, periodic=True, slave_scaling=1.0 + 0.01 * i)
        g.start_position_cam(s, m, law)
    g.update()
    assert g.start_jog(m, 0, 360.0, 1000.0, 1000.0).ok
    updates = round(sim_seconds / CUP)
    t0, c0 = time.perf_counter(), time.process_time()
    for _ in range(updates):
        g.update()
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    assert len(g.position_cams.rows) == SLAVES
    return sim_seconds / wall, sim_seconds / cpu


def program() -> str:
    pts = ", ".join(
        f"(Master := {x:.1f}, Slave := {y:.9f}, SegmentType := 1)"
        for x, y in zip(X, Y, strict=True)
    )
    slaves = ", ".join(f"S{i}" for i in range(SLAVES))
    blocks = ", ".join(f"cam{i}" for i in range(SLAVES))
    calls = "\n".join(
        f"cam{i}(Master := M, Slave := S{i}, Execute := sel{i}.Done, CamTableID := sel{i}.CamTableID,"
        f" SlaveScaling := {1.0 + 0.01 * i});"
        for i in range(SLAVES)
    )
    selects = "\n".join(
        f"sel{i}(Master := M, Slave := S{i}, CamTable := table, Execute := TRUE, Periodic := TRUE);"
        for i in range(SLAVES)
    )
    sels = ", ".join(f"sel{i}" for i in range(SLAVES))
    return f"""VAR
  M, {slaves} : AXIS_VIRTUAL;
  mj : MOTION_INSTRUCTION;
  table : CAM[{len(X)}] := [{pts}];
  {sels} : MC_CamTableSelect;
  {blocks} : MC_CamIn;
END_VAR
{selects}
{calls}
IF S:FS THEN
  MAJ(M, mj, forward, 360.0, unitspersec, 1000.0, unitspersec2, 1000.0, unitspersec2,
      trapezoidal, 0.0, 0.0, unitspersec3, disabled, programmed, 0.0, none);
END_IF;
"""


def program_factor(sim_seconds: float, scan_ms: float) -> tuple[float, float]:
    from interpreter.runtime.controller import Controller
    from interpreter.runtime.loader import load

    with tempfile.TemporaryDirectory() as d:
        p = Path(d) / "camin.st"
        p.write_text(program())
        ctl = Controller(load([p]), scan_period_ms=scan_ms, coarse_update_ms=CUP * 1e3)
    ctl.prescan()
    scans = round(sim_seconds * 1000.0 / scan_ms)
    t0, c0 = time.perf_counter(), time.process_time()
    for _ in range(scans):
        assert ctl.scan()
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    return sim_seconds / wall, sim_seconds / cpu


def main(sim_seconds: float = 60.0) -> dict[str, tuple[float, float]]:
    r = {
        "core": core_factor(sim_seconds),
        "program_1ms_scans": program_factor(sim_seconds, 1.0),
        "program_4ms_scans": program_factor(sim_seconds, 4.0),
    }
    print(f"{SLAVES} MC_CamIn slaves, {sim_seconds:.0f} s simulated at {CUP * 1e3:.0f} ms:")
    print("  (real-time factor = simulated s / wall s, and / CPU s of this process: on a busy")
    print("  machine the CPU figure is the one that does not depend on the other processes)")
    for k, (wall, cpu) in r.items():
        print(f"  {k:20s} wall {wall:6.1f}x   cpu {cpu:6.1f}x   (goal 20x, minimum 10x)")
    return r


if __name__ == "__main__":
    main(float(sys.argv[1]) if len(sys.argv) > 1 else 60.0)
