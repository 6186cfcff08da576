"""SPEC audit (session 5): one test per SPEC statement of sections 2, 3, 4, 7 and 9 that
tests/test_spec_conformance.py does not already show, run through the `logixst` command.

Each docstring quotes the SPEC item; the expected values are worked out by hand in the
comments from SPEC's words (and Logix arithmetic), never taken from the program's output.
"""

from __future__ import annotations

import csv
from pathlib import Path

import pytest


def _trace(st, src: str, name: str, scans: int, *watch: str, args: tuple[str, ...] = ()):  # type: ignore[no-untyped-def]
    """Run `src` with `--trace`; the CSV rows as lists of strings (header first)."""
    p = st.write(name, src)
    out = Path(st.tmp) / "trace.csv"
    argv = ["run", str(p), "--scans", str(scans), "--trace", str(out), *args]
    for w in watch:
        argv += ["--watch", w]
    r = st.cli(*argv)
    with out.open(newline="") as fh:
        return r, list(csv.reader(fh))


# ------------------------------------------------------------------ 3.1 operators
def test_precedence_not_binds_tighter_than_comparison_and_arithmetic(st) -> None:
    """SPEC 3.1: precedence `**`, unary -, NOT, `* / MOD`, `+ -`, comparisons, `= <>`, `& AND`,
    XOR, OR; equal ranks left to right; NOT is bitwise on integers."""
    src = """
    VAR t : BOOL := TRUE; f : BOOL; x : DINT := 3;
        b1, b2, b3, b4, b5 : BOOL; d1, d2, d3, d4, d5 : DINT; END_VAR
    b1 := NOT 5 = 0;
    b2 := t OR f AND f;
    b3 := t XOR t OR t;
    b4 := t & f OR t;
    b5 := 1 < 2 = 3 < 4;
    d1 := NOT x + 1;
    d2 := 7 MOD 4 * 2;
    d3 := 2 ** 3 ** 2;
    d4 := 10 - 4 - 3;
    d5 := -x ** 2;
    """
    t = st.tags(src, "b1", "b2", "b3", "b4", "b5", "d1", "d2", "d3", "d4", "d5")
    assert t == {
        "b1": False,  # (NOT 5) = 0 -> -6 = 0 -> FALSE (NOT(5 = 0) would be TRUE)
        "b2": True,  # t OR (f AND f)
        "b3": True,  # (t XOR t) OR t
        "b4": True,  # (t & f) OR t
        "b5": True,  # (1 < 2) = (3 < 4): TRUE = TRUE
        "d1": -3,  # (NOT 3) + 1 = -4 + 1
        "d2": 6,  # (7 MOD 4) * 2 = 3 * 2
        "d3": 64,  # left to right: (2 ** 3) ** 2 = 8 ** 2
        "d4": 3,  # (10 - 4) - 3
        "d5": -9,  # -(3 ** 2)
    }


def test_integer_division_truncates_and_mod_follows_it(st) -> None:
    """SPEC 3.3: integer `/` truncates toward zero; `MOD` is `A - TRUNC(A/B)*B`."""
    src = """
    VAR q1, q2, m1, m2, m3 : DINT; END_VAR
    q1 := -7 / 2; q2 := 7 / -2;
    m1 := -7 MOD 2; m2 := 7 MOD -2; m3 := -7 MOD -2;
    """
    # -7/2 = -3.5 -> -3; 7/-2 -> -3; -7 - (-3)*2 = -1; 7 - (-3)(-2) = 1; -7 - 3*(-2) = -1
    assert st.tags(src, "q1", "q2", "m1", "m2", "m3") == {
        "q1": -3,
        "q2": -3,
        "m1": -1,
        "m2": 1,
        "m3": -1,
    }


