"""Structured Text front end: lark LALR grammar (st.lark) -> AST (nodes.py), with recovery.

The AST is built by a transformer handed to the parser, so no intermediate parse tree is
made; spans come from tokens. Syntax errors are collected (several per file): a missing
`;` or END_xxx is inserted and parsing goes on; other errors blank the offending statement
and the text is parsed again.
"""

from __future__ import annotations

import re
from functools import cache
from pathlib import Path

from lark import Lark, Token, Transformer, UnexpectedCharacters, UnexpectedInput, UnexpectedToken

from ..diagnostics import Diagnostic, diag
from . import nodes as n
from .comments import line_starts, strip_comments
from .literals import LiteralError, number_or_zero, parse_number, parse_string
from .st_lexer import SlowPath, StLexer, fast_parse

MAX_ERRORS = 25

_BLOCKS = {
    "IF": "END_IF",
    "CASE": "END_CASE",
    "FOR": "END_FOR",
    "WHILE": "END_WHILE",
    "REPEAT": "END_REPEAT",
}
_CLOSERS = {v: k for k, v in _BLOCKS.items()}


def tspan(t: Token) -> n.Span:
    return n.Span(t.line, t.column, t.end_line, t.end_column)  # type: ignore[arg-type]


def _span(x: object) -> n.Span:
    if isinstance(x, Token):
        return tspan(x)
    return x.span  # type: ignore[attr-defined, no-any-return]


def _join(first: object, last: object) -> n.Span:
    # Hot path of AST building: no intermediate Span for the two ends.
    if isinstance(first, Token):
        line, col = first.line, first.column
    else:
        line, col = first.span[:2]  # type: ignore[attr-defined]
    if isinstance(last, Token):
        return n.Span(line, col, last.end_line, last.end_column)  # type: ignore[arg-type]
    end = last.span  # type: ignore[attr-defined]
    return n.Span(line, col, end[2], end[3])  # type: ignore[arg-type]


def _body(children: list) -> list:
    return [c for c in children if c is not None]


