"""The VS Code extension (editors/vscode) and the Helix snippet (editors/helix).

Neither editor can be installed on these machines (no Debian package), so these tests check
what can be checked without them, and the README says so: the extension's manifest, its
script run under Node with VS Code's two modules replaced by recorders (the client it makes:
server command, documents, settings), and then the server started with exactly that command
and those initialization options; the Helix file parsed as TOML, naming the same command.
"""

from __future__ import annotations

import asyncio
import json
import os
import shutil
import subprocess
import tomllib
from pathlib import Path

import pytest
from lsp_client import ROOT, logixst_shim
from lsprotocol import types as t
from pytest_lsp import ClientServerConfig

VSCODE = ROOT / "editors" / "vscode"
HELIX = ROOT / "editors" / "helix" / "languages.toml"
PROBE = Path(__file__).with_name("vscode_probe.js")
NODE = shutil.which("node")


def manifest() -> dict:  # type: ignore[type-arg]
    return json.loads((VSCODE / "package.json").read_text())


def test_manifest_contributes_the_documents_and_settings() -> None:
    m = manifest()
    assert (VSCODE / m["main"]).is_file()
    assert m["engines"]["vscode"].startswith("^1.")
    assert m["dependencies"]["vscode-languageclient"].startswith("^9.")
    languages = {lang["id"]: lang["extensions"] for lang in m["contributes"]["languages"]}
    extensions = {e.lower() for exts in languages.values() for e in exts}
    assert extensions == {".st", ".rll", ".l5x", ".l5k"}  # SPEC 9.31: the documents we read
    assert {f"onLanguage:{lang}" for lang in languages} == set(m["activationEvents"])
    props = m["contributes"]["configuration"]["properties"]
    assert set(props) == {"logixst.path", "logixst.tags"}
    assert props["logixst.path"]["default"] == "logixst"


def probe(settings: dict[str, str]) -> dict:  # type: ignore[type-arg]
    assert NODE is not None
    done = subprocess.run(
        [NODE, str(PROBE), str(VSCODE / "extension.js")],
        capture_output=True,
        text=True,
        timeout=60,
        env=dict(os.environ, LOGIXST_SETTINGS=json.dumps(settings)),
        check=True,
    )
    return json.loads(done.stdout)  # type: ignore[no-any-return]


@pytest.mark.skipif(
    NODE is None, reason="Node.js is not installed (.ci/run installs the Debian package nodejs)"
)
def test_extension_starts_logixst_lsp_for_its_languages() -> None:
    out = probe({"logixst.tags": "/plant/tags.L5X"})
    assert out["subscriptions"] == 1 and out["started"]
    (client,) = out["made"]
    assert client["serverOptions"] == {"command": "logixst", "args": ["lsp"]}
    selector = client["clientOptions"]["documentSelector"]
    assert {s["language"] for s in selector} == {
        lang["id"] for lang in manifest()["contributes"]["languages"]
    }
    assert client["clientOptions"]["initializationOptions"] == {
        "logixst": {"tags": "/plant/tags.L5X"}
    }
    assert client["clientOptions"]["synchronize"] == {"configurationSection": "logixst"}
    other = probe({"logixst.path": "/opt/logixst/bin/logixst"})["made"][0]
    assert other["serverOptions"]["command"] == "/opt/logixst/bin/logixst"
    assert other["clientOptions"]["initializationOptions"] == {"logixst": {"tags": None}}


@pytest.mark.skipif(
    NODE is None, reason="Node.js is not installed (.ci/run installs the Debian package nodejs)"
)
def test_the_extensions_command_serves_with_its_options(tmp_path: Path) -> None:
    """The command line and initialization options the extension sends start a server that
    takes `logixst.tags`: a routine using a tag of that export checks clean."""
    tags = ROOT / "tests" / "l5x" / "fixtures" / "rll_project.L5X"
    client_options = probe({"logixst.tags": str(tags)})["made"][0]
    server = client_options["serverOptions"]
    work = tmp_path / "work"
    work.mkdir()
    prog = work / "uses_tags.st"
    text = "IF Start THEN Run := TRUE; END_IF;\n"  # Start and Run are tags of rll_project.L5X
    prog.write_text(text)
    env = dict(os.environ, PATH=f"{logixst_shim(tmp_path / 'bin')}{os.pathsep}{os.environ['PATH']}")

    async def session(options: object) -> list[str]:
        config = ClientServerConfig(
            server_command=[server["command"], *server["args"]], server_env=env
        )
        client = await config.start()
        await client.initialize_session(
            t.InitializeParams(
                capabilities=t.ClientCapabilities(),
                initialization_options=options,
            )
        )
        uri = prog.resolve().as_uri()
        client.text_document_did_open(
            t.DidOpenTextDocumentParams(t.TextDocumentItem(uri, "logix-st", 1, text))
        )
        for _ in range(500):
            if uri in client.diagnostics:
                break
            await asyncio.sleep(0.02)
        codes = [str(d.code) for d in client.diagnostics.get(uri, [None])]  # type: ignore[union-attr]
        await client.shutdown_session()
        await client.stop()
        return codes

    assert asyncio.run(session(client_options["clientOptions"]["initializationOptions"])) == []
    assert asyncio.run(session(None)) == ["E101", "E101"]  # without it Start and Run are unknown


def test_helix_snippet_names_the_server_and_the_documents() -> None:
    config = tomllib.loads(HELIX.read_text())
    assert config["language-server"]["logixst"] == {"command": "logixst", "args": ["lsp"]}
    (language,) = config["language"]
    assert language["language-servers"] == ["logixst"]
    assert {f.lower() for f in language["file-types"]} == {"st", "rll", "l5x", "l5k"}


def test_readme_shows_the_editor_files() -> None:
    readme = (ROOT / "README.md").read_text()
    assert HELIX.read_text().strip() in readme
    assert (VSCODE / "extension.js").read_text().strip() in readme
