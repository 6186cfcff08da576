"""Structured Text function-block timers, counter and one-shots (TONR TOFR RTOR CTUD OSRI OSFI).

Sources: 1756-RM003 (timer/counter and bit chapters) and the Studio 5000 v37 instruction help.
- In ST the block always executes whatever EnableIn holds ("EnableIn is always set").
- Time is virtual: `ctx.now_ms` is the start of the current scan. A running timer adds the
  time since its previous execution (`ACC += now - last_time_scanned`, RM003), so the first
  enabled execution leaves ACC at 0 and each later one adds the elapsed scan time.
  Sub-millisecond remainders are kept in the hidden ACCFraction member, the previous
  execution time in the hidden LastTime member.
- ACC stops at PRE (it never runs past the preset).
- PRE < 0: Status.PresetInv and Status.InstructFault are set, EnableOut is cleared and the
  timer does not execute (RM003: "If invalid, the instruction sets the appropriate bit in
  Status and the timer does not execute"). A valid PRE clears those bits again.
- Prescan performs the documented "instruction first scan" initialisation.
"""

from __future__ import annotations

import math

from ..semantics.types import StructType, TypeTable
from ..vm.context import ExecContext
from .registry import implements, prescan

DINT_MAX = 2**31 - 1
DINT_MIN = -(2**31)


def _layout(name: str) -> dict[str, int]:
    t = TypeTable().get(name)
    assert isinstance(t, StructType), name
    return t.index


_T = _layout("FBD_TIMER")
T_ENABLE, T_PRE, T_RESET, T_EOUT = _T["TIMERENABLE"], _T["PRE"], _T["RESET"], _T["ENABLEOUT"]
T_ACC, T_EN, T_TT, T_DN = _T["ACC"], _T["EN"], _T["TT"], _T["DN"]
T_STATUS, T_FAULT, T_PRESET_INV = _T["STATUS"], _T["INSTRUCTFAULT"], _T["PRESETINV"]
T_PREV, T_FRAC, T_LAST = _T["TIMERENABLEPREV"], _T["ACCFRACTION"], _T["LASTTIME"]

_C = _layout("FBD_COUNTER")
C_UP_IN, C_DOWN_IN, C_PRE, C_RESET = _C["CUENABLE"], _C["CDENABLE"], _C["PRE"], _C["RESET"]
C_EOUT, C_ACC, C_CU, C_CD = _C["ENABLEOUT"], _C["ACC"], _C["CU"], _C["CD"]
C_DN, C_OV, C_UN = _C["DN"], _C["OV"], _C["UN"]
C_UP_PREV, C_DOWN_PREV = _C["CUENABLEPREV"], _C["CDENABLEPREV"]

_O = _layout("FBD_ONESHOT")
O_IN, O_EOUT, O_OUT, O_PREV = _O["INPUTBIT"], _O["ENABLEOUT"], _O["OUTPUTBIT"], _O["INPUTBITPREV"]

# Virtual times are sums of float scan periods; a tiny tolerance keeps 0.1 ms steps from
# losing a millisecond to representation error (0.30000000000000004 vs 0.3).
_EPS = 1e-9


# ------------------------------------------------------------------ timer helpers
def _preset_ok(t: list) -> bool:
    """Check PRE, keep Status and its BOOL aliases consistent; False = do not execute."""
    invalid = t[T_PRE] < 0
    t[T_STATUS] = 0b11 if invalid else 0
    t[T_FAULT] = t[T_PRESET_INV] = int(invalid)
    t[T_EOUT] = int(not invalid)
    return not invalid


def _start_timing(
    ctx: ExecContext, t: list, keep_fraction: bool = False, last: int = T_LAST, frac: int = T_FRAC
) -> None:
    """Remember now as the previous execution time (`last`/`frac` index the hidden members)."""
    t[last] = ctx.now_ms
    if not keep_fraction:
        t[frac] = 0.0


def _elapsed_ms(ctx: ExecContext, t: list, last: int = T_LAST, frac: int = T_FRAC) -> int:
    """Whole milliseconds since the previous execution; the remainder is carried.

    Shared with the ladder timers (ladder_timers_counters.py), whose TIMER keeps the same two
    hidden members at other indices.
    """
    total = max(0.0, ctx.now_ms - t[last]) + t[frac]
    whole = math.floor(total + _EPS)
    t[frac] = max(0.0, total - whole)
    t[last] = ctx.now_ms
    return int(whole)


def _accumulate(ctx: ExecContext, t: list) -> None:
    """ACC += elapsed time, stopping at PRE (an ACC already past PRE is left alone)."""
    step = _elapsed_ms(ctx, t)
    if t[T_ACC] < t[T_PRE]:
        t[T_ACC] = min(t[T_ACC] + step, t[T_PRE])


def _clear_bits(t: list) -> None:
    t[T_EN] = t[T_TT] = t[T_DN] = 0


def _reset_timer(t: list) -> None:
    _clear_bits(t)
    t[T_ACC] = 0
    t[T_PREV] = 0
    t[T_FRAC] = 0.0


def _on_delay_step(ctx: ExecContext, t: list, retentive: bool) -> None:
    """One enabled execution of TONR/RTOR."""
    if t[T_PREV]:
        _accumulate(ctx, t)
    else:
        if not retentive:
            t[T_ACC] = 0  # non-retentive: every on period starts from zero
        _start_timing(ctx, t, keep_fraction=retentive)
        t[T_PREV] = 1
    t[T_EN] = 1
    t[T_DN] = int(t[T_ACC] >= t[T_PRE])
    t[T_TT] = int(not t[T_DN])


