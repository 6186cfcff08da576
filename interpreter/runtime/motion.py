"""Motion runtime: connects the program's motion tags to the numpy motion core (SPEC 4, 9.3).

It builds one MotionGroup per motion group from the AXIS_* tags, runs the planner at
t = 0, CUP, 2·CUP, ... before the scan that starts then, writes the axis attributes back
into the axis tags after every update and turns the core's events into MOTION_INSTRUCTION
control bits. Instruction adapters (interpreter/instructions/motion_*.py) call into it;
the controller only calls `before_scan`. Decisions: docs/decisions/0101-motion-runtime.md.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field, fields, is_dataclass
from functools import cache
from typing import Protocol

import numpy as np

from ..motion import STATUS_BITS, AxisKind, CamProfile, EventKind, MotionEvent, MotionGroup
from ..motion.rotary import travel_array
from ..semantics.program import ProgramModel
from ..semantics.types import ArrayType, StructType, is_axis
from ..syntax import nodes as n
from ..vm.values import f32
from .motion_layout import (
    AC,
    CP_STATUS,
    AxisLayout,
    Signature,
    read_profile,
    set_bits,
    signature,
    stored_length,
    struct_type,
    write_profile,
)

DEFAULT_CUP_MS = 2.0
_MG = struct_type("MOTION_GROUP").index

# axis members written after every planner update (REAL) ...
_REALS = (
    "ActualPosition", "CommandPosition", "ActualVelocity", "CommandVelocity",
    "ActualAcceleration", "CommandAcceleration", "AverageVelocity", "PositionError",
)  # fmt: skip
_AVG_MAX_UPDATES = 100_000  # longest AverageVelocity window kept (updates)


@dataclass(eq=False, slots=True)
class Axis:
    """One axis tag: its live storage list and its place in a motion group."""

    name: str
    value: list
    layout: AxisLayout
    group: Group
    index: int
    unwind_ok: bool = True  # False: RotaryAxis set with PositionUnwind not > 0 (ERR 11)


@dataclass(eq=False, slots=True)
class Tracked:
    """A motion process started by an instruction, whose events drive its control bits.

    What its end means is said by the process itself, not by the instruction's name
    (docs/decisions/0104-motion-binding.md): `pc` -- completion sets PC (MAJ never
    completes, MAG and MAR only end); `link` -- a master link (MDAC): IP until the link
    ends, AC while a motion driven by it runs, no ACCEL/DECEL/PC.
    """

    control: list  # the MOTION_INSTRUCTION storage list
    axes: tuple[Axis, ...] = ()  # axes whose Start*Position it sets when it goes in process
    pc: bool = False
    link: bool = False
    profile: list | None = None  # CAM_PROFILE element [0] whose Status counts users
    counted: bool = False  # this process holds one count on profile
    on_start: Callable[[Group], None] | None = None
    on_end: Callable[[Group, bool], None] | None = None  # completed?


class UpdateHook(Protocol):
    """Tags a kind of motion reads before every planner update and writes after it (an
    output cam's Input/Output words and axis words), registered by its binding once."""

    def before_update(self) -> None: ...

    def after_update(self) -> None: ...


@dataclass(eq=False, slots=True)
class Group:
    """A motion group: the core MotionGroup plus the tags and processes attached to it."""

    name: str  # MOTION_GROUP tag name, or "" for the implicit group
    value: list | None  # MOTION_GROUP storage list (None for the implicit group)
    cup_ms: float
    core: MotionGroup
    axes: list[Axis] = field(default_factory=list)
    tracked: dict[int, Tracked] = field(default_factory=dict)
    links: list[int] = field(default_factory=list)  # handles of the tracked master links
    after: list[Callable[[], None]] = field(default_factory=list)
    prev_vel: np.ndarray = field(default_factory=lambda: np.zeros(0))
    history: np.ndarray = field(default_factory=lambda: np.zeros((1, 0)))  # ring of positions
    ring_at: int = 0  # row of the latest position in history
    filled: int = 0  # updates recorded (capped at the ring length - 1)
    actual_accel: np.ndarray = field(default_factory=lambda: np.zeros(0))
    vel_before: np.ndarray = field(default_factory=lambda: np.zeros(0))  # one update earlier
    accel_known: bool = False  # two updates done: ActualAcceleration can be formed
    average_velocity: np.ndarray = field(default_factory=lambda: np.zeros(0))
    stale: bool = True  # updated since its axis attributes were last written to the tags
    hooks: list[UpdateHook] = field(default_factory=list)
    # written with the axis attributes (once before a scan that follows updates): the tags
    # of what a kind of motion binds to the group besides axes (a coordinate system)
    observers: list[Callable[[Group], None]] = field(default_factory=list)

    @property
    def next_time_ms(self) -> float:
        return self.core.updates * self.cup_ms


class MotionRuntime:
    """Motion groups of one program, built from its tags; `before_scan` runs the planner."""

    def __init__(
        self, model: ProgramModel, storage: list[object], coarse_update_ms: float | None = None
    ) -> None:
        self.groups: list[Group] = []
        self._axis_of: dict[int, Axis] = {}
        self._group_of: dict[int, Group] = {}
        self._owner: dict[int, tuple[Group, int]] = {}
        self._profiles: dict[int, tuple[Signature, CamProfile]] = {}
        # objects a kind of motion binds to a tag's storage (id of the storage list), e.g. a
        # coordinate system registered with its group's core on first use
        self.attached: dict[int, object] = {}
        # state that instruction families keep per run (PLCopen blocks: their selections and
        # the state of each instance), by family name
        self.extensions: dict[str, object] = {}
        self._build(model, storage, coarse_update_ms)
        self._init_cam_profiles(model, storage)
        # Axis attributes are written lazily (decision 0104): every one once now, then only
        # the members somebody can read -- the program, --watch/--trace -- before each scan.
        self._demand: frozenset[str] | None = None  # upper-case member names; None: all
        for g in self.groups:
            if g.axes:  # the AverageVelocity window starts here
                g.average_velocity = self._average_velocity(g)
            self._write_axes(g)
        self._demand = program_demand(model) if self.groups else frozenset()

    # ------------------------------------------------------------ building
    def _build(self, model: ProgramModel, T: list[object], cli_cup: float | None) -> None:
        group_tags = [
            t for t in model.tags.values()
            if isinstance(t.type, StructType) and t.type.name == "MOTION_GROUP"
            and t.alias_of is None  # an alias names a group already counted
        ]  # fmt: skip
        by_name: dict[str, Group] = {}
        for t in group_tags:
            value = T[t.slot]
            assert isinstance(value, list)
            g = self._new_group(t.name, value, self._cup(value, model, cli_cup))
            by_name[t.name.upper()] = g
            self._group_of[id(value)] = g
        explicit = model.extra.get("axis_groups", {})  # L5X: axis tag -> MOTION_GROUP tag
        assert isinstance(explicit, dict)
        default: Group | None = self.groups[0] if self.groups else None
        for t in model.tags.values():
            if not is_axis(t.type) or t.alias_of is not None:  # an alias is no second axis
                continue
            home = by_name.get(str(explicit.get(t.name.upper(), "")).upper()) or default
            if home is None:  # SPEC 2.1: axes without a declared group join one implicit group
                home = default = self._new_group("", None, self._cup(None, model, cli_cup))
            value = T[t.slot]
            assert isinstance(value, list) and isinstance(t.type, StructType)
            self._add_axis(home, t.name, t.type.name, value)

    def _new_group(self, name: str, value: list | None, cup_ms: float) -> Group:
        g = Group(name, value, cup_ms, MotionGroup(cup_ms / 1000.0))
        if value is not None:  # the tag shows the period actually used
            value[_MG["COARSEUPDATEPERIOD"]] = round(cup_ms * 1000.0)
        self.groups.append(g)
        return g

    @staticmethod
    def _cup(value: list | None, model: ProgramModel, cli_cup: float | None) -> float:
        """Coarse update period in ms: --coarse-update, else the MOTION_GROUP tag, else 2 ms."""
        if cli_cup is not None:
            return cli_cup
        if value is not None and value[_MG["COARSEUPDATEPERIOD"]] > 0:
            return float(value[_MG["COARSEUPDATEPERIOD"]]) / 1000.0
        if model.coarse_update_ms:
            return float(model.coarse_update_ms)
        return DEFAULT_CUP_MS

    def _add_axis(self, g: Group, name: str, type_name: str, value: list) -> None:
        layout = AxisLayout.of(type_name)
        kind = AxisKind.VIRTUAL if type_name == "AXIS_VIRTUAL" else AxisKind.CIP_DRIVE
        bw = layout.get(value, "PositionLoopBandwidth")
        # servo model (docs/decisions/0101): first-order lag with the loop's time constant
        tau = 1.0 / (2.0 * math.pi * bw) if bw > 0 else 0.0
        idx = g.core.add_axis(name, kind, tau=tau, position=layout.get(value, "ActualPosition"))
        ax = Axis(name, value, layout, g, idx)
        self.read_unwind(ax)
        g.axes.append(ax)
        self._axis_of[id(value)] = ax
        self.refresh(ax)
        g.prev_vel = np.zeros(len(g.axes))
        g.history = np.repeat(g.core.actual_position[None, :], 2, 0)
        g.ring_at, g.filled = 0, 0

    def _init_cam_profiles(self, model: ProgramModel, T: list[object]) -> None:
        """SPEC 2.1: a CAM_PROFILE initialised with points is calculated at load (slopes 0)."""
        from ..motion import calculate_cam_profile
        from ..semantics.checker import cam_points, is_cam_profile_array

        for t in model.tags.values():
            if (
                t.init is None
                or not isinstance(t.init, n.ArrayInit)
                or not is_cam_profile_array(t.type)
            ):
                continue
            pts = cam_points(t.init)
            elements = T[t.slot]
            assert isinstance(elements, list) and isinstance(t.type, ArrayType)
            # the points are REAL data, as MCCP would read them from a CAM array
            profile = calculate_cam_profile(
                [f32(p[0]) for p in pts], [f32(p[1]) for p in pts], [p[2] for p in pts]
            )
            self._profiles[id(elements)] = (write_profile(elements, profile), profile)

    # ------------------------------------------------------------ lookups for adapters
    def axis(self, value: list) -> Axis | None:
        return self._axis_of.get(id(value))

    def group(self, value: list) -> Group | None:
        return self._group_of.get(id(value))

    def refresh(self, ax: Axis) -> None:
        """Copy the axis's configured limits from its tag (the program may change them)."""
        cfg = ax.group.core.axes[ax.index]
        get = ax.layout.get
        v = ax.value
        cfg.max_speed = _limit(get(v, "MaximumSpeed"))
        cfg.max_accel = _limit(get(v, "MaximumAccel"))
        cfg.max_decel = _limit(get(v, "MaximumDecel"))
        cfg.max_accel_jerk = _limit(get(v, "MaximumAccelJerk"))
        cfg.max_decel_jerk = _limit(get(v, "MaximumDecelJerk"))

    def read_unwind(self, ax: Axis) -> bool:
        """Rotary or linear from the tag (RotaryAxis, PositionUnwind; decision 0115): the
        core wraps a rotary axis at its unwind. A rotary axis whose unwind is not > 0 is not
        configured (its motion instructions give error 11) and stays linear; False then."""
        get, v = ax.layout.get, ax.value
        rotary = bool(get(v, "RotaryAxis"))
        unwind = float(get(v, "PositionUnwind")) if rotary else 0.0
        ax.unwind_ok = not rotary or (math.isfinite(unwind) and unwind > 0.0)
        u = unwind if ax.unwind_ok else 0.0
        core = ax.group.core
        if float(core.unwind[ax.index]) != u:
            core.set_unwind(ax.index, u)
            ax.group.stale = True
        return ax.unwind_ok

    def demand(self, members: frozenset[str] | None) -> None:
        """Members (upper case; None: all) that are read from now on, e.g. by a --watch;
        they are written at once so that the reader sees the present state."""
        if self._demand is None:
            return
        self._demand = None if members is None else self._demand | members
        for g in self.groups:
            g.stale = True
            self._write_axes(g)

    # ------------------------------------------------------------ control ownership
    def own(self, ctl: list, g: Group | None = None, handle: int = 0) -> None:
        """The latest execution of an instruction owns its control structure (or none: 0)."""
        if g is None or not handle:
            self._owner.pop(id(ctl), None)
        else:
            self._owner[id(ctl)] = (g, handle)

    def owns(self, ctl: list, g: Group, handle: int) -> bool:
        o = self._owner.get(id(ctl))
        return o is not None and o[0] is g and o[1] == handle

    def track(self, g: Group, handle: int, tracked: Tracked) -> None:
        g.tracked[handle] = tracked
        if tracked.link and handle not in g.links:
            g.links.append(handle)
        self.own(tracked.control, g, handle)

    def token(self, g: Group) -> int:
        return g.core.reserve_handle()

    def after_update(self, g: Group, fn: Callable[[], None]) -> None:
        """Run fn after the group's next planner update (drive messages complete then)."""
        g.after.append(fn)

    # ------------------------------------------------------------ cam profiles
    def load_profile(self, elements: list) -> CamProfile | None:
        """The calculated profile stored in CAM_PROFILE elements (None: not calculated)."""
        count = stored_length(elements)
        if count < 2:
            return None
        sig = signature(elements, count)
        cached = self._profiles.get(id(elements))
        if cached is not None and cached[0] == sig:
            return cached[1]  # the full-precision profile this storage was written from
        profile = read_profile(elements, count)
        if profile is not None:
            self._profiles[id(elements)] = (sig, profile)
        return profile

    def store_profile(self, elements: list, profile: CamProfile) -> None:
        self._profiles[id(elements)] = (write_profile(elements, profile), profile)

    # ------------------------------------------------------------ the planner
    def before_scan(self, now_ms: float) -> None:
        """Run every planner update due at or before the scan that starts at now_ms."""
        groups = self.groups
        if not groups:
            return
        due = now_ms + 1e-6
        if len(groups) == 1:  # the usual case: no choosing between groups
            g = groups[0]
            while g.core.updates * g.cup_ms <= due:
                self._update(g)
        else:
            while True:
                g = min(groups, key=lambda x: x.next_time_ms)
                if g.next_time_ms > due:
                    break
                self._update(g)
        for g in groups:  # the scan may read them: once per scan, not once per update
            if g.stale:
                self._write_axes(g)
                for fn in g.observers:
                    fn(g)

    def _update(self, g: Group) -> None:
        for h in g.hooks:
            h.before_update()
        events = g.core.update()
        if g.core.shifted:  # MRP / MAH: the AverageVelocity window moves with the axis
            g.history += g.core.shift
        for ev in events:
            self._event(g, ev)
        self._active_bits(g)
        for h in g.hooks:
            h.after_update()
        self._record(g)
        after, g.after = g.after, []
        for fn in after:
            fn()

    def _event(self, g: Group, ev: MotionEvent) -> None:
        tr = g.tracked.get(ev.handle)
        if tr is None:
            return
        ctl = tr.control
        own = self.owns(ctl, g, ev.handle)
        k = ev.kind
        if k is EventKind.IN_PROCESS:
            for ax in tr.axes:
                self._start_positions(ax)
            if tr.on_start is not None:
                tr.on_start(g)
        elif k is EventKind.PENDING_STARTED:
            self.count(tr, +1)
        elif k is EventKind.COMPLETE or k is EventKind.ENDED:
            self.count(tr, -1)
            del g.tracked[ev.handle]
            if ev.handle in g.links:
                g.links.remove(ev.handle)
            if tr.on_end is not None:
                tr.on_end(g, k is EventKind.COMPLETE)
            if own:
                pc = 1 if k is EventKind.COMPLETE and tr.pc else 0
                if tr.link:
                    set_bits(ctl, IP=0, AC=0)
                else:
                    set_bits(ctl, IP=0, ACCEL=0, DECEL=0, PC=pc)
        elif k is EventKind.ACCEL or k is EventKind.DECEL or k is EventKind.CONSTANT:
            if own:
                set_bits(ctl, ACCEL=int(k is EventKind.ACCEL), DECEL=int(k is EventKind.DECEL))
        elif k is EventKind.ACTIVE and own:
            set_bits(ctl, AC=1)

    def count(self, tr: Tracked, delta: int) -> None:
        """Profile Status counts the cams using it (SPEC 9.23)."""
        if tr.profile is None:
            return
        if delta > 0 and not tr.counted:
            tr.profile[CP_STATUS] += 1
            tr.counted = True
        elif delta < 0 and tr.counted:
            tr.profile[CP_STATUS] = max(2, tr.profile[CP_STATUS] - 1)
            tr.counted = False

    def _active_bits(self, g: Group) -> None:
        """MDAC .AC follows whether a master-driven motion of the link is running."""
        if not g.links:
            return
        in_use = None
        for h in g.links:
            tr = g.tracked[h]
            if tr.link and tr.control[AC] and self.owns(tr.control, g, h):
                if in_use is None:
                    in_use = g.core.links_in_use()
                if h not in in_use:
                    set_bits(tr.control, AC=0)

    def _start_positions(self, ax: Axis) -> None:
        core, i, v, ix = ax.group.core, ax.index, ax.value, ax.layout.index
        v[ix["STARTCOMMANDPOSITION"]] = f32(float(core.command_position[i]))
        v[ix["STARTACTUALPOSITION"]] = f32(float(core.actual_position[i]))

    # ------------------------------------------------------------ axis attributes
    def _record(self, g: Group) -> None:
        """Per-update history the written attributes derive from: actual acceleration (a
        difference quotient of actual velocity) and, when read, AverageVelocity's window."""
        core = g.core
        av = core.actual_velocity
        # ActualAcceleration = (this update's velocity - the previous one) / cup, formed
        # when written (_write_axes): most updates are never read
        g.vel_before, g.prev_vel = g.prev_vel, av.copy()
        g.accel_known = core.updates > 1
        if self._demand is None or "AVERAGEVELOCITY" in self._demand:
            g.average_velocity = self._average_velocity(g)
        g.stale = True

    def _write_axes(self, g: Group) -> None:
        """The demanded axis attributes into the axis tags (REAL members rounded to float32).

        The values of all axes are computed as arrays, one column per demanded member; each
        axis then takes one store per column (or two slice stores when all are demanded).
        """
        g.stale = False
        if not g.axes:
            return
        plan = _write_plan(g.axes[0].layout, self._demand)
        if not plan.real_names and not plan.int_names:
            return
        core = g.core
        n_axes = len(g.axes)
        if g.accel_known and len(g.vel_before) == n_axes:
            g.actual_accel = (g.prev_vel - g.vel_before) / core.cup
        if len(g.actual_accel) != n_axes or not g.accel_known:
            g.actual_accel = np.zeros(n_axes)
        if len(g.average_velocity) != n_axes:
            g.average_velocity = np.zeros(n_axes)
        columns = {
            "ACTUALPOSITION": lambda: _on_circle(core.actual_position, core.unwind),
            "COMMANDPOSITION": lambda: _on_circle(core.command_position, core.unwind),
            "ACTUALVELOCITY": lambda: core.actual_velocity,
            "COMMANDVELOCITY": lambda: core.command_velocity,
            "ACTUALACCELERATION": lambda: g.actual_accel,
            "COMMANDACCELERATION": lambda: core.command_acceleration,
            "AVERAGEVELOCITY": lambda: g.average_velocity,
            # the short way round on a rotary axis (the command may have wrapped, not yet
            # the actual)
            "POSITIONERROR": lambda: travel_array(
                core.command_position, core.actual_position, core.unwind
            ),
        }
        reals = (
            np.vstack([columns[m]() for m in plan.real_names]).astype(np.float32).T.tolist()
            if plan.real_names
            else None
        )
        ints = None
        if plan.int_names:
            st = core.status
            zero = np.zeros(n_axes, dtype=np.int64)
            servo = core.servo_on.astype(np.int64)
            drive = (servo | core.direct_drive.astype(np.int64)) & ~core.virtual  # MSO or MDO
            sources = {
                "MOTIONSTATUS": lambda: core.motion_status_word().astype(np.int64),
                "AXISSTATUS": lambda: servo | (drive << 1) | (core.shutdown.astype(np.int64) << 2),
                "SERVOACTIONSTATUS": lambda: servo,
                "DRIVEENABLESTATUS": lambda: drive,
            }
            cols = []
            for m in plan.int_names:  # status members the core does not simulate stay 0
                src = sources.get(m)
                cols.append(src() if src is not None else st.get(_STATUS_KEY.get(m, ""), zero))
            ints = np.vstack(cols).astype(np.int64).T.tolist()
        for ax in g.axes:
            v, i = ax.value, ax.index
            if reals is not None:
                if plan.reals is not None:
                    v[plan.reals] = reals[i]
                else:
                    for at, x in zip(plan.real_at, reals[i], strict=True):
                        v[at] = x
            if ints is not None:
                if plan.ints is not None:
                    v[plan.ints] = ints[i]
                else:
                    for at, x in zip(plan.int_at, ints[i], strict=True):
                        v[at] = x

    def _average_velocity(self, g: Group) -> np.ndarray:
        """Actual travel over each axis's AverageVelocityTimebase, per second."""
        cup = g.core.cup
        pos = g.core.actual_position
        tb_at = g.axes[0].layout.index["AVERAGEVELOCITYTIMEBASE"]
        tb = np.array([ax.value[tb_at] for ax in g.axes], dtype=float)
        windows = np.where(tb > 0, np.clip(np.rint(tb / cup), 1, _AVG_MAX_UPDATES), 1).astype(
            np.intp
        )
        size = int(windows.max()) + 1
        if g.history.shape[0] < size:  # grow the ring (rare: a longer timebase was set)
            g.history = np.vstack((g.history, np.repeat(g.history[-1:], size - len(g.history), 0)))
            g.ring_at = len(g.history) - 1
        ring = g.history
        if g.core.unwind.any():  # rotary axes: the ring counts travel through the wrap
            last = ring[g.ring_at]
            u = g.core.unwind
            pos = np.where(u > 0.0, last + travel_array(pos, last, u), pos)
        g.ring_at = (g.ring_at + 1) % len(ring)
        ring[g.ring_at] = pos
        g.filled = min(g.filled + 1, len(ring) - 1)
        k = np.minimum(windows, g.filled)
        past = ring[(g.ring_at - k) % len(ring), np.arange(len(pos))]
        return np.where(k > 0, (pos - past) / (np.maximum(k, 1) * cup), 0.0)


_STATUS_KEY = {name.upper(): name for name in (*STATUS_BITS, "ServoActionStatus", "ShutdownStatus")}


@dataclass(frozen=True, slots=True)
class _WritePlan:
    """Where _write_axes stores. All members demanded: a slice of REAL members (in _REALS
    order) and a slice of status members (the AxisStatus word through
    MaximumSpeedExceeded); otherwise one position per demanded member."""

    real_names: tuple[str, ...]  # upper-case REAL members written, in _REALS order
    real_at: tuple[int, ...]
    int_names: tuple[str, ...]  # upper-case status members written
    int_at: tuple[int, ...]
    reals: slice | None = None  # set when every REAL member is written
    ints: slice | None = None  # set when every status member is written


@cache
def _write_plan(layout: AxisLayout, demand: frozenset[str] | None) -> _WritePlan:
    ix = layout.index
    names = {i: name for name, i in ix.items()}
    r0 = ix[_REALS[0].upper()]
    # the catalog declares these members consecutively; the slices rely on it
    assert [ix[n.upper()] for n in _REALS] == list(range(r0, r0 + len(_REALS))), (
        "AXIS REAL member order"
    )
    s0, s1 = ix["AXISSTATUS"], ix["MAXIMUMSPEEDEXCEEDED"] + 1
    assert s0 < ix["MOTIONSTATUS"] < s1
    all_reals = tuple(m.upper() for m in _REALS)
    all_ints = tuple(names[i] for i in range(s0, s1))
    if demand is None:
        return _WritePlan(
            all_reals, tuple(range(r0, r0 + len(_REALS))), all_ints, tuple(range(s0, s1)),
            slice(r0, r0 + len(_REALS)), slice(s0, s1),
        )  # fmt: skip
    # a packed BOOL read alone still needs its value; the word needs every bit
    reals = tuple(m for m in all_reals if m in demand)
    ints = tuple(m for m in all_ints if m in demand)
    return _WritePlan(reals, tuple(ix[m] for m in reals), ints, tuple(ix[m] for m in ints))


def axis_attributes() -> frozenset[str]:
    """Upper-case names of the axis members the runtime writes after planner updates."""
    plan = _write_plan(AxisLayout.of("AXIS_VIRTUAL"), None)
    return frozenset(plan.real_names + plan.int_names)


def program_demand(model: ProgramModel) -> frozenset[str] | None:
    """Axis attributes the program may read: every member name, GSV attribute name or
    identifier written anywhere in its routines (an over-approximation that needs no
    types), and the members aliases point at. None (all) when an alias names a whole axis."""
    words: set[str] = set()
    for r in model.all_routines():
        _collect_words((r.body, r.rungs, r.decls), words)
    for t in model.tags.values():
        base = t.alias_of
        if base is not None and is_axis(base.type):
            if not t.access:
                return None
            assert isinstance(base.type, StructType)
            words.add(base.type.members[t.access[0]][0].upper())
    return frozenset(words) & axis_attributes()


def watched_members(expr: n.Expr, t: object) -> frozenset[str] | None:
    """Axis attributes a watched reference reads (None: a whole axis, all of them)."""
    if isinstance(t, StructType) and is_axis(t):
        return None
    words: set[str] = set()
    _collect_words(expr, words)
    return frozenset(words) & axis_attributes()


def _collect_words(node: object, out: set[str]) -> None:
    """Identifiers, member names and words (GSV attribute names ...) anywhere below a node.

    The nodes semantics.locate.walk visits, walked here with each node type's field names
    looked up once: a program with large initialised arrays has tens of thousands of nodes
    and this runs before the first scan."""
    stack = [node]
    while stack:
        x = stack.pop()
        if isinstance(x, list | tuple):
            stack.extend(x)
            continue
        cls = type(x)
        names = _NODE_FIELDS[cls] if cls in _NODE_FIELDS else _node_fields(cls)
        if names is None:  # not an AST node (walk skips it too)
            continue
        if isinstance(x, n.Member):
            out.add(x.name.upper())
            words = False
        elif isinstance(x, n.Name):
            out.add(x.ident.upper().rsplit(".", 1)[-1])
            words = False
        else:
            words = True
        for name in names:
            value = getattr(x, name)
            if isinstance(value, str):
                if words:
                    out.add(value.upper())
            elif isinstance(value, list | tuple) or is_dataclass(value):
                stack.append(value)


_NODE_FIELDS: dict[type, tuple[str, ...] | None] = {}


def _node_fields(cls: type) -> tuple[str, ...] | None:
    """Field names of a dataclass node type but its span (None: not a dataclass, or a class
    object itself, which walk does not visit); kept in _NODE_FIELDS."""
    names = None
    if is_dataclass(cls) and not issubclass(cls, type):
        names = tuple(f.name for f in fields(cls) if f.name != "span")
    _NODE_FIELDS[cls] = names
    return names


def _on_circle(pos: np.ndarray, unwind: np.ndarray) -> np.ndarray:
    """Positions as the REAL tag shows them: a rotary position just below the unwind
    that float32 rounds up to the unwind itself is shown as 0, so the tag stays in
    [0, unwind) too (decision 0115)."""
    if not unwind.any():
        return pos
    up = (unwind > 0.0) & (pos.astype(np.float32) >= unwind.astype(np.float32))
    return np.where(up, 0.0, pos) if up.any() else pos


def _limit(x: float) -> float:
    """A configured maximum of 0 means "not configured": no limit."""
    return x if x > 0 else math.inf
