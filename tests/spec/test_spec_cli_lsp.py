"""SPEC audit (session 6) of sections 1 (layout), 6 (command line), 8 (language server) and
9.31-9.32: one test per statement that the rest of tests/ does not already show.

Already shown elsewhere (not repeated here): exit codes 0-3 and one-line usage errors
(tests/test_cli_inputs.py, tests/language/test_cli.py), --watch forms, JSON value kinds,
progress bar, check text/json (tests/test_spec_conformance.py), github/sarif basics
(tests/language/test_check.py), --plot (tests/motion_programs/test_plot.py), --tcp
(tests/language_server/test_tcp.py), diagnostics on open/change, MATC enumeration completion
in ST, tag and member completion, instruction hover, signature help, tag definition,
symbols, tokens, L5X positions (tests/language_server/test_server.py), U diagnostics in
`run`/`check` (tests/language/test_unsupported.py), MSG/ASCII with nothing connected
(tests/instructions/test_communication.py).

The CLI is driven through `interpreter.cli.entry` (the console script's code path) in a
child process; the language server is a real `logixst lsp` process over stdio (pytest-lsp).
Expected values come from SPEC's words and the seed pages, worked out in the comments.
"""

from __future__ import annotations

import asyncio
import json
import re
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest
import pytest_lsp
from lsprotocol import types as t
from pytest_lsp import ClientServerConfig, LanguageClient

from tests.hardening.harness import ROOT, logixst

# ====================================================================== 1 layout
PYPROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text())
SEEDS = ("MATC", "MDAC", "MAOC", "MCCM", "MC_CamTableSelect", "MC_CamIn")  # SPEC intro


def _names(requirements: list[str]) -> set[str]:
    """Distribution names of PEP 508 requirement strings (`pygls>=2,<3` -> `pygls`)."""
    return {re.split(r"[<>=!~\[; ]", r, maxsplit=1)[0].lower() for r in requirements}


def test_pyproject_distribution_python_and_console_script() -> None:
    """SPEC 1: distribution `logixst`, Python >= 3.11, console script `logixst`."""
    project = PYPROJECT["project"]
    assert project["name"] == "logixst"
    assert project["requires-python"] == ">=3.11"
    module, _, func = project["scripts"]["logixst"].partition(":")
    # the script's target is a callable of the interpreter package
    r = subprocess.run(
        [sys.executable, "-c", f"import {module}; assert callable({module}.{func})"],
        cwd=ROOT,
        capture_output=True,
        text=True,
        check=False,
    )
    assert module.startswith("interpreter.") and r.returncode == 0, r.stderr


def test_pyproject_dependencies_and_extras() -> None:
    """SPEC 1: runtime deps lark, numpy, pygls (+ lsprotocol); plotting extra uses
    matplotlib; test extra pytest (+ pytest-lsp)."""
    project = PYPROJECT["project"]
    assert {"lark", "numpy", "pygls", "lsprotocol"} <= _names(project["dependencies"])
    extras = project["optional-dependencies"]
    assert "matplotlib" in _names(extras["plot"])
    assert {"pytest", "pytest-lsp"} <= _names(extras["test"])


@pytest.mark.parametrize(
    ("package", "parts"),
    [
        ("stdlib", ()),
        (
            "interpreter",
            (
                "syntax",
                "semantics",
                "compiler",
                "vm",
                "instructions",
                "motion",
                "runtime",
                "cli",
            ),
        ),
        ("lsp", ("server",)),
    ],
)
def test_packages_are_importable_with_their_parts(package: str, parts: tuple[str, ...]) -> None:
    """SPEC 1: importable packages `stdlib`, `interpreter` (syntax, semantics, compiler, vm,
    instruction implementations, numpy motion core, runtime, CLI) and `lsp`."""
    imports = "; ".join([f"import {package}"] + [f"import {package}.{p}" for p in parts])
    r = subprocess.run(
        [sys.executable, "-c", imports], cwd=ROOT, capture_output=True, text=True, check=False
    )
    assert r.returncode == 0, r.stderr


def test_stdlib_catalog_is_toml_data_with_a_small_loader() -> None:
    """SPEC 1: stdlib/ holds the catalog as TOML data files plus the small loader; the
    seed instructions' operand names live there."""
    tomls = list((ROOT / "stdlib").rglob("*.toml"))
    assert tomls
    text = "\n".join(p.read_text() for p in tomls)
    for name in ("MATC", "MDAC", "MAOC", "MCCM"):
        assert re.search(rf"^\s*name\s*=\s*\"{name}\"|^\[.*\b{name}\b", text, re.M), name


