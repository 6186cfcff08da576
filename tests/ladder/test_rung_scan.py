"""The fast rung scanner (rung_scan.py) against the grammar (rll.lark through the LALR tables).

The scanner must build exactly the AST the grammar builds, spans included, or give up. Each
text is compared both at the start of a file and at an offset origin (line 7, column 5), so
the position arithmetic is exercised on one-line and multi-line rungs.
"""

from __future__ import annotations

import os
import random
import re
import sys
from pathlib import Path

import pytest

from interpreter.syntax import nodes as n
from interpreter.syntax.rll_parser import _parser, _plain_name
from interpreter.syntax.rung_scan import scan_rung
from interpreter.syntax.st_lexer import SlowPath, contextual_tokens, fast_parse

ROOT = Path(__file__).resolve().parents[2]

# Texts the scanner must take on itself: the everyday shapes of exported rungs.
SCANNED = [
    "XIC(a)OTE(b);",
    "XIC(a)OTE(b)",
    ";",
    "  ;  ",
    "NOP();",
    "XIC( )OTE(b);",
    "[XIC(a) ,XIC(b) ]XIO(c)OTE(d);",
    "[XIC(a),[XIC(b),[XIC(c),XIO(d)]]]OTE(e);",  # nested three deep
    "[XIC(a),]OTE(b);",  # empty leg (a shorted branch)
    "[,XIC(a)]OTE(b);",
    "[XIC(a)];",
    "TON(T1,?,?);",
    "TON(Timers[3],1000,0);",
    "GSV(WallClockTime,,LocalDateTime,Dest[0]);",  # empty operand between separators
    "MOV(,x);",
    "MOV(x,);",
    "MOV(,);",
    "MOV(-1,x);",
    "MOV(-2.5,x)MOV(1_000,y);",
    "MOV(50.0,R)MOV(0,V[1,2,3]);",
    "XIC(a.b.3)OTE(v[1,i].x);",
    "XIC(Flags.31)OTE(Tank[i].Valve[j].Open);",
    "XIC(Tank[Idx[2]].Run)OTE(b);",
    "XIC(Move.AND)OTE(Move.Array);",  # members may be reserved words
    "NOT(a,b)AND(a,b,c)MOD(a,b,c);",  # instruction names may be reserved words
    "XIC ( a ) OTE ( b ) ;",
    "XIC(a)\n  OTE(b);",
    "\n  XIC(a)OTE(b);\n",  # as an L5X <Text> holds it: the rung alone on its line
    "\r\n\r\n\tXIC(a)OTE(b)\r\n  ",
    "[XIC(a)\r\n ,XIC(b)\n]\n OTE(c)\n;",
    "MSO(Axis1,MSO_1)MAM(Axis1,MAM_1,0,100.0,50,Units_per_sec,10,Units_per_sec2,10,Units_per_sec2,Trapezoidal,100,100,Units_per_sec3,0,0);",
    "CTU(C[2],?,?)RES(C[2]);",
    "XIC(_underscore)OTE(x9);",
    "JSR(Sub,0);",
    # expressions (CMP, CPT, FAL, FSC operands and computed subscripts)
    "CPT(R,R*2.0+V[1]/4.0);",
    "CMP(a>b)OTE(c);",
    "CMP(a >= b AND NOT c OR d XOR e & f)OTE(g);",
    "CPT(x,-2**2)CPT(y,a**-b**c)CPT(z,+a - -b);",
    "CPT(x,(a + b) * (c - d) / e MOD f);",
    "CMP(a = b < c)CMP(a <> b)CMP(a <= b)CMP(a < b < c);",
    "CPT(x,ABS(a - b) + SQR(c) + f())CPT(y,ATN(a, b));",
    "CPT(x,ABS (a));",
    "CPT(x, NOT NOT a)CPT(y,NOT -a);",
    "MOV(v[i+1],x)MOV(v[-1],x)MOV(v[w[1] * 2, j],x);",
    "MAM(Axis1,MAM_1,0,100.0,S-Curve);",  # one-word enumeration text stays an expression
    "CPT(x,a.b.3 + Tank[i].Level * 1_000);",
    "CPT(x,a and b or c mod d);",
    "CPT(x,a AND(b))CPT(x,a mod(b));",
    # REALs with the point first or last, as Studio 5000 accepts them (issue 9)
    "MOV(.25,r)MOV(1.,x)MOV(-.5,y)MOV(-5.,z);",
    "CPT(x,y*.6)CPT(x,.5+2.*a.5)CPT(x,d.5-.5)CPT(x,v[1].3*.1);",
    "CPT(x,(5.)/(.5))CPT(x,f(.5,1.));",
    # IEC declaration words are not Logix keywords: names in a rung (real exports)
    "GSV(PROGRAM,THIS,LASTSCANTIME,t)SIZE(array[0],0,n)MOV(Type.Struct,end_type);",
]

