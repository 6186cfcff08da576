"""Output cams (MAOC/MDOC) on the numpy core: no tags, no VM, no group.

`OutputCamSet` holds the execution targets (axis, 0..7) of a motion group. A binding
calls `arm()` when an MAOC executes (validation answers at once), `disarm()` for MDOC, and
`update()` once per coarse update with the axis positions at the start and end of the
interval. Switch instants are found inside the interval from the axis motion (linear in
time, or an exact inverse given by the caller), so narrow windows are never skipped.
Design and readings of the reference: docs/decisions/0107-output-cam-core.md.
"""

from __future__ import annotations

import math
from bisect import bisect_left, bisect_right
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from interpreter.motion.outputcam_tables import (
    BITS,
    OK,
    ArrayCheck,
    CamElements,
    Compensation,
    DisarmType,
    EnableType,
    LatchType,
    OutputCamExecutionMode,
    OutputCamExecutionSchedule,
    OutputMode,
    PositionReference,
    UnlatchType,
    error_code,
)

# plain ints for the hot paths (IntEnum attribute access costs a call)
_L_POSITION = int(LatchType.POSITION)
_L_ENABLE = int(LatchType.ENABLE)
_L_POSITION_AND_ENABLE = int(LatchType.POSITION_AND_ENABLE)
_U_POSITION = int(UnlatchType.POSITION)
_U_DURATION = int(UnlatchType.DURATION)
_U_ENABLE = int(UnlatchType.ENABLE)
_U_POSITION_AND_ENABLE = int(UnlatchType.POSITION_AND_ENABLE)
_U_DURATION_AND_ENABLE = int(UnlatchType.DURATION_AND_ENABLE)
_M_NORMAL = int(OutputMode.NORMAL)
_M_INVERTED = int(OutputMode.INVERTED)
_M_PULSED = int(OutputMode.PULSED)
_M_INVERTED_AND_PULSED = int(OutputMode.INVERTED_AND_PULSED)
_E_INVERTED_INPUT = int(EnableType.INVERTED_INPUT)
_E_OUTPUT = int(EnableType.OUTPUT)
_E_INVERTED_OUTPUT = int(EnableType.INVERTED_OUTPUT)

TARGETS = 8

# Event kinds reported by update(), for the MOTION_INSTRUCTION bits of the arming MAOC.
LOCKED = "locked"  # cam position locked to the axis (armed position reached)
COMPLETE = "complete"  # Once: left the range (PC set, IP cleared)
ENDED = "ended"  # superseded, disarmed or replaced while pending (IP cleared, no PC)
PENDING_STARTED = "pending_started"  # a pending cam took over


@dataclass(frozen=True, slots=True)
class OutputCamEvent:
    handle: int
    kind: str
    time: float


@dataclass(frozen=True, slots=True)
class Edge:
    """One switch of an output bit at an exact instant (absolute seconds)."""

    axis: int
    target: int
    bit: int
    time: float
    value: bool


@dataclass(slots=True)
class ArmRequest:
    """One MAOC's operands after validation (cam range is fixed for this execution)."""

    handle: int
    elements: CamElements
    cam_start: float
    cam_end: float
    mode: OutputCamExecutionMode
    schedule: OutputCamExecutionSchedule
    axis_arm: float
    cam_arm: float
    reference: PositionReference


@dataclass(frozen=True, slots=True)
class ArmResult:
    """armed is True when the cam was accepted; error/exerr/segment go to MOTION_INSTRUCTION."""

    armed: bool
    error: int = 0
    exerr: int = 0
    segment: int = 0


@dataclass(slots=True)
class _Cam:
    req: ArmRequest
    locked: bool = False
    in_range: bool = True
    c: float = 0.0  # cam position
    on: np.ndarray = field(default_factory=lambda: np.zeros(0, bool))
    off_time: np.ndarray = field(default_factory=lambda: np.zeros(0))
    enable_prev: np.ndarray = field(default_factory=lambda: np.zeros(0, bool))
    active: np.ndarray = field(default_factory=lambda: np.zeros(BITS, bool))
    # inside the compensated window at the end of the last evaluation; the window moves
    # with the velocity, so an edge can pass the cam position between two updates
    inside: np.ndarray = field(default_factory=lambda: np.zeros(0, bool))
    sync_inside: bool = True  # take `inside` from the position (arming, re-entry)
    pulse_origin: np.ndarray = field(default_factory=lambda: np.zeros(BITS))
    # the quiet interval (decision 0114): evaluated at velocity vref, no compensated level
    # lies strictly between gap_lo and gap_hi around c; nothing is due before t_due; the
    # enable words were `words`. nan vref: evaluate exactly at the next update.
    vref: float = math.nan
    gap_lo: float = -math.inf
    gap_hi: float = math.inf
    t_due: float = math.inf
    pulsing: bool = False
    words: tuple[int, int] = (0, 0)

    def __post_init__(self) -> None:
        n = len(self.req.elements)
        self.on = np.zeros(n, bool)
        self.off_time = np.full(n, math.inf)
        self.enable_prev = np.zeros(n, bool)
        self.inside = np.zeros(n, bool)

    @property
    def periodic(self) -> bool:
        return self.req.mode == OutputCamExecutionMode.CONTINUOUS

    @property
    def span(self) -> float:
        return self.req.cam_end - self.req.cam_start


@dataclass(slots=True)
class OutputCamTarget:
    """One execution target: its armed cam, a pending one, and the words it reads/writes."""

    axis: int
    target: int
    output: int = 0  # Output word as the program left it (the binding sets it)
    input: int = 0  # Input word
    compensation: Compensation = field(default_factory=Compensation.none)
    cam: _Cam | None = None
    pending: ArmRequest | None = None
    request: ArmRequest | None = None  # accepted by arm(), applied at the next update
    transition: bool = False
    dropped: list[int] = field(default_factory=list)  # replaced before taking effect


