"""Read input files into a checked program (syntax + semantics; nothing runs here)."""

from __future__ import annotations

import gc
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

from ..diagnostics import Diagnostic
from ..limits import MAX_PROJECT_BYTES, MAX_SOURCE_BYTES, LimitError, read_limited
from ..semantics.document import (
    PROGRAM_SUFFIXES,
    PROJECT_SUFFIXES,
    Loaded,
    Source,
    analyse_program,
    analyse_project,
    looks_binary,
    parse_source,
    read_export,
)
from ..syntax import nodes as n
from ..syntax.l5x import L5XProject

SUFFIXES = PROGRAM_SUFFIXES  # program files `run` and `check` read


class InputError(Exception):
    """A file cannot be used at all (missing, directory, binary...): exit code 2."""


def _require_file(path: Path) -> None:
    if not path.exists():
        raise InputError(f"{path}: no such file or directory")
    if path.is_dir():
        raise InputError(f"{path}: is a directory, expected a .st or .rll file")


def read_bytes(path: Path) -> bytes:
    """The file's bytes after the checks every input gets (exists, size, not empty, text)."""
    _require_file(path)
    limit = MAX_PROJECT_BYTES if is_project(path) else MAX_SOURCE_BYTES
    try:
        data = read_limited(path, limit)
    except LimitError as exc:
        raise InputError(f"{path}: {exc}") from None
    except OSError as exc:
        raise InputError(f"{path}: cannot read: {exc.strerror}") from exc
    if not data.strip():
        raise InputError(f"{path}: file is empty")
    if looks_binary(data):
        raise InputError(f"{path}: looks like a binary file, not Logix source text")
    return data


def read_text(path: Path) -> str:
    data = read_bytes(path)
    if data.startswith(b"\xef\xbb\xbf"):
        data = data[3:]
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError:
        return data.decode("latin-1")


def is_project(path: Path) -> bool:
    return path.suffix.lower() in PROJECT_SUFFIXES


def parse_file(path: Path) -> tuple[list[n.Routine], list[Diagnostic]]:
    _require_file(path)  # a missing file or a directory is named as such, whatever its suffix
    if path.suffix.lower() in SUFFIXES:
        routine, diags = parse_source(Source(str(path), read_text(path)))
        return [routine], diags
    raise InputError(
        f"{path}: unsupported file type '{path.suffix}' (expected .st, .rll, .L5X or .L5K)"
    )


def read_project(path: Path) -> tuple[L5XProject | None, list[Diagnostic]]:
    """An .L5X or .L5K export; both give the same project model."""
    return read_export(str(path), read_bytes(path))


def load_project(path: Path) -> Loaded:
    """One .L5X or .L5K export is one project (SPEC 9.8): controller, programs, tasks, AOIs."""
    return analyse_project(str(path), read_bytes(path))


@contextmanager
def gc_paused() -> Iterator[None]:
    """Pause the cyclic garbage collector while building ASTs, then freeze what was built.

    Parsing allocates hundreds of thousands of small objects and no reference cycles worth
    collecting; the collector's passes over them cost a third of the load time. Re-enabling
    it alone would only defer the cost: the first allocation after the load would trace every
    new object (0.4 s for a 2 MB export). The loaded program lives as long as the command,
    so it is frozen (`gc.freeze`): moved out of the generations the collector traces.
    Objects still free as usual when their last reference goes (docs/performance.md).
    """
    was_enabled = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if was_enabled:
            gc.freeze()
            gc.enable()


def load(paths: list[Path], tags: Path | None = None) -> Loaded:
    """Parse and verify the files of one program (SPEC 2.4): routine name = file stem.

    `tags` is an .L5X or .L5K export whose data types and controller tags the files use
    (SPEC 9.16).
    """
    if not paths:
        raise InputError("no program file given")
    if any(is_project(p) for p in paths):
        if len(paths) > 1:
            raise InputError(
                "an .L5X or .L5K file is a whole project: give it alone (use --tags to share its tags with .st/.rll files)"
            )
        if tags is not None:
            raise InputError(
                "--tags gives controller tags to .st/.rll files; an .L5X or .L5K project has its own"
            )
        with gc_paused():
            return load_project(paths[0])
    with gc_paused():
        return _load(paths, tags)


def _load(paths: list[Path], tags: Path | None) -> Loaded:
    for p in paths:  # every file is named before any is read
        if p.suffix.lower() not in SUFFIXES:
            parse_file(p)
    sources = [Source(str(p), read_text(p)) for p in paths]
    shared: tuple[L5XProject, str] | None = None
    tag_diags: list[Diagnostic] = []
    if tags is not None:
        if not is_project(tags):
            raise InputError(f"{tags}: --tags expects an .L5X or .L5K export")
        project, tag_diags = read_project(tags)
        if project is not None:
            shared = (project, str(tags))
    loaded = analyse_program(sources, shared)
    if tag_diags:
        loaded.diagnostics = sorted(tag_diags + loaded.diagnostics, key=lambda d: d.sort_key())
    return loaded
