"""TOT and ALM (process_blocks.py, decisions 0177 and 0178), expected values by hand.

The totalizer integrates with the trapezoidal rule: each execution in run adds
Gain x DeltaT / TimeBase seconds x (In + previous In) / 2; the first execution in run only
records In. Status bits by the catalog (TOTALIZER / ALARM types).
"""

from __future__ import annotations

from pathlib import Path

import pytest

from interpreter.instructions import process_blocks as pb
from interpreter.semantics.types import REAL
from interpreter.vm.context import ExecContext
from interpreter.vm.refs import ArrayRef
from tests.instructions.run_cli import trace
from tests.instructions.structs import new_struct, struct_type

TI = struct_type("TOTALIZER").index


def _tot(**members: object) -> list:
    return new_struct("TOTALIZER", **members)


def _run(s: list, ctx: ExecContext, **members: object) -> list:
    for name, v in members.items():
        s[TI[name.upper()]] = v
    pb.tot(ctx, True, s)
    return s


def g(s: list, name: str) -> object:
    return s[TI[name.upper()]]


def test_new_totalizer_defaults() -> None:
    s = _tot()
    # a new tag: flow per minute, gain 1, stopped, in operator control
    assert (g(s, "TimeBase"), g(s, "Gain"), g(s, "RunStop"), g(s, "ProgOper")) == (1, 1.0, 0, 0)


def test_constant_flow_through_run(tmp_path: Path) -> None:
    src = (
        "VAR t : TOTALIZER; total : REAL; END_VAR\n"
        "t.In := 60.0; t.TimeBase := 1; t.ProgProgReq := 1; t.ProgStartReq := 1;\n"
        "TOT(t);\ntotal := t.Total;\n"
    )
    rows, report = trace(tmp_path, src, ".st", 11, ["total", "t.RunStop", "t.ProgOper"], 100.0)
    # 60 per minute = 1 per second; 100 ms scans in the continuous task: the first execution
    # starts the run (records In only, DeltaT 0), each later one adds 1 x 0.1 = 0.1
    assert [float(r["total"]) for r in rows] == pytest.approx(
        [0.1 * i for i in range(11)], abs=1e-6
    )
    assert rows[-1]["t.RunStop"] == "1" and rows[-1]["t.ProgOper"] == "1"
    assert report["diagnostics"] == []


def test_trapezoidal_rule_and_time_bases() -> None:
    ctx = ExecContext(task_period_ms=1000.0)  # periodic 1 s task: DeltaT = 1 s
    s = _tot(TimeBase=0, ProgOper=1, ProgStartReq=1)
    _run(s, ctx, In=0.0)  # first in run: records In = 0
    assert g(s, "Total") == 0.0
    _run(s, ctx, In=10.0)  # (0 + 10) / 2 x 1 s = 5
    assert g(s, "Total") == 5.0
    _run(s, ctx, In=20.0)  # + (10 + 20) / 2 = 15 -> 20
    assert g(s, "Total") == 20.0
    _run(s, ctx, Gain=2.0, In=20.0)  # + 2 x 20 = 40 -> 60
    assert g(s, "Total") == 60.0
    _run(s, ctx, Gain=1.0, TimeBase=2, In=7200.0)  # hours: + (20 + 7200) / 2 / 3600 = 1.002777..
    assert g(s, "Total") == pytest.approx(61.0027777, rel=1e-7)
    _run(s, ctx, TimeBase=3, In=86400.0)  # days: + (7200 + 86400) / 2 / 86400 = 0.541666..
    assert g(s, "Total") == pytest.approx(61.5444444, rel=1e-7)


def test_total_is_kept_in_double_precision() -> None:
    ctx = ExecContext(task_period_ms=1.0)  # 1 ms
    s = _tot(TimeBase=0, ProgOper=1, ProgStartReq=1, Total=1000.0, In=0.1)
    for _ in range(10001):
        pb.tot(ctx, True, s)
    # 10,000 integrating executions x 0.1 x 0.001 s = +1.0 -> 1001.0; a REAL accumulator
    # would round every 0.0001 step to a multiple of 1000's ulp (6.1e-5) and drift by ~22 %
    assert g(s, "Total") == pytest.approx(1001.0, abs=1e-4)


