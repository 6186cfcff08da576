"""One project written as .L5X and as .L5K (both by hand, from one design) reads the same.

Each fixture here is the text-form twin of the L5X fixture of the same name in
tests/l5x/fixtures: the same controller, types, tags and data, AOIs, programs, routines and
tasks. `check` must report the same diagnostics (code, message with its program / routine /
rung or line context) and `run --json` the same tag values; the values themselves are worked
out by hand in the comments, not taken from either run.
"""

from __future__ import annotations

import json
from collections import Counter
from pathlib import Path
from typing import Any

import pytest

from interpreter.cli import main

HERE = Path(__file__).parent / "fixtures"
L5X = Path(__file__).parent.parent / "l5x" / "fixtures"
TWINS = [
    "st_project",
    "rll_project",
    "st_errors",
    "unsupported",
    "keyword_members",
    "program_parameters",
]


def check(capsys: pytest.CaptureFixture[str], path: Path) -> tuple[int, list[dict[str, Any]]]:
    capsys.readouterr()
    code = main(["check", str(path), "--format", "json"])
    return code, json.loads(capsys.readouterr().out)


def run(capsys: pytest.CaptureFixture[str], path: Path, *argv: str) -> dict[str, Any]:
    capsys.readouterr()
    code = main(["run", str(path), "--json", *argv])
    out = capsys.readouterr()
    assert code == 0, (code, out.err)
    return json.loads(out.out)["tags"]  # type: ignore[no-any-return]


@pytest.mark.parametrize("name", TWINS)
def test_twins_give_the_same_diagnostics(capsys: pytest.CaptureFixture[str], name: str) -> None:
    code_k, k = check(capsys, HERE / f"{name}.L5K")
    code_x, x = check(capsys, L5X / f"{name}.L5X")
    assert code_k == code_x
    assert all(d["path"].endswith(".L5K") for d in k)
    keep = ("code", "message", "severity")
    assert Counter(tuple(d[f] for f in keep) for d in k) == Counter(
        tuple(d[f] for f in keep) for d in x
    )


def test_expected_diagnostics_of_the_twins(capsys: pytest.CaptureFixture[str]) -> None:
    # Written down once, so the twin comparison above cannot pass by both readers failing.
    _, rll = check(capsys, HERE / "rll_project.L5K")
    assert [(d["code"], d["line"], d["column"]) for d in rll] == [("S006", 22, 8)]
    assert "(program MainProgram, routine MainRoutine, rung 2)" in rll[0]["message"]
    _, uns = check(capsys, HERE / "unsupported.L5K")
    assert [(d["code"], d["line"]) for d in uns] == [("U301", 17), ("U301", 26), ("U302", 35)]
    assert (
        uns[0]["message"] == "function block diagram routine 'Blend' (program P) is not supported"
    )
    assert (
        uns[2]["message"] == "routine 'Secret' is protected (encoded); its content cannot be read"
    )


WATCH = [
    "Speed",
    "Shared",
    "Program:MainProgram.Shared",
    "V1.Open",
    "V1.Fault",
    "V1.Count",
    "V1.Hist[1]",
    "Label",
    "Table[1,1]",
    "Program:MainProgram.Sc.Gain",
    "Program:Fast.Runs",
    "Ticks",
    "Program:MainProgram.Result",
    "Program:MainProgram.Counted",
    "SpeedAlias",
    "CountAlias",
]


def test_st_project_runs_the_same_from_both_forms(capsys: pytest.CaptureFixture[str]) -> None:
    argv = ["--scans", "25"] + [a for w in WATCH for a in ("--watch", w)]
    from_l5k = run(capsys, HERE / "st_project.L5K", *argv)
    from_l5x = run(capsys, L5X / "st_project.L5X", *argv)
    assert from_l5k == from_l5x
    # MainProgram runs every scan: Sub adds 2 to Speed (7 from `:= 7`), Main adds 1 to the
    # program's own Shared (100); the periodic 10 ms task runs Fast at t = 0, 10, 20 ms.
    assert from_l5k == {
        "Speed": 7 + 2 * 25,
        "Shared": 16,  # 16#0000_0010
        "Program:MainProgram.Shared": 100 + 25,
        "V1.Open": True,  # [1,...]: the hidden SINT is 1, so bit 0 (Open) is set
        "V1.Fault": False,  # and bit 1 (Fault) is not
        "V1.Count": 3,
        "V1.Hist[1]": 20,
        "Label": "abc",  # [3,'abc$00...']: LEN 3
        "Table[1,1]": 4,  # [1,2,3,4] for DINT[2,2] row-major
        "Program:MainProgram.Sc.Gain": 2.0,  # DefaultData := 2.00000000e+000
        "Program:Fast.Runs": 3,
        "Ticks": 3,
        "Program:MainProgram.Result": 3.0,  # Out = In * Gain = 1.5 * 2.0
        "Program:MainProgram.Counted": 25,  # +((N - Calls) + 1) = +1 a call: N aliases Calls
        "SpeedAlias": 7 + 2 * 25,
        "CountAlias": 30,  # V1.Hist[2]
    }


