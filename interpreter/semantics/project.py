"""An L5X project as one ProgramModel: controller tags, programs with their own tag scopes,
AOIs, tasks and motion settings (SPEC 2.3, 9.16)."""

from __future__ import annotations

from ..diagnostics import Diagnostic, diag
from ..syntax import nodes as n
from ..syntax.l5x import AliasDecl, L5XProject
from .alias import AliasRequest, resolve_aliases
from .aoi import define_aoi
from .program import (
    ProgramInfo,
    ProgramModel,
    Tag,
    TaskInfo,
    declare_tags,
    declare_types,
    define_members,
    module_tag_note,
    scope_key,
)
from .types import ArrayType, DataType, StructType, TypeTable, unknown_type


def build_project(
    project: L5XProject, types: TypeTable | None = None
) -> tuple[ProgramModel, list[Diagnostic]]:
    types = types or TypeTable()
    path = project.path
    diags: list[Diagnostic] = []
    routines = [r for p in project.programs for r in p.routines]
    model = ProgramModel(project.controller or "project", routines, types)
    model.extra["l5x"] = project
    model.extra["modules"] = project.modules
    udts = declare_types(types, [(td, path) for td in project.types], diags)
    aoi_types = declare_types(
        types, [(n.TypeDecl(a.name, [], a.span, a.span), path) for a in project.aois], diags
    )
    define_members(types, udts, diags)
    declared = {st.name.upper(): st for _, st, _ in aoi_types}
    for a in project.aois:
        st = declared.get(a.name.upper())
        if st is not None:
            model.aois[a.name.upper()] = define_aoi(types, a, st, path, diags, frozenset(declared))
    _prune_inits(project.tags, types)
    declare_tags(model, project.tags, path, diags)
    for p in project.programs:
        key = p.name.upper()
        if key in model.programs:
            diags.append(diag("E117", f"program '{p.name}' is declared twice", path, p.span))
            continue
        model.programs[key] = ProgramInfo(p.name, p.main, p.span, p.disabled)
        _prune_inits(p.tags, types)
        declare_tags(model, p.tags, path, diags, program=p.name)
        if p.main and model.routine(p.main, p.name) is None:
            diags.append(
                diag(
                    "E124",
                    f"program '{p.name}' names main routine '{p.main}', which it does not have",
                    path,
                    p.span,
                )
            )
        seen: set[str] = set()
        for r in p.routines:
            if r.name.upper() in seen:
                diags.append(
                    diag(
                        "E117",
                        f"routine '{r.name}' is declared twice in program '{p.name}'",
                        path,
                        r.span,
                    )
                )
            seen.add(r.name.upper())
    _aliases(model, project, path, diags)
    for t in project.tasks:
        names = []
        for pname, sp in t.programs:
            if pname.upper() not in model.programs:
                diags.append(
                    diag(
                        "E124",
                        f"task '{t.name}' schedules program '{pname}', which the project does not have",
                        path,
                        sp,
                    )
                )
            else:
                names.append(model.programs[pname.upper()].name)
        model.tasks.append(TaskInfo(t.name, t.type, t.rate_ms, t.priority, names, t.inhibited))
    if project.coarse_update_us is not None:
        model.coarse_update_ms = project.coarse_update_us / 1000.0
    model.extra["axis_groups"] = dict(project.axis_groups)
    first = next((p for p in project.programs if p.main), None)
    model.main = first.main if first is not None else ""
    return model, [project.annotate(d) for d in diags]


def controller_scope(
    project: L5XProject, types: TypeTable | None = None
) -> tuple[TypeTable, list[n.VarDecl], list[Diagnostic]]:
    """For `--tags FILE.L5X`: the export's data types (UDTs, AOIs) and controller tags only
    (its controller aliases are declared once the model exists: declare_aliases)."""
    types = types or TypeTable()
    diags: list[Diagnostic] = []
    udts = declare_types(types, [(td, project.path) for td in project.types], diags)
    define_members(types, udts, diags)
    _prune_inits(project.tags, types)
    return types, project.tags, diags


def _aliases(model: ProgramModel, project: L5XProject, path: str, diags: list[Diagnostic]) -> None:
    scopes: list[tuple[str | None, list[AliasDecl]]] = [(None, project.aliases)]
    scopes += [(p.name, p.aliases) for p in project.programs]
    declare_aliases(model, scopes, path, diags)


def declare_aliases(
    model: ProgramModel,
    scopes: list[tuple[str | None, list[AliasDecl]]],
    path: str,
    diags: list[Diagnostic],
) -> None:
    """Controller (program None) and program aliases, resolved to their base tags
    (semantics/alias.py); `--tags FILE.L5X` declares the export's controller aliases too."""
    requests: dict[str, AliasRequest] = {}  # model.tags key -> request
    ordered: list[AliasRequest] = []
    for program, aliases in scopes:
        for a in aliases:
            key = scope_key(program, a.name) if program is not None else a.name.upper()
            prev = model.tags.get(key) or requests.get(key)
            if prev is not None:
                diags.append(
                    diag(
                        "E117",
                        f"tag '{a.name}' is already declared at line {prev.span.line}",
                        path,
                        a.span,
                    )
                )
                continue
            req = AliasRequest(a.name, a.target, a.span, program)
            requests[key] = req
            ordered.append(req)

    def lookup(ident: str, program: str | None) -> Tag | AliasRequest | None:
        if program is not None:
            key = scope_key(program, ident)
            found = model.tags.get(key) or requests.get(key)
            if found is not None:
                return found
        return model.tags.get(ident.upper()) or requests.get(ident.upper())

    resolved = resolve_aliases(
        ordered, lookup, path, diags, lambda ident: module_tag_note(model, ident)
    )
    for key, req in requests.items():
        tag = resolved.get(id(req))
        if tag is None:  # reported at the alias (E101/U305...): its uses are not, again
            tag = Tag(req.name, unknown_type(req.target), req.span, path, program=req.program)
        model.tags[key] = tag


def _prune_inits(decls: list[n.VarDecl], types: TypeTable) -> None:
    """Drop exported data for members this tool does not model (a Logix structure may have
    more members than our catalog type); what remains is verified like any initialiser."""
    for d in decls:
        if d.init is None:
            continue
        t = types.parse_type_text(d.type.name)
        if t is None:
            continue
        if d.type.dims:
            sizes = tuple(hi - lo + 1 for lo, hi in d.type.dims)
            t = ArrayType(t, sizes)
        d.init = _prune(d.init, t)


def _prune(init: n.Init, t: DataType) -> n.Init | None:
    if isinstance(init, n.StructInit):
        if not isinstance(t, StructType):
            return init
        kept = []
        for name, sp, v in init.members:
            m = t.member(name)
            if m is None or name.upper() in t.hidden:
                continue
            pv = _prune(v, m[1])
            if pv is not None:
                kept.append((name, sp, pv))
        init.members = kept
        return init
    if isinstance(init, n.ArrayInit) and isinstance(t, ArrayType):
        init.items = [x if (y := _prune(x, t.elem)) is None else y for x in init.items][: t.size]
        return init
    if isinstance(init, n.Literal) and isinstance(t, StructType) and not t.is_string:
        return None  # a scalar where we model a structure (e.g. L5K of an unmodelled layout)
    return init
