"""Rung-level verification of ladder routines (SPEC 7): empty rungs, shorted branches, labels.

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
    jumps_seen: bool = False  # an LBL or JMP was met by `sequence` in the current routine

    def err(self, code: str, msg: str, span: n.Span) -> None: ...  # provided by Checker

    def ladder_instr(self, i: n.LadderInstr) -> None: ...  # provided by Checker

    def rungs(self, rungs: list[n.Rung]) -> None:
        self.jumps_seen = False
        for rung in rungs:
            if not rung.elements:
                self.err(
                    "E129",
                    f"rung {rung.number} is empty: give it at least one instruction (NOP)",
                    rung.span,
                )
            self.sequence(rung.elements, feeds=False)
        if self.jumps_seen:  # most routines have no label: spare them a second walk
            self.labels(rungs)

    def labels(self, rungs: list[n.Rung]) -> None:
        """E131: every JMP names an LBL of the same routine; an LBL is unique and first on its rung
        (the compiler cuts the routine into segments at those rungs, decision 0021)."""
        defined: dict[str, int] = {}
        jumps: list[tuple[str, n.Expr]] = []
        for rung in rungs:
            for k, ins in enumerate(rung_instructions(rung.elements)):
                name = ins.name.upper()
                if name not in ("LBL", "JMP") or len(ins.operands) != 1:
                    continue
                e = ins.operands[0]
                if not isinstance(e, n.Name):
                    self.err("E131", f"{name} needs a label name", e.span)
                    continue
                if name == "JMP":
                    jumps.append((e.ident, e))
                elif e.ident.upper() in defined:
                    self.err(
                        "E131",
                        f"label '{e.ident}' is already defined on rung {defined[e.ident.upper()]}",
                        e.span,
                    )
                else:
                    if k != 0 or not isinstance(rung.elements[0], n.LadderInstr):
                        self.err(
                            "E131",
                            f"LBL({e.ident}) must be the first instruction of its rung",
                            ins.span,
                        )
                    defined[e.ident.upper()] = rung.number  # known either way: one error, not two
        for label, e in jumps:
            if label.upper() not in defined:
                known = sorted(defined)
                hint = f" (labels here: {', '.join(known)})" if known else ""
                self.err("E131", f"no LBL({label}) in this routine{hint}", e.span)

    def sequence(self, elements: list[n.LadderElement], feeds: bool) -> bool:
        """Check elements in series (`feeds`: the rung goes on after the last of them).
        True when a shorted branch was reported among them."""
        shorted = False
        for k, e in enumerate(elements):
            if isinstance(e, n.LadderInstr):
                self.ladder_instr(e)
                if e.name.upper() in ("LBL", "JMP"):  # the instructions `labels` checks
                    self.jumps_seen = True
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
            self.a.diags.append(
                diag(
                    "W202",
                    f"leg {bare[0] + 1} of this branch has no input instruction: it is always true and "
                    "shorts the conditions of the other legs",
                    self.path,
                    b.span,
                )
            )
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


def rung_instructions(elements: list[n.LadderElement]):  # type: ignore[no-untyped-def]
    """The rung's instructions in scan order, branch legs included."""
    for e in elements:
        if isinstance(e, n.Branch):
            for leg in e.legs:
                yield from rung_instructions(leg)
        else:
            yield e
