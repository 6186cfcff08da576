"""Ladder neutral text -> AST (SPEC 2.2, 9.18): parse_rung and parse_rll.

Columns in the span assertions are counted by hand on the source text shown next to them
(1-based, end exclusive).
"""

from __future__ import annotations

import pytest

from interpreter.syntax import nodes as n
from interpreter.syntax.rll_parser import parse_rll, parse_rung


def rung(text: str) -> n.Rung:
    r, diags = parse_rung(text, "t.rll", 0)
    assert diags == [], [d.text() for d in diags]
    assert r is not None
    return r


def shape(elements: list) -> list:
    """Compact structure: instruction names and nested legs."""
    out: list = []
    for e in elements:
        if isinstance(e, n.LadderInstr):
            out.append(e.name)
        else:
            out.append([shape(leg) for leg in e.legs])
    return out


def ident(e: n.Expr) -> str:
    assert isinstance(e, n.Name), e
    return e.ident


# ------------------------------------------------------------------ operands
def test_member_names_may_be_reserved_words() -> None:
    # Studio 5000 exports hold UDT members named AND, OR, XOR, NOT, MOD, Array (fanno/l5x-emulator)
    r = rung("AND(Move.A,Move.B,Move.AND)SQO(Seq.Array,Seq.Mask,Seq.Src,Seq.Ctl,?,?)")
    dest = r.elements[0].operands[2]
    assert isinstance(dest, n.Member) and dest.name == "AND" and ident(dest.base) == "Move"
    arr = r.elements[1].operands[0]
    assert isinstance(arr, n.Member) and arr.name == "Array"
    # "AND(Move.A,Move.B," is 18 characters, so `Move.AND` occupies columns 19..26
    assert dest.span == n.Span(1, 19, 1, 27)


# ------------------------------------------------------------------ rung structure
def test_concatenated_instructions() -> None:
    r = rung("XIC(a)XIO(b)OTE(c)")
    assert shape(r.elements) == ["XIC", "XIO", "OTE"]
    assert [ident(i.operands[0]) for i in r.elements] == ["a", "b", "c"]


def test_branch_nesting_start_and_empty_legs() -> None:
    r = rung("[XIC(a),[XIC(b),,XIO(c)]XIC(d),]OTE(e);")
    # outer branch: leg 1 = XIC(a); leg 2 = inner branch (3 legs, middle empty) then XIC(d); leg 3 empty
    assert shape(r.elements) == [[["XIC"], [[["XIC"], [], ["XIO"]], "XIC"], []], "OTE"]


def test_deep_nesting() -> None:
    depth = 12
    text = "[" * depth + "XIC(a)" + "]" * depth + "OTE(b)"
    expect: list = ["XIC"]
    for _ in range(depth):
        expect = [[expect]]
    assert shape(rung(text).elements) == [*expect, "OTE"]


def test_branch_starting_with_empty_leg() -> None:
    # `[,XIC(a)]` is what exports write for a branch whose first leg is a bare wire
    assert shape(rung("[,XIC(a)]OTE(b)").elements) == [[[], ["XIC"]], "OTE"]


def test_whitespace_and_line_breaks_are_insignificant() -> None:
    text = "XIC( a ) [ XIC(b) ,\n\tXIC(c) ]\n  OTE( d );"
    assert shape(rung(text).elements) == ["XIC", [["XIC"], ["XIC"]], "OTE"]


def test_export_spacing_inside_branches() -> None:
    assert shape(rung("[XIC(a) ,XIC(b) ]OTE(c)").elements) == [[["XIC"], ["XIC"]], "OTE"]


def test_any_identifier_is_an_instruction_name() -> None:
    # Add-On Instructions and the logical instructions whose names are ST keywords
    r = rung("MyAOI(inst,p1,2)AND(a,b,c)OR(a,b,c)XOR(a,b,c)NOT(a,b)MOD(a,b,c)")
    assert shape(r.elements) == ["MyAOI", "AND", "OR", "XOR", "NOT", "MOD"]
    assert len(r.elements[0].operands) == 3