def test_low_input_cutoff_stops_totalizing() -> None:
    ctx = ExecContext(task_period_ms=1000.0)
    s = _tot(TimeBase=0, ProgOper=1, ProgStartReq=1, LowInCutoff=1.0, In=4.0)
    _run(s, ctx)
    _run(s, ctx)  # + 4
    assert (g(s, "Total"), g(s, "LowInCutoffFlag")) == (4.0, 0)
    _run(s, ctx, In=1.0)  # In <= LowInCutoff: flag, nothing added
    assert (g(s, "Total"), g(s, "LowInCutoffFlag")) == (4.0, 1)
    _run(s, ctx, In=3.0)  # back above: trapezoid from the cut-off In 1 -> + (1 + 3) / 2 = 2
    assert (g(s, "Total"), g(s, "LowInCutoffFlag")) == (6.0, 0)


def test_program_start_stop_and_first_scan_after_restart() -> None:
    ctx = ExecContext(task_period_ms=1000.0)
    s = _tot(TimeBase=0, ProgOper=1, In=2.0)
    _run(s, ctx)  # stopped: nothing
    assert (g(s, "RunStop"), g(s, "Total")) == (0, 0.0)
    _run(s, ctx, ProgStartReq=1, ProgStopReq=1)  # both: the stop wins
    assert g(s, "RunStop") == 0
    _run(s, ctx, ProgStopReq=0)  # running, first scan only records In
    assert (g(s, "RunStop"), g(s, "Total")) == (1, 0.0)
    _run(s, ctx)  # + 2
    _run(s, ctx, ProgStartReq=0, ProgStopReq=1)  # stopped: held at 2
    assert (g(s, "RunStop"), g(s, "Total")) == (0, 2.0)
    _run(s, ctx, ProgStopReq=0, ProgStartReq=1, In=100.0)  # first in run again: records 100
    assert g(s, "Total") == 2.0
    _run(s, ctx, In=100.0)  # + 100 (not + (2 + 100) / 2 from the In before the stop)
    assert g(s, "Total") == 102.0


def test_prescan_makes_the_next_execution_a_first_one() -> None:
    ctx = ExecContext(task_period_ms=1000.0)
    s = _tot(TimeBase=0, ProgOper=1, ProgStartReq=1, In=5.0)
    _run(s, ctx)
    _run(s, ctx)  # + 5
    pb.tot_prescan(ctx, True, s)
    _run(s, ctx, In=50.0)  # after prescan: records 50 only
    assert g(s, "Total") == 5.0


def test_program_reset_handshake() -> None:
    ctx = ExecContext(task_period_ms=1000.0)
    s = _tot(TimeBase=0, ProgOper=1, Total=42.0, ResetValue=3.0)
    _run(s, ctx, ProgResetReq=1)  # rising edge: OldTotal 42, Total 3, done
    assert (g(s, "OldTotal"), g(s, "Total"), g(s, "ProgResetDone")) == (42.0, 3.0, 1)
    _run(s, ctx, Total=10.0)  # still requested: no second reset, done stays
    assert (g(s, "OldTotal"), g(s, "Total"), g(s, "ProgResetDone")) == (42.0, 10.0, 1)
    _run(s, ctx, ProgResetReq=0)  # request dropped: done clears
    assert g(s, "ProgResetDone") == 0
    _run(s, ctx, ProgOper=0, ProgResetReq=1)  # operator control: the program cannot reset
    assert (g(s, "Total"), g(s, "ProgResetDone")) == (10.0, 0)


