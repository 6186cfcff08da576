"""MotionGroup: the axes of one motion group in numpy arrays, advanced one coarse update at a time.

Instructions executed between updates are validated at once (an error comes back from the
start call) and take effect at the next update(), where their own clock is 0 (SPEC 9.3).
Start requests are applied at the end of that update, after the running generators have
been advanced to it, so a replaced or stopped generator hands over its velocity at the
same instant and absolute targets are measured from the command position at that update.
"""

from __future__ import annotations

import dis
import math
from collections.abc import Callable
from dataclasses import dataclass
from functools import cache
from operator import is_not
from types import CodeType

import numpy as np

from interpreter.motion.cam import CamProfile
from interpreter.motion.clock import MasterClock
from interpreter.motion.enums import (
    AxisKind,
    CamDirection,
    EventKind,
    ExecutionMode,
    ExecutionSchedule,
    InstructionMode,
    LockDirection,
    MasterReference,
    MotionType,
    StopType,
)
from interpreter.motion.errors import MotionError, StartResult, bad_operand
from interpreter.motion.events import (
    WatchSet,
    arm_registration,
    arm_watch,
    disarm_registration,
    disarm_watch,
)
from interpreter.motion.gear import GearSet, start_gear
from interpreter.motion.generators import ProfileGen, ProfileSet
from interpreter.motion.homing import HomingSet, home
from interpreter.motion.links import LinkTable, MasterLink, assign_master
from interpreter.motion.moves import (
    change_dynamics,
    check_rotary_move,
    end_gen,
    generator_profile,
    running_limits,
    start_jog,
    start_move,
    stop,
    stop_group,
)
from interpreter.motion.outputcams import (
    OutputCamProcessSet,
    arm_output_cam,
    disarm_output_cam,
)
from interpreter.motion.path_moves import (
    add_coordinate_system,
    change_path_dynamics,
    path_start_point,
    start_path,
    stop_path,
)
from interpreter.motion.paths import PathSet
from interpreter.motion.poscam import (
    CamLaw,
    Coupling,
    PositionCamSet,
    start_mapc,
    start_position_cam,
)
from interpreter.motion.process import Ending, EndReason, LevelSel, MotionlessSet, ProcessSet
from interpreter.motion.rotary import travel_array, wrap, wrap_array
from interpreter.motion.servo import DEFAULT_TAU, lag_alpha, servo_step
from interpreter.motion.timecam import TimeCamSet, start_time_cam
from stdlib import catalog


def _motion_status_bits() -> dict[str, int]:
    """Bit numbers of the AXIS MotionStatus word, read from the catalog: the BOOL members
    with a `bit` that follow the MotionStatus member of the AXIS types (stdlib/types)."""
    td = catalog().type("AXIS_VIRTUAL")
    assert td is not None
    bits: dict[str, int] = {}
    after = False
    for m in td.members:
        if m.name == "MotionStatus":
            after = True
        elif after:
            if m.bit is None:
                break
            bits[m.name] = m.bit
    assert bits, "AXIS MotionStatus bits missing from the catalog"
    return bits


# per level of the plan: (the level is every axis, its views of command position, actual
# position, command velocity, command acceleration, actual velocity and the actual position
# before the update; None when the level's axes are not consecutive; the axis when the
# level is that one axis, else -1)
_LevelViews = tuple[bool, tuple[np.ndarray, ...] | None, int]

# Bit numbers of the AXIS MotionStatus word (names are the AXIS attribute names).
STATUS_BITS: dict[str, int] = _motion_status_bits()
_STATUS_SHIFTS = np.array(list(STATUS_BITS.values()), dtype=np.uint32)
_VEL_EPS = 1e-9


@cache
def _empty_code(code: CodeType) -> bool:
    ops = [(i.opname, i.argval) for i in dis.get_instructions(code) if i.opname != "RESUME"]
    return ops in ([("LOAD_CONST", None), ("RETURN_VALUE", None)], [("RETURN_CONST", None)])


def _motionless(ps: ProcessSet) -> bool:
    """Does the set keep MotionlessSet's step (it contributes nothing, ever)?"""
    return getattr(type(ps), "step", None) is MotionlessSet.step


def _statusless(ps: ProcessSet) -> bool:
    """Does the set keep MotionlessSet's status (no AXIS status member, ever)?"""
    return getattr(type(ps), "status", None) is MotionlessSet.status


