"""GuardLogix configurable redundant output: CROUT (decision 0076).

SPEC 9.32: with nothing connected the feedbacks and statuses read 0. Times are virtual ms.

- Actuate on energizes O1 and O2 when no fault is present; Actuate off de-energizes them.
- Feedback 1 and Feedback 2 are watched all the time: each must show the state of its output
  (Positive: feedback equals the output; Negative: feedback is its complement). A
  disagreement may last the Feedback Reaction Time; when it has lasted that long the
  instruction faults: O1 and O2 off, FP on.
- InputStatus or OutputStatus off is a fault at once (the I/O behind the feedbacks or the
  outputs is not healthy; nothing connected shows this).
- A fault is cleared by an off-to-on transition of Reset once it is corrected: both
  statuses on and both feedbacks showing the de-energized state. Actuate then acts on the
  same execution.
- A false rung de-energizes both outputs; feedback disagreement timing goes on being judged
  against the (now off) outputs on the next true execution.
"""

from __future__ import annotations

from ..vm.context import ExecContext
from .fbd_timers import _layout
from .registry import implements, prescan
from .safety_common import enum_value, mirror, reset_edge

_C = _layout("CONFIGURABLE_ROUT")
O1, O2, FP = _C["O1"], _C["O2"], _C["FP"]
WAITING, WAIT_START, RESET_PREV = _C["WAITING"], _C["WAITSTART"], _C["RESETPREV"]
NEGATIVE = enum_value("SAFETY_FeedbackType", "Negative")
NO_FEEDBACK = enum_value("SAFETY_FeedbackType", "None")


def _shows(feedback_type: int, output: int, feedback: object) -> bool:
    """Does a feedback show the state of its output for this feedback type?"""
    if feedback_type == NO_FEEDBACK:
        return True
    if feedback_type == NEGATIVE:
        return bool(feedback) != bool(output)
    return bool(feedback) == bool(output)


@implements("CROUT")
def crout(
    ctx: ExecContext,
    rung: bool,
    s: list,
    feedback_type: int,
    reaction_ms: int,
    actuate: object,
    feedback1: object,
    feedback2: object,
    input_status: object,
    output_status: object,
    reset: object,
) -> None:
    mirror(s, _C, rung, FeedbackReactionTime=int(reaction_ms), Actuate=actuate, Feedback1=feedback1)
    mirror(s, _C, rung, Feedback2=feedback2, InputStatus=input_status)
    mirror(s, _C, rung, OutputStatus=output_status, Reset=reset)
    edge = reset_edge(s, RESET_PREV, reset)
    ftype = int(feedback_type)
    s[_C["FEEDBACKTYPE"]] = int(ftype != NEGATIVE)  # the tag shows Positive as 1, Negative as 0
    if not rung:
        s[O1] = s[O2] = 0
        return
    agree = _shows(ftype, s[O1], feedback1) and _shows(ftype, s[O2], feedback2)
    if agree:
        s[WAITING] = 0
    elif not s[WAITING]:
        s[WAITING], s[WAIT_START] = 1, ctx.now_ms
    elif ctx.now_ms - s[WAIT_START] >= int(reaction_ms):
        s[FP] = 1
    if not input_status or not output_status:
        s[FP] = 1
    if s[FP]:
        s[O1] = s[O2] = 0
        off_shown = _shows(ftype, 0, feedback1) and _shows(ftype, 0, feedback2)
        if not (edge and input_status and output_status and off_shown):
            return
        s[FP] = s[WAITING] = 0
    s[O1] = s[O2] = int(bool(actuate))
    if not (_shows(ftype, s[O1], feedback1) and _shows(ftype, s[O2], feedback2)):
        if not s[WAITING]:
            s[WAITING], s[WAIT_START] = 1, ctx.now_ms  # the outputs just changed: feedback due
    else:
        s[WAITING] = 0


@prescan("CROUT")
def crout_prescan(ctx: ExecContext, rung: bool, s: list, *ops: object) -> None:
    s[O1] = s[O2] = s[FP] = s[WAITING] = 0
    s[RESET_PREV] = int(bool(ops[-1]))
