"""Process control blocks of 1756-RM006 that logixst simulates: TOT (totalizer), ALM
(analog alarm), FGEN (function generator) and ESEL (enhanced select). Decisions where the
reference is silent: docs/decisions/0177 (TOT), 0178 (ALM), 0180 (FGEN), 0181 (ESEL).

Conventions (as select_limit_blocks.py, decision 0063): in Structured Text the block always
executes (EnableIn is not read) and sets EnableOut; REAL outputs are rounded to single
precision; the Status word is packed from its BOOL members (motion_layout.pack) after they
are set; InstructFault summarises the "...Inv" bits of the block.

TOT (totalizer), one execution:
- DeltaT comes from the timing mode (block_timing.py, decision 0139). TimeBase 0..3 says
  whether In is a rate per second, minute, hour or day (1, 60, 3600, 86400 s); another value
  sets TimeBaseInv and nothing is integrated.
- Program/operator control: ProgOperReq or OperOperReq put the block in operator control
  (ProgOper false) and keep it there; otherwise ProgProgReq or OperProgReq put it in program
  control.
- Run/stop: in program control ProgStopReq stops and otherwise ProgStartReq starts; in
  operator control OperStopReq / OperStartReq do the same (a stop request wins).
- Reset: a rising ProgResetReq in program control, or OperResetReq in operator control,
  copies Total into OldTotal and loads ResetValue; the program reset also sets
  ProgResetDone, which clears once ProgResetReq is false again.
- Integration (trapezoidal rule, in double precision as the reference says): while running,
  with In above LowInCutoff (LowInCutoffFlag is In <= LowInCutoff) and InFault clear,
  Total += Gain x DeltaT / TimeBase seconds x (In + In of the previous execution) / 2.
  The first execution in run after a stop (or after prescan) only records In.
- TargetFlag: Total >= Target; TargetDev1Flag / TargetDev2Flag: Total >= Target -
  TargetDev1 / TargetDev2 (the pre-targets).
- At the end of every execution the operator requests are cleared; with ProgValueReset the
  program requests are cleared too.
"""

from __future__ import annotations

import math

from ..runtime.motion_layout import pack, packed_words, struct_type
from ..vm.context import ExecContext
from ..vm.refs import ArrayRef
from ..vm.values import f32
from . import block_timing
from .registry import implements, prescan


def pack_status(s: list, words: tuple[tuple[int, tuple[tuple[int, int], ...]], ...]) -> None:
    for word, bits in words:
        pack(s, word, bits)


# ------------------------------------------------------------------ TOT
_T = struct_type("TOTALIZER").index
_T_TIMING = block_timing.timing_layout("TOTALIZER")
_T_WORDS = packed_words("TOTALIZER")
TIME_BASE_SECONDS = (1.0, 60.0, 3600.0, 86400.0)  # TimeBase 0 s, 1 min, 2 h, 3 days
_T_OPER_REQS = tuple(
    _T[m] for m in ("OPERPROGREQ", "OPEROPERREQ", "OPERSTARTREQ", "OPERSTOPREQ", "OPERRESETREQ")
)
_T_PROG_REQS = tuple(
    _T[m] for m in ("PROGPROGREQ", "PROGOPERREQ", "PROGSTARTREQ", "PROGSTOPREQ", "PROGRESETREQ")
)
_T_INVS = tuple(
    _T[m]
    for m in (
        "TIMEBASEINV",
        "TIMINGMODEINV",
        "RTSTIMEINV",
        "RTSTIMESTAMPINV",
        "DELTATINV",
    )
)


def _tot_reset(s: list) -> None:
    s[_T["OLDTOTAL"]] = s[_T["TOTAL"]]
    s[_T["TOTALACC"]] = float(s[_T["RESETVALUE"]])
    s[_T["TOTAL"]] = f32(s[_T["RESETVALUE"]])