def test_language_server_is_pygls() -> None:
    """SPEC 1 / 8: lsp/ is the pygls language server."""
    r = subprocess.run(
        [
            sys.executable,
            "-c",
            "from pygls.lsp.server import LanguageServer; from lsp.server import server; "
            "assert isinstance(server, LanguageServer)",
        ],
        cwd=ROOT,
        capture_output=True,
        text=True,
        check=False,
    )
    assert r.returncode == 0, r.stderr


def test_benchmarks_are_not_run_by_default() -> None:
    """SPEC 1: benchmarks under tests/benchmarks, not run by default."""
    assert (ROOT / "tests" / "benchmarks").is_dir()
    assert "tests/benchmarks" in PYPROJECT["tool"]["pytest"]["ini_options"]["norecursedirs"]


def test_samples_cover_every_seed_instruction_in_each_input_kind() -> None:
    """SPEC 1: samples/ holds runnable, documented .st, .rll and .L5X programs covering every
    seed instruction."""
    samples = sorted((ROOT / "samples").iterdir())
    assert {".st", ".rll", ".l5x"} <= {p.suffix.lower() for p in samples}
    text = {p.name: p.read_text() for p in samples}
    for name in SEEDS:
        # called as an instruction, or declared as a function-block instance (`c : MC_CamIn;`)
        used = rf"\b{name}\s*\(|:\s*{name}\s*;"
        assert any(re.search(used, s) for s in text.values()), name
    for p in samples:  # documented: each starts with a comment saying what it shows
        head = text[p.name].lstrip()[:2]
        assert head in ("//", "(*", "<?"), p.name


def test_samples_check_clean() -> None:
    """SPEC 1: the samples are runnable: `check` finds no errors in any of them."""
    for p in sorted((ROOT / "samples").iterdir()):
        r = logixst("check", p, timeout=120)
        assert r.code == 0, (p.name, r.out)


def test_readme_set_up_usage_and_features() -> None:
    """SPEC 1: README has the two set-up commands, usage of every subcommand and a feature
    table; .ci/run runs exactly the README's test command."""
    readme = (ROOT / "README.md").read_text()
    setup = readme.split("## Set-up", 1)[1].split("\n## ", 1)[0]
    commands = re.findall(r"```sh\n(.*?)\n```", setup, re.S)
    assert len(commands) == 2
    for sub in ("run", "check", "lsp"):
        assert f"## `logixst {sub}`" in readme, sub
    features = readme.split("## Features", 1)[1]
    assert re.search(r"^\|.*\|\n\|[-|: ]+\|$", features, re.M)  # a markdown table
    ci = ROOT / ".ci" / "run"
    assert ci.stat().st_mode & 0o111  # executable
    # the README's test command is `pip install -e ".[test]" && python -m pytest`; .ci/run
    # runs its two halves
    install, _, test = commands[1].partition(" && ")
    ci_lines = [ln.strip() for ln in ci.read_text().splitlines()]
    assert f"python -m {install}" in ci_lines or install in ci_lines
    assert test in ci_lines


# ====================================================================== 6 command line
COUNTER = "VAR\n  n : DINT;\n  r : REAL;\nEND_VAR\nn := n + 1;\nr := r + 0.5;\n"


@pytest.fixture
def counter(tmp_path: Path) -> Path:
    p = tmp_path / "counter.st"
    p.write_text(COUNTER)
    return p


def test_every_run_option_of_the_synopsis_at_once(counter: Path, tmp_path: Path) -> None:
    """SPEC 6: `run PROGRAM... [--duration S] [--scan-period MS] [--coarse-update MS]
    [--set TAG=VALUE]... [--watch EXPR]... [--trace FILE.csv] [--plot FILE.png] [--json]
    [--tags FILE.L5X]`, spelled exactly so."""
    trace, plot = tmp_path / "t.csv", tmp_path / "p.png"
    r = logixst(
        "run",
        counter,
        "--duration",
        "0.02",
        "--scan-period",
        "4",
        "--coarse-update",
        "2",
        "--set",
        "n=10",
        "--set",
        "r=1.5",
        "--watch",
        "n",
        "--watch",
        "r",
        "--trace",
        trace,
        "--plot",
        plot,
        "--json",
        "--tags",
        ROOT / "samples" / "mixer.L5X",
        timeout=120,
    )
    assert r.code == 0, r.err
    report = json.loads(r.out)
    # 0.02 s / 4 ms = 5 scans; n = 10 + 5; r = 1.5 + 5 x 0.5; time = 5 x 4 ms
    assert (report["time"], report["scans"], report["tags"]) == (
        0.02,
        5,
        {"n": 15, "r": 4.0},
    )
    rows = trace.read_text().splitlines()
    assert rows[0] == "time,n,r" and len(rows) == 1 + 5
    assert plot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_json_report_is_the_one_object_on_stdout(counter: Path) -> None:
    """SPEC 6 / 9.32: with --json stdout is one object with exactly `time`, `scans`, `tags`,
    `faults`, `diagnostics` (and `unsupported`, SPEC 9.32); a clean run prints nothing on
    stderr."""
    r = logixst("run", counter, "--scans", "3", "--json", "--watch", "n", timeout=60)
    assert (r.code, r.err) == (0, "")
    report = json.loads(r.out)  # the whole of stdout is one JSON value
    assert report == {
        "time": 0.003,  # 3 scans x 1 ms (default --scan-period)
        "scans": 3,
        "tags": {"n": 3},
        "faults": [],
        "diagnostics": [],
        "unsupported": [],
    }


