"""Ranges of motion configuration values in initialisers and exported tag data.

The axis properties and the motion group's coarse update period are set in Studio's
property pages, which refuse a negative or non-numeric maximum; the motion core divides by
some of them. A value out of range is refused where it is written (E118), in `check` and
`run` alike (docs/decisions/0133-literal-and-configuration-limits.md).
"""

from __future__ import annotations

import math

from ..limits import MAX_COARSE_UPDATE_MS, MIN_COARSE_UPDATE_MS

# member (upper case) -> (description of the range, test)
_AT_LEAST_ZERO = ("a finite number >= 0 (0: not configured)", lambda x: 0 <= x < math.inf)
# 0 keeps an axis linear; a rotary axis without an unwind is not configured (ERR 11, 0115)
_UNWIND = ("a finite number >= 0 (0: linear, no unwind)", lambda x: 0 <= x < math.inf)
_LIMITS = {
    "MAXIMUMSPEED": _AT_LEAST_ZERO,
    "MAXIMUMACCEL": _AT_LEAST_ZERO,
    "MAXIMUMDECEL": _AT_LEAST_ZERO,
    "MAXIMUMACCELJERK": _AT_LEAST_ZERO,
    "MAXIMUMDECELJERK": _AT_LEAST_ZERO,
    "POSITIONUNWIND": _UNWIND,
}
_CUP_US = (MIN_COARSE_UPDATE_MS * 1000.0, MAX_COARSE_UPDATE_MS * 1000.0)
_CUP = (
    f"{_CUP_US[0]:.0f} to {_CUP_US[1]:.0f} microseconds",
    lambda x: _CUP_US[0] <= x <= _CUP_US[1],
)
_AXES = ("AXIS_VIRTUAL", "AXIS_CIP_DRIVE", "AXIS_GENERIC", "AXIS_SERVO", "AXIS_SERVO_DRIVE")


def config_problem(type_name: str, member: str, value: int | float) -> str | None:
    """Why `value` cannot configure `member` of a `type_name` tag, or None."""
    key, owner = member.upper(), type_name.upper()
    if owner == "MOTION_GROUP" and key == "COARSEUPDATEPERIOD":
        rule = _CUP
    elif (owner in _AXES or owner == "COORDINATE_SYSTEM") and key in _LIMITS:
        rule = _LIMITS[key]
    else:
        return None
    what, ok = rule
    if ok(value):  # type: ignore[operator]
        return None
    return f"{type_name}.{member} must be {what}, not {value:g}"
