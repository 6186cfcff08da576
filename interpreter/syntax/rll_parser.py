"""Ladder front end: Logix neutral text (rll.lark) -> ladder AST (nodes.Rung, LadderInstr, Branch).

A `.rll` file is an optional TYPE/VAR header, parsed by the ST front end, followed by rungs.
The rung part is cut at every `;` outside a string (no operand can hold a `;`), and each
piece is parsed on its own, so one bad rung never hides errors in the rungs after it.
Positions are those of the file; text handed to `parse_rung` starts at a given (line, col).
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from functools import cache
from pathlib import Path
from typing import Any

from lark import Lark, Token, UnexpectedInput, UnexpectedToken

from ..diagnostics import Diagnostic, diag
from . import nodes as n
from .comments import strip_comments
from .literals import decode_text
from .rung_scan import scan_rung
from .st_lexer import SlowPath, contextual_tokens, fast_parse
from .st_parser import AstBuilder, grammar_cache, parse_st, tspan

_ST_PREFIX = "st__"


class RllBuilder(AstBuilder):
    """AstBuilder plus the ladder rules; imported ST rules (`st__binary`) map to AstBuilder."""

    def __getattr__(self, name: str) -> Any:
        if name.startswith(_ST_PREFIX):
            return getattr(self, name[len(_ST_PREFIX) :])
        raise AttributeError(name)

    def rung_line(self, c: list) -> n.Rung:
        elements = next(x for x in c if isinstance(x, list))
        return n.Rung(elements, _extent(c))

    rung_only = rung_line

    def rung_comment(self, c: list) -> n.Comment:
        text = "".join(
            decode_text(str(t)) for t in c if isinstance(t, Token) and t.type == "STRING_LIT"
        )
        return n.Comment(text, _extent(c))

    def rung(self, c: list) -> list[n.LadderElement]:
        return c[0] if c else []

    leg = rung

    def elements_first(self, c: list) -> list[n.LadderElement]:
        return [c[0]]

    def elements_more(self, c: list) -> list[n.LadderElement]:
        c[0].append(c[1])
        return c[0]  # type: ignore[no-any-return]

    def legs_first(self, c: list) -> list[list[n.LadderElement]]:
        return [c[0]]

    def legs_more(self, c: list) -> list[list[n.LadderElement]]:
        c[0].append(c[2])
        return c[0]  # type: ignore[no-any-return]

    def branch(self, c: list) -> n.Branch:
        return n.Branch(c[1], tspan(c[0]).to(tspan(c[2])))

    def slots_first(self, c: list) -> list:
        return [c[0]]

    def slots_more(self, c: list) -> list:
        c[0].extend((c[1], c[2]))  # keep the commas: an empty slot's span runs between them
        return c[0]  # type: ignore[no-any-return]

    def instr(self, c: list) -> n.LadderInstr:
        name: Token = c[0]
        items = [c[1], *c[2], c[3]]  # "(" slot ("," slot)* ")": slots sit between separators
        slots = items[1:-1:2]
        seps = items[0::2]
        operands: list[n.Expr] = []
        if not (len(slots) == 1 and slots[0] is None):  # `NOP()`: no operands at all
            for i, slot in enumerate(slots):
                if slot is None:
                    before, after = seps[i], seps[i + 1]
                    slot = n.Placeholder(tspan(before).to(tspan(after)))  # the separators around it
                operands.append(slot)
        return n.LadderInstr(str(name), operands, tspan(name).to(tspan(c[3])), tspan(name))

    def placeholder(self, c: list) -> n.Placeholder:
        return n.Placeholder(tspan(c[0]))

    def enum_words(self, c: list) -> n.EnumText:
        return n.EnumText(" ".join(str(c[0]).split()), tspan(c[0]))


def _extent(c: list) -> n.Span:
    """Span from the first to the last token or node among children (NOWHERE if none)."""
    spans = [tspan(x) if isinstance(x, Token) else x.span for x in _flat(c)]
    return spans[0].to(spans[-1]) if spans else n.NOWHERE


def _flat(c: list) -> list:
    out: list = []
    for x in c:
        if isinstance(x, list):
            out.extend(_flat(x))
        elif x is not None:
            out.append(x)
    return out


@cache
def _parser() -> Lark:
    return Lark.open(
        str(Path(__file__).with_name("rll.lark")),
        parser="lalr",
        lexer="contextual",
        transformer=RllBuilder(),
        maybe_placeholders=True,
        start=["rung_line", "rung_only"],
        cache=grammar_cache("rll"),
    )


@cache
def _plain_name() -> re.Pattern[str]:
    """The grammar's NAME terminal (an identifier that is not a reserved word), for rung_scan.

    TRUE and FALSE are soft keywords (st.lark): names where no operand is expected, literals
    in an operand, which is where the scanner meets them, so it leaves them to the grammar.
    """
    name = _parser().get_terminal("st__NAME").pattern.to_regexp()
    return re.compile(r"(?i:(?!(?:TRUE|FALSE)(?![A-Za-z0-9_])))" + name)


# ---------------------------------------------------------------- positions
@dataclass(slots=True)
class _Origin:
    """Where text[0] of a parsed piece sits in the file."""

    line: int
    col: int

    def span(self, s: n.Span) -> n.Span:
        return n.Span(*self.pos(s.line, s.col), *self.pos(s.end_line, s.end_col))

    def pos(self, line: int, col: int) -> tuple[int, int]:
        return (self.line + line - 1, self.col + col - 1 if line == 1 else col)


def _shift(node: object, o: _Origin) -> None:
    """Move every span in an AST subtree from piece coordinates to file coordinates."""
    if isinstance(node, list):
        for x in node:
            _shift(x, o)
        return
    fields = getattr(node, "__dataclass_fields__", None)
    if fields is None:
        return
    for f in fields:
        v = getattr(node, f)
        if isinstance(v, n.Span):
            setattr(node, f, o.span(v))
        elif isinstance(v, list) or hasattr(v, "__dataclass_fields__"):
            _shift(v, o)


# ---------------------------------------------------------------- errors
_OPEN = {"(": ")", "[": "]"}
_CLOSE = {")": "(", "]": "["}
_WHAT = {"(": "parenthesis", "[": "branch"}


def _balance(text: str) -> tuple[int, str, str] | None:
    """First unterminated string or unbalanced bracket (offset, code, message), or None."""
    stack: list[tuple[str, int]] = []
    i = 0
    while i < len(text):
        ch = text[i]
        if ch in "'\"":
            end, closed = _string_end(text, i)
            if not closed:
                return i, "S003", "string is not terminated"
            i = end
            continue
        if ch in _OPEN:
            stack.append((ch, i))
        elif ch in _CLOSE:
            if not stack:
                return i, "S006", f"'{ch}' closes a {_WHAT[_CLOSE[ch]]} that was never opened"
            top, at = stack.pop()
            if top != _CLOSE[ch]:
                return i, "S006", f"'{ch}' cannot close the {_WHAT[top]} '{top}' opened before it"
        i += 1
    if stack:
        top, at = stack[-1]
        return at, "S006", f"'{top}' {_WHAT[top]} is not closed before the end of the rung"
    return None


def _string_end(text: str, i: int) -> tuple[int, bool]:
    """Offset after the string starting at text[i], and whether it is closed (strings never span lines)."""
    quote = text[i]
    j = i + 1
    while j < len(text) and text[j] != quote and text[j] != "\n":
        j += 2 if text[j] == "$" else 1
    if j < len(text) and text[j] == quote:
        return j + 1, True
    return min(j, len(text)), False


_END = {"$END", "<END-OF-FILE>"}
_FRIENDLY = {
    "LSQB": "'['",
    "RSQB": "']'",
    "COMMA": "','",
    "LPAR": "'('",
    "RPAR": "')'",
    "SEMI": "';'",
    "STRING_LIT": "a string",
    "st__MEMBER_NAME": "a member name",
}


def _expected(names: set[str]) -> str:
    names = {x for x in names if not x.startswith("__")}
    if "QMARK" in names or "st__NAME" in names:
        return "an operand" + (" or ')'" if "RPAR" in names else "")
    if "INSTR_NAME" in names:
        return "an instruction, a branch or the end of the rung"
    friendly = sorted({_FRIENDLY.get(x, x.removeprefix(_ST_PREFIX)) for x in names - _END})
    if names & _END:
        friendly.append("the end of the rung")
    if len(friendly) > 5:
        return "an operator, ',' or ')'"
    return " or ".join(friendly)


def _syntax_error(e: UnexpectedInput, text: str, path: str, o: _Origin) -> Diagnostic:
    if isinstance(e, UnexpectedToken):
        tok = e.token
        expected = set(e.expected)
        if tok.type in _END:
            line, col = _end_pos(text)
            return diag(
                "S001",
                f"the rung ends early, expected {_expected(expected)}",
                path,
                o.span(n.Span(line, col, line, col)),
            )
        if expected <= _END:
            return diag(
                "S001",
                f"unexpected {str(tok)!r} after the end of the rung (one rung only)",
                path,
                o.span(tspan(tok)),
            )
        return diag(
            "S001",
            f"unexpected {str(tok)!r}, expected {_expected(expected)}",
            path,
            o.span(tspan(tok)),
        )
    line, col = e.line, e.column
    off = _offset(text, line, col)
    ch = text[off] if off < len(text) else ""
    return diag(
        "S004", f"unexpected character {ch!r}", path, o.span(n.Span(line, col, line, col + 1))
    )


def _offset(text: str, line: int, col: int) -> int:
    off = 0
    for _ in range(line - 1):
        off = text.index("\n", off) + 1
    return off + col - 1


def _end_pos(text: str) -> tuple[int, int]:
    line = text.count("\n") + 1
    return line, len(text) - (text.rfind("\n") + 1) + 1


def _parse_piece(
    text: str, path: str, o: _Origin, start: str
) -> tuple[n.Rung | n.Comment | None, list[Diagnostic]]:
    parser = _parser()
    rung = scan_rung(text, o.line, o.col, _plain_name())  # ordinary rungs: no parser at all
    if rung is not None:
        return rung, []
    try:  # then the LALR tables without recovery, tokens already at file positions
        fast: n.Rung | n.Comment = fast_parse(
            parser,
            text,
            start,
            lambda state: contextual_tokens(parser, text, state, o.line, o.col),
        )
        return fast, []
    except SlowPath:
        pass
    bad = _balance(text)  # a rung that parses has balanced brackets: only errors need this scan
    if bad is not None:
        off, code, msg = bad
        line = text.count("\n", 0, off) + 1
        col = off - (text.rfind("\n", 0, off) + 1) + 1
        return None, [diag(code, msg, path, o.span(n.Span(line, col, line, col + 1)))]
    try:
        result: n.Rung | n.Comment = parser.parse(text, start=start)  # type: ignore[assignment]
    except UnexpectedInput as e:
        return None, [_syntax_error(e, text, path, o)]
    _shift(result, o)
    return result, []


# ---------------------------------------------------------------- public API
def parse_rung(
    text: str, path: str, number: int, line: int = 1, col: int = 1
) -> tuple[n.Rung | None, list[Diagnostic]]:
    """Parse one rung's neutral text (trailing `;` optional); text[0] sits at (line, col)."""
    o = _Origin(line, col)
    rung, diags = _parse_piece(text, path, o, "rung_only")
    if not isinstance(rung, n.Rung):
        return None, diags
    if rung.span == n.NOWHERE:  # empty text: an empty rung where the text starts
        rung.span = n.Span(line, col, line, col)
    rung.number = number
    return rung, diags