class AstBuilder(Transformer):
    """Bottom-up construction of AST nodes; one method per grammar rule alias."""

    # ------------------------------------------------------------ units
    def program_unit(self, c: list) -> tuple:
        header, body = c[2], c[3]
        return (str(c[1]), header, body, _join(c[0], c[4]))

    def bare_unit(self, c: list) -> tuple:
        return (None, c[0], c[1], None)

    def header(self, c: list) -> tuple[list, list]:
        types: list[n.TypeDecl] = []
        decls: list[n.VarDecl] = []
        for item in c:
            if isinstance(item, tuple) and item[0] == "types":
                types.extend(item[1])
            else:
                decls.extend(item)
        return types, decls

    def type_block(self, c: list) -> tuple:
        return ("types", list(c))

    def type_def(self, c: list) -> n.TypeDecl:
        name = c[0]
        members = list(c[1:])
        end = members[-1].span if members else tspan(name)
        return n.TypeDecl(str(name), members, tspan(name).to(end), tspan(name))

    def member_decl(self, c: list) -> n.VarDecl:
        return self.var_decl(c)

    def var_block(self, c: list) -> list[n.VarDecl]:
        kind = str(c[0]).upper()
        out = []
        for d in c[1:]:
            if isinstance(d, n.VarDecl):
                d.block = kind
                out.append(d)
        return out

    def var_modifier(self, c: list) -> None:
        return None

    def var_decl(self, c: list) -> n.VarDecl:
        names, tref = c[0], c[1]
        init = c[2] if len(c) > 2 else None
        end = _span(init) if init is not None else tref.span
        return n.VarDecl(names, tref, init, names[0][1].to(end))

    def name_list(self, c: list) -> list[tuple[str, n.Span]]:
        return [(str(t), tspan(t)) for t in c]

    def type_simple(self, c: list) -> n.TypeRef:
        return n.TypeRef(str(c[0]).upper(), [], tspan(c[0]))

    def type_logix_array(self, c: list) -> n.TypeRef:
        dims = [(0, _dimension(str(t)) - 1) for t in c[1:]]
        return n.TypeRef(str(c[0]).upper(), dims, _join(c[0], c[-1]))

    def type_iec_array(self, c: list) -> n.TypeRef:
        inner: n.TypeRef = c[-1]
        dims = list(c[:-1]) + inner.dims
        return n.TypeRef(inner.name, dims, inner.span)

    def dim_range(self, c: list) -> tuple[int, int]:
        return (c[0], c[1])

    def signed_int(self, c: list) -> int:
        v = _dimension(str(c[-1]))
        return -v if len(c) == 2 else v

    # The brackets are kept (named terminals in the grammar) so that the initialiser's span
    # covers them: E118 then marks `[1, 2]` as written, not just the items inside.
    def array_init(self, c: list) -> n.ArrayInit:
        return n.ArrayInit(list(c[1:-1]), tspan(c[0]).to(tspan(c[-1])))

    def struct_init(self, c: list) -> n.StructInit:
        return n.StructInit(list(c[1:-1]), tspan(c[0]).to(tspan(c[-1])))

    def member_init(self, c: list) -> tuple[str, n.Span, object]:
        return (str(c[0]), tspan(c[0]), c[1])

    # ------------------------------------------------------------ statements
    def body(self, c: list) -> list:
        return _body(c)

    def assign_stmt(self, c: list) -> n.Assign:
        return n.Assign(c[0], c[2], str(c[1]) == "[:=]", _join(c[0], c[2]))

    def call_stmt(self, c: list) -> n.CallStmt:
        name: Token = c[0]
        items = [c[1], *c[2], c[3]]  # "(" slot ("," slot)* ")": slots sit between separators
        slots = items[1:-1:2]
        args: list[n.Arg] = []
        if not (len(slots) == 1 and slots[0] is None):  # `f()`: no arguments at all
            for i, slot in enumerate(slots):
                if slot is None:  # an empty operand: its span is the separators around it
                    sp = tspan(items[2 * i]).to(tspan(items[2 * i + 2]))
                    slot = n.Arg(n.Placeholder(sp), None, sp)
                args.append(slot)
        end = args[-1].span if args else tspan(name)
        call = n.Call(str(name), args, tspan(name).to(end), tspan(name))
        return n.CallStmt(call, call.span)

    def call_args_first(self, c: list) -> list:
        return [c[0]]

    def call_args_more(self, c: list) -> list:
        c[0].extend((c[1], c[2]))  # keep the commas
        return c[0]  # type: ignore[no-any-return]

    def call(self, c: list) -> n.Call:
        name = c[0]
        args = [a for a in c[1:] if a is not None]
        end = args[-1].span if args else tspan(name)
        return n.Call(str(name), args, tspan(name).to(end), tspan(name))

    def arg_pos(self, c: list) -> n.Arg:
        return n.Arg(c[0], None, _span(c[0]))

    def arg_named(self, c: list) -> n.Arg:
        return n.Arg(c[1], str(c[0]), _join(c[0], c[1]))

    def arg_out(self, c: list) -> n.Arg:
        return n.Arg(c[1], str(c[0]) + "=>", _join(c[0], c[1]))

    def if_stmt(self, c: list) -> n.If:
        branches = [(c[1], c[2])]
        else_body = None
        for part in c[3:-1]:
            if isinstance(part, tuple):
                branches.append(part)
            elif isinstance(part, list):
                else_body = part
        return n.If(branches, else_body, _join(c[0], c[-1]))

    def elsif_part(self, c: list) -> tuple:
        return (c[0], c[1])

    def else_part(self, c: list) -> list:
        return list(c[0])

    def case_stmt(self, c: list) -> n.Case:
        arms = [a for a in c[2:-1] if isinstance(a, n.CaseArm)]
        else_body = next((a for a in c[2:-1] if isinstance(a, list)), None)
        return n.Case(c[1], arms, else_body, _join(c[0], c[-1]))

    def case_arm(self, c: list) -> n.CaseArm:
        labels, body = list(c[:-1]), c[-1]
        end = body[-1].span if body else _span(labels[-1])
        return n.CaseArm(labels, body, _span(labels[0]).to(end))

    def label_value(self, c: list) -> n.Expr:
        return c[0]

    def label_range(self, c: list) -> n.CaseRange:
        return n.CaseRange(c[0], c[1], _join(c[0], c[1]))

    def label_name(self, c: list) -> n.Name:
        return n.Name(str(c[0]), tspan(c[0]))

    def signed_const(self, c: list) -> n.Expr:
        lit = self.literal([c[-1]])
        if len(c) == 2:
            return n.Unary("-", lit, _join(c[0], lit))
        return lit

    def for_stmt(self, c: list) -> n.For:
        step = c[4] if len(c) == 7 else None
        return n.For(c[1], c[2], c[3], step, c[-2], _join(c[0], c[-1]))

    def while_stmt(self, c: list) -> n.While:
        return n.While(c[1], c[2], _join(c[0], c[-1]))

    def repeat_stmt(self, c: list) -> n.Repeat:
        return n.Repeat(c[1], c[2], _join(c[0], c[-1]))

    def exit_stmt(self, c: list) -> n.Exit:
        return n.Exit(tspan(c[0]))

    def unsupported_stmt(self, c: list) -> n.Unsupported:
        return n.Unsupported(str(c[0]).upper(), _join(c[0], c[-1]))

    def empty_stmt(self, c: list) -> n.Empty:
        return n.Empty(tspan(c[0]))

    # ------------------------------------------------------------ expressions
    def binary(self, c: list) -> n.Binary:
        op = str(c[1]).upper()
        if op == "&":
            op = "AND"
        return n.Binary(op, c[0], c[2], _join(c[0], c[2]))

    def unary(self, c: list) -> n.Unary:
        return n.Unary(str(c[0]).upper(), c[1], _join(c[0], c[1]))

    def unary_plus(self, c: list) -> n.Expr:
        return c[1]

    def enum_text(self, c: list) -> n.EnumText:
        return n.EnumText(str(c[0]), tspan(c[0]))

    def literal(self, c: list) -> n.Literal:
        t: Token = c[0]
        text = str(t)
        kind = t.type
        if kind in ("INT", "RADIX_INT", "REAL"):
            value, typ = number_or_zero(text)  # a refused literal: the checker reports it
            return n.Literal(value, typ, text, tspan(t))
        if kind == "STRING_LIT":
            return n.Literal(parse_string(text), "STRING", text, tspan(t))
        return n.Literal(1 if kind == "TRUE" else 0, "BOOL", text, tspan(t))

    def name(self, c: list) -> n.Name:
        return n.Name(str(c[0]), tspan(c[0]))

    def param_ref(self, c: list) -> n.Name:
        # `\P.T` names tag T of program P, which the model keys and watches as `Program:P.T`
        program, tag = c
        return n.Name(f"Program:{str(program)[1:]}.{tag}", tspan(program).to(tspan(tag)))

    def member(self, c: list) -> n.Member:
        return n.Member(c[0], str(c[1]), _join(c[0], c[1]), tspan(c[1]))

    def bit(self, c: list) -> n.Bit:
        return n.Bit(c[0], int(str(c[1]).replace("_", "")), _join(c[0], c[1]))

    def indirect_bit(self, c: list) -> n.IndirectBit:
        return n.IndirectBit(c[0], c[1], _join(c[0], c[1]))

    def index(self, c: list) -> n.Index:
        return n.Index(c[0], list(c[1:]), _join(c[0], c[-1]))


