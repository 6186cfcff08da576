"""Ladder programs run through `logixst run` (SPEC 3.2, 4, 9.1, 9.4; decisions 0020-0023).

Inputs that change from scan to scan come from the program itself: a DINT `k` counts the
scans (the last rung adds 1, so scan i sees k = i) and its bits k.0, k.1, ... act as
inputs. Per-scan results are read from a `--trace` CSV. Every expected value is worked out
by hand in the comments.
"""

from __future__ import annotations

import csv
from pathlib import Path
from typing import Any

import pytest

from tests.conftest import Runner

COUNT = "CPT(k, k + 1);"  # the last rung of the stimulus programs


def tags(
    st: Runner, src: str, *watch: str, scans: int = 1, args: tuple[str, ...] = ()
) -> dict[str, Any]:
    r = st.run(src, *watch, scans=scans, args=args, name="main.rll")
    assert r.code == 0, (r.code, r.err, r.out)
    return r.tags


def trace(
    st: Runner, src: str, watch: list[str], scans: int, files: dict[str, str] | None = None
) -> dict[str, list[float]]:
    """Per-scan values of `watch` (one list per expression, index = scan)."""
    main = st.write("main.rll", src)
    extra = [str(st.write(name, text)) for name, text in (files or {}).items()]
    out = st.tmp / "trace.csv"
    argv = ["run", str(main), *extra, "--scans", str(scans), "--trace", str(out)]
    for w in watch:
        argv += ["--watch", w]
    r = st.cli(*argv)
    assert r.code == 0, (r.code, r.err)
    with out.open() as fh:
        rows = list(csv.DictReader(fh))
    return {w: [float(row[w]) for row in rows] for w in watch}


def bits(values: list[float]) -> list[int]:
    return [int(v) for v in values]


# ------------------------------------------------------------------ rung logic
def test_series_parallel_truth_table(st: Runner) -> None:
    src = f"""VAR k : DINT; q1, q2, q3 : BOOL; END_VAR
    XIC(k.0) XIO(k.1) OTE(q1);
    [XIC(k.0), XIC(k.1)] XIO(k.2) OTE(q2);
    XIC(k.2) [XIO(k.0), XIC(k.1) XIC(k.0)] OTE(q3);
    {COUNT}
    """
    t = trace(st, src, ["q1", "q2", "q3"], 8)
    # k    : 0 1 2 3 4 5 6 7     a = k.0, b = k.1, c = k.2
    # q1 = a AND NOT b                     -> true for k = 1, 5
    # q2 = (a OR b) AND NOT c              -> true for k = 1, 2, 3
    # q3 = c AND (NOT a OR (b AND a))      -> true for k = 4, 6, 7 (k = 5: a AND NOT b)
    assert bits(t["q1"]) == [0, 1, 0, 0, 0, 1, 0, 0]
    assert bits(t["q2"]) == [0, 1, 1, 1, 0, 0, 0, 0]
    assert bits(t["q3"]) == [0, 0, 0, 0, 1, 0, 1, 1]


def test_branches_nested_three_deep(st: Runner) -> None:
    src = f"""VAR k : DINT; q, o1, o2, o3, o3b, q2 : BOOL; END_VAR
    XIC(k.0)[XIC(k.1)[XIC(k.2)[XIC(k.3),XIO(k.4)],XIO(k.2)XIC(k.4)],XIO(k.1)]OTE(q);
    XIC(k.0)[XIC(k.1)[XIC(k.2)[OTE(o3),XIO(k.3)OTE(o3b)]OTE(o2),XIO(k.2)]OTE(o1),XIO(k.1)]OTE(q2);
    {COUNT}
    """
    t = trace(st, src, ["q", "o1", "o2", "o3", "o3b", "q2"], 32)
    for k in range(32):
        a, b, c, d, e = ((k >> i) & 1 for i in range(5))
        # rung 1, read off the rung by hand, innermost branch first:
        #   inner  = d OR NOT e;  middle = (c AND inner) OR (NOT c AND e)
        #   q      = a AND ((b AND middle) OR NOT b)
        inner = d or not e
        middle = (c and inner) or (not c and e)
        q = a and ((b and middle) or not b)
        # rung 2: o3 sees a.b.c; o3b a.b.c.NOT d; the inner branch ORs to a.b.c, so o2 = a.b.c;
        # the middle branch is a.b.c OR a.b.NOT c = a.b = o1; the outer a.b OR a.NOT b = a = q2
        expect = {
            "q": q,
            "o3": a and b and c,
            "o3b": a and b and c and not d,
            "o2": a and b and c,
            "o1": a and b,
            "q2": a,
        }
        for name, value in expect.items():
            assert t[name][k] == (1 if value else 0), (name, k)
    # a few rows of rung 1 written out: k = 1 (a only): NOT b -> 1; k = 3 (a, b; c = 0,
    # e = 0): middle = 0 -> 0; k = 19 (a, b, e; c = 0): middle = e = 1 -> 1; k = 23 (a b c e,
    # d = 0): inner = 0 -> 0; k = 31: inner = d = 1 -> 1
    assert [t["q"][k] for k in (1, 3, 19, 23, 31)] == [1, 0, 1, 0, 1]


