"""String and string-conversion instructions (CONCAT MID FIND DELETE INSERT UPPER LOWER
DTOS STOD RTOS STOR).

String operands arrive as their structure list [LEN, DATA]; positions are 1-based.
Faults follow the Studio 5000 v37/v38 instruction help and 1756-RM003 (minor, type 4):
- 51: a source LEN is negative or larger than its DATA size -> nothing is written.
  CONCAT also reports a result longer than the destination as 51 (the help says so).
- 52: the result is longer than the destination's DATA: the destination receives the
  result cut to its size (field reports show CONCAT truncating rather than refusing).
- 53: STOD/STOR number beyond the destination type: the destination is left cleared.
- 56: Start/Qty invalid -> nothing is written. MID/DELETE: 1 <= Start <= DATA size of the
  source, Qty >= 0 and Start + Qty <= LEN + 1. INSERT: 1 <= Start <= LEN(SourceA) + 1 (a
  later Start would leave a gap). FIND: 1 <= Start <= DATA size of the source.
STOD/STOR (RM003): Dest is cleared, leading characters that cannot start a number are
skipped (a minus sign directly before a digit belongs to the number), conversion stops at
the first character that cannot continue it; STOD reads only the whole part. RTOS: see
`real_text`.
"""

from __future__ import annotations

import math
import re

from ..vm.context import ExecContext
from ..vm.refs import Ref
from ..vm.values import set_string
from .registry import implements

_INT_RE = re.compile(rb"-?[0-9]+")
_REAL_RE = re.compile(rb"-?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?")
_F32_MAX = 3.4028234663852886e38


def _text(ctx: ExecContext, s: list) -> bytes | None:
    """Characters of a source string, or None after fault 4/51 when LEN is invalid."""
    n = int(s[0])
    if n < 0 or n > len(s[1]):
        ctx.minor(4, 51, "string LEN is larger than its DATA size")
        return None
    return bytes(b & 0xFF for b in s[1][:n])


def _store(ctx: ExecContext, dest: list, data: bytes, code: int = 52) -> None:
    if len(data) > len(dest[1]):
        ctx.minor(4, code, "result string is longer than the destination")
    set_string(dest, data)


def _bad_range(ctx: ExecContext) -> None:
    ctx.minor(4, 56, "Start or Quantity value is invalid")


def _value(x: object) -> object:
    return x.get() if isinstance(x, Ref) else x


def _span(ctx: ExecContext, src: list, qty: int, start: int) -> tuple[bytes, int, int] | None:
    """Source text and a valid (Qty, Start) for MID/DELETE; None (after the fault) otherwise."""
    text = _text(ctx, src)
    if text is None:
        return None
    qty, start = int(qty), int(start)
    if not (qty >= 0 and 1 <= start <= len(src[1]) and start + qty <= len(text) + 1):
        _bad_range(ctx)
        return None
    return text, qty, start


# ------------------------------------------------------------------ ASCII string
@implements("CONCAT")
def concat(ctx: ExecContext, rung: bool, a: list, b: list, dest: list) -> None:
    ta, tb = _text(ctx, a), _text(ctx, b)
    if ta is None or tb is None:
        return
    _store(ctx, dest, ta + tb, code=51)


@implements("MID")
def mid(ctx: ExecContext, rung: bool, src: list, qty: int, start: int, dest: list) -> None:
    span = _span(ctx, src, qty, start)
    if span is not None:
        text, qty, start = span
        _store(ctx, dest, text[start - 1 : start - 1 + qty])


@implements("DELETE")
def delete(ctx: ExecContext, rung: bool, src: list, qty: int, start: int, dest: list) -> None:
    span = _span(ctx, src, qty, start)
    if span is not None:
        text, qty, start = span
        _store(ctx, dest, text[: start - 1] + text[start - 1 + qty :])


