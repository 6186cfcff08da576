"""Ladder math (ADD ... TRN), LIM and MEQ called directly on Refs; flags in ctx.status."""

from __future__ import annotations

import math

from interpreter.instructions import ladder_math as lm
from interpreter.instructions.registry import lookup
from interpreter.semantics.types import DINT, INT, LINT, LREAL, REAL, SINT
from interpreter.vm.context import ExecContext
from interpreter.vm.refs import Ref
from interpreter.vm.values import f32


def _dest(t, value: object = 0) -> Ref:  # noqa: ANN001
    return Ref([value], 0, t)


def _flags(ctx: ExecContext) -> tuple[int, int, int, int]:
    s = ctx.status
    return (s["N"], s["Z"], s["V"], s["C"])


def _faults(ctx: ExecContext) -> int:
    return sum(f.count for f in ctx.minor_faults.values() if (f.type, f.code) == (4, 4))


# ------------------------------------------------------------------ ADD / SUB / carry
def test_add_dint_overflow_wraps_sets_v_and_records_minor_fault() -> None:
    ctx, d = ExecContext(site=7), _dest(DINT)
    lm.add(ctx, True, 2147483647, 1, d)
    # 2^31 does not fit DINT: stored wrapped -2^31; 16#7FFFFFFF + 1 has no carry out of bit 31
    assert d.get() == -2147483648
    assert _flags(ctx) == (1, 0, 1, 0)
    assert ctx.minor_faults[(4, 4, 7)].count == 1


def test_add_carry_without_overflow() -> None:
    ctx, d = ExecContext(), _dest(DINT)
    lm.add(ctx, True, -1, 1, d)
    # 16#FFFFFFFF + 1 = 2^32: carry out of bit 31; the signed result 0 fits
    assert d.get() == 0
    assert _flags(ctx) == (0, 1, 0, 1)
    assert _faults(ctx) == 0


def test_sub_borrow_and_negative() -> None:
    ctx, d = ExecContext(), _dest(DINT)
    lm.sub(ctx, True, 0, 1, d)
    # 0 - 1 = -1: negative; unsigned 0 < 1 borrows
    assert d.get() == -1
    assert _flags(ctx) == (1, 0, 0, 1)


def test_flags_are_cleared_by_the_next_instruction() -> None:
    ctx, d = ExecContext(), _dest(DINT)
    lm.add(ctx, True, 2147483647, 1, d)
    lm.add(ctx, True, 2, 3, d)
    assert d.get() == 5
    assert _flags(ctx) == (0, 0, 0, 0)


def test_sint_example_from_spec_sets_overflow() -> None:
    ctx, d = ExecContext(), _dest(SINT)
    lm.add(ctx, True, -91, -91, d)
    # -182 + 256 = 74 (SPEC 3.3); -182 is outside SINT: V
    assert d.get() == 74
    assert ctx.status["V"] == 1


def test_false_rung_does_nothing() -> None:
    ctx, d = ExecContext(), _dest(DINT, 9)
    lm.add(ctx, False, 1, 2, d)
    assert d.get() == 9 and ctx.status == {}


# ------------------------------------------------------------------ REAL vs LREAL
def test_real_addition_rounds_to_float32() -> None:
    ctx, d = ExecContext(), _dest(REAL)
    lm.add(ctx, True, 16777216.0, 1.0, d)
    # 2^24 + 1 is not a float32: round to even -> 2^24
    assert d.get() == 16777216.0
    d2 = _dest(LREAL)
    lm.add(ctx, True, 16777216.0, 1.0, d2)
    assert d2.get() == 16777217.0  # LREAL destination: double operation


def test_mixed_dint_real_operation_is_real() -> None:
    ctx, d = ExecContext(), _dest(DINT)
    lm.add(ctx, True, 16777217, 0.0, d)
    # the DINT converts to REAL first: 16777217 -> 16777216.0; + 0.0 -> DINT 16777216
    assert d.get() == 16777216