def test_empty_legs_are_true(st: Runner) -> None:
    src = f"""VAR k : DINT; e1, e2, e3, e4 : BOOL; END_VAR
    XIC(k.0)[,XIC(k.1)]OTE(e1);
    [XIC(k.0),]OTE(e2);
    XIC(k.0)[OTE(e3),]XIC(k.1)OTE(e4);
    {COUNT}
    """
    t = trace(st, src, ["e1", "e2", "e3", "e4"], 4)
    # e1 = a AND (TRUE OR b) = a; e2 = a OR TRUE = 1; e3 = a; e4 = a AND (a OR a) AND b
    assert bits(t["e1"]) == [0, 1, 0, 1]
    assert bits(t["e2"]) == [1, 1, 1, 1]
    assert bits(t["e3"]) == [0, 1, 0, 1]
    assert bits(t["e4"]) == [0, 0, 0, 1]


def test_reals_with_the_point_first_or_last(st: Runner) -> None:
    # `.25`, `5.` and `y*.6` as real exports write them (issue 9); `d.5` stays bit 5 of d.
    src = """VAR r, s, x, y, z : REAL; d : DINT; q : BOOL; END_VAR
    MOV(.25,r)MOV(5.,s)MOV(10.0,y)MOV(16#20,d);
    CPT(x,y*.6)CPT(z,-.5+2.*r);
    XIC(d.5)OTE(q);
    """
    t = tags(st, src, "r", "s", "x", "z", "q")
    assert t["r"] == 0.25
    assert t["s"] == 5.0
    assert abs(t["x"] - 6.0) < 1e-5  # 10 * 0.6 in float32
    assert t["z"] == 0.0  # -0.5 + 2 * 0.25
    assert t["q"] is True  # 16#20 has bit 5 set


def test_latch_and_unlatch(st: Runner) -> None:
    src = f"""VAR k : DINT; lat : BOOL; END_VAR
    EQU(k, 1) OTL(lat);
    EQU(k, 3) OTU(lat);
    {COUNT}
    """
    # set in scan 1, held through scan 2 (rung false: OTL leaves it), cleared in scan 3
    assert bits(trace(st, src, ["lat"], 5)["lat"]) == [0, 1, 1, 0, 0]


def test_compares_at_the_equal_boundary_and_in_the_promoted_type(st: Runner) -> None:
    src = """VAR
      d : DINT := 3; i : INT := 2; r : REAL := 2.5; r01 : REAL := 0.1; l01 : LREAL := 0.1;
      le, ge, lt, gt, eq, ne, mix_ge, mix_le, eq32, eq64 : BOOL;
    END_VAR
    LEQ(r, 2.5) OTE(le);
    GEQ(d, 3) OTE(ge);
    LES(d, 3) OTE(lt);
    GRT(r, 2.5) OTE(gt);
    EQU(d, 3.0) OTE(eq);
    NEQ(d, 3) OTE(ne);
    GEQ(i, r) OTE(mix_ge);
    LEQ(i, r) OTE(mix_le);
    EQU(r01, 0.1) OTE(eq32);
    EQU(l01, r01) OTE(eq64);
    """
    t = tags(st, src, "le", "ge", "lt", "gt", "eq", "ne", "mix_ge", "mix_le", "eq32", "eq64")
    # 2.5 <= 2.5 and 3 >= 3 hold, the strict forms do not; 3 = 3.0 compared in REAL;
    # INT 2 vs REAL 2.5 in REAL: 2.0 >= 2.5 false, 2.0 <= 2.5 true.
    # r01 holds float32(0.1); the literal 0.1 in a REAL compare is float32(0.1) too: equal.
    # LREAL 0.1 (double) vs REAL r01 compares in LREAL: float32(0.1) = 0.100000001490116...
    # differs from the double 0.1: not equal.
    assert t == {
        "le": True,
        "ge": True,
        "lt": False,
        "gt": False,
        "eq": True,
        "ne": False,
        "mix_ge": False,
        "mix_le": True,
        "eq32": True,
        "eq64": False,
    }


def test_cmp_expression_is_the_rung_condition(st: Runner) -> None:
    src = """VAR a : DINT := 6; b : REAL := 2.5; q1, q2, q3 : BOOL; END_VAR
    CMP(a * b > 14) OTE(q1);
    CMP((a MOD 4) <> 2) OTE(q2);
    CMP(a / 4 = 1 AND b < 3) OTE(q3);
    """
    # 6 * 2.5 = 15.0 > 14; 6 MOD 4 = 2 so '<> 2' is false; 6 / 4 = 1 in DINT and 2.5 < 3
    assert tags(st, src, "q1", "q2", "q3") == {"q1": True, "q2": False, "q3": True}


