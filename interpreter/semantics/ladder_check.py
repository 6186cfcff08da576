"""Rung-level verification of ladder routines (SPEC 7): empty rungs and shorted branches.

Each instruction on a rung is checked by the same code as an ST instruction call
(Checker.instruction); this module only walks the rung structure. The rule for W202 is
recorded in docs/decisions/0011-ladder-checks.md.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from ..diagnostics import diag
from ..syntax import nodes as n

if TYPE_CHECKING:
    from .checker import Analysis


class LadderChecks:
    """Mixed into Checker: needs `a`, `path`, `err` and `ladder_instr`."""

    a: Analysis
    path: str

    def err(self, code: str, msg: str, span: n.Span) -> None: ...  # provided by Checker

    def ladder_instr(self, i: n.LadderInstr) -> None: ...  # provided by Checker

    def rungs(self, rungs: list[n.Rung]) -> None:
        for rung in rungs:
            if not rung.elements:
                self.err("E129", f"rung {rung.number} is empty: give it at least one instruction (NOP)", rung.span)
            self.sequence(rung.elements, feeds=False)

    def sequence(self, elements: list[n.LadderElement], feeds: bool) -> bool:
        """Check elements in series (`feeds`: the rung goes on after the last of them).
        True when a shorted branch was reported among them."""
        shorted = False
        for k, e in enumerate(elements):
            if isinstance(e, n.LadderInstr):
                self.ladder_instr(e)
            else:
                shorted |= self.branch(e, feeds or k < len(elements) - 1)
        return shorted

    def branch(self, b: n.Branch, feeds: bool) -> bool:
        inner = [self.sequence(leg, feeds) for leg in b.legs]
        if not feeds:
            return any(inner)  # an output branch: what its legs pass on is not used
        conditional = [self.conditional(leg) for leg in b.legs]
        # a leg that is always true only through a shorted branch inside it was reported there
        bare = [i for i, c in enumerate(conditional) if not c and not inner[i]]
        if bare and any(conditional):
            self.a.diags.append(diag(
                "W202",
                f"leg {bare[0] + 1} of this branch has no input instruction: it is always true and "
                "shorts the conditions of the other legs",
                self.path, b.span,
            ))
            return True
        return any(inner)

    def conditional(self, leg: list[n.LadderElement]) -> bool:
        """Whether a leg can be false: it holds an input instruction, or a branch whose legs
        all can. An instruction the catalog does not know (an AOI) may be a condition."""
        for e in leg:
            if isinstance(e, n.Branch):
                if all(self.conditional(x) for x in e.legs):
                    return True
            else:
                ins = self.a.call_of.get(id(e))
                if ins is None or ins.input:
                    return True
        return False