# Texts only the grammar reads: the scanner must give up (and the grammar then parses them).
GIVEN_UP = [
    "EQU(s,'a;b$'c');",
    "XIC(S:FS)OTE(b);",
    "XIC(Local:1:I.Data.3)OTE(b);",
    "XIC(\\Other.Flag)OTE(b);",
    "XIC(TRUE)OTE(b);",
    "MAM(Axis1,MAM_1,0,100.0,50,Units per sec,10,Units per sec2);",
    "PID(% of Maximum);",
    "XIC(a.[b])OTE(c);",
    "MOV(16#FF,x);",
    "MOV(5UL,x);",
    "MOV(1.5e3,x);",
    "MOV(.5e3,x);",
    "CPT(x,f(a := 1));",
    "CPT(x,a ** NOT b);",
    "CPT(x,- NOT a);",
    "CPT(x,a **);",
    "CPT(x,(a + b);",
    "CPT(x,f(a,));",
    "CMP(a == b);",
    "CPT(x,a >< b);",
    "XIC(a . b)OTE(c);",
    "N: XIC(a)OTE(b);",
    "RC: 'a comment';",
    # syntax errors
    "XIC(a)[OTE(b),OTE(c);",
    "XIC(a)]OTE(b);",
    "XIC a;",
    "XIC(a)@OTE(b);",
    "XIC(a);OTE(b);",
    "XIC(a,;",
    "XIC(a.)OTE(b);",
    "XIC(a[)OTE(b);",
    "XIC(IF)OTE(b);",
]


def grammar(text: str, line: int, col: int, start: str = "rung_only") -> object:
    parser = _parser()
    try:
        return fast_parse(
            parser, text, start, lambda state: contextual_tokens(parser, text, state, line, col)
        )
    except SlowPath:
        return None


def scan(text: str, line: int, col: int) -> n.Rung | None:
    return scan_rung(text, line, col, _plain_name())


@pytest.mark.parametrize("text", SCANNED)
@pytest.mark.parametrize(("line", "col"), [(1, 1), (7, 5)])
def test_scanner_builds_the_grammars_ast(text: str, line: int, col: int) -> None:
    got = scan(text, line, col)
    assert got is not None, "the scanner gave up on an everyday rung"
    expected = grammar(text, line, col)
    if text.strip() == "" or text.strip() == ";":
        assert isinstance(expected, n.Rung) and expected.elements == got.elements == []
    assert got == expected
    assert got == grammar(text, line, col, "rung_line")  # the same rung as a .rll line


@pytest.mark.parametrize("text", GIVEN_UP)
def test_scanner_leaves_the_rest_to_the_grammar(text: str) -> None:
    assert scan(text, 3, 9) is None


def test_empty_text_is_left_without_a_span() -> None:
    # parse_rung gives an empty rung the position where its text starts
    assert scan("", 4, 2) == n.Rung([], n.NOWHERE)


def test_spans_worked_by_hand() -> None:
    # '[XIC(a) ,XIC(b) ]' at line 7 column 5: '[' at 5, XIC at 6..8, 'a' at 10, ']' at 21
    r = scan("[XIC(a) ,XIC(b) ]OTE(Tank[3].Level);", 7, 5)
    assert r is not None
    branch, ote = r.elements
    assert isinstance(branch, n.Branch) and branch.span == n.Span(7, 5, 7, 22)
    xic = branch.legs[0][0]
    assert isinstance(xic, n.LadderInstr)
    assert xic.name_span == n.Span(7, 6, 7, 9) and xic.operands[0].span == n.Span(7, 10, 7, 11)
    # OTE at 22..24, '(' 25, Tank 26..29, '[' 30, '3' 31, ']' 32, '.' 33, Level 34..38, ')' 39
    assert isinstance(ote, n.LadderInstr) and ote.span == n.Span(7, 22, 7, 40)
    member = ote.operands[0]
    assert isinstance(member, n.Member) and member.name == "Level"
    assert member.span == n.Span(7, 26, 7, 39) and member.name_span == n.Span(7, 34, 7, 39)
    index = member.base
    # as the grammar builds it, an Index ends with its last subscript, before the ']'
    assert isinstance(index, n.Index) and index.span == n.Span(7, 26, 7, 32)
    assert r.span == n.Span(7, 5, 7, 41)  # through the ';' at column 40