# ------------------------------------------------------------------ MOV, CPT, flags
def test_cpt_evaluates_in_the_promoted_type_and_converts_at_the_end(st: Runner) -> None:
    src = """VAR d1, d2, d3, d4, d5 : DINT; r1 : REAL; s1 : SINT; i1 : INT := 300; END_VAR
    CPT(d1, 10 / 4);
    CPT(d2, 10 / 4.0);
    CPT(d3, 7 * 0.5);
    CPT(r1, 10 / 4);
    CPT(s1, 100 + 100);
    CPT(d4, i1 * i1);
    CPT(d5, -5 / 2.0);
    """
    t = tags(st, src, "d1", "d2", "d3", "d4", "d5", "r1", "s1")
    # 10 / 4 in DINT = 2; 10 / 4.0 = 2.5 -> ties to even 2; 7 * 0.5 = 3.5 -> 4;
    # REAL dest of the DINT quotient 2 -> 2.0; 200 into SINT wraps to 200 - 256 = -56;
    # INT * INT stays INT: 90000 - 65536 = 24464; -2.5 -> ties to even -2
    assert t == {"d1": 2, "d2": 2, "d3": 4, "d4": 24464, "d5": -2, "r1": 2.0, "s1": -56}


def test_cpt_real_mod_of_infinity_is_nan(st: Runner) -> None:
    # TRUNC(inf / 2.0) has no integer value: the ladder CPT MOD raised OverflowError (a
    # traceback, found by fuzzing). IEEE fmod: inf MOD 2.0 = NaN, 7.5 MOD inf = 7.5.
    src = """VAR inf : REAL; m1, m2 : REAL; END_VAR
    CPT(inf, 3.0e38 * 10.0);
    CPT(m1, inf MOD 2.0);
    CPT(m2, 7.5 MOD inf);
    """
    r = st.run(src, "inf", "m1", "m2", name="main.rll")
    assert r.code == 0, r.err
    t = r.tags
    # non-finite REALs are JSON strings (docs/decisions/0132)
    assert t["inf"] == "Infinity" and t["m1"] == "NaN" and t["m2"] == 7.5


def test_mov_converts_like_an_assignment_and_sets_flags(st: Runner) -> None:
    src = """VAR
      src : DINT := 200; s : SINT; r : REAL := 2.5; d : DINT; big : REAL := 3.0e9; d2 : DINT;
      n1, z1, v1, n2, z2, v2, v3 : BOOL;
    END_VAR
    MOV(src, s) [XIC(S:N) OTE(n1), XIC(S:Z) OTE(z1), XIC(S:V) OTE(v1)];
    MOV(r, d) [XIC(S:N) OTE(n2), XIC(S:Z) OTE(z2), XIC(S:V) OTE(v2)];
    MOV(big, d2) XIC(S:V) OTE(v3);
    """
    r = st.run(src, "s", "d", "n1", "z1", "v1", "n2", "z2", "v2", "v3", name="main.rll")
    assert r.code == 0, r.err
    # 200 -> SINT -56: negative, overflow; 2.5 -> DINT 2 (ties to even): no flag;
    # 3.0e9 does not fit a DINT: overflow
    assert r.tags == {
        "s": -56,
        "d": 2,
        "n1": True,
        "z1": False,
        "v1": True,
        "n2": False,
        "z2": False,
        "v2": False,
        "v3": True,
    }
    # each overflow is also minor fault 4/4 at its MOV (lines 5 and 7)
    minors = [(f["type"], f["code"], f["line"]) for f in r.json["faults"]]
    assert minors == [(4, 4, 5), (4, 4, 7)]


def test_cpt_overflow_inside_the_expression_sets_v(st: Runner) -> None:
    """S:V also reports an operation of the expression that overflowed, not only the store
    (5580 math status flags: the result of a math operation overflowed); decision 0025."""
    src = """VAR
      big : DINT := 1000000000; d1, d2, d3 : DINT; huge : REAL := 1.0e20; r1 : REAL;
      n1, z1, v1, n2, z2, v2, v3, v4 : BOOL;
    END_VAR
    CPT(d1, big * 4 / 4) [XIC(S:N) OTE(n1), XIC(S:Z) OTE(z1), XIC(S:V) OTE(v1)];
    CPT(r1, 1.0 / (huge * huge)) [XIC(S:N) OTE(n2), XIC(S:Z) OTE(z2), XIC(S:V) OTE(v2)];
    CPT(d2, 2 + 3 * 4) XIC(S:V) OTE(v3);
    CPT(d3, big * 2) XIC(S:V) OTE(v4);
    """
    r = st.run(
        src, "d1", "r1", "d2", "d3", "n1", "z1", "v1", "n2", "z2", "v2", "v3", "v4", name="main.rll"
    )
    assert r.code == 0, r.err
    # DINT: 1e9 * 4 = 4 000 000 000 wraps to 4 000 000 000 - 2^32 = -294 967 296, / 4 =
    # -73 741 824, which fits the DINT Dest: only the intermediate product overflowed.
    # REAL: 1e20 * 1e20 = 1e40 > 3.4028235e38 (largest REAL) -> +inf; 1.0 / inf = 0.0 stored,
    # finite: again only the intermediate overflowed (Z from the stored 0.0).
    # 2 + 3 * 4 = 14: nothing overflows, V is cleared again.
    # 1e9 * 2 = 2 000 000 000 fits a DINT (max 2 147 483 647): no overflow.
    assert r.tags == {
        "d1": -73741824,
        "r1": 0.0,
        "d2": 14,
        "d3": 2000000000,
        "n1": True,
        "z1": False,
        "v1": True,
        "n2": False,
        "z2": True,
        "v2": True,
        "v3": False,
        "v4": False,
    }
    # one minor fault 4/4 per overflowing CPT, at the instruction (lines 5 and 6)
    minors = [(f["type"], f["code"], f["line"], f["count"]) for f in r.json["faults"]]
    assert minors == [(4, 4, 5, 1), (4, 4, 6, 1)]


