"""Profile-driven generators (move, jog, stop): each adds its position change per update."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from interpreter.motion.clock import MasterClock
from interpreter.motion.enums import EventKind, GeneratorKind, LockDirection, StopType
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
from interpreter.motion.profiles import Limits, MoveProfile


@dataclass(slots=True)
class ProfileGen:
    """A planned profile run on one axis by time (clock None) or by master distance."""

    handle: int
    kind: GeneratorKind
    axis: int
    profile: MoveProfile
    clock: MasterClock | None = None
    link: int = 0  # MDAC handle driving this generator (0: time driven)
    owner: int = 0  # MGS handle for stops started by a group stop
    t: float = -1.0  # own clock; < 0 until the first update
    n: int = 0  # updates since the start (time-driven clock = n * cup, without drift)
    last_p: float = 0.0
    v_native: float = 0.0  # velocity in profile units (per s, or per master unit)
    v: float = 0.0  # velocity in units/s
    a: float = 0.0
    phase: EventKind | None = None
    limits: Limits | None = None  # the dynamics it was planned with (MCD changes them)
    goal: float = 0.0  # moves: end point in profile coordinates (a dwelling move keeps it)
    direction: float = 1.0  # jogs: sign of the jog speed
    t_offset: float = 0.0  # master distance at which the current profile started (MCD)
    hold: bool = False  # a stop of all motion waiting for another set's motion to end

    def step(self, cup: float, master_pos: float, master_vel: float) -> float:
        """Advance the own clock one update; returns the position change."""
        if self.clock is None:
            self.n += 1
            self.t = self.n * cup
        else:
            self.t = self.clock.advance(master_pos) - self.t_offset
        p, v, a = self.profile.at(self.t)
        self.v_native = v
        if self.clock is None:
            self.v, self.a = v, a
        else:  # chain rule with the master velocity; master acceleration is neglected
            self.v, self.a = v * master_vel, a * master_vel * master_vel
        dp = p - self.last_p
        self.last_p = p
        return dp

    def replan(self, profile: MoveProfile, limits: Limits) -> None:
        """Continue on a new profile planned from the present state (its clock starts at 0
        here); the contribution made so far is kept, the goal moves with the origin."""
        self.goal -= self.last_p
        if self.clock is None:
            self.n = 0
        else:
            self.t_offset += self.t
        self.t = 0.0
        self.profile = profile
        self.limits = limits
        self.last_p = 0.0

    @property
    def finished(self) -> bool:
        return not self.hold and self.t >= self.profile.duration

    def current_phase(self) -> EventKind:
        if self.v * self.a > 1e-12 or (abs(self.v) <= 1e-12 and abs(self.a) > 1e-12):
            return EventKind.ACCEL
        if self.v * self.a < -1e-12:
            return EventKind.DECEL
        return EventKind.CONSTANT


_ALL = slice(None)
_FEW = 16  # up to this many time-driven rows are stepped on Python floats (_step_few)
_PHASES = (EventKind.ACCEL, EventKind.DECEL, EventKind.CONSTANT)
_PHASE_CODE = {None: -1, EventKind.ACCEL: 0, EventKind.DECEL: 1, EventKind.CONSTANT: 2}
_KIND_STATUS = {
    GeneratorKind.MOVE: "MoveStatus",
    GeneratorKind.JOG: "JogStatus",
    GeneratorKind.STOP: "StoppingStatus",
}


@dataclass(slots=True)
class GroupStop:
    """An MGS: complete when the stops it started on every axis have all completed."""

    handle: int
    members: set[int] = field(default_factory=set)


_ALL_KINDS = frozenset({GeneratorKind.MOVE, GeneratorKind.JOG, GeneratorKind.STOP})
# which generators a reason ends (MAS stop types not listed end none of them)
_ENDS: dict[EndReason, frozenset[GeneratorKind]] = {
    Ending.KILL: _ALL_KINDS,
    Ending.MERGE_ALL: _ALL_KINDS,
    StopType.ALL: _ALL_KINDS,
    StopType.MOVE: frozenset({GeneratorKind.MOVE}),
    StopType.JOG: frozenset({GeneratorKind.JOG}),
}


class ProfileSet:
    """The moves, jogs and stops of a group, stepped together with numpy.

    The ProfileGen objects are the state between updates (start calls, merges and MCD edit
    them); while nothing touches them the state lives in arrays, one row per generator,
    with every profile's segment table padded into one matrix. Time-driven generators need
    no Python per update; master-driven ones advance their master clock one by one (as
    time cams do). `gens` hands out the objects (arrays copied back) and marks the rows for
    a rebuild; `view()` only reads them.
    """

    def __init__(self, on_end: Callable[[ProfileGen, EventKind, Events], None]) -> None:
        self._on_end = on_end  # the group ends a generator (MGS bookkeeping, levels)
        self._gens: list[ProfileGen] = []
        self._dirty = True  # rows must be rebuilt from the objects
        self._fresh = True  # the objects hold the latest state
        self.done: list[ProfileGen] = []  # reached their end in the latest step
        self.group_stops: dict[int, GroupStop] = {}  # MGS handle -> its stops
        # status arrays while the generators are unchanged (shared with the group: read-only)
        self._status_cache: tuple[int, dict[str, np.ndarray]] | None = None

    @property
    def gens(self) -> list[ProfileGen]:
        self._sync_out()
        self._dirty = True
        return self._gens

    def view(self) -> list[ProfileGen]:
        self._sync_out()
        return self._gens

    def __len__(self) -> int:
        return len(self._gens)

    def _sync_out(self) -> None:
        if self._fresh:
            return
        f = float
        for k, g in enumerate(self._gens):
            g.n = int(self._n[k])
            g.t = f(self._t[k])
            g.last_p = f(self._last[k])
            g.v_native = f(self._vn[k])
            g.v = f(self._v[k])
            g.a = f(self._a[k])
            g.phase = None if self._phase[k] < 0 else _PHASES[self._phase[k]]
        self._fresh = True

    def _rebuild(self) -> None:
        self._status_cache = None
        gens = self._gens
        f = float
        self._axis = np.array([g.axis for g in gens], dtype=np.intp)
        self._timed = np.array([g.clock is None for g in gens], dtype=bool)
        self._md_rows = np.flatnonzero(~self._timed).tolist()
        self._n = np.array([g.n for g in gens], dtype=np.int64)
        self._t = np.array([g.t for g in gens], dtype=f)
        self._t_offset = np.array([g.t_offset for g in gens], dtype=f)
        self._last = np.array([g.last_p for g in gens], dtype=f)
        self._vn = np.array([g.v_native for g in gens], dtype=f)
        self._v = np.array([g.v for g in gens], dtype=f)
        self._a = np.array([g.a for g in gens], dtype=f)
        self._phase = np.array([_PHASE_CODE[g.phase] for g in gens], dtype=np.int64)
        kinds = list(_KIND_STATUS)
        self._kind = np.array([kinds.index(g.kind) for g in gens], dtype=np.intp)
        self._ends = np.array(
            [g.kind != GeneratorKind.JOG and not g.hold for g in gens], dtype=bool
        )
        self._duration = np.array([g.profile.duration for g in gens], dtype=f)
        width = max((len(g.profile.t0) for g in gens), default=1)
        # segment k of row r: start time in _t0[r, k] (padding never starts), and its
        # (start, p, v, a, jerk) in _coef[r * width + k]
        self._t0 = np.full((len(gens), width), np.inf)
        coef = np.zeros((len(gens) * width, 5))
        for r, g in enumerate(gens):
            pr = g.profile
            m = len(pr.t0)
            self._t0[r, :m] = pr.t0
            coef[r * width : r * width + m] = np.column_stack((pr.t0, pr.p0, pr.v0, pr.a0, pr.j))
        self._coef = coef
        self._base = np.arange(len(gens), dtype=np.intp) * width
        self._all_rows = np.arange(len(gens))
        self._few_seg: list[tuple[float, float, list[float]]] | None = None  # _step_few
        self._seg_c = self._coef[:0]  # step: the segment rows of every row, kept until
        self._next_start: np.ndarray | None = None  # a row reaches its next start (None)
        self._dirty = False

    # -- stepping -----------------------------------------------------------------
    def step(
        self,
        cup: float,
        level_sel: LevelSel,
        positions: AxisState,
        velocities: AxisState,
        events: Events,
    ) -> Contribution:
        """Advance the generators (all, or those whose axis has the given level) one update.
        Generators that reached their end are left in `done` (the group ends them)."""
        self.done = []
        if not self._gens:
            return EMPTY
        if self._dirty:
            self._rebuild()
        sel = rows_at_level(level_sel, self._axis)
        if isinstance(sel, np.ndarray) and len(sel) == 0:
            return EMPTY
        self._fresh = False
        if not self._md_rows and isinstance(sel, slice) and len(self._gens) <= _FEW:
            return self._step_few(cup, events)
        self._n[sel] += self._timed[sel]  # a time-driven clock is counted updates (no drift)
        t = self._n[sel] * cup
        mvel: np.ndarray | None = None
        if self._md_rows:
            t = self._master_times(sel, positions, velocities, t)
            mvel = self._mvel
        self._t[sel] = t
        if mvel is not None:  # a master backing up before the start holds the profile at 0
            t = np.maximum(t, 0.0)
        if mvel is None and isinstance(sel, slice):  # every row, all time driven
            # the segments in use are kept until a row's clock reaches its next segment
            # start: the clocks only count up, so no segment changes before then
            nxt = self._next_start
            if nxt is None or not (t < nxt).all():
                self._seg_c, self._next_start = self._segments(t)
            c = self._seg_c
        else:
            c = self._segments(t, sel)[0]
        d = t - c[:, 0]
        v0, a0, jj = c[:, 2], c[:, 3], c[:, 4]
        p = c[:, 1] + d * (v0 + d * (a0 / 2.0 + d * jj / 6.0))
        v = v0 + d * (a0 + d * jj / 2.0)
        a = a0 + d * jj
        self._vn[sel] = v
        if mvel is None:
            vel, acc = v, a
        else:  # master driven: chain rule, master acceleration neglected
            mv = mvel if level_sel is None else mvel[sel]
            vel, acc = v * mv, a * mv * mv
        self._v[sel] = vel
        self._a[sel] = acc
        dp = p - self._last[sel]
        self._last[sel] = p
        va = vel * acc
        phase = np.where(
            (va > 1e-12) | ((np.abs(vel) <= 1e-12) & (np.abs(acc) > 1e-12)),
            0,
            np.where(va < -1e-12, 1, 2),
        )
        changed = phase != self._phase[sel]
        finished = self._ends[sel] & (self._t[sel] >= self._duration[sel])
        done = self.done
        flagged = changed | finished
        if flagged.any():
            self._phase[sel] = phase
            rows = self._all_rows[sel]
            for j in np.flatnonzero(flagged).tolist():
                g = self._gens[int(rows[j])]
                if changed[j]:
                    events.append((g.handle, _PHASES[int(phase[j])], g.axis))
                if finished[j]:
                    done.append(g)
        out = Contribution(self._axis[sel], dp, vel, acc)
        for g in done:
            self._on_end(g, EventKind.COMPLETE, events)
        return out

    def _step_few(self, cup: float, events: Events) -> Contribution:
        """step() of every row when there are only a few, all time driven: the same
        arithmetic, operation by operation, on Python floats (IEEE doubles as in numpy, so
        the results are identical); numpy's cost per call would outweigh the work. The
        segment in use is kept with the time the next one starts: the clock only counts
        up, so it stays in use until then."""
        seg_at = self._few_seg
        if seg_at is None:  # after a rebuild: the rows as lists, no segment known yet
            self._few_rows = (self._t0.tolist(), self._coef.tolist(), self._base.tolist())
            seg_at = self._few_seg = [(math.inf, math.inf, [])] * len(self._gens)
        t0s, coefs, bases = self._few_rows
        n_arr, last_arr, phase_arr = self._n, self._last, self._phase
        ends, durations = self._ends, self._duration
        rows = len(self._gens)
        dps, vels, accs = [0.0] * rows, [0.0] * rows, [0.0] * rows
        done = self.done
        for r in range(rows):
            k = int(n_arr[r]) + 1
            n_arr[r] = k
            t = k * cup
            self._t[r] = t
            start, until, c = seg_at[r]
            if not start <= t < until:  # the last segment started at t, and the next start
                row = t0s[r]
                seg = sum(1 for x in row if x <= t) - 1
                until = min((x for x in row if x > t), default=math.inf)
                c = coefs[bases[r] + seg]
                seg_at[r] = (t, until, c)
            d = t - c[0]
            v0, a0, jj = c[2], c[3], c[4]
            p = c[1] + d * (v0 + d * (a0 / 2.0 + d * jj / 6.0))
            v = v0 + d * (a0 + d * jj / 2.0)
            a = a0 + d * jj
            self._vn[r] = v
            self._v[r] = v
            self._a[r] = a
            dps[r] = p - float(last_arr[r])
            last_arr[r] = p
            vels[r], accs[r] = v, a
            va = v * a
            if va > 1e-12 or (abs(v) <= 1e-12 and abs(a) > 1e-12):
                phase = 0
            else:
                phase = 1 if va < -1e-12 else 2
            if phase != phase_arr[r]:
                phase_arr[r] = phase
                g = self._gens[r]
                events.append((g.handle, _PHASES[phase], g.axis))
            if ends[r] and t >= durations[r]:
                done.append(self._gens[r])
        out = Contribution(self._axis, np.array(dps), np.array(vels), np.array(accs))
        for g in done:
            self._on_end(g, EventKind.COMPLETE, events)
        return out

    def _segments(
        self, t: np.ndarray, sel: slice | np.ndarray = _ALL
    ) -> tuple[np.ndarray, np.ndarray]:
        """Per row: the coefficients of the segment in use at t (the last one started at
        t; segment 0 starts at 0) and the next segment start after t (inf: none)."""
        t0 = self._t0[sel]
        later = t0 > t[:, None]
        seg = (~later).sum(axis=1) - 1
        return self._coef[self._base[sel] + seg], np.where(later, t0, np.inf).min(axis=1)

    def begin_update(self) -> None:
        pass

    def end_update(self, actual: np.ndarray, events: Events) -> None:
        pass

    def edges(self) -> list[tuple[int, int]]:
        return [(g.axis, g.clock.master) for g in self.view() if g.clock is not None]

    def stop_requested(self, axis: int | None, stop_type: StopType) -> None:
        pass

    def busy(self, axis: int) -> bool:
        return any(g.axis == axis for g in self.view())

    def links_in_use(self) -> set[int]:
        return {g.link for g in self.view() if g.link}

    def end_axis(self, axis: int, reason: EndReason, events: Events) -> tuple[float, bool]:
        kinds = _ENDS.get(reason, frozenset())
        ending = [g for g in self.gens if g.axis == axis and g.kind in kinds]
        v = 0.0
        for g in ending:
            v += g.v
            self._on_end(g, EventKind.ENDED, events)
        return v, bool(ending)

    def shift_master(self, axis: int, delta: float) -> None:
        for g in self.view():
            if g.clock is not None:
                g.clock.shift(axis, delta)

    def _master_times(
        self,
        sel: slice | np.ndarray,
        positions: tuple[np.ndarray, np.ndarray],
        velocities: tuple[np.ndarray, np.ndarray],
        t: np.ndarray,
    ) -> np.ndarray:
        """Own clocks of the master-driven rows in sel (master distance, one by one); their
        master velocities are left in _mvel (1 for time-driven rows)."""
        rows = self._all_rows[sel]
        where = {int(r): j for j, r in enumerate(rows.tolist())}
        self._mvel = np.ones(len(self._gens))
        t = t.copy()
        for k in self._md_rows:
            j = where.get(k)
            if j is None:
                continue
            clock = self._gens[k].clock
            assert clock is not None
            ref, m = int(clock.reference), clock.master  # 0 actual, 1 command
            t[j] = clock.advance(float(positions[ref][m])) - self._t_offset[k]
            self._mvel[k] = velocities[ref][m]
        return t

    # -- queries ------------------------------------------------------------------
    def velocity_sums(self, n: int) -> tuple[np.ndarray, np.ndarray]:
        if self._dirty:
            self._rebuild()
        if not self._gens:
            return np.zeros(n), np.zeros(n)
        return np.bincount(self._axis, self._v, n), np.bincount(self._axis, self._a, n)

    def status(self, n: int) -> dict[str, np.ndarray]:
        """MoveStatus, JogStatus, StoppingStatus and the lock bits of master-driven moves
        and jogs that follow their master (a lock direction other than None, locked)."""
        if self._dirty:
            self._rebuild()
        cache = self._status_cache
        if cache is not None and cache[0] == n and not self._md_rows:
            return cache[1]  # same generators, no master-driven lock state: nothing changed
        out = {}
        for code, name in enumerate(_KIND_STATUS.values()):
            arr = np.zeros(n, dtype=bool)
            arr[self._axis[self._kind == code]] = True
            out[name] = arr
        out["MoveLockStatus"] = np.zeros(n, dtype=bool)
        out["JogLockStatus"] = np.zeros(n, dtype=bool)
        for k in self._md_rows:  # the master clocks live in the objects
            g = self._gens[k]
            c = g.clock
            assert c is not None
            if c.lock_direction != LockDirection.NONE and c.locked:
                if g.kind == GeneratorKind.MOVE:
                    out["MoveLockStatus"][g.axis] = True
                elif g.kind == GeneratorKind.JOG:
                    out["JogLockStatus"][g.axis] = True
        self._status_cache = (n, out)
        return out
