"""PIDE, the enhanced PID block (1756-RM006), in Structured Text: `PIDE(myLoop);`.
Decisions 0190 (algorithm and modes) and 0191 (autotuner not simulated).

The block works in percent: PV and SP are mapped onto 0..100 % of PVEUMin..PVEUMax, CV is
0..100 % and CVEU = CVEUMin + CV x (CVEUMax - CVEUMin) / 100. DeltaT comes from block_timing
(decision 0139); an execution with no new real-time sample does nothing, an invalid timing
input forces Manual.

Velocity form: in Auto and Cascade/Ratio CV(n) = CV(n-1) + dCV + FF(n) - FF(n-1), where
  independent (DependIndepend 0): dCV = PGain dP + IGain / 60 E dt + dD, D = 60 DGain dx/dt
  dependent   (DependIndepend 1): dCV = PGain (dP + dt / (60 IGain) E + dD), D = 60 DGain dx/dt
with E in percent of the PV span (SP - PV, or PV - SP with ControlAction set), dt in seconds,
IGain in 1/min (independent) or min/repeat (dependent, 0 = no integral), DGain in minutes.
dP is the change of E, or of the signed PV with PVEProportional (no proportional kick on a
setpoint step); the derivative acts on the signed PV with PVEDerivative (the default), on E
otherwise. DSmoothing passes D through a first-order lag of time constant 0.1 x 60 DGain s.
Inside the zero-crossing deadband (ZCDeadbandOn) dCV is 0: CV holds, FF still passes.
CV(n-1) is the previous CV (or CVPrevious with CVSetPrevious): being the limited output,
the velocity form cannot wind up, and any mode change into Auto is bumpless by itself.

CV then goes through windup limiting (WindupHIn: no increase, WindupLIn: no decrease, in
Auto and Cascade/Ratio), the limits (CVHLimit/CVLLimit in Auto, Cascade/Ratio and in Manual
with CVManLimiting, else 0..100 %; CVHAlarm/CVLAlarm when it was limited) and the rate
limit CVROCLimit (% per second, 0 = none, same modes as the limits; CVROCAlarm).

Manual: CV = CVProg (Program control) or CVOper (Operator control); Override: CVOverride;
Hand: HandFB (held while HandFBFault). CVInitReq, and the first execution after prescan,
initialise CV from CVInitValue (EU) and set CVInitializing (not with CVFault or an invalid
CV span); ManualAfterInit then puts the loop in Manual.

Modes and requests: program requests win over operator requests, Operator control wins a
tie from one side; Hand, then Override, while their request is set (Manual once released),
else Manual, Auto, Cascade/Ratio (with AllowCasRat) in that precedence from the requests of
the side in control (decision 0190). A faulted or invalid PV (PVFault, PVSpanInv,
SPLimitsInv, a PV that is not a number), a faulted output (CVFault, CVEUSpanInv) or an
invalid timing input forces Auto and Cascade/Ratio to Manual. Operator requests (Oper*Req) are
cleared after every execution; program requests only when ProgValueReset is set, which
also makes SPProg, CVProg and RatioProg follow the loop in Operator control. The operator
values follow the loop whenever they are not in use (bumpless Program -> Operator).
PVTracking: in Manual, Override and Hand the setpoint in use follows PV.

Alarms: PVHHAlarm/PVHAlarm set at PV >= limit, cleared below limit - PVDeadband;
PVLAlarm/PVLLAlarm mirror them. Deviation alarms compare PV - SP with the four Dev limits
(all entered positive): DevH* at PV - SP >= limit, DevL* at PV - SP <= -limit, each clearing
DevDeadband inside. PV rate of change is sampled every PVROCPeriod seconds. PV alarms and
deviation alarms are cleared while PV is faulted. InitPrimary, WindupHOut and WindupLOut
serve a primary loop (the windup outputs report the SP limit or the CV limit that stops PV
moving that way). Only the program or operator value in use is range-checked.

The autotuner cannot be attached in Structured Text (only a function block diagram has the
Autotune operand), so the Atune* members are left alone (decision 0191).
"""

from __future__ import annotations

import math

from ..runtime.motion_layout import pack, packed_words
from ..vm.context import ExecContext
from ..vm.values import f32
from .block_timing import restart, sample, timing_layout
from .registry import implements, prescan
from .select_limit_blocks import layout

