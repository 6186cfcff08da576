"""SCL (Structured Text scaling block) and PID (ladder and Structured Text), decision 0031.

SCL (1756-RM006): Out = (In - InRawMin) x (InEUMax - InEUMin) / (InRawMax - InRawMin) + InEUMin.
MaxAlarm = In > InRawMax, MinAlarm = In < InRawMin; with Limiting an alarmed Out is held at
InEUMax / InEUMin. InRawMax <= InRawMin sets Status.InRawRangeInv and leaves Out alone. In ST the
block always executes (EnableIn is not read) and sets EnableOut.

PID (1756-RM003), one execution with dt = UPD seconds (the instruction trusts UPD; it must
match the rate the PID is executed at, as on the controller):
- PV is scaled from MINI..MAXI to MINS..MAXS when both ranges are set (else used as is);
  a cascade slave (CL set, CT clear) with a master loop takes SP from the master's OUT (%)
  mapped onto MINS..MAXS. SP outside MINS..MAXS sets SPOR (minor fault 4/36).
- ERR = SP - PV (CA clear) or PV - SP (CA set), in engineering units; the algorithm works in
  percent of the span (MAXS - MINS, else MAXI - MINI, else unscaled).
- Deadband DB (> 0): with NOZC set the error counts as 0 whenever |ERR| <= DB; otherwise
  only once the error has crossed zero (or reached it) inside the band (EWD).
- Independent gains (PE clear): P = KP E, I += KI E dt, D = KD d/dt. Dependent (PE set):
  P = KP E, I += KP / (60 KI) E dt (KI minutes per repeat, 0 = no integral),
  D = KP 60 KD d/dt (KD minutes). d/dt acts on the error (DOE set) or on the PV with the
  error's sign (DOE clear: a setpoint step gives no derivative kick); the first execution
  after prescan (INI clear) has no derivative. NDF averages the derivative with the
  previous one.
- Auto: OUT = P + I + D + BIAS. Software manual (SWM): OUT = SO. Station manual (MO):
  OUT = the tieback mapped from MINTIE..MAXTIE to percent. Inhold bit set: OUT = the inhold
  value mapped from MINCV..MAXCV (bumpless restart of an analog output). In a manual
  mode with NOBC clear the integral term is set so that auto resumes from OUT (bumpless),
  and with PVT set SP follows PV.
- OUT is limited to MINO..MAXO (OLL / OLH) in every mode; in auto the integral term stops
  growing in the direction of a limit (no windup).
- CV = OUT / 100 x (MAXCV - MINCV) + MINCV, converted to the CV's type.
- A range whose two ends are equal is not configured and is not applied: a PID tag Studio
  creates holds 0 in every member (real exports show it), so MINO = MAXO = 0 means no
  output limits, MINCV = MAXCV CV = OUT, MINTIE = MAXTIE a tieback already in percent.
- Alarms, always evaluated: PVHA above PVH until PV < PVH - PVDB, PVLA below PVL until
  PV > PVL + PVDB; DVPA when ERR > DVP until ERR < DVP - DVDB, DVNA when ERR < DVN (a
  negative number) until ERR > DVN + DVDB. Real exports of running loops show these rules
  (PVHA with PVH 0, DVPA/DVNA following ERR's sign under either control action).
- UPD <= 0: minor fault 4/35 and the loop is not computed.
- Ladder: a false rung clears EN and INI and computes nothing. Prescan clears EN and INI.
"""

from __future__ import annotations

import math

from ..vm.context import ExecContext
from ..vm.refs import BitRef, Ref
from ..vm.values import f32
from .fbd_timers import _layout
from .registry import implements, prescan

_S = _layout("SCALE")
S_IN, S_RMAX, S_RMIN = _S["IN"], _S["INRAWMAX"], _S["INRAWMIN"]
S_EMAX, S_EMIN, S_LIM = _S["INEUMAX"], _S["INEUMIN"], _S["LIMITING"]
S_EOUT, S_OUT, S_MAXA, S_MINA = _S["ENABLEOUT"], _S["OUT"], _S["MAXALARM"], _S["MINALARM"]
S_STATUS, S_FAULT, S_RANGE_INV = _S["STATUS"], _S["INSTRUCTFAULT"], _S["INRAWRANGEINV"]


