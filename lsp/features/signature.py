"""Signature help: the called instruction's operands with the active one (top-level commas)."""

from __future__ import annotations

from dataclasses import dataclass

from ..workspace import Analysed
from .context import Where, classify, offset_of
from .resolve import find_instruction


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
