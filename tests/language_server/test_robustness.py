"""10,000 seeded random edits per sample through the real server: it never crashes, answers
every request, and after the last edit publishes exactly what `check` says of the text."""

from __future__ import annotations

import json
import random
from pathlib import Path

import pytest
from lsp_client import open_doc, wait_diagnostics
from lsprotocol import types as t
from pytest_lsp import LanguageClient

from interpreter.cli import main

pytestmark = pytest.mark.asyncio(loop_scope="module")

SAMPLES = sorted((Path(__file__).resolve().parents[2] / "samples").iterdir())
EDITS = int(__import__("os").environ.get("LOGIXST_FUZZ_EDITS", "10000"))
BATCH = 250  # a request after each batch
PIECES = [
    # Structured Text
    "IF ", " THEN ", "END_IF;", "x := ", "1.5", ";", "(", ")", "MATC(", ", ", "CASE ", " OF ",
    "VAR ", "END_VAR", ".", "[", "]", "'str'", "(*", "*)", "//", "\n", ":=", "16#FF", ".5",
    # ladder
    "XIC(a)", "OTE(b)", "[", ",", "]", "MOV(", "TON(t,?,?)", "Units per sec", "N: ", "RC: \"",
    # garbage
    "\t", "é", "µ", "$", "#", "@", "]]>", "<", "&", "\"", "}", "{", "\\",
]  # fmt: skip
# No lone "\r": LSP counts it as a line break, so this test's own position arithmetic
# (which counts "\n") would send edits to other places than it applies them to locally.
# No NUL: one early NUL would make the rest of the run a binary document that is never
# analysed (test_nul_makes_a_document_binary covers that case).


def edit(rng: random.Random, text: str) -> tuple[int, int, str]:
    """A random insert or delete: (start offset, end offset, new text)."""
    start = rng.randrange(len(text) + 1)
    if text and rng.random() < 0.4:
        end = min(len(text), start + rng.randrange(1, 12))
        return start, end, ""
    return start, start, "".join(rng.choice(PIECES) for _ in range(rng.randrange(1, 4)))


def position(text: str, offset: int) -> t.Position:
    line = text.count("\n", 0, offset)
    return t.Position(line, offset - (text.rfind("\n", 0, offset) + 1))


@pytest.mark.parametrize("sample", SAMPLES, ids=lambda p: p.name)
async def test_random_edits(client: LanguageClient, tmp_path: Path, sample: Path, capsys) -> None:  # type: ignore[no-untyped-def]
    rng = random.Random(f"logixst-{sample.name}")
    path = tmp_path / sample.name  # alone in its directory: no sibling routines
    text = sample.read_text(encoding="utf-8")
    uri = await open_doc(client, path, text)
    version = 1
    for i in range(EDITS):
        start, end, new = edit(rng, text)
        version += 1
        client.text_document_did_change(
            t.DidChangeTextDocumentParams(
                t.VersionedTextDocumentIdentifier(version=version, uri=uri),
                [
                    t.TextDocumentContentChangePartial(
                        t.Range(position(text, start), position(text, end)), new
                    )
                ],
            )
        )
        text = text[:start] + new + text[end:]
        if i % BATCH == BATCH - 1:
            at = position(text, rng.randrange(len(text) + 1))
            doc = t.TextDocumentIdentifier(uri)
            kind = (i // BATCH) % 3
            if kind == 0:
                await client.text_document_completion_async(t.CompletionParams(doc, at))
            elif kind == 1:
                await client.text_document_hover_async(t.HoverParams(doc, at))
            else:
                await client.text_document_signature_help_async(t.SignatureHelpParams(doc, at))
    client.diagnostics.pop(uri, None)
    # The debounced diagnostics of the final text, then the same text through `check`.
    got = await wait_diagnostics(client, uri, timeout=60)
    path.write_text(text, encoding="utf-8", newline="")
    capsys.readouterr()
    main(["check", str(path), "--format", "json"])
    want = json.loads(capsys.readouterr().out)
    assert [
        (d.code, d.range.start.line + 1, d.range.start.character + 1, d.message) for d in got
    ] == [(w["code"], w["line"], w["column"], w["message"]) for w in want]
    assert client.error is None  # the server process is still alive and sane


async def test_nul_makes_a_document_binary(client: LanguageClient, tmp_path: Path, capsys) -> None:  # type: ignore[no-untyped-def]
    # `check` refuses a file with a NUL byte as input (exit 2, no diagnostics); the server
    # publishes no diagnostics for it and keeps answering.
    text = "VAR x : DINT; END_VAR\nx := y;\x00\n"
    path = tmp_path / "nul.st"
    path.write_text(text)
    capsys.readouterr()
    assert main(["check", str(path)]) == 2
    client.messages.clear()
    uri = await open_doc(client, path, text)
    assert list(client.diagnostics[uri]) == []
    # the editor is told why, once, in the CLI's words
    told = [m.message for m in client.messages if m.type == t.MessageType.Warning]
    assert told == [f"{path}: not a text file (it holds NUL bytes): not analysed"]
    doc = t.TextDocumentIdentifier(uri)
    assert await client.text_document_hover_async(t.HoverParams(doc, t.Position(1, 0))) is None


async def test_a_document_over_the_size_limit_is_refused_with_a_message(
    client: LanguageClient, tmp_path: Path
) -> None:  # type: ignore[no-untyped-def]
    # `check` refuses a .st file over 1 MB (docs/limits.md); the server analyses nothing and
    # says why once, then answers requests as usual
    text = "VAR x : DINT; END_VAR\n" + "// filler line of comment text\n" * 40_000  # 1.24 MB
    path = tmp_path / "big.st"
    client.messages.clear()
    uri = await open_doc(client, path, text)
    assert list(client.diagnostics[uri]) == []
    size = len(text.encode())
    told = [m.message for m in client.messages if m.type == t.MessageType.Warning]
    assert told == [
        f"{path.resolve()}: file is too large ({size:,} bytes; the limit is 1 MB): not analysed"
    ]
    doc = t.TextDocumentIdentifier(uri)
    assert await client.text_document_hover_async(t.HoverParams(doc, t.Position(0, 4))) is None
    client.text_document_did_close(t.DidCloseTextDocumentParams(doc))