@implements("SCL")
def scl(ctx: ExecContext, rung: bool, s: list) -> None:
    x, rmax, rmin = s[S_IN], s[S_RMAX], s[S_RMIN]
    s[S_EOUT] = 1
    if not rmax > rmin:
        s[S_STATUS] = 0b10
        s[S_RANGE_INV], s[S_FAULT] = 1, 0
        return
    s[S_STATUS] = 0
    s[S_RANGE_INV] = s[S_FAULT] = 0
    s[S_MAXA] = int(x > rmax)
    s[S_MINA] = int(x < rmin)
    out = (x - rmin) * (s[S_EMAX] - s[S_EMIN]) / (rmax - rmin) + s[S_EMIN]
    if s[S_LIM]:
        if s[S_MAXA]:
            out = s[S_EMAX]
        elif s[S_MINA]:
            out = s[S_EMIN]
    s[S_OUT] = f32(out)


# ------------------------------------------------------------------ PID
_P = _layout("PID")
P = {name: _P[name] for name in _P}  # every member index, by upper-case name
EN, CT, CL, PVT, DOE, SWM, CA, MO, PE, NDF, NOBC, NOZC = (
    P[b] for b in ("EN", "CT", "CL", "PVT", "DOE", "SWM", "CA", "MO", "PE", "NDF", "NOBC", "NOZC")
)
INI, SPOR, OLL, OLH, EWD = P["INI"], P["SPOR"], P["OLL"], P["OLH"], P["EWD"]
DVNA, DVPA, PVLA, PVHA = P["DVNA"], P["DVPA"], P["PVLA"], P["PVHA"]
ITERM, LAST_DIN, LAST_D, LAST_E = P["ITERM"], P["LASTDIN"], P["LASTD"], P["LASTE"]


def _span(lo: float, hi: float) -> float | None:
    return hi - lo if hi != lo else None


def _alarms(p: list, pv: float, err: float) -> None:
    """PV alarms against PVH/PVL and deviation alarms of the error against DVP/DVN, each with
    its deadband, always evaluated: real exports of loops with PVH = PVL = 0 show PVHA set
    for a positive PV, and DVPA / DVNA following the sign of ERR (not PV - SP)."""
    hi, lo, db = p[P["PVH"]], p[P["PVL"]], max(0.0, p[P["PVDB"]])
    p[PVHA] = int(pv > hi or (bool(p[PVHA]) and pv >= hi - db))
    p[PVLA] = int(pv < lo or (bool(p[PVLA]) and pv <= lo + db))
    dvp, dvn, db = p[P["DVP"]], p[P["DVN"]], max(0.0, p[P["DVDB"]])
    p[DVPA] = int(err > dvp or (bool(p[DVPA]) and err >= dvp - db))
    p[DVNA] = int(err < dvn or (bool(p[DVNA]) and err <= dvn + db))


def _deadband(p: list, err: float) -> float:
    db = p[P["DB"]]
    if db <= 0 or abs(err) > db:
        p[EWD] = 0
    elif p[NOZC] or p[EWD] or err == 0 or (err > 0) != (p[LAST_E] > 0):
        p[EWD] = 1
    p[LAST_E] = err
    return 0.0 if p[EWD] else err


def _limit(p: list, out: float) -> float:
    hi, lo = p[P["MAXO"]], p[P["MINO"]]
    if hi == lo:  # limits not configured (a new PID tag holds 0 and 0)
        p[OLH] = p[OLL] = 0
        return out
    p[OLH] = int(out > hi)
    p[OLL] = int(out < lo)
    return min(max(out, lo), hi)


def _terms(p: list, e: float, din: float, dt: float) -> tuple[float, float, float]:
    """Proportional term, integral increment and derivative term in % (before limiting)."""
    kp, ki, kd = p[P["KP"]], p[P["KI"]], p[P["KD"]]
    if p[PE]:  # dependent (ISA): KP is the controller gain, KI Ti in min/repeat, KD Td in min
        di = kp / (ki * 60.0) * e * dt if ki > 0 else 0.0
        kd_s = kp * kd * 60.0
    else:
        di = ki * e * dt
        kd_s = kd
    d = kd_s * (din - p[LAST_DIN]) / dt if p[INI] else 0.0
    if p[NDF]:
        d = (d + p[LAST_D]) / 2.0 if p[INI] else d
    p[LAST_DIN] = din
    p[LAST_D] = d
    return kp * e, di, d


