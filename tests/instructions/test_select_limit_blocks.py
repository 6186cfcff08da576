"""HLL MUX SEL SNEG SSUM MAXC MINC UPDN called directly on their instance structures.

Expected values are worked by hand from the blocks' documented behaviour (1756-RM006,
Studio 5000 v37 help; decision 0063 where the help is silent).
"""

from __future__ import annotations

import math

from interpreter.instructions import select_limit_blocks as sl
from interpreter.vm.context import ExecContext
from tests.instructions.structs import new_struct, struct_type


def _m(type_name: str, v: list, name: str) -> object:
    return v[struct_type(type_name).index[name.upper()]]


# ------------------------------------------------------------------ HLL
def _hll(**members: object) -> list:
    v = new_struct("HL_LIMIT", **members)
    sl.hll(ExecContext(), True, v)
    return v


def test_hll_both_limits_clamp_and_alarm() -> None:
    v = _hll(In=150.0, HighLimit=100.0, LowLimit=0.0)
    # 150 > 100: Out held at 100, HighAlarm (In >= HighLimit), no LowAlarm
    assert _m("HL_LIMIT", v, "Out") == 100.0
    assert (_m("HL_LIMIT", v, "HighAlarm"), _m("HL_LIMIT", v, "LowAlarm")) == (1, 0)
    v = _hll(In=-5.0, HighLimit=100.0, LowLimit=0.0)
    assert _m("HL_LIMIT", v, "Out") == 0.0 and _m("HL_LIMIT", v, "LowAlarm") == 1
    v = _hll(In=42.5, HighLimit=100.0, LowLimit=0.0)
    assert _m("HL_LIMIT", v, "Out") == 42.5
    assert (_m("HL_LIMIT", v, "HighAlarm"), _m("HL_LIMIT", v, "LowAlarm")) == (0, 0)
    assert _m("HL_LIMIT", v, "Status") == 0 and _m("HL_LIMIT", v, "EnableOut") == 1


def test_hll_alarm_at_the_limit_itself() -> None:
    v = _hll(In=100.0, HighLimit=100.0, LowLimit=0.0)
    # In = HighLimit: Out is In (=100) and HighAlarm is on (In >= HighLimit)
    assert _m("HL_LIMIT", v, "Out") == 100.0 and _m("HL_LIMIT", v, "HighAlarm") == 1


def test_hll_select_high_only_and_low_only() -> None:
    # SelectLimit 1: only HighLimit applies; -50 passes below LowLimit 0, no LowAlarm
    v = _hll(In=-50.0, HighLimit=100.0, LowLimit=0.0, SelectLimit=1)
    assert _m("HL_LIMIT", v, "Out") == -50.0 and _m("HL_LIMIT", v, "LowAlarm") == 0
    # SelectLimit 2: only LowLimit applies; 500 passes above HighLimit, no HighAlarm
    v = _hll(In=500.0, HighLimit=100.0, LowLimit=0.0, SelectLimit=2)
    assert _m("HL_LIMIT", v, "Out") == 500.0 and _m("HL_LIMIT", v, "HighAlarm") == 0


def test_hll_invalid_limits_give_low_limit() -> None:
    # both limits, HighLimit 10 <= LowLimit 20: LimitsInv (bit 1) + InstructFault (bit 0),
    # Out = LowLimit = 20 -> Status = 0b011 = 3
    v = _hll(In=15.0, HighLimit=10.0, LowLimit=20.0)
    assert _m("HL_LIMIT", v, "Out") == 20.0
    assert _m("HL_LIMIT", v, "LimitsInv") == 1 and _m("HL_LIMIT", v, "Status") == 3


def test_hll_invalid_select_limit_is_treated_as_both() -> None:
    # SelectLimit 7: SelectLimitInv (bit 2) + InstructFault -> Status 0b101 = 5; clamps as 0
    v = _hll(In=150.0, HighLimit=100.0, LowLimit=0.0, SelectLimit=7)
    assert _m("HL_LIMIT", v, "Out") == 100.0 and _m("HL_LIMIT", v, "Status") == 5


# ------------------------------------------------------------------ MUX
def test_mux_selects_the_numbered_input() -> None:
    v = new_struct("MULTIPLEXER", In1=1.5, In3=3.25, In8=-8.0, Selector=3)
    sl.mux(ExecContext(), True, v)
    assert _m("MULTIPLEXER", v, "Out") == 3.25
    v[struct_type("MULTIPLEXER").index["SELECTOR"]] = 8
    sl.mux(ExecContext(), True, v)
    assert _m("MULTIPLEXER", v, "Out") == -8.0 and _m("MULTIPLEXER", v, "Status") == 0


