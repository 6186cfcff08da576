"""MVM / CLR / BTD / AND / OR / XOR / NOT called directly on Refs."""

from __future__ import annotations

from interpreter.instructions import ladder_move_logic as ml
from interpreter.semantics.types import DINT, INT, SINT
from interpreter.vm.context import ExecContext
from interpreter.vm.refs import Ref


def _flags(ctx: ExecContext) -> tuple[int, int, int, int]:
    s = ctx.status
    return (s["N"], s["Z"], s["V"], s["C"])


def test_mvm_copies_only_masked_bits() -> None:
    ctx, d = ExecContext(), Ref([0x0000FF00], 0, DINT)
    ml.mvm(ctx, True, 0x12345678, 0x0000FFFF, d)
    # (16#FF00 AND NOT 16#FFFF) OR (16#12345678 AND 16#FFFF) = 16#5678 = 22136
    assert d.get() == 0x5678
    assert _flags(ctx) == (0, 0, 0, 0)


def test_mvm_of_a_dint_into_an_int_overflows() -> None:
    ctx, d = ExecContext(), Ref([0], 0, INT)
    ml.mvm(ctx, True, -1, 0xFFFF, d)
    # 0 OR (-1 AND 16#FFFF) = 65535, which INT cannot hold: stored as -1, S:V and fault 4/4
    assert d.get() == -1
    assert ctx.status["V"] == 1
    assert sum(f.count for f in ctx.minor_faults.values()) == 1


def test_bitwise_and_or_xor_not() -> None:
    ctx, d = ExecContext(), Ref([0], 0, DINT)
    ml.and_(ctx, True, 12, 10, d)
    assert d.get() == 8  # 1100 AND 1010 = 1000
    ml.or_(ctx, True, 12, 10, d)
    assert d.get() == 14  # 1110
    ml.xor(ctx, True, 12, 12, d)
    assert d.get() == 0 and _flags(ctx) == (0, 1, 0, 0)
    ml.not_(ctx, True, 0, d)
    assert d.get() == -1 and _flags(ctx) == (1, 0, 0, 0)  # all 32 bits set


def test_clr_sets_zero_flag() -> None:
    ctx, d = ExecContext(), Ref([123], 0, DINT)
    ctx.status.update(N=1, V=1, C=1)
    ml.clr(ctx, True, d)
    assert d.get() == 0 and _flags(ctx) == (0, 1, 0, 0)
    d.set(5)
    ml.clr(ctx, False, d)
    assert d.get() == 5  # false rung: no action


def test_btd_moves_a_bit_field() -> None:
    ctx, d = ExecContext(), Ref([0x0F], 0, DINT)
    ml.btd(ctx, True, 0b1011_0000, 4, d, 8, 4)
    # field = bits 4..7 of 16#B0 = 2#1011; written at bits 8..11: 16#B00 OR the old 16#0F
    assert d.get() == 0xB0F
    assert ctx.status == {}  # BTD does not touch the math flags


def test_btd_drops_bits_beyond_the_destination() -> None:
    ctx, d = ExecContext(), Ref([0], 0, SINT)
    ml.btd(ctx, True, 0b1111, 0, d, 6, 4)
    # bits 6 and 7 land in the SINT, bits 8 and 9 fall off: 2#1100_0000 = -64 as SINT
    assert d.get() == -64
