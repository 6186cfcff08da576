"""Ladder move and bitwise-logic instructions: MVM CLR BTD AND OR XOR NOT.

(MOV is lowered by the compiler; SWPB and COP/CPS/FLL live in file_ops.py for both languages.)
- AND/OR/XOR/NOT and MVM compute on the operand values as two's-complement integers and
  store into Dest; a result that does not fit Dest sets S:V and records minor fault 4/4
  (for example MVM of a DINT with mask 16#FFFF into an INT whose value becomes 65535).
  Logix zero-fills SINT/INT operands of logical instructions; the operand types are not
  visible here, so a negative SINT/INT operand counts as its sign-extended value. Only the
  V flag can differ (the stored bits are the same).
- CLR stores 0: S:Z set, S:N S:V S:C cleared.
- BTD copies Length bits from Source (starting at SourceBit) into Dest (starting at
  DestBit); bits that would land beyond Dest's width are dropped, Source bits above bit 31
  read as 0. BTD does not affect the math flags.
A false rung does nothing.
"""

from __future__ import annotations

from ..vm.context import ExecContext
from ..vm.refs import Ref
from .ladder_status import Dest, store
from .registry import implements


@implements("MVM")
def mvm(ctx: ExecContext, rung: bool, source: int, mask: int, dest: Dest) -> None:
    if rung:
        store(ctx, dest, (int(dest.get()) & ~int(mask)) | (int(source) & int(mask)))


@implements("CLR")
def clr(ctx: ExecContext, rung: bool, dest: Dest) -> None:
    if rung:
        store(ctx, dest, 0)


@implements("AND@rll")
def and_(ctx: ExecContext, rung: bool, a: int, b: int, dest: Dest) -> None:
    if rung:
        store(ctx, dest, int(a) & int(b))


@implements("OR@rll")
def or_(ctx: ExecContext, rung: bool, a: int, b: int, dest: Dest) -> None:
    if rung:
        store(ctx, dest, int(a) | int(b))


@implements("XOR@rll")
def xor(ctx: ExecContext, rung: bool, a: int, b: int, dest: Dest) -> None:
    if rung:
        store(ctx, dest, int(a) ^ int(b))


@implements("NOT@rll")
def not_(ctx: ExecContext, rung: bool, a: int, dest: Dest) -> None:
    if rung:
        store(ctx, dest, ~int(a))


@implements("BTD")
def btd(
    ctx: ExecContext,
    rung: bool,
    source: int,
    source_bit: int,
    dest: Ref,
    dest_bit: int,
    length: int,
) -> None:
    if not rung:
        return
    width = dest.type.bits
    n, sb, db = int(length), int(source_bit), int(dest_bit)
    if n <= 0 or not 0 <= sb < 32 or not 0 <= db < width:
        return  # Verify rejects these immediates; nothing sensible to copy
    field = ((int(source) & 0xFFFFFFFF) >> sb) & ((1 << n) - 1)
    mask = ((1 << n) - 1) << db
    raw = int(dest.get()) & ((1 << width) - 1)
    raw = (raw & ~mask) | ((field << db) & mask)
    dest.set(raw & ((1 << width) - 1))  # Ref.set wraps the pattern into Dest's signed range