def test_cpt_integer_divide_by_zero_inside_the_expression_sets_v(st: Runner) -> None:
    src = """VAR a : DINT := 7; zero : DINT; d : DINT; v : BOOL; END_VAR
    CPT(d, a / zero + 1) XIC(S:V) OTE(v);
    """
    r = st.run(src, "d", "v", name="main.rll")
    assert r.code == 0, r.err
    # integer divide by zero leaves Source A (7), + 1 = 8; it counts as an overflow (as for
    # the DIV instruction) and is recorded once, at the CPT, as minor fault 4/4
    assert r.tags == {"d": 8, "v": True}
    assert [(f["type"], f["code"], f["line"]) for f in r.json["faults"]] == [(4, 4, 2)]


def test_fal_overflow_inside_the_expression_stops_with_er(st: Runner) -> None:
    src = """VAR src : DINT[3] := [1, 1000000000, 2]; dst : DINT[3]; ctl : CONTROL; END_VAR
    FAL(ctl, 3, 0, ALL, dst[ctl.POS], src[ctl.POS] * 4 / 4);
    """
    r = st.run(src, "dst", "ctl.ER", "ctl.POS", "ctl.DN", name="main.rll")
    assert r.code == 0, r.err
    # element 0: 1 * 4 / 4 = 1; element 1: the product 4e9 overflows (stored -73 741 824 as
    # in the CPT case) -> ER, the instruction stops on element 1; element 2 is not reached
    assert r.tags == {"dst": [1, -73741824, 0], "ctl.ER": True, "ctl.POS": 1, "ctl.DN": False}


# ------------------------------------------------------------------ prescan
def test_prescan_clears_ote_and_timer_bits_keeps_latches(st: Runner) -> None:
    src = """VAR coil, lat, never : BOOL; t : TIMER; END_VAR
    XIC(never) OTE(coil);
    XIC(never) OTL(lat);
    XIC(never) TON(t, 500, 0);
    """
    args = (
        "--set",
        "coil=1",
        "--set",
        "lat=1",
        "--set",
        "t.ACC=40",
        "--set",
        "t.DN=1",
        "--set",
        "t.EN=1",
    )
    t = tags(st, src, "coil", "lat", "t", scans=0, args=args)
    # --set comes before the prescan: the OTE is cleared, the OTL is retentive, the TON
    # clears EN/TT/DN and ACC and takes its preset from the rung
    assert t["coil"] is False and t["lat"] is True
    assert t["t"] == {"PRE": 500, "ACC": 0, "EN": False, "TT": False, "DN": False}


def test_mov_and_cpt_do_not_run_in_prescan(st: Runner) -> None:
    src = """VAR a : DINT := 5; b : DINT := 1; END_VAR
    MOV(99, a);
    CPT(b, b + 10);
    """
    assert tags(st, src, "a", "b", scans=0) == {"a": 5, "b": 1}
    assert tags(st, src, "a", "b", scans=2) == {"a": 99, "b": 21}


# ------------------------------------------------------------------ MCR, JMP/LBL, TND
def test_mcr_zone(st: Runner) -> None:
    src = f"""VAR k : DINT; inz, latz, outz : BOOL; END_VAR
    XIC(k.0) MCR();
    XIC(k.1) OTE(inz);
    XIC(k.1) OTL(latz);
    MCR();
    XIC(k.1) OTE(outz);
    {COUNT}
    """
    t = trace(st, src, ["inz", "latz", "outz"], 5)
    # zone = k.0, input b = k.1
    # k=0: zone off -> inz 0, latz 0, outz = b = 0
    # k=1: zone on, b = 0 -> 0, 0, 0
    # k=2: zone off -> inz 0 although b = 1; latz untouched (0); outz = 1 (after the zone)
    # k=3: zone on, b = 1 -> inz 1, latz latched 1, outz 1
    # k=4: zone off -> inz 0, latz stays 1, outz 0
    assert bits(t["inz"]) == [0, 0, 0, 1, 0]
    assert bits(t["latz"]) == [0, 0, 0, 1, 1]
    assert bits(t["outz"]) == [0, 0, 1, 1, 0]


