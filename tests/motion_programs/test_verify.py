"""What Verify reports for the motion instructions (SPEC 7): a failing fixture and a clean
twin for each check, run through `logixst check --format json`."""

from __future__ import annotations

import json

import pytest

from interpreter.cli import main

HEAD = """VAR
  ax, ax2 : AXIS_VIRTUAL;
  dr : AXIS_CIP_DRIVE;
  grp : MOTION_GROUP;
  mc, mc2 : MOTION_INSTRUCTION;
  pts : CAM[3];
  cp : CAM_PROFILE[3];
  b : BOOL;
  d : DINT;
END_VAR
"""
MATC = "MATC(ax, mc, 0, {p}, 1.0, 1.0, once, immediate, 0.0, none, timedrivenmode);"

# code -> (failing body, clean twin)
CASES: dict[str, tuple[str, str]] = {
    # only element [0] of a CAM_PROFILE may be given
    "E111": (
        "IF b THEN MCCP(mc, pts, 3, 0.0, 0.0, cp[1]); END_IF;",
        "IF b THEN MCCP(mc, pts, 3, 0.0, 0.0, cp[0]); END_IF;",
    ),
    # master and slave are one axis (names are case-insensitive)
    "E112": (
        "IF b THEN MDAC(ax, AX, mc, all, command); END_IF;",
        "IF b THEN MDAC(ax, ax2, mc, all, command); END_IF;",
    ),
    # an axis where a motion group belongs, a group where an axis belongs
    "E113": (
        "IF b THEN MGS(ax, mc, programmed); MATC(grp, mc2, 0, cp, 1.0, 1.0, once, immediate, 0.0, none, 0); END_IF;",
        "IF b THEN MGS(grp, mc, programmed); MATC(dr, mc2, 0, cp, 1.0, 1.0, once, immediate, 0.0, none, 0); END_IF;",
    ),
    # one MOTION_INSTRUCTION shared by two instructions (warning on the second use)
    "W203": (
        "IF b THEN " + MATC.format(p="cp") + " MDAC(ax, ax2, mc, all, command); END_IF;",
        "IF b THEN " + MATC.format(p="cp") + " MDAC(ax, ax2, mc2, all, command); END_IF;",
    ),
    # a transitional instruction reached every scan
    "W204": (MATC.format(p="cp"), "IF NOT b THEN " + MATC.format(p="cp") + " END_IF;"),
    # enumeration number out of range / unknown text
    "E109": (
        "IF b THEN MATC(ax, mc, 0, cp, 1.0, 1.0, 2, immediate, 0.0, none, 0); END_IF;",
        "IF b THEN MATC(ax, mc, 0, cp, 1.0, 1.0, 1, immediate, 0.0, none, 0); END_IF;",
    ),
    "E108": (
        "IF b THEN MDAC(ax, ax2, mc, timecams, command); END_IF;",
        "IF b THEN MDAC(ax, ax2, mc, timecam, command); END_IF;",
    ),
}


def _check(tmp_path, capsys, text: str) -> tuple[int, list[dict]]:  # noqa: ANN001
    p = tmp_path / "v.st"
    p.write_text(text)
    capsys.readouterr()
    code = main(["check", str(p), "--format", "json"])
    out = capsys.readouterr().out
    return code, json.loads(out)


@pytest.mark.parametrize("code", sorted(CASES))
def test_failing_fixture_and_clean_twin(tmp_path, capsys, code: str) -> None:
    bad, good = CASES[code]
    _, diags = _check(tmp_path, capsys, HEAD + bad + "\n")
    assert code in [d["code"] for d in diags], diags
    exit_code, diags = _check(tmp_path, capsys, HEAD + good + "\n")
    assert diags == [] and exit_code == 0


INIT_OK = "(Master := 0.0, Slave := 0.0, SegmentType := 1), (Master := 1.0, Slave := 2.0, SegmentType := 0)"


@pytest.mark.parametrize(
    "init",
    [
        "(Master := 0.0, Slave := 0.0, SegmentType := 0), (Master := 0.0, Slave := 2.0, SegmentType := 0)",  # not increasing
        "(Master := 0.0, Slave := 0.0, SegmentType := 5), (Master := 1.0, Slave := 2.0, SegmentType := 0)",  # segment type
        "(Master := 0.0, Slave := 0.0, SegmentType := 0)",  # one point
        "(Master := 0.0, Slope := 0.0), (Master := 1.0, Slave := 2.0)",  # unknown member
        INIT_OK
        + ", (Master := 2.0, Slave := 2.0), (Master := 3.0, Slave := 2.0)",  # more points than elements
    ],
)
def test_cam_profile_initialisers_are_verified(tmp_path, capsys, init: str) -> None:
    # SPEC 2.1: a CAM_PROFILE initialised with points (CAM form) is calculated at load
    exit_code, diags = _check(tmp_path, capsys, f"VAR p : CAM_PROFILE[3] := [{init}]; END_VAR\n")
    assert [d["code"] for d in diags] == ["E118"] and exit_code == 1
    exit_code, diags = _check(tmp_path, capsys, f"VAR p : CAM_PROFILE[3] := [{INIT_OK}]; END_VAR\n")
    assert diags == [] and exit_code == 0


def test_integer_literals_are_accepted_for_real_operands(tmp_path, capsys) -> None:
    # SPEC 9.15; an integer tag too, as Logix converts it (decision 0054: Rockwell's own
    # ST_Motion_Example passes DINT tags as MAM Position and Speed); a BOOL is not a number
    good = (
        "IF b THEN MATC(ax, mc, 0, cp, 2, 1, once, immediate, 0, none, timedrivenmode); END_IF;\n"
    )
    assert _check(tmp_path, capsys, HEAD + good) == (0, [])
    assert _check(tmp_path, capsys, HEAD + good.replace(", 2, 1,", ", d, 1,")) == (0, [])
    _, diags = _check(tmp_path, capsys, HEAD + good.replace(", 2, 1,", ", b, 1,"))
    assert [x["code"] for x in diags] == ["E105"]