def test_literal_forms(st) -> None:
    """SPEC 3.1: radix literals `2#` `8#` `16#` (zero-filled bit patterns), `_` separators,
    `U`/`L`/`UL` suffixes, REAL `1.5e3`, integer literal into a REAL."""
    src = """
    VAR h1, h2, h3, h7, n3 : DINT; h4 : SINT; h5 : INT; h6 : LINT; r1, r2 : REAL; END_VAR
    h1 := 2#1010; h2 := 8#17; h3 := 16#FF; h4 := 16#FF; h5 := 16#8000;
    h6 := 16#FFFF_FFFF_FFFF_FFFF; h7 := 1_000;
    r1 := 1.5e3; r2 := 7;
    n3 := 1U + 2L + 3UL;
    """
    t = st.tags(src, "h1", "h2", "h3", "h4", "h5", "h6", "h7", "r1", "r2", "n3")
    # 16#FF in a SINT is the bit pattern 1111_1111 = -1; 16#8000 in an INT = -32768
    assert t == {
        "h1": 10,
        "h2": 15,
        "h3": 255,
        "h4": -1,
        "h5": -32768,
        "h6": -1,
        "h7": 1000,
        "r1": 1500.0,
        "r2": 7.0,
        "n3": 6,
    }


def test_loops_case_ranges_and_bits(st) -> None:
    """SPEC 3.1: CASE lists and ranges, FOR with a negative BY, WHILE with EXIT,
    REPEAT/UNTIL, bit `d.5` and indirect bit `d.[expr]`."""
    src = """
    VAR c, i, k, w, r : DINT; d : DINT := 16#20; idx : DINT := 5; bb, bc : BOOL; END_VAR
    CASE idx OF
      1: c := 1;
      2,3,5..6: c := 2;
    ELSE c := 3;
    END_CASE;
    FOR i := 10 TO 1 BY -3 DO k := k + 1; END_FOR;
    WHILE w < 5 DO w := w + 1; IF w = 3 THEN EXIT; END_IF; END_WHILE;
    REPEAT r := r + 2; UNTIL r >= 5 END_REPEAT;
    bb := d.5;
    bc := d.[idx];
    """
    t = st.tags(src, "c", "i", "k", "w", "r", "bb", "bc")
    # 5 is in 5..6; i takes 10, 7, 4, 1 (4 passes) then -2 ends the loop; EXIT at w = 3;
    # r: 2, 4, 6 (stops at >= 5); 16#20 is bit 5
    assert t == {"c": 2, "i": -2, "k": 4, "w": 3, "r": 6, "bb": True, "bc": True}


# ------------------------------------------------------------------ 3.3 arithmetic
def test_wrap_float32_and_ties_to_even(st) -> None:
    """SPEC 3.3 / 9.13: integers wrap (two's complement); every REAL operation rounds to
    float32; REAL -> integer rounds to nearest, ties to even."""
    src = """
    VAR r1, r2 : REAL; i1 : INT; u : USINT; ud : UDINT; d1, d2, d3, d4, d5 : DINT; END_VAR
    r1 := 16777216.0 + 1.0;
    r2 := (16777216.0 + 1.0) - 16777216.0;
    i1 := 32767; i1 := i1 + 1;
    u := 255; u := u + 1;
    ud := -1;
    d1 := 0.5; d2 := 1.5; d3 := -3.5; d4 := 7.0 / 2; d5 := 2147483647 + 1;
    """
    t = st.tags(src, "r1", "r2", "i1", "u", "ud", "d1", "d2", "d3", "d4", "d5")
    # 2**24 + 1 is not a float32: the sum is 2**24, so the difference is 0 (in double it would be 1)
    assert t == {
        "r1": 16777216.0,
        "r2": 0.0,
        "i1": -32768,
        "u": 0,
        "ud": 4294967295,
        "d1": 0,
        "d2": 2,
        "d3": -4,
        "d4": 4,  # 3.5 -> 4 (even)
        "d5": -2147483648,
    }


def test_divide_by_zero_results_and_minor_fault_entries(st) -> None:
    """SPEC 3.3 / 9.5: divide or MOD by zero records minor fault 4/4 and goes on; REAL results
    are IEEE, integer `/` gives Source A, MOD gives 0; one entry per location with a count."""
    src = """
    VAR r1, r3 : REAL; d5, d6 : DINT; END_VAR
    r1 := 1.0 / 0.0;
    r3 := 0.0 / 0.0;
    d5 := 7 / 0;
    d6 := 7 MOD 0;
    """
    r = st.run(src, "r1", "r3", "d5", "d6", scans=3)
    assert r.code == 0
    # strict JSON writes the non-finite REALs as strings (decision 0132)
    assert (r.tags["r1"], r.tags["r3"]) == ("Infinity", "NaN")
    assert (r.tags["d5"], r.tags["d6"]) == (7, 0)
    # four places (lines 3..6 after the dedent's leading blank line), each faulted in 3 scans
    assert [
        (f["type"], f["code"], f["major"], f["line"], f["column"], f["count"])
        for f in r.json["faults"]
    ] == [(4, 4, False, line, 7, 3) for line in (3, 4, 5, 6)]


