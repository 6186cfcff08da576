"""What Logix lets the time and date types (DT, LDT, TIME, TIME32, LTIME; v36+) meet.

Logix documents them as 64-bit (TIME32: 32-bit) signed counts of microseconds (DT, TIME,
TIME32) or nanoseconds (LDT, LTIME), usable in ladder ADD, SUB, CLR, MOV, the six compares,
GSV/SSV and JSR/SBR/RET, and in Structured Text with assignment and the single operators
+ - = <> < <= > >=; mixed with no other type but LINT. The pairings of two different time
types follow IEC 61131-3 where the units agree (decision 0072): a date plus or minus a
duration is a date, a date minus a date is a duration. Everything else is refused with a
message naming the types, so the checker reports it once (E121 / E105).
"""

from __future__ import annotations

from .types import DT, LDT, LINT, LTIME, TIME, Elementary

_COMPARE = frozenset(("=", "<>", "<", "<=", ">", ">="))

# (left, op, right) -> result, for two different time types
_PAIRS: dict[tuple[str, str, str], Elementary] = {
    ("DT", "+", "TIME"): DT,
    ("TIME", "+", "DT"): DT,
    ("DT", "-", "TIME"): DT,
    ("DT", "-", "DT"): TIME,
    ("LDT", "+", "LTIME"): LDT,
    ("LTIME", "+", "LDT"): LDT,
    ("LDT", "-", "LTIME"): LDT,
    ("LDT", "-", "LDT"): LTIME,
}


def _plain(t: Elementary, literal: bool) -> bool:
    """LINT, or an integer literal (a count in the other operand's unit), meets any time type."""
    return t is LINT or (literal and t.is_integer)


def binary_type(
    op: str, lt: Elementary, rt: Elementary, l_lit: bool = False, r_lit: bool = False
) -> Elementary | str:
    """Result type of `lt op rt` where at least one side is a time type, or why Logix refuses it.
    Comparisons give LINT here (the type both sides are compared in); the caller says BOOL."""
    if op not in _COMPARE and op not in ("+", "-"):
        return f"'{op}' is not defined for {_which(lt, rt)}: only + - and comparisons are"
    if lt.is_time and rt.is_time:
        if op in _COMPARE:
            return LINT if lt is rt else _mix(op, lt, rt)
        if lt is rt and not (lt.absolute and op == "+"):
            return TIME if lt is DT and op == "-" else LTIME if lt is LDT and op == "-" else lt
        return _PAIRS.get((lt.name, op, rt.name)) or _mix(op, lt, rt)
    time, other, other_lit = (lt, rt, r_lit) if lt.is_time else (rt, lt, l_lit)
    if not _plain(other, other_lit):
        return _mix(op, lt, rt)
    if op in _COMPARE:
        return LINT
    if time.absolute and op == "-" and rt is time:
        return _mix(op, lt, rt)  # a count minus a date means nothing
    return time


def assignable(target: Elementary, value: Elementary, literal: bool = False) -> str | None:
    """Why `target := value` (or MOV value into target) is refused, or None when Logix takes it:
    the same time type, or a time type and LINT either way (a straight copy of the count)."""
    if target is value:
        return None
    if target.is_time and value.is_time:
        return f"{value} cannot be stored in {target}: they are different time types"
    if (target.is_time and _plain(value, literal)) or (value.is_time and target is LINT):
        return None
    return (
        f"{value} cannot be stored in {target}: a time or date type only meets its own type or LINT"
    )


def _which(lt: Elementary, rt: Elementary) -> str:
    return str(lt) if lt.is_time else str(rt)


def _mix(op: str, lt: Elementary, rt: Elementary) -> str:
    return f"'{op}' cannot mix {lt} and {rt}: a time or date type only meets its own type or LINT"


def instruction_error(
    name: str, types: list[Elementary | None], literals: list[bool]
) -> str | None:
    """Cross-operand rule of the ladder instructions that take time types (their catalog
    operands list ANY_TIME): ADD/SUB need a result their Dest can hold, MOV a Dest that takes
    the Source, the compares two comparable operands. None when no time type is involved."""
    if not any(t is not None and t.is_time for t in types):
        return None
    if any(t is None for t in types):
        return None  # an operand already reported
    ts: list[Elementary] = [t for t in types if t is not None]
    if name in ("ADD", "SUB") and len(ts) == 3:
        r = binary_type("+" if name == "ADD" else "-", ts[0], ts[1], literals[0], literals[1])
        if isinstance(r, str):
            return f"{name}: {r}"
        why = assignable(ts[2], r)
        return None if why is None else f"{name}: {why}"
    if name == "MOV" and len(ts) == 2:
        why = assignable(ts[1], ts[0], literals[0])
        return None if why is None else f"MOV: {why}"
    if name in ("EQU", "NEQ", "GRT", "GEQ", "LES", "LEQ") and len(ts) == 2:
        r = binary_type("=", ts[0], ts[1], literals[0], literals[1])
        return f"{name}: {r}" if isinstance(r, str) else None
    return None
