"""`logixst check` on .rll files: a failing fixture and a clean twin per ladder diagnostic
(SPEC 7, 9.10, 9.17, 9.18), the W202 rule (docs/decisions/0011), and the Analysis the
ladder compiler reads (call_of, type_of, enum_of filled as for ST calls)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from interpreter.diagnostics import REGISTRY
from interpreter.runtime.loader import load
from interpreter.semantics.types import DINT, REAL
from interpreter.syntax import nodes as n

HEADER = """VAR
  a, b, c : BOOL;
  x, y : DINT;
  r : REAL;
  t : TIMER;
  cnt : COUNTER;
  ctl : CONTROL;
  arr : DINT[10];
  s : STRING;
  ax, ax2 : AXIS_VIRTUAL;
  mc, mc2 : MOTION_INSTRUCTION;
END_VAR
"""

# code -> (failing rungs, clean twin); rungs follow HEADER unless they start with "VAR"
FIXTURES: dict[str, tuple[str, str]] = {
    "S001": ("MOV(x+,y);\n", "MOV(x,y);\n"),
    "S003": ("XIC(a)OTE(b);\n(* open comment\n", "XIC(a)OTE(b);\n(* closed *)\n"),
    "S004": ("XIC(a)@OTE(b);\n", "XIC(a)OTE(b);\n"),
    "S005": ("XIC(a)OTE(b)\n", "XIC(a)OTE(b);\n"),
    "S006": ("XIC(a)[OTE(b),OTE(c);\n", "XIC(a)[OTE(b),OTE(c)];\n"),
    "E101": ("XIC(zz)OTE(b);\n", "XIC(a)OTE(b);\n"),
    "E102": ("XIC(t.XX)OTE(b);\n", "XIC(t.DN)OTE(b);\n"),
    "E103": ("MyAOI(x,1)OTE(b);\n", "XIC(a)OTE(b);\n"),
    "E104": ("XIC(a,b)OTE(c);\n", "XIC(a)OTE(c);\n"),
    "E105": ("XIC(a)TON(x,100,0);\n", "XIC(a)TON(t,100,0);\n"),
    "E106": ("XIC(a)MOV(x,5);\n", "XIC(a)MOV(5,x);\n"),
    "E107": ("XIC(a)TON(t,x,0);\n", "XIC(a)TON(t,100,0);\n"),
    "E108": (
        "XIC(a)FAL(ctl,10,0,ALLL,arr[ctl.POS],x);\n",
        "XIC(a)FAL(ctl,10,0,ALL,arr[ctl.POS],x);\n",
    ),
    "E109": (
        "XIC(a)FAL(ctl,10,0,-5,arr[ctl.POS],x);\n",
        "XIC(a)FAL(ctl,10,0,INC,arr[ctl.POS],x);\n",
    ),
    "E110": ("MOV(arr[1,2],x);\n", "MOV(arr[1],x);\n"),
    "E112": ("XIC(a)MDAC(ax,ax,mc,0,0);\n", "XIC(a)MDAC(ax,ax2,mc,0,0);\n"),
    "E113": ("XIC(a)MSO(x,mc);\n", "XIC(a)MSO(ax,mc);\n"),
    "E116": ("CPT(x,s+1);\n", "CPT(x,y+1);\n"),
    "E117": (
        "VAR\n  a : BOOL;\n  a : DINT;\nEND_VAR\nXIC(a)NOP();\n",
        "VAR\n  a : BOOL;\nEND_VAR\nXIC(a)NOP();\n",
    ),
    "E119": ("VAR\n  a : NOTATYPE;\nEND_VAR\nNOP();\n", "VAR\n  a : BOOL;\nEND_VAR\nNOP();\n"),
    "E121": ("CPT(x,r AND 1);\n", "CPT(x,y AND 1);\n"),
    "E122": ("MOV(arr[10],x);\n", "MOV(arr[9],x);\n"),
    "E124": ("XIC(a)JSR(nowhere,0);\n", "XIC(a)JSR(main,0);\n"),
    "E126": ("XIC(a)TONR(t);\n", "XIC(a)TON(t,100,0);\n"),
    "E128": ("XIC(a)MOV(?,x);\n", "XIC(a)TON(t,?,?);\n"),
    "E129": ("XIC(a)OTE(b);\n;\n", "XIC(a)OTE(b);\nNOP();\n"),
    "E131": (
        "XIC(a)JMP(over);\nXIC(a)OTE(b);\nLBL(ovr)NOP();\n",
        "XIC(a)JMP(over);\nXIC(a)OTE(b);\nLBL(over)NOP();\n",
    ),
    "W202": ("[XIC(a),]OTE(b);\n", "[XIC(a),XIC(c)]OTE(b);\n"),
    "W203": ("XIC(a)MSO(ax,mc);\nXIC(b)MSF(ax,mc);\n", "XIC(a)MSO(ax,mc);\nXIC(b)MSF(ax,mc2);\n"),
}

# U304: an instruction the catalog knows but no implementation runs yet (ladder instructions
# arrive with the ladder compiler); it does not depend on the ladder checks tested here.
TOLERATED = {"U304"}


def _source(body: str) -> str:
    return body if body.startswith(("VAR", "TYPE")) else HEADER + body


def _check(st, body: str, name: str = "main.rll") -> tuple[int, list[dict]]:  # noqa: ANN001
    r = st.check(_source(body), "json", name=name)
    assert "Traceback" not in r.err, r.err
    return r.code, json.loads(r.out)


@pytest.mark.parametrize("code", sorted(FIXTURES))
def test_failing_fixture(st, code: str) -> None:
    bad, _ = FIXTURES[code]
    exit_code, diags = _check(st, bad)
    assert code in {d["code"] for d in diags}, diags
    assert all(d["severity"] == REGISTRY[d["code"]].severity.value for d in diags)
    if REGISTRY[code].severity.value == "error":
        assert exit_code == 1
    else:
        assert [d["code"] for d in diags if d["code"] not in TOLERATED] == [code]


@pytest.mark.parametrize("code", sorted(FIXTURES))
def test_clean_twin(st, code: str) -> None:
    _, good = FIXTURES[code]
    exit_code, diags = _check(st, good)
    assert [d for d in diags if d["code"] not in TOLERATED] == []
    if not diags:
        assert exit_code == 0


def test_every_ladder_code_has_a_fixture() -> None:
    ladder = {"S006", "E128", "E129", "E131", "W202", "E124"}
    assert ladder <= set(FIXTURES)


# ------------------------------------------------------------------ positions and messages
@pytest.mark.parametrize("rung", ["LES(s,x)OTE(b);\n", "EQU(5,s)OTE(b);\n"])
def test_compare_of_a_string_with_a_number(st, rung: str) -> None:
    # Each compare operand alone accepts a number or a STRING, so LES(s,x) passed the check and
    # crashed at run time (a TypeError traceback, found by fuzzing). Line 13 follows the 12-line
    # HEADER; the second operand starts in column 7 of 'LES(s,x)' / 'EQU(5,s)'.
    exit_code, diags = _check(st, rung)
    assert exit_code == 1
    assert [(d["code"], d["line"], d["column"]) for d in diags] == [("E116", 13, 7)]
    _, clean = _check(st, "VAR\n  s, s2 : STRING;\n  b : BOOL;\nEND_VAR\nLES(s,s2)OTE(b);\n")
    assert clean == []


def test_positions_are_file_positions(st) -> None:
    # HEADER is 12 lines; line 13: 'XIC(a)MOV(?,x);' - the '?' is column 11
    _, diags = _check(st, FIXTURES["E128"][0])
    (d,) = [d for d in diags if d["code"] == "E128"]
    assert (d["line"], d["column"], d["endLine"], d["endColumn"]) == (13, 11, 13, 12)
    assert "MOV operand Source" in d["message"]


def test_empty_operand_is_a_placeholder_too(st) -> None:
    _, diags = _check(st, "XIC(a)MOV(,x);\n")
    assert [d["code"] for d in diags if d["code"] not in TOLERATED] == ["E128"]


def test_empty_rung_names_its_number(st) -> None:
    _, diags = _check(st, "NOP();\nNOP();\n;\n")
    (d,) = diags
    assert d["code"] == "E129" and d["line"] == 15 and "rung 2" in d["message"]


def test_unbalanced_branch_is_reported_and_later_rungs_still_checked(st) -> None:
    _, diags = _check(st, "XIC(a)[OTE(b),OTE(c);\nXIC(zz)OTE(b);\n")
    assert [(d["code"], d["line"]) for d in diags] == [("S006", 13), ("E101", 14)]


def test_jsr_between_files(st) -> None:
    main = st.write("main.rll", HEADER + "XIC(a)JSR(helper,0);\n")
    helper = st.write("helper.rll", "XIC(b)OTE(c);\n")
    r = st.cli("check", str(main), str(helper), "--format", "json")
    assert (r.code, json.loads(r.out)) == (0, [])


def test_directory_check_reads_rll_files(st) -> None:
    d = st.tmp / "prog"
    d.mkdir()
    (d / "a_main.st").write_text(HEADER + "JSR(b_lad);\n")
    (d / "b_lad.rll").write_text("XIC(zz)OTE(a);\n")
    r = st.cli("check", str(d), "--format", "json")
    assert [(Path(x["path"]).name, x["code"]) for x in json.loads(r.out)] == [("b_lad.rll", "E101")]


# ------------------------------------------------------------------ status flags (SPEC 9.17)
def test_math_status_flags_are_ladder_only(st) -> None:
    rll = "XIC(S:FS)XIC(S:N)XIO(S:Z)XIC(S:V)XIO(S:C)OTE(a);\n"
    assert _check(st, rll) == (0, [])
    for flag in ("S:N", "S:Z", "S:V", "S:C"):
        code, diags = _check(st, f"a := {flag};\n", name="main.st")
        assert code == 1 and [d["code"] for d in diags] == ["E123"]
    assert _check(st, "a := S:FS;\n", name="main.st") == (0, [])


# ------------------------------------------------------------------ W202 rule
@pytest.mark.parametrize(
    ("rung", "shorted"),
    [
        ("[XIC(a),]OTE(b);", True),  # empty leg beside a condition, rung goes on
        ("[,XIC(a)]OTE(b);", True),
        ("XIC(c)[OTE(a),XIC(b)]OTE(c);", True),  # an output-only leg is always true
        ("XIC(c)[OTE(a),XIC(b)OTE(c)];", False),  # output branch at the end: nothing uses it
        ("[XIC(a),XIC(b)]OTE(c);", False),
        ("[OTE(a),OTE(b)];", False),  # parallel outputs
        ("[[XIC(a),XIC(b)],XIC(c)]OTE(a);", False),  # nested legs are all conditional
        ("[[XIC(a),],XIC(c)]OTE(a);", True),  # the inner branch shorts (it feeds OTE)
        ("[ONS(a),]OTE(b);", True),
        (
            "[MyAOI(x),]OTE(b);",
            True,
        ),  # unknown instruction counts as a condition: the empty leg still shorts
        ("[MyAOI(x),XIC(a)]OTE(b);", False),
        ("[NOP(),XIC(a)]OTE(b);", True),
        ("[AFI(),XIC(a)]OTE(b);", False),  # AFI is an (always false) input
    ],
)
def test_shorted_branch_rule(st, rung: str, shorted: bool) -> None:
    _, diags = _check(st, rung + "\n")
    assert ("W202" in {d["code"] for d in diags}) is shorted, diags


def test_w202_is_reported_once_per_branch_at_the_branch(st) -> None:
    _, diags = _check(st, "XIC(c)[XIC(a),,XIC(b)]OTE(c);\n")
    (d,) = [d for d in diags if d["code"] == "W202"]
    # '[' at column 7, ']' at column 22 -> end column 23
    assert (d["line"], d["column"], d["endColumn"]) == (13, 7, 23)
    assert "leg 2" in d["message"]


def test_nested_short_is_reported_once_where_it_is(st) -> None:
    # the inner branch [XIC(a),] (columns 2..10) is shorted; the outer leg is always true only
    # through it, so the outer branch is not reported again
    _, diags = _check(st, "[[XIC(a),],XIC(c)]OTE(a);\n")
    assert [(d["code"], d["column"], d["endColumn"]) for d in diags] == [("W202", 2, 11)]


def test_nested_output_only_branch_shorts_the_outer_one(st) -> None:
    _, diags = _check(st, "[[OTE(b),OTE(c)],XIC(c)]OTE(a);\n")
    assert [(d["code"], d["column"]) for d in diags] == [("W202", 1)]


def test_unknown_instruction_is_a_condition_for_the_rule(st) -> None:
    _, diags = _check(st, "[MyAOI(x),XIC(a)]OTE(b);\n")
    assert [d["code"] for d in diags] == ["E103"]


# ------------------------------------------------------------------ mnemonics and expressions
@pytest.mark.parametrize(
    ("old", "new"),
    [
        ("EQU", "EQ"),
        ("NEQ", "NE"),
        ("GRT", "GT"),
        ("GEQ", "GE"),
        ("LES", "LT"),
        ("LEQ", "LE"),
        ("MOV", "MOVE"),
    ],
)
def test_v36_mnemonics_two_operands(tmp_path: Path, old: str, new: str) -> None:
    ins = _analysed(
        tmp_path,
        f"{old}(x,1)OTE(a);\n{new}(x,1)OTE(a);\n" if old != "MOV" else "MOV(x,y);\nMOVE(x,y);\n",
    )
    first, second = ins
    assert first is second and first.name == old


@pytest.mark.parametrize(
    ("old", "new"),
    [("SQR", "SQRT"), ("TRN", "TRUNC"), ("ACS", "ACOS"), ("ASN", "ASIN"), ("ATN", "ATAN")],
)
def test_v36_mnemonics_math(tmp_path: Path, old: str, new: str) -> None:
    first, second = _analysed(tmp_path, f"{old}(r,r);\n{new}(r,r);\n")
    assert first is second and first.name == old


def test_v36_mnemonics_three_operands(tmp_path: Path) -> None:
    a1, a2 = _analysed(tmp_path, "LIM(0,x,10)OTE(a);\nLIMIT(0,x,10)OTE(a);\n")
    assert a1 is a2 and a1.name == "LIM"
    x1, x2 = _analysed(tmp_path, "XPY(r,2,r);\nEXPT(r,2,r);\n")
    assert x1 is x2 and x1.name == "XPY"


def _loaded(tmp_path: Path, rungs: str):  # noqa: ANN202
    p = tmp_path / "main.rll"
    p.write_text(HEADER + rungs)
    loaded = load([p])
    assert [d.code for d in loaded.diagnostics if d.code not in TOLERATED] == [], [
        d.text() for d in loaded.diagnostics
    ]
    return loaded


def _analysed(tmp_path: Path, rungs: str) -> list:
    """The catalog entry the checker recorded for the first instruction of each rung."""
    loaded = _loaded(tmp_path, rungs)
    routine = loaded.model.routines[0]
    return [loaded.analysis.call_of[id(r.elements[0])] for r in routine.rungs]


def test_analysis_is_filled_like_st_calls(tmp_path: Path) -> None:
    loaded = _loaded(tmp_path, "XIC(a)CPT(r,x*2+1)FAL(ctl,10,0,ALL,arr[ctl.POS],x+1)TON(t,?,?);\n")
    a = loaded.analysis
    xic, cpt, fal, ton = loaded.model.routines[0].rungs[0].elements
    assert [a.call_of[id(i)].name for i in (xic, cpt, fal, ton)] == ["XIC", "CPT", "FAL", "TON"]
    # x*2+1 with x DINT is DINT; the destination r is REAL
    assert a.type_of[id(cpt.operands[1])] is DINT
    assert a.type_of[id(cpt.operands[0])] is REAL
    assert a.tag_of[id(cpt.operands[0])].name == "r"
    # FAL Mode ALL is enumeration value 0 (catalog FAL_Mode)
    assert a.enum_of[id(fal.operands[3])] == 0
    assert isinstance(ton.operands[1], n.Placeholder) and id(ton.operands[1]) not in a.type_of


def test_enumeration_words_with_spaces_resolve(tmp_path: Path) -> None:
    rungs = "XIC(a)MAJ(ax,mc,0,10.0,Units per sec,100.0,% of Maximum,100.0,% of Maximum,S-Curve,100.0,100.0,% of Time,Disabled,Programmed,0.0,0);\n"
    loaded = _loaded(tmp_path, rungs)
    a = loaded.analysis
    maj = loaded.model.routines[0].rungs[0].elements[1]
    # catalog: SpeedUnits 'Units per sec' = 0, AccelUnits '% of Maximum' = 1, Profile 'S-Curve' = 1
    assert a.enum_of[id(maj.operands[4])] == 0
    assert a.enum_of[id(maj.operands[6])] == 1
    assert a.enum_of[id(maj.operands[9])] == 1


def test_fal_numeric_mode_counts_elements(tmp_path: Path) -> None:
    loaded = _loaded(tmp_path, "XIC(a)FAL(ctl,10,0,3,arr[ctl.POS],x);\n")
    fal = loaded.model.routines[0].rungs[0].elements[1]
    assert loaded.analysis.enum_of[id(fal.operands[3])] == 3


def test_ladder_function_mnemonics_in_expressions(tmp_path: Path) -> None:
    loaded = _loaded(tmp_path, "CPT(r,SQR(r)+ABS(x)+TRN(r))CMP(SQRT(r)>1.0)OTE(a);\n")
    cpt = loaded.model.routines[0].rungs[0].elements[0]
    expr = cpt.operands[1]
    sqr = expr.left.left
    assert isinstance(sqr, n.Call) and loaded.analysis.call_of[id(sqr)].name == "SQRT"


def test_expression_operands_are_type_checked(st) -> None:
    _, diags = _check(st, "CMP(x+1)OTE(a);\n")
    # CMP needs a BOOL expression; x+1 is DINT
    assert [d["code"] for d in diags] == ["E105"]
    _, diags = _check(st, "CPT(x,zz*2);\n")
    assert [d["code"] for d in diags] == ["E101"]


def test_string_literal_operand(st) -> None:
    assert _check(st, "EQU(s,'abc')OTE(a);\n") == (0, [])


# ------------------------------------------------------------------ sample
SAMPLE = Path(__file__).resolve().parents[2] / "samples" / "conveyor.rll"


def test_conveyor_sample_checks_clean() -> None:
    from interpreter.instructions.registry import lookup

    loaded = load([SAMPLE])
    # the only thing allowed is U304 for an instruction whose implementation has not landed
    for d in loaded.diagnostics:
        assert d.code == "U304", d.text()
        assert lookup(d.message.split()[0], "rll") is None, d.text()
    routine = loaded.model.routines[0]
    assert routine.language == "rll"
    # 12 rungs; RC: comments sit on rungs 0 (seal-in), 1 (horn timer), 6 (count), 8 (jam), 11 (CPT)
    assert [r.number for r in routine.rungs] == list(range(12))
    assert [r.number for r in routine.rungs if r.comment] == [0, 1, 6, 8, 11]
    assert routine.rungs[0].comment.startswith("Start/stop with seal-in.")


# ------------------------------------------------------------------ CLI input handling
def test_unsupported_suffix_names_every_input_type(st) -> None:
    p = st.write("prog.txt", "XIC(a)OTE(b);\n")
    r = st.cli("check", str(p))
    assert r.code == 2
    assert "Traceback" not in r.err and len(r.err.strip().splitlines()) == 1
    assert "expected .st, .rll, .L5X or .L5K" in r.err
