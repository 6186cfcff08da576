"""GuardLogix dual-channel safety input instructions: DCS (decision 0075).

SPEC 9.32: safety instructions are not U diagnostics; they run as on a controller whose
safety I/O is not connected, so channels and input status read 0 unless the program (or
`--set`) drives them. The state machine follows the documented behaviour of the Dual
Channel Input Stop, in virtual milliseconds (`ctx.now_ms`):

- A channel is active when it reads 1 (Equivalent - Active High) or, for a Complementary
  device, channel A reads 1 and channel B reads 0.
- O1 is on only while both channels are active, the input status is on and no fault is
  present. Either channel going inactive turns O1 off at once (a stop demand).
- When the channels disagree the discrepancy time starts (IP); if they still disagree
  when it has run out the instruction faults (FP) and needs both channels inactive (CI
  cleared) and then a reset (an off-to-on transition of Reset) to clear the fault.
- Input status off turns O1 off and sets FP; a reset once the status is back clears it.
- After a stop demand O1 comes back with both channels active either at once (Restart
  Type Automatic) or at the next reset (Manual, RR set while waiting). From the go to Run
  until the first stop demand or first O1, the Cold Start Type decides instead.
- A false rung turns O1 off and stops the discrepancy timing; the fault state is kept.
"""

from __future__ import annotations

from stdlib import catalog

from ..vm.context import ExecContext
from .fbd_timers import _layout
from .registry import implements, prescan

_D = _layout("DCI_STOP")
O1, IP, RR, II, CI, FP = (_D[m] for m in ("O1", "IP", "RR", "II", "CI", "FP"))
RESET_PREV, COLD, DISC_START = (_D[m] for m in ("RESETPREV", "COLDSTART", "DISCSTART"))


def _code(enum: str, text: str) -> int:
    v = catalog().enum(enum).lookup(text)
    assert v is not None, (enum, text)
    return v.value


COMPLEMENTARY = _code("SAFETY_InputType", "Complementary")
AUTOMATIC = _code("SAFETY_ResetType", "Automatic")


def _channels(input_type: int, a: object, b: object) -> tuple[bool, bool]:
    """(channel A active, channel B active) for the configured input type."""
    if int(input_type) == COMPLEMENTARY:
        return bool(a), not b
    return bool(a), bool(b)


def _discrepancy(ctx: ExecContext, s: list, a_on: bool, b_on: bool, limit_ms: int) -> bool:
    """Time a disagreement of the channels; True when it has lasted the discrepancy time."""
    if a_on == b_on:
        s[IP] = 0
        return False
    if not s[IP]:
        s[IP] = 1
        s[DISC_START] = ctx.now_ms
        return False
    return bool(ctx.now_ms - s[DISC_START] >= int(limit_ms))


@implements("DCS")
def dcs(
    ctx: ExecContext,
    rung: bool,
    s: list,
    safety_function: int,
    input_type: int,
    discrepancy_ms: int,
    restart_type: int,
    cold_start_type: int,
    channel_a: object,
    channel_b: object,
    input_status: object,
    reset: object,
) -> None:
    reset_edge = bool(reset) and not s[RESET_PREV]
    s[RESET_PREV] = int(bool(reset))
    if not rung:
        s[O1] = s[IP] = s[RR] = 0
        return
    a_on, b_on = _channels(input_type, channel_a, channel_b)
    both, none = a_on and b_on, not a_on and not b_on
    s[II] = int(none)
    if not s[FP] and _discrepancy(ctx, s, a_on, b_on, discrepancy_ms):
        s[FP] = s[CI] = 1
    if not input_status and not s[FP]:
        s[FP] = 1
    if s[FP]:
        s[O1] = s[RR] = s[IP] = 0
        if none:
            s[CI] = 0  # the channels were cycled to their stop state
        if reset_edge and input_status and not s[CI]:
            s[FP] = 0  # the same reset may also restart O1 below
        else:
            return
    if not both:
        s[O1] = s[RR] = 0
        s[COLD] = 0  # a stop demand: from now on the restart type applies
        return
    if s[O1]:
        return
    automatic = (cold_start_type if s[COLD] else restart_type) == AUTOMATIC
    if automatic or reset_edge:
        s[O1], s[RR], s[COLD] = 1, 0, 0
    else:
        s[RR] = 1


@prescan("DCS")
def dcs_prescan(
    ctx: ExecContext,
    rung: bool,
    s: list,
    safety_function: int,
    input_type: int,
    discrepancy_ms: int,
    restart_type: int,
    cold_start_type: int,
    channel_a: object,
    channel_b: object,
    input_status: object,
    reset: object,
) -> None:
    # Going to Run: outputs off, the cold start type governs the first start, and a Reset
    # already held on is not a transition.
    s[O1] = s[IP] = s[RR] = s[CI] = s[FP] = 0
    s[COLD] = 1
    s[RESET_PREV] = int(bool(reset))
