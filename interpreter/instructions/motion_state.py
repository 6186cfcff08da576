"""Motion state instructions: MSO (servo on), MSF (servo off), MAFR (axis fault reset).

A drive axis (AXIS_CIP_DRIVE and its aliases) completes the request at the next planner
update (DN then, as the drive message takes a coarse update); a virtual axis has no drive,
so the instruction completes in the executing scan with no effect (SPEC 9.25).
MSO/MSF/MAFR have no IP or PC bits.
"""

from __future__ import annotations

from ..runtime.motion import Axis, MotionRuntime
from ..runtime.motion_layout import set_bits
from ..vm.context import ExecContext
from .motion_common import begin, clear_on_prescan, configured, runtime
from .registry import implements, prescan


def _complete(rt: MotionRuntime, ax: Axis, ctl: list, handle: int) -> None:
    if ax.group.core.virtual[ax.index]:
        set_bits(ctl, DN=1)
        return
    g = ax.group
    rt.own(ctl, g, handle)

    def done() -> None:  # unless a later execution took the control over
        if rt.owns(ctl, g, handle):
            set_bits(ctl, DN=1)

    rt.after_update(g, done)


@implements("MSO")
def mso(ctx: ExecContext, rung: bool, axis: list, ctl: list) -> None:
    if not begin(ctl, rung):
        return
    rt = runtime(ctx)
    ax = configured(rt, ctl, rt.axis(axis))
    if ax is not None:
        _complete(rt, ax, ctl, ax.group.core.servo_on_axis(ax.index).handle)


@implements("MSF")
def msf(ctx: ExecContext, rung: bool, axis: list, ctl: list) -> None:
    if not begin(ctl, rung):
        return
    rt = runtime(ctx)
    ax = configured(rt, ctl, rt.axis(axis))
    if ax is not None:
        _complete(rt, ax, ctl, ax.group.core.servo_off_axis(ax.index).handle)


@implements("MAFR")
def mafr(ctx: ExecContext, rung: bool, axis: list, ctl: list) -> None:
    """The simulated axes never fault, so the reset only completes (no fault to clear)."""
    if not begin(ctl, rung):
        return
    rt = runtime(ctx)
    ax = configured(rt, ctl, rt.axis(axis))
    if ax is not None:
        _complete(rt, ax, ctl, rt.token(ax.group))


@prescan("MSO", "MSF", "MAFR")
def _prescan(ctx: ExecContext, rung: bool, axis: list, ctl: list) -> None:
    clear_on_prescan(ctl)