def test_operator_control_and_request_clearing() -> None:
    ctx = ExecContext(task_period_ms=1000.0)
    s = _tot(TimeBase=0, ProgOper=1, In=1.0, Total=7.0, ResetValue=0.5)
    _run(s, ctx, OperOperReq=1)  # to operator control; the request is cleared after
    assert (g(s, "ProgOper"), g(s, "OperOperReq")) == (0, 0)
    _run(s, ctx, ProgStartReq=1)  # a program start is not obeyed in operator control
    assert g(s, "RunStop") == 0
    _run(s, ctx, OperStartReq=1)
    assert (g(s, "RunStop"), g(s, "OperStartReq")) == (1, 0)
    _run(s, ctx, OperResetReq=1)  # operator reset: OldTotal 7, Total 0.5, no ProgResetDone;
    # then this execution's own + (1 + 1) / 2 x 1 s -> 1.5
    assert (g(s, "OldTotal"), g(s, "Total"), g(s, "ProgResetDone")) == (7.0, 1.5, 0)
    assert g(s, "OperResetReq") == 0
    _run(s, ctx, ProgOperReq=1, OperProgReq=1)  # ProgOperReq keeps operator control
    assert g(s, "ProgOper") == 0
    _run(s, ctx, ProgOperReq=0, OperProgReq=1)  # now the operator hands over to the program
    assert g(s, "ProgOper") == 1
    # ProgStartReq is still set (no ProgValueReset), so the program keeps it running
    assert g(s, "RunStop") == 1 and g(s, "ProgStartReq") == 1
    _run(s, ctx, ProgValueReset=1)  # program requests cleared at the end of the execution
    assert (g(s, "ProgStartReq"), g(s, "ProgProgReq"), g(s, "RunStop")) == (0, 0, 1)


def test_target_and_pre_target_flags() -> None:
    ctx = ExecContext(task_period_ms=1000.0)
    s = _tot(Target=100.0, TargetDev1=10.0, TargetDev2=20.0, Total=79.0)
    _run(s, ctx)  # 79 < 80 (Target - Dev2)
    assert [g(s, f) for f in ("TargetFlag", "TargetDev1Flag", "TargetDev2Flag")] == [0, 0, 0]
    _run(s, ctx, Total=80.0)  # reaches Target - TargetDev2 = 80
    assert [g(s, f) for f in ("TargetFlag", "TargetDev1Flag", "TargetDev2Flag")] == [0, 0, 1]
    _run(s, ctx, Total=90.0)  # Target - TargetDev1 = 90
    assert [g(s, f) for f in ("TargetFlag", "TargetDev1Flag", "TargetDev2Flag")] == [0, 1, 1]
    _run(s, ctx, Total=100.0)
    assert [g(s, f) for f in ("TargetFlag", "TargetDev1Flag", "TargetDev2Flag")] == [1, 1, 1]


def test_invalid_time_base_timing_mode_and_in_fault() -> None:
    ctx = ExecContext(task_period_ms=1000.0)
    s = _tot(TimeBase=4, ProgOper=1, ProgStartReq=1, In=1.0)
    _run(s, ctx)
    _run(s, ctx)
    # TimeBaseInv (bit 2) + InstructFault (bit 0) = 5; nothing integrated
    assert (g(s, "Status"), g(s, "TimeBaseInv"), g(s, "Total")) == (5, 1, 0.0)
    _run(s, ctx, TimeBase=0, TimingMode=7)
    # TimingModeInv is bit 27: 2**27 + 1 = 134217729
    assert (g(s, "Status"), g(s, "TimingModeInv"), g(s, "Total")) == (134217729, 1, 0.0)
    _run(s, ctx, TimingMode=0)
    _run(s, ctx)  # valid again: + 1
    assert (g(s, "Status"), g(s, "Total")) == (0, 1.0)
    _run(s, ctx, InFault=1)  # InFaulted (bit 1) only, no InstructFault; Total held
    assert (g(s, "Status"), g(s, "InFaulted"), g(s, "Total")) == (2, 1, 1.0)
    _run(s, ctx, InFault=0)
    assert (g(s, "Status"), g(s, "Total")) == (0, 2.0)


# ------------------------------------------------------------------ ALM
AI = struct_type("ALARM").index


def _alm(s: list, ctx: ExecContext | None = None, **members: object) -> list:
    for name, v in members.items():
        s[AI[name.upper()]] = v
    pb.alm(ctx or ExecContext(), True, s)
    return s


def alarms(s: list) -> list[object]:
    return [s[AI[n]] for n in ("HHALARM", "HALARM", "LALARM", "LLALARM")]


def test_new_alarm_tag_never_alarms() -> None:
    # limits default to the largest / most negative REAL, so no level alarm fires
    s = _alm(new_struct("ALARM"), In=1.0e30)
    assert alarms(s) == [0, 0, 0, 0]
    s = _alm(s, In=-1.0e30)
    assert alarms(s) == [0, 0, 0, 0] and s[AI["STATUS"]] == 0 and s[AI["ENABLEOUT"]] == 1


