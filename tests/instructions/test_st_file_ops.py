"""COP / CPS / FLL / SIZE / SWPB called directly on ArrayRef / Ref operands."""

from __future__ import annotations

import pytest

from interpreter.instructions.file_ops import cop, cps, fll, size, swpb
from interpreter.semantics.types import DINT, INT, REAL, SINT, TypeTable
from interpreter.vm.context import ExecContext, MajorFault
from interpreter.vm.refs import ArrayRef, Ref
from interpreter.vm.values import default_value, set_string, string_text


def _arr(values: list, t, start: int = 0) -> ArrayRef:
    return ArrayRef(values, start, t, (len(values),))


# ------------------------------------------------------------------ COP / CPS
def test_cop_dint_bits_to_real() -> None:
    src = [0x3F800000, 0x40000000]
    dst = [0.0, 0.0]
    cop(ExecContext(), True, _arr(src, DINT), _arr(dst, REAL), 2)
    # 16#3F800000: sign 0, exponent 127, mantissa 0 -> 1.0; 16#40000000: exponent 128 -> 2.0
    assert dst == [1.0, 2.0]


def test_cop_real_to_dint_bits() -> None:
    dst = [0]
    cop(ExecContext(), True, _arr([1.0], REAL), _arr(dst, DINT), 1)
    assert dst == [0x3F800000]  # = 1065353216


def test_cop_two_ints_into_one_dint_little_endian() -> None:
    dst = [0]
    cop(ExecContext(), True, _arr([0x1234, 0x5678], INT), _arr(dst, DINT), 1)
    # bytes 34 12 | 78 56 read back as one little-endian DINT: 16#56781234
    assert dst == [0x56781234]


def test_cop_length_counts_dest_elements_and_clamps_at_dest_end() -> None:
    src = [1, 2, 3, 4, 5]
    dst = [0, 0, 0, 0]
    cop(ExecContext(), True, _arr(src, DINT), _arr(dst, DINT, start=2), 5)
    # from dst[2]: only 2 elements remain in the destination -> dst[2], dst[3] = 1, 2
    assert dst == [0, 0, 1, 2]


def test_cop_stops_at_source_end_keeping_remaining_dest_bytes() -> None:
    dst = [0x11223344]
    cop(ExecContext(), True, _arr([1, 2], SINT), _arr(dst, DINT), 1)
    # dest bytes 44 33 22 11; the 2 source bytes replace the low two: 01 02 22 11
    assert dst == [0x11220201]
    dst = [7, 8, 9]
    cop(ExecContext(), True, _arr([5], DINT), _arr(dst, DINT), 3)
    assert dst == [5, 8, 9]  # one source element only


def test_cop_zero_or_negative_length_copies_nothing() -> None:
    dst = [9, 9]
    cop(ExecContext(), True, _arr([1, 2], DINT), _arr(dst, DINT), 0)
    cop(ExecContext(), True, _arr([1, 2], DINT), _arr(dst, DINT), -3)
    assert dst == [9, 9]


def test_cop_overlapping_in_one_array_reads_source_first() -> None:
    a = [1, 2, 3, 4]
    cop(ExecContext(), True, _arr(a, DINT, start=1), _arr(a, DINT, start=0), 3)
    assert a == [2, 3, 4, 4]  # shift down by one
    a = [1, 2, 3, 4]
    cps(ExecContext(), True, _arr(a, DINT, start=0), _arr(a, DINT, start=1), 3)
    assert a == [1, 1, 2, 3]  # shift up by one (source snapshot, memmove)


def test_cop_scalar_ref_destination_is_one_element() -> None:
    store = [0, 77]  # two neighbouring scalars in one container
    cop(ExecContext(), True, _arr([5, 6], DINT), Ref(store, 0, DINT), 2)
    assert store == [5, 77]  # a non-array destination is never walked past


def test_cop_structure_in_place() -> None:
    st = TypeTable().get("STRING")
    a, b = default_value(st), default_value(st)
    assert isinstance(a, list) and isinstance(b, list)
    set_string(a, b"hello")
    data_list = b[1]
    cps(ExecContext(), True, ArrayRef([a], 0, st, ()), ArrayRef([b], 0, st, ()), 1)
    assert string_text(b) == b"hello" and b[0] == 5
    assert b[1] is data_list  # the destination structure keeps its identity


def test_cop_rejects_untyped_operands() -> None:
    with pytest.raises(TypeError):
        cop(ExecContext(), True, 5, _arr([0], DINT), 1)


