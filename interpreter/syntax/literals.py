"""Literal decoding shared by the ST and ladder front ends and `--set`."""

from __future__ import annotations

_SUFFIX_TYPES = {"": "DINT", "U": "UDINT", "L": "LINT", "UL": "ULINT"}
_ESCAPES = {"$": "$", "'": "'", '"': '"', "L": "\n", "N": "\n", "R": "\r", "T": "\t", "P": "\f"}


def parse_number(text: str) -> tuple[int | float, str]:
    """Value and Logix type of an INT, radix or REAL literal (`16#FF_FF`, `5UL`, `1.5e3`)."""
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
    typ = _SUFFIX_TYPES[suffix]
    if typ == "DINT" and value > 0x7FFFFFFF:
        typ = "LINT"
    return value, typ


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