def test_jmp_forward_skips_rungs_which_keep_their_outputs(st: Runner) -> None:
    src = """VAR k, cnt : DINT; mid : BOOL; END_VAR
    XIC(k.0) JMP(skip);
    XIC(k.1) OTE(mid);
    CPT(cnt, cnt + 1);
    LBL(skip) CPT(k, k + 1);
    """
    t = trace(st, src, ["mid", "cnt"], 5)
    # odd k jumps over the two middle rungs: mid and cnt keep their values
    # k=0: mid 0, cnt 1; k=1: skipped (0, 1); k=2: mid 1, cnt 2; k=3: skipped; k=4: mid 0, cnt 3
    assert bits(t["mid"]) == [0, 0, 1, 1, 0]
    assert bits(t["cnt"]) == [1, 1, 2, 2, 3]


def test_jmp_backward_loops(st: Runner) -> None:
    src = """VAR i, total : DINT; END_VAR
    MOV(0, i) MOV(0, total);
    LBL(again) CPT(i, i + 1) CPT(total, total + i * i);
    LES(i, 5) JMP(again);
    """
    # 1 + 4 + 9 + 16 + 25 = 55
    assert tags(st, src, "i", "total") == {"i": 5, "total": 55}


def test_endless_backward_jump_trips_the_watchdog(st: Runner) -> None:
    src = """VAR n : DINT; END_VAR
    LBL(spin) CPT(n, n + 1) JMP(spin);
    """
    r = st.run(src, "n", args=("--watchdog", "3000"), name="main.rll")
    assert r.code == 3
    f = r.json["faults"]
    # at the JMP: line 2, column 29 (the rung keeps its 4-space indent: dedent finds none
    # because the first line starts at the quotes)
    assert [(x["type"], x["code"], x["major"], x["line"], x["column"]) for x in f] == [
        (6, 1, True, 2, 29)
    ]
    # 3 instructions per pass: the check at the JMP of pass 1000 sees exactly 3000 (not
    # over), pass 1001 sees 3003: n = 1001 when the scan stops
    assert r.tags == {"n": 1001}


def test_tnd_ends_the_routine_and_returns_from_a_subroutine(st: Runner) -> None:
    src = """VAR stop : BOOL; n, m, after, x : DINT; END_VAR
    CPT(n, n + 1);
    XIC(stop) TND();
    CPT(m, m + 1);
    JSR(sub, 0) CPT(after, after + 1);
    """
    sub = "TND();\nCPT(x, 1);\n"
    st.write("sub.rll", sub)
    main = st.write("main.rll", src)
    r = st.cli(
        "run",
        str(main),
        str(st.tmp / "sub.rll"),
        "--scans",
        "3",
        "--json",
        "--watch",
        "n",
        "--watch",
        "m",
        "--watch",
        "after",
        "--watch",
        "x",
    )
    assert r.code == 0, r.err
    # no stop: every rung runs 3 times; the subroutine ends at its TND, so x stays 0
    assert r.tags == {"n": 3, "m": 3, "after": 3, "x": 0}
    r = st.cli(
        "run",
        str(main),
        str(st.tmp / "sub.rll"),
        "--scans",
        "3",
        "--json",
        "--set",
        "stop=1",
        "--watch",
        "n",
        "--watch",
        "m",
        "--watch",
        "after",
    )
    assert r.tags == {"n": 3, "m": 0, "after": 0}


# ------------------------------------------------------------------ JSR / SBR / RET
def test_jsr_with_parameters_between_ladder_and_st(st: Runner) -> None:
    main = """VAR
      x : DINT := 7; y : REAL := 1.5; r1 : DINT; r2 : REAL; r3 : DINT;
      p1 : DINT; p2 : REAL; s : REAL; a, n1 : DINT;
    END_VAR
    JSR(scale, 2, x, y, r1, r2);
    JSR(triple, 1, 4, r3);
    """
    files = {
        "scale.rll": "SBR(p1, p2);\nCPT(s, p1 * p2) CPT(n1, p1 + 1);\nRET(s, n1);\n",
        "triple.st": "SBR(a);\nRET(a * 3);\n",
    }
    t = trace(st, main, ["r1", "r2", "r3", "s"], 1, files)
    # scale: p1 = 7, p2 = 1.5, s = 10.5; RET hands back 10.5 -> DINT r1 rounds half to
    # even = 10, and 7 + 1 = 8 -> REAL r2 = 8.0; triple (ST): 4 * 3 = 12
    assert (t["s"], t["r1"], t["r2"], t["r3"]) == ([10.5], [10.0], [8.0], [12.0])


def test_st_calls_a_ladder_subroutine(st: Runner) -> None:
    main = st.write(
        "main.st", "VAR v : DINT := 21; w : DINT; q : DINT; END_VAR\nJSR(twice, 1, v, w);\n"
    )
    st.write("twice.rll", "SBR(q);\nCPT(q, q * 2);\nRET(q);\n")
    r = st.cli("run", str(main), str(st.tmp / "twice.rll"), "--json", "--watch", "w")
    assert r.code == 0, r.err
    assert r.tags == {"w": 42}


