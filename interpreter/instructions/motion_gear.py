"""Electronic gearing (MAG) and on-the-fly dynamics changes (MCD).

MAG sets DN and IP in the executing scan; the gear engages at the next planner update and
IP stays set until the gearing is replaced by another MAG on the slave, stopped (MAS Gear
or All, MGS), merged away (MAM/MAJ Merge Enabled) or ended by servo off / shutdown. MAG has
no PC. A Fraction ratio is SlaveCounts slave feedback counts per MasterCounts master counts;
with the axes' ConversionConstant (counts per position unit) that is
`(SlaveCounts / MasterCounts) * (CC_master / CC_slave)` slave units per master unit.

MCD completes in the executing scan (DN at once, no IP); the change takes effect at the
next update (decision 0103).
"""

from __future__ import annotations

import math

from ..motion import GeneratorKind, MotionError
from ..runtime.motion import Tracked
from ..runtime.motion_layout import set_bits
from ..vm.context import ExecContext
from .motion_common import (
    PER_MASTER_UNIT,
    PERCENT_OF_MAX,
    PERCENT_OF_TIME,
    PERCENT_OF_TIME_MD,
    UNITS_PER_SEC,
    begin,
    clear_on_prescan,
    fail,
    failed,
    jerk_value,
    real,
    runtime,
    whole,
)
from .registry import implements, prescan

# MAG faceplate indices (EXERR of error 13)
_MASTER, _COUNTS, _RATIO_FORMAT, _CLUTCH, _ACCEL, _ACCEL_UNITS = 1, 6, 8, 9, 10, 11
_CLUTCH_ENABLED = 0  # Clutch enumeration: 0 Enabled, 1 Disabled


@implements("MAG")
def mag(
    ctx: ExecContext, rung: bool, slave: list, master: list, ctl: list, direction: int,
    ratio: float, slave_counts: int, master_counts: int, master_reference: int,
    ratio_format: int, clutch: int, accel_rate: float, accel_units: int,
) -> None:  # fmt: skip
    if not begin(ctl, rung):
        return
    rt = runtime(ctx)
    sa, ma = rt.axis(slave), rt.axis(master)
    if sa is None or ma is None:
        fail(rt, ctl, MotionError.AXIS_NOT_CONFIGURED)
        return
    if sa.group is not ma.group:  # gearing needs both axes in one planner
        fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, _MASTER)
        return
    rt.refresh(sa)
    fmt = whole(ratio_format)
    if fmt not in (0, 1):
        fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, _RATIO_FORMAT)
        return
    if fmt == 0:
        units_ratio = real(ratio)
    else:
        sc, mc = whole(slave_counts), whole(master_counts)
        if mc <= 0 or sc < 0:
            fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, _COUNTS - (mc > 0))
            return
        cc_s = sa.layout.get(sa.value, "ConversionConstant") or 1.0
        cc_m = ma.layout.get(ma.value, "ConversionConstant") or 1.0
        units_ratio = sc / mc * cc_m / cc_s
    cl, au = whole(clutch), whole(accel_units)
    if cl not in (0, 1):
        fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, _CLUTCH)
        return
    if au not in (UNITS_PER_SEC, PERCENT_OF_MAX):
        fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, _ACCEL_UNITS)
        return
    accel = math.inf
    if cl == _CLUTCH_ENABLED:
        accel = real(accel_rate)
        if au == PERCENT_OF_MAX:
            accel *= sa.layout.get(sa.value, "MaximumAccel") / 100.0
        if not (math.isfinite(accel) and accel > 0.0):
            fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, _ACCEL)
            return
    g = sa.group
    r = g.core.start_gear(
        sa.index, ma.index, whole(direction), units_ratio, whole(master_reference), accel
    )
    if failed(rt, ctl, r):
        return
    rt.track(g, r.handle, Tracked(ctl, (sa,)))
    set_bits(ctl, DN=1, IP=1)


# MCD faceplate indices: Change flags 3, 5, 7, 9, 11 (each followed by its value), units 13..16
_MCD_SPEED_UNITS = 13
_MASTER_UNITS = (PER_MASTER_UNIT, PERCENT_OF_TIME_MD)