# ------------------------------------------------------------------ FLL
def test_fll_converts_and_clamps() -> None:
    d = [0, 0, 0, 0, 0]
    fll(ExecContext(), True, 2.5, _arr(d, DINT, start=1), 3)
    assert d == [0, 2, 2, 2, 0]  # 2.5 rounds half to even -> 2
    fll(ExecContext(), True, 3.5, _arr(d, DINT, start=3), 10)
    assert d == [0, 2, 2, 4, 4]  # 3.5 -> 4; only 2 elements left from index 3
    i = [0, 0]
    fll(ExecContext(), True, 70000, _arr(i, INT), 2)
    assert i == [4464, 4464]  # 70000 - 65536 = 4464 (INT wraps)
    r = [0.0]
    fll(ExecContext(), True, 16777217, _arr(r, REAL), 1)
    assert r == [16777216.0]  # REAL holds 24 mantissa bits


def test_fll_zero_length_does_nothing() -> None:
    d = [1, 1]
    fll(ExecContext(), True, 9, _arr(d, DINT), 0)
    assert d == [1, 1]


def test_fll_into_structures_writes_the_source_bytes_unconverted() -> None:
    # FLL into STRING elements raised TypeError (a traceback, found by fuzzing). Into a
    # structure the source is written without conversion, its bytes repeated (1756-RM003).
    t = TypeTable().get("STRING")
    a = [default_value(t) for _ in range(3)]
    for v in a:
        set_string(v, b"hi")
    fll(ExecContext(), True, 0, ArrayRef(a, 1, t, (3,)), 5)  # Length 5 stops at the array end
    assert [string_text(v) for v in a] == [b"hi", b"", b""] and a[2][0] == 0  # LEN 0, DATA zeros
    fll(ExecContext(), True, 0x41414141, ArrayRef(a, 0, t, (3,)), 1)
    # every byte is 16#41 = 'A': LEN reads 16#41414141 = 1094795585, all 82 DATA bytes are 'A'
    assert a[0][0] == 1094795585 and string_text(a[0]) == b"A" * 82
    fll(ExecContext(), True, 1.0, ArrayRef(a, 0, t, (3,)), 1)
    # REAL 1.0 = 16#3F800000, little-endian bytes 00 00 80 3F; as SINTs 0, 0, -128, 63
    assert a[0][0] == 0x3F800000 and a[0][1][:8] == [0, 0, -128, 63] * 2
    assert string_text(a[1]) == b""  # only Length 1 element written


# ------------------------------------------------------------------ SIZE
def test_size_of_each_dimension_of_3d_array() -> None:
    arr = ArrayRef([0] * 24, 0, DINT, (2, 3, 4))  # DINT[2,3,4]: 2*3*4 = 24 elements
    out = [0]
    for dim, expected in ((0, 2), (1, 3), (2, 4)):
        size(ExecContext(), True, arr, dim, Ref(out, 0, DINT))
        assert out == [expected]
    with pytest.raises(MajorFault) as exc:
        size(ExecContext(), True, arr, 3, Ref(out, 0, DINT))
    assert (exc.value.type, exc.value.code) == (4, 20)


def test_size_into_real_dest() -> None:
    out = [0.0]
    size(ExecContext(), True, ArrayRef([0] * 10, 4, SINT, (10,)), 0, Ref(out, 0, REAL))
    assert out == [10.0]  # the whole dimension, whatever the start element


# ------------------------------------------------------------------ SWPB
@pytest.mark.parametrize(
    ("mode", "expected"),
    [(0, 0x78563412), (1, 0x56781234), (2, 0x34127856)],  # DCBA, CDAB, BADC of 12 34 56 78
)
def test_swpb_dint_modes(mode: int, expected: int) -> None:
    out = [0]
    swpb(ExecContext(), True, 0x12345678, mode, Ref(out, 0, DINT))
    assert out == [expected]


def test_swpb_negative_dint_reverse() -> None:
    out = [0]
    swpb(ExecContext(), True, -2147483647, 0, Ref(out, 0, DINT))
    # -2147483647 = 16#80000001 -> reversed 16#01000080 = 16777344
    assert out == [0x01000080]


def test_swpb_int_always_swaps_two_bytes_and_sign_extends() -> None:
    for mode in (0, 1, 2):
        out = [0]
        swpb(ExecContext(), True, 0x1234, mode, Ref(out, 0, INT))
        assert out == [0x3412]
    src = [0x00FF]
    out = [0]
    swpb(ExecContext(), True, Ref(src, 0, INT), 0, Ref(out, 0, DINT))
    # INT 16#00FF -> 16#FF00 = -256 as INT, sign-extended into the DINT
    assert out == [-256]
