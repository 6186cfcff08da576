"""Coordinated motion on a COORDINATE_SYSTEM: MCLM (line), MCCM (arc) and MCS (stop).

Operands arrive in catalog (faceplate) order; EXERR of error 13 is the zero-based operand
index. DN and IP are set in the executing scan (the move is verified and queued); AC when
the move becomes the active one; PC when it reaches its end (or, blending, when its own
path is done); IP cleared when it ends, is merged away or stopped. The coordinate system's
status members are written with the axis attributes. Decisions 0122..0125.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from stdlib import catalog

from ..motion import MotionError, ProfileShape, StartResult
from ..motion.path_geometry import GeometryError, Segment, circle, line
from ..motion.paths import Termination
from ..motion.profiles import Limits, MoveProfile
from ..runtime.motion import Axis, Group, MotionRuntime, Tracked
from ..runtime.motion_layout import AC, pack, packed_words, set_bits, struct_type
from ..vm.context import ExecContext
from ..vm.refs import ArrayRef
from ..vm.values import f32
from .motion_common import (
    PER_MASTER_UNIT,
    PERCENT_OF_TIME,
    Dynamics,
    begin,
    clear_on_prescan,
    dynamics,
    fail,
    failed,
    jerk_value,
    real,
    runtime,
    whole,
)
from .registry import implements, prescan

_CS = struct_type("COORDINATE_SYSTEM")
_IX = _CS.index
_WORDS = packed_words("COORDINATE_SYSTEM")
_CMD, _ACT = _IX["COMMANDPOSITION"], _IX["ACTUALPOSITION"]
_READY = _IX["READYSTATUS"]
_VCV, _VAV = _IX["VECTORCOMMANDVELOCITY"], _IX["VECTORACTUALVELOCITY"]
_STATUS_MEMBERS = (
    "MotionStatus", "AccelStatus", "DecelStatus", "ActualPosToleranceStatus",
    "CommandPosToleranceStatus", "StoppingStatus", "MoveStatus", "MoveTransitionStatus",
    "MovePendingStatus", "MovePendingQueueFullStatus",
)  # fmt: skip
_TERMINATION_TYPES = frozenset(int(t) for t in Termination)
_STOP_TYPES = catalog().enum("CoordStopType")  # All, Coordinated Move, Coordinated Transform


def _stop_type(text: str) -> int:
    ev = _STOP_TYPES.lookup(text)
    assert ev is not None, text
    return ev.value


_STOP_ALL = _stop_type("All")
_STOP_MOVE = _stop_type("Coordinated Move")
_STOP_TRANSFORM = _stop_type("Coordinated Transform")


@dataclass(eq=False, slots=True)
class System:
    """A COORDINATE_SYSTEM tag bound to its group's core (registered on first use)."""

    value: list
    group: Group
    axes: list[Axis]
    index: int  # in the core's PathSet
    index_of_axes: tuple[int, ...] = ()  # the axes' indices in the group
    seen: int = -1  # PathSet.version whose status the tag shows

    def get(self, name: str) -> float:
        return float(self.value[_IX[name.upper()]])

    def maximum(self, name: str) -> float:
        return self.get(name)

    def refresh(self) -> None:
        """Tolerances and stop limits from the tag (the program may change them)."""
        cs = self.group.core.paths.systems[self.index]
        cs.command_tolerance = max(self.get("CommandTolerance"), 0.0)
        cs.actual_tolerance = max(self.get("ActualTolerance"), 0.0)
        cs.max_decel = _limit(self.get("MaximumDecel"))
        cs.max_decel_jerk = _limit(self.get("MaximumDecelJerk"))


def _limit(x: float) -> float:
    return x if x > 0 else math.inf


