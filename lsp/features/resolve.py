"""Names at a place: the tags visible there, the type of an operand's text, the instruction
a call names. Shared by completion, hover, signature help and navigation."""

from __future__ import annotations

import re

from interpreter.semantics.program import ProgramModel, Tag
from interpreter.semantics.types import ArrayType, DataType, Elementary, StructType
from stdlib import Instruction, catalog

from ..workspace import Analysed

_PROGRAM = re.compile(r"program ([^,)]+)")


def program_at(an: Analysed, line: int) -> str | None:
    """The L5X program whose routine holds 1-based `line` (None: controller scope, or a file)."""
    project = an.loaded.project
    if project is None:
        return None
    where = project.context.get(line)
    m = _PROGRAM.search(where or "")
    return m.group(1).strip() if m else None


def visible_tags(model: ProgramModel, program: str | None) -> list[Tag]:
    """Tags a routine of `program` can name: its own, then the controller's (not shadowed)."""
    own = [t for t in model.tags.values() if program is not None and t.program == program]
    names = {t.name.upper() for t in own}
    shared = [t for t in model.tags.values() if t.program is None and t.name.upper() not in names]
    return own + shared


def find_tag(model: ProgramModel, name: str, program: str | None) -> Tag | None:
    if name.upper().startswith("PROGRAM:") and "." in name:
        prog, _, tag = name[len("PROGRAM:") :].partition(".")
        return model.tag(tag, prog)
    return model.tag(name, program)


def split_operand(text: str) -> list[str]:
    """`a.b[i, j].c` -> ['a', 'b', '[]', 'c']; `Program:P.x.y` keeps `Program:P.x` whole."""
    parts: list[str] = []
    depth = 0
    cur = ""
    for c in text:
        if c == "[":
            if depth == 0:
                parts.append(cur)
                cur = ""
            depth += 1
        elif c == "]":
            depth -= 1
            if depth == 0:
                parts.append("[]")
        elif depth == 0 and c == ".":
            parts.append(cur)
            cur = ""
        elif depth == 0:
            cur += c
    parts.append(cur)
    parts = [p.strip() for p in parts if p.strip()]
    if len(parts) >= 2 and parts[0].upper().startswith("PROGRAM:"):
        parts[:2] = [f"{parts[0]}.{parts[1]}"]
    return parts


def type_of_operand(model: ProgramModel, text: str, program: str | None) -> DataType | None:
    """The data type of an operand written as text (tag, members, elements); None if unknown."""
    parts = split_operand(text)
    if not parts:
        return None
    tag = find_tag(model, parts[0], program)
    if tag is None:
        return None
    t: DataType | None = tag.type
    for part in parts[1:]:
        if t is None:
            return None
        if part == "[]":
            t = t.elem if isinstance(t, ArrayType) else None
        elif isinstance(t, StructType):
            m = t.member(part)
            t = m[1] if m is not None else None
        elif isinstance(t, Elementary) and part.isdecimal():
            from interpreter.semantics.types import BOOL

            t = BOOL
        else:
            return None
    return t


def find_instruction(model: ProgramModel, name: str, language: str) -> Instruction | None:
    """A project's add-on instruction, else the catalog entry for this language (or any)."""
    aoi = model.aois.get(name.upper())
    if aoi is not None:
        return getattr(aoi, "instruction", None)
    cat = catalog()
    return cat.instruction(name, language) or cat.instruction_any(name)


def word_at(text: str, offset: int) -> tuple[int, int]:
    """[start, end) of the identifier (with `:` for `S:FS`, `%` for enum texts) at `offset`."""
    start = offset
    while start > 0 and (text[start - 1].isalnum() or text[start - 1] in "_:%"):
        start -= 1
    end = offset
    while end < len(text) and (text[end].isalnum() or text[end] in "_:%"):
        end += 1
    return start, end