def test_string_escapes_every_form(st) -> None:
    """SPEC 9.14: `$$`, `$'`, `$L` and `$N` (line feed), `$R`, `$T`, `$P`, `$hh` (hex byte)."""
    src = """
    VAR s : STRING; n : DINT; END_VAR
    s := 'a$$b$'c$Ld$ne$Rf$tg$Ph$41$7e';
    n := s.LEN;
    """
    t = st.tags(src, "s", "n")
    # a $ b ' c LF d LF e CR f TAB g FF h A ~ : 17 characters
    assert t == {"s": "a$b'c\nd\ne\rf\tg\fhA~", "n": 17}


# ------------------------------------------------------------------ 3.2 ladder
LADDER_BITS = """\
VAR go : BOOL; tf : TIMER := (PRE := 2); c : COUNTER := (PRE := 2); n : DINT; cnt : DINT;
    osb : BOOL; r : TIMER := (PRE := 3); o : BOOL; stop : BOOL; END_VAR
ADD(n,1,n);
EQU(n,2) OTE(go);
EQU(n,4) OTL(go);
EQU(n,5) OTU(go);
XIC(go) TOF(tf,?,?);
XIC(go) CTU(c,?,?);
XIC(go) ONS(osb) ADD(cnt,1,cnt);
XIO(go) RTO(r,?,?);
EQU(n,9) RES(r);
[XIC(go) , XIC(o)] XIO(stop) OTE(o);
"""


def test_ladder_timer_counter_oneshot_and_seal_in(st) -> None:
    """SPEC 3.2 / 4: inputs AND into the rung, a branch ORs its legs, OTE clears on a false
    rung, OTL/OTU latch, TOF/RTO/CTU/ONS/RES bits as Logix, timers count virtual ms."""
    r, rows = _trace(
        st,
        LADDER_BITS,
        "bits.rll",
        10,
        "go",
        "tf.TT",
        "tf.DN",
        "tf.ACC",
        "c.DN",
        "c.ACC",
        "cnt",
        "r.ACC",
        "r.DN",
        "o",
    )
    assert r.code == 0, r.err
    assert rows[0] == [
        "time",
        "go",
        "tf.TT",
        "tf.DN",
        "tf.ACC",
        "c.DN",
        "c.ACC",
        "cnt",
        "r.ACC",
        "r.DN",
        "o",
    ]
    # n = k + 1 in scan k: go is TRUE in scans 1 (OTE while n = 2) and 3 (OTL at n = 4,
    # OTU at n = 5). TOF: prescan ACC = PRE = 2; TRUE rung -> DN, ACC 0; on a FALSE rung TT
    # counts 1 ms per scan from the first false scan: DN drops when ACC reaches 2 (scan 6).
    # CTU counts the two rising edges (DN at 2); ONS adds once per rising edge.
    # RTO runs while go is FALSE, restarting its clock after each TRUE scan: from scan 4 it
    # counts 0, 1, 2, 3 (DN at scan 7); RES in scan 8 zeroes it; scan 9 starts again at 0.
    # The seal-in branch holds o once go has been TRUE.
    expected = [
        ["0.0", "0", "0", "0", "2", "0", "0", "0", "0", "0", "0"],
        ["0.001", "1", "0", "1", "0", "0", "1", "1", "0", "0", "1"],
        ["0.002", "0", "1", "1", "0", "0", "1", "1", "0", "0", "1"],
        ["0.003", "1", "0", "1", "0", "1", "2", "2", "0", "0", "1"],
        ["0.004", "0", "1", "1", "0", "1", "2", "2", "0", "0", "1"],
        ["0.005", "0", "1", "1", "1", "1", "2", "2", "1", "0", "1"],
        ["0.006", "0", "0", "0", "2", "1", "2", "2", "2", "0", "1"],
        ["0.007", "0", "0", "0", "2", "1", "2", "2", "3", "1", "1"],
        ["0.008", "0", "0", "0", "2", "1", "2", "2", "0", "0", "1"],
        ["0.009", "0", "0", "0", "2", "1", "2", "2", "0", "0", "1"],
    ]
    assert rows[1:] == expected


