"""Literal decoding shared by the ST and ladder front ends and `--set`."""

from __future__ import annotations

from ..limits import MAX_LITERAL_DIGITS

_SUFFIX_TYPES = {"": "DINT", "U": "UDINT", "L": "LINT", "UL": "ULINT"}
_ESCAPES = {"$": "$", "'": "'", '"': '"', "L": "\n", "N": "\n", "R": "\r", "T": "\t", "P": "\f"}


class LiteralError(ValueError):
    """A numeric literal no Logix type holds, or one too long to read (docs/limits.md)."""


def parse_number(text: str) -> tuple[int | float, str]:
    """Value and Logix type of an INT, radix or REAL literal (`16#FF_FF`, `5UL`, `1.5e3`).

    Raises LiteralError for a literal longer than MAX_LITERAL_DIGITS characters or an
    integer beyond 64 bits (Logix verification refuses both; nothing wraps silently).
    """
    if len(text) > MAX_LITERAL_DIGITS:  # before int(): Python refuses 4,300+ digits anyway
        raise LiteralError(
            f"numeric literal of {len(text):,} characters: the limit is {MAX_LITERAL_DIGITS:,}"
        )
    t = text.replace("_", "")
    upper = t.upper()
    if "#" in upper:
        radix, digits = upper.split("#", 1)
        suffix = ""
        for s in ("UL", "U", "L"):
            # hex digits never include U or L, so a trailing U/L is a suffix
            if digits.endswith(s):
                suffix, digits = s, digits[: -len(s)]
                break
        value = int(digits, int(radix))
        if value >= 1 << 64:
            raise LiteralError(f"integer literal {text} does not fit in 64 bits (LINT/ULINT)")
        typ = _SUFFIX_TYPES[suffix]
        if typ == "DINT" and value > 0xFFFFFFFF:
            typ = "LINT"
        # Radix literals give a bit pattern: 16#FFFF_FFFF is DINT -1.
        if typ == "DINT" and value >= 0x80000000:
            value -= 1 << 32
        elif typ == "LINT" and value >= 1 << 63:
            value -= 1 << 64
        return value, typ
    if "." in t or ("E" in upper and not upper.endswith(("U", "L"))):
        return float(t), "REAL"
    suffix = ""
    for s in ("UL", "U", "L"):
        if upper.endswith(s):
            suffix, upper = s, upper[: -len(s)]
            break
    value = int(upper)
    limit = (1 << 64) - 1 if "U" in suffix else (1 << 63)  # 2**63 only as -9223372036854775808
    if value > limit:
        raise LiteralError(
            f"integer literal {text} is out of range: the largest is "
            f"{limit if 'U' in suffix else limit - 1} ({'ULINT' if 'U' in suffix else 'LINT'})"
        )
    typ = _SUFFIX_TYPES[suffix]
    if typ == "DINT" and value > 0x7FFFFFFF:
        typ = "LINT"
    return value, typ


def number_or_zero(text: str) -> tuple[int | float, str]:
    """parse_number for the parsers: a refused literal reads as 0 and keeps its text, and the
    checker reports it at its place with literal_problem (so `check` and `run` agree)."""
    try:
        return parse_number(text)
    except LiteralError:
        return 0, "LINT"


def literal_problem(text: str) -> str | None:
    """Why a numeric literal's text is refused, or None."""
    try:
        parse_number(text)
    except LiteralError as exc:
        return str(exc)
    except ValueError:
        return None  # a REAL such as 1e999 is +inf, as Logix reads it; not this check's case
    return None


def parse_string(text: str) -> bytes:
    """Decode a quoted ST string with `$` escapes (`$$ $' $L $N $R $T $P $hh`) to its bytes."""
    return decode_text(text).encode("latin-1", "replace")


def decode_text(text: str) -> str:
    """The text of a quoted Logix string (`'...'` or `"..."`) with its `$` escapes decoded.

    `$hh` gives the character with that code, so encoding the result as latin-1 yields the
    string's bytes; characters beyond latin-1 stay intact (ladder rung comments).
    """
    body = text[1:-1]
    out: list[str] = []
    i = 0
    while i < len(body):
        ch = body[i]
        if ch == "$" and i + 1 < len(body):
            nxt = body[i + 1]
            if nxt.upper() in _ESCAPES:
                out.append(_ESCAPES[nxt.upper()])
                i += 2
                continue
            hexpart = body[i + 1 : i + 3]
            if len(hexpart) == 2 and all(c in "0123456789abcdefABCDEF" for c in hexpart):
                out.append(chr(int(hexpart, 16)))
                i += 3
                continue
            out.append(nxt)
            i += 2
            continue
        out.append(ch)
        i += 1
    return "".join(out)
