"""String and string-conversion instructions, including their fault cases."""

from __future__ import annotations

import pytest

from interpreter.instructions import strings as S
from interpreter.semantics.types import DINT, INT, REAL, SINT, TypeTable
from interpreter.vm.context import ExecContext
from interpreter.vm.refs import Ref
from interpreter.vm.values import default_value, set_string, string_text


def _s(text: bytes = b"", cap: int | None = None) -> list:
    """A STRING (82 chars) or a string-like UDT value with `cap` characters of DATA."""
    if cap is None:
        v = default_value(TypeTable().get("STRING"))  # type: ignore[arg-type]
        assert isinstance(v, list)
    else:
        v = [0, [0] * cap]
    set_string(v, text)
    return v


def _faults(ctx: ExecContext) -> set[tuple[int, int]]:
    return {(f.type, f.code) for f in ctx.minor_faults.values()}


# ------------------------------------------------------------------ CONCAT
def test_concat() -> None:
    ctx, d = ExecContext(), _s(b"old text")
    S.concat(ctx, True, _s(b"AB"), _s(b"cde"), d)
    assert string_text(d) == b"ABcde" and d[0] == 5 and not ctx.minor_faults


def test_concat_into_source_a() -> None:
    a = _s(b"abc")
    S.concat(ExecContext(), True, a, _s(b"def"), a)
    assert string_text(a) == b"abcdef"


def test_concat_too_long_truncates_with_fault_51() -> None:
    ctx, d = ExecContext(), _s(cap=4)
    S.concat(ctx, True, _s(b"abc"), _s(b"def"), d)
    # 6 characters into DATA[4]: "abcd" kept, minor fault 4/51 (Studio 5000 help)
    assert string_text(d) == b"abcd" and d[0] == 4
    assert _faults(ctx) == {(4, 51)}


def test_source_len_beyond_data_is_fault_51_and_dest_unchanged() -> None:
    ctx, bad, d = ExecContext(), _s(b"xy"), _s(b"keep")
    bad[0] = 90  # LEN 90 > DATA 82
    S.concat(ctx, True, bad, _s(b"z"), d)
    assert string_text(d) == b"keep" and _faults(ctx) == {(4, 51)}


# ------------------------------------------------------------------ MID
def test_mid() -> None:
    ctx, d = ExecContext(), _s()
    S.mid(ctx, True, _s(b"ABCDEFGHIJ"), 3, 4, d)  # 3 chars from position 4: D E F
    assert string_text(d) == b"DEF" and not ctx.minor_faults
    S.mid(ctx, True, _s(b"ABCDEFGHIJ"), 2, 9, d)  # Start 9 + Qty 2 = 11 = LEN + 1: "IJ"
    assert string_text(d) == b"IJ"


@pytest.mark.parametrize(("qty", "start"), [(3, 9), (1, 0), (1, 83), (-1, 2)])
def test_mid_out_of_range_is_fault_56(qty: int, start: int) -> None:
    # (3, 9): 9 + 3 = 12 > LEN 10 + 1; (1, 0): Start < 1; (1, 83): Start > DATA size 82;
    # (-1, 2): negative quantity
    ctx, d = ExecContext(), _s(b"keep")
    S.mid(ctx, True, _s(b"ABCDEFGHIJ"), qty, start, d)
    assert string_text(d) == b"keep" and _faults(ctx) == {(4, 56)}


def test_mid_result_longer_than_dest_is_fault_52() -> None:
    ctx, d = ExecContext(), _s(cap=2)
    S.mid(ctx, True, _s(b"ABCDEF"), 4, 1, d)
    assert string_text(d) == b"AB" and _faults(ctx) == {(4, 52)}


# ------------------------------------------------------------------ FIND
def test_find() -> None:
    ctx, r = ExecContext(), [0]
    src = _s(b"abcabc")
    S.find(ctx, True, src, _s(b"bc"), 1, Ref(r, 0, DINT))
    assert r == [2]  # first "bc" starts at character 2
    S.find(ctx, True, src, _s(b"bc"), 3, Ref(r, 0, DINT))
    assert r == [5]  # searching from character 3: next "bc" at 5
    S.find(ctx, True, src, _s(b"xyz"), 1, Ref(r, 0, DINT))
    assert r == [0]  # not found
    S.find(ctx, True, src, _s(b"a"), 20, Ref(r, 0, DINT))
    assert r == [0]  # Start past LEN but within DATA: nothing there
    assert not ctx.minor_faults


@pytest.mark.parametrize("start", [0, 83])
def test_find_invalid_start_is_fault_56(start: int) -> None:
    ctx, r = ExecContext(), [7]
    S.find(ctx, True, _s(b"abc"), _s(b"a"), start, Ref(r, 0, INT))
    assert r == [7] and _faults(ctx) == {(4, 56)}


# ------------------------------------------------------------------ DELETE
def test_delete() -> None:
    ctx, d = ExecContext(), _s()
    S.delete(ctx, True, _s(b"ABCDEFG"), 2, 3, d)  # remove "CD" (positions 3, 4)
    assert string_text(d) == b"ABEFG"
    S.delete(ctx, True, _s(b"ABCDEFG"), 1, 7, d)  # last character: 7 + 1 = 8 = LEN + 1
    assert string_text(d) == b"ABCDEF" and not ctx.minor_faults


