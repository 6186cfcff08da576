"""`logixst check` on IEC function-block calls with named parameters (SPEC 3.1, 9.29):
unknown parameter names, wrong types, missing required inputs, outputs given as inputs,
enumeration words of StartMode."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from interpreter.cli import main

HEAD = """VAR
  M : AXIS_VIRTUAL;
  S : AXIS_CIP_DRIVE;
  table : CAM[3];
  sel : MC_CamTableSelect;
  camIn : MC_CamIn;
  go : BOOL;
  x : REAL;
  txt : STRING;
END_VAR
"""


def check(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], body: str
) -> list[tuple[str, int, str]]:
    p = tmp_path / "fb.st"
    p.write_text(HEAD + body)
    capsys.readouterr()
    main(["check", str(p), "--format", "json"])
    out = json.loads(capsys.readouterr().out)
    return [(d["code"], d["line"] - HEAD.count("\n"), d["message"]) for d in out]


def test_a_complete_call_is_clean(tmp_path, capsys):
    body = (
        "sel(Master := M, Slave := S, CamTable := table, Execute := go, Periodic := TRUE);\n"
        "camIn(Master := M, Slave := S, Execute := sel.Done, CamTableID := sel.CamTableID,\n"
        "  StartMode := ramp_in_pos, VelocityDiff := 10, MasterScaling := x, InSync => go);\n"
        "go := camIn.InSync AND NOT camIn.Error;\n"
    )
    assert check(tmp_path, capsys, body) == []


@pytest.mark.parametrize(
    ("call", "code", "words"),
    [
        ("camIn(Master := M, Slave := S, Speed := 1);", "E102", "no parameter 'Speed'"),
        ("camIn(Master := M, Slave := S, Exec := go);", "E102", "did you mean 'Execute'"),
        ("camIn(Master := M, Slave := S, MasterOffset := txt);", "E116", "STRING"),
        ("camIn(Master := x, Slave := S);", "E105", "Master needs an axis tag"),
        ("sel(Master := M, Slave := S, CamTable := table[0]);", "E105", "whole CAM array"),
        ("camIn(Slave := S, Execute := go);", "E104", "missing Master"),
        ("sel(Master := M, Slave := S);", "E104", "missing CamTable"),
        ("camIn(Master := M, Slave := S, Busy := go);", "E120", "Busy is an output"),
        ("camIn(Master := M, Slave := S, StartMode := ramp);", "E108", "not a value"),
        ("camIn(Master := M, Slave := S, StartMode := 5);", "E109", "4 ramp_in_neg"),
        ("camIn(M, S);", "E130", "given by name"),
    ],
)
def test_errors(tmp_path, capsys, call, code, words):
    found = check(tmp_path, capsys, call + "\n")
    assert {(c, line) for c, line, _ in found} == {(code, 1)}, found
    assert words in found[0][2]