def grammar_cache(name: str) -> str | bool:
    """Where lark keeps a grammar's analysed tables between runs (saves ~0.3 s per start).

    A file in the user's own cache directory rather than lark's default in the shared temp
    directory. Its name carries a hash of every grammar file here, because lark's own check
    does not notice a change in a file the grammar imports (rll.lark imports st.lark).
    False (no caching) when the directory cannot be created.
    """
    import hashlib
    import os

    import lark

    digest = hashlib.sha256()
    for grammar in sorted(Path(__file__).parent.glob("*.lark")):
        digest.update(grammar.read_bytes())
    base = Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache") / "logixst"
    current = base / f"{name}-lark{lark.__version__}-{digest.hexdigest()[:16]}.cache"
    try:
        base.mkdir(parents=True, exist_ok=True)
        for old in base.glob(f"{name}-lark*.cache"):
            if old != current:
                old.unlink(missing_ok=True)
    except OSError:
        return False
    return str(current)


@cache
def _parser() -> Lark:
    grammar = (Path(__file__).parent / "st.lark").read_text()
    return Lark(
        grammar,
        parser="lalr",
        lexer=StLexer,
        transformer=AstBuilder(),
        maybe_placeholders=True,
        start=["start", "expr"],
        cache=grammar_cache("st"),
    )


