"""Time cams (MATC) of a group, advanced together with numpy (one row per active cam)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from interpreter.motion.cam import CamProfile, ProfileBank
from interpreter.motion.clock import MasterClock
from interpreter.motion.enums import (
    CamDirection,
    EventKind,
    ExecutionMode,
    ExecutionSchedule,
    InstructionMode,
    LockDirection,
    MotionType,
    StopType,
    direction_sign,
)
from interpreter.motion.errors import MotionError, StartResult, bad_operand
from interpreter.motion.process import (
    EMPTY,
    AxisState,
    Contribution,
    Ending,
    EndReason,
    Events,
    LevelSel,
    rows_at_level,
)
from interpreter.motion.rowset import RowSet

if TYPE_CHECKING:  # the group calls start_time_cam; only the annotation needs the class
    from interpreter.motion.group import MotionGroup


@dataclass(slots=True)
class TimeCam:
    """One MATC: contribution = gain * (P(clock / ts) - P(0) + passes * net)."""

    handle: int
    axis: int
    profile: CamProfile
    gain: float  # direction (+1/-1) * DistanceScaling
    time_scaling: float
    mode: ExecutionMode
    clock: MasterClock | None = None  # master-driven when set
    link: int = 0
    raw: float = 0.0  # seconds since start, or master distance
    count: int = 0  # updates since start (time-driven raw = count * cup)
    offset: float = 0.0  # raw value at the start of the current pass
    passes: float = 0.0
    last: float = 0.0
    v: float = 0.0
    a: float = 0.0

    @property
    def lock_direction(self) -> LockDirection:
        return LockDirection.NONE if self.clock is None else self.clock.lock_direction


class TimeCamSet(RowSet[TimeCam]):
    """Active time cams in struct-of-arrays form; rows are rebuilt when the set changes."""

    STATE = (
        ("raw", "_raw", float),
        ("count", "_count", int),
        ("offset", "_offset", float),
        ("passes", "_passes", float),
        ("last", "_last", float),
        ("v", "_v", float),
        ("a", "_a", float),
    )

    def __init__(self) -> None:
        super().__init__()
        self.pending: dict[int, TimeCam] = {}
        self.claim: set[int] = set()  # axes with an active or queued immediate cam
        self.claim_mode: dict[int, bool] = {}  # claimed axis -> its cam is master driven
        self.last_dir: dict[int, int] = {}  # axis -> +1 same, -1 opposite (absent: none yet)
        self._bank: ProfileBank | None = None
        # status arrays while the cams are unchanged (shared with the group: read-only)
        self._status_cache: tuple[int, dict[str, np.ndarray]] | None = None
        self._claim_touched = False  # a stop freed a claim since the last status

    def _rebuild(self) -> None:
        self._status_cache = None
        cams = self.rows
        profiles: list[CamProfile] = []
        index: dict[int, int] = {}
        for c in cams:
            if id(c.profile) not in index:
                index[id(c.profile)] = len(profiles)
                profiles.append(c.profile)
        if self._bank is None or self._bank.key != tuple(id(p) for p in profiles):
            self._bank = ProfileBank(profiles)
        f = float
        self._axis = np.array([c.axis for c in cams], dtype=np.intp)
        self._prof = np.array([index[id(c.profile)] for c in cams], dtype=np.intp)
        self._gain = np.array([c.gain for c in cams], dtype=f)
        self._ts = np.array([c.time_scaling for c in cams], dtype=f)
        self._cont = np.array([c.mode == ExecutionMode.CONTINUOUS for c in cams], dtype=bool)
        self._md = np.array([c.clock is not None for c in cams], dtype=bool)
        self._md_rows = np.flatnonzero(self._md).tolist()
        self._all_rows = np.arange(len(cams))
        self._raw = np.array([c.raw for c in cams], dtype=f)
        self._count = np.array([c.count for c in cams], dtype=np.int64)
        self._offset = np.array([c.offset for c in cams], dtype=f)
        self._passes = np.array([c.passes for c in cams], dtype=f)
        self._last = np.array([c.last for c in cams], dtype=f)
        self._v = np.array([c.v for c in cams], dtype=f)
        self._a = np.array([c.a for c in cams], dtype=f)
        self._span = np.array([p.span for p in profiles], dtype=f)[self._prof]
        self._p0 = np.array([p.p_start for p in profiles], dtype=f)[self._prof]
        self._net = np.array([p.net for p in profiles], dtype=f)[self._prof]
        bank = self._bank
        self._row_base = bank.base[self._prof]
        self._row_first = bank.first_seg[self._prof]
        self._row_last = bank.last_seg[self._prof]
        self._has_pending = np.array([c.axis in self.pending for c in cams], dtype=bool)
        self._ts2 = self._ts * self._ts
        self._pass_net = self._passes * self._net  # passes * net, kept with the passes
        self._dirty = False

    def stop_requested(self, axis: int | None, stop_type: StopType) -> None:
        """MAS All / Time Cam (or MGS: axis None) frees the axis for an immediate cam in
        the same scan; the cam itself ends at the next update (end_axis)."""
        if axis is None:
            self.claim.clear()
        elif stop_type in (StopType.ALL, StopType.TIME_CAM):
            self.claim.discard(axis)
        self._claim_touched = True

    def busy(self, axis: int) -> bool:
        return bool(self.on_axis(axis))

    def links_in_use(self) -> set[int]:
        return {c.link for c in self.rows if c.link}

    def end_axis(self, axis: int, reason: EndReason, events: Events) -> tuple[float, bool]:
        """Stops (All, Time Cam), merges and kills end the axis's cams; stops and kills also
        drop its pending cam; merges and kills free the axis for an immediate cam at once
        (a stop frees it when it executes)."""
        if reason not in (Ending.KILL, Ending.MERGE_ALL, StopType.ALL, StopType.TIME_CAM):
            return 0.0, False
        cams = self.on_axis(axis)
        v = 0.0
        for c in cams:
            v += c.v
            events.append((c.handle, EventKind.ENDED, axis))
        self.remove(cams)
        if reason != Ending.MERGE_ALL:
            self.drop_pending(axis, events)
        if reason in (Ending.KILL, Ending.MERGE_ALL):
            self.claim.discard(axis)
        return v, bool(cams)

    def drop_pending(self, axis: int, ev: Events) -> None:
        """A pending cam of the axis is dropped (replaced, stopped): it ends, never counted."""
        cam = self.pending.pop(axis, None)
        if cam is not None:
            ev.append((cam.handle, EventKind.ENDED, axis))
            self.pending_changed()

    def pending_changed(self) -> None:
        self._sync_out()
        self._dirty = True

    # -- stepping -----------------------------------------------------------------
    def step(
        self,
        cup: float,
        level_sel: LevelSel,
        positions: AxisState,
        velocities: AxisState,
        events: Events,
    ) -> Contribution:
        """Advance the cams (all, or those whose axis has the given level) one update."""
        if not self.rows:
            return EMPTY
        if self._dirty:
            self._rebuild()
        if level_sel is None and not self._md_rows:  # every row, all time driven
            # a cam starts with count 0 at the update that applies it; then one more each
            count = self._count
            count += 1
            self._raw = raw = count * cup
            x = (raw - self._offset) / self._ts
            q = x / self._span
            if q.max() < 1.0 and q.min() >= 0.0:  # every cam inside its pass
                return self._step_inside(x)
            return self._step_rows(slice(None), x, None, events)
        sel = rows_at_level(level_sel, self._axis)
        if isinstance(sel, np.ndarray) and len(sel) == 0:
            return EMPTY
        self._count[sel] += 1
        self._raw[sel] = self._count[sel] * cup
        mvel: np.ndarray | None = None
        if self._md_rows:
            in_sel = set(self._all_rows[sel].tolist())
            mvel = np.ones(len(self.rows))
            for k in self._md_rows:
                if k not in in_sel:
                    continue
                c = self.rows[k]
                assert c.clock is not None
                ref, m = int(c.clock.reference), c.clock.master  # 0 actual, 1 command
                self._raw[k] = c.clock.advance(float(positions[ref][m]))
                mvel[k] = velocities[ref][m]
        x = (self._raw[sel] - self._offset[sel]) / self._ts[sel]
        return self._step_rows(sel, x, mvel, events)

    def _step_rows(
        self, sel: slice | np.ndarray, x: np.ndarray, mvel: np.ndarray | None, events: Events
    ) -> Contribution:
        """step() for the selected rows, at cam time x (in profile units): pass wraps,
        completions, hand-overs to pending cams, master-driven velocity."""
        ts = self._ts[sel]
        span = self._span[sel]
        over = x >= span
        cont = self._cont[sel]
        handover = over & self._has_pending[sel]
        complete = over & ~cont & ~handover
        # unwind continuous cams (both directions) by whole passes
        k_pass = np.where(cont & ~handover, np.floor(x / span), 0.0)
        if k_pass.any():
            self._offset[sel] += k_pass * span * ts
            self._passes[sel] += k_pass
            self._pass_net = self._passes * self._net
            x = x - k_pass * span
        local = np.minimum(np.maximum(x, 0.0), span)
        assert self._bank is not None
        r = self._bank.evaluate_rows(
            self._row_base[sel], self._row_first[sel], self._row_last[sel], local
        )
        p, v, a = r[0], r[1], r[2]
        gain = self._gain[sel]
        passes = self._passes[sel]
        contrib = gain * (p - self._p0[sel] + passes * self._net[sel])
        held = (x < 0.0) & ~cont  # before the start of a Once cam (master backing up)
        contrib = np.where(complete, gain * (self._net[sel] * (passes + 1.0)), contrib)
        mv = np.ones(len(x)) if mvel is None else mvel[sel]
        if mvel is not None:
            v = v * mv
            a = a * mv * mv
        stopped = complete | held
        vel = np.where(stopped, 0.0, gain * v / ts)
        acc = np.where(stopped, 0.0, gain * a / (ts * ts))
        dpos = contrib - self._last[sel]
        self._last[sel] = contrib
        self._v[sel] = vel
        self._a[sel] = acc
        axis = self._axis[sel]
        if complete.any() or handover.any():
            dpos = dpos.copy()
            rows = self._all_rows[sel]
            for j in np.flatnonzero(complete | handover):
                row = int(rows[j])
                dpos[j] += self._finish(
                    row, bool(handover[j]), events, vel, acc, int(j), float(mv[j])
                )
        return Contribution(axis, dpos, vel, acc)

    def _step_inside(self, x: np.ndarray) -> Contribution:
        """step() for every row, time driven, when each cam is inside its pass (0 <= x <
        span): no pass wraps, completes or hands over, nothing is held. The same
        arithmetic as step() without the selections and masks that are all empty then
        (the common update of a running cam; about half the time of the full step)."""
        assert self._bank is not None
        # x itself is the local cam time: the clamp to [0, span] of step() changes nothing
        r = self._bank.evaluate_rows(self._row_base, self._row_first, self._row_last, x)
        p, v, a = r[0], r[1], r[2]
        gain = self._gain
        contrib = gain * (p - self._p0 + self._pass_net)
        vel = gain * v / self._ts
        acc = gain * a / self._ts2
        dpos = contrib - self._last
        self._last = contrib
        self._v = vel
        self._a = acc
        return Contribution(self._axis, dpos, vel, acc)

    def _finish(
        self,
        row: int,
        handover: bool,
        events: list[tuple[int, EventKind, int]],
        vel: np.ndarray,
        acc: np.ndarray,
        j: int,
        mv: float,
    ) -> float:
        """End a cam at the end of its pass; start the pending cam with the leftover time."""
        self._sync_out()
        old = self.rows[row]
        end_value = old.gain * old.profile.net * (old.passes + 1.0)
        extra = end_value - old.last  # rows computed for handovers hold P(clamped x)
        old.last = end_value
        pass_end = old.offset + old.profile.span * old.time_scaling
        events.append(
            (
                old.handle,
                EventKind.ENDED
                if handover and old.mode == ExecutionMode.CONTINUOUS
                else EventKind.COMPLETE,
                old.axis,
            )
        )
        self._finished.append(old)  # removed in end_update()
        if not handover:
            return extra
        new = self.pending.pop(old.axis)
        # the pending cam inherits the running clock: time, or the same master distance
        new.clock = old.clock
        new.link = old.link
        new.raw = old.raw
        new.count = old.count
        new.offset = pass_end
        xn = (new.raw - new.offset) / new.time_scaling
        span = new.profile.span
        k = math.floor(xn / span) if new.mode == ExecutionMode.CONTINUOUS else 0.0
        new.offset += k * span * new.time_scaling
        new.passes = float(k)
        local = min(max(xn - k * span, 0.0), span)
        p, v, a = new.profile.evaluate(local)
        new.last = new.gain * (float(p) - new.profile.p_start + k * new.profile.net)
        new.v = new.gain * float(v) / new.time_scaling * mv
        new.a = new.gain * float(a) / new.time_scaling**2 * mv * mv
        vel[j] = new.v
        acc[j] = new.a
        events.append((new.handle, EventKind.PENDING_STARTED, new.axis))
        events.append((new.handle, EventKind.IN_PROCESS, new.axis))
        self._started.append(new)
        return extra + new.last

    def begin_update(self) -> None:
        self._finished: list[TimeCam] = []
        self._started: list[TimeCam] = []

    def end_update(self, actual: np.ndarray, events: Events) -> None:
        """Apply the removals and hand-overs collected during step()."""
        if self._finished or self._started:
            self._sync_out()
            gone = {id(c) for c in self._finished}
            self.rows = [c for c in self.rows if id(c) not in gone] + self._started
            self._dirty = True

    def velocity_sums(self, n: int) -> tuple[np.ndarray, np.ndarray]:
        """Per-axis sums of the cams' command velocity and acceleration."""
        if self._dirty:
            self._rebuild()
        if not self.rows:
            return np.zeros(n), np.zeros(n)
        return (
            np.bincount(self._axis, self._v, n),
            np.bincount(self._axis, self._a, n),
        )

    # -- queries for status arrays ---------------------------------------------------
    def active_axes(self) -> np.ndarray:
        if self._dirty:
            self._rebuild()
        return self._axis

    def edges(self) -> list[tuple[int, int]]:
        return [(c.axis, c.clock.master) for c in self.rows if c.clock is not None]

    def shift_master(self, axis: int, delta: float) -> None:
        for c in self.rows:
            if c.clock is not None:
                c.clock.shift(axis, delta)

    def status(self, n: int) -> dict[str, np.ndarray]:
        """TimeCamStatus (active), TimeCamPendingStatus, TimeCamLockStatus (following a
        master with a lock direction)."""
        if self._dirty:
            self._rebuild()
        cache = self._status_cache
        if cache is not None and cache[0] == n and not self._md_rows and not self._claim_touched:
            return cache[1]  # same cams, no master-driven lock state: nothing changed
        # asked at the end of an update, when every queued request has been applied: the
        # claim on an axis is exactly its running cam
        self.claim = set(self.active_axes().tolist())
        self.claim_mode = {c.axis: c.clock is not None for c in self.rows}
        self._claim_touched = False
        tc = np.zeros(n, dtype=bool)
        tc[self.active_axes()] = True
        tp = np.zeros(n, dtype=bool)
        tp[list(self.pending)] = True
        tl = np.zeros(n, dtype=bool)
        tl[self.locked_axes()] = True
        out = {"TimeCamStatus": tc, "TimeCamPendingStatus": tp, "TimeCamLockStatus": tl}
        self._status_cache = (n, out)
        return out

    def locked_axes(self) -> list[int]:
        return [
            c.axis
            for c in self.rows
            if c.clock is not None
            and c.clock.lock_direction != LockDirection.NONE
            and c.clock.locked
        ]


