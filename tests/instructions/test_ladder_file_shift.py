"""AVE / STD / SRT / BSL / BSR / FFL / FFU / LFL / LFU called directly on ArrayRefs and a CONTROL."""

from __future__ import annotations

import math

import pytest

from interpreter.instructions import ladder_file_shift as fs
from interpreter.instructions.ladder_timers_counters import K_LEN, K_POS
from interpreter.semantics.types import DINT, REAL
from interpreter.vm.context import ExecContext, MajorFault
from interpreter.vm.refs import ArrayRef, Ref
from interpreter.vm.values import f32
from tests.instructions.structs import new_control, new_struct, struct_type


def _arr(values: list, t=DINT, start: int = 0, dims: tuple[int, ...] | None = None) -> ArrayRef:  # noqa: ANN001
    return ArrayRef(values, start, t, dims or (len(values),))


# ------------------------------------------------------------------ AVE / STD
def test_ave_integer_mean_rounds_into_dint_and_runs_once_per_true_period() -> None:
    ctx, data = ExecContext(), [1, 2, 3, 4]
    ctl, d = new_control(LEN=4), Ref([0], 0, DINT)
    fs.ave(ctx, True, _arr(data), 0, d, ctl)
    # (1+2+3+4)/4 = 2.5 -> DINT by round-half-even = 2
    assert d.get() == 2
    assert (ctl[fs.EN], ctl[fs.DN], ctl[K_POS]) == (1, 1, 4)
    data[0] = 9
    fs.ave(ctx, True, _arr(data), 0, d, ctl)
    assert d.get() == 2  # held true and done: not recomputed
    fs.ave(ctx, False, _arr(data), 0, d, ctl)
    assert (ctl[fs.EN], ctl[fs.DN], ctl[K_POS]) == (0, 0, 0)
    r = Ref([0.0], 0, REAL)
    fs.ave(ctx, True, _arr(data), 0, r, ctl)
    assert r.get() == 4.5  # (9+2+3+4)/4


def test_ave_along_the_first_dimension_of_a_2d_array() -> None:
    flat = list(range(12))  # a[3,4] with a[i,j] = 4i + j
    ctl, d = new_control(LEN=3), Ref([0.0], 0, REAL)
    fs.ave(ExecContext(), True, _arr(flat, start=1, dims=(3, 4)), 0, d, ctl)
    # from a[0,1], varying i: a[0,1], a[1,1], a[2,1] = 1, 5, 9 -> mean 5
    assert d.get() == 5.0


def test_std_is_the_sample_deviation() -> None:
    ctl, d = new_control(LEN=8), Ref([0.0], 0, REAL)
    ctx = ExecContext()
    fs.std(ctx, True, _arr([2, 4, 4, 4, 5, 5, 7, 9]), 0, d, ctl)
    # mean 5; squared deviations 9+1+1+1+0+0+4+16 = 32; divided by n-1 = 7; root
    assert d.get() == f32(math.sqrt(32 / 7))
    assert ctx.status["N"] == 0 and ctx.status["Z"] == 0


def test_file_errors_fault() -> None:
    d = Ref([0], 0, DINT)
    with pytest.raises(MajorFault) as e:
        fs.ave(ExecContext(), True, _arr([1, 2]), 0, d, new_control(LEN=-1))
    assert (e.value.type, e.value.code) == (4, 21)
    with pytest.raises(MajorFault) as e:
        fs.ave(
            ExecContext(), True, _arr([1, 2]), 1, d, new_control(LEN=2)
        )  # a 1-D array has no dim 1
    assert (e.value.type, e.value.code) == (4, 20)
    with pytest.raises(MajorFault) as e:
        fs.ave(
            ExecContext(), True, _arr([1, 2, 3], start=1), 0, d, new_control(LEN=3)
        )  # 1..3 of 0..2
    assert (e.value.type, e.value.code) == (4, 20)


# ------------------------------------------------------------------ SRT
def test_srt_sorts_ascending_in_place() -> None:
    data, ctl = [5, 3, 9, 1], new_control(LEN=4)
    fs.srt(ExecContext(), True, _arr(data), 0, ctl)
    assert data == [1, 3, 5, 9]
    assert (ctl[fs.DN], ctl[K_POS]) == (1, 4)


def test_srt_part_of_an_array_and_st_form() -> None:
    data = [5, 3, 9, 1]
    fs.srt(ExecContext(), True, _arr(data, start=2), 0, new_control(LEN=2))
    assert data == [5, 3, 1, 9]  # only elements 2 and 3
    ctl, ctx = new_control(LEN=4), ExecContext()
    fs.srt_st(ctx, True, _arr(data), 0, ctl)
    assert data == [1, 3, 5, 9]
    data[:] = [4, 2, 3, 1]
    fs.srt_st(ctx, True, _arr(data), 0, ctl)  # ST: sorts again on every call
    assert data == [1, 2, 3, 4]
    assert ctx.status == {}  # SRT does not affect the math flags


def test_srt_prescan_writes_pseudo_operands() -> None:
    ctl = new_control()
    fs.srt_prescan(ExecContext(), True, _arr([0]), 0, ctl, 7, 0)
    assert (ctl[K_LEN], ctl[K_POS]) == (7, 0)