@dataclass(slots=True)
class OutputCamStep:
    events: list[OutputCamEvent]
    edges: list[Edge]
    changed: dict[tuple[int, int], int]  # (axis, target) -> mask of bits written


# Time within the interval of a displacement d (from the start position, same sign as
# the total displacement). None: linear in time.
TimeOf = Callable[[np.ndarray], np.ndarray]


class OutputCamSet:
    """All output cam execution targets of one motion group."""

    def __init__(self, min_width: float = 0.0, batch: bool = True) -> None:
        self.targets: dict[tuple[int, int], OutputCamTarget] = {}
        self.min_width = min_width  # smallest compensated window, position units
        self._bank: _Bank | None = None
        self._dirty = True  # cams, their lock/range state or a compensation changed
        self.batch = batch  # False: every cam through the exact path (tests compare both)
        # a target's armed/pending/lock/transition state changed (the status words); the
        # binding clears it when it has written them
        self.status_changed = True

    def _quiet(
        self,
        t0: float,
        dt: float,
        start: np.ndarray,
        end: np.ndarray,
        unwind: np.ndarray | None,
        velocity: np.ndarray | None,
        time_of: dict[tuple[int, int], TimeOf] | None,
        step: OutputCamStep,
    ) -> list[OutputCamTarget] | None:
        """The targets that need the exact evaluation this update (None: all of them).

        A running cam is quiet when its travel, widened by how far a velocity change can move
        its compensated levels, stays inside its quiet interval, nothing of it is due and its
        enable words did not change: then only its cam position moves, in one numpy pass over
        the cams (decision 0114). The others go through the exact per-cam evaluation."""
        if time_of or not self.batch:
            return None
        if self._dirty or self._bank is None:
            if self._bank is not None:
                self._bank.store()
            rows = []
            others = []
            for t in self.targets.values():
                cam = t.cam
                if (
                    cam is not None
                    and t.request is None
                    and not t.dropped
                    and cam.locked
                    and cam.in_range
                ):
                    rows.append(t)
                else:
                    others.append(t)
            self._bank = _Bank(rows, others)
            self._dirty = False
        b = self._bank
        if not b.rows:
            return b.others
        c = b.c
        ref, axis = b.ref, b.axis
        x0 = start[ref, axis]
        dx = end[ref, axis] - x0
        if unwind is not None:
            u = unwind[axis]
            if u.any():
                dx = np.where(u > 0, (dx + u / 2) % np.where(u > 0, u, 1.0) - u / 2, dx)
        cb = c + dx
        low, high = np.minimum(c, cb), np.maximum(c, cb)
        if b.any_delay:  # how far a velocity change moves the levels (nan vref: not quiet)
            v = velocity[ref, axis] if velocity is not None else dx / dt
            tol = np.abs(v - b.vref) * b.maxd
            low -= tol
            high += tol
        quiet = (low > b.gap_lo) & (high < b.gap_hi) & (cb >= b.start) & (cb <= b.end)
        if b.any_due:
            quiet &= b.t_due > t0 + dt
        for i in b.enable_rows:  # the program (or the cam) changed an enable word
            t = b.rows[i]
            cam = t.cam
            if cam is not None and cam.words != (t.input, t.output):
                quiet[i] = False
        np.copyto(c, cb, where=quiet)
        busy = np.flatnonzero(~quiet).tolist()
        out = b.others.copy()
        if busy:
            in_range = (cb >= b.start) & (cb <= b.end)
            for i in busy:
                t = b.rows[i]
                cam = t.cam
                assert cam is not None
                sim = b.simple[i]
                if sim is not None and in_range[i] and not cam.sync_inside and not t.transition:
                    # position windows only, no delays: crossings by bisection (0114)
                    ca, cbi = float(c[i]), float(cb[i])
                    _simple_step(t, cam, sim, ca, cbi, float(dx[i]), t0, dt, step)
                    cam.c = cbi
                    c[i] = cbi
                    b.gap_lo[i], b.gap_hi[i] = sim.gap(cbi, cam)
                    b.vref[i] = 0.0
                    continue
                cam.c = float(c[i])
                out.append(t)
        return out

    def target(self, axis: int, target: int) -> OutputCamTarget:
        key = (axis, target)
        t = self.targets.get(key)
        if t is None:
            t = self.targets[key] = OutputCamTarget(axis, target)
        return t

    # -- instructions ----------------------------------------------------------------
    def arm(
        self,
        axis: int,
        target: int,
        request: ArmRequest,
        compensation: Compensation | None = None,
        check: ArrayCheck = OK,
    ) -> ArmResult:
        """MAOC: accept (or refuse) the request; it takes effect at the next update.

        `check` is the first array-check error of the cam/compensation (reported, the cam
        still runs). Refusals: target outside 0..7 (ERR 35), bad range or cam arm position
        (ERR 13 with the operand index), a directional or pending arm while the target is
        locked or in transition (ERR 23)."""
        if not 0 <= target < TARGETS:
            return ArmResult(False, error_code("Illegal Execution Target"))
        if request.cam_start >= request.cam_end:
            return ArmResult(False, error_code("Parameter Out Of Range"), 7)
        if not request.cam_start <= request.cam_arm <= request.cam_end:
            return ArmResult(False, error_code("Parameter Out Of Range"), 12)
        t = self.target(axis, target)
        sched = request.schedule
        busy = t.cam is not None or t.request is not None
        if busy and sched != OutputCamExecutionSchedule.IMMEDIATE:
            locked = t.cam is not None and t.cam.locked
            if t.transition or (sched != OutputCamExecutionSchedule.PENDING and locked):
                return ArmResult(False, error_code("Illegal Dynamic Change"))
        if compensation is not None:
            t.compensation = compensation
        self._dirty = True
        self.status_changed = True
        if sched == OutputCamExecutionSchedule.PENDING and busy:
            if t.pending is not None:  # a later pending MAOC replaces an earlier one
                t.dropped.append(t.pending.handle)
            t.pending = request
        else:
            # a new arming replaces what was waiting: an earlier request of the same scan
            # and a queued pending cam
            for old in (t.request, t.pending):
                if old is not None:
                    t.dropped.append(old.handle)
            t.pending = None
            t.request = request
        return ArmResult(True, check.error, check.exerr, check.segment)

    def set_compensation(self, axis: int, target: int, compensation: Compensation) -> None:
        """Compensation changes take effect at once (next update)."""
        self.target(axis, target).compensation = compensation
        self._dirty = True

    def disarm(self, axis: int, target: int, disarm_type: DisarmType) -> list[int]:
        """MDOC: drop armed and pending cams; outputs keep their state. Returns the handles
        whose MAOC ends (IP cleared)."""
        ended: list[int] = []
        self._dirty = True
        self.status_changed = True
        for (a, tg), t in self.targets.items():
            if a != axis or (disarm_type == DisarmType.SPECIFIC and tg != target):
                continue
            for req in (t.cam.req if t.cam else None, t.pending, t.request):
                if req is not None:
                    ended.append(req.handle)
            t.cam = None
            t.pending = None
            t.request = None
            t.transition = False
        return ended

    # -- status words --------------------------------------------------------------
    def status_words(self, axis: int) -> dict[str, int]:
        """OutputCamStatus / PendingStatus / LockStatus / TransitionStatus of one axis."""
        words = dict.fromkeys(
            (
                "OutputCamStatus",
                "OutputCamPendingStatus",
                "OutputCamLockStatus",
                "OutputCamTransitionStatus",
            ),
            0,
        )
        for (a, tg), t in self.targets.items():
            if a != axis:
                continue
            bit = 1 << tg
            if t.cam is not None or t.request is not None:
                words["OutputCamStatus"] |= bit
            if t.pending is not None:
                words["OutputCamPendingStatus"] |= bit
            if t.cam is not None and t.cam.locked and t.cam.in_range:
                words["OutputCamLockStatus"] |= bit
            if t.transition:
                words["OutputCamTransitionStatus"] |= bit
        return words

    # -- evaluation ----------------------------------------------------------------
    def update(
        self,
        t0: float,
        dt: float,
        start: np.ndarray,
        end: np.ndarray,
        unwind: np.ndarray | None = None,
        velocity: np.ndarray | None = None,
        time_of: dict[tuple[int, int], TimeOf] | None = None,
    ) -> OutputCamStep:
        """Advance every target over [t0, t0 + dt].

        start/end: positions of shape (2, axes), row 0 actual, row 1 command (the
        PositionReference values). unwind: per-axis unwind (0 = linear axis); positions of a
        rotary axis may wrap, the displacement is taken as the short way round. velocity:
        (2, axes) velocity for the delay compensation (default: mean over the interval).
        time_of: exact inverse of the motion per (reference, axis), see TimeOf."""
        step = OutputCamStep([], [], {})
        todo = self._quiet(t0, dt, start, end, unwind, velocity, time_of, step)
        for t in self.targets.values() if todo is None else todo:
            before = _signature(t)
            was = t.transition
            if t.cam is None and t.request is None:
                t.transition = False
                self.status_changed |= was
                for h in t.dropped:
                    step.events.append(OutputCamEvent(h, ENDED, t0))
                t.dropped.clear()
                continue
            words = (t.input, t.output)  # the enable words this evaluation reads
            v = _advance(self, t, t0, dt, start, end, unwind, velocity, time_of, step)
            if _signature(t) != before:
                self._dirty = True
                self.status_changed = True
            elif t.transition != was:
                self.status_changed = True
            if self.batch and t.cam is not None:
                _refresh(self, t, t.cam, v, words)
                if self._bank is not None:  # also when dirty: store() must not undo it
                    self._bank.reload(t)
        return step