def test_jsr_with_fewer_inputs_than_the_sbr_faults_4_31(st: Runner) -> None:
    # 1756-RM003: "JSR instruction has fewer input parameters than SBR instruction" is a
    # major fault, type 4 code 31 (decision 0073)
    main = st.write("main.rll", "VAR a, p, q : DINT; END_VAR\nJSR(sub, 1, a);\n")
    st.write("sub.rll", "SBR(p, q);\nNOP();\n")
    r = st.cli("run", str(main), str(st.tmp / "sub.rll"), "--json")
    assert r.code == 3
    assert [(f["type"], f["code"], f["line"]) for f in r.json["faults"]] == [(4, 31, 2)]


def test_jsr_inputs_beyond_the_sbr_are_not_received(st: Runner) -> None:
    # More inputs than the SBR takes is no fault: the SBR receives the first ones, the others
    # are dropped; a routine without SBR receives none (Rockwell's ControllerLogServices
    # sample calls `JSR(Initialize,1,ControllerSlot,Messages_OK)` with no SBR in Initialize).
    main = st.write(
        "main.rll",
        "VAR a : DINT := 5; b : DINT := 9; p, q, r : DINT; END_VAR\n"
        "JSR(sub, 2, a, b);\nJSR(plain, 1, a, r);\n",
    )
    st.write("sub.rll", "SBR(p);\nADD(p, 1, q);\n")
    st.write("plain.rll", "RET(7);\n")
    r = st.cli(
        "run",
        str(main),
        str(st.tmp / "sub.rll"),
        str(st.tmp / "plain.rll"),
        "--json",
        "--watch",
        "p",
        "--watch",
        "q",
        "--watch",
        "r",
    )
    assert r.code == 0, r.err
    # p receives a = 5 (b is dropped), q = 5 + 1 = 6; plain's RET(7) still comes back into r
    assert r.tags == {"p": 5, "q": 6, "r": 7}


# ------------------------------------------------------------------ FAL / FSC
FILE_VARS = """VAR
  k : DINT; ctl : CONTROL;
  src : DINT[5] := [1, 7, 3, 7, 5];
  dst : DINT[5];
END_VAR
"""


def test_fal_all_mode(st: Runner) -> None:
    src = (
        FILE_VARS
        + f"""EQU(k, 0) FAL(ctl, 5, 0, ALL, dst[ctl.POS], src[ctl.POS] * 2 + 1);
    {COUNT}
    """
    )
    t = trace(st, src, ["dst[0]", "dst[4]", "ctl.POS", "ctl.DN", "ctl.EN"], 3)
    # scan 0: the whole array in one scan, 2 * src + 1 = [3, 15, 7, 15, 11], POS = LEN = 5, DN;
    # scan 1: the rung is false: EN off, DN cleared and POS back to 0 (re-armed)
    assert t["dst[0]"][0] == 3 and t["dst[4]"][0] == 11
    assert bits(t["ctl.POS"]) == [5, 0, 0]
    assert bits(t["ctl.DN"]) == [1, 0, 0]
    assert bits(t["ctl.EN"]) == [1, 0, 0]


def test_fal_inc_mode_one_element_per_rising_edge(st: Runner) -> None:
    src = (
        FILE_VARS
        + f"""XIC(k.1) FAL(ctl, 3, 0, INC, dst[ctl.POS], src[ctl.POS] + 100);
    {COUNT}
    """
    )
    t = trace(st, src, ["ctl.POS", "ctl.DN", "dst[0]", "dst[1]", "dst[2]"], 16)
    # the rung (k.1) rises at k = 2, 6, 10, 14: one element each; the third one finishes
    # (POS = LEN = 3, DN); the rung falls at k = 12 and re-arms it (POS 0), so k = 14 starts over
    assert bits(t["ctl.POS"]) == [0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 0, 0, 1, 1]
    assert bits(t["ctl.DN"]) == [0] * 10 + [1, 1] + [0] * 4
    assert (t["dst[0]"][-1], t["dst[1]"][-1], t["dst[2]"][-1]) == (101, 107, 103)


def test_fsc_all_mode_finds_each_match(st: Runner) -> None:
    src = (
        FILE_VARS
        + f"""FSC(ctl, 5, 0, ALL, src[ctl.POS] = 7);
    XIC(ctl.FD) EQU(k, 1) OTU(ctl.IN);
    {COUNT}
    """
    )
    t = trace(st, src, ["ctl.POS", "ctl.FD", "ctl.IN", "ctl.DN"], 4)
    # scan 0: first 7 at element 1 (FD, IN); scan 1: inhibited, then the second rung clears
    # IN; scan 2: resumes at element 2, next 7 at 3; scan 3: still inhibited
    assert bits(t["ctl.POS"]) == [1, 1, 3, 3]
    assert bits(t["ctl.FD"]) == [1, 1, 1, 1]
    assert bits(t["ctl.IN"]) == [1, 0, 1, 1]
    assert bits(t["ctl.DN"]) == [0, 0, 0, 0]


