"""Hover: an instruction's summary and operand table, a tag's type and declaration, an
enumeration value's meaning, a diagnostic code's explanation (markdown)."""

from __future__ import annotations

import re

from interpreter.diagnostics import REGISTRY
from interpreter.semantics.program import Tag
from stdlib import Instruction, catalog

from ..workspace import Analysed
from .context import Where, classify, offset_of
from .fblock import block, block_markdown, member_line, named_parameter
from .resolve import find_instruction, find_tag, program_at, word_at

_CODE = re.compile(r"^[SEWU]\d{3}$")


def hover(an: Analysed, line: int, character: int) -> str | None:
    text = an.document.text
    offset = offset_of(text, line, character)
    start, end = word_at(text, offset)
    word = text[start:end]
    if not word:
        return None
    model = an.loaded.model
    program = program_at(an, line + 1)
    if _CODE.match(word) and word in REGISTRY:
        return code_markdown(word)
    if text[end : end + 1] == "(" or text[end:].lstrip()[:1] == "(":
        fb = block(model, word, program) if _language(an) == "st" else None
        if fb is not None:
            return block_markdown(fb)
        ins = find_instruction(model, word, _language(an))
        if ins is not None:
            return instruction_markdown(ins)
    ctx = classify(text, end, an.document.language or "st")
    if ctx.where is Where.OPERAND and text[end:].lstrip()[:2] in (":=", "=>"):
        fb = block(model, ctx.instruction, program)
        m = fb.member(word) if fb is not None else None
        if fb is not None and m is not None:
            return f"**{fb.type.name}.{m.name}**: {member_line(m)}"
    if ctx.where is Where.OPERAND:
        fb = block(model, ctx.instruction, program)
        param = named_parameter(ctx.arg_text)
        m = fb.member(param) if fb is not None and param is not None else None
        if fb is not None and m is not None and m.enum is not None:
            value = catalog().enum(m.enum).lookup(word)
            if value is not None:
                return f"**{value.text}** = {value.value}: {value.doc}\n\n{fb.type.name} input {m.name}"
    if ctx.where is Where.OPERAND:
        ins = find_instruction(model, ctx.instruction, ctx.language)
        if ins is not None and ins.operands:
            op = ins.operands[min(ctx.index, len(ins.operands) - 1)]
            if op.enum is not None:
                value = catalog().enum(op.enum).lookup(word)
                if value is not None:
                    return f"**{value.text}** = {value.value}: {value.doc}\n\n{ins.name} operand {op.name}"
    if text[start - 1 : start] != ".":
        tag = find_tag(model, word, program)
        if tag is not None:
            return tag_markdown(tag)
    t = catalog().type(word)
    if t is not None:
        return f"**{t.name}** (predefined structure)\n\n{t.doc}"
    return None


def _language(an: Analysed) -> str:
    lang = an.document.language
    return "rll" if lang == "rll" else "st"


def instruction_markdown(ins: Instruction) -> str:
    rows = ["| # | operand | type | format | meaning |", "|---|---|---|---|---|"]
    for i, op in enumerate(ins.operands):
        meaning = op.doc
        if op.enum is not None:
            values = ", ".join(f"{v.value} {v.text}" for v in catalog().enum(op.enum).values)
            meaning = f"{meaning} ({values})"
        rows.append(f"| {i} | {op.name} | {' '.join(op.types)} | {op.format} | {meaning} |")
    head = f"**{ins.name}**({', '.join(op.name for op in ins.operands)})"
    note = f"\n\n_Not simulated: {ins.unsupported}_" if ins.unsupported else ""
    return f"{head}\n\n{ins.doc}{note}\n\n" + "\n".join(rows)


def tag_markdown(tag: Tag) -> str:
    scope = f"program {tag.program}" if tag.program else "controller"
    lines = [
        f"**{tag.name}** : `{tag.type}` ({scope} tag)",
        f"declared at {tag.path}:{tag.span.line}",
    ]
    if tag.alias_of is not None:
        lines.append(f"alias of {tag.alias_of.name}")
    lines.append(f"initial value: `{_initial(tag)}`")
    return "\n\n".join(lines)


_INIT_CHARS = 200  # an export's array data can be megabytes: the hover shows its start


def _initial(tag: Tag) -> str:
    """The tag's initial value as ST writes it (SPEC 8: hover gives type and initial value);
    with no initialiser, the zero the controller starts from."""
    from interpreter.semantics.types import Elementary

    if tag.init is None:
        t = tag.type
        if isinstance(t, Elementary):
            return "FALSE" if t.is_bool else "0.0" if t.is_real else "0"
        return "''" if getattr(t, "is_string", False) else "(the type's defaults)"
    out: list[str] = []
    _render(tag.init, out)
    text = "".join(out)
    return text if len(text) <= _INIT_CHARS else text[: _INIT_CHARS - 3] + "..."


def _render(init: object, out: list[str]) -> None:
    """Append `init` as ST initialiser text to `out`, stopping once it is long enough."""
    from interpreter.syntax import nodes as n

    if sum(map(len, out)) > _INIT_CHARS:
        return
    if isinstance(init, n.Literal):
        out.append(init.text)
    elif isinstance(init, n.Unary) and isinstance(init.operand, n.Literal):
        out.append(f"{'-' if init.op == '-' else 'NOT '}{init.operand.text}")
    elif isinstance(init, n.ArrayInit):
        out.append("[")
        for i, item in enumerate(init.items):
            if i:
                out.append(", ")
            _render(item, out)
        out.append("]")
    elif isinstance(init, n.StructInit):
        out.append("(")
        for i, (name, _, value) in enumerate(init.members):
            out.append(f"{', ' if i else ''}{name} := ")
            _render(value, out)
        out.append(")")
    else:
        out.append("(an expression)")


def code_markdown(code: str) -> str:
    """A diagnostic code: its severity and title, and the docs section that explains it."""
    from .diagnostics import DOCS, anchor

    c = REGISTRY[code]
    return f"**{c.code}** ({c.severity.value}): {c.title}\n\n[explanation, example and fix]({DOCS}#{anchor(code)})"