def _signature(t: OutputCamTarget) -> tuple:
    """What decides a target's place in the bank (compared around the exact path)."""
    c = t.cam
    waiting = (t.request is not None, bool(t.dropped))
    return (id(c), c.locked, c.in_range, *waiting) if c is not None else (None, *waiting)


class _Bank:
    """The running cams (locked, in range, nothing waiting) as per-cam arrays for the quiet
    pass; `c` holds their cam positions (written back to the cams before an exact
    evaluation and when the bank is rebuilt)."""

    def __init__(self, rows: list[OutputCamTarget], others: list[OutputCamTarget]) -> None:
        self.rows = rows
        self.others = others
        self.at = {id(t): i for i, t in enumerate(rows)}
        cams = [t.cam for t in rows if t.cam is not None]
        assert len(cams) == len(rows)
        self.axis = np.array([t.axis for t in rows], np.intp)
        self.ref = np.array([int(c.req.reference) for c in cams], np.intp)
        self.start = np.array([c.req.cam_start for c in cams])
        self.end = np.array([c.req.cam_end for c in cams])
        self.c = np.array([c.c for c in cams])
        self.vref = np.array([c.vref for c in cams])
        self.gap_lo = np.array([c.gap_lo for c in cams])
        self.gap_hi = np.array([c.gap_hi for c in cams])
        self.t_due = np.array([-math.inf if c.pulsing else c.t_due for c in cams])
        # nan vref (never evaluated) must also fail the test: a nan tolerance does that
        self.maxd = np.array([_max_delay(t) for t in rows])
        self.any_delay = bool(self.maxd.any()) or bool(np.isnan(self.vref).any())
        self.simple = [_Simple.of(t) for t in rows]
        for i, sim in enumerate(self.simple):  # their quiet interval does not need v
            cam = cams[i]
            if sim is not None and not cam.sync_inside and not rows[i].transition:
                self.gap_lo[i], self.gap_hi[i] = sim.gap(cam.c, cam)
                self.vref[i] = 0.0
        self.any_due = bool((self.t_due < math.inf).any())  # a duration or a pulse train
        self.enable_rows = [i for i, c in enumerate(cams) if _uses_enable(c.req.elements)]
        self.any_delay = bool(self.maxd.any()) or bool(np.isnan(self.vref).any())

    def reload(self, t: OutputCamTarget) -> None:
        """A cam of the bank was evaluated exactly: take its new position and interval."""
        i = self.at.get(id(t))
        cam = t.cam
        if i is None or cam is None:
            return
        self.c[i] = cam.c
        self.vref[i] = cam.vref
        self.gap_lo[i] = cam.gap_lo
        self.gap_hi[i] = cam.gap_hi
        self.t_due[i] = due = -math.inf if cam.pulsing else cam.t_due
        self.any_due |= due < math.inf
        self.any_delay |= math.isnan(cam.vref)

    def store(self) -> None:
        """Hand the cam positions back to the cams (before a rebuild)."""
        for t, c in zip(self.rows, self.c.tolist(), strict=True):
            if t.cam is not None:
                t.cam.c = c