def _pid(ctx: ExecContext, p: list, pv_raw: float, tieback: float, cv: Ref | BitRef,
         master: list | None, inhold: bool, inhold_value: float) -> None:  # fmt: skip
    dt = p[P["UPD"]]
    if not dt > 0:
        ctx.minor(4, 35, "PID: loop update time UPD is 0 or negative")
        return
    mins, maxs, mini, maxi = p[P["MINS"]], p[P["MAXS"]], p[P["MINI"]], p[P["MAXI"]]
    s_span, i_span = _span(mins, maxs), _span(mini, maxi)
    pv = (pv_raw - mini) * (maxs - mins) / i_span + mins if s_span and i_span else pv_raw
    p[P["PV"]] = f32(pv)
    manual = bool(p[SWM] or p[MO] or inhold)
    if manual and p[PVT]:
        p[P["SP"]] = p[P["PV"]]
    if master is not None and p[CL] and not p[CT] and s_span:
        p[P["SP"]] = f32(master[P["OUT"]] / 100.0 * s_span + mins)
    sp = p[P["SP"]]
    p[SPOR] = int(bool(s_span) and not min(mins, maxs) <= sp <= max(mins, maxs))
    if p[SPOR]:
        ctx.minor(4, 36, "PID: setpoint outside MINS..MAXS")
    err = pv - sp if p[CA] else sp - pv
    p[P["ERR"]] = f32(err)
    pct = 100.0 / (s_span or i_span or 100.0)
    e = _deadband(p, err) * pct
    signed_pv = (pv if p[CA] else -pv) * pct
    prop, di, d = _terms(p, e, e if p[DOE] else signed_pv, dt)
    bias = p[P["BIAS"]]
    if manual:
        if inhold:
            cv_span = _span(p[P["MINCV"]], p[P["MAXCV"]]) or 100.0
            out = (inhold_value - p[P["MINCV"]]) * 100.0 / cv_span
        elif p[SWM]:
            out = p[P["SO"]]
        else:
            tie_span = _span(p[P["MINTIE"]], p[P["MAXTIE"]]) or 100.0
            out = (tieback - p[P["MINTIE"]]) * 100.0 / tie_span
        out = _limit(p, out)
        if not p[NOBC]:
            p[ITERM] = out - prop - bias  # auto resumes from this output
    else:
        i_new = p[ITERM] + di
        unlimited = prop + i_new + d + bias
        out = _limit(p, unlimited)
        if (p[OLH] and di > 0) or (p[OLL] and di < 0):
            i_new = p[ITERM]  # no windup against the limit
        p[ITERM] = i_new
    p[P["OUT"]] = f32(out)
    p[INI] = 1
    cv_range = _span(p[P["MINCV"]], p[P["MAXCV"]])
    cv.set(out / 100.0 * cv_range + p[P["MINCV"]] if cv_range else out)
    _alarms(p, pv, err)


@implements("PID")
def pid(
    ctx: ExecContext,
    rung: bool,
    p: list,
    pv: float,
    tieback: float,
    cv: Ref,
    master: list | None,
    inhold: int,
    inhold_value: float,
) -> None:
    p[EN] = int(bool(rung))
    if not rung:
        p[INI] = 0  # re-initialised when enabled again (exports of idle loops: EN 0, INI 0)
        return
    if not all(math.isfinite(float(v)) for v in (pv, tieback, inhold_value)):
        ctx.minor(4, 4, "PID: an input is not a finite number")
        return
    _pid(ctx, p, float(pv), float(tieback), cv, master, bool(inhold), float(inhold_value))


@prescan("PID")
def pid_prescan(ctx: ExecContext, rung: bool, p: list, *operands: object) -> None:
    p[EN] = 0
    p[INI] = 0
