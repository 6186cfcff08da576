"""Signature help: the called instruction's operands with the active one (top-level commas)."""

from __future__ import annotations

from dataclasses import dataclass

from ..workspace import Analysed
from .context import Where, classify, offset_of
from .fblock import block, member_line, named_parameter
from .resolve import find_instruction, program_at


@dataclass(frozen=True, slots=True)
class Signature:
    label: str
    documentation: str
    parameters: list[tuple[str, str]]  # (operand name, its doc)
    active: int


def signature(an: Analysed, line: int, character: int) -> Signature | None:
    text = an.document.text
    ctx = classify(text, offset_of(text, line, character), an.document.language or "st")
    if ctx.where is not Where.OPERAND:
        return None
    fb = block(an.loaded.model, ctx.instruction, program_at(an, line + 1))
    if fb is not None and ctx.language == "st":
        inputs = fb.inputs
        param = (named_parameter(ctx.arg_text) or "").upper()
        names = [m.name.upper() for m in inputs]
        return Signature(
            f"{fb.tag.name}({', '.join(f'{m.name} := ' for m in inputs)})",
            fb.instruction.doc,
            [(f"{m.name} := ", member_line(m)) for m in inputs],
            names.index(param) if param in names else min(ctx.index, len(inputs) - 1),
        )
    ins = find_instruction(an.loaded.model, ctx.instruction, ctx.language)
    if ins is None:
        return None
    names = [op.name for op in ins.operands]
    active = min(ctx.index, len(names) - 1) if names else 0
    return Signature(
        f"{ins.name}({', '.join(names)})",
        ins.doc,
        [(op.name, op.doc) for op in ins.operands],
        active,
    )