@dataclass(slots=True)
class _Simple:
    """A cam whose elements are all Position latch / Position unlatch windows on bits with
    no delays and a Normal or Inverted mode: its levels do not depend on the velocity, so
    crossings are found by bisection in the sorted levels (decision 0114)."""

    lo: list[float]  # sorted left levels (forward latch) ...
    lo_el: list[int]  # ... and their elements
    hi: list[float]
    hi_el: list[int]
    period: float  # the range span for a continuous cam, else inf
    bit: list[int]  # output bit of each element
    by_bit: dict[int, list[int]]  # elements of each bit

    @staticmethod
    def of(t: OutputCamTarget) -> _Simple | None:
        cam = t.cam
        if cam is None:
            return None
        el = cam.req.elements
        comp = t.compensation
        if not len(el) or not ((el.latch == _L_POSITION) & (el.unlatch == _U_POSITION)).all():
            return None
        b = el.bit
        if (comp.latch_delay[b] != 0).any() or (comp.unlatch_delay[b] != 0).any():
            return None
        if (comp.mode[b] > _M_INVERTED).any():
            return None
        lo = el.left + comp.offset[b]
        hi = el.right + comp.offset[b]
        if not (hi > lo).all():  # the minimum width would change the windows
            return None
        start, end = cam.req.cam_start, cam.req.cam_end
        period = math.inf
        elems = np.arange(len(el))
        if cam.periodic:
            # a continuous cam's levels repeat every span: the copies one span below and
            # above cover every crossing inside the range when the levels lie within a span
            # of it (the values are computed as _levels computes them)
            period = end - start
            if not ((lo >= start - period) & (hi <= end + period)).all():
                return None
            lo = np.concatenate((lo + -1 * period, lo, lo + 1 * period))
            hi = np.concatenate((hi + -1 * period, hi, hi + 1 * period))
            elems = np.tile(elems, 3)
        lo_order = np.argsort(lo, kind="stable")
        hi_order = np.argsort(hi, kind="stable")
        bits = [int(x) for x in b.tolist()]
        by_bit: dict[int, list[int]] = {}
        for e, bit in enumerate(bits):
            by_bit.setdefault(bit, []).append(e)
        return _Simple(
            lo[lo_order].tolist(), elems[lo_order].tolist(), hi[hi_order].tolist(),
            elems[hi_order].tolist(), period, bits, by_bit,
        )  # fmt: skip

    def gap(self, c: float, cam: _Cam) -> tuple[float, float]:
        """The quiet interval around cam position c: the nearest levels at or below / above."""
        below = -math.inf
        above = math.inf
        for levels in (self.lo, self.hi):  # (with their copies a span away when continuous)
            k = bisect_right(levels, c)
            if k:
                below = max(below, levels[k - 1])
            k = bisect_left(levels, c)
            if k < len(levels):
                above = min(above, levels[k])
        return below, above


