"""DCS, DCM and DCSRT dual-channel inputs, scan by scan through `logixst run --trace` (0075).

SPEC 9.32: a safety instruction is not a U diagnostic; with nothing connected its channels
and input status read 0. The programs below drive the inputs from a scan counter n (n = k
on scan k, at virtual time (k - 1) * period). Only O1 and FP are members of the Studio
backing tag (logixst keeps its discrepancy/reset state hidden), so the traces watch those.
Expected bits follow the documented DCS behaviour: O1 only with both channels active, input
status on and no fault; a channel disagreement lasting the discrepancy time faults (FP)
until both channels go inactive and Reset makes an off-to-on transition; manual cold start
/ restart wait for that transition, automatic ones do not. DCM's O1 follows the channels with no reset; DCSRT's
O1 needs both channels to turn active (after being inactive together) while Enable is on.
"""

from __future__ import annotations

import json
from pathlib import Path

from interpreter.cli import main
from tests.instructions.run_cli import trace

BITS = ["d.O1", "d.FP"]
HEAD = "VAR d : DCI_STOP; a, b, st, r : BOOL; n : DINT; END_VAR\nADD(n,1,n);\n"


def _dcs(tmp_path: Path, drive: str, args: str, scans: int, period: float = 10.0) -> list:
    src = HEAD + drive + f"DCS(d,E-Stop,{args},a,b,st,r);\n"
    rows, report = trace(tmp_path, src, ".rll", scans, BITS, period_ms=period)
    assert report["diagnostics"] == [] and report["faults"] == []
    return [tuple(int(row[k]) for k in BITS) for row in rows]


#            O1 FP
OFF_IDLE = (0, 0)  # both channels inactive, no fault
WAIT_RESET = (0, 0)  # both active, waiting for a reset
RUNNING = (1, 0)


def test_nothing_connected_input_status_off_is_a_fault(tmp_path: Path) -> None:
    # a = b = st = r = 0 on every scan: channels inactive (II) and status off (FP); O1 off
    rows = _dcs(tmp_path, "", "Equivalent - Active High,500,Manual,Manual", 3)
    assert rows == [(0, 1)] * 3


def test_manual_cold_start_and_manual_restart(tmp_path: Path) -> None:
    drive = (
        "OTL(st);\n"
        "LIM(2,n,5)OTE(a);\nGEQ(n,8)OTL(a);\nLIM(2,n,5)OTE(b);\nGEQ(n,8)OTL(b);\n"
        "EQU(n,4)OTE(r);\nEQU(n,10)OTL(r);\n"
    )
    rows = _dcs(tmp_path, drive, "Equivalent - Active High,30,Manual,Manual", 11)
    assert rows == [
        OFF_IDLE,  # n 1: nothing active yet
        WAIT_RESET,  # n 2: both active; (inactive at n 1 was a demand) manual restart waits
        WAIT_RESET,  # n 3
        RUNNING,  # n 4: Reset 0 -> 1
        RUNNING,  # n 5
        OFF_IDLE,  # n 6: both inactive: stop demand, O1 off at once
        OFF_IDLE,  # n 7
        WAIT_RESET,  # n 8: active again; manual restart waits (Reset is off)
        WAIT_RESET,  # n 9
        RUNNING,  # n 10: Reset 0 -> 1
        RUNNING,  # n 11: Reset held on changes nothing
    ]


def test_reset_held_on_is_not_a_reset(tmp_path: Path) -> None:
    # Reset on from scan 1 (before the channels are active): no off-to-on transition when
    # they become active at n 3, so O1 waits; Reset dropped at n 5 and raised at n 6 starts.
    drive = "OTL(st);\nGEQ(n,3)OTE(a);\nGEQ(n,3)OTE(b);\nLES(n,5)OTE(r);\nGEQ(n,6)OTL(r);\n"
    rows = _dcs(tmp_path, drive, "Equivalent - Active High,30,Manual,Manual", 6)
    assert rows == [OFF_IDLE, OFF_IDLE, WAIT_RESET, WAIT_RESET, WAIT_RESET, RUNNING]


def test_automatic_cold_start_and_restart(tmp_path: Path) -> None:
    # both channels follow one signal: on n 1-2, off n 3, on again n 4
    drive = "OTL(st);\nNEQ(n,3)OTE(a);\nNEQ(n,3)OTE(b);\n"
    rows = _dcs(tmp_path, drive, "Equivalent - Active High,30,Automatic,Automatic", 4)
    assert rows == [RUNNING, RUNNING, OFF_IDLE, RUNNING]


