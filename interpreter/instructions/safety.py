"""GuardLogix dual-channel safety input instructions: DCS, DCM, DCSRT (decision 0075).

SPEC 9.32: safety instructions are not U diagnostics; they run as on a controller whose
safety I/O is not connected, so channels and input status read 0 unless the program (or
`--set`) drives them. The state machine follows the documented behaviour of the Dual
Channel Input Stop where we could check it, and decision 0075 where we could not; times
are virtual milliseconds (`ctx.now_ms`):

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

DCM (monitor) shares the channel, discrepancy, status and fault handling; its O1 simply
follows "both channels active" with no reset. DCSRT (start) shares them too; its O1 comes on
when both channels turn active while Enable is on, after having been inactive together
since the previous start, and goes off with either channel or Enable.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..vm.context import ExecContext
from .fbd_timers import _layout
from .registry import implements, prescan
from .safety_common import enum_value, mirror


@dataclass(frozen=True, slots=True)
class _Members:
    """Indices of the members the dual-channel instructions share, in one instance type."""

    o1: int
    ip: int
    rr: int
    ii: int
    ci: int
    fp: int
    reset_prev: int
    disc_start: int

    @classmethod
    def of(cls, type_name: str) -> _Members:
        d = _layout(type_name)
        names = ("O1", "IP", "RR", "II", "CI", "FP", "RESETPREV", "DISCSTART")
        return cls(*(d[n] for n in names))


STOP_L, MONITOR_L, START_L = _layout("DCI_STOP"), _layout("DCI_MONITOR"), _layout("DCI_START")
DCS_M = _Members.of("DCI_STOP")
DCM_M = _Members.of("DCI_MONITOR")
DCSRT_M = _Members.of("DCI_START")
COLD = _layout("DCI_STOP")["COLDSTART"]
ARMED = _layout("DCI_START")["ARMED"]


COMPLEMENTARY = enum_value("SAFETY_InputType", "Complementary")
AUTOMATIC = enum_value("SAFETY_ResetType", "Automatic")


def _channels(input_type: int, a: object, b: object) -> tuple[bool, bool]:
    """(channel A active, channel B active) for the configured input type."""
    if int(input_type) == COMPLEMENTARY:
        return bool(a), not b
    return bool(a), bool(b)


def _discrepancy(
    ctx: ExecContext, s: list, m: _Members, a_on: bool, b_on: bool, limit_ms: int
) -> bool:
    """Time a disagreement of the channels; True when it has lasted the discrepancy time."""
    if a_on == b_on:
        s[m.ip] = 0
        return False
    if not s[m.ip]:
        s[m.ip] = 1
        s[m.disc_start] = ctx.now_ms
        return False
    return bool(ctx.now_ms - s[m.disc_start] >= int(limit_ms))


def _front_end(
    ctx: ExecContext,
    rung: bool,
    s: list,
    m: _Members,
    input_type: int,
    discrepancy_ms: int,
    channel_a: object,
    channel_b: object,
    input_status: object,
    reset: object,
) -> tuple[bool, bool, bool] | None:
    """Shared part: reset transition, channels, discrepancy, status and fault handling.

    Returns None when O1 must stay off this scan (false rung or fault still present), else
    (both channels active, both inactive, reset transition this scan).
    """
    reset_edge = bool(reset) and not s[m.reset_prev]
    s[m.reset_prev] = int(bool(reset))
    if not rung:
        s[m.o1] = s[m.ip] = s[m.rr] = 0
        return None
    a_on, b_on = _channels(input_type, channel_a, channel_b)
    both, none = a_on and b_on, not a_on and not b_on
    s[m.ii] = int(none)
    if not s[m.fp] and _discrepancy(ctx, s, m, a_on, b_on, discrepancy_ms):
        s[m.fp] = s[m.ci] = 1
    if not input_status and not s[m.fp]:
        s[m.fp] = 1
    if s[m.fp]:
        s[m.o1] = s[m.rr] = s[m.ip] = 0
        if none:
            s[m.ci] = 0  # the channels were cycled to their inactive state
        if not (reset_edge and input_status and not s[m.ci]):
            return None
        s[m.fp] = 0  # the same reset may also restart O1
    return both, none, reset_edge


def _clear(s: list, m: _Members, reset: object) -> None:
    """Prescan (go to Run): outputs off; a Reset already held on is not a transition."""
    s[m.o1] = s[m.ip] = s[m.rr] = s[m.ci] = s[m.fp] = 0
    s[m.reset_prev] = int(bool(reset))


# ------------------------------------------------------------------ DCS
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
    m = DCS_M
    mirror(
        s,
        STOP_L,
        rung,
        DiscrepancyTime=int(discrepancy_ms),
        ChannelA=channel_a,
        ChannelB=channel_b,
        InputStatus=input_status,
        Reset=reset,
    )
    got = _front_end(
        ctx, rung, s, m, input_type, discrepancy_ms, channel_a, channel_b, input_status, reset
    )
    if got is None:
        return
    both, _, reset_edge = got
    if not both:
        s[m.o1] = s[m.rr] = 0
        s[COLD] = 0  # a stop demand: from now on the restart type applies
        return
    if s[m.o1]:
        return
    automatic = (cold_start_type if s[COLD] else restart_type) == AUTOMATIC
    if automatic or reset_edge:
        s[m.o1], s[m.rr], s[COLD] = 1, 0, 0
    else:
        s[m.rr] = 1


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
    _clear(s, DCS_M, reset)
    s[COLD] = 1  # the cold start type governs the first start


# ------------------------------------------------------------------ DCM
@implements("DCM")
def dcm(
    ctx: ExecContext,
    rung: bool,
    s: list,
    safety_function: int,
    input_type: int,
    discrepancy_ms: int,
    channel_a: object,
    channel_b: object,
    input_status: object,
    reset: object,
) -> None:
    mirror(
        s,
        MONITOR_L,
        rung,
        DiscrepancyTime=int(discrepancy_ms),
        ChannelA=channel_a,
        ChannelB=channel_b,
        InputStatus=input_status,
        Reset=reset,
    )
    got = _front_end(
        ctx, rung, s, DCM_M, input_type, discrepancy_ms, channel_a, channel_b, input_status, reset
    )
    if got is not None:
        s[DCM_M.o1] = int(got[0])


@prescan("DCM")
def dcm_prescan(
    ctx: ExecContext,
    rung: bool,
    s: list,
    safety_function: int,
    input_type: int,
    discrepancy_ms: int,
    channel_a: object,
    channel_b: object,
    input_status: object,
    reset: object,
) -> None:
    _clear(s, DCM_M, reset)


# ------------------------------------------------------------------ DCSRT
@implements("DCSRT")
def dcsrt(
    ctx: ExecContext,
    rung: bool,
    s: list,
    safety_function: int,
    input_type: int,
    discrepancy_ms: int,
    enable: object,
    channel_a: object,
    channel_b: object,
    input_status: object,
    reset: object,
) -> None:
    m = DCSRT_M
    mirror(s, START_L, rung, DiscrepancyTime=int(discrepancy_ms), Enable=enable)
    mirror(
        s,
        START_L,
        rung,
        ChannelA=channel_a,
        ChannelB=channel_b,
        InputStatus=input_status,
        Reset=reset,
    )
    got = _front_end(
        ctx, rung, s, m, input_type, discrepancy_ms, channel_a, channel_b, input_status, reset
    )
    if got is None:
        return
    both, none, _ = got
    if none:
        s[ARMED] = 1
    if not both or not enable:
        s[m.o1] = 0
        if both:
            s[ARMED] = 0  # turned active while not enabled: that start is used up
        return
    if s[ARMED]:
        s[m.o1], s[ARMED] = 1, 0


@prescan("DCSRT")
def dcsrt_prescan(
    ctx: ExecContext,
    rung: bool,
    s: list,
    safety_function: int,
    input_type: int,
    discrepancy_ms: int,
    enable: object,
    channel_a: object,
    channel_b: object,
    input_status: object,
    reset: object,
) -> None:
    _clear(s, DCSRT_M, reset)
    s[ARMED] = 0  # channels already active at the go to Run are not a start
