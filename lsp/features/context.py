"""Classify the cursor: what may be written here (statement, member, operand N of X, type).

Completion, signature help and hover start here. The classification reads the text before
the cursor only, so it works in half-typed code (an unclosed call, a missing `;`) where the
parser has nothing to offer.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from enum import Enum

from ..lines import line_start

_WORD = re.compile(r"[A-Za-z0-9_%:]*\Z")
_IDENT_BEFORE = re.compile(r"([A-Za-z_][A-Za-z0-9_]*)\s*\Z")
_VAR_OPEN = re.compile(r"\bVAR(?:_INPUT|_OUTPUT|_IN_OUT|_GLOBAL|_EXTERNAL|_TEMP)?\b", re.I)
_VAR_CLOSE = re.compile(r"\bEND_VAR\b", re.I)
_LINE_COMMENT = re.compile(r"//[^\n]*")
_BLOCK_COMMENT = re.compile(r"\(\*.*?\*\)|/\*.*?\*/", re.S)
_STRING = re.compile(r"'(?:\$.|[^'$\n])*'")


WINDOW = 8192  # characters of context before the cursor (a statement is never longer)


class Where(Enum):
    STATEMENT = "statement"  # start of a statement / rung element: instructions, keywords, tags
    MEMBER = "member"  # after `.`: members of the expression's type, or bit numbers
    OPERAND = "operand"  # inside NAME( ... ): operand `index` of `instruction`
    TYPE = "type"  # after `:` in a VAR block
    VALUE = "value"  # an initialiser or the right of `:=`
    NONE = "none"  # inside a comment or string: nothing to offer


@dataclass(frozen=True, slots=True)
class Context:
    where: Where
    prefix: str = ""  # the part of the word already typed
    instruction: str = ""  # OPERAND: the called name as written
    index: int = 0  # OPERAND: 0-based operand position (top-level commas only)
    base: str = ""  # MEMBER: the expression text before the dot
    language: str = "st"  # "st" or "rll" (a rung)
    arg_text: str = ""  # OPERAND: the operand text typed so far (may hold spaces in a rung)


def _blank(m: re.Match[str]) -> str:
    return re.sub(r"[^\n]", " ", m.group(0))


def mask(text: str) -> str:
    """Comments and strings replaced by spaces (same length), so brackets inside them are inert."""
    text = _BLOCK_COMMENT.sub(_blank, text)
    text = _STRING.sub(_blank, text)
    return _LINE_COMMENT.sub(_blank, text)


def offset_of(text: str, line: int, character: int) -> int:
    """0-based (line, character) to an index into `text`, clamped to the text."""
    pos = line_start(text, line)
    if pos >= len(text):
        return len(text)
    end = text.find("\n", pos)
    end = len(text) if end < 0 else end
    return min(pos + max(character, 0), end)


def l5x_region(text: str, offset: int) -> tuple[int, str] | None:
    """For an .L5X document: the start of the ST line or rung text holding `offset`, and its
    language; None when the cursor is in the XML around them."""
    start = text.rfind("<![CDATA[", 0, offset)
    if start < 0 or text.rfind("]]>", start, offset) >= 0:
        return None
    element = text.rfind("<", 0, start)
    head = text[element:start].lstrip("<")
    language = "rll" if head.startswith("Text") else "st"
    return start + len("<![CDATA["), language


def classify(text: str, offset: int, language: str) -> Context:
    """The context at `offset` in `text` ("st", "rll" or "l5x" document)."""
    begin = 0
    if language == "l5x":
        region = l5x_region(text, offset)
        if region is None:
            return Context(Where.NONE)
        begin, language = region
    # The statement around the cursor is what matters: look back at most WINDOW characters
    # (from a line start), so that a keystroke deep in a long document stays cheap.
    window = (
        text.rfind("\n", begin, max(begin, offset - WINDOW)) + 1
        if offset - begin > WINDOW
        else begin
    )
    var_head = text[begin:window]  # only for finding an open VAR block further up
    raw = text[window:offset]
    before = mask(raw)
    if before != raw and before[-1:] == " " and raw[-1:] != " ":
        return Context(Where.NONE, language=language)  # inside a comment or string
    prefix = _WORD.search(before).group(0)  # type: ignore[union-attr]
    head = before[: len(before) - len(prefix)]
    if "." in prefix and ":" not in prefix:  # `a.b` typed as one word is caught below
        pass
    if head.endswith(".") and not head.endswith(".."):
        return Context(Where.MEMBER, prefix, base=_expression_before(head[:-1]), language=language)
    call = _enclosing_call(head, language)
    if call is not None:
        name, index, arg_start = call
        arg_text = before[arg_start:].strip()
        return Context(Where.OPERAND, prefix, name, index, language=language, arg_text=arg_text)
    if language == "st":
        last_open = _last(_VAR_OPEN, head)
        last_close = _last(_VAR_CLOSE, head)
        if last_open < 0 and last_close < 0 and var_head:
            far_open, far_close = _last(_VAR_OPEN, var_head), _last(_VAR_CLOSE, var_head)
            if far_open > far_close:  # a VAR block opened before the window is still open
                last_open, last_close = 0, -1
        if last_open > last_close:
            decl = head[max(head.rfind(";"), last_open) :]
            if ":=" in decl:
                return Context(Where.VALUE, prefix, language=language)
            if ":" in decl:
                return Context(Where.TYPE, prefix, language=language)
            return Context(Where.NONE, prefix, language=language)  # naming a new tag
        tail = head.rstrip()
        if tail.endswith(":=") or re.search(
            r"(?:[-+*/(<>=,&]|\b(?:AND|OR|XOR|NOT|MOD))$", tail, re.I
        ):
            return Context(Where.VALUE, prefix, language=language)
    return Context(Where.STATEMENT, prefix, language=language)


def _last(pattern: re.Pattern[str], text: str) -> int:
    found = -1
    for m in pattern.finditer(text):
        found = m.start()
    return found


def _enclosing_call(head: str, language: str) -> tuple[str, int, int] | None:
    """(name, operand index, where the current operand starts) of the unclosed call around the
    end of `head`; commas inside nested (), [] do not count. None outside any call."""
    depth = 0
    commas = 0
    arg_start = len(head)
    stop = ";"
    for i in range(len(head) - 1, -1, -1):
        c = head[i]
        if c in ")]":
            depth += 1
        elif c == "[":
            if depth == 0:
                if language == "rll":  # a branch opens: the call (if any) is inside its leg
                    return None
                continue
            depth -= 1
        elif c == "(":
            if depth == 0:
                m = _IDENT_BEFORE.search(head[:i])
                if m is None:
                    return None  # a parenthesised expression: treat as a value
                return m.group(1), commas, arg_start if commas else i + 1
            depth -= 1
        elif c == "," and depth == 0:
            if commas == 0:
                arg_start = i + 1
            commas += 1
        elif c == stop and depth == 0:
            return None
    return None


def _expression_before(text: str) -> str:
    """The operand text that ends `text`: `a.b[i, 2].c`, `Program:Main.x`, `Local:1:I`."""
    depth = 0
    i = len(text)
    while i > 0:
        c = text[i - 1]
        if c == "]":
            depth += 1
        elif c == "[":
            if depth == 0:
                break
            depth -= 1
        elif depth == 0 and not (c.isalnum() or c in "_.:"):
            break
        i -= 1
    return text[i:].strip()
