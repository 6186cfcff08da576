"""samples/glue_labeller.st does what its header says (output cam on a rotary axis, delay
compensation, a pulsed glue bead, an enable bit; decisions 0112-0115)."""

from __future__ import annotations

import json
from pathlib import Path

from interpreter.cli import main

SAMPLE = Path(__file__).resolve().parents[2] / "samples" / "glue_labeller.st"
US = 1e-6


def t_at(p: float) -> float:
    """Time the drum reaches the unwrapped position p (at speed: 180 + 720 (t - 0.502))."""
    return 0.502 + (p - 180.0) / 720.0


def test_glue_labeller(capsys) -> None:  # noqa: ANN001
    capsys.readouterr()
    code = main(["run", str(SAMPLE), "--duration", "2.6", "--json", "--watch", "Revs",
                 "--watch", "Outputs.0@edges", "--watch", "Outputs.1@edges",
                 "--watch", "Drum.ActualPosition", "--watch", "CamCtl.ER"])  # fmt: skip
    assert code == 0
    tags = json.loads(capsys.readouterr().out)["tags"]
    # the last scan starts at 2.599, after the update 2.598: unwrapped 180 + 720 * 2.096 =
    # 1689.12, 4 wraps, 249.12 deg
    assert tags["Revs"] == 4 and not tags["CamCtl.ER"]
    assert abs(tags["Drum.ActualPosition"] - 249.12) < 1e-3
    # label kick: on at 240 - 2 - 720 * 0.004 = 235.12 deg of each carton, 25 + 4 ms long
    label = tags["Outputs.1@edges"]
    expected = []
    for n in range(1, 5):
        on = t_at(360.0 * n + 235.12 - 360.0)
        expected += [(on, 1), (on + 0.029, 0)]
    expected.append((t_at(360.0 * 5 + 235.12 - 360.0), 1))  # 2.5786: still on at 2.6 s
    assert len(label) == len(expected)
    for (t, v), (te, ve) in zip(label, expected, strict=True):
        assert v == ve and abs(t - te) <= US, (label, expected)
    # glue: the command from 60 - 720 * 0.006 = 55.68 to 150 - 720 * 0.003 = 147.84 deg,
    # dots of 6 ms every 10 ms from the start of the command: 13 per carton (the 13th at
    # +120 ms ends at +126 ms, before the end at +128 ms); cartons 1, 2 and 4 (the third is
    # missing); carton 0 is glued while the drum still accelerates (not checked here)
    glue = [(t, v) for t, v in tags["Outputs.0@edges"] if t > t_at(360.0)]
    expected = []
    for n in (1, 2, 4):
        start = t_at(360.0 * n + 55.68)
        for k in range(13):
            expected += [(start + 0.01 * k, 1), (start + 0.01 * k + 0.006, 0)]
    assert len(glue) == len(expected)
    for (t, v), (te, ve) in zip(glue, expected, strict=True):
        assert v == ve and abs(t - te) <= US, (t, te)