def _simple_step(
    t: OutputCamTarget,
    cam: _Cam,
    sim: _Simple,
    ca: float,
    cb: float,
    dx: float,
    t0: float,
    dt: float,
    step: OutputCamStep,
) -> None:
    """The exact evaluation of a _Simple cam over a travel that stays in its range, with the
    same crossing rules and tie order as _evaluate: moving forward a window is entered at
    its left level in (ca, cb] and left at its right level in [ca, cb); in reverse entered
    at the right level in [cb, ca) and left at the left level in (cb, ca]."""
    lo, hi = sim.lo, sim.hi
    found: list[tuple[int, float, int, float]] = []  # (element, travel, kind, level)
    if cb > ca:
        enter = (bisect_right(lo, ca), bisect_right(lo, cb), lo, sim.lo_el)
        leave = (bisect_left(hi, ca), bisect_left(hi, cb), hi, sim.hi_el)
        sign = 1.0
    else:
        enter = (bisect_left(hi, cb), bisect_left(hi, ca), hi, sim.hi_el)
        leave = (bisect_right(lo, cb), bisect_right(lo, ca), lo, sim.lo_el)
        sign = -1.0
    for (a, z, levels, elems), kind in ((enter, _ENTER), (leave, _EXIT)):
        for k in range(a, z):
            y = levels[k]
            found.append((elems[k], (y - ca) * sign, kind, y))
    if not found:
        return
    found.sort()
    bit_of = sim.bit
    # elements on per bit before the switches (only the bits concerned)
    counts = {}
    for e, _, _, _ in found:
        b = bit_of[e]
        if b not in counts:
            counts[b] = sum(1 for x in sim.by_bit[b] if cam.on[x])
    switches: list[tuple[float, int, int, bool]] = []
    on = cam.on
    inside = cam.inside
    seq = 0
    for e, _, kind, y in found:
        when = t0 + (y - ca) / dx * dt
        if kind == _ENTER:
            inside[e] = True
            if not on[e]:
                on[e] = True
                switches.append((when, seq, e, True))
                seq += 1
        else:
            inside[e] = False
            if on[e]:
                on[e] = False
                switches.append((when, seq, e, False))
                seq += 1
    if not switches:
        return
    # _bits for Normal/Inverted bits without pulses: OR per bit, then the mode
    writes: list[tuple[float, int, int, bool]] = []
    order = 0
    mode = t.compensation.mode
    for when, _, e, now_on in sorted(switches, key=_switch_key):
        b = bit_of[e]
        before = counts[b] > 0
        counts[b] += 1 if now_on else -1
        after = counts[b] > 0
        if before == after:
            continue
        cam.active[b] = after
        if after:
            cam.pulse_origin[b] = when
        writes.append((when, order, b, after if mode[b] == _M_NORMAL else not after))
        order += 1
    word = t.output
    written = 0
    for when, _, b, value in sorted(writes):
        mask = 1 << b
        if bool(word & mask) == value and not _zero_width(writes, b, when):
            continue
        word = (word | mask) if value else (word & ~mask)
        written |= mask
        step.edges.append(Edge(t.axis, t.target, b, float(when), bool(value)))
    if written:
        key = (t.axis, t.target)
        step.changed[key] = step.changed.get(key, 0) | written
    t.output = word


def _switch_key(sw: tuple[float, int, int, bool]) -> tuple[float, bool, int]:
    """Element switches in time order; at one instant the ons before the offs, so that two
    elements of one bit handing over at the same position (a window split at the end of a
    continuous range, [350, 360] and [0, 10]) keep the bit on without a zero-width gap."""
    return sw[0], not sw[3], sw[1]


def _max_delay(t: OutputCamTarget) -> float:
    """Largest latch/unlatch delay of the bits a cam drives (how far its levels move per
    unit of velocity change)."""
    cam = t.cam
    assert cam is not None
    bits = cam.req.elements.bit
    if not bits.size:
        return 0.0
    comp = t.compensation
    return float(max(np.abs(comp.latch_delay[bits]).max(), np.abs(comp.unlatch_delay[bits]).max()))


def _uses_enable(el: CamElements) -> bool:
    return bool(
        (
            (el.latch == _L_ENABLE)
            | (el.latch == _L_POSITION_AND_ENABLE)
            | (el.unlatch >= _U_ENABLE)
        ).any()
    )


def _refresh(
    s: OutputCamSet, t: OutputCamTarget, cam: _Cam, v: float, words: tuple[int, int]
) -> None:
    """Recompute a cam's quiet interval at velocity v after an exact evaluation: the nearest
    compensated levels below and above its cam position (replicated over the range when
    continuous), when a duration unlatch is due, whether a pulse train runs, and the enable
    words it has seen."""
    if not (cam.locked and cam.in_range) or t.transition or cam.sync_inside:
        cam.vref = math.nan
        return
    el = cam.req.elements
    comp = t.compensation
    off = comp.offset[el.bit]
    if v >= 0:
        lo = el.left + off - v * comp.latch_delay[el.bit]
        hi = np.maximum(el.right + off - v * comp.unlatch_delay[el.bit], lo + s.min_width)
    else:
        hi = el.right + off - v * comp.latch_delay[el.bit]
        lo = np.minimum(el.left + off - v * comp.unlatch_delay[el.bit], hi - s.min_width)
    levels = np.concatenate((lo, hi))
    c = cam.c
    if not levels.size:
        cam.gap_lo, cam.gap_hi = -math.inf, math.inf
    elif cam.periodic:
        period = cam.span
        cam.gap_lo = c - float(((c - levels) % period).min())
        cam.gap_hi = c + float(((levels - c) % period).min())
    else:
        below = levels[levels <= c]
        above = levels[levels >= c]
        cam.gap_lo = float(below.max()) if below.size else -math.inf
        cam.gap_hi = float(above.min()) if above.size else math.inf
    due = cam.off_time[cam.on]
    cam.t_due = float(due.min()) if due.size else math.inf
    cam.pulsing = bool((cam.active & (comp.mode >= _M_PULSED) & (comp.cycle_time > 0)).any())
    cam.words = words
    cam.vref = v


def _displacement(x0: float, x1: float, unwind: float) -> float:
    d = x1 - x0
    if unwind > 0:
        d = (d + unwind / 2) % unwind - unwind / 2
    return d


@dataclass(slots=True)
class _Motion:
    """The axis motion over one interval as a function of displacement from its start."""

    t0: float
    dt: float
    x0: float
    dx: float
    v: float
    inverse: TimeOf | None

    def time(self, d: np.ndarray) -> np.ndarray:
        """Absolute time at displacement(s) d (monotone motion within the interval)."""
        if self.dx == 0:
            return np.full(np.shape(d), self.t0)
        if self.inverse is not None:
            return self.t0 + np.clip(self.inverse(np.asarray(d, float)), 0.0, self.dt)
        return self.t0 + np.asarray(d, float) / self.dx * self.dt