def test_real_overflow_to_infinity_sets_v() -> None:
    ctx, d = ExecContext(), _dest(REAL)
    lm.mul(ctx, True, 3.0e38, 10.0, d)
    # 3e39 exceeds the float32 maximum 3.4028235e38: +inf
    assert d.get() == math.inf
    assert ctx.status["V"] == 1 and _faults(ctx) == 1


# ------------------------------------------------------------------ MUL / DIV / MOD
def test_mul_int_overflow() -> None:
    ctx, d = ExecContext(), _dest(INT)
    lm.mul(ctx, True, 300, 300, d)
    # 90000 - 65536 = 24464
    assert d.get() == 24464 and ctx.status["V"] == 1


def test_integer_div_truncates_toward_zero() -> None:
    ctx = ExecContext()
    for a, b, q in [(7, 2, 3), (-7, 2, -3), (7, -2, -3), (-7, -2, 3)]:
        d = _dest(DINT)
        lm.div(ctx, True, a, b, d)
        assert d.get() == q


def test_div_into_real_destination_divides_in_real() -> None:
    ctx, d = ExecContext(), _dest(REAL)
    lm.div(ctx, True, 7, 2, d)
    assert d.get() == 3.5  # SPEC 9.19: not 3
    lm.div(ctx, True, 1, 3, d)
    assert d.get() == f32(1 / 3)  # 0.3333333432674408


def test_real_div_into_dint_rounds_half_even() -> None:
    ctx = ExecContext()
    for a, b, q in [(7.0, 2, 4), (5.0, 2, 2), (-5.0, 2, -2)]:  # 3.5 -> 4, 2.5 -> 2, -2.5 -> -2
        d = _dest(DINT)
        lm.div(ctx, True, a, b, d)
        assert d.get() == q


def test_div_by_zero_integer_keeps_source_a_with_one_fault() -> None:
    ctx, d = ExecContext(site=3), _dest(DINT)
    lm.div(ctx, True, 42, 0, d)
    assert d.get() == 42
    assert ctx.status["V"] == 1
    assert ctx.minor_faults[(4, 4, 3)].count == 1


def test_div_by_zero_real_gives_ieee_results() -> None:
    ctx = ExecContext()
    for a, expected in [(1.0, math.inf), (-1.0, -math.inf)]:
        d = _dest(REAL)
        lm.div(ctx, True, a, 0.0, d)
        assert d.get() == expected
    d = _dest(REAL)
    lm.div(ctx, True, 0.0, 0, d)
    assert math.isnan(d.get())
    assert _faults(ctx) == 3


def test_mod_sign_follows_dividend_and_mod_zero() -> None:
    ctx = ExecContext()
    for a, b, r in [(-7, 3, -1), (7, -3, 1), (7, 3, 1)]:  # a - trunc(a/b)*b
        d = _dest(DINT)
        lm.mod(ctx, True, a, b, d)
        assert d.get() == r
    d = _dest(DINT, 5)
    lm.mod(ctx, True, 7, 0, d)
    assert d.get() == 0 and ctx.status["V"] == 1
    r = _dest(REAL)
    lm.mod(ctx, True, 7.5, 2, r)
    assert r.get() == 1.5  # 7.5 - trunc(3.75) * 2 = 7.5 - 6


# ------------------------------------------------------------------ one-operand math
def test_sqr_absolute_value_and_integer_truncation() -> None:
    ctx = ExecContext()
    d = _dest(DINT)
    lm.sqr(ctx, True, -16, d)
    assert d.get() == 4  # root of |-16|, no fault
    lm.sqr(ctx, True, 24, d)
    assert d.get() == 4  # sqrt 24 = 4.899: integer source into integer dest truncates
    lm.sqr(ctx, True, 24.0, d)
    assert d.get() == 5  # REAL source: 4.899 rounds
    r = _dest(REAL)
    lm.sqr(ctx, True, 2.0, r)
    assert r.get() == f32(math.sqrt(2))
    assert _faults(ctx) == 0