# ------------------------------------------------------------------ 6 / 9.2 trace, report
def test_trace_time_is_the_scan_start_without_binary_noise(st) -> None:
    """SPEC 9.1 / 9.2: normal scan k runs at t = k x scan period; `time` is that start time in
    seconds. 3 x 0.1 ms is 0.0003 s (the float product 0.00030000000000000003 is not a time
    an engineer would expect in the CSV)."""
    r, rows = _trace(
        st,
        "VAR n : DINT; END_VAR\nn := n + 1;\n",
        "t.st",
        4,
        "n",
        args=("--scan-period", "0.1"),
    )
    assert r.code == 0
    assert rows == [["time", "n"], ["0.0", "1"], ["0.0001", "2"], ["0.0002", "3"], ["0.0003", "4"]]


def test_default_table_lists_string_tags(st) -> None:
    """SPEC 6: without --watch, every elementary program tag is reported; SPEC 3.3 lists
    STRING among the elementary types, so a STRING tag is reported (as text)."""
    p = st.write("s.st", "VAR s : STRING; n : DINT; END_VAR\ns := 'ok'; n := 2;\n")
    r = st.cli("run", str(p), "--scans", "1", "--json")
    assert r.code == 0
    assert r.tags == {"s": "ok", "n": 2}


# ------------------------------------------------------------------ 9.4 watchdog
def test_watchdog_counts_straight_line_statements_too(st) -> None:
    """SPEC 9.4: a scan that executes more than N statements major-faults 6/1 (`--watchdog N`);
    exactly N is fine."""
    src = "VAR n : DINT; END_VAR\nn := 1; n := 2; n := 3; n := 4; n := 5; n := 6;\n"
    ok = st.run(src, "n", args=("--watchdog", "6"))
    assert (ok.code, ok.json["faults"]) == (0, [])  # six statements, budget six
    bad = st.run(src, "n", args=("--watchdog", "5"))
    assert bad.code == 3
    assert [(f["type"], f["code"], f["major"]) for f in bad.json["faults"]] == [(6, 1, True)]
    assert bad.json["scans"] == 1


# ------------------------------------------------------------------ 2.1 initialisers
def test_initial_values_that_do_not_fit_the_type_are_errors(st) -> None:
    """SPEC 2.1: type mismatches in an initialiser are verification errors; a value that does
    not fit the tag (Studio refuses `SINT := 300`) is one, a radix literal is a bit pattern
    at the tag's width (`SINT := 16#FF` is -1, as an ST store of it)."""
    src = (
        "VAR b : BOOL := 2; s : SINT := 300; u : USINT := -1; h : SINT := 16#1FF;\n"
        "ok1 : SINT := 16#FF; ok2 : DINT := -2147483648; ok3 : UDINT := 4294967295;\n"
        "ok4 : BOOL := TRUE; ok5 : REAL := 1; t : TIMER := (PRE := 4294967296); END_VAR\n"
        "ok2 := ok2;\n"
    )
    r = st.check(src)
    assert r.code == 1
    lines = src.splitlines()

    def col(line: int, text: str) -> int:
        return lines[line - 1].index(text) + 1

    # each refused value where it is written; the TIMER's PRE (a DINT) is 2**32 > 2147483647
    assert [(d["code"], d["line"], d["column"]) for d in r.json] == [
        ("E118", 1, col(1, "2;")),
        ("E118", 1, col(1, "300")),
        ("E118", 1, col(1, "-1")),
        ("E118", 1, col(1, "16#1FF")),
        ("E118", 3, col(3, "4294967296")),
    ]
    fixed = src.replace("BOOL := 2", "BOOL := 1").replace("SINT := 300", "SINT := 127")
    fixed = fixed.replace("USINT := -1", "USINT := 255").replace("16#1FF", "16#80")
    r = st.run(fixed.replace("4294967296", "2147483647"), "b", "s", "u", "h", "ok1", "t.PRE")
    assert r.code == 0, r.err
    # 16#80 and 16#FF as SINT patterns: -128 and -1
    assert r.tags == {"b": True, "s": 127, "u": 255, "h": -128, "ok1": -1, "t.PRE": 2147483647}


