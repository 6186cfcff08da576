"""Document-level entry point: source text in, program model and diagnostics out.

No file system here: `check`, `run` (through runtime/loader.py, which reads the files) and
the language server (which holds the editor's unsaved text) all call these two functions,
so an editor sees exactly the diagnostics `logixst check` prints for the same text.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from itertools import islice

from ..diagnostics import Diagnostic
from ..syntax import nodes as n
from ..syntax.l5k import read_l5k
from ..syntax.l5x import L5XProject, ParseMemo, read_l5x
from ..syntax.rll_parser import parse_rll
from ..syntax.st_parser import parse_st
from .checker import Analysis, Checker, check_program
from .program import ProgramModel, build_program
from .project import build_project, controller_scope, declare_aliases
from .types import TypeTable

PROGRAM_SUFFIXES = (".st", ".rll")  # the routine files of one program (SPEC 2.4)
PROJECT_SUFFIXES = (".l5x", ".l5k")  # whole-project exports: XML and text form (SPEC 2.3, 2.3a)


def looks_binary(data: bytes) -> bool:
    """A NUL byte near the start: not Logix source text (the CLI refuses such a file)."""
    return b"\x00" in data[:8192]


@dataclass(frozen=True, slots=True)
class Source:
    """The text of one `.st` or `.rll` routine file; `path` names it in diagnostics."""

    path: str
    text: str


@dataclass(slots=True)
class Loaded:
    model: ProgramModel
    analysis: Analysis
    diagnostics: list[Diagnostic] = field(default_factory=list)
    project: L5XProject | None = None  # the export, for an .L5X document


def parse_source(source: Source) -> tuple[n.Routine, list[Diagnostic]]:
    """One routine file; the language comes from the suffix (SPEC 9.31: never the editor's id)."""
    if source.path.lower().endswith(".rll"):
        return parse_rll(source.text, source.path)
    return parse_st(source.text, source.path)


def analyse_program(sources: list[Source], tags: tuple[L5XProject, str] | None = None) -> Loaded:
    """Routine files forming one program: routine = file stem, the first is main (SPEC 2.4).

    `tags` is an export (and its path) whose controller tags and data types the routines use
    (`--tags`, SPEC 9.16).
    """
    routines: list[n.Routine] = []
    diags: list[Diagnostic] = []
    for s in sources:
        routine, ds = parse_source(s)
        routines.append(routine)
        diags.extend(ds)
    types: TypeTable | None = None
    shared: tuple[list[n.VarDecl], str] | None = None
    if tags is not None:
        project, tags_path = tags
        types, decls, cdiags = controller_scope(project)
        diags.extend(cdiags)
        shared = (decls, tags_path)
    model, mdiags = build_program(
        routines[0].program_name or routines[0].name, routines, types, shared
    )
    diags.extend(mdiags)
    if tags is not None and tags[0].aliases:  # the export's controller aliases (decision 0044)
        declare_aliases(model, [(None, tags[0].aliases)], tags[1], diags)
    analysis = check_program(model)
    diags.extend(analysis.diags)
    diags.sort(key=lambda d: d.sort_key())
    return Loaded(model, analysis, diags)


def read_export(
    path: str, data: bytes, memo: ParseMemo | None = None
) -> tuple[L5XProject | None, list[Diagnostic]]:
    """An .L5X or .L5K export (by suffix); both give the same project model. `memo` keeps
    an L5X document's parsed routines between reads (the language server)."""
    if path.lower().endswith(".l5k"):
        return read_l5k(data, path)
    return read_l5x(data, path, memo)


def analyse_project(path: str, data: bytes, memo: ParseMemo | None = None) -> Loaded:
    """One .L5X/.L5K export is one project (SPEC 9.8); positions are positions in that file."""
    return analyse_export(path, data, memo).loaded


@dataclass(slots=True)
class RoutineCheck:
    """What verifying one routine of a project gave, and left for the routines after it."""

    raw: list[Diagnostic]  # as the verifier gave them (Analysis.diags)
    diags: list[Diagnostic]  # annotated with program / routine / rung
    motion: list[tuple[str, int]]  # motion control tags first used here, with that line (W203)
    modules: set[str]  # modules whose U306 was given here


@dataclass(slots=True)
class ProjectAnalysis:
    """An export's analysis kept in the parts that an edit inside one routine's text replaces
    (the language server, decision 0117): the reading's diagnostics, the model's, and the
    verifier's routine by routine (model.routines in order, then the add-on instructions'
    routines, then the tag data)."""

    loaded: Loaded
    read_diags: list[Diagnostic]
    model_diags: list[Diagnostic]
    checks: list[RoutineCheck] = field(default_factory=list)

    def diagnostics(self) -> list[Diagnostic]:
        """All of them in `check`'s order: the parts in the order one full analysis made them,
        then a stable sort by place and code."""
        diags = self.read_diags + self.model_diags
        for c in self.checks:
            diags.extend(c.diags)
        diags.sort(key=lambda d: d.sort_key())
        return diags


def analyse_export(path: str, data: bytes, memo: ParseMemo | None = None) -> ProjectAnalysis:
    """analyse_project, with the verification kept routine by routine."""
    project, diags = read_export(path, data, memo)
    if project is None:
        stem = path.rsplit("/", 1)[-1].rsplit(".", 1)[0]
        loaded = Loaded(ProgramModel(stem, [], TypeTable()), Analysis(), diags)
        return ProjectAnalysis(loaded, diags, [])
    model, mdiags = build_project(project)
    checker = Checker(model)
    result = ProjectAnalysis(Loaded(model, checker.a, [], project), diags, mdiags)
    result.checks = record_checks(checker, checker.each_routine(), project.annotate)
    result.loaded.diagnostics = result.diagnostics()
    return result


def record_checks(
    checker: Checker, steps: Iterable[object], annotate: Callable[[Diagnostic], Diagnostic]
) -> list[RoutineCheck]:
    """Run `steps` (routines being checked), keeping what each one added."""
    motion, modules = checker.carried()
    diags = checker.a.diags
    out: list[RoutineCheck] = []
    d0, m0, seen = len(diags), len(motion), set(modules)
    for _ in steps:
        added = list(islice(motion.items(), m0, None)) if len(motion) > m0 else []
        new_modules = modules - seen if len(modules) > len(seen) else set()
        raw = diags[d0:]
        out.append(RoutineCheck(raw, [annotate(d) for d in raw], added, new_modules))
        d0, m0 = len(diags), len(motion)
        seen |= new_modules
    return out