def parse_expression(text: str) -> n.Expr:
    """Parse one expression (`--watch`, `--set`); raises ValueError with a one-line reason."""
    try:
        expr: n.Expr = _parser().parse(text, start="expr")  # type: ignore[assignment]
        return expr
    except UnexpectedInput as e:
        raise ValueError(f"cannot parse '{text}' at column {getattr(e, 'column', '?')}") from None


_FRIENDLY = {
    "SEMI": "';'",
    "NAME": "a name",
    "MEMBER_NAME": "a member name",
    "QNAME": "a name",
    "PARAM_REF": "a name",
    "INT": "a number",
    "REAL": "a number",
    "RPAR": "')'",
    "LPAR": "'('",
    "COMMA": "','",
    "COLON": "':'",
    "ASSIGN": "':='",
    "NR_ASSIGN": "'[:=]'",
    "RSQB": "']'",
    "LSQB": "'['",
    "DOT": "'.'",
    "$END": "end of file",
}


def _describe(tok: Token) -> str:
    if tok.type == "$END":
        return "end of file"
    return repr(str(tok))


def _expected(names: set[str]) -> str:
    names = {x for x in names if not x.startswith("__")}
    if {"NAME", "INT"} <= names or {"INT", "MINUS"} <= names:
        return "an expression"
    friendly = sorted({_FRIENDLY.get(x, x.replace("_KW", "")) for x in names})
    if len(friendly) > 6:
        return "a statement"
    return " or ".join(friendly)


