"""Time-based filter blocks: LPF, HPF, NTCH, LDL2 (filters), LDLG, DEDT (process), decisions
0170-0171 (LDLG is bilinear, as a real controller shows; see its docstring).

Sources: 1756-RM006 (filter and process chapters) and the Studio 5000 v37 help of each block.
- Structured Text calls the block on its tag; EnableIn is not read (decision 0063), the
  block executes at every call. DeltaT comes from block_timing.py (decision 0139); when it
  answers None (an invalid timing input, or no new real-time sample) the block leaves Out
  alone.
- Each linear filter is its Laplace transfer function H(s) discretised exactly for an input
  that is constant over the interval that ends at this execution (zero-order hold on the
  new sample): x_n = Ad x_(n-1) + Bd In_n, Out_n = C x_n + D In_n, with Ad = e^(A DeltaT)
  and Bd = integral of e^(A t) B over DeltaT (A, B, C, D the controllable canonical form of
  H). For a first-order lag this is Out_n = Out_(n-1) + (In_n - Out_(n-1)) (1 - e^(-w DeltaT)),
  and every output sample equals the continuous response at the same instant. DeltaT 0
  (no time elapsed) leaves the state where it is.
- Initialisation (the Initialize input, and the first execution after prescan = the
  reference's "instruction first scan") puts the filter in its steady state for the present
  input: Out = H(0) x In (LPF, NTCH, LDL2: Out = In; HPF: Out = 0).
- A frequency outside its limits sets its Status bit and is clamped (the block still runs);
  an invalid Order sets OrderInv and the block uses its lowest order. InstructFault is set
  with any "...Inv" bit. A computed Out that is not finite is written as is and EnableOut
  cleared; the next finite execution re-initialises (Out = H(0) x In).
Hidden members State1..n keep the filter state (scaled so that a filter at rest stays at
rest when its parameters change), Primed whether it was initialised since the last prescan.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cache, lru_cache

import numpy as np

from ..runtime.motion_layout import pack, packed_words, struct_type
from ..vm.context import ExecContext
from ..vm.refs import ArrayRef
from ..vm.values import f32
from .block_timing import TimingLayout, restart, sample, timing_layout
from .registry import implements, prescan

SQRT2 = math.sqrt(2.0)


# ------------------------------------------------------------------ common block plumbing
@dataclass(frozen=True, slots=True)
class Block:
    """Member positions shared by the time-based blocks of one type."""

    type_name: str
    ix: dict[str, int]
    timing: TimingLayout | None
    words: tuple[tuple[int, tuple[tuple[int, int], ...]], ...]
    fault: int
    invalid: tuple[int, ...]  # every "...Inv" flag of the type (InstructFault summarises them)

    def __getitem__(self, name: str) -> int:
        return self.ix[name.upper()]


@cache
def block(type_name: str) -> Block:
    ix = struct_type(type_name).index
    words = packed_words(type_name)
    flags = [i for _, bits in words for i, _ in bits]
    inv = tuple(i for i in flags if _name_of(ix, i).endswith("INV"))
    timing = timing_layout(type_name) if "TIMINGMODE" in ix else None
    return Block(type_name, ix, timing, words, ix["INSTRUCTFAULT"], inv)


def delta_t(ctx: ExecContext, s: list, b: Block) -> float | None:
    """This execution's DeltaT (block_timing.sample), None = do not compute now."""
    assert b.timing is not None, b.type_name
    return sample(ctx, s, b.timing)


def _name_of(ix: dict[str, int], i: int) -> str:
    return next(k for k, v in ix.items() if v == i)


def clear_flags(s: list, b: Block, *names: str) -> None:
    for n in names:
        s[b[n]] = 0


def finish(s: list, b: Block) -> None:
    """InstructFault = any invalid-parameter bit; pack the Status word(s)."""
    s[b.fault] = int(any(s[i] for i in b.invalid))
    for word, bits in b.words:
        pack(s, word, bits)