@implements("MCD")
def mcd(
    ctx: ExecContext, rung: bool, axis: list, ctl: list, motion_type: int, change_speed: int,
    speed: float, change_accel: int, accel_rate: float, change_decel: int, decel_rate: float,
    change_accel_jerk: int, accel_jerk: float, change_decel_jerk: int, decel_jerk: float,
    speed_units: int, accel_units: int, decel_units: int, jerk_units: int,
) -> None:  # fmt: skip
    if not begin(ctl, rung):
        return
    rt = runtime(ctx)
    ax = rt.axis(axis)
    if ax is None:
        fail(rt, ctl, MotionError.AXIS_NOT_CONFIGURED)
        return
    rt.refresh(ax)
    mt = whole(motion_type)
    if mt not in (0, 1):  # ChangeMotionType: 0 Jog, 1 Move
        fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, 2)
        return
    flags = [whole(f) for f in (change_speed, change_accel, change_decel)]
    flags += [whole(change_accel_jerk), whole(change_decel_jerk)]
    for k, f in enumerate(flags):
        if f not in (0, 1):
            fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, 3 + 2 * k)
            return
    units = [whole(u) for u in (speed_units, accel_units, decel_units, jerk_units)]
    rate_units = (UNITS_PER_SEC, PERCENT_OF_MAX, PER_MASTER_UNIT)
    allowed = (rate_units,) * 3 + ((*rate_units, PERCENT_OF_TIME, PERCENT_OF_TIME_MD),)
    for k, (u, ok) in enumerate(zip(units, allowed, strict=True)):
        if u not in ok:
            fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, _MCD_SPEED_UNITS + k)
            return
    core, i = ax.group.core, ax.index
    kind = GeneratorKind.JOG if mt == 0 else GeneratorKind.MOVE
    running = core.running_limits(i, kind)
    # the units of every changed value must be of the running motion's mode (else 94)
    used = [u for u, f in zip(units[:3], flags[:3], strict=True) if f] + (
        [units[3]] if flags[3] or flags[4] else []
    )
    modes = {u in _MASTER_UNITS for u in used}
    if len(modes) > 1 or (running is not None and modes and modes != {running[1]}):
        fail(rt, ctl, MotionError.MDSC_UNITS_CONFLICT)
        return
    get, v = ax.layout.get, ax.value
    values: list[float | None] = []
    for flag, value, unit, maximum in (
        (flags[0], speed, units[0], "MaximumSpeed"),
        (flags[1], accel_rate, units[1], "MaximumAccel"),
        (flags[2], decel_rate, units[2], "MaximumDecel"),
    ):
        x = real(value)
        values.append(
            (x * get(v, maximum) / 100.0 if unit == PERCENT_OF_MAX else x) if flag else None
        )
    new_speed, new_accel, new_decel = values
    jerks: list[float | None] = [None, None]
    for k, (flag, value, maximum) in enumerate(
        ((flags[3], accel_jerk, "MaximumAccelJerk"), (flags[4], decel_jerk, "MaximumDecelJerk"))
    ):
        if not flag:
            continue
        lim = running[0] if running is not None else None
        spd = new_speed if new_speed is not None else (lim.speed if lim else 0.0)
        rate = (new_accel, new_decel)[k]
        if rate is None:
            rate = (lim.accel, lim.decel)[k] if lim else math.inf
        j = jerk_value(real(value), units[3], rate, spd, get(v, maximum))
        if j is None:
            fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, 10 + 2 * k)
            return
        jerks[k] = j
    r = core.change_dynamics(i, kind, new_speed, new_accel, new_decel, jerks[0], jerks[1])
    if failed(rt, ctl, r):
        return
    rt.own(ctl)  # completes in this scan: no process bits to follow
    set_bits(ctl, DN=1)


@prescan("MAG")
def _prescan_mag(
    ctx: ExecContext, rung: bool, slave: list, master: list, ctl: list, *rest: object
) -> None:
    clear_on_prescan(ctl)


@prescan("MCD")
def _prescan_mcd(ctx: ExecContext, rung: bool, axis: list, ctl: list, *rest: object) -> None:
    clear_on_prescan(ctl)
