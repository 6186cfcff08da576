"""Run-time helpers for the ops ladder added to the bytecode (STOREF, RETN, RETV, structure copies)."""

from __future__ import annotations

import math
from typing import Any

from ..instructions.ladder_status import _int_overflow, set_flags
from ..semantics.types import Elementary, Kind
from .context import ExecContext, MajorFault
from .values import convert


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
    set_flags(ctx, v, over)
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