def test_run_warnings_go_to_stderr_and_into_the_report(tmp_path: Path) -> None:
    """SPEC 6 / 9.6 / 9.7: a run with warnings only runs (exit 0); the diagnostics are text
    on stderr (`path:line:col: warning CODE message`) and the report's `diagnostics` has the
    `check --format json` objects."""
    p = tmp_path / "w.st"
    # W201: the FOR index assigned in its body (a warning, SPEC 9.10): line 3, column 3
    p.write_text("VAR i, n : DINT; END_VAR\nFOR i := 0 TO 3 DO\n  i := i + 1;\nEND_FOR;\nn := 7;\n")
    r = logixst("run", p, "--scans", "1", "--json", "--watch", "n", timeout=60)
    assert r.code == 0
    [line] = r.err.splitlines()
    assert line.startswith(f"{p}:3:3: warning W201 ")
    report = json.loads(r.out)
    assert report["tags"] == {"n": 7}
    [d] = report["diagnostics"]
    assert set(d) == {
        "path",
        "line",
        "column",
        "endLine",
        "endColumn",
        "severity",
        "code",
        "message",
    }
    assert (d["path"], d["line"], d["column"], d["severity"], d["code"]) == (
        str(p),
        3,
        3,
        "warning",
        "W201",
    )
    assert line == f"{p}:3:3: warning W201 {d['message']}"


def test_run_table_without_json_is_on_stdout_only(counter: Path) -> None:
    """SPEC 6: without --json the watched values are a readable table on stdout."""
    r = logixst("run", counter, "--scans", "4", "--watch", "r", "--watch", "n", timeout=60)
    assert (r.code, r.err) == (0, "")
    # one row per watched expression, in the order given: r = 4 x 0.5, n = 4
    assert [ln.split() for ln in r.out.splitlines()] == [["r", "2.0"], ["n", "4"]]


@pytest.mark.parametrize("fmt", ["text", "json", "github", "sarif"])
def test_check_formats_are_spelled_as_in_the_synopsis(counter: Path, fmt: str) -> None:
    """SPEC 6: `check PATH... [--format text|json|github|sarif]`; a clean program exits 0."""
    r = logixst("check", counter, "--format", fmt, timeout=60)
    assert (r.code, r.err) == (0, "")


@pytest.mark.parametrize(
    "argv",
    [["--format", "xml"], ["--format"], []],
    ids=["unknown-format", "format-without-value", "no-path"],
)
def test_check_usage_errors_exit_2(counter: Path, argv: list[str]) -> None:
    """SPEC 6: check exits 2 on a usage error, with a clear message and no traceback."""
    paths = [counter] if argv else []
    r = logixst("check", *paths, *argv, timeout=60)
    assert (r.code, r.out) == (2, "")
    r.one_line_error("logixst: error:")


def test_lines_and_columns_are_one_based_in_every_format(tmp_path: Path) -> None:
    """SPEC 6: lines and columns are 1-based (the very first character is line 1, column 1)."""
    p = tmp_path / "first.st"
    p.write_text("nosuch := 1;\n")  # E101 undefined tag at the first character
    text = logixst("check", p, timeout=60)
    assert text.code == 1 and text.out.splitlines()[0].startswith(f"{p}:1:1: error E101 ")
    [d] = json.loads(logixst("check", p, "--format", "json", timeout=60).out)
    # `nosuch` is 6 characters: end column 7, one past its last (SPEC 9.7)
    assert (d["line"], d["column"], d["endLine"], d["endColumn"]) == (1, 1, 1, 7)
    gh = logixst("check", p, "--format", "github", timeout=60).out.strip()
    assert gh.startswith(f"::error file={p},line=1,col=1::")
    sarif = json.loads(logixst("check", p, "--format", "sarif", timeout=60).out)
    region = sarif["runs"][0]["results"][0]["locations"][0]["physicalLocation"]["region"]
    assert (region["startLine"], region["startColumn"]) == (1, 1)


