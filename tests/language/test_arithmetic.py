"""Integer wrap, REAL float32 rounding, conversions, division and promotion (SPEC 3.3, 9.13)."""

from __future__ import annotations

import math


def test_dint_wraps(st) -> None:
    src = """
    VAR d : DINT := 2147483647; m : DINT := -2147483648; p : DINT := 100000; q : DINT; END_VAR
    d := d + 1;
    m := m - 1;
    q := p * p;
    """
    t = st.tags(src, "d", "m", "q")
    assert t["d"] == -2147483648  # 2147483647 + 1 = 2^31; 2^31 - 2^32 = -2147483648
    assert t["m"] == 2147483647  # -2^31 - 1 = -2147483649; + 2^32 = 2147483647
    # 100000 * 100000 = 10_000_000_000; - 2 * 4_294_967_296 = 1_410_065_408
    assert t["q"] == 1410065408


def test_sint_and_int_wrap(st) -> None:
    src = """
    VAR s : SINT := -91; s2 : SINT := 127; i : INT := 32767; j : INT := -32768; END_VAR
    s := s + s;
    s2 := s2 + 1;
    i := i + 1;
    j := j - 1;
    """
    t = st.tags(src, "s", "s2", "i", "j")
    assert t["s"] == 74  # SINT: -91 + -91 = -182; -182 + 256 = 74
    assert t["s2"] == -128  # 127 + 1 = 128; 128 - 256 = -128
    assert t["i"] == -32768  # 32767 + 1 = 32768; 32768 - 65536 = -32768
    assert t["j"] == 32767  # -32768 - 1 = -32769; + 65536 = 32767


def test_unsigned_wrap(st) -> None:
    src = """
    VAR u8 : USINT; u16 : UINT := 65535; u32 : UDINT; u64 : ULINT; u8b : USINT := 200; END_VAR
    u8 := u8 - 1;
    u16 := u16 + 1;
    u32 := u32 - 1;
    u64 := u64 - 1;
    u8b := u8b + 100;
    """
    t = st.tags(src, "u8", "u16", "u32", "u64", "u8b")
    assert t["u8"] == 255  # 0 - 1 = -1; -1 + 256 = 255
    assert t["u16"] == 0  # 65535 + 1 = 65536; 65536 mod 65536 = 0
    assert t["u32"] == 4294967295  # 0 - 1 + 2^32
    assert t["u64"] == 18446744073709551615  # 0 - 1 + 2^64
    assert t["u8b"] == 44  # 200 + 100 = 300; 300 - 256 = 44


def test_lint_wrap_and_range(st) -> None:
    src = """
    VAR li : LINT := 9223372036854775807; big : LINT; small : DINT; END_VAR
    li := li + 1;
    big := 2147483647L + 1;
    small := 2147483647 + 1;
    """
    t = st.tags(src, "li", "big", "small")
    assert t["li"] == -9223372036854775808  # 2^63 - 1 + 1 = 2^63; - 2^64 = -2^63
    assert t["big"] == 2147483648  # LINT arithmetic: no wrap at 2^31
    assert t["small"] == -2147483648  # DINT arithmetic wraps: 2^31 - 2^32


def test_real_rounds_on_store(st) -> None:
    src = """
    VAR r : REAL; l : LREAL; END_VAR
    r := 16777217.0;
    l := 16777217.0;
    """
    t = st.tags(src, "r", "l")
    # 16777217 = 2^24 + 1 needs 25 significant bits; float32 has 24 -> tie, rounds to even 2^24
    assert t["r"] == 16777216.0
    assert t["l"] == 16777217.0  # LREAL is a double: exact