def _advance(
    s: OutputCamSet,
    t: OutputCamTarget,
    t0: float,
    dt: float,
    start: np.ndarray,
    end: np.ndarray,
    unwind: np.ndarray | None,
    velocity: np.ndarray | None,
    time_of: dict[tuple[int, int], TimeOf] | None,
    step: OutputCamStep,
) -> float:
    """Exact evaluation of one target over the update; returns the velocity it used."""
    t.transition = False
    word = t.output
    written = 0
    for h in t.dropped:
        step.events.append(OutputCamEvent(h, ENDED, t0))
    t.dropped.clear()
    if t.request is not None:  # MAOC executed since the last update: applies at t0
        req, t.request = t.request, None
        if t.cam is not None:
            step.events.append(OutputCamEvent(t.cam.req.handle, ENDED, t0))
        t.cam = _Cam(req)
        if req.schedule in (
            OutputCamExecutionSchedule.IMMEDIATE,
            OutputCamExecutionSchedule.PENDING,
        ):
            t.cam.locked = True
            t.cam.c = req.cam_arm
            t.cam.enable_prev[:] = _enables(req.elements, t.input, word)
            step.events.append(OutputCamEvent(req.handle, LOCKED, t0))
    cam = t.cam
    assert cam is not None
    ref = int(cam.req.reference)
    uw = float(unwind[t.axis]) if unwind is not None else 0.0
    x0 = float(start[ref, t.axis])
    dx = _displacement(x0, float(end[ref, t.axis]), uw)
    v = float(velocity[ref, t.axis]) if velocity is not None else (dx / dt if dt > 0 else 0.0)
    inv = time_of.get((ref, t.axis)) if time_of else None
    motion = _Motion(t0, dt, x0, dx, v, inv)
    d = 0.0  # displacement processed so far
    for _ in range(64):  # segments: lock, range exit, hand-over (bounded for safety)
        cam = t.cam
        if cam is None:
            break
        if not cam.locked:
            d_lock = _arm_crossing(cam.req, x0, d, dx, uw)
            if d_lock is None:
                break
            cam.locked = True
            cam.c = cam.req.cam_arm
            d = d_lock
            step.events.append(
                OutputCamEvent(cam.req.handle, LOCKED, float(motion.time(np.array(d))))
            )
            cam.enable_prev[:] = _enables(cam.req.elements, t.input, word)
            cam.sync_inside = True
        lo, hi = cam.req.cam_start, cam.req.cam_end
        if not cam.in_range:  # Persistent, outside the range: wait for re-entry
            target_c = lo if cam.c < lo else hi
            rem = dx - d
            gap = target_c - cam.c
            if gap * rem <= 0 or abs(gap) > abs(rem):
                cam.c += rem
                break
            d_in = d + gap
            cam.c = target_c
            d = d_in
            cam.in_range = True
            cam.sync_inside = True
            cam.enable_prev[:] = _enables(cam.req.elements, t.input, word)
        remaining = dx - d
        c_end = cam.c + remaining
        boundary: float | None = None
        if remaining > 0 and c_end > hi:
            boundary = hi
        elif remaining < 0 and c_end < lo:
            boundary = lo
        handover = boundary is not None and (not cam.periodic or t.pending is not None)
        if handover and boundary is not None:
            d_seg_end = d + (boundary - cam.c)
        else:
            d_seg_end = dx
        word, w = _evaluate(s, t, cam, motion, d, d_seg_end, word, step)
        written |= w
        if not handover:
            cam.c = cam.c + (dx - d)
            if cam.periodic and not lo <= cam.c <= hi:
                cam.c = lo + (cam.c - lo) % (hi - lo)
            break
        assert boundary is not None
        d = d_seg_end
        t_x = float(motion.time(np.array(d)))
        cam.c = boundary
        if t.pending is not None:  # hand-over: the pending cam starts at its cam arm
            nxt, t.pending = t.pending, None
            nxt.reference = cam.req.reference
            kind = COMPLETE if cam.req.mode == OutputCamExecutionMode.ONCE else ENDED
            step.events.append(OutputCamEvent(cam.req.handle, kind, t_x))
            t.cam = _Cam(nxt, locked=True, c=nxt.cam_arm)
            t.cam.enable_prev[:] = _enables(nxt.elements, t.input, word)
            t.transition = True
            step.events.append(OutputCamEvent(nxt.handle, PENDING_STARTED, t_x))
        elif cam.req.mode == OutputCamExecutionMode.ONCE:
            step.events.append(OutputCamEvent(cam.req.handle, COMPLETE, t_x))
            t.cam = None
        else:  # Persistent: out of range until the cam position comes back
            cam.in_range = False
            cam.c = boundary + (dx - d)
            break
    if written:
        step.changed[(t.axis, t.target)] = written
    t.output = word
    return v


def _arm_crossing(req: ArmRequest, x0: float, d: float, dx: float, unwind: float) -> float | None:
    """Displacement at which the axis reaches AxisArm in the scheduled direction, if any."""
    sched = req.schedule
    if dx == d:
        return None
    forward = dx > d
    if sched == OutputCamExecutionSchedule.FORWARD_ONLY and not forward:
        return None
    if sched == OutputCamExecutionSchedule.REVERSE_ONLY and forward:
        return None
    rel = req.axis_arm - x0  # displacement that reaches the arm position
    a, b = (d, dx) if forward else (dx, d)
    if unwind > 0:  # a rotary axis passes the arm position once per revolution
        k = math.ceil((a - rel) / unwind) if forward else math.floor((b - rel) / unwind)
        rel = rel + k * unwind
    return rel if a <= rel <= b else None


