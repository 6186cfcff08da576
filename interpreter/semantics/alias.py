"""Alias tags: a name for a fixed place in another tag (decision 0044).

`<Tag Name="A" TagType="Alias" AliasFor="Base.Member[2].3">` owns no storage: it is a Tag
whose `alias_of` is the base tag (never another alias), whose `access` is the path of member
and element positions from the base's slot to the aliased place, and whose `bit` names the
bit when the alias is one bit of an integer. The checker types a use of the alias as the
aliased place and the compiler reaches the base's storage through the path, so reading,
writing, members and bits through an alias are exactly those of the base.

Aliases may name other aliases in any order of declaration (a chain is followed to its
base), program aliases may name controller tags, and AOI alias parameters name local tags.
A missing base, a cycle or a place that is not fixed (a variable subscript) is one
diagnostic at the alias declaration; uses of that alias are left undeclared.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from ..diagnostics import Diagnostic, diag
from ..syntax import nodes as n
from ..syntax.st_lexer import SlowPath, fast_parse
from ..syntax.st_parser import _parser, parse_expression
from .program import Tag
from .types import BOOL, ArrayType, DataType, Elementary, StructType


@dataclass(slots=True)
class AliasRequest:
    """One alias to resolve: its name, AliasFor text, declaration and where it is declared."""

    name: str
    target: str
    span: n.Span
    program: str | None = None  # program scope; None = controller (or AOI) scope


class _Unresolved(Exception):
    def __init__(self, code: str, reason: str, cycle: list[AliasRequest] | None = None) -> None:
        self.code, self.reason, self.cycle = code, reason, cycle


# `lookup(ident, program)` finds what a root name means in the alias's scope: a declared Tag,
# another alias request, or None. Program scope comes first, then controller scope.
Lookup = Callable[[str, str | None], "Tag | AliasRequest | None"]


def resolve_aliases(
    requests: list[AliasRequest],
    lookup: Lookup,
    path: str,
    diags: list[Diagnostic],
    missing_note: Callable[[str], str] = lambda ident: "",
) -> dict[int, Tag]:
    """Resolve every request; id(request) -> its alias Tag (absent when it has no base).

    Each alias without a base gets one diagnostic at its own declaration. `missing_note(ident)`
    explains a base name that is missing for a known reason (a module whose data is not in
    the export): that alias is reported as not simulated (U305) rather than as an error.
    """
    done: dict[int, Tag | None] = {}

    def report(req: AliasRequest, code: str, reason: str) -> None:
        suffix = "; it is not simulated" if code == "U305" else ""
        msg = f"alias '{req.name}' for '{req.target}': {reason}{suffix}"
        diags.append(diag(code, msg, path, req.span))
        done[id(req)] = None

    def resolve(req: AliasRequest, chain: list[AliasRequest]) -> Tag | None:
        """The alias Tag of `req`, or None (reported); `chain` are the aliases leading here."""
        if id(req) in done:
            return done[id(req)]
        if any(r is req for r in chain):
            cycle = chain[next(i for i, r in enumerate(chain) if r is req) :]
            names = " -> ".join(r.name for r in [*cycle, req])
            raise _Unresolved("E101", f"the aliases form a cycle ({names}) with no base tag", cycle)
        try:
            tag = _resolve_one(req, chain)
        except _Unresolved as why:
            if why.cycle is not None and any(r is req for r in why.cycle):
                if req is not why.cycle[0]:
                    raise  # the first alias of the cycle reports it for every member
                for r in why.cycle:
                    report(r, why.code, why.reason)
                return None
            report(req, why.code, why.reason)
            return None
        done[id(req)] = tag
        return tag

    def _resolve_one(req: AliasRequest, chain: list[AliasRequest]) -> Tag:
        expr = _reference(req.target.strip())
        if expr is None:
            raise _Unresolved("E101", "this is not a tag reference")
        steps: list[n.Expr] = []
        root = expr
        while isinstance(root, n.Member | n.Index | n.Bit):
            steps.append(root)
            root = root.base
        if not isinstance(root, n.Name):
            raise _Unresolved("E101", "this is not a tag reference")
        found = lookup(root.ident, req.program)
        if found is None:
            note = missing_note(root.ident)
            if note:
                raise _Unresolved("U305", f"'{root.ident}'{note}")
            raise _Unresolved("E101", f"'{root.ident}' is not a declared tag")
        if isinstance(found, AliasRequest):
            inner = resolve(found, [*chain, req])
            if inner is None:
                raise _Unresolved("E101", f"alias '{found.name}' has no base tag")
            found = inner
        base = found.alias_of or found
        t, access, bit = _walk(found.type, list(found.access), found.bit, reversed(steps))
        tag = Tag(
            req.name,
            t,
            req.span,
            path,
            program=req.program,
            access=tuple(access),
            alias_of=base,
            bit=bit,
        )
        tag.slot = base.slot
        return tag

    for req in requests:
        resolve(req, [])
    return {k: v for k, v in done.items() if v is not None}


def _reference(text: str) -> n.Expr | None:
    """The AliasFor text as an expression; the fast LALR driver first (exports may hold
    thousands of aliases), lark's parser for anything it refuses."""
    try:
        return fast_parse(_parser(), text, "expr")  # type: ignore[no-any-return]
    except SlowPath:
        pass
    try:
        return parse_expression(text)
    except ValueError:
        return None


def _walk(
    t: DataType,
    access: list[int],
    bit: tuple[int, Elementary] | None,
    steps: object,
) -> tuple[DataType, list[int], tuple[int, Elementary] | None]:
    """Follow members, constant subscripts and a bit number from a place of type `t`."""
    for step in steps:  # type: ignore[attr-defined]
        if isinstance(t, StructType) and not t.members:
            # a type this tool does not model (reported where the base is declared): the
            # alias shares it, so its uses are judged as the base's would be
            return t, access, None
        if bit is not None:
            raise _Unresolved("E121", "a single bit has no members, elements or bits")
        if isinstance(step, n.Member):
            m = t.member(step.name) if isinstance(t, StructType) else None
            if m is None or step.name.upper() in t.hidden:  # type: ignore[union-attr]
                raise _Unresolved("E102", f"{t} has no member '{step.name}'")
            access.append(m[0])
            t = m[1]
        elif isinstance(step, n.Index):
            if not isinstance(t, ArrayType):
                raise _Unresolved("E110", f"{t} is not an array")
            if len(step.indices) != len(t.dims):
                raise _Unresolved("E110", f"{t} takes {len(t.dims)} subscript(s)")
            flat = 0
            for i, size in zip(step.indices, t.dims, strict=True):
                if not (isinstance(i, n.Literal) and isinstance(i.value, int)):
                    raise _Unresolved(
                        "E110", "an alias names a fixed element: subscripts are numbers"
                    )
                if not 0 <= i.value < size:
                    raise _Unresolved("E122", f"subscript {i.value} is outside 0..{size - 1}")
                flat = flat * size + i.value
            access.append(flat)
            t = t.elem
        else:
            assert isinstance(step, n.Bit)
            if not isinstance(t, Elementary) or not t.is_integer or t is BOOL:
                raise _Unresolved("E121", f"{t} has no bits")
            if not 0 <= step.bit < t.bits:
                raise _Unresolved("E122", f"bit {step.bit} is outside 0..{t.bits - 1} of {t}")
            bit = (step.bit, t)
            t = BOOL
    return t, access, bit
