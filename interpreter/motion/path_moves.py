"""Coordinated path requests (MCLM, MCCM, MCS): the start calls of the path kind.

The path set and its numpy stepping live in paths.py (PathSet); here are the requests that
register coordinate systems, queue, merge and stop path moves. Each function takes the
group as its first argument; MotionGroup binds them as methods of the same name (decision
0104), as moves.py does for generators.py. Decisions 0122..0125.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import replace
from typing import TYPE_CHECKING

import numpy as np

from interpreter.motion.enums import MergeMode, StopType
from interpreter.motion.errors import MotionError, StartResult
from interpreter.motion.path_geometry import Segment
from interpreter.motion.paths import Build, CoordSystem, PathMove
from interpreter.motion.process import Ending, Events
from interpreter.motion.profiles import Limits, MoveProfile

if TYPE_CHECKING:  # bound as MotionGroup methods; only the annotations need the class
    from interpreter.motion.group import MotionGroup

_EPS = 1e-9  # speeds and lengths below this are zero


def add_coordinate_system(group: MotionGroup, axes: list[int]) -> int:
    """Register a coordinate system of 2 or 3 of the group's axes; returns its index."""
    group.paths.systems.append(CoordSystem(tuple(axes)))
    group.paths.changed()
    if group.paths.snap is None:
        group.paths.snap = lambda ax, end: _snap(group, ax, end)
    return len(group.paths.systems) - 1


def _snap(group: MotionGroup, axes: tuple[int, ...], end: np.ndarray) -> None:
    """A path ended with nothing else moving its axes: the command position is its end
    point to rounding (1e-9 relative); make it the end point itself. Anything else moving
    an axis keeps it away from the end, and then nothing changes."""
    idx = list(axes)
    delta = np.asarray(end, dtype=float) - group.command_position[idx]
    if np.all(np.abs(delta) <= 1e-9 * np.maximum(1.0, np.abs(end))):
        group.command_position[idx] += delta
        virtual = group.virtual[idx]
        group.actual_position[idx] = np.where(
            virtual, group.command_position[idx], group.actual_position[idx]
        )


def path_start_point(group: MotionGroup, cs_id: int) -> np.ndarray:
    """Where a move executed now starts: the end of the last accepted move, else the
    command position of the axes."""
    cs = group.paths.systems[cs_id]
    end = cs.end_point()
    if end is not None:
        return np.array(end, dtype=float)
    return group.command_position[list(cs.axes)].astype(float)


def start_path(
    group: MotionGroup,
    cs_id: int,
    segment: Segment,
    limits: Limits,
    termination: int,
    tolerance: float,
    merge: int,
    merge_current: bool,
    rebuild: Build | None = None,
    decel_jerk_percent: float | None = None,
) -> StartResult:
    """MCLM/MCCM with a validated segment from path_start_point. Merge Disabled queues
    behind the active move (one deep, else error 43); a merge ends the running and queued
    coordinated moves (All: also the axes' single-axis motion) at the next update and
    continues from there with the speed along the new path (Current: at that speed).
    decel_jerk_percent: the S-curve decel jerk was given in % of Time; a merge that starts
    at speed V0 takes it from max(V, |V0 - V|) instead of V (SPEC 9.28)."""
    paths = group.paths
    cs = paths.systems[cs_id]
    # every primary axis must be able to move, as for single-axis moves; EXERR names the
    # first one that cannot by its index in the system (MCCM seed, decision 0140)
    for k, ax in enumerate(cs.axes):
        if group.shutdown[ax]:
            return StartResult(error=MotionError.SHUTDOWN_STATE, exerr=k)
        if not group.servo_on[ax]:
            return StartResult(error=MotionError.SERVO_OFF_STATE, exerr=k)
    h = group.new_handle()
    mv = PathMove(h, cs_id, segment, limits, termination, tolerance)
    if merge == MergeMode.DISABLED:
        busy = (cs.lead is not None and cs.stop == 0) + len(cs.queue)
        if busy >= 2:
            return StartResult(error=MotionError.COORDINATE_SYSTEM_QUEUE_FULL)
        cs.queue.append(mv)
        paths.changed()
        return StartResult(handle=h)

    def apply(ev: Events) -> None:
        paths._sync_out()
        axes = list(cs.axes)
        vel = group.command_velocity[axes].astype(float)
        paths._end_all(cs, ev)
        if merge == MergeMode.ALL:
            for ax in axes:
                _, _ = group.end_axis(ax, Ending.MERGE_ALL, ev)
        start = group.command_position[axes].astype(float)
        seg = mv.segment
        if rebuild is not None:  # the system has moved since the execution
            again = rebuild(start)
            if isinstance(again, Segment):
                seg = again
        mv.segment = seg
        tan = seg.tangent(np.array([0.0]))[0] if seg.length > _EPS else np.zeros(len(axes))
        v0 = max(float(vel @ tan), 0.0)
        lim = limits
        if merge_current and v0 > _EPS:
            lim = replace(lim, speed=float(np.linalg.norm(vel)))
        if decel_jerk_percent is not None and math.isfinite(lim.decel_jerk) and lim.speed > 0:
            ref = max(lim.speed, abs(v0 - lim.speed))
            jd = lim.decel * lim.decel / ref * (200.0 / decel_jerk_percent - 1.0)
            lim = replace(lim, decel_jerk=jd if jd > 0.0 else math.inf)
        mv.limits = lim
        paths.start_row(cs, mv, v0, ev)

    group.after_update(apply)
    return StartResult(handle=h)