def set_out(s: list, b: Block, value: float) -> bool:
    """Store Out rounded to REAL; EnableOut drops when it is not finite. True when finite."""
    v = f32(value)
    s[b["OUT"]] = v
    ok = math.isfinite(v)
    s[b["ENABLEOUT"]] = int(ok)
    return ok


def limit(value: float, lo: float, hi: float) -> tuple[float, bool]:
    """(value clamped to lo..hi, whether it had to be clamped)."""
    if value < lo:
        return lo, True
    if value > hi:
        return hi, True
    return value, False


def reset_block(s: list, b: Block) -> None:
    """Prescan: forget the timing series and the filter state ("instruction first scan")."""
    if b.timing is not None:
        restart(s, b.timing)
    s[b["PRIMED"]] = 0
    s[b["ENABLEOUT"]] = 0


# ------------------------------------------------------------------ exact discretisation
def _expm(m: np.ndarray) -> np.ndarray:
    """Matrix exponential by scaling and squaring of a Taylor series (small matrices)."""
    norm = float(np.abs(m).sum(axis=1).max())
    k = max(0, math.ceil(math.log2(norm)) + 1) if norm > 0.5 else 0
    a = m / float(2**k)
    term = np.eye(len(m))
    total = term.copy()
    for i in range(1, 24):
        term = term @ a / i
        total = total + term
    for _ in range(k):
        total = total @ total
    return total