# ------------------------------------------------------------------ operands
def test_commas_inside_brackets_and_parentheses_do_not_split() -> None:
    (mov, cpt) = rung("MOV(a[1,2],b)CPT(d,ABS(x)+m[i,j])").elements
    assert len(mov.operands) == 2
    assert isinstance(mov.operands[0], n.Index) and len(mov.operands[0].indices) == 2
    assert len(cpt.operands) == 2
    assert isinstance(cpt.operands[1], n.Binary)


def test_empty_operands_and_question_marks_are_placeholders() -> None:
    ton, gsv = rung("TON(T,?,?)GSV(WallClockTime,,LocalDateTime,Dest)").elements
    assert [type(o) for o in ton.operands] == [n.Name, n.Placeholder, n.Placeholder]
    assert [type(o) for o in gsv.operands] == [n.Name, n.Placeholder, n.Name, n.Name]
    # GSV(WallClockTime,,LocalDateTime,Dest) after TON(T,?,?) (10 chars): G at 11, '(' 14,
    # WallClockTime 15..27, the commas at 28 and 29: the empty operand spans them
    assert gsv.operands[1].span == n.Span(1, 28, 1, 30)
    # '?' of TON at column 7
    assert ton.operands[1].span == n.Span(1, 7, 1, 8)


def test_trailing_empty_operand() -> None:
    (mov,) = rung("MOV(a,)").elements
    assert [type(o) for o in mov.operands] == [n.Name, n.Placeholder]


def test_no_operands() -> None:
    r = rung("NOP()AFI()")
    assert [len(i.operands) for i in r.elements] == [0, 0]


@pytest.mark.parametrize(
    "text",
    [
        "Units per sec2",
        "% of Maximum",
        "Units per sec",
        "% of Time-Master Driven",
        "Immediate Forward Only",
        "Active and Pending Motion",  # MCCD Scope: `and` between words (decision 0185)
        "Send Message to Linked Phase and Wait",
    ],
)
def test_enumeration_words_with_spaces(text: str) -> None:
    (i,) = rung(f"MAM(ax,mc,0,1.0,{text},5)").elements
    e = i.operands[4]
    assert isinstance(e, n.EnumText)
    assert e.text == text


def test_enumeration_words_normalise_blanks() -> None:
    (i,) = rung("MAJ(ax,mc,Units  per\tsec)").elements
    assert i.operands[2].text == "Units per sec"


def test_hyphenated_enumeration_stays_an_expression() -> None:
    # `S-Curve` is the ST form too: Binary('-', S, Curve), read as enumeration by the checker
    (i,) = rung("MAM(ax,S-Curve)").elements
    e = i.operands[1]
    assert isinstance(e, n.Binary) and e.op == "-"
    assert (ident(e.left), ident(e.right)) == ("S", "Curve")


def test_keyword_operators_are_not_enumeration_words() -> None:
    (cmp_,) = rung("CMP(a AND NOT b OR c MOD 2 = 0)").elements
    e = cmp_.operands[0]
    # precedence: a AND (NOT b) is done first, then OR with (c MOD 2 = 0)
    assert isinstance(e, n.Binary) and e.op == "OR"
    assert isinstance(e.left, n.Binary) and e.left.op == "AND"
    assert isinstance(e.left.right, n.Unary) and e.left.right.op == "NOT"
    assert isinstance(e.right, n.Binary) and e.right.op == "="


def test_a_and_b_stays_an_expression() -> None:
    # only a blank-joined pair of words on one side of `and` makes an enumeration text
    (cmp_,) = rung("CMP(a and b)").elements
    e = cmp_.operands[0]
    assert isinstance(e, n.Binary) and e.op == "AND"
    (cmp_,) = rung("CMP(a - b and c)").elements
    assert isinstance(cmp_.operands[0], n.Binary) and cmp_.operands[0].op == "AND"