def test_github_file_property_escapes_a_comma(tmp_path: Path) -> None:
    """SPEC 6: `github` workflow annotations, written as GitHub's runner reads them: a `,`
    in the file property is %2C (a bare one would end the property)."""
    folder = tmp_path / "line 1,2"
    folder.mkdir()
    p = folder / "m.st"
    # E101 at line 2, column 6; the message names the tag `pct`
    p.write_text("VAR n : DINT; END_VAR\nn := pct + 1;\n")
    r = logixst("check", p, "--format", "github", timeout=60)
    assert r.code == 1
    [line] = r.out.splitlines()
    escaped = str(p).replace(",", "%2C")
    assert line.startswith(f"::error file={escaped},line=2,col=6::E101 ")
    assert "," not in line.split("::")[1].split(",line=")[0]


def test_github_message_percent_is_escaped(tmp_path: Path) -> None:
    """SPEC 6: a `%` in a message is written %25 (GitHub decodes %25, %0D, %0A)."""
    p = tmp_path / "m.rll"
    # MAM SpeedUnits takes `Units per sec` or `% of Maximum`; `of Maximum` is unknown (E108)
    # and the did-you-mean names the value with its `%`
    p.write_text(
        "VAR ax : AXIS_VIRTUAL; c : MOTION_INSTRUCTION; go : BOOL; cd : REAL[4]; END_VAR\n"
        "XIC(go)MAM(ax,c,0,10,100,of Maximum,100,Units per sec2,100,Units per sec2,"
        "Trapezoidal,100,100,Units per sec3,Disabled,Programmed,0,0,0,cd);\n"
    )
    text = logixst("check", p, "--format", "json", timeout=60)
    [d] = json.loads(text.out)
    assert d["code"] == "E108" and "%" in d["message"]
    r = logixst("check", p, "--format", "github", timeout=60)
    [line] = r.out.splitlines()
    message = line.split("::", 2)[2]
    assert message == f"E108 {d['message']}".replace("%", "%25")


def test_sarif_locations_are_uri_references(tmp_path: Path) -> None:
    """SPEC 6: `sarif` SARIF 2.1.0, whose artifactLocation.uri is a URI reference: a path
    is kept as given, with a space percent-encoded (%20); a relative path stays relative."""
    folder = tmp_path / "my programs"
    folder.mkdir()
    (folder / "m.st").write_text("VAR n : DINT; END_VAR\nn := zz;\n")
    r = logixst("check", folder / "m.st", "--format", "sarif", timeout=60)
    [result] = json.loads(r.out)["runs"][0]["results"]
    uri = result["locations"][0]["physicalLocation"]["artifactLocation"]["uri"]
    assert uri == str(folder / "m.st").replace(" ", "%20")
    r = logixst("check", "my programs/m.st", "--format", "sarif", timeout=60, cwd=tmp_path)
    [result] = json.loads(r.out)["runs"][0]["results"]
    uri = result["locations"][0]["physicalLocation"]["artifactLocation"]["uri"]
    assert uri == "my%20programs/m.st"


PFL_TWICE = (
    "VAR f : DINT := 7; n, i : DINT; END_VAR\n"
    "FOR i := 1 TO 3 DO\n"
    "  PFL(f);\n"  # reached three times a scan
    "END_FOR;\n"
    "n := n + 1;\n"
    "IF n > 0 THEN PFL(f); END_IF;\n"  # a second place
)


def test_unsupported_places_each_listed_once_with_their_keys(tmp_path: Path) -> None:
    """SPEC 9.32: the report lists each place not simulated once under `unsupported` as
    {code, message, file, line, column}; the instruction does not execute (its operand keeps
    its value) and the rest runs."""
    p = tmp_path / "u.st"
    p.write_text(PFL_TWICE)
    r = logixst("run", p, "--scans", "4", "--json", "--watch", "n", "--watch", "f", timeout=60)
    assert r.code == 0
    report = json.loads(r.out)
    assert report["tags"] == {"n": 4, "f": 7}
    places = [(u["code"], u["file"], u["line"], u["column"]) for u in report["unsupported"]]
    # PFL at line 3 column 3 and line 6 column 15, however often each is reached
    assert places == [("U304", str(p), 3, 3), ("U304", str(p), 6, 15)]
    assert all(
        set(u) == {"code", "message", "file", "line", "column"} for u in report["unsupported"]
    )