def test_real_vs_lreal_point_one_plus_point_two(st) -> None:
    src = """
    VAR ra : REAL := 0.1; rb : REAL := 0.2; r : REAL; r3 : REAL := 0.3; req : BOOL;
        la : LREAL := 0.1; lb : LREAL := 0.2; l : LREAL; l3 : LREAL := 0.3; leq : BOOL; END_VAR
    r := ra + rb;
    req := r = r3;
    l := la + lb;
    leq := l = l3;
    """
    t = st.tags(src, "r", "req", "l", "leq")
    # float32(0.1) + float32(0.2) = 0.30000000447034836 exactly; the float32 neighbours are
    # 0.2999999821186066 and 0.30000001192092896; the nearer is 0.30000001192092896 = float32(0.3)
    assert t["r"] == 0.30000001192092896
    assert t["req"] is True
    # double: 0.1 + 0.2 = 0.30000000000000004 <> 0.3 (0.29999999999999998890)
    assert t["l"] == 0.30000000000000004
    assert t["leq"] is False


def test_every_real_operation_rounds(st) -> None:
    src = """
    VAR r : REAL := 16777216.0; one : REAL := 1.0; l : LREAL; d : LREAL; big : LREAL := 16777216.0; l2 : LREAL; END_VAR
    l := r + one;
    d := (r + one) - r;
    l2 := big + 1.0;
    """
    t = st.tags(src, "l", "d", "l2")
    # REAL + REAL is single precision even when stored into an LREAL: 2^24 + 1 -> 2^24
    assert t["l"] == 16777216.0
    # (2^24 + 1 rounded = 2^24) - 2^24 = 0 (in double it would be 1)
    assert t["d"] == 0.0
    # LREAL + REAL promotes to LREAL: exact 16777217
    assert t["l2"] == 16777217.0


def test_real_multiplication_rounds(st) -> None:
    src = """
    VAR a : REAL := 0.1; r : REAL; l : LREAL; la : LREAL := 0.1; END_VAR
    r := a * 3.0;
    l := la * 3.0;
    """
    t = st.tags(src, "r", "l")
    # float32(0.1) = 0.100000001490116119384765625; * 3 = 0.300000004470348358154296875
    # -> nearest float32 is 0.300000011920928955078125
    assert t["r"] == 0.30000001192092896
    # double 0.1 * 3 = 0.30000000000000004
    assert t["l"] == 0.30000000000000004


def test_real_to_integer_ties_to_even(st) -> None:
    src = """
    VAR a : REAL := 2.5; b : REAL := 3.5; c : REAL := -2.5; d : REAL := -3.5; e : REAL := 2.6; f : REAL := -0.5;
        da, db, dc, dd, de, df : DINT; s : SINT; END_VAR
    da := a; db := b; dc := c; dd := d; de := e; df := f;
    s := 0.5 + 1.0;
    """
    t = st.tags(src, "da", "db", "dc", "dd", "de", "df", "s")
    assert t["da"] == 2  # 2.5 halfway between 2 and 3 -> even 2
    assert t["db"] == 4  # 3.5 halfway between 3 and 4 -> even 4
    assert t["dc"] == -2  # -2.5 -> even -2
    assert t["dd"] == -4  # -3.5 -> even -4
    assert t["de"] == 3  # 2.6 not a tie -> nearest 3
    assert t["df"] == 0  # -0.5 -> even 0
    assert t["s"] == 2  # 0.5 + 1.0 = 1.5 -> even 2


def test_integer_division_and_mod(st) -> None:
    src = """
    VAR a : DINT := -7; b : DINT := 2; q, m, q2, m2, q3 : DINT; END_VAR
    q := a / b;
    m := a MOD b;
    q2 := 7 / -2;
    m2 := 7 MOD -2;
    q3 := 7 / 2;
    """
    t = st.tags(src, "q", "m", "q2", "m2", "q3")
    assert t["q"] == -3  # -3.5 truncated toward zero
    assert t["m"] == -1  # -7 - TRUNC(-7/2)*2 = -7 - (-3*2) = -1
    assert t["q2"] == -3  # -3.5 -> -3
    assert t["m2"] == 1  # 7 - TRUNC(7/-2)*(-2) = 7 - (-3)(-2) = 1
    assert t["q3"] == 3  # 3.5 -> 3


