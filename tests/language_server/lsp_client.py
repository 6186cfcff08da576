"""A real `logixst lsp` process over stdio, driven by pytest-lsp (SPEC 8)."""

from __future__ import annotations

import asyncio
import sys
from pathlib import Path

import pytest_lsp
from lsprotocol import types as t
from pytest_lsp import ClientServerConfig, LanguageClient

ROOT = Path(__file__).resolve().parents[2]
SERVER = [
    sys.executable,
    "-c",
    "import sys; from interpreter.cli import main; sys.exit(main(['lsp']))",
]


@pytest_lsp.fixture(config=ClientServerConfig(server_command=SERVER), scope="module")
async def client(lsp_client: LanguageClient):  # type: ignore[no-untyped-def]
    await lsp_client.initialize_session(
        t.InitializeParams(capabilities=t.ClientCapabilities(), root_uri=ROOT.as_uri())
    )
    yield
    await lsp_client.shutdown_session()


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