@pytest.mark.parametrize(("qty", "start"), [(2, 7), (1, 0), (-1, 1)])
def test_delete_out_of_range_is_fault_56(qty: int, start: int) -> None:
    ctx, d = ExecContext(), _s(b"keep")
    S.delete(ctx, True, _s(b"ABCDEFG"), qty, start, d)  # (2, 7): 7 + 2 = 9 > 8
    assert string_text(d) == b"keep" and _faults(ctx) == {(4, 56)}


# ------------------------------------------------------------------ INSERT
def test_insert() -> None:
    ctx, d = ExecContext(), _s()
    S.insert(ctx, True, _s(b"ABEF"), _s(b"CD"), 3, d)  # "CD" begins at character 3
    assert string_text(d) == b"ABCDEF"
    S.insert(ctx, True, _s(b"AB"), _s(b"xy"), 1, d)
    assert string_text(d) == b"xyAB"
    S.insert(ctx, True, _s(b"AB"), _s(b"xy"), 3, d)  # LEN + 1: appended
    assert string_text(d) == b"ABxy" and not ctx.minor_faults


@pytest.mark.parametrize("start", [0, 4])
def test_insert_out_of_range_is_fault_56(start: int) -> None:
    ctx, d = ExecContext(), _s(b"keep")
    S.insert(ctx, True, _s(b"AB"), _s(b"xy"), start, d)  # valid Start: 1 .. LEN 2 + 1
    assert string_text(d) == b"keep" and _faults(ctx) == {(4, 56)}


def test_insert_too_long_is_fault_52() -> None:
    ctx, d = ExecContext(), _s(cap=3)
    S.insert(ctx, True, _s(b"AB"), _s(b"xy"), 2, d)  # "AxyB" cut to 3
    assert string_text(d) == b"Axy" and _faults(ctx) == {(4, 52)}


# ------------------------------------------------------------------ UPPER / LOWER
def test_upper_lower() -> None:
    ctx, d = ExecContext(), _s()
    S.upper(ctx, True, _s(b"abZ9 _x\xe9"), d)
    assert string_text(d) == b"ABZ9 _X\xe9"  # only a-z change
    S.lower(ctx, True, _s(b"ABz9-Q"), d)
    assert string_text(d) == b"abz9-q"


# ------------------------------------------------------------------ DTOS / STOD
def test_dtos() -> None:
    d = _s(b"previous")
    S.dtos(ExecContext(), True, -2147483648, d)
    assert string_text(d) == b"-2147483648"
    S.dtos(ExecContext(), True, 0, d)
    assert string_text(d) == b"0"
    ctx, short = ExecContext(), _s(cap=3)
    S.dtos(ctx, True, 12345, short)
    assert string_text(short) == b"123" and _faults(ctx) == {(4, 52)}


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        (b"324", 324),
        (b"\x06324\\12\\1\r", 324),  # RM003 example: control char skipped, stops at "\"
        (b"abc-42xyz", -42),  # minus directly before the digits belongs to the number
        (b"- 7", 7),  # a minus not followed by a digit is skipped
        (b"12.9", 12),  # only the whole part
        (b"no digits", 0),  # destination cleared
        (b"", 0),
    ],
)
def test_stod(text: bytes, expected: int) -> None:
    out = [99]
    S.stod(ExecContext(), True, _s(text), Ref(out, 0, DINT))
    assert out == [expected]


def test_stod_beyond_destination_is_fault_53() -> None:
    ctx, out = ExecContext(), [5]
    S.stod(ctx, True, _s(b"300"), Ref(out, 0, SINT))  # SINT holds -128 .. 127
    assert out == [0] and _faults(ctx) == {(4, 53)}


# ------------------------------------------------------------------ RTOS / STOR
@pytest.mark.parametrize(
    ("value", "text"),
    [
        (1.5, "1.5"),
        (2.0, "2.0"),
        (-0.25, "-0.25"),
        (0.1, "0.1"),  # REAL 0.1 is 0.100000001..., 7 significant digits give 0.1
        (1234567.0, "1234567.0"),
        (12345678.0, "1.234568e+007"),  # 8 digits: exponent form, rounded to 7 digits
        (0.00001, "1.0e-005"),
        (float("inf"), "1.#INF"),
        (float("nan"), "1.#QNAN"),
    ],
)
def test_real_text(value: float, text: str) -> None:
    assert S.real_text(value) == text


def test_rtos_writes_dest_and_checks_size() -> None:
    d = _s()
    S.rtos(ExecContext(), True, 1.5, d)
    assert string_text(d) == b"1.5" and d[0] == 3
    ctx, short = ExecContext(), _s(cap=4)
    S.rtos(ctx, True, 123.25, short)  # "123.25" needs 6 characters
    assert string_text(short) == b"123." and _faults(ctx) == {(4, 52)}


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        (b"1.5", 1.5),
        (b"temp=-12.25C", -12.25),
        (b"x1.5e3y", 1500.0),
        (b"2E-2", 0.02),
        (b"abc", 0.0),
    ],
)
def test_stor(text: bytes, expected: float) -> None:
    out = [7.0]
    S.stor(ExecContext(), True, _s(text), Ref(out, 0, REAL))
    # REAL stores float32: compare against the float32 rounding of the expected value
    assert out == [pytest.approx(expected, rel=1e-7)]


def test_stor_overflow_is_fault_53() -> None:
    ctx, out = ExecContext(), [1.0]
    S.stor(ctx, True, _s(b"1e39"), Ref(out, 0, REAL))  # REAL max is about 3.4e38
    assert out == [0.0] and _faults(ctx) == {(4, 53)}
