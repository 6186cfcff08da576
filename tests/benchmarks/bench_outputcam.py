"""Output cam core benchmark (issue 11): 8 axes, each with 8 armed execution targets of 32
elements (2,048 elements), 60 s simulated at 1 ms coarse update.

Each axis runs at constant speed over a continuous cam range of 360 units (one pass per
1.8-3.6 s, depending on the axis); each target holds 32 position windows of 4 units spread
over the range, one bit each, so outputs switch several times per update across the group.
`python tests/benchmarks/bench_outputcam.py [SECONDS]` times the numpy core alone
(`OutputCamSet.update`); `... [SECONDS] --program` runs the same cams as an ST program through
the whole `logixst run` command (MAJ on 8 virtual axes, 64 MAOCs, start-up included).
Goal (issue 11): >= 20x real time; below 10x the issue is not done.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

from interpreter.motion.outputcam import ArmRequest, OutputCamSet  # noqa: E402
from interpreter.motion.outputcam_tables import (  # noqa: E402
    OutputCamExecutionMode,
    OutputCamExecutionSchedule,
    PositionReference,
    check_output_cam,
    columns_from_records,
)

AXES, TARGETS, ELEMENTS = 8, 8, 32
RANGE = 360.0
DT = 0.001


def build() -> tuple[OutputCamSet, np.ndarray]:
    s = OutputCamSet()
    for axis in range(AXES):
        for target in range(TARGETS):
            records = [
                {
                    "OutputBit": k,
                    "LatchType": 1,
                    "UnlatchType": 1,
                    "Left": (k * RANGE / ELEMENTS + target * 1.3) % (RANGE - 5.0),
                    "Right": (k * RANGE / ELEMENTS + target * 1.3) % (RANGE - 5.0) + 4.0,
                }
                for k in range(ELEMENTS)
            ]
            elements, check = check_output_cam(
                columns_from_records(records, "OUTPUT_CAM"), 0.0, RANGE
            )
            assert check.ok
            request = ArmRequest(
                axis * TARGETS + target + 1, elements, 0.0, RANGE,
                OutputCamExecutionMode.CONTINUOUS, OutputCamExecutionSchedule.IMMEDIATE,
                0.0, 0.0, PositionReference.ACTUAL,
            )  # fmt: skip
            assert s.arm(axis, target, request).armed
    speeds = 100.0 + 100.0 * np.arange(AXES) / AXES  # 100 .. 187.5 units/s
    return s, speeds


def run(seconds: float) -> tuple[float, int]:
    s, speeds = build()
    x = np.zeros(AXES)
    edges = 0
    steps = round(seconds / DT)
    t_start = time.perf_counter()
    for k in range(steps):
        x1 = x + speeds * DT
        start = np.vstack((x, x))
        end = np.vstack((x1, x1))
        edges += len(s.update(k * DT, DT, start, end).edges)
        x = x1
    return time.perf_counter() - t_start, edges


def program() -> str:
    """The benchmark as an ST program: the same windows, speeds and continuous cams."""
    decl = ["VAR"]
    body = ["IF k = 0 THEN"]
    for axis in range(AXES):
        speed = 100.0 + 100.0 * axis / AXES
        decl.append(f"  A{axis} : AXIS_VIRTUAL := (MaximumSpeed := 1000.0, "
                    "MaximumAccel := 1000000.0, MaximumDecel := 1000000.0);")  # fmt: skip
        decl.append(f"  jog{axis} : MOTION_INSTRUCTION;")
        body.append(
            f"  MAJ(A{axis}, jog{axis}, forward, {speed}, unitspersec, 1000000.0, unitspersec2, "
            "1000000.0, unitspersec2, trapezoidal, 0.0, 0.0, unitspersec3, disabled, "
            "programmed, 0.0, none);"
        )
        for target in range(TARGETS):
            n = axis * TARGETS + target
            windows = []
            for k in range(ELEMENTS):
                left = (k * RANGE / ELEMENTS + target * 1.3) % (RANGE - 5.0)
                windows.append(f"(OutputBit := {k}, LatchType := 1, UnlatchType := 1, "
                               f"Left := {left!r}, Right := {left + 4.0!r})")  # fmt: skip
            decl.append(f"  cam{n} : OUTPUT_CAM[{ELEMENTS}] := [{', '.join(windows)}];")
            decl.append(f"  arm{n} : MOTION_INSTRUCTION;")
            body.append(
                f"  MAOC(A{axis}, {target}, arm{n}, outs[{n}], ins[{n}], cam{n}, 0.0, {RANGE}, "
                "comp, continuous, immediate, 0.0, 0.0, actual);"
            )
    decl += [f"  outs, ins : DINT[{AXES * TARGETS}];", "  comp : OUTPUT_COMPENSATION[32];",
             "  k : DINT;", "END_VAR"]  # fmt: skip
    return "\n".join(decl + body + ["END_IF;", "k := k + 1;", ""])


def run_program(seconds: float) -> float:
    import contextlib
    import io
    import tempfile

    from interpreter.cli import main as cli

    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "outputcams.st"
        path.write_text(program())
        t_start = time.perf_counter()
        with contextlib.redirect_stdout(io.StringIO()):
            code = cli(["run", str(path), "--duration", str(seconds), "--coarse-update", "1",
                        "--watch", "outs[0]", "--json"])  # fmt: skip
        wall = time.perf_counter() - t_start
    assert code == 0
    return wall


def main() -> None:
    seconds = float(sys.argv[1]) if len(sys.argv) > 1 else 60.0
    if "--program" in sys.argv:
        wall = run_program(seconds)
        print(
            f"logixst run, {AXES} axes x {TARGETS} MAOCs x {ELEMENTS} elements, {seconds:g} s "
            f"at 1 ms: {wall:.2f} s wall, {seconds / wall:.1f}x real time"
        )
        return
    wall, edges = run(seconds)
    print(
        f"{AXES} axes x {TARGETS} targets x {ELEMENTS} elements, {seconds:g} s at 1 ms: "
        f"{wall:.2f} s wall, {seconds / wall:.1f}x real time, {edges} output edges"
    )


if __name__ == "__main__":
    main()