@lru_cache(maxsize=512)
def discretise(
    num: tuple[float, ...], den: tuple[float, ...], dt: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
    """(Ad, Bd, C, D) of H(s) = num/den (highest power first, den monic, len(num) ==
    len(den)) held constant over dt: controllable canonical form, then e^([[A B],[0 0]] dt)."""
    n = len(den) - 1
    a = np.zeros((n, n))
    a[0, :] = [-c for c in den[1:]]
    for i in range(1, n):
        a[i, i - 1] = 1.0
    d = num[0]
    c = np.array([num[i] - d * den[i] for i in range(1, n + 1)])
    m = np.zeros((n + 1, n + 1))
    m[:n, :n] = a * dt
    m[0, n] = dt
    e = _expm(m)
    return e[:n, :n], e[:n, n], c, d


def run_filter(
    s: list, b: Block, num: tuple[float, ...], den: tuple[float, ...], dt: float, u: float,
    init: bool,
) -> float:  # fmt: skip
    """Advance the filter held in State1..n by dt with input u; returns the output.

    The members hold the canonical-form state times den[-1] (the last one is then In at
    rest, whatever the coefficients): a filter at rest stays at rest when its frequency
    or damping is changed online, and for a low-pass the members are Out and its
    derivatives."""
    n = len(den) - 1
    states = [b[f"STATE{i}"] for i in range(1, n + 1)]
    scale = den[-1]
    if init or not s[b["PRIMED"]]:
        s[b["PRIMED"]] = 1
        for i in states:
            s[i] = 0.0
        s[states[-1]] = u
        return num[-1] / den[-1] * u  # H(0) x In, exactly
    x = np.array([float(s[i]) for i in states]) / scale
    if dt > 0.0:
        ad, bd, _, _ = discretise(num, den, dt)
        x = ad @ x + bd * u
        for i, v in zip(states, x, strict=True):
            s[i] = float(v) * scale
    _, _, c, d = discretise(num, den, 0.0)
    return float(c @ x) + d * u


def store_filtered(s: list, b: Block, y: float) -> None:
    """Write Out; a non-finite result un-primes the block so the next finite one restarts."""
    if not set_out(s, b, y):
        s[b["PRIMED"]] = 0


# ------------------------------------------------------------------ LPF / HPF
# Butterworth denominators for w = 1 (decision 0170): order 1, 2, 3.
_BUTTER = {1: (1.0, 1.0), 2: (1.0, SQRT2, 1.0), 3: (1.0, 2.0, 2.0, 1.0)}
# Lowest valid frequency x DeltaT per order, highest valid frequency x DeltaT (decision 0170).
_LOW_W_DT = {1: 0.0000001, 2: 0.00005, 3: 0.00017}
HIGH_W_DT = 0.36


def _butter_den(order: int, w: float) -> tuple[float, ...]:
    return tuple(c * w**k for k, c in enumerate(_BUTTER[order]))


def frequency_limits(w: float, dt: float, low_w_dt: float) -> tuple[float, bool]:
    """Clamp a frequency (rad/s) to low_w_dt/DeltaT .. 0.36/DeltaT; with DeltaT 0 only a
    frequency <= 0 is invalid (no limit can be computed) and it is left as is."""
    if dt <= 0.0:
        return w, not w > 0.0
    return limit(w, low_w_dt / dt, HIGH_W_DT / dt)


def _order(s: list, b: Block, valid: tuple[int, ...]) -> int:
    """The Order to filter with (OrderInv and the lowest order when invalid). A change of
    order changes the state's meaning: the filter re-initialises on the present In."""
    order = s[b["ORDER"]]
    s[b["ORDERINV"]] = int(order not in valid)
    order = order if order in valid else valid[0]
    if s[b["LASTORDER"]] != order:
        s[b["LASTORDER"]], s[b["PRIMED"]] = order, 0
    return order


def _pass_filter(ctx: ExecContext, s: list, b: Block, w_name: str, high_pass: bool) -> None:
    dt = delta_t(ctx, s, b)
    clear_flags(s, b, f"{w_name}INV", "ORDERINV")
    if dt is not None:
        order = _order(s, b, (1, 2, 3))
        w, s[b[f"{w_name}INV"]] = frequency_limits(s[b[w_name]], dt, _LOW_W_DT[order])
        if w > 0.0:
            den = _butter_den(order, w)
            num = (1.0,) + (0.0,) * order if high_pass else (0.0,) * order + (den[-1],)
            u = float(s[b["IN"]])
            store_filtered(s, b, run_filter(s, b, num, den, dt, u, bool(s[b["INITIALIZE"]])))
    finish(s, b)


_LPF = block("FILTER_LOW_PASS")
_HPF = block("FILTER_HIGH_PASS")


@implements("LPF")
def lpf(ctx: ExecContext, rung: bool, s: list) -> None:
    """Low-pass Butterworth filter of Order 1..3 with cut-off WLag (rad/s)."""
    _pass_filter(ctx, s, _LPF, "WLAG", high_pass=False)


@implements("HPF")
def hpf(ctx: ExecContext, rung: bool, s: list) -> None:
    """High-pass Butterworth filter of Order 1..3 with cut-off WLead (rad/s)."""
    _pass_filter(ctx, s, _HPF, "WLEAD", high_pass=True)


@prescan("LPF")
def lpf_prescan(ctx: ExecContext, rung: bool, s: list) -> None:
    reset_block(s, _LPF)


@prescan("HPF")
def hpf_prescan(ctx: ExecContext, rung: bool, s: list) -> None:
    reset_block(s, _HPF)


# ------------------------------------------------------------------ LDLG
_LDLG = block("LEAD_LAG")


@implements("LDLG")
def ldlg(ctx: ExecContext, rung: bool, s: list) -> None:
    """Out = Gain x (1 + Lead s)/(1 + Lag s) x In + Bias, Lead and Lag in seconds,
    discretised with the bilinear (Tustin) transform as the controller does (decision 0171):
    y_n = ((DeltaT + 2 Lead) In_n + (DeltaT - 2 Lead) In_(n-1) - (DeltaT - 2 Lag) y_(n-1))
    / (DeltaT + 2 Lag). A negative Lead sets LeadInv and counts as 0; a Lag below DeltaT/2
    sets LagInv and counts as DeltaT/2. Initialize: steady state on InitialValue,
    Out = Gain x InitialValue + Bias; the first execution after prescan: steady on In."""
    b = _LDLG
    dt = delta_t(ctx, s, b)
    clear_flags(s, b, "LEADINV", "LAGINV")
    if dt is not None:
        lead, lag = float(s[b["LEAD"]]), float(s[b["LAG"]])
        s[b["LEADINV"]] = int(lead < 0.0)
        lead = max(lead, 0.0)
        if dt > 0.0:
            s[b["LAGINV"]] = int(lag < dt / 2.0)
            lag = max(lag, dt / 2.0)
        else:
            s[b["LAGINV"]] = int(lag < 0.0)
        init = bool(s[b["INITIALIZE"]])
        u = float(s[b["INITIALVALUE"]] if init else s[b["IN"]])
        if init or not s[b["PRIMED"]]:
            y = u  # steady state: DC gain 1
            s[b["PRIMED"]], s[b["PREVIN"]], s[b["PREVOUT"]] = 1, u, y
        elif dt > 0.0:
            y = (
                (dt + 2.0 * lead) * u
                + (dt - 2.0 * lead) * s[b["PREVIN"]]
                - (dt - 2.0 * lag) * s[b["PREVOUT"]]
            ) / (dt + 2.0 * lag)
            s[b["PREVIN"]], s[b["PREVOUT"]] = u, y
        else:
            y = float(s[b["PREVOUT"]])  # no time has passed
        store_filtered(s, b, s[b["GAIN"]] * y + s[b["BIAS"]])
    finish(s, b)


@prescan("LDLG")
def ldlg_prescan(ctx: ExecContext, rung: bool, s: list) -> None:
    reset_block(s, _LDLG)


# ------------------------------------------------------------------ DEDT
_DEDT = block("DEADTIME")


@implements("DEDT")
def dedt(ctx: ExecContext, rung: bool, s: list, storage: ArrayRef) -> None:
    """Out = Gain x In(Deadtime ago) + Bias (decision 0171). The storage array is a ring of
    past inputs: the delay in executions is N = Deadtime / DeltaT rounded to the nearest
    whole number; each execution reads the element written N executions ago, then writes In.
    Deadtime below 0 or above (array size x DeltaT) sets DeadtimeInv and is clamped. The first
    execution after prescan fills the array with In (the process was at rest). While
    InFault is set: InFaulted, Out held, nothing stored; when it clears the block
    re-initialises on In."""
    b = _DEDT
    dt = delta_t(ctx, s, b)
    clear_flags(s, b, "DEADTIMEINV")
    if dt is not None:
        x, size = float(s[b["IN"]]), len(storage)
        s[b["INFAULTED"]] = int(bool(s[b["INFAULT"]]))
        if s[b["INFAULTED"]]:
            s[b["PRIMED"]] = 0
        elif not s[b["PRIMED"]] or size == 0:
            for i in range(size):
                storage.set(i, x)
            s[b["INDEX"]], s[b["PRIMED"]] = 0, 1
            set_out(s, b, s[b["GAIN"]] * x + s[b["BIAS"]])
        elif dt > 0.0:
            deadtime = float(s[b["DEADTIME"]])
            deadtime, s[b["DEADTIMEINV"]] = limit(deadtime, 0.0, size * dt)
            steps = min(size, round(deadtime / dt))
            i = s[b["INDEX"]] % size
            delayed = float(storage.get((i - steps) % size)) if steps else x  # type: ignore[arg-type]
            storage.set(i, x)
            s[b["INDEX"]] = (i + 1) % size
            set_out(s, b, s[b["GAIN"]] * delayed + s[b["BIAS"]])
    finish(s, b)


@prescan("DEDT")
def dedt_prescan(ctx: ExecContext, rung: bool, s: list, storage: ArrayRef) -> None:
    reset_block(s, _DEDT)


# ------------------------------------------------------------------ LDL2
_LDL2 = block("LEAD_LAG_SEC_ORDER")
_LDL2_MAX_RATIO = {1: 40.0, 2: 10.0}  # largest WLag:WLead the block accepts, per order
_LDL2_LOW_W_DT = {1: _LOW_W_DT[1], 2: _LOW_W_DT[2]}


@implements("LDL2")
def ldl2(ctx: ExecContext, rung: bool, s: list) -> None:
    """Order 1: (s/WLead + 1)/(s/WLag + 1). Order 2: (s^2/WLead^2 + 2 ZetaLead s/WLead + 1)/
    (s^2/WLag^2 + 2 ZetaLag s/WLag + 1). Frequencies limited as LPF's (decision 0170); then
    WLag above 40 x WLead (order 1) or 10 x WLead (order 2) sets WLagRatioInv and WLag is
    limited to that ratio. Order 2 only: ZetaLead 0..4, ZetaLag 0.05..4, else clamped with
    their Status bit. Order outside 1..2: OrderInv, order 1. DC gain 1: Initialize gives
    Out = In."""
    b = _LDL2
    dt = delta_t(ctx, s, b)
    clear_flags(s, b, "WLEADINV", "WLAGINV", "ZETALEADINV", "ZETALAGINV", "ORDERINV")
    clear_flags(s, b, "WLAGRATIOINV")
    if dt is not None:
        order = _order(s, b, (1, 2))
        low = _LDL2_LOW_W_DT[order]
        lead, s[b["WLEADINV"]] = frequency_limits(float(s[b["WLEAD"]]), dt, low)
        lag, s[b["WLAGINV"]] = frequency_limits(float(s[b["WLAG"]]), dt, low)
        if lead > 0.0 and lag > _LDL2_MAX_RATIO[order] * lead:
            lag, s[b["WLAGRATIOINV"]] = _LDL2_MAX_RATIO[order] * lead, 1
        if lead > 0.0 and lag > 0.0:
            if order == 1:
                num: tuple[float, ...] = (lag / lead, lag)
                den: tuple[float, ...] = (1.0, lag)
            else:
                z_lead, s[b["ZETALEADINV"]] = limit(float(s[b["ZETALEAD"]]), 0.0, 4.0)
                z_lag, s[b["ZETALAGINV"]] = limit(float(s[b["ZETALAG"]]), 0.05, 4.0)
                r = lag * lag / (lead * lead)
                num = (r, 2.0 * z_lead * lag * lag / lead, lag * lag)
                den = (1.0, 2.0 * z_lag * lag, lag * lag)
            u = float(s[b["IN"]])
            store_filtered(s, b, run_filter(s, b, num, den, dt, u, bool(s[b["INITIALIZE"]])))
    finish(s, b)


@prescan("LDL2")
def ldl2_prescan(ctx: ExecContext, rung: bool, s: list) -> None:
    reset_block(s, _LDL2)


# ------------------------------------------------------------------ NTCH
_NTCH = block("FILTER_NOTCH")
_NTCH_LOW_W_DT = {2: _LOW_W_DT[2], 4: _LOW_W_DT[3]}


@implements("NTCH")
def ntch(ctx: ExecContext, rung: bool, s: list) -> None:
    """Order 2: (s^2 + w^2)/(s^2 + (w/Q) s + w^2) with w = WNotch, Q = QFactor; order 4 is
    its square. WNotch limited as LPF's (decision 0170, order 4 with the order-3 low limit),
    QFactor 0.5..100; Order other than 2 or 4: OrderInv, order 2. Initialize: Out = In."""
    b = _NTCH
    dt = delta_t(ctx, s, b)
    clear_flags(s, b, "WNOTCHINV", "QFACTORINV", "ORDERINV")
    if dt is not None:
        order = _order(s, b, (2, 4))
        w, s[b["WNOTCHINV"]] = frequency_limits(float(s[b["WNOTCH"]]), dt, _NTCH_LOW_W_DT[order])
        q, s[b["QFACTORINV"]] = limit(float(s[b["QFACTOR"]]), 0.5, 100.0)
        if w > 0.0:
            num: tuple[float, ...] = (1.0, 0.0, w * w)
            den: tuple[float, ...] = (1.0, w / q, w * w)
            if order == 4:
                num, den = _square(num), _square(den)
            u = float(s[b["IN"]])
            store_filtered(s, b, run_filter(s, b, num, den, dt, u, bool(s[b["INITIALIZE"]])))
    finish(s, b)


def _square(p: tuple[float, ...]) -> tuple[float, ...]:
    return tuple(float(c) for c in np.convolve(p, p))


@prescan("NTCH")
def ntch_prescan(ctx: ExecContext, rung: bool, s: list) -> None:
    reset_block(s, _NTCH)
