"""Closed sets used by the motion core; numeric values are the Logix operand values."""

from __future__ import annotations

from enum import Enum, IntEnum


class AxisKind(Enum):
    VIRTUAL = "AXIS_VIRTUAL"
    CIP_DRIVE = "AXIS_CIP_DRIVE"


class ProfileShape(IntEnum):
    TRAPEZOIDAL = 0
    S_CURVE = 1


class MoveType(IntEnum):
    ABSOLUTE = 0
    INCREMENTAL = 1
    ROTARY_SHORTEST_PATH = 2  # the rotary types need a rotary axis (else error 17)
    ROTARY_POSITIVE = 3
    ROTARY_NEGATIVE = 4


class MergeMode(IntEnum):
    DISABLED = 0
    COORDINATED = 1
    ALL = 2


class MergeSpeed(IntEnum):
    PROGRAMMED = 0
    CURRENT = 1


class StopType(IntEnum):
    """MAS StopType operand."""

    ALL = 0
    JOG = 1
    MOVE = 2
    GEAR = 3
    HOME = 4
    TUNE = 5
    TEST = 6
    TIME_CAM = 7
    POSITION_CAM = 8
    MASTER_OFFSET_MOVE = 9
    DIRECT_CONTROL = 10


class CamDirection(IntEnum):
    SAME = 0
    OPPOSITE = 1
    REVERSE = 2
    UNCHANGED = 3


def direction_sign(direction: int, last_dir: dict[int, int], axis: int) -> int:
    """The sign a cam or gear applies on `axis` (Same +1, Opposite -1, Reverse the opposite of
    the axis's last one, Unchanged the last one; first time: Opposite, Same), remembered
    in `last_dir` for the next start (SPEC 5, MATC direction; MAG and position cams alike)."""
    last = last_dir.get(axis, 0)
    sign = {
        CamDirection.SAME: 1,
        CamDirection.OPPOSITE: -1,
        CamDirection.REVERSE: -last if last else -1,
        CamDirection.UNCHANGED: last if last else 1,
    }[CamDirection(direction)]
    last_dir[axis] = sign
    return sign


class ExecutionMode(IntEnum):
    ONCE = 0
    CONTINUOUS = 1


class ExecutionSchedule(IntEnum):
    IMMEDIATE = 0
    PENDING = 1


class LockDirection(IntEnum):
    NONE = 0
    IMMEDIATE_FORWARD_ONLY = 1
    IMMEDIATE_REVERSE_ONLY = 2
    POSITION_FORWARD = 3
    POSITION_REVERSE = 4


class InstructionMode(IntEnum):
    TIME_DRIVEN = 0
    MASTER_DRIVEN = 1


class MotionType(IntEnum):
    """MDAC MotionType operand."""

    ALL = 0
    MOVE = 1
    JOG = 2
    TIME_CAM = 3
    MASTER_OFFSET_MOVE = 4


class MasterReference(IntEnum):
    ACTUAL = 0
    COMMAND = 1


class GeneratorKind(Enum):
    MOVE = "move"
    JOG = "jog"
    STOP = "stop"
    TIME_CAM = "time_cam"
    MASTER_LINK = "master_link"


class EventKind(Enum):
    """What happened to a handle during one update()."""

    IN_PROCESS = "in_process"  # generator began moving at this update
    COMPLETE = "complete"  # reached its end (PC): move at target, Once cam done, stop done
    ENDED = "ended"  # terminated without completion (replaced, stopped, handed over)
    ERROR = "error"
    PENDING_STARTED = "pending_started"  # a pending time cam became the active one
    ACCEL = "accel"  # phase changes of moves/jogs/stops (MOTION_INSTRUCTION ACCEL/DECEL)
    DECEL = "decel"
    CONSTANT = "constant"  # neither accelerating nor decelerating
    ACTIVE = "active"  # an MDAC link drove a motion that went IP (MDAC .AC)


class HomeMode(IntEnum):
    """AXIS HomeMode attribute."""

    PASSIVE = 0
    ACTIVE = 1
    ABSOLUTE = 2


class HomeSequence(IntEnum):
    """AXIS HomeSequence attribute."""

    IMMEDIATE = 0
    SWITCH = 1
    MARKER = 2
    SWITCH_MARKER = 3
    TORQUE_LEVEL = 4
    TORQUE_LEVEL_MARKER = 5
