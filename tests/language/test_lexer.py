"""The fast ST lexer and LALR driver (interpreter/syntax/st_lexer.py) against lark's own.

The oracle is lark's contextual lexer and parser on the same grammar: both must build
identical ASTs. The context-dependent token choices are tested one by one.
"""

from __future__ import annotations

import sys
from pathlib import Path

import pytest
from lark import Lark

from interpreter.syntax import nodes as n
from interpreter.syntax.st_lexer import SlowPath, fast_parse
from interpreter.syntax.st_parser import AstBuilder, _parser, parse_st

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tests" / "benchmarks"))
from bench_parse import program  # noqa: E402


def lark_reference() -> Lark:
    grammar = (ROOT / "interpreter" / "syntax" / "st.lark").read_text()
    return Lark(
        grammar,
        parser="lalr",
        lexer="contextual",
        transformer=AstBuilder(),
        maybe_placeholders=True,
        start=["start", "expr"],
    )


SNIPPETS = {
    # A declaration without spaces: `a:DINT` is a name then ':' (QNAME is not expected there).
    "decl_no_spaces": "VAR a:DINT; b:REAL:=1.5; END_VAR a := 1;",
    # RETAIN/CONSTANT are keywords only in a VAR header; elsewhere they are tag names.
    "soft_keyword": "VAR RETAIN a : DINT; END_VAR retain := 5; constant := TRUE;",
    # `step:` inside CASE is a label; `x : REAL` in VAR is a declaration.
    "case_label": "VAR x : REAL; s : DINT; idle : DINT := 0; END_VAR\n"
    "CASE s OF idle: x := 1.0; 1..3 : x := 2.0; END_CASE;",
    # Qualified names where a name is expected.
    "qualified": "VAR ok : BOOL; END_VAR ok := S:FS; Program:Main.ok := ok;",
    "radix_real": "VAR a : DINT; r : REAL; END_VAR a := 16#FF_FF + 2#1010 + 8#17 + 10U; r := 1.5e3 + 2.0;",
    "operators": "VAR a, b : DINT; c : BOOL; END_VAR c := a <= b OR a >= b AND a <> b; a := -2 ** 2 MOD 3;",
    "enum_text": "VAR m : MOTION_INSTRUCTION; END_VAR MAJ(ax, m, 0, 1.0, %ofTime, 1, Unitspersec2);",
    # After '.', reserved words are member names (UDT members AND, MOD, Array in real exports).
    "program_parameter": "\\Other.Flag := \\Other.In.OR AND NOT \\P2.x[1];",
    # Empty operands in an instruction call statement (the checker decides where they are allowed).
    "empty_operands": "VAR dt : DINT[7]; END_VAR GSV(WallClockTime,,LocalDateTime,dt[0]);\n"
    "SSV( WallClockTime , , LocalDateTime , dt[0] ); NOP(); COP(dt[0],,1); f(,); g(a := 1,);",
    # REALs with the point first or last; `.` after an operand stays member or bit access.
    "real_points": "VAR q : ARRAY[0..5] OF REAL; END_VAR a [:=] .5; b := 5. * -.25e1 + d.5;"
    "c := a.b.3 + d.[i] + v[1].2 + f(.5, 1.); CASE k OF 1..5, -.5..-.25: x := .1; END_CASE;",
    # IEC header words are keywords only in the header: tags `array`, GSV class `Program`.
    "soft_header_words": "TYPE T : STRUCT x : DINT; END_STRUCT END_TYPE VAR a : ARRAY[0..1] OF T;"
    " array : DINT[3]; END_VAR array[1] := a[0].x + type + struct; GSV(Program, THIS, LastScanTime, t);",
    # PROGRAM and TYPE open a unit or block only before a name; else they are tags.
    "type_program_tags": "type.a := 4; program := type.b; type[1] := program;",
    "type_after_header": "TYPE END_TYPE VAR x : DINT; END_VAR type := x; program.x := 1;",
    "program_unit": "PROGRAM Main\nTYPE P : STRUCT a : DINT; END_STRUCT END_TYPE VAR q : P; END_VAR q.a := 1; END_PROGRAM",
    # VAR words are tags outside a header; VAR opens a block only before a name.
    "var_words_as_tags": "VAR v : REAL; END_VAR Var := v; var_in := var + 1; var_temp[0] := Var;",
    "keyword_members": "m.AND := m.or + m.Mod MOD 2; m.Array[m.NOT] := Local:1:I.Data; IF m.THEN THEN m.end_if := 1; END_IF;",
}


@pytest.mark.parametrize("name", sorted(SNIPPETS))
def test_fast_parse_matches_lark(name: str) -> None:
    text = SNIPPETS[name]
    assert fast_parse(_parser(), text, "start") == lark_reference().parse(text, start="start")


def test_fast_parse_matches_lark_on_samples_and_generated_program() -> None:
    texts = [p.read_text() for p in sorted((ROOT / "samples").glob("*.st"))]
    texts += [p.read_text() for p in sorted((ROOT / "tests" / "golden").glob("*/*.st"))]
    texts.append(program(600))
    ref = lark_reference()
    from interpreter.syntax.comments import strip_comments

    for text in texts:
        work = strip_comments(text).text
        assert fast_parse(_parser(), work, "start") == ref.parse(work, start="start")