def test_expression_operands_use_st_nodes() -> None:
    cmp_, cpt = rung("CMP(a+b>c)CPT(dest,a*2+b)").elements
    e = cmp_.operands[0]
    # a+b>c = (a+b) > c
    assert isinstance(e, n.Binary) and e.op == ">"
    assert isinstance(e.left, n.Binary) and e.left.op == "+"
    assert ident(e.right) == "c"
    e = cpt.operands[1]
    # a*2+b = (a*2) + b
    assert isinstance(e, n.Binary) and e.op == "+"
    assert isinstance(e.left, n.Binary) and e.left.op == "*"
    assert isinstance(e.left.right, n.Literal) and e.left.right.value == 2


def test_fal_fsc_expression_operands() -> None:
    fal, fsc = rung("FAL(c,10,0,ALL,d[c.POS],s[c.POS]*2)FSC(c2,10,0,ALL,s[c2.POS]<>0)").elements
    assert isinstance(fal.operands[5], n.Binary) and fal.operands[5].op == "*"
    assert isinstance(fal.operands[4], n.Index) and isinstance(fal.operands[4].indices[0], n.Member)
    assert isinstance(fsc.operands[4], n.Binary) and fsc.operands[4].op == "<>"


def test_functions_in_expressions_are_calls() -> None:
    (cpt,) = rung("CPT(d,SQR(a)+ABS(-b))").elements
    e = cpt.operands[1]
    assert isinstance(e.left, n.Call) and e.left.name == "SQR"
    assert isinstance(e.right, n.Call) and isinstance(e.right.args[0].value, n.Unary)


def test_indirect_bit() -> None:
    (i,) = rung("XIC(d.[t.m])").elements
    e = i.operands[0]
    assert isinstance(e, n.IndirectBit)
    assert ident(e.base) == "d"
    assert isinstance(e.index, n.Member) and e.index.name == "m"


def test_module_io_tag() -> None:
    (i,) = rung("XIC(Local:1:I.Data.3)").elements
    e = i.operands[0]
    assert isinstance(e, n.Bit) and e.bit == 3
    assert isinstance(e.base, n.Member) and e.base.name == "Data"
    assert ident(e.base.base) == "Local:1:I"


@pytest.mark.parametrize("flag", ["S:FS", "S:N", "S:Z", "S:V", "S:C"])
def test_system_flags(flag: str) -> None:
    (i,) = rung(f"XIC({flag})").elements
    assert ident(i.operands[0]) == flag


def test_subscripts_with_expressions() -> None:
    (i,) = rung("MOV(a[i+1],b[2*j,k])").elements
    src, dst = i.operands
    assert isinstance(src, n.Index) and isinstance(src.indices[0], n.Binary)
    assert isinstance(dst, n.Index) and len(dst.indices) == 2


def test_numeric_literals() -> None:
    ops = rung("MOV(16#FF,a)MOV(1.5e3,r)MOV(2#1010,a)MOV(-7,a)MOV(1_000,a)").elements
    first = [i.operands[0] for i in ops]
    assert (first[0].value, first[0].type) == (255, "DINT")  # 0xFF
    assert (first[1].value, first[1].type) == (1500.0, "REAL")  # 1.5 * 10**3
    assert first[2].value == 10  # 8 + 2
    assert isinstance(first[3], n.Unary) and first[3].operand.value == 7
    assert first[4].value == 1000


def test_string_literal_operand() -> None:
    (i,) = rung("EQU(s,'a;b$'c')").elements
    lit = i.operands[1]
    assert isinstance(lit, n.Literal) and lit.type == "STRING"
    assert lit.value == b"a;b'c"


# ------------------------------------------------------------------ spans
def test_spans_are_file_positions() -> None:
    r, diags = parse_rung("XIC(a)\n  OTE(b)", "p.L5X", 4, line=10, col=20)
    assert diags == [] and r is not None
    assert r.number == 4
    xic, ote = r.elements
    # text[0] is at line 10 column 20: XIC spans columns 20..25, 'a' is column 24
    assert xic.span == n.Span(10, 20, 10, 26)
    assert xic.name_span == n.Span(10, 20, 10, 23)
    assert xic.operands[0].span == n.Span(10, 24, 10, 25)
    # the second line is not shifted: '  OTE(b)' puts OTE at columns 3..5 and b at 7
    assert ote.span == n.Span(11, 3, 11, 9)
    assert ote.operands[0].span == n.Span(11, 7, 11, 8)
    assert r.span == n.Span(10, 20, 11, 9)