def test_neg_and_abs_of_the_dint_minimum_overflow() -> None:
    ctx = ExecContext()
    d = _dest(DINT)
    lm.neg(ctx, True, -2147483648, d)
    assert d.get() == -2147483648 and ctx.status["V"] == 1  # +2^31 wraps back
    lm.abs_(ctx, True, -5, d)
    assert d.get() == 5 and _flags(ctx) == (0, 0, 0, 0)


def test_xpy() -> None:
    ctx = ExecContext()
    d = _dest(DINT)
    lm.xpy(ctx, True, 2, 10, d)
    assert d.get() == 1024
    r = _dest(REAL)
    lm.xpy(ctx, True, -8.0, 0.5, r)  # negative base, fractional power
    assert math.isnan(r.get()) and ctx.status["V"] == 1
    lm.xpy(ctx, True, 0, -1, r)
    assert r.get() == math.inf
    lm.xpy(ctx, True, -2.0, 3, r)
    assert r.get() == -8.0 and _flags(ctx) == (1, 0, 0, 0)


def test_functions_round_to_real_and_fault_once() -> None:
    ctx = ExecContext(site=1)
    r = _dest(REAL, 5.0)
    sin, ln, asn, deg, log = (lookup(n, "rll") for n in ("SIN", "LN", "ASN", "DEG", "LOG"))
    assert None not in (sin, ln, asn, deg, log)
    sin(ctx, True, 0.0, r)
    assert r.get() == 0.0 and _flags(ctx) == (0, 1, 0, 0)
    ln(ctx, True, 0.0, r)
    assert r.get() == -math.inf and ctx.status["V"] == 1
    assert ctx.minor_faults[(4, 4, 1)].count == 1  # not twice (function core + flags)
    asn(ctx, True, 2.0, r)
    assert math.isnan(r.get()) and ctx.minor_faults[(4, 4, 1)].count == 2
    deg(ctx, True, f32(math.pi), r)
    # f32(pi) = 3.14159274...; * 180/pi = 180.0000050 -> nearest float32 is 180.0
    assert r.get() == 180.0
    d = _dest(DINT)
    log(ctx, True, 1000, d)
    assert d.get() == 3 and ctx.status["V"] == 0


def test_trn() -> None:
    ctx = ExecContext()
    r, d = _dest(REAL), _dest(DINT)
    lm.trn(ctx, True, -2.7, r)
    lm.trn(ctx, True, -2.7, d)
    assert (r.get(), d.get()) == (-2.0, -2)
    assert ctx.status["N"] == 1


def test_lint_destination_keeps_64_bit_integers() -> None:
    ctx, d = ExecContext(), _dest(LINT)
    lm.add(ctx, True, 2_000_000_000, 2_000_000_000, d)
    assert d.get() == 4_000_000_000 and ctx.status["V"] == 0


# ------------------------------------------------------------------ LIM / MEQ
def test_lim_normal_and_circular_ranges() -> None:
    ctx = ExecContext()
    assert lm.lim(ctx, True, 0, 5, 10) is True
    assert lm.lim(ctx, True, 0, 10, 10) is True  # limits inclusive
    assert lm.lim(ctx, True, 0, 11, 10) is False
    # Low 10 > High 0: true outside the gap (0, 10): Test >= 10 or Test <= 0 (SPEC 9.19)
    assert lm.lim(ctx, True, 10, 5, 0) is False
    assert lm.lim(ctx, True, 10, 11, 0) is True
    assert lm.lim(ctx, True, 10, -1, 0) is True
    assert lm.lim(ctx, True, 10, 0, 0) is True
    assert lm.lim(ctx, False, 0, 5, 10) is False
    assert lm.lim(ctx, True, 0.5, 1, 1.5) is True


def test_meq() -> None:
    ctx = ExecContext()
    # 2#1010 AND 2#1110 = 2#1010; 2#1011 AND 2#1110 = 2#1010: equal under the mask
    assert lm.meq(ctx, True, 0b1010, 0b1110, 0b1011) is True
    assert lm.meq(ctx, True, 0b1010, 0b1111, 0b1011) is False
    assert lm.meq(ctx, False, 1, 1, 1) is False
