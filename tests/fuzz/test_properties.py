"""Property tests (hypothesis): programs generated from the ST and ladder grammars.

Invariants, for every generated program: loading and checking never raise; when it checks
clean, prescan and scans never raise a Python exception (a major fault is a Logix outcome);
afterwards every integer tag holds a value of its type's range and every REAL tag a float32
value. The generators are typed (integer, numeric and BOOL expressions) so that most
programs verify and reach the VM. Budget: SCALE x 150 programs per language (a few seconds);
LOGIXST_FUZZ_LONG=1 for the long mode.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from tests.fuzz.common import SCALE, check_and_run

INT_TYPES = {"si": "SINT", "i": "INT", "d": "DINT", "l": "LINT"}
UINT_TYPES = {"us": "USINT", "ui": "UINT", "ud": "UDINT", "ul": "ULINT"}
INT_TAGS = sorted(INT_TYPES) + sorted(UINT_TYPES)
REAL_TAGS = ["r", "lr"]
DECLS = (
    "VAR\n"
    + "".join(f"  {n} : {t};\n" for n, t in {**INT_TYPES, **UINT_TYPES}.items())
    + "  r : REAL;\n  lr : LREAL;\n  b : BOOL;\n  ad : DINT[4];\n  ar : REAL[3];\n  k : DINT;\n"
    + "  s1, s2 : STRING;\n  ft : FBD_TIMER;\n  t : TIMER;\n  c : COUNTER;\n"
    + "END_VAR\n"
)

# Memory grows with every example a hypothesis run checks (60-130 KB each for these programs,
# docs/reliability.md): a long run of 78,000 examples in one process with the other tests
# grew past 20 GB and was killed. The budget is spent in rounds of at most ROUND examples,
# each a fresh hypothesis run, and the long mode runs one process per component.
TOTAL = 150 * SCALE
ROUND = 1_000
SETTINGS = settings(
    deadline=None,
    derandomize=SCALE == 1,  # the CI run is reproducible; the long mode explores
    suppress_health_check=[
        HealthCheck.too_slow,
        HealthCheck.data_too_large,
        HealthCheck.function_scoped_fixture,
    ],
    database=None,
)


def in_rounds(strategy: st.SearchStrategy[str], check: Callable[[str], None]) -> None:
    """Run `check` on TOTAL generated examples, ROUND at a time."""
    for start in range(0, TOTAL, ROUND):

        def one(example: str) -> None:  # a new function each round: a new hypothesis run
            check(example)

        rules = settings(SETTINGS, max_examples=min(ROUND, TOTAL - start))
        given(strategy)(rules(one))()


integers = st.one_of(
    st.integers(-5, 5),
    st.sampled_from([127, -128, 255, 32767, -32768, 65535, 2**31 - 1, -(2**31), 2**32 - 1]),
    st.integers(-(2**40), 2**40),
)
out_of_range = st.sampled_from(["18446744073709551616", "16#1_0000_0000_0000_0000"])  # E133
reals = st.one_of(
    st.sampled_from(["0.0", "1.5", "-2.25", "3.0E38", "1.0E-38", "1.0E39", "0.1", "1.0E999"]),
    st.floats(-1e6, 1e6, allow_nan=False).map(lambda x: f"{x:.6E}"),
)
radix = st.sampled_from(
    ["16#FF", "16#FFFF_FFFF", "2#1010", "8#777", "16#8000_0000", "16#FFFF_FFFF_FFFF_FFFF"]
)
# a variable subscript may be out of range at run time: a major fault, not a crash
index = st.one_of(st.integers(0, 2).map(str), st.sampled_from(["k", "d", "si"]))
int_element = index.map(lambda i: f"ad[{i}]")
real_element = index.map(lambda i: f"ar[{i}]")
bits = st.tuples(st.sampled_from(["d", "si", "i", "ud"]), st.integers(0, 7)).map(
    lambda p: f"{p[0]}.{p[1]}"
)

int_leaf = st.one_of(integers.map(str), radix, st.sampled_from(INT_TAGS), int_element)
real_leaf = st.one_of(reals, st.sampled_from(REAL_TAGS), real_element)
FUNCS = ["ABS", "SQRT", "TRUNC", "LN", "LOG", "SIN", "COS", "TAN", "ASIN", "ACOS", "ATAN"]
INT_OPS = ["+", "-", "*", "/", "MOD", "**", "AND", "OR", "XOR"]
int_expr = st.recursive(
    int_leaf,
    lambda inner: st.one_of(
        st.tuples(inner, st.sampled_from(INT_OPS), inner).map(lambda p: f"({p[0]} {p[1]} {p[2]})"),
        st.tuples(st.sampled_from(["-", "NOT "]), inner).map(lambda p: f"({p[0]}{p[1]})"),
        inner.map(lambda x: f"ABS({x})"),
    ),
    max_leaves=8,
)
num_expr = st.recursive(
    st.one_of(real_leaf, int_leaf),
    lambda inner: st.one_of(
        st.tuples(inner, st.sampled_from(["+", "-", "*", "/", "MOD", "**"]), inner).map(
            lambda p: f"({p[0]} {p[1]} {p[2]})"
        ),
        inner.map(lambda x: f"(-{x})"),
        st.tuples(st.sampled_from(FUNCS), inner).map(lambda p: f"{p[0]}({p[1]})"),
    ),
    max_leaves=8,
)
compare = st.tuples(num_expr, st.sampled_from(["=", "<>", "<", "<=", ">", ">="]), num_expr).map(
    lambda p: f"({p[0]} {p[1]} {p[2]})"
)
bool_expr = st.recursive(
    st.one_of(st.sampled_from(["TRUE", "FALSE", "b"]), bits, compare),
    lambda inner: st.one_of(
        st.tuples(inner, st.sampled_from(["AND", "OR", "XOR", "&"]), inner).map(
            lambda p: f"({p[0]} {p[1]} {p[2]})"
        ),
        inner.map(lambda x: f"(NOT {x})"),
    ),
    max_leaves=6,
)

typed_assignment = st.one_of(
    st.tuples(st.one_of(st.sampled_from(INT_TAGS), int_element), st.one_of(int_expr, num_expr)),
    st.tuples(st.one_of(st.sampled_from(INT_TAGS), int_element), int_expr),
    st.tuples(st.one_of(st.sampled_from(REAL_TAGS), real_element), num_expr),
    st.tuples(st.one_of(st.just("b"), bits), bool_expr),
)
# one assignment in 40 has a literal no Logix type holds (E133): check must cope with it too
assignment = (
    st.integers(0, 39)
    .flatmap(lambda i: st.tuples(st.just("l"), out_of_range) if i == 0 else typed_assignment)
    .map(lambda p: f"{p[0]} := {p[1]};\n")
)


# strings (any start/quantity: a bad one is a minor fault) and a timer function block
text = st.text(alphabet="abcXYZ 09$'", max_size=90).map(
    lambda x: "'" + x.replace("$", "$$").replace("'", "$'") + "'"
)
small = st.one_of(st.integers(-2, 90).map(str), st.sampled_from(["k", "si", "d"]))
string_call = st.one_of(
    st.tuples(st.sampled_from(["s1", "s2"]), text).map(lambda p: f"{p[0]} := {p[1]};\n"),
    st.tuples(st.sampled_from(["s1", "s2"]), st.sampled_from(["s1", "s2"])).map(
        lambda p: f"CONCAT({p[0]}, {p[1]}, s1);\n"
    ),
    st.tuples(small, small).map(lambda p: f"MID(s1, {p[0]}, {p[1]}, s2);\n"),
    st.tuples(small, small).map(lambda p: f"DELETE(s1, {p[0]}, {p[1]}, s2);\n"),
    small.map(lambda x: f"INSERT(s1, s2, {x}, s1);\n"),
    small.map(lambda x: f"FIND(s1, s2, {x}, k);\n"),
    st.sampled_from(["UPPER(s1, s2);\n", "DTOS(d, s1);\n", "RTOS(r, s2);\n", "STOD(s1, k);\n"]),
    st.tuples(int_expr, bool_expr).map(
        lambda p: f"ft.PRE := {p[0]};\nft.TimerEnable := {p[1]};\nTONR(ft);\nk := ft.ACC;\n"
    ),
)


def statements(depth: int = 0) -> st.SearchStrategy[str]:
    if depth >= 2:
        return st.one_of(assignment, assignment, string_call)
    body = st.lists(statements(depth + 1), min_size=1, max_size=3).map("".join)
    return st.one_of(
        assignment,
        assignment,
        string_call,
        st.tuples(bool_expr, body, body).map(
            lambda p: f"IF {p[0]} THEN\n{p[1]}ELSE\n{p[2]}END_IF;\n"
        ),
        st.tuples(
            st.integers(-3, 3), st.integers(-3, 6), st.sampled_from(["1", "2", "-1"]), body
        ).map(lambda p: f"FOR k := {p[0]} TO {p[1]} BY {p[2]} DO\n{p[3]}END_FOR;\n"),
        st.tuples(body, body).map(
            lambda p: f"CASE d OF\n0: {p[0]}1, 2..4: {p[1]}ELSE\nk := 0;\nEND_CASE;\n"
        ),
        st.tuples(bool_expr, body).map(lambda p: f"WHILE {p[0]} DO\n{p[1]}EXIT;\nEND_WHILE;\n"),
    )


st_programs = st.lists(statements(), min_size=1, max_size=6).map(lambda s: DECLS + "".join(s))


def test_st_programs(tmp_path: Path) -> None:
    path = tmp_path / "gen.st"

    def check(program: str) -> None:
        path.write_text(program)
        check_and_run([path])

    in_rounds(st_programs, check)


# ---- ladder: rungs of bit, math, compare and move instructions with branches
operand = st.one_of(
    st.sampled_from(INT_TAGS + REAL_TAGS), int_element, real_element, integers.map(str), reals
)
target = st.one_of(st.sampled_from(INT_TAGS + REAL_TAGS), int_element, real_element)
instructions = st.one_of(
    st.tuples(
        st.sampled_from(["XIC", "XIO", "OTE", "OTL", "OTU", "ONS"]),
        st.sampled_from(["b", "d.3", "ad[1].0"]),
    ).map(lambda p: f"{p[0]}({p[1]})"),
    st.tuples(st.sampled_from(["ADD", "SUB", "MUL", "DIV", "MOD"]), operand, operand, target).map(
        lambda p: f"{p[0]}({p[1]},{p[2]},{p[3]})"
    ),
    st.tuples(operand, target).map(lambda p: f"MOV({p[0]},{p[1]})"),
    st.tuples(st.sampled_from(["TON", "TOF", "RTO"]), st.integers(-5, 100)).map(
        lambda p: f"{p[0]}(t,{p[1]},?)"
    ),
    st.tuples(st.sampled_from(["CTU", "CTD"]), st.integers(-5, 100)).map(
        lambda p: f"{p[0]}(c,{p[1]},?)"
    ),
    st.sampled_from(["RES(t)", "RES(c)", "CONCAT(s1,s2,s1)", "MID(s1,3,80,s2)", "FIND(s1,s2,1,k)"]),
    st.tuples(target, num_expr).map(lambda p: f"CPT({p[0]},{p[1]})"),
    st.tuples(st.sampled_from(["EQU", "NEQ", "LES", "GRT", "LEQ", "GEQ"]), operand, operand).map(
        lambda p: f"{p[0]}({p[1]},{p[2]})"
    ),
)
rung_body = st.recursive(
    instructions,
    lambda inner: st.one_of(
        st.lists(inner, min_size=2, max_size=4).map("".join),
        st.lists(inner, min_size=2, max_size=3).map(lambda legs: "[" + ",".join(legs) + "]"),
    ),
    max_leaves=8,
)
ladder_programs = st.lists(rung_body.map(lambda r: r + ";\n"), min_size=1, max_size=6).map("".join)


def test_ladder_programs(tmp_path: Path) -> None:
    (tmp_path / "tags.st").write_text(DECLS)
    main = tmp_path / "main.rll"

    def check(rungs: str) -> None:
        main.write_text(rungs)
        check_and_run([main, tmp_path / "tags.st"])

    in_rounds(ladder_programs, check)
