"""An export re-analysed after an edit inside one routine's text (decision 0117): only that
routine is read and verified again, and the diagnostics always equal a fresh analysis of the
same text, which is what `logixst check` prints (test_server.py compares the two end to end).

The fixture has two programs; P1's routines use one motion control tag twice (W203 at the
second use, naming the line of the first) and one module's I/O tags twice (one U306, at the
first use), so that a routine's check depends on the routines before it.
"""

from __future__ import annotations

import json
import random
from pathlib import Path

import pytest

from interpreter.cli import main
from interpreter.semantics.document import analyse_project
from interpreter.semantics.incremental import ExportState, changed
from lsp.workspace import Workspace

FIXTURE = Path(__file__).parent / "fixtures" / "two_programs.L5X"
TEXT = FIXTURE.read_text(encoding="utf-8")
PATH = "/virtual/two_programs.L5X"


def fresh(text: str) -> list[tuple[str, str, tuple[int, int, int, int]]]:
    return summary(analyse_project(PATH, text.encode("utf-8")).diagnostics)


def summary(diags) -> list[tuple[str, str, tuple[int, int, int, int]]]:  # type: ignore[no-untyped-def]
    return [(d.code, d.message, tuple(d.span)) for d in diags]


def replace(text: str, old: str, new: str) -> str:
    assert text.count(old) == 1, old
    return text.replace(old, new)


def line_col(text: str, marker: str) -> tuple[int, int]:
    """1-based line and column of `marker`'s first character."""
    at = text.index(marker)
    return text.count("\n", 0, at) + 1, at - text.rfind("\n", 0, at)


def state_for(text: str) -> ExportState:
    return ExportState.read(PATH, text.encode("utf-8"))


def test_the_fixture_as_check_sees_it() -> None:
    got = fresh(TEXT)
    assert [c for c, _, _ in got] == ["U306", "W203"]
    # W203 at `mc` of MSF in Sub names the line of MSO(ax,mc) in Main
    assert "(line 27)" in got[1][1] and line_col(TEXT, "<![CDATA[XIC(Run)MSO")[0] == 27


def test_edit_inside_a_rung_patches_one_routine() -> None:
    state = state_for(TEXT)
    text = replace(TEXT, "XIC(Start)OTE(Run);", "XIC(Stark)OTE(Run);")
    loaded = state.update(text.encode("utf-8"))
    assert loaded is not None  # patched, not read again
    got = summary(loaded.diagnostics)
    assert got == fresh(text)
    line, col = line_col(text, "Stark")
    e101 = [g for g in got if g[0] == "E101"]
    assert len(e101) == 1 and e101[0][2] == (line, col, line, col + len("Stark"))
    assert "(program P1, routine Main, rung 0)" in e101[0][1]
    # and back: the error goes, the rest stays
    loaded = state.update(TEXT.encode("utf-8"))
    assert loaded is not None and summary(loaded.diagnostics) == fresh(TEXT)


def test_edit_inside_an_st_line_and_a_comment() -> None:
    state = state_for(TEXT)
    text = replace(TEXT, "n := n + 1;", "n := n + q;")
    loaded = state.update(text.encode("utf-8"))
    assert loaded is not None
    assert summary(loaded.diagnostics) == fresh(text)
    assert [c for c, _, _ in summary(loaded.diagnostics)].count("E101") == 1
    text = replace(text, "Seal in", "Seal it in")
    loaded = state.update(text.encode("utf-8"))
    assert loaded is not None and summary(loaded.diagnostics) == fresh(text)
    main_routine = loaded.model.routine("Main", "P1")
    assert main_routine is not None and main_routine.rungs[0].comment == "Seal it in"


def test_second_use_of_a_control_tag_edited_in_place() -> None:
    # Sub's MSF is the second use of mc: renaming it there drops W203 (an E101 instead) and
    # changes nothing the routines after Sub depend on, so Sub alone is checked again.
    state = state_for(TEXT)
    text = replace(TEXT, "MSF(ax,mc)", "MSF(ax,mx)")
    loaded = state.update(text.encode("utf-8"))
    assert loaded is not None
    assert [c for c, _, _ in summary(loaded.diagnostics)] == ["U306", "E101"]
    assert summary(loaded.diagnostics) == fresh(text)


