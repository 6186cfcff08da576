"""BCD conversion: TOD (TO_BCD) and FRD (BCD_TO), ladder boxes and expression functions.

Rules (1756-RM003 math conversion chapter; Studio 5000 v37 help; decision 0063):
- TOD writes the decimal digits of Source as 4-bit nibbles (1234 -> 16#1234). A negative
  Source clears Dest and sets S:V (minor fault 4/4). A Source above 99,999,999 (the eight
  digits a 32-bit word holds; 9,999,999,999,999,999 into a 64-bit Dest) sets S:V and leaves
  Dest alone. The BCD pattern is stored as a bit pattern: 99,999,999 into a DINT is
  16#9999_9999, a negative DINT, without overflow; a pattern wider than Dest (12345 into an
  INT) is cut to Dest's width and sets S:V.
- FRD reads Source's bit pattern as BCD nibbles (16#1234 -> 1234). A nibble above 9 is no
  BCD digit: S:V is set and Dest left alone. A result that does not fit Dest wraps and sets
  S:V as any ladder math result does (ladder_status.store).
- Both update S:N and S:Z from the value in Dest.
"""

from __future__ import annotations

from ..vm.context import ExecContext
from ..vm.values import wrap
from .ladder_status import Dest, set_flags, store
from .registry import implements

_MAX_32 = 99_999_999
_MAX_64 = 9_999_999_999_999_999


def _bcd(x: int) -> int:
    """The BCD pattern of a non-negative integer: its decimal digits read as hexadecimal."""
    return int(str(x), 16)


def _from_bcd(x: int) -> int | None:
    """The integer a BCD bit pattern stands for; None when a nibble is above 9."""
    pattern = x & (0xFFFFFFFF if -(2**31) <= x else 0xFFFFFFFFFFFFFFFF)
    digits = f"{pattern:x}"
    if any(d in "abcdef" for d in digits):
        return None
    return int(digits)


@implements("TOD@rll")
def tod(ctx: ExecContext, rung: bool, source: int, dest: Dest) -> None:
    if not rung:
        return
    x = int(source)
    if x < 0:
        store(ctx, dest, 0, overflow=True)  # RM003: minor fault and Dest cleared
        return
    if x > (_MAX_64 if dest.type.bits == 64 else _MAX_32):
        set_flags(ctx, dest.get(), overflow=True)  # not converted: Dest keeps its value
        return
    pattern = _bcd(x)
    bits = dest.type.bits
    dest.set(wrap(pattern, bits, dest.type.signed))
    set_flags(ctx, dest.get(), overflow=pattern >> bits != 0)


@implements("FRD@rll")
def frd(ctx: ExecContext, rung: bool, source: int, dest: Dest) -> None:
    if not rung:
        return
    value = _from_bcd(int(source))
    if value is None:
        set_flags(ctx, dest.get(), overflow=True)
        return
    store(ctx, dest, value)


# Expression forms (CPT, CMP, FSC and array subscripts): the result keeps the argument's type.
@implements("TOD@st")
def tod_fn(ctx: ExecContext, rung: bool, source: int) -> int:
    x = int(source)
    if x < 0 or x > _MAX_64:
        ctx.minor(4, 4, "TOD: Source outside 0..99,999,999 (arithmetic overflow)")
        return 0
    return _bcd(x)


@implements("FRD@st")
def frd_fn(ctx: ExecContext, rung: bool, source: int) -> int:
    value = _from_bcd(int(source))
    if value is None:
        ctx.minor(4, 4, "FRD: Source is not a BCD value (arithmetic overflow)")
        return 0
    return value
