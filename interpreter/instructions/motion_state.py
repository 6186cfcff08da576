"""Motion state instructions: MSO (servo on), MSF (servo off), MAFR (axis fault reset),
MASD/MASR (axis shutdown and its reset), MGSD/MGSR and MCSD/MCSR (the same for every axis
of a group or of a coordinate system) and MGSP (group strobe position).

A drive axis (AXIS_CIP_DRIVE and its aliases) completes the request at the next planner
update (DN then, as the drive message takes a coarse update); a virtual axis has no drive,
so the instruction completes in the executing scan with no effect (SPEC 9.25).
MSO/MSF/MAFR have no IP or PC bits. The shutdown instructions follow the same rule (a
group completes at the next update when it has a drive axis); ShutdownStatus shows on the
axis tag at once. MGSP completes in the executing scan: each axis's strobe attributes take
the positions the tag shows, which are those of the latest planner update
(docs/decisions/0065-motion-shutdown-watch-strobe.md).
"""

from __future__ import annotations

from ..motion import MotionError
from ..runtime.motion import Axis, Group, MotionRuntime
from ..runtime.motion_layout import pack, packed_words, set_bits, struct_type
from ..vm.context import ExecContext
from ..vm.values import f32
from .motion_common import (
    begin,
    clear_on_prescan,
    configured,
    fail,
    runtime,
    start_on_axis,
    start_on_group,
)
from .registry import implements, prescan


def _end_direct(rt: MotionRuntime, ax: Axis) -> None:
    """MSO, MSF and a shutdown also end MDO's direct drive state (motion_drive.py)."""
    from .motion_drive import end_direct_drive  # motion_drive uses set_tag_bits from here

    end_direct_drive(rt, ax)


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


@implements("MSF")
def msf(ctx: ExecContext, rung: bool, axis: list, ctl: list) -> None:
    if not begin(ctl, rung):
        return
    rt = runtime(ctx)
    ax = configured(rt, ctl, rt.axis(axis))
    if ax is not None:
        _end_direct(rt, ax)
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


@implements("MSO")
def mso(ctx: ExecContext, rung: bool, axis: list, ctl: list) -> None:
    started = start_on_axis(ctx, rung, axis, ctl)
    if started is None:
        return
    rt, ax = started
    r = ax.group.core.servo_on_axis(ax.index)
    if not r.ok:  # a shut-down axis refuses servo on (error 7) until MASR
        fail(rt, ctl, r.error)
        return
    _end_direct(rt, ax)
    _complete(rt, ax, ctl, r.handle)


def set_tag_bits(ax: Axis, **bits: int) -> None:
    """Show BOOL members on the axis tag at once, with the packed word they belong to."""
    v, ix = ax.value, ax.layout.index
    names = set()
    for name, on in bits.items():
        v[ix[name.upper()]] = 1 if on else 0
        names.add(ix[name.upper()])
    for word, members in _axis_words(ax):
        if any(idx in names for idx, _ in members):
            pack(v, word, members)


def _axis_words(ax: Axis) -> tuple[tuple[int, tuple[tuple[int, int], ...]], ...]:
    return packed_words("AXIS_VIRTUAL" if ax.group.core.virtual[ax.index] else "AXIS_CIP_DRIVE")


def _group_done(
    rt: MotionRuntime, g: Group, ctl: list, handle: int, axes: list[Axis] | None = None
) -> None:
    """A group request completes at the next update when a drive takes part, else at once."""
    if all(g.core.virtual[ax.index] for ax in (g.axes if axes is None else axes)):
        set_bits(ctl, DN=1)
        return
    rt.own(ctl, g, handle)

    def done() -> None:
        if rt.owns(ctl, g, handle):
            set_bits(ctl, DN=1)

    rt.after_update(g, done)


@implements("MASD")
def masd(ctx: ExecContext, rung: bool, axis: list, ctl: list) -> None:
    if not begin(ctl, rung):
        return
    rt = runtime(ctx)
    ax = configured(rt, ctl, rt.axis(axis))
    if ax is not None:
        r = ax.group.core.shutdown_axis(ax.index)
        _end_direct(rt, ax)
        set_tag_bits(ax, ShutdownStatus=1)
        _complete(rt, ax, ctl, r.handle)


