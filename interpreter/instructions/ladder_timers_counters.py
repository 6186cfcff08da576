"""Ladder timers TON TOF RTO, counters CTU CTD and RES (1756-RM003 timer/counter chapter).

Operands: the TIMER / COUNTER as its live member list, then the Preset and Accum
pseudo-operands. At run time the instructions read PRE and ACC from the structure (the rung's
numbers only display them). Logix writes the pseudo-operand values into the structure when
the project is downloaded; logixst does that in the prescan action, which runs once before
the first scan, so `TON(T, 500, 0)` gives T.PRE = 500 unless the rung says `?`
(decision 0030).

Timing follows the RM003 flow charts, in virtual milliseconds (`ctx.now_ms`):
- TON, rung true: a done timer does nothing more. The first true execution sets EN and TT and
  remembers the time; each later one adds the elapsed time to ACC (saturating at
  2147483647); ACC >= PRE sets DN and clears TT. ACC is not clamped to PRE: a scan that
  overshoots leaves ACC past PRE, as on the controller. Rung false: EN TT DN and ACC cleared.
- TOF mirrors it on the false rung: a true rung sets EN and DN, clears TT and ACC; the
  first false execution of a done timer clears EN, sets TT and remembers the time; later
  ones accumulate until ACC >= PRE clears DN and TT. A false rung with DN already clear does
  nothing (so TOF does not run after prescan, which sets ACC = PRE).
- RTO times like TON but keeps ACC (and DN) on a false rung; only RES clears them.
- Sub-millisecond scan periods carry the remainder in the hidden ACCFraction member; the
  hidden LastTime member is the controller's last_time_scanned.
Counters count rising edges of the rung, using CU (CTU) / CD (CTD) as the edge memory. A
count past 2147483647 wraps to -2147483648 and sets OV (or clears UN when the counter had
underflowed before), and symmetrically for CTD. DN: set while OV is set, clear while UN is
set, otherwise ACC >= PRE; it is evaluated whenever the rung is true.
"""

from __future__ import annotations

from ..vm.context import ExecContext
from .fbd_timers import DINT_MAX, DINT_MIN, _elapsed_ms, _layout, _start_timing
from .registry import implements, prescan

_T = _layout("TIMER")
PRE, ACC, EN, TT, DN = _T["PRE"], _T["ACC"], _T["EN"], _T["TT"], _T["DN"]
FRAC, LAST = _T["ACCFRACTION"], _T["LASTTIME"]

_C = _layout("COUNTER")
C_PRE, C_ACC, CU, CD = _C["PRE"], _C["ACC"], _C["CU"], _C["CD"]
C_DN, OV, UN = _C["DN"], _C["OV"], _C["UN"]

_K = _layout("CONTROL")
K_LEN, K_POS = _K["LEN"], _K["POS"]
K_BITS = tuple(_K[b] for b in ("EN", "EU", "DN", "EM", "ER", "UL", "IN", "FD"))


def apply_pseudo(s: list, pairs: tuple[tuple[int, object], ...]) -> None:
    """Write literal pseudo-operand values (Preset/Accum, Length/Position) into a structure.

    A `?` placeholder arrives as None and leaves the member alone.
    """
    for index, value in pairs:
        if isinstance(value, int | float) and not isinstance(value, bool):
            s[index] = int(value)


def _clear_bits(t: list) -> None:
    t[EN] = t[TT] = t[DN] = 0


def _start(ctx: ExecContext, t: list, keep_fraction: bool) -> None:
    _start_timing(ctx, t, keep_fraction, last=LAST, frac=FRAC)


def _accumulate(ctx: ExecContext, t: list) -> int:
    """ACC += time since the previous execution, saturating at the DINT maximum."""
    acc = t[ACC] + _elapsed_ms(ctx, t, last=LAST, frac=FRAC)
    t[ACC] = min(acc, DINT_MAX)
    return t[ACC]  # type: ignore[no-any-return]


def _on_delay(ctx: ExecContext, t: list, retentive: bool) -> None:
    """The true-rung branch shared by TON and RTO."""
    if t[DN]:
        return
    if not t[EN]:
        t[EN] = t[TT] = 1
        _start(ctx, t, keep_fraction=retentive)
        return
    if _accumulate(ctx, t) >= t[PRE]:
        t[DN] = 1
        t[TT] = 0
    else:
        t[TT] = 1


# ------------------------------------------------------------------ TON
@implements("TON")
def ton(ctx: ExecContext, rung: bool, t: list, preset: object = None, accum: object = None) -> None:
    if rung:
        _on_delay(ctx, t, retentive=False)
    else:
        _clear_bits(t)
        t[ACC] = 0
        t[FRAC] = 0.0


