"""What Verify says about MCLM, MCCM and MCS operands (catalog rules, SPEC 7): a failing
program and a clean twin, through `logixst check --format json`."""

from __future__ import annotations

import json

import pytest

from interpreter.cli import main

HEAD = """VAR
  X, Y : AXIS_VIRTUAL;
  XY : COORDINATE_SYSTEM := (Axes := [X, Y]);
  c : MOTION_INSTRUCTION;
  pos, via : REAL[2];
  flags : BOOL[2];
  r : REAL;
  b : BOOL;
END_VAR
"""
TAIL = (
    "0, unitspersec, 100.0, unitspersec2, 100.0, unitspersec2, trapezoidal, 100.0, 100.0, "
    "%oftime, 0, disabled, programmed, 0.0, 0.0, none, 0, 0"
)


def mccm(circle: str, aux: str, pos: str = "pos") -> str:
    return f"IF b THEN MCCM(XY, c, 0, {pos}, {circle}, {aux}, 0, 1{TAIL}); END_IF;"


def codes(tmp_path, capsys, body: str) -> list[str]:  # noqa: ANN001
    src = tmp_path / "p.st"
    src.write_text(HEAD + body + "\n")
    capsys.readouterr()
    main(["check", str(src), "--format", "json"])
    return [d["code"] for d in json.loads(capsys.readouterr().out) if d["severity"] == "error"]


@pytest.mark.parametrize(
    "body",
    [
        mccm("via", "via"),  # a via point: a REAL array
        mccm("center", "via[0]"),  # an element stands for the array from there
        mccm("radius", "5.0"),  # a radius: an immediate ...
        mccm("radius", "r"),  # ... or a REAL tag
        f"IF b THEN MCLM(XY, c, 1, pos, 1{TAIL}); END_IF;",
        "IF b THEN MCS(XY, c, coordinatedmove, yes, 10.0, unitspersec2, no, 0.0, unitspersec3); END_IF;",
    ],
)
def test_clean_coordinated_calls(tmp_path, capsys, body: str) -> None:  # noqa: ANN001
    assert codes(tmp_path, capsys, body) == []


@pytest.mark.parametrize(
    ("body", "code"),
    [
        (mccm("via", "flags"), "E105"),  # a BOOL array is no point
        (mccm("via", "via", pos="r"), "E105"),  # Position needs an array tag
        (mccm("sideways", "via"), "E108"),  # unknown Circle Type text
        (mccm("via", "via").replace(", 0);", ");"), "E104"),  # 24 operands instead of 25
        ("IF b THEN MCS(X, c, all, no, 0.0, unitspersec2, no, 0.0, unitspersec3); END_IF;", "E113"),
    ],
)
def test_coordinated_operand_errors(tmp_path, capsys, body: str, code: str) -> None:  # noqa: ANN001
    assert code in codes(tmp_path, capsys, body)
