"""Output cams (MAOC/MDOC) as a process set of the motion group (decisions 0104, 0112).

The switching itself is `outputcam.OutputCamSet` (pure numpy, decisions 0107/0108). This
module makes it one more element of `MotionGroup._sets`: it moves no axis (`step` gives
nothing), and at `end_update` it takes the interval's start and end positions (actual and
command) and locates every switch inside the coarse update. A stop does not disarm an
output cam (only MDOC or the cam's own end does), so `end_axis` ends nothing.

The tags (Output/Input words, the axis status words) are the binding's business
(`interpreter/instructions/motion_outputcam.py`): it fills `target.output`/`target.input`
before an update and reads `last` (switches, edges) and `status_words` after it.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

import numpy as np

from interpreter.motion.enums import EventKind
from interpreter.motion.outputcam import (
    COMPLETE,
    ENDED,
    PENDING_STARTED,
    ArmRequest,
    ArmResult,
    OutputCamSet,
    OutputCamStep,
)
from interpreter.motion.outputcam_tables import OK, ArrayCheck, Compensation, DisarmType
from interpreter.motion.process import EndReason, Events, MotionlessSet

if TYPE_CHECKING:
    from interpreter.motion.group import MotionGroup

_KINDS = {
    COMPLETE: EventKind.COMPLETE,
    ENDED: EventKind.ENDED,
    PENDING_STARTED: EventKind.PENDING_STARTED,
}
STATUS_WORDS = (
    "OutputCamStatus",
    "OutputCamPendingStatus",
    "OutputCamLockStatus",
    "OutputCamTransitionStatus",
)


class OutputCamProcessSet(MotionlessSet):
    """The output cam execution targets of one motion group, advanced after the axes moved."""

    __slots__ = ("core", "_group", "_start", "_end", "_axis_of", "_ended", "last")

    def __init__(self, group: MotionGroup) -> None:
        self.core = OutputCamSet()
        self._group = group
        self._start: np.ndarray | None = None  # (2, axes): actual, command at the interval start
        self._end = np.zeros((2, 0))  # the same at its end (buffers reused every update)
        self._axis_of: dict[int, int] = {}  # MAOC handle -> axis (events name an axis)
        self._ended: list[int] = []  # handles an MDOC disarmed in a scan: ENDED at the next update
        self.last: OutputCamStep | None = None  # the latest update's switches and edges

    def begin_update(self) -> None:
        if self.core.targets:
            g = self._group
            n = len(g.actual_position)
            if self._start is None or self._start.shape != (2, n):
                self._start = np.empty((2, n))
            self._start[0] = g.actual_position
            self._start[1] = g.command_position

    def end_update(self, actual: np.ndarray, events: Events) -> None:
        for h in self._ended:
            events.append((h, EventKind.ENDED, self._axis_of.pop(h, 0)))
        self._ended.clear()
        if not self.core.targets:
            self.last = None
            return
        g = self._group
        n = len(g.actual_position)
        if self._end.shape != (2, n):
            self._end = np.empty((2, n))
        end = self._end
        end[0] = g.actual_position
        end[1] = g.command_position
        start = self._start if self._start is not None and self._start.shape == end.shape else end
        # rotary axes (decision 0115): positions are wrapped into [0, unwind) before the
        # sets' end_update; the core takes each displacement the short way round
        unwind = g.unwind if g.unwind.any() else None
        # the update at g.time ends the interval that began one coarse update earlier
        step = self.core.update(g.time - g.cup, g.cup, start, end, unwind=unwind)
        for e in step.events:
            kind = _KINDS.get(e.kind)
            if kind is None:  # LOCKED shows in the axis words, not on the MAOC
                continue
            axis = self._axis_of.get(e.handle, 0)
            if kind is not EventKind.PENDING_STARTED:
                self._axis_of.pop(e.handle, None)
            events.append((e.handle, kind, axis))
        self.last = step

    def end_axis(self, axis: int, reason: EndReason, events: Events) -> tuple[float, bool]:
        """A stop, a merge or a servo off does not disarm output cams: MDOC does (and a
        Once cam ends by itself)."""
        return 0.0, False

    def status_words(self, axis: int) -> dict[str, int]:
        return self.core.status_words(axis)


def arm_output_cam(
    group: MotionGroup,
    axis: int,
    target: int,
    request_of: Callable[[int], ArmRequest],
    compensation: Compensation | None,
    check: ArrayCheck = OK,
) -> tuple[int, ArmResult]:
    """MAOC: a fresh handle and the core's answer (refusal, or armed with an array check)."""
    ps = group.output_cams
    h = group.new_handle()
    result = ps.core.arm(axis, target, request_of(h), compensation, check)
    if result.armed:
        ps._axis_of[h] = axis
    return h, result


def disarm_output_cam(group: MotionGroup, axis: int, target: int, disarm_type: DisarmType) -> int:
    """MDOC: drop the armed and pending cams at once (outputs keep their state); the MAOCs
    they belong to end (IP cleared) at the next update. Returns a handle for the MDOC."""
    ps = group.output_cams
    ps._ended.extend(ps.core.disarm(axis, target, disarm_type))
    return group.new_handle()