def system(rt: MotionRuntime, cs: list) -> System | MotionError:
    """The system a COORDINATE_SYSTEM tag names, bound to its group's core on first use;
    11 when an axis is not a configured axis, 13 when the axes are not 2 or 3 different
    axes of one motion group."""
    bound = rt.attached.get(id(cs))
    if isinstance(bound, System):
        return bound
    names = [a for a in cs[_IX["AXES"]] if isinstance(a, str) and a]
    by_name = {ax.name.upper(): ax for g in rt.groups for ax in g.axes}
    axes = [by_name.get(n.upper()) for n in names]
    if any(ax is None for ax in axes):
        return MotionError.AXIS_NOT_CONFIGURED
    found = [ax for ax in axes if ax is not None]
    if (
        len(found) not in (2, 3)
        or len({id(ax) for ax in found}) != len(found)  # an axis named twice
        or len({id(ax.group) for ax in found}) != 1
    ):
        return MotionError.PARAMETER_OUT_OF_RANGE
    g = found[0].group
    idx = g.core.add_coordinate_system([ax.index for ax in found])
    sysm = System(cs, g, found, idx, tuple(ax.index for ax in found))
    cs[_IX["DIMENSION"]] = len(found)
    rt.attached[id(cs)] = sysm
    g.observers.append(lambda grp: _write_status(sysm))
    _write_status(sysm)
    return sysm


def _write_status(s: System) -> None:
    """Status members, positions and vector velocities of the system into its tag (the
    status only when the path set reports a change)."""
    core = s.group.core
    v = s.value
    paths = core.paths
    # ReadyStatus: every member axis can move (servo on, not shut down; virtual axes are)
    on, down = core.servo_on, core.shutdown
    ready = 1 if all(on[i] and not down[i] for i in s.index_of_axes) else 0
    if s.seen != paths.version or v[_READY] != ready:
        s.seen = paths.version
        v[_READY] = ready
        for name, bit in paths.system_status(s.index).items():
            v[_IX[name.upper()]] = 1 if bit else 0
        for word, members in _WORDS:
            pack(v, word, members)
    cmd, act = v[_CMD], v[_ACT]
    cp, ap = core.command_position, core.actual_position
    cv, av = core.command_velocity, core.actual_velocity
    for k, i in enumerate(s.index_of_axes):
        cmd[k] = f32(float(cp[i]))
        act[k] = f32(float(ap[i]))
    v[_VCV] = f32(math.hypot(*(float(cv[i]) for i in s.index_of_axes)))
    v[_VAV] = f32(math.hypot(*(float(av[i]) for i in s.index_of_axes)))


def _start(
    ctx: ExecContext, rung: bool, cs: list, ctl: list
) -> tuple[MotionRuntime, System] | None:
    """The handshake, then the bound system (errors 11 / 13 EXERR 0 reported)."""
    if not begin(ctl, rung):
        return None
    rt = runtime(ctx)
    s = system(rt, cs)
    if isinstance(s, MotionError):
        fail(rt, ctl, s, 0)
        return None
    s.refresh()
    return rt, s


def _point(arr: object, ndim: int) -> np.ndarray | None:
    """The first ndim elements of an array operand (None: too short or not an array)."""
    if isinstance(arr, ArrayRef):
        if len(arr) < ndim:
            return None
        return np.array([real(arr.get(i)) for i in range(ndim)], dtype=float)
    return None


@dataclass(frozen=True, slots=True)
class _Common:
    """Operands MCLM and MCCM share from Speed on, converted and checked."""

    limits: Limits
    termination: int
    tolerance: float
    merge: int
    merge_current: bool
    decel_jerk_percent: float | None  # S-curve decel jerk in % of Time (merges rescale it)


