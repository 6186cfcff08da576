"""A program as semantics sees it: routines, UDTs and tags with their declared types."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from ..diagnostics import Diagnostic, diag
from ..limits import MAX_ARRAY_ELEMENTS
from ..syntax import nodes as n
from .types import ArrayType, DataType, Elementary, StructType, TypeTable, unknown_type

MAX_DIMS = 3


@dataclass(slots=True)
class Tag:
    name: str
    type: DataType
    span: n.Span
    path: str
    init: n.Init | None = None
    slot: int = -1
    program: str | None = None  # program scope (L5X); None = controller / file scope
    init_path: str | None = None
    access: tuple[int, ...] = ()  # member/element positions below the slot (AOI frames, aliases)
    alias_of: Tag | None = None  # an alias shares its base tag's storage (semantics/alias.py)
    bit: tuple[int, Elementary] | None = None  # a BOOL alias of one bit: (bit, integer type)

    @property
    def qualified(self) -> str:
        """The name `--watch` takes: `Program:Main.Tag` for program tags (SPEC 9.9)."""
        return f"Program:{self.program}.{self.name}" if self.program else self.name


@dataclass(slots=True)
class ProgramInfo:
    """An L5X program: its own tag scope, routines and main routine (SPEC 2.3, 9.16)."""

    name: str
    main: str
    span: n.Span
    disabled: bool = False


@dataclass(slots=True)
class TaskInfo:
    name: str
    type: str  # CONTINUOUS | PERIODIC | EVENT
    rate_ms: float
    priority: int
    programs: list[str]
    inhibited: bool = False


def scope_key(program: str, name: str) -> str:
    """Key of a program-scope tag in ProgramModel.tags (controller tags use the plain name)."""
    return f"PROGRAM:{program.upper()}.{name.upper()}"  # scoped_programs reads this form back


def scoped_programs(tags: dict[str, Tag]) -> set[str]:
    """Upper-case names of the programs that may own tags among `tags` (keys from scope_key).

    A program not in the set has no tags of its own: it sees the controller scope. A key
    `PROGRAM:A.B.NAME` counts for `A` and for `A.B`, as a dot in the program name cannot be
    told apart here; naming one program too many never hides a tag.
    """
    programs: set[str] = set()
    for key in tags:
        if key.startswith("PROGRAM:"):
            rest = key[len("PROGRAM:") :]
            dot = rest.find(".")
            while dot >= 0:
                programs.add(rest[:dot])
                dot = rest.find(".", dot + 1)
    return programs


@dataclass(slots=True)
class ProgramModel:
    """What `run`, `check` and the language server work on: one program (or L5X project)."""

    name: str
    routines: list[n.Routine]
    types: TypeTable
    tags: dict[str, Tag] = field(default_factory=dict)  # upper-case name -> Tag
    main: str = ""
    coarse_update_ms: float | None = None
    extra: dict[str, object] = field(default_factory=dict)
    programs: dict[str, ProgramInfo] = field(default_factory=dict)  # L5X only; upper name -> info
    tasks: list[TaskInfo] = field(default_factory=list)
    aois: dict[str, object] = field(default_factory=dict)  # upper name -> semantics.aoi.Aoi

    def all_routines(self) -> list[n.Routine]:
        """The program's routines and those of its add-on instructions (Logic, Prescan ...)."""
        routines = list(self.routines)
        for aoi in self.aois.values():
            routines.extend(getattr(aoi, "routines", {}).values())
        return routines

    def routine(self, name: str, program: str | None = None) -> n.Routine | None:
        """A routine by name; in an L5X project only among the routines of `program`."""
        key = name.upper()
        scope = program.upper() if program is not None and self.programs else None
        for r in self.routines:
            if r.name.upper() == key and (scope is None or (r.program_name or "").upper() == scope):
                return r
        return None

    def tag(self, name: str, program: str | None = None) -> Tag | None:
        """Program tags shadow controller tags of the same name (L5X); `Program:P.T` names one."""
        if program is not None:
            t = self.tags.get(scope_key(program, name))
            if t is not None:
                return t
        return self.tags.get(name.upper())


def module_tag_note(model: ProgramModel, ident: str) -> str:
    """Why a module I/O tag name (`Local:3:I`, `Drive1:O`) has no tag: its module's data is not
    in the export (a connection without Decorated data, or no such module in `<Modules>`).
    Empty for a name that is not a module tag's (every other tag name is free of ':')."""
    if ":" not in ident or ident.upper().startswith("PROGRAM:"):
        return ""
    modules: dict[str, str] = model.extra.get("modules", {})  # type: ignore[assignment]
    module = modules.get(ident.rsplit(":", 1)[0].upper())
    if module is not None:
        project = model.extra.get("l5x")
        if str(getattr(project, "path", "")).lower().endswith(".l5k"):
            # L5K gives connection data as bare values, never the module-defined layout
            return f": the layout of module '{module}' data is not in an .L5K export"
        return f": the data of module '{module}' is not in the export (no Decorated data)"
    if "l5x" in model.extra:
        return ": its module is not in the export"
    return ": module I/O tags exist only in an L5X export holding the module's data"


def const_number(e: object) -> int | float | None:
    """Value of a literal number, possibly negated; None for anything else."""
    if isinstance(e, n.Literal) and isinstance(e.value, int | float):
        return e.value
    if isinstance(e, n.Unary) and e.op == "-":
        inner = const_number(e.operand)
        return None if inner is None else -inner
    return None


