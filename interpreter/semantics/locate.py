"""Find AST nodes: every node under a routine, and the innermost nodes at a position.

The AST is plain dataclasses with `span`s (syntax/nodes.py); these walk them generically so
that new node kinds are found without edits here.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import fields, is_dataclass

from ..syntax import nodes as n


def walk(node: object) -> Iterator[object]:
    """`node` and every AST node below it, depth first, in source order."""
    stack = [node]
    while stack:
        cur = stack.pop()
        if isinstance(cur, list | tuple):
            stack.extend(reversed(cur))
            continue
        if not is_dataclass(cur) or isinstance(cur, type):
            continue
        yield cur
        children = [getattr(cur, f.name) for f in fields(cur) if f.name != "span"]
        stack.extend(
            reversed([c for c in children if isinstance(c, list | tuple) or is_dataclass(c)])
        )


def contains(span: n.Span, line: int, col: int) -> bool:
    """1-based (line, col) inside `span` (end exclusive, but a cursor just after a word counts)."""
    if (line, col) < (span.line, span.col):
        return False
    return (line, col) <= (span.end_line, span.end_col)


def nodes_at(routine: n.Routine, line: int, col: int) -> list[object]:
    """The nodes whose span holds the position, outermost first (the last is the innermost)."""
    chain: list[object] = []
    for node in walk([routine.body, routine.rungs, routine.decls, routine.types]):
        span = getattr(node, "span", None)
        if isinstance(span, n.Span) and contains(span, line, col):
            chain.append(node)
    return chain


def names_in(routines: list[n.Routine]) -> Iterator[tuple[n.Routine, n.Name]]:
    """Every tag reference (`Name` node) in the routines' code and initialisers."""
    for r in routines:
        for node in walk([r.body, r.rungs, r.decls]):
            if isinstance(node, n.Name):
                yield r, node