def stop_path(
    group: MotionGroup,
    cs_id: int,
    stop_all: bool,
    decel: float,
    jerk: float,
) -> StartResult:
    """MCS: at the next update the system decelerates to rest along its path (All: the
    single-axis motion of its axes stops too, with their configured limits)."""
    h = group.new_handle()
    paths = group.paths
    cs = paths.systems[cs_id]

    def apply(ev: Events) -> None:
        paths._sync_out()
        paths.stop_system(cs_id, h, decel, jerk, ev)

    group.after_update(apply)
    if stop_all:
        # requested now, so they apply at the same update as the path stop (SPEC 9.3), after
        # it: the stopping system is then left alone by the axes' stops
        for ax in cs.axes:
            group.stop(ax, StopType.ALL)
    return StartResult(handle=h)


# a jerk operand resolved per move: (rate it shapes, the move's speed) -> jerk in units/s^3
# (% of Time depends on both; units and % of maximum ignore them)
JerkOf = Callable[[float, float], float]


def change_path_dynamics(
    group: MotionGroup,
    cs_id: int,
    speed: float | None,
    accel: float | None,
    decel: float | None,
    accel_jerk: JerkOf | None,
    decel_jerk: JerkOf | None,
    pending: bool,
) -> StartResult:
    """MCCD: at the next update the active coordinated move of the system is planned again
    from its present path position and speed with the changed limits (None: unchanged) and
    keeps its end point and termination; pending: the queued move takes them too. Jerks
    only change S-curve moves. A system with nothing running (or stopping) is left as is."""
    h = group.new_handle()
    paths = group.paths
    cs = paths.systems[cs_id]

    def new_limits(old: Limits) -> Limits:
        lim = replace(
            old,
            speed=old.speed if speed is None else speed,
            accel=old.accel if accel is None else accel,
            decel=old.decel if decel is None else decel,
        )
        if math.isinf(old.accel_jerk) and math.isinf(old.decel_jerk):
            return lim  # trapezoidal: no jerk to change
        return replace(
            lim,
            accel_jerk=lim.accel_jerk if accel_jerk is None else accel_jerk(lim.accel, lim.speed),
            decel_jerk=lim.decel_jerk if decel_jerk is None else decel_jerk(lim.decel, lim.speed),
        )

    def apply(ev: Events) -> None:
        paths._sync_out()
        lead = cs.lead
        if lead is not None and cs.stop == 0 and lead.owner == lead.handle:
            if not lead.settling:  # settling: its path is done, nothing left to change
                paths.replan(lead, new_limits(lead.limits))
        if pending:
            for q in cs.queue:
                q.limits = new_limits(q.limits)
        paths.changed()

    group.after_update(apply)
    return StartResult(handle=h)


def path_trajectory(
    segment: Segment, profile: MoveProfile, t: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Points (len(t), ndim) and vector speeds of a move run from rest at times t (plots,
    tests): the whole trajectory in one call."""
    s, v, _ = profile.evaluate(np.asarray(t, dtype=float))
    return segment.points(s), v
