"""Semantic tokens: keywords, tags, members, instructions, enumeration values, literals,
comments, types. A small regular-expression scan over the text, classified with the model."""

from __future__ import annotations

import re

from stdlib import catalog

from ..workspace import Analysed
from .completion import ELEMENTARY_TYPES, ST_KEYWORDS
from .context import Where, classify

LEGEND = (
    "keyword",
    "variable",
    "property",
    "function",
    "enumMember",
    "number",
    "string",
    "comment",
    "type",
)
_KW = {k.upper() for k in ST_KEYWORDS} | {
    "ELSIF",
    "RETAIN",
    "CONSTANT",
    "STRUCT",
    "END_STRUCT",
    "TYPE",
    "END_TYPE",
    "PROGRAM",
    "END_PROGRAM",
    "ARRAY",
}
_TOKEN = re.compile(
    r"(?P<comment>//[^\n]*|\(\*.*?\*\)|/\*.*?\*/)"
    r"|(?P<string>'(?:\$.|[^'$\n])*')"
    r"|(?P<number>(?:\d+#[0-9A-Fa-f_]+|\d[\d_]*(?:\.\d+)?(?:[eE][-+]?\d+)?))"
    r"|(?P<word>[A-Za-z_%][A-Za-z0-9_]*)",
    re.S,
)


def semantic_tokens(an: Analysed) -> list[tuple[int, int, int, int]]:
    """(0-based line, 0-based start character, length, LEGEND index) in document order."""
    doc = an.document
    language = doc.language or "st"
    text = doc.text
    regions = [(0, len(text))] if language != "l5x" else _cdata(text)
    model = an.loaded.model
    tags = {t.name.upper() for t in model.tags.values()}
    types = {name for name in catalog().types} | set(ELEMENTARY_TYPES)
    out: list[tuple[int, int, int, int]] = []
    for begin, end in regions:
        for m in _TOKEN.finditer(text, begin, end):
            kind = m.lastgroup
            start, stop = m.span()
            if kind == "word":
                kind = _classify_word(text, start, stop, language, tags, types, model)
                if kind is None:
                    continue
            _emit(out, text, start, stop, LEGEND.index(kind))
    return out


def _classify_word(text, start, stop, language, tags, types, model):  # type: ignore[no-untyped-def]
    word = text[start:stop].upper()
    if text[start - 1 : start] == ".":
        return "property"
    after = text[stop:].lstrip()[:1]
    if after == "(" and (catalog().instruction_any(word) or word in model.aois):
        return "function"
    if word in _KW and language != "rll":
        return "keyword"
    if word in tags:
        return "variable"
    if word in types:
        return "type"
    ctx = classify(text, stop, language)
    if ctx.where is Where.OPERAND:
        ins = catalog().instruction_any(ctx.instruction)
        if ins is not None and ins.operands:
            op = ins.operands[min(ctx.index, len(ins.operands) - 1)]
            if op.enum and catalog().enum(op.enum).lookup(word):
                return "enumMember"
    return None


def _emit(
    out: list[tuple[int, int, int, int]], text: str, start: int, stop: int, kind: int
) -> None:
    """One token per line (multi-line comments are split, as most clients need)."""
    line = text.count("\n", 0, start)
    col = start - (text.rfind("\n", 0, start) + 1)
    for part in text[start:stop].split("\n"):
        if part:
            out.append((line, col, len(part), kind))
        line += 1
        col = 0


def _cdata(text: str) -> list[tuple[int, int]]:
    out: list[tuple[int, int]] = []
    pos = 0
    while True:
        a = text.find("<![CDATA[", pos)
        if a < 0:
            return out
        b = text.find("]]>", a)
        if b < 0:
            return out
        out.append((a + 9, b))
        pos = b + 3


def encode(tokens: list[tuple[int, int, int, int]]) -> list[int]:
    """The LSP relative encoding: deltas of line and start, length, type, no modifiers."""
    data: list[int] = []
    prev_line = prev_col = 0
    for line, col, length, kind in tokens:
        delta_col = col - prev_col if line == prev_line else col
        data += [line - prev_line, delta_col, length, kind, 0]
        prev_line, prev_col = line, col
    return data
