"""Motion from an L5X export: the MotionGroup's CoarseUpdatePeriod, axes assigned to it by
their MotionGroup parameter, axis limits from AxisParameters (used by % of Maximum)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from interpreter.cli import main

PROJECT = Path(__file__).parent / "fixtures" / "motion_project.L5X"


def test_l5x_motion_group_and_axis(capsys) -> None:  # noqa: ANN001
    capsys.readouterr()
    code = main(
        [
            "run",
            str(PROJECT),
            "--scans",
            "300",
            "--json",
            "--watch",
            "Conveyor.CommandPosition",
            "--watch",
            "Conveyor.CommandVelocity",
            "--watch",
            "Group1.CoarseUpdatePeriod",
            "--watch",
            "JogCtl.IP",
        ]
    )
    out = capsys.readouterr().out
    assert code == 0
    tags = json.loads(out)["tags"]
    # jog at 50 % of MaximumSpeed 100 with 100 % of MaximumAcceleration 1000: at speed after
    # 0.05 s (1.25 units). Coarse update 4 ms: executed in scan 0, the jog starts at the update
    # at 4 ms; the row of scan 299 shows the update at 296 ms: 0.292 s of jog:
    #   1.25 + 50 (0.292 - 0.05) = 13.35
    assert tags["Conveyor.CommandPosition"] == pytest.approx(13.35, abs=1e-4)
    assert tags["Conveyor.CommandVelocity"] == 50.0
    assert tags["Group1.CoarseUpdatePeriod"] == 4000 and tags["JogCtl.IP"] is True
