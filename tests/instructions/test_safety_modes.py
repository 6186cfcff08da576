"""FPMS and EPMS mode selectors, scan by scan through `logixst run --trace` (decision 0076).

Expectations follow the documented behaviour: one output per active input; no input for
longer than 250 ms is a fault (documented for EPMS, FPMS uses the same figure); two or more
inputs at once is a fault at once; a fault clears on an off-to-on transition of the reset
input once exactly one position is selected. EPMS: Lock forbids changing the outputs (a
change attempt de-energizes them, no fault); InputStatus off is a fault. Scan k runs at
virtual time (k - 1) * period; n counts the scans (n = k on scan k).
"""

from __future__ import annotations

from pathlib import Path

from tests.instructions.run_cli import trace

EHEAD = (
    "VAR e : EIGHT_POS_MODE_SELECTOR; i1, i2, i3, i4, i5, i6, i7, i8, st, lk, r : BOOL;"
    " n : DINT; END_VAR\nADD(n,1,n);\n"
)
EBITS = ["e.O1", "e.O2", "e.O3", "e.FP"]


def _epms(tmp_path: Path, drive: str, scans: int, period: float) -> list:
    src = EHEAD + drive + "EPMS(e,i1,i2,i3,i4,i5,i6,i7,i8,st,lk,r);\n"
    rows, report = trace(tmp_path, src, ".rll", scans, EBITS, period_ms=period)
    assert report["diagnostics"] == [] and report["faults"] == []
    return [tuple(int(row[k]) for k in EBITS) for row in rows]


#        O1 O2 O3 FP
NONE = (0, 0, 0, 0)
FAULT = (0, 0, 0, 1)


def test_epms_nothing_connected_is_a_fault(tmp_path: Path) -> None:
    # every input 0 and InputStatus 0: the status fault shows on the first scan
    assert _epms(tmp_path, "", 2, 10.0) == [FAULT, FAULT]


def test_epms_no_mode_longer_than_250_ms_faults(tmp_path: Path) -> None:
    # period 50 ms. i1 at n 1, i3 at n 3, nothing from n 4 (t 150) to n 10, i2 from n 11,
    # Reset at n 12. No mode since t 150: n 9 (t 400) is 250 ms, not more, n 10 (t 450) is 300.
    drive = "OTL(st);\nEQU(n,1)OTE(i1);\nEQU(n,3)OTE(i3);\nGEQ(n,11)OTE(i2);\nEQU(n,12)OTE(r);\n"
    rows = _epms(tmp_path, drive, 12, 50.0)
    assert rows == [
        (1, 0, 0, 0),  # n 1: mode 1
        NONE,  # n 2 t 50: between positions, 0 ms
        (0, 0, 1, 0),  # n 3: mode 3
        *[NONE] * 6,  # n 4-9 t 150-400: 0 ... 250 ms without a mode
        FAULT,  # n 10 t 450: 300 ms > 250 ms
        FAULT,  # n 11: a mode again but no reset yet
        (0, 1, 0, 0),  # n 12: Reset 0 -> 1 with one mode: cleared, O2 on this scan
    ]


def test_epms_two_inputs_fault_at_once(tmp_path: Path) -> None:
    # i1 n 1-2, i2 from n 2: both on at n 2 (fault at once); i2 alone from n 3 but no reset
    # until n 4, which clears the fault and selects mode 2 on the same scan.
    drive = "OTL(st);\nLES(n,3)OTE(i1);\nGEQ(n,2)OTE(i2);\nEQU(n,4)OTE(r);\n"
    rows = _epms(tmp_path, drive, 4, 10.0)
    assert rows == [(1, 0, 0, 0), FAULT, FAULT, (0, 1, 0, 0)]


