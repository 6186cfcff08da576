"""Move/logical function blocks: BAND BOR BXOR BNOT (function block diagram only, called on
their tag), MVMT, BTDT, DFF, JKFF, RESD, SETD (function block and Structured Text).

Sources: 1756-RM003 move/logical chapter and the Studio 5000 v37 instruction help.
In Structured Text the block always executes (EnableIn is not consulted, as for the timers)
and EnableOut is set. Flip-flops detect the Clock edge against the value Clock had at the
previous execution, kept in the hidden ClockPrev member.
"""

from __future__ import annotations

from ..vm.context import ExecContext
from ..vm.values import wrap
from .registry import implements
from .select_limit_blocks import layout

_AND = layout("FBD_BOOLEAN_AND")
_OR = layout("FBD_BOOLEAN_OR")
_XOR = layout("FBD_BOOLEAN_XOR")
_NOT = layout("FBD_BOOLEAN_NOT")
_AND_INS = [_AND[f"IN{i}"] for i in range(1, 9)]
_OR_INS = [_OR[f"IN{i}"] for i in range(1, 9)]


@implements("BAND")
def band(ctx: ExecContext, rung: bool, s: list) -> None:
    s[_AND["OUT"]] = int(all(s[i] for i in _AND_INS))
    s[_AND["ENABLEOUT"]] = 1


@implements("BOR")
def bor(ctx: ExecContext, rung: bool, s: list) -> None:
    s[_OR["OUT"]] = int(any(s[i] for i in _OR_INS))
    s[_OR["ENABLEOUT"]] = 1


@implements("BXOR")
def bxor(ctx: ExecContext, rung: bool, s: list) -> None:
    s[_XOR["OUT"]] = int(bool(s[_XOR["IN1"]]) != bool(s[_XOR["IN2"]]))
    s[_XOR["ENABLEOUT"]] = 1


@implements("BNOT")
def bnot(ctx: ExecContext, rung: bool, s: list) -> None:
    s[_NOT["OUT"]] = int(not s[_NOT["IN"]])
    s[_NOT["ENABLEOUT"]] = 1


# ------------------------------------------------------------------ MVMT / BTDT
_MV = layout("FBD_MASKED_MOVE")


@implements("MVMT")
def mvmt(ctx: ExecContext, rung: bool, s: list) -> None:
    """Dest = (Source AND Mask) OR (Target AND NOT Mask), as DINTs."""
    src, mask, target = s[_MV["SOURCE"]], s[_MV["MASK"]], s[_MV["TARGET"]]
    s[_MV["DEST"]] = wrap((src & mask) | (target & ~mask), 32, True)
    s[_MV["ENABLEOUT"]] = 1


_BT = layout("FBD_BIT_FIELD_DISTRIBUTE")


@implements("BTDT")
def btdt(ctx: ExecContext, rung: bool, s: list) -> None:
    """Dest = Target with Length bits from DestBit replaced by Source's bits from SourceBit.

    Bits that would fall beyond bit 31 of Dest are dropped (the field is cut at the word's
    end, as BTD does); a Length, SourceBit or DestBit outside 0..31 (1..32 for Length)
    leaves Dest = Target."""
    src, sb, length = s[_BT["SOURCE"]], s[_BT["SOURCEBIT"]], s[_BT["LENGTH"]]
    db, target = s[_BT["DESTBIT"]], s[_BT["TARGET"]]
    dest = target
    if 1 <= length <= 32 and 0 <= sb <= 31 and 0 <= db <= 31:
        field = ((src & 0xFFFFFFFF) >> sb) & ((1 << length) - 1)
        mask = (((1 << length) - 1) << db) & 0xFFFFFFFF
        dest = ((target & 0xFFFFFFFF) & ~mask) | ((field << db) & mask)
    s[_BT["DEST"]] = wrap(dest, 32, True)
    s[_BT["ENABLEOUT"]] = 1


# ------------------------------------------------------------------ DFF / JKFF
_DF = layout("FLIP_FLOP_D")
_JK = layout("FLIP_FLOP_JK")


def _clock_rose(s: list, ix: dict[str, int]) -> bool:
    clock = bool(s[ix["CLOCK"]])
    rose = clock and not s[ix["CLOCKPREV"]]
    s[ix["CLOCKPREV"]] = int(clock)
    return rose


def _q(s: list, ix: dict[str, int], q: bool) -> None:
    s[ix["Q"]] = int(q)
    s[ix["QNOT"]] = int(not q)
    s[ix["ENABLEOUT"]] = 1


@implements("DFF")
def dff(ctx: ExecContext, rung: bool, s: list) -> None:
    """Clear wins: Q false. Otherwise a rising Clock copies D into Q."""
    rose = _clock_rose(s, _DF)
    if s[_DF["CLEAR"]]:
        _q(s, _DF, False)
    else:
        _q(s, _DF, bool(s[_DF["D"]]) if rose else bool(s[_DF["Q"]]))


@implements("JKFF")
def jkff(ctx: ExecContext, rung: bool, s: list) -> None:
    """Clear wins: Q false. Otherwise a rising Clock toggles Q."""
    rose = _clock_rose(s, _JK)
    q = bool(s[_JK["Q"]])
    _q(s, _JK, False if s[_JK["CLEAR"]] else (not q if rose else q))


# ------------------------------------------------------------------ RESD / SETD
_RD = layout("DOMINANT_RESET")
_SD = layout("DOMINANT_SET")


def _latch(s: list, ix: dict[str, int], set_wins: bool) -> None:
    set_, reset, out = bool(s[ix["SET"]]), bool(s[ix["RESET"]]), bool(s[ix["OUT"]])
    if set_ and reset:
        out = set_wins
    elif set_:
        out = True
    elif reset:
        out = False
    s[ix["OUT"]] = int(out)
    s[ix["OUTNOT"]] = int(not out)
    s[ix["ENABLEOUT"]] = 1


@implements("RESD")
def resd(ctx: ExecContext, rung: bool, s: list) -> None:
    _latch(s, _RD, set_wins=False)


@implements("SETD")
def setd(ctx: ExecContext, rung: bool, s: list) -> None:
    _latch(s, _SD, set_wins=True)
