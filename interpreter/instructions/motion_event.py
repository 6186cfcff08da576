"""Motion event instructions: MAW (arm a watch-position event) and MDW (disarm it), MAR
(arm registration) and MDR (disarm it).

MAW sets DN and IP in the executing scan, arms the watch in the core at once and shows it
on the axis: WatchEventArmedStatus set, WatchEventStatus cleared, WatchPosition the armed
position. At the first planner update where the actual position has passed the watch
position in the armed direction, the event occurs: PC set, IP cleared, WatchEventStatus
set and WatchEventArmedStatus cleared. A later MAW on the axis replaces the watch (the
earlier instruction's IP clears at the next update, without PC); MDW disarms it and clears
both status bits at once (docs/decisions/0065-motion-shutdown-watch-strobe.md).

Registration latches the position on an edge of a physical input. Nothing is wired to the
simulated controller's inputs (SPEC 9.32), so MAR arms (DN, IP, RegEventNArmedStatus) and
waits; MDR disarms it (the MAR's IP clears at the next update, without PC).
"""

from __future__ import annotations

import math

from ..motion import MotionError
from ..runtime.motion import Group, Tracked
from ..runtime.motion_layout import set_bits
from ..vm.context import ExecContext
from ..vm.values import f32, wrap
from .motion_common import (
    clear_on_prescan,
    fail,
    real,
    start_on_axis,
    whole,
)
from .motion_state import set_tag_bits
from .registry import implements, prescan

# MAW faceplate indices (EXERR): Axis 0, MotionControl 1, TriggerCondition 2, Position 3
_MAW_TRIGGER, _MAW_POSITION = 2, 3
FORWARD, REVERSE = 0, 1  # WatchTriggerCondition (stdlib/instructions/motion_event.toml)


@implements("MAW")
def maw(
    ctx: ExecContext, rung: bool, axis: list, ctl: list, trigger: object, position: object
) -> None:
    started = start_on_axis(ctx, rung, axis, ctl)
    if started is None:
        return
    rt, ax = started
    tc = whole(trigger)
    if tc not in (FORWARD, REVERSE):
        fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, _MAW_TRIGGER)
        return
    pos = real(position)
    if not math.isfinite(pos):
        fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, _MAW_POSITION)
        return
    pos = f32(pos)  # the watch compares against the REAL the axis shows as WatchPosition
    r = ax.group.core.arm_watch(ax.index, pos, tc == FORWARD)
    ax.value[ax.layout.index["WATCHPOSITION"]] = pos
    set_tag_bits(ax, WatchEventArmedStatus=1, WatchEventStatus=0)

    def on_end(g: Group, completed: bool) -> None:
        if completed:  # a replaced or disarmed watch leaves the bits to its successor
            set_tag_bits(ax, WatchEventArmedStatus=0, WatchEventStatus=1)
            # WatchTime: the CST (µs, low 32 bits) of the update that saw the crossing
            ax.value[ax.layout.index["WATCHTIME"]] = wrap(round(g.core.time * 1e6), 32, True)

    rt.track(ax.group, r.handle, Tracked(ctl, pc=True, on_end=on_end))
    set_bits(ctl, DN=1, IP=1)


@implements("MDW")
def mdw(ctx: ExecContext, rung: bool, axis: list, ctl: list) -> None:
    started = start_on_axis(ctx, rung, axis, ctl)
    if started is None:
        return
    rt, ax = started
    ax.group.core.disarm_watch(ax.index)
    set_tag_bits(ax, WatchEventArmedStatus=0, WatchEventStatus=0)
    set_bits(ctl, DN=1)


@prescan("MAW", "MDW")
def _prescan(ctx: ExecContext, rung: bool, axis: list, ctl: list, *rest: object) -> None:
    clear_on_prescan(ctl)


# MAR faceplate indices (EXERR): Axis 0, MotionControl 1, TriggerCondition 2,
# WindowedRegistration 3, MinimumPosition 4, MaximumPosition 5, InputNumber 6
_MAR_TRIGGER, _MAR_WINDOWED, _MAR_MIN, _MAR_MAX, _MAR_INPUT = 2, 3, 4, 5, 6
_MDR_INPUT = 2


def _input_number(value: object) -> int | None:
    n = whole(value)
    return n if n in (1, 2) else None


@implements("MAR")
def mar(
    ctx: ExecContext, rung: bool, axis: list, ctl: list, trigger: object, windowed: object,
    minimum: object, maximum: object, input_number: object = 1,
) -> None:  # fmt: skip
    """Arm registration: DN and IP at once, RegEventNArmedStatus set and RegEventNStatus
    cleared. No edge ever reaches the simulated inputs, so the event does not occur."""
    started = start_on_axis(ctx, rung, axis, ctl)
    if started is None:
        return
    rt, ax = started
    lo, hi = real(minimum), real(maximum)
    checks = (
        (whole(trigger) in (0, 1), _MAR_TRIGGER),
        (whole(windowed) in (0, 1), _MAR_WINDOWED),
        (math.isfinite(lo), _MAR_MIN),
        (math.isfinite(hi) and (whole(windowed) != 1 or hi > lo), _MAR_MAX),
        (_input_number(input_number) is not None, _MAR_INPUT),
    )
    for ok, index in checks:
        if not ok:
            fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, index)
            return
    n = whole(input_number)
    r = ax.group.core.arm_registration(ax.index, n)
    set_tag_bits(ax, **{f"RegEvent{n}ArmedStatus": 1, f"RegEvent{n}Status": 0})
    rt.track(ax.group, r.handle, Tracked(ctl))
    set_bits(ctl, DN=1, IP=1)


@implements("MDR")
def mdr(ctx: ExecContext, rung: bool, axis: list, ctl: list, input_number: object = 1) -> None:
    started = start_on_axis(ctx, rung, axis, ctl)
    if started is None:
        return
    rt, ax = started
    n = _input_number(input_number)
    if n is None:
        fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, _MDR_INPUT)
        return
    ax.group.core.disarm_registration(ax.index, n)
    set_tag_bits(ax, **{f"RegEvent{n}ArmedStatus": 0, f"RegEvent{n}Status": 0})
    set_bits(ctl, DN=1)


@prescan("MAR", "MDR")
def _prescan_registration(
    ctx: ExecContext, rung: bool, axis: list, ctl: list, *rest: object
) -> None:
    clear_on_prescan(ctl)