def test_epms_lock_holds_and_a_change_while_locked_de_energizes(tmp_path: Path) -> None:
    # i1 n 1-2, i2 n 3, i1 n 4-5; Lock n 2-4.
    drive = "OTL(st);\nLES(n,3)OTE(i1);\nGEQ(n,4)OTL(i1);\nEQU(n,3)OTE(i2);\nLIM(2,n,4)OTE(lk);\n"
    rows = _epms(tmp_path, drive, 5, 10.0)
    assert rows == [
        (1, 0, 0, 0),  # n 1: mode 1
        (1, 0, 0, 0),  # n 2: locked, unchanged: held
        NONE,  # n 3: mode 2 asked while locked: no mode, no fault
        NONE,  # n 4: still locked: back to 1 is a change too
        (1, 0, 0, 0),  # n 5: unlocked: follows the selector
    ]


def test_epms_input_status_loss(tmp_path: Path) -> None:
    drive = "OTL(i1);\nNEQ(n,2)OTE(st);\nEQU(n,4)OTE(r);\n"
    rows = _epms(tmp_path, drive, 4, 10.0)
    assert rows == [(1, 0, 0, 0), FAULT, FAULT, (1, 0, 0, 0)]


def test_epms_false_rung_de_energizes(tmp_path: Path) -> None:
    src = EHEAD + "OTL(st);\nOTL(i3);\nNEQ(n,2)EPMS(e,i1,i2,i3,i4,i5,i6,i7,i8,st,lk,r);\n"
    rows, _ = trace(tmp_path, src, ".rll", 3, ["e.O3", "e.EnableIn"], period_ms=10.0)
    assert [(int(r["e.O3"]), int(r["e.EnableIn"])) for r in rows] == [(1, 1), (0, 0), (1, 1)]


FHEAD = "VAR f : FIVE_POS_MODE_SELECTOR; i1, i2, i3, i4, i5, r : BOOL; n : DINT; END_VAR\n"
FBITS = ["f.O1", "f.O2", "f.NM", "f.MMS", "f.FP"]


def _fpms(tmp_path: Path, drive: str, scans: int, period: float) -> list:
    src = FHEAD + "ADD(n,1,n);\n" + drive + "FPMS(f,i1,i2,i3,i4,i5,r);\n"
    rows, report = trace(tmp_path, src, ".rll", scans, FBITS, period_ms=period)
    assert report["diagnostics"] == [] and report["faults"] == []
    return [tuple(int(row[k]) for k in FBITS) for row in rows]


def test_fpms_nothing_connected_faults_no_mode_after_250_ms(tmp_path: Path) -> None:
    # period 100 ms, no input: 0, 100, 200 ms without a mode, then 300 > 250: NM and FP
    #                                O1 O2 NM MMS FP
    assert _fpms(tmp_path, "", 4, 100.0) == [(0, 0, 0, 0, 0)] * 3 + [(0, 0, 1, 0, 1)]


def test_fpms_multiple_modes_and_fault_reset(tmp_path: Path) -> None:
    # i1 n 1-2, i2 at n 2 and from n 4 (so both at n 2, none at n 3); FaultReset at n 5
    drive = "LES(n,3)OTE(i1);\nEQU(n,2)OTE(i2);\nGEQ(n,4)OTL(i2);\nEQU(n,5)OTE(r);\n"
    assert _fpms(tmp_path, drive, 5, 10.0) == [
        (1, 0, 0, 0, 0),  # n 1: mode 1
        (0, 0, 0, 1, 1),  # n 2: i1 and i2: MMS at once
        (0, 0, 0, 1, 1),  # n 3: no input (10 ms), fault kept
        (0, 0, 0, 1, 1),  # n 4: i2 alone, no reset yet
        (0, 1, 0, 0, 0),  # n 5: FaultReset 0 -> 1 with one mode: cleared, O2 on
    ]


def test_fpms_reset_is_refused_while_not_corrected(tmp_path: Path) -> None:
    # no input for 300 ms (period 100): NM at n 4; reset at n 5 with still no input: kept;
    # i5 from n 6, reset again at n 7: cleared.
    drive = "GEQ(n,6)OTE(i5);\nEQU(n,5)OTE(r);\nEQU(n,7)OTL(r);\n"
    rows = _fpms(tmp_path, drive, 7, 100.0)
    assert [r[2:] for r in rows] == [(0, 0, 0)] * 3 + [(1, 0, 1)] * 3 + [(0, 0, 0)]
