"""End to end: the real server process over stdio (pytest-lsp), one capability per test."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from lsp_client import open_doc, wait_diagnostics
from lsprotocol import types as t
from pytest_lsp import LanguageClient

from interpreter.cli import main

pytestmark = pytest.mark.asyncio(loop_scope="module")

MOTION = """VAR
  Axis1, Master : AXIS_VIRTUAL;
  ctl, dac : MOTION_INSTRUCTION;
  prof : CAM_PROFILE[3];
  n : DINT;
END_VAR
IF n = 0 THEN
  MATC(Axis1, ctl, 0, prof, 1.0, 1.0, Once, Immediate, 0.0, 0, TimeDrivenMode);
END_IF;
"""


def pos(text: str, line: int, marker: str) -> t.Position:
    """The position just after `marker` on 0-based `line`."""
    return t.Position(line, text.splitlines()[line].index(marker) + len(marker))


async def complete(client: LanguageClient, uri: str, p: t.Position) -> list[t.CompletionItem]:
    result = await client.text_document_completion_async(
        t.CompletionParams(t.TextDocumentIdentifier(uri), p)
    )
    assert result is not None
    return result.items if isinstance(result, t.CompletionList) else result


async def test_diagnostics_equal_check_json(client: LanguageClient, tmp_path: Path, capsys) -> None:  # type: ignore[no-untyped-def]
    src = tmp_path / "bad.st"
    text = "VAR x : DINT; END_VAR\nx := y + 1;\nMATC(x);\n"
    src.write_text(text)
    uri = await open_doc(client, src, text)
    got = client.diagnostics[uri]
    capsys.readouterr()
    main(["check", str(src), "--format", "json"])
    want = json.loads(capsys.readouterr().out)
    assert [
        (d.code, d.range.start.line + 1, d.range.start.character + 1, d.message) for d in got
    ] == [(w["code"], w["line"], w["column"], w["message"]) for w in want]
    assert all(d.code_description is not None for d in got)  # links to docs/diagnostics.md


async def test_diagnostics_appear_and_clear_as_the_text_changes(
    client: LanguageClient, tmp_path: Path
) -> None:
    text = "VAR x : DINT; END_VAR\nx := 1;\n"
    uri = await open_doc(client, tmp_path / "edit.st", text)
    assert list(client.diagnostics[uri]) == []
    # Replace `1` (line 1, characters 5..6) by `y`: an undefined tag, E101.
    client.diagnostics.pop(uri)
    client.text_document_did_change(
        t.DidChangeTextDocumentParams(
            t.VersionedTextDocumentIdentifier(version=2, uri=uri),
            [t.TextDocumentContentChangePartial(t.Range(t.Position(1, 5), t.Position(1, 6)), "y")],
        )
    )
    diags = await wait_diagnostics(client, uri)
    assert [d.code for d in diags] == ["E101"]
    client.diagnostics.pop(uri)
    client.text_document_did_change(
        t.DidChangeTextDocumentParams(
            t.VersionedTextDocumentIdentifier(version=3, uri=uri),
            [t.TextDocumentContentChangePartial(t.Range(t.Position(1, 5), t.Position(1, 6)), "2")],
        )
    )
    assert list(await wait_diagnostics(client, uri)) == []


@pytest.mark.parametrize(
    ("marker", "labels", "detail"),
    [
        ("prof, 1.0, 1.0, ", ["once", "continuous"], "0: "),  # ExecutionMode
        ("Once, ", ["immediate", "pending"], "0: "),  # ExecutionSchedule
        ("0.0, 0, ", ["timedrivenmode", "masterdrivenmode"], "0: "),  # InstructionMode
    ],
)
async def test_enumeration_completion_at_matc_operands(
    client: LanguageClient, tmp_path: Path, marker: str, labels: list[str], detail: str
) -> None:
    uri = await open_doc(client, tmp_path / "m.st", MOTION)
    items = await complete(client, uri, pos(MOTION, 7, marker))
    enum_items = [i for i in items if i.kind == t.CompletionItemKind.EnumMember]
    assert [i.label for i in enum_items] == labels
    assert enum_items[0].detail is not None and enum_items[0].detail.startswith(detail)
    assert all(i.kind == t.CompletionItemKind.EnumMember for i in items)  # immediate: values only


async def test_tag_completion_offers_fitting_types_only(
    client: LanguageClient, tmp_path: Path
) -> None:
    uri = await open_doc(client, tmp_path / "m.st", MOTION)
    axes = await complete(client, uri, pos(MOTION, 7, "MATC("))
    assert sorted(i.label for i in axes) == ["Axis1", "Master"]
    controls = await complete(client, uri, pos(MOTION, 7, "MATC(Axis1, "))
    assert sorted(i.label for i in controls) == ["ctl", "dac"]


async def test_ladder_enumeration_uses_the_lower_case_text(
    client: LanguageClient, tmp_path: Path
) -> None:
    text = (
        "VAR ax : AXIS_VIRTUAL; c : MOTION_INSTRUCTION; go : BOOL; END_VAR\n"
        "XIC(go)MAM(ax,c,0,10,100,\n"
    )
    uri = await open_doc(client, tmp_path / "r.rll", text)
    items = await complete(client, uri, t.Position(1, len("XIC(go)MAM(ax,c,0,10,100,")))
    labels = [i.label for i in items if i.kind == t.CompletionItemKind.EnumMember]
    # MAM SpeedUnits: the documented text in lower case (SPEC 9.31), spaced as ladder writes it
    assert "units per sec" in labels


async def test_member_completion_on_axis_motion_instruction_and_udt(
    client: LanguageClient, tmp_path: Path
) -> None:
    text = (
        "TYPE Pt : STRUCT X : REAL; Y : REAL; END_STRUCT END_TYPE\n"
        "VAR ax : AXIS_VIRTUAL; c : MOTION_INSTRUCTION; p : Pt; n : DINT; END_VAR\n"
        "ax.\nc.\np.\nn.\n"
    )
    uri = await open_doc(client, tmp_path / "mem.st", text)
    axis = {i.label for i in await complete(client, uri, t.Position(2, 3))}
    assert {"ActualPosition", "CommandVelocity", "TimeCamStatus"} <= axis
    control = {i.label for i in await complete(client, uri, t.Position(3, 2))}
    assert {"EN", "DN", "ER", "PC", "IP", "ERR", "EXERR"} <= control
    assert [i.label for i in await complete(client, uri, t.Position(4, 2))] == ["X", "Y"]
    bits = [i.label for i in await complete(client, uri, t.Position(5, 2))]
    assert bits == [str(b) for b in range(32)]  # DINT: bits 0..31


async def test_hover_signature_and_definition(client: LanguageClient, tmp_path: Path) -> None:
    uri = await open_doc(client, tmp_path / "m.st", MOTION)
    h = await client.text_document_hover_async(
        t.HoverParams(t.TextDocumentIdentifier(uri), t.Position(7, 3))
    )
    assert h is not None and isinstance(h.contents, t.MarkupContent)
    assert h.contents.kind == t.MarkupKind.Markdown and "| ExecutionMode |" in h.contents.value
    tag = await client.text_document_hover_async(
        t.HoverParams(t.TextDocumentIdentifier(uri), t.Position(6, 4))
    )
    assert tag is not None and "DINT" in tag.contents.value  # type: ignore[union-attr]
    # `MATC(Axis1, ctl, 0, prof, 1.0, ` -> operand 5 (TimeScaling); m[1,2] would not count.
    sig = await client.text_document_signature_help_async(
        t.SignatureHelpParams(t.TextDocumentIdentifier(uri), pos(MOTION, 7, "prof, 1.0, "))
    )
    assert sig is not None and sig.active_parameter == 5
    assert sig.signatures[0].label.startswith("MATC(Axis, MotionControl, Direction")
    defs = await client.text_document_definition_async(
        t.DefinitionParams(t.TextDocumentIdentifier(uri), pos(MOTION, 7, "MATC(Axi"))
    )
    assert defs and defs[0].range.start.line == 1  # type: ignore[index,union-attr]


async def test_symbols_and_tokens(client: LanguageClient, tmp_path: Path) -> None:
    uri = await open_doc(client, tmp_path / "m.st", MOTION)
    symbols = await client.text_document_document_symbol_async(
        t.DocumentSymbolParams(t.TextDocumentIdentifier(uri))
    )
    names = {s.name for s in symbols or []}
    assert {"Axis1", "Master", "ctl", "dac", "prof", "n"} <= names
    tokens = await client.text_document_semantic_tokens_full_async(
        t.SemanticTokensParams(t.TextDocumentIdentifier(uri))
    )
    assert tokens is not None and len(tokens.data) % 5 == 0 and tokens.data


async def test_l5x_positions_are_file_positions(client: LanguageClient, tmp_path: Path) -> None:
    fixture = Path(__file__).resolve().parents[1] / "l5x" / "fixtures" / "st_errors.L5X"
    text = fixture.read_text()
    copy = tmp_path / "st_errors.L5X"
    copy.write_text(text)
    uri = await open_doc(client, copy, text)
    e101 = next(d for d in client.diagnostics[uri] if d.code == "E101")
    # tests/l5x/test_malformed.py: line 16, columns 12..19 of the file (1-based).
    assert (e101.range.start.line, e101.range.start.character, e101.range.end.character) == (
        15,
        11,
        18,
    )


async def test_unknown_document_and_bad_positions_get_empty_answers(client: LanguageClient) -> None:
    ghost = t.TextDocumentIdentifier("file:///nowhere/ghost.st")
    assert await client.text_document_hover_async(t.HoverParams(ghost, t.Position(0, 0))) is None
    items = await client.text_document_completion_async(
        t.CompletionParams(ghost, t.Position(999, 999))
    )
    assert (
        items is None or items == [] or (isinstance(items, t.CompletionList) and items.items == [])
    )


async def test_code_actions_take_the_suggestion_or_declare_the_tag(
    client: LanguageClient, tmp_path: Path
) -> None:
    text = "VAR Speed : REAL; ax : AXIS_VIRTUAL; END_VAR\nSpeed := Sped + 1.0;\nMSO(axis2, ctl);\n"
    uri = await open_doc(client, tmp_path / "fix.st", text)
    diags = list(client.diagnostics[uri])
    sped = next(d for d in diags if "'Sped'" in d.message)
    result = await client.text_document_code_action_async(
        t.CodeActionParams(t.TextDocumentIdentifier(uri), sped.range, t.CodeActionContext([sped]))
    )
    titles = [a.title for a in result or [] if isinstance(a, t.CodeAction)]
    assert "Change to 'Speed'" in titles
    ctl = next(d for d in diags if "'ctl'" in d.message)
    result = await client.text_document_code_action_async(
        t.CodeActionParams(t.TextDocumentIdentifier(uri), ctl.range, t.CodeActionContext([ctl]))
    )
    declare = next(
        a for a in result or [] if isinstance(a, t.CodeAction) and a.title.startswith("Declare")
    )
    # MSO's second operand is a MOTION_INSTRUCTION; the one-line VAR block gets the
    # declaration just before its END_VAR (column 38, 0-based).
    assert declare.title == "Declare 'ctl' as MOTION_INSTRUCTION"
    assert declare.edit is not None and declare.edit.changes is not None
    [edit] = declare.edit.changes[uri]
    assert edit.new_text == "ctl : MOTION_INSTRUCTION; "
    assert (edit.range.start.line, edit.range.start.character) == (0, text.index("END_VAR"))


async def test_l5x_edit_inside_a_rung_equals_check_json(  # type: ignore[no-untyped-def]
    client: LanguageClient, tmp_path: Path, capsys
) -> None:
    # An edit inside one rung's text is patched into the last analysis (decision 0117); what
    # is published must still be what `check` prints for the edited file.
    fixture = Path(__file__).parent / "fixtures" / "two_programs.L5X"
    text = fixture.read_text()
    path = tmp_path / "two_programs.L5X"
    uri = await open_doc(client, path, text)
    assert [d.code for d in client.diagnostics[uri]] == ["U306", "W203"]
    at = text.index("XIC(Start)OTE(Run);") + len("XIC(Sta")
    line = text.count("\n", 0, at)
    col = at - text.rfind("\n", 0, at) - 1
    client.diagnostics.pop(uri)
    client.text_document_did_change(
        t.DidChangeTextDocumentParams(
            t.VersionedTextDocumentIdentifier(version=2, uri=uri),
            [
                t.TextDocumentContentChangePartial(
                    t.Range(t.Position(line, col), t.Position(line, col + 1)), "k"
                )
            ],
        )
    )
    got = await wait_diagnostics(client, uri)
    edited = text[:at] + "k" + text[at + 1 :]
    path.write_text(edited)
    capsys.readouterr()
    main(["check", str(path), "--format", "json"])
    want = json.loads(capsys.readouterr().out)
    assert [
        (d.code, d.range.start.line + 1, d.range.start.character + 1, d.message) for d in got
    ] == [(w["code"], w["line"], w["column"], w["message"]) for w in want]
    assert [w["code"] for w in want] == ["E101", "U306", "W203"]