def test_manual_cold_start_automatic_restart(tmp_path: Path) -> None:
    # active from scan 1: the cold start is manual (RR) until the reset at n 2; the stop at
    # n 3 makes the restart type apply, which is automatic: O1 back at n 4 with no reset.
    drive = "OTL(st);\nNEQ(n,3)OTE(a);\nNEQ(n,3)OTE(b);\nEQU(n,2)OTE(r);\n"
    rows = _dcs(tmp_path, drive, "Equivalent - Active High,30,Automatic,Manual", 4)
    assert rows == [WAIT_RESET, RUNNING, OFF_IDLE, RUNNING]


def test_discrepancy_within_time_is_no_fault(tmp_path: Path) -> None:
    # a on at n 2 (t 10), b follows at n 4 (t 30): 20 ms < 30 ms, so only IP while waiting
    drive = "OTL(st);\nGEQ(n,2)OTE(a);\nGEQ(n,4)OTE(b);\n"
    rows = _dcs(tmp_path, drive, "Equivalent - Active High,30,Automatic,Automatic", 4)
    assert rows == [OFF_IDLE, (0, 0), (0, 0), RUNNING]


def test_discrepancy_fault_cycle_and_reset(tmp_path: Path) -> None:
    # a on n 2-6 alone, b never until n 9 when both come on; Reset pulses at n 6 and n 8.
    drive = (
        "OTL(st);\nLIM(2,n,6)OTE(a);\nGEQ(n,9)OTL(a);\nGEQ(n,9)OTE(b);\n"
        "EQU(n,6)OTE(r);\nEQU(n,8)OTL(r);\n"
    )
    rows = _dcs(tmp_path, drive, "Equivalent - Active High,30,Manual,Manual", 9)
    assert rows == [
        OFF_IDLE,  # n 1 t 0
        (0, 0),  # n 2 t 10: disagreement starts
        (0, 0),  # n 3 t 20: 10 ms
        (0, 0),  # n 4 t 30: 20 ms
        (0, 1),  # n 5 t 40: 30 ms = discrepancy time: fault, cycle required
        (0, 1),  # n 6: reset ignored, the channels were not cycled
        (0, 1),  # n 7: both inactive: cycle done, fault still present
        OFF_IDLE,  # n 8: reset clears the fault
        WAIT_RESET,  # n 9: both active, manual restart waits
    ]


def test_input_status_loss_and_reset(tmp_path: Path) -> None:
    # channels active throughout; status off at n 3 only; Reset at n 5
    drive = "OTL(a);\nOTL(b);\nNEQ(n,3)OTE(st);\nEQU(n,5)OTE(r);\n"
    rows = _dcs(tmp_path, drive, "Equivalent - Active High,30,Automatic,Automatic", 5)
    fault = (0, 1)
    # the reset at n 5 clears the fault and the automatic restart turns O1 on at once
    assert rows == [RUNNING, RUNNING, fault, fault, RUNNING]


def test_complementary_channels(tmp_path: Path) -> None:
    # Complementary: active is A = 1 with B = 0; n 1 A 1 B 0 -> run; n 2 A 0 B 1 -> stop;
    # n 3 A 1 B 1 -> a disagreement (A active, B inactive) is timed
    drive = "OTL(st);\nNEQ(n,2)OTE(a);\nGEQ(n,2)OTE(b);\n"
    rows = _dcs(tmp_path, drive, "Complementary,30,Automatic,Automatic", 3)
    assert rows == [RUNNING, OFF_IDLE, (0, 0)]


def test_false_rung_turns_o1_off(tmp_path: Path) -> None:
    src = (
        "VAR d : DCI_STOP; n : DINT; go : BOOL; END_VAR\nADD(n,1,n);\nNEQ(n,2)OTE(go);\n"
        "XIC(go)DCS(d,E-Stop,Equivalent - Active High,30,Automatic,Automatic,1,1,1,0);\n"
    )
    rows, report = trace(tmp_path, src, ".rll", 3, ["d.O1"], period_ms=10.0)
    assert [int(r["d.O1"]) for r in rows] == [1, 0, 1]
    assert report["diagnostics"] == []


def test_dcs_and_dcst_check_without_u304(tmp_path: Path, capsys) -> None:  # noqa: ANN001
    # DCS is simulated (0075); DCST shows the nothing-connected state (0078): neither is U304
    prog = tmp_path / "p.rll"
    prog.write_text(
        "VAR d : DCI_STOP; t : DCI_STOP_TEST; x : BOOL; END_VAR\n"
        "DCS(d,E-Stop,Equivalent - Active High,30,Manual,Manual,x,x,x,x);\n"
        "DCST(t,E-Stop,Equivalent - Active High,30,Manual,Manual,x,x,x,x,x);\n"
    )
    main(["check", str(prog)])
    out = capsys.readouterr().out
    assert out.strip() == "0 error(s), 0 warning(s)"


