"""Numpy motion core: axes, move/jog/stop profiles, cams and time cams (no VM knowledge)."""

from interpreter.motion.cam import CamProfile, calculate_cam_profile, time_cam_trajectory
from interpreter.motion.enums import (
    AxisKind,
    CamDirection,
    EventKind,
    ExecutionMode,
    ExecutionSchedule,
    GeneratorKind,
    InstructionMode,
    LockDirection,
    MasterReference,
    MergeMode,
    MergeSpeed,
    MotionType,
    MoveType,
    ProfileShape,
    StopType,
)
from interpreter.motion.errors import MotionError, MotionParameterError, StartResult
from interpreter.motion.group import STATUS_BITS, MotionEvent, MotionGroup
from interpreter.motion.profiles import MoveProfile, plan_jog, plan_move, plan_stop

__all__ = [
    "STATUS_BITS",
    "AxisKind",
    "CamDirection",
    "CamProfile",
    "EventKind",
    "ExecutionMode",
    "ExecutionSchedule",
    "GeneratorKind",
    "InstructionMode",
    "LockDirection",
    "MasterReference",
    "MergeMode",
    "MergeSpeed",
    "MotionError",
    "MotionEvent",
    "MotionGroup",
    "MotionParameterError",
    "MotionType",
    "MoveProfile",
    "MoveType",
    "ProfileShape",
    "StartResult",
    "StopType",
    "calculate_cam_profile",
    "plan_jog",
    "plan_move",
    "plan_stop",
    "time_cam_trajectory",
]
