"""Storing a ladder math result: conversion to Dest plus the S:N S:Z S:V S:C flags.

Rules (5580 controllers, Studio 5000 v37 "Math Status Flags"; decision 0030):
- Only ladder instructions that affect the flags call `store`; each such execution clears all
  four flags first and then sets them from the value actually stored in Dest.
- N: the stored value is negative. Z: it is zero.
- V: the operation overflowed (integer result outside Dest's range, division by zero, a
  REAL result that is infinite or NaN). The stored value is the wrapped / converted one.
- C: only ADD and SUB with integer operands (carry out of / borrow into the most
  significant bit of the operation); every other caller leaves it cleared.
- Each time V is set, minor fault type 4 code 4 is recorded at the instruction (the flag
  goes from cleared to set because the instruction cleared it first).
"""

from __future__ import annotations

import math

from ..semantics.types import Elementary, Kind
from ..vm.context import ExecContext
from ..vm.refs import BitRef, Ref
from ..vm.values import convert, real_to_int, wrap

Dest = Ref | BitRef
Number = int | float


def fault_count(ctx: ExecContext) -> int:
    """How many 4/4 minor faults the current instruction site has recorded so far."""
    f = ctx.minor_faults.get((4, 4, ctx.site))
    return f.count if f is not None else 0


def set_flags(
    ctx: ExecContext, value: Number, overflow: bool = False, carry: bool = False, fault: bool = True
) -> None:
    """Flags for a value already stored (N, Z from it; V, C as given)."""
    st = ctx.status
    st["N"] = int(value < 0)
    st["Z"] = int(value == 0)
    st["V"] = int(overflow)
    st["C"] = int(carry)
    if overflow and fault:
        ctx.minor(4, 4, "arithmetic overflow: the result does not fit the destination")


def store(
    ctx: ExecContext,
    dest: Dest,
    value: Number,
    *,
    overflow: bool = False,
    carry: bool = False,
    fault: bool = True,
) -> None:
    """Convert `value` to Dest's type, store it and update the math status flags.

    `overflow` reports an overflow the caller detected (division by zero); `fault=False`
    when the caller's helper already recorded the minor fault for this execution.
    """
    t = dest.type
    stored = convert(value, t)
    if t.kind is Kind.REAL:
        overflow = overflow or not math.isfinite(stored)
    elif t.kind is Kind.INT:
        overflow = overflow or _int_overflow(value, t)
    dest.set(stored)
    set_flags(ctx, dest.get(), overflow, carry, fault)


def _int_overflow(value: Number, t: Elementary) -> bool:
    if isinstance(value, float):
        if not math.isfinite(value):
            return True
        value = real_to_int(value)
    return wrap(int(value), t.bits, t.signed) != value
