"""Electronic gearing (MAG): the slave moves by ratio x the master's travel, all gears of a
group advanced together with numpy (one row per gear, struct-of-arrays).

Each update a locked gear adds `ratio * (m - m_prev)` to its slave, m being the master's
actual or command position at that update (masters are advanced before their slaves, so
it is the master position of the same update). Travel is counted incrementally, so a
redefined master position (MRP) only has to shift `prev` to leave the slave undisturbed.

Clutch: a gear that does not start locked ramps its own velocity towards the geared speed
`ratio * master velocity` at its clutch acceleration; the position integrates that velocity
exactly for a constant acceleration ((v_old + v_new) / 2 * cup). The update at which the
ramp reaches the geared speed locks the gear (GearingLockStatus); from then on the slave
follows the master travel exactly. The phase lost while clutching is not made up (Logix
matches speed, not position).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from interpreter.motion.enums import EventKind, MasterReference, StopType, direction_sign
from interpreter.motion.errors import MotionError, StartResult, bad_operand
from interpreter.motion.process import (
    EMPTY,
    AxisState,
    Contribution,
    Ending,
    EndReason,
    Events,
    LevelSel,
)
from interpreter.motion.rotary import travel_array

if TYPE_CHECKING:  # the group calls start_gear; only the annotation needs the class
    from interpreter.motion.group import MotionGroup


class GearSet:
    """The gears of a motion group; the arrays are the state (at most one gear per slave)."""

    def __init__(self) -> None:
        self.handle = np.zeros(0, dtype=np.int64)
        self.slave = np.zeros(0, dtype=np.intp)
        self.master = np.zeros(0, dtype=np.intp)
        self.ref = np.zeros(0, dtype=np.intp)  # 0 actual, 1 command (MasterReference values)
        self.ratio = np.zeros(0)  # signed: the direction is applied
        self.accel = np.zeros(0)  # clutch acceleration (inf: no clutch)
        self.prev = np.zeros(0)  # master position at the previous update
        self.m_unwind = np.zeros(0)  # the master's unwind (0: linear): travel through the wrap
        self.v = np.zeros(0)  # the gear's own contribution to the slave velocity
        self.a = np.zeros(0)
        self.locked = np.zeros(0, dtype=bool)
        self.last_dir: dict[int, int] = {}  # slave -> +1 same, -1 opposite (absent: none yet)
        self._status_cache: tuple[tuple[int, bytes, bytes], dict[str, np.ndarray]] | None = None

    def __len__(self) -> int:
        return len(self.handle)

    # -- membership ---------------------------------------------------------------
    def add(
        self,
        handle: int,
        slave: int,
        master: int,
        reference: MasterReference,
        ratio: float,
        accel: float,
        master_pos: float,
        master_vel: float,
        v0: float = 0.0,
        master_unwind: float = 0.0,
    ) -> None:
        """Engage a gear at this update: travel counts from master_pos; the gear starts at
        velocity v0 (the velocity of a gear it replaces) and is locked at once when that is
        already the geared speed or there is no clutch."""
        target = ratio * master_vel
        locked = math.isinf(accel) or abs(target - v0) <= 1e-12
        v = target if locked else v0
        self.handle = np.append(self.handle, handle)
        self.slave = np.append(self.slave, slave)
        self.master = np.append(self.master, master)
        self.ref = np.append(self.ref, int(reference))
        self.ratio = np.append(self.ratio, ratio)
        self.accel = np.append(self.accel, accel)
        self.prev = np.append(self.prev, master_pos)
        self.m_unwind = np.append(self.m_unwind, master_unwind)
        self.v = np.append(self.v, v)
        self.a = np.append(self.a, 0.0)
        self.locked = np.append(self.locked, locked)

    def end_on(self, slave: int, ev: Events) -> tuple[float, bool]:
        """End the gearing of a slave: (the velocity it contributed, for hand-overs; whether
        a gear ended)."""
        ended = self.remove(self.rows_on(slave))
        for h, _, _ in ended:
            ev.append((h, EventKind.ENDED, slave))
        return sum((v for _, _, v in ended), 0.0), bool(ended)

    def stop_requested(self, axis: int | None, stop_type: StopType) -> None:
        pass

    def busy(self, axis: int) -> bool:
        return bool(len(self.rows_on(axis)))

    def links_in_use(self) -> set[int]:
        return set()  # gears name their master themselves (MAG), not through MDAC

    def end_axis(self, axis: int, reason: EndReason, events: Events) -> tuple[float, bool]:
        """Stops (All, Gear), merges and kills end the gearing of the slave."""
        if reason not in (Ending.KILL, Ending.MERGE_ALL, StopType.ALL, StopType.GEAR):
            return 0.0, False
        return self.end_on(axis, events)

    def rows_on(self, slave: int) -> np.ndarray:
        return np.flatnonzero(self.slave == slave)

    def remove(self, rows: np.ndarray) -> list[tuple[int, int, float]]:
        """Drop gears; returns (handle, slave, velocity) of each, for stops and merges."""
        out = [(int(self.handle[r]), int(self.slave[r]), float(self.v[r])) for r in rows]
        if len(rows):
            keep = np.ones(len(self), dtype=bool)
            keep[rows] = False
            for name in (
                "handle",
                "slave",
                "master",
                "ref",
                "ratio",
                "accel",
                "prev",
                "m_unwind",
                "v",
                "a",
            ):
                setattr(self, name, getattr(self, name)[keep])
            self.locked = self.locked[keep]
        return out

    def shift_master(self, axis: int, delta: float) -> None:
        """The master's position was redefined by delta: its travel is unchanged."""
        self.prev[self.master == axis] += delta

    def edges(self) -> list[tuple[int, int]]:
        """(slave, master) pairs for the masters-before-slaves ordering."""
        return list(zip(self.slave.tolist(), self.master.tolist(), strict=True))

    def begin_update(self) -> None:
        pass

    def end_update(self, actual: np.ndarray, events: Events) -> None:
        pass

    def status(self, n: int) -> dict[str, np.ndarray]:
        """GearingStatus (geared) and GearingLockStatus (clutch done); the same dict while
        they do not change (the group merges the sets' status only when one changed)."""
        key = (n, self.slave.tobytes(), self.locked.tobytes())
        cached = self._status_cache
        if cached is not None and cached[0] == key:
            return cached[1]
        gear = np.zeros(n, dtype=bool)
        gear[self.slave] = True
        lock = np.zeros(n, dtype=bool)
        lock[self.slave[self.locked]] = True
        out = {"GearingStatus": gear, "GearingLockStatus": lock}
        self._status_cache = (key, out)
        return out

    def velocity_sums(self, n: int) -> tuple[np.ndarray, np.ndarray]:
        return np.bincount(self.slave, self.v, n), np.bincount(self.slave, self.a, n)

    # -- stepping -----------------------------------------------------------------
    def step(
        self,
        cup: float,
        level_sel: LevelSel,
        positions: AxisState,
        velocities: AxisState,
        events: Events | None = None,  # gears report no events from a step
    ) -> Contribution:
        """Advance the gears (all, or those whose slave has the given level) one update."""
        if not len(self):
            return EMPTY
        if level_sel is None:
            rows = np.arange(len(self))
        else:
            rows = np.flatnonzero(level_sel[0][self.slave] == level_sel[1])
            if not len(rows):
                return EMPTY
        master, ref = self.master[rows], self.ref[rows]
        m = np.where(ref == 0, positions[0][master], positions[1][master])
        mv = np.where(ref == 0, velocities[0][master], velocities[1][master])
        ratio, v_old, locked = self.ratio[rows], self.v[rows], self.locked[rows]
        target = ratio * mv
        # clutching rows: velocity ramps towards the geared speed at the clutch rate
        room = self.accel[rows] * cup
        dv = target - v_old
        reach = np.abs(dv) <= room * (1.0 + 1e-9) + 1e-12  # the last ramp step, up to rounding
        with np.errstate(invalid="ignore"):
            v_ramp = np.where(reach, target, v_old + np.sign(dv) * room)
        moved = travel_array(m, self.prev[rows], self.m_unwind[rows])
        dp = np.where(locked, ratio * moved, 0.5 * (v_old + v_ramp) * cup)
        vel = np.where(locked, target, v_ramp)
        acc = (vel - v_old) / cup
        self.prev[rows] = m
        self.v[rows] = vel
        self.a[rows] = acc
        self.locked[rows] = locked | reach
        return Contribution(self.slave[rows], dp, vel, acc)


