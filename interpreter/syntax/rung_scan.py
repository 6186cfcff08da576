"""Fast path for ordinary rungs: instructions, branches and their operands, without the LALR parser.

Most rungs of an export are contacts, coils, timers, moves, compares and computes whose
operands are tag references (`Tank[3].Level`, `Motor.Run`, `Flags.5`), numbers, `?`, empty
slots or arithmetic over those. For them this recursive scanner builds exactly the AST that
rll.lark and RllBuilder build (same nodes, same spans) at a fraction of the cost. Anything
else (a string, enumeration text, a qualified name, an L5K `N:`/`RC:` line, any syntax
error) makes it give up with None, and the grammar parses the rung: rll.lark stays the
definition of the language, and tests/ladder/test_rung_scan.py checks both paths agree
(decision 0012).
"""

from __future__ import annotations

import re
from bisect import bisect_left

from . import nodes as n
from .literals import number_or_zero

_BLANKS = re.compile(r"[ \t\r\n\f]*")
_INSTR = re.compile(r"([A-Za-z_][A-Za-z0-9_]*)[ \t\r\n\f]*\(")
_IDENT = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
_DIGITS = re.compile(r"[0-9]+(?![A-Za-z0-9_])")
# INT or REAL without suffix, radix or exponent, the point possibly first (`.5`) or last
# (`5.`) as st.lark's REAL allows; anything longer is left to the grammar.
_NUMBER = re.compile(r"(?:[0-9][0-9_]*(?:\.(?:[0-9][0-9_]*)?)?|\.[0-9][0-9_]*)(?![A-Za-z0-9_.#\[])")
_IDENT_START = frozenset("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz_")
_DIGIT = frozenset("0123456789")
_NUMBER_START = frozenset("0123456789.")
_BLANK = frozenset(" \t\r\n\f")
# A binary operator after blanks; `=>` and `:=` (named call arguments) are left to the grammar.
_BINARY = re.compile(
    r"[ \t\r\n\f]*(<>|<=|>=|=(?!>)|<|>|\+|-|\*(?!\*)|/|&|(?:AND|OR|XOR|MOD)(?![A-Za-z0-9_]))", re.I
)
_PRECEDENCE = {
    "OR": 1,
    "XOR": 2,
    "AND": 3,
    "&": 3,
    "=": 4,
    "<>": 4,
    "<": 5,
    "<=": 5,
    ">": 5,
    ">=": 5,
    "+": 6,
    "-": 6,
    "*": 7,
    "/": 7,
    "MOD": 7,
}
_NOT = re.compile(r"NOT(?![A-Za-z0-9_])", re.I)
_POW = re.compile(r"[ \t\r\n\f]*\*\*")


class _GiveUp(Exception):
    """The rung holds something only the grammar handles."""