_HEADER_START = re.compile(
    r"\s*(TYPE|VAR(?:_INPUT|_OUTPUT|_IN_OUT|_GLOBAL|_EXTERNAL|_TEMP)?)(?![A-Za-z0-9_])", re.I
)
_HEADER_END = {"TYPE": re.compile(r"(?<![A-Za-z0-9_])END_TYPE(?![A-Za-z0-9_])(\s*;)?", re.I)}
_END_VAR = re.compile(r"(?<![A-Za-z0-9_])END_VAR(?![A-Za-z0-9_])", re.I)


def _header_end(text: str) -> int:
    """Offset where the TYPE/VAR blocks at the top of a .rll file end (0 when there are none)."""
    pos = 0
    while True:
        m = _HEADER_START.match(text, pos)
        if m is None:
            return pos
        closer = _HEADER_END.get(m.group(1).upper(), _END_VAR)
        end = closer.search(text, m.end())
        if end is None:
            return len(text)
        pos = end.end()


def _pieces(text: str, start: int) -> list[tuple[int, int]]:
    """(begin, end) of each rung or L5K line: cut after every `;` outside strings."""
    out = []
    i = begin = start
    while i < len(text):
        ch = text[i]
        if ch in "'\"":
            i = _string_end(text, i)[0]
            continue
        if ch == ";":
            out.append((begin, i + 1))
            begin = i + 1
        i += 1
    if text[begin:].strip():
        out.append((begin, len(text)))
    return out


