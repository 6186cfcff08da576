"""ALMD (digital) and ALMA (analog) instruction-based alarms, decision 0032.

Sources: 1756-RM003 / 1756-RM006 alarm chapters. One execution, in this order:
1. The program operands are copied into the members of the same name (ProgAck, ...; ST and
   ALMA also In). Ladder ALMD takes In from the rung; a false rung stops ladder ALMA
   (EnableOut cleared, nothing evaluated).
2. Commands. Enable wins over disable, unsuppress over suppress, unshelve over shelve.
   Prog... disable/enable/suppress/unsuppress act while set; ProgAck, ProgAckAll, ProgReset
   and AlarmCountReset act on a false-to-true change; Oper... members are one-shot requests
   that the instruction clears once handled. A shelve lasts ShelveDuration minutes (at most
   MaxShelveDuration when that is set). Disabling clears InAlarm and sets Acked.
3. Condition. ALMD: In = Condition. ALMA levels: HH In >= HHLimit, H In >= HLimit, L In <=
   LLimit, LL In <= LLLimit; an active level clears once In is back past its limit by
   Deadband. Rates: every ROCPeriod seconds ROC = (In - In at the period's start) / ROCPeriod;
   ROCPos is active while ROC >= ROCPosLimit, ROCNeg while ROC <= -ROCNegLimit (a limit of
   0 turns the condition off). A condition must hold MinDurationPRE ms before it becomes
   active (ALMA: only the levels whose ..MinDurationEnable is set); MinDurationACC shows how
   long a condition has been waiting (0 when none waits).
4. A condition becoming active counts (AlarmCount), is timestamped and, with AckRequired,
   waits for an acknowledgement (Acked clear). It goes back to normal when its condition
   ends, except a latched ALMD, which needs a reset with the condition gone and the alarm
   acknowledged. An acknowledgement applies whether or not the condition is still active.
   Without AckRequired Acked is always set.
Timestamps are the controller wall clock in microseconds (as GSV WallClockTime reads it).
No FactoryTalk subscriber ever connects: the delivery members stay clear.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..vm.context import ExecContext
from ..vm.values import f32
from .fbd_timers import _layout
from .ladder_system import _utc_us
from .registry import implements

DINT_MAX = 2**31 - 1


def _edge(s: list, now: int, prev: int) -> bool:
    """Rising edge of the member at `now`, remembered in the hidden member at `prev`."""
    rose = bool(s[now]) and not s[prev]
    s[prev] = int(bool(s[now]))
    return rose


def _request(s: list, i: int) -> bool:
    """An operator request: read and clear."""
    on = bool(s[i])
    s[i] = 0
    return on


def _held_ms(ctx: ExecContext, s: list, since: int, holds: bool) -> float:
    """How long a condition has held (0 on its first execution); resets when it drops."""
    if not holds:
        s[since] = -1.0
        return 0.0
    if s[since] < 0:
        s[since] = ctx.now_ms
    return ctx.now_ms - s[since]  # type: ignore[no-any-return]


def _severity_ok(value: int) -> bool:
    return 1 <= value <= 1000


def _shelve_ms(s: list, duration: int, maximum: int) -> float:
    minutes = s[duration]
    if s[maximum] > 0:
        minutes = min(minutes, s[maximum])
    return max(0, minutes) * 60_000.0


# ------------------------------------------------------------------ ALMD
_D = _layout("ALARM_DIGITAL")


def _d(name: str) -> int:
    return _D[name.upper()]


D_EIN, D_IN, D_INFAULT, D_COND, D_ACKREQ, D_LATCHED = (
    _d(n) for n in ("EnableIn", "In", "InFault", "Condition", "AckRequired", "Latched")
)
D_PACK, D_OACK, D_PRESET, D_ORESET = (
    _d(n) for n in ("ProgAck", "OperAck", "ProgReset", "OperReset")
)
D_PSUP, D_OSUP, D_PUNSUP, D_OUNSUP = (
    _d(n) for n in ("ProgSuppress", "OperSuppress", "ProgUnsuppress", "OperUnsuppress")
)
D_OSHELVE, D_PUNSHELVE, D_OUNSHELVE = (
    _d(n) for n in ("OperShelve", "ProgUnshelve", "OperUnshelve")
)
D_PDIS, D_ODIS, D_PEN, D_OEN, D_CNTRESET = (
    _d(n) for n in ("ProgDisable", "OperDisable", "ProgEnable", "OperEnable", "AlarmCountReset")
)
D_USEPROG, D_PROGTIME, D_SEV, D_MINPRE = (
    _d(n) for n in ("UseProgTime", "ProgTime", "Severity", "MinDurationPRE")
)
D_SHDUR, D_SHMAX = _d("ShelveDuration"), _d("MaxShelveDuration")
D_EOUT, D_INALARM, D_ACKED, D_UNACK, D_SUPPRESSED, D_SHELVED, D_DISABLED = (
    _d(n)
    for n in ("EnableOut", "InAlarm", "Acked", "InAlarmUnack", "Suppressed", "Shelved", "Disabled")
)
D_MINACC, D_COUNT, D_INTIME, D_ACKTIME, D_RTNTIME, D_CNTTIME = (
    _d(n)
    for n in (
        "MinDurationACC",
        "AlarmCount",
        "InAlarmTime",
        "AckTime",
        "RetToNormalTime",
        "AlarmCountResetTime",
    )
)
D_SHTIME, D_UNSHTIME = _d("ShelveTime"), _d("UnshelveTime")
D_STATUS, D_IFAULT, D_INFAULTED, D_SEVINV = (
    _d(n) for n in ("Status", "InstructFault", "InFaulted", "SeverityInv")
)
D_PACK_PREV, D_PRESET_PREV, D_CNT_PREV, D_SINCE, D_UNSHELVE_AT = (
    _d(n)
    for n in ("ProgAckPrev", "ProgResetPrev", "AlarmCountResetPrev", "PendingSince", "UnshelveAt")
)


def _stamp(ctx: ExecContext, s: list, use_prog: int = -1, prog_time: int = -1) -> int:
    if use_prog >= 0 and s[use_prog]:
        return int(s[prog_time])
    return _utc_us(ctx)


def _almd(ctx: ExecContext, s: list) -> None:
    now = _stamp(ctx, s, D_USEPROG, D_PROGTIME)
    # commands
    if s[D_PDIS] or _request(s, D_ODIS):
        s[D_DISABLED] = 1
    if s[D_PEN] or _request(s, D_OEN):
        s[D_DISABLED] = 0
    if s[D_PSUP] or _request(s, D_OSUP):
        s[D_SUPPRESSED] = 1
    if s[D_PUNSUP] or _request(s, D_OUNSUP):
        s[D_SUPPRESSED] = 0
    if _request(s, D_OSHELVE) and not s[D_SHELVED]:
        s[D_SHELVED] = 1
        s[D_UNSHELVE_AT] = ctx.now_ms + _shelve_ms(s, D_SHDUR, D_SHMAX)
        s[D_SHTIME] = now
        s[D_UNSHTIME] = now + round((s[D_UNSHELVE_AT] - ctx.now_ms) * 1000)
    unshelve = _request(s, D_OUNSHELVE) or bool(s[D_PUNSHELVE])
    if s[D_SHELVED] and (unshelve or ctx.now_ms >= s[D_UNSHELVE_AT]):
        s[D_SHELVED] = 0
    if _edge(s, D_CNTRESET, D_CNT_PREV):
        s[D_COUNT] = 0
        s[D_CNTTIME] = now
    ack = _edge(s, D_PACK, D_PACK_PREV) | _request(s, D_OACK)
    reset = _edge(s, D_PRESET, D_PRESET_PREV) | _request(s, D_ORESET)
    # condition
    s[D_INFAULTED] = int(bool(s[D_INFAULT]))
    s[D_SEVINV] = int(not _severity_ok(s[D_SEV]))
    s[D_STATUS] = (s[D_INFAULTED] << 1) | (s[D_SEVINV] << 2)
    s[D_IFAULT] = 0
    s[D_EOUT] = 1
    if s[D_DISABLED]:
        s[D_INALARM] = 0
        s[D_ACKED] = 1
        s[D_UNACK] = 0
        s[D_MINACC] = 0
        s[D_SINCE] = -1.0
        return
    cond = bool(s[D_IN]) == bool(s[D_COND])
    held = _held_ms(ctx, s, D_SINCE, cond)
    if cond and not s[D_INALARM] and held + 1e-9 >= max(0, s[D_MINPRE]):
        s[D_INALARM] = 1
        s[D_COUNT] = min(DINT_MAX, s[D_COUNT] + 1)
        s[D_INTIME] = now
        s[D_ACKED] = 0
    # the time a condition has been waiting to become active; 0 when none waits
    s[D_MINACC] = min(DINT_MAX, math.floor(held + 1e-9)) if cond and not s[D_INALARM] else 0
    if ack and not s[D_ACKED]:
        s[D_ACKED] = 1
        s[D_ACKTIME] = now
    if not s[D_ACKREQ]:
        s[D_ACKED] = 1
    if s[D_INALARM] and not cond:
        if not s[D_LATCHED] or (reset and s[D_ACKED]):
            s[D_INALARM] = 0
            s[D_RTNTIME] = now
    s[D_UNACK] = int(bool(s[D_INALARM]) and not s[D_ACKED])


@implements("ALMD@rll")
def almd_ladder(
    ctx: ExecContext, rung: bool, s: list, ack: int, reset: int, disable: int, enable: int
) -> None:
    s[D_IN] = int(bool(rung))  # the rung is the input; the alarm is evaluated either way
    _prog(s, ack, reset, disable, enable)
    _almd(ctx, s)


@implements("ALMD@st")
def almd_st(
    ctx: ExecContext,
    rung: bool,
    s: list,
    x: int,
    ack: int,
    reset: int,
    disable: int,
    enable: int,
) -> None:
    s[D_IN] = int(bool(x))
    _prog(s, ack, reset, disable, enable)
    _almd(ctx, s)


def _prog(s: list, ack: int, reset: int, disable: int, enable: int) -> None:
    s[D_PACK], s[D_PRESET] = int(bool(ack)), int(bool(reset))
    s[D_PDIS], s[D_PEN] = int(bool(disable)), int(bool(enable))


# ------------------------------------------------------------------ ALMA
_A = _layout("ALARM_ANALOG")


def _a(name: str) -> int:
    return _A[name.upper()]


@dataclass(frozen=True, slots=True)
class _Cond:
    """Member indices of one ALMA condition (HH, H, L, LL, ROCPos, ROCNeg)."""

    name: str
    in_alarm: int
    acked: int
    unack: int
    shelved: int
    prog_ack: int
    oper_ack: int
    ack_prev: int
    oper_shelve: int
    oper_unshelve: int
    unshelve_at: int
    count: int
    time: int
    severity: int
    min_enable: int = -1
    since: int = -1
    limit: int = -1


def _cond(c: str, count: str) -> _Cond:
    level = c in ("HH", "H", "L", "LL")
    return _Cond(
        c,
        _a(f"{c}InAlarm"),
        _a(f"{c}Acked"),
        _a(f"{c}InAlarmUnack"),
        _a(f"{c}Shelved"),
        _a(f"{c}ProgAck"),
        _a(f"{c}OperAck"),
        _a(f"{c}ProgAckPrev"),
        _a(f"{c}OperShelve"),
        _a(f"{c}OperUnshelve"),
        _a(f"{c}UnshelveAt"),
        _a(count),
        _a(f"{c}InAlarmTime"),
        _a(f"{c}Severity"),
        _a(f"{c}MinDurationEnable") if level else -1,
        _a(f"{c}PendingSince") if level else -1,
        _a(f"{c}Limit"),
    )


HH, H, L, LL = (_cond(c, f"{c}AlarmCount") for c in ("HH", "H", "L", "LL"))
ROC_POS = _cond("ROCPos", "ROCPosInAlarmCount")
ROC_NEG = _cond("ROCNeg", "ROCNegAlarmCount")
CONDITIONS = (HH, H, L, LL, ROC_POS, ROC_NEG)
A_EIN, A_IN, A_INFAULT, A_ACKREQ = (_a(n) for n in ("EnableIn", "In", "InFault", "AckRequired"))
A_PACKALL, A_OACKALL, A_PACKALL_PREV = (
    _a(n) for n in ("ProgAckAll", "OperAckAll", "ProgAckAllPrev")
)
A_PSUP, A_OSUP, A_PUNSUP, A_OUNSUP = (
    _a(n) for n in ("ProgSuppress", "OperSuppress", "ProgUnsuppress", "OperUnsuppress")
)
A_PUNSHELVEALL, A_PDIS, A_ODIS, A_PEN, A_OEN = (
    _a(n) for n in ("ProgUnshelveAll", "ProgDisable", "OperDisable", "ProgEnable", "OperEnable")
)
A_CNTRESET, A_CNT_PREV, A_CNTTIME = (
    _a(n) for n in ("AlarmCountReset", "AlarmCountResetPrev", "AlarmCountResetTime")
)
A_MINPRE, A_MINACC, A_SHDUR, A_SHMAX = (
    _a(n) for n in ("MinDurationPRE", "MinDurationACC", "ShelveDuration", "MaxShelveDuration")
)
A_DEADBAND, A_ROCPERIOD, A_ROC, A_ROC_IN, A_ROC_T = (
    _a(n) for n in ("Deadband", "ROCPeriod", "ROC", "ROCSampleIn", "ROCSampleTime")
)
A_EOUT, A_INALARM, A_ANYUNACK, A_SUPPRESSED, A_DISABLED = (
    _a(n) for n in ("EnableOut", "InAlarm", "AnyInAlarmUnack", "Suppressed", "Disabled")
)
A_ACKTIME, A_RTNTIME, A_SHTIME, A_UNSHTIME = (
    _a(n) for n in ("AckTime", "RetToNormalTime", "ShelveTime", "UnshelveTime")
)
A_STATUS = _a("Status")
A_STATUS_BITS = tuple(
    _a(n)
    for n in (
        "InstructFault",
        "InFaulted",
        "SeverityInv",
        "AlarmLimitsInv",
        "DeadbandInv",
        "ROCPosLimitInv",
        "ROCNegLimitInv",
        "ROCPeriodInv",
    )
)


def _alma_commands(ctx: ExecContext, s: list, now: int) -> bool:
    """Enable/suppress/shelve/count commands; returns whether every condition is acked."""
    if s[A_PDIS] or _request(s, A_ODIS):
        s[A_DISABLED] = 1
    if s[A_PEN] or _request(s, A_OEN):
        s[A_DISABLED] = 0
    if s[A_PSUP] or _request(s, A_OSUP):
        s[A_SUPPRESSED] = 1
    if s[A_PUNSUP] or _request(s, A_OUNSUP):
        s[A_SUPPRESSED] = 0
    unshelve_all = bool(s[A_PUNSHELVEALL])
    for c in CONDITIONS:
        if _request(s, c.oper_shelve) and not s[c.shelved]:
            s[c.shelved] = 1
            s[c.unshelve_at] = ctx.now_ms + _shelve_ms(s, A_SHDUR, A_SHMAX)
            s[A_SHTIME] = now
            s[A_UNSHTIME] = now + round((s[c.unshelve_at] - ctx.now_ms) * 1000)
        unshelve = _request(s, c.oper_unshelve) or unshelve_all
        if s[c.shelved] and (unshelve or ctx.now_ms >= s[c.unshelve_at]):
            s[c.shelved] = 0
    if _edge(s, A_CNTRESET, A_CNT_PREV):
        for c in CONDITIONS:
            s[c.count] = 0
        s[A_CNTTIME] = now
    return _edge(s, A_PACKALL, A_PACKALL_PREV) | _request(s, A_OACKALL)


def _alma_status(s: list) -> tuple[bool, float, bool, bool, bool]:
    """Configuration checks -> (levels valid, deadband, ROC+ on, ROC- on, ROC period valid)."""
    bits = [0] * len(A_STATUS_BITS)
    bits[1] = int(bool(s[A_INFAULT]))
    bits[2] = int(not all(_severity_ok(s[c.severity]) for c in CONDITIONS))
    enabled = [s[c.limit] for c in (LL, L, H, HH) if s[_a(f"{c.name}Enabled")]]
    bits[3] = int(any(a > b for a, b in zip(enabled, enabled[1:], strict=False)))
    deadband = s[A_DEADBAND]
    bits[4] = int(deadband < 0)
    bits[5] = int(s[ROC_POS.limit] < 0)
    bits[6] = int(s[ROC_NEG.limit] < 0)
    bits[7] = int(s[A_ROCPERIOD] < 0)
    for i, b in zip(A_STATUS_BITS, bits, strict=True):
        s[i] = b
    s[A_STATUS] = sum(b << k for k, b in enumerate(bits))
    return (
        not bits[3],
        0.0 if bits[4] else deadband,
        not bits[5] and s[ROC_POS.limit] > 0,
        not bits[6] and s[ROC_NEG.limit] > 0,
        not bits[7] and s[A_ROCPERIOD] > 0,
    )


def _rate(ctx: ExecContext, s: list, x: float, period_s: float) -> None:
    """Take a rate-of-change sample once per ROCPeriod; ROC keeps the last one between."""
    if s[A_ROC_T] < 0:
        s[A_ROC_T], s[A_ROC_IN] = ctx.now_ms, x
        return
    if ctx.now_ms - s[A_ROC_T] + 1e-9 >= period_s * 1000.0:
        s[A_ROC] = (x - s[A_ROC_IN]) / period_s
        s[A_ROC_T], s[A_ROC_IN] = ctx.now_ms, x


def _level(c: _Cond, s: list, x: float, deadband: float) -> bool:
    limit = s[c.limit]
    high = c in (HH, H)
    if s[c.in_alarm]:
        return x > limit - deadband if high else x < limit + deadband
    return x >= limit if high else x <= limit


def _alma(ctx: ExecContext, s: list) -> None:
    now = _utc_us(ctx)
    ack_all = _alma_commands(ctx, s, now)
    levels_ok, deadband, roc_pos, roc_neg, roc_ok = _alma_status(s)
    s[A_EOUT] = 1
    x = float(s[A_IN])
    if s[A_DISABLED]:
        for c in CONDITIONS:
            s[c.in_alarm] = s[c.unack] = 0
            s[c.acked] = 1
            if c.since >= 0:
                s[c.since] = -1.0
        s[A_INALARM] = s[A_ANYUNACK] = s[A_MINACC] = 0
        s[A_ROC_T] = -1.0
        return
    if roc_ok:
        _rate(ctx, s, x, s[A_ROCPERIOD])
    else:
        s[A_ROC_T] = -1.0
        s[A_ROC] = 0.0
    acc = 0.0
    for c in CONDITIONS:
        if c.since >= 0:  # a level
            holds = levels_ok and bool(s[_a(f"{c.name}Enabled")]) and _level(c, s, x, deadband)
            held = _held_ms(ctx, s, c.since, holds and not s[c.in_alarm])
            need = max(0, s[A_MINPRE]) if s[c.min_enable] else 0
            active = holds and (bool(s[c.in_alarm]) or held + 1e-9 >= need)
            if holds and not active:
                acc = max(acc, held)  # still waiting for its minimum duration
        elif c is ROC_POS:
            active = roc_pos and roc_ok and s[A_ROC] >= s[c.limit]
        else:
            active = roc_neg and roc_ok and s[A_ROC] <= -s[c.limit]
        _transition(s, c, active, now)
        if (ack_all or _edge(s, c.prog_ack, c.ack_prev) | _request(s, c.oper_ack)) and not s[
            c.acked
        ]:
            s[c.acked] = 1
            s[A_ACKTIME] = now
        if not s[A_ACKREQ]:
            s[c.acked] = 1
        s[c.unack] = int(bool(s[c.in_alarm]) and not s[c.acked])
    s[A_MINACC] = min(DINT_MAX, math.floor(acc + 1e-9))
    s[A_INALARM] = int(any(s[c.in_alarm] for c in CONDITIONS))
    s[A_ANYUNACK] = int(any(s[c.unack] for c in CONDITIONS))


def _transition(s: list, c: _Cond, active: bool, now: int) -> None:
    if active and not s[c.in_alarm]:
        s[c.in_alarm] = 1
        s[c.count] = min(DINT_MAX, s[c.count] + 1)
        s[c.time] = now
        s[c.acked] = 0
    elif not active and s[c.in_alarm]:
        s[c.in_alarm] = 0
        s[A_RTNTIME] = now


@implements("ALMA")
def alma(
    ctx: ExecContext, rung: bool, s: list, x: float, ack_all: int, disable: int, enable: int
) -> None:
    s[A_EIN] = int(bool(rung))
    if not rung:  # ladder: a false rung does not evaluate the alarm
        s[A_EOUT] = 0
        return
    s[A_IN] = f32(float(x))
    s[A_PACKALL], s[A_PDIS], s[A_PEN] = (int(bool(v)) for v in (ack_all, disable, enable))
    _alma(ctx, s)
