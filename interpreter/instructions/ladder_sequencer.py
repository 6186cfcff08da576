"""Ladder sequencers SQI, SQO, SQL (1756-RM003 sequencer chapter, Studio 5000 v37 help).

The sequencer array holds LEN + 1 steps: element 0 is the start-up position, steps run
1..LEN. The CONTROL's POS is the current step; Length/Position are pseudo-operands written
into LEN/POS by the prescan action (decision 0030).
- SQI (input instruction): with LEN <= 0, POS < 0 or POS > LEN it sets ER and the rung goes
  false; otherwise it clears ER and the rung stays true only when Source and Array[POS]
  agree in every bit the mask selects. Operands are compared as 32-bit patterns.
- SQO / SQL: when the rung goes true (EN was clear) POS advances by one, wrapping from LEN
  (or beyond) back to 1, and DN = (POS = LEN). While the rung stays true the step's work is
  repeated every scan: SQO writes (Dest AND NOT Mask) OR (Array[POS] AND Mask), SQL stores
  Source into Array[POS]. LEN <= 0 or POS < 0 sets ER and does nothing. A step outside the
  array: major fault 4/20. A false rung clears EN; prescan sets EN so a rung already true
  at start-up does not step.
None of them affects the math flags.
"""

from __future__ import annotations

from ..vm.context import ExecContext
from ..vm.refs import ArrayRef, BitRef, Ref
from .fbd_timers import DINT_MAX
from .ladder_timers_counters import _K, K_LEN, K_POS, apply_pseudo
from .registry import implements, prescan

EN, DN, ER = _K["EN"], _K["DN"], _K["ER"]
WORD = 0xFFFFFFFF


def _pseudo(ctl: list, length: object, position: object) -> None:
    apply_pseudo(ctl, ((K_LEN, length), (K_POS, position)))


def _step(ctx: ExecContext, arr: ArrayRef, pos: int) -> int:
    if pos >= len(arr):
        raise ctx.major(4, 20, f"sequencer step {pos} is past the end of the array")
    return int(arr.get(pos))  # type: ignore[call-overload]


@implements("SQI")
def sqi(
    ctx: ExecContext,
    rung: bool,
    arr: ArrayRef,
    mask: int,
    source: int,
    ctl: list,
    length: object = None,
    position: object = None,
) -> bool:
    if not rung:
        return False
    n, pos = ctl[K_LEN], ctl[K_POS]
    if n <= 0 or pos < 0 or pos > n:
        ctl[ER] = 1
        return False
    ctl[ER] = 0
    m = int(mask) & WORD
    return (int(source) & m) == (_step(ctx, arr, pos) & m)


def _advance(ctl: list, rung: bool) -> bool:
    """SQO/SQL rung handling: True when the step's work is to be done (at POS).

    A false rung clears EN; a true rung steps on a new true period. False when the rung is
    false or LEN/POS are invalid (ER).
    """
    if not rung:
        ctl[EN] = 0
        return False
    n, pos = ctl[K_LEN], ctl[K_POS]
    if n <= 0 or pos < 0:
        ctl[ER] = 1
        return False
    if not ctl[EN]:
        ctl[EN] = 1
        ctl[ER] = 0
        if pos >= n:
            pos = 1
        elif pos == DINT_MAX:
            ctl[ER] = 1  # the position would roll over
            return False
        else:
            pos += 1
        ctl[K_POS] = pos
    ctl[DN] = int(ctl[K_POS] == n)
    return True


@implements("SQO")
def sqo(
    ctx: ExecContext,
    rung: bool,
    arr: ArrayRef,
    mask: int,
    dest: Ref | BitRef,
    ctl: list,
    length: object = None,
    position: object = None,
) -> None:
    if _advance(ctl, rung):
        m = int(mask) & WORD
        step = _step(ctx, arr, ctl[K_POS])
        dest.set(((int(dest.get()) & ~m) | (step & m)) & WORD)


@implements("SQL")
def sql(
    ctx: ExecContext,
    rung: bool,
    arr: ArrayRef,
    source: int,
    ctl: list,
    length: object = None,
    position: object = None,
) -> None:
    if _advance(ctl, rung):
        _step(ctx, arr, ctl[K_POS])  # bounds check
        arr.set(ctl[K_POS], source)


@prescan("SQI")
def sqi_prescan(
    ctx: ExecContext,
    rung: bool,
    arr: ArrayRef,
    mask: int,
    source: int,
    ctl: list,
    length: object = None,
    position: object = None,
) -> bool:
    _pseudo(ctl, length, position)
    return False


@prescan("SQO")
def sqo_prescan(
    ctx: ExecContext,
    rung: bool,
    arr: ArrayRef,
    mask: int,
    dest: object,
    ctl: list,
    length: object = None,
    position: object = None,
) -> None:
    _pseudo(ctl, length, position)
    ctl[EN] = 1


@prescan("SQL")
def sql_prescan(
    ctx: ExecContext,
    rung: bool,
    arr: ArrayRef,
    source: int,
    ctl: list,
    length: object = None,
    position: object = None,
) -> None:
    _pseudo(ctl, length, position)
    ctl[EN] = 1
