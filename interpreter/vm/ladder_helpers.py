"""Run-time helpers for the ops ladder added to the bytecode (STOREF, RETN, RETV, structure copies)."""

from __future__ import annotations

import math
from typing import Any

from ..semantics.types import Elementary, Kind
from .context import ExecContext, MajorFault
from .values import convert, real_to_int, wrap


def store_flags(ctx: ExecContext, x: Any, t: Elementary) -> int | float:
    """Convert `x` for storage in `t` and set S:N, S:Z, S:V from the stored value.

    S:V is set when the value does not fit: an integer out of the destination's range, a
    REAL that is not finite or out of range for an integer destination, or a finite value
    that becomes infinite in a REAL.
    """
    status = ctx.status
    if t.kind is Kind.REAL:
        v = convert(x, t)
        over = math.isinf(v) and not (isinstance(x, float) and math.isinf(x))
    elif t.kind is Kind.BOOL:
        v = 1 if x else 0
        over = False
    elif isinstance(x, float):
        if math.isnan(x) or math.isinf(x):
            v, over = 0 if math.isnan(x) else wrap(real_to_int(x), t.bits, t.signed), True
        else:
            r = real_to_int(x)
            v = wrap(r, t.bits, t.signed)
            over = v != r
    else:
        v = wrap(int(x), t.bits, t.signed)
        over = v != x
    status["N"] = 1 if v < 0 else 0
    status["Z"] = 1 if v == 0 else 0
    status["V"] = 1 if over else 0
    return v


def returned(ctx: ExecContext, count: int, site: int) -> bool:
    """Did the routine just called end with a RET handing back `count` values?"""
    rv = ctx.rv
    if rv is None:
        return False
    if len(rv) != count:
        raise MajorFault(4, 31, f"RET handed back {len(rv)} value(s), the JSR expects {count}", site)
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
