"""Ladder compute/math instructions with a destination: ADD SUB MUL DIV MOD SQR NEG ABS XPY,
the trigonometric and logarithmic family SIN COS TAN ASN ACS ATN ATAN2 LN LOG, DEG RAD TRN, and
the limit / mask-compare input instructions LIM and MEQ.

Arithmetic (SPEC 3.3, 9.19, decision 0030):
- Operands arrive as Python numbers, so their declared types are not visible here. Integer
  operands are computed exactly and the result is judged against Dest: a result outside
  Dest's range is stored wrapped and sets S:V (minor fault 4/4).
- When a float operand is present the operation is REAL (float32): each operand and the
  result are rounded to single precision. It is LREAL (double) instead when Dest is LREAL
  or a 64-bit integer, or when an operand is not exactly representable in float32 (it can
  only have come from an LREAL tag).
- DIV: integer operands truncate toward zero, except into a REAL/LREAL Dest, where they are
  divided in floating point (SPEC 9.19). Division by zero sets S:V and records minor fault
  4/4; the integer result is Source A, the floating result ±inf or NaN (IEEE).
- MOD is A - TRN(A / B) * B (sign of the dividend); MOD by zero: 0 for integers, NaN for
  floating operands, with S:V.
- SQR takes the square root of |Source| (documented, no fault). Integer Source into an
  integer Dest truncates the root, as for DIV; a REAL result is rounded on conversion.
- XPY is computed in floating point; a negative X with a non-integer Y, or 0 to a negative
  power, gives NaN / inf and S:V.
- The functions reuse the Structured Text implementations (functions.py) for their domain
  rules; their minor fault is not recorded twice.
Flags: every instruction here except LIM and MEQ updates S:N S:Z S:V; ADD/SUB also S:C.
A false rung does nothing (rung-condition-out = rung-condition-in).
"""

from __future__ import annotations

import math
from collections.abc import Callable

from ..semantics.types import Kind
from ..vm.context import ExecContext
from ..vm.values import f32
from . import functions as fn
from .ladder_status import Dest, Number, fault_count, store
from .registry import implements

UNARY = Callable[[ExecContext, bool, Number], Number]


# ------------------------------------------------------------------ operation type
def _all_int(*xs: Number) -> bool:
    return all(isinstance(x, int) for x in xs)


def _single(dest: Dest, *xs: Number) -> bool:
    """True when a floating operation is REAL (float32) rather than LREAL."""
    t = dest.type
    if t.bits == 64:
        return False
    return all(isinstance(x, int) or not math.isfinite(x) or f32(x) == x for x in xs)


def _fl(x: Number, single: bool) -> float:
    return f32(float(x)) if single else float(x)


def _fop(dest: Dest, op: Callable[[float, float], float], a: Number, b: Number) -> float:
    """A binary floating operation in REAL or LREAL, rounded like the controller."""
    single = _single(dest, a, b)
    r = op(_fl(a, single), _fl(b, single))
    return f32(r) if single else r


def _fdiv(x: float, y: float) -> float:
    if y == 0.0:
        if x == 0.0 or math.isnan(x):
            return math.nan
        return math.copysign(math.inf, x) * math.copysign(1.0, y)
    return x / y


def _carry_bits(dest: Dest) -> int:
    # Integer ladder math is DINT unless LINT is involved (Data conversions, v37).
    return 64 if dest.type.kind is Kind.INT and dest.type.bits == 64 else 32


# ------------------------------------------------------------------ + - * / MOD
@implements("ADD")
def add(ctx: ExecContext, rung: bool, a: Number, b: Number, dest: Dest) -> None:
    if not rung:
        return
    if isinstance(a, int) and isinstance(b, int):
        m = (1 << _carry_bits(dest)) - 1
        store(ctx, dest, a + b, carry=(a & m) + (b & m) > m)
    else:
        store(ctx, dest, _fop(dest, lambda x, y: x + y, a, b))


@implements("SUB")
def sub(ctx: ExecContext, rung: bool, a: Number, b: Number, dest: Dest) -> None:
    if not rung:
        return
    if isinstance(a, int) and isinstance(b, int):
        m = (1 << _carry_bits(dest)) - 1
        store(ctx, dest, a - b, carry=(a & m) < (b & m))  # borrow into the top bit
    else:
        store(ctx, dest, _fop(dest, lambda x, y: x - y, a, b))


@implements("MUL")
def mul(ctx: ExecContext, rung: bool, a: Number, b: Number, dest: Dest) -> None:
    if not rung:
        return
    if _all_int(a, b):
        store(ctx, dest, a * b)
    else:
        store(ctx, dest, _fop(dest, lambda x, y: x * y, a, b))


def _trunc_div(a: int, b: int) -> int:
    q = abs(a) // abs(b)
    return q if (a >= 0) == (b >= 0) else -q


@implements("DIV")
def div(ctx: ExecContext, rung: bool, a: Number, b: Number, dest: Dest) -> None:
    if not rung:
        return
    if _all_int(a, b) and dest.type.kind is not Kind.REAL:
        if b == 0:
            store(ctx, dest, a, overflow=True)
        else:
            store(ctx, dest, _trunc_div(a, b))  # type: ignore[arg-type]
        return
    store(ctx, dest, _fop(dest, _fdiv, a, b), overflow=b == 0)