def _common(
    rt: MotionRuntime, ctl: list, s: System, first: int, ops: tuple[object, ...]
) -> _Common | None:
    """Speed .. LockDirection (`first` = operand index of Speed); None after reporting."""
    (speed, speed_units, accel, accel_units, decel, decel_units, profile, accel_jerk,
     decel_jerk, jerk_units, termination, merge, merge_speed, command_tolerance, _lock_pos,
     lock_direction) = ops  # fmt: skip
    shape = whole(profile)
    if shape not in (0, 1):
        fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, first + 6)
        return None
    dyn = dynamics(
        s.maximum, first, real(speed), speed_units, real(accel), accel_units, real(decel),
        decel_units, shape == 1, real(accel_jerk), real(decel_jerk), jerk_units, False,
    )  # fmt: skip
    if isinstance(dyn, StartResult):
        failed(rt, ctl, dyn)
        return None
    assert isinstance(dyn, Dynamics)
    tt = whole(termination)
    if tt not in _TERMINATION_TYPES:
        fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, first + 10)
        return None
    mm = whole(merge)
    if mm not in (0, 1, 2):
        fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, first + 11)
        return None
    ms = whole(merge_speed)
    if ms not in (0, 1):
        fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, first + 12)
        return None
    ct = real(command_tolerance)
    if tt == Termination.COMMAND_TOLERANCE_PROGRAMMED and not (math.isfinite(ct) and ct >= 0.0):
        fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, first + 13)
        return None
    ld = whole(lock_direction)
    if ld not in range(5):
        fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, first + 15)
        return None
    if dyn.master_driven or whole(speed_units) == PER_MASTER_UNIT:
        # master-driven coordinated motion needs an active MDCC, which is not simulated
        fail(rt, ctl, MotionError.MDSC_NOT_ACTIVATED)
        return None
    if ld != 0:  # a lock direction only applies to master-driven motion
        fail(rt, ctl, MotionError.LOCK_DIRECTION_CONFLICT)
        return None
    lim = Limits.of(
        dyn.speed, dyn.accel, dyn.decel, ProfileShape(shape), dyn.accel_jerk, dyn.decel_jerk
    )
    cs = s.group.core.paths.systems[s.index]
    tol = ct if tt == Termination.COMMAND_TOLERANCE_PROGRAMMED else cs.command_tolerance
    pct = real(decel_jerk) if shape == 1 and whole(jerk_units) == PERCENT_OF_TIME else None
    return _Common(lim, tt, tol, mm, ms == 1, pct)


def _queue(
    rt: MotionRuntime,
    ctl: list,
    s: System,
    segment: Segment,
    common: _Common,
    rebuild: Callable[[np.ndarray], Segment | GeometryError],
    event_distance: ArrayRef | None,
    calculated_data: ArrayRef | None,
) -> None:
    if event_distance is not None and (
        calculated_data is None or len(calculated_data) < len(event_distance)
    ):
        fail(rt, ctl, MotionError.MDSC_CALCULATED_DATA_SIZE)
        return
    core = s.group.core
    r = core.start_path(
        s.index, segment, common.limits, common.termination, common.tolerance, common.merge,
        common.merge_current, rebuild, common.decel_jerk_percent,
    )  # fmt: skip
    if failed(rt, ctl, r):
        return
    h = r.handle

    def on_start(g: Group) -> None:
        if rt.owns(ctl, g, h):
            set_bits(ctl, AC=1)
        if event_distance is not None and calculated_data is not None:
            _event_points(g.core.paths.profile_of(h), event_distance, calculated_data)

    def on_end(g: Group, completed: bool) -> None:
        if rt.owns(ctl, g, h) and ctl[AC]:
            set_bits(ctl, AC=0)

    rt.track(s.group, h, Tracked(ctl, tuple(s.axes), pc=True, on_start=on_start, on_end=on_end))
    set_bits(ctl, DN=1, IP=1)
    # the queue bits show at once: a program tests MovePendingQueueFullStatus before it
    # queues the next move in the same scan
    s.seen = -1
    _write_status(s)


