"""Ladder file and shift instructions driven by a CONTROL: AVE STD SRT, BSL BSR, FFL FFU LFL LFU.

Operands: arrays as ArrayRef (from the element named), the CONTROL as its live member
list, Length/Position as pseudo-operands written into LEN/POS by the prescan action (they
are download values in Logix, decision 0030). At run time LEN and POS come from the CONTROL.

Edge detection uses the CONTROL's EN bit (EU for FFU/LFU), as on the controller: the work is
done when the rung is true and EN was clear; a false rung clears EN.
- AVE / STD / SRT: the elements are taken along DimToVary starting at the given element
  (stride = product of the later dimensions). All LEN elements are processed in one scan;
  then POS = LEN and DN is set, and nothing is recomputed until a false rung clears EN, DN,
  ER and POS. LEN or POS negative: major fault 4/21; DimToVary the array does not have or
  an element outside the array: major fault 4/20. AVE divides the exact sum by LEN; STD
  divides by LEN - 1 (sample deviation; 0 for a single element). AVE and STD set the math
  flags from the stored result, SRT does not. In Structured Text SRT sorts every time it
  is reached (it has no rung): guard it with an edge.
- BSL / BSR shift whole DINT words: the ceil(LEN / 32) words holding LEN bits move one bit as
  one number, so bits above LEN - 1 in the last word shift too (Logix does the same and
  calls them invalid). BSL: UL = old bit LEN - 1, the source bit enters bit 0. BSR: UL = old
  bit 0, the source bit enters bit LEN - 1. DN is set after the shift. LEN < 0 sets ER.
  Prescan clears EN and UL; a false rung clears EN, DN, ER and POS.
- FFL / LFL store Source at element POS and increment POS unless the queue is full
  (POS >= LEN). FFU returns element 0 and moves the others down one place; LFU returns
  element POS - 1. Unloading an empty queue returns 0. Both then decrement POS. EM = (POS =
  0) and DN = (POS >= LEN) are evaluated at every execution; LEN <= 0 or POS < 0 sets both.
  Prescan sets EN (FFL/LFL) or EU (FFU/LFU) so a rung already true does not load or unload
  on the first scan. Elements past POS are left as they are.
"""

from __future__ import annotations

import math
from math import prod

from ..semantics.types import Elementary
from ..vm.context import ExecContext
from ..vm.refs import ArrayRef, Ref
from ..vm.values import copy_value
from .file_ops import _assign
from .ladder_status import Dest, store
from .ladder_timers_counters import _K, K_LEN, K_POS, apply_pseudo
from .registry import implements, prescan

EN, EU, DN, EM, ER, UL = (_K[b] for b in ("EN", "EU", "DN", "EM", "ER", "UL"))
WORD = 0xFFFFFFFF


def _pseudo(ctl: list, length: object, position: object = None) -> None:
    apply_pseudo(ctl, ((K_LEN, length), (K_POS, position)))


def _walk(ctx: ExecContext, arr: ArrayRef, dim: int, count: int) -> list[int]:
    """Flat indices of `count` elements along dimension `dim` from the ArrayRef's start."""
    dims = arr.dims or (len(arr.elements),)
    if not 0 <= dim < len(dims):
        raise ctx.major(4, 20, f"the array has no dimension {dim} to vary")
    stride = prod(dims[dim + 1 :])
    idx = [arr.start + k * stride for k in range(count)]
    if idx and idx[-1] >= len(arr.elements):
        raise ctx.major(4, 20, "the instruction would reach past the end of the array")
    return idx


def _file_start(ctx: ExecContext, rung: bool, ctl: list) -> int | None:
    """Common rung/EN/DN handling of AVE, STD and SRT; the element count to process or None."""
    if not rung:
        ctl[EN] = ctl[DN] = ctl[ER] = 0
        ctl[K_POS] = 0
        return None
    if ctl[EN] or ctl[DN]:
        return None  # already done for this true period
    ctl[EN] = 1
    if ctl[K_LEN] < 0 or ctl[K_POS] < 0:
        ctl[ER] = 1
        raise ctx.major(4, 21, "CONTROL .LEN or .POS is negative")
    return int(ctl[K_LEN])


def _file_values(ctx: ExecContext, rung: bool, arr: ArrayRef, dim: int, ctl: list) -> list | None:
    """AVE/STD: the LEN elements to reduce, or None when there is nothing to do this scan.

    No elements (LEN 0) sets ER: a mean or deviation of nothing is undefined.
    """
    n = _file_start(ctx, rung, ctl)
    if n is None:
        return None
    if n == 0:
        ctl[ER] = 1
        return None
    return [arr.elements[i] for i in _walk(ctx, arr, int(dim), n)]