# ------------------------------------------------------------------ 7 syntax recovery
def test_missing_semicolon_before_a_closer_is_reported_as_such(st) -> None:
    """SPEC 7: syntax errors with recovery, several per file, precise ranges. A statement
    missing its `;` before END_IF is a missing `;` at the END_IF (not a missing END_REPEAT:
    there is no REPEAT), and the blocks after it parse normally."""
    src = (
        "VAR a : DINT; b : BOOL; END_VAR\n"
        "a := ;\n"
        "IF b THEN\n"
        "  a := 2\n"
        "END_IF;\n"
        "WHILE b DO a := 1 END_WHILE;\n"
        "a := 3;\n"
    )
    r = st.check(src)
    assert r.code == 1
    # line 2: the expression is missing where `;` stands (column 6); line 5: END_IF in
    # column 1; line 6: END_WHILE after `a := 1 ` starts in column 19
    assert [(d["code"], d["line"], d["column"], d["message"]) for d in r.json] == [
        ("S001", 2, 6, "unexpected ';', expected an expression"),
        ("S005", 5, 1, "expected ';' before 'END_IF'"),
        ("S005", 6, 19, "expected ';' before 'END_WHILE'"),
    ]


def test_wrong_operand_count_is_one_diagnostic(st) -> None:
    """SPEC 7: wrong operand count is reported; with the operands miscounted the enumeration
    words (ST `%ofTime`, ladder `Units per sec`) are not also reported as undefined tags or
    misplaced enumeration texts: one finding per mistake."""
    head = "VAR X : AXIS_VIRTUAL; ctl : MOTION_INSTRUCTION; a : BOOL; END_VAR\n"
    rll = (
        "XIC(a) MAJ(X, ctl, 0, 10, Units per sec, 100, Units per sec2, 100, Units per sec2, "
        "Trapezoidal, 100, 100, % of Time, 0, 0, 0);\n"
    )
    st_src = (
        "IF a THEN MAJ(X, ctl, 0, 10, Unitspersec, 100, Unitspersec2, 100, Unitspersec2, "
        "scurve, 100, 100, %ofTime, 0, 0, 0); END_IF;\n"
    )
    # MAJ has 17 operands (seed MAJ: Axis .. LockDirection); 16 are written in both forms,
    # MAJ starting in column 8 of the rung and column 11 of the IF line
    for name, body, column in (("m.rll", rll, 8), ("m.st", st_src, 11)):
        r = st.check(head + body, name=name)
        assert r.code == 1
        assert [(d["code"], d["line"], d["column"], d["message"]) for d in r.json] == [
            ("E104", 2, column, "MAJ takes 17 operands, 16 given")
        ]


def test_ladder_outputs_pass_the_condition_on_and_nested_branches_or(st) -> None:
    """SPEC 3.2: outputs act on the rung condition and pass it on; a branch starts every leg
    with the incoming condition and ORs the legs (nested too); a false rung skips ADD."""
    src = """\
VAR a : BOOL := TRUE; f : BOOL; o1, o2, o3, o4, o5 : BOOL; n : DINT; END_VAR
XIC(a) OTE(o1) XIC(f) OTE(o2);
[XIC(f) , XIC(a) [XIC(f) , XIO(f) OTE(o3)] ] OTE(o4);
XIC(f) [OTE(o5), ADD(n, 1, n)];
"""
    r = st.run(src, "o1", "o2", "o3", "o4", "o5", "n", name="b.rll", scans=2)
    assert r.code == 0, r.err
    # rung 1: a TRUE -> o1 on; then f FALSE -> o2 off. rung 2: second leg: a TRUE, inner
    # branch: XIO(f) TRUE -> o3 on, so the leg is TRUE and o4 on. rung 3: FALSE: o5 off, no ADD
    assert r.tags == {"o1": True, "o2": False, "o3": True, "o4": True, "o5": False, "n": 0}


