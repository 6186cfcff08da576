"""Size and nesting limits of one routine, measured without recursion (docs/limits.md).

The checker, compiler and code generator walk the AST recursively, and the generated Python
has limits of its own (about 100 nested blocks, 20 nested loops). This pass measures the
routine first, with an explicit stack, so a routine beyond a limit gets one diagnostic at
the place that exceeds it, from `check` and `run` alike, and is not walked any further.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator
from typing import Any

from ..limits import (
    MAX_BLOCK_NESTING,
    MAX_BRANCH_NESTING,
    MAX_EXPRESSION_DEPTH,
    MAX_LOOP_NESTING,
    MAX_ROUTINE_ELEMENTS,
    MAX_RUNG_ELEMENTS,
    MAX_TAG_ELEMENTS,
)
from ..syntax import nodes as n
from .program import Tag
from .types import ArrayType, StructType

_BLOCKS = (n.If, n.Case, n.For, n.While, n.Repeat)
_LOOPS = (n.For, n.While, n.Repeat)
_EXPRS = (
    n.Literal,
    n.Name,
    n.Member,
    n.Index,
    n.Bit,
    n.IndirectBit,
    n.Unary,
    n.Binary,
    n.Call,
    n.EnumText,
    n.Placeholder,
)


def routine_limits(r: n.Routine) -> list[tuple[str, n.Span]]:
    """The limits this routine exceeds: (message, place), at most one per top-level statement
    or rung (the first place found beyond a limit)."""
    if r.language == "rll":
        problems = [p for rung in r.rungs if (p := _rung(rung)) is not None]
    else:
        problems = list(_statements(r.body))
    return problems or _routine_size(r)


def _routine_size(r: n.Routine) -> list[tuple[str, n.Span]]:
    """Statements or ladder elements of the whole routine (compiled code grows with them)."""
    count = 0
    stack: list[object] = [*reversed(r.rungs), *reversed(r.body)]
    while stack:
        node = stack.pop()
        if isinstance(node, n.Rung):
            stack.extend(reversed(node.elements))
            continue
        if isinstance(node, n.Branch):
            stack.extend(e for leg in reversed(node.legs) for e in reversed(leg))
        elif isinstance(node, n.If):
            stack.extend(
                reversed([*(s for _, b in node.branches for s in b), *(node.else_body or [])])
            )
        elif isinstance(node, n.Case):
            stack.extend(
                reversed([*(s for a in node.arms for s in a.body), *(node.else_body or [])])
            )
        elif isinstance(node, n.For | n.While | n.Repeat):
            stack.extend(reversed(node.body))
        count += 1
        if count > MAX_ROUTINE_ELEMENTS:
            what = "instructions and branches" if r.language == "rll" else "statements"
            return [
                (
                    f"routine of more than {MAX_ROUTINE_ELEMENTS:,} {what}: the limit is "
                    f"{MAX_ROUTINE_ELEMENTS:,} (split it into several routines)",
                    node.span,  # type: ignore[attr-defined]
                )
            ]
    return []


_NODE_FIELDS: dict[type, tuple[str, ...]] = {}

# the common nodes' children without reflection: this pass sees every node of every routine
_FAST: dict[type, Callable[[Any], list[object]]] = {
    n.Assign: lambda x: [x.target, x.value],
    n.Binary: lambda x: [x.left, x.right],
    n.Unary: lambda x: [x.operand],
    n.Name: lambda x: [],
    n.Literal: lambda x: [],
    n.EnumText: lambda x: [],
    n.Placeholder: lambda x: [],
    n.Member: lambda x: [x.base],
    n.Index: lambda x: [x.base, *x.indices],
    n.Call: lambda x: [a.value for a in x.args],
    n.CallStmt: lambda x: [x.call],
}


def _children(node: object) -> Iterable[object]:
    """The AST nodes directly inside `node` (in fields, lists and (expr, body) pairs)."""
    cls = type(node)
    fast = _FAST.get(cls)
    if fast is not None:
        return fast(node)
    fields = _NODE_FIELDS.get(cls)
    if fields is None:
        fields = _NODE_FIELDS[cls] = tuple(
            f
            for f in cls.__slots__  # type: ignore[attr-defined]
            if f not in ("span", "name_span", "text", "ident", "op")
        )
    return [c for name in fields for c in _flatten(getattr(node, name))]


def _flatten(value: object) -> Iterator[object]:
    if isinstance(value, n.Span | str | int | float | bytes) or value is None:
        return
    if isinstance(value, list | tuple):
        for v in value:
            yield from _flatten(v)
    elif hasattr(value, "__slots__"):
        yield value


def _statements(body: list[n.Stmt]) -> Iterator[tuple[str, n.Span]]:
    """At most one problem per top-level statement: the first place beyond a limit."""
    for stmt in body:
        problem = _first_problem(stmt)
        if problem is not None:
            yield problem


def _first_problem(root: object) -> tuple[str, n.Span] | None:
    # (node, enclosing blocks, enclosing loops, expression depth); expressions count from 1
    stack: list[tuple[object, int, int, int]] = [(root, 0, 0, 0)]
    while stack:
        node, blocks, loops, depth = stack.pop()
        if isinstance(node, _EXPRS):
            depth += 1
            if depth > MAX_EXPRESSION_DEPTH:
                return (
                    f"expression nested more than {MAX_EXPRESSION_DEPTH:,} operations deep: "
                    f"the limit is {MAX_EXPRESSION_DEPTH:,} (split it with intermediate tags)",
                    node.span,
                )
        elif isinstance(node, _BLOCKS):
            blocks += 1
            loops += isinstance(node, _LOOPS)
            depth = 0
            if blocks > MAX_BLOCK_NESTING:
                return (
                    f"statement blocks nested {blocks} deep: the limit is {MAX_BLOCK_NESTING}",
                    node.span,
                )
            if loops > MAX_LOOP_NESTING:
                return f"loops nested {loops} deep: the limit is {MAX_LOOP_NESTING}", node.span
        elif not isinstance(node, n.Arg | n.CaseArm | n.CaseRange):
            depth = 0  # a plain statement
        stack.extend((c, blocks, loops, depth) for c in _children(node))
    return None


def _rung(rung: n.Rung) -> tuple[str, n.Span] | None:
    """Elements in one rung and branch nesting, counted iteratively."""
    count = 0
    stack: list[tuple[list[n.LadderElement], int]] = [(rung.elements, 0)]
    while stack:
        elements, level = stack.pop()
        for e in elements:
            count += 1
            if count > MAX_RUNG_ELEMENTS:
                return (
                    f"rung of more than {MAX_RUNG_ELEMENTS:,} instructions and branches: "
                    f"the limit is {MAX_RUNG_ELEMENTS:,} (split it into several rungs)",
                    e.span,
                )
            if isinstance(e, n.Branch):
                if level + 1 > MAX_BRANCH_NESTING:
                    return (
                        f"branches nested {level + 1} deep: the limit is {MAX_BRANCH_NESTING}",
                        e.span,
                    )
                stack.extend((leg, level + 1) for leg in reversed(e.legs))
            else:
                for op in e.operands:  # an operand expression (CPT) has the ST depth limit
                    problem = _first_problem(op)
                    if problem is not None:
                        return problem
    return None


def storage_elements(t: object, memo: dict[int, int]) -> int:
    """Elementary values a tag of type `t` holds (an array of structures: all their members)."""
    if isinstance(t, ArrayType):
        return t.size * storage_elements(t.elem, memo)
    if isinstance(t, StructType):
        known = memo.get(id(t))
        if known is None:
            memo[id(t)] = 0  # a (malformed) type that contains itself counts once
            known = memo[id(t)] = sum(storage_elements(mt, memo) for _, mt in t.members)
        return known
    return 1


def storage_limit(tags: Iterable[Tag]) -> tuple[Tag, int] | None:
    """The tag whose storage takes the total past MAX_TAG_ELEMENTS, and the total so far."""
    memo: dict[int, int] = {}
    total = 0
    for tag in tags:
        if tag.alias_of is not None:
            continue  # an alias shares its base tag's storage
        total += storage_elements(tag.type, memo)
        if total > MAX_TAG_ELEMENTS:
            return tag, total
    return None
