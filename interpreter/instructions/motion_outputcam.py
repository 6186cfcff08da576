"""Output cams: MAOC (arm an output cam on an execution target) and MDOC (disarm).

MAOC reads its OUTPUT_CAM and OUTPUT_COMPENSATION arrays, runs the array checks and arms
the cam in the group's output cam process set (`motion/outputcams.py`); it sets DN and IP in
the executing scan, and ER with ERR 36/37, EXERR and SEGMENT when an array check found an
illegal element (the cam still runs with the substituted or skipped elements, SPEC 9.27).
A refused arming (target, range, schedule) sets ER only. IP clears when the cam ends: PC
when a Once cam leaves its range or hands over, no PC when MDOC disarms it or a later MAOC
replaces it. A stop (MAS, MGS) does not disarm output cams.

Per planner update the binding (one `_Binding` hook per motion group) hands the Input and
Output words to the core before the update, then writes the switched Output bits (only those:
bits the program drives itself stay), the axis words OutputCamStatus, OutputCamPendingStatus,
OutputCamLockStatus and OutputCamTransitionStatus (bit n = execution target n), and records
the exact switch instants for `--watch TAG@edges` (decisions 0112, 0113).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..motion import MotionError
from ..motion.outputcam import ArmRequest, Edge, OutputCamTarget
from ..motion.outputcam_tables import (
    DisarmType,
    OutputCamExecutionMode,
    OutputCamExecutionSchedule,
    PositionReference,
    check_compensation,
    check_output_cam,
    error_code,
    first_error,
    member_names,
)
from ..motion.outputcams import STATUS_WORDS
from ..runtime.motion import Axis, Group, MotionRuntime, Tracked
from ..runtime.motion_layout import ERR, EXERR, SEGMENT, set_bits, struct_type
from ..vm.context import ExecContext
from ..vm.refs import ArrayRef, BitRef, Ref
from ..vm.values import wrap
from .motion_common import clear_on_prescan, fail, real, start_on_axis, whole
from .registry import implements, prescan

# MAOC faceplate indices (EXERR of ERR 13), ST operand order
_MAOC_START, _MAOC_END, _MAOC_MODE, _MAOC_SCHEDULE = 6, 7, 9, 10
_MAOC_AXIS_ARM, _MAOC_CAM_ARM, _MAOC_REFERENCE = 11, 12, 13
_MDOC_TARGET, _MDOC_DISARM = 1, 3


def _members(type_name: str) -> list[tuple[str, int]]:
    ix = struct_type(type_name).index
    return [(m, ix[m.upper()]) for m in member_names(type_name)]


_CAM_MEMBERS = _members("OUTPUT_CAM")
_COMP_MEMBERS = _members("OUTPUT_COMPENSATION")


def _columns(arr: ArrayRef, members: list[tuple[str, int]]) -> dict[str, np.ndarray]:
    """Member columns (one value per array element from the operand's start element)."""
    rows = arr.elements[arr.start :]
    return {m: np.array([float(r[i]) for r in rows], dtype=float) for m, i in members}


def _snapshot(arr: ArrayRef) -> list:
    """The compensation array's values now (compared each update: changes apply at once)."""
    return [list(r) for r in arr.elements[arr.start :]]


@dataclass(eq=False, slots=True)
class _Words:
    """The tags of one execution target: its Output and Input words and compensation array."""

    axis: Axis
    output: Ref
    input: ArrayRef  # the Input tag's storage location (read every update)
    compensation: ArrayRef


@dataclass(eq=False, slots=True)
class _Binding:
    """Tags of the output cams of one motion group (runtime UpdateHook)."""

    g: Group
    words: dict[tuple[int, int], _Words] = field(default_factory=dict)
    # compensation arrays by identity: (the array, its last values, the targets using it)
    comps: dict[int, tuple[ArrayRef, list, set[tuple[int, int]]]] = field(default_factory=dict)
    # exact switch instants of watched Output words: (container id, key) -> edges
    edge_log: dict[tuple[int, int], list[Edge]] = field(default_factory=dict)
    # (core target, Output storage, index, Input storage, index) per bound target
    _reads: list[tuple[OutputCamTarget, list, int, list, int]] | None = None

    def bind(self, key: tuple[int, int], w: _Words) -> None:
        self._reads = None
        old = self.words.get(key)
        if old is not None:
            self._unuse(key, old.compensation)
        self.words[key] = w
        arr = w.compensation
        entry = self.comps.get(id(arr.elements))
        if entry is None:
            entry = self.comps[id(arr.elements)] = (arr, _snapshot(arr), set())
        entry[2].add(key)

    def _unuse(self, key: tuple[int, int], arr: ArrayRef) -> None:
        entry = self.comps.get(id(arr.elements))
        if entry is not None:
            entry[2].discard(key)
            if not entry[2]:
                del self.comps[id(arr.elements)]

    def before_update(self) -> None:
        reads = self._reads
        if reads is None:
            targets = self.g.core.output_cams.core.targets
            reads = self._reads = [
                (targets[key], w.output.container, w.output.key, w.input.elements, w.input.start)
                for key, w in self.words.items()
                if key in targets
            ]
        for t, out, at, inp, start in reads:
            t.output = out[at]
            t.input = inp[start]
        for arr, snap, keys in self.comps.values():
            if arr.elements[arr.start :] != snap:  # changes take effect at once (issue 11)
                snap[:] = _snapshot(arr)
                comp, _ = check_compensation(_columns(arr, _COMP_MEMBERS))
                core = self.g.core.output_cams.core
                for a, tg in keys:
                    core.set_compensation(a, tg, comp)

    def after_update(self) -> None:
        ps = self.g.core.output_cams
        step = ps.last
        if step is None:
            return
        targets = ps.core.targets
        for key, mask in step.changed.items():
            w = self.words.get(key)
            if w is None:
                continue
            ref = w.output
            old = int(ref.container[ref.key])
            ref.container[ref.key] = wrap((old & ~mask) | (targets[key].output & mask), 32, True)
        if self.edge_log and step.edges:
            for e in step.edges:
                w = self.words.get((e.axis, e.target))
                if w is not None:
                    log = self.edge_log.get((id(w.output.container), w.output.key))
                    if log is not None:
                        log.append(e)
        if ps.core.status_changed:
            self.write_status()

    def write_status(self) -> None:
        """The four per-target words of every axis that has output cams."""
        core = self.g.core.output_cams.core
        core.status_changed = False
        words: dict[int, list[int]] = {}
        for (a, tg), t in core.targets.items():
            acc = words.setdefault(a, [0, 0, 0, 0])
            bit = 1 << tg
            cam = t.cam
            if cam is not None or t.request is not None:
                acc[0] |= bit
            if t.pending is not None:
                acc[1] |= bit
            if cam is not None and cam.locked and cam.in_range:
                acc[2] |= bit
            if t.transition:
                acc[3] |= bit
        for ax in self.g.axes:
            found = words.get(ax.index)
            if found is None:
                continue
            ix = ax.layout.index
            for name, value in zip(STATUS_WORDS, found, strict=True):
                ax.value[ix[name.upper()]] = value


def _binding(g: Group) -> _Binding:
    for h in g.hooks:
        if isinstance(h, _Binding):
            return h
    b = _Binding(g)
    g.hooks.append(b)
    return b


def edge_log(rt: MotionRuntime, container: list, key: int) -> list[Edge]:
    """The list the Output word at container[key] records its switch instants into (shared
    by every group's binding; an Output word belongs to one axis)."""
    where = (id(container), key)
    for g in rt.groups:
        found = _binding(g).edge_log.get(where)
        if found is not None:
            return found  # a second watch of the same word reads the same record
    log: list[Edge] = []
    for g in rt.groups:
        _binding(g).edge_log[where] = log
    return log


@implements("MAOC")
def maoc(
    ctx: ExecContext, rung: bool, axis: list, execution_target: object, ctl: list, output: Ref,
    input_word: ArrayRef, output_cam: ArrayRef, cam_start: object, cam_end: object,
    output_compensation: ArrayRef, execution_mode: object, execution_schedule: object,
    axis_arm: object, cam_arm: object, reference: object,
) -> None:  # fmt: skip
    started = start_on_axis(ctx, rung, axis, ctl)
    if started is None:
        return
    rt, ax = started
    ctl[SEGMENT] = 0
    mode, sched, ref = whole(execution_mode), whole(execution_schedule), whole(reference)
    lo, hi, xa, ca = real(cam_start), real(cam_end), real(axis_arm), real(cam_arm)
    for bad, index in (
        (not math.isfinite(lo), _MAOC_START),
        (not math.isfinite(hi), _MAOC_END),
        (mode not in OutputCamExecutionMode.__members__.values(), _MAOC_MODE),
        (sched not in OutputCamExecutionSchedule.__members__.values(), _MAOC_SCHEDULE),
        (not math.isfinite(xa), _MAOC_AXIS_ARM),
        (not math.isfinite(ca), _MAOC_CAM_ARM),
        (ref not in PositionReference.__members__.values(), _MAOC_REFERENCE),
    ):
        if bad:
            fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, index)
            return
    target = whole(execution_target)
    g = ax.group
    b = _binding(g)
    key = (ax.index, target)
    t = g.core.output_cams.core.targets.get(key)
    busy = t is not None and (t.cam is not None or t.request is not None)
    elements, cam_check = check_output_cam(_columns(output_cam, _CAM_MEMBERS), lo, hi)
    comp, comp_check = check_compensation(_columns(output_compensation, _COMP_MEMBERS))
    check = first_error(cam_check, comp_check)
    schedule = OutputCamExecutionSchedule(sched)

    def request(handle: int) -> ArmRequest:
        return ArmRequest(
            handle, elements, lo, hi, OutputCamExecutionMode(mode), schedule, xa, ca,
            PositionReference(ref),
        )  # fmt: skip

    h, r = g.core.arm_output_cam(ax.index, target, request, comp, check)
    if not r.armed:
        fail(rt, ctl, r.error, r.exerr)
        return
    if not (schedule == OutputCamExecutionSchedule.PENDING and busy):
        # a pending cam keeps the running cam's words (it ignores Output and Input)
        b.bind(key, _Words(ax, output, input_word, output_compensation))
    elif (w := b.words.get(key)) is not None:
        b.bind(key, _Words(ax, w.output, w.input, output_compensation))
    rt.track(g, h, Tracked(ctl, (), pc=True))
    b.write_status()  # OutputCamStatus (or PendingStatus) shows in the executing scan
    if r.error:
        ctl[ERR] = wrap(r.error, 16, True)
        ctl[EXERR] = wrap(r.exerr, 8, True)
        ctl[SEGMENT] = r.segment
        set_bits(ctl, ER=1, DN=1, IP=1)
    else:
        set_bits(ctl, DN=1, IP=1)