TYPE = "PID_ENHANCED"
M = layout(TYPE)
TIMING = timing_layout(TYPE)
WORDS = packed_words(TYPE)
_STATUS_BITS = tuple(idx for _, bits in WORDS for idx, _bit in bits)
_INSTRUCT_FAULT = M["INSTRUCTFAULT"]
# Mode bits, in the order they are stored.
MODES = ("CASRAT", "AUTO", "MANUAL", "OVERRIDE", "HAND")
_OPER_REQS = ("OPERPROGREQ", "OPEROPERREQ", "OPERCASRATREQ", "OPERAUTOREQ", "OPERMANUALREQ")
_PROG_REQS = (
    "PROGPROGREQ",
    "PROGOPERREQ",
    "PROGCASRATREQ",
    "PROGAUTOREQ",
    "PROGMANUALREQ",
    "PROGOVERRIDEREQ",
    "PROGHANDREQ",
)
SMOOTHING = 0.1  # derivative lag time constant as a fraction of the derivative time


def _g(s: list, name: str) -> float:
    return float(s[M[name]])


def _b(s: list, name: str) -> bool:
    return bool(s[M[name]])


def _set(s: list, name: str, v: object) -> None:
    s[M[name]] = int(bool(v)) if isinstance(v, bool) else v


def _clamp(x: float, lo: float, hi: float) -> float:
    return min(max(x, lo), hi)


def _checked(s: list, value: float, lo: float, hi: float, flag: str) -> float:
    """An input limited to lo..hi, with its Inv flag set when it was outside."""
    bad = not lo <= value <= hi
    _set(s, flag, bad)
    if math.isnan(value):
        return lo if math.isfinite(lo) else 0.0
    return _clamp(value, lo, hi)


def _mode(s: list) -> str | None:
    for m in MODES:
        if s[M[m]]:
            return m
    return None


def _set_mode(s: list, mode: str) -> None:
    for m in MODES:
        s[M[m]] = int(m == mode)


def _requests(s: list) -> None:
    """Program/Operator control, then the mode, from the request bits (decision 0190)."""
    # program requests before operator requests; of two requests from the same side,
    # Operator control wins
    if _b(s, "PROGOPERREQ"):
        _set(s, "PROGOPER", False)
    elif _b(s, "PROGPROGREQ"):
        _set(s, "PROGOPER", True)
    elif _b(s, "OPEROPERREQ"):
        _set(s, "PROGOPER", False)
    elif _b(s, "OPERPROGREQ"):
        _set(s, "PROGOPER", True)
    mode = _mode(s)
    if _b(s, "PROGHANDREQ"):
        mode = "HAND"
    elif _b(s, "PROGOVERRIDEREQ"):
        mode = "OVERRIDE"
    else:
        if mode in ("HAND", "OVERRIDE", None):
            mode = "MANUAL"  # the program released Hand/Override (or no mode yet)
        pre = "PROG" if _b(s, "PROGOPER") else "OPER"
        if _b(s, pre + "MANUALREQ"):
            mode = "MANUAL"
        elif _b(s, pre + "AUTOREQ"):
            mode = "AUTO"
        elif _b(s, pre + "CASRATREQ") and _b(s, "ALLOWCASRAT"):
            mode = "CASRAT"
        if mode == "CASRAT" and not _b(s, "ALLOWCASRAT"):
            mode = "AUTO"
    _set_mode(s, mode)
    for r in _OPER_REQS:
        s[M[r]] = 0
    if _b(s, "PROGVALUERESET"):
        for r in _PROG_REQS:
            s[M[r]] = 0