def test_dcsrt_and_dcm_check_clean(tmp_path: Path, capsys) -> None:  # noqa: ANN001
    prog = tmp_path / "p.rll"
    prog.write_text(
        "VAR s : DCI_START; m : DCI_MONITOR; x : BOOL; END_VAR\n"
        "DCSRT(s,User Defined,Complementary,30,x,x,x,x,x);\n"
        "DCM(m,Light Curtain,Equivalent - Active High,30,x,x,x,x);\n"
    )
    assert main(["check", str(prog)]) == 0
    assert "U304" not in capsys.readouterr().out


# ------------------------------------------------------------------ DCM
MBITS = ["m.O1", "m.FP"]
MHEAD = "VAR m : DCI_MONITOR; a, b, st, r : BOOL; n : DINT; END_VAR\nADD(n,1,n);\n"


def _dcm(tmp_path: Path, drive: str, disc_ms: int, scans: int) -> list:
    src = MHEAD + drive + f"DCM(m,Safety Gate,Equivalent - Active High,{disc_ms},a,b,st,r);\n"
    rows, report = trace(tmp_path, src, ".rll", scans, MBITS, period_ms=10.0)
    assert report["diagnostics"] == [] and report["faults"] == []
    return [tuple(int(row[k]) for k in MBITS) for row in rows]


def test_dcm_nothing_connected(tmp_path: Path) -> None:
    #              O1 FP
    assert _dcm(tmp_path, "", 500, 2) == [(0, 1)] * 2


def test_dcm_follows_the_channels_without_reset(tmp_path: Path) -> None:
    # both on n 2-3, off n 4, on n 5
    drive = "OTL(st);\nGEQ(n,2)OTE(a);\nEQU(n,4)OTU(a);\nXIC(a)OTE(b);\n"
    idle, on = (0, 0), (1, 0)
    assert _dcm(tmp_path, drive, 20, 5) == [idle, on, on, idle, on]


def test_dcm_discrepancy_fault_cycle_and_reset(tmp_path: Path) -> None:
    # a alone n 2-4; both off n 5-6; Reset n 6; both on n 7. Discrepancy time 20 ms.
    drive = "OTL(st);\nLIM(2,n,4)OTE(a);\nGEQ(n,7)OTL(a);\nGEQ(n,7)OTE(b);\nEQU(n,6)OTE(r);\n"
    assert _dcm(tmp_path, drive, 20, 7) == [
        (0, 0),  # n 1 t 0
        (0, 0),  # n 2 t 10: disagreement starts
        (0, 0),  # n 3 t 20: 10 ms
        (0, 1),  # n 4 t 30: 20 ms = discrepancy time: fault
        (0, 1),  # n 5: both inactive, cycle done, fault kept
        (0, 0),  # n 6: reset clears it
        (1, 0),  # n 7: both active: O1 with no further reset
    ]


# ------------------------------------------------------------------ DCSRT
SBITS = ["s.O1", "s.FP"]
SHEAD = "VAR s : DCI_START; a, b, st, r, en : BOOL; n : DINT; END_VAR\nADD(n,1,n);\n"


def _dcsrt(tmp_path: Path, drive: str, scans: int) -> list:
    src = SHEAD + drive + "DCSRT(s,User Defined,Equivalent - Active High,30,en,a,b,st,r);\n"
    rows, report = trace(tmp_path, src, ".rll", scans, SBITS, period_ms=10.0)
    assert report["diagnostics"] == [] and report["faults"] == []
    return [tuple(int(row[k]) for k in SBITS) for row in rows]


#           O1 FP
S_IDLE = (0, 0)
S_ON = (1, 0)
S_HELD = (0, 0)  # both active but no start (not armed or not enabled)


def test_dcsrt_nothing_connected(tmp_path: Path) -> None:
    assert _dcsrt(tmp_path, "OTL(en);\n", 2) == [(0, 1)] * 2


def test_dcsrt_start_from_inactive(tmp_path: Path) -> None:
    # enabled throughout; both channels on n 2-3, off n 4, on n 5-6
    drive = "OTL(st);\nOTL(en);\nNEQ(n,1)OTE(a);\nEQU(n,4)OTU(a);\nXIC(a)OTE(b);\n"
    assert _dcsrt(tmp_path, drive, 6) == [S_IDLE, S_ON, S_ON, S_IDLE, S_ON, S_ON]


def test_dcsrt_channels_active_at_go_to_run_are_no_start(tmp_path: Path) -> None:
    # active from scan 1: no start until they have been inactive (n 3) and come back (n 4)
    drive = "OTL(st);\nOTL(en);\nNEQ(n,3)OTE(a);\nNEQ(n,3)OTE(b);\n"
    assert _dcsrt(tmp_path, drive, 4) == [S_HELD, S_HELD, S_IDLE, S_ON]


