"""FBC (file bit comparison) and DDT (diagnostic detect), ladder, 1756-RM003; decision 0184.

Operands: Source, Reference and Result arrays (ArrayRef from the element named), the compare
CONTROL (LEN bits to compare, POS the next bit) and the result CONTROL (LEN places in
Result, POS the next free place). Length/Position are pseudo-operands written into LEN/POS
by the prescan action, as for BSL and the FIFOs (decision 0030).

- Bits are numbered from the named element: bit n of a DINT array is bit n mod 32 of element
  n div 32; a BOOL array has one bit per element. Result receives these numbers.
- The search runs on a false-to-true rung transition (EN was clear). Before it: a compare
  that had reached its end (POS = LEN) starts again from bit 0 with an empty Result (both
  POS cleared); a full Result (its POS = LEN) is emptied (its POS cleared). The result
  DN bit is cleared.
- Compare .LEN or .POS, result .LEN or .POS negative: the compare ER bit is set and the
  instruction does nothing until the program clears ER. Bits past the end of Source or
  Reference, or a Result place past the end of Result: major fault 4/20.
- All mode (compare IN clear): every mismatch from POS to LEN is recorded in one execution;
  FD is set after recording if any was found. One-at-a-time mode (IN set): the search stops
  after recording a mismatch (FD set, POS past that bit); the next false-to-true transition
  goes on from there.
- Recording a mismatch: Result[result POS] = the bit number, result POS + 1; DDT also copies
  the Source bit into Reference (so it reports each change once). When Result fills (its
  POS = LEN) its DN bit is set and the search stops until the next transition.
- Compare DN is set when POS reaches LEN.
- A false rung (and prescan) clears EN, FD and DN of both CONTROLs; ER stays until the program
  clears it. Rung-condition-out follows rung-condition-in.
"""

from __future__ import annotations

from ..semantics.types import BOOL
from ..vm.context import ExecContext
from ..vm.refs import ArrayRef
from .ladder_timers_counters import _K, K_LEN, K_POS, apply_pseudo
from .registry import implements, prescan

EN, DN, ER, IN, FD = (_K[b] for b in ("EN", "DN", "ER", "IN", "FD"))


class _Bits:
    """Bit view of a DINT or BOOL array from the element an ArrayRef names."""

    def __init__(self, ctx: ExecContext, arr: ArrayRef, need: int) -> None:
        self.arr = arr
        self.bool = arr.type == BOOL
        per = 1 if self.bool else 32
        if -(-need // per) > len(arr):
            raise ctx.major(4, 20, "the compare would reach past the end of the array")

    def get(self, n: int) -> int:
        if self.bool:
            return 1 if self.arr.get(n) else 0
        return (int(self.arr.get(n // 32)) >> (n % 32)) & 1  # type: ignore[call-overload]

    def set(self, n: int, bit: int) -> None:
        if self.bool:
            self.arr.set(n, bit)
            return
        word = int(self.arr.get(n // 32)) & 0xFFFFFFFF  # type: ignore[call-overload]
        word = word | (1 << (n % 32)) if bit else word & ~(1 << (n % 32))
        self.arr.set(n // 32, word - (1 << 32) if word >= 1 << 31 else word)


def _clear(cmp: list, res: list) -> None:
    cmp[EN] = cmp[FD] = cmp[DN] = 0
    res[EN] = res[FD] = res[DN] = 0


def _compare(
    ctx: ExecContext,
    rung: bool,
    source: ArrayRef,
    reference: ArrayRef,
    result: ArrayRef,
    cmp: list,
    res: list,
    update_reference: bool,
) -> None:
    if not rung:
        _clear(cmp, res)
        return
    if cmp[EN]:
        return  # rung still true: the work was done at the transition
    cmp[EN] = res[EN] = 1
    if cmp[ER]:
        return  # stopped until the program clears ER
    if min(cmp[K_LEN], cmp[K_POS], res[K_LEN], res[K_POS]) < 0:
        cmp[ER] = 1
        return
    if cmp[K_POS] >= cmp[K_LEN]:
        cmp[K_POS] = res[K_POS] = 0
    if res[K_POS] >= res[K_LEN]:
        res[K_POS] = 0
    cmp[DN] = cmp[FD] = res[DN] = 0
    length = int(cmp[K_LEN])
    src, ref = _Bits(ctx, source, length), _Bits(ctx, reference, length)
    found = False
    while cmp[K_POS] < length:
        n = int(cmp[K_POS])
        cmp[K_POS] = n + 1
        bit = src.get(n)
        if bit == ref.get(n):
            continue
        place = int(res[K_POS])
        if place >= len(result):
            raise ctx.major(4, 20, "the result position is past the end of the Result array")
        result.set(place, n)
        res[K_POS] = place + 1
        if update_reference:
            ref.set(n, bit)
        found = True
        if res[K_POS] >= res[K_LEN]:
            res[DN] = 1
            break
        if cmp[IN]:
            break
    cmp[FD] = int(found)
    cmp[DN] = int(cmp[K_POS] >= length)


@implements("FBC")
def fbc(
    ctx: ExecContext,
    rung: bool,
    source: ArrayRef,
    reference: ArrayRef,
    result: ArrayRef,
    cmp: list,
    length: object,
    position: object,
    res: list,
    result_length: object = None,
    result_position: object = None,
) -> None:
    _compare(ctx, rung, source, reference, result, cmp, res, update_reference=False)


@implements("DDT")
def ddt(
    ctx: ExecContext,
    rung: bool,
    source: ArrayRef,
    reference: ArrayRef,
    result: ArrayRef,
    cmp: list,
    length: object,
    position: object,
    res: list,
    result_length: object = None,
    result_position: object = None,
) -> None:
    _compare(ctx, rung, source, reference, result, cmp, res, update_reference=True)


@prescan("FBC", "DDT")
def compare_prescan(
    ctx: ExecContext,
    rung: bool,
    source: ArrayRef,
    reference: ArrayRef,
    result: ArrayRef,
    cmp: list,
    length: object,
    position: object,
    res: list,
    result_length: object = None,
    result_position: object = None,
) -> None:
    apply_pseudo(cmp, ((K_LEN, length), (K_POS, position)))
    apply_pseudo(res, ((K_LEN, result_length), (K_POS, result_position)))
    _clear(cmp, res)