# ------------------------------------------------------------------ every rung the repository holds
_RUNG_TEXT = re.compile(r"<Rung\b[^>]*>.*?<Text>\s*<!\[CDATA\[(.*?)\]\]>", re.S)


def _export_rungs() -> list[tuple[str, str]]:
    files = sorted(ROOT.glob("tests/**/*.L5X")) + sorted(ROOT.glob("samples/*.L5X"))
    corpus = Path(os.environ.get("LOGIXST_L5X_CORPUS") or "/nonexistent")
    if corpus.is_dir():  # the corpus of public exports, when asked for (docs/l5x-corpus.md)
        files += sorted(corpus.glob("*.L5X"))
    out = []
    for f in files:
        text = f.read_text(encoding="utf-8", errors="replace")
        out += [(f.name, m.group(1)) for m in _RUNG_TEXT.finditer(text)]
    if corpus.is_dir():
        for f in sorted(corpus.glob("*.rungs")):
            out += [
                (f.name, line)
                for line in f.read_text(encoding="utf-8").splitlines()
                if line.strip()
            ]
    return out


def test_every_export_rung_agrees() -> None:
    rungs = _export_rungs()
    assert len(rungs) > 50, "the fixture exports should hold rungs"
    scanned = 0
    for name, text in rungs:
        got = scan(text, 2, 3)
        if got is not None:
            scanned += 1
            assert got == grammar(text, 2, 3), (name, text)
    assert scanned > len(rungs) // 2, "most exported rungs should take the fast path"


def test_benchmark_rungs_take_the_fast_path() -> None:
    sys.path.insert(0, str(ROOT / "tests" / "benchmarks"))
    try:
        from bench_l5x import RUNGS  # the typical rung shapes of the 2 MB benchmark export
    finally:
        sys.path.pop(0)
    for shape in RUNGS:
        text = shape.format(i=12, j=19)
        got = scan(text, 1, 1)
        assert got is not None and got == grammar(text, 1, 1), text


# ------------------------------------------------------------------ random expressions
_ATOMS = [
    "a",
    "b1",
    "Tank[i].Level",
    "v[2]",
    "x.3",
    "7",
    "2.5",
    "1_0",
    "f(a)",
    "g()",
    "h(a, b)",
    "AND",
    "TRUE",
    "'s'",
    "S:N",
]
_OPS = [
    "+",
    "-",
    "*",
    "/",
    "**",
    " MOD ",
    " AND ",
    "&",
    " OR ",
    " XOR ",
    "=",
    "<>",
    "<",
    "<=",
    ">",
    ">=",
    "=>",
    ":=",
]
_PREFIX = ["", "", "", "-", "+", "NOT ", "- ", "NOT -", "-NOT "]


def _random_expr(rng: random.Random, depth: int) -> str:
    if depth == 0 or rng.random() < 0.3:
        atom = rng.choice(_ATOMS)
    elif rng.random() < 0.3:
        atom = "(" + _random_expr(rng, depth - 1) + ")"
    else:
        atom = _random_expr(rng, depth - 1) + rng.choice(_OPS) + _random_expr(rng, depth - 1)
    blank = rng.choice(["", "", " ", "  "])
    return rng.choice(_PREFIX) + blank + atom + blank


def test_random_expressions_agree_with_the_grammar() -> None:
    # Expressions from a small generator, valid and invalid alike: whenever the grammar parses
    # the rung the scanner must give the same AST or give up, and it must never accept a rung
    # the grammar rejects. Seeded, so a failure is reproducible.
    rng = random.Random(20261121)
    scanned = 0
    for _ in range(3000):
        text = f"XIC(c)CPT(d,{_random_expr(rng, 3)});"
        got = scan(text, 1, 1)
        expected = grammar(text, 1, 1)
        if got is not None:
            scanned += 1
            assert got == expected, text
    assert scanned > 500, "the scanner should take most valid expressions"
