"""Read input files into a checked program (syntax + semantics; nothing runs here)."""

from __future__ import annotations

import gc
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path

from ..diagnostics import Diagnostic
from ..semantics.checker import Analysis, check_program
from ..semantics.program import ProgramModel, build_program
from ..semantics.project import build_project, controller_scope, declare_aliases
from ..semantics.types import TypeTable
from ..syntax import nodes as n
from ..syntax.l5x import L5XProject, read_l5x
from ..syntax.rll_parser import parse_rll
from ..syntax.st_parser import parse_st

MAX_FILE_BYTES = 64 * 1024 * 1024
SUFFIXES = (".st", ".rll")  # program files `run` and `check` read


class InputError(Exception):
    """A file cannot be used at all (missing, directory, binary...): exit code 2."""


@dataclass(slots=True)
class Loaded:
    model: ProgramModel
    analysis: Analysis
    diagnostics: list[Diagnostic] = field(default_factory=list)


def _require_file(path: Path) -> None:
    if not path.exists():
        raise InputError(f"{path}: no such file")
    if path.is_dir():
        raise InputError(f"{path}: is a directory, expected a .st or .rll file")


def read_bytes(path: Path) -> bytes:
    """The file's bytes after the checks every input gets (exists, size, not empty, text)."""
    _require_file(path)
    try:
        size = path.stat().st_size
        if size > MAX_FILE_BYTES:
            raise InputError(f"{path}: file is too large ({size} bytes)")
        data = path.read_bytes()
    except OSError as exc:
        raise InputError(f"{path}: cannot read: {exc.strerror}") from exc
    if not data.strip():
        raise InputError(f"{path}: file is empty")
    if b"\x00" in data[:8192]:
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
    return path.suffix.lower() == ".l5x"


def parse_file(path: Path) -> tuple[list[n.Routine], list[Diagnostic]]:
    _require_file(path)  # a missing file or a directory is named as such, whatever its suffix
    suffix = path.suffix.lower()
    if suffix == ".st":
        routine, diags = parse_st(read_text(path), str(path))
        return [routine], diags
    if suffix == ".rll":
        routine, diags = parse_rll(read_text(path), str(path))
        return [routine], diags
    raise InputError(
        f"{path}: unsupported file type '{path.suffix}' (expected {' or '.join(SUFFIXES)})"
    )


def read_project(path: Path) -> tuple[L5XProject | None, list[Diagnostic]]:
    return read_l5x(read_bytes(path), str(path))


def load_project(path: Path) -> Loaded:
    """One .L5X export is one project (SPEC 9.8): controller, programs, tasks, AOIs."""
    project, diags = read_project(path)
    if project is None:
        return Loaded(ProgramModel(path.stem, [], TypeTable()), Analysis(), diags)
    model, mdiags = build_project(project)
    analysis = check_program(model)
    diags = diags + mdiags + [project.annotate(d) for d in analysis.diags]
    diags.sort(key=lambda d: d.sort_key())
    return Loaded(model, analysis, diags)


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

    `tags` is an .L5X export whose data types and controller tags the files use (SPEC 9.16).
    """
    if not paths:
        raise InputError("no program file given")
    if any(is_project(p) for p in paths):
        if len(paths) > 1:
            raise InputError(
                "an .L5X file is a whole project: give it alone (use --tags to share its tags with .st/.rll files)"
            )
        if tags is not None:
            raise InputError(
                "--tags gives controller tags to .st/.rll files; an .L5X project has its own"
            )
        with gc_paused():
            return load_project(paths[0])
    with gc_paused():
        return _load(paths, tags)


def _load(paths: list[Path], tags: Path | None) -> Loaded:
    routines: list[n.Routine] = []
    diags: list[Diagnostic] = []
    for p in paths:
        rs, ds = parse_file(p)
        routines.extend(rs)
        diags.extend(ds)
    types: TypeTable | None = None
    shared: tuple[list[n.VarDecl], str] | None = None
    if tags is not None:
        if not is_project(tags):
            raise InputError(f"{tags}: --tags expects an .L5X export")
        project, tdiags = read_project(tags)
        diags.extend(tdiags)
        if project is not None:
            types, decls, cdiags = controller_scope(project)
            diags.extend(cdiags)
            shared = (decls, str(tags))
    model, mdiags = build_program(
        routines[0].program_name or routines[0].name, routines, types, shared
    )
    diags.extend(mdiags)
    if shared is not None and project is not None and project.aliases:
        declare_aliases(model, [(None, project.aliases)], shared[1], diags)
    analysis = check_program(model)
    diags.extend(analysis.diags)
    diags.sort(key=lambda d: d.sort_key())
    return Loaded(model, analysis, diags)
