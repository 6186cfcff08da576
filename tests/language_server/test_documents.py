"""The server's document applies an incremental change by splicing the text (server.py
FastDocument); pygls' own TextDocument rebuilds it line by line. Both must give the same text
for any change, so pygls' implementation is the reference here."""

from __future__ import annotations

import random

from lsprotocol import types as t
from pygls.workspace.position_codec import PositionCodec
from pygls.workspace.text_document import TextDocument

from lsp.lines import line_start
from lsp.server import FastDocument

PIECES = ["a", "XIC(b)", "\n", "é", "😋", " ", ";", "]]>", "\t"]  # 😋: two UTF-16 units


def test_line_start_against_split() -> None:
    rng = random.Random("lines")
    text = "".join(rng.choice(["ab", "\n", "é", "x"]) for _ in range(3000))
    starts = [0]
    for line in text.split("\n")[:-1]:
        starts.append(starts[-1] + len(line) + 1)
    for _ in range(3000):  # random order: the remembered line is sometimes after, sometimes before
        k = rng.randrange(len(starts) + 3)
        assert line_start(text, k) == (starts[k] if k < len(starts) else len(text))


def test_fast_document_equals_pygls_document() -> None:
    for encoding in (t.PositionEncodingKind.Utf16, t.PositionEncodingKind.Utf8):
        rng = random.Random(f"documents-{encoding}")
        codec = PositionCodec(encoding)
        source = "".join(rng.choice(PIECES) for _ in range(400))
        ref = TextDocument("file:///r.st", source, position_codec=codec)
        fast = FastDocument("file:///f.st", source, position_codec=codec)
        for _ in range(1500):
            lines = ref.source.split("\n")
            a = rng.randrange(len(lines) + 1)
            b = min(len(lines), a + rng.choice([0, 0, 0, 1, 2]))
            # positions on the line (pygls and the LSP differ past a line's end: see below)
            ca = rng.randrange(len(lines[a]) + 1) if a < len(lines) else 0
            cb = rng.randrange(len(lines[b]) + 1) if b < len(lines) else 0
            if b == a:
                cb = max(ca, cb)
            text = "".join(rng.choice(PIECES) for _ in range(rng.randrange(0, 3)))
            change = t.TextDocumentContentChangePartial(
                t.Range(t.Position(a, ca), t.Position(b, cb)), text
            )
            ref.apply_change(change)
            change = t.TextDocumentContentChangePartial(
                t.Range(t.Position(a, ca), t.Position(b, cb)), text
            )
            fast.apply_change(change)
            assert fast.source == ref.source
        assert fast._plain  # the splice path was the one taken
        # a CR (or another break pygls splits lines at) hands the text to pygls' own way
        change = t.TextDocumentContentChangePartial(
            t.Range(t.Position(0, 0), t.Position(0, 0)), "a\r\nb"
        )
        for doc in (ref, fast):
            doc.apply_change(change)
        assert fast.source == ref.source and fast._plain is False


def test_fast_document_on_a_text_with_only_newlines() -> None:
    # no CR, form feed or other break: the splice path itself (the test above soon holds CR LF)
    rng = random.Random("plain")
    source = "\n".join("XIC(a)OTE(b);" * rng.randrange(1, 4) for _ in range(200)) + "\n"
    ref = TextDocument("file:///r.st", source)
    fast = FastDocument("file:///f.st", source)
    for _ in range(1000):
        lines = ref.source.split("\n")
        a = rng.randrange(len(lines))
        ca = rng.randrange(len(lines[a]) + 1)
        b = min(len(lines) - 1, a + rng.choice([0, 0, 1]))
        cb = (
            rng.randrange(len(lines[b]) + 1) if b > a else min(len(lines[a]), ca + rng.randrange(3))
        )
        text = rng.choice(["", "x", "é", "😋", "\n", "OTE(c)"])
        for doc in (ref, fast):
            doc.apply_change(
                t.TextDocumentContentChangePartial(
                    t.Range(t.Position(a, ca), t.Position(b, cb)), text
                )
            )
        assert fast.source == ref.source
    assert fast._plain  # the splice path was the one taken


def test_a_position_past_the_line_end_is_the_line_end() -> None:
    # LSP: "If the character value is greater than the line length it defaults back to the
    # line length" (the line break not included).
    doc = FastDocument("file:///f.st", "ab\ncd\n")
    doc.apply_change(
        t.TextDocumentContentChangePartial(t.Range(t.Position(0, 9), t.Position(0, 12)), "X")
    )
    assert doc.source == "abX\ncd\n"
    doc.apply_change(
        t.TextDocumentContentChangePartial(t.Range(t.Position(1, 1), t.Position(1, 40)), "")
    )
    assert doc.source == "abX\nc\n"
    doc.apply_change(  # a line past the last: at the end of the text
        t.TextDocumentContentChangePartial(t.Range(t.Position(7, 0), t.Position(7, 0)), "e")
    )
    assert doc.source == "abX\nc\ne"