@implements("MOD@rll")
def mod(ctx: ExecContext, rung: bool, a: Number, b: Number, dest: Dest) -> None:
    if not rung:
        return
    if _all_int(a, b):
        if b == 0:
            store(ctx, dest, 0, overflow=True)
        else:
            store(ctx, dest, a - _trunc_div(a, b) * b)  # type: ignore[arg-type]
        return
    single = _single(dest, a, b)
    x, y = _fl(a, single), _fl(b, single)
    if y == 0.0:
        store(ctx, dest, math.nan)
        return
    q = _fl(x / y, single)
    t = float(math.trunc(q)) if math.isfinite(q) else q
    store(ctx, dest, _fl(x - _fl(t * y, single), single))


# ------------------------------------------------------------------ one-operand math
@implements("NEG")
def neg(ctx: ExecContext, rung: bool, x: Number, dest: Dest) -> None:
    if rung:
        store(ctx, dest, -x if isinstance(x, int) else _fl(-x, _single(dest, x)))


@implements("ABS@rll")
def abs_(ctx: ExecContext, rung: bool, x: Number, dest: Dest) -> None:
    if rung:
        store(ctx, dest, abs(x) if isinstance(x, int) else _fl(abs(x), _single(dest, x)))


@implements("SQR@rll")
def sqr(ctx: ExecContext, rung: bool, x: Number, dest: Dest) -> None:
    if not rung:
        return
    if isinstance(x, int) and dest.type.kind is Kind.INT:
        store(ctx, dest, math.isqrt(abs(x)))  # integer Source and Dest: the root is truncated
        return
    single = _single(dest, x)
    store(ctx, dest, _fl(math.sqrt(abs(_fl(x, single))), single))


@implements("XPY@rll")
def xpy(ctx: ExecContext, rung: bool, x: Number, y: Number, dest: Dest) -> None:
    if not rung:
        return
    single = _single(dest, x, y)
    bx, ey = _fl(x, single), _fl(y, single)
    try:
        r = math.pow(bx, ey)
    except (ValueError, ZeroDivisionError):  # (-8) ** 0.5, 0 ** -1
        r = math.inf if bx == 0.0 else math.nan
    except OverflowError:
        r = math.copysign(math.inf, bx) if ey.is_integer() and ey % 2 else math.inf
    store(ctx, dest, _fl(r, single))


def _function(ctx: ExecContext, dest: Dest, x: Number, f: UNARY) -> None:
    """Apply an ST function core in REAL or LREAL and store it, faulting once."""
    single = _single(dest, x)
    before = fault_count(ctx)
    r = f(ctx, True, _fl(x, single))
    store(ctx, dest, _fl(r, single), fault=fault_count(ctx) == before)


def _unary(name: str, f: UNARY) -> None:
    def impl(ctx: ExecContext, rung: bool, x: Number, dest: Dest) -> None:
        if rung:
            _function(ctx, dest, x, f)

    impl.__name__ = impl.__qualname__ = name.lower()
    implements(f"{name}@rll")(impl)


for _name, _f in (
    ("SIN", fn.sin),
    ("COS", fn.cos),
    ("TAN", fn.tan),
    ("ASN", fn.asin),
    ("ACS", fn.acos),
    ("ATN", fn.atan),
    ("LN", fn.ln),
    ("LOG", fn.log),
    ("DEG", fn.deg),
    ("RAD", fn.rad),
):
    _unary(_name, _f)


@implements("TRN@rll")
def trn(ctx: ExecContext, rung: bool, x: Number, dest: Dest) -> None:
    if rung:
        store(ctx, dest, fn.trunc(ctx, True, x if isinstance(x, int) else _fl(x, _single(dest, x))))


# ------------------------------------------------------------------ LIM / MEQ (input instructions)
@implements("LIM")
def lim(ctx: ExecContext, rung: bool, low: Number, test: Number, high: Number) -> bool:
    """Low <= Test <= High; with Low > High the circular range Test >= Low or Test <= High."""
    if not rung:
        return False
    if not _all_int(low, test, high) and all(
        isinstance(v, int) or f32(v) == v for v in (low, test, high)
    ):
        low, test, high = (f32(float(v)) for v in (low, test, high))  # compared as REALs
    if low <= high:
        return low <= test <= high
    return test >= low or test <= high


@implements("MEQ")
def meq(ctx: ExecContext, rung: bool, source: int, mask: int, compare: int) -> bool:
    """Source and Compare are equal in every bit the mask selects."""
    if not rung:
        return False
    return (int(source) & int(mask)) == (int(compare) & int(mask))


# ------------------------------------------------------------------ ATAN2
@implements("ATAN2@rll")
def atan2_rung(ctx: ExecContext, rung: bool, y: Number, x: Number, dest: Dest) -> None:
    """Dest = atan2(Source Y, Source X) in radians; REAL unless Dest or a source is LREAL."""
    if rung:
        single = _single(dest, y, x)
        store(ctx, dest, _fl(math.atan2(_fl(y, single), _fl(x, single)), single))