@pytest.mark.parametrize("fmt", ["github", "sarif"])
def test_unsupported_is_a_warning_in_github_and_sarif(tmp_path: Path, fmt: str) -> None:
    """SPEC 9.32: U diagnostics are warnings, in every format; check exits 0."""
    p = tmp_path / "u.st"
    p.write_text(PFL_TWICE)
    r = logixst("check", p, "--format", fmt, timeout=60)
    assert r.code == 0
    if fmt == "github":
        lines = r.out.splitlines()
        assert lines[0].startswith(f"::warning file={p},line=3,col=3::U304 ")
        assert lines[1].startswith(f"::warning file={p},line=6,col=15::U304 ")
    else:
        results = json.loads(r.out)["runs"][0]["results"]
        assert [(x["ruleId"], x["level"]) for x in results] == [("U304", "warning")] * 2


# ====================================================================== 8 language server
SERVER = [
    sys.executable,
    "-c",
    "import sys; sys.argv = ['logixst', 'lsp']; from interpreter.cli import entry; entry()",
]


INITIALIZED: list[t.InitializeResult] = []  # the server's answer to `initialize`


@pytest_lsp.fixture(config=ClientServerConfig(server_command=SERVER), scope="module")
async def client(lsp_client: LanguageClient):  # type: ignore[no-untyped-def]
    result = await lsp_client.initialize_session(
        t.InitializeParams(capabilities=t.ClientCapabilities(), root_uri=ROOT.as_uri())
    )
    INITIALIZED[:] = [result]
    yield
    await lsp_client.shutdown_session()


lsp_mark = pytest.mark.asyncio(loop_scope="module")


async def _open(client: LanguageClient, path: Path, text: str, language_id: str) -> str:
    """Open `text` as the document at `path` (also written to disk); its first diagnostics."""
    path.write_text(text)
    uri = path.resolve().as_uri()
    client.diagnostics.pop(uri, None)
    client.text_document_did_open(
        t.DidOpenTextDocumentParams(t.TextDocumentItem(uri, language_id, 1, text))
    )
    for _ in range(500):
        if uri in client.diagnostics:
            return uri
        await asyncio.sleep(0.02)
    raise AssertionError(f"no diagnostics published for {uri}")


async def _complete(client: LanguageClient, uri: str, line: int, ch: int) -> list[t.CompletionItem]:
    result = await client.text_document_completion_async(
        t.CompletionParams(t.TextDocumentIdentifier(uri), t.Position(line, ch))
    )
    assert result is not None
    return result.items if isinstance(result, t.CompletionList) else result


async def _hover(client: LanguageClient, uri: str, line: int, ch: int) -> t.MarkupContent:
    h = await client.text_document_hover_async(
        t.HoverParams(t.TextDocumentIdentifier(uri), t.Position(line, ch))
    )
    assert h is not None and isinstance(h.contents, t.MarkupContent)
    return h.contents


def _end_of(text: str, line: int, marker: str) -> int:
    """Character just after `marker` on 0-based `line`."""
    return text.splitlines()[line].index(marker) + len(marker)


@lsp_mark
async def test_capabilities(client: LanguageClient) -> None:
    """SPEC 8: diagnostics on open/change, completion (`.` opens member completion),
    hover, signature help, go to definition, document symbols, semantic tokens."""
    server_caps = INITIALIZED[0].capabilities
    sync = server_caps.text_document_sync
    assert isinstance(sync, t.TextDocumentSyncOptions)
    assert sync.open_close and sync.change in (
        t.TextDocumentSyncKind.Full,
        t.TextDocumentSyncKind.Incremental,
    )
    assert server_caps.completion_provider is not None
    assert "." in (server_caps.completion_provider.trigger_characters or [])
    assert server_caps.hover_provider
    assert server_caps.signature_help_provider is not None
    assert server_caps.definition_provider
    assert server_caps.document_symbol_provider
    assert server_caps.semantic_tokens_provider is not None


LADDER_DECL = (
    "VAR ax : AXIS_VIRTUAL; c : MOTION_INSTRUCTION; p : CAM_PROFILE[4]; go, out : BOOL; END_VAR\n"
)


@lsp_mark
@pytest.mark.parametrize("language_id", ["st", "structured-text", "plaintext"])
async def test_language_is_chosen_by_extension(
    client: LanguageClient, tmp_path: Path, language_id: str
) -> None:
    """SPEC 9.31: the server picks the language by file extension, not `languageId`: a
    `.rll` document is ladder whatever the editor calls it."""
    # XIC(nosuch): as ladder, one E101 undefined tag at line 2, column 5 (0-based 1, 4);
    # read as ST the rung would be a syntax error (S...) instead
    text = LADDER_DECL + "XIC(nosuch)OTE(out);\n"
    uri = await _open(client, tmp_path / "r.rll", text, language_id)
    diags = client.diagnostics[uri]
    assert [(d.code, d.range.start.line, d.range.start.character) for d in diags] == [
        ("E101", 1, 4)
    ]
    # and an `.st` document is ST even when the editor says ladder
    uri = await _open(client, tmp_path / "s.st", "VAR n : DINT; END_VAR\nn := n + 1;\n", "rll")
    assert list(client.diagnostics[uri]) == []


