"""A fast lexer for st.lark, plugged into lark's LALR parser in place of its contextual lexer.

lark's own lexer costs about half of a parse (docs/performance.md): it runs a Python loop per
token *and* per whitespace run, and tries each parser state's own regex. Logix ST is almost
context-free at the token level, so one master regex finds every token and its leading
whitespace in one match, and keywords come from a dict. The only context-dependent choices
are asked of the parser state, exactly where the contextual lexer would decide:
- `name:` is LABEL_NAME (a CASE label) only where the parser accepts one;
- `a:b` is QNAME (`S:FS`, `Local:1:I`) only where accepted, else NAME then ':';
- soft keywords (RETAIN, CONSTANT ...) are NAMEs where the keyword is not expected;
- any word right after '.' is MEMBER_NAME, reserved words included (`Move.AND`).
The keyword and operator tables are read from the grammar's terminals, so st.lark stays the
single definition; a terminal this lexer does not know fails at construction (tests catch it).
"""

from __future__ import annotations

import re
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from functools import cache
from typing import Any

from lark import Lark
from lark.exceptions import UnexpectedCharacters
from lark.lexer import Lexer, LexerState, PatternStr, Token
from lark.parse_tree_builder import ExpandSingleChild
from lark.parsers.lalr_analysis import Shift

_WORD = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\Z")
# Regex terminals of st.lark and the words a keyword-like regex terminal stands for.
_REGEX_TERMINALS = {
    "NAME",
    "MEMBER_NAME",
    "PARAM_REF",
    "QNAME",
    "LABEL_NAME",
    "ENUM_PCT",
    "REAL",
    "RADIX_INT",
    "INT",
    "STRING_LIT",
    "VAR_KW",
    "UNSUPPORTED_KW",
    "PROGRAM",
    "_TYPE",
}
# Keyword terminals that are keywords only where their regex's lookahead holds (st.lark); the
# VAR_KW words (below) too: VAR opens a block only before a name, else it is a tag (`Var := 0`).
_LOOKAHEAD_WORDS = {"PROGRAM": "PROGRAM", "_TYPE": "TYPE"}
_REGEX_WORDS = {
    "VAR_KW": (
        "VAR",
        "VAR_INPUT",
        "VAR_OUTPUT",
        "VAR_IN_OUT",
        "VAR_GLOBAL",
        "VAR_EXTERNAL",
        "VAR_TEMP",
    ),
    "UNSUPPORTED_KW": ("RETURN", "GOTO", "CONTINUE"),
}
# Tokens that can end an operand: a '.' after one is member or bit access.
_OPERAND_END = frozenset({"NAME", "QNAME", "MEMBER_NAME", "INT", "RSQB", "RPAR"})
_LABEL_AFTER = re.compile(r"[ \t\r\n]*:(?![=A-Za-z0-9_])")