class _Recovery:
    """State of one parse attempt's error handling."""

    def __init__(self, path: str, pending_closers: dict[str, int]) -> None:
        self.path = path
        self.pending_closers = pending_closers
        self.diags: list[Diagnostic] = []
        self.fatal: UnexpectedInput | None = None

    def on_error(self, e: UnexpectedInput) -> bool:
        if len(self.diags) >= MAX_ERRORS:
            return False
        if not isinstance(e, UnexpectedToken):
            self.fatal = e
            return False
        tok = e.token
        expected = set(e.expected)
        ip = e.interactive_parser
        if (
            tok.type in _CLOSERS
            and self.pending_closers.get(tok.type, 0) > 0
            and tok.type not in expected
        ):
            self.fatal = e
            return False
        if (
            tok.type in _CLOSERS
            and "SEMI" in expected
            and _find_open(ip.parser_state.value_stack, _CLOSERS[tok.type]) is not None
        ):
            # `x := 2 END_IF`: the statement before an open block's own closer lacks its `;`.
            # (An expression state also "expects" END_REPEAT, from `UNTIL expr END_REPEAT`:
            # that must not be taken for a missing END_REPEAT.)
            self.diags.append(
                diag("S005", f"expected ';' before {_describe(tok)}", self.path, _at(tok))
            )
            ip.feed_token(Token.new_borrow_pos("SEMI", ";", tok))
            ip.feed_token(tok)
            return True
        closers = [c for c in _CLOSERS if c in expected]
        if closers and (tok.type in _CLOSERS or tok.type in ("$END", "END_PROGRAM")):
            closer = closers[0]
            opener = _find_open(ip.parser_state.value_stack, _CLOSERS[closer])
            where = f" for {_CLOSERS[closer]} at line {opener.line}" if opener else ""
            self.diags.append(diag("S002", f"missing {closer}{where}", self.path, _at(tok)))
            ip.feed_token(Token.new_borrow_pos(closer, closer, tok))
            ip.feed_token(Token.new_borrow_pos("SEMI", ";", tok))
            if tok.type != "$END":
                ip.feed_token(tok)
            return True
        if expected == {"SEMI"} or (
            "SEMI" in expected
            and (tok.type in _STMT_START or tok.line > _last_line(ip.parser_state.value_stack))
        ):
            self.diags.append(
                diag("S005", f"expected ';' before {_describe(tok)}", self.path, _at(tok))
            )
            ip.feed_token(Token.new_borrow_pos("SEMI", ";", tok))
            if tok.type != "$END":
                ip.feed_token(tok)
            return True
        self.fatal = e
        return False


_STMT_START = {
    "IF",
    "CASE",
    "FOR",
    "WHILE",
    "REPEAT",
    "EXIT",
    "END_IF",
    "END_CASE",
    "END_FOR",
    "END_WHILE",
    "END_REPEAT",
    "ELSIF",
    "ELSE",
    "UNTIL",
    "END_PROGRAM",
    "$END",
}


def _last_line(stack: list) -> int:
    for item in reversed(stack):
        if isinstance(item, Token) and item.end_line is not None:
            return item.end_line
        span = getattr(item, "span", None)
        if isinstance(span, n.Span):
            return span.end_line
    return 0


def _dimension(text: str) -> int:
    """An array bound; one too long to read counts as too large, for the size limit to report."""
    try:
        return int(parse_number(text)[0])
    except LiteralError:
        return 1 << 64


def _find_open(stack: list, kind: str) -> Token | None:
    for item in reversed(stack):
        if isinstance(item, Token) and item.type == kind:
            return item
    return None


def _at(tok: Token) -> n.Span:
    if tok.line is None:
        return n.Span(1, 1, 1, 1)
    if tok.type == "$END" and tok.end_line is not None and tok.end_column is not None:
        # Lark gives end of input the last token's position; what is missing belongs just
        # after that token (SPEC 9.10: where the parser expected it), so point there.
        return n.Span(tok.end_line, tok.end_column, tok.end_line, tok.end_column + 1)
    return n.Span(
        tok.line, tok.column or 1, tok.end_line or tok.line, tok.end_column or (tok.column or 1) + 1
    )


def _blank(text: str, start: int, end: int) -> str:
    seg = "".join("\n" if ch == "\n" else " " for ch in text[start:end])
    return text[:start] + seg + text[end:]


def _offset(text: str, starts: list[int], line: int, col: int) -> int:
    return min(len(text), starts[line - 1] + col - 1) if line - 1 < len(starts) else len(text)


