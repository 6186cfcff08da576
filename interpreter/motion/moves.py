"""Moves, jogs and stops (MAM, MAJ, MAS, MGS, MCD): the start calls of the profile kind.

The generators themselves and their numpy stepping live in generators.py (ProfileSet);
here are the requests that create, replace, merge, stop and replan them. Each function
takes the group as its first argument; MotionGroup binds them as its methods of the same
name (decision 0104), so `group.start_move(...)` keeps working.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import TYPE_CHECKING

from interpreter.motion.clock import MasterClock
from interpreter.motion.enums import (
    EventKind,
    GeneratorKind,
    LockDirection,
    MergeMode,
    MergeSpeed,
    MotionType,
    MoveType,
    ProfileShape,
    StopType,
)
from interpreter.motion.errors import MotionError, StartResult, bad_operand
from interpreter.motion.generators import GroupStop, ProfileGen
from interpreter.motion.process import Ending
from interpreter.motion.profiles import Limits, MoveProfile, plan_jog, plan_move, plan_stop
from interpreter.motion.rotary import rotary_travel

if TYPE_CHECKING:  # bound as MotionGroup methods; only the annotations need the class
    from interpreter.motion.group import MotionGroup

_VEL_EPS = 1e-9


def generator_profile(group: MotionGroup, handle: int) -> MoveProfile | None:
    """The planned profile of a running move/jog/stop (for event distances and plots)."""
    for g in group.moves.gens:
        if g.handle == handle:
            return g.profile
    return None


def running_limits(
    group: MotionGroup, axis: int, kind: GeneratorKind
) -> tuple[Limits, bool] | None:
    """Limits of the latest running move/jog of the axis and whether it is master driven
    (MCD: % of Time jerks and unit checks need what is in use)."""
    for g in reversed(group.moves.gens):
        if g.axis == axis and g.kind == kind and g.limits is not None:
            return g.limits, g.clock is not None
    return None


# -- moves and jogs ----------------------------------------------------------------


def start_move(
    group: MotionGroup,
    axis: int,
    move_type: int,
    position: float,
    speed: float,
    accel: float,
    decel: float,
    profile: int = ProfileShape.TRAPEZOIDAL,
    accel_jerk: float = math.inf,
    decel_jerk: float = math.inf,
    merge: int = MergeMode.DISABLED,
    merge_speed: int = MergeSpeed.PROGRAMMED,
    lock_position: float = 0.0,
    lock_direction: int = LockDirection.NONE,
    master_driven: bool = False,
) -> StartResult:
    """MAM: absolute, incremental or (on a rotary axis) rotary shortest path, positive
    or negative move; EXERR indices follow the MAM faceplate."""
    if move_type not in MoveType.__members__.values():
        return bad_operand(2)
    if not math.isfinite(position):
        return bad_operand(3)
    if move_type >= MoveType.ROTARY_SHORTEST_PATH:
        bad = check_rotary_move(group, axis, move_type, position)
        if not bad.ok:
            return bad
    err = check_dynamics(group,
        speed, accel, decel, profile, accel_jerk, decel_jerk, merge, merge_speed,
        lock_direction, master_driven, axis, MotionType.MOVE, first=4, step=2,
    )  # fmt: skip
    if err is not None:
        return err
    h = group.new_handle()
    lim = Limits.of(speed, accel, decel, ProfileShape(profile), accel_jerk, decel_jerk)

    def apply(ev: list[tuple[int, EventKind, int]]) -> None:
        replaced = [g for g in group.moves.gens if g.axis == axis and g.kind == GeneratorKind.MOVE]
        remaining = sum(g.goal - g.last_p for g in replaced)
        v0, clock, link = merge_out(
            group,
            axis,
            replaced,
            MergeMode(merge),
            ev,
            MotionType.MOVE,
            master_driven,
            LockDirection(lock_direction),
            lock_position,
        )
        dist = move_distance(group, axis, move_type, position, remaining)
        use = lim
        if merge_speed == MergeSpeed.CURRENT and abs(v0) > _VEL_EPS:
            use = Limits(abs(v0), lim.accel, lim.decel, lim.accel_jerk, lim.decel_jerk)
        gen = ProfileGen(h, GeneratorKind.MOVE, axis, plan_move(dist, use, v0), clock, link)
        gen.limits, gen.goal = use, dist
        add_gen(group, gen, ev)

    group.after_update(apply)
    return StartResult(handle=h)


def check_rotary_move(
    group: MotionGroup, axis: int, move_type: int, position: float
) -> StartResult:
    """A rotary move type needs a rotary axis (error 17) and a target on the circle,
    0 <= Position < unwind (error 13, the Position operand)."""
    unwind = float(group.unwind[axis])
    if unwind == 0.0:
        return StartResult(error=MotionError.AXIS_MODE_NOT_ROTARY)
    if not 0.0 <= position < unwind:
        return bad_operand(3)
    return StartResult()


def move_distance(
    group: MotionGroup, axis: int, move_type: int, position: float, remaining: float = 0.0
) -> float:
    """Travel of a MAM planned from the axis's command position now. Absolute: to the
    position (on a rotary axis too: it is read as a point of the unwound axis, so a
    target beyond the unwind or below 0 turns more than once or backwards); incremental:
    by the position plus what the replaced move still had to go; rotary types: the short,
    forward or reverse way round (rotary.rotary_travel)."""
    current = float(group.command_position[axis])
    if move_type == MoveType.ABSOLUTE:
        return position - current
    if move_type == MoveType.INCREMENTAL:
        return position + remaining
    return rotary_travel(move_type, position, current, float(group.unwind[axis]))


def start_jog(
    group: MotionGroup,
    axis: int,
    direction: int,
    speed: float,
    accel: float,
    decel: float,
    profile: int = ProfileShape.TRAPEZOIDAL,
    accel_jerk: float = math.inf,
    decel_jerk: float = math.inf,
    merge: int = MergeMode.DISABLED,
    merge_speed: int = MergeSpeed.PROGRAMMED,
    lock_position: float = 0.0,
    lock_direction: int = LockDirection.NONE,
    master_driven: bool = False,
) -> StartResult:
    """MAJ: direction 0 forward, 1 reverse; runs until stopped or replaced."""
    if direction not in (0, 1):
        return bad_operand(2)
    err = check_dynamics(group,
        speed, accel, decel, profile, accel_jerk, decel_jerk, merge, merge_speed,
        lock_direction, master_driven, axis, MotionType.JOG, first=3, step=2,
    )  # fmt: skip
    if err is not None:
        return err
    h = group.new_handle()
    lim = Limits.of(speed, accel, decel, ProfileShape(profile), accel_jerk, decel_jerk)
    sign = 1.0 if direction == 0 else -1.0

    def apply(ev: list[tuple[int, EventKind, int]]) -> None:
        replaced = [g for g in group.moves.gens if g.axis == axis and g.kind == GeneratorKind.JOG]
        v0, clock, link = merge_out(
            group,
            axis,
            replaced,
            MergeMode(merge),
            ev,
            MotionType.JOG,
            master_driven,
            LockDirection(lock_direction),
            lock_position,
        )
        target = sign * speed
        if merge_speed == MergeSpeed.CURRENT and abs(v0) > _VEL_EPS:
            target = sign * abs(v0)
        gen = ProfileGen(h, GeneratorKind.JOG, axis, plan_jog(target, lim, v0), clock, link)
        gen.limits, gen.direction = lim, sign
        add_gen(group, gen, ev)

    group.after_update(apply)
    return StartResult(handle=h)


def check_dynamics(
    group: MotionGroup,
    speed: float,
    accel: float,
    decel: float,
    profile: int,
    accel_jerk: float,
    decel_jerk: float,
    merge: int,
    merge_speed: int,
    lock_direction: int,
    master_driven: bool,
    axis: int,
    mt: MotionType,
    first: int,
    step: int,
) -> StartResult | None:
    # operand order on both faceplates: Speed, Units, Accel, Units, Decel, Units,
    # Profile, AccelJerk, DecelJerk, JerkUnits, Merge, MergeSpeed, LockPos, LockDir
    if not (math.isfinite(speed) and speed >= 0.0):
        return bad_operand(first)
    # +inf is "unlimited" (a velocity step), as time-based planning with zero ramp time
    if not accel > 0.0:
        return bad_operand(first + step)
    if not decel > 0.0:
        return bad_operand(first + 2 * step)
    p = first + 3 * step
    if profile not in (0, 1):
        return bad_operand(p)
    if profile == ProfileShape.S_CURVE:
        if not accel_jerk > 0.0:
            return bad_operand(p + 1)
        if not decel_jerk > 0.0:
            return bad_operand(p + 2)
    if merge not in (0, 1, 2):
        return bad_operand(p + 4)
    if merge_speed not in (0, 1):
        return bad_operand(p + 5)
    if lock_direction not in (0, 1, 2, 3, 4):
        return bad_operand(p + 7)
    if not master_driven and lock_direction != LockDirection.NONE:
        return StartResult(error=MotionError.LOCK_DIRECTION_CONFLICT)
    if group.shutdown[axis]:
        return StartResult(error=MotionError.SHUTDOWN_STATE)
    if not group.servo_on[axis]:
        return StartResult(error=MotionError.SERVO_OFF_STATE)
    if master_driven and group.find_link(axis, mt) is None:
        return StartResult(error=MotionError.MDSC_NOT_ACTIVATED)
    return None


def merge_out(
    group: MotionGroup,
    axis: int,
    replaced: list[ProfileGen],
    merge: MergeMode,
    ev: list,
    mt: MotionType,
    master_driven: bool,
    lock_direction: LockDirection,
    lock_position: float,
) -> tuple[float, MasterClock | None, int]:
    """End the replaced generators (all motion for Merge All); their velocity carries on."""
    v_time = sum(g.v for g in replaced)
    v_native = sum(g.v_native for g in replaced)
    same_units = all((g.clock is not None) == master_driven for g in replaced)
    for g in replaced:
        end_gen(group, g, EventKind.ENDED, ev)
    if merge == MergeMode.ALL:
        v_other, other = group.end_axis(axis, Ending.MERGE_ALL, ev)
        v_time += v_other
        same_units = same_units and not other
    clock, link_handle = None, 0
    v0 = v_time
    if master_driven:
        link = group.take_link(axis, mt, ev)
        assert link is not None
        clock = group.master_clock(link, lock_direction, lock_position)
        pos, mvel = group.master_state(clock)
        clock.advance(pos)
        link_handle = link.handle
        ev.append((link.handle, EventKind.ACTIVE, axis))
        if same_units and replaced:
            v0 = v_native
        else:
            v0 = v_time / mvel if abs(mvel) > _VEL_EPS else 0.0
    elif not same_units or not replaced:
        v0 = v_time
    return v0, clock, link_handle


def add_gen(group: MotionGroup, gen: ProfileGen, ev: list[tuple[int, EventKind, int]]) -> None:
    """Start a generator at this update: own clock 0, contribution 0, velocity v0."""
    gen.t = 0.0 if gen.clock is None else gen.clock.value
    p, v, a = gen.profile.at(gen.t)
    gen.last_p = p
    gen.v_native = v
    if gen.clock is None:
        gen.v, gen.a = v, a
    else:
        _, mvel = group.master_state(gen.clock)
        gen.v, gen.a = v * mvel, a * mvel * mvel
    group.moves.gens.append(gen)
    group.levels_changed()
    ev.append((gen.handle, EventKind.IN_PROCESS, gen.axis))
    gen.phase = gen.current_phase()
    ev.append((gen.handle, gen.phase, gen.axis))
    if gen.finished:
        end_gen(group, gen, EventKind.COMPLETE, ev)


def end_gen(group: MotionGroup, g: ProfileGen, kind: EventKind, ev: list) -> None:
    if g in group.moves.gens:
        group.moves.gens.remove(g)
        group.levels_changed()
    ev.append((g.handle, kind, g.axis))
    if g.owner:
        gs = group.moves.group_stops.get(g.owner)
        if gs is not None:
            gs.members.discard(g.handle)
            if not gs.members:
                ev.append((gs.handle, EventKind.COMPLETE, -1))
                del group.moves.group_stops[g.owner]


# -- stops ---------------------------------------------------------------------------


def stop(
    group: MotionGroup,
    axis: int,
    stop_type: int = StopType.ALL,
    decel: float | None = None,
    decel_jerk: float | None = None,
) -> StartResult:
    """MAS: decelerate the selected motion to rest (None: the axis's configured limits)."""
    if stop_type not in StopType.__members__.values():
        return bad_operand(2)
    if decel is not None and not decel > 0.0:
        return bad_operand(4)
    if decel_jerk is not None and not decel_jerk > 0.0:
        return bad_operand(7)
    h = group.new_handle()
    group.after_update(
        lambda ev: apply_stop(group, h, axis, StopType(stop_type), decel, decel_jerk, 0, ev)
    )
    if stop_type in (StopType.ALL, StopType.TIME_CAM):
        group.stop_requested(axis, StopType(stop_type))
    return StartResult(handle=h)


def stop_group(group: MotionGroup) -> StartResult:
    """MGS (programmed): stop all motion of every axis with its configured decel."""
    h = group.new_handle()

    def apply(ev: list[tuple[int, EventKind, int]]) -> None:
        gs = GroupStop(h)
        group.moves.group_stops[h] = gs
        for axis in range(len(group.axes)):
            sh = group.new_handle()
            gs.members.add(sh)
            apply_stop(group, sh, axis, StopType.ALL, None, None, h, ev)
        if h in group.moves.group_stops and not gs.members:
            ev.append((h, EventKind.COMPLETE, -1))
            del group.moves.group_stops[h]

    group.after_update(apply)
    group.stop_requested(None, StopType.ALL)
    return StartResult(handle=h)


def apply_stop(
    group: MotionGroup,
    h: int,
    axis: int,
    stop_type: StopType,
    decel: float | None,
    decel_jerk: float | None,
    owner: int,
    ev: list[tuple[int, EventKind, int]],
) -> None:
    v0, _ = group.end_axis(axis, stop_type, ev)
    cfg = group.axes[axis]
    dec = cfg.max_decel if decel is None else decel
    jerk = cfg.max_decel_jerk if decel_jerk is None else decel_jerk
    lim = Limits(0.0, dec, dec, jerk, jerk)
    gen = ProfileGen(h, GeneratorKind.STOP, axis, plan_stop(v0, lim), owner=owner)
    if stop_type == StopType.ALL and group.moved_by_another_set(axis, group.moves):
        # motion the stop could not end at once (a coordinate system decelerating along
        # its path) still moves the axis: the stop completes when that has ended
        gen.hold = True
        _release_when_alone(group, gen)
    add_gen(group, gen, ev)


def _release_when_alone(group: MotionGroup, gen: ProfileGen) -> None:
    """After each update: a held stop that no other set's motion keeps busy ends its hold
    (and completes once its own profile has run out)."""

    def check(ev: list[tuple[int, EventKind, int]]) -> None:
        if gen not in group.moves.view():
            return  # ended otherwise (another stop, a shutdown)
        if group.moved_by_another_set(gen.axis, group.moves):
            group.after_update(check)
            return
        _ = group.moves.gens  # handing the objects out rebuilds the rows: the hold is lifted
        gen.hold = False
        if gen.finished:
            end_gen(group, gen, EventKind.COMPLETE, ev)

    group.after_update(check)


# -- dynamics changes (MCD) ---------------------------------------------------------


def change_dynamics(
    group: MotionGroup,
    axis: int,
    kind: GeneratorKind,
    speed: float | None = None,
    accel: float | None = None,
    decel: float | None = None,
    accel_jerk: float | None = None,
    decel_jerk: float | None = None,
) -> StartResult:
    """MCD: the running move or jog of the axis is planned again at the next update from
    its present velocity with the changed limits (None: unchanged); a move keeps its end
    point. Jerks only matter for S-curve motion. Nothing running: no effect."""
    first = 4  # faceplate index of Speed; rates follow every second operand
    for value, index, ok in (
        (speed, first, lambda x: math.isfinite(x) and x >= 0.0),
        (accel, first + 2, lambda x: x > 0.0),
        (decel, first + 4, lambda x: x > 0.0),
        (accel_jerk, first + 6, lambda x: x > 0.0),
        (decel_jerk, first + 8, lambda x: x > 0.0),
    ):
        if value is not None and not ok(value):
            return bad_operand(index)
    h = group.new_handle()

    def apply(ev: list[tuple[int, EventKind, int]]) -> None:
        for g in [g for g in group.moves.gens if g.axis == axis and g.kind == kind]:
            old = g.limits
            if old is None:
                continue
            s_curve = not (math.isinf(old.accel_jerk) and math.isinf(old.decel_jerk))
            lim = replace(
                old,
                speed=old.speed if speed is None else speed,
                accel=old.accel if accel is None else accel,
                decel=old.decel if decel is None else decel,
                accel_jerk=old.accel_jerk if accel_jerk is None or not s_curve else accel_jerk,
                decel_jerk=old.decel_jerk if decel_jerk is None or not s_curve else decel_jerk,
            )
            v0 = g.v_native
            if kind == GeneratorKind.JOG:
                prof = plan_jog(g.direction * lim.speed, lim, v0)
            else:
                prof = plan_move(g.goal - g.last_p, lim, v0)
            g.replan(prof, lim)

    group.after_update(apply)
    return StartResult(handle=h)
