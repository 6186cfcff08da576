"""A program as semantics sees it: routines, UDTs and tags with their declared types."""

from __future__ import annotations

from dataclasses import dataclass, field

from ..diagnostics import Diagnostic, diag
from ..syntax import nodes as n
from .types import ArrayType, DataType, StructType, TypeTable

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

    def routine(self, name: str) -> n.Routine | None:
        key = name.upper()
        for r in self.routines:
            if r.name.upper() == key:
                return r
        return None

    def tag(self, name: str) -> Tag | None:
        return self.tags.get(name.upper())


def const_number(e: object) -> int | float | None:
    """Value of a literal number, possibly negated; None for anything else."""
    if isinstance(e, n.Literal) and isinstance(e.value, int | float):
        return e.value
    if isinstance(e, n.Unary) and e.op == "-":
        inner = const_number(e.operand)
        return None if inner is None else -inner
    return None


def resolve_typeref(types: TypeTable, ref: n.TypeRef, path: str, diags: list[Diagnostic]) -> DataType | None:
    base = types.get(ref.name)
    if base is None:
        diags.append(diag("E119", f"unknown data type '{ref.name}'", path, ref.span))
        return None
    if not ref.dims:
        return base
    if len(ref.dims) > MAX_DIMS:
        diags.append(diag("E125", f"at most {MAX_DIMS} array dimensions are allowed", path, ref.span))
        return None
    sizes = []
    for lo, hi in ref.dims:
        if lo != 0:
            diags.append(diag("E125", f"Logix arrays start at 0, not {lo}", path, ref.span))
            return None
        if hi < lo:
            diags.append(diag("E125", "array dimension must hold at least one element", path, ref.span))
            return None
        sizes.append(hi - lo + 1)
    return ArrayType(base, tuple(sizes))


def build_program(name: str, routines: list[n.Routine], types: TypeTable | None = None) -> tuple[ProgramModel, list[Diagnostic]]:
    """Collect UDTs and tag declarations of all routines into one scope (SPEC 2.4)."""
    types = types or TypeTable()
    diags: list[Diagnostic] = []
    model = ProgramModel(name, routines, types, main=routines[0].name if routines else "")
    # UDTs first, in two passes so members may name UDTs declared later.
    udts: list[tuple[n.TypeDecl, StructType, str]] = []
    for r in routines:
        for td in r.types:
            if types.get(td.name) is not None and (
                not isinstance(types.get(td.name), StructType) or types.get(td.name).builtin  # type: ignore[union-attr]
            ):
                diags.append(diag("E117", f"type '{td.name}' is already defined", r.path, td.name_span))
                continue
            if any(u[0].name.upper() == td.name.upper() for u in udts):
                diags.append(diag("E117", f"type '{td.name}' is declared twice", r.path, td.name_span))
                continue
            udts.append((td, types.declare_udt(td.name), r.path))
    for td, st, path in udts:
        for m in td.members:
            mt = resolve_typeref(types, m.type, path, diags)
            for mname, mspan in m.names:
                if st.member(mname) is not None:
                    diags.append(diag("E117", f"member '{mname}' is declared twice", path, mspan))
                elif mt is not None:
                    types.add_member(st, mname, mt)
                    if m.init is not None:
                        value = const_number(m.init)
                        if value is None:
                            diags.append(diag("E118", "a member default must be a number", path, m.span))
                        else:
                            st.defaults[mname.upper()] = value
    for r in routines:
        for d in r.decls:
            t = resolve_typeref(types, d.type, r.path, diags)
            for tname, tspan in d.names:
                key = tname.upper()
                if key in model.tags:
                    prev = model.tags[key]
                    diags.append(
                        diag("E117", f"tag '{tname}' is already declared at line {prev.span.line}", r.path, tspan)
                    )
                    continue
                if t is not None:
                    model.tags[key] = Tag(tname, t, tspan, r.path, d.init, init_path=r.path)
    return model, diags