def _finish(ctl: list, n: int) -> None:
    ctl[K_POS] = n
    ctl[DN] = 1


# ------------------------------------------------------------------ AVE / STD / SRT
@implements("AVE")
def ave(
    ctx: ExecContext,
    rung: bool,
    arr: ArrayRef,
    dim: int,
    dest: Dest,
    ctl: list,
    length: object = None,
    position: object = None,
) -> None:
    values = _file_values(ctx, rung, arr, dim, ctl)
    if values is None:
        return
    n = len(values)
    # an integer sum is exact and int / int is correctly rounded; REAL data sums in double
    total = sum(values) if all(isinstance(v, int) for v in values) else math.fsum(values)
    store(ctx, dest, total / n)
    _finish(ctl, n)


@implements("STD")
def std(
    ctx: ExecContext,
    rung: bool,
    arr: ArrayRef,
    dim: int,
    dest: Dest,
    ctl: list,
    length: object = None,
    position: object = None,
) -> None:
    found = _file_values(ctx, rung, arr, dim, ctl)
    if found is None:
        return
    values = [float(v) for v in found]
    n = len(values)
    mean = math.fsum(values) / n
    spread = math.fsum((v - mean) ** 2 for v in values)
    store(ctx, dest, math.sqrt(spread / (n - 1)) if n > 1 else 0.0)
    _finish(ctl, n)


def _sort(ctx: ExecContext, arr: ArrayRef, dim: int, n: int) -> None:
    idx = _walk(ctx, arr, dim, n)
    for i, v in zip(idx, sorted(arr.elements[i] for i in idx), strict=True):
        arr.elements[i] = v


@implements("SRT@rll")
def srt(
    ctx: ExecContext,
    rung: bool,
    arr: ArrayRef,
    dim: int,
    ctl: list,
    length: object = None,
    position: object = None,
) -> None:
    n = _file_start(ctx, rung, ctl)
    if n is None:
        return
    _sort(ctx, arr, int(dim), n)
    _finish(ctl, n)


@implements("SRT@st")
def srt_st(ctx: ExecContext, rung: bool, arr: ArrayRef, dim: int, ctl: list) -> None:
    ctl[EN] = ctl[DN] = ctl[ER] = 0  # no rung in ST: every call is a new execution
    ctl[K_POS] = 0
    srt(ctx, True, arr, dim, ctl)


@prescan("AVE", "STD")
def statistics_prescan(
    ctx: ExecContext,
    rung: bool,
    arr: ArrayRef,
    dim: int,
    dest: Dest,
    ctl: list,
    length: object = None,
    position: object = None,
) -> None:
    _pseudo(ctl, length, position)


@prescan("SRT@rll")
def srt_prescan(
    ctx: ExecContext,
    rung: bool,
    arr: ArrayRef,
    dim: int,
    ctl: list,
    length: object = None,
    position: object = None,
) -> None:
    _pseudo(ctl, length, position)


# ------------------------------------------------------------------ BSL / BSR
def _shift(
    ctx: ExecContext, rung: bool, arr: ArrayRef, ctl: list, source: object, left: bool
) -> None:
    if not rung:
        ctl[EN] = ctl[DN] = ctl[ER] = 0
        ctl[K_POS] = 0
        return
    if ctl[EN]:
        return
    ctl[EN] = 1
    n = int(ctl[K_LEN])
    if n < 0:
        ctl[ER] = 1
        return
    if n == 0:
        ctl[DN] = 1
        return
    words = (n + 31) // 32
    if words > len(arr):
        raise ctx.major(4, 20, f"{n} bits do not fit the array")
    value = 0
    for i in range(words):
        value |= (int(arr.elements[arr.start + i]) & WORD) << (32 * i)
    bit_in = 1 if source else 0
    if left:
        ctl[UL] = (value >> (n - 1)) & 1
        value = (value << 1) | bit_in
    else:
        ctl[UL] = value & 1
        value >>= 1
        value = value | (1 << (n - 1)) if bit_in else value & ~(1 << (n - 1))
    for i in range(words):
        arr.set(i, (value >> (32 * i)) & WORD)  # ArrayRef.set wraps into DINT
    ctl[DN] = 1


@implements("BSL")
def bsl(
    ctx: ExecContext, rung: bool, arr: ArrayRef, ctl: list, source: object, length: object = None
) -> None:
    _shift(ctx, rung, arr, ctl, source, left=True)


@implements("BSR")
def bsr(
    ctx: ExecContext, rung: bool, arr: ArrayRef, ctl: list, source: object, length: object = None
) -> None:
    _shift(ctx, rung, arr, ctl, source, left=False)


