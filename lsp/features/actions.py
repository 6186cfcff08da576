"""Code actions for the fixes the diagnostics registry knows: take the did-you-mean
suggestion, or declare an undefined tag with the type its use implies."""

from __future__ import annotations

import re
from dataclasses import dataclass

from interpreter.syntax import nodes as n
from stdlib import catalog

from ..workspace import Analysed
from .context import Where, classify, offset_of
from .resolve import find_instruction

_SUGGESTION = re.compile(r"\(did you mean '([^']+)'\?\)")
_UNDEFINED = re.compile(r"undefined tag '([A-Za-z_][A-Za-z0-9_]*)'")
_END_VAR = re.compile(r"\bEND_VAR\b", re.I)
# A catalog type class -> the concrete type to declare for it.
_CONCRETE = {"AXIS": "AXIS_VIRTUAL", "ANY_NUM": "DINT", "ANY_INT": "DINT", "ANY_REAL": "REAL",
             "ANY_BIT": "DINT", "ANY_ELEMENTARY": "DINT", "ANY": "DINT", "STRING_FAMILY": "STRING"}  # fmt: skip


@dataclass(frozen=True, slots=True)
class Edit:
    span: n.Span  # 1-based, end exclusive (as diagnostics)
    text: str


@dataclass(frozen=True, slots=True)
class Action:
    title: str
    edits: list[Edit]
    code: str  # the diagnostic it fixes


def actions(an: Analysed, code: str, message: str, span: n.Span) -> list[Action]:
    """Fixes for one diagnostic of the document (given as the editor sent it back)."""
    out = []
    m = _SUGGESTION.search(message)
    if m is not None:
        out.append(Action(f"Change to '{m.group(1)}'", [Edit(span, m.group(1))], code))
    u = _UNDEFINED.search(message)
    if code == "E101" and u is not None and an.document.language in ("st", "rll"):
        declare = _declaration(an, u.group(1), span)
        if declare is not None:
            out.append(declare)
    return out


def _declaration(an: Analysed, name: str, span: n.Span) -> Action | None:
    text = an.document.text
    type_name = implied_type(an, span)
    ends = list(_END_VAR.finditer(text))
    if ends:
        at = ends[-1].start()
        line_start = text.rfind("\n", 0, at) + 1
        line = text.count("\n", 0, at) + 1
        col = at - line_start + 1
        own_line = not text[line_start:at].strip()  # END_VAR alone on its line
        new = f"  {name} : {type_name};\n" if own_line else f"{name} : {type_name}; "
        col = 1 if own_line else col
        edit = Edit(n.Span(line, col, line, col), new)
    else:
        edit = Edit(n.Span(1, 1, 1, 1), f"VAR\n  {name} : {type_name};\nEND_VAR\n")
    return Action(f"Declare '{name}' as {type_name}", [edit], "E101")


def implied_type(an: Analysed, span: n.Span) -> str:
    """The type an operand position asks for; DINT where nothing says otherwise."""
    text = an.document.text
    offset = offset_of(text, span.end_line - 1, span.end_col - 1)
    ctx = classify(text, offset, an.document.language or "st")
    if ctx.where is Where.OPERAND:
        ins = find_instruction(an.loaded.model, ctx.instruction, ctx.language)
        if ins is not None and ins.operands:
            op = ins.operands[min(ctx.index, len(ins.operands) - 1)]
            first = op.types[0]
            if first in _CONCRETE:
                return _CONCRETE[first]
            if catalog().type(first) is not None or first in (
                "BOOL",
                "SINT",
                "INT",
                "DINT",
                "LINT",
                "REAL",
                "LREAL",
            ):
                return first
    return "DINT"
