"""Watch-position events (MAW/MDW): one armed watch per axis, checked at every coarse update.

A watch fires when the axis's actual position passes the watch position in the armed
direction between two updates: forward when last < W <= now, reverse when last > W >= now
(`last` is the position at arming, then at the previous update). An axis standing beyond
the position when armed does not fire until it comes back and crosses it
(docs/decisions/0065-motion-shutdown-watch-strobe.md).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from interpreter.motion.enums import EventKind
from interpreter.motion.errors import StartResult
from interpreter.motion.process import (
    EndReason,
    Events,
    MotionlessSet,
)
from interpreter.motion.rotary import travel

if TYPE_CHECKING:  # bound as MotionGroup methods; only the annotations need the class
    from interpreter.motion.group import MotionGroup


@dataclass(slots=True)
class Watch:
    handle: int
    axis: int
    position: float
    forward: bool
    last: float  # actual position at arming, then at the latest update
    unwind: float = 0.0  # rotary axis: `last` counts on through the wrap (unwrapped)


@dataclass(slots=True)
class WatchSet(MotionlessSet):
    armed: dict[int, Watch] = field(default_factory=dict)  # by axis
    # MAR: (axis, input) -> handle; nothing is wired to the simulated inputs (decision 0065)
    registration: dict[tuple[int, int], int] = field(default_factory=dict)

    def arm(self, watch: Watch) -> Watch | None:
        """Arm a watch; returns the watch it replaces on the same axis, if any."""
        old = self.armed.get(watch.axis)
        self.armed[watch.axis] = watch
        return old

    def disarm(self, axis: int) -> Watch | None:
        return self.armed.pop(axis, None)

    # -- as a process set of the group (decision 0104): no motion, it watches the result
    def end_update(self, actual: np.ndarray, events: Events) -> None:
        if self.armed:  # most updates have no watch armed
            self.check(actual, events)

    def end_axis(self, axis: int, reason: EndReason, events: Events) -> tuple[float, bool]:
        return 0.0, False  # a watch stays armed through stops (only MDW or a new MAW ends it)

    def check(self, actual: np.ndarray, ev: list[tuple[int, EventKind, int]]) -> None:
        """Fire (COMPLETE) and disarm every watch whose position was passed this update."""
        for axis, w in list(self.armed.items()):
            now = float(actual[axis])
            p, u = w.position, w.unwind
            if u > 0.0:  # a rotary axis passes the watch position once per revolution
                now = w.last + travel(now, w.last, u)
                p += u * (math.floor if w.forward else math.ceil)((now - p) / u)
            hit = w.last < p <= now if w.forward else w.last > p >= now
            w.last = now
            if hit:
                del self.armed[axis]
                ev.append((w.handle, EventKind.COMPLETE, axis))


# -- watch position ------------------------------------------------------------------


def arm_watch(group: MotionGroup, axis: int, position: float, forward: bool) -> StartResult:
    """MAW: arm a watch on the actual position; a watch armed earlier on the axis ends."""
    h = group.new_handle()
    at = float(group.actual_position[axis])
    old = group.watch.arm(Watch(h, axis, position, forward, at, float(group.unwind[axis])))
    if old is not None:
        group.after_update(lambda ev: ev.append((old.handle, EventKind.ENDED, axis)))
    return StartResult(handle=h)


def disarm_watch(group: MotionGroup, axis: int) -> StartResult:
    """MDW: disarm the axis's watch; the arming instruction ends without completing."""
    old = group.watch.disarm(axis)
    if old is not None:
        group.after_update(lambda ev: ev.append((old.handle, EventKind.ENDED, axis)))
    return StartResult(handle=group.new_handle())


# -- registration ---------------------------------------------------------------------


def arm_registration(group: MotionGroup, axis: int, input_number: int) -> StartResult:
    """MAR: arm registration input 1 or 2. Nothing is wired to the simulated inputs, so
    an armed registration waits (IP) until MDR or a later MAR on the same input."""
    h = group.new_handle()
    old = group.watch.registration.get((axis, input_number))
    group.watch.registration[(axis, input_number)] = h
    if old is not None:
        group.after_update(lambda ev: ev.append((old, EventKind.ENDED, axis)))
    return StartResult(handle=h)


def disarm_registration(group: MotionGroup, axis: int, input_number: int) -> StartResult:
    """MDR: disarm the input; the arming MAR ends without completing."""
    old = group.watch.registration.pop((axis, input_number), None)
    if old is not None:
        group.after_update(lambda ev: ev.append((old, EventKind.ENDED, axis)))
    return StartResult(handle=group.new_handle())