@pytest.mark.parametrize(
    ("name", "expected"),
    [
        # AND(3,5) = 2#011 AND 2#101 = 1; 7 MOD 4 = 3; Array[1] := MOD = 3;
        # NOT := AND + Array[1] * MOD = 1 + 3 * 3 = 10
        ("keyword_members", {"Kw.AND": 1, "Kw.MOD": 3, "Kw.Array[1]": 3, "Kw.NOT": 10}),
        # Source runs first in the task: Level = 5; then User: Sum = 5 + 2, Scaled = 5 * 10
        (
            "program_parameters",
            {"Program:Source.Level": 5, "Program:User.Sum": 7, "Program:User.Scaled": 50},
        ),
    ],
)
def test_ladder_twins_run_the_same(
    capsys: pytest.CaptureFixture[str], name: str, expected: dict[str, Any]
) -> None:
    argv = ["--scans", "1"] + [a for w in expected for a in ("--watch", w)]
    assert run(capsys, HERE / f"{name}.L5K", *argv) == expected
    assert run(capsys, L5X / f"{name}.L5X", *argv) == expected


def test_l5k_tags_file_supplies_controller_tags_and_types(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    st = tmp_path / "bare.st"
    st.write_text("Speed := Speed + V1.Count;\nV1.Fault := TRUE;\n")
    argv = ["--scans", "2", "--watch", "Speed", "--watch", "V1.Fault"]
    tags = run(capsys, st, *argv, "--tags", str(HERE / "st_project.L5K"))
    assert tags == {"Speed": 7 + 3 + 3, "V1.Fault": True}


def test_check_of_a_directory_takes_each_l5k_as_a_project(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    for name in ("st_errors", "st_project"):
        (tmp_path / f"{name}.L5K").write_bytes((HERE / f"{name}.L5K").read_bytes())
    code, diags = check(capsys, tmp_path)
    assert code == 1  # st_errors has two errors, st_project none
    assert sorted((Path(d["path"]).name, d["code"]) for d in diags) == [
        ("st_errors.L5K", "E101"),
        ("st_errors.L5K", "S001"),
    ]


def test_motion_twin_homes_and_gears_the_same(capsys: pytest.CaptureFixture[str]) -> None:
    watch = [
        "Master.CommandPosition",
        "Slave.CommandPosition",
        "HomeCtl.PC",
        "GearCtl.IP",
        "Master.HomeMode",
        "Master.HomeSequence",
        "Slave.HomeMode",
        "Slave.HomeDirection",
        "Master.HomePosition",
    ]
    argv = ["--scans", "300"] + [a for w in watch for a in ("--watch", w)]
    twin = Path(__file__).parent.parent / "motion_programs" / "fixtures"
    from_l5k = run(capsys, HERE / "gear_home_project.L5K", *argv)
    assert from_l5k == run(capsys, twin / "gear_home_project.L5X", *argv)
    # Attribute texts through the catalog enumerations: Passive 0, Immediate 0, Active 1,
    # Uni-directional Reverse 2; HomePosition 1.25000000e+001
    assert [from_l5k[w] for w in watch[4:]] == [0, 0, 1, 2, 12.5]
    # CoarseUpdatePeriod 4000 us. The home (master at rest: 0 -> 12.5) applies at the 4 ms
    # update, then the jog (50 % of 100 units/s, 100 % of 1000 units/s^2) and the ratio-2
    # gear start from 12.5. At the update of 296 ms the jog has run 0.292 s: travel
    # 1.25 (ramp of 0.05 s to 50 units/s) + 50 x (0.292 - 0.05) = 13.35 -> master 25.85,
    # slave 2 x 13.35 = 26.7.
    assert from_l5k["Master.CommandPosition"] == pytest.approx(25.85, abs=1e-4)
    assert from_l5k["Slave.CommandPosition"] == pytest.approx(26.7, abs=1e-4)
    assert from_l5k["HomeCtl.PC"] is True and from_l5k["GearCtl.IP"] is True
