"""Real Studio 5000 exports (issue 9): what logixst must say about each of them.

Two sets of files:

- tests/l5x/public/*.L5X: exports of MIT-licensed repositories, committed unmodified
  (LICENSES.md there); always tested, with the exact codes they give.
- tests/l5x/corpus/manifest.toml: about a hundred exports of public repositories, NOT
  committed (most carry no licence). tests/l5x/corpus/fetch_corpus.py copies them into a
  directory (by default /work/l5x-corpus) and checks their sha256. They are tested when
  $LOGIXST_L5X_CORPUS names that directory; otherwise, or for a file that is not there, the
  test is skipped with a reason naming the script. A run never depends on what happens to
  lie on the machine.

What every corpus file must give (the manifest's fields are documented in its header):
- no S diagnostic: Studio wrote these files, so every one of them is valid syntax;
- kind = "project" (a whole controller): no E diagnostic, and `logixst run FILE --scans 100`
  exits 0, or 3 only where the manifest names the genuine Logix major fault
  (`expected_fault`). A project that Studio itself could not verify as exported carries its
  genuine errors in `expected_e` (each with the evidence in its reason): exactly those E
  diagnostics, and `run` refuses it (exit 1) as a controller download would be refused;
- kind = "partial" (a program, routine, rung, AOI or UDT export): exactly the E diagnostics
  listed in `expected_e`, the ones naming something that lives outside the file;
- an L5K export: the same diagnostics (code and message) as the L5X export of the same
  project (`l5k_pair`), but for one U306 per module whose layout only the L5X holds.

The manifest itself is checked in CI too (fields, kinds, unique names, pairs).
docs/l5x-corpus.md lists the files and explains every expected E.
"""

from __future__ import annotations

import hashlib
import os
import re
import tomllib
from collections import Counter
from functools import cache
from pathlib import Path
from typing import Any

import pytest

from interpreter.cli import main
from interpreter.diagnostics import REGISTRY
from interpreter.runtime.loader import load

HERE = Path(__file__).parent
COMMITTED = HERE / "public"
MANIFEST = HERE / "corpus" / "manifest.toml"
CORPUS = Path(os.environ["LOGIXST_L5X_CORPUS"]) if os.environ.get("LOGIXST_L5X_CORPUS") else None
FETCH = "python tests/l5x/corpus/fetch_corpus.py"
BOM = b"\xef\xbb\xbf"

ENTRIES: list[dict[str, Any]] = tomllib.loads(MANIFEST.read_text(encoding="utf-8"))["file"]
BY_NAME = {e["file"]: e for e in ENTRIES}
PROJECTS = [e for e in ENTRIES if e["kind"] == "project"]
PARTIALS = [e for e in ENTRIES if e["kind"] == "partial"]
PAIRS = [e for e in ENTRIES if "l5k_pair" in e]


def _ids(entries: list[dict[str, Any]]) -> list[str]:
    return [e["file"] for e in entries]


def _path(entry: dict[str, Any]) -> Path:
    """The local copy of a manifest file; skips the test when it has not been fetched."""
    if CORPUS is None:
        pytest.skip(f"set LOGIXST_L5X_CORPUS to the directory `{FETCH}` fills to test the corpus")
    p = CORPUS / entry["file"]
    if not p.is_file():
        pytest.skip(f"{entry['file']} is not in {CORPUS}: run `{FETCH}` to fetch the corpus")
    return p


@cache
def _diagnostics(name: str) -> tuple[tuple[str, str, int], ...]:
    """(code, message, line) of every diagnostic `check` gives the corpus file `name`."""
    assert CORPUS is not None
    loaded = load([CORPUS / name])
    return tuple((d.code, d.message, d.span.line) for d in loaded.diagnostics)


def _texts(name: str, prefix: str) -> list[str]:
    return [
        f"{name}:{line}: {code} {msg}"
        for code, msg, line in _diagnostics(name)
        if code.startswith(prefix)
    ]