def _validate(s: list) -> None:
    """The invalid-parameter flags that do not depend on the mode."""
    _set(s, "PVSPANINV", not _g(s, "PVEUMAX") > _g(s, "PVEUMIN"))
    sph, spl = _g(s, "SPHLIMIT"), _g(s, "SPLLIMIT")
    _set(s, "SPLIMITSINV", sph < spl or sph > _g(s, "PVEUMAX") or spl < _g(s, "PVEUMIN"))
    rh, rl = _g(s, "RATIOHLIMIT"), _g(s, "RATIOLLIMIT")
    _set(s, "RATIOLIMITSINV", rl < 0 or rh < rl)
    _set(s, "CVEUSPANINV", _g(s, "CVEUMAX") == _g(s, "CVEUMIN"))
    ch, cl = _g(s, "CVHLIMIT"), _g(s, "CVLLIMIT")
    _set(s, "CVLIMITSINV", cl < 0 or ch > 100 or ch < cl)
    _set(s, "CVROCLIMITINV", _g(s, "CVROCLIMIT") < 0)
    for name in ("PGAIN", "IGAIN", "DGAIN", "ZCDEADBAND", "PVDEADBAND", "DEVDEADBAND"):
        _set(s, name + "INV", _g(s, name) < 0)
    _set(
        s,
        "PVROCLIMITSINV",
        min(_g(s, "PVROCPOSLIMIT"), _g(s, "PVROCNEGLIMIT"), _g(s, "PVROCPERIOD")) < 0,
    )
    dhh, dh, dl, dll = (_g(s, n) for n in ("DEVHHLIMIT", "DEVHLIMIT", "DEVLLIMIT", "DEVLLLIMIT"))
    _set(s, "DEVHLLIMITSINV", min(dhh, dh, dl, dll) < 0 or dhh < dh or dll < dl)
    _set(s, "PVFAULTED", _b(s, "PVFAULT"))
    _set(s, "CVFAULTED", _b(s, "CVFAULT"))
    _set(s, "HANDFBFAULTED", _b(s, "HANDFBFAULT"))


def _cv_limits(s: list) -> tuple[float, float]:
    """CVLLimit..CVHLimit within 0..100; high below low counts as the low limit."""
    lo = _clamp(_g(s, "CVLLIMIT"), 0.0, 100.0)
    hi = _clamp(_g(s, "CVHLIMIT"), 0.0, 100.0)
    return lo, max(hi, lo)


def _setpoint(s: list, mode: str, pv: float) -> float:
    """Ratio and SP in engineering units, with their alarms and Inv flags. Only the program
    or operator value in use is checked (and limited), as it is the value used for SP."""
    prog = _b(s, "PROGOPER")
    for flag in ("RATIOPROGINV", "RATIOOPERINV", "SPPROGINV", "SPOPERINV", "SPCASCADEINV"):
        _set(s, flag, False)
    rl, rh = _g(s, "RATIOLLIMIT"), max(_g(s, "RATIOHLIMIT"), _g(s, "RATIOLLIMIT"))
    raw_ratio = _g(s, "RATIOPROG") if prog else _g(s, "RATIOOPER")
    ratio = _checked(s, raw_ratio, rl, rh, "RATIOPROGINV" if prog else "RATIOOPERINV")
    _set(s, "RATIOHALARM", raw_ratio > rh)
    _set(s, "RATIOLALARM", raw_ratio < rl)
    _set(s, "RATIO", f32(ratio))
    # a high limit below the low limit counts as the low limit (SPLimitsInv is set)
    lo = _g(s, "SPLLIMIT")
    hi = max(_g(s, "SPHLIMIT"), lo)
    source = "SPPROG" if prog else "SPOPER"
    if _b(s, "PVTRACKING") and mode in ("MANUAL", "OVERRIDE", "HAND") and math.isfinite(pv):
        _set(s, source, f32(pv))  # the setpoint in use follows PV: bumpless back to Auto
    if mode == "CASRAT":
        sp = _checked(s, _g(s, "SPCASCADE"), lo, hi, "SPCASCADEINV")
        if _b(s, "USERATIO"):
            sp *= ratio
        _set(s, "SPHALARM", sp > hi)
        _set(s, "SPLALARM", sp < lo)
        return _clamp(sp, lo, hi)
    sp = _g(s, source)
    _set(s, "SPHALARM", sp > hi)
    _set(s, "SPLALARM", sp < lo)
    return _checked(s, sp, lo, hi, source + "INV")


def _level_alarms(s: list, pv: float, sp: float) -> None:
    """PV level alarms and deviation alarms, each with its deadband for clearing."""
    db = max(0.0, _g(s, "PVDEADBAND"))
    for alarm, limit, high in (
        ("PVHHALARM", "PVHHLIMIT", True),
        ("PVHALARM", "PVHLIMIT", True),
        ("PVLALARM", "PVLLIMIT", False),
        ("PVLLALARM", "PVLLLIMIT", False),
    ):
        _set(s, alarm, _latch(_b(s, alarm), pv, _g(s, limit), db, high))
    db = max(0.0, _g(s, "DEVDEADBAND"))
    dev = pv - sp
    for alarm, limit, high in (
        ("DEVHHALARM", "DEVHHLIMIT", True),
        ("DEVHALARM", "DEVHLIMIT", True),
        ("DEVLALARM", "DEVLLIMIT", False),
        ("DEVLLALARM", "DEVLLLIMIT", False),
    ):
        lim = _g(s, limit) if high else -_g(s, limit)
        _set(s, alarm, _latch(_b(s, alarm), dev, lim, db, high))