@lsp_mark
async def test_ladder_enumeration_labels_are_the_lower_case_texts(
    client: LanguageClient, tmp_path: Path
) -> None:
    """SPEC 9.31: an enumeration item's label is the documented text in lower case (`once`),
    in ladder as in ST; its detail the number and meaning."""
    text = LADDER_DECL + "XIC(go)MATC(ax,c,0,p,1.0,1.0,\n"
    uri = await _open(client, tmp_path / "m.rll", text, "rll")
    items = await _complete(client, uri, 1, len(text.splitlines()[1]))
    enum = [i for i in items if i.kind == t.CompletionItemKind.EnumMember]
    # MATC ExecutionMode (seed): Once = 0, Continuous = 1
    assert [i.label for i in enum] == ["once", "continuous"]
    assert [(i.detail or "").split(":")[0] for i in enum] == ["0", "1"]
    assert enum == list(items)  # an immediate operand (seed's Format column): its values only


@lsp_mark
async def test_enumeration_detail_gives_number_and_meaning(
    client: LanguageClient, tmp_path: Path
) -> None:
    """SPEC 8 / 9.31: enumeration values with their numbers in the detail, and the meaning."""
    text = (
        "VAR s, m : AXIS_VIRTUAL; c : MOTION_INSTRUCTION; k : DINT; x : REAL; END_VAR\n"
        "MDAC(s, m, c, \n"
    )
    uri = await _open(client, tmp_path / "d.st", text, "st")
    items = await _complete(client, uri, 1, len(text.splitlines()[1]))
    enum = [i for i in items if i.kind == t.CompletionItemKind.EnumMember]
    # MDAC Motion Type (seed): All = 0, Move = 1, Jog = 2, Time Cam = 3, Master Offset Move = 4
    # (SPEC 9.24 spells them all, move, jog, timecam, masteroffsetmove)
    assert [i.label for i in enum] == ["all", "move", "jog", "timecam", "masteroffsetmove"]
    for number, item in enumerate(enum):
        head, _, meaning = (item.detail or "").partition(":")
        assert head.strip() == str(number) and meaning.strip(), item
    # Motion Type is "Immediate or Tag" (seed): a DINT tag fits; the REAL, the axes and the
    # control word do not; nothing else is offered at this operand
    others = [i for i in items if i.kind != t.CompletionItemKind.EnumMember]
    assert [i.label for i in others] == ["k"]


@lsp_mark
async def test_instructions_are_snippets_with_operand_placeholders(
    client: LanguageClient, tmp_path: Path
) -> None:
    """SPEC 8: instructions complete as snippets with operand placeholders."""
    text = "VAR n : DINT; END_VAR\nMA\n"
    uri = await _open(client, tmp_path / "s.st", text, "st")
    items = await _complete(client, uri, 1, 2)
    [matc] = [i for i in items if i.label == "MATC"]
    assert matc.insert_text_format == t.InsertTextFormat.Snippet
    # the seed's 11 MATC operands, Axis first, each a numbered placeholder
    placeholders = re.findall(r"\$\{(\d+):([A-Za-z]+)\}", matc.insert_text or "")
    assert [int(k) for k, _ in placeholders] == list(range(1, 12))
    assert placeholders[0][1] == "Axis" and placeholders[1][1] == "MotionControl"
    assert (matc.insert_text or "").startswith("MATC(")


@lsp_mark
async def test_keywords_and_types(client: LanguageClient, tmp_path: Path) -> None:
    """SPEC 8: completion of keywords (statement start) and types (a declaration's type)."""
    text = "TYPE Pt : STRUCT X : REAL; END_STRUCT END_TYPE\nVAR n : DINT;\n  q : \nEND_VAR\n\n"
    uri = await _open(client, tmp_path / "k.st", text, "st")
    statement = await _complete(client, uri, 4, 0)
    keywords = {i.label for i in statement if i.kind == t.CompletionItemKind.Keyword}
    assert {"IF", "CASE", "FOR", "WHILE", "REPEAT"} <= keywords
    assert "n" in {i.label for i in statement if i.kind == t.CompletionItemKind.Variable}
    types = {i.label for i in await _complete(client, uri, 2, len("  q : "))}
    assert {"BOOL", "DINT", "REAL", "TIMER", "AXIS_VIRTUAL", "CAM_PROFILE", "Pt"} <= types