class StLexer(Lexer):
    """lark custom lexer (interface 2: receives the parser state)."""

    __future_interface__ = 2

    def __init__(self, conf: Any) -> None:
        by_name = {t.name: t for t in conf.terminals}
        names = set(by_name) - set(conf.ignore)
        strings = {
            t.name: t.pattern.value for t in conf.terminals if isinstance(t.pattern, PatternStr)
        }
        unknown = names - set(strings) - _REGEX_TERMINALS
        if unknown:
            raise ValueError(f"st_lexer does not know the terminals {sorted(unknown)}")
        name_re = re.compile(by_name["NAME"].pattern.to_regexp(), re.IGNORECASE)
        self.keywords: dict[str, str] = {}
        ops: dict[str, str] = {}
        for tname, value in strings.items():
            if _WORD.match(value):
                self.keywords[value.upper()] = tname
            else:
                ops[value] = tname
        for tname, words in _REGEX_WORDS.items():
            pattern = re.compile(by_name[tname].pattern.to_regexp(), re.IGNORECASE)
            for w in words:
                m = pattern.match(f"{w} a")  # VAR_KW's lookahead wants a name after it
                assert m is not None and m.end() == len(w), (tname, w)
                self.keywords[w] = tname
        # the keyword's own regex decides, at the word's position, where it has a lookahead
        self.lookahead: dict[str, re.Pattern[str]] = {}
        for tname, w in _LOOKAHEAD_WORDS.items():
            self.keywords[w] = tname
        for tname in (*_LOOKAHEAD_WORDS, "VAR_KW"):
            self.lookahead[tname] = re.compile(by_name[tname].pattern.to_regexp(), re.IGNORECASE)
        self.hard = {w for w in self.keywords if not name_re.fullmatch(w)}
        self.ops = ops
        op_alts = "|".join(re.escape(o) for o in sorted(ops, key=len, reverse=True))
        self.master = re.compile(
            r"([ \t\r\n\f]*)(?:"
            r"(?P<W>[A-Za-z_][A-Za-z0-9_]*(?::[A-Za-z0-9_]+)*)"
            rf"|(?P<RADIX_INT>{by_name['RADIX_INT'].pattern.value})"
            rf"|(?P<REAL>{by_name['REAL'].pattern.value})"
            rf"|(?P<INT>{by_name['INT'].pattern.value})"
            rf"|(?P<STRING_LIT>{by_name['STRING_LIT'].pattern.value})"
            rf"|(?P<ENUM_PCT>{by_name['ENUM_PCT'].pattern.value})"
            rf"|(?P<PARAM_REF>{by_name['PARAM_REF'].pattern.value})"
            rf"|(?P<O>{op_alts})"
            r")",
            re.IGNORECASE,
        )
        self.trailing_ws = re.compile(r"[ \t\r\n\f]*\Z")

    def lex(self, lexer_state: LexerState, parser_state: Any) -> Iterator[Token]:
        src = lexer_state.text
        text: str = src if isinstance(src, str) else src.text
        # lark calls lex() again after an error handler resumes the parse: continue where
        # the line counter stands, and keep it current, as lark's own lexers do.
        ctr = lexer_state.line_ctr
        end = getattr(src, "end", len(text))
        accepts = None
        if parser_state is not None:
            states = parser_state.parse_conf.parse_table.states
            accepts = lambda: states[parser_state.position]  # noqa: E731
        for tok in self.tokens(
            text, max(ctr.char_pos, getattr(src, "start", 0)), end, accepts, parser_state, ctr
        ):
            lexer_state.last_token = tok
            yield tok
        ctr.char_pos = end

    def tokens(
        self,
        text: str,
        pos: int,
        end: int,
        accepts: Callable[[], Any] | None,
        parser_state: Any = None,
        counter: Any = None,
    ) -> Iterator[Token]:
        """Tokens of text[pos:end]; `accepts()` gives the terminals the parser accepts now.

        `counter` (lark's LineCounter) is kept at the end of the last token when given.
        """
        keywords, hard, ops = self.keywords, self.hard, self.ops
        match = self.master.match
        line = 1 + text.count("\n", 0, pos)
        line_start = text.rfind("\n", 0, pos) + 1
        last: Token | None = None
        while pos < end:
            m = match(text, pos, end)
            if m is None:
                ws_end = self._skip_ws(text, pos, end)
                if ws_end >= end:
                    return
                line, line_start = _advance(text, pos, ws_end, line, line_start)
                col = ws_end - line_start + 1
                raise UnexpectedCharacters(
                    text,
                    ws_end,
                    line,
                    col,
                    state=parser_state,
                    token_history=[last] if last else None,
                )
            start = m.end(1)
            if start > pos:
                line, line_start = _advance(text, pos, start, line, line_start)
            kind = m.lastgroup
            value = m.group(kind)  # type: ignore[arg-type]
            stop = m.end()
            ttype: str | None
            if kind == "W" and last is not None and last.type == "DOT":
                # a member name: keywords are names here; `a.b:c` is not one word
                if ":" in value:
                    stop = start + value.index(":")
                    value = value[: stop - start]
                ttype = "MEMBER_NAME"
            elif kind == "W":
                upper = value.upper()
                ttype = keywords.get(upper)
                if ttype is not None:
                    if upper not in hard and accepts is not None and ttype not in accepts():
                        ttype = "NAME"
                    elif ttype in self.lookahead and not self.lookahead[ttype].match(text, start):
                        ttype = "NAME"
                elif ":" in value:
                    if accepts is not None and "QNAME" not in accepts():
                        stop = start + value.index(":")
                        value = value[: stop - start]
                        ttype = "NAME"
                    else:
                        ttype = "QNAME"
                elif (
                    accepts is not None
                    and text.startswith(":", self._skip_ws(text, stop, end))
                    and _LABEL_AFTER.match(text, stop, end)
                    and "LABEL_NAME" in accepts()
                ):
                    ttype = "LABEL_NAME"
                else:
                    ttype = "NAME"
            elif kind == "O":
                ttype = ops[value]
            elif kind == "REAL" and value[0] == "." and not self._real_here(accepts, last):
                # `d.5`, `a.5e3`: after an operand '.' is member or bit access, not `.5`
                stop = start + 1
                value = "."
                ttype = ops["."]
            else:
                ttype = str(kind)
            col = start - line_start + 1
            tok = make_token(ttype, value, start, line, col, line, col + (stop - start), stop)
            last = tok
            pos = stop
            if counter is not None:
                counter.char_pos, counter.line, counter.line_start_pos = stop, line, line_start
                counter.column = stop - line_start + 1
            yield tok

    @staticmethod
    def _real_here(accepts: Callable[[], Any] | None, last: Token | None) -> bool:
        """Whether a leading-dot REAL (`.5`) may stand here, as lark's contextual lexer decides."""
        if accepts is not None:
            return "REAL" in accepts()
        return last is None or last.type not in _OPERAND_END

    @staticmethod
    def _skip_ws(text: str, pos: int, end: int) -> int:
        while pos < end and text[pos] in " \t\r\n\f":
            pos += 1
        return pos