@implements("INSERT")
def insert(ctx: ExecContext, rung: bool, a: list, b: list, start: int, dest: list) -> None:
    ta, tb = _text(ctx, a), _text(ctx, b)
    if ta is None or tb is None:
        return
    start = int(start)
    if not 1 <= start <= len(ta) + 1:
        _bad_range(ctx)
        return
    _store(ctx, dest, ta[: start - 1] + tb + ta[start - 1 :])


@implements("FIND")
def find(ctx: ExecContext, rung: bool, src: list, search: list, start: int, result: Ref) -> None:
    text, pattern = _text(ctx, src), _text(ctx, search)
    if text is None or pattern is None:
        return
    start = int(start)
    if not 1 <= start <= len(src[1]):
        _bad_range(ctx)
        return
    # An empty search string is never "found" (0), rather than matching at Start.
    pos = text.find(pattern, start - 1) if pattern else -1
    result.set(pos + 1)


@implements("UPPER")
def upper(ctx: ExecContext, rung: bool, src: list, dest: list) -> None:
    text = _text(ctx, src)
    if text is not None:
        _store(ctx, dest, text.upper())  # bytes.upper changes ASCII a-z only


@implements("LOWER")
def lower(ctx: ExecContext, rung: bool, src: list, dest: list) -> None:
    text = _text(ctx, src)
    if text is not None:
        _store(ctx, dest, text.lower())


# ------------------------------------------------------------------ ASCII conversion
@implements("DTOS")
def dtos(ctx: ExecContext, rung: bool, source: object, dest: list) -> None:
    _store(ctx, dest, str(int(_value(source))).encode("ascii"))  # type: ignore[call-overload]


def _in_range(value: int, dest: Ref) -> bool:
    t = dest.type
    if not t.is_integer:
        return True
    lo, hi = (-(1 << (t.bits - 1)), (1 << (t.bits - 1)) - 1) if t.signed else (0, (1 << t.bits) - 1)
    return lo <= value <= hi


@implements("STOD")
def stod(ctx: ExecContext, rung: bool, src: list, dest: Ref) -> None:
    text = _text(ctx, src)
    if text is None:
        return
    dest.set(0)  # RM003 execution: "Destination is cleared"
    m = _INT_RE.search(text)
    if m is None:
        return
    value = int(m.group())
    if not _in_range(value, dest):
        ctx.minor(4, 53, "STOD: number beyond the limits of the destination type")
        return
    dest.set(value)


@implements("STOR")
def stor(ctx: ExecContext, rung: bool, src: list, dest: Ref) -> None:
    text = _text(ctx, src)
    if text is None:
        return
    dest.set(0.0)
    m = _REAL_RE.search(text)
    if m is None:
        return
    value = float(m.group())
    limit = _F32_MAX if dest.type.bits == 32 else math.inf
    if math.isinf(value) or abs(value) > limit:
        ctx.minor(4, 53, "STOR: number beyond the limits of the destination type")
        return
    dest.set(value)


def real_text(x: float) -> str:
    """Text of a REAL as RTOS writes it (our documented choice, RM003 gives no format).

    Seven significant digits (a REAL's precision), trailing zeros dropped but at least one
    decimal ("2.0", "1.5", "0.1"); below 1e-4 or from 1e7 on, exponent form with a
    three-digit exponent as Logix software displays it ("1.234568e+007"). Infinities and
    NaN as the Windows runtime prints them: "1.#INF", "-1.#INF", "1.#QNAN".
    """
    if math.isnan(x):
        return "1.#QNAN"
    if math.isinf(x):
        return "1.#INF" if x > 0 else "-1.#INF"
    s = f"{x:.7g}"
    mantissa, _, exponent = s.partition("e")
    if "." not in mantissa:
        mantissa += ".0"
    if not exponent:
        return mantissa
    e = int(exponent)
    return f"{mantissa}e{'-' if e < 0 else '+'}{abs(e):03d}"


@implements("RTOS")
def rtos(ctx: ExecContext, rung: bool, source: object, dest: list) -> None:
    _store(ctx, dest, real_text(float(_value(source))).encode("ascii"))  # type: ignore[arg-type]
