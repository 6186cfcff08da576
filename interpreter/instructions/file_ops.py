"""Array/file instructions COP, CPS, FLL, SIZE and the byte swap SWPB.

Operand shapes expected from the VM (calling convention in registry.py):
- COP/CPS Source and Dest, FLL Dest: an ArrayRef from the element named (whole array ->
  element 0), or a Ref for a single elementary location. An ArrayRef with `dims == ()`
  stands for one non-array value (`elements[start]`), so it is never walked past.
  Untyped operands (a bare number or structure list) cannot be laid out as bytes and are
  rejected with TypeError: the VM must pass a typed reference for these operands.
- SIZE Source: ArrayRef. SWPB Source: a number, or a Ref when the VM can give its type.

Decisions (1756-RM003 "File/Misc" chapter and Studio 5000 help):
- COP/CPS copy Length * (Dest element size) bytes; the copy stops at the end of the
  destination array and at the end of the source array (bytes beyond the source keep
  their destination value). The source is read completely before the destination is
  written (memmove), so overlapping copies within one array are well defined.
- Length <= 0 copies / fills nothing.
- CPS is COP: this interpreter has no task that could interrupt a copy.
- FLL converts Source to the Dest element type (REAL -> integer rounds half to even). Into
  structure elements (a UDT, TIMER, STRING...) the Source is written unconverted, its bytes
  repeated over Length * (element size) bytes (1756-RM003). The VM hands Source over as a
  value, not a typed location, so an integer is laid out as a DINT (LINT beyond the DINT
  range) and a REAL as a REAL: exact for the usual `FLL(0, udt, n)` clear, and for DINT or
  REAL sources; a non-zero SINT or INT source is widened to 4 bytes first.
- SIZE with a dimension the array does not have: major fault 4/20 (subscript range).
- SWPB on an INT source swaps its two bytes whatever the mode; an INT result stored in a
  DINT is sign-extended (catalog doc).
"""

from __future__ import annotations

from math import ceil

from ..semantics.types import DINT, INT, LINT, REAL, DataType, Elementary
from ..vm.context import ExecContext
from ..vm.refs import ArrayRef, Ref
from ..vm.values import byte_size, convert, from_bytes, to_bytes, wrap
from .registry import implements


def _block(op: object, what: str) -> tuple[list, int, DataType, int]:
    """(flat elements, first index, element type, elements available from there)."""
    if isinstance(op, ArrayRef):
        available = len(op) if op.dims else 1
        return op.elements, op.start, op.type, max(0, available)
    if isinstance(op, Ref):
        return op.container, op.key, op.type, 1
    raise TypeError(f"{what}: expected an ArrayRef or Ref operand, got {type(op).__name__}")


def _assign(elements: list, i: int, value: object) -> None:
    """Store a decoded element; structures are updated in place to keep their identity."""
    old = elements[i]
    if isinstance(old, list) and isinstance(value, list):
        for k, member in enumerate(value):
            _assign(old, k, member)
    else:
        elements[i] = value


def _copy_bytes(source: object, dest: object, length: int) -> None:
    if length <= 0:
        return
    d_el, d_start, d_type, d_avail = _block(dest, "Dest")
    s_el, s_start, s_type, s_avail = _block(source, "Source")
    count = min(length, d_avail)
    size = byte_size(d_type)
    s_size = byte_size(s_type)
    wanted = count * size
    s_count = min(s_avail, ceil(wanted / s_size)) if s_size else 0
    data = b"".join(to_bytes(s_el[s_start + i], s_type) for i in range(s_count))[:wanted]
    old = b"".join(to_bytes(d_el[d_start + i], d_type) for i in range(count))
    merged = data + old[len(data) :]
    for i in range(count):
        _assign(d_el, d_start + i, from_bytes(merged[i * size : (i + 1) * size], d_type))


@implements("COP")
def cop(ctx: ExecContext, rung: bool, source: object, dest: object, length: int) -> None:
    _copy_bytes(source, dest, int(length))


@implements("CPS")
def cps(ctx: ExecContext, rung: bool, source: object, dest: object, length: int) -> None:
    _copy_bytes(source, dest, int(length))


@implements("FLL")
def fll(ctx: ExecContext, rung: bool, source: object, dest: object, length: int) -> None:
    if int(length) <= 0:
        return
    elements, start, etype, available = _block(dest, "Dest")
    value = source.get() if isinstance(source, Ref) else source
    count = min(int(length), available)
    if not isinstance(etype, Elementary):
        _fill_structures(elements, start, etype, count, value)
        return
    converted = convert(value, etype)
    for i in range(count):
        elements[start + i] = converted


def _fill_structures(
    elements: list, start: int, etype: DataType, count: int, value: object
) -> None:
    """Structure elements get the source's bytes unconverted, repeated over every byte."""
    if isinstance(value, float):
        pattern = to_bytes(value, REAL)
    else:
        v = int(value)  # type: ignore[call-overload]
        pattern = to_bytes(v, DINT if -(1 << 31) <= v < (1 << 31) else LINT)
    size = byte_size(etype)
    data = pattern * (count * size // len(pattern) + 1)
    for i in range(count):
        _assign(elements, start + i, from_bytes(data[i * size : (i + 1) * size], etype))


@implements("SIZE")
def size(ctx: ExecContext, rung: bool, source: ArrayRef, dim: int, dest: Ref) -> None:
    dims = source.dims
    if not 0 <= int(dim) < len(dims):
        raise ctx.major(4, 20, f"SIZE: the array has no dimension {dim}")
    dest.set(dims[int(dim)])


# ------------------------------------------------------------------ SWPB
SWPB_REVERSE, SWPB_WORD, SWPB_HIGHLOW = 0, 1, 2


def _swap_dint(u: int, mode: int) -> int | None:
    """Rearrange the bytes ABCD (A most significant) of an unsigned 32-bit value."""
    if mode == SWPB_REVERSE:  # ABCD -> DCBA
        return int.from_bytes(u.to_bytes(4, "big"), "little")
    if mode == SWPB_WORD:  # ABCD -> CDAB
        return ((u & 0xFFFF) << 16) | (u >> 16)
    if mode == SWPB_HIGHLOW:  # ABCD -> BADC
        return ((u & 0x00FF00FF) << 8) | ((u >> 8) & 0x00FF00FF)
    return None


def _source_type(source: object, dest: Ref) -> Elementary:
    if isinstance(source, Ref):
        return source.type
    # A bare value carries no type: an INT destination means a 16-bit swap, else DINT.
    return INT if dest.type is INT else DINT


@implements("SWPB")
def swpb(ctx: ExecContext, rung: bool, source: object, mode: int, dest: Ref) -> None:
    stype = _source_type(source, dest)
    raw = source.get() if isinstance(source, Ref) else source
    value = int(raw) if isinstance(raw, int | float) else 0
    if stype.bits == 16:
        u = value & 0xFFFF
        dest.set(wrap(((u & 0xFF) << 8) | (u >> 8), 16, True))  # DINT dest: sign-extended
        return
    swapped = _swap_dint(value & 0xFFFFFFFF, int(mode))
    if swapped is not None:  # an unknown mode is rejected by Verify; nothing is written
        dest.set(wrap(swapped, 32, True))