@lsp_mark
@pytest.mark.parametrize(
    ("tag", "decl", "type_text", "initial"),
    [
        ("Speed", "REAL := 2.5", "REAL", "2.5"),
        ("Gains", "DINT[3] := [1, -2, 3]", "DINT[3]", "[1, -2, 3]"),
        ("Delay", "TIMER := (PRE := 100)", "TIMER", "(PRE := 100)"),
        # no initialiser: a DINT starts at 0 (SPEC 3.3 / 9.1: tags start from zero)
        ("Count", "DINT", "DINT", "0"),
    ],
)
async def test_hover_on_a_tag_gives_type_and_initial_value(
    client: LanguageClient, tmp_path: Path, tag: str, decl: str, type_text: str, initial: str
) -> None:
    """SPEC 8 / 9.31: hover on a tag gives its type and initial value, as markdown."""
    text = f"VAR {tag} : {decl}; END_VAR\n{tag} := {tag};\n"
    uri = await _open(client, tmp_path / "h.st", text, "st")
    md = await _hover(client, uri, 1, 1)
    assert md.kind == t.MarkupKind.Markdown
    assert f"`{type_text}`" in md.value and f"`{initial}`" in md.value, md.value


@lsp_mark
async def test_hover_in_ladder_shows_instruction_operands(
    client: LanguageClient, tmp_path: Path
) -> None:
    """SPEC 8: hover (instruction docs and operand list) works on `.rll` too."""
    text = LADDER_DECL + "XIC(go)MATC(ax,c,0,p,1.0,1.0,0,0,0.0,0,0);\n"
    uri = await _open(client, tmp_path / "h.rll", text, "rll")
    md = await _hover(client, uri, 1, _end_of(text, 1, "MAT"))
    assert md.kind == t.MarkupKind.Markdown
    for operand in ("Axis", "MotionControl", "CamProfile", "ExecutionMode", "InstructionMode"):
        assert operand in md.value


@lsp_mark
async def test_signature_help_highlights_the_active_operand_itself(
    client: LanguageClient, tmp_path: Path
) -> None:
    """SPEC 8: signature help with the active operand highlighted. MAS's operands (SPEC 9.26)
    are Axis, MotionControl, StopType, ChangeDecel, DecelRate, DecelUnits, ChangeDecelJerk,
    DecelJerk, JerkUnits: after seven commas the active one is DecelJerk (index 7), and what
    is highlighted is that operand, not the `DecelJerk` inside `ChangeDecelJerk`."""
    text = (
        "VAR ax : AXIS_VIRTUAL; c : MOTION_INSTRUCTION; END_VAR\n"
        "IF ax.ActualPosition > 1.0 THEN MAS(ax, c, 0, 0, 10.0, 0, 0, \nEND_IF;\n"
    )
    uri = await _open(client, tmp_path / "sig.st", text, "st")
    sig = await client.text_document_signature_help_async(
        t.SignatureHelpParams(
            t.TextDocumentIdentifier(uri), t.Position(1, _end_of(text, 1, "0, 0, 10.0, 0, 0, "))
        )
    )
    assert sig is not None and sig.active_parameter == 7
    [info] = sig.signatures
    assert info.label == (
        "MAS(Axis, MotionControl, StopType, ChangeDecel, DecelRate, DecelUnits, "
        "ChangeDecelJerk, DecelJerk, JerkUnits)"
    )
    assert info.parameters is not None
    spans = []
    for p in info.parameters:
        label = p.label
        if isinstance(label, str):  # a name: the client highlights its first occurrence
            start = info.label.index(label)
            label = (start, start + len(label))
        spans.append(tuple(label))
    words = [info.label[a:b] for a, b in spans]
    assert words[7] == "DecelJerk" and info.label[: spans[7][0]].endswith("ChangeDecelJerk, ")
    # every operand highlights its own place: the spans follow one another
    assert [a for a, _ in spans] == sorted({a for a, _ in spans}) and len(set(spans)) == 9


@lsp_mark
async def test_definition_of_a_jsr_routine(client: LanguageClient, tmp_path: Path) -> None:
    """SPEC 8: go to definition of a JSR's routine (a file of the same program)."""
    sub = tmp_path / "Fill.rll"
    sub.write_text("VAR n : DINT; END_VAR\nADD(n,1,n);\n")
    text = "VAR m : DINT; END_VAR\nJSR(Fill);\nm := 1;\n"
    uri = await _open(client, tmp_path / "main.st", text, "st")
    assert list(client.diagnostics[uri]) == []  # Fill resolves: the two files are one program
    defs = await client.text_document_definition_async(
        t.DefinitionParams(t.TextDocumentIdentifier(uri), t.Position(1, _end_of(text, 1, "JSR(F")))
    )
    assert defs, defs
    loc = defs[0] if isinstance(defs, list) else defs
    assert isinstance(loc, t.Location) and loc.uri == sub.resolve().as_uri()