@implements("TOT")
def tot(ctx: ExecContext, rung: bool, s: list) -> None:
    dt = block_timing.sample(ctx, s, _T_TIMING)
    time_base = s[_T["TIMEBASE"]]
    s[_T["TIMEBASEINV"]] = int(not 0 <= time_base <= 3)
    s[_T["INFAULTED"]] = int(bool(s[_T["INFAULT"]]))
    # A program (or the operator) writing Total directly moves the running total with it.
    if f32(s[_T["TOTALACC"]]) != s[_T["TOTAL"]]:
        s[_T["TOTALACC"]] = float(s[_T["TOTAL"]])

    # program / operator control
    if s[_T["PROGOPERREQ"]] or s[_T["OPEROPERREQ"]]:
        s[_T["PROGOPER"]] = 0
    elif s[_T["PROGPROGREQ"]] or s[_T["OPERPROGREQ"]]:
        s[_T["PROGOPER"]] = 1
    prog = bool(s[_T["PROGOPER"]])

    # run / stop: the requests of the controlling side, stop first
    start, stop = ("PROGSTARTREQ", "PROGSTOPREQ") if prog else ("OPERSTARTREQ", "OPERSTOPREQ")
    if s[_T[stop]]:
        s[_T["RUNSTOP"]] = 0
    elif s[_T[start]]:
        s[_T["RUNSTOP"]] = 1

    # reset
    prog_reset = bool(s[_T["PROGRESETREQ"]])
    if prog and prog_reset and not s[_T["PROGRESETREQPREV"]]:
        _tot_reset(s)
        s[_T["PROGRESETDONE"]] = 1
    elif not prog_reset:
        s[_T["PROGRESETDONE"]] = 0
    s[_T["PROGRESETREQPREV"]] = int(prog_reset)
    if not prog and s[_T["OPERRESETREQ"]]:
        _tot_reset(s)

    # totalization
    x = s[_T["IN"]]
    s[_T["LOWINCUTOFFFLAG"]] = cutoff = int(x <= s[_T["LOWINCUTOFF"]])
    running = bool(s[_T["RUNSTOP"]])
    if dt is not None and not s[_T["TIMEBASEINV"]]:
        if running and s[_T["WASRUNNING"]] and not cutoff and not s[_T["INFAULT"]]:
            rate = (x + s[_T["INPREV"]]) / 2.0
            acc = s[_T["TOTALACC"]] + s[_T["GAIN"]] * dt / TIME_BASE_SECONDS[time_base] * rate
            s[_T["TOTALACC"]] = acc
            s[_T["TOTAL"]] = f32(acc)
        s[_T["INPREV"]] = x
        s[_T["WASRUNNING"]] = int(running)

    total, target = s[_T["TOTAL"]], s[_T["TARGET"]]
    s[_T["TARGETFLAG"]] = int(total >= target)
    s[_T["TARGETDEV1FLAG"]] = int(total >= target - s[_T["TARGETDEV1"]])
    s[_T["TARGETDEV2FLAG"]] = int(total >= target - s[_T["TARGETDEV2"]])

    s[_T["INSTRUCTFAULT"]] = int(any(s[i] for i in _T_INVS))
    pack_status(s, _T_WORDS)
    for i in _T_OPER_REQS:
        s[i] = 0
    if s[_T["PROGVALUERESET"]]:
        for i in _T_PROG_REQS:
            s[i] = 0
    s[_T["ENABLEOUT"]] = 1


@prescan("TOT")
def tot_prescan(ctx: ExecContext, rung: bool, s: list) -> None:
    # Instruction first scan: a new DeltaT series, and the first execution in run only
    # records In (no trapezoid with an In from before the restart).
    block_timing.restart(s, _T_TIMING)
    s[_T["WASRUNNING"]] = 0


# ------------------------------------------------------------------ ALM
_A = struct_type("ALARM").index
_A_WORDS = packed_words("ALARM")
ROC_PERIOD_MAX = 32767.0  # seconds: the longest rate-of-change period the block accepts


def _level(s: list, alarm: int, on: bool, clear: bool) -> None:
    """A latching level alarm: set when `on`, cleared only when `clear` (limit +/- deadband)."""
    if on:
        s[alarm] = 1
    elif clear:
        s[alarm] = 0