def _latch(on: bool, x: float, limit: float, db: float, high: bool) -> bool:
    if high:
        return x >= limit or (on and x >= limit - db)
    return x <= limit or (on and x <= limit + db)


def _roc_alarms(s: list, pv: float, dt: float) -> None:
    """PV rate of change over each PVROCPeriod (EU per second) against the two limits."""
    period = _g(s, "PVROCPERIOD")
    if _b(s, "PVROCLIMITSINV") or period <= 0:
        _set(s, "PVROCPOSALARM", False)
        _set(s, "PVROCNEGALARM", False)
        s[M["ROCTIME"]] = -1.0
        return
    t = s[M["ROCTIME"]]
    if t < 0:
        s[M["ROCBASEPV"]], s[M["ROCTIME"]] = pv, 0.0
        return
    t += dt
    if t + 1e-9 < period:
        s[M["ROCTIME"]] = t
        return
    rate = (pv - s[M["ROCBASEPV"]]) / period
    s[M["ROCBASEPV"]], s[M["ROCTIME"]] = pv, 0.0
    pos, neg = _g(s, "PVROCPOSLIMIT"), _g(s, "PVROCNEGLIMIT")
    _set(s, "PVROCPOSALARM", pos > 0 and rate >= pos)
    _set(s, "PVROCNEGALARM", neg > 0 and rate <= -neg)


def _clear_pv_alarms(s: list) -> None:
    for a in (
        "PVHH",
        "PVH",
        "PVL",
        "PVLL",
        "PVROCPOS",
        "PVROCNEG",
        "DEVHH",
        "DEVH",
        "DEVL",
        "DEVLL",
    ):
        s[M[a + "ALARM"]] = 0
    s[M["ROCTIME"]] = -1.0


def _zero_crossing(s: list, e: float, last_e: float) -> bool:
    """ZCDeadbandOn: inside the band once E has crossed (or reached) zero; always inside the
    band with ZCOff; off as soon as |E| leaves the band."""
    db = _g(s, "ZCDEADBAND")
    if db <= 0 or abs(e) > db:
        return False
    crossed = e == 0 or (e > 0) != (last_e > 0)
    return _b(s, "ZCOFF") or _b(s, "ZCDEADBANDON") or crossed


def _pid_delta(s: list, e_pct: float, pv_pct: float, dt: float, first: bool) -> float:
    """dCV of the velocity form (percent); updates the derivative memory."""
    sign = 1.0 if _b(s, "CONTROLACTION") else -1.0  # the PV's sign in E
    last_e, last_pv = s[M["LASTEPCT"]], s[M["LASTPVPCT"]]
    if first:
        last_e, last_pv = e_pct, pv_pct
    kp, ki, kd = (max(0.0, _g(s, n)) for n in ("PGAIN", "IGAIN", "DGAIN"))
    dep = _b(s, "DEPENDINDEPEND")
    dp = sign * (pv_pct - last_pv) if _b(s, "PVEPROPORTIONAL") else e_pct - last_e
    dx = sign * (pv_pct - last_pv) if _b(s, "PVEDERIVATIVE") else e_pct - last_e
    td = 60.0 * kd  # derivative time (dependent) or gain (independent), in seconds
    last_d = 0.0 if first else s[M["LASTDTERM"]]
    tf = SMOOTHING * td if _b(s, "DSMOOTHING") else 0.0
    d = (tf * last_d + td * dx) / (tf + dt) if tf + dt > 0 else 0.0
    s[M["LASTDTERM"]] = d
    if dep:
        integral = dt / (60.0 * ki) * e_pct if ki > 0 else 0.0
        return kp * (dp + integral + d - last_d)
    return kp * dp + ki / 60.0 * e_pct * dt + d - last_d


def _limit_cv(s: list, cv: float, prev: float, dt: float, limiting: bool) -> float:
    lo, hi = _cv_limits(s) if limiting else (0.0, 100.0)
    _set(s, "CVHALARM", cv > hi)
    _set(s, "CVLALARM", cv < lo)
    cv = _clamp(cv, lo, hi)
    roc = _g(s, "CVROCLIMIT")
    rate_alarm = False
    if limiting and roc > 0 and not _b(s, "CVROCLIMITINV"):
        step = roc * dt
        if abs(cv - prev) > step:
            cv = prev + math.copysign(step, cv - prev)
            rate_alarm = True
    _set(s, "CVROCALARM", rate_alarm)
    return cv