def _event_points(prof: MoveProfile | None, events: ArrayRef, out: ArrayRef) -> None:
    """CalculatedData[k]: time from the move's start to EventDistance[k] before its end."""
    for k in range(len(events)):
        ev = abs(real(events.get(k)))
        t = 0.0
        if prof is not None and math.isfinite(prof.duration):
            target = prof.end_position - ev
            if target > 0.0:
                lo, hi = 0.0, prof.duration
                for _ in range(100):  # bisection: the path parameter only grows
                    mid = 0.5 * (lo + hi)
                    if prof.at(mid)[0] < target:
                        lo = mid
                    else:
                        hi = mid
                t = hi
        out.set(k, t)


def _start_move(
    ctx: ExecContext, rung: bool, cs: list, ctl: list, move_type: int, position: ArrayRef
) -> tuple[MotionRuntime, System, int, np.ndarray] | None:
    """MCLM's and MCCM's common start: the system, Move Type (operand 2) and the end
    Position (operand 3), each refused with ERR 13 and its operand index."""
    started = _start(ctx, rung, cs, ctl)
    if started is None:
        return None
    rt, s = started
    mt = whole(move_type)
    if mt not in (0, 1):
        fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, 2)
        return None
    target = _point(position, len(s.axes))
    if target is None or not np.isfinite(target).all():
        fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, 3)
        return None
    return rt, s, mt, target


# ------------------------------------------------------------------ MCLM
@implements("MCLM")
def mclm(
    ctx: ExecContext, rung: bool, cs: list, ctl: list, move_type: int, position: ArrayRef,
    speed: float, speed_units: int, accel: float, accel_units: int, decel: float,
    decel_units: int, profile: int, accel_jerk: float, decel_jerk: float, jerk_units: int,
    termination: int, merge: int, merge_speed: int, command_tolerance: float,
    lock_position: float, lock_direction: int, event_distance: ArrayRef | None,
    calculated_data: ArrayRef | None,
) -> None:  # fmt: skip
    """Straight line to Position (absolute or incremental) at the vector dynamics given."""
    started = _start_move(ctx, rung, cs, ctl, move_type, position)
    if started is None:
        return
    rt, s, mt, target = started
    common = _common(rt, ctl, s, 4, (
        speed, speed_units, accel, accel_units, decel, decel_units, profile, accel_jerk,
        decel_jerk, jerk_units, termination, merge, merge_speed, command_tolerance,
        lock_position, lock_direction,
    ))  # fmt: skip
    if common is None:
        return
    start = s.group.core.path_start_point(s.index)

    def build(p0: np.ndarray) -> Segment | GeometryError:
        return line(p0, target if mt == 0 else p0 + target)

    seg = build(start)
    assert isinstance(seg, Segment)
    # an absolute end point stays where it is when a merge starts from elsewhere; an
    # incremental one is measured from the start point of the move
    _queue(rt, ctl, s, seg, common, build, event_distance, calculated_data)


# ------------------------------------------------------------------ MCCM
@implements("MCCM")
def mccm(
    ctx: ExecContext, rung: bool, cs: list, ctl: list, move_type: int, position: ArrayRef,
    circle_type: int, via_center_radius: object, direction: int, speed: float,
    speed_units: int, accel: float, accel_units: int, decel: float, decel_units: int,
    profile: int, accel_jerk: float, decel_jerk: float, jerk_units: int, termination: int,
    merge: int, merge_speed: int, command_tolerance: float, lock_position: float,
    lock_direction: int, event_distance: ArrayRef | None, calculated_data: ArrayRef | None,
) -> None:  # fmt: skip
    """Circular arc (or full circle) to Position, defined by a via point, a centre or a
    radius (path_geometry.circle); geometry errors 44..49 (25: Radius in 3D)."""
    started = _start_move(ctx, rung, cs, ctl, move_type, position)
    if started is None:
        return
    rt, s, mt, target = started
    ndim = len(s.axes)
    ct = whole(circle_type)
    if ct not in range(4):
        fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, 4)
        return
    aux: np.ndarray | float
    if ct == 2:  # Radius: a single value (the first element of an array)
        aux = (
            real(via_center_radius.get(0))
            if isinstance(via_center_radius, ArrayRef)
            else (real(via_center_radius))
        )
    else:
        point = _point(via_center_radius, ndim)
        if point is None:
            fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, 5)
            return
        aux = point
    dr = whole(direction)
    if dr not in range(4):
        fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, 6)
        return
    common = _common(rt, ctl, s, 7, (
        speed, speed_units, accel, accel_units, decel, decel_units, profile, accel_jerk,
        decel_jerk, jerk_units, termination, merge, merge_speed, command_tolerance,
        lock_position, lock_direction,
    ))  # fmt: skip
    if common is None:
        return

    def build(p0: np.ndarray) -> Segment | GeometryError:
        end = target if mt == 0 else p0 + target
        return circle(p0, end, aux, ct, dr, ndim, mt)

    seg = build(s.group.core.path_start_point(s.index))
    if isinstance(seg, GeometryError):
        fail(rt, ctl, seg.err)
        return
    _queue(rt, ctl, s, seg, common, build, event_distance, calculated_data)