@implements("ALM")
def alm(ctx: ExecContext, rung: bool, s: list) -> None:
    """Level alarms with a deadband for clearing, and rate-of-change alarms over ROCPeriod.

    Invalid settings set their bit and the block uses 0 instead (the reference's rule):
    Deadband < 0, ROCPosLimit < 0, ROCNegLimit < 0, ROCPeriod outside 0..32767 s. A limit
    or period of 0 turns the rate-of-change alarm off. Decision 0178."""
    x = s[_A["IN"]]
    db, pos, neg, period = (
        s[_A["DEADBAND"]],
        s[_A["ROCPOSLIMIT"]],
        s[_A["ROCNEGLIMIT"]],
        s[_A["ROCPERIOD"]],
    )
    s[_A["DEADBANDINV"]] = int(db < 0)
    s[_A["ROCPOSLIMITINV"]] = int(pos < 0)
    s[_A["ROCNEGLIMITINV"]] = int(neg < 0)
    s[_A["ROCPERIODINV"]] = int(not 0.0 <= period <= ROC_PERIOD_MAX)
    db = max(db, 0.0)
    pos, neg = max(pos, 0.0), max(neg, 0.0)
    if s[_A["ROCPERIODINV"]]:
        period = 0.0

    hh, h, lo, ll = s[_A["HHLIMIT"]], s[_A["HLIMIT"]], s[_A["LLIMIT"]], s[_A["LLLIMIT"]]
    _level(s, _A["HHALARM"], x >= hh, x < hh - db)
    _level(s, _A["HALARM"], x >= h, x < h - db)
    _level(s, _A["LALARM"], x <= lo, x > lo + db)
    _level(s, _A["LLALARM"], x <= ll, x > ll + db)

    # Rate of change: a sample of In is stored each time ROCPeriod has elapsed (checked at
    # the next execution after it), and ROC = (this sample - the previous) / ROCPeriod.
    if period > 0.0:
        since = s[_A["ROCSAMPLETIME"]]
        if since < 0:
            s[_A["ROCSAMPLEIN"]], s[_A["ROCSAMPLETIME"]] = x, ctx.now_ms
        elif ctx.now_ms - since >= period * 1000.0:
            s[_A["ROC"]] = f32((x - s[_A["ROCSAMPLEIN"]]) / period)
            s[_A["ROCSAMPLEIN"]], s[_A["ROCSAMPLETIME"]] = x, ctx.now_ms
    else:
        s[_A["ROC"]] = 0.0
        s[_A["ROCSAMPLETIME"]] = -1.0
    roc = s[_A["ROC"]]
    s[_A["ROCPOSALARM"]] = int(period > 0.0 and pos > 0.0 and roc >= pos)
    s[_A["ROCNEGALARM"]] = int(period > 0.0 and neg > 0.0 and roc <= -neg)

    s[_A["INSTRUCTFAULT"]] = int(
        any(s[_A[b]] for b in ("DEADBANDINV", "ROCPOSLIMITINV", "ROCNEGLIMITINV", "ROCPERIODINV"))
    )
    pack_status(s, _A_WORDS)
    s[_A["ENABLEOUT"]] = int(not math.isinf(roc))


@prescan("ALM")
def alm_prescan(ctx: ExecContext, rung: bool, s: list) -> None:
    # Instruction first scan: the rate-of-change period starts again with the next sample.
    s[_A["ROCSAMPLETIME"]] = -1.0


# ------------------------------------------------------------------ FGEN
_F = struct_type("FUNCTION_GENERATOR").index
_F_WORDS = packed_words("FUNCTION_GENERATOR")


def interpolate(x: float, xs: list[float], ys: list[float]) -> float:
    """Piecewise-linear through (xs, ys), xs strictly ascending; held flat beyond the ends."""
    if x <= xs[0]:
        return ys[0]
    if x >= xs[-1]:
        return ys[-1]
    hi = next(i for i in range(1, len(xs)) if x < xs[i])
    x0, x1, y0, y1 = xs[hi - 1], xs[hi], ys[hi - 1], ys[hi]
    return y0 + (x - x0) * (y1 - y0) / (x1 - x0)


@implements("FGEN")
def fgen(
    ctx: ExecContext, rung: bool, s: list, x1: ArrayRef, y1: ArrayRef, x2: ArrayRef, y2: ArrayRef
) -> None:
    """Out = f(In) through the first (Select false) or second table of XY<n>Size points.
    XY1Size must be 1..the arrays' length, XY2Size 0..theirs (0: no second table) and at
    least 1 when selected; the X points of the table in use must ascend strictly
    (XisOutofOrder otherwise). Any of these holds Out. Decision 0180."""
    n1, n2, second = s[_F["XY1SIZE"]], s[_F["XY2SIZE"]], bool(s[_F["SELECT"]])
    s[_F["XY1SIZEINV"]] = int(not 1 <= n1 <= min(len(x1), len(y1)))
    s[_F["XY2SIZEINV"]] = int(not (1 if second else 0) <= n2 <= min(len(x2), len(y2)))
    s[_F["XISOUTOFORDER"]] = 0
    xs_ref, ys_ref, n, bad = (x2, y2, n2, "XY2SIZEINV") if second else (x1, y1, n1, "XY1SIZEINV")
    if not s[_F[bad]]:
        xs = [float(xs_ref.get(i)) for i in range(n)]  # type: ignore[arg-type]
        ys = [float(ys_ref.get(i)) for i in range(n)]  # type: ignore[arg-type]
        if all(a < b for a, b in zip(xs, xs[1:], strict=False)):
            out = f32(interpolate(s[_F["IN"]], xs, ys))
            s[_F["OUT"]] = out
        else:
            s[_F["XISOUTOFORDER"]] = 1
    s[_F["INSTRUCTFAULT"]] = int(
        bool(s[_F["XY1SIZEINV"]] or s[_F["XY2SIZEINV"]] or s[_F["XISOUTOFORDER"]])
    )
    pack_status(s, _F_WORDS)
    s[_F["ENABLEOUT"]] = int(not math.isinf(s[_F["OUT"]]))


