"""Select/limit, statistical and accumulator blocks that are one step of arithmetic:
HLL, MUX, SEL, SNEG, SSUM (select/limit), MAXC, MINC (statistical), UPDN (drives).

Sources: 1756-RM006 and the Studio 5000 v37 instruction help for each block.
- Structured Text calls the block on its tag (`HLL(myLimit);`); as for the timers
  (fbd_timers.py), EnableIn is not consulted in ST: the block always executes.
- Out is a REAL member: results are rounded to single precision. EnableOut is set after an
  execution and cleared when Out overflows to an infinity (the blocks' documented rule).
- InstructFault (Status.0) is set whenever another Status bit reports an invalid parameter
  (RM006: it summarises the execution errors that the other bits detail).
Decisions where the help is silent are in docs/decisions/0063-simple-function-blocks.md.
"""

from __future__ import annotations

import math

from ..semantics.types import StructType, TypeTable
from ..vm.context import ExecContext
from ..vm.values import f32
from .registry import implements


def layout(name: str) -> dict[str, int]:
    """Member index by upper-case name of a catalog structure."""
    t = TypeTable().get(name)
    assert isinstance(t, StructType), name
    return t.index


def set_out(s: list, out: int, eout: int, value: float) -> None:
    """Store a REAL output rounded to float32; EnableOut drops if it overflowed."""
    v = f32(value)
    s[out] = v
    s[eout] = int(not math.isinf(v))


# ------------------------------------------------------------------ HLL
_H = layout("HL_LIMIT")


@implements("HLL")
def hll(ctx: ExecContext, rung: bool, s: list) -> None:
    """Clamp In. SelectLimit 0 both limits, 1 high only, 2 low only; anything else is
    SelectLimitInv and treated as 0. With both limits and HighLimit <= LowLimit: LimitsInv and
    Out = LowLimit. HighAlarm is In >= HighLimit (not with SelectLimit 2), LowAlarm is
    In <= LowLimit (not with SelectLimit 1)."""
    x, hi, lo = s[_H["IN"]], s[_H["HIGHLIMIT"]], s[_H["LOWLIMIT"]]
    sel = s[_H["SELECTLIMIT"]]
    sel_inv = sel not in (0, 1, 2)
    if sel_inv:
        sel = 0
    limits_inv = sel == 0 and hi <= lo
    use_high, use_low = sel in (0, 1), sel in (0, 2)
    if limits_inv:
        out = lo
    else:
        out = x
        if use_high and out > hi:
            out = hi
        if use_low and out < lo:
            out = lo
    s[_H["HIGHALARM"]] = int(use_high and x >= hi)
    s[_H["LOWALARM"]] = int(use_low and x <= lo)
    s[_H["LIMITSINV"]] = int(limits_inv)
    s[_H["SELECTLIMITINV"]] = int(sel_inv)
    s[_H["INSTRUCTFAULT"]] = int(limits_inv or sel_inv)
    s[_H["STATUS"]] = int(limits_inv or sel_inv) | limits_inv << 1 | sel_inv << 2
    set_out(s, _H["OUT"], _H["ENABLEOUT"], out)


# ------------------------------------------------------------------ MUX
_M = layout("MULTIPLEXER")
_M_INS = [_M[f"IN{i}"] for i in range(1, 9)]


@implements("MUX")
def mux(ctx: ExecContext, rung: bool, s: list) -> None:
    """Out = In<Selector>; a Selector outside 1..8 sets SelectorInv and leaves Out alone."""
    sel = s[_M["SELECTOR"]]
    invalid = not 1 <= sel <= 8
    s[_M["SELECTORINV"]] = s[_M["INSTRUCTFAULT"]] = int(invalid)
    s[_M["STATUS"]] = 0b11 if invalid else 0
    if invalid:
        s[_M["ENABLEOUT"]] = 1
        return
    set_out(s, _M["OUT"], _M["ENABLEOUT"], s[_M_INS[sel - 1]])


# ------------------------------------------------------------------ SEL / SNEG
_S = layout("SELECT")


@implements("SEL")
def sel(ctx: ExecContext, rung: bool, s: list) -> None:
    pick = _S["IN2"] if s[_S["SELECTORIN"]] else _S["IN1"]
    set_out(s, _S["OUT"], _S["ENABLEOUT"], s[pick])


_N = layout("SELECTABLE_NEGATE")


@implements("SNEG")
def sneg(ctx: ExecContext, rung: bool, s: list) -> None:
    x = s[_N["IN"]]
    set_out(s, _N["OUT"], _N["ENABLEOUT"], -x if s[_N["NEGATEENABLE"]] else x)


# ------------------------------------------------------------------ SSUM
_U = layout("SELECTED_SUMMER")
_U_TERMS = [(_U[f"IN{i}"], _U[f"GAIN{i}"], _U[f"SELECT{i}"]) for i in range(1, 9)]


@implements("SSUM")
def ssum(ctx: ExecContext, rung: bool, s: list) -> None:
    """Out = Bias + sum of In(i) * Gain(i) over the selected inputs, each product and sum
    rounded to REAL as the controller computes in single precision."""
    total = s[_U["BIAS"]]
    for i, g, on in _U_TERMS:
        if s[on]:
            total = f32(total + f32(s[i] * s[g]))
    set_out(s, _U["OUT"], _U["ENABLEOUT"], total)


# ------------------------------------------------------------------ MAXC / MINC
_MAX = layout("MAXIMUM_CAPTURE")
_MIN = layout("MINIMUM_CAPTURE")


def _capture(s: list, ix: dict[str, int], better: object) -> None:
    if s[ix["RESET"]]:
        out = s[ix["RESETVALUE"]]
    else:
        out = better(s[ix["OUT"]], s[ix["IN"]])  # type: ignore[operator]
    set_out(s, ix["OUT"], ix["ENABLEOUT"], out)


@implements("MAXC")
def maxc(ctx: ExecContext, rung: bool, s: list) -> None:
    """Out keeps the largest In since Reset; while Reset is set Out = ResetValue."""
    _capture(s, _MAX, max)


@implements("MINC")
def minc(ctx: ExecContext, rung: bool, s: list) -> None:
    """Out keeps the smallest In since Reset; while Reset is set Out = ResetValue."""
    _capture(s, _MIN, min)


# ------------------------------------------------------------------ UPDN
_D = layout("UP_DOWN_ACCUM")


@implements("UPDN")
def updn(ctx: ExecContext, rung: bool, s: list) -> None:
    """Initialize: Out = InitialValue. Otherwise, unless Hold: Out += InPlus - InMinus."""
    if s[_D["INITIALIZE"]]:
        out = s[_D["INITIALVALUE"]]
    elif s[_D["HOLD"]]:
        out = s[_D["OUT"]]
    else:
        out = f32(f32(s[_D["OUT"]] + s[_D["INPLUS"]]) - s[_D["INMINUS"]])
    set_out(s, _D["OUT"], _D["ENABLEOUT"], out)
