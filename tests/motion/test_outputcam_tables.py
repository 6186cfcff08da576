"""MAOC array checks: substitution or skipping, ERR 36/37, first bad index in SEGMENT."""

from __future__ import annotations

import numpy as np
import pytest

from interpreter.motion.outputcam_tables import (
    CATALOG_ENUMS,
    EX_CYCLE_TIME,
    EX_DURATION,
    EX_DUTY_CYCLE,
    EX_ENABLE_BIT,
    EX_ENABLE_TYPE,
    EX_INACTIVE_WITH_DURATION,
    EX_LATCH_TYPE,
    EX_LEFT_BELOW_START,
    EX_LEFT_RIGHT,
    EX_MODE,
    EX_OUTPUT_BIT,
    EX_RIGHT_ABOVE_END,
    EX_UNLATCH_TYPE,
    check_compensation,
    check_output_cam,
    columns_from_records,
    first_error,
)
from stdlib import catalog

# stdlib/motion_errors.toml: 36 Illegal Output Cam, 37 Illegal Output Compensation
ERR36, ERR37 = 36, 37
GOOD = {"OutputBit": 0, "LatchType": 1, "UnlatchType": 1, "Left": 10.0, "Right": 20.0}


def check(*bad: dict, before: int = 2, start: float = 0.0, end: float = 100.0):
    """Two good elements, then the element under test, then one more good one."""
    recs = [GOOD] * before + [{**GOOD, **b} for b in bad] + [GOOD]
    return check_output_cam(columns_from_records(recs, "OUTPUT_CAM"), start, end)


def test_enums_equal_the_catalog() -> None:
    cat = catalog()
    for name, cls in CATALOG_ENUMS.items():
        values = {(v.value) for v in cat.enum(name).values}
        assert values == {int(m) for m in cls}, name


def test_error_numbers_come_from_the_catalog() -> None:
    errs = catalog().motion_errors
    assert errs[ERR36].name == "Illegal Output Cam"
    assert errs[ERR37].name == "Illegal Output Compensation"


def test_good_array_has_no_error() -> None:
    el, chk = check()
    assert chk.ok and len(el) == 3


@pytest.mark.parametrize(
    ("bad", "exerr", "kept"),
    [
        ({"OutputBit": 32}, EX_OUTPUT_BIT, False),  # not considered
        ({"OutputBit": -1}, EX_OUTPUT_BIT, False),
        ({"LatchType": 4}, EX_LATCH_TYPE, True),  # Inactive used
        ({"UnlatchType": 6}, EX_UNLATCH_TYPE, True),  # Inactive used
        ({"Left": 20.0, "Right": 20.0}, EX_LEFT_RIGHT, False),
        ({"Left": -5.0}, EX_LEFT_BELOW_START, True),  # cam start used
        ({"Right": 150.0}, EX_RIGHT_ABOVE_END, True),  # cam end used
        ({"UnlatchType": 2, "Duration": 0.0}, EX_DURATION, False),
        ({"UnlatchType": 5, "Duration": -1.0}, EX_DURATION, True),  # works as Enable
        ({"LatchType": 2, "EnableType": 4}, EX_ENABLE_TYPE, False),
        ({"LatchType": 2, "EnableBit": 32}, EX_ENABLE_BIT, False),
        ({"LatchType": 0, "UnlatchType": 2, "Duration": 1.0}, EX_INACTIVE_WITH_DURATION, False),
    ],
)
def test_each_output_cam_check(bad: dict, exerr: int, kept: bool) -> None:
    el, chk = check(bad)
    # the bad element is index 2 (after two good ones); the rest is still processed
    assert (chk.error, chk.exerr, chk.segment) == (ERR36, exerr, 2)
    assert len(el) == (4 if kept else 3)
    assert (2 in el.index.tolist()) == kept


def test_substituted_values() -> None:
    el, _ = check({"LatchType": 9}, {"UnlatchType": -1}, {"Left": -5.0}, {"Right": 150.0},
                  {"UnlatchType": 5, "Duration": 0.0}, before=0)  # fmt: skip
    assert el.latch[0] == 0  # Inactive
    assert el.unlatch[1] == 0
    assert el.left[2] == 0.0  # cam start
    assert el.right[3] == 100.0  # cam end
    assert el.unlatch[4] == 3  # Duration and Enable without duration -> Enable


def test_segment_is_the_first_of_several_bad_elements() -> None:
    _, chk = check({"OutputBit": 40}, {"LatchType": 7}, before=3)
    assert (chk.error, chk.exerr, chk.segment) == (ERR36, EX_OUTPUT_BIT, 3)


def test_enable_checks_only_when_an_enable_is_used() -> None:
    # Position/Position: EnableType and EnableBit are not looked at
    el, chk = check({"EnableType": 9, "EnableBit": 99})
    assert chk.ok and len(el) == 4


def comp_check(*recs: dict):
    return check_compensation(columns_from_records(list(recs), "OUTPUT_COMPENSATION"))


@pytest.mark.parametrize(
    ("bad", "exerr", "mode", "duty"),
    [
        ({"Mode": 4}, EX_MODE, 0, 0.0),  # Normal used
        ({"Mode": 2, "CycleTime": 0.1, "DutyCycle": 120}, EX_DUTY_CYCLE, 2, 1.0),  # 100 %
        ({"Mode": 3, "CycleTime": 0.1, "DutyCycle": -3}, EX_DUTY_CYCLE, 3, 0.0),  # 0 %
        ({"Mode": 2, "CycleTime": 0.0, "DutyCycle": 50}, EX_CYCLE_TIME, 0, 0.5),  # not pulsed
        ({"Mode": 3, "CycleTime": -1.0, "DutyCycle": 50}, EX_CYCLE_TIME, 1, 0.5),  # inverted
    ],
)
def test_each_compensation_check(bad: dict, exerr: int, mode: int, duty: float) -> None:
    comp, chk = comp_check({}, bad)
    # SPEC 9.27: for ERR 37 SEGMENT is the compensation index (1 here)
    assert (chk.error, chk.exerr, chk.segment) == (ERR37, exerr, 1)
    assert comp.mode[1] == mode and comp.duty[1] == pytest.approx(duty)


def test_duty_cycle_ignored_when_not_pulsed_and_short_array_leaves_bits_uncompensated() -> None:
    comp, chk = comp_check({"Mode": 1, "DutyCycle": 500, "Offset": 2.5})
    assert chk.ok
    assert comp.offset[0] == 2.5 and np.all(comp.offset[1:] == 0) and np.all(comp.mode[1:] == 0)


def test_oversized_compensation_array() -> None:
    _, chk = comp_check(*([{}] * 33))
    assert (chk.error, chk.segment) == (ERR37, 32)


def test_output_cam_error_reported_before_compensation_error() -> None:
    _, c36 = check({"OutputBit": 40})
    _, c37 = comp_check({"Mode": 9})
    assert first_error(c36, c37) is c36
    assert first_error(check()[1], c37) is c37
