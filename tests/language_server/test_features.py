"""The protocol-free features, called directly (the server tests cover the wire)."""

from __future__ import annotations

from pathlib import Path

import pytest

from interpreter.syntax import nodes as n
from lsp.features.actions import actions
from lsp.features.context import Where, classify
from lsp.workspace import Workspace


def ctx(text: str, language: str = "st"):  # type: ignore[no-untyped-def]
    """Classify at the `|` marker."""
    at = text.index("|")
    return classify(text.replace("|", ""), at, language)


@pytest.mark.parametrize(
    ("text", "name", "index"),
    [
        ("MATC(a, |", "MATC", 1),
        ("MATC(a, m[1,2], |", "MATC", 2),  # commas inside [] do not count
        ("MAM(ax, c, 0, ABS(x, y), |", "MAM", 4),  # nor inside a nested call
        ("x := 1;\nMAM(ax, c, 0, 'a,b', |", "MAM", 4),  # nor inside a string
        ("MAM(ax, c, 0, (* , *) |", "MAM", 3),  # nor inside a comment
        ("MAM(ax, c, 0, 10, 100, Units per s|", "MAM", 5),
    ],
)
def test_operand_index_counts_top_level_commas(text: str, name: str, index: int) -> None:
    c = ctx(text)
    assert (c.where, c.instruction, c.index) == (Where.OPERAND, name, index)


def test_contexts() -> None:
    assert ctx("a.b[i, 2].|").where is Where.MEMBER
    assert ctx("a.b[i, 2].|").base == "a.b[i, 2]"
    assert ctx("VAR\n  x : |").where is Where.TYPE
    assert ctx("VAR\n  x : DINT := |").where is Where.VALUE
    assert ctx("VAR x : DINT; END_VAR\n|").where is Where.STATEMENT
    assert ctx("x := |").where is Where.VALUE
    assert ctx("// MAM(|").where is Where.NONE
    rung = ctx("XIC(a)[OTE(b) ,MOV(c,|", "rll")
    assert (rung.where, rung.instruction, rung.index, rung.language) == (
        Where.OPERAND,
        "MOV",
        1,
        "rll",
    )
    assert ctx("XIC(a)[|", "rll").where is Where.STATEMENT  # a new branch leg


def test_l5x_context_only_inside_routine_text() -> None:
    xml = '<Routine Name="R" Type="ST"><STContent><Line Number="0"><![CDATA[MATC(a, |]]></Line>'
    c = ctx(xml, "l5x")
    assert (c.where, c.instruction, c.language) == (Where.OPERAND, "MATC", "st")
    rung = '<Rung Number="0"><Text><![CDATA[XIC(a)OTE(|]]></Text>'
    assert ctx(rung, "l5x").language == "rll"
    assert ctx('<Tag Name="|', "l5x").where is Where.NONE


def test_declare_before_end_var_on_its_own_line(tmp_path: Path) -> None:
    ws = Workspace()
    text = "VAR\n  ax : AXIS_VIRTUAL;\nEND_VAR\nMSO(ax, mc);\n"
    uri = (tmp_path / "a.st").as_uri()
    ws.open(uri, text)
    an = ws.analyse(uri)
    assert an is not None
    [d] = [x for x in an.diagnostics if x.code == "E101"]
    found = actions(an, d.code, d.message, d.span)
    assert [a.title for a in found] == ["Declare 'mc' as MOTION_INSTRUCTION"]
    [edit] = found[0].edits
    assert edit.span == n.Span(3, 1, 3, 1) and edit.text == "  mc : MOTION_INSTRUCTION;\n"


def test_declarations_still_known_while_the_text_does_not_parse(tmp_path: Path) -> None:
    ws = Workspace()
    uri = (tmp_path / "a.st").as_uri()
    ws.open(uri, "VAR\n  ax : AXIS_VIRTUAL;\nEND_VAR\nMSO(ax, \n")
    an = ws.analyse(uri)
    assert an is not None
    assert [d.code for d in an.diagnostics] == ["S001"]  # what check says of the text
    assert "AX" in an.loaded.model.tags  # and completion still knows the axis


def test_completion_narrows_to_the_typed_prefix_and_caps_the_list(tmp_path: Path) -> None:
    from lsp.features.completion import MAX_ITEMS, complete_list

    decls = "".join(f"  tag{i} : DINT;\n" for i in range(MAX_ITEMS + 50))
    text = f"VAR\n  Speed, Spare : REAL;\n{decls}END_VAR\nSp\nx\n"
    ws = Workspace()
    uri = (tmp_path / "a.st").as_uri()
    ws.open(uri, text)
    an = ws.analyse(uri)
    assert an is not None
    line = text.count("\n", 0, text.index("Sp\n"))
    items, incomplete = complete_list(an, line, 2)  # after "Sp"
    assert sorted(i.label for i in items if i.kind == 6) == ["Spare", "Speed"]  # variables
    assert not incomplete
    items, incomplete = complete_list(an, line + 1, 0)  # a statement start: everything
    assert len(items) == MAX_ITEMS and incomplete


def test_var_block_found_beyond_the_context_window() -> None:
    from lsp.features.context import WINDOW

    decls = "".join(f"  a{i} : DINT;\n" for i in range(WINDOW // 10))
    text = "VAR\n" + decls + "  last : |"
    assert ctx(text).where is Where.TYPE  # the VAR opened more than WINDOW characters back


def test_hover_on_a_diagnostic_code_links_its_docs_section(tmp_path: Path) -> None:
    from lsp.features.hover import hover

    ws = Workspace()
    uri = (tmp_path / "a.st").as_uri()
    ws.open(uri, "// see E101 in the docs\n")
    an = ws.analyse(uri)
    assert an is not None
    md = hover(an, 0, 8)
    assert md is not None and md.startswith("**E101** (error): undefined tag")
    section = md.rsplit("#", 1)[1].rstrip(")")
    docs = (Path(__file__).resolve().parents[2] / "docs" / "diagnostics.md").read_text()
    assert "## E101 undefined tag" in docs and section == "e101-undefined-tag"