@implements("MASR")
def masr(ctx: ExecContext, rung: bool, axis: list, ctl: list) -> None:
    if not begin(ctl, rung):
        return
    rt = runtime(ctx)
    ax = configured(rt, ctl, rt.axis(axis))
    if ax is not None:
        r = ax.group.core.reset_shutdown(ax.index)
        set_tag_bits(ax, ShutdownStatus=0)
        _complete(rt, ax, ctl, r.handle)


def _group_shutdown(ctx: ExecContext, rung: bool, group: list, ctl: list, down: bool) -> None:
    """MGSD (down) / MGSR: shut down or reset every axis of the group; done in this scan."""
    started = start_on_group(ctx, rung, group, ctl)
    if started is None:
        return
    rt, g = started
    for ax in g.axes:
        if down:
            g.core.shutdown_axis(ax.index)
            _end_direct(rt, ax)
        else:
            g.core.reset_shutdown(ax.index)
        set_tag_bits(ax, ShutdownStatus=1 if down else 0)
    _group_done(rt, g, ctl, rt.token(g))


@implements("MGSD")
def mgsd(ctx: ExecContext, rung: bool, group: list, ctl: list) -> None:
    _group_shutdown(ctx, rung, group, ctl, down=True)


@implements("MGSR")
def mgsr(ctx: ExecContext, rung: bool, group: list, ctl: list) -> None:
    _group_shutdown(ctx, rung, group, ctl, down=False)


@implements("MGSP")
def mgsp(ctx: ExecContext, rung: bool, group: list, ctl: list) -> None:
    started = start_on_group(ctx, rung, group, ctl)
    if started is None:
        return
    rt, g = started
    core = g.core
    for ax in g.axes:
        v, ix = ax.value, ax.layout.index
        v[ix["STROBEACTUALPOSITION"]] = f32(float(core.actual_position[ax.index]))
        v[ix["STROBECOMMANDPOSITION"]] = f32(float(core.command_position[ax.index]))
        v[ix["STROBEMASTEROFFSET"]] = v[ix["MASTEROFFSET"]]
    set_bits(ctl, DN=1)


_CS = struct_type("COORDINATE_SYSTEM")
_CS_WORDS = packed_words("COORDINATE_SYSTEM")


def _system_axes(rt: MotionRuntime, cs: list) -> list[Axis] | None:
    """The axes a COORDINATE_SYSTEM tag names (None when one is not a configured axis)."""
    names = [a.upper() for a in cs[_CS.index["AXES"]] if isinstance(a, str) and a]
    by_name = {ax.name.upper(): ax for g in rt.groups for ax in g.axes}
    axes = [by_name.get(n) for n in names]
    if not axes or any(ax is None for ax in axes):
        return None
    return [ax for ax in axes if ax is not None]


def _system_shutdown(cs: list, on: int) -> None:
    at = _CS.index["SHUTDOWNSTATUS"]
    cs[at] = on
    for word, members in _CS_WORDS:
        if any(idx == at for idx, _ in members):
            pack(cs, word, members)


def _coordinate_shutdown(ctx: ExecContext, rung: bool, cs: list, ctl: list, on: bool) -> None:
    if not begin(ctl, rung):
        return
    rt = runtime(ctx)
    axes = _system_axes(rt, cs)
    if axes is None:  # a system without configured axes: error 11, as for an axis
        fail(rt, ctl, MotionError.AXIS_NOT_CONFIGURED)
        return
    for ax in axes:
        core = ax.group.core
        core.shutdown_axis(ax.index) if on else core.reset_shutdown(ax.index)
        set_tag_bits(ax, ShutdownStatus=int(on))
    _system_shutdown(cs, int(on))
    g = axes[0].group
    _group_done(rt, g, ctl, rt.token(g), axes)


@implements("MCSD")
def mcsd(ctx: ExecContext, rung: bool, cs: list, ctl: list) -> None:
    """Shut down every axis of a coordinate system, and show it on the system's status."""
    _coordinate_shutdown(ctx, rung, cs, ctl, True)


@implements("MCSR")
def mcsr(ctx: ExecContext, rung: bool, cs: list, ctl: list) -> None:
    _coordinate_shutdown(ctx, rung, cs, ctl, False)


@prescan("MSO", "MSF", "MAFR", "MASD", "MASR", "MGSD", "MGSR", "MGSP", "MCSD", "MCSR")
def _prescan(ctx: ExecContext, rung: bool, target: list, ctl: list) -> None:
    clear_on_prescan(ctl)