def _enables(el: CamElements, input_word: int, output_word: int) -> np.ndarray:
    """Enable state of each element from its source word, bit and inversion."""
    src = np.where(el.enable_type >= _E_OUTPUT, output_word, input_word)
    bits = ((src.astype(np.int64) >> el.enable_bit) & 1).astype(bool)
    inverted = (el.enable_type == _E_INVERTED_INPUT) | (el.enable_type == _E_INVERTED_OUTPUT)
    return bits ^ inverted


def _levels(
    level: np.ndarray, a: float, b: float, incl_a: bool, incl_b: bool, period: float
) -> tuple[np.ndarray, np.ndarray]:
    """(element, k) pairs with level + k*period inside the interval from a to b (a < b)."""
    n = level.size
    if not math.isfinite(period):
        inside = ((level >= a) if incl_a else (level > a)) & (
            (level <= b) if incl_b else (level < b)
        )
        idx = np.flatnonzero(inside)
        return idx, np.zeros(idx.size, np.int64)
    ka = (np.ceil((a - level) / period) if incl_a else np.floor((a - level) / period) + 1).astype(
        np.int64
    )
    kb = (np.floor((b - level) / period) if incl_b else np.ceil((b - level) / period) - 1).astype(
        np.int64
    )
    count = np.maximum(kb - ka + 1, 0)
    idx = np.repeat(np.arange(n), count)
    first = np.repeat(ka, count)
    offs = np.arange(idx.size) - np.repeat(np.cumsum(count) - count, count)
    return idx, first + offs


_ENTER, _EXIT = 0, 1


def _evaluate(
    s: OutputCamSet,
    t: OutputCamTarget,
    cam: _Cam,
    motion: _Motion,
    da: float,
    db: float,
    word: int,
    step: OutputCamStep,
) -> tuple[int, int]:
    """Element events and bit switches of one cam over the displacement range [da, db]."""
    el = cam.req.elements
    comp = t.compensation
    ta = float(motion.time(np.array(da)))
    tb = float(motion.time(np.array(db)))
    period = cam.span if cam.periodic else math.inf
    ca = cam.c
    cb = ca + (db - da)
    v = motion.v
    off = comp.offset[el.bit]
    ld = comp.latch_delay[el.bit]
    ud = comp.unlatch_delay[el.bit]
    if v >= 0:  # forward: latch at the left edge, unlatch at the right edge
        lo = el.left + off - v * ld
        hi = el.right + off - v * ud
        hi = np.maximum(hi, lo + s.min_width)
    else:  # mirrored: latch at the right edge (earlier by |v|*LatchDelay)
        hi = el.right + off - v * ld
        lo = el.left + off - v * ud
        lo = np.minimum(lo, hi - s.min_width)
    forward = db > da
    ev_elem: list[np.ndarray] = []
    ev_pos: list[np.ndarray] = []
    ev_kind: list[np.ndarray] = []
    if db != da:
        if forward:
            plan = ((lo, ca, cb, False, True, _ENTER), (hi, ca, cb, True, False, _EXIT))
        else:
            plan = ((hi, cb, ca, True, False, _ENTER), (lo, cb, ca, False, True, _EXIT))
        for level, a, b, ia, ib, kind in plan:
            idx, k = _levels(level, a, b, ia, ib, period)
            if idx.size:
                ev_elem.append(idx)
                ev_pos.append(level[idx] + k * (period if math.isfinite(period) else 0.0))
                ev_kind.append(np.full(idx.size, kind))
    if math.isfinite(period):
        k0 = np.floor((ca - lo) / period)
        inside0 = ca - (lo + k0 * period) <= hi - lo
    else:
        inside0 = (lo <= ca) & (ca <= hi)
    if cam.sync_inside:
        cam.inside[:] = inside0
        cam.sync_inside = False
    jump = np.flatnonzero(cam.inside != inside0)
    if jump.size:  # the window edge moved over the cam position: switch at the start
        ev_elem.append(jump)
        ev_pos.append(np.full(jump.size, ca))
        ev_kind.append(np.where(inside0[jump], _ENTER, _EXIT))
    # enable edges happen at the start of the update (words are sampled per update)
    enable = _enables(el, t.input, word)
    changed = enable != cam.enable_prev
    cam.enable_prev[:] = enable
    due = cam.on & (cam.off_time <= tb)
    pulsing = cam.active & (comp.mode >= _M_PULSED) & (comp.cycle_time > 0)
    if not ev_elem and not changed.any() and not due.any() and not pulsing.any():
        return word, 0
    elem = np.concatenate(ev_elem) if ev_elem else np.zeros(0, np.int64)
    pos = np.concatenate(ev_pos) if ev_pos else np.zeros(0)
    kinds = np.concatenate(ev_kind) if ev_kind else np.zeros(0, np.int64)
    times = motion.time(pos - ca + da) if pos.size else np.zeros(0)
    travel = (pos - ca) * (1.0 if forward else -1.0)
    order = np.lexsort((kinds, travel, elem))
    per_elem: dict[int, list[tuple[float, int]]] = {}
    for i in order:
        per_elem.setdefault(int(elem[i]), []).append((float(times[i]), int(kinds[i])))
    todo = set(per_elem) | set(np.flatnonzero(changed).tolist()) | set(np.flatnonzero(due).tolist())
    switches: list[tuple[float, int, int, bool]] = []  # (time, order, element, on)
    seq = 0
    for e in sorted(todo):
        latch = int(el.latch[e])
        unlatch = int(el.unlatch[e])
        en = bool(enable[e])
        inside = bool(cam.inside[e])
        on = bool(cam.on[e])
        off_at = float(cam.off_time[e])
        dur = float(el.duration[e] + comp.latch_delay[el.bit[e]] - comp.unlatch_delay[el.bit[e]])
        events: list[tuple[float, int]] = []
        if changed[e]:
            events.append((ta, 2 if en else 3))  # 2 enable rises, 3 enable falls
        events.extend(per_elem.get(e, []))
        for when, kind in events:
            if on and off_at <= when:  # duration ran out before this event
                on = False
                switches.append((off_at, seq, e, False))
                seq += 1
            set_it = reset = False
            if kind == _ENTER:
                inside = True
                set_it = latch == _L_POSITION or (latch == _L_POSITION_AND_ENABLE and en)
            elif kind == _EXIT:
                inside = False
                reset = unlatch in (_U_POSITION, _U_POSITION_AND_ENABLE)
            elif kind == 2:
                set_it = latch == _L_ENABLE or (latch == _L_POSITION_AND_ENABLE and inside)
            else:
                reset = unlatch in (
                    _U_ENABLE,
                    _U_POSITION_AND_ENABLE,
                    _U_DURATION_AND_ENABLE,
                )
            if set_it and not on:
                on = True
                switches.append((when, seq, e, True))
                seq += 1
                if unlatch in (_U_DURATION, _U_DURATION_AND_ENABLE):
                    off_at = when + max(dur, 0.0)
                else:
                    off_at = math.inf
            elif reset and on:
                on = False
                off_at = math.inf
                switches.append((when, seq, e, False))
                seq += 1
        if on and off_at <= tb:
            on = False
            switches.append((off_at, seq, e, False))
            seq += 1
            off_at = math.inf
        cam.on[e] = on
        cam.off_time[e] = off_at
        cam.inside[e] = inside
    return _bits(t, cam, switches, ta, tb, word, step)