def resolve_typeref(
    types: TypeTable, ref: n.TypeRef, path: str, diags: list[Diagnostic]
) -> DataType:
    """The declared type; one that cannot be resolved is reported here, once, and stands in
    as an unknown type that accepts every use (decision 0054), so nothing cascades."""
    base = types.get(ref.name)
    if base is None:
        if ":" in ref.name:  # AB:1756_DI:I:0 ...: defined by a module profile, not the export
            diags.append(
                diag(
                    "U306",
                    f"module-defined data type '{ref.name}' is not described in this export",
                    path,
                    ref.span,
                )
            )
            return types.declare_unknown(ref.name)  # one U306 per type (decision 0056)
        # Studio exports `DataType="NULL"` for a member whose type it could not resolve: the
        # data type does not verify in Studio either (decision 0074)
        what = (
            "no data type: Studio writes NULL where the member's type is undefined"
            if ref.name.upper() == "NULL"
            else f"unknown data type '{ref.name}'"
        )
        diags.append(diag("E119", what, path, ref.span))
        return unknown_type(ref.name)
    if isinstance(base, StructType) and base.unknown:
        return base  # already reported; an array of it accepts any use as well
    if not ref.dims:
        return base
    if len(ref.dims) > MAX_DIMS:
        diags.append(
            diag("E125", f"at most {MAX_DIMS} array dimensions are allowed", path, ref.span)
        )
        return unknown_type(ref.name)
    sizes = []
    for lo, hi in ref.dims:
        if lo != 0:
            diags.append(diag("E125", f"Logix arrays start at 0, not {lo}", path, ref.span))
            return unknown_type(ref.name)
        if hi < lo:
            diags.append(
                diag("E125", "array dimension must hold at least one element", path, ref.span)
            )
            return unknown_type(ref.name)
        sizes.append(hi - lo + 1)
    count = math.prod(sizes)
    if count > MAX_ARRAY_ELEMENTS:  # refused here, before anything allocates it (docs/limits.md)
        diags.append(
            diag(
                "E132",
                f"array of {count:,} elements: the limit is {MAX_ARRAY_ELEMENTS:,} per array",
                path,
                ref.span,
            )
        )
        return unknown_type(ref.name)
    return ArrayType(base, tuple(sizes))


def declare_types(
    types: TypeTable, decls: list[tuple[n.TypeDecl, str]], diags: list[Diagnostic]
) -> list[tuple[n.TypeDecl, StructType, str]]:
    """Declare UDT names (first pass, so members may name UDTs declared later)."""
    udts: list[tuple[n.TypeDecl, StructType, str]] = []
    # names a user type or a module declares: a described type of the same name gives way
    own = {td.name.upper() for td, _ in decls if not td.described}
    for td, path in decls:
        existing = types.get(td.name)
        if td.described and (existing is not None or td.name.upper() in own):
            # Studio's description of a type known here already (a built-in, or a module's
            # type read from its connection data): the known definition stands
            continue
        if existing is not None and (not isinstance(existing, StructType) or existing.builtin):
            diags.append(diag("E117", f"type '{td.name}' is already defined", path, td.name_span))
            continue
        if any(u[0].name.upper() == td.name.upper() for u in udts):
            diags.append(diag("E117", f"type '{td.name}' is declared twice", path, td.name_span))
            continue
        udts.append((td, types.declare_udt(td.name), path))
    return udts


def define_members(
    types: TypeTable, udts: list[tuple[n.TypeDecl, StructType, str]], diags: list[Diagnostic]
) -> None:
    """Second pass: resolve every member type and default."""
    for td, st, path in udts:
        for m in td.members:
            mt = resolve_typeref(types, m.type, path, diags)
            for mname, mspan in m.names:
                if st.member(mname) is not None:
                    diags.append(diag("E117", f"member '{mname}' is declared twice", path, mspan))
                else:
                    types.add_member(st, mname, mt)
                    if m.init is not None:
                        value = const_number(m.init)
                        if value is None:
                            diags.append(
                                diag("E118", "a member default must be a number", path, m.span)
                            )
                        else:
                            st.defaults[mname.upper()] = value


def declare_tags(
    model: ProgramModel,
    decls: list[n.VarDecl],
    path: str,
    diags: list[Diagnostic],
    program: str | None = None,
) -> None:
    """Add tags to the model; program tags are keyed `PROGRAM:P.NAME` (see scope_key)."""
    types = model.types
    for d in decls:
        t = resolve_typeref(types, d.type, path, diags)
        for tname, tspan in d.names:
            key = scope_key(program, tname) if program is not None else tname.upper()
            if key in model.tags:
                prev = model.tags[key]
                diags.append(
                    diag(
                        "E117",
                        f"tag '{tname}' is already declared at line {prev.span.line}",
                        path,
                        tspan,
                    )
                )
                continue
            model.tags[key] = Tag(tname, t, tspan, path, d.init, program=program, init_path=path)


def build_program(
    name: str,
    routines: list[n.Routine],
    types: TypeTable | None = None,
    shared: tuple[list[n.VarDecl], str] | None = None,
) -> tuple[ProgramModel, list[Diagnostic]]:
    """Collect UDTs and tag declarations of all routines into one scope (SPEC 2.4).

    `shared` are controller tags from `--tags FILE.L5X` (declared first, checked as L5X data).
    """
    types = types or TypeTable()
    diags: list[Diagnostic] = []
    model = ProgramModel(name, routines, types, main=routines[0].name if routines else "")
    udts = declare_types(types, [(td, r.path) for r in routines for td in r.types], diags)
    define_members(types, udts, diags)
    if shared is not None:
        declare_tags(model, shared[0], shared[1], diags)
        model.extra["tag_data"] = shared[1]
    for r in routines:
        declare_tags(model, r.decls, r.path, diags)
    return model, diags
