"""Time-based drives blocks: INTG, DERV (drives, filters), RLIM (select/limit), decision 0171.

Sources: 1756-RM006 (drives, filter and select/limit chapters), Studio 5000 v37 help.
Conventions as filter_blocks.py (decision 0170): the block executes at every ST call,
DeltaT from block_timing (decision 0139; None = leave the outputs), REAL outputs rounded
to single precision, EnableOut cleared when Out is not finite, InstructFault with any
"...Inv" Status bit, Status packed from its BOOL members. The input is taken as constant
over the interval that ends at this execution, so integrals are exact sums In_n x DeltaT.
Initialisation: the Initialize input and the first computing execution after prescan (the
reference's "instruction first scan"); the hidden Primed member records the latter.
"""

from __future__ import annotations

from ..vm.context import ExecContext
from .filter_blocks import Block, block, clear_flags, delta_t, finish, reset_block, set_out
from .registry import implements, prescan


def _limits(s: list, b: Block, value: float, previous: float) -> float:
    """Hold inputs, then HighLimit/LowLimit with HighAlarm/LowAlarm (the value before
    limiting at or beyond a limit) and HighLowLimsInv (HighLimit <= LowLimit: Out is held
    on LowLimit)."""
    ix = b.ix
    if s[ix["HOLDHIGH"]] and value > previous:
        value = previous  # no movement upwards while HoldHigh (anti-windup)
    if s[ix["HOLDLOW"]] and value < previous:
        value = previous
    hi, lo = float(s[ix["HIGHLIMIT"]]), float(s[ix["LOWLIMIT"]])
    inv = not hi > lo
    s[ix["HIGHLOWLIMSINV"]] = int(inv)
    if inv:
        hi = lo  # an empty range: Out sits on LowLimit
    s[ix["HIGHALARM"]] = int(value >= hi)
    s[ix["LOWALARM"]] = int(value <= lo)
    return min(max(value, lo), hi)


# ------------------------------------------------------------------ INTG
_INTG = block("INTEGRATOR")


@implements("INTG")
def intg(ctx: ExecContext, rung: bool, s: list) -> None:
    """Out_n = Out_(n-1) + IGain x In_n x DeltaT, then the hold inputs (no change upwards
    with HoldHigh, downwards with HoldLow) and the limits. IGain < 0 sets IGainInv and the
    block does not integrate. Initialize (and the first execution after prescan):
    Out = InitialValue, limited."""
    b = _INTG
    dt = delta_t(ctx, s, b)
    clear_flags(s, b, "IGAININV")
    if dt is not None:
        gain = float(s[b["IGAIN"]])
        s[b["IGAININV"]] = int(gain < 0.0)
        previous = float(s[b["OUT"]])
        if s[b["INITIALIZE"]] or not s[b["PRIMED"]]:
            value = previous = float(s[b["INITIALVALUE"]])
            s[b["PRIMED"]] = 1
        elif gain < 0.0:
            value = previous
        else:
            value = previous + gain * float(s[b["IN"]]) * dt
        set_out(s, b, _limits(s, b, value, previous))
    finish(s, b)


@prescan("INTG")
def intg_prescan(ctx: ExecContext, rung: bool, s: list) -> None:
    reset_block(s, _INTG)


# ------------------------------------------------------------------ DERV
_DERV = block("DERIVATIVE")


@implements("DERV")
def derv(ctx: ExecContext, rung: bool, s: list) -> None:
    """Out = Gain x (In_n - In_(n-1)) / DeltaT; ByPass: Out = In. The first execution after
    prescan only records In (Out = 0); DeltaT 0 leaves Out and the recorded In."""
    b = _DERV
    dt = delta_t(ctx, s, b)
    if dt is not None:
        x = float(s[b["IN"]])
        if s[b["BYPASS"]]:
            set_out(s, b, x)
        elif not s[b["PRIMED"]]:
            set_out(s, b, 0.0)
        elif dt > 0.0:
            set_out(s, b, s[b["GAIN"]] * (x - s[b["PREVIN"]]) / dt)
        if dt > 0.0 or not s[b["PRIMED"]]:
            s[b["PREVIN"]], s[b["PRIMED"]] = x, 1
    finish(s, b)


@prescan("DERV")
def derv_prescan(ctx: ExecContext, rung: bool, s: list) -> None:
    reset_block(s, _DERV)


# ------------------------------------------------------------------ RLIM
_RLIM = block("RATE_LIMITER")


@implements("RLIM")
def rlim(ctx: ExecContext, rung: bool, s: list) -> None:
    """Out follows In, rising at most IncRate x DeltaT and falling at most DecRate x DeltaT
    per execution; ByPass (and the first execution after prescan): Out = In. A negative rate
    sets IncRateInv / DecRateInv and Out is not updated."""
    b = _RLIM
    dt = delta_t(ctx, s, b)
    clear_flags(s, b, "INCRATEINV", "DECRATEINV")
    if dt is not None:
        x, inc, dec = float(s[b["IN"]]), float(s[b["INCRATE"]]), float(s[b["DECRATE"]])
        s[b["INCRATEINV"]], s[b["DECRATEINV"]] = int(inc < 0.0), int(dec < 0.0)
        out = float(s[b["OUT"]])
        if s[b["BYPASS"]] or not s[b["PRIMED"]]:
            set_out(s, b, x)
            s[b["PRIMED"]] = 1
        elif inc >= 0.0 and dec >= 0.0:
            set_out(s, b, min(max(x, out - dec * dt), out + inc * dt))
    finish(s, b)


@prescan("RLIM")
def rlim_prescan(ctx: ExecContext, rung: bool, s: list) -> None:
    reset_block(s, _RLIM)