# ------------------------------------------------------------------ BSL / BSR
def test_bsl_across_two_words() -> None:
    words, ctl = [0x80000001, 1 << 7], new_control(LEN=40)
    src = Ref([1], 0, DINT)
    fs.bsl(ExecContext(), True, _arr(words), ctl, src.get())
    # 40-bit register: bit 39 (word 1 bit 7) = 1 goes to UL; every bit moves up one:
    # word 0 bit 31 -> word 1 bit 0, bit 0 -> bit 1, source 1 -> bit 0; word 1 bit 7 -> bit 8
    assert words == [0b11, (1 << 8) | 1]
    assert (ctl[fs.UL], ctl[fs.DN], ctl[fs.EN]) == (1, 1, 1)
    fs.bsl(ExecContext(), True, _arr(words), ctl, 0)
    assert words == [0b11, (1 << 8) | 1]  # rung still true: no second shift
    fs.bsl(ExecContext(), False, _arr(words), ctl, 0)
    assert (ctl[fs.EN], ctl[fs.DN]) == (0, 0)
    fs.bsl(ExecContext(), True, _arr(words), ctl, 0)
    # bit 39 was 0 now: UL 0; word 1 = 2#10_0000_0010 << 1 = 2#100_0000_0100
    assert words == [0b110, (1 << 9) | 2] and ctl[fs.UL] == 0


def test_bsr_source_enters_the_top_bit() -> None:
    words, ctl = [0b1000_0001], new_control(LEN=8)
    fs.bsr(ExecContext(), True, _arr(words), ctl, 1)
    # bit 0 (1) -> UL; shift down: 2#0100_0000; source 1 into bit 7: 2#1100_0000 = 192
    assert words == [192] and ctl[fs.UL] == 1


def test_bsl_length_beyond_the_array_faults_and_prescan() -> None:
    with pytest.raises(MajorFault):
        fs.bsl(ExecContext(), True, _arr([0]), new_control(LEN=33), 1)
    ctl = new_control(EN=1, UL=1)
    fs.shift_prescan(ExecContext(), True, _arr([0]), ctl, 0, 16)
    assert (ctl[K_LEN], ctl[fs.EN], ctl[fs.UL]) == (16, 0, 0)


# ------------------------------------------------------------------ FIFO / LIFO
def _pulse(fn, *args) -> None:  # noqa: ANN001
    """One false and one true execution: a rising edge of the rung."""
    fn(ExecContext(), False, *args)
    fn(ExecContext(), True, *args)


def test_fifo_load_until_full_then_unload_in_order() -> None:
    q, ctl = [0, 0, 0], new_control(LEN=3)
    for v in (10, 20, 30, 40):
        _pulse(fs.ffl, v, _arr(q), ctl)
    # the fourth load finds the queue full (POS 3 = LEN): DN set, 40 not stored
    assert q == [10, 20, 30] and (ctl[K_POS], ctl[fs.DN], ctl[fs.EM]) == (3, 1, 0)
    out = Ref([0], 0, DINT)
    _pulse(fs.ffu, _arr(q), out, ctl)
    # oldest out; the rest move down one place (the last element keeps its value)
    assert out.get() == 10 and q == [20, 30, 30]
    assert (ctl[K_POS], ctl[fs.DN], ctl[fs.EM]) == (2, 0, 0)
    _pulse(fs.ffu, _arr(q), out, ctl)
    _pulse(fs.ffu, _arr(q), out, ctl)
    assert out.get() == 30 and (ctl[K_POS], ctl[fs.EM]) == (0, 1)
    out.set(99)
    _pulse(fs.ffu, _arr(q), out, ctl)
    assert out.get() == 0 and ctl[K_POS] == 0  # empty queue returns 0


def test_fifo_prescan_prevents_a_load_on_the_first_scan() -> None:
    q, ctl = [0, 0], new_control()
    fs.load_prescan(ExecContext(), True, 5, _arr(q), ctl, 2, 0)
    assert (ctl[K_LEN], ctl[K_POS], ctl[fs.EN]) == (2, 0, 1)
    fs.ffl(ExecContext(), True, 5, _arr(q), ctl)
    assert q == [0, 0] and ctl[K_POS] == 0
    fs.unload_prescan(ExecContext(), True, _arr(q), Ref([0], 0, DINT), ctl, None, None)
    assert ctl[fs.EU] == 1 and ctl[K_LEN] == 2


def test_lifo_unloads_newest_first() -> None:
    s, ctl, out = [0, 0, 0], new_control(LEN=3), Ref([0], 0, DINT)
    _pulse(fs.lfl, 1, _arr(s), ctl)
    _pulse(fs.lfl, 2, _arr(s), ctl)
    _pulse(fs.lfu, _arr(s), out, ctl)
    assert out.get() == 2 and ctl[K_POS] == 1
    _pulse(fs.lfu, _arr(s), out, ctl)
    assert out.get() == 1 and (ctl[K_POS], ctl[fs.EM]) == (0, 1)


def test_fifo_of_structures_copies_values() -> None:
    counter_t = struct_type("COUNTER")
    q = [new_struct("COUNTER"), new_struct("COUNTER")]
    ctl = new_control(LEN=2)
    src = new_struct("COUNTER", PRE=5, ACC=3)
    _pulse(fs.ffl, src, ArrayRef(q, 0, counter_t, (2,)), ctl)
    src[1] = 99  # the queued copy must not follow the source
    assert q[0] == new_struct("COUNTER", PRE=5, ACC=3)
    dest = new_struct("COUNTER")
    _pulse(fs.ffu, ArrayRef(q, 0, counter_t, (2,)), dest, ctl)
    assert dest == new_struct("COUNTER", PRE=5, ACC=3)


def test_invalid_length_sets_em_and_dn() -> None:
    ctl = new_control(LEN=0)
    _pulse(fs.ffl, 1, _arr([0]), ctl)
    assert (ctl[fs.EM], ctl[fs.DN], ctl[K_POS]) == (1, 1, 0)
