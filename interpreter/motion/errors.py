"""Logix motion error numbers (.ERR) used by the core, and the result of a start call."""

from __future__ import annotations

from dataclasses import dataclass
from enum import IntEnum


class MotionError(IntEnum):
    """The subset of the Logix motion error table the core can report."""

    OK = 0
    SERVO_ON_STATE = 4
    SERVO_OFF_STATE = 5
    SHUTDOWN_STATE = 7
    MASTER_AXIS_CONFLICT = 10
    AXIS_NOT_CONFIGURED = 11
    PARAMETER_OUT_OF_RANGE = 13
    AXIS_MODE_NOT_ROTARY = 17
    ILLEGAL_DYNAMIC_CHANGE = 23
    ILLEGAL_CAM_LENGTH = 26
    ILLEGAL_CAM_PROFILE_LENGTH = 27
    ILLEGAL_CAM_TYPE = 28
    ILLEGAL_CAM_ORDER = 29
    CAM_PROFILE_BEING_USED = 31
    CAM_PROFILE_NOT_CALCULATED = 32
    POSITION_CAM_NOT_ENABLED = 33
    ILLEGAL_HOMING_CONFIGURATION = 41
    COORDINATE_SYSTEM_QUEUE_FULL = 43
    ZERO_MAX_DECEL = 54
    DRIVE_DIGITAL_INPUT_NOT_ASSIGNED = 84
    MDSC_NOT_ACTIVATED = 93
    MDSC_UNITS_CONFLICT = 94
    LOCK_DIRECTION_CONFLICT = 95
    MDSC_ALL_CONFLICT = 96
    AXIS_NOT_AT_REST = 100
    MDSC_CALCULATED_DATA_SIZE = 101
    MDSC_INVALID_MODE_OR_MASTER_CHANGE = 105
    MERGE_CURRENT_USING_SECONDS = 106


@dataclass(frozen=True, slots=True)
class StartResult:
    """Outcome of a start call: a generator handle, or an error with its extended code."""

    handle: int = 0
    error: MotionError = MotionError.OK
    exerr: int = 0

    @property
    def ok(self) -> bool:
        return self.error == MotionError.OK


class MotionParameterError(ValueError):
    """Raised by pure planning functions (e.g. MCCP) on bad input; carries .ERR/.EXERR."""

    def __init__(self, error: MotionError, exerr: int, message: str) -> None:
        super().__init__(message)
        self.error = error
        self.exerr = exerr


def bad_operand(index: int) -> StartResult:
    """ERR 13 with the faceplate operand index (first operand is 0) as EXERR."""
    return StartResult(error=MotionError.PARAMETER_OUT_OF_RANGE, exerr=index)
