"""The motion samples do what their headers say (samples/timecam_blend.st, flying_shear.st,
rounded_rectangle.st)."""

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


def test_rounded_rectangle_closes_the_path_without_stopping(tmp_path, capsys) -> None:
    trace = tmp_path / "rr.csv"
    tags = _run(
        capsys, "rounded_rectangle.st", "--duration", "6", "--trace", str(trace),
        "--watch", "X.CommandPosition", "--watch", "Y.CommandPosition",
        "--watch", "XY.VectorCommandVelocity", "--watch", "ArcCtl[7].PC", "--watch", "Step",
    )  # fmt: skip
    assert tags["X.CommandPosition"] == 5.0 and tags["Y.CommandPosition"] == 0.0
    assert tags["ArcCtl[7].PC"] is True and tags["Step"] == 8
    rows = [line.split(",") for line in trace.read_text().splitlines()[1:]]
    # between the first ramp and the last: the joints dip to sqrt(2 * 200 * 0.5) = 14.1
    # at the least (less one update of deceleration, 200 * 0.002), never to zero
    middle = [float(r[3]) for r in rows if 0.2 <= float(r[0]) <= 5.7]
    assert min(middle) >= 14.142 - 0.4 - 1e-3
    # the path: every point on the rounded rectangle (sides or corner circles of radius 5);
    # a blend leaves it by a few thousandths (the two moves' motions add up there)
    for r in rows:
        x, y = float(r[1]), float(r[2])
        cx, cy = min(max(x, 5.0), 35.0), min(max(y, 5.0), 15.0)
        if (cx, cy) != (x, y) and not (5.0 <= x <= 35.0 or 5.0 <= y <= 15.0):
            assert abs(((x - cx) ** 2 + (y - cy) ** 2) ** 0.5 - 5.0) < 0.01
        else:
            assert min(abs(x), abs(x - 40.0), abs(y), abs(y - 20.0)) < 0.01


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
