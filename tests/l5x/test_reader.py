"""The L5X reader: types, data, routines and tasks, with positions in the .L5X file."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from interpreter.cli import main
from interpreter.syntax import nodes as n
from interpreter.syntax.l5x import read_l5x
from interpreter.syntax.l5x_data import _L5KParser, parse_value
from interpreter.syntax.xml_reader import XmlRejected, parse_xml

FIX = Path(__file__).parent / "fixtures"


def read(name: str):  # type: ignore[no-untyped-def]
    path = FIX / name
    project, diags = read_l5x(path.read_bytes(), str(path))
    assert project is not None
    return project, diags


def line_of(name: str, needle: str) -> int:
    for i, line in enumerate((FIX / name).read_text().splitlines(), 1):
        if needle in line:
            return i
    raise AssertionError(needle)


def test_udt_bits_become_bool_members_and_the_host_is_dropped() -> None:
    p, diags = read("st_project.L5X")
    assert diags == []
    valve = next(t for t in p.types if t.name == "Valve")
    members = [(m.names[0][0], m.type.name, m.type.dims) for m in valve.members]
    assert members == [
        ("Open", "BOOL", []),
        ("Fault", "BOOL", []),
        ("Count", "DINT", []),
        ("Hist", "INT", [(0, 2)]),
    ]


def test_tasks_and_programs() -> None:
    p, _ = read("st_project.L5X")
    assert [
        (t.name, t.type, t.rate_ms, t.priority, [x for x, _ in t.programs]) for t in p.tasks
    ] == [
        ("MainTask", "CONTINUOUS", 10.0, 10, ["MainProgram"]),
        ("Every10", "PERIODIC", 10.0, 5, ["Fast"]),
    ]
    assert [(q.name, q.main, [r.name for r in q.routines]) for q in p.programs] == [
        ("MainProgram", "Main", ["Main", "Sub", "Unused"]),
        ("Fast", "Main", ["Main"]),
        ("Idle", "Main", ["Main"]),
    ]


def test_st_spans_point_into_the_file() -> None:
    p, _ = read("st_project.L5X")
    main = p.programs[0].routines[0]
    stmt = main.body[2]  # Gained(Sc, 1.5, Result, Counted);
    line = line_of("st_project.L5X", "Gained(Sc, 1.5")
    assert isinstance(stmt, n.CallStmt)
    # `<![CDATA[` takes columns 1-9, so the statement starts in column 10.
    assert (stmt.span.line, stmt.span.col) == (line, 10)
    assert p.context[line] == "program MainProgram, routine Main, line 2"


def test_rungs_keep_file_positions_numbers_and_comments() -> None:
    p, diags = read("rll_project.L5X")
    rungs = p.programs[0].routines[0].rungs
    assert [r.number for r in rungs] == [0, 1, 3]  # rung 2 has unbalanced brackets
    assert rungs[0].comment == "Seal in"
    line = line_of("rll_project.L5X", "[XIC(Start) ,XIC(Run) ]OTE(Run)")
    assert (rungs[0].span.line, rungs[0].span.col) == (line, 10)
    assert [(d.code, d.span.line, d.span.col) for d in diags] == [
        ("S006", line_of("rll_project.L5X", "[XIC(Start),XIC(Run)OTE"), 10)
    ]
    assert "rung 2" in diags[0].message


def test_rung_with_unbalanced_brackets_via_cli(capsys: pytest.CaptureFixture[str]) -> None:
    capsys.readouterr()
    code = main(["check", str(FIX / "rll_project.L5X"), "--format", "json"])
    diags = json.loads(capsys.readouterr().out)
    assert code == 1
    # U304 only while the ladder TON implementation is not merged
    assert [d["code"] for d in diags if d["code"] != "U304"] == ["S006"]


def test_l5k_timer_data_is_unpacked() -> None:
    p, _ = read("rll_project.L5X")
    delay = next(t for t in p.tags if t.names[0][0] == "Delay")
    assert isinstance(delay.init, n.StructInit)
    values = {name: v.value for name, _, v in delay.init.members}  # type: ignore[union-attr]
    # [control word 0, PRE 500, ACC 0]: EN, TT and DN are bits 31, 30, 29 of the word
    assert values == {"PRE": 500, "ACC": 0, "EN": 0, "TT": 0, "DN": 0}


@pytest.mark.parametrize(
    ("text", "radix", "dtype", "value"),
    [
        ("42", "Decimal", "DINT", 42),
        ("-7", "Decimal", "INT", -7),
        ("16#0000_00ff", "Hex", "DINT", 255),
        ("16#ffff_ffff", "Hex", "DINT", -1),  # a bit pattern: DINT -1
        ("2#0000_0101", "Binary", "SINT", 5),
        ("8#17", "Octal", "DINT", 15),
        ("'AB'", "ASCII", "INT", 0x4142),
        ("1.5", "Float", "REAL", 1.5),
        ("1.50000000e+002", "Exponential", "REAL", 150.0),
    ],
)
def test_decorated_values_in_every_radix(text: str, radix: str, dtype: str, value: object) -> None:
    assert parse_value(text, radix, dtype) == value


def test_l5k_parser_nests() -> None:
    assert _L5KParser("[1,[2,3.5],'a$'b',[]]").parse() == [1, [2, 3.5], b"a'b", []]


def test_xml_positions_are_characters_not_bytes() -> None:
    # 'é' is two bytes in UTF-8; the element after it is still column 3 of line 1.
    root, pos = parse_xml("<a>é<b/></a>".encode())
    assert pos.elem_span(root.children[0])[:2] == (1, 5)


def test_doctype_is_refused_at_its_position() -> None:
    with pytest.raises(XmlRejected) as exc:
        parse_xml(
            b'<?xml version="1.0"?>\n<!DOCTYPE a SYSTEM "http://example.invalid/x.dtd">\n<a/>'
        )
    assert exc.value.line == 2


def test_context_exports_with_studio_details_read_without_syntax_errors() -> None:
    # Hand-made after the shape of real v32 exports: Use="Context", StringFamily UDT, ASCII
    # and Octal radix members, L5K data across lines with tabs, an empty Prescan routine,
    # Comments with Operand, a MESSAGE tag with its own data format.
    p, diags = read("studio_features.L5X")
    assert diags == []
    pair = p.tags[0].init
    assert isinstance(pair, n.StructInit)
    # L5K [8, 1094861636, 8]: the hidden SINT host is 8 = bit 3 set, so Flag (BitNumber 3) = 1
    assert {name: v.value for name, _, v in pair.members} == {
        "Flag": 1,
        "Code": 1094861636,
        "Mode": 8,
    }  # type: ignore[union-attr]
    assert p.tags[1].init.value == b"ok"  # type: ignore[union-attr]
    assert [r.number for r in p.programs[0].routines[0].rungs] == [7, 8]