def test_real_division_and_mod(st) -> None:
    src = """
    VAR r, m : REAL; one : REAL := 1.0; third : REAL; END_VAR
    r := 7.0 / 2.0;
    m := 7.5 MOD 2.0;
    third := one / 3.0;
    """
    t = st.tags(src, "r", "m", "third")
    assert t["r"] == 3.5
    assert t["m"] == 1.5  # 7.5 - TRUNC(3.75)*2.0 = 7.5 - 6.0
    # 1/3 in float32 = 0.3333333432674408 (0x3EAAAAAB)
    assert t["third"] == 0.3333333432674408


def test_real_mod_of_infinity_and_nan(st) -> None:
    # TRUNC(inf / 2.0) has no integer value: this raised OverflowError (a traceback, found by
    # fuzzing). IEEE fmod of an infinite or NaN dividend is NaN; a finite one MOD inf keeps a.
    src = """
    VAR big : REAL := 3.0e38; inf, nan, m1, m2, m3 : REAL; END_VAR
    inf := big * 10.0;
    nan := inf - inf;
    m1 := inf MOD 2.0;
    m2 := nan MOD 2.0;
    m3 := 7.5 MOD inf;
    """
    t = st.tags(src, "inf", "m1", "m2", "m3")
    # non-finite REALs are JSON strings (docs/decisions/0132)
    assert t["inf"] == "Infinity"  # 3e38 x 10 = 3e39 is above the REAL range (3.4e38)
    assert t["m1"] == "NaN" and t["m2"] == "NaN"
    assert t["m3"] == 7.5  # IEEE fmod(7.5, inf) = 7.5 (the quotient truncates to 0)


def test_mixed_promotion(st) -> None:
    src = """
    VAR d : DINT := 7; r : REAL; q : DINT; s : SINT := 100; i : DINT; half : REAL := 0.5; END_VAR
    r := d / 2.0;
    q := d / 2.0;
    i := s * 2;
    r := r + d * half;
    """
    t = st.tags(src, "r", "q", "i")
    # DINT / REAL -> REAL: 7 / 2.0 = 3.5; then 3.5 + (7 * 0.5 = 3.5) = 7.0
    assert t["r"] == 7.0
    assert t["q"] == 4  # 3.5 computed in REAL, stored to DINT: tie -> even 4
    assert t["i"] == 200  # SINT * DINT literal -> DINT: 100 * 2 = 200 fits a DINT


def test_real_functions_single_precision(st) -> None:
    src = """
    VAR r : REAL; two : REAL := 2.0; p : REAL; END_VAR
    r := SQRT(two);
    p := 2.0 ** 0.5;
    """
    t = st.tags(src, "r", "p")
    # sqrt(2) = 1.4142135623730951 -> float32 1.41421353816986083984375
    assert t["r"] == 1.4142135381698608
    assert t["p"] == 1.4142135381698608
    assert not math.isclose(t["r"], math.sqrt(2), rel_tol=1e-12)


def test_dint_min_edge_cases(st) -> None:
    src = """
    VAR mn : DINT := -2147483648; m1 : DINT := -1; neg, q : DINT; rm : REAL; rp : REAL; END_VAR
    neg := -mn;
    q := mn / m1;
    rm := -7.5 MOD 2.0;
    rp := -2.0 ** 2;
    """
    t = st.tags(src, "neg", "q", "rm", "rp")
    assert t["neg"] == -2147483648  # -(-2^31) = 2^31 wraps back to -2^31
    assert t["q"] == -2147483648  # -2^31 / -1 = 2^31 wraps to -2^31
    assert t["rm"] == -1.5  # -7.5 - TRUNC(-3.75) * 2.0 = -7.5 + 6.0
    assert t["rp"] == -4.0  # -(2.0 ** 2) in REAL