def test_first_uses_moved_give_a_full_analysis() -> None:
    # Main holds the first use of mc and of module Local:1: edits there change what Sub sees
    # (no W203 any more; the U306 moves to Sub), so they are not patched.
    for old, new in (("MSO(ax,mc)", "MSO(ax,mx)"), ("Local:1:I.Data.0", "Local:2:I.Data.0")):
        ws = Workspace()
        ws.open("file://" + PATH, TEXT)
        ws.analyse("file://" + PATH)
        state = ws._exports["file://" + PATH]
        text = replace(TEXT, old, new)
        assert state_for(TEXT).update(text.encode("utf-8")) is None
        ws.change("file://" + PATH, text, 2)
        an = ws.analyse("file://" + PATH)
        assert an is not None and summary(an.diagnostics) == fresh(text)
        assert ws._exports["file://" + PATH] is not state  # read again
    text = replace(TEXT, "MSO(ax,mc)", "MSO(ax,mx)")
    assert "W203" not in [c for c, _, _ in fresh(text)]
    text = replace(TEXT, "Local:1:I.Data.0", "Local:2:I.Data.0")
    assert [c for c, _, _ in fresh(text)] == ["U306", "U306", "W203"]


def test_declaration_and_structure_edits_are_read_again() -> None:
    edits = [
        ('Name="Run" TagType="Base" DataType="BOOL"', 'Name="Run" TagType="Base" DataType="DINT"'),
        ('Name="n" TagType', 'Name="m" TagType'),  # a tag renamed: uses of n become E101
        ("XIC(Start)OTE(Run);]]>", "XIC(Start)OTE(Run);]]>]]>"),  # breaks the XML
        ("XIC(Start)OTE(Run);", "XIC(Start)]]>OTE(Run);"),  # ends the CDATA early
        ("XIC(Start)OTE(Run);", "XIC(Start)\nOTE(Run);"),  # a new line moves every line below
        ("XIC(Start)OTE(Run);", "XIC(Start)\x01OTE(Run);"),  # not an XML character
        ('<Rung Number="3" Type="N">', '<Rung Number="3" Type="N" >'),
    ]
    for old, new in edits:
        text = replace(TEXT, old, new)
        assert state_for(TEXT).update(text.encode("utf-8")) is None, new
        ws = Workspace()
        uri = "file://" + PATH
        ws.open(uri, TEXT)
        ws.analyse(uri)
        ws.change(uri, text, 2)
        an = ws.analyse(uri)
        assert an is not None and summary(an.diagnostics) == fresh(text), new
    assert "E101" in [c for c, _, _ in fresh(replace(TEXT, 'Name="n" TagType', 'Name="m" TagType'))]
    broken = fresh(replace(TEXT, "XIC(Start)OTE(Run);]]>", "XIC(Start)OTE(Run);]]>]]>"))
    assert [c for c, _, _ in broken] == ["S007"]


def test_changed_finds_the_edit() -> None:
    assert changed(b"abcdef", b"abXdef") == (2, 3, 3)
    assert changed(b"abcdef", b"abcXdef") == (3, 3, 4)
    assert changed(b"abcdef", b"abef") == (2, 4, 2)
    assert changed(b"aaaa", b"aaaaa") == (4, 4, 5)  # the longest common prefix comes first
    assert changed(b"", b"x") == (0, 0, 1)


PIECES = ["\r\n", "XIC(Run)", "OTE(", ")", ";", "mc", "ax", ",", "[", "]", "n", "1", " ", "+", ":=",
          "Start", "Local:1:I.Data.3", "MSF(ax,mc)", "é", "]]>", "<", "&", "\n", "\r", "\x01"]  # fmt: skip


