"""Single-axis moves and stops: MAM, MAJ, MAS and the group stop MGS.

Operands arrive in catalog (faceplate) order; EXERR of error 13 is the zero-based faceplate
index. MAM/MAJ set DN and IP in the executing scan; the planner reports the rest: ACCEL /
DECEL during the ramps, PC when a move or stop completes, IP cleared when the motion ends
(completed, replaced, stopped). The rotary move types (shortest path, positive, negative)
need a rotary axis (error 17 on a linear one; decision 0115). Position cams are not
simulated: master offset moves give error 33.
"""

from __future__ import annotations

import math

from ..motion import MergeMode, MotionError, MoveType, StartResult
from ..motion.moves import move_distance
from ..runtime.motion import Axis, Group, MotionRuntime, Tracked
from ..runtime.motion_layout import set_bits
from ..vm.context import ExecContext
from ..vm.refs import ArrayRef
from .motion_common import (
    PERCENT_OF_MAX,
    Dynamics,
    TimeBased,
    begin,
    clear_on_prescan,
    configured,
    dynamics,
    fail,
    failed,
    jerk_value,
    real,
    runtime,
    start_on_group,
    time_based_rates,
    whole,
)
from .registry import implements, prescan

_MASTER_OFFSET_MOVES = (5, 6)
_AT_REST = 1e-9


def _axis(rt: MotionRuntime, ctl: list, axis: list) -> Axis | None:
    """The named axis with its limits read again from the tag; None (error 11) if unknown."""
    ax = configured(rt, ctl, rt.axis(axis))
    if ax is not None:
        rt.refresh(ax)
    return ax


def _move_dynamics(
    rt: MotionRuntime, ctl: list, ax: Axis, first: int, speed: float, speed_units: int,
    accel: float, accel_units: int, decel: float, decel_units: int, profile: int,
    accel_jerk: float, decel_jerk: float, jerk_units: int, merge: int, allow_time_based: bool,
) -> tuple[int, MergeMode, Dynamics | TimeBased] | None:  # fmt: skip
    """The operands MAM and MAJ share, Speed .. Merge (`first` = faceplate index of Speed):
    (profile shape, merge mode, dynamics), or None after reporting the first bad one."""
    shape = whole(profile)
    if shape not in (0, 1):
        fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, first + 6)
        return None
    # Merge: Disabled 0 / Enabled 1 (Enabled takes over all motion of the axis)
    mm = {0: MergeMode.DISABLED, 1: MergeMode.ALL}.get(whole(merge))
    if mm is None:
        fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, first + 10)
        return None
    dyn = dynamics(
        ax, first, real(speed), speed_units, real(accel), accel_units, real(decel), decel_units,
        shape == 1, real(accel_jerk), real(decel_jerk), jerk_units, allow_time_based,
    )  # fmt: skip
    if isinstance(dyn, StartResult):
        failed(rt, ctl, dyn)
        return None
    return shape, mm, dyn