@prescan("BSL", "BSR")
def shift_prescan(
    ctx: ExecContext, rung: bool, arr: ArrayRef, ctl: list, source: object, length: object = None
) -> None:
    _pseudo(ctl, length)
    ctl[EN] = ctl[UL] = 0


# ------------------------------------------------------------------ FIFO / LIFO
def _queue_status(ctl: list) -> bool:
    """Update EM and DN from LEN/POS; False when LEN/POS are unusable."""
    n, pos = ctl[K_LEN], ctl[K_POS]
    if n <= 0 or pos < 0:
        ctl[EM] = ctl[DN] = 1
        return False
    ctl[EM] = int(pos == 0)
    ctl[DN] = int(pos >= n)
    return True


def _put(arr: ArrayRef, i: int, value: object) -> None:
    if isinstance(arr.type, Elementary):
        arr.set(i, value.get() if isinstance(value, Ref) else value)
    else:
        _assign(arr.elements, arr.start + i, copy_value(value))


def _check_room(ctx: ExecContext, arr: ArrayRef, i: int) -> None:
    if i >= len(arr):
        raise ctx.major(4, 20, "POS points past the end of the FIFO/LIFO array")


def _load(ctx: ExecContext, rung: bool, source: object, arr: ArrayRef, ctl: list) -> None:
    if not rung:
        ctl[EN] = 0
        _queue_status(ctl)
        return
    if not ctl[EN]:
        ctl[EN] = 1
        if _queue_status(ctl) and not ctl[DN]:
            pos = int(ctl[K_POS])
            _check_room(ctx, arr, pos)
            _put(arr, pos, source)
            ctl[K_POS] = pos + 1
    _queue_status(ctl)


def _give(dest: object, value: object) -> None:
    if isinstance(dest, list):
        if value is not None:
            _assign([dest], 0, copy_value(value))
    elif value is None:
        dest.set(0)  # type: ignore[attr-defined]
    else:
        dest.set(value)  # type: ignore[attr-defined]


def _unload(
    ctx: ExecContext, rung: bool, arr: ArrayRef, dest: object, ctl: list, fifo: bool
) -> None:
    if not rung:
        ctl[EU] = 0
        _queue_status(ctl)
        return
    if not ctl[EU]:
        ctl[EU] = 1
        if _queue_status(ctl):
            pos = int(ctl[K_POS])
            if pos == 0:
                _give(dest, None)  # empty: the destination receives 0
            elif fifo:
                _give(dest, arr.get(0))
                for i in range(min(int(ctl[K_LEN]), len(arr)) - 1):
                    _put(arr, i, arr.get(i + 1))
                ctl[K_POS] = pos - 1
            else:
                _check_room(ctx, arr, pos - 1)
                _give(dest, arr.get(pos - 1))
                ctl[K_POS] = pos - 1
    _queue_status(ctl)


@implements("FFL")
def ffl(
    ctx: ExecContext,
    rung: bool,
    source: object,
    arr: ArrayRef,
    ctl: list,
    length: object = None,
    position: object = None,
) -> None:
    _load(ctx, rung, source, arr, ctl)


@implements("LFL")
def lfl(
    ctx: ExecContext,
    rung: bool,
    source: object,
    arr: ArrayRef,
    ctl: list,
    length: object = None,
    position: object = None,
) -> None:
    _load(ctx, rung, source, arr, ctl)


@implements("FFU")
def ffu(
    ctx: ExecContext,
    rung: bool,
    arr: ArrayRef,
    dest: object,
    ctl: list,
    length: object = None,
    position: object = None,
) -> None:
    _unload(ctx, rung, arr, dest, ctl, fifo=True)


@implements("LFU")
def lfu(
    ctx: ExecContext,
    rung: bool,
    arr: ArrayRef,
    dest: object,
    ctl: list,
    length: object = None,
    position: object = None,
) -> None:
    _unload(ctx, rung, arr, dest, ctl, fifo=False)


@prescan("FFL", "LFL")
def load_prescan(
    ctx: ExecContext,
    rung: bool,
    source: object,
    arr: ArrayRef,
    ctl: list,
    length: object = None,
    position: object = None,
) -> None:
    _pseudo(ctl, length, position)
    ctl[EN] = 1


@prescan("FFU", "LFU")
def unload_prescan(
    ctx: ExecContext,
    rung: bool,
    arr: ArrayRef,
    dest: object,
    ctl: list,
    length: object = None,
    position: object = None,
) -> None:
    _pseudo(ctl, length, position)
    ctl[EU] = 1