def _advance(text: str, pos: int, stop: int, line: int, line_start: int) -> tuple[int, int]:
    """(line, offset where that line starts) after moving from `pos` to `stop`."""
    nl = text.count("\n", pos, stop)
    if nl:
        return line + nl, text.rfind("\n", pos, stop) + 1
    return line, line_start


class SlowPath(Exception):
    """The fast driver met a syntax error: parse again with lark's parser and its recovery."""


def fast_parse(
    parser: Lark,
    text: str,
    start: str,
    tokens: Callable[[Callable[[], int]], Iterator[Token]] | None = None,
) -> Any:
    """LALR parse of a well-formed text with lark's own tables and callbacks.

    The same shift/reduce steps as lark's `ParserState.feed_token`, in one loop with local
    variables (lark pays a method call, two asserts and rule comparisons per token). Any
    syntax error raises SlowPath so the caller re-parses with lark for exact error recovery.
    `tokens(state)` supplies the tokens (default: the parser's StLexer over `text`); `state()`
    is the current LALR state, for context-dependent lexing.
    """
    states, starts, ends = _tables(parser)
    end_state = ends[start]
    state_stack = [starts[start]]
    value_stack: list[Any] = []
    if tokens is None:
        lexer = parser.parser.lexer
        assert isinstance(lexer, StLexer)
        stream = lexer.tokens(text, 0, len(text), lambda: states[state_stack[-1]])
    else:
        stream = tokens(lambda: state_stack[-1])
    try:
        for tok in stream:
            ttype = tok.type
            while True:
                shift, arg = states[state_stack[-1]][ttype]
                if shift:
                    state_stack.append(arg)
                    value_stack.append(tok)
                    break
                size, callback, origin = arg
                if (
                    callback is None
                ):  # `?rule` with one child: the value stays, only the state moves
                    state_stack[-1] = states[state_stack[-2]][origin][1]
                    continue
                if size:
                    children = value_stack[-size:]
                    del state_stack[-size:]
                    del value_stack[-size:]
                else:
                    children = []
                value_stack.append(callback(children))
                state_stack.append(states[state_stack[-1]][origin][1])
        while True:
            shift, arg = states[state_stack[-1]]["$END"]
            if shift:  # pragma: no cover - $END is never shifted
                raise SlowPath
            size, callback, origin = arg
            if callback is None:
                state_stack[-1] = states[state_stack[-2]][origin][1]
                if state_stack[-1] == end_state:
                    return value_stack[-1]
                continue
            children = value_stack[-size:] if size else []
            if size:
                del state_stack[-size:]
                del value_stack[-size:]
            value = callback(children)
            state_stack.append(states[state_stack[-1]][origin][1])
            value_stack.append(value)
            if state_stack[-1] == end_state:
                return value
    except (KeyError, UnexpectedCharacters):
        raise SlowPath from None