class _Scanner:
    __slots__ = ("text", "end", "i", "line", "col", "newlines", "plain_name")

    def __init__(self, text: str, line: int, col: int, plain_name: re.Pattern[str]) -> None:
        self.text = text
        self.end = len(text)
        self.i = 0
        self.line, self.col = line, col
        self.plain_name = plain_name
        # L5X <Text> holds the rung between newlines: when the rung itself is on one line,
        # positions are a fixed offset from that line's start (col = self.col + offset).
        lead = _BLANKS.match(text).end()  # type: ignore[union-attr]
        if text.find("\n", lead, len(text.rstrip(" \t\r\n\f"))) < 0:
            self.newlines = None
            nl = text.rfind("\n", 0, lead)
            if nl >= 0:
                self.line, self.col = line + text.count("\n", 0, lead), -nl
        else:
            self.newlines = [k for k, ch in enumerate(text) if ch == "\n"]

    # ------------------------------------------------------------ positions
    def at(self, off: int) -> tuple[int, int]:
        """File (line, column) of text offset `off`, as lark counts them."""
        if self.newlines is None:
            return self.line, self.col + off
        k = bisect_left(self.newlines, off)  # newlines before off
        if k == 0:
            return self.line, self.col + off
        return self.line + k, off - self.newlines[k - 1]

    def span(self, a: int, b: int) -> n.Span:
        if self.newlines is None:  # the usual one-line rung, without the general arithmetic
            line, col = self.line, self.col
            return n.Span(line, col + a, line, col + b)
        return n.Span(*self.at(a), *self.at(b))

    def skip(self) -> str:
        """Skip blanks; the character there ('' at the end)."""
        i = self.i
        if i >= self.end:
            return ""
        ch = self.text[i]
        if ch not in _BLANK:  # exports rarely put blanks between tokens
            return ch
        self.i = i = _BLANKS.match(self.text, i).end()  # type: ignore[union-attr]
        return self.text[i] if i < self.end else ""

    # ------------------------------------------------------------ rung structure
    def rung(self) -> n.Rung:
        elements = self.elements()
        last: n.Span | None = elements[-1].span if elements else None
        if self.skip() == ";":
            last = self.span(self.i, self.i + 1)
            self.i += 1
            self.skip()
        if self.i != self.end:
            raise _GiveUp
        if last is None:
            return n.Rung([], n.NOWHERE)
        first = elements[0].span if elements else last
        return n.Rung(elements, first.to(last))

    def elements(self) -> list[n.LadderElement]:
        out: list[n.LadderElement] = []
        while True:
            ch = self.skip()
            if ch == "[":
                out.append(self.branch())
            elif ch in _IDENT_START:
                out.append(self.instr())
            else:
                return out

    def branch(self) -> n.Branch:
        start = self.i
        self.i += 1
        legs = [self.elements()]
        while True:
            ch = self.skip()
            self.i += 1
            if ch == ",":
                legs.append(self.elements())
            elif ch == "]":
                return n.Branch(legs, self.span(start, self.i))
            else:
                raise _GiveUp

    def instr(self) -> n.LadderInstr:
        start = self.i
        m = _INSTR.match(self.text, start)
        if m is None:
            raise _GiveUp
        name = m.group(1)
        before = m.end() - 1  # the separator in front of the current slot: '(' then each ','
        self.i = m.end()
        operands: list[n.Expr] = []
        empty = False  # met an empty slot (its placeholder spans the separators around it)
        while True:
            ch = self.skip()
            if ch in ",)" and ch:
                operands.append(n.Placeholder(self.span(before, self.i + 1)))
                empty = True
            else:
                operands.append(self.operand(ch))
                ch = self.skip()
            self.i += 1
            if ch == ",":
                before = self.i - 1
            elif ch == ")":
                break
            else:
                raise _GiveUp
        if len(operands) == 1 and empty:  # `NOP()`: no operands at all
            operands = []
        return n.LadderInstr(
            name, operands, self.span(start, self.i), self.span(start, start + len(name))
        )

    # ------------------------------------------------------------ operands
    def operand(self, ch: str) -> n.Expr:
        if ch == "?":
            self.i += 1
            return n.Placeholder(self.span(self.i - 1, self.i))
        if ch in _IDENT_START or ch in _NUMBER_START:  # most operands: one tag or one number
            start = self.i
            try:
                node = self.reference() if ch in _IDENT_START else self.number()
                if self.i < self.end and self.text[self.i] in ",)":
                    return node
            except _GiveUp:  # `NOT a`, `TRUE` ...: the expression reader decides
                pass
            self.i = start  # more follows: read it again as an expression
        return self.expr(0)

    # Expressions by precedence climbing over st.lark's levels: OR < XOR < AND/& < = <> <
    # < <= > >= < + - < * / MOD, all left-associative; then NOT, unary - and +, ** and primaries.
    def expr(self, min_prec: int) -> n.Expr:
        left = self.not_expr()
        while True:
            m = _BINARY.match(self.text, self.i)
            if m is None:
                return left
            op = m.group(1).upper()
            prec = _PRECEDENCE[op]
            if prec < min_prec:
                return left
            self.i = m.end()
            right = self.expr(prec + 1)
            left = n.Binary("AND" if op == "&" else op, left, right, left.span.to(right.span))

    def not_expr(self) -> n.Expr:
        self.skip()
        start = self.i
        m = _NOT.match(self.text, start)
        if m is None:
            return self.neg_expr()
        self.i = m.end()
        operand = self.not_expr()
        return n.Unary("NOT", operand, self.span(start, start).to(operand.span))

    def neg_expr(self) -> n.Expr:
        ch = self.skip()
        if ch == "-":
            start = self.i
            self.i += 1
            operand = self.neg_expr()
            return n.Unary("-", operand, self.span(start, start).to(operand.span))
        if ch == "+":  # unary plus: the operand itself, as the grammar's unary_plus
            self.i += 1
            return self.neg_expr()
        left = self.primary()
        while True:
            m = _POW.match(self.text, self.i)
            if m is None:
                return left
            self.i = m.end()
            if self.skip() == "-":  # `a ** -b`: only a primary may follow the minus
                start = self.i
                self.i += 1
                self.skip()
                operand = self.primary()
                right: n.Expr = n.Unary("-", operand, self.span(start, start).to(operand.span))
            else:
                right = self.primary()
            left = n.Binary("**", left, right, left.span.to(right.span))

    def primary(self) -> n.Expr:
        ch = self.skip()
        if ch == "(":  # parentheses leave no node and no span of their own
            self.i += 1
            inner = self.expr(0)
            if self.skip() != ")":
                raise _GiveUp
            self.i += 1
            return inner
        if ch in _NUMBER_START and ch:  # `.5` here is a number: no operand precedes it
            return self.number()
        return self.reference()

    def number(self) -> n.Literal:
        m = _NUMBER.match(self.text, self.i)
        if m is None:
            raise _GiveUp
        text = m.group()
        value, typ = number_or_zero(text)  # a refused literal: the checker reports it
        node = n.Literal(value, typ, text, self.span(self.i, m.end()))
        self.i = m.end()
        return node

    def reference(self) -> n.Expr:
        """A tag reference: name, then `.member`, `.bit` and `[index, ...]` in any order."""
        text, start = self.text, self.i
        m = self.plain_name.match(text, start)
        if m is None or (m.end() < self.end and text[m.end()] in ":\\"):
            raise _GiveUp  # reserved word, qualified name, not a name at all
        name = n.Name(m.group(), self.span(start, m.end()))
        self.i = j = m.end()
        nxt = text[j] if j < self.end else ""
        if nxt == "(" or (nxt in _BLANK and nxt and self.skip() == "("):  # a call (`ABS(x)` in CPT)
            return self.call(name)
        self.i = j
        node: n.Expr = name
        first = name.span[:2]
        while self.i < self.end:
            ch = text[self.i]
            if ch == ".":
                nxt = text[self.i + 1 : self.i + 2]
                if nxt in _DIGIT and nxt:
                    d = _DIGITS.match(text, self.i + 1)
                    if d is None:
                        raise _GiveUp
                    node = n.Bit(node, int(d.group()), n.Span(*first, *self.at(d.end())))
                    self.i = d.end()
                    continue
                w = _IDENT.match(text, self.i + 1)
                if w is None:
                    raise _GiveUp  # `.[x]` indirect bit and the like
                name_span = self.span(w.start(), w.end())
                node = n.Member(
                    node,
                    w.group(),
                    n.Span(*first, name_span.end_line, name_span.end_col),
                    name_span,
                )
                self.i = w.end()
            elif ch == "[":
                self.i += 1
                indices: list[n.Expr] = []
                while True:
                    indices.append(self.expr(0))
                    c = self.skip()
                    self.i += 1
                    if c == "]":
                        break
                    if c != ",":
                        raise _GiveUp
                end = indices[-1].span
                node = n.Index(node, indices, n.Span(*first, end.end_line, end.end_col))
            else:
                break
        return node

    def call(self, name: n.Name) -> n.Call:
        """`NAME(arg, ...)` with positional arguments; its span ends with the last argument."""
        self.i += 1
        args: list[n.Arg] = []
        if self.skip() != ")":
            while True:
                value = self.expr(0)
                args.append(n.Arg(value, None, value.span))
                ch = self.skip()
                if ch == ")":
                    break
                if ch != ",":
                    raise _GiveUp  # `:=` and `=>` arguments, errors
                self.i += 1
        self.i += 1
        end = args[-1].span if args else name.span
        return n.Call(name.ident, args, name.span.to(end), name.span)


def scan_rung(text: str, line: int, col: int, plain_name: re.Pattern[str]) -> n.Rung | None:
    """The rung in `text` (text[0] at file position line:col), or None when the grammar must parse it.

    `plain_name` is the grammar's NAME terminal: it refuses reserved words, which the grammar
    reads as literals or operators.
    """
    try:
        return _Scanner(text, line, col, plain_name).rung()
    except (
        _GiveUp,
        IndexError,
        RecursionError,
    ):  # deep nesting too: the LALR parser has no stack limit
        return None
