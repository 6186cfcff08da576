"""Helpers for the language server tests: open a document, wait for its diagnostics, put a
`logixst` command for this checkout on an editor's PATH."""

from __future__ import annotations

import asyncio
import sys
from pathlib import Path

from lsprotocol import types as t
from pytest_lsp import LanguageClient


async def open_doc(client: LanguageClient, path: Path, text: str) -> str:
    """Open `text` as the document at `path`; wait for its first diagnostics."""
    uri = path.resolve().as_uri()
    client.diagnostics.pop(uri, None)
    client.text_document_did_open(
        t.DidOpenTextDocumentParams(t.TextDocumentItem(uri, "plaintext", 1, text))
    )
    await wait_diagnostics(client, uri)
    return uri


async def wait_diagnostics(
    client: LanguageClient, uri: str, timeout: float = 10.0
) -> list[t.Diagnostic]:
    loop = asyncio.get_running_loop()
    end = loop.time() + timeout
    while uri not in client.diagnostics:
        if loop.time() > end:
            raise AssertionError(f"no diagnostics published for {uri}")
        await asyncio.sleep(0.02)
    return client.diagnostics[uri]


ROOT = Path(__file__).resolve().parents[2]


def logixst_shim(bin_dir: Path) -> Path:
    """A `logixst` command on PATH that runs this checkout's code, as the snippet calls it."""
    bin_dir.mkdir()
    shim = bin_dir / "logixst"
    shim.write_text(
        f"#!{sys.executable}\nimport sys\nsys.path.insert(0, {str(ROOT)!r})\n"
        "from interpreter.cli import entry\nsys.argv[0] = 'logixst'\nentry()\n"
    )
    shim.chmod(0o755)
    return bin_dir
