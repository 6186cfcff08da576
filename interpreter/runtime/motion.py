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
from dataclasses import dataclass, field
from functools import cache

import numpy as np

from ..motion import STATUS_BITS, AxisKind, CamProfile, EventKind, MotionEvent, MotionGroup
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


@dataclass(eq=False, slots=True)
class Group:
    """A motion group: the core MotionGroup plus the tags and processes attached to it."""

    name: str  # MOTION_GROUP tag name, or "" for the implicit group
    value: list | None  # MOTION_GROUP storage list (None for the implicit group)
    cup_ms: float
    core: MotionGroup
    axes: list[Axis] = field(default_factory=list)
    tracked: dict[int, Tracked] = field(default_factory=dict)
    after: list[Callable[[], None]] = field(default_factory=list)
    prev_vel: np.ndarray = field(default_factory=lambda: np.zeros(0))
    history: np.ndarray = field(default_factory=lambda: np.zeros((1, 0)))  # ring of positions
    ring_at: int = 0  # row of the latest position in history
    filled: int = 0  # updates recorded (capped at the ring length - 1)

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
        self._build(model, storage, coarse_update_ms)
        self._init_cam_profiles(model, storage)
        for g in self.groups:
            self._write_axes(g)

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
        while True:
            g = min(groups, key=lambda x: x.next_time_ms)
            if g.next_time_ms > now_ms + 1e-6:
                return
            self._update(g)

    def _update(self, g: Group) -> None:
        events = g.core.update()
        if g.core.shift.any():  # MRP / MAH: the AverageVelocity window moves with the axis
            g.history += g.core.shift
        for ev in events:
            self._event(g, ev)
        self._active_bits(g)
        self._write_axes(g)
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
        in_use = None
        for h, tr in g.tracked.items():
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
    def _write_axes(self, g: Group) -> None:
        """Axis attributes into the axis tags (REAL members rounded to float32).

        The values of all axes are computed as arrays, in member order; each axis then takes
        two slice stores (the REAL block and the status block), the only per-axis cost.
        """
        if not g.axes:
            return
        core = g.core
        av = core.actual_velocity
        acc = (av - g.prev_vel) / core.cup if core.updates > 1 else np.zeros_like(av)
        g.prev_vel = av.copy()
        reals = np.vstack((
            core.actual_position, core.command_position, av, core.command_velocity, acc,
            core.command_acceleration, self._average_velocity(g),
            core.command_position - core.actual_position,
        )).astype(np.float32).T.tolist()  # fmt: skip
        st = core.status
        n = len(g.axes)
        servo = core.servo_on.astype(np.int64)
        drive = servo & ~core.virtual
        shutdown = core.shutdown.astype(np.int64)
        sources = {
            "MOTIONSTATUS": core.motion_status_word().astype(np.int64),
            "AXISSTATUS": servo | (drive << 1) | (shutdown << 2),
            "SERVOACTIONSTATUS": servo,
            "DRIVEENABLESTATUS": drive,
        }
        zero = np.zeros(n, dtype=np.int64)
        rows_by_plan: dict[int, list[list[int]]] = {}
        for ax in g.axes:
            plan = _write_plan(ax.layout)
            rows = rows_by_plan.get(id(plan))
            if rows is None:  # status members the core does not simulate stay 0
                cols = [
                    sources.get(m, st.get(_STATUS_KEY.get(m, ""), zero)) for m in plan.int_names
                ]
                rows = rows_by_plan[id(plan)] = np.vstack(cols).astype(np.int64).T.tolist()
            v, i = ax.value, ax.index
            v[plan.reals] = reals[i]
            v[plan.ints] = rows[i]

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
        g.ring_at = (g.ring_at + 1) % len(ring)
        ring[g.ring_at] = pos
        g.filled = min(g.filled + 1, len(ring) - 1)
        k = np.minimum(windows, g.filled)
        past = ring[(g.ring_at - k) % len(ring), np.arange(len(pos))]
        return np.where(k > 0, (pos - past) / (np.maximum(k, 1) * cup), 0.0)


_STATUS_KEY = {name.upper(): name for name in (*STATUS_BITS, "ServoActionStatus", "ShutdownStatus")}


@dataclass(frozen=True, slots=True)
class _WritePlan:
    """Where _write_axes stores: a slice of REAL members (in _REALS order) and a slice of
    status members (the AxisStatus word through MaximumSpeedExceeded)."""

    reals: slice
    ints: slice
    int_names: tuple[str, ...]  # upper-case member name of each position in `ints`


@cache
def _write_plan(layout: AxisLayout) -> _WritePlan:
    ix = layout.index
    names = {i: name for name, i in ix.items()}
    r0 = ix[_REALS[0].upper()]
    # the catalog declares these members consecutively; the slices rely on it
    assert [ix[n.upper()] for n in _REALS] == list(range(r0, r0 + len(_REALS))), (
        "AXIS REAL member order"
    )
    s0, s1 = ix["AXISSTATUS"], ix["MAXIMUMSPEEDEXCEEDED"] + 1
    assert s0 < ix["MOTIONSTATUS"] < s1
    return _WritePlan(
        slice(r0, r0 + len(_REALS)), slice(s0, s1), tuple(names[i] for i in range(s0, s1))
    )


def _limit(x: float) -> float:
    """A configured maximum of 0 means "not configured": no limit."""
    return x if x > 0 else math.inf
