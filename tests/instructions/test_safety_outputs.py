"""CROUT configurable redundant output, scan by scan through `logixst run --trace` (0076).

Documented behaviour: Actuate energizes O1 and O2 when no fault exists; each feedback must
show its output's state (Positive: equal, Negative: complement) within the Feedback Reaction
Time or the instruction faults (O1, O2 off, FP on); Reset (off-to-on) clears a corrected
fault. InputStatus/OutputStatus off is a fault (decision 0076). Scan k runs at virtual time
(k - 1) * 10 ms; n counts the scans. Feedbacks are wired from the outputs by rungs after the
instruction, so a feedback shows an output change one scan (10 ms) later, like a relay.
"""

from __future__ import annotations

from pathlib import Path

from tests.instructions.run_cli import trace

HEAD = "VAR c : CONFIGURABLE_ROUT; act, f1, f2, ist, ost, r : BOOL; n : DINT; END_VAR\n"
BITS = ["c.O1", "c.O2", "c.FP"]


def _crout(tmp_path: Path, ftype: str, drive: str, wiring: str, scans: int) -> list:
    src = HEAD + "ADD(n,1,n);\n" + drive + f"CROUT(c,{ftype},30,act,f1,f2,ist,ost,r);\n" + wiring
    rows, report = trace(tmp_path, src, ".rll", scans, BITS, period_ms=10.0)
    assert report["diagnostics"] == [] and report["faults"] == []
    return [tuple(int(row[k]) for k in BITS) for row in rows]


def test_crout_nothing_connected(tmp_path: Path) -> None:
    # statuses read 0: fault at once, outputs stay off even with Actuate on
    assert _crout(tmp_path, "Positive", "OTL(act);\n", "", 2) == [(0, 0, 1)] * 2


def test_crout_positive_feedback_follows(tmp_path: Path) -> None:
    # Actuate n 2-4; both feedbacks follow their outputs one scan later: never 30 ms apart
    drive = "OTL(ist);\nOTL(ost);\nLIM(2,n,4)OTE(act);\n"
    wiring = "XIC(c.O1)OTE(f1);\nXIC(c.O2)OTE(f2);\n"
    rows = _crout(tmp_path, "Positive", drive, wiring, 6)
    assert rows == [(0, 0, 0), (1, 1, 0), (1, 1, 0), (1, 1, 0), (0, 0, 0), (0, 0, 0)]


def test_crout_negative_feedback_follows(tmp_path: Path) -> None:
    # Negative: the feedback is the complement of its output (1 while the output is off)
    drive = "OTL(ist);\nOTL(ost);\nLIM(2,n,4)OTE(act);\n"
    wiring = "XIO(c.O1)OTE(f1);\nXIO(c.O2)OTE(f2);\n"
    rows = _crout(tmp_path, "Negative", drive, wiring, 6)
    assert rows == [(0, 0, 0), (1, 1, 0), (1, 1, 0), (1, 1, 0), (0, 0, 0), (0, 0, 0)]


def test_crout_stuck_feedback_faults_after_reaction_time(tmp_path: Path) -> None:
    # Feedback 2 never comes on. Outputs on at n 2 (t 10): the feedbacks are due from then.
    # t 20: 10 ms, t 30: 20 ms, t 40 (n 5): 30 ms = reaction time: fault, outputs off.
    # n 6: no reset; n 7: Reset 0 -> 1 with both feedbacks showing off: cleared, Actuate
    # (still on) energizes again at once and the wait starts again (t 60; n 8 is 10 ms).
    drive = "OTL(ist);\nOTL(ost);\nGEQ(n,2)OTE(act);\nEQU(n,7)OTE(r);\n"
    wiring = "XIC(c.O1)OTE(f1);\n"
    rows = _crout(tmp_path, "Positive", drive, wiring, 8)
    assert rows == [
        (0, 0, 0),
        (1, 1, 0),
        (1, 1, 0),
        (1, 1, 0),
        (0, 0, 1),
        (0, 0, 1),
        (1, 1, 0),
        (1, 1, 0),
    ]


def test_crout_output_status_loss_and_reset(tmp_path: Path) -> None:
    # outputs on from n 1; OutputStatus off at n 3 only; Reset at n 5. During the fault the
    # outputs are off and the feedbacks follow them off, so the reset is accepted.
    drive = "OTL(ist);\nNEQ(n,3)OTE(ost);\nOTL(act);\nEQU(n,5)OTE(r);\n"
    wiring = "XIC(c.O1)OTE(f1);\nXIC(c.O2)OTE(f2);\n"
    rows = _crout(tmp_path, "Positive", drive, wiring, 5)
    assert rows == [(1, 1, 0), (1, 1, 0), (0, 0, 1), (0, 0, 1), (1, 1, 0)]


def test_crout_welded_feedback_faults_and_refuses_reset(tmp_path: Path) -> None:
    # Feedback 1 stuck on (a welded contact) while the outputs are off: the disagreement
    # starts at t 0 and reaches the 30 ms reaction time at n 4 (t 30): fault. The reset at
    # n 6 is refused because feedback 1 still does not show the off state.
    drive = "OTL(ist);\nOTL(ost);\nOTL(f1);\nEQU(n,6)OTE(r);\n"
    rows = _crout(tmp_path, "Positive", drive, "", 6)
    assert rows == [(0, 0, 0)] * 3 + [(0, 0, 1)] * 3
