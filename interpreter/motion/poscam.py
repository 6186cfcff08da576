"""Position cams: a slave follows a cam profile of its master's position, advanced together
with numpy (one row per coupling). Front ends: the PLCopen MC_CamIn block (adapters in
interpreter/instructions/plcopen.py). Decisions 0126-0128.

The law of one coupling, evaluated at every coarse update:
    X = MasterScaling * (master - m0) + MasterOffset            (m0 = 0: master absolute)
    Y = SlaveScaling * CAM(local(X)) + base + rel * (k - k0) * SlaveScaling * CAM(end)
    slave = Y + c(t)
- periodic cams wrap X into the profile range (k = passes counted from the start of the
  range, k0 at coupling); a relative coupling adds the cam's end value at each pass (its
  slave position at the end of a pass becomes the offset of the next), an absolute one
  evaluates every pass as it is (it may jump);
- base = SlaveOffset (absolute) or SlaveOffset + the slave's position at coupling (relative);
- c(t) is the ramp-in compensation: it starts at the jump the law would make at coupling
  and runs to 0 as a trapezoid (VelocityDiff, Acceleration, Deceleration) starting at rest,
  so the velocity the slave adds to the cam never exceeds VelocityDiff.
Rotary axes (decision 0137): a rotary master's travel is accumulated through the wrap the
short way round (rotary.travel, as gears and master clocks count it), so X runs on; a
rotary slave's contribution is a change of position taken the short way round, which the
group wraps, and its ramp-in compensates forward only (ramp_in_pos) or in reverse only
(ramp_in_neg).
The cam profiles are evaluated with cam.ProfileBank (one searchsorted for every row), the
evaluation the time cams use.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from enum import IntEnum
from typing import TYPE_CHECKING

import numpy as np

from interpreter.motion.cam import CamProfile, ProfileBank
from interpreter.motion.enums import (
    CamDirection,
    EventKind,
    MasterReference,
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
)
from interpreter.motion.rotary import travel, travel_array, wrap
from interpreter.motion.rowset import RowSet

if TYPE_CHECKING:
    from interpreter.motion.group import MotionGroup


class CamInError(IntEnum):
    """ErrorID of the PLCopen camming blocks (our numbering; catalog enum MC_ErrorID)."""

    NONE = 0
    INVALID_AXIS = 1
    SAME_AXIS = 2
    INVALID_CAM_TABLE = 3
    INVALID_CAM_TABLE_ID = 4
    MASTER_OUT_OF_RANGE = 5
    INVALID_PARAMETER = 6
    SLAVE_NOT_READY = 7


class CamStartMode(IntEnum):
    """MC_CamIn StartMode (catalog enum StartMode)."""

    ABSOLUTE = 0
    RELATIVE = 1
    RAMP_IN = 2
    RAMP_IN_POS = 3
    RAMP_IN_NEG = 4


class PositionCamMode(IntEnum):
    """MAPC ExecutionMode (catalog enum PositionCamExecutionMode)."""

    ONCE = 0
    CONTINUOUS = 1
    PERSISTENT = 2


class PositionCamSchedule(IntEnum):
    """MAPC ExecutionSchedule (catalog enum PositionCamExecutionSchedule)."""

    IMMEDIATE = 0
    PENDING = 1
    FORWARD_ONLY = 2
    REVERSE_ONLY = 3
    BI_DIRECTIONAL = 4


class CamMasterDirection(IntEnum):
    """MAPC MasterDirection (catalog enum CamMasterDirection)."""

    BI_DIRECTIONAL = 0
    FORWARD_ONLY = 1
    REVERSE_ONLY = 2


class CouplingState(IntEnum):
    STARTING = 0  # executed, applied at the next update
    RAMPING = 1  # coupled, ramp-in compensation running
    IN_SYNC = 2  # the slave follows the law
    ENDED = 3  # a non-periodic cam reached its end: the slave holds
    ABORTED = 4  # another motion took the slave
    ERROR = 5
    ARMED = 6  # MAPC: waiting for the master to cross MasterLockPosition


@dataclass(frozen=True, slots=True)
class CamLaw:
    """What a coupling evaluates: the profile, its options and the scalings."""

    profile: CamProfile
    periodic: bool = False
    master_absolute: bool = True
    slave_absolute: bool = True
    master_scaling: float = 1.0
    master_offset: float = 0.0
    slave_scaling: float = 1.0
    slave_offset: float = 0.0
    start_mode: CamStartMode = CamStartMode.ABSOLUTE
    velocity_diff: float = 0.0
    acceleration: float = 0.0
    deceleration: float = 0.0
    # Logix MAPC: the cam moves the slave incrementally from where it is at lock (each
    # continuous pass adds the profile's net change), Persistent holds outside the range
    # instead of ending, and MasterDirection lets the slave follow one way only
    incremental: bool = False
    persistent: bool = False
    master_direction: int = 0  # 0 both ways, 1 forward only, 2 reverse only

    @property
    def relative(self) -> bool:
        """The seed's StartMode x SlaveAbsolute table: relative StartMode is always relative,
        every other one becomes relative when SlaveAbsolute is FALSE."""
        return self.start_mode == CamStartMode.RELATIVE or not self.slave_absolute

    @property
    def ramp(self) -> bool:
        return self.start_mode >= CamStartMode.RAMP_IN


@dataclass(slots=True)
class Coupling:
    """One position cam coupling; the front end reads its state after every update."""

    handle: int
    slave: int
    master: int
    reference: MasterReference
    law: CamLaw
    state: CouplingState = CouplingState.STARTING
    error: CamInError = CamInError.NONE
    ends: int = 0  # profile ends passed so far (EndOfProfile)
    pending: CamLaw | None = None  # a table switch taken at the next profile end
    lock: tuple[int, float] | None = None  # MAPC armed: (schedule, MasterLockPosition)
    prev_master: float | None = None  # the master position at the previous update (lock)
    mapc: bool = False  # shows in the axis PositionCam* status bits
    # rotary axes (decision 0137): the master's unwind (its travel is accumulated the short
    # way round, as the gears and master clocks do) and the slave's (its contribution is a
    # change of position, taken the short way round; the group wraps the position)
    m_unwind: float = 0.0
    s_unwind: float = 0.0
    mu: float = 0.0  # the master position of the previous update, unwrapped
    # row state (copied from/to the set's arrays when rows are rebuilt)
    m0: float = 0.0
    base: float = 0.0
    k0: float = 0.0
    k: float = 0.0
    last: float = 0.0
    pass_add: float = 0.0  # added to the slave per pass of a periodic cam
    peak: float = math.nan  # MasterDirection one way: the furthest X reached
    ramp_dist: float = 0.0  # signed compensation at coupling (slave minus law)
    ramp_t: float = 0.0
    ramp_total: float = 0.0
    v: float = 0.0
    a: float = 0.0

    @property
    def in_sync(self) -> bool:
        return self.state == CouplingState.IN_SYNC

    @property
    def busy(self) -> bool:
        return self.state in (CouplingState.STARTING, CouplingState.RAMPING, CouplingState.IN_SYNC)


def validate_law(law: CamLaw) -> CamInError:
    """Operand checks that need no axis state (done when the block executes)."""
    scalars = (law.master_scaling, law.master_offset, law.slave_scaling, law.slave_offset)
    if not all(math.isfinite(x) for x in scalars) or law.master_scaling == 0.0:
        return CamInError.INVALID_PARAMETER
    if law.start_mode not in CamStartMode.__members__.values():
        return CamInError.INVALID_PARAMETER
    if law.ramp and not all(
        math.isfinite(x) and x > 0.0
        for x in (law.velocity_diff, law.acceleration, law.deceleration)
    ):
        return CamInError.INVALID_PARAMETER
    return CamInError.NONE


def ramp_time(dist: float, v: float, a: float, d: float) -> float:
    """Duration of a rest-to-rest trapezoid over |dist| with speed v, accel a, decel d."""
    dist = abs(dist)
    if dist == 0.0:
        return 0.0
    d_min = v * v / (2.0 * a) + v * v / (2.0 * d)
    if dist >= d_min:
        return v / a + v / d + (dist - d_min) / v
    vp = math.sqrt(2.0 * dist * a * d / (a + d))
    return vp / a + vp / d


def ramp_profile(
    t: np.ndarray, dist: np.ndarray, v: np.ndarray, a: np.ndarray, d: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Distance travelled, velocity and acceleration of rest-to-rest trapezoids at time t."""
    dist = np.abs(dist)
    d_min = v * v / (2.0 * a) + v * v / (2.0 * d)
    full = dist >= d_min
    vp = np.where(full, v, np.sqrt(2.0 * dist * a * d / (a + d)))
    t1 = vp / a
    t3 = vp / d
    t2 = np.where(full, (dist - d_min) / np.where(v > 0, v, 1.0), 0.0)
    total = t1 + t2 + t3
    tau = np.maximum(total - t, 0.0)
    q = np.where(
        t <= t1,
        0.5 * a * t * t,
        np.where(t <= t1 + t2, 0.5 * a * t1 * t1 + vp * (t - t1), dist - 0.5 * d * tau * tau),
    )
    vel = np.where(t <= t1, a * t, np.where(t <= t1 + t2, vp, d * tau))
    acc = np.where(t <= t1, a, np.where(t <= t1 + t2, 0.0, -d))
    after = t >= total
    return (
        np.where(after, dist, q),
        np.where(after, 0.0, vel),
        np.where(after, 0.0, acc),
    )


