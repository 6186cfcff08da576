"""Axis position instructions: MAH (home the axis) and MRP (redefine its position).

Both take effect at the next planner update (SPEC 9.3). MRP sets DN after that update (the
request needs a coarse update, as the reference says DN is not set at once); it has no IP.
MAH sets DN and IP in the executing scan and PC (IP cleared) when homing completes; its
behaviour follows the axis's HomeMode, HomeSequence and HomePosition members
(interpreter/motion/homing.py, decision 0103).
"""

from __future__ import annotations

from ..motion import MotionError
from ..runtime.motion import Tracked
from ..runtime.motion_layout import set_bits
from ..vm.context import ExecContext
from .motion_common import (
    clear_on_prescan,
    fail,
    failed,
    real,
    start_on_axis,
    whole,
)
from .registry import implements, prescan

_MRP_TYPE = 2  # faceplate index of Type (EXERR)


@implements("MAH")
def mah(ctx: ExecContext, rung: bool, axis: list, ctl: list) -> None:
    started = start_on_axis(ctx, rung, axis, ctl)
    if started is None:
        return
    rt, ax = started
    get, v = ax.layout.get, ax.value
    r = ax.group.core.home(
        ax.index, int(get(v, "HomeMode")), int(get(v, "HomeSequence")), get(v, "HomePosition")
    )
    if failed(rt, ctl, r):
        return
    rt.track(ax.group, r.handle, Tracked(ctl, pc=True))
    set_bits(ctl, DN=1, IP=1)


@implements("MRP")
def mrp(
    ctx: ExecContext, rung: bool, axis: list, ctl: list, type_: int, select: int, position: float
) -> None:
    started = start_on_axis(ctx, rung, axis, ctl)
    if started is None:
        return
    rt, ax = started
    kind = whole(type_)
    if kind not in (0, 1):  # RedefineType: 0 Absolute, 1 Relative
        fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, _MRP_TYPE)
        return
    g = ax.group
    r = g.core.redefine_position(ax.index, kind == 1, whole(select), real(position))
    if failed(rt, ctl, r):
        return
    rt.own(ctl, g, r.handle)

    def done() -> None:  # unless a later execution took the control over
        if rt.owns(ctl, g, r.handle):
            set_bits(ctl, DN=1)

    rt.after_update(g, done)


@prescan("MAH", "MRP")
def _prescan(ctx: ExecContext, rung: bool, axis: list, ctl: list, *rest: object) -> None:
    clear_on_prescan(ctl)