def test_old_and_new_mnemonics_run_the_same(st) -> None:
    """SPEC 2.2: both old and v36+ mnemonics EQU/EQ ... SQR/SQRT TRN/TRUNC XPY/EXPT ACS/ACOS
    ASN/ASIN ATN/ATAN run."""
    src = """\
VAR a : DINT := 5; b : BOOL[7]; r : REAL[12]; END_VAR
EQ(a,5) OTE(b[0]);
NE(a,4) OTE(b[1]);
GT(a,4) OTE(b[2]);
GE(a,5) OTE(b[3]);
LT(a,6) OTE(b[4]);
LE(a,5) OTE(b[5]);
LIMIT(0,a,10) OTE(b[6]);
MOVE(2.0, r[0]);
SQRT(16.0, r[1]);
SQR(9.0, r[2]);
TRUNC(2.7, r[3]);
TRN(-2.7, r[4]);
EXPT(2.0, 3.0, r[5]);
XPY(2, 4, r[6]);
ACOS(1.0, r[7]);
ACS(0.0, r[8]);
ASIN(1.0, r[9]);
ASN(0.0, r[10]);
ATN(0.0, r[11]);
"""
    r = st.run(src, "b", "r", name="m.rll")
    assert r.code == 0, r.err
    assert r.tags["b"] == [True] * 7  # 5 = 5, 5 <> 4, 5 > 4, 5 >= 5, 5 < 6, 5 <= 5, 0 <= 5 <= 10
    half_pi = 1.5707963705062866  # pi/2 as float32
    # sqrt 16 = 4, sqrt 9 = 3, trunc 2.7 = 2, trunc -2.7 = -2, 2^3 = 8, 2^4 = 16, acos 1 = 0,
    # acos 0 = pi/2, asin 1 = pi/2, asin 0 = 0, atan 0 = 0
    assert r.tags["r"] == [2.0, 4.0, 3.0, 2.0, -2.0, 8.0, 16.0, 0.0, half_pi, half_pi, 0.0, 0.0]


def test_ladder_mov_rounds_ties_to_even_and_overflow_is_minor_4_4(st) -> None:
    """SPEC 3.3: REAL -> integer rounds to nearest, ties to even, in instructions as in `:=`;
    integers wrap (an overflowing store records minor fault 4/4 and goes on)."""
    src = "VAR d1, d2, d3 : DINT; s : SINT; END_VAR\nMOV(2.5, d1);\nMOV(-2.5, d2);\nMOV(3.5, d3);\nMOV(200.0, s);\n"
    r = st.run(src, "d1", "d2", "d3", "s", name="mv.rll")
    assert r.code == 0
    # 200 in a SINT wraps: 200 - 256 = -56
    assert r.tags == {"d1": 2, "d2": -2, "d3": 4, "s": -56}
    assert [(f["type"], f["code"], f["major"], f["line"]) for f in r.json["faults"]] == [
        (4, 4, False, 5)
    ]


def test_planner_timing_with_a_declared_group(st) -> None:
    """SPEC 9.3 / 2.1: a MOTION_GROUP's CoarseUpdatePeriod (µs) sets the planner period; a
    move executed in the scan at t = 0 takes effect at the next update (t = CUP), its clock 0
    there."""
    src = """\
VAR grp : MOTION_GROUP := (CoarseUpdatePeriod := 4000);
    X : AXIS_VIRTUAL := (MaximumSpeed := 100.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0);
    ctl : MOTION_INSTRUCTION; go : BOOL := TRUE; END_VAR
IF go THEN
  MAJ(X, ctl, 0, 10.0, Unitspersec, 1000, Unitspersec2, 1000, Unitspersec2, Trapezoidal, 100, 100, %ofTime, 0, 0, 0, 0);
  go := FALSE;
END_IF;
"""
    r, rows = _trace(st, src, "g.st", 10, "X.CommandVelocity", "X.CommandPosition")
    assert r.code == 0, r.err
    # updates at 0, 4, 8 ms. The jog starts at the 4 ms update with its clock at 0 (v = 0);
    # at 8 ms it has accelerated 4 ms at 1000: v = 4, x = 1000 * 0.004**2 / 2 = 0.008
    v = [float(row[1]) for row in rows[1:]]
    x = [float(row[2]) for row in rows[1:]]
    assert v == [0.0] * 8 + [4.0, 4.0]
    assert x[:8] == [0.0] * 8
    assert x[8] == pytest.approx(0.008, rel=1e-6) and x[9] == x[8]