@pytest.mark.parametrize("newline", ["\n", "\r\n"], ids=["lf", "crlf"])
def test_random_edits_inside_routine_texts_equal_a_fresh_analysis(newline: str) -> None:
    """Seeded random inserts and deletes, mostly inside rung and ST line texts, applied one
    after another to one open document: after each, the analysis equals a fresh one. The
    export is also written with CR LF line ends (as on Windows), with multi-line comments."""
    rng = random.Random(f"logixst-incremental-{newline!r}")
    ws = Workspace()
    uri = "file://" + PATH
    start = TEXT.replace("Seal in", "Seal in\nand hold").replace("\n", newline)
    text = start
    ws.open(uri, text)
    ws.analyse(uri)
    patched = 0
    for version in range(2, 402):
        starts = [i + len("<![CDATA[") for i in range(len(text)) if text.startswith("<![CDATA[", i)]
        if rng.random() < 0.9 and starts:
            at = rng.choice(starts)
            end = text.find("]]>", at)
            at = rng.randint(at, max(at, end if end >= 0 else at))
        else:
            at = rng.randrange(len(text) + 1)
        if rng.random() < 0.4:
            text = text[:at] + text[at + rng.randrange(1, 4) :]
        else:
            text = text[:at] + rng.choice(PIECES) + text[at:]
        before = ws._exports.get(uri)
        ws.change(uri, text, version)
        an = ws.analyse(uri)
        assert an is not None
        want = fresh(text)
        assert summary(an.diagnostics) == want, (version, text)
        patched += ws._exports.get(uri) is before
        if any(code == "S007" for code, _, _ in want):
            text = start  # the XML is broken: start again from the fixture (a full read)
    assert patched > 150  # most edits took the patch (the rest were read again)


def test_patched_equals_check_json(tmp_path: Path, capsys) -> None:  # type: ignore[no-untyped-def]
    state = state_for(TEXT)
    text = replace(TEXT, "XIO(Run)MSF(ax,mc);", "XIO(Run)MSF(ax,mc)OTE(Nope);")
    loaded = state.update(text.encode("utf-8"))
    assert loaded is not None
    path = tmp_path / "two_programs.L5X"
    path.write_text(text, encoding="utf-8")
    capsys.readouterr()
    main(["check", str(path), "--format", "json"])
    want = json.loads(capsys.readouterr().out)
    assert [
        (d.code, d.span.line, d.span.col, d.span.end_line, d.span.end_col, d.message)
        for d in loaded.diagnostics
    ] == [
        (w["code"], w["line"], w["column"], w["endLine"], w["endColumn"], w["message"])
        for w in want
    ]
    assert [w["code"] for w in want] == ["U306", "W203", "E101"]


def test_an_element_after_the_text_on_its_line_is_not_moved() -> None:
    # Rung 0's text, its end tags and rung 1's start on one line: an edit in that text would
    # move rung 1's column, so it is read again; with only end tags after it, it is patched.
    one_line = replace(
        TEXT,
        'XIC(Start)OTE(Run);]]>\n</Text>\n</Rung>\n<Rung Number="1" Type="N">',
        'XIC(Start)OTE(Run);]]></Text></Rung><Rung Number="1" Type="N">',
    )
    text = replace(one_line, "XIC(Start)OTE(Run);", "XIC(Start)OTE(Runs);")
    assert state_for(one_line).update(text.encode("utf-8")) is None
    end_tags = replace(TEXT, "XIC(Start)OTE(Run);]]>\n</Text>", "XIC(Start)OTE(Run);]]></Text>")
    text = replace(end_tags, "XIC(Start)OTE(Run);", "XIC(Start)OTE(Runs);")
    state = ExportState.read(PATH, end_tags.encode("utf-8"))
    loaded = state.update(text.encode("utf-8"))
    assert loaded is not None
    assert summary(loaded.diagnostics) == summary(
        analyse_project(PATH, text.encode("utf-8")).diagnostics
    )
    assert "E101" in [c for c, _, _ in summary(loaded.diagnostics)]