# ------------------------------------------------------------------ the committed exports
# Diagnostic codes of the committed exports. belt_conveyor (v20) writes `Failures`, the member
# declared Hidden="true" that hosts the UDT's BIT members; hidden members are not part of the
# type's visible members in our model, hence E102.
COMMITTED_CODES = {
    "WEST77-tech__AOI-CONVEYOR-Studio5000__CONVEYOR_AOI.L5X": [],
    "alairjunior__l5x2c__belt_conveyor.L5X": ["E102"],
}


@pytest.mark.parametrize("name", sorted(COMMITTED_CODES))
def test_committed_public_export(name: str) -> None:
    loaded = load([COMMITTED / name])
    assert [d.code for d in loaded.diagnostics] == COMMITTED_CODES[name], [
        d.text() for d in loaded.diagnostics
    ]


def test_committed_exports_are_the_manifest_bytes() -> None:
    # The committed copies are the bytes of their manifest entries, so a fix found on one is
    # seen on the other. The CONVEYOR_AOI copy lost the UTF-8 byte-order mark Studio writes
    # (it was copied through a text interface); everything after it is identical.
    for name, entry in (
        (
            "WEST77-tech__AOI-CONVEYOR-Studio5000__CONVEYOR_AOI.L5X",
            "WEST77-tech__AOI-CONVEYOR-Studio5000__CONVEYOR_AOI.L5X",
        ),
        (
            "alairjunior__l5x2c__belt_conveyor.L5X",
            "alairjunior__l5x2c__examples__belt_conveyor.L5X",
        ),
    ):
        data = (COMMITTED / name).read_bytes()
        digests = {hashlib.sha256(data).hexdigest(), hashlib.sha256(BOM + data).hexdigest()}
        assert BY_NAME[entry]["sha256"] in digests, name


# ------------------------------------------------------------------ the manifest itself
_REQUIRED = {"file", "repo", "path", "commit", "sha256", "bytes", "version", "kind", "note"}
_OPTIONAL = {"expected_e", "expected_fault", "l5k_pair"}


def test_manifest_entries_are_complete() -> None:
    problems: list[str] = []
    for e in ENTRIES:
        name = e.get("file", "?")
        missing = _REQUIRED - e.keys()
        unknown = e.keys() - _REQUIRED - _OPTIONAL
        if missing or unknown:
            problems.append(f"{name}: missing {sorted(missing)}, unknown {sorted(unknown)}")
            continue
        if e["kind"] not in ("project", "partial"):
            problems.append(f"{name}: kind {e['kind']!r}")
        if not re.fullmatch(r"[0-9a-f]{40}", e["commit"]) or not re.fullmatch(
            r"[0-9a-f]{64}", e["sha256"]
        ):
            problems.append(f"{name}: commit or sha256 is not a full hex digest")
        want = e["repo"].replace("/", "__") + "__" + e["path"].replace("/", "__").replace(" ", "_")
        if name != want:
            problems.append(f"{name}: local name should be {want}")
        if "expected_fault" in e and e["kind"] != "project":
            problems.append(f"{name}: expected_fault is only for project exports")
        for x in e.get("expected_e", []):
            keys = set(x) - {"count"}
            if keys != {"code", "message", "reason"} or not x["code"].startswith("E"):
                problems.append(f"{name}: expected_e entry {x} needs an E code, message, reason")
            elif x["code"] not in REGISTRY:
                problems.append(f"{name}: expected_e code {x['code']} is not registered")
        if "l5k_pair" in e:
            pair = BY_NAME.get(e["l5k_pair"])
            if not e["path"].lower().endswith(".l5k") or pair is None or pair["kind"] != e["kind"]:
                problems.append(f"{name}: l5k_pair must name an L5X entry of the same kind")
    assert problems == []
    assert len(BY_NAME) == len(ENTRIES), "local names must be unique"
    assert len({e["sha256"] for e in ENTRIES}) == len(ENTRIES), "the same bytes twice"