def _execute(s: list, dt: float | None, first: bool) -> None:
    _validate(s)
    _requests(s)
    mode = _mode(s) or "MANUAL"
    # PV health: PVFault, or a PV that is not a number (an infinity or NaN from a broken
    # input) counts as bad health without a Status bit, as the manual's "PV health bad" row
    pv_health = not _b(s, "PVFAULTED") and math.isfinite(_g(s, "PV"))
    pv_ok = pv_health and not (_b(s, "PVSPANINV") or _b(s, "SPLIMITSINV"))
    cv_ok = not (_b(s, "CVFAULTED") or _b(s, "CVEUSPANINV"))
    ratio_bad = _b(s, "RATIOLIMITSINV") and _b(s, "USERATIO")
    timing_bad = dt is None
    if mode in ("AUTO", "CASRAT") and (not pv_ok or not cv_ok or timing_bad):
        mode = "MANUAL"
    if mode == "CASRAT" and ratio_bad:
        mode = "MANUAL"
    initializing = (first or _b(s, "CVINITREQ")) and cv_ok
    if initializing and _b(s, "MANUALAFTERINIT") and mode not in ("OVERRIDE", "HAND"):
        mode = "MANUAL"
    _set_mode(s, mode)
    _set(s, "CVINITIALIZING", initializing)

    pv = _g(s, "PV")
    sp = _setpoint(s, mode, pv)
    _set(s, "SP", f32(sp))
    eu_lo, eu_hi = _g(s, "PVEUMIN"), _g(s, "PVEUMAX")
    e = pv - sp if _b(s, "CONTROLACTION") else sp - pv
    span_ok = not (_b(s, "PVSPANINV") or _b(s, "SPLIMITSINV")) and math.isfinite(e)
    _set(s, "E", f32(e))
    pv_pct = e_pct = 0.0
    if span_ok:
        pct = 100.0 / (eu_hi - eu_lo)
        pv_pct, e_pct = (pv - eu_lo) * pct, e * pct
        _set(s, "PVPERCENT", f32(pv_pct))
        _set(s, "SPPERCENT", f32((sp - eu_lo) * pct))
        _set(s, "EPERCENT", f32(e_pct))
    if not pv_health or not span_ok:
        _clear_pv_alarms(s)
    else:
        _level_alarms(s, pv, sp)
        _roc_alarms(s, pv, dt or 0.0)

    # ---- CV(n-1), FF(n-1)
    prev = _g(s, "CV")
    if _b(s, "CVSETPREVIOUS"):
        prev = _checked(s, _g(s, "CVPREVIOUS"), 0.0, 100.0, "CVPREVIOUSINV")
    else:
        _set(s, "CVPREVIOUSINV", False)
    ff = _checked(s, _g(s, "FF"), -100.0, 100.0, "FFINV")
    last_ff = float(s[M["LASTFF"]])
    if _b(s, "FFSETPREVIOUS"):
        last_ff = _checked(s, _g(s, "FFPREVIOUS"), -100.0, 100.0, "FFPREVIOUSINV")
    else:
        _set(s, "FFPREVIOUSINV", False)
    if first:
        last_ff = ff

    zc = span_ok and _zero_crossing(s, e, float(s[M["LASTEPCT"]]) if not first else e_pct)
    _set(s, "ZCDEADBANDON", zc)
    delta = 0.0
    if span_ok and dt:
        delta = _pid_delta(s, e_pct, pv_pct, dt, first)
    if span_ok:
        s[M["LASTEPCT"]], s[M["LASTPVPCT"]] = e_pct, pv_pct

    prog = _b(s, "PROGOPER")
    for flag in ("CVPROGINV", "CVOPERINV", "CVOVERRIDEINV", "HANDFBINV"):
        _set(s, flag, False)
    step = dt or 0.0
    if initializing and mode not in ("OVERRIDE", "HAND"):
        span = _g(s, "CVEUMAX") - _g(s, "CVEUMIN")
        cv = _clamp((_g(s, "CVINITVALUE") - _g(s, "CVEUMIN")) * 100.0 / span, 0.0, 100.0)
        for flag in ("CVHALARM", "CVLALARM", "CVROCALARM"):
            s[M[flag]] = 0
    elif mode == "HAND":
        _checked(s, _g(s, "HANDFB"), 0.0, 100.0, "HANDFBINV")
        cv = prev if _b(s, "HANDFBFAULTED") else _g(s, "HANDFB")
        cv = _limit_cv(s, cv, prev, step, False)
    elif mode == "OVERRIDE":
        _checked(s, _g(s, "CVOVERRIDE"), 0.0, 100.0, "CVOVERRIDEINV")
        cv = _limit_cv(s, _g(s, "CVOVERRIDE"), prev, step, False)
    elif mode == "MANUAL":
        man_lim = _b(s, "CVMANLIMITING")
        lo, hi = _cv_limits(s) if man_lim else (0.0, 100.0)
        source = "CVPROG" if prog else "CVOPER"
        _checked(s, _g(s, source), lo, hi, source + "INV")
        cv = _limit_cv(s, _g(s, source), prev, step, man_lim)  # alarms on the asked value
    else:
        cv = prev + (0.0 if zc else delta) + (ff - last_ff)
        if cv_ok:  # windup inputs are ignored while the output is faulted
            if _b(s, "WINDUPHIN") and cv > prev:
                cv = prev
            if _b(s, "WINDUPLIN") and cv < prev:
                cv = prev
        cv = _limit_cv(s, cv, prev, step, True)
    s[M["LASTFF"]] = ff
    cv = f32(cv)
    _set(s, "CV", cv)
    if cv_ok:
        lo, span = _g(s, "CVEUMIN"), _g(s, "CVEUMAX") - _g(s, "CVEUMIN")
        _set(s, "CVEU", f32(lo + cv * span / 100.0))

    # ---- values that follow the loop, outputs for a primary loop
    if initializing:  # both manual values start from the initialised output
        _set(s, "CVOPER", cv)
        _set(s, "CVPROG", cv)
    elif not (mode == "MANUAL" and not prog):
        _set(s, "CVOPER", cv)
    if prog:
        _set(s, "SPOPER", s[M["SP"]])
        _set(s, "RATIOOPER", s[M["RATIO"]])
    elif _b(s, "PROGVALUERESET"):
        _set(s, "SPPROG", s[M["SP"]])
        _set(s, "CVPROG", cv)
        _set(s, "RATIOPROG", s[M["RATIO"]])
    if mode == "CASRAT" and not prog:
        _set(s, "SPOPER", s[M["SP"]])  # back to Auto from Cascade/Ratio without a bump
    _set(s, "INITPRIMARY", mode != "CASRAT" or initializing)
    # the windup outputs tell a primary loop that this loop cannot take its PV further up
    # (or down): its SP is at a limit, or its CV is at the limit that moves PV that way
    reverse = not _b(s, "CONTROLACTION")  # CV up drives PV up
    windup = cv_ok and not initializing
    up = _b(s, "SPHALARM") or (_b(s, "CVHALARM") if reverse else _b(s, "CVLALARM"))
    down = _b(s, "SPLALARM") or (_b(s, "CVLALARM") if reverse else _b(s, "CVHALARM"))
    _set(s, "WINDUPHOUT", windup and up)
    _set(s, "WINDUPLOUT", windup and down)


def _pack_status(s: list) -> None:
    s[_INSTRUCT_FAULT] = 0
    s[_INSTRUCT_FAULT] = int(
        any(s[i] for i in _STATUS_BITS if i not in (_INSTRUCT_FAULT, M["RTSMISSED"]))
    )
    for word, bits in WORDS:
        pack(s, word, bits)


@implements("PIDE")
def pide(ctx: ExecContext, rung: bool, s: list) -> None:
    first = not s[M["STARTED"]]
    dt = sample(ctx, s, TIMING)
    timing_bad = any(
        s[getattr(TIMING, f)] for f in ("mode_inv", "rts_time_inv", "rts_stamp_inv", "delta_t_inv")
    )
    s[M["ENABLEOUT"]] = 1
    if dt is None and not timing_bad:
        return  # real-time sampling without a new sample: nothing to compute this time
    _execute(s, dt, first)
    s[M["STARTED"]] = 1
    _pack_status(s)


@prescan("PIDE")
def pide_prescan(ctx: ExecContext, rung: bool, s: list) -> None:
    # The next execution is the instruction first scan: CV initialises from CVInitValue,
    # the derivative and feed forward memories restart, DeltaT starts a new series.
    s[M["STARTED"]] = 0
    restart(s, TIMING)
