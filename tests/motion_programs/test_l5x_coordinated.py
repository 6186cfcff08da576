"""A coordinate system from an L5X export: its primary axes (the Axes attribute with their
CoordinationMode), its limits for % of Maximum and its tolerances; a ladder MCLM."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from interpreter.cli import main

PROJECT = Path(__file__).parent / "fixtures" / "coordinated_project.L5X"


def test_l5x_coordinate_system_runs_a_ladder_mclm(capsys) -> None:  # noqa: ANN001
    capsys.readouterr()
    watches = [
        "GX.CommandPosition", "GY.CommandPosition", "GZ.CommandPosition", "GR.CommandPosition",
        "Head.Dimension", "Head.CommandTolerance", "Head.ActualTolerance", "MoveCtl.PC",
        "MoveCtl.ER",
    ]  # fmt: skip
    argv = ["run", str(PROJECT), "--scans", "2400", "--json"]
    for w in watches:
        argv += ["--watch", w]
    code = main(argv)
    tags = json.loads(capsys.readouterr().out)["tags"]
    assert code == 0
    # three primary axes (GR is an orientation axis and stays out)
    assert tags["Head.Dimension"] == 3
    assert tags["Head.CommandTolerance"] == 0.5
    assert tags["Head.ActualTolerance"] == pytest.approx(0.02)
    # L = |(20, 0, 15)| = 25 at 50 % of 20 = 10 units/s, 50 % of 200 = 100 units/s^2:
    # ramps of 0.1 s (0.5 units), T = 2.5 + 0.1 = 2.6 s from the update at 2 ms. The last
    # row (scan 2399) shows the update at 2.398 s, 2.396 s into the move, still cruising:
    # s = 0.5 + 10 (2.396 - 0.1) = 23.46, of which 0.8 on X and 0.6 on Z
    assert tags["MoveCtl.ER"] is False and tags["MoveCtl.PC"] is False
    assert tags["GX.CommandPosition"] == pytest.approx(0.8 * 23.46, abs=1e-4)
    assert tags["GZ.CommandPosition"] == pytest.approx(0.6 * 23.46, abs=1e-4)
    assert tags["GY.CommandPosition"] == 0.0


def test_l5x_coordinated_move_completes(capsys) -> None:  # noqa: ANN001
    capsys.readouterr()
    argv = ["run", str(PROJECT), "--scans", "2700", "--json"]
    for w in ("GX.CommandPosition", "GZ.CommandPosition", "GR.CommandPosition", "MoveCtl.PC"):
        argv += ["--watch", w]
    assert main(argv) == 0
    tags = json.loads(capsys.readouterr().out)["tags"]
    # T = 2.6 s from the update at 2 ms: PC by the scan at 2.604 s
    assert tags["MoveCtl.PC"] is True
    assert (tags["GX.CommandPosition"], tags["GZ.CommandPosition"]) == (20.0, 15.0)
    assert tags["GR.CommandPosition"] == 0.0
