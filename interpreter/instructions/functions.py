"""Structured Text expression functions: ABS SQRT LN LOG SIN COS TAN ASIN ACOS ATAN DEG RAD
TRUNC (and the aliases TRN ASN ACS ATN), and ATAN2, the only one with two arguments.

Each returns the function result as a Python number; the VM converts it to the result type
the catalog states (REAL, LREAL for an LREAL argument; ABS and TRUNC keep the argument's
type). Computing in double and letting the VM round once to float32 gives the correctly
rounded single-precision result.

Domain rules (Studio 5000 help / 1756-RM003):
- SQRT of a negative value takes the absolute value first (documented, no fault).
- LN/LOG "Source must be greater than zero or a minor fault will occur": the arithmetic
  overflow minor fault 4/4 is recorded and the IEEE result returned (-inf for 0, NaN below).
- ASIN/ACOS outside [-1, 1] and SIN/COS/TAN of an infinity: NaN plus minor fault 4/4
  (the same S:V overflow rule as LN).
- A NaN argument gives NaN without a new fault (it was reported where it was produced).
"""

from __future__ import annotations

import math
from collections.abc import Callable

from ..vm.context import ExecContext
from .registry import implements

Number = int | float


def _overflow(ctx: ExecContext, name: str) -> None:
    ctx.minor(4, 4, f"{name}: argument outside the function's domain (arithmetic overflow)")


@implements("ABS@st")
def abs_(ctx: ExecContext, rung: bool, x: Number) -> Number:
    return abs(x)


@implements("SQRT@st")
def sqrt(ctx: ExecContext, rung: bool, x: Number) -> float:
    return math.sqrt(abs(x))


def _log(ctx: ExecContext, x: Number, fn: Callable[[float], float], name: str) -> float:
    if math.isnan(x):
        return math.nan
    if x > 0:
        return fn(x)
    _overflow(ctx, name)
    return -math.inf if x == 0 else math.nan


@implements("LN@st")
def ln(ctx: ExecContext, rung: bool, x: Number) -> float:
    return _log(ctx, x, math.log, "LN")


@implements("LOG@st")
def log(ctx: ExecContext, rung: bool, x: Number) -> float:
    return _log(ctx, x, math.log10, "LOG")


def _periodic(ctx: ExecContext, x: Number, fn: Callable[[float], float], name: str) -> float:
    if math.isinf(x):  # Python raises here; Logix yields NaN with S:V set
        _overflow(ctx, name)
        return math.nan
    return fn(x)


@implements("SIN@st")
def sin(ctx: ExecContext, rung: bool, x: Number) -> float:
    return _periodic(ctx, x, math.sin, "SIN")


@implements("COS@st")
def cos(ctx: ExecContext, rung: bool, x: Number) -> float:
    return _periodic(ctx, x, math.cos, "COS")


@implements("TAN@st")
def tan(ctx: ExecContext, rung: bool, x: Number) -> float:
    return _periodic(ctx, x, math.tan, "TAN")


def _inverse(ctx: ExecContext, x: Number, fn: Callable[[float], float], name: str) -> float:
    if math.isnan(x):
        return math.nan
    if not -1 <= x <= 1:
        _overflow(ctx, name)
        return math.nan
    return fn(x)


@implements("ASIN@st", "ASN@st")
def asin(ctx: ExecContext, rung: bool, x: Number) -> float:
    return _inverse(ctx, x, math.asin, "ASIN")


@implements("ACOS@st", "ACS@st")
def acos(ctx: ExecContext, rung: bool, x: Number) -> float:
    return _inverse(ctx, x, math.acos, "ACOS")


@implements("ATAN@st", "ATN@st")
def atan(ctx: ExecContext, rung: bool, x: Number) -> float:
    return math.atan(x)


@implements("DEG@st")
def deg(ctx: ExecContext, rung: bool, x: Number) -> float:
    return x * (180.0 / math.pi)


@implements("RAD@st")
def rad(ctx: ExecContext, rung: bool, x: Number) -> float:
    return x * (math.pi / 180.0)


@implements("TRUNC@st", "TRN@st")
def trunc(ctx: ExecContext, rung: bool, x: Number) -> Number:
    if isinstance(x, int):
        return x  # an integer has no fractional part
    if not math.isfinite(x):
        return x
    return float(math.trunc(x))  # stays a REAL/LREAL: -2.7 -> -2.0


@implements("ATAN2@st")
def atan2(ctx: ExecContext, rung: bool, y: Number, x: Number) -> float:
    """Angle of (x, y) in radians, -pi..pi; atan2(0, 0) is 0 (IEEE, as the controller)."""
    return math.atan2(y, x)