# ------------------------------------------------------------------ ESEL
_E = struct_type("SELECT_ENHANCED").index
_E_WORDS = packed_words("SELECT_ENHANCED")
_E_INS = tuple((_E[f"IN{i}"], _E[f"IN{i}FAULT"]) for i in range(1, 7))
MANUAL, HIGH, LOW, MEDIAN, AVERAGE = 0, 1, 2, 3, 4  # SelectorMode
_E_OPER_REQS = (_E["OPERPROGREQ"], _E["OPEROPERREQ"])
_E_PROG_REQS = (_E["PROGPROGREQ"], _E["PROGOPERREQ"], _E["PROGOVERRIDEREQ"])


def _esel_pick(s: list, mode: int, selector: int, used: int) -> tuple[float | None, int, bool]:
    """(Out or None to hold it, SelectedIn, InsFaulted) for one execution."""
    if mode == MANUAL:
        if selector == 0:
            return None, 0, False  # no input selected: Out holds
        value, fault = _E_INS[selector - 1]
        return s[value], selector, bool(s[fault])
    healthy = [(s[v], n) for n, (v, f) in enumerate(_E_INS[:used], start=1) if not s[f]]
    if not healthy:
        return None, 0, True  # every used input faulted: Out holds
    if mode == HIGH:  # ties go to the lowest-numbered input
        value, n = max(healthy, key=lambda p: (p[0], -p[1]))
        return value, n, False
    if mode == LOW:
        value, n = min(healthy, key=lambda p: (p[0], p[1]))
        return value, n, False
    if mode == MEDIAN:
        ranked = sorted(healthy, key=lambda p: (p[0], p[1]))
        mid = len(ranked) // 2
        if len(ranked) % 2:
            return ranked[mid][0], ranked[mid][1], False
        return (ranked[mid - 1][0] + ranked[mid][0]) / 2.0, 0, False
    return math.fsum(v for v, _ in healthy) / len(healthy), 0, False  # AVERAGE


@implements("ESEL")
def esel(ctx: ExecContext, rung: bool, s: list) -> None:
    """Select Out from In1..In<InsUsed> by SelectorMode: 0 manual (ProgSelector in program
    control, OperSelector in operator control; 0 selects nothing), 1 highest, 2 lowest,
    3 median (even count: mean of the middle two), 4 average of the inputs not faulted.
    ProgOverrideReq forces manual selection by ProgSelector (Override). Program/operator
    requests as TOT. Invalid InsUsed (1..6), SelectorMode (0..4) or the selector in use
    (0..6) hold Out. Decision 0181."""
    if s[_E["PROGOPERREQ"]] or s[_E["OPEROPERREQ"]]:
        s[_E["PROGOPER"]] = 0
    elif s[_E["PROGPROGREQ"]] or s[_E["OPERPROGREQ"]]:
        s[_E["PROGOPER"]] = 1
    s[_E["OVERRIDE"]] = override = int(bool(s[_E["PROGOVERRIDEREQ"]]))

    used, mode = s[_E["INSUSED"]], s[_E["SELECTORMODE"]]
    prog_sel, oper_sel = s[_E["PROGSELECTOR"]], s[_E["OPERSELECTOR"]]
    s[_E["INSUSEDINV"]] = int(not 1 <= used <= 6)
    s[_E["SELECTORMODEINV"]] = int(not MANUAL <= mode <= AVERAGE)
    s[_E["PROGSELECTORINV"]] = int(not 0 <= prog_sel <= 6)
    s[_E["OPERSELECTORINV"]] = int(not 0 <= oper_sel <= 6)
    if override:
        mode, selector, sel_inv = MANUAL, prog_sel, "PROGSELECTORINV"
    elif s[_E["PROGOPER"]]:
        selector, sel_inv = prog_sel, "PROGSELECTORINV"
    else:
        selector, sel_inv = oper_sel, "OPERSELECTORINV"
    blocked = s[_E["INSUSEDINV"]] or (not override and s[_E["SELECTORMODEINV"]])
    if mode == MANUAL and s[_E[sel_inv]]:
        blocked = 1
    if not blocked:
        out, selected, faulted = _esel_pick(s, mode, selector, used)
        s[_E["SELECTEDIN"]] = selected
        s[_E["INSFAULTED"]] = int(faulted)
        if out is not None:
            s[_E["OUT"]] = f32(out)

    s[_E["INSTRUCTFAULT"]] = int(
        any(
            s[_E[b]]
            for b in ("INSUSEDINV", "SELECTORMODEINV", "PROGSELECTORINV", "OPERSELECTORINV")
        )
    )
    pack_status(s, _E_WORDS)
    for i in _E_OPER_REQS:
        s[i] = 0
    if s[_E["PROGVALUERESET"]]:
        for i in _E_PROG_REQS:
            s[i] = 0
    s[_E["ENABLEOUT"]] = int(not math.isinf(s[_E["OUT"]]))
