"""The v36+ time and date types DT, LDT, TIME, TIME32, LTIME (decision 0072).

Logix documents them as signed counts: DT and TIME in microseconds (64-bit), TIME32 in
microseconds (32-bit), LDT and LTIME in nanoseconds (64-bit), DT/LDT from 1970-01-01 UTC.
Expected counts are worked by hand in the comments; the L5K data Studio writes next to the
decorated values in L5Sharp's Test.L5X export (e.g. `-7384000001` for `T#-2h_3m_4s_1us`)
is the same arithmetic.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from interpreter.cli import main
from interpreter.syntax.l5x_data import parse_duration, parse_value
from tests.conftest import Runner

FIXTURE = Path(__file__).parent / "fixtures" / "time_types.L5X"


@pytest.mark.parametrize(
    ("text", "count"),
    [
        # 2 h + 3 min + 4 s = 7,200 + 180 + 4 = 7,384 s = 7,384,000,000 us; + 1 us, negative
        ("T#-2h_3m_4s_1us", -7_384_000_001),
        # 35 min 47 s = 2,147 s -> 2,147,000,000 us + 483,000 + 647 = 2,147,483,647 (2^31 - 1)
        ("T32#35m_47s_483ms_647us", 2_147_483_647),
        # 10 d 7 h 35 min 47 s = 864,000 + 25,200 + 2,100 + 47 = 891,347 s, in ns,
        # + 621 us (621,000 ns) + 879 ns
        ("LT#10d_7h_35m_47s_621us_879ns", 891_347_000_621_879),
        ("LT#0ns", 0),
        ("T#0us", 0),
        ("t#1m", 60_000_000),
        ("T#1500ms", 1_500_000),
    ],
)
def test_duration_values(text: str, count: int) -> None:
    assert parse_duration(text) == count
    assert parse_value(text, "Time (us)", "TIME") == count


@pytest.mark.parametrize("text", ["T#1ns", "T#", "T#5x", "T#1s_", "LT#--1s"])
def test_malformed_durations_are_not_read(text: str) -> None:
    # T# and T32# count microseconds: nanoseconds cannot be held; the others are not durations
    assert parse_duration(text) is None


def test_fixture_checks_clean(capsys: pytest.CaptureFixture[str]) -> None:
    capsys.readouterr()
    assert main(["check", str(FIXTURE)]) == 0
    assert capsys.readouterr().out.strip() == "0 error(s), 0 warning(s)"


def _run(capsys: pytest.CaptureFixture[str], scans: int, *names: str) -> dict[str, object]:
    argv = ["run", str(FIXTURE), "--scans", str(scans), "--json"]
    for w in names:
        argv += ["--watch", w]
    capsys.readouterr()
    assert main(argv) == 0
    return json.loads(capsys.readouterr().out)["tags"]  # type: ignore[no-any-return]


def test_tag_data_forms(capsys: pytest.CaptureFixture[str]) -> None:
    tags = _run(
        capsys, 0, "Span", "Short", "Long", "Delay", "Laps[0]", "Laps[1]", "Laps[2]", "Start",
        "StartNs",
    )  # fmt: skip
    assert tags == {
        "Span": -7_384_000_001,
        "Short": 2_147_483_647,
        "Long": 891_347_000_621_879,
        "Delay": 1_500_000,  # L5K data only: the count itself
        "Laps[0]": 1_000_000,
        "Laps[1]": 500_000,
        "Laps[2]": 0,
        # 2024-03-01 12:30:15.25 UTC: 19,783 days since 1970 (54 years, 13 leap days, + 31 + 29)
        # = 1,709,251,200 s, + 45,015 s = 1,709,296,215 s, in us, + 250,000 us
        "Start": 1_709_296_215_250_000,
        "StartNs": 1_000_000_001,
    }


def test_ladder_and_st_operations(capsys: pytest.CaptureFixture[str]) -> None:
    tags = _run(
        capsys, 1, "Elapsed", "Earlier", "Late", "Raw", "Cleared", "Less", "Sum", "Diff",
        "LaterNs", "IsBefore", "Neg", "FromLint",
    )  # fmt: skip
    assert tags == {
        # SUB(Now, Start): 12:31:15.25 - 12:30:15.25 = 60 s = 60,000,000 us, a TIME
        "Elapsed": 60_000_000,
        # ADD(Start, Span): 1,709,296,215,250,000 - 7,384,000,001 = 1,709,288,831,249,999
        "Earlier": 1_709_288_831_249_999,
        "Late": True,  # GRT: 60,000,000 > 1,500,000
        "Raw": 891_347_000_621_879,  # MOV LTIME -> LINT copies the count
        "Cleared": 0,  # CLR
        # SUB(Short, 1000000): 2,147,483,647 - 1,000,000 = 2,146,483,647 (a literal counts us)
        "Less": 2_146_483_647,
        # ST: Elapsed + Delay = 60,000,000 + 1,500,000
        "Sum": 61_500_000,
        # DT - DT is a TIME: Start - Earlier = 7,384,000,001 us
        "Diff": 7_384_000_001,
        # LDT + LTIME: 1,000,000,001 + 891,347,000,621,879
        "LaterNs": 891_348_000_621_880,
        "IsBefore": True,  # Earlier < Start AND Laps[1] (500 ms) > 0
        "Neg": 7_384_000_001,  # -Span
        "FromLint": 891_347_000_621_879,  # LINT -> TIME copies the count
    }


ST_REFUSED = """VAR t, u : TIME; lt : LTIME; d : DINT; a, b : DT; s : TIME32; r : LINT; x : BOOL; END_VAR
t := d;
t := t * 2;
u := a + b;
lt := lt + t;
d := t;
r := t;
t := r;
x := t > d;
x := a > t;
u := -a;
x := NOT s;
u := t + 1000;
u := 5 - a;
"""


def test_st_refuses_what_logix_refuses(st: Runner) -> None:
    r = st.check(ST_REFUSED)
    got = [(d["line"], d["code"]) for d in r.json]
    # lines 7, 8 (LINT either way) and 13 (a literal is a count in TIME's unit) are accepted
    assert got == [(n, "E121") for n in (2, 3, 4, 5, 6, 9, 10, 11, 12, 14)]


RLL_REFUSED = """VAR t, u : TIME; lt : LTIME; d : DINT; a : DT; s : TIME32; r : LINT; END_VAR
MUL(t, 2, u);
ADD(t, d, u);
MOV(t, lt);
EQU(t, a);
MOV(t, d);
ADD(a, t, u);
SUB(a, a, u);
MOV(r, t);
LES(s, 5);
"""


def test_ladder_refuses_what_logix_refuses(st: Runner) -> None:
    r = st.check(RLL_REFUSED, name="main.rll")
    got = [(d["line"], d["code"]) for d in r.json]
    # MUL takes no time type (both time operands); ADD TIME + DINT; MOV TIME -> LTIME or
    # DINT; EQU TIME with DT; ADD DT + TIME is a DT, which a TIME Dest cannot hold. DT - DT
    # into TIME, MOV LINT -> TIME and LES TIME32 with a literal are accepted.
    assert got == [(2, "E105"), (2, "E105"), (3, "E105"), (4, "E105"), (5, "E105")] + [
        (6, "E105"),
        (7, "E105"),
    ]
