"""Grammar coverage: every rule and alias of st.lark and rll.lark is exercised and handled (DESIGN: tests).

The corpus below is parsed twice:
- by a plain Lark parser built from a rewritten copy of st.lark, in which no rule is inlined
  (`?` removed) and every alias is prefixed with its rule (`-> or_expr__binary`), so the
  tree shows exactly which rules and which aliased alternatives were reduced;
- by the real front end (`parse_st` with AstBuilder), which must report no syntax error and
  leave no lark Tree in the AST.
Every rule and alias must occur, and each must have an AstBuilder method or be an inlined
`?rule` (whose single child passes through). rll.lark gets the same treatment with
RllBuilder; the ST expression rules it imports are covered by the ST corpus.
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from functools import cache
from pathlib import Path

import pytest
from lark import Lark, Token, Tree

from interpreter.syntax import nodes, st_parser
from interpreter.syntax.rll_parser import RllBuilder, parse_rll, parse_rung
from interpreter.syntax.st_parser import AstBuilder, parse_st

GRAMMAR = Path(st_parser.__file__).with_name("st.lark")
RLL_GRAMMAR = GRAMMAR.with_name("rll.lark")

CORPUS: dict[str, str] = {
    "program_unit": """
        PROGRAM Mixer
        VAR x : DINT; END_VAR
        x := 1;
        END_PROGRAM;
    """,
    "types_and_declarations": """
        TYPE
          Pt : STRUCT
            x, y : REAL := 0.5;
            tag : DINT;
          END_STRUCT;
          Empty : STRUCT END_STRUCT
        END_TYPE;
        VAR RETAIN
          a, b : DINT;
          r : REAL := -1.5;
          arr : ARRAY[0..9] OF DINT := [1, 2, 3, 4, 5, 6, 7, 8, 9, 10,];
          neg : ARRAY[-1..1, 0..2] OF BOOL;
          m : DINT[3,4];
          s : STRING := 'hi$N';
          t : FBD_TIMER := (PRE := 500, Reset := FALSE,);
          pts : Pt[2] := [(x := 1.0, y := 2.0), (x := 3.0)];
          nested : ARRAY[0..1] OF ARRAY[0..2] OF INT;
        END_VAR
        VAR CONSTANT k : DINT := 16#FF; END_VAR
        VAR NON_RETAIN flag : BOOL; END_VAR
        VAR_INPUT in1 : BOOL; END_VAR
    """,
    "statements": """
        a := 1;
        a [:=] 0;
        ;
        TONR(t);
        COP(arr[0], m[0,0], 4);
        SIZE();
        camIn(Master := X, Slave := Y, Execute := TRUE, InSync => ok);
        IF a > 0 THEN
          a := 0;
        ELSIF a < -5 THEN
          a := 1;
        ELSIF a = 3 THEN
          a := 2;
        ELSE
          a := 3;
        END_IF;
        CASE a OF
          1: a := 2;
          2, 3, 7..9: a := 0;
          -4..-1, 16#10, 2#101, 1.5: ;
          Idle: a := 1;
        ELSE
          a := 5;
        END_CASE;
        FOR i := 0 TO 9 BY 2 DO
          EXIT;
        END_FOR;
        FOR i := 9 TO 0 DO END_FOR;
        WHILE a < 10 DO
          a := a + 1;
        END_WHILE;
        REPEAT
          a := a - 1;
        UNTIL a <= 0
        END_REPEAT;
        RETURN;
        GOTO lbl;
    """,
    "expressions": """
        b := a OR b XOR c AND d & e;
        b := a = 1 AND a <> 2 OR a < 1 OR a <= 1 OR a > 1 OR a >= 1;
        x := a + b - c * d / e MOD f;
        x := -a ** -2 + 2 ** 3 ** 2;
        b := NOT NOT b;
        x := +a - -b;
        x := ((a));
        x := ABS(a) + SQRT(2.0) + TRUNC(-1.5e3);
        x := s.Member.Sub + arr[i + 1] + m[1, 2] + cube[1, 2, 3];
        b := d.5 OR d.[i + 1] OR arr[2].3;
        x := Local:1:I.Data + Local:2:O.Data.3;
        x := \\Other.Param + \\Other.Arr[1].AND;
        MAM(ax, mc, 0, 10.0, 5.0, %ofMaximum, 100.0, Unitspersec2, 100.0, %ofMaximum, S-Curve);
        GSV(WallClockTime,,LocalDateTime,dt[0]);
        NOP();
        x := 1 + 1U + 2L + 3UL + 1_000 + 8#17 + 16#FF_FF + 2#1010_1010L + 1.25 + 1e6;
        s := 'it$'s' + "double";
        b := TRUE AND FALSE;
    """,
}

# The expression entry point (`--watch`, `--set`) is a second start symbol.
EXPRESSIONS = ["Axis1.ActualPosition", "arr[2]", "d.5", "-1.5", "a + b * 2"]


def _unlined_grammar(path: Path = GRAMMAR) -> str:
    """A grammar with no `?` inlining and every alias prefixed by its rule: `-> rule__alias`."""
    out = []
    current: str | None = None
    for line in path.read_text().splitlines():
        rule = re.match(r"^\??([a-z_][a-z0-9_]*)\s*:", line)
        if rule:
            current = rule.group(1)
            line = line.lstrip("?")
        elif re.match(r"^[A-Z_][A-Z0-9_]*(\.\d+)?\s*:", line) or line.startswith("%"):
            current = None
        if current is not None and not line.lstrip().startswith("//"):
            line = re.sub(r"->\s*([a-z_][a-z0-9_]*)", rf"-> {current}__\1", line)
        out.append(line)
    return "\n".join(out)


@cache
def _plain() -> Lark:
    return Lark(
        _unlined_grammar(),
        parser="lalr",
        lexer="contextual",
        maybe_placeholders=True,
        start=["start", "expr"],
    )


def _inlined_rules(path: Path = GRAMMAR) -> set[str]:
    return {m.group(1) for m in re.finditer(r"^\?([a-z_][a-z0-9_]*)\s*:", path.read_text(), re.M)}


def _grammar_names() -> set[str]:
    """Every rule (`name`) and aliased alternative (`rule__alias`) the grammar can produce."""
    return {
        str(r.alias or r.origin.name)
        for r in _plain().rules
        if not str(r.origin.name).startswith("_")
    }


def _tree_names(tree: Tree) -> Iterator[str]:
    for sub in tree.iter_subtrees():
        if not str(sub.data).startswith("_"):
            yield str(sub.data)


def _observed() -> set[str]:
    seen: set[str] = set()
    for text in CORPUS.values():
        seen.update(_tree_names(_plain().parse(_strip(text), start="start")))
    for text in EXPRESSIONS:
        seen.update(_tree_names(_plain().parse(text, start="expr")))
    return seen


def _strip(text: str) -> str:
    from interpreter.syntax.comments import strip_comments

    return strip_comments(text).text


def test_every_rule_and_alias_is_exercised() -> None:
    missing = sorted(_grammar_names() - _observed())
    assert not missing, f"grammar rules/aliases no corpus snippet reaches: {missing}"


def test_every_rule_and_alias_is_handled_by_the_ast_builder() -> None:
    inlined = _inlined_rules()
    unhandled = []
    for name in sorted(_grammar_names()):
        rule, _, alias = name.partition("__")
        if alias:
            ok = callable(getattr(AstBuilder, alias, None))
        else:
            ok = rule in inlined or callable(getattr(AstBuilder, rule, None))
        if not ok:
            unhandled.append(name)
    assert not unhandled, (
        f"rules/aliases without an AstBuilder method (and not ?inlined): {unhandled}"
    )


def _no_lark_objects(value: object, where: str) -> None:
    if isinstance(value, Tree):
        raise AssertionError(f"lark Tree '{value.data}' left in the AST at {where}")
    if isinstance(value, Token):
        raise AssertionError(f"lark Token {value.type} left in the AST at {where}")
    if isinstance(value, list | tuple):
        for i, v in enumerate(value):
            _no_lark_objects(v, f"{where}[{i}]")
    elif hasattr(value, "__dataclass_fields__"):
        for f in value.__dataclass_fields__:  # type: ignore[attr-defined]
            _no_lark_objects(getattr(value, f), f"{where}.{f}")


@pytest.mark.parametrize("name", list(CORPUS))
def test_corpus_parses_cleanly_into_a_pure_ast(name: str) -> None:
    routine, diags = parse_st(CORPUS[name], f"{name}.st")
    assert not diags, [d.text() for d in diags]
    assert routine.body or routine.decls or routine.types
    for part in ("types", "decls", "body"):
        _no_lark_objects(getattr(routine, part), part)


@pytest.mark.parametrize("text", EXPRESSIONS)
def test_expression_entry_point(text: str) -> None:
    _no_lark_objects(st_parser.parse_expression(text), text)


def test_rewritten_grammar_has_the_same_rules() -> None:
    # The rewrite must only remove inlining and rename aliases, never drop a rule.
    original = {
        m.group(1) for m in re.finditer(r"^[?!]?([a-z_][a-z0-9_]*)\s*:", GRAMMAR.read_text(), re.M)
    }
    plain_rules = {
        str(r.origin.name) for r in _plain().rules if not str(r.origin.name).startswith("_")
    }
    assert plain_rules == original


def test_program_scope_reference_parses() -> None:
    # SPEC 9.9 watches program-scope tags as Program:Name.Tag
    e = st_parser.parse_expression("Program:Main.Tag")
    assert isinstance(e, nodes.Member) and isinstance(e.base, nodes.Name)
    assert (e.base.ident, e.name) == ("Program:Main", "Tag")


# ------------------------------------------------------------------ rll.lark
RLL_CORPUS: dict[str, str] = {
    "plain": "XIC(a)XIO(b)OTE(c);",
    "numbered": "N: [XIC(a),[XIC(b),],]OTE(c);",
    "comment": 'RC: "one; two" "three";',
    "operands": "TON(t,?,?)GSV(WallClockTime,,LocalDateTime,d)MAM(ax,mc,0,1.0,Units per sec)NOP();",
    "expressions": "CMP(a+b>c)CPT(d,ABS(x)*2);",
    "empty": ";",
}
RLL_RUNGS = ["XIC(a)OTE(b)", "[,XIC(a)]OTE(b);"]


@cache
def _rll_plain() -> Lark:
    return Lark(
        _unlined_grammar(RLL_GRAMMAR),
        parser="lalr",
        lexer="contextual",
        maybe_placeholders=True,
        start=["rung_line", "rung_only"],
        source_path=str(RLL_GRAMMAR),
        import_paths=[str(RLL_GRAMMAR.parent)],
    )


def _rll_imported() -> set[str]:
    m = re.search(r"^%import \.st \(([^)]*)\)", RLL_GRAMMAR.read_text(), re.M)
    assert m is not None
    return {x.strip() for x in m.group(1).split(",")}


def _rll_grammar_names() -> set[str]:
    """Rules and aliases rll.lark itself defines (imported ST rules arrive as `st__...`)."""
    names = {str(r.alias or r.origin.name) for r in _rll_plain().rules}
    return {x for x in names if not x.startswith(("_", "st__")) and x not in _rll_imported()}


def test_every_rll_rule_and_alias_is_exercised() -> None:
    seen: set[str] = set()
    for text in RLL_CORPUS.values():
        seen.update(_tree_names(_rll_plain().parse(text, start="rung_line")))
    for text in RLL_RUNGS:
        seen.update(_tree_names(_rll_plain().parse(text, start="rung_only")))
    missing = sorted(_rll_grammar_names() - seen)
    assert not missing, f"rll.lark rules/aliases no corpus line reaches: {missing}"


def test_every_rll_rule_and_alias_is_handled_by_the_builder() -> None:
    inlined = _inlined_rules(RLL_GRAMMAR)
    unhandled = []
    for name in sorted(_rll_grammar_names()):
        rule, _, alias = name.partition("__")
        target = alias or rule
        if not (rule in inlined and not alias) and not callable(getattr(RllBuilder, target, None)):
            unhandled.append(name)
    assert not unhandled, f"rll.lark rules/aliases without an RllBuilder method: {unhandled}"


def test_rll_corpus_parses_cleanly_into_a_pure_ast() -> None:
    routine, diags = parse_rll("\n".join(RLL_CORPUS.values()) + "\n", "corpus.rll")
    assert not diags, [d.text() for d in diags]
    assert len(routine.rungs) == len(RLL_CORPUS) - 1  # the RC: line is a comment
    _no_lark_objects(routine.rungs, "rungs")
    for text in RLL_RUNGS:
        rung, diags = parse_rung(text, "r.L5X", 0)
        assert not diags
        _no_lark_objects(rung, text)


def test_rll_imports_only_what_st_lark_defines() -> None:
    # the shared expression grammar must stay importable: each imported name exists in st.lark
    defined = {
        m.group(1)
        for m in re.finditer(r"^\??([A-Za-z_][A-Za-z0-9_]*)(\.\d+)?\s*:", GRAMMAR.read_text(), re.M)
    }
    assert _rll_imported() <= defined
