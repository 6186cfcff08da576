"""Motion event instructions: MAW (arm a watch-position event) and MDW (disarm it).

MAW sets DN and IP in the executing scan, arms the watch in the core at once and shows it
on the axis: WatchEventArmedStatus set, WatchEventStatus cleared, WatchPosition the armed
position. At the first planner update where the actual position has passed the watch
position in the armed direction, the event occurs: PC set, IP cleared, WatchEventStatus
set and WatchEventArmedStatus cleared. A later MAW on the axis replaces the watch (the
earlier instruction's IP clears at the next update, without PC); MDW disarms it and clears
both status bits at once (docs/decisions/0065-motion-shutdown-watch-strobe.md).
"""

from __future__ import annotations

import math

from ..motion import MotionError
from ..runtime.motion import Group, Tracked
from ..runtime.motion_layout import set_bits
from ..vm.context import ExecContext
from ..vm.values import f32, wrap
from .motion_common import begin, clear_on_prescan, configured, fail, real, runtime, whole
from .motion_state import set_tag_bits
from .registry import implements, prescan

# MAW faceplate indices (EXERR): Axis 0, MotionControl 1, TriggerCondition 2, Position 3
_MAW_TRIGGER, _MAW_POSITION = 2, 3
FORWARD, REVERSE = 0, 1  # WatchTriggerCondition (stdlib/instructions/motion_event.toml)


@implements("MAW")
def maw(
    ctx: ExecContext, rung: bool, axis: list, ctl: list, trigger: object, position: object
) -> None:
    if not begin(ctl, rung):
        return
    rt = runtime(ctx)
    ax = configured(rt, ctl, rt.axis(axis))
    if ax is None:
        return
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

    rt.track(ax.group, r.handle, Tracked("MAW", ctl, None, on_end=on_end))
    set_bits(ctl, DN=1, IP=1)


@implements("MDW")
def mdw(ctx: ExecContext, rung: bool, axis: list, ctl: list) -> None:
    if not begin(ctl, rung):
        return
    rt = runtime(ctx)
    ax = configured(rt, ctl, rt.axis(axis))
    if ax is None:
        return
    ax.group.core.disarm_watch(ax.index)
    set_tag_bits(ax, WatchEventArmedStatus=0, WatchEventStatus=0)
    set_bits(ctl, DN=1)


@prescan("MAW", "MDW")
def _prescan(ctx: ExecContext, rung: bool, axis: list, ctl: list, *rest: object) -> None:
    clear_on_prescan(ctl)
