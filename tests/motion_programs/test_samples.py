"""The motion samples do what their headers say (samples/timecam_blend.st, flying_shear.st)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from interpreter.cli import main

SAMPLES = Path(__file__).resolve().parents[2] / "samples"


def _run(capsys, name: str, *argv: str) -> dict:  # noqa: ANN001
    capsys.readouterr()
    code = main(["run", str(SAMPLES / name), "--json", *argv])
    out = capsys.readouterr().out
    assert code == 0
    return json.loads(out)["tags"]  # type: ignore[no-any-return]


@pytest.mark.parametrize(("extra", "end"), [((), 300.0), (("--set", "StopAt=2000"), 200.0)])
def test_timecam_blend_ends_where_the_header_says(
    capsys, extra: tuple[str, ...], end: float
) -> None:
    # Accel 50 + n Run passes of 50 + Decel 50: n = 4 by default, 2 when stopping at 2 s
    tags = _run(
        capsys,
        "timecam_blend.st",
        "--duration",
        "4.5",
        *extra,
        "--watch",
        "Axis.CommandPosition",
        "--watch",
        "Axis.TimeCamStatus",
        "--watch",
        "DecelCtl.PC",
        "--watch",
        "AccelProf[0].Status",
    )
    assert tags == {
        "Axis.CommandPosition": end,
        "Axis.TimeCamStatus": False,
        "DecelCtl.PC": True,
        "AccelProf[0].Status": 2,
    }


def test_flying_shear_cuts_four_pieces_in_sync(tmp_path, capsys) -> None:
    trace = tmp_path / "fs.csv"
    tags = _run(
        capsys,
        "flying_shear.st",
        "--duration",
        "4.5",
        "--trace",
        str(trace),
        "--watch",
        "Cuts",
        "--watch",
        "KnifeDown",
        "--watch",
        "Line.CommandPosition",
        "--watch",
        "Shear.CommandVelocity",
        "--watch",
        "Line.CommandVelocity",
        "--watch",
        "Shear.CommandPosition",
    )
    # line: 250 mm of ramp, then 1000 mm/s; stopped after cut 4 (from 3252 mm, 250 mm to rest)
    assert tags["Cuts"] == 4 and tags["Line.CommandPosition"] == 3502.0
    rows = [line.split(",") for line in trace.read_text().splitlines()[1:]]
    starts = [
        float(r[0])
        for prev, r in zip(rows, rows[1:], strict=False)
        if r[2] == "1" and prev[2] == "0"
    ]
    assert starts == [0.502, 1.502, 2.502, 3.502]
    for r in rows:
        if r[2] == "1":  # knife down: carriage in the synchronous stretch at strip speed
            assert float(r[4]) == pytest.approx(float(r[5]), abs=1e-3)
            assert 150.0 - 1e-3 <= float(r[6]) <= 250.0 + 1e-3


def test_rotary_knife_both_knives_run_the_same_cam(tmp_path, capsys) -> None:
    """samples/rotary_knife.st: once KnifeA is in sync the two knives keep a constant
    distance (the same cam, KnifeB moved from where it stood), and each turns 360 degrees
    per 500 mm of strip (one cut per piece)."""
    import csv

    trace = tmp_path / "knife.csv"
    watch = ["Line.CommandPosition", "KnifeA.CommandPosition", "KnifeB.CommandPosition"]
    watch += ["CamA.InSync", "CamA.Error", "KnifeBCam.ER"]
    argv = ["--duration", "2", "--trace", str(trace)]
    for w in watch:
        argv += ["--watch", w]
    _run(capsys, "rotary_knife.st", *argv)
    with trace.open() as fh:
        rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(fh)]
    synced = [r for r in rows if r["CamA.InSync"] == 1]
    assert synced and all(r["CamA.Error"] == 0 and r["KnifeBCam.ER"] == 0 for r in rows)
    gap = [r["KnifeA.CommandPosition"] - r["KnifeB.CommandPosition"] for r in synced]
    assert max(gap) - min(gap) < 1e-3
    # the strip advances 1000 mm/s: 500 mm is 0.5 s = 500 scans later
    first = rows.index(synced[0])
    a, b = rows[first], rows[first + 500]
    assert b["Line.CommandPosition"] - a["Line.CommandPosition"] == 500.0
    for knife in ("KnifeA", "KnifeB"):
        turned = b[f"{knife}.CommandPosition"] - a[f"{knife}.CommandPosition"]
        assert abs(turned - 360.0) < 1e-3