# ------------------------------------------------------------------ TONR / RTOR / TOFR
@implements("TONR")
def tonr(ctx: ExecContext, rung: bool, t: list) -> None:
    if not _preset_ok(t):
        return
    if t[T_RESET] or not t[T_ENABLE]:
        _reset_timer(t)
        return
    _on_delay_step(ctx, t, retentive=False)


@implements("RTOR")
def rtor(ctx: ExecContext, rung: bool, t: list) -> None:
    if not _preset_ok(t):
        return
    if t[T_RESET]:
        _reset_timer(t)
        return
    if not t[T_ENABLE]:
        # ACC and DN are retained; only the running indication drops.
        t[T_EN] = t[T_TT] = 0
        t[T_PREV] = 0
        return
    _on_delay_step(ctx, t, retentive=True)


@implements("TOFR")
def tofr(ctx: ExecContext, rung: bool, t: list) -> None:
    if not _preset_ok(t):
        return
    if t[T_RESET]:
        # RM003: with TimerEnable cleared, timing does not restart when Reset clears.
        _reset_timer(t)
        return
    if t[T_ENABLE]:
        t[T_EN] = t[T_DN] = 1
        t[T_TT] = 0
        t[T_ACC] = 0
        t[T_PREV] = 1
        return
    t[T_EN] = 0
    if t[T_PREV]:  # falling edge of TimerEnable: the off delay starts now
        t[T_PREV] = 0
        t[T_ACC] = 0
        _start_timing(ctx, t)
    elif t[T_TT]:
        _accumulate(ctx, t)
    else:
        return  # idle (never enabled, reset, or delay already over)
    done = t[T_ACC] >= t[T_PRE]
    t[T_TT] = int(not done)
    t[T_DN] = int(not done)


@prescan("TONR")
def tonr_prescan(ctx: ExecContext, rung: bool, t: list) -> None:
    # RM003 "instruction first scan": EN, TT and DN cleared, ACC set to 0.
    _reset_timer(t)


@prescan("RTOR")
def rtor_prescan(ctx: ExecContext, rung: bool, t: list) -> None:
    # RM003 "instruction first scan": EN, TT and DN cleared, ACC not modified.
    _clear_bits(t)
    t[T_PREV] = 0


@prescan("TOFR")
def tofr_prescan(ctx: ExecContext, rung: bool, t: list) -> None:
    # As ladder TOF prescan (SPEC 3.2): bits cleared and ACC = PRE, so nothing is timing.
    _clear_bits(t)
    t[T_PREV] = 0
    t[T_ACC] = t[T_PRE]


# ------------------------------------------------------------------ CTUD
def _count_up(c: list) -> None:
    if c[C_ACC] == DINT_MAX:
        c[C_ACC] = DINT_MIN
        # Ladder CTU rule: wrapping up out of an underflow cancels it, otherwise overflow.
        if c[C_UN]:
            c[C_UN] = 0
        else:
            c[C_OV] = 1
    else:
        c[C_ACC] += 1


def _count_down(c: list) -> None:
    if c[C_ACC] == DINT_MIN:
        c[C_ACC] = DINT_MAX
        if c[C_OV]:
            c[C_OV] = 0
        else:
            c[C_UN] = 1
    else:
        c[C_ACC] -= 1


@implements("CTUD")
def ctud(ctx: ExecContext, rung: bool, c: list) -> None:
    c[C_EOUT] = 1
    if c[C_RESET]:
        # RM003: Reset clears CUEnable(n-1), CDEnable(n-1), CU, CD, DN, OV, UN and ACC.
        c[C_ACC] = 0
        c[C_CU] = c[C_CD] = c[C_DN] = c[C_OV] = c[C_UN] = 0
        c[C_UP_PREV] = c[C_DOWN_PREV] = 0
        return
    up, down = c[C_UP_IN], c[C_DOWN_IN]
    if up and not c[C_UP_PREV]:
        _count_up(c)  # RM003: the up count is applied before the down count
    if down and not c[C_DOWN_PREV]:
        _count_down(c)
    c[C_UP_PREV], c[C_DOWN_PREV] = int(bool(up)), int(bool(down))
    c[C_CU], c[C_CD] = int(bool(up)), int(bool(down))
    c[C_DN] = int(c[C_ACC] >= c[C_PRE])


@prescan("CTUD")
def ctud_prescan(ctx: ExecContext, rung: bool, c: list) -> None:
    # RM003 "instruction first scan": CUEnable(n-1) and CDEnable(n-1) are set, so an input
    # already true when the controller enters Run does not count.
    c[C_UP_PREV] = c[C_DOWN_PREV] = 1


# ------------------------------------------------------------------ OSRI / OSFI
@implements("OSRI")
def osri(ctx: ExecContext, rung: bool, o: list) -> None:
    o[O_EOUT] = 1
    o[O_OUT] = int(bool(o[O_IN]) and not o[O_PREV])
    o[O_PREV] = int(bool(o[O_IN]))


@implements("OSFI")
def osfi(ctx: ExecContext, rung: bool, o: list) -> None:
    o[O_EOUT] = 1
    o[O_OUT] = int(not o[O_IN] and bool(o[O_PREV]))
    o[O_PREV] = int(bool(o[O_IN]))


@prescan("OSRI")
def osri_prescan(ctx: ExecContext, rung: bool, o: list) -> None:
    # First scan: input history set, so an input already true at Run gives no pulse.
    o[O_PREV] = 1
    o[O_OUT] = 0


@prescan("OSFI")
def osfi_prescan(ctx: ExecContext, rung: bool, o: list) -> None:
    # First scan: input history cleared, so a true-to-false transition is required.
    o[O_PREV] = 0
    o[O_OUT] = 0