# ------------------------------------------------------------------ MCS
@implements("MCS")
def mcs(
    ctx: ExecContext, rung: bool, cs: list, ctl: list, stop_type: int, change_decel: int,
    decel_rate: float, decel_units: int, change_decel_jerk: int, decel_jerk: float,
    jerk_units: int,
) -> None:  # fmt: skip
    """Bring the system to rest along its path (All: its axes' other motion too) with the
    system's maximum deceleration or the given one; the queued move is cancelled."""
    started = _start(ctx, rung, cs, ctl)
    if started is None:
        return
    rt, s = started
    st, cd, du, cj, ju = (
        whole(stop_type), whole(change_decel), whole(decel_units), whole(change_decel_jerk),
        whole(jerk_units),
    )  # fmt: skip
    for value, ok, index in (
        (st, (_STOP_ALL, _STOP_MOVE, _STOP_TRANSFORM), 2), (cd, (0, 1), 3), (du, (0, 1), 5),
        (cj, (0, 1), 6), (ju, (0, 1, 2), 8),
    ):  # fmt: skip
        if value not in ok:
            fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, index)
            return
    core = s.group.core
    if st == _STOP_TRANSFORM:  # no transform is ever running in the simulation
        h = rt.token(s.group)
        rt.own(ctl, s.group, h)
        set_bits(ctl, DN=1, PC=1)
        return
    max_decel = s.get("MaximumDecel")
    if cd == 0:
        if not max_decel > 0.0:
            fail(rt, ctl, MotionError.ZERO_MAX_DECEL, -1)
            return
        decel = max_decel
    else:
        decel = real(decel_rate) * (max_decel / 100.0 if du == 1 else 1.0)
        if not (math.isfinite(decel) and decel > 0.0):
            fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, 4)
            return
    jerk = _limit(s.get("MaximumDecelJerk"))
    if cj == 1:
        idx = [ax.index for ax in s.axes]
        speed = float(np.linalg.norm(core.command_velocity[idx]))
        j = jerk_value(real(decel_jerk), ju, decel, speed, s.get("MaximumDecelJerk"))
        if j is None:
            fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, 7)
            return
        jerk = j
    r = core.stop_path(s.index, st == _STOP_ALL, decel, jerk)
    if failed(rt, ctl, r):
        return
    rt.track(s.group, r.handle, Tracked(ctl, pc=True))
    set_bits(ctl, DN=1, IP=1)


@prescan("MCLM", "MCCM", "MCS", "MCCD")
def _prescan(ctx: ExecContext, rung: bool, cs: list, ctl: list, *rest: object) -> None:
    """Prescan clears the control bits and binds the system, so its tag shows the
    positions and status from the first scan on."""
    clear_on_prescan(ctl)
    system(runtime(ctx), cs)
