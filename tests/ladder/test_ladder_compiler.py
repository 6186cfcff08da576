"""Ladder lowering on hand-built rungs (before the .rll parser lands): rung logic, outputs, prescan."""

from __future__ import annotations

from typing import Any

from interpreter.runtime.controller import Controller
from interpreter.runtime.loader import Loaded
from interpreter.semantics.checker import Checker
from interpreter.semantics.program import build_program
from interpreter.syntax import nodes as n
from interpreter.syntax.st_parser import parse_expression, parse_st


def _operand(text: str) -> n.Expr:
    text = text.strip()
    if text in ("", "?"):
        return n.Placeholder(n.NOWHERE)
    return parse_expression(text)


def _elements(s: str, i: int, stop: str) -> tuple[list[n.LadderElement], int]:
    out: list[n.LadderElement] = []
    while i < len(s) and s[i] not in stop:
        if s[i].isspace():
            i += 1
        elif s[i] == "[":
            legs: list[list[n.LadderElement]] = []
            i += 1
            while True:
                leg, i = _elements(s, i, ",]")
                legs.append(leg)
                if s[i] == "]":
                    i += 1
                    break
                i += 1
            out.append(n.Branch(legs, n.NOWHERE))
        else:
            j = s.index("(", i)
            name = s[i:j].strip()
            depth, k, args, start = 0, j + 1, [], j + 1
            while True:
                ch = s[k]
                if ch in "([":
                    depth += 1
                elif ch in ")]" and depth:
                    depth -= 1
                elif ch == "," and not depth:
                    args.append(s[start:k])
                    start = k + 1
                elif ch == ")":
                    args.append(s[start:k])
                    break
                k += 1
            ops = [] if args == [""] else [_operand(a) for a in args]
            out.append(n.LadderInstr(name, ops, n.NOWHERE, n.NOWHERE))
            i = k + 1
    return out, i


def routine(name: str, decls: str, rungs: list[str]) -> n.Routine:
    header, _ = parse_st(decls, f"{name}.rll") if decls else (n.Routine(name, "st", f"{name}.rll"), [])
    r = n.Routine(name, "rll", f"{name}.rll", decls=header.decls, types=header.types)
    for k, text in enumerate(rungs):
        els, _ = _elements(text.rstrip(";"), 0, "")
        r.rungs.append(n.Rung(els, n.NOWHERE, k))
    return r


def load_ladder(*routines: n.Routine) -> Loaded:
    """What the rllparse checker will do: type operands, resolve enums, map instructions."""
    model, diags = build_program(routines[0].name, list(routines))
    assert not diags, diags
    ch = Checker(model)
    a = ch.run()
    for r in routines:
        if r.language != "rll":
            continue
        ch.language, ch.path = "rll", r.path
        stack: list[Any] = [el for rung in r.rungs for el in rung.elements]
        while stack:
            el = stack.pop()
            if isinstance(el, n.Branch):
                stack.extend(x for leg in el.legs for x in leg)
                continue
            ins = ch.cat.instruction(el.name, "rll")
            assert ins is not None, el.name
            a.call_of[id(el)] = ins
            for i, e in enumerate(el.operands):
                op = ins.operands[min(i, len(ins.operands) - 1)]
                if ins.name in ("JMP", "LBL"):
                    continue
                if op.enum is not None and ch.enum_operand(ins, op, e):
                    continue
                if op.format == "routine" or isinstance(e, n.Placeholder):
                    continue
                ch.expr(e)
    assert not a.diags, a.diags
    return Loaded(model, a, [])


def run(decls: str, rungs: list[str], scans: int = 1, sets: dict[str, Any] | None = None,
        per_scan: list[dict[str, Any]] | None = None) -> Controller:
    ctl = Controller(load_ladder(routine("main", decls, rungs)))
    for k, v in (sets or {}).items():
        ctl.reference(k)[2](v)
    assert ctl.prescan()
    for s in range(scans):
        for k, v in (per_scan[s] if per_scan and s < len(per_scan) else {}).items():
            ctl.reference(k)[2](v)
        assert ctl.scan(), ctl.major_fault
    return ctl


def get(ctl: Controller, ref: str) -> Any:
    return ctl.reference(ref)[0]()


DECL = "VAR a, b, c, d, e, q, q2 : BOOL; END_VAR\n"


def test_series_and_parallel_contacts() -> None:
    # q = a AND (b OR NOT c); q2 = NOT a
    for a in (0, 1):
        for b in (0, 1):
            for c in (0, 1):
                ctl = run(DECL, ["XIC(a)[XIC(b),XIO(c)]OTE(q);", "XIO(a)OTE(q2);"], sets={"a": a, "b": b, "c": c})
                assert get(ctl, "q") == (1 if a and (b or not c) else 0)
                assert get(ctl, "q2") == (0 if a else 1)


def test_output_on_a_leg_sees_the_incoming_condition() -> None:
    # [OTE(q), XIC(b) OTE(q2)] after XIC(a): q = a, q2 = a AND b; the rung continues with
    # a AND (TRUE OR b) = a, so OTE(d) = a.
    for a in (0, 1):
        for b in (0, 1):
            ctl = run(DECL, ["XIC(a)[OTE(q),XIC(b)OTE(q2)]OTE(d);"], sets={"a": a, "b": b})
            assert (get(ctl, "q"), get(ctl, "q2"), get(ctl, "d")) == (a, a & b, a)
