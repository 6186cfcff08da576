"""What the motion group schedules: sets of motion processes of one kind.

A motion process is started by an instruction and identified by its handle; it may cover
several axes (a gear: a slave and its master; a path: the axes of a coordinate system) and
may keep outputs that are not axis attributes (an output cam's output word). Processes of
one kind live together in a set that advances all of them per update with numpy, in its own
module beside the group: moves/jogs/stops (generators.py), time cams (timecam.py), gears
(gear.py), watch positions (events.py). MotionGroup keeps the axis state arrays and, per
coarse update, steps every set level by level (masters before slaves, from `edges`), sums
their contributions per axis, runs the servo model, then lets each set look at the final
axis state (`end_update`). It has no branch on the kind of a set. Decision 0104.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum
from typing import Protocol

import numpy as np

from interpreter.motion.enums import EventKind, StopType

Events = list[tuple[int, EventKind, int]]  # (handle, kind, axis) in order of occurrence
LevelSel = tuple[np.ndarray, int] | None  # (level of each axis, level stepped) or all
AxisState = tuple[np.ndarray, np.ndarray]  # (actual, command): index with MasterReference


class Ending(Enum):
    """Why the motion of an axis ends other than by a stop (a StopType says which motion a
    MAS ends; each set decides which of its processes a reason ends)."""

    KILL = "kill"  # servo off, shutdown, active homing: everything at once, pending too
    MERGE_ALL = "merge_all"  # a MAM/MAJ with Merge Enabled takes over the running motion


EndReason = Ending | StopType


@dataclass(slots=True)
class Contribution:
    """What a set of processes adds to its axes in one update (one row per process and
    axis; rows of one axis are summed): position change, command velocity, acceleration."""

    axis: np.ndarray
    dpos: np.ndarray
    vel: np.ndarray
    acc: np.ndarray


# the status of a kind that owns no AXIS status member (one dict: read, never written)
_NO_STATUS: dict[str, np.ndarray] = {}

EMPTY = Contribution(np.zeros(0, np.intp), np.zeros(0), np.zeros(0), np.zeros(0))


_ALL = slice(None)
_NO_ROWS = np.zeros(0, dtype=np.intp)
# rows_at_level answers by row-axis array: (that array, the level array it was computed
# for, rows per level). The arrays are held, so their ids are not reused while cached;
# the sets and the group build new arrays when rows or levels change, never edit them.
_LEVEL_ROWS: dict[int, tuple[np.ndarray, np.ndarray, dict[int, slice | np.ndarray]]] = {}


def rows_at_level(level_sel: LevelSel, row_axes: np.ndarray) -> slice | np.ndarray:
    """The rows of a set to step now: every row (a slice: views, no copies) or the rows whose
    axis has the selected level (masters are stepped before their slaves); no row: an empty
    array. The answer is kept while the set's row-axis array and the group's level array
    are the same objects (the group asks every set at every level of every update)."""
    if level_sel is None:
        return _ALL
    levels, lvl = level_sel
    hit = _LEVEL_ROWS.get(id(row_axes))
    if hit is None or hit[0] is not row_axes or hit[1] is not levels:
        if len(_LEVEL_ROWS) >= 256:  # arrays of sets rebuilt since: let them go
            _LEVEL_ROWS.clear()
        hit = (row_axes, levels, {})
        _LEVEL_ROWS[id(row_axes)] = hit
    by_level = hit[2]
    rows = by_level.get(lvl)
    if rows is None:
        found = np.flatnonzero(levels[row_axes] == lvl)
        n = len(found)
        rows = by_level[lvl] = _NO_ROWS if n == 0 else _ALL if n == len(row_axes) else found
    return rows


class ProcessSet(Protocol):
    """The interface MotionGroup schedules. Start calls stay in the kind's own API (the
    group's start_* methods validate and queue them for the next update)."""

    def begin_update(self) -> None:
        """Before the first level of an update."""

    def step(
        self,
        cup: float,
        level_sel: LevelSel,
        positions: AxisState,
        velocities: AxisState,
        events: Events,
    ) -> Contribution:
        """Advance the processes whose (driven) axis has the selected level one update."""

    def end_update(self, actual: np.ndarray, events: Events) -> None:
        """After every level and the servo step: the final axis state of this update
        (removals and hand-overs collected during step, events that watch positions)."""

    def velocity_sums(self, n: int) -> tuple[np.ndarray, np.ndarray]:
        """Per-axis sums of the processes' command velocity and acceleration."""

    def edges(self) -> list[tuple[int, int]]:
        """(driven axis, master axis) pairs: the master is stepped first."""

    def shift_master(self, axis: int, delta: float) -> None:
        """The axis's position was redefined by delta (MRP, MAH): keep counting travel."""

    def status(self, n: int) -> dict[str, np.ndarray]:
        """AXIS status members (bool per axis) this kind owns, e.g. TimeCamStatus."""

    def end_axis(self, axis: int, reason: EndReason, events: Events) -> tuple[float, bool]:
        """End the processes on the axis that `reason` ends (ENDED events, no PC); returns
        the command velocity they contributed (a stop or merge carries it on) and whether
        any ended."""

    def busy(self, axis: int) -> bool:
        """Does a process of this set move the axis (MDAC: a busy slave keeps its master
        reference)?"""

    def links_in_use(self) -> set[int]:
        """MDAC handles that drive a running process of this set (MDAC .AC)."""

    def stop_requested(self, axis: int | None, stop_type: StopType) -> None:
        """A MAS on the axis (MGS: None) was executed; it applies at the next update, but
        what it frees at once (an axis claimed by a time cam) is freed now."""


class MotionlessSet:
    """The ProcessSet methods of a kind that moves no axis (watch, homing, MDAC links): it
    contributes nothing to the update, and a subclass keeps only what it does."""

    __slots__ = ()

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
        return EMPTY

    def end_update(self, actual: np.ndarray, events: Events) -> None:
        pass

    def velocity_sums(self, n: int) -> tuple[np.ndarray, np.ndarray]:
        return np.zeros(n), np.zeros(n)

    def edges(self) -> list[tuple[int, int]]:
        return []  # the motion a link drives reports its own edge

    def shift_master(self, axis: int, delta: float) -> None:
        pass

    def status(self, n: int) -> dict[str, np.ndarray]:
        return _NO_STATUS

    def busy(self, axis: int) -> bool:
        return False  # moves nothing

    def links_in_use(self) -> set[int]:
        return set()

    def stop_requested(self, axis: int | None, stop_type: StopType) -> None:
        pass