def test_mux_invalid_selector_keeps_out() -> None:
    v = new_struct("MULTIPLEXER", In1=1.5, Out=9.0, Selector=0)
    sl.mux(ExecContext(), True, v)
    # Selector 0 is outside 1..8: Out stays 9.0, SelectorInv (bit 1) + InstructFault -> 3
    assert _m("MULTIPLEXER", v, "Out") == 9.0 and _m("MULTIPLEXER", v, "Status") == 3


# ------------------------------------------------------------------ SEL / SNEG
def test_sel_picks_in2_while_selector_is_set() -> None:
    v = new_struct("SELECT", In1=10.0, In2=20.0)
    sl.sel(ExecContext(), True, v)
    assert _m("SELECT", v, "Out") == 10.0
    v[struct_type("SELECT").index["SELECTORIN"]] = 1
    sl.sel(ExecContext(), True, v)
    assert _m("SELECT", v, "Out") == 20.0


def test_sneg_negates_only_when_enabled() -> None:
    v = new_struct("SELECTABLE_NEGATE", In=4.5)
    sl.sneg(ExecContext(), True, v)
    assert _m("SELECTABLE_NEGATE", v, "Out") == 4.5
    v[struct_type("SELECTABLE_NEGATE").index["NEGATEENABLE"]] = 1
    sl.sneg(ExecContext(), True, v)
    assert _m("SELECTABLE_NEGATE", v, "Out") == -4.5


# ------------------------------------------------------------------ SSUM
def test_ssum_adds_selected_products_and_bias() -> None:
    v = new_struct(
        "SELECTED_SUMMER",
        In1=2.0,
        Gain1=3.0,
        Select1=1,
        In2=10.0,
        Gain2=0.5,
        Select2=1,
        In3=100.0,
        Gain3=1.0,
        Select3=0,
        Bias=1.0,
    )
    sl.ssum(ExecContext(), True, v)
    # 1 + 2*3 + 10*0.5 = 1 + 6 + 5 = 12 (In3 not selected)
    assert _m("SELECTED_SUMMER", v, "Out") == 12.0


def test_ssum_overflow_clears_enable_out() -> None:
    v = new_struct("SELECTED_SUMMER", In1=3e38, Gain1=10.0, Select1=1)
    sl.ssum(ExecContext(), True, v)
    # 3e38 * 10 exceeds the REAL range: Out is +inf and EnableOut drops
    assert math.isinf(_m("SELECTED_SUMMER", v, "Out"))  # type: ignore[arg-type]
    assert _m("SELECTED_SUMMER", v, "EnableOut") == 0


# ------------------------------------------------------------------ MAXC / MINC
def test_maxc_holds_the_largest_value_until_reset() -> None:
    ix = struct_type("MAXIMUM_CAPTURE").index
    v = new_struct("MAXIMUM_CAPTURE", Reset=1, ResetValue=-100.0)
    sl.maxc(ExecContext(), True, v)
    assert v[ix["OUT"]] == -100.0  # Reset: Out = ResetValue
    v[ix["RESET"]] = 0
    seen = []
    for x in (5.0, 12.0, 7.0, 12.5, -3.0):
        v[ix["IN"]] = x
        sl.maxc(ExecContext(), True, v)
        seen.append(v[ix["OUT"]])
    assert seen == [5.0, 12.0, 12.0, 12.5, 12.5]


def test_minc_holds_the_smallest_value_until_reset() -> None:
    ix = struct_type("MINIMUM_CAPTURE").index
    v = new_struct("MINIMUM_CAPTURE", Reset=1, ResetValue=100.0)
    sl.minc(ExecContext(), True, v)
    v[ix["RESET"]] = 0
    seen = []
    for x in (50.0, 70.0, -2.0, 0.0):
        v[ix["IN"]] = x
        sl.minc(ExecContext(), True, v)
        seen.append(v[ix["OUT"]])
    assert seen == [50.0, 50.0, -2.0, -2.0]


# ------------------------------------------------------------------ UPDN
def test_updn_accumulates_holds_and_initialises() -> None:
    ix = struct_type("UP_DOWN_ACCUM").index
    v = new_struct("UP_DOWN_ACCUM", InPlus=2.5, InMinus=0.5)
    for _ in range(3):
        sl.updn(ExecContext(), True, v)
    assert v[ix["OUT"]] == 6.0  # 3 executions of +2.5 - 0.5 = 3 * 2.0
    v[ix["HOLD"]] = 1
    sl.updn(ExecContext(), True, v)
    assert v[ix["OUT"]] == 6.0  # Hold: unchanged
    v[ix["INITIALIZE"]], v[ix["INITIALVALUE"]] = 1, -1.0
    sl.updn(ExecContext(), True, v)
    assert v[ix["OUT"]] == -1.0  # Initialize wins over Hold: Out = InitialValue
