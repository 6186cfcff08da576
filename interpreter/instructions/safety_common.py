"""Helpers shared by the simulated GuardLogix safety instructions (decisions 0075-0076)."""

from __future__ import annotations

from stdlib import catalog

# A mode selector may show no position for this long (ms) before that is a fault: documented
# for EPMS as 250 ms; FPMS uses the same figure (decision 0076).
NO_MODE_MS = 250


def enum_value(enum: str, text: str) -> int:
    """The logixst number of a catalog enumeration text (the numbers are private to logixst)."""
    v = catalog().enum(enum).lookup(text)
    assert v is not None, (enum, text)
    return v.value


def reset_edge(s: list, prev: int, value: object) -> bool:
    """True on an off-to-on transition of a reset input since the previous execution."""
    edge = bool(value) and not s[prev]
    s[prev] = int(bool(value))
    return edge


def mirror(s: list, layout: dict[str, int], rung: bool, **values: object) -> None:
    """Copy the rung condition and the plain input operands into the backing tag's members
    of the same names, as a GuardLogix backing tag shows them; enumerated options are not
    copied (their numbers in the real tag are not documented to us)."""
    s[layout["ENABLEIN"]] = s[layout["ENABLEOUT"]] = int(rung)
    for name, v in values.items():
        s[layout[name.upper()]] = int(v) if isinstance(v, bool) else v
