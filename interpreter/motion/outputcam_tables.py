"""OUTPUT_CAM / OUTPUT_COMPENSATION arrays: enumerations and the MAOC array checks.

Pure numpy, no tags: the binding hands over the members as columns (one array per member,
named as in the catalog types) and gets back validated columns plus the first error.
Checks follow the MAOC reference (array checks) and SPEC 5 / 9.27; the extended error
numbers are listed in docs/decisions/0107-output-cam-core.md.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from enum import IntEnum
from functools import cache

import numpy as np

from stdlib import catalog


class LatchType(IntEnum):
    INACTIVE = 0
    POSITION = 1
    ENABLE = 2
    POSITION_AND_ENABLE = 3


class UnlatchType(IntEnum):
    INACTIVE = 0
    POSITION = 1
    DURATION = 2
    ENABLE = 3
    POSITION_AND_ENABLE = 4
    DURATION_AND_ENABLE = 5


class EnableType(IntEnum):
    INPUT = 0
    INVERTED_INPUT = 1
    OUTPUT = 2
    INVERTED_OUTPUT = 3


class OutputMode(IntEnum):
    NORMAL = 0
    INVERTED = 1
    PULSED = 2
    INVERTED_AND_PULSED = 3


class OutputCamExecutionMode(IntEnum):
    ONCE = 0
    CONTINUOUS = 1
    PERSISTENT = 2


class OutputCamExecutionSchedule(IntEnum):
    IMMEDIATE = 0
    PENDING = 1
    FORWARD_ONLY = 2
    REVERSE_ONLY = 3
    BIDIRECTIONAL = 4


class PositionReference(IntEnum):
    ACTUAL = 0
    COMMAND = 1


class DisarmType(IntEnum):
    ALL = 0
    SPECIFIC = 1


# The catalog enumerations these classes mirror (tests/motion/test_outputcam_tables.py
# checks them equal, so the numbers are stated once in stdlib/).
CATALOG_ENUMS: dict[str, type[IntEnum]] = {
    "OutputCamLatchType": LatchType,
    "OutputCamUnlatchType": UnlatchType,
    "OutputCamEnableType": EnableType,
    "OutputCompensationMode": OutputMode,
    "OutputCamExecutionMode": OutputCamExecutionMode,
    "OutputCamExecutionSchedule": OutputCamExecutionSchedule,
    "PositionReference": PositionReference,
    "DisarmType": DisarmType,
}


@cache
def error_code(name: str) -> int:
    """The .ERR number of a motion error, by its name in stdlib/motion_errors.toml."""
    for code, err in catalog().motion_errors.items():
        if err.name == name:
            return code
    raise KeyError(name)


def illegal_output_cam() -> int:
    return error_code("Illegal Output Cam")


def illegal_output_compensation() -> int:
    return error_code("Illegal Output Compensation")


# Extended error numbers of ERR 36, in check order (the reference fixes 2, 3 and 8).
EX_OUTPUT_BIT = 1
EX_LATCH_TYPE = 2
EX_UNLATCH_TYPE = 3
EX_LEFT_RIGHT = 4
EX_LEFT_BELOW_START = 5
EX_RIGHT_ABOVE_END = 6
EX_DURATION = 8
EX_ENABLE_TYPE = 9
EX_ENABLE_BIT = 10
EX_INACTIVE_WITH_DURATION = 11
# Extended error numbers of ERR 37.
EX_MODE = 1
EX_DUTY_CYCLE = 2
EX_CYCLE_TIME = 3
EX_COMPENSATION_SIZE = 4

BITS = 32


@dataclass(frozen=True, slots=True)
class ArrayCheck:
    """First offending element of an array check: ERR, EXERR and SEGMENT (0 = no error)."""

    error: int = 0
    exerr: int = 0
    segment: int = 0

    @property
    def ok(self) -> bool:
        return self.error == 0


OK = ArrayCheck()


def first_error(*checks: ArrayCheck) -> ArrayCheck:
    """The error MAOC reports: the OutputCam operand's before the compensation's."""
    for c in checks:
        if not c.ok:
            return c
    return OK


def member_names(type_name: str) -> tuple[str, ...]:
    td = catalog().type(type_name)
    assert td is not None, type_name
    return tuple(m.name for m in td.members)


def columns_from_records(
    records: Sequence[Mapping[str, float]], type_name: str
) -> dict[str, np.ndarray]:
    """Turn a list of member dicts (one per array element) into member columns."""
    names = member_names(type_name)
    return {n: np.array([float(r.get(n, 0.0)) for r in records], dtype=float) for n in names}


@dataclass(slots=True)
class CamElements:
    """The usable elements of an OUTPUT_CAM array after the checks (skipped ones removed)."""

    index: np.ndarray  # position in the original array (for diagnostics)
    bit: np.ndarray
    latch: np.ndarray
    unlatch: np.ndarray
    left: np.ndarray
    right: np.ndarray
    duration: np.ndarray
    enable_type: np.ndarray
    enable_bit: np.ndarray

    def __len__(self) -> int:
        return int(self.index.size)


def _col(columns: Mapping[str, np.ndarray | Sequence[float]], name: str, n: int) -> np.ndarray:
    raw = columns.get(name)
    if raw is None:
        return np.zeros(n)
    return np.asarray(raw, dtype=float).reshape(-1)


def _first(checks: list[tuple[int, np.ndarray]], n: int, error: int) -> ArrayCheck:
    """Lowest offending index; its first failing check gives EXERR."""
    exerr = np.zeros(n, dtype=np.int64)
    for code, bad in reversed(checks):  # earlier checks overwrite later ones
        exerr[bad] = code
    hits = np.flatnonzero(exerr)
    if hits.size == 0:
        return OK
    i = int(hits[0])
    return ArrayCheck(error, int(exerr[i]), i)


def check_output_cam(
    columns: Mapping[str, np.ndarray | Sequence[float]], cam_start: float, cam_end: float
) -> tuple[CamElements, ArrayCheck]:
    """Apply the MAOC output cam array checks: substitute or skip, report the first error."""
    names = member_names("OUTPUT_CAM")
    n = max((np.asarray(columns[k]).size for k in names if k in columns), default=0)
    c = {k: _col(columns, k, n) for k in names}
    bit = c["OutputBit"].astype(np.int64)
    latch = c["LatchType"].astype(np.int64)
    unlatch = c["UnlatchType"].astype(np.int64)
    left = c["Left"].copy()
    right = c["Right"].copy()
    duration = c["Duration"].copy()
    etype = c["EnableType"].astype(np.int64)
    ebit = c["EnableBit"].astype(np.int64)

    bad_bit = (bit < 0) | (bit > 31)
    bad_latch = (latch < 0) | (latch > 3)
    latch = np.where(bad_latch, LatchType.INACTIVE, latch)
    bad_unlatch = (unlatch < 0) | (unlatch > 5)
    unlatch = np.where(bad_unlatch, UnlatchType.INACTIVE, unlatch)

    pos_latch = (latch == LatchType.POSITION) | (latch == LatchType.POSITION_AND_ENABLE)
    pos_unlatch = (unlatch == UnlatchType.POSITION) | (unlatch == UnlatchType.POSITION_AND_ENABLE)
    bad_order = (pos_latch | pos_unlatch) & (left >= right)
    below = pos_latch & (left < cam_start)
    left = np.where(below, cam_start, left)
    above = pos_unlatch & (right > cam_end)
    right = np.where(above, cam_end, right)
    # a window wholly outside the range is empty after the substitution: skipped as bad order
    bad_order |= (pos_latch | pos_unlatch) & ~bad_order & (left >= right) & (below | above)

    dur_unlatch = (unlatch == UnlatchType.DURATION) | (unlatch == UnlatchType.DURATION_AND_ENABLE)
    bad_duration = dur_unlatch & (duration <= 0)
    # Duration and Enable with no usable duration keeps working as an Enable unlatch
    unlatch = np.where(
        bad_duration & (unlatch == UnlatchType.DURATION_AND_ENABLE), UnlatchType.ENABLE, unlatch
    )
    uses_enable = (
        (latch == LatchType.ENABLE)
        | (latch == LatchType.POSITION_AND_ENABLE)
        | (unlatch == UnlatchType.ENABLE)
        | (unlatch == UnlatchType.POSITION_AND_ENABLE)
        | (unlatch == UnlatchType.DURATION_AND_ENABLE)
    )
    bad_etype = uses_enable & ((etype < 0) | (etype > 3))
    bad_ebit = uses_enable & ((ebit < 0) | (ebit > 31))
    inactive_dur = (latch == LatchType.INACTIVE) & dur_unlatch & ~bad_latch

    check = _first(
        [
            (EX_OUTPUT_BIT, bad_bit),
            (EX_LATCH_TYPE, bad_latch),
            (EX_UNLATCH_TYPE, bad_unlatch),
            (EX_LEFT_RIGHT, bad_order),
            (EX_LEFT_BELOW_START, below),
            (EX_RIGHT_ABOVE_END, above),
            (EX_DURATION, bad_duration),
            (EX_ENABLE_TYPE, bad_etype),
            (EX_ENABLE_BIT, bad_ebit),
            (EX_INACTIVE_WITH_DURATION, inactive_dur),
        ],
        n,
        illegal_output_cam(),
    )
    skip = (
        bad_bit
        | bad_order
        | (bad_duration & (unlatch == UnlatchType.DURATION))
        | bad_etype
        | bad_ebit
        | inactive_dur
    )
    keep = ~skip
    elements = CamElements(
        index=np.flatnonzero(keep),
        bit=bit[keep],
        latch=latch[keep],
        unlatch=unlatch[keep],
        left=left[keep],
        right=right[keep],
        duration=duration[keep],
        enable_type=np.where(uses_enable, etype, 0)[keep],
        enable_bit=np.where(uses_enable, ebit, 0)[keep],
    )
    return elements, check


@dataclass(slots=True)
class Compensation:
    """Per output bit (32 entries): uncompensated bits have zeros and Normal mode."""

    offset: np.ndarray
    latch_delay: np.ndarray
    unlatch_delay: np.ndarray
    mode: np.ndarray
    cycle_time: np.ndarray
    duty: np.ndarray  # fraction 0..1

    @staticmethod
    def none() -> Compensation:
        z = np.zeros(BITS)
        return Compensation(z, z.copy(), z.copy(), np.zeros(BITS, np.int64), z.copy(), z.copy())


def check_compensation(
    columns: Mapping[str, np.ndarray | Sequence[float]] | None,
) -> tuple[Compensation, ArrayCheck]:
    """Apply the output compensation checks; index i compensates output bit i."""
    comp = Compensation.none()
    if columns is None:
        return comp, OK
    names = member_names("OUTPUT_COMPENSATION")
    size = max((np.asarray(columns[k]).size for k in names if k in columns), default=0)
    n = min(size, BITS)
    c = {k: _col(columns, k, size)[:n] for k in names}
    mode = c["Mode"].astype(np.int64)
    bad_mode = (mode < 0) | (mode > 3)
    mode = np.where(bad_mode, OutputMode.NORMAL, mode)
    pulsed = (mode == OutputMode.PULSED) | (mode == OutputMode.INVERTED_AND_PULSED)
    duty = c["DutyCycle"]
    bad_duty = pulsed & ((duty < 0) | (duty > 100))
    duty = np.clip(duty, 0.0, 100.0)
    cycle = c["CycleTime"]
    bad_cycle = pulsed & (cycle <= 0)
    # not pulsed: Pulsed falls back to Normal, Inverted and Pulsed to Inverted
    mode = np.where(bad_cycle, mode - 2, mode)
    check = _first(
        [(EX_MODE, bad_mode), (EX_DUTY_CYCLE, bad_duty), (EX_CYCLE_TIME, bad_cycle)],
        n,
        illegal_output_compensation(),
    )
    if check.ok and size > BITS:
        check = ArrayCheck(illegal_output_compensation(), EX_COMPENSATION_SIZE, BITS)
    comp.offset[:n] = c["Offset"]
    comp.latch_delay[:n] = c["LatchDelay"]
    comp.unlatch_delay[:n] = c["UnlatchDelay"]
    comp.mode[:n] = mode
    comp.cycle_time[:n] = cycle
    comp.duty[:n] = duty / 100.0
    return comp, check