@cache
def _tables(
    parser: Lark,
) -> tuple[dict[int, dict[str, tuple[bool, Any]]], dict[str, int], dict[str, int]]:
    """lark's LALR table re-keyed by plain strings, reductions as (size, callback, goto name).

    A reduction whose callback is None is an inlined `?rule` of one child.

    lark keys nonterminals by its Token subclass, whose Python-level __eq__ then runs on
    every dict probe; plain `str` keys keep lookups in C.
    """
    inner = parser.parser.parser.parser  # ParsingFrontend -> LALR_Parser -> _Parser
    table = inner.parse_table
    callbacks = inner.callbacks
    states: dict[int, dict[str, tuple[bool, Any]]] = {}
    for state, actions in table.states.items():
        row: dict[str, tuple[bool, Any]] = {}
        for key, (action, arg) in actions.items():
            if action is Shift:
                row[str(key)] = (True, arg)
            else:
                size, callback = len(arg.expansion), callbacks[arg]
                if size == 1 and isinstance(callback, ExpandSingleChild):
                    callback = None  # a pass-through reduction: fast_parse only moves the state
                row[str(key)] = (False, (size, callback, str(arg.origin.name)))
        states[state] = row
    return states, dict(table.start_states), dict(table.end_states)


def make_token(
    ttype: str, value: str, start: int, line: int, col: int, end_line: int, end_col: int, stop: int
) -> Token:
    """A lark Token without `Token.__new__`'s argument handling (same slots, same values)."""
    tok = str.__new__(Token, value)
    tok.type, tok.value, tok.start_pos, tok.end_pos = ttype, value, start, stop
    tok.line, tok.column, tok.end_line, tok.end_column = line, col, end_line, end_col
    return tok


@dataclass(slots=True)
class _StateScanner:
    """One parser state's terminals as a single regex that also swallows leading blanks."""

    regex: re.Pattern[str]
    retype: dict[str, Any]  # lark's keyword callbacks (NAME -> keyword type)
    ignore: frozenset[str]


def _state_scanner(parser: Lark, state: int, cache: dict[int, _StateScanner]) -> _StateScanner:
    basic = parser.parser.lexer.lexers[state]  # type: ignore[attr-defined]
    terms = basic.scanner.terminals  # lark's own order (priority, width, name)
    alts = "|".join(f"(?P<{t.name}>{t.pattern.to_regexp()})" for t in terms)
    found = _StateScanner(
        re.compile(rf"([ \t\r\n\f]*)(?:{alts})", basic.scanner.g_regex_flags),
        dict(basic.callback),
        frozenset(basic.ignore_types),
    )
    cache[state] = found
    return found


def contextual_tokens(
    parser: Lark, text: str, state: Callable[[], int], line: int = 1, col: int = 1
) -> Iterator[Token]:
    """Tokens of `text` from lark's own per-state terminals (any grammar using lexer="contextual").

    The terminal choice is exactly lark's (the terminals of the current parser state in
    lark's order, with its keyword re-typing callbacks); lark's per-token bookkeeping is
    left out and leading blanks are matched with the token. Positions are file positions
    when text[0] sits at (line, col), so callers need not shift the spans afterwards.
    """
    cache: dict[int, _StateScanner] = parser.__dict__.setdefault("_logixst_scanners", {})
    pos, end = 0, len(text)
    line_start = 1 - col  # so that column = offset - line_start + 1 on the first line
    while pos < end:
        st = state()
        sc = cache.get(st) or _state_scanner(parser, st, cache)
        m = sc.regex.match(text, pos)
        if m is None:
            ws_end = StLexer._skip_ws(text, pos, end)
            if ws_end >= end:
                return
            line, line_start = _advance(text, pos, ws_end, line, line_start)
            raise UnexpectedCharacters(text, ws_end, line, ws_end - line_start + 1, state=None)
        start = m.end(1)
        if start > pos:
            line, line_start = _advance(text, pos, start, line, line_start)
        ttype = m.lastgroup
        assert ttype is not None
        stop = m.end()
        value = text[start:stop]
        column = start - line_start + 1
        nl = value.count("\n")
        if nl:
            last_nl = start + value.rindex("\n")
            tok = make_token(ttype, value, start, line, column, line + nl, stop - last_nl, stop)
            line, line_start = line + nl, last_nl + 1
        else:
            tok = make_token(ttype, value, start, line, column, line, column + (stop - start), stop)
        pos = stop
        if ttype in sc.retype:
            tok = sc.retype[ttype](tok)
        if tok.type not in sc.ignore:
            yield tok