def test_manifest_meets_the_issue_9_bar() -> None:
    # Issue 9 asks for at least 40 exports from 12 repositories, v19 to v38, one of 1.5 MB or
    # more, L5K exports and Rockwell Automation's own sample projects.
    majors = {int(e["version"].split(".")[0]) for e in ENTRIES}
    assert len(ENTRIES) >= 40
    assert len({e["repo"] for e in ENTRIES}) >= 12
    assert min(majors) <= 19 and max(majors) >= 38
    assert max(e["bytes"] for e in ENTRIES) >= 1_500_000
    assert any(e["path"].lower().endswith(".l5k") for e in ENTRIES)
    assert PAIRS
    assert any("Rockwell Automation" in e["note"] for e in ENTRIES)


# ------------------------------------------------------------------ the corpus files
@pytest.mark.parametrize("entry", ENTRIES, ids=_ids(ENTRIES))
def test_corpus_file_is_the_manifest_version(entry: dict[str, Any]) -> None:
    data = _path(entry).read_bytes()
    assert hashlib.sha256(data).hexdigest() == entry["sha256"], f"stale copy: run `{FETCH}`"


@pytest.mark.parametrize("entry", ENTRIES, ids=_ids(ENTRIES))
def test_corpus_file_has_no_syntax_diagnostics(entry: dict[str, Any]) -> None:
    _path(entry)
    assert _texts(entry["file"], "S") == []


def _assert_expected_errors(entry: dict[str, Any]) -> None:
    got = Counter((c, m) for c, m, _ in _diagnostics(entry["file"]) if c.startswith("E"))
    want: Counter[tuple[str, str]] = Counter()
    for x in entry.get("expected_e", []):
        want[(x["code"], x["message"])] += x.get("count", 1)
    assert sorted(got.elements()) == sorted(want.elements()), _texts(entry["file"], "E")


@pytest.mark.parametrize("entry", PROJECTS, ids=_ids(PROJECTS))
def test_corpus_project_has_no_errors(entry: dict[str, Any]) -> None:
    # no E at all, but for the genuine errors of a project Studio could not have verified
    # either (expected_e: docs/l5x-corpus.md says why for each)
    _path(entry)
    _assert_expected_errors(entry)


@pytest.mark.parametrize("entry", PARTIALS, ids=_ids(PARTIALS))
def test_corpus_partial_export_has_only_the_expected_errors(entry: dict[str, Any]) -> None:
    _path(entry)
    _assert_expected_errors(entry)


@pytest.mark.parametrize("entry", PROJECTS, ids=_ids(PROJECTS))
def test_corpus_project_runs_100_scans(
    entry: dict[str, Any], capsys: pytest.CaptureFixture[str]
) -> None:
    path = _path(entry)
    code = main(["run", str(path), "--scans", "100"])
    err = capsys.readouterr().err
    fault = entry.get("expected_fault")
    if "expected_e" in entry:  # genuine errors: refused, as a download would be
        assert code == 1, err[-2000:]
        return
    assert code == (3 if fault else 0), err[-2000:]
    if fault:
        assert f"major fault type {fault['type']} code {fault['code']}" in err, err[-2000:]


@pytest.mark.parametrize("entry", PAIRS, ids=_ids(PAIRS))
def test_l5k_export_gives_what_its_l5x_gives(entry: dict[str, Any]) -> None:
    _path(entry)
    _path(BY_NAME[entry["l5k_pair"]])
    # Lines differ between the two formats; codes and messages (which name the program,
    # routine, rung or tag) must not. One difference is the format's: an L5K gives module
    # connection data as bare values, so where its MODULE block does not show a module's
    # layout (and the L5X's Decorated data does) the L5K says so once for that module or
    # module-defined type, with a U306 naming it (decision 0071). Nothing else may differ.
    l5k = Counter((c, m) for c, m, _ in _diagnostics(entry["file"]))
    l5x = Counter((c, m) for c, m, _ in _diagnostics(entry["l5k_pair"]))
    assert sorted((l5x - l5k).elements()) == []
    layout_missing = ("is not in an .L5K export", "is not described in this export")
    assert [
        (c, m)
        for c, m in (l5k - l5x).elements()
        if c != "U306" or not any(why in m for why in layout_missing)
    ] == []
