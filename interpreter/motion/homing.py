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

from interpreter.motion.enums import HomeMode, HomeSequence
from interpreter.motion.errors import MotionError

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