def _empty(method: Callable[..., object]) -> bool:
    """Is the bound method's body empty (`pass` or a docstring only)? The update leaves such
    hooks out rather than calling them every update; any other body is called."""
    code = getattr(getattr(method, "__func__", None), "__code__", None)
    return code is not None and _empty_code(code)


@dataclass(frozen=True, slots=True)
class MotionEvent:
    """Something that happened to a handle in one update."""

    handle: int
    kind: EventKind
    axis: int


@dataclass(slots=True)
class AxisConfig:
    """Configured limits used where an instruction does not give its own (MAS, MGS)."""

    name: str
    kind: AxisKind
    max_speed: float = math.inf
    max_accel: float = 1000.0
    max_decel: float = 1000.0
    max_accel_jerk: float = math.inf
    max_decel_jerk: float = math.inf


class MotionGroup:
    """State of all axes of a motion group; update() advances them one coarse update."""

    def __init__(self, cup: float = 0.002) -> None:
        if not cup > 0:
            raise ValueError("coarse update period must be > 0")
        self.cup = float(cup)
        self.time = 0.0  # time of the latest update
        self.updates = 0  # updates done; the next one happens at updates * cup
        self.axes: list[AxisConfig] = []
        self.command_position = np.zeros(0)
        self.actual_position = np.zeros(0)
        self.command_velocity = np.zeros(0)
        self.actual_velocity = np.zeros(0)
        self.command_acceleration = np.zeros(0)
        self.servo_on = np.zeros(0, dtype=bool)
        self._closed: bool | None = None  # every servo loop closed (None: not known)
        self._servo_copied = False  # the status holds copies of servo_on and shutdown
        self.shutdown = np.zeros(0, dtype=bool)  # MASD/MGSD until MASR/MGSR
        self.direct_drive = np.zeros(0, dtype=bool)  # MDO until MDF, MSO, MSF or a shutdown
        self.watch = WatchSet()  # MAW watch-position events
        self.virtual = np.zeros(0, dtype=bool)
        self.tau = np.zeros(0)
        # Rotary axes (decision 0115): unwind per axis, position units per revolution; 0.0
        # is a linear axis. Command and actual positions of a rotary axis stay in
        # [0, unwind): both are wrapped at the end of every update, before the sets'
        # end_update; differences of positions go through rotary.travel (short way round).
        self.unwind = np.zeros(0)
        self._rotary = np.zeros(0, dtype=np.intp)  # indices of the rotary axes
        self._alpha = np.zeros(0)
        self._level = np.zeros(0, dtype=np.intp)
        self._max_level = 0
        self._levels_dirty = True
        # AXIS status members per axis, computed when read after an update (`status`)
        self._status: dict[str, np.ndarray] = {}
        self._status_stale = False
        # moves, jogs and stops; ending one goes through moves.end_gen (MGS bookkeeping)
        self.moves = ProfileSet(lambda g, kind, ev: end_gen(self, g, kind, ev))
        self._cams = TimeCamSet()
        self._pre: list[Callable[[list[tuple[int, EventKind, int]]], None]] = []
        self._post: list[Callable[[list[tuple[int, EventKind, int]]], None]] = []
        self._next_handle = 1
        self._links = LinkTable()  # MDAC master assignments
        self._gears = GearSet()
        self._homing = HomingSet()
        self.output_cams = OutputCamProcessSet(self)  # MAOC/MDOC: after the axes moved
        self.paths = PathSet()  # coordinate systems and their path moves (MCLM, MCCM, MCS)
        self.position_cams = PositionCamSet()  # MC_CamIn couplings
        # every kind of motion process, stepped in this order at each level (decision 0104)
        self._sets: list[ProcessSet] = [
            self.moves,
            self._cams,
            self._gears,
            self.position_cams,
            self.watch,
            self._homing,
            self._links,
            self.output_cams,
            self.paths,
        ]
        # the bound per-update calls of the sets; the step of a set that moves no axis
        # (MotionlessSet.step: no contribution) and begin/end hooks with an empty body are
        # left out
        self._steps = [ps.step for ps in self._sets if not _motionless(ps)]
        self._begin_hooks = [ps.begin_update for ps in self._sets if not _empty(ps.begin_update)]
        self._end_hooks = [ps.end_update for ps in self._sets if not _empty(ps.end_update)]
        # a set that keeps MotionlessSet.status owns no status member (it always hands out
        # the same empty dict, which adds nothing to the merge): not asked
        self._status_calls = [ps.status for ps in self._sets if not _statusless(ps)]
        # per level: (the sets' level selection, the level's axes, their servo alpha)
        self._level_plan: list[tuple[LevelSel, np.ndarray | slice, np.ndarray]] = []
        # the plan with each level's views (_plan_views)
        self._level_run: list[
            tuple[tuple[LevelSel, np.ndarray | slice, np.ndarray], _LevelViews]
        ] = []
        self._views_of: tuple[np.ndarray, ...] = (np.zeros(0),) * 6
        self._prev_actual = np.zeros(0)  # the actual positions before this update
        self.shift = np.zeros(0)  # per-axis position redefinition applied by the last update
        self.shifted = False  # some shift is not 0 (spares resetting and testing the array)
        # the sets' status dicts of the latest update and their merge (kept while unchanged)
        self._owned: tuple[list[dict[str, np.ndarray]], dict[str, np.ndarray]] | None = None

    @property
    def _gens(self) -> list[ProfileGen]:
        """The move/jog/stop generators, for start calls that edit them (rows rebuilt)."""
        return self.moves.gens

    # the start calls of each kind, bound as methods (decision 0104)
    generator_profile = generator_profile
    running_limits = running_limits
    start_move = start_move
    check_rotary_move = check_rotary_move
    start_jog = start_jog
    stop = stop
    stop_group = stop_group
    arm_watch = arm_watch
    disarm_watch = disarm_watch
    arm_registration = arm_registration
    disarm_registration = disarm_registration
    change_dynamics = change_dynamics
    arm_output_cam = arm_output_cam
    disarm_output_cam = disarm_output_cam
    add_coordinate_system = add_coordinate_system
    path_start_point = path_start_point
    start_path = start_path
    stop_path = stop_path
    change_path_dynamics = change_path_dynamics

    def stop_requested(self, axis: int | None, stop_type: StopType) -> None:
        """A MAS (axis) or MGS (None) was executed: sets release what a stop frees at once."""
        for ps in self._sets:
            ps.stop_requested(axis, stop_type)

    # -- configuration ---------------------------------------------------------------
    def add_axis(
        self,
        name: str,
        kind: AxisKind = AxisKind.VIRTUAL,
        *,
        tau: float = DEFAULT_TAU,
        position: float = 0.0,
        max_speed: float = math.inf,
        max_accel: float = 1000.0,
        max_decel: float = 1000.0,
        max_accel_jerk: float = math.inf,
        max_decel_jerk: float = math.inf,
        unwind: float = 0.0,
    ) -> int:
        """Add an axis (before running); returns its index. unwind > 0: a rotary axis."""
        self.axes.append(
            AxisConfig(name, kind, max_speed, max_accel, max_decel, max_accel_jerk, max_decel_jerk)
        )
        virtual = kind == AxisKind.VIRTUAL
        self.command_position = np.append(self.command_position, position)
        self.actual_position = np.append(self.actual_position, position)
        self.command_velocity = np.append(self.command_velocity, 0.0)
        self.actual_velocity = np.append(self.actual_velocity, 0.0)
        self.command_acceleration = np.append(self.command_acceleration, 0.0)
        self.servo_on = np.append(self.servo_on, virtual)  # a virtual axis needs no MSO
        self._servo_changed()
        self.shutdown = np.append(self.shutdown, False)
        self.direct_drive = np.append(self.direct_drive, False)
        self.virtual = np.append(self.virtual, virtual)
        self.tau = np.append(self.tau, 0.0 if virtual else tau)
        self.unwind = np.append(self.unwind, 0.0)
        self._alpha = lag_alpha(self.tau, self.cup)
        self.shift = np.append(self.shift, 0.0)
        self._level = np.append(self._level, 0)
        st = self.status
        self._levels_dirty = True  # also recomputes the level plan's servo alphas
        self._owned = None  # the status arrays below replace the merged ones
        for name_ in STATUS_BITS:
            st[name_] = np.zeros(len(self.axes), dtype=bool)
        st["ServoActionStatus"] = self.servo_on.copy()
        self.set_unwind(len(self.axes) - 1, unwind)
        return len(self.axes) - 1

    def set_unwind(self, axis: int, unwind: float) -> None:
        """Make the axis rotary with this unwind (position units per revolution), or
        linear with 0; its positions are wrapped into [0, unwind) at once."""
        if not (math.isfinite(unwind) and unwind >= 0.0):
            raise ValueError("unwind must be finite and >= 0")
        self.unwind[axis] = unwind
        self._rotary = np.flatnonzero(self.unwind > 0.0)
        self.command_position[axis] = wrap(float(self.command_position[axis]), unwind)
        self.actual_position[axis] = wrap(float(self.actual_position[axis]), unwind)

    def axis_index(self, name: str) -> int:
        for i, a in enumerate(self.axes):
            if a.name == name:
                return i
        raise KeyError(name)

    def set_position(self, axis: int, position: float) -> None:
        """Redefine command and actual position (for set-up and MRP-like use)."""
        u = float(self.unwind[axis])
        self.command_position[axis] = wrap(position, u)
        self.actual_position[axis] = wrap(position, u)

    @property
    def status(self) -> dict[str, np.ndarray]:
        """AXIS status members (bool per axis) as of the latest update. The bits the group
        derives from velocity and acceleration are computed when first read after it: the
        runtime reads them right after the updates due before a scan, and only when a
        status member is demanded (decision 0104), so most updates never build them."""
        if self._status_stale:
            self._status_stale = False
            self._motion_bits()
        return self._status

    def motion_status_word(self) -> np.ndarray:
        """MotionStatus DINT bits per axis from the status arrays."""
        bits = np.array([self.status[name] for name in STATUS_BITS], dtype=np.uint32)
        return (bits << _STATUS_SHIFTS[:, None]).sum(axis=0, dtype=np.uint32)

    def reserve_handle(self) -> int:
        """A fresh handle for a request that starts no generator (e.g. a fault reset)."""
        return self.new_handle()

    # -- services for the process modules (start calls of each kind) -------------------
    def after_update(self, fn: Callable[[list[tuple[int, EventKind, int]]], None]) -> None:
        """Apply a start request at the end of the next update (its own clock is 0 there)."""
        self._post.append(fn)

    def before_update(self, fn: Callable[[list[tuple[int, EventKind, int]]], None]) -> None:
        """Apply a request at the start of the next update, before its motion step."""
        self._pre.append(fn)

    def levels_changed(self) -> None:
        """A process that follows a master started or ended: recompute the levels."""
        self._levels_dirty = True

    def new_handle(self) -> int:
        h = self._next_handle
        self._next_handle += 1
        return h

    # -- servo -------------------------------------------------------------------------
    def _servo_changed(self) -> None:
        """servo_on or shutdown was written (they change only here, between updates): the
        update asks again whether every loop is closed and copies them into the status."""
        self._closed = None
        self._servo_copied = False

    def servo_on_axis(self, axis: int) -> StartResult:
        """MSO: close the loop (no effect on a virtual axis); refused while shut down."""
        if self.shutdown[axis]:
            return StartResult(error=MotionError.SHUTDOWN_STATE)
        self.direct_drive[axis] = False
        if not self.virtual[axis]:
            self.servo_on[axis] = True
            self._servo_changed()
            # the loop closes at the current actual position: no jump
            self.command_position[axis] = self.actual_position[axis]
        return StartResult(handle=self.new_handle())

    def servo_off_axis(self, axis: int) -> StartResult:
        """MSF: open the loop; running motion on the axis ends at the next update."""
        h = self.new_handle()
        self.direct_drive[axis] = False
        if self.virtual[axis]:
            return StartResult(handle=h)
        self.servo_on[axis] = False
        self._servo_changed()
        self.before_update(lambda ev: self.kill_axis(axis, ev))
        return StartResult(handle=h)

    def shutdown_axis(self, axis: int) -> StartResult:
        """MASD: end all motion of the axis at once, break its MDAC links and keep it in the
        shutdown state (motion is refused with error 7) until reset_shutdown."""
        h = self.new_handle()
        self.shutdown[axis] = True
        self._servo_changed()
        self.direct_drive[axis] = False
        if not self.virtual[axis]:
            self.servo_on[axis] = False
            self._servo_changed()

        def apply(ev: list[tuple[int, EventKind, int]]) -> None:
            self.kill_axis(axis, ev)
            self._break_links(lambda lk: axis in (lk.slave, lk.master), ev)

        self.before_update(apply)
        return StartResult(handle=h)

    def reset_shutdown(self, axis: int) -> StartResult:
        """MASR: leave the shutdown state; the loop stays open (a drive axis needs MSO)."""
        self.shutdown[axis] = False
        self._servo_changed()
        return StartResult(handle=self.new_handle())

    def kill_axis(self, axis: int, ev: list[tuple[int, EventKind, int]]) -> None:
        """End every motion of the axis at once (servo off, shutdown, active homing)."""
        self.end_axis(axis, Ending.KILL, ev)
        self.command_velocity[axis] = 0.0
        self.command_acceleration[axis] = 0.0
        self._levels_dirty = True

    def end_axis(
        self, axis: int, reason: EndReason, ev: list[tuple[int, EventKind, int]]
    ) -> tuple[float, bool]:
        """Every set ends what `reason` ends on the axis, in step order; returns the summed
        command velocity of what ended (carried on by a stop or merge) and whether any did."""
        v, any_ended = 0.0, False
        for ps in self._sets:
            dv, ended = ps.end_axis(axis, reason, ev)
            v += dv
            any_ended = any_ended or ended
        if any_ended:
            self._levels_dirty = True
        return v, any_ended

    # -- MDAC ----------------------------------------------------------------------------
    def assign_master(
        self,
        slave: int,
        master: int,
        motion_type: int = MotionType.ALL,
        reference: int = MasterReference.COMMAND,
    ) -> StartResult:
        """MDAC (see links.assign_master)."""
        return assign_master(self, self._links, slave, master, motion_type, reference)

    def effective_reference(self, master: int, reference: MasterReference) -> MasterReference:
        """A virtual master has no actual position of its own: it is always followed by command."""
        return MasterReference.COMMAND if self.virtual[master] else reference

    def axis_busy(self, axis: int) -> bool:
        """Is any process moving the axis (or is it still moving)?"""
        return (
            any(ps.busy(axis) for ps in self._sets)
            or abs(float(self.command_velocity[axis])) > _VEL_EPS
        )

    def moved_by_another_set(self, axis: int, own: object) -> bool:
        """Does a process of a set other than `own` move the axis (a stop of all motion
        waits for what it cannot end at once, e.g. a path stopping along its path)?"""
        return any(ps.busy(axis) for ps in self._sets if ps is not own)

    def links_in_use(self) -> set[int]:
        """MDAC handles that drive a running master-driven process (MDAC .AC)."""
        used: set[int] = set()
        for ps in self._sets:
            used |= ps.links_in_use()
        return used

    def find_link(self, slave: int, mt: MotionType) -> MasterLink | None:
        return self._links.find(slave, mt)

    def take_link(self, slave: int, mt: MotionType, ev: list) -> MasterLink | None:
        """Promote a pending master (if any) at a slave motion start and return the link."""
        return self._links.take(slave, mt, ev)

    def _break_links(self, pred: Callable[[MasterLink], bool], ev: list) -> None:
        self._links.break_where(pred, ev)

    def master_clock(
        self, link: MasterLink, lock_direction: LockDirection, lock_position: float
    ) -> MasterClock:
        ref = self.effective_reference(link.master, link.reference)
        clock = MasterClock(link.master, ref, LockDirection(lock_direction), lock_position)
        clock.unwind = float(self.unwind[link.master])
        return clock

    def master_state(self, clock: MasterClock) -> tuple[float, float]:
        m = clock.master
        if clock.reference == MasterReference.ACTUAL:
            return float(self.actual_position[m]), float(self.actual_velocity[m])
        return float(self.command_position[m]), float(self.command_velocity[m])

    # -- position redefinition (MRP) and homing (MAH) ------------------------------------
    def redefine_position(
        self, axis: int, relative: bool, reference: int, position: float
    ) -> StartResult:
        """MRP: at the next update the selected position becomes `position` (or moves by it);
        the other one moves with it, so the following error and running motion are kept."""
        if reference not in MasterReference.__members__.values():
            return bad_operand(3)
        if not math.isfinite(position):
            return bad_operand(4)
        h = self.new_handle()

        def apply(ev: list[tuple[int, EventKind, int]]) -> None:
            base = (
                self.actual_position
                if reference == MasterReference.ACTUAL
                else self.command_position
            )
            self.shift_position(axis, position if relative else position - float(base[axis]))
            ev.append((h, EventKind.COMPLETE, axis))

        self.before_update(apply)
        return StartResult(handle=h)

    def shift_position(self, axis: int, delta: float) -> None:
        """Add delta to the axis's positions; whatever follows this axis as a master keeps
        counting travel, not positions, so its slaves do not see the jump."""
        u = float(self.unwind[axis])
        self.command_position[axis] = wrap(float(self.command_position[axis]) + delta, u)
        self.actual_position[axis] = wrap(float(self.actual_position[axis]) + delta, u)
        self.shift[axis] += delta
        self.shifted = True
        for ps in self._sets:
            ps.shift_master(axis, delta)

    def home(self, axis: int, mode: int, sequence: int, home_position: float) -> StartResult:
        """MAH with the axis's homing configuration (see homing.home)."""
        return home(self, self._homing, axis, mode, sequence, home_position)

    # -- gearing (MAG) --------------------------------------------------------------------
    def start_gear(
        self,
        slave: int,
        master: int,
        direction: int,
        ratio: float,
        reference: int = MasterReference.COMMAND,
        clutch_accel: float = math.inf,
    ) -> StartResult:
        """MAG (see gear.start_gear)."""
        return start_gear(
            self, self._gears, slave, master, direction, ratio, reference, clutch_accel
        )

    # -- time cams -----------------------------------------------------------------------
    def start_time_cam(
        self,
        axis: int,
        profile: CamProfile | None,
        direction: int = CamDirection.SAME,
        distance_scaling: float = 1.0,
        time_scaling: float = 1.0,
        execution_mode: int = ExecutionMode.ONCE,
        execution_schedule: int = ExecutionSchedule.IMMEDIATE,
        lock_position: float = 0.0,
        lock_direction: int = LockDirection.NONE,
        instruction_mode: int = InstructionMode.TIME_DRIVEN,
    ) -> StartResult:
        """MATC; profile None means not calculated (ERR 32). See timecam.start_time_cam."""
        return start_time_cam(
            self, self._cams, axis, profile, direction, distance_scaling, time_scaling,
            execution_mode, execution_schedule, lock_position, lock_direction,
            instruction_mode,
        )  # fmt: skip

    # -- position cams (MC_CamIn) -------------------------------------------------------
    def start_position_cam(
        self, slave: int, master: int, law: CamLaw, reference: int = MasterReference.COMMAND
    ) -> Coupling:
        """Couple slave to master through a cam law (see poscam.start_position_cam)."""
        return start_position_cam(self, self.position_cams, slave, master, law, reference)

    def start_mapc(
        self,
        slave: int,
        master: int,
        profile: CamProfile | None,
        direction: int = CamDirection.SAME,
        slave_scaling: float = 1.0,
        master_scaling: float = 1.0,
        execution_mode: int = 0,
        execution_schedule: int = 0,
        master_lock_position: float = 0.0,
        cam_lock_position: float = 0.0,
        reference: int = MasterReference.ACTUAL,
        master_direction: int = 0,
    ) -> StartResult:
        """MAPC; profile None means not calculated (ERR 32). See poscam.start_mapc."""
        return start_mapc(
            self, self.position_cams, slave, master, profile, direction, slave_scaling,
            master_scaling, execution_mode, execution_schedule, master_lock_position,
            cam_lock_position, reference, master_direction,
        )  # fmt: skip

    # -- the update ------------------------------------------------------------------------
    def _compute_levels(self) -> None:
        """Masters before slaves: level(slave) = level(master) + 1 (cycles are capped)."""
        n = len(self.axes)
        edges = [e for ps in self._sets for e in ps.edges()]
        level = np.zeros(n, dtype=np.intp)
        for _ in range(n):
            changed = False
            for s, m in edges:
                if level[s] < level[m] + 1 and level[m] + 1 < n:
                    level[s] = level[m] + 1
                    changed = True
            if not changed:
                break
        self._level = level
        self._max_level = int(level.max()) if n else 0
        if self._max_level == 0:  # one level: every axis, as views (no fancy indexing)
            self._level_plan = [(None, slice(None), self._alpha)]
        else:  # per level: the sets' selection, the axes of the level and their servo alpha
            plan: list[tuple[LevelSel, np.ndarray | slice, np.ndarray]] = []
            for lv in range(self._max_level + 1):
                rows = np.flatnonzero(level == lv)
                first, end = int(rows[0]), int(rows[-1]) + 1
                # consecutive axes (a master, then its slaves): a slice, so views not copies
                idx = slice(first, end) if end - first == len(rows) else rows
                plan.append(((level, lv), idx, self._alpha[idx]))
            self._level_plan = plan
        self._levels_dirty = False
        self._plan_views()

    def _plan_views(self) -> None:
        """Per level of the plan, the views the update writes through: the level's axes of
        the state arrays (None for a level whose axes are not consecutive: fancy indexing)
        and whether the level is every axis. Built again when the levels or the state
        arrays change (add_axis replaces them), so the update makes no view per level."""
        n = len(self.axes)
        if len(self._prev_actual) != n:
            self._prev_actual = np.zeros(n)
        arrays = (
            self.command_position,
            self.actual_position,
            self.command_velocity,
            self.command_acceleration,
            self.actual_velocity,
            self._prev_actual,
        )
        self._views_of = arrays
        views: list[_LevelViews] = []
        for _sel, idx, _alpha in self._level_plan:
            if isinstance(idx, slice):
                whole = idx == slice(None) or (idx.start == 0 and idx.stop == n)
                one = not whole and idx.stop is not None and idx.stop - idx.start == 1
                single = idx.start if one else -1
                views.append((whole, tuple(a[idx] for a in arrays), single))  # type: ignore[arg-type]
            else:
                views.append((False, None, -1))
        self._level_run = list(zip(self._level_plan, views, strict=True))

    def update(self) -> list[MotionEvent]:
        """Advance every axis one coarse update; returns the events of this update."""
        ev: list[tuple[int, EventKind, int]] = []
        self.time = self.updates * self.cup  # updates happen at 0, cup, 2 cup, ...
        if self.shifted:
            self.shift[:] = 0.0
            self.shifted = False
        if self._pre:
            pre, self._pre = self._pre, []
            for f in pre:
                f(ev)
        if self._levels_dirty:
            self._compute_levels()
        n = len(self.axes)
        cup = self.cup
        for begin in self._begin_hooks:
            begin()
        cmd, act = self.command_position, self.actual_position
        cvel, cacc, avel = self.command_velocity, self.command_acceleration, self.actual_velocity
        if self._views_of[0] is not cmd or self._views_of[4] is not avel:
            self._plan_views()  # the state arrays were replaced since the plan was made
        prev_actual = self._prev_actual
        np.copyto(prev_actual, act)
        positions = (act, cmd)
        velocities = (avel, cvel)
        rot = len(self._rotary) > 0
        closed = self._closed
        if closed is None:  # servo_on changes only in the servo and shutdown calls
            closed = self._closed = bool(self.servo_on.all())
        bincount = np.bincount
        steps = self._steps
        for (sel, idx, alpha), (whole, views, single) in self._level_run:
            parts = []
            for step in steps:
                c = step(cup, sel, positions, velocities, ev)
                if len(c.axis):
                    parts.append(c)
            if views is not None and not rot and closed:
                # consecutive axes, no wrap, every loop closed (the usual case): the same
                # operations as below, written through the level's views
                if single >= 0 and len(parts) == 1 and len(parts[0].axis) == 1:
                    # one axis driven by one process (a master jogging ahead of its
                    # slaves): the same operations on Python floats (IEEE doubles, the
                    # same results); bincount's sum of one row is 0.0 + its value
                    c = parts[0]
                    cmd += bincount(c.axis, c.dpos, n)
                    i = single
                    cvel[i] = 0.0 + float(c.vel[0])
                    cacc[i] = 0.0 + float(c.acc[0])
                    a_i = float(act[i])
                    d_i = float(cmd[i]) - a_i
                    d_i *= float(alpha[0])
                    a_i += d_i
                    act[i] = a_i
                    avel[i] = (a_i - float(prev_actual[i])) / cup
                    continue
                cmd_v, act_v, cvel_v, cacc_v, avel_v, prev_v = views
                if len(parts) == 1:  # one kind of motion at this level (e.g. only cams)
                    c = parts[0]
                    cmd += bincount(c.axis, c.dpos, n)
                    if whole:
                        cvel_v[...] = bincount(c.axis, c.vel, n)
                        cacc_v[...] = bincount(c.axis, c.acc, n)
                    else:
                        cvel_v[...] = bincount(c.axis, c.vel, n)[idx]
                        cacc_v[...] = bincount(c.axis, c.acc, n)[idx]
                elif parts:
                    axes = np.concatenate([c.axis for c in parts])
                    cmd += bincount(axes, np.concatenate([c.dpos for c in parts]), n)
                    cvel_v[...] = bincount(axes, np.concatenate([c.vel for c in parts]), n)[idx]
                    cacc_v[...] = bincount(axes, np.concatenate([c.acc for c in parts]), n)[idx]
                else:
                    cvel_v[...] = 0.0
                    cacc_v[...] = 0.0
                d = cmd_v - act_v  # servo.servo_step: act + alpha * (cmd - act), in place
                d *= alpha
                act_v += d
                np.subtract(act_v, prev_v, out=avel_v)
                avel_v /= cup
                continue
            if len(parts) == 1:  # one kind of motion at this level (e.g. only cams)
                c = parts[0]
                cmd += bincount(c.axis, c.dpos, n)
                cvel[idx] = bincount(c.axis, c.vel, n)[idx]
                cacc[idx] = bincount(c.axis, c.acc, n)[idx]
            elif parts:
                axes = np.concatenate([c.axis for c in parts])
                cmd += bincount(axes, np.concatenate([c.dpos for c in parts]), n)
                cvel[idx] = bincount(axes, np.concatenate([c.vel for c in parts]), n)[idx]
                cacc[idx] = bincount(axes, np.concatenate([c.acc for c in parts]), n)[idx]
            else:
                cvel[idx] = 0.0
                cacc[idx] = 0.0
            if rot:  # the servo follows the command the short way round the wrap
                self._align_actual()
            if closed:  # every loop closed (always so for virtual axes): servo.servo_step
                a0 = act[idx]
                if isinstance(idx, slice):  # a view: act + alpha * (cmd - act) in place
                    d = cmd[idx] - a0
                    d *= alpha
                    a0 += d
                else:
                    act[idx] = a0 + alpha * (cmd[idx] - a0)
            else:
                servo_step(cmd, act, self._alpha, self.servo_on, idx)
            if rot:
                moved = travel_array(act, prev_actual, self.unwind)
                avel[idx] = moved[idx] / cup
            elif isinstance(idx, slice):  # views: the same operations, no temporaries
                v = avel[idx]
                np.subtract(act[idx], prev_actual[idx], out=v)
                v /= cup
            else:
                avel[idx] = (act[idx] - prev_actual[idx]) / cup
        if rot:
            wrap_array(cmd, self.unwind, self._rotary)
            wrap_array(act, self.unwind, self._rotary)
        for end in self._end_hooks:
            end(act, ev)
        if self._post:
            post, self._post = self._post, []
            for f in post:
                f(ev)
            # processes started at this update report their start velocity now
            sums = [ps.velocity_sums(n) for ps in self._sets]
            cvel[:] = np.sum([v_ for v_, _ in sums], axis=0)
            cacc[:] = np.sum([a_ for _, a_ in sums], axis=0)
        self.updates += 1
        self._update_status()
        if not ev:
            return []
        return [MotionEvent(h, k, a) for h, k, a in ev]

    def _align_actual(self) -> None:
        """Put each rotary axis's actual position within half an unwind of its command
        (the command may have crossed the wrap since both were last wrapped)."""
        r, u = self._rotary, self.unwind[self._rotary]
        cmd, act = self.command_position[r], self.actual_position[r]
        d = cmd - act
        self.actual_position[r] = cmd - (d - u * np.floor(d / u + 0.5))

    def _update_status(self) -> None:
        """At the end of an update: the sets' status members (asking them is part of the
        update: a time cam set settles its axis claims then) and the servo state; the
        velocity bits follow when read (`status`)."""
        n = len(self.axes)
        st = self._status
        parts = [f(n) for f in self._status_calls]
        cached = self._owned
        if cached is None or any(map(is_not, parts, cached[0])):
            # the sets hand out the same dict while their status is unchanged (its arrays
            # read-only); a member two kinds set (CoordinatedMotionStatus) is their OR
            owned: dict[str, np.ndarray] = {}
            for part in parts:
                for name, arr in part.items():
                    prev = owned.get(name)
                    owned[name] = arr if prev is None else prev | arr
            self._owned = (parts, owned)
            # unchanged, the merged members are already in st (only add_axis replaces them,
            # and it drops the merge)
            st.update(owned)
        if not self._servo_copied:  # copied again only after a servo or shutdown change
            st["ServoActionStatus"] = self.servo_on.copy()
            st["ShutdownStatus"] = self.shutdown.copy()
            self._servo_copied = True
        self._status_stale = True

    def _motion_bits(self) -> None:
        """AccelStatus, DecelStatus and MaximumSpeedExceeded of the latest update."""
        st = self._status
        v, a = self.command_velocity, self.command_acceleration
        moving = np.abs(v) > _VEL_EPS
        st["AccelStatus"] = (v * a > _VEL_EPS) | (~moving & (np.abs(a) > _VEL_EPS))
        st["DecelStatus"] = v * a < -_VEL_EPS
        st["MaximumSpeedExceeded"] = np.abs(v) > np.array([c.max_speed for c in self.axes])