def test_level_alarms_clear_past_the_deadband() -> None:
    s = new_struct("ALARM", HHLimit=90.0, HLimit=80.0, LLimit=20.0, LLLimit=10.0, Deadband=2.0)
    assert alarms(_alm(s, In=50.0)) == [0, 0, 0, 0]
    assert alarms(_alm(s, In=80.0)) == [0, 1, 0, 0]  # In >= HLimit
    assert alarms(_alm(s, In=79.0)) == [0, 1, 0, 0]  # 79 >= 80 - 2: still on
    assert alarms(_alm(s, In=77.5)) == [0, 0, 0, 0]  # 77.5 < 78: cleared
    assert alarms(_alm(s, In=90.0)) == [1, 1, 0, 0]
    assert alarms(_alm(s, In=88.5)) == [1, 1, 0, 0]  # HH clears only below 88
    assert alarms(_alm(s, In=87.0)) == [0, 1, 0, 0]  # below 88, H stays (87 >= 78)
    assert alarms(_alm(s, In=20.0)) == [0, 0, 1, 0]  # In <= LLimit
    assert alarms(_alm(s, In=21.5)) == [0, 0, 1, 0]  # not above 20 + 2
    assert alarms(_alm(s, In=22.5)) == [0, 0, 0, 0]
    assert alarms(_alm(s, In=10.0)) == [0, 0, 1, 1]
    assert alarms(_alm(s, In=11.0)) == [0, 0, 1, 1]  # LL clears only above 12
    assert alarms(_alm(s, In=12.5)) == [0, 0, 1, 0]
    assert s[AI["STATUS"]] == 0


def test_rate_of_change_through_run(tmp_path: Path) -> None:
    src = (
        "VAR a : ALARM; x : REAL; roc : REAL; up : BOOL; END_VAR\n"
        "x := x + 1.0; a.In := x; a.ROCPeriod := 0.5; a.ROCPosLimit := 8.0;\n"
        "ALM(a);\nroc := a.ROC; up := a.ROCPosAlarm;\n"
    )
    rows, report = trace(tmp_path, src, ".st", 11, ["roc", "up"], 100.0)
    # In rises by 1 every 100 ms scan (x = 1 at t = 0). The first sample is In 1 at t 0;
    # the next at t 500 ms (In 6): ROC = (6 - 1) / 0.5 = 10 >= 8 -> ROCPosAlarm; at t 1000
    # (In 11) again (11 - 6) / 0.5 = 10. Between samples ROC holds.
    assert [float(r["roc"]) for r in rows] == [0.0] * 5 + [10.0] * 6
    assert [r["up"] for r in rows] == ["0"] * 5 + ["1"] * 6
    assert report["diagnostics"] == []


def test_negative_rate_of_change_and_disabling() -> None:
    ctx = ExecContext(now_ms=0.0)
    s = new_struct("ALARM", ROCPeriod=2.0, ROCNegLimit=3.0, ROCPosLimit=1.0)
    _alm(s, ctx, In=100.0)  # first sample
    ctx.now_ms = 1999.0
    _alm(s, ctx, In=80.0)  # period not over yet
    assert (s[AI["ROC"]], s[AI["ROCNEGALARM"]]) == (0.0, 0)
    ctx.now_ms = 2000.0
    _alm(s, ctx, In=92.0)  # (92 - 100) / 2 = -4 <= -3
    assert (s[AI["ROC"]], s[AI["ROCNEGALARM"]], s[AI["ROCPOSALARM"]]) == (-4.0, 1, 0)
    ctx.now_ms = 4000.0
    _alm(s, ctx, In=88.0)  # (88 - 92) / 2 = -2 > -3: cleared
    assert (s[AI["ROC"]], s[AI["ROCNEGALARM"]]) == (-2.0, 0)
    ctx.now_ms = 6000.0
    _alm(s, ctx, In=88.0, ROCPeriod=0.0)  # period 0: rate alarming off, ROC 0
    assert (s[AI["ROC"]], s[AI["ROCNEGALARM"]], s[AI["ROCPOSALARM"]]) == (0.0, 0, 0)


