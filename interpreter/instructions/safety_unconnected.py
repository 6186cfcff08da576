"""Safety instructions shown as on a controller whose safety I/O is not connected (0078).

SPEC 9.32: safety instructions are not U diagnostics; they run as on a controller with
nothing connected. In a GuardLogix, a safety input connection that is missing makes the
controller put the connection's data in the safe state (0) and its status bits at fault
(0); the output connections are not there to energize anything. logixst has no safety I/O,
so every connection is missing. Six instructions are simulated in full (safety.py,
safety_modes.py, safety_outputs.py). For the rest, whose full state machines (test, lock,
muting and press sequences) are not simulated, this one engine shows that missing-I/O
picture, whatever values the program passes, from each instruction's catalog entry
`unconnected`:

- every execution copies the rung condition into EnableIn/EnableOut and the plain operands
  (BOOL and number values; enumerated options are not copied, decision 0076) into the members
  of the same names, and holds the members listed in `off` (the outputs) at 0;
- a true-rung execution sets the members listed in `on` (the fault bit FP for an
  instruction that watches an input or output status; II, inputs inactive, for the
  dual-channel inputs whose channels then read 0) and those of each `cases` entry whose
  enumerated operand has the given value (ROUT with Negative feedback);
- a false rung leaves the `on` members as they are (a fault is kept, as for DCS);
- prescan (go to Run) clears the `off`, `on` and case members; the first true execution
  sets them again.

A reset input changes nothing: the cause (the missing I/O) is still there. FaultCode and
DiagnosticCode are left as they are (0 unless the program writes them, decision 0076).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from functools import partial

from stdlib import Instruction, catalog

from ..vm.context import ExecContext
from .fbd_timers import _layout
from .registry import implements, prescan

# operand formats whose value the backing tag mirrors (tags, arrays and routines are not)
_PLAIN = frozenset({"value", "immediate"})


@dataclass(frozen=True, slots=True)
class _Plan:
    """Member indices one instruction writes, worked out once from the catalog."""

    enable: tuple[int, int]
    mirrors: tuple[tuple[int, int, bool], ...]  # (operand position, member index, BOOL member)
    off: tuple[int, ...]
    on: tuple[int, ...]
    cases: tuple[tuple[int, int, tuple[int, ...]], ...]  # (operand position, value, members)

    @classmethod
    def of(cls, ins: Instruction) -> _Plan:
        u = ins.unconnected
        assert u is not None
        type_name = ins.operands[0].types[0]
        lay = _layout(type_name)
        kinds = {m.name.upper(): m.type for m in catalog().types[type_name].members}
        mirrors = []
        # operand positions count from the first operand after the instance tag
        for pos, op in enumerate(ins.operands[1:]):
            key = op.name.upper()
            if op.format in _PLAIN and op.enum is None and key in lay:
                mirrors.append((pos, lay[key], kinds[key] == "BOOL"))
        positions = {op.name: pos for pos, op in enumerate(ins.operands[1:])}
        cases = []
        for c in u.cases:
            op = ins.operands[1 + positions[c.operand]]
            assert op.enum is not None
            value = catalog().enum(op.enum).lookup(c.value)
            assert value is not None, (ins.name, c.value)
            members = tuple(lay[n.upper()] for n in c.on)
            cases.append((positions[c.operand], value.value, members))
        return cls(
            enable=(lay["ENABLEIN"], lay["ENABLEOUT"]),
            mirrors=tuple(mirrors),
            off=tuple(lay[n.upper()] for n in u.off),
            on=tuple(lay[n.upper()] for n in u.on),
            cases=tuple(cases),
        )


def _execute(plan: _Plan, ctx: ExecContext, rung: bool, s: list, *ops: object) -> None:
    s[plan.enable[0]] = s[plan.enable[1]] = int(rung)
    for pos, idx, is_bool in plan.mirrors:
        v = ops[pos]
        s[idx] = int(bool(v)) if is_bool else int(v)  # type: ignore[call-overload]
    for idx in plan.off:
        s[idx] = 0
    if not rung:
        return  # outputs off; a fault or status bit already shown is kept
    for idx in plan.on:
        s[idx] = 1
    for pos, value, members in plan.cases:
        if int(ops[pos]) == value:  # type: ignore[call-overload]
            for idx in members:
                s[idx] = 1


def _prescan(plan: _Plan, ctx: ExecContext, rung: bool, s: list, *ops: object) -> None:
    for idx in (*plan.off, *plan.on, *(i for _, _, m in plan.cases for i in m)):
        s[idx] = 0


def _register(instructions: Sequence[Instruction]) -> None:
    for ins in instructions:
        if ins.unconnected is None:
            continue
        plan = _Plan.of(ins)
        implements(ins.name)(partial(_execute, plan))
        prescan(ins.name)(partial(_prescan, plan))


_register(catalog().instructions)
