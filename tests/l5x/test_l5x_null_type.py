"""A UDT member Studio wrote as DataType="NULL" and an empty rung in an L5X export
(decision 0074; fixture null_member.L5X, shaped after L5Sharp's test controllers)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from interpreter.cli import main

FIXTURE = Path(__file__).parent / "fixtures" / "null_member.L5X"


def test_null_member_and_empty_rung_are_genuine_errors(capsys: pytest.CaptureFixture[str]) -> None:
    capsys.readouterr()
    assert main(["check", str(FIXTURE), "--format", "json"]) == 1
    got = [(d["line"], d["code"], d["message"]) for d in json.loads(capsys.readouterr().out)]
    assert got == [
        # once, at the member (line 9); the other member and the tag of the type still resolve:
        # ADD(Thing.Count, ...) on line 22 gives nothing
        (9, "E119", "no data type: Studio writes NULL where the member's type is undefined"),
        # the empty rung of routine Fault (line 27), as in an .rll file (SPEC 9.10)
        (
            27,
            "E129",
            "rung 0 is empty: give it at least one instruction (NOP) (program NProgram, routine Fault, rung 0)",
        ),
    ]


def test_a_project_with_errors_is_not_run(capsys: pytest.CaptureFixture[str]) -> None:
    # Studio would not download it either
    capsys.readouterr()
    assert main(["run", str(FIXTURE), "--scans", "1"]) == 1