def test_invalid_settings_set_their_bits_and_act_as_zero() -> None:
    s = new_struct("ALARM", HLimit=50.0, Deadband=-5.0)
    _alm(s, In=50.0)
    # DeadbandInv (bit 1) + InstructFault (bit 0) = 3; deadband taken as 0
    assert (s[AI["STATUS"]], s[AI["HALARM"]]) == (3, 1)
    _alm(s, In=49.9)  # with deadband 0 the alarm clears as soon as In < 50
    assert s[AI["HALARM"]] == 0
    _alm(s, Deadband=0.0, ROCPosLimit=-1.0)  # ROCPosLimitInv bit 2 -> 1 + 4 = 5
    assert s[AI["STATUS"]] == 5
    _alm(s, ROCPosLimit=0.0, ROCNegLimit=-1.0)  # bit 3 -> 9
    assert s[AI["STATUS"]] == 9
    _alm(s, ROCNegLimit=0.0, ROCPeriod=40000.0)  # beyond 32767 s: bit 4 -> 17
    assert (s[AI["STATUS"]], s[AI["ROCPERIODINV"]], s[AI["INSTRUCTFAULT"]]) == (17, 1, 1)
    _alm(s, ROCPeriod=1.0)
    assert s[AI["STATUS"]] == 0


def test_alarm_prescan_restarts_the_rate_period() -> None:
    ctx = ExecContext(now_ms=0.0)
    s = new_struct("ALARM", ROCPeriod=1.0, ROCPosLimit=5.0)
    _alm(s, ctx, In=0.0)
    pb.alm_prescan(ctx, True, s)
    ctx.now_ms = 1000.0
    _alm(s, ctx, In=50.0)  # a new first sample after prescan, not (50 - 0) / 1
    assert (s[AI["ROC"]], s[AI["ROCPOSALARM"]]) == (0.0, 0)
    ctx.now_ms = 2000.0
    _alm(s, ctx, In=56.0)  # (56 - 50) / 1 = 6 >= 5
    assert (s[AI["ROC"]], s[AI["ROCPOSALARM"]]) == (6.0, 1)


# ------------------------------------------------------------------ FGEN
FI = struct_type("FUNCTION_GENERATOR").index


def _real_array(*values: float, size: int | None = None) -> ArrayRef:
    v = [*values] + [0.0] * ((size or len(values)) - len(values))
    return ArrayRef(v, 0, REAL, (len(v),))


def test_fgen_interpolates_through_run(tmp_path: Path) -> None:
    src = (
        "VAR f : FUNCTION_GENERATOR;\n"
        "  x1 : ARRAY[0..4] OF REAL := [0.0, 10.0, 20.0, 50.0, 0.0];\n"
        "  y1 : ARRAY[0..4] OF REAL := [0.0, 100.0, 150.0, 0.0, 0.0];\n"
        "  x2 : ARRAY[0..1] OF REAL; y2 : ARRAY[0..1] OF REAL; x : REAL := -5.0; END_VAR\n"
        "f.In := x; f.XY1Size := 4;\nFGEN(f, x1, y1, x2, y2);\nx := x + 7.5;\n"
    )
    rows, report = trace(tmp_path, src, ".st", 10, ["f.Out", "f.Status"])
    # In = -5, 2.5, 10, ..., 62.5 through (0,0) (10,100) (20,150) (50,0):
    #  -5 below X[0] -> Y[0] 0; 2.5 -> 25; 10 -> 100; 17.5 -> 100 + 7.5 x 5 = 137.5;
    #  25 -> 150 - 5 x 150/30 = 125; 32.5 -> 87.5; 40 -> 50; 47.5 -> 12.5; beyond 50 -> 0
    expected = [0.0, 25.0, 100.0, 137.5, 125.0, 87.5, 50.0, 12.5, 0.0, 0.0]
    assert [float(r["f.Out"]) for r in rows] == expected
    assert {r["f.Status"] for r in rows} == {"0"}
    assert report["diagnostics"] == []


def test_fgen_select_chooses_the_second_table() -> None:
    s = new_struct("FUNCTION_GENERATOR", In=3.0, XY1Size=2, XY2Size=3, Select=1)
    x1, y1 = _real_array(0.0, 10.0), _real_array(0.0, 10.0)
    x2, y2 = _real_array(0.0, 2.0, 4.0), _real_array(-1.0, 1.0, 9.0)
    pb.fgen(ExecContext(), True, s, x1, y1, x2, y2)
    assert s[FI["OUT"]] == 5.0  # between (2,1) and (4,9): 1 + 1 x 8/2 = 5
    s[FI["SELECT"]] = 0
    pb.fgen(ExecContext(), True, s, x1, y1, x2, y2)
    assert s[FI["OUT"]] == 3.0  # identity table 1
    s[FI["XY1SIZE"]] = 1  # one point: Out is that Y whatever In
    pb.fgen(ExecContext(), True, s, x1, y1, x2, y2)
    assert (s[FI["OUT"]], s[FI["STATUS"]]) == (0.0, 0)