def _bits(
    t: OutputCamTarget,
    cam: _Cam,
    switches: list[tuple[float, int, int, bool]],
    ta: float,
    tb: float,
    word: int,
    step: OutputCamStep,
) -> tuple[int, int]:
    """Combine element switches per bit (OR), apply the output mode, record the edges."""
    el = cam.req.elements
    comp = t.compensation
    count = np.bincount(el.bit[cam.on], minlength=BITS)  # state after the segment
    # rebuild the per-bit count at the segment start from the end state and the switches
    start_count = count.copy()
    for _, _, e, on in switches:
        start_count[el.bit[e]] += -1 if on else 1
    written = 0
    writes: list[tuple[float, int, int, bool]] = []  # (time, order, bit, value)
    running = start_count.copy()
    order = 0
    for when, _, e, on in sorted(switches, key=_switch_key):
        b = int(el.bit[e])
        before = running[b] > 0
        running[b] += 1 if on else -1
        after = running[b] > 0
        if before == after:
            continue
        mode = int(comp.mode[b])
        if after:
            cam.active[b] = True
            cam.pulse_origin[b] = when
        else:
            cam.active[b] = False
        if mode == _M_NORMAL:
            writes.append((when, order, b, after))
        elif mode == _M_INVERTED:
            writes.append((when, order, b, not after))
        elif mode == _M_PULSED:
            writes.append((when, order, b, after and comp.duty[b] > 0))
        else:
            writes.append((when, order, b, not (after and comp.duty[b] > 0)))
        order += 1
    # pulse trains of pulsed bits while active (origin = the instant the bit turned active)
    pulsed = (comp.mode == _M_PULSED) | (comp.mode == _M_INVERTED_AND_PULSED)
    for b in np.flatnonzero(pulsed & ((start_count > 0) | (count > 0))).tolist():
        writes.extend(_pulse_writes(b, comp, cam, switches, int(start_count[b]), ta, tb, el))
    for when, _, b, value in sorted(writes):
        mask = 1 << b
        if bool(word & mask) == value and not _zero_width(writes, b, when):
            continue
        word = (word | mask) if value else (word & ~mask)
        written |= mask
        step.edges.append(Edge(t.axis, t.target, b, float(when), bool(value)))
    return word, written


def _zero_width(writes: list[tuple[float, int, int, bool]], b: int, when: float) -> bool:
    """A bit switched on and off at the same instant is still reported as two edges."""
    same = [w for w in writes if w[2] == b and w[0] == when]
    return len({w[3] for w in same}) > 1


def _pulse_writes(
    b: int,
    comp: Compensation,
    cam: _Cam,
    switches: list[tuple[float, int, int, bool]],
    start_count: int,
    ta: float,
    tb: float,
    el: CamElements,
) -> list[tuple[float, int, int, bool]]:
    """Pulse edges of bit b inside its active spans within [ta, tb]."""
    period = float(comp.cycle_time[b])
    width = float(comp.duty[b]) * period
    inverted = int(comp.mode[b]) == _M_INVERTED_AND_PULSED
    if period <= 0 or width <= 0 or width >= period:
        return []  # a 0 % or 100 % pulse has no edges of its own
    # active spans of the bit inside the segment
    spans: list[tuple[float, float, float]] = []  # (from, to, origin)
    running = start_count
    active_at_start = start_count > 0
    start = ta if active_at_start else None
    origin = float(cam.pulse_origin[b]) if active_at_start else ta
    count = 0
    for when, _, e, on in sorted(switches, key=_switch_key):
        if int(el.bit[e]) != b:
            continue
        count += 1 if on else -1
        now = (running + count) > 0
        if now and start is None:
            start, origin = when, when
        elif not now and start is not None:
            spans.append((start, when, origin))
            start = None
    if start is not None:
        spans.append((start, tb, origin))
    out: list[tuple[float, int, int, bool]] = []
    for lo, hi, org in spans:
        k = math.floor((lo - org) / period)
        while True:
            on_t = org + k * period
            off_t = on_t + width
            if on_t > hi:
                break
            for x, value in ((on_t, not inverted), (off_t, inverted)):
                if lo < x < hi or lo < x == hi == tb:
                    out.append((x, 1, b, value))
            k += 1
    return out