def test_dcsrt_enable_off_stops_and_needs_a_new_start(tmp_path: Path) -> None:
    # channels on from n 2 on; Enable off at n 3 only: O1 off at n 3 and stays off at n 4
    # (the channels never went inactive again)
    drive = "OTL(st);\nNEQ(n,3)OTE(en);\nGEQ(n,2)OTE(a);\nGEQ(n,2)OTE(b);\n"
    assert _dcsrt(tmp_path, drive, 4) == [S_IDLE, S_ON, S_HELD, S_HELD]


def test_dcsrt_activation_while_disabled_is_used_up(tmp_path: Path) -> None:
    # channels on at n 2 with Enable off; Enable on at n 3: no start
    drive = "OTL(st);\nGEQ(n,3)OTE(en);\nGEQ(n,2)OTE(a);\nGEQ(n,2)OTE(b);\n"
    assert _dcsrt(tmp_path, drive, 3) == [S_IDLE, S_HELD, S_HELD]


def test_cold_start_type_only_covers_inputs_active_at_the_go_to_run(tmp_path: Path) -> None:
    # Cold start Automatic, restart Manual. Channels inactive at n 1 (a stop demand), active
    # from n 2: the restart type applies, so O1 waits for the reset at n 3.
    drive = "OTL(st);\nGEQ(n,2)OTE(a);\nGEQ(n,2)OTE(b);\nEQU(n,3)OTE(r);\n"
    rows = _dcs(tmp_path, drive, "Equivalent - Active High,30,Manual,Automatic", 3)
    assert rows == [OFF_IDLE, WAIT_RESET, RUNNING]


def test_backing_tags_have_the_studio_members(tmp_path: Path, capsys) -> None:  # noqa: ANN001
    # members real projects read from safety backing tags (Studio 5000's predefined types)
    prog = tmp_path / "p.rll"
    prog.write_text(
        "VAR d : DCI_STOP; t : DCI_STOP_TEST_LOCK; o : REDUNDANT_OUTPUT;"
        " p : CB_CRANKSHAFT_POS_MONITOR; m : MUTING_TWO_SENSOR_SYM; x : DINT; b : BOOL; END_VAR\n"
        "MOV(d.FaultCode,x);\nMOV(d.DiagnosticCode,x);\nMOV(p.SlideZone,x);\n"
        "MOV(m.S1S2DiscrepancyTime,x);\n"
        "XIC(t.ULC)XIC(o.O1FF)XIC(o.O2FF)XIC(p.TZ)XIC(d.EnableOut)XIC(d.ChannelA)OTE(b);\n"
    )
    assert main(["check", str(prog)]) == 0, capsys.readouterr().out
    # logixst's own state is hidden: not a member a program can name
    prog.write_text("VAR d : DCI_STOP; b : BOOL; END_VAR\nXIC(d.RR)OTE(b);\n")
    assert main(["check", str(prog)]) != 0


def test_dcs_backing_tag_shows_its_operands(tmp_path: Path) -> None:
    # the backing tag mirrors the rung and plain operands, as a GuardLogix backing tag does
    src = HEAD + "OTL(a);\nDCS(d,E-Stop,Equivalent - Active High,250,Manual,Manual,a,b,st,r);\n"
    watch = ["d.EnableIn", "d.ChannelA", "d.ChannelB", "d.DiscrepancyTime"]
    rows, _ = trace(tmp_path, src, ".rll", 1, watch, period_ms=10.0)
    assert [int(rows[0][k]) for k in watch] == [1, 1, 0, 250]


def test_export_with_safety_backing_tags_checks_and_runs(capsys) -> None:  # noqa: ANN001
    # a GuardLogix-shaped export: decorated DCI_STOP data with Studio's members, a safety task
    # running DCS and EPMS with nothing connected, standard logic reading the backing tags
    fix = Path(__file__).parents[1] / "l5x" / "fixtures" / "safety_tags.L5X"
    capsys.readouterr()
    assert main(["check", str(fix)]) == 0
    assert capsys.readouterr().out.strip() == "0 error(s), 0 warning(s)"
    argv = ["run", str(fix), "--scans", "3", "--json"]
    for w in ("Gate.O1", "Gate.FP", "Gate.FaultCode", "GateOk", "ModeFault"):
        argv += ["--watch", w]
    assert main(argv) == 0
    report = json.loads(capsys.readouterr().out)
    # nothing connected: input status 0 -> DCS and EPMS both show their fault bit; no U304
    assert report["tags"] == {
        "Gate.O1": False,
        "Gate.FP": True,
        "Gate.FaultCode": 0,
        "GateOk": False,
        "ModeFault": True,
    }
    assert report["unsupported"] == [] and report["faults"] == []
