"""GuardLogix mode selector safety instructions: FPMS and EPMS (decision 0076).

SPEC 9.32: safety instructions run as on a controller with nothing connected; their inputs
read 0 unless the program (or `--set`) drives them. Both instructions interface a mode
selector switch whose positions are wired to one input each. Times are virtual ms.

- Exactly one input on: its output is on, the others off.
- No input on: every output off ("no mode"). The switch passes through that state between
  positions (break before make), so it is a fault only once it has lasted longer than the
  no-mode time, 250 ms (documented for EPMS; FPMS uses the same figure, decision 0076).
- More than one input on: every output off and a fault at once.
- A fault holds every output off and sets FP (FPMS also NM or MMS for its cause) until the
  selector shows exactly one position again and the reset input makes an off-to-on
  transition; the same execution then energizes the selected output.
- EPMS only: Lock on forbids changing the outputs. A different selection while locked
  de-energizes every output (no mode) without a fault; they follow the selector again once
  Lock is off. InputStatus off is a fault like the ones above.
- A false rung turns every output off and stops the no-mode timing; faults are kept.
"""

from __future__ import annotations

from ..vm.context import ExecContext
from .fbd_timers import _layout
from .registry import implements, prescan
from .safety_common import NO_MODE_MS, mirror, reset_edge

_F = _layout("FIVE_POS_MODE_SELECTOR")
_E = _layout("EIGHT_POS_MODE_SELECTOR")
F_OUT = [_F[f"O{i}"] for i in range(1, 6)]
E_OUT = [_E[f"O{i}"] for i in range(1, 9)]


def _no_mode_expired(ctx: ExecContext, s: list, lay: dict[str, int], none: bool) -> bool:
    """Time a selector with no input on; True once that has lasted longer than NO_MODE_MS."""
    if not none:
        s[lay["NONETIMING"]] = 0
        return False
    if not s[lay["NONETIMING"]]:
        s[lay["NONETIMING"]] = 1
        s[lay["NONESTART"]] = ctx.now_ms
        return False
    return bool(ctx.now_ms - s[lay["NONESTART"]] > NO_MODE_MS)


def _set_outputs(s: list, outs: list[int], selected: int | None) -> None:
    for i, idx in enumerate(outs):
        s[idx] = int(selected == i)


# ------------------------------------------------------------------ FPMS
@implements("FPMS")
def fpms(ctx: ExecContext, rung: bool, s: list, *ops: object) -> None:
    inputs, fault_reset = [bool(x) for x in ops[:5]], ops[5]
    mirror(s, _F, rung, Input1=ops[0], Input2=ops[1], Input3=ops[2], Input4=ops[3])
    mirror(s, _F, rung, Input5=ops[4], FaultReset=fault_reset)
    edge = reset_edge(s, _F["RESETPREV"], fault_reset)
    if not rung:
        _set_outputs(s, F_OUT, None)
        s[_F["NONETIMING"]] = 0
        return
    on = [i for i, x in enumerate(inputs) if x]
    if len(on) > 1:
        s[_F["MMS"]] = s[_F["FP"]] = 1
    elif _no_mode_expired(ctx, s, _F, not on):
        s[_F["NM"]] = s[_F["FP"]] = 1
    if s[_F["FP"]]:
        if not (edge and len(on) == 1):
            _set_outputs(s, F_OUT, None)
            return
        s[_F["FP"]] = s[_F["NM"]] = s[_F["MMS"]] = 0  # corrected and reset: run this scan
    _set_outputs(s, F_OUT, on[0] if len(on) == 1 else None)


@prescan("FPMS")
def fpms_prescan(ctx: ExecContext, rung: bool, s: list, *ops: object) -> None:
    _set_outputs(s, F_OUT, None)
    s[_F["NONETIMING"]] = 0
    s[_F["RESETPREV"]] = int(bool(ops[5]))


# ------------------------------------------------------------------ EPMS
@implements("EPMS")
def epms(ctx: ExecContext, rung: bool, s: list, *ops: object) -> None:
    inputs = [bool(x) for x in ops[:8]]
    input_status, lock, reset = ops[8], ops[9], ops[10]
    names = {f"Input{i + 1}": ops[i] for i in range(8)}
    mirror(s, _E, rung, InputStatus=input_status, Lock=lock, Reset=reset, **names)
    edge = reset_edge(s, _E["RESETPREV"], reset)
    if not rung:
        _set_outputs(s, E_OUT, None)
        s[_E["NONETIMING"]] = 0
        return
    on = [i for i, x in enumerate(inputs) if x]
    if len(on) > 1 or not input_status or _no_mode_expired(ctx, s, _E, not on):
        s[_E["FP"]] = 1
    if s[_E["FP"]]:
        if not (edge and len(on) == 1 and input_status):
            _set_outputs(s, E_OUT, None)
            return
        s[_E["FP"]] = 0
    selected = on[0] if len(on) == 1 else None
    current = next((i for i, idx in enumerate(E_OUT) if s[idx]), None)
    if lock and selected != current:
        selected = None  # a change while locked: de-energize, no fault
    elif lock:
        return  # locked and unchanged: hold
    _set_outputs(s, E_OUT, selected)


@prescan("EPMS")
def epms_prescan(ctx: ExecContext, rung: bool, s: list, *ops: object) -> None:
    _set_outputs(s, E_OUT, None)
    s[_E["NONETIMING"]] = 0
    s[_E["RESETPREV"]] = int(bool(ops[10]))