def parse_rll(text: str, path: str) -> tuple[n.Routine, list[Diagnostic]]:
    """Parse a `.rll` file: optional TYPE/VAR header, then rungs each ending in `;`."""
    stripped = strip_comments(text)
    work = stripped.text
    diags: list[Diagnostic] = [
        diag("S003", "comment is not terminated", path, sp) for sp in stripped.unterminated
    ]
    routine = n.Routine(Path(path).stem, "rll", path, comments=stripped.comments)
    head = _header_end(work)
    if head:
        header, hdiags = parse_st(work[:head], path)
        routine.types, routine.decls = header.types, header.decls
        diags.extend(hdiags)
    line, line_start, scanned = 1, 0, 0
    pending: list[n.Comment] = []
    number = 0
    for begin, end in _pieces(work, head):
        lead = len(work[begin:end]) - len(work[begin:end].lstrip())
        begin += lead
        # file position of `begin`, counting newlines incrementally
        line += work.count("\n", scanned, begin)
        nl = work.rfind("\n", scanned, begin)
        if nl >= 0:
            line_start = nl + 1
        scanned = begin
        o = _Origin(line, begin - line_start + 1)
        piece = work[begin:end]
        result, pdiags = _parse_piece(piece, path, o, "rung_line")
        diags.extend(pdiags)
        if isinstance(result, n.Comment):
            pending.append(result)
            continue
        if not piece.endswith(";"):
            lend = o.pos(*_end_pos(piece.rstrip()))
            diags.append(
                diag("S005", "the last rung is missing its ';'", path, n.Span(*lend, *lend))
            )
        if isinstance(result, n.Rung):
            result.number = number
            if pending:
                result.comment = "\n".join(c.text for c in pending)
            routine.rungs.append(result)
        else:  # a rung with a syntax error: keep its RC: text as a plain comment
            routine.comments.extend(pending)
        pending = []
        number += 1
    routine.comments.extend(pending)  # an RC: line with no rung after it
    routine.comments.sort(key=lambda c: (c.span.line, c.span.col))
    return routine, diags
