"""MCCD: change the vector speed, accel, decel or jerks of a coordinate system's move.

Operands arrive in catalog (faceplate) order; EXERR of error 13 is the zero-based operand
index. Like MCD, MCCD completes in the executing scan (DN, no IP or PC) and the change takes
effect at the next update: the active move (and with Scope "Active and Pending Motion" the
queued one) is planned again from its present path speed to its own end point
(path_moves.change_path_dynamics). No move running is not an error. Decision 0185.
"""

from __future__ import annotations

import math

from stdlib import catalog

from ..motion import MotionError
from ..motion.path_moves import JerkOf
from ..runtime.motion_layout import set_bits
from ..vm.context import ExecContext
from .motion_common import (
    PER_MASTER_UNIT,
    PERCENT_OF_MAX,
    PERCENT_OF_TIME_MD,
    fail,
    failed,
    jerk_value,
    real,
    whole,
)
from .motion_coordinated import _start
from .registry import implements


def _values(enum: str) -> frozenset[int]:
    return frozenset(v.value for v in catalog().enum(enum).values)


def _value(enum: str, text: str) -> int:
    ev = catalog().enum(enum).lookup(text)
    assert ev is not None, (enum, text)
    return ev.value


_COORDINATED_MOVE = _value("CoordChangeMotionType", "Coordinated Move")
_ACTIVE_AND_PENDING = _value("CoordChangeScope", "Active and Pending Motion")
_SCOPES = _values("CoordChangeScope")
_CHANGE = _values("ChangeDynamics")
_YES = _value("ChangeDynamics", "Yes")
_SPEED_UNITS = _values("SpeedUnits")
_RATE_UNITS = _values("AccelUnits")
_JERK_UNITS = _values("JerkUnits")
# master-driven units: coordinated moves here are always time driven (MDCC is not simulated)
_MASTER_UNITS = frozenset({PER_MASTER_UNIT, PERCENT_OF_TIME_MD})

# faceplate indices (EXERR): each Change flag, its value and its units
_SPEED = (3, 4, 5)
_ACCEL = (6, 7, 8)
_DECEL = (9, 10, 11)
_ACCEL_JERK = (12, 13, 16)
_DECEL_JERK = (14, 15, 16)
_SCOPE = 17


@implements("MCCD")
def mccd(
    ctx: ExecContext, rung: bool, cs: list, ctl: list, motion_type: int, change_speed: int,
    speed: float, speed_units: int, change_accel: int, accel_rate: float, accel_units: int,
    change_decel: int, decel_rate: float, decel_units: int, change_accel_jerk: int,
    accel_jerk: float, change_decel_jerk: int, decel_jerk: float, jerk_units: int,
    scope: int,
) -> None:  # fmt: skip
    started = _start(ctx, rung, cs, ctl)
    if started is None:
        return
    rt, s = started
    if whole(motion_type) != _COORDINATED_MOVE:
        fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, 2)
        return
    ops = (
        (change_speed, speed, speed_units, _SPEED, _SPEED_UNITS, "MaximumSpeed"),
        (change_accel, accel_rate, accel_units, _ACCEL, _RATE_UNITS, "MaximumAccel"),
        (change_decel, decel_rate, decel_units, _DECEL, _RATE_UNITS, "MaximumDecel"),
        (change_accel_jerk, accel_jerk, jerk_units, _ACCEL_JERK, _JERK_UNITS, "MaximumAccelJerk"),
        (change_decel_jerk, decel_jerk, jerk_units, _DECEL_JERK, _JERK_UNITS, "MaximumDecelJerk"),
    )  # fmt: skip
    # the enumerations first, the lowest faceplate index reported (a literal out of range is
    # a verification error; these catch what gets past it)
    checks = [(i_flag, flag, _CHANGE) for flag, _, _, (i_flag, _, _), _, _ in ops]
    checks += [(i_units, units, ok) for _, _, units, (_, _, i_units), ok, _ in ops]
    checks.append((_SCOPE, scope, _SCOPES))
    for i_enum, given, allowed in sorted(checks, key=lambda c: c[0]):
        if whole(given) not in allowed:
            fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, i_enum)
            return
    sc = whole(scope)
    changed = [whole(flag) == _YES for flag, *_ in ops]
    if any(whole(op[2]) in _MASTER_UNITS for op, c in zip(ops, changed, strict=True) if c):
        # master-driven units for a move that runs in time (decision 0185)
        fail(rt, ctl, MotionError.MDSC_UNITS_CONFLICT)
        return
    rates: list[float | None] = []
    for (_, value, units, (_, index, _), _, maximum), c in zip(ops[:3], changed[:3], strict=True):
        if not c:
            rates.append(None)
            continue
        x = real(value) * (s.get(maximum) / 100.0 if whole(units) == PERCENT_OF_MAX else 1.0)
        # speed 0 is allowed: the move comes to rest on its path and waits (as MCD)
        ok = math.isfinite(x) and (x >= 0.0 if index == _SPEED[1] else x > 0.0)
        if not ok:
            fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, index)
            return
        rates.append(x)
    jerks: list[JerkOf | None] = []
    for (_, value, units, (_, index, _), _, maximum), c in zip(ops[3:], changed[3:], strict=True):
        if not c:
            jerks.append(None)
            continue
        j, ju, mx = real(value), whole(units), s.get(maximum)
        if jerk_value(j, ju, 1.0, 1.0, mx) is None:  # the operand's own range
            fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, index)
            return

        def jerk(rate: float, spd: float, j: float = j, ju: int = ju, mx: float = mx) -> float:
            # % of Time depends on the move's (new) rate and speed, so it is resolved per move
            return jerk_value(j, ju, rate, spd, mx) or math.inf

        jerks.append(jerk)
    r = s.group.core.change_path_dynamics(
        s.index, rates[0], rates[1], rates[2], jerks[0], jerks[1], sc == _ACTIVE_AND_PENDING
    )
    if failed(rt, ctl, r):
        return
    rt.own(ctl)  # completes in this scan: no process bits to follow
    set_bits(ctl, DN=1)