def start_gear(
    group: MotionGroup,
    gears: GearSet,
    slave: int,
    master: int,
    direction: int,
    ratio: float,
    reference: int = MasterReference.COMMAND,
    clutch_accel: float = math.inf,
) -> StartResult:
    """MAG: from the next update the slave adds ratio x the master's travel; a gear
    already on the slave is replaced, its velocity carried into the clutch ramp.
    `ratio` is unsigned by direction (Same +1, Opposite -1, Reverse / Unchanged relative
    to the slave's present gearing direction); clutch_accel inf: lock at once."""
    if slave == master:
        return StartResult(error=MotionError.MASTER_AXIS_CONFLICT)
    if direction not in (0, 1, 2, 3):
        return bad_operand(3)
    if not math.isfinite(ratio):
        return bad_operand(4)
    if reference not in MasterReference.__members__.values():
        return bad_operand(7)
    if not clutch_accel > 0.0:
        return bad_operand(10)
    if group.shutdown[slave]:
        return StartResult(error=MotionError.SHUTDOWN_STATE)
    if not group.servo_on[slave]:
        return StartResult(error=MotionError.SERVO_OFF_STATE)
    sign = direction_sign(direction, gears.last_dir, slave)
    ref = group.effective_reference(master, MasterReference(reference))
    h = group.new_handle()

    def apply(ev: list[tuple[int, EventKind, int]]) -> None:
        v0 = gears.end_on(slave, ev)[0]
        if ref == MasterReference.ACTUAL:
            mpos, mvel = group.actual_position[master], group.actual_velocity[master]
        else:
            mpos, mvel = group.command_position[master], group.command_velocity[master]
        gears.add(
            h, slave, master, ref, sign * ratio, clutch_accel, float(mpos), float(mvel), v0,
            float(group.unwind[master]),
        )  # fmt: skip
        group.levels_changed()
        ev.append((h, EventKind.IN_PROCESS, slave))

    group.after_update(apply)
    return StartResult(handle=h)