def test_fgen_invalid_sizes_and_order_hold_out() -> None:
    x, y = _real_array(0.0, 5.0, 5.0), _real_array(1.0, 2.0, 3.0)
    s = new_struct("FUNCTION_GENERATOR", In=1.0, XY1Size=4, Out=7.0)
    pb.fgen(ExecContext(), True, s, x, y, x, y)
    # 4 points but the arrays hold 3: XY1SizeInv (bit 1) + InstructFault = 3; Out held
    assert (s[FI["STATUS"]], s[FI["OUT"]]) == (3, 7.0)
    s[FI["XY1SIZE"]] = 0
    pb.fgen(ExecContext(), True, s, x, y, x, y)
    assert s[FI["STATUS"]] == 3
    s[FI["XY1SIZE"]] = 3  # X 0, 5, 5 does not ascend strictly: XisOutofOrder bit 3 -> 9
    pb.fgen(ExecContext(), True, s, x, y, x, y)
    assert (s[FI["STATUS"]], s[FI["XISOUTOFORDER"]], s[FI["OUT"]]) == (9, 1, 7.0)
    s[FI["XY1SIZE"]] = 2  # 0, 5 ascends: Out = 1 + 1 x 1/5 = 1.2
    pb.fgen(ExecContext(), True, s, x, y, x, y)
    assert (s[FI["STATUS"]], s[FI["OUT"]]) == (0, pytest.approx(1.2))
    s[FI["SELECT"]] = 1  # second table selected with XY2Size 0: XY2SizeInv bit 2 -> 5
    pb.fgen(ExecContext(), True, s, x, y, x, y)
    assert (s[FI["STATUS"]], s[FI["XY2SIZEINV"]]) == (5, 1)
    s[FI["XY2SIZE"]] = -1  # negative is invalid even when not selected
    s[FI["SELECT"]] = 0
    pb.fgen(ExecContext(), True, s, x, y, x, y)
    assert s[FI["STATUS"]] == 5


# ------------------------------------------------------------------ ESEL
EI = struct_type("SELECT_ENHANCED").index
INS = {"In1": 5.0, "In2": 9.0, "In3": 1.0, "In4": 7.0, "In5": 3.0, "In6": 100.0}


def _esel(s: list, **members: object) -> list:
    for name, v in members.items():
        s[EI[name.upper()]] = v
    pb.esel(ExecContext(), True, s)
    return s


def pick(s: list) -> tuple[object, object]:
    return s[EI["OUT"]], s[EI["SELECTEDIN"]]


def test_esel_high_low_median_average_of_the_used_inputs() -> None:
    s = new_struct("SELECT_ENHANCED", InsUsed=5, **INS)  # In6 = 100 is not used
    assert pick(_esel(s, SelectorMode=1)) == (9.0, 2)  # highest of 5 9 1 7 3
    assert pick(_esel(s, SelectorMode=2)) == (1.0, 3)  # lowest
    assert pick(_esel(s, SelectorMode=3)) == (5.0, 1)  # sorted 1 3 5 7 9: middle 5 (In1)
    assert pick(_esel(s, SelectorMode=4)) == (5.0, 0)  # (5 + 9 + 1 + 7 + 3) / 5 = 5
    assert pick(_esel(s, SelectorMode=3, InsUsed=4)) == (6.0, 0)  # 1 5 7 9: (5 + 7) / 2
    assert s[EI["STATUS"]] == 0 and s[EI["ENABLEOUT"]] == 1


def test_esel_faulted_inputs_are_left_out() -> None:
    s = new_struct("SELECT_ENHANCED", InsUsed=5, In2Fault=1, **INS)
    assert pick(_esel(s, SelectorMode=1)) == (7.0, 4)  # In2 (9) faulted: next highest In4
    assert pick(_esel(s, SelectorMode=4)) == (4.0, 0)  # (5 + 1 + 7 + 3) / 4 = 4
    assert s[EI["INSFAULTED"]] == 0
    faults = {f"In{i}Fault": 1 for i in range(1, 6)}
    _esel(s, SelectorMode=2, **faults)  # every used input faulted: Out holds, InsFaulted
    assert (pick(s), s[EI["INSFAULTED"]]) == ((4.0, 0), 1)