@implements("MDOC")
def mdoc(
    ctx: ExecContext, rung: bool, axis: list, execution_target: object, ctl: list,
    disarm_type: object,
) -> None:  # fmt: skip
    started = start_on_axis(ctx, rung, axis, ctl)
    if started is None:
        return
    rt, ax = started
    dt = whole(disarm_type)
    if dt not in DisarmType.__members__.values():
        fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, _MDOC_DISARM)
        return
    target = whole(execution_target)
    if dt == DisarmType.SPECIFIC and not 0 <= target < 8:
        fail(rt, ctl, error_code("Illegal Execution Target"))
        return
    g = ax.group
    g.core.disarm_output_cam(ax.index, target, DisarmType(dt))
    _binding(g).write_status()  # the words clear at once; the MAOCs' IP at the next update
    set_bits(ctl, DN=1)


@prescan("MAOC")
def _prescan_maoc(
    ctx: ExecContext, rung: bool, axis: list, target: object, ctl: list, *rest: object
) -> None:
    clear_on_prescan(ctl)


@prescan("MDOC")
def _prescan_mdoc(
    ctx: ExecContext, rung: bool, axis: list, target: object, ctl: list, *rest: object
) -> None:
    clear_on_prescan(ctl)


class EdgeWatch:
    """`--watch TAG@edges` (decision 0113): the exact switch instants an output cam gave the
    Output word TAG (or its bit TAG.n). Called once per trace row, it answers the edges
    since the previous row as text: `TIME:VALUE` per edge for a bit, `TIME:BIT:VALUE` for
    a word, separated by spaces, times in seconds with nanosecond digits; `edges` keeps
    them all (the JSON report and --plot)."""

    __slots__ = ("_log", "_seen", "bit", "edges")

    def __init__(self, rt: MotionRuntime, location: Ref | BitRef) -> None:
        self._log = edge_log(rt, location.container, location.key)
        self._seen = 0
        self.bit: int | None = location.bit if isinstance(location, BitRef) else None
        self.edges: list[tuple[float, int, int]] = []  # (time, bit, value)

    def __call__(self) -> str:
        new = self._log[self._seen :]
        self._seen = len(self._log)
        cells = []
        for e in new:
            if self.bit is not None and e.bit != self.bit:
                continue
            self.edges.append((e.time, e.bit, int(e.value)))
            if self.bit is None:
                cells.append(f"{e.time:.9f}:{e.bit}:{int(e.value)}")
            else:
                cells.append(f"{e.time:.9f}:{int(e.value)}")
        return " ".join(cells)

    def json(self) -> list[list[float]]:
        self()  # edges of the updates after the last row
        if self.bit is None:
            return [[t, b, v] for t, b, v in self.edges]
        return [[t, v] for t, _, v in self.edges]
