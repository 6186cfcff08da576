"""IEC function-block calls (`camIn(Master := M, ...)`, SPEC 3.1): the block an instance tag
names and its parameters, from the catalog type of the same name (inputs are the writable
members, outputs the read-only ones). Completion, signature help and hover use it."""

from __future__ import annotations

import re
from dataclasses import dataclass

from interpreter.semantics.program import ProgramModel, Tag
from interpreter.semantics.types import StructType
from stdlib import Instruction, Member, TypeDef, catalog

from .resolve import find_tag

_NAMED = re.compile(r"([A-Za-z_][A-Za-z0-9_]*)\s*(:=|=>)")


@dataclass(frozen=True, slots=True)
class Block:
    tag: Tag
    type: TypeDef
    instruction: Instruction

    @property
    def inputs(self) -> list[Member]:
        return [m for m in self.type.members if not m.readonly and not m.hidden]

    @property
    def outputs(self) -> list[Member]:
        return [m for m in self.type.members if m.readonly and not m.hidden]

    def member(self, name: str) -> Member | None:
        key = name.upper()
        return next((m for m in self.type.members if m.name.upper() == key), None)


def block(model: ProgramModel, name: str, program: str | None) -> Block | None:
    """The function block an instance tag called `name` is, or None (not an instance)."""
    tag = find_tag(model, name, program)
    if tag is None or not isinstance(tag.type, StructType):
        return None
    cat = catalog()
    ins = cat.instruction(tag.type.name, "st")
    td = cat.type(tag.type.name)
    if ins is None or td is None:
        return None
    return Block(tag, td, ins)


def named_parameter(arg_text: str) -> str | None:
    """`Master := M` -> 'Master' (the parameter whose value is being written)."""
    m = _NAMED.match(arg_text)
    return m.group(1) if m else None


def member_line(m: Member) -> str:
    enum = ""
    if m.enum is not None:
        enum = " (" + ", ".join(f"{v.value} {v.text}" for v in catalog().enum(m.enum).values) + ")"
    need = " required;" if m.required else ""
    return f"{m.type}{need} {m.doc}{enum}"


def block_markdown(b: Block) -> str:
    rows = ["| parameter | type | meaning |", "|---|---|---|"]
    for m in b.inputs + b.outputs:
        direction = "output" if m.readonly else ("input, required" if m.required else "input")
        rows.append(
            f"| {m.name} | {m.type} | {direction}: {m.doc.removeprefix('input: ').removeprefix('output: ')} |"
        )
    head = f"**{b.tag.name}** : `{b.type.name}` (function block instance)"
    return f"{head}\n\n{b.instruction.doc}\n\n" + "\n".join(rows)