def test_branch_span() -> None:
    (b, _) = rung("[XIC(a),XIC(b)]OTE(c)").elements
    assert b.span == n.Span(1, 1, 1, 16)  # '[' at 1, ']' at 15


def test_parse_rung_trailing_semicolon_is_optional() -> None:
    assert shape(rung("XIC(a)OTE(b);").elements) == shape(rung("XIC(a)OTE(b)").elements)


def test_parse_rung_empty_text_is_an_empty_rung() -> None:
    for text in ("", ";", "  ;  "):
        assert rung(text).elements == []


# ------------------------------------------------------------------ syntax errors
def errors(text: str, **kw: int) -> list[tuple[str, n.Span]]:
    r, diags = parse_rung(text, "t.rll", 0, **kw)
    assert r is None
    return [(d.code, d.span) for d in diags]


def test_s001_unexpected_token_span() -> None:
    # 'MOV(a+,b)': the ',' at column 7 cannot follow '+'
    assert errors("MOV(a+,b)") == [("S001", n.Span(1, 7, 1, 8))]


def test_s001_missing_parenthesis_after_name() -> None:
    assert errors("XIC a") == [("S001", n.Span(1, 5, 1, 6))]


def test_s001_instruction_cut_short() -> None:
    # 'XIC(a)X' ends after the name X at column 8
    ((code, span),) = errors("XIC(a)X")
    assert code == "S001" and span == n.Span(1, 8, 1, 8)


def test_s001_two_rungs_given_to_parse_rung() -> None:
    assert errors("XIC(a);OTE(b)") == [("S001", n.Span(1, 8, 1, 11))]


def test_s004_bad_character() -> None:
    assert errors("XIC(a)@OTE(b)") == [("S004", n.Span(1, 7, 1, 8))]


def test_s003_unterminated_string() -> None:
    assert errors("EQU(s,'abc)") == [("S003", n.Span(1, 7, 1, 8))]


@pytest.mark.parametrize(
    ("text", "col"),
    [
        ("XIC(a)[OTE(b),OTE(c)", 7),  # '[' at column 7 never closed
        ("XIC(a)]OTE(b)", 7),  # ']' with no branch open
        ("[XIC(a),XIC(b))", 15),  # ')' would close the '['
        ("XIC(a", 4),  # '(' never closed
        ("XIC(a))", 7),  # one ')' too many
    ],
)
def test_s006_unbalanced(text: str, col: int) -> None:
    assert errors(text) == [("S006", n.Span(1, col, 1, col + 1))]


def test_s006_position_with_offset() -> None:
    assert errors("XIC(a)\n[OTE(b)", line=3, col=5) == [("S006", n.Span(4, 1, 4, 2))]


# ------------------------------------------------------------------ .rll files
FILE = """\
TYPE
  Pair : STRUCT
    a, b : DINT;
  END_STRUCT
END_TYPE
VAR
  start, stop, run : BOOL;   // push buttons
  t : TIMER;
END_VAR
// rung 0: seal-in
XIC(start)[XIC(run),] XIO(stop)OTE(run);
RC: "Timer; starts with run";
N: XIC(run)TON(t,?,?);
;
XIC(t.DN)
  OTU(run);
"""


def test_rll_file_header_and_rungs() -> None:
    r, diags = parse_rll(FILE, "conv.rll")
    assert diags == []
    assert (r.name, r.language) == ("conv", "rll")
    assert [t.name for t in r.types] == ["Pair"]
    assert [[name for name, _ in d.names] for d in r.decls] == [["start", "stop", "run"], ["t"]]
    assert [g.number for g in r.rungs] == [0, 1, 2, 3]
    assert shape(r.rungs[0].elements) == ["XIC", [["XIC"], []], "XIO", "OTE"]
    assert r.rungs[1].comment == "Timer; starts with run"
    assert shape(r.rungs[1].elements) == ["XIC", "TON"]
    assert r.rungs[2].elements == []
    assert r.rungs[3].span == n.Span(15, 1, 16, 12)  # 'XIC(t.DN)' .. '  OTU(run);'


