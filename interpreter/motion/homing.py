"""Homing (MAH): which homing configurations the simulated axes can carry out.

The simulated axes have no home limit switch, no encoder marker and no torque feedback, so
only the Immediate sequence finds its home event. What happens otherwise (decision 0103):
- a virtual axis accepts Immediate homing only (as in Logix), Active or Passive;
- a sequence that needs the home switch (Switch, Switch-Marker) needs a drive digital input
  the simulated drive does not have: error 84;
- active Marker and Torque Level sequences would search forever for an event that never
  comes: error 41 (the simulated drive's configuration cannot support them);
- passive Marker and Torque Level homing waits for that event without commanding motion:
  the request stays in process (HomingStatus) until a stop, servo off or shutdown ends it;
- active homing of a drive needs the servo loop closed (error 5); absolute homing needs it
  open (error 4) and the Immediate sequence (error 41).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from interpreter.motion.enums import EventKind, HomeMode, HomeSequence, StopType
from interpreter.motion.errors import MotionError, StartResult
from interpreter.motion.process import (
    Ending,
    EndReason,
    Events,
    MotionlessSet,
)

if TYPE_CHECKING:  # the group calls home; only the annotation needs the class
    from interpreter.motion.group import MotionGroup

_SWITCH = (HomeSequence.SWITCH, HomeSequence.SWITCH_MARKER)


def homing_error(
    virtual: bool, servo_on: bool, mode: int, sequence: int
) -> tuple[MotionError, bool]:
    """(error or OK, waits) for a homing request; waits: passive homing that never ends."""
    if mode not in HomeMode.__members__.values() or sequence not in (
        HomeSequence.__members__.values()
    ):
        return MotionError.ILLEGAL_HOMING_CONFIGURATION, False
    immediate = sequence == HomeSequence.IMMEDIATE
    if virtual:
        if mode == HomeMode.ABSOLUTE or not immediate:
            return MotionError.ILLEGAL_HOMING_CONFIGURATION, False
        return MotionError.OK, False
    if mode == HomeMode.ABSOLUTE:
        if not immediate:
            return MotionError.ILLEGAL_HOMING_CONFIGURATION, False
        if servo_on:
            return MotionError.SERVO_ON_STATE, False
        return MotionError.OK, False
    if sequence in _SWITCH:
        return MotionError.DRIVE_DIGITAL_INPUT_NOT_ASSIGNED, False
    if mode == HomeMode.ACTIVE:
        if not servo_on:
            return MotionError.SERVO_OFF_STATE, False
        if not immediate:
            return MotionError.ILLEGAL_HOMING_CONFIGURATION, False
        return MotionError.OK, False
    return MotionError.OK, not immediate


class HomingSet(MotionlessSet):
    """Homing requests of a group as a process set: no motion of its own (immediate homing
    shifts the positions at the start of an update; passive homing that waits commands
    nothing), HomingStatus while one waits, AxisHomedStatus once an axis was homed."""

    def __init__(self) -> None:
        self.waiting: dict[int, int] = {}  # axis -> handle of a passive homing that waits
        self.homed: set[int] = set()
        self.version = 0  # bumped on every change of waiting/homed (status cache key)
        self._status_cache: tuple[int, int, dict[str, np.ndarray]] | None = None

    def end_on(self, axis: int, ev: Events) -> None:
        """A stop, servo off or shutdown ends a waiting homing (IP cleared, no PC)."""
        h = self.waiting.pop(axis, None)
        if h is not None:
            ev.append((h, EventKind.ENDED, axis))
            self.version += 1

    def end_axis(self, axis: int, reason: EndReason, events: Events) -> tuple[float, bool]:
        """Stops (All, Home) and kills end a waiting homing; a merge does not."""
        if reason not in (Ending.KILL, StopType.ALL, StopType.HOME):
            return 0.0, False
        ended = axis in self.waiting
        self.end_on(axis, events)
        return 0.0, ended

    def status(self, n: int) -> dict[str, np.ndarray]:
        cache = self._status_cache
        if cache is not None and cache[0] == n and cache[1] == self.version:
            return cache[2]
        homing = np.zeros(n, dtype=bool)
        homing[list(self.waiting)] = True
        homed = np.zeros(n, dtype=bool)
        homed[list(self.homed)] = True
        out = {"HomingStatus": homing, "AxisHomedStatus": homed}
        self._status_cache = (n, self.version, out)
        return out


def home(
    group: MotionGroup,
    homing: HomingSet,
    axis: int,
    mode: int,
    sequence: int,
    home_position: float,
) -> StartResult:
    """MAH with the axis's homing configuration (see homing.py for what is simulated).

    Immediate homing completes at the next update: the actual position becomes
    `home_position` (the command keeps the following error); Active mode first ends
    every motion of the axis. Passive homing that waits for a marker or torque event
    stays in process until a stop (Home or All), servo off or shutdown ends it.
    """
    if mode == HomeMode.ACTIVE and group.shutdown[axis]:  # active homing moves the axis
        return StartResult(error=MotionError.SHUTDOWN_STATE)
    err, waits = homing_error(bool(group.virtual[axis]), bool(group.servo_on[axis]), mode, sequence)
    if err != MotionError.OK:
        return StartResult(error=err)
    if not math.isfinite(home_position):
        return StartResult(error=MotionError.ILLEGAL_HOMING_CONFIGURATION)
    h = group.new_handle()

    def apply(ev: list[tuple[int, EventKind, int]]) -> None:
        homing.end_on(axis, ev)
        ev.append((h, EventKind.IN_PROCESS, axis))
        if waits:
            homing.waiting[axis] = h
            homing.version += 1
            return
        if mode == HomeMode.ACTIVE:
            group.kill_axis(axis, ev)
        group.shift_position(axis, home_position - float(group.actual_position[axis]))
        homing.homed.add(axis)
        homing.version += 1
        group.status["AxisHomedStatus"][axis] = True
        ev.append((h, EventKind.COMPLETE, axis))

    group.before_update(apply)
    return StartResult(handle=h)