def test_fsc_inc_mode_searches_one_element_per_transition(st: Runner) -> None:
    src = (
        FILE_VARS
        + f"""XIC(k.0) FSC(ctl, 5, 0, INC, src[ctl.POS] >= 5);
    {COUNT}
    """
    )
    t = trace(st, src, ["ctl.POS", "ctl.FD"], 6)
    # rising edges at k = 1, 3, 5: element 0 (1 >= 5 no), element 1 (7: found, POS stays 1)
    assert bits(t["ctl.POS"]) == [0, 1, 1, 1, 1, 1]
    assert bits(t["ctl.FD"]) == [0, 0, 0, 1, 1, 1]


# ------------------------------------------------------------------ transitional edge
def test_transitional_instruction_runs_on_the_rising_edge_only(
    st: Runner, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The edge contract (HELPERS.md), with a stand-in MSO that logs its calls."""
    from interpreter.instructions import registry

    calls: list[tuple[float, bool]] = []
    registry.load_all()
    monkeypatch.setitem(
        registry.IMPLEMENTATIONS,
        "MSO@rll",
        lambda ctx, rung, ax, mc: calls.append((ctx.now_ms, rung)),
    )
    src = f"""VAR k : DINT; ax : AXIS_VIRTUAL; mc : MOTION_INSTRUCTION; END_VAR
    [EQU(k, 0), EQU(k, 1), GEQ(k, 4)] MSO(ax, mc);
    {COUNT}
    """
    r = st.run(src, "k", scans=7, name="main.rll")
    assert r.code == 0, r.err
    # rung true at k = 0, 1, 4, 5, 6 and false at 2, 3 (scan period 1 ms): True at the rise in
    # the first scan (prescan clears the edge), False in each false scan, True at k = 4
    assert calls == [(0.0, True), (2.0, False), (3.0, False), (4.0, True)]


def test_ladder_file_without_header_uses_tags_of_the_other_files(
    st: Runner, tmp_path: Path
) -> None:
    main = st.write("main.st", "VAR go, lamp : BOOL; END_VAR\nJSR(logic);\n")
    st.write("logic.rll", "XIC(go) OTE(lamp);\n")
    r = st.cli(
        "run", str(main), str(tmp_path / "logic.rll"), "--json", "--set", "go=1", "--watch", "lamp"
    )
    assert r.code == 0, r.err
    assert r.tags == {"lamp": True}


def test_st_jsr_passes_expressions_into_a_ladder_subroutine(st: Runner) -> None:
    main = st.write(
        "main.st",
        "VAR a : DINT := 2; b : DINT := 3; r, p, q, s : DINT; END_VAR\n"
        "JSR(sub, 2, a + 1, b * 2, r);\n",
    )
    st.write("sub.rll", "SBR(p, q);\nCPT(s, p * 10 + q);\nRET(s);\n")
    r = st.cli("run", str(main), str(st.tmp / "sub.rll"), "--json", "--watch", "r")
    assert r.code == 0, r.err
    # p = 2 + 1 = 3, q = 3 * 2 = 6: 3 * 10 + 6 = 36
    assert r.tags == {"r": 36}


def test_st_tnd_and_first_scan_flag_in_ladder(st: Runner) -> None:
    main = st.write(
        "main.st", "VAR n, m, f : DINT; END_VAR\nn := n + 1;\nJSR(lad);\nTND();\nm := m + 1;\n"
    )
    st.write("lad.rll", "XIC(S:FS) CPT(f, f + 1);\n")
    r = st.cli(
        "run",
        str(main),
        str(st.tmp / "lad.rll"),
        "--scans",
        "3",
        "--json",
        "--watch",
        "n",
        "--watch",
        "m",
        "--watch",
        "f",
    )
    assert r.code == 0, r.err
    # TND ends the ST routine before m; S:FS is true in the first normal scan only
    assert r.tags == {"n": 3, "m": 0, "f": 1}


def test_afi_makes_the_rest_of_the_rung_false(st: Runner) -> None:
    src = """VAR a : BOOL := TRUE; q1, q2, q3 : BOOL; END_VAR
    XIC(a) OTE(q1) AFI() OTE(q2);
    [AFI(), XIC(a)] OTE(q3);
    """
    # q1 sees a = 1 before the AFI; q2 after it is false; the branch is AFI OR a = 1
    assert tags(st, src, "q1", "q2", "q3", args=("--set", "q2=1")) == {
        "q1": True,
        "q2": False,
        "q3": True,
    }


def test_subscript_fault_points_at_the_instruction(st: Runner) -> None:
    src = """VAR i : DINT := 7; arr : DINT[5]; q : BOOL; END_VAR
    XIC(q) MOV(1, arr[i]);
    NOP() MOV(i, arr[i]);
    """
    r = st.run(src, "i", name="main.rll", args=("--set", "q=0"))
    # the first MOV is on a false rung: it does not run, so no subscript check (1756-PM004);
    # the second faults 4/20 at its mnemonic: line 3, column 11
    assert r.code == 3
    assert [(f["type"], f["code"], f["line"], f["column"]) for f in r.json["faults"]] == [
        (4, 20, 3, 11)
    ]


def test_conveyor_sample_runs_as_its_comment_says(st: Runner) -> None:
    import numpy as np

    sample = Path(__file__).resolve().parents[2] / "samples" / "conveyor.rll"
    r = st.cli(
        "run",
        str(sample),
        "--duration",
        "6",
        "--set",
        "StartPB=1",
        "--json",
        "--watch",
        "Motor",
        "--watch",
        "BoxCount.ACC",
        "--watch",
        "BatchDone",
        "--watch",
        "BeltMeters",
    )
    assert r.code == 0, r.err
    # StartDelay (2000 ms) is done in scan 2000, so Motor is on from scan 2000. BoxGap starts
    # there: the eye covers at ACC = 400 (scan 2400); DN at 500 (scan 2500); the next scan's
    # XIO(DN) resets it and the one after restarts it, so a cycle takes 502 scans. Box 5 is
    # counted in scan 2400 + 4 * 502 = 4408 (BatchDone); Run and Motor drop in scan 4409.
    # BeltMeters adds float32(30 / 60000) in float32 in scans 2000..4408: 2409 times.
    step, meters = np.float32(30.0) / np.float32(60000.0), np.float32(0.0)
    for _ in range(2409):
        meters = np.float32(meters + step)
    t = r.tags
    assert (t["Motor"], t["BoxCount.ACC"], t["BatchDone"]) == (False, 5, True)
    assert t["BeltMeters"] == float(meters)


@pytest.mark.parametrize(
    ("rungs", "message", "line"),
    [
        (
            "XIC(a)JMP(nowhere);\nLBL(here)NOP();\n",
            "no LBL(nowhere) in this routine (labels here: HERE)",
            2,
        ),
        ("LBL(x)NOP();\nLBL(x)NOP();\n", "label 'x' is already defined on rung 0", 3),
        ("XIC(a)LBL(x)NOP();\nJMP(x);\n", "LBL(x) must be the first instruction of its rung", 2),
    ],
)
def test_label_errors_are_reported_before_running(
    st: Runner, rungs: str, message: str, line: int
) -> None:
    r = st.run("VAR a : BOOL; END_VAR\n" + rungs, name="main.rll")
    assert r.code == 1
    assert [(d["code"], d["message"], d["line"]) for d in r.json["diagnostics"]] == [
        ("E131", message, line)
    ]


def test_very_long_and_deeply_nested_rungs_compile(st: Runner) -> None:
    """Python refuses ~200 nested parentheses: long series and deep branches must still run."""
    series = " ".join(f"XIO(a[{i % 300}])" for i in range(1000)) + " OTE(q1);"
    # 150 nested branches, each [XIO(a[i]) [ ... ], XIC(a[i+1])]: all a are 0, so every XIO passes
    nested = (
        "".join(f"XIO(a[{i}])[XIC(a[{i + 1}])," for i in range(150))
        + "NOP()"
        + "]" * 150
        + " OTE(q2);"
    )
    outputs = (
        "".join(f"XIO(a[{i}])[OTE(b[{i}]),XIC(a[{i}])" for i in range(150))
        + "]" * 150
        + " OTE(q3);"
    )
    src = (
        "VAR a, b : BOOL[300]; q1, q2, q3 : BOOL; END_VAR\n"
        + "\n".join([series, nested, outputs])
        + "\n"
    )
    t = tags(st, src, "q1", "q2", "q3", "b[0]", "b[1]", "b[149]")
    # all a are 0: the XIO series passes (q1), the XIO path through the nested branches
    # passes (q2). In the third rung level i is XIO(a[i]) [OTE(b[i]), XIC(a[i]) <level i+1>]:
    # b[0] sees the true rung, every deeper level sits behind a false XIC(a[i]); the outer
    # branch is true through its OTE leg (q3)
    assert t == {"q1": True, "q2": True, "q3": True, "b[0]": True, "b[1]": False, "b[149]": False}


def test_return_values_missing_or_mismatched(st: Runner) -> None:
    main = st.write("main.rll", "VAR r : DINT := 5; sel : BOOL; END_VAR\nJSR(sub, 0, r);\n")
    st.write("sub.rll", "XIC(sel) RET();\nNOP();\n")
    # sel = 0: the subroutine ends without RET, the return parameter keeps its value
    r = st.cli("run", str(main), str(st.tmp / "sub.rll"), "--json", "--watch", "r")
    assert (r.code, r.tags) == (0, {"r": 5})
    # sel = 1: RET() hands back no value where the JSR expects one: fault 4/31 at the JSR
    r = st.cli(
        "run", str(main), str(st.tmp / "sub.rll"), "--json", "--set", "sel=1", "--watch", "r"
    )
    assert r.code == 3
    assert [(f["type"], f["code"], f["line"]) for f in r.json["faults"]] == [(4, 31, 2)]


def test_compares_on_strings(st: Runner) -> None:
    src = """VAR s1 : STRING := 'abc'; s2 : STRING := 'abd'; lt, eq, ge : BOOL; END_VAR
    LES(s1, s2) OTE(lt);
    EQU(s1, s2) OTE(eq);
    GEQ(s2, s1) OTE(ge);
    """
    # character codes in order: 'c' (99) < 'd' (100)
    assert tags(st, src, "lt", "eq", "ge") == {"lt": True, "eq": False, "ge": True}