# ------------------------------------------------------------------ MAM
@implements("MAM")
def mam(
    ctx: ExecContext, rung: bool, axis: list, ctl: list, move_type: int, position: float,
    speed: float, speed_units: int, accel: float, accel_units: int, decel: float,
    decel_units: int, profile: int, accel_jerk: float, decel_jerk: float, jerk_units: int,
    merge: int, merge_speed: int, lock_position: float, lock_direction: int,
    event_distance: ArrayRef | None, calculated_data: ArrayRef | None,
) -> None:  # fmt: skip
    if not begin(ctl, rung):
        return
    rt = runtime(ctx)
    ax = _axis(rt, ctl, axis)
    if ax is None:
        return
    core, i = ax.group.core, ax.index
    mt = whole(move_type)
    if mt in _MASTER_OFFSET_MOVES:
        fail(rt, ctl, MotionError.POSITION_CAM_NOT_ENABLED)
        return
    if mt not in MoveType.__members__.values():
        fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, 2)
        return
    if mt >= MoveType.ROTARY_SHORTEST_PATH:  # operand errors first, as the core would
        r = core.check_rotary_move(i, mt, real(position))
        if failed(rt, ctl, r):
            return
    block = _move_dynamics(
        rt, ctl, ax, 4, speed, speed_units, accel, accel_units, decel, decel_units, profile,
        accel_jerk, decel_jerk, jerk_units, merge, allow_time_based=True,
    )  # fmt: skip
    if block is None:
        return
    shape, mm, dyn = block
    if isinstance(dyn, TimeBased):  # a rest-to-rest move lasting the programmed time
        if whole(merge_speed) == 1:
            fail(rt, ctl, MotionError.MERGE_CURRENT_USING_SECONDS)
            return
        if (
            abs(float(core.command_velocity[i])) > _AT_REST
            or abs(float(core.command_acceleration[i])) > _AT_REST
        ):
            fail(rt, ctl, MotionError.AXIS_NOT_AT_REST)
            return
        dist = move_distance(core, i, mt, real(position))
        dyn = time_based_rates(dyn, dist)
    if event_distance is not None and (
        calculated_data is None or len(calculated_data) < len(event_distance)
    ):
        fail(rt, ctl, MotionError.MDSC_CALCULATED_DATA_SIZE)
        return
    r = core.start_move(
        i, mt, real(position), dyn.speed, dyn.accel, dyn.decel, shape, dyn.accel_jerk,
        dyn.decel_jerk, mm, whole(merge_speed), real(lock_position), whole(lock_direction),
        dyn.master_driven,
    )  # fmt: skip
    if failed(rt, ctl, r):
        return
    on_start = None
    if event_distance is not None and calculated_data is not None:
        on_start = _event_points(r.handle, event_distance, calculated_data)
    rt.track(ax.group, r.handle, Tracked(ctl, (ax,), pc=True, on_start=on_start))
    set_bits(ctl, DN=1, IP=1)


def _event_points(handle: int, events: ArrayRef, out: ArrayRef):  # type: ignore[no-untyped-def]
    """CalculatedData[k]: time (master distance) from the move start to EventDistance[k]
    before its end point, found on the planned profile when the move goes in process."""

    def on_start(g: Group) -> None:
        prof = g.core.generator_profile(handle)
        for k in range(len(events)):
            ev = abs(real(events.get(k)))
            t = 0.0
            if prof is not None and math.isfinite(prof.duration):
                total = prof.end_position
                target = abs(total) - ev
                if target > 0.0:
                    lo, hi = 0.0, prof.duration
                    s = 1.0 if total >= 0 else -1.0
                    for _ in range(100):  # bisection: travel along the move is monotone
                        mid = 0.5 * (lo + hi)
                        if s * prof.at(mid)[0] < target:
                            lo = mid
                        else:
                            hi = mid
                    t = hi
            out.set(k, t)

    return on_start


# ------------------------------------------------------------------ MAJ
@implements("MAJ")
def maj(
    ctx: ExecContext, rung: bool, axis: list, ctl: list, direction: int, speed: float,
    speed_units: int, accel: float, accel_units: int, decel: float, decel_units: int,
    profile: int, accel_jerk: float, decel_jerk: float, jerk_units: int, merge: int,
    merge_speed: int, lock_position: float, lock_direction: int,
) -> None:  # fmt: skip
    if not begin(ctl, rung):
        return
    rt = runtime(ctx)
    ax = _axis(rt, ctl, axis)
    if ax is None:
        return
    block = _move_dynamics(
        rt, ctl, ax, 3, speed, speed_units, accel, accel_units, decel, decel_units, profile,
        accel_jerk, decel_jerk, jerk_units, merge, allow_time_based=False,
    )  # fmt: skip
    if block is None:
        return
    shape, mm, dyn = block
    assert isinstance(dyn, Dynamics)  # MAJ has no time-based planning
    r = ax.group.core.start_jog(
        ax.index, whole(direction), dyn.speed, dyn.accel, dyn.decel, shape, dyn.accel_jerk,
        dyn.decel_jerk, mm, whole(merge_speed), real(lock_position), whole(lock_direction),
        dyn.master_driven,
    )  # fmt: skip
    if failed(rt, ctl, r):
        return
    rt.track(ax.group, r.handle, Tracked(ctl, (ax,)))
    set_bits(ctl, DN=1, IP=1)