def test_rll_comments_kept_with_positions() -> None:
    r, _ = parse_rll(FILE, "conv.rll")
    assert [(c.text, c.span.line, c.span.col) for c in r.comments] == [
        ("// push buttons", 7, 30),
        ("// rung 0: seal-in", 10, 1),
    ]


def test_rll_rung_positions() -> None:
    r, _ = parse_rll(FILE, "conv.rll")
    # line 13 'N: XIC(run)TON(t,?,?);' : XIC at column 4, TON at 12, its first '?' at 18
    xic, ton = r.rungs[1].elements
    assert xic.span.line == 13 and xic.span.col == 4
    assert ton.name_span == n.Span(13, 12, 13, 15)
    assert ton.operands[1].span == n.Span(13, 18, 13, 19)
    assert r.rungs[2].span == n.Span(14, 1, 14, 2)


def test_rll_without_header() -> None:
    r, diags = parse_rll("XIC(a)OTE(b);\n", "bare.rll")
    assert diags == [] and r.decls == [] and len(r.rungs) == 1


def test_rll_rc_comment_with_escapes_and_several_strings() -> None:
    r, diags = parse_rll('RC: "one$Ntwo; "\n  "three";\nNOP();\n', "c.rll")
    assert diags == []
    assert r.rungs[0].comment == "one\ntwo; three"


def test_rll_errors_in_every_rung_are_reported() -> None:
    src = "XIC(a OTE(b);\nXIC(a)]OTE(b);\nMOV(a+,b);\nXIC(a)@;\nXIC(ok)OTE(ok);\n"
    r, diags = parse_rll(src, "bad.rll")
    # line 1: the '(' of XIC (column 4) is left open; line 2: ']' at column 7 closes nothing;
    # line 3: ',' at column 7 after '+'; line 4: '@' at column 7
    assert [(d.code, d.span.line, d.span.col) for d in diags] == [
        ("S006", 1, 4),
        ("S006", 2, 7),
        ("S001", 3, 7),
        ("S004", 4, 7),
    ]
    # the good rung after them is still parsed, with its file-order number
    assert [g.number for g in r.rungs] == [4]


def test_rll_missing_final_semicolon() -> None:
    r, diags = parse_rll("XIC(a)OTE(b);\nXIC(b)OTE(c)\n", "m.rll")
    assert [(d.code, d.span.line, d.span.col) for d in diags] == [("S005", 2, 13)]
    assert len(r.rungs) == 2


def test_rll_header_error_is_reported() -> None:
    # the header is read by the ST front end, so it reports what a .st file with the same
    # declarations reports; a missing ';' is S005 where END_VAR stands
    from interpreter.syntax.st_parser import parse_st

    header = "VAR\n  a : BOOL\nEND_VAR\n"
    r, diags = parse_rll(header + "XIC(a)OTE(a);\n", "h.rll")
    _, st_diags = parse_st(header, "h.rll")
    assert diags == st_diags
    assert ("S005", 3, 1) in [(d.code, d.span.line, d.span.col) for d in diags]
    assert len(r.rungs) == 1


def test_rll_unterminated_block_comment() -> None:
    _, diags = parse_rll("XIC(a)OTE(b);\n(* open\n", "u.rll")
    assert [d.code for d in diags] == ["S003"]


def test_no_lark_objects_in_ast() -> None:
    from lark import Token, Tree

    r, _ = parse_rll(FILE, "conv.rll")

    def walk(v: object) -> None:
        assert not isinstance(v, Tree | Token), v
        if isinstance(v, list | tuple):
            for x in v:
                walk(x)
        elif hasattr(v, "__dataclass_fields__"):
            for f in v.__dataclass_fields__:  # type: ignore[attr-defined]
                walk(getattr(v, f))

    walk(r)
