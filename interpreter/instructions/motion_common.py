"""Shared parts of the motion instruction adapters: the execution handshake of a
MOTION_INSTRUCTION, error reporting and the speed/accel/jerk unit conversions.

Handshake (MOTION_INSTRUCTION seed tables; ladder passes `rung`, ST always True):
- rung false: EN is cleared when DN or ER is set (the false-rung action);
- rung true: EN set, DN ER PC IP AC ACCEL DECEL and ERR/EXERR cleared, then the
  instruction executes; success sets DN (and IP for processes), failure sets ER, ERR and
  EXERR (error 13: EXERR is the zero-based faceplate index of the bad operand; errors 5, 7
  and 54 of coordinated instructions: the axis's index in the system, 54 also -1 for the
  system itself).
Operand problems never raise: they become `.ERR` codes.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import TypeVar

from ..motion import MotionError, StartResult
from ..runtime.motion import Axis, Group, MotionRuntime
from ..runtime.motion_layout import DN, ER, ERR, EXERR, set_bits, set_error
from ..vm.context import ExecContext

# speed / accel / jerk unit enumeration values (stdlib/instructions/motion.toml)
UNITS_PER_SEC = 0
PERCENT_OF_MAX = 1
PERCENT_OF_TIME = 2
SECONDS = 3
PER_MASTER_UNIT = 4
PERCENT_OF_TIME_MD = 6
MASTER_UNITS = 7

_SPEED_UNITS = {UNITS_PER_SEC, PERCENT_OF_MAX, SECONDS, PER_MASTER_UNIT, MASTER_UNITS}
_JERK_UNITS = _SPEED_UNITS | {PERCENT_OF_TIME, PERCENT_OF_TIME_MD}
_MASTER_UNITS = {PER_MASTER_UNIT, MASTER_UNITS, PERCENT_OF_TIME_MD}
_TIME_BASED = {SECONDS, MASTER_UNITS}

_A = TypeVar("_A", Axis, Group)


def runtime(ctx: ExecContext) -> MotionRuntime:
    rt = ctx.motion
    assert isinstance(rt, MotionRuntime), "the controller always provides a motion runtime"
    return rt


def begin(ctl: list, rung: bool) -> bool:
    """The handshake before executing; False when there is nothing to execute (rung false)."""
    if not rung:
        if ctl[DN] or ctl[ER]:
            set_bits(ctl, EN=0)
        return False
    ctl[ERR] = 0
    ctl[EXERR] = 0
    set_bits(ctl, EN=1, DN=0, ER=0, PC=0, IP=0, AC=0, ACCEL=0, DECEL=0)
    return True


# errors whose EXERR the seeds define: 13 names the operand; 5, 7 and 54 of a coordinated
# move name the axis by its index in the coordinate system (54: -1 the system itself);
# single-axis instructions report those with EXERR 0; other errors leave EXERR 0
_EXERR_ERRORS = (
    MotionError.PARAMETER_OUT_OF_RANGE,
    MotionError.SERVO_OFF_STATE,
    MotionError.SHUTDOWN_STATE,
    MotionError.ZERO_MAX_DECEL,
)


def fail(rt: MotionRuntime, ctl: list, error: int, exerr: int = 0) -> None:
    """The execution failed: ER with the Logix error number; the control leaves any process."""
    rt.own(ctl)
    set_error(ctl, error, exerr if error in _EXERR_ERRORS else 0)


def failed(rt: MotionRuntime, ctl: list, result: StartResult) -> bool:
    if result.ok:
        return False
    fail(rt, ctl, result.error, result.exerr)
    return True


def configured(rt: MotionRuntime, ctl: list, target: _A | None) -> _A | None:
    """The axis or group an instruction names; None (error 11) when it is not configured."""
    if target is None or (isinstance(target, Axis) and not rt.read_unwind(target)):
        fail(rt, ctl, MotionError.AXIS_NOT_CONFIGURED)
        return None
    return target


def start_on_axis(
    ctx: ExecContext, rung: bool, axis: list, ctl: list
) -> tuple[MotionRuntime, Axis] | None:
    """The handshake, then the axis the instruction names (error 11 when it is not
    configured); None when there is nothing more to do."""
    if not begin(ctl, rung):
        return None
    rt = runtime(ctx)
    ax = configured(rt, ctl, rt.axis(axis))
    return None if ax is None else (rt, ax)


def start_on_group(
    ctx: ExecContext, rung: bool, group: list, ctl: list
) -> tuple[MotionRuntime, Group] | None:
    """As start_on_axis, for an instruction on a motion group."""
    if not begin(ctl, rung):
        return None
    rt = runtime(ctx)
    g = configured(rt, ctl, rt.group(group))
    return None if g is None else (rt, g)


def clear_on_prescan(ctl: list) -> None:
    """Prescan (seed tables): EN, DN, ER and IP cleared."""
    set_bits(ctl, EN=0, DN=0, ER=0, IP=0)


def set_axis_status(ax: Axis, **bits: int) -> None:
    """Show a status bit on the axis tag at once (MATC: TimeCamStatus on execution)."""
    v, ix, bit_of = ax.value, ax.layout.index, ax.layout.bits
    word = v[ix["MOTIONSTATUS"]]
    for name, on in bits.items():
        v[ix[name.upper()]] = 1 if on else 0
        mask = 1 << bit_of[name.upper()]
        word = (word | mask) if on else (word & ~mask)
    v[ix["MOTIONSTATUS"]] = word


def real(x: object) -> float:
    return float(x)  # type: ignore[arg-type]


NOT_WHOLE = -1  # never a valid enumeration value: the range checks reject it


def whole(x: object) -> int:
    """An enumeration-like operand as an int (NOT_WHOLE when it is not a whole number)."""
    if isinstance(x, float):
        return int(x) if x.is_integer() else NOT_WHOLE
    return int(x)  # type: ignore[call-overload]


@dataclass(frozen=True, slots=True)
class Dynamics:
    """Speed/accel/decel/jerks in core units (per second, or per master unit when master driven)."""

    speed: float
    accel: float
    decel: float
    accel_jerk: float
    decel_jerk: float
    master_driven: bool


@dataclass(frozen=True, slots=True)
class TimeBased:
    """Time-based planning (speed in Seconds / Master Units): durations, not rates."""

    total: float
    accel_time: float
    decel_time: float
    jerk: float  # seconds of each jerk ramp, or percent of the ramp time
    jerk_percent: bool
    master_driven: bool


def dynamics(
    maximum: Callable[[str], float],
    first: int,
    speed: float,
    speed_units: object,
    accel: float,
    accel_units: object,
    decel: float,
    decel_units: object,
    s_curve: bool,
    accel_jerk: float,
    decel_jerk: float,
    jerk_units: object,
    allow_time_based: bool,
) -> Dynamics | TimeBased | StartResult:
    """Convert MAM/MAJ/MCLM/MCCM dynamics operands; `first` is the faceplate index of Speed,
    `maximum(name)` reads a configured maximum (MaximumSpeed ...) of the axis or system.

    The speed units choose the mode: Units per MasterUnit / Master Units make the motion
    master driven, the others time driven; accel, decel and (S-curve) jerk units must be of
    the same mode (else error 94, MDSC units conflict).
    """
    su, au, du, ju = whole(speed_units), whole(accel_units), whole(decel_units), whole(jerk_units)
    allowed = _SPEED_UNITS if allow_time_based else _SPEED_UNITS - _TIME_BASED
    for value, index, ok in (
        (su, first + 1, allowed), (au, first + 3, allowed), (du, first + 5, allowed),
        (ju, first + 9, _JERK_UNITS if allow_time_based else _JERK_UNITS - _TIME_BASED),
    ):  # fmt: skip
        if value not in ok:
            return StartResult(error=MotionError.PARAMETER_OUT_OF_RANGE, exerr=index)
    md = su in _MASTER_UNITS
    used = [au, du] + ([ju] if s_curve else [])
    if any((u in _MASTER_UNITS) != md for u in used):
        return StartResult(error=MotionError.MDSC_UNITS_CONFLICT)
    if su in _TIME_BASED or au in _TIME_BASED or du in _TIME_BASED:
        if not (su in _TIME_BASED and au in _TIME_BASED and du in _TIME_BASED):
            return StartResult(error=MotionError.MDSC_UNITS_CONFLICT)
        return _time_based(first, speed, accel, decel, s_curve, accel_jerk, ju, md)
    if su == PERCENT_OF_MAX:
        speed = speed * maximum("MaximumSpeed") / 100.0
    if au == PERCENT_OF_MAX:
        accel = accel * maximum("MaximumAccel") / 100.0
    if du == PERCENT_OF_MAX:
        decel = decel * maximum("MaximumDecel") / 100.0
    if not (math.isfinite(speed) and speed >= 0.0):
        return StartResult(error=MotionError.PARAMETER_OUT_OF_RANGE, exerr=first)
    if not (math.isfinite(accel) and accel > 0.0):
        return StartResult(error=MotionError.PARAMETER_OUT_OF_RANGE, exerr=first + 2)
    if not (math.isfinite(decel) and decel > 0.0):
        return StartResult(error=MotionError.PARAMETER_OUT_OF_RANGE, exerr=first + 4)
    ja = jd = math.inf
    if s_curve:
        jerks = []
        for j, rate, name, index in (
            (accel_jerk, accel, "MaximumAccelJerk", first + 7),
            (decel_jerk, decel, "MaximumDecelJerk", first + 8),
        ):
            jerk = jerk_value(j, ju, rate, speed, maximum(name))
            if jerk is None:
                return StartResult(error=MotionError.PARAMETER_OUT_OF_RANGE, exerr=index)
            jerks.append(jerk)
        ja, jd = jerks
    return Dynamics(speed, accel, decel, ja, jd, md)


def jerk_value(j: float, units: int, rate: float, speed: float, maximum: float) -> float | None:
    """Jerk in units/s³ (or per master unit³); None when the operand is out of range.

    % of Time: the share p of the accel (decel) time spent changing acceleration,
    J = A²/V · (200/p − 1) (p = 100: a pure S; at speed 0 the ramp is immaterial).
    """
    if units in (PERCENT_OF_TIME, PERCENT_OF_TIME_MD):
        if not 0.0 < j <= 100.0:
            return None
        return math.inf if speed <= 0.0 else rate * rate / speed * (200.0 / j - 1.0)
    value: float = j * maximum / 100.0 if units == PERCENT_OF_MAX else j
    return value if math.isfinite(value) and value > 0.0 else None


def _time_based(
    first: int, total: float, ta: float, td: float, s_curve: bool, jerk: float, ju: int, md: bool
) -> TimeBased | StartResult:
    if not (math.isfinite(total) and total > 0.0):
        return StartResult(error=MotionError.PARAMETER_OUT_OF_RANGE, exerr=first)
    if not (math.isfinite(ta) and ta >= 0.0):
        return StartResult(error=MotionError.PARAMETER_OUT_OF_RANGE, exerr=first + 2)
    if not (math.isfinite(td) and td >= 0.0):
        return StartResult(error=MotionError.PARAMETER_OUT_OF_RANGE, exerr=first + 4)
    percent = ju in (PERCENT_OF_TIME, PERCENT_OF_TIME_MD)
    if s_curve and not (math.isfinite(jerk) and (0.0 < jerk <= 100.0 if percent else jerk >= 0.0)):
        return StartResult(error=MotionError.PARAMETER_OUT_OF_RANGE, exerr=first + 7)
    return TimeBased(total, ta, td, jerk if s_curve else 0.0, percent, md)


def time_based_rates(tb: TimeBased, distance: float) -> Dynamics:
    """Rates for a rest-to-rest move of `distance` that lasts tb.total (time-based planning).

    Priorities (Logix): the distance, then the total time, then the ramp times (scaled down
    together when they do not fit), then the jerk times (at most half a ramp). A symmetric
    ramp of time Ta covers V·Ta/2 whatever its jerk, so V = D / (T − Ta/2 − Td/2).
    """
    total, ta, td = tb.total, tb.accel_time, tb.decel_time
    if ta + td > total:
        scale = total / (ta + td)
        ta, td = ta * scale, td * scale
    d = abs(distance)
    v = d / (total - 0.5 * (ta + td)) if total > 0.5 * (ta + td) else math.inf

    def rates(t_ramp: float) -> tuple[float, float]:
        if t_ramp <= 0.0:
            return math.inf, math.inf
        tj = tb.jerk * t_ramp / 200.0 if tb.jerk_percent else tb.jerk
        tj = min(tj, 0.5 * t_ramp)
        a = v / (t_ramp - tj)
        return a, (a / tj if tj > 0.0 else math.inf)

    a, ja = rates(ta)
    dcc, jd = rates(td)
    return Dynamics(v, a, dcc, ja, jd, tb.master_driven)