def test_esel_manual_selection_program_and_operator() -> None:
    s = new_struct("SELECT_ENHANCED", InsUsed=6, SelectorMode=0, ProgSelector=2, **INS)
    s[EI["OPERSELECTOR"]] = 6
    assert pick(_esel(s)) == (100.0, 6)  # a new tag is in operator control: OperSelector 6
    _esel(s, ProgProgReq=1)  # to program control: ProgSelector 2
    assert (s[EI["PROGOPER"]], pick(s)) == (1, (9.0, 2))
    _esel(s, ProgProgReq=0, OperOperReq=1)  # operator request: back to OperSelector
    assert (s[EI["PROGOPER"]], s[EI["OPEROPERREQ"]], pick(s)) == (0, 0, (100.0, 6))
    _esel(s, OperSelector=0)  # selector 0: nothing selected, Out holds
    assert pick(s) == (100.0, 0)
    _esel(s, OperSelector=3, In3Fault=1)  # a faulted input chosen by hand: InsFaulted
    assert (pick(s), s[EI["INSFAULTED"]]) == ((1.0, 3), 1)


def test_esel_override_uses_the_program_selector() -> None:
    s = new_struct("SELECT_ENHANCED", InsUsed=6, SelectorMode=1, ProgSelector=5, **INS)
    assert pick(_esel(s)) == (100.0, 6)  # high select
    _esel(s, ProgOverrideReq=1)  # override: manual by ProgSelector, even in operator control
    assert (s[EI["OVERRIDE"]], s[EI["PROGOPER"]], pick(s)) == (1, 0, (3.0, 5))
    _esel(s, ProgValueReset=1)  # program requests cleared after this execution
    assert (s[EI["PROGOVERRIDEREQ"]], s[EI["OVERRIDE"]]) == (0, 1)
    _esel(s, ProgValueReset=0)
    assert (s[EI["OVERRIDE"]], pick(s)) == (0, (100.0, 6))


def test_esel_invalid_settings_hold_out() -> None:
    s = new_struct("SELECT_ENHANCED", InsUsed=7, SelectorMode=1, Out=-2.0, **INS)
    _esel(s)  # InsUsedInv (bit 1) + InstructFault = 3
    assert (s[EI["STATUS"]], s[EI["OUT"]]) == (3, -2.0)
    _esel(s, InsUsed=3, SelectorMode=5)  # SelectorModeInv bit 2 -> 5
    assert (s[EI["STATUS"]], s[EI["OUT"]]) == (5, -2.0)
    _esel(s, SelectorMode=0, ProgSelector=9)  # ProgSelectorInv bit 3 -> 9, not in use: works
    assert (s[EI["STATUS"]], s[EI["SELECTORMODEINV"]]) == (9, 0)
    _esel(s, ProgSelector=0, OperSelector=-1)  # OperSelectorInv bit 4 -> 17, in use: holds
    assert (s[EI["STATUS"]], s[EI["OPERSELECTORINV"]], s[EI["OUT"]]) == (17, 1, -2.0)


def test_esel_through_run(tmp_path: Path) -> None:
    src = (
        "VAR e : SELECT_ENHANCED; k : DINT; END_VAR\n"
        "k := k + 1;\n"
        "e.In1 := 10.0; e.In2 := 20.0; e.In3 := 40.0; e.InsUsed := 3; e.SelectorMode := 3;\n"
        "e.In2Fault := k >= 3;\n"
        "ESEL(e);\n"
    )
    rows, report = trace(tmp_path, src, ".st", 4, ["e.Out", "e.SelectedIn"])
    # median of 10 20 40 is In2 (20); from the third scan In2 is faulted: the median of the
    # two left is their mean (10 + 40) / 2 = 25, with no single input selected
    assert [(r["e.Out"], r["e.SelectedIn"]) for r in rows] == [
        ("20.0", "2"),
        ("20.0", "2"),
        ("25.0", "0"),
        ("25.0", "0"),
    ]
    assert report["diagnostics"] == []
