"""MAH and MAG in ladder from an L5X export: homing configuration from AxisParameters
(HomeMode / HomeSequence / HomeDirection texts, HomePosition), gearing in a branch."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from interpreter.cli import main

PROJECT = Path(__file__).parent / "fixtures" / "gear_home_project.L5X"


def test_l5x_passive_home_and_gear_in_ladder(capsys) -> None:  # noqa: ANN001
    watch = [
        "Master.CommandPosition", "Slave.CommandPosition", "HomeCtl.PC", "GearCtl.IP",
        "Master.AxisHomedStatus", "Master.HomeMode", "Master.HomeSequence",
        "Slave.HomeMode", "Slave.HomeDirection", "Master.HomePosition",
    ]  # fmt: skip
    capsys.readouterr()
    code = main(["run", str(PROJECT), "--scans", "300", "--json", *(f"--watch={w}" for w in watch)])
    out = capsys.readouterr().out
    assert code == 0
    tags = json.loads(out)["tags"]
    # AxisParameters texts through the catalog enumerations: Passive 0, Immediate 0,
    # Active 1, Uni-directional Reverse 2
    assert [tags[w] for w in watch[5:]] == [0, 0, 1, 2, 12.5]
    # Coarse update 4 ms. Scan 0: MAJ (50 % of 100 units/s, 100 % of 1000 units/s^2) and MAG
    # ratio 2 on the command position; scan 1: MAH (Passive, Immediate). All apply at the
    # update at 4 ms: the home first (master at rest: 0 -> 12.5), then the jog and the gear
    # start (the gear counts from 12.5). Row of scan 299 = update at 296 ms: 0.292 s of jog,
    #   travel 1.25 + 50 (0.292 - 0.05) = 13.35 -> master 25.85, slave 2 x 13.35 = 26.7
    assert tags["Master.CommandPosition"] == pytest.approx(25.85, abs=1e-4)
    assert tags["Slave.CommandPosition"] == pytest.approx(26.7, abs=1e-4)
    assert tags["HomeCtl.PC"] is True and tags["Master.AxisHomedStatus"] is True
    assert tags["GearCtl.IP"] is True
