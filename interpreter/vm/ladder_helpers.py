"""Run-time helpers for the ops ladder added to the bytecode (STOREF, RETN, RETV, structure copies)."""

from __future__ import annotations

import math
from typing import Any

from ..instructions.ladder_status import _int_overflow, set_flags
from ..semantics.types import Elementary, Kind
from .context import ExecContext, MajorFault
from .values import convert, f32, real_mod, wrap


def store_flags(ctx: ExecContext, x: Any, t: Elementary) -> int | float:
    """Convert `x` for storage in `t`; math status flags as every ladder math instruction
    sets them (instructions/ladder_status.py: N, Z from the stored value, V on overflow with
    minor fault 4/4 at `ctx.site`, C cleared)."""
    v = convert(x, t)
    if t.kind is Kind.REAL:
        over = not math.isfinite(v)
    elif t.kind is Kind.INT:
        over = _int_overflow(x, t)
    else:
        over = False
    over = over or ctx.overflow  # an operation of a CPT/FAL expression overflowed
    ctx.overflow = False
    set_flags(ctx, v, over)
    return v


# Checked arithmetic of ladder CPT/FAL expressions (the OVF op, decision 0025): the same
# results as the plain operations, plus ctx.overflow when a result does not fit its type.
# Division by zero counts as an overflow here; its minor fault 4/4 is then recorded once,
# at the instruction, by store_flags.
def over_int(ctx: ExecContext, x: int, bits: int, signed: bool) -> int:
    w = wrap(x, bits, signed)
    if w != x:
        ctx.overflow = True
    return w


def over_real(ctx: ExecContext, x: float) -> float:
    if not math.isfinite(x):
        ctx.overflow = True
    return x


def over_idiv(ctx: ExecContext, a: int, b: int, bits: int, signed: bool) -> int:
    if b == 0:
        ctx.overflow = True
        return a  # as the unchecked divide: Source A
    q = abs(a) // abs(b)
    return over_int(ctx, q if (a >= 0) == (b >= 0) else -q, bits, signed)  # MIN / -1 overflows


def over_imod(ctx: ExecContext, a: int, b: int) -> int:
    if b == 0:
        ctx.overflow = True
        return 0
    q = abs(a) // abs(b)
    return a - (q if (a >= 0) == (b >= 0) else -q) * b  # |result| < |b|: always fits


def over_ipow(ctx: ExecContext, a: int, b: int, bits: int, signed: bool) -> int:
    if b < 0:
        if a == 0:
            ctx.overflow = True
            return 0
        return (-1 if b % 2 else 1) if a == -1 else 1 if a == 1 else 0
    if abs(a) >= 2 and b >= bits:  # |a| ** b >= 2 ** bits: never fits, skip the huge number
        ctx.overflow = True
        return wrap(pow(a, b, 1 << bits), bits, signed)
    return over_int(ctx, a**b, bits, signed)


def over_fdiv(ctx: ExecContext, a: float, b: float, single: bool) -> float:
    if b == 0.0:
        r = (
            math.nan
            if a == 0.0 or math.isnan(a)
            else math.copysign(math.inf, a) * math.copysign(1.0, b)
        )
    else:
        r = a / b
    return over_real(ctx, f32(r) if single else r)


def over_fmod(ctx: ExecContext, a: float, b: float, single: bool) -> float:
    r = real_mod(a, b)
    return over_real(ctx, f32(r) if single else r)


def returned(ctx: ExecContext, count: int, site: int) -> bool:
    """Did the routine just called end with a RET handing back `count` values?"""
    rv = ctx.rv
    if rv is None:
        return False
    if len(rv) != count:
        raise MajorFault(
            4, 31, f"RET handed back {len(rv)} value(s), the JSR expects {count}", site
        )
    return True


def return_value(ctx: ExecContext, i: int, t: object) -> object:
    """Return value i of the last RET, converted for its JSR return parameter's type."""
    assert ctx.rv is not None
    v = ctx.rv[i]
    return convert(v, t) if isinstance(t, Elementary) else v


def copy_into(dst: list, src: list) -> None:
    """Copy a structure or array value member by member, keeping `dst`'s own lists."""
    for i, x in enumerate(src):
        if isinstance(x, list):
            copy_into(dst[i], x)
        else:
            dst[i] = x