def evaluate_law(
    law: CamLaw, master: np.ndarray | float, m0: float = 0.0, base: float | None = None,
    k0: float = 0.0,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:  # fmt: skip
    """Whole-trajectory form of the law (no ramp, both master directions): Y, dY/dmaster,
    d2Y/dmaster2 and the pass index k at master positions (plots and tests; the set evaluates
    the same law)."""
    p = law.profile
    ms, ss = law.master_scaling, law.slave_scaling
    x = ms * (np.asarray(master, dtype=float) - m0) + law.master_offset
    if law.periodic:
        k = np.floor((x - p.start) / p.span)
        local = x - k * p.span
    else:
        k = np.zeros_like(x)
        local = np.clip(x, p.start, p.end)
    pos, vel, acc = p.evaluate(local)
    b = law.slave_offset if base is None else base
    y = ss * pos + b + (k - k0) * pass_add(law)
    return y, ss * vel * ms, ss * acc * ms * ms, k


def pass_add(law: CamLaw) -> float:
    """What a periodic cam adds to the slave per pass: MAPC the profile's net change; a
    relative MC_CamIn the cam's end value (the slave's position at the end of a pass is the
    offset of the next); an absolute MC_CamIn nothing (each pass as it is)."""
    if law.incremental:
        return law.slave_scaling * law.profile.net
    return law.slave_scaling * law.profile.p_end if law.relative else 0.0


_STATUS_NAMES = ("PositionCamStatus", "PositionCamLockStatus", "PositionCamPendingStatus")


class PositionCamSet(RowSet[Coupling]):
    """Running couplings in struct-of-arrays form; rows are rebuilt when the set changes.
    MAPC cams waiting for their lock position (`armed`) and queued behind an active one
    (`pending`, per slave) are kept aside until they start."""

    STATE = (
        ("k", "_k", float),
        ("last", "_last", float),
        ("mu", "_mu", float),
        ("ramp_t", "_rt", float),
        ("peak", "_peak", float),
        ("v", "_v", float),
        ("a", "_a", float),
    )
    AXIS = "slave"

    def __init__(self) -> None:
        super().__init__()
        self.armed: list[Coupling] = []
        self.pending: dict[int, Coupling] = {}
        self.claim: set[int] = set()  # slaves with an active or armed MAPC (ERR 23)
        self.last_dir: dict[int, int] = {}  # slave -> +1 / -1 of its last MAPC
        self._bank: ProfileBank | None = None
        self._ended: list[Coupling] = []
        self._started: list[Coupling] = []
        self._mapc_rows = False
        self._lockok = np.zeros(0, dtype=bool)
        self._idle_status: dict[str, np.ndarray] | None = None

    def _rebuild(self) -> None:
        rows = self.rows
        profiles: list[CamProfile] = []
        index: dict[int, int] = {}
        for c in rows:
            if id(c.law.profile) not in index:
                index[id(c.law.profile)] = len(profiles)
                profiles.append(c.law.profile)
        if self._bank is None or self._bank.key != tuple(id(p) for p in profiles):
            self._bank = ProfileBank(profiles)
        f = float
        laws = [c.law for c in rows]
        prof = np.array([index[id(law.profile)] for law in laws], dtype=np.intp)
        self._slave = np.array([c.slave for c in rows], dtype=np.intp)
        self._master = np.array([c.master for c in rows], dtype=np.intp)
        self._cmd = np.array([c.reference == MasterReference.COMMAND for c in rows], dtype=bool)
        self._ms = np.array([law.master_scaling for law in laws], dtype=f)
        self._mo = np.array([law.master_offset for law in laws], dtype=f)
        self._ss = np.array([law.slave_scaling for law in laws], dtype=f)
        self._padd = np.array([c.pass_add for c in rows], dtype=f)
        self._periodic = np.array([law.periodic for law in laws], dtype=bool)
        self._persist = np.array([law.persistent for law in laws], dtype=bool)
        self._any_persist = bool(self._persist.any())
        self._mdir = np.array([law.master_direction for law in laws], dtype=np.intp)
        self._any_mdir = bool(self._mdir.any())
        self._start = np.array([law.profile.start for law in laws], dtype=f)
        self._span = np.array([law.profile.span for law in laws], dtype=f)
        self._m0 = np.array([c.m0 for c in rows], dtype=f)
        self._base = np.array([c.base for c in rows], dtype=f)
        self._k0 = np.array([c.k0 for c in rows], dtype=f)
        self._k = np.array([c.k for c in rows], dtype=f)
        self._last = np.array([c.last for c in rows], dtype=f)
        self._mu = np.array([c.mu for c in rows], dtype=f)
        self._mun = np.array([c.m_unwind for c in rows], dtype=f)
        self._any_mrot = bool(self._mun.any())
        self._sun = np.array([c.s_unwind for c in rows], dtype=f)
        self._any_srot = bool(self._sun.any())
        self._peak = np.array([c.peak for c in rows], dtype=f)
        self._rd = np.array([c.ramp_dist for c in rows], dtype=f)
        self._rt = np.array([c.ramp_t for c in rows], dtype=f)
        self._rtotal = np.array([c.ramp_total for c in rows], dtype=f)
        self._rv = np.array([max(law.velocity_diff, 1e-300) for law in laws], dtype=f)
        self._ra = np.array([max(law.acceleration, 1e-300) for law in laws], dtype=f)
        self._rdec = np.array([max(law.deceleration, 1e-300) for law in laws], dtype=f)
        self._ramping = np.array([c.state == CouplingState.RAMPING for c in rows], dtype=bool)
        self._any_ramp = bool(self._ramping.any())
        self._mapc = np.array([c.mapc for c in rows], dtype=bool)
        self._mapc_rows = bool(self._mapc.any())
        self._lockok = np.ones(len(rows), dtype=bool)
        # velocity and acceleration as the rows of one array: _step_plain stores both at once
        self._va = np.array([[c.v for c in rows], [c.a for c in rows]], dtype=f).reshape(2, -1)
        self._v, self._a = self._va[0], self._va[1]
        bank = self._bank
        self._row_base = bank.base[prof]
        self._row_first = bank.first_seg[prof]
        self._row_last = bank.last_seg[prof]
        self._all = np.arange(len(rows))
        self._xoff = self._mo - self._ms * self._m0
        self._all_cmd = bool(self._cmd.all())
        self._all_periodic = bool(self._periodic.all())
        self._no_row = np.zeros(len(rows), dtype=bool)
        self._any_padd = bool(self._padd.any())
        # the common couplings (_step_plain): command masters, periodic, no direction,
        # rotary, persistent or MAPC handling (a ramp is checked at each step: it ends)
        self._plain = (
            self._all_cmd
            and self._all_periodic
            and not (self._any_mrot or self._any_mdir or self._any_srot)
            and not (self._mapc_rows or self._any_persist)
        )
        self._levels: np.ndarray | None = None  # the rows of each level: see _select
        self._dirty = False

    # -- stepping -----------------------------------------------------------------
    def begin_update(self) -> None:
        self._ended = []
        self._started = []

    def step(
        self,
        cup: float,
        level_sel: LevelSel,
        positions: AxisState,
        velocities: AxisState,
        events: Events,
    ) -> Contribution:
        if self.armed:
            self._check_locks(level_sel, positions)
        if not self.rows:
            return EMPTY
        if self._dirty:
            self._rebuild()
        sel = self._select(level_sel)
        if sel is None:
            return EMPTY
        if self._plain and not self._any_ramp and sel.__class__ is slice:
            return self._step_plain(positions, velocities, events)
        master = self._master[sel]
        if self._all_cmd:  # the usual case: every master followed by command position
            m = positions[1][master]
            vm = velocities[1][master]
        else:
            cmd = self._cmd[sel]
            m = np.where(cmd, positions[1][master], positions[0][master])
            vm = np.where(cmd, velocities[1][master], velocities[0][master])
        if self._any_mrot:  # a rotary master: its travel through the wrap, not its position
            mu, mun = self._mu[sel], self._mun[sel]
            m = np.where(mun > 0.0, mu + travel_array(m, mu, mun), m)
            self._mu[sel] = m
        ms = self._ms[sel]
        x = ms * m + self._xoff[sel]  # MasterScaling * (master - m0) + MasterOffset
        following: np.ndarray | bool = True
        if self._any_mdir:  # one-way cams keep the furthest X reached (they pause meanwhile)
            mdir, peak = self._mdir[sel], self._peak[sel]
            peak = np.where(np.isnan(peak), x, peak)
            ratchet = np.where(
                mdir == CamMasterDirection.FORWARD_ONLY, np.maximum(x, peak), np.minimum(x, peak)
            )
            held = np.where(mdir == 0, x, ratchet)
            following = held == x
            x = held
            self._peak[sel] = x
            vm = np.where(following, vm, 0.0)
        start, span = self._start[sel], self._span[sel]
        if self._all_periodic:
            k = np.floor((x - start) / span)
            local = x - start - k * span  # 0..span
            outside = self._no_row[sel]
        else:
            periodic = self._periodic[sel]
            k = np.where(periodic, np.floor((x - start) / span), 0.0)
            local = x - start - k * span  # 0..span inside the range
            outside = ~periodic & ((local < 0.0) | (local > span))
        local = np.minimum(np.maximum(local, 0.0), span)
        assert self._bank is not None
        r = self._bank.evaluate_rows(
            self._row_base[sel], self._row_first[sel], self._row_last[sel], local
        )
        p, dp, ddp = r[0], r[1], r[2]
        ss = self._ss[sel]
        y = ss * p + self._base[sel]
        if self._any_padd:
            y += (k - self._k0[sel]) * self._padd[sel]
        mv = ms * vm
        vel = ss * dp * mv
        acc = ss * ddp * mv * mv
        if not self._all_periodic:
            vel = np.where(outside, 0.0, vel)
            acc = np.where(outside, 0.0, acc)
        if self._any_ramp:
            ramping = self._ramping[sel]
            t = self._rt[sel] + np.where(ramping, cup, 0.0)
            self._rt[sel] = t
            rd = self._rd[sel]
            q, qv, qa = ramp_profile(t, rd, self._rv[sel], self._ra[sel], self._rdec[sel])
            sign = np.sign(rd)
            y = y + np.where(ramping, rd - sign * q, 0.0)
            vel = vel - np.where(ramping, sign * qv, 0.0)
            acc = acc - np.where(ramping, sign * qa, 0.0)
        dpos = y - self._last[sel]
        if self._any_srot:  # a rotary slave: the law's value counts modulo the unwind
            dpos = travel_array(dpos, np.zeros_like(dpos), self._sun[sel])
        self._last[sel] = y
        self._v[sel] = vel
        self._a[sel] = acc
        prev_k = self._k[sel]
        passed = k != prev_k
        if self._mapc_rows:
            self._lockok[sel] = ~outside & following
        if self._any_persist:  # a persistent cam holds outside its range and stays
            outside = outside & ~self._persist[sel]
        if self._any_ramp or passed.any() or outside.any():
            prev_k = prev_k.copy()
            self._k[sel] = k
            self._events(sel, outside, passed, prev_k, k, x, m, events)
        return Contribution(self._slave[sel], dpos, vel, acc)

    def _step_plain(
        self, positions: AxisState, velocities: AxisState, events: Events
    ) -> Contribution:
        """step() for every row when all are plain (see _rebuild) and none ramps: the same
        arithmetic in the same order on the whole arrays, without the per-row selections
        and the branches (about 5 of the 15 us of 32 couplings)."""
        master = self._master
        m = positions[1][master]
        vm = velocities[1][master]
        ms = self._ms
        x = ms * m + self._xoff  # MasterScaling * (master - m0) + MasterOffset
        start, span = self._start, self._span
        d = x - start
        k = np.floor(d / span)
        local = d - k * span  # 0..span
        np.maximum(local, 0.0, out=local)
        np.minimum(local, span, out=local)
        assert self._bank is not None
        # (3, rows): p, dp, ddp, fresh from the evaluation; scaled in place below
        sc = self._bank.evaluate_rows(self._row_base, self._row_first, self._row_last, local)
        sc *= self._ss  # ss * p, ss * dp, ss * ddp in one operation
        y = sc[0]
        y += self._base  # y = ss * p + base
        if self._any_padd:
            y += (k - self._k0) * self._padd
        mv = ms * vm
        va = sc[1:]
        va *= mv  # vel = ss * dp * mv, and ss * ddp * mv
        acc = sc[2]
        acc *= mv  # acc = ss * ddp * mv * mv
        last = self._last
        dpos = y - last
        last[:] = y
        self._va[...] = va  # self._v, self._a
        prev_k = self._k
        passed = k != prev_k
        if passed.any():  # a profile end passed: no cam here leaves its range (all periodic)
            prev_k = prev_k.copy()
            self._k[:] = k
            self._events(slice(None), self._no_row, passed, prev_k, k, x, m, events)
        return Contribution(self._slave, dpos, sc[1], acc)

    def _select(self, level_sel: LevelSel) -> slice | np.ndarray | None:
        """The rows to step at this level (None: none); the answer per level is kept while
        the group's level array and the rows are unchanged (the level loop asks every set
        at every level of every update)."""
        if level_sel is None:
            return slice(None)
        levels, lvl = level_sel
        if self._levels is not levels:  # the group computes a new array when levels change
            self._levels = levels
            self._row_levels = levels[self._slave]
            self._by_level: dict[int, slice | np.ndarray | None] = {}
        if lvl not in self._by_level:
            rows = np.flatnonzero(self._row_levels == lvl)
            n = len(rows)
            self._by_level[lvl] = None if n == 0 else slice(None) if n == len(self.rows) else rows
        return self._by_level[lvl]

    def _check_locks(self, level_sel: LevelSel, positions: AxisState) -> None:
        """Armed MAPC cams lock when the master crosses MasterLockPosition in the scheduled
        direction; the distance counts from the lock position itself."""
        for c in list(self.armed):
            if level_sel is not None and level_sel[0][c.slave] != level_sel[1]:
                continue
            ref = 1 if c.reference == MasterReference.COMMAND else 0
            m = float(positions[ref][c.master])
            prev, u = c.prev_master, c.m_unwind
            if prev is not None and u > 0.0:  # a rotary master: count travel through the wrap
                m = prev + travel(m, prev, u)
            c.prev_master = m
            assert c.lock is not None
            schedule, lp = c.lock
            if prev is None:
                continue
            lp_fwd = lp_rev = lp
            if u > 0.0:  # a rotary master passes the lock position once per revolution
                lp_fwd = lp + u * math.floor((m - lp) / u)
                lp_rev = lp + u * math.ceil((m - lp) / u)
            fwd = prev < lp_fwd <= m
            rev = prev > lp_rev >= m
            if (
                (schedule == 2 and fwd)
                or (schedule == 3 and rev)
                or (schedule == 4 and (fwd or rev))
            ):
                self.armed.remove(c)
                place(c, lp_fwd if fwd else lp_rev, float(positions[1][c.slave]))
                c.mu = m  # the distance counts from the lock point, in the same frame
                c.lock = None
                self._started.append(c)

    def _events(
        self,
        sel: slice | np.ndarray,
        outside: np.ndarray,
        passed: np.ndarray,
        prev_k: np.ndarray,
        k: np.ndarray,
        x: np.ndarray,
        m: np.ndarray,
        events: Events,
    ) -> None:
        """The rare per-row changes: ramp finished, profile end passed, table switch,
        hand-over to a pending MAPC."""
        rows = self._all[sel]
        for j in np.flatnonzero(passed | outside | self._ramping[sel]):
            r = int(rows[j])
            c = self.rows[r]
            if self._ramping[r] and self._rt[r] >= self._rtotal[r] - 1e-12:
                self._ramping[r] = False
                self._any_ramp = bool(self._ramping.any())
                c.state = CouplingState.IN_SYNC
            if not (passed[j] or outside[j]):
                continue
            c.ends += int(abs(k[j] - prev_k[j])) if passed[j] else 1
            p = c.law.profile
            if outside[j]:  # the end the master left the range by
                forward = bool(x[j] > p.end)
                x_end = p.end if forward else p.start
            else:  # the pass boundary crossed, forward or back
                forward = bool(k[j] > prev_k[j])
                x_end = p.start + max(k[j], prev_k[j]) * p.span
            handover = c.mapc and c.slave in self.pending
            if outside[j] or handover:
                c.state = CouplingState.ENDED
                self._v[r] = 0.0
                self._a[r] = 0.0
                self._ended.append(c)
                kind = EventKind.COMPLETE if outside[j] else EventKind.ENDED
                events.append((c.handle, kind, c.slave))
            if c.pending is not None:
                self._switch(r, c, float(x_end), bool(outside[j]), forward, events)
            elif handover:
                self._hand_over(r, c, float(x_end), forward, events)

    def _end_point(self, r: int, c: Coupling, x_end: float, forward: bool) -> tuple[float, float]:
        """Master position and slave value of the law at the end of the pass just left
        (forward: the profile's end, backward: its start)."""
        law = c.law
        m_end = (x_end - law.master_offset) / law.master_scaling + float(self._m0[r])
        p = law.profile
        boundary = round((x_end - p.start) / p.span) if law.periodic else 0
        pass_left = boundary - 1 if forward and law.periodic else boundary
        pv = p.p_end if forward else p.p_start
        y_end = law.slave_scaling * pv + (pass_left - float(self._k0[r])) * c.pass_add
        return m_end, y_end + float(self._base[r])

    def _hand_over(self, r: int, c: Coupling, x_end: float, forward: bool, ev: Events) -> None:
        """A pending MAPC starts where the active one ended, from the slave value there."""
        new = self.pending.pop(c.slave)
        m_end, y_end = self._end_point(r, c, x_end, forward)
        place(new, m_end, y_end)
        new.mu = float(self._mu[r])  # the master travel goes on in the same frame
        # the new cam takes over this update's position: its next step moves on from here
        y_now = float(self._last[r])
        new.last = y_now
        new.base += y_now - y_end
        ev.append((new.handle, EventKind.PENDING_STARTED, new.slave))
        ev.append((new.handle, EventKind.IN_PROCESS, new.slave))
        self._started.append(new)

    def _switch(
        self, r: int, c: Coupling, x_end: float, ended: bool, forward: bool, events: Events
    ) -> None:
        """A new table selected while coupled takes over at the profile end: its master zero
        is the master position at that end, its relative base the slave position there."""
        new = c.pending
        assert new is not None
        m_end, y_end = self._end_point(r, c, x_end, forward)
        c.pending = None
        if ended:  # the coupling goes on with the new table: no end after all
            self._ended = [e for e in self._ended if e is not c]
            events.remove((c.handle, EventKind.COMPLETE, c.slave))
        self._sync_out()
        contributed = c.last
        c.law = new
        err = place(c, float(m_end), float(y_end))
        c.last = contributed  # the next update moves on from what this one commanded
        if err != CamInError.NONE:  # e.g. the new non-periodic cam does not cover the master
            c.state, c.error = CouplingState.ERROR, err
            self._ended.append(c)
            events.append((c.handle, EventKind.ENDED, c.slave))
        self._dirty = True

    def end_update(self, actual: np.ndarray, events: Events) -> None:
        if self._ended or self._started:
            self.remove(self._ended)
            for c in self._started:
                self.add(c)
            self._ended = []
            self._started = []

    def velocity_sums(self, n: int) -> tuple[np.ndarray, np.ndarray]:
        if self._dirty:
            self._rebuild()
        if not self.rows:
            return np.zeros(n), np.zeros(n)
        return np.bincount(self._slave, self._v, n), np.bincount(self._slave, self._a, n)

    def edges(self) -> list[tuple[int, int]]:
        return [(c.slave, c.master) for c in self.rows + self.armed]

    def shift_master(self, axis: int, delta: float) -> None:
        """A master counted from its coupling position keeps counting travel (MRP, MAH)."""
        self._sync_out()
        for c in self.rows:
            if c.master == axis and c.m_unwind > 0.0:  # the unwrapped master moves with it
                c.mu += delta
                self._dirty = True
            if c.master == axis and not c.law.master_absolute:
                c.m0 += delta
                self._dirty = True
        for c in self.armed:
            if c.master == axis and c.prev_master is not None:
                c.prev_master += delta

    def status(self, n: int) -> dict[str, np.ndarray]:
        """PositionCamStatus (a MAPC active or armed), PositionCamLockStatus (following the
        master inside the profile), PositionCamPendingStatus; MC_CamIn shows none."""
        if self._dirty:
            self._rebuild()
        if not (self._mapc_rows or self.armed or self.pending):
            self.claim.clear()
            if self._idle_status is None or len(self._idle_status["PositionCamStatus"]) != n:
                idle = np.zeros(n, dtype=bool)  # shared, read-only: nothing to show
                self._idle_status = {name: idle for name in _STATUS_NAMES}
            return self._idle_status
        active = np.zeros(n, dtype=bool)
        locked = np.zeros(n, dtype=bool)
        pending = np.zeros(n, dtype=bool)
        if self._mapc_rows:
            active[self._slave[self._mapc]] = True
            locked[self._slave[self._mapc & self._lockok]] = True
        for c in self.armed:
            active[c.slave] = True
        pending[list(self.pending)] = True
        # asked at the end of an update: the claim on a slave is exactly its MAPC now
        self.claim = {c.slave for c in self.rows if c.mapc} | {c.slave for c in self.armed}
        return {
            "PositionCamStatus": active,
            "PositionCamLockStatus": locked,
            "PositionCamPendingStatus": pending,
        }

    def end_axis(self, axis: int, reason: EndReason, events: Events) -> tuple[float, bool]:
        """A stop of all motion or of position cams, a merge and a kill take the slave
        (MAPC cams armed or pending on it end too)."""
        if reason not in (Ending.KILL, Ending.MERGE_ALL, StopType.ALL, StopType.POSITION_CAM):
            return 0.0, False
        gone = self.on_axis(axis)
        v = 0.0
        for c in gone:
            v += c.v
            c.state = CouplingState.ABORTED
            events.append((c.handle, EventKind.ENDED, axis))
        if gone:
            self.remove(gone)
        waiting = [c for c in self.armed if c.slave == axis]
        if axis in self.pending:
            waiting.append(self.pending.pop(axis))
        for c in waiting:
            c.state = CouplingState.ABORTED
            events.append((c.handle, EventKind.ENDED, axis))
        self.armed = [c for c in self.armed if c.slave != axis]
        return v, bool(gone or waiting)

    def busy(self, axis: int) -> bool:
        return bool(self.on_axis(axis))

    def links_in_use(self) -> set[int]:
        return set()

    def stop_requested(self, axis: int | None, stop_type: StopType) -> None:
        """MAS All / Position Cam (MGS: None) frees the slave for an immediate MAPC at once."""
        if axis is None:
            self.claim.clear()
        elif stop_type in (StopType.ALL, StopType.POSITION_CAM):
            self.claim.discard(axis)


def place(c: Coupling, m: float, s: float) -> CamInError:
    """Fix a coupling's reference at master position m and slave position s (the coupling
    update, a lock, a table switch): master zero, slave base, pass count and ramp-in."""
    law = c.law
    p = law.profile
    c.m0 = 0.0 if law.master_absolute else m
    x = law.master_scaling * (m - c.m0) + law.master_offset
    if not law.periodic and not (p.start - 1e-9 <= x <= p.end + 1e-9):
        return CamInError.MASTER_OUT_OF_RANGE
    c.k0 = math.floor((x - p.start) / p.span) if law.periodic else 0.0
    c.k = c.k0
    c.pass_add = pass_add(law)
    c.peak = math.nan
    if law.incremental:  # MAPC: the slave moves on from where it is
        local = x - c.k0 * p.span if law.periodic else x
        c.base = s - law.slave_scaling * float(p.evaluate(local)[0])
    else:
        c.base = law.slave_offset + (s if law.relative else 0.0)
    y, _, _, _ = evaluate_law(law, m, c.m0, c.base, c.k0)
    c.last = s
    c.ramp_t = 0.0
    gap = slave_gap(law.start_mode, s - float(y), c.s_unwind)
    if law.ramp and abs(gap) > 1e-12:
        c.ramp_dist = gap
        if c.s_unwind > 0.0:  # the slave where it is, modulo its unwind
            c.last = float(y) + gap
        c.ramp_total = ramp_time(c.ramp_dist, law.velocity_diff, law.acceleration, law.deceleration)
        c.state = CouplingState.RAMPING
    else:
        c.ramp_dist = 0.0
        c.ramp_total = 0.0
        c.state = CouplingState.IN_SYNC
    return CamInError.NONE


def slave_gap(mode: CamStartMode, gap: float, unwind: float) -> float:
    """The slave's position minus the law's, as the ramp-in removes it. On a linear slave as
    it is; on a rotary one modulo the unwind: ramp_in_pos so that the slave compensates
    forward only (the gap in (-unwind, 0]), ramp_in_neg in reverse only ([0, unwind)), the
    other modes the short way round (the seed; decision 0137)."""
    if unwind <= 0.0:
        return gap
    if mode == CamStartMode.RAMP_IN_POS:
        ahead = wrap(-gap, unwind)  # forward distance to the law's position
        return 0.0 if ahead > unwind - 1e-9 else -ahead
    if mode == CamStartMode.RAMP_IN_NEG:
        behind = wrap(gap, unwind)
        return 0.0 if behind > unwind - 1e-9 else behind
    return travel(gap, 0.0, unwind)


def start_position_cam(
    group: MotionGroup,
    cams: PositionCamSet,
    slave: int,
    master: int,
    law: CamLaw,
    reference: int = MasterReference.COMMAND,
) -> Coupling:
    """Couple the slave to the master at the next update (MC_CamIn). The returned coupling
    reports its state; a check that needs the axis state at coupling (the master inside a
    non-periodic cam's range) is made there and shows as state ERROR."""
    h = group.new_handle()
    ref = group.effective_reference(master, MasterReference(reference))
    c = Coupling(h, slave, master, ref, law)
    c.m_unwind, c.s_unwind = float(group.unwind[master]), float(group.unwind[slave])
    err = validate_law(law)
    if err == CamInError.NONE and slave == master:
        err = CamInError.SAME_AXIS
    if err == CamInError.NONE and (group.shutdown[slave] or not group.servo_on[slave]):
        err = CamInError.SLAVE_NOT_READY
    if err != CamInError.NONE:
        c.state, c.error = CouplingState.ERROR, err
        return c

    def apply(ev: Events) -> None:
        if c.state != CouplingState.STARTING:  # replaced before it was applied
            return
        # another coupling of this slave is taken over (CommandAborted)
        for old in cams.on_axis(slave):
            old.state = CouplingState.ABORTED
            ev.append((old.handle, EventKind.ENDED, slave))
            cams.remove([old])
        pos = group.command_position if ref == MasterReference.COMMAND else group.actual_position
        vel = group.command_velocity if ref == MasterReference.COMMAND else group.actual_velocity
        err = place(c, float(pos[master]), float(group.command_position[slave]))
        c.mu = float(pos[master])
        if err != CamInError.NONE:
            c.state, c.error = CouplingState.ERROR, err
            return
        _, dy, _, _ = evaluate_law(law, float(pos[master]), c.m0, c.base, c.k0)
        c.v = float(dy) * float(vel[master])
        cams.add(c)
        group.levels_changed()
        ev.append((h, EventKind.IN_PROCESS, slave))

    group.after_update(apply)
    return c


def switch_table(cams: PositionCamSet, c: Coupling, law: CamLaw) -> CamInError:
    """Select another table for a running coupling; it takes over at the next profile end."""
    err = validate_law(law)
    if err == CamInError.NONE:
        c.pending = law
        cams._sync_out()
        cams._dirty = True
    return err


def start_mapc(
    group: MotionGroup,
    cams: PositionCamSet,
    slave: int,
    master: int,
    profile: CamProfile | None,
    direction: int = CamDirection.SAME,
    slave_scaling: float = 1.0,
    master_scaling: float = 1.0,
    execution_mode: int = PositionCamMode.ONCE,
    execution_schedule: int = PositionCamSchedule.IMMEDIATE,
    master_lock_position: float = 0.0,
    cam_lock_position: float = 0.0,
    reference: int = MasterReference.ACTUAL,
    master_direction: int = 0,
) -> StartResult:
    """MAPC (decision 0128): validates at once (ERR/EXERR with the faceplate indices) and
    starts at the next update, locks when the master crosses MasterLockPosition, or waits
    behind the slave's active position cam (Pending)."""
    if slave == master:
        return bad_operand(1)
    if direction not in (0, 1, 2, 3):
        return bad_operand(3)
    if profile is None:
        return StartResult(error=MotionError.CAM_PROFILE_NOT_CALCULATED)
    if not math.isfinite(slave_scaling):
        return bad_operand(5)
    if not (math.isfinite(master_scaling) and master_scaling > 0.0):
        return bad_operand(6)
    if execution_mode not in PositionCamMode.__members__.values():
        return bad_operand(7)
    if execution_schedule not in PositionCamSchedule.__members__.values():
        return bad_operand(8)
    if not math.isfinite(master_lock_position):
        return bad_operand(9)
    if not (math.isfinite(cam_lock_position) and profile.start <= cam_lock_position <= profile.end):
        return bad_operand(10)
    if reference not in (0, 1):
        return bad_operand(11)
    if master_direction not in CamMasterDirection.__members__.values():
        return bad_operand(12)
    pending = execution_schedule == PositionCamSchedule.PENDING
    if not pending and slave in cams.claim:
        return StartResult(error=MotionError.ILLEGAL_DYNAMIC_CHANGE)
    if group.shutdown[slave]:
        return StartResult(error=MotionError.SHUTDOWN_STATE)
    if not group.servo_on[slave]:
        return StartResult(error=MotionError.SERVO_OFF_STATE)
    sign = direction_sign(direction, cams.last_dir, slave)
    law = CamLaw(
        profile,
        periodic=execution_mode == PositionCamMode.CONTINUOUS,
        master_absolute=False,
        master_scaling=1.0 / master_scaling,  # MasterScaling stretches the profile's master axis
        master_offset=cam_lock_position,
        slave_scaling=sign * slave_scaling,
        incremental=True,
        persistent=execution_mode == PositionCamMode.PERSISTENT,
        master_direction=master_direction,
    )
    h = group.new_handle()
    ref = group.effective_reference(master, MasterReference(reference))
    c = Coupling(h, slave, master, ref, law, mapc=True)
    c.m_unwind, c.s_unwind = float(group.unwind[master]), float(group.unwind[slave])
    if pending:

        def apply_pending(ev: Events) -> None:
            old = cams.pending.pop(slave, None)
            if old is not None:  # a later pending cam replaces the queued one
                ev.append((old.handle, EventKind.ENDED, slave))
            cams.pending[slave] = c

        group.after_update(apply_pending)
        return StartResult(handle=h)
    cams.claim.add(slave)

    def apply(ev: Events) -> None:
        pos = group.command_position if ref == MasterReference.COMMAND else group.actual_position
        if execution_schedule == PositionCamSchedule.IMMEDIATE:
            place(c, float(pos[master]), float(group.command_position[slave]))
            c.mu = float(pos[master])
            cams.add(c)
        else:
            c.state = CouplingState.ARMED
            c.lock = (int(execution_schedule), float(master_lock_position))
            c.prev_master = float(pos[master])
            cams.armed.append(c)
        group.levels_changed()
        ev.append((h, EventKind.IN_PROCESS, slave))

    group.after_update(apply)
    return StartResult(handle=h)
