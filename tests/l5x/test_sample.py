"""samples/mixer.L5X: a hand-written project that checks clean and runs."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from interpreter.cli import main

MIXER = Path(__file__).resolve().parents[2] / "samples" / "mixer.L5X"


def test_mixer_checks_clean(capsys: pytest.CaptureFixture[str]) -> None:
    capsys.readouterr()
    code = main(["check", str(MIXER), "--format", "json"])
    diags = json.loads(capsys.readouterr().out)
    assert diags == []
    assert code == 0


def test_mixer_runs(capsys: pytest.CaptureFixture[str]) -> None:
    capsys.readouterr()
    code = main(
        [
            "run",
            str(MIXER),
            "--scans",
            "1000",
            "--json",
            "--watch",
            "Step",
            "--watch",
            "Level",
            "--watch",
            "ValveB.IsOpen",
            "--watch",
            "Batches",
        ]
    )
    out = capsys.readouterr()
    assert code == 0, out.err
    # Plant (periodic, 10 ms) runs before Sequence (continuous, 1 ms scans). Sequence opens
    # A at t = 0, Plant adds 0.5 % at t = 10, 20, ... so Level = 40 at t = 800 and Step
    # becomes 1; A closes and B opens at t = 801, Plant adds 0.5 at t = 810 .. 990
    # (19 runs): 40 + 19 * 0.5 = 49.5 when the 1000th scan (t = 999 ms) ends.
    assert json.loads(out.out)["tags"] == {
        "Step": 1,
        "Level": 49.5,
        "ValveB.IsOpen": True,
        "Batches": 0,
    }
