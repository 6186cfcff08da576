"""ST expression functions: values, domain faults and registry keys."""

from __future__ import annotations

import math

import pytest

from interpreter.instructions import functions as F
from interpreter.instructions.registry import IMPLEMENTATIONS
from interpreter.vm.context import ExecContext


def _faults(ctx: ExecContext) -> set[tuple[int, int]]:
    return {(f.type, f.code) for f in ctx.minor_faults.values()}


def test_abs_keeps_type() -> None:
    ctx = ExecContext()
    assert F.abs_(ctx, True, -5) == 5 and isinstance(F.abs_(ctx, True, -5), int)
    assert F.abs_(ctx, True, -2.5) == 2.5


def test_sqrt_takes_absolute_value_of_negative_source() -> None:
    ctx = ExecContext()
    assert F.sqrt(ctx, True, 16) == 4.0
    assert F.sqrt(ctx, True, -25) == 5.0  # documented: |-25| = 25 -> 5, no fault
    assert not ctx.minor_faults


def test_ln_log_values_and_domain_faults() -> None:
    ctx = ExecContext()
    assert F.ln(ctx, True, math.e) == pytest.approx(1.0)
    assert F.log(ctx, True, 1000) == pytest.approx(3.0)  # 10**3 = 1000
    assert not ctx.minor_faults
    assert F.ln(ctx, True, 0) == -math.inf
    assert _faults(ctx) == {(4, 4)}
    ctx = ExecContext()
    assert math.isnan(F.log(ctx, True, -1.0))
    assert _faults(ctx) == {(4, 4)}


def test_trig() -> None:
    ctx = ExecContext()
    assert F.sin(ctx, True, math.pi / 2) == pytest.approx(1.0)
    assert F.cos(ctx, True, 0) == 1.0
    assert F.tan(ctx, True, math.pi / 4) == pytest.approx(1.0)
    assert F.asin(ctx, True, 1) == pytest.approx(math.pi / 2)
    assert F.acos(ctx, True, -1) == pytest.approx(math.pi)
    assert F.atan(ctx, True, 1.0) == pytest.approx(math.pi / 4)
    assert not ctx.minor_faults


def test_trig_domain_faults() -> None:
    ctx = ExecContext()
    assert math.isnan(F.asin(ctx, True, 1.5))
    assert math.isnan(F.acos(ctx, True, -2))
    assert math.isnan(F.sin(ctx, True, math.inf))
    assert _faults(ctx) == {(4, 4)}
    assert ctx.minor_faults[(4, 4, -1)].count == 3  # one location, counted three times


def test_deg_rad() -> None:
    ctx = ExecContext()
    assert F.deg(ctx, True, math.pi) == pytest.approx(180.0)
    assert F.rad(ctx, True, 90) == pytest.approx(math.pi / 2)


@pytest.mark.parametrize(
    ("x", "expected"), [(2.7, 2.0), (-2.7, -2.0), (0.5, 0.0), (7, 7), (-3, -3)]
)
def test_trunc_toward_zero_keeping_type(x: float, expected: float) -> None:
    r = F.trunc(ExecContext(), True, x)
    assert r == expected and type(r) is type(x)


def test_trunc_non_finite_passes_through() -> None:
    assert F.trunc(ExecContext(), True, -math.inf) == -math.inf


@pytest.mark.parametrize(
    ("name", "fn"),
    [
        ("ABS", F.abs_),
        ("SQRT", F.sqrt),
        ("LN", F.ln),
        ("LOG", F.log),
        ("SIN", F.sin),
        ("COS", F.cos),
        ("TAN", F.tan),
        ("ASIN", F.asin),
        ("ASN", F.asin),
        ("ACOS", F.acos),
        ("ACS", F.acos),
        ("ATAN", F.atan),
        ("ATN", F.atan),
        ("DEG", F.deg),
        ("RAD", F.rad),
        ("TRUNC", F.trunc),
        ("TRN", F.trunc),
    ],
)
def test_registered_for_st(name: str, fn: object) -> None:
    # the key the VM looks up first for an ST call (registry.lookup: NAME@st)
    assert IMPLEMENTATIONS[f"{name}@st"] is fn
