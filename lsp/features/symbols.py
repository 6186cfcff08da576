"""Document symbols (types, tags, routines, rungs with their comments) and folding ranges."""

from __future__ import annotations

from dataclasses import dataclass, field

from interpreter.syntax import nodes as n

from ..workspace import Analysed


class SymbolKind:
    """The LSP numbers, so the server passes them through."""

    NAMESPACE = 3
    METHOD = 6
    FIELD = 8
    FUNCTION = 12
    VARIABLE = 13
    STRUCT = 23
    EVENT = 24


@dataclass(slots=True)
class Symbol:
    name: str
    kind: int
    span: n.Span
    detail: str = ""
    children: list[Symbol] = field(default_factory=list)


def document_symbols(an: Analysed) -> list[Symbol]:
    path = an.document.path
    model = an.loaded.model
    out: list[Symbol] = []
    for r in model.routines:
        if r.path != path:
            continue
        out.extend(_types(r.types))
        out.extend(_decls(r.decls))
    project = an.loaded.project
    if project is not None:
        out.extend(_types(project.types))
        out.extend(_decls(project.tags))
        for prog in project.programs:
            kids = _decls(prog.tags) + [_routine(r) for r in prog.routines]
            out.append(Symbol(prog.name, SymbolKind.NAMESPACE, prog.span, "program", kids))
    else:
        out.extend(_routine(r) for r in model.routines if r.path == path)
    return out


def _types(types: list[n.TypeDecl]) -> list[Symbol]:
    return [
        Symbol(td.name, SymbolKind.STRUCT, td.span, "type", _decls(td.members, SymbolKind.FIELD))
        for td in types
    ]


def _decls(decls: list[n.VarDecl], kind: int = SymbolKind.VARIABLE) -> list[Symbol]:
    return [
        Symbol(name, kind, d.span if d.span.line == span.line else span, _type_text(d.type))
        for d in decls
        for name, span in d.names
    ]


def _type_text(t: n.TypeRef) -> str:
    if not t.dims:
        return t.name
    return f"{t.name}[{','.join(str(hi - lo + 1) for lo, hi in t.dims)}]"


def _routine(r: n.Routine) -> Symbol:
    rungs = [
        Symbol(f"Rung {rung.number}", SymbolKind.EVENT, rung.span, rung.comment or "")
        for rung in r.rungs
    ]
    span = r.span if r.span.line > 0 else n.Span(1, 1, 1, 1)
    return Symbol(r.name, SymbolKind.FUNCTION, span, f"{r.language} routine", rungs)


BLOCKS = (n.If, n.Case, n.For, n.While, n.Repeat)


def folding_ranges(an: Analysed) -> list[tuple[int, int, str]]:
    """(first line, last line, kind) 1-based; kind 'region' or 'comment'."""
    from interpreter.semantics.locate import walk

    path = an.document.path
    out: list[tuple[int, int, str]] = []
    routines = [r for r in an.loaded.model.routines if r.path == path]
    for r in routines:
        for node in walk([r.body, r.types]):
            if isinstance(node, (*BLOCKS, n.TypeDecl)) and node.span.end_line > node.span.line:
                out.append((node.span.line, node.span.end_line, "region"))
        for c in r.comments:
            if c.span.end_line > c.span.line:
                out.append((c.span.line, c.span.end_line, "comment"))
        if r.decls:
            first, last = r.decls[0].span.line, r.decls[-1].span.end_line
            if last > first:
                out.append((first, last, "region"))
    return sorted(set(out))
