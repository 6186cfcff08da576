"""Coordinated paths (MCLM, MCCM, MCS): the axes of a coordinate system along a Segment.

A path move runs the closed-form move profile of profiles.py (the one MAM uses) on its
path parameter s, the arc length along its Segment (path_geometry.py); the axes follow
p(s). Every path row of the group (one per running move, across all coordinate systems)
is evaluated together: the profiles' segment tables are padded into one matrix, the
geometry is one SegmentTable, and rows x the next updates go through one numpy pass
(paths are time driven, so nothing but a start, blend, end or stop changes them).

A coordinate system keeps one move queued behind the active one (SPEC 9.28). Blending
(termination types 2, 3, 6 and, here, 4 and 5) starts the queued move while the active one
is still running; both rows then contribute and their motions add up, so the vector speed
does not drop to zero between tangent moves. Decisions: docs/decisions/0122..0125.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from enum import IntEnum
from typing import TYPE_CHECKING

import numpy as np

from interpreter.motion.enums import EventKind, StopType
from interpreter.motion.path_geometry import GeometryError, Segment, SegmentTable
from interpreter.motion.process import (
    EMPTY,
    AxisState,
    Contribution,
    Ending,
    EndReason,
    Events,
    LevelSel,
)
from interpreter.motion.profiles import (
    Limits,
    MoveProfile,
    change_distance,
    plan_move,
    plan_stop,
)

if TYPE_CHECKING:  # bound as MotionGroup methods; only the annotations need the class
    pass

Build = Callable[[np.ndarray], Segment | GeometryError]

_EPS = 1e-9
_CLOCK_EPS = 1e-9  # s: a profile whose duration the update clock misses by rounding ends


class Termination(IntEnum):
    """TerminationType operand values (catalog enum TerminationType)."""

    ACTUAL_TOLERANCE = 0
    NO_SETTLE = 1
    COMMAND_TOLERANCE = 2
    NO_DECEL = 3
    FOLLOW_CONTOUR_CONSTRAINED = 4
    FOLLOW_CONTOUR_UNCONSTRAINED = 5
    COMMAND_TOLERANCE_PROGRAMMED = 6


# termination types that blend from the active move's deceleration point
_AT_DECEL_POINT = frozenset(
    {
        Termination.NO_DECEL,
        Termination.FOLLOW_CONTOUR_CONSTRAINED,
        Termination.FOLLOW_CONTOUR_UNCONSTRAINED,
    }
)


@dataclass(slots=True)
class PathMove:
    """One MCLM/MCCM: a segment, its dynamics and how it ends; a row while it moves."""

    handle: int
    system: int
    segment: Segment
    limits: Limits
    termination: int
    tolerance: float  # blend distance of termination 2/6 (system's or the operand)
    profile: MoveProfile | None = None
    owner: int = 0  # handle its events go to (a stopping move reports to the MCS)
    n: int = 0  # updates since its profile started
    s0: float = 0.0  # path parameter where the profile starts (a stop replans from s)
    s: float = 0.0
    v: float = 0.0
    a: float = 0.0
    last: np.ndarray = field(default_factory=lambda: np.zeros(3))  # point reached (3D)
    phase: int = -1  # 0 accel, 1 decel, 2 constant
    blend_s: float = math.inf  # s from which the queued move may start
    tol_s: float = math.inf  # s from which the remaining path is within CommandTolerance
    settling: bool = False  # termination 0: profile done, waiting for the actual position
    # packed once per segment / profile for the set's arrays (_pack): the SegmentTable row
    # (start, end, a, b, rate, length, arc) and the profile's (t0, p0, v0, a0, j) rows
    geo: np.ndarray = field(default_factory=lambda: np.zeros(15))
    coef: np.ndarray = field(default_factory=lambda: np.zeros((1, 5)))
    duration: float = 0.0

    def use_profile(self, profile: MoveProfile) -> None:
        """Run this profile from here (its table packed for the set's arrays)."""
        self.profile = profile
        self.coef = np.column_stack((profile.t0, profile.p0, profile.v0, profile.a0, profile.j))
        self.duration = profile.duration

    def pack_segment(self) -> None:
        seg = self.segment
        table = SegmentTable.of([seg])
        self.geo = np.concatenate(
            (table.start[0], table.end[0], table.a[0], table.b[0],
             [table.rate[0], table.length[0], float(table.arc[0])])
        )  # fmt: skip


@dataclass(slots=True)
class CoordSystem:
    """A coordinate system of the group: its axes, moving rows and the one-deep queue."""

    axes: tuple[int, ...]
    command_tolerance: float = 0.1
    actual_tolerance: float = 0.01
    max_decel: float = math.inf
    max_decel_jerk: float = math.inf
    rows: list[PathMove] = field(default_factory=list)  # moving (the leading one last)
    lead: PathMove | None = None  # the active move (the queued one starts after it)
    queue: list[PathMove] = field(default_factory=list)  # accepted, not started
    stop: int = 0  # MCS handle while stopping
    cmd_tol: bool = False  # CommandPosToleranceStatus (kept until a new move starts)
    act_tol: bool = False  # ActualPosToleranceStatus

    @property
    def ndim(self) -> int:
        return len(self.axes)

    def end_point(self) -> np.ndarray | None:
        """Where the last accepted move ends (the next one starts there), if any."""
        if self.queue:
            return self.queue[-1].segment.end
        if self.lead is not None and self.stop == 0:
            return self.lead.segment.end
        return None


_PHASES = (EventKind.ACCEL, EventKind.DECEL, EventKind.CONSTANT)


class PathSet:
    """The coordinate systems of a group and their moving path rows, stepped together."""

    def __init__(self) -> None:
        self.systems: list[CoordSystem] = []
        self._rows: list[PathMove] = []
        self._dirty = True
        self._fresh = True  # the row objects hold the latest state
        # rows whose profile ended (True) or that reached their blend point, latest step
        self._done: list[tuple[PathMove, bool]] = []
        self._status_cache: tuple[int, dict[str, np.ndarray]] | None = None
        self._check = False  # end_update must look at the systems (a queue, a settling move)
        self.version = 0  # counts changes of what system_status reports (readers cache on it)
        self._settling = 0  # rows waiting for the actual position (termination 0)
        self._k = -1  # row of the chunk handed out by the latest step
        self._K = 0  # rows in the chunk (0: none)
        self._chunk_len = self.CHUNK  # updates the next chunk evaluates at most
        # lands the axes of a system that came to rest exactly on its end point (the
        # per-update increments add up to it only to rounding); set by the group
        self.snap: Callable[[tuple[int, ...], np.ndarray], None] | None = None

    # -- rows ------------------------------------------------------------------
    # Paths are time driven and deterministic between events (a start, a blend, an end, a
    # stop), so the rows are evaluated for the next CHUNK updates at once, vectorised over
    # rows and time; an update then hands out one precomputed row. Anything that changes
    # the rows (changed()) drops the rest of the chunk. The values do not depend on the
    # chunk length (row n is evaluated at n * cup whatever chunk holds it), only the cost
    # does: a chunk used up to its end is followed by one twice as long, up to CHUNK_MAX
    # (one system's path: few numpy passes per move), and a rebuild starts again at CHUNK
    # (many systems: a start in any of them drops the rest, so long chunks are wasted).
    CHUNK = 64
    CHUNK_MAX = 512

    def _sync_out(self) -> None:
        """The state of the latest step back into the row objects."""
        if self._fresh or self._dirty:
            return
        k = self._k
        for i, r in enumerate(self._rows):
            r.n = int(self._n0[i]) + k + 1
            r.s = float(self._S[k, i])
            r.v = float(self._V[k, i])
            r.a = float(self._A[k, i])
            r.last = self._P[k, i].copy()
            r.phase = int(self._PH[k, i])
        self._fresh = True

    def changed(self) -> None:
        """Rows or queues changed: state back into the objects, arrays rebuilt at the next step."""
        self._sync_out()
        self._dirty = True
        self._check = True
        self._status_cache = None
        self.version += 1

    def _rebuild(self) -> None:
        """The struct-of-arrays form of the rows, from what each row packed once (its
        segment's table row and its profile's segment table: _pack)."""
        rows = self._rows
        m = len(rows)
        geo = np.array([r.geo for r in rows], dtype=float).reshape(m, 15)
        self.table = SegmentTable(
            geo[:, 0:3], geo[:, 3:6], geo[:, 6:9], geo[:, 9:12], geo[:, 12], geo[:, 13],
            geo[:, 14] > 0.5,
        )  # fmt: skip
        width = max((len(r.coef) for r in rows), default=1)
        coef = np.zeros((m, width, 5))
        coef[:, :, 0] = np.inf  # padding never starts
        for i, r in enumerate(rows):
            coef[i, : len(r.coef)] = r.coef
        self._t0 = coef[:, :, 0].copy()
        coef[:, :, 0] = np.where(np.isinf(coef[:, :, 0]), 0.0, coef[:, :, 0])
        self._coef = coef.reshape(m * width, 5)
        self._base = np.arange(m, dtype=np.intp) * width
        self._duration = np.array([r.duration for r in rows], dtype=float)
        self._s_end = np.array([r.s0 + r.coef[-1, 1] for r in rows], dtype=float)
        self._n0 = np.array([r.n for r in rows], dtype=np.int64)
        self._s0 = np.array([r.s0 for r in rows], dtype=float)
        self._last0 = np.array([r.last for r in rows], dtype=float).reshape(m, 3)
        self._phase0 = np.array([r.phase for r in rows], dtype=np.int64)
        queued = {id(cs.lead) for cs in self.systems if cs.queue and cs.lead is not None}
        self._blend = np.array(
            [r.blend_s if id(r) in queued else math.inf for r in rows], dtype=float
        )
        self._tol = np.array([r.tol_s for r in rows], dtype=float)
        # one contribution entry per (row, axis of its system)
        ax: list[int] = []
        ri: list[int] = []
        col: list[int] = []
        for i, r in enumerate(rows):
            axes = self.systems[r.system].axes
            ax.extend(axes)
            ri.extend([i] * len(axes))
            col.extend(range(len(axes)))
        self._ax = np.array(ax, dtype=np.intp)
        self._ri = np.array(ri, dtype=np.intp)
        self._col = np.array(col, dtype=np.intp)
        self._k, self._K = -1, 0  # no chunk yet
        self._chunk_len = self.CHUNK
        self._dirty = False
        self._fresh = True

    def _chunk(self, cup: float) -> None:
        """Evaluate every row at its next updates (one numpy pass over rows x time): CHUNK
        of them, or up to the update where the first profile ends (the rows change there)."""
        m = len(self._rows)
        rem = self._duration - self._n0 * cup  # time to each profile's end (inf: never)
        rem = rem[(rem > _CLOCK_EPS) & np.isfinite(rem)]
        kk = self._chunk_len
        if len(rem):
            kk = max(1, min(kk, math.ceil(float(rem.min()) / cup - 1e-6) + 1))
        self._K = kk
        n = self._n0[None, :] + np.arange(1, kk + 1)[:, None]  # (K, m)
        t = n * cup
        seg = (self._t0[None, :, :] <= t[:, :, None]).sum(axis=2) - 1
        c = self._coef[self._base[None, :] + seg]  # (K, m, 5)
        d = t - c[..., 0]
        v0, a0, jj = c[..., 2], c[..., 3], c[..., 4]
        s = self._s0[None, :] + c[..., 1] + d * (v0 + d * (a0 / 2.0 + d * jj / 6.0))
        v = v0 + d * (a0 + d * jj / 2.0)
        a = a0 + d * jj
        # the last update of a profile lands on its end exactly (the segment's end point),
        # also when the clock passes the duration by rounding (0.1 + 0.1 + 0.1 > 0.3)
        finished = t >= self._duration[None, :] - _CLOCK_EPS
        s = np.where(finished, self._s_end[None, :], s)
        tb = self.table
        rows = np.broadcast_to(np.arange(m), (kk, m)).reshape(-1)
        sf = s.reshape(-1)
        pts = tb.points(rows, sf).reshape(kk, m, 3)
        tan = tb.tangents(rows, sf).reshape(kk, m, 3)
        # curvature term of the acceleration: d2p/ds2 = -k^2 (cos(ks) A + sin(ks) B) on arcs
        k = tb.rate[rows]
        ks = k * np.clip(sf, 0.0, tb.length[rows])
        k2 = k * k
        curv = -(k2 * np.cos(ks))[:, None] * tb.a[rows] - (k2 * np.sin(ks))[:, None] * tb.b[rows]
        curv = curv.reshape(kk, m, 3)
        vel = v[..., None] * tan
        acc = a[..., None] * tan + (v * v)[..., None] * curv
        dpos = np.diff(pts, axis=0, prepend=self._last0[None, :, :])
        va = v * a
        phase = np.where(
            (va > 1e-12) | ((np.abs(v) <= 1e-12) & (np.abs(a) > 1e-12)),
            0,
            np.where(va < -1e-12, 1, 2),
        )
        prev = np.vstack((self._phase0[None, :], phase[:-1]))
        changed = phase != prev
        blend = s >= self._blend[None, :] - _EPS
        tol = s >= self._tol[None, :] - _EPS
        self._changed, self._finished, self._blend_hit, self._tol_hit = (
            changed, finished, blend, tol,
        )  # fmt: skip
        self._flags = (changed | finished | blend | tol).any(axis=1).tolist()
        ri, col = self._ri, self._col
        self._dpos = dpos[:, ri, col]
        self._vel = vel[:, ri, col]
        self._acc = acc[:, ri, col]
        self._S, self._V, self._A, self._P, self._PH = s, v, a, pts, phase

    # -- ProcessSet ------------------------------------------------------------
    def begin_update(self) -> None:
        pass

    def step(
        self,
        cup: float,
        level_sel: LevelSel,
        positions: AxisState,
        velocities: AxisState,
        events: Events,
    ) -> Contribution:
        """Advance every path row one update (paths are time driven: level 0 only)."""
        if self._done:
            self._done = []
        if not self._rows or (level_sel is not None and level_sel[1] != 0):
            return EMPTY
        if self._dirty:
            self._rebuild()
        k = self._k + 1
        if k >= self._K:  # the next stretch of updates, from the state of the last one
            if self._K:
                self._n0 = self._n0 + self._K
                self._s_base_shift()
                if self._K >= self._chunk_len:  # used up whole: the next one is longer
                    self._chunk_len = min(2 * self._chunk_len, self.CHUNK_MAX)
            self._chunk(cup)
            k = 0
        self._k = k
        self._fresh = False
        if self._flags[k]:
            self._events(k, events)
        return Contribution(self._ax, self._dpos[k], self._vel[k], self._acc[k])

    def _s_base_shift(self) -> None:
        """A chunk was used up: the next one continues from its last row."""
        last = self._K - 1
        self._last0 = self._P[last].copy()
        self._phase0 = self._PH[last].copy()

    def _events(self, k: int, events: Events) -> None:
        """Phase changes, ends, blend points and command tolerance reached at update k."""
        self.version += 1
        done: list[tuple[PathMove, bool]] = []
        for i in np.flatnonzero(self._changed[k]).tolist():
            r = self._rows[i]
            events.append((r.owner, _PHASES[int(self._PH[k, i])], self.systems[r.system].axes[0]))
        for i in np.flatnonzero(self._tol_hit[k]).tolist():
            r = self._rows[i]
            cs = self.systems[r.system]
            if cs.lead is r:
                cs.cmd_tol = True
            r.tol_s = math.inf
            self._check = True
            self._tol[i] = math.inf  # reported once (the chunk keeps the old flags)
            self._tol_hit[k + 1 :, i] = False
            self._flags = (
                (self._changed | self._finished | self._blend_hit | self._tol_hit)
                .any(axis=1)
                .tolist()
            )
        for i in np.flatnonzero(self._finished[k] | self._blend_hit[k]).tolist():
            done.append((self._rows[i], bool(self._finished[k, i])))
        self._done = done

    def end_update(self, actual: np.ndarray, events: Events) -> None:
        """Ended profiles complete (termination 0 once the actual position is in tolerance),
        blend points reached start the queued move, idle systems start their queued move."""
        if not (self._done or self._check or self._settling):
            return
        self._check = False
        if self._done:
            self._sync_out()
            for r, ended in self._done:
                cs = self.systems[r.system]
                if cs.lead is r and cs.queue and r.s >= r.blend_s - _EPS:
                    self._start_next(cs, events)  # blend: r keeps running underneath
                if not ended or r not in cs.rows or r.settling:
                    continue
                if r.termination == Termination.ACTUAL_TOLERANCE and r.owner == r.handle:
                    r.settling = True
                    self._settling += 1
                else:
                    self._finish(cs, r, events)
            self._done = []
        for cs in self.systems:
            if not (cs.rows or cs.queue):
                continue
            for r in [r for r in cs.rows if r.settling]:
                self._sync_out()
                err = float(np.linalg.norm(actual[list(cs.axes)] - r.segment.end))
                if err <= cs.actual_tolerance + _EPS:
                    cs.act_tol = True
                    self._finish(cs, r, events)
                self._check = True  # look again at the next update
            if cs.lead is None and cs.queue and cs.stop == 0:
                self._start_next(cs, events)

    def _finish(self, cs: CoordSystem, r: PathMove, events: Events) -> None:
        """A row reached its end: PC for its move (or, for a stop, when the last row ends)."""
        self.changed()
        if r.settling:
            self._settling -= 1
        r.settling = False
        if r in cs.rows:
            cs.rows.remove(r)
        self._rows.remove(r)
        if cs.lead is r:
            cs.lead = None
        if r.owner == r.handle:
            events.append((r.handle, EventKind.COMPLETE, cs.axes[0]))
            if not cs.rows and self.snap is not None:
                self.snap(cs.axes, r.segment.end)
        elif not any(x.owner == r.owner for x in cs.rows):
            events.append((r.owner, EventKind.COMPLETE, cs.axes[0]))
            cs.stop = 0

    def _start_next(self, cs: CoordSystem, events: Events) -> None:
        self.start_row(cs, cs.queue.pop(0), 0.0, events)

    def start_row(self, cs: CoordSystem, mv: PathMove, v0: float, events: Events) -> None:
        """The move starts at this update: own clock 0, contribution 0, speed v0."""
        self.changed()
        mv.use_profile(plan_move(mv.segment.length, mv.limits, v0))
        mv.pack_segment()
        mv.owner = mv.handle
        mv.n, mv.s0, mv.s, mv.v, mv.a = 0, 0.0, 0.0, v0, 0.0
        last = np.zeros(3)
        last[: cs.ndim] = mv.segment.start
        mv.last = last
        mv.blend_s = _blend_point(mv)
        mv.tol_s = mv.segment.tolerance_point(cs.command_tolerance)
        cs.rows.append(mv)
        cs.lead = mv
        cs.cmd_tol = cs.act_tol = False
        self._rows.append(mv)
        axis = cs.axes[0]
        events.append((mv.handle, EventKind.IN_PROCESS, axis))
        mv.phase = 0 if mv.duration > 0 and v0 < mv.limits.speed else 2
        events.append((mv.handle, _PHASES[mv.phase], axis))
        if mv.segment.length <= _EPS and mv.duration <= 0.0:
            self._finish(cs, mv, events)

    def replan(self, r: PathMove, lim: Limits) -> None:
        """MCCD: the running row continues from its present path position, speed and
        acceleration with the limits lim, to the same end point (an S-curve first brings
        its acceleration to 0 at the jerk: profiles.plan_move). A row that could no longer
        come to rest by its end point with lim (in its final deceleration, with a lower
        decel or jerk) keeps the profile it runs: the path never runs past its end."""
        self.changed()  # the row's latest state is in the object from here
        remaining = r.segment.length - r.s
        prof = plan_move(remaining, lim, r.v, r.a)
        if len(prof.p0) > 1 and float(prof.p0[:-1].max()) > remaining + 1e-9 * max(
            1.0, r.segment.length
        ):
            return
        r.limits = lim
        r.use_profile(prof)
        r.s0, r.n = r.s, 0
        r.a = float(r.coef[0, 3]) if r.duration > 0.0 else 0.0
        r.blend_s = _blend_point(r)

    def velocity_sums(self, n: int) -> tuple[np.ndarray, np.ndarray]:
        vel, acc = np.zeros(n), np.zeros(n)
        self._sync_out()
        for r in self._rows:
            axes = list(self.systems[r.system].axes)
            k = len(axes)
            tan = self._tangent(r)
            vel[axes] += r.v * tan[:k]
            acc[axes] += r.a * tan[:k]
        return vel, acc

    @staticmethod
    def _tangent(r: PathMove) -> np.ndarray:
        t = np.zeros(3)
        t[: r.segment.ndim] = r.segment.tangent(np.array([r.s]))[0]
        return t

    def edges(self) -> list[tuple[int, int]]:
        return []  # time driven only (master-driven coordinated motion needs MDCC)

    def shift_master(self, axis: int, delta: float) -> None:
        pass

    def status(self, n: int) -> dict[str, np.ndarray]:
        """CoordinatedMotionStatus of the axes of systems with a move running or queued."""
        cache = self._status_cache
        if cache is not None and cache[0] == n:
            return cache[1]
        arr = np.zeros(n, dtype=bool)
        for cs in self.systems:
            if cs.rows or cs.queue:
                arr[list(cs.axes)] = True
        out = {"CoordinatedMotionStatus": arr}
        self._status_cache = (n, out)
        return out

    def end_axis(self, axis: int, reason: EndReason, events: Events) -> tuple[float, bool]:
        """A stop (MAS All) or a merging single-axis move on a member axis brings the
        system to rest along its path at its maximum deceleration; servo off, shutdown and
        homing end the path at once (the axis's velocity component is handed on)."""
        v_axis, any_ended = 0.0, False
        for cs_id, cs in enumerate(self.systems):
            if axis not in cs.axes or not (cs.rows or cs.queue) or cs.stop:
                continue
            if reason is Ending.KILL:
                self._sync_out()
                k = cs.axes.index(axis)
                for r in list(cs.rows):
                    v_axis += r.v * float(self._tangent(r)[k])
                self._end_all(cs, events)
                any_ended = True
            elif reason in (Ending.MERGE_ALL, StopType.ALL):
                self.stop_system(cs_id, 0, cs.max_decel, cs.max_decel_jerk, events)
        return v_axis, any_ended

    def _end_all(self, cs: CoordSystem, events: Events) -> None:
        """Every move of the system ends without PC (running and queued)."""
        self.changed()
        axis = cs.axes[0]
        owners: list[int] = []
        for r in cs.rows:
            self._rows.remove(r)
            if r.settling:
                self._settling -= 1
                r.settling = False
            if r.owner not in owners:
                owners.append(r.owner)
        for h in owners:
            events.append((h, EventKind.ENDED, axis))
        for q in cs.queue:
            events.append((q.handle, EventKind.ENDED, axis))
        cs.rows, cs.queue, cs.lead, cs.stop = [], [], None, 0

    def stop_system(
        self, cs_id: int, handle: int, decel: float, jerk: float, events: Events
    ) -> None:
        """MCS (handle; 0: no instruction waits for it): each running row decelerates to
        rest along its own path; the queue is cancelled; the moves end without PC."""
        cs = self.systems[cs_id]
        self.changed()
        axis = cs.axes[0]
        for q in cs.queue:
            events.append((q.handle, EventKind.ENDED, axis))
        cs.queue = []
        for r in cs.rows:
            if r.owner == r.handle:
                events.append((r.handle, EventKind.ENDED, axis))
            r.owner = handle if handle else -cs_id - 1
            # a trapezoidal move stops with a trapezoidal ramp; S-curve with the stop's jerk
            j = jerk if math.isfinite(r.limits.decel_jerk) else math.inf
            r.use_profile(plan_stop(r.v, Limits(0.0, decel, decel, j, j)))
            r.s0, r.n = r.s, 0
            if r.settling:
                self._settling -= 1
            r.settling = False
            r.blend_s = r.tol_s = math.inf
        cs.lead = None
        if cs.rows:
            cs.stop = handle if handle else -cs_id - 1
            events.append((cs.stop, EventKind.DECEL, axis))
        elif handle:
            events.append((handle, EventKind.COMPLETE, axis))

    def busy(self, axis: int) -> bool:
        return any(axis in cs.axes and (cs.rows or cs.queue) for cs in self.systems)

    def links_in_use(self) -> set[int]:
        return set()

    def stop_requested(self, axis: int | None, stop_type: StopType) -> None:
        pass

    # -- what the bridge shows ---------------------------------------------------
    def profile_of(self, handle: int) -> MoveProfile | None:
        """The planned profile (path parameter over time) of a running move."""
        for r in self._rows:
            if r.handle == handle and r.owner == handle:
                return r.profile
        return None

    def system_status(self, cs_id: int) -> dict[str, bool]:
        """The coordinate system's status members (names of the COORDINATE_SYSTEM type)."""
        cs = self.systems[cs_id]
        self._sync_out()
        moving = [r for r in cs.rows if r.owner == r.handle]
        blending = len(moving) > 1
        lead = cs.lead
        accel = decel = False
        if lead is not None and not blending and cs.stop == 0:
            accel, decel = lead.phase == 0, lead.phase == 1
        elif cs.stop and cs.rows:
            decel = any(r.v > _EPS for r in cs.rows)
        pending = bool(cs.queue) and (lead is not None or len(cs.queue) > 1)
        # blending collinear lines keeps the axes on the path: no transition (MCCM seed)
        off_path = blending and not _collinear(moving)
        return {
            "MotionStatus": bool(cs.rows or cs.queue),
            "AccelStatus": accel,
            "DecelStatus": decel,
            "ActualPosToleranceStatus": cs.act_tol,
            "CommandPosToleranceStatus": cs.cmd_tol,
            "StoppingStatus": cs.stop != 0,
            "MoveStatus": bool(moving) or bool(cs.queue and cs.stop == 0),
            "MoveTransitionStatus": off_path,
            "MovePendingStatus": pending,
            "MovePendingQueueFullStatus": pending,
        }


def _collinear(moves: list[PathMove]) -> bool:
    """Straight lines all in one direction (their superposition stays on the line)."""
    first = moves[0].segment
    return all(
        not m.segment.is_arc
        and m.segment.length > _EPS
        and float(np.dot(first.u, m.segment.u)) > 1.0 - 1e-9
        for m in moves
    )


def _blend_point(mv: PathMove) -> float:
    """Path parameter from which the queued move may start (inf: only after the end)."""
    length = mv.segment.length
    if mv.termination in (Termination.COMMAND_TOLERANCE, Termination.COMMAND_TOLERANCE_PROGRAMMED):
        # the tolerance is a distance to the end point (a chord on an arc)
        return mv.segment.tolerance_point(mv.tolerance)
    if mv.termination in _AT_DECEL_POINT:
        pr = mv.profile
        assert pr is not None
        if not math.isfinite(pr.duration):
            return math.inf  # speed 0 (MCCD): it dwells short of its end
        return max(length - change_distance(_decel_speed(pr), 0.0, mv.limits), 0.0)
    return math.inf


def _decel_speed(pr: MoveProfile) -> float:
    """Speed where the profile's final deceleration to rest begins: the start of its last
    stretch of strictly falling segment speeds (the peak of a profile from rest; after an
    MCCD the lower new speed, not the speed it was running at)."""
    v = np.abs(pr.v0)
    k = len(v) - 1  # the last row is the rest at the end
    while k > 0 and v[k - 1] > v[k] + 1e-12:
        k -= 1
    return float(v[k]) if len(v) else 0.0
