"""The documents the editor has open, and their analysis (protocol-free).

A `.st`/`.rll` document is analysed as `check DIR` sees a program: together with the
`.st`/`.rll` files beside it (the editor's unsaved text wins over the file on disk), so JSR
targets and shared tags resolve. An `.L5X` document is one project. The language comes from
the file extension, never from the editor's languageId (SPEC 9.31).
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path
from urllib.parse import unquote, urlparse

from interpreter.diagnostics import Diagnostic
from interpreter.limits import MAX_PROJECT_BYTES, MAX_SOURCE_BYTES, LimitError, mb, read_limited
from interpreter.semantics.document import (
    PROGRAM_SUFFIXES,
    PROJECT_SUFFIXES,
    Loaded,
    Source,
    analyse_program,
    looks_binary,
    read_export,
)
from interpreter.semantics.incremental import ExportState
from interpreter.syntax.l5x import L5XProject


def uri_to_path(uri: str) -> str:
    parsed = urlparse(uri)
    if parsed.scheme == "file":
        return unquote(parsed.path)
    return uri


_HEADER_END = re.compile(r"\bEND_(?:VAR|TYPE)\b", re.I)


def _header_only(text: str) -> str:
    """The text up to the last END_VAR/END_TYPE: the declarations without the code."""
    last = None
    for m in _HEADER_END.finditer(text):
        last = m
    return text[: last.end()] + "\n" if last is not None else ""


_HEADER_RETRIES = 3  # declarations being typed at once (each blanking is one more analysis)


def _blank_lines(text: str, errors: list[tuple[int, int]]) -> str:
    """`text` with the line of each 1-based (line, column) syntax error emptied, the line
    count (so every position) kept. An error at the first word of its line (`END_VAR` after
    `q : `) belongs to the unfinished line before it, which is emptied instead."""
    rows = text.split("\n")
    for line, col in errors:
        k = line - 1
        if not 0 <= k < len(rows):
            continue
        if not rows[k][: col - 1].strip():
            k -= 1
            while k >= 0 and not rows[k].strip():
                k -= 1
        if k >= 0:
            rows[k] = ""
    return "\n".join(rows)


def language_of(path: str) -> str | None:
    """'st', 'rll' or 'l5x' (an .L5X or .L5K export) by extension; None for other documents."""
    suffix = Path(path).suffix.lower()
    if suffix in PROGRAM_SUFFIXES:
        return suffix[1:]
    if suffix in PROJECT_SUFFIXES:
        return "l5x"
    return None


@dataclass(slots=True)
class Document:
    uri: str
    path: str
    text: str
    version: int = 0

    @property
    def language(self) -> str | None:
        return language_of(self.path)


@dataclass(slots=True)
class Analysed:
    """One document's view of its program: the shared analysis and this file's diagnostics.

    `loaded` is the analysis of the text as it is; while the text does not parse, its
    declarations are taken from the declaration header alone (`_header_only`), so that
    completion and hover still know the tags in half-typed code.
    """

    document: Document
    loaded: Loaded
    diagnostics: list[Diagnostic]


@dataclass(slots=True)
class Workspace:
    documents: dict[str, Document] = field(default_factory=dict)
    tags_path: str | None = None  # the `logixst.tags` setting: plays the role of --tags
    _cache: dict[str, tuple[tuple[object, ...], Analysed]] = field(default_factory=dict)
    _exports: dict[str, ExportState] = field(default_factory=dict)  # an export's last analysis
    analyses: int = 0  # how many analyses were run (not answered from the cache)

    def open(self, uri: str, text: str, version: int = 0) -> Document:
        doc = Document(uri, uri_to_path(uri), text, version)
        self.documents[uri] = doc
        return doc

    def change(self, uri: str, text: str, version: int) -> Document | None:
        doc = self.documents.get(uri)
        if doc is not None:
            doc.text, doc.version = text, version
        return doc

    def close(self, uri: str) -> None:
        self.documents.pop(uri, None)
        self._cache.pop(uri, None)
        self._exports.pop(uri, None)

    def get(self, uri: str) -> Document | None:
        return self.documents.get(uri)

    def refused(self, uri: str) -> str | None:
        """Why `check` would refuse this open document as an input file (too large for its
        kind, or not text), in the CLI's words; None when it is analysed."""
        doc = self.documents.get(uri)
        if doc is None or doc.language is None:
            return None
        limit = MAX_PROJECT_BYTES if doc.language == "l5x" else MAX_SOURCE_BYTES  # as the CLI
        size = len(doc.text.encode("utf-8", "surrogatepass"))
        if size > limit:
            return f"{doc.path}: file is too large ({size:,} bytes; the limit is {mb(limit)}): not analysed"
        if looks_binary(doc.text[:8192].encode("utf-8", "surrogatepass")):
            return f"{doc.path}: not a text file (it holds NUL bytes): not analysed"
        return None

    def analyse(self, uri: str) -> Analysed | None:
        """The analysis of an open document (cached while nothing it reads has changed)."""
        doc = self.documents.get(uri)
        if doc is None or doc.language is None or self.refused(uri) is not None:
            return None  # `check` refuses such a file as input: nothing to verify
        sources = self._program_sources(doc) if doc.language != "l5x" else []
        key: tuple[object, ...] = (doc.text, self.tags_path, tuple(sources))
        hit = self._cache.get(uri)
        if hit is not None and hit[0] == key:
            return hit[1]
        self.analyses += 1
        if doc.language == "l5x":
            loaded = self._export(uri, doc)
        else:
            loaded = analyse_program(sources, self._tags())
        mine = [d for d in loaded.diagnostics if d.path == doc.path]
        if (
            doc.language != "l5x"
            and not loaded.model.tags
            and any(d.code.startswith("S") for d in mine)
        ):
            header = _header_only(doc.text)
            if header:
                others = [x for x in sources if x.path != doc.path]
                loaded = self._header_analysis(doc.path, header, others)
        result = Analysed(doc, loaded, mine)
        self._cache[uri] = (key, result)
        return result

    def _header_analysis(self, path: str, header: str, others: list[Source]) -> Loaded:
        """The declarations of a text that does not parse. A declaration being typed
        (`q : ` with no type yet) breaks the header too; its lines are blanked (line numbers
        kept) so the other tags and the user types stay known to completion and hover."""
        loaded = analyse_program([Source(path, header), *others], self._tags())
        for _ in range(_HEADER_RETRIES):
            broken = [
                (d.span.line, d.span.col)
                for d in loaded.diagnostics
                if d.path == path and d.code[0] == "S"
            ]
            if not broken:
                break
            # the first error only: later ones are often its echo (`unexpected end of file`)
            header = _blank_lines(header, [min(broken)])
            retry = analyse_program([Source(path, header), *others], self._tags())
            if len(retry.model.tags) + len(retry.model.types.user_types()) < len(
                loaded.model.tags
            ) + len(loaded.model.types.user_types()):
                break  # blanking lost names (a VAR or TYPE line): keep what was known
            loaded = retry
        loaded.diagnostics = [d for d in loaded.diagnostics if d.path != path]
        return loaded

    def _export(self, uri: str, doc: Document) -> Loaded:
        """An export's analysis: the last one patched where the edit allows (an edit inside
        one routine's text, decision 0117), else a full read that reuses the parsed pieces."""
        data = doc.text.encode("utf-8")
        state = self._exports.get(uri)
        if state is not None:
            try:
                loaded = state.update(data)
            except Exception:  # noqa: BLE001 - a failed patch is never worse than a full read
                loaded = None
            if loaded is not None:
                return loaded
        memo = state.memo if state is not None else None
        state = ExportState.read(doc.path, data, memo)
        self._exports[uri] = state
        return state.loaded

    def latest(self, uri: str) -> Analysed | None:
        """The last analysis of the document, even if its text has changed since.

        Completion, hover and signature help need names and types, which a keystroke rarely
        changes, and must answer in milliseconds: they read this (with the document's current
        text, which `Analysed.document` always holds) instead of re-analysing. Diagnostics
        and navigation use `analyse`.
        """
        hit = self._cache.get(uri)
        if hit is not None and uri in self.documents:
            return hit[1]
        return self.analyse(uri)

    def _program_sources(self, doc: Document) -> list[Source]:
        """This document and its sibling routine files, in `check DIR` order (sorted)."""
        open_text = {d.path: d.text for d in self.documents.values()}
        here = Path(doc.path)
        paths = {doc.path}
        if here.parent.is_dir():
            try:
                for p in here.parent.iterdir():
                    if p.suffix.lower() in PROGRAM_SUFFIXES and p.is_file():
                        paths.add(str(p))
            except OSError:
                pass
        sources = []
        for name in sorted(paths):
            text = open_text.get(name)
            if text is None:
                try:  # bounded, regular files only, as the CLI reads them (docs/limits.md)
                    text = read_limited(Path(name), MAX_SOURCE_BYTES).decode("utf-8", "replace")
                except (OSError, LimitError):
                    continue
            sources.append(Source(name, text))
        return sources

    def _tags(self) -> tuple[L5XProject, str] | None:
        if not self.tags_path:
            return None
        try:
            data = read_limited(Path(self.tags_path), MAX_PROJECT_BYTES)
        except (OSError, LimitError):
            return None
        project, _ = read_export(self.tags_path, data)
        return None if project is None else (project, self.tags_path)