def parse_st(text: str, path: str, name: str | None = None) -> tuple[n.Routine, list[Diagnostic]]:
    """Parse a `.st` file (or an L5X ST routine's joined lines) into a Routine."""
    stripped = strip_comments(text)
    diags: list[Diagnostic] = [
        diag("S003", "comment is not terminated", path, sp) for sp in stripped.unterminated
    ]
    work = stripped.text
    starts = line_starts(work)
    pending_closers: dict[str, int] = {}
    seen: set[tuple[str, int, int]] = set()
    result = None
    try:
        result = fast_parse(_parser(), work, "start")
        attempts = 0  # well-formed text: no recovery passes needed
    except SlowPath:
        attempts = MAX_ERRORS + 1
    for _ in range(attempts):
        rec = _Recovery(path, pending_closers)
        try:
            result = _parser().parse(work, start="start", on_error=rec.on_error)
        except UnexpectedInput as e:  # noqa: PERF203
            rec.fatal = rec.fatal or e
        for d in rec.diags:
            key = (d.code, d.span.line, d.span.col)
            if key not in seen:
                seen.add(key)
                diags.append(d)
        if rec.fatal is None:
            break
        err = rec.fatal
        if isinstance(err, UnexpectedCharacters):
            off = _offset(work, starts, err.line, err.column)
            ch = work[off] if off < len(work) else ""
            sp = n.Span(err.line, err.column, err.line, err.column + 1)
            code, msg = (
                ("S003", "string is not terminated")
                if ch in "'\""
                else ("S004", f"unexpected character {ch!r}")
            )
            if (code, err.line, err.column) not in seen:
                seen.add((code, err.line, err.column))
                diags.append(diag(code, msg, path, sp))
            end = work.find("\n", off) if ch in "'\"" else off + 1
            work = _blank(work, off, end if end > off else len(work))
            continue
        assert isinstance(err, UnexpectedToken)
        tok = err.token
        if tok.type == "$END":
            key = ("S001", -1, -1)
            if key not in seen:
                diags.append(diag("S001", "unexpected end of file", path, _eof_span(work, starts)))
            break
        off = _offset(work, starts, tok.line, tok.column)  # type: ignore[arg-type]
        if tok.type in _CLOSERS and pending_closers.get(tok.type, 0) > 0:
            # The opener of this block was blanked by an earlier recovery: drop it silently.
            pending_closers[tok.type] -= 1
        else:
            key = ("S001", tok.line, tok.column)  # type: ignore[assignment]
            if key not in seen:
                seen.add(key)  # type: ignore[arg-type]
                diags.append(
                    diag(
                        "S001",
                        f"unexpected {_describe(tok)}, expected {_expected(set(err.expected))}",
                        path,
                        _at(tok),
                    )
                )
        start = _statement_start(work, off)
        semi = work.find(";", off)
        end = len(work) if semi < 0 else semi + 1
        if tok.type == "SEMI":
            end = off + 1
        region = work[start:end].upper()
        for opener, closer in _BLOCKS.items():
            opened = _count_word(region, opener) - _count_word(region, closer)
            if opened > 0:
                pending_closers[closer] = pending_closers.get(closer, 0) + opened
        work = _blank(work, start, end)
    else:
        if attempts:
            result = None
    routine = n.Routine(name or Path(path).stem, "st", path, comments=stripped.comments)
    if result is not None:
        prog_name, (types, decls), body, span = result
        routine.types, routine.decls, routine.body = types, decls, body
        routine.program_name = prog_name
        if span is not None:
            routine.span = span
    return routine, diags


_BOUNDARY = re.compile(
    r";|(?<![A-Za-z0-9_])(END_VAR|END_TYPE|END_STRUCT|THEN|DO|ELSE|REPEAT|OF)(?![A-Za-z0-9_])",
    re.IGNORECASE,
)


def _statement_start(text: str, off: int) -> int:
    """Offset just after the last statement boundary before `off`."""
    lo = max(0, off - 4000)
    start = 0
    for m in _BOUNDARY.finditer(text, lo, off):
        start = m.end()
    return start


def _eof_span(text: str, starts: list[int]) -> n.Span:
    line = len(starts)
    col = len(text) - starts[-1] + 1
    return n.Span(line, col, line, col)


def _count_word(region: str, word: str) -> int:
    return len(re.findall(rf"(?<![A-Z0-9_]){word}(?![A-Z0-9_])", region))