@lsp_mark
async def test_semantic_tokens_classify_the_text(client: LanguageClient, tmp_path: Path) -> None:
    """SPEC 8: semantic tokens. Decoded with the legend the server announced: keywords, tags,
    types, instructions, numbers and comments where they stand."""
    text = "VAR n : DINT; ax : AXIS_VIRTUAL; c : MOTION_INSTRUCTION; END_VAR\nn := n + 12; // up\n"
    text += "IF n > 1 THEN MSO(ax, c); END_IF;\n"
    uri = await _open(client, tmp_path / "tok.st", text, "st")
    provider = INITIALIZED[0].capabilities.semantic_tokens_provider
    assert provider is not None
    legend = provider.legend.token_types
    result = await client.text_document_semantic_tokens_full_async(
        t.SemanticTokensParams(t.TextDocumentIdentifier(uri))
    )
    assert result is not None
    data, line, col, found = list(result.data), 0, 0, {}
    for k in range(0, len(data), 5):  # relative encoding of the LSP specification
        d_line, d_col, length, kind = data[k : k + 4]
        line, col = line + d_line, (col + d_col if d_line == 0 else d_col)
        found[text.splitlines()[line][col : col + length], line] = legend[kind]
    lowered = {k: v.lower() for k, v in found.items()}
    assert lowered[("VAR", 0)] == "keyword" and lowered[("IF", 2)] == "keyword"
    assert lowered[("n", 1)] == "variable" and lowered[("ax", 2)] == "variable"
    assert lowered[("DINT", 0)] == "type" and lowered[("AXIS_VIRTUAL", 0)] == "type"
    assert lowered[("MSO", 2)] == "function"
    assert lowered[("12", 1)] == "number" and lowered[("// up", 1)] == "comment"


@lsp_mark
async def test_l5x_completion_inside_routine_text(client: LanguageClient, tmp_path: Path) -> None:
    """SPEC 8: works on `.L5X` (positions mapped to the file): completion of tags and of
    members inside an ST routine's line of the export."""
    text = (ROOT / "samples" / "mixer.L5X").read_text()
    uri = await _open(client, tmp_path / "mixer.L5X", text, "xml")
    assert not [d for d in client.diagnostics[uri] if d.severity == t.DiagnosticSeverity.Error]
    # routine Steps, line 1: `ValveA.Cmd := Step = 0;` in its CDATA on a line of its own
    row = next(k for k, ln in enumerate(text.splitlines()) if "CDATA[ValveA.Cmd :=" in ln)
    start = len("<![CDATA[")
    tags = {i.label for i in await _complete(client, uri, row, start)}
    assert {"ValveA", "Step"} <= tags  # a program tag and one the routine uses
    members = {i.label for i in await _complete(client, uri, row, start + len("ValveA."))}
    assert "Cmd" in members
    # hover on `Step`: a DINT controller tag the export gives no data for, so it starts at 0
    md = await _hover(client, uri, row, start + len("ValveA.Cmd := S"))
    assert "`DINT`" in md.value and "initial value: `0`" in md.value


# ====================================================================== 9.32 hardware
def test_hmi_button_runs_as_with_no_terminal_connected(tmp_path: Path) -> None:
    """SPEC 9.32: instructions that talk to hardware are not U; they run as on a controller
    with nothing connected. HMIBC serves a PanelView 5000 button over an I/O connection:
    with no terminal no press is ever seen, so Out is 0 even if the program set it, and
    EnableOut follows the rung (decision 0151)."""
    st = tmp_path / "b.st"
    st.write_text("VAR b : HMIBC; END_VAR\nb.Out := TRUE;\nb.ProgFB := TRUE;\nHMIBC(b);\n")
    assert json.loads(logixst("check", st, "--format", "json", timeout=60).out) == []
    r = logixst("run", st, "--scans", "2", "--json", "--watch", "b", timeout=60)
    assert r.code == 0, r.err
    report = json.loads(r.out)
    assert report["unsupported"] == []
    b = report["tags"]["b"]
    # ST always executes: EnableOut 1; Out cleared; the program's ProgFB kept
    assert (b["EnableOut"], b["Out"], b["ProgFB"]) == (True, False, True)
    rll = tmp_path / "b.rll"
    rll.write_text("VAR b : HMIBC; go : BOOL; END_VAR\nXIC(go)HMIBC(b);\n")
    for go, enable_out in (("0", False), ("1", True)):
        r = logixst(
            "run", rll, "--scans", "1", "--set", f"go={go}", "--json", "--watch", "b", timeout=60
        )
        assert r.code == 0, r.err
        b = json.loads(r.out)["tags"]["b"]
        assert (b["EnableIn"], b["EnableOut"], b["Out"]) == (enable_out, enable_out, False)