@prescan("TON")
def ton_prescan(
    ctx: ExecContext, rung: bool, t: list, preset: object = None, accum: object = None
) -> None:
    apply_pseudo(t, ((PRE, preset), (ACC, accum)))
    _clear_bits(t)
    t[ACC] = 0
    t[FRAC] = 0.0


# ------------------------------------------------------------------ TOF
@implements("TOF")
def tof(ctx: ExecContext, rung: bool, t: list, preset: object = None, accum: object = None) -> None:
    if rung:
        t[EN] = t[DN] = 1
        t[TT] = 0
        t[ACC] = 0
        t[FRAC] = 0.0
        return
    if not t[DN]:
        return  # timed out (or paused by clearing DN): nothing to do
    if t[EN]:
        t[EN] = 0
        t[TT] = 1
        _start(ctx, t, keep_fraction=False)
        return
    if _accumulate(ctx, t) >= t[PRE]:
        t[DN] = t[TT] = 0
    else:
        t[TT] = 1


@prescan("TOF")
def tof_prescan(
    ctx: ExecContext, rung: bool, t: list, preset: object = None, accum: object = None
) -> None:
    apply_pseudo(t, ((PRE, preset), (ACC, accum)))
    _clear_bits(t)
    t[ACC] = t[PRE]


# ------------------------------------------------------------------ RTO
@implements("RTO")
def rto(ctx: ExecContext, rung: bool, t: list, preset: object = None, accum: object = None) -> None:
    if rung:
        _on_delay(ctx, t, retentive=True)
    else:
        t[EN] = t[TT] = 0  # ACC and DN are retained


@prescan("RTO")
def rto_prescan(
    ctx: ExecContext, rung: bool, t: list, preset: object = None, accum: object = None
) -> None:
    apply_pseudo(t, ((PRE, preset), (ACC, accum)))
    _clear_bits(t)


# ------------------------------------------------------------------ CTU / CTD
def _counter_done(c: list) -> None:
    if c[OV]:
        c[C_DN] = 1  # the true count is above every DINT preset
    elif c[UN]:
        c[C_DN] = 0
    else:
        c[C_DN] = int(c[C_ACC] >= c[C_PRE])


@implements("CTU")
def ctu(ctx: ExecContext, rung: bool, c: list, preset: object = None, accum: object = None) -> None:
    if not rung:
        c[CU] = 0
        return
    if not c[CU]:
        c[CU] = 1
        acc = c[C_ACC] + 1
        if acc > DINT_MAX:
            acc = DINT_MIN
            if c[UN]:
                c[UN] = 0  # counting back up over the wrap undoes an earlier underflow
            else:
                c[OV] = 1
        c[C_ACC] = acc
    _counter_done(c)


@prescan("CTU")
def ctu_prescan(
    ctx: ExecContext, rung: bool, c: list, preset: object = None, accum: object = None
) -> None:
    apply_pseudo(c, ((C_PRE, preset), (C_ACC, accum)))
    c[CU] = 1  # a rung already true at start-up is not a count


@implements("CTD")
def ctd(ctx: ExecContext, rung: bool, c: list, preset: object = None, accum: object = None) -> None:
    if not rung:
        c[CD] = 0
        return
    if not c[CD]:
        c[CD] = 1
        acc = c[C_ACC] - 1
        if acc < DINT_MIN:
            acc = DINT_MAX
            if c[OV]:
                c[OV] = 0
            else:
                c[UN] = 1
        c[C_ACC] = acc
    _counter_done(c)


@prescan("CTD")
def ctd_prescan(
    ctx: ExecContext, rung: bool, c: list, preset: object = None, accum: object = None
) -> None:
    apply_pseudo(c, ((C_PRE, preset), (C_ACC, accum)))
    c[CD] = 1


# ------------------------------------------------------------------ RES
@implements("RES")
def res(ctx: ExecContext, rung: bool, s: list) -> None:
    """Reset a TIMER, COUNTER or CONTROL on a true rung (a false rung does nothing)."""
    if not rung:
        return
    if len(s) == len(_K):
        s[K_POS] = 0
        for i in K_BITS:
            s[i] = 0
    elif isinstance(s[FRAC], float):
        # TIMER and COUNTER have the same length; only the TIMER holds (hidden) LREALs.
        _clear_bits(s)
        s[ACC] = 0
        s[FRAC] = 0.0
    else:
        s[C_ACC] = 0
        for i in (CU, CD, C_DN, OV, UN):
            s[i] = 0