# ------------------------------------------------------------------ MAS
@implements("MAS")
def mas(
    ctx: ExecContext, rung: bool, axis: list, ctl: list, stop_type: int, change_decel: int,
    decel_rate: float, decel_units: int, change_decel_jerk: int, decel_jerk: float,
    jerk_units: int,
) -> None:  # fmt: skip
    """Stop one kind of motion (or All) with the configured or the given deceleration."""
    if not begin(ctl, rung):
        return
    rt = runtime(ctx)
    ax = _axis(rt, ctl, axis)
    if ax is None:
        return
    core, i, get, v = ax.group.core, ax.index, ax.layout.get, ax.value
    cd, du, cj, ju = (
        whole(change_decel),
        whole(decel_units),
        whole(change_decel_jerk),
        whole(jerk_units),
    )
    for value, ok, index in ((cd, (0, 1), 3), (du, (0, 1), 5), (cj, (0, 1), 6), (ju, (0, 1, 2), 8)):
        if value not in ok:
            fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, index)
            return
    max_decel = get(v, "MaximumDecel")
    if cd == 0:
        if not max_decel > 0.0:
            fail(rt, ctl, MotionError.ZERO_MAX_DECEL)
            return
        decel = max_decel
    else:
        decel = real(decel_rate) * (max_decel / 100.0 if du == PERCENT_OF_MAX else 1.0)
        if not (math.isfinite(decel) and decel > 0.0):
            fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, 4)
            return
    jerk: float | None = None  # the configured maximum decel jerk
    if cj == 1:
        speed = abs(float(core.command_velocity[i]))
        jerk = jerk_value(real(decel_jerk), ju, decel, speed, get(v, "MaximumDecelJerk"))
        if jerk is None:
            fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, 7)
            return
    r = core.stop(i, whole(stop_type), decel, jerk)
    if failed(rt, ctl, r):
        return
    rt.track(ax.group, r.handle, Tracked(ctl, (ax,), pc=True))
    set_bits(ctl, DN=1, IP=1)


# ------------------------------------------------------------------ MGS
FAST_STOP, FAST_DISABLE, HARD_DISABLE, FAST_SHUTDOWN, HARD_SHUTDOWN = range(5)


@implements("MGS")
def mgs(ctx: ExecContext, rung: bool, group: list, ctl: list, stop_mode: int) -> None:
    """Stop every axis of the group: Programmed (each axis's ProgrammedStopMode), Fast Stop
    or Fast Disable. Fast modes decelerate at the configured maximum; Disable turns the
    drive off at rest, Hard modes at once, Shutdown also breaks the axis's MDAC links."""
    started = start_on_group(ctx, rung, group, ctl)
    if started is None:
        return
    rt, g = started
    sm = whole(stop_mode)
    if sm not in (0, 1, 2):
        fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, 2)
        return
    core = g.core
    modes: dict[int, int] = {}
    for ax in g.axes:
        rt.refresh(ax)
        mode = int(ax.layout.get(ax.value, "ProgrammedStopMode")) if sm == 0 else (sm - 1)
        modes[ax.index] = mode if mode in range(5) else FAST_STOP
        if mode == HARD_DISABLE:
            core.servo_off_axis(ax.index)
        elif mode == HARD_SHUTDOWN:
            core.shutdown_axis(ax.index)
    r = core.stop_group()

    def on_end(grp: Group, completed: bool) -> None:
        for axis_index, mode in modes.items():
            if completed and mode == FAST_DISABLE:
                grp.core.servo_off_axis(axis_index)
            elif completed and mode == FAST_SHUTDOWN:
                grp.core.shutdown_axis(axis_index)

    rt.track(g, r.handle, Tracked(ctl, pc=True, on_end=on_end))
    set_bits(ctl, DN=1, IP=1)


@prescan("MAM", "MAJ", "MAS", "MGS")
def _prescan(ctx: ExecContext, rung: bool, target: list, ctl: list, *rest: object) -> None:
    clear_on_prescan(ctl)