def start_time_cam(
    group: MotionGroup,
    cams: TimeCamSet,
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
    """MATC on the group's axis; profile None means not calculated (ERR 32).

    Validates at once (decision 0100: ERR/EXERR from the start call) and queues the
    start for the end of the next update."""
    if direction not in (0, 1, 2, 3):
        return bad_operand(2)
    if profile is None:
        return StartResult(error=MotionError.CAM_PROFILE_NOT_CALCULATED)
    if not math.isfinite(distance_scaling):
        return bad_operand(4)
    if not (math.isfinite(time_scaling) and time_scaling > 0.0):
        return bad_operand(5)
    if execution_mode not in (0, 1):
        return bad_operand(6)
    if execution_schedule not in (0, 1):
        return bad_operand(7)
    if not math.isfinite(lock_position):
        return bad_operand(8)
    if lock_direction not in (0, 1, 2, 3, 4):
        return bad_operand(9)
    if instruction_mode not in (0, 1):
        return bad_operand(10)
    pending = execution_schedule == ExecutionSchedule.PENDING
    master_driven = instruction_mode == InstructionMode.MASTER_DRIVEN
    if pending and lock_direction in (
        LockDirection.POSITION_FORWARD,
        LockDirection.POSITION_REVERSE,
    ):
        return StartResult(error=MotionError.LOCK_DIRECTION_CONFLICT)
    if not master_driven and lock_direction != LockDirection.NONE and not pending:
        return StartResult(error=MotionError.LOCK_DIRECTION_CONFLICT)
    if not pending and axis in cams.claim:
        return StartResult(error=MotionError.ILLEGAL_DYNAMIC_CHANGE)
    if pending and axis in cams.claim and cams.claim_mode.get(axis) != master_driven:
        # a pending cam must be in the mode of the active one (MATC seed)
        return StartResult(error=MotionError.MDSC_INVALID_MODE_OR_MASTER_CHANGE)
    if group.shutdown[axis]:
        return StartResult(error=MotionError.SHUTDOWN_STATE)
    if not group.servo_on[axis]:
        return StartResult(error=MotionError.SERVO_OFF_STATE)
    if master_driven and not pending and group.find_link(axis, MotionType.TIME_CAM) is None:
        return StartResult(error=MotionError.MDSC_NOT_ACTIVATED)
    sign = direction_sign(direction, cams.last_dir, axis)
    h = group.new_handle()
    cam = TimeCam(
        h, axis, profile, sign * distance_scaling, time_scaling, ExecutionMode(execution_mode)
    )
    if pending:

        def apply_pending(ev: list[tuple[int, EventKind, int]]) -> None:
            # a pending cam runs in the mode (and with the master) of the active cam
            cams.drop_pending(axis, ev)
            cams.pending[axis] = cam
            cams.pending_changed()

        group.after_update(apply_pending)
        return StartResult(handle=h)

    cams.claim.add(axis)
    cams.claim_mode[axis] = master_driven

    def apply(ev: list[tuple[int, EventKind, int]]) -> None:
        if master_driven:
            link = group.take_link(axis, MotionType.TIME_CAM, ev)
            assert link is not None
            cam.clock = group.master_clock(link, LockDirection(lock_direction), lock_position)
            cam.link = link.handle
            pos, _ = group.master_state(cam.clock)
            cam.raw = cam.clock.advance(pos)
            cam.offset = cam.raw
            ev.append((link.handle, EventKind.ACTIVE, axis))
        p, v, _a = profile.evaluate(profile.start)
        cam.v = cam.gain * float(v) / time_scaling if cam.clock is None else 0.0
        cams.add(cam)
        group.levels_changed()
        ev.append((h, EventKind.IN_PROCESS, axis))

    group.after_update(apply)
    return StartResult(handle=h)