def test_token_positions_are_one_based_and_exact() -> None:
    routine, diags = parse_st("VAR\n  abc : DINT;\nEND_VAR\n  abc :=  16#1F;\n", "p.st")
    assert diags == []
    stmt = routine.body[0]
    assert isinstance(stmt, n.Assign)
    assert stmt.target.span == n.Span(4, 3, 4, 6)  # `abc` at line 4, columns 3..5
    assert stmt.value.span == n.Span(4, 11, 4, 16)  # `16#1F`: 2 + 3 + 1 + 2 + 2 spaces -> col 11


@pytest.mark.parametrize(
    "bad", ["VAR a : DINT; END_VAR a := 1 @ 2;", "VAR a : DINT; END_VAR a := 1", "x := 'open"]
)
def test_errors_take_the_slow_path_with_recovery(bad: str) -> None:
    with pytest.raises(SlowPath):
        fast_parse(_parser(), bad, "start")
    _, diags = parse_st(bad, "bad.st")
    assert diags and all(d.code.startswith("S") for d in diags)


@pytest.mark.parametrize("text", ["a := AND;", "a := b.;", "a := OR.x;"])
def test_reserved_words_stay_reserved_outside_member_position(text: str) -> None:
    _, diags = parse_st(text, "kw.st")
    assert [d.code for d in diags] == ["S001"], [d.text() for d in diags]


def test_recovery_resumes_after_the_error_not_at_the_start() -> None:
    # lark calls the lexer again after an error handler inserts the missing ';': lexing must
    # continue after END_VAR's position, so exactly one S005 and nothing else is reported.
    _, diags = parse_st("VAR\n  a : DINT\nEND_VAR\na := 1;\nb := a\n;", "semi.st")
    assert [(d.code, d.span.line) for d in diags] == [("S005", 3)]


RUNGS = [
    "XIC(a)XIO(b)OTE(c);",
    "[XIC(a) ,XIC(b) [XIO(c),,XIC(d.5)] ]OTE(e);",
    "TON(T,?,?)MOV(16#FF,d)CPT(r,r*2.0+v[i+1]/4.0)CMP(a+b>c);",
    "GSV(WallClockTime,,LocalDateTime,dt[0])XIC(Local:1:I.Data.3)OTE(S:FS);",
    "MAJ(ax,m,0,1.0,Units per sec,1.0,Units per sec2,S-Curve,100.0,100.0,% of Maximum);",
    "XIC(x.[idx.y])OTE(z);",
    "XIC(\\CM_HMI.HMI.Use.Bool[126])MOV(\\P.x,\\Q.y.AND);",
    "AND(Move.A,Move.B,Move.AND)NOT(a.NOT,b.Array[1])MOD(x.MOD,2,y.mod)XIC(s.TO);",
]


@pytest.mark.parametrize("text", RUNGS)
def test_rung_fast_path_matches_lark(text: str) -> None:
    from interpreter.syntax import rll_parser as rp
    from interpreter.syntax.st_lexer import contextual_tokens

    parser = rp._parser()
    origin = rp._Origin(7, 12)  # the rung text starts at line 7, column 12 of its file
    slow = parser.parse(text, start="rung_only")
    rp._shift(slow, origin)
    fast = fast_parse(
        parser, text, "rung_only", lambda state: contextual_tokens(parser, text, state, 7, 12)
    )
    assert fast == slow


def test_rung_fast_path_matches_lark_on_a_generated_export() -> None:
    import re

    from interpreter.syntax import rll_parser as rp
    from interpreter.syntax.st_lexer import contextual_tokens

    sys.path.insert(0, str(ROOT / "tests" / "benchmarks"))
    from bench_l5x import export

    parser = rp._parser()
    texts = re.findall(r"<Text>\n<!\[CDATA\[(.*?)\]\]>", export(400_000))
    assert len(texts) > 100
    for text in texts:
        slow = parser.parse(text, start="rung_only")
        rp._shift(slow, rp._Origin(1, 1))
        assert (
            fast_parse(parser, text, "rung_only", lambda s, t=text: contextual_tokens(parser, t, s))
            == slow
        )


def test_grammar_cache_file_changes_with_any_grammar_file(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # rll.lark imports st.lark: editing either must give both parsers a fresh cache file.
    import shutil

    from interpreter.syntax import st_parser

    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    fake = tmp_path / "syntax"
    fake.mkdir()
    for g in (ROOT / "interpreter" / "syntax").glob("*.lark"):
        shutil.copy(g, fake / g.name)
    monkeypatch.setattr(st_parser, "__file__", str(fake / "st_parser.py"))
    before = st_parser.grammar_cache("rll")
    (fake / "st.lark").write_text((fake / "st.lark").read_text() + "\n// edited\n")
    after = st_parser.grammar_cache("rll")
    assert isinstance(before, str) and isinstance(after, str) and before != after
