"""LPF, HPF, LDLG, DEDT, LDL2, NTCH through `logixst run` and on their tags (decisions 0139,
0170, 0171). Expected values are closed-form responses of the continuous filters sampled at
the scan instants (the blocks' discretisation is exact for an input held over the interval
ending at the execution), with the working in the comments.

A lone .st file runs in the continuous task: the first scan's DeltaT is 0 (the block
initialises, Out = steady state for In), every later one is the scan period.
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from interpreter.instructions import filter_blocks as fb
from interpreter.vm.context import ExecContext
from tests.instructions.run_cli import column as _col
from tests.instructions.run_cli import int_column as _ints
from tests.instructions.run_cli import run_each_scan as _run
from tests.instructions.structs import new_struct, struct_type

STEP = "IF n > 1 THEN f.In := 1.0; END_IF;\n"  # In steps 0 -> 1 after the first scan


# ------------------------------------------------------------------ LPF
def test_lpf_first_order_step_response(tmp_path: Path) -> None:
    rows = _run(tmp_path, "f : FILTER_LOW_PASS;",
                "f.WLag := 10.0; f.Order := 1;\n" + STEP + "LPF(f);", 8, ["f.Out", "f.Status",
                "f.DeltaT", "f.EnableOut"], 10.0)  # fmt: skip
    out = _col(rows, "f.Out")
    assert out[0] == 0.0  # first scan: initialised on In = 0
    # scan k >= 1: t = k x 0.01 s after the step, Out = 1 - e^(-10 t)
    for k in range(1, 8):
        assert out[k] == pytest.approx(1.0 - math.exp(-10.0 * 0.01 * k), rel=1e-6)
    assert _col(rows, "f.DeltaT")[1:] == [pytest.approx(0.01)] * 7
    assert set(_ints(rows, "f.Status")) == {0} and set(_ints(rows, "f.EnableOut")) == {1}


def test_lpf_second_order_is_butterworth(tmp_path: Path) -> None:
    rows = _run(tmp_path, "f : FILTER_LOW_PASS;",
                "f.WLag := 20.0; f.Order := 2;\n" + STEP + "LPF(f);", 10, ["f.Out"], 10.0)  # fmt: skip
    out = _col(rows, "f.Out")
    # w^2 / (s^2 + sqrt2 w s + w^2): zeta = 1/sqrt2, wd = w/sqrt2, zeta/sqrt(1-zeta^2) = 1:
    # y(t) = 1 - e^(-w t/sqrt2) (cos(w t/sqrt2) + sin(w t/sqrt2))
    for k in range(1, 10):
        a = 20.0 * 0.01 * k / math.sqrt(2.0)
        assert out[k] == pytest.approx(1.0 - math.exp(-a) * (math.cos(a) + math.sin(a)), rel=1e-5)


def test_lpf_third_order_is_butterworth(tmp_path: Path) -> None:
    rows = _run(tmp_path, "f : FILTER_LOW_PASS;",
                "f.WLag := 20.0; f.Order := 3;\n" + STEP + "LPF(f);", 10, ["f.Out"], 10.0)  # fmt: skip
    out = _col(rows, "f.Out")
    # w^3 / ((s + w)(s^2 + w s + w^2)), partial fractions of the step:
    # y(t) = 1 - e^(-w t) - (2/sqrt3) e^(-w t/2) sin(sqrt3 w t/2)
    for k in range(1, 10):
        t = 0.01 * k
        want = (
            1
            - math.exp(-20 * t)
            - 2 / math.sqrt(3) * math.exp(-10 * t) * math.sin(math.sqrt(3) * 10 * t)
        )
        assert out[k] == pytest.approx(want, rel=1e-5, abs=1e-7)


def test_lpf_initialize_sets_out_to_in(tmp_path: Path) -> None:
    body = "f.WLag := 1.0; f.In := 5.0 * n; f.Initialize := n = 3;\nLPF(f);"
    rows = _run(tmp_path, "f : FILTER_LOW_PASS;", body, 4, ["f.Out"], 10.0)
    out = _col(rows, "f.Out")
    assert out[0] == 5.0  # first execution: steady state on In 5
    # scan 2: In 10, Out = 5 + (10 - 5)(1 - e^(-0.01))
    assert out[1] == pytest.approx(5 + 5 * (1 - math.exp(-0.01)), rel=1e-6)
    assert out[2] == 15.0  # Initialize: Out = In = 15
    # scan 4: from 15 towards In 20 over 0.01 s
    assert out[3] == pytest.approx(15 + 5 * (1 - math.exp(-0.01)), rel=1e-6)


def test_lpf_invalid_order_and_clamped_frequency(tmp_path: Path) -> None:
    # Order 5: OrderInv (bit 2) + InstructFault (bit 0) = 5, filtered as order 1.
    # WLag 100 above 0.36 / 0.01 s = 36 rad/s: WLagInv (bit 1), filtered with WLag 36.
    body = "f.WLag := 100.0; f.Order := 5;\n" + STEP + "LPF(f);"
    rows = _run(tmp_path, "f : FILTER_LOW_PASS;", body, 3, ["f.Out", "f.Status",
                "f.WLagInv", "f.OrderInv", "f.InstructFault"], 10.0)  # fmt: skip
    assert _col(rows, "f.Out")[1] == pytest.approx(1 - math.exp(-0.36), rel=1e-6)
    assert _ints(rows, "f.Status")[1:] == [7, 7]  # bits 0, 1, 2
    assert (rows[1]["f.WLagInv"], rows[1]["f.OrderInv"], rows[1]["f.InstructFault"]) == (
        "1",
        "1",
        "1",
    )
    # the first scan (DeltaT 0) cannot compute the frequency limits: only OrderInv
    assert _ints(rows, "f.Status")[0] == 5


def test_lpf_zero_frequency_is_raised_to_the_low_limit(tmp_path: Path) -> None:
    # WLag 0 (a new tag). Scan 1 (DeltaT 0): no limit can be computed, WLag <= 0 is invalid
    # and nothing is filtered. Scan 2 (DeltaT 0.01): WLag raised to the order-1 low limit
    # 1e-7 / 0.01 = 1e-5 rad/s, the block initialises on In 0. Scan 3, In 1:
    # Out = 1 - e^(-1e-5 x 0.01) = 1e-7 (to 6 digits). Status = bits 0, 1 throughout.
    body = "f.Order := 1; f.WLag := 0.0; IF n > 2 THEN f.In := 1.0; END_IF;\nLPF(f);"
    rows = _run(tmp_path, "f : FILTER_LOW_PASS;", body, 3, ["f.Out", "f.Status"], 10.0)
    assert _col(rows, "f.Out")[:2] == [0.0, 0.0]
    assert _col(rows, "f.Out")[2] == pytest.approx(1e-7, rel=1e-5)
    assert _ints(rows, "f.Status") == [3, 3, 3]


def test_lpf_timing_modes(tmp_path: Path) -> None:
    # oversample: DeltaT = OversampleDT = 0.05 s whatever the scan period
    body = "f.WLag := 2.0; f.Order := 1; f.TimingMode := 1; f.OversampleDT := 0.05;\n"
    rows = _run(tmp_path, "f : FILTER_LOW_PASS;", body + STEP + "LPF(f);", 3, ["f.Out"], 1.0)
    # scan 0 is the initialisation (Out = In = 0), then two steps of 0.05 s
    assert _col(rows, "f.Out")[2] == pytest.approx(1 - math.exp(-2.0 * 0.1), rel=1e-6)


def test_lpf_invalid_timing_mode_leaves_out(tmp_path: Path) -> None:
    body = "f.WLag := 2.0; f.Order := 1; f.In := 4.0;\nIF n > 2 THEN f.TimingMode := 3; END_IF;\nLPF(f);"
    rows = _run(tmp_path, "f : FILTER_LOW_PASS;", body, 4, ["f.Out", "f.Status"], 10.0)
    assert _col(rows, "f.Out") == [4.0, 4.0, 4.0, 4.0]
    # TimingModeInv is bit 27, with InstructFault: 2^27 + 1
    assert _ints(rows, "f.Status") == [0, 0, 2**27 + 1, 2**27 + 1]


def test_lpf_real_time_sampling_missed_and_invalid_delta_t(tmp_path: Path) -> None:
    # stamps every scan 20 ms apart with RTSTime 10: RTSMissed (bit 28, not a fault)
    body = (
        "f.WLag := 1.0; f.Order := 1; f.TimingMode := 2; f.RTSTime := 10;\n"
        "f.RTSTimeStamp := 20 * n;\n" + STEP + "LPF(f);"
    )
    rows = _run(tmp_path, "f : FILTER_LOW_PASS;", body, 3, ["f.Out", "f.Status"], 1.0)
    assert _ints(rows, "f.Status") == [0, 2**28, 2**28]
    assert _col(rows, "f.Out")[2] == pytest.approx(1 - math.exp(-0.04), rel=1e-6)  # 2 x 20 ms
    # oversample DeltaT -1: DeltaTInv (bit 31) + InstructFault, a negative DINT
    body = "f.WLag := 1.0; f.TimingMode := 1; f.OversampleDT := -1.0;\nLPF(f);"
    rows = _run(tmp_path, "f : FILTER_LOW_PASS;", body, 1, ["f.Status"], 1.0)
    assert _ints(rows, "f.Status") == [-(2**31) + 1]


def test_lpf_at_rest_stays_at_rest_when_retuned(tmp_path: Path) -> None:
    # In constant 3: the third-order filter is at rest; changing WLag online must not bump Out
    body = "f.Order := 3; f.In := 3.0;\nIF n < 3 THEN f.WLag := 5.0; ELSE f.WLag := 20.0; END_IF;\nLPF(f);"
    rows = _run(tmp_path, "f : FILTER_LOW_PASS;", body, 5, ["f.Out"], 10.0)
    assert _col(rows, "f.Out") == pytest.approx([3.0] * 5, rel=1e-6)


def test_lpf_prescan_reinitialises() -> None:
    s = new_struct("FILTER_LOW_PASS", WLag=1.0, Order=1, In=3.0)
    ctx = ExecContext(now_ms=0.0, task_period_ms=10.0)
    fb.lpf(ctx, True, s)
    ix = struct_type("FILTER_LOW_PASS").index
    assert s[ix["OUT"]] == 3.0  # first execution: steady state
    s[ix["IN"]] = 4.0
    fb.lpf(ctx, True, s)
    assert s[ix["OUT"]] == pytest.approx(3 + (1 - math.exp(-0.01)), rel=1e-6)
    fb.lpf_prescan(ctx, True, s)
    fb.lpf(ctx, True, s)
    assert s[ix["OUT"]] == 4.0  # initialised again on In


def test_lpf_non_finite_out_then_restart() -> None:
    s = new_struct("FILTER_LOW_PASS", WLag=1.0, Order=1, In=math.inf)
    ix = struct_type("FILTER_LOW_PASS").index
    ctx = ExecContext(now_ms=0.0, task_period_ms=10.0)
    fb.lpf(ctx, True, s)
    assert not math.isfinite(s[ix["OUT"]]) and s[ix["ENABLEOUT"]] == 0  # inf - inf
    s[ix["IN"]] = 2.0
    fb.lpf(ctx, True, s)
    assert s[ix["OUT"]] == 2.0 and s[ix["ENABLEOUT"]] == 1  # valid again: Out = In


# ------------------------------------------------------------------ HPF
def test_hpf_first_order_step_decays(tmp_path: Path) -> None:
    rows = _run(tmp_path, "f : FILTER_HIGH_PASS;",
                "f.WLead := 10.0; f.Order := 1;\n" + STEP + "HPF(f);", 6, ["f.Out", "f.Status"],
                10.0)  # fmt: skip
    out = _col(rows, "f.Out")
    assert out[0] == 0.0
    # s / (s + w): a unit step gives e^(-w t), t = k x 0.01 s
    for k in range(1, 6):
        assert out[k] == pytest.approx(math.exp(-10.0 * 0.01 * k), rel=1e-6)
    assert set(_ints(rows, "f.Status")) == {0}


def test_hpf_second_order_step(tmp_path: Path) -> None:
    rows = _run(tmp_path, "f : FILTER_HIGH_PASS;",
                "f.WLead := 20.0; f.Order := 2;\n" + STEP + "HPF(f);", 8, ["f.Out"], 10.0)  # fmt: skip
    out = _col(rows, "f.Out")
    # s^2 / (s^2 + sqrt2 w s + w^2) step = second derivative of the low-pass step over w^2...
    # directly: Y = s / (s^2 + sqrt2 w s + w^2) = e^(-a t)(cos(b t) - sin(b t)), a = b = w/sqrt2
    for k in range(1, 8):
        a = 20.0 * 0.01 * k / math.sqrt(2.0)
        assert out[k] == pytest.approx(math.exp(-a) * (math.cos(a) - math.sin(a)), abs=1e-6)


def test_hpf_initialize_gives_zero_and_invalid_inputs(tmp_path: Path) -> None:
    body = "f.WLead := 0.0; f.Order := 0; f.In := 7.0; f.Initialize := TRUE;\nHPF(f);"
    rows = _run(tmp_path, "f : FILTER_HIGH_PASS;", body, 2, ["f.Out", "f.Status",
                "f.WLeadInv", "f.OrderInv"], 10.0)  # fmt: skip
    assert _col(rows, "f.Out") == [0.0, 0.0]  # steady state of a high-pass: 0
    assert _ints(rows, "f.Status") == [7, 7]  # WLeadInv bit 1, OrderInv bit 2, fault bit 0
    assert rows[1]["f.WLeadInv"] == "1" and rows[1]["f.OrderInv"] == "1"


# ------------------------------------------------------------------ LDLG
# LDLG is bilinear (decision 0171): with p = (2 Lag - dt)/(2 Lag + dt) and a = dt/(dt + 2 Lag),
# a unit step applied after a rest at 0 gives y_1 = a (1 + 0) and then
# y_k = 2a + p y_(k-1), whose fixed point is 1: y_k = 1 - (1 - a) p^(k-1).


def test_ldlg_pure_lag_with_gain_and_bias(tmp_path: Path) -> None:
    body = "f.Lag := 1.0; f.Gain := 2.0; f.Bias := 1.0;\n" + STEP + "LDLG(f);"
    rows = _run(tmp_path, "f : LEAD_LAG;", body, 6, ["f.Out", "f.Status"], 100.0)
    out = _col(rows, "f.Out")
    assert out[0] == 1.0  # steady state on In 0: 2 x 0 + 1
    a, p = 0.1 / 2.1, 1.9 / 2.1  # dt 0.1 s, Lag 1 s
    for k in range(1, 6):
        assert out[k] == pytest.approx(2 * (1 - (1 - a) * p ** (k - 1)) + 1, rel=1e-6)
    assert set(_ints(rows, "f.Status")) == {0}


def test_ldlg_matches_the_coefficients_of_a_running_controller(tmp_path: Path) -> None:
    # A running LDLG exported from a controller (FBDLevelControlSimulation.L5X in the real
    # export corpus: Lag 5 s, Lead 0, DeltaT 0.1 s) keeps two internal coefficients
    # 0.00990099 = dt/(dt + 2 Lag) and -0.980198 = (dt - 2 Lag)/(dt + 2 Lag): the bilinear
    # form. One step of 1 from rest: y_1 = 0.00990099 (1 + 0) = 0.00990099.
    body = "f.Lag := 5.0;\n" + STEP + "LDLG(f);"
    rows = _run(tmp_path, "f : LEAD_LAG;", body, 3, ["f.Out"], 100.0)
    a, p = 0.1 / 10.1, 9.9 / 10.1
    assert _col(rows, "f.Out")[1:] == pytest.approx([a, 2 * a + p * a], rel=1e-6)


def test_ldlg_lead_over_lag(tmp_path: Path) -> None:
    body = "f.Lead := 2.0; f.Lag := 1.0;\n" + STEP + "LDLG(f);"
    rows = _run(tmp_path, "f : LEAD_LAG;", body, 5, ["f.Out"], 100.0)
    out = _col(rows, "f.Out")
    # y_1 = ((0.1 + 4) x 1 + (0.1 - 4) x 0 - (0.1 - 2) x 0)/2.1 = 4.1/2.1;
    # then y_k = ((0.1 + 4) + (0.1 - 4) + 1.9 y_(k-1))/2.1 = (0.2 + 1.9 y_(k-1))/2.1,
    # fixed point 1: y_k = 1 + (4.1/2.1 - 1) p^(k-1), p = 1.9/2.1
    p = 1.9 / 2.1
    for k in range(1, 5):
        assert out[k] == pytest.approx(1 + (4.1 / 2.1 - 1) * p ** (k - 1), rel=1e-6)


def test_ldlg_initialize(tmp_path: Path) -> None:
    body = (
        "f.Lag := 1.0; f.Gain := 3.0; f.Bias := -1.0; f.In := 4.0; f.InitialValue := 10.0;\n"
        "f.Initialize := n = 2;\nLDLG(f);"
    )
    rows = _run(tmp_path, "f : LEAD_LAG;", body, 3, ["f.Out"], 100.0)
    out = _col(rows, "f.Out")
    assert out[0] == 11.0  # steady on In 4: 3 x 4 - 1
    assert out[1] == 29.0  # Initialize: 3 x 10 - 1, the lag at rest on 10
    # from rest on 10, In 4: y = (0.1 x 4 + 0.1 x 10 + 1.9 x 10)/2.1 = 20.4/2.1; x 3 - 1
    assert out[2] == pytest.approx(3 * 20.4 / 2.1 - 1, rel=1e-6)


def test_ldlg_invalid_time_constants(tmp_path: Path) -> None:
    # Lead -1: LeadInv (bit 1), taken as 0. Lag 0 < dt/2 = 0.05: LagInv (bit 2), taken as
    # 0.05: y = (0.1 u_n + 0.1 u_(n-1) - 0 y)/0.2, the mean of the last two inputs.
    body = "f.Lead := -1.0; f.Lag := 0.0; f.In := 10.0 * n;\nLDLG(f);"
    rows = _run(tmp_path, "f : LEAD_LAG;", body, 3, ["f.Out", "f.Status", "f.LeadInv",
                "f.LagInv"], 100.0)  # fmt: skip
    assert _ints(rows, "f.Status") == [3, 7, 7]  # scan 1 (DeltaT 0): Lag 0 is not below 0
    assert rows[2]["f.LeadInv"] == "1" and rows[2]["f.LagInv"] == "1"
    assert _col(rows, "f.Out") == pytest.approx([10.0, 15.0, 25.0])


# ------------------------------------------------------------------ DEDT
DEDT_DECL = "d : DEADTIME; buf : ARRAY[0..9] OF REAL;"


def test_dedt_delays_by_whole_scans(tmp_path: Path) -> None:
    body = "d.Deadtime := 0.3; d.Gain := 2.0; d.Bias := 1.0; d.In := n;\nDEDT(d, buf);"
    rows = _run(tmp_path, DEDT_DECL, body, 8, ["d.Out", "d.Status", "buf[0]"], 100.0)
    # 0.3 s / 0.1 s = 3 scans. Scan 1 fills the array with In 1: Out = 2 x 1 + 1 = 3.
    # Scans 2-4 read the filled 1s (3); scan k >= 5 reads In of scan k - 3 = k - 3:
    # Out = 2 (k - 3) + 1 -> 5, 7, 9, 11 for k = 5..8
    assert _col(rows, "d.Out") == [3.0, 3.0, 3.0, 3.0, 5.0, 7.0, 9.0, 11.0]
    assert set(_ints(rows, "d.Status")) == {0}
    assert _col(rows, "buf[0]")[1] == 2.0  # the ring starts at element 0 after the fill


def test_dedt_zero_deadtime_and_invalid_deadtime(tmp_path: Path) -> None:
    body = "d.Deadtime := 0.0; d.Gain := 1.0; d.In := n;\nDEDT(d, buf);"
    rows = _run(tmp_path, DEDT_DECL, body, 3, ["d.Out"], 100.0)
    assert _col(rows, "d.Out") == [1.0, 2.0, 3.0]  # no delay
    # 2 s > 10 elements x 0.1 s: DeadtimeInv (bit 2) + fault = 5, clamped to 10 scans:
    # Out stays on the fill value 1 until scan 12 reads In of scan 2
    body = "d.Deadtime := 2.0; d.Gain := 1.0; d.In := n;\nDEDT(d, buf);"
    rows = _run(tmp_path, DEDT_DECL, body, 13, ["d.Out", "d.Status", "d.DeadtimeInv"], 100.0)
    assert _col(rows, "d.Out") == [1.0] * 11 + [2.0, 3.0]
    assert _ints(rows, "d.Status")[1:] == [5] * 12 and rows[5]["d.DeadtimeInv"] == "1"
    body = "d.Deadtime := -1.0; d.Gain := 1.0; d.In := n;\nDEDT(d, buf);"
    rows = _run(tmp_path, DEDT_DECL, body, 3, ["d.Out", "d.Status"], 100.0)
    assert _col(rows, "d.Out") == [1.0, 2.0, 3.0] and _ints(rows, "d.Status")[1:] == [5, 5]


def test_dedt_in_fault_holds_then_restarts(tmp_path: Path) -> None:
    body = "d.Deadtime := 0.2; d.Gain := 1.0; d.In := 10.0 * n; d.InFault := n = 4;\nDEDT(d, buf);"
    rows = _run(tmp_path, DEDT_DECL, body, 7, ["d.Out", "d.Status", "d.InFaulted"], 100.0)
    # 2 scans of delay: 10 (fill), 10, 10, then InFault: held 10 with InFaulted (Status bit
    # 1, not a parameter fault); scan 5 re-fills with 50, scan 6 reads 50, scan 7 reads 50
    assert _col(rows, "d.Out") == [10.0, 10.0, 10.0, 10.0, 50.0, 50.0, 50.0]
    assert _ints(rows, "d.Status") == [0, 0, 0, 2, 0, 0, 0]
    assert _ints(rows, "d.InFaulted") == [0, 0, 0, 1, 0, 0, 0]


# ------------------------------------------------------------------ LDL2
def test_ldl2_first_order_step(tmp_path: Path) -> None:
    body = "f.WLead := 2.0; f.WLag := 10.0; f.Order := 1;\n" + STEP + "LDL2(f);"
    rows = _run(tmp_path, "f : LEAD_LAG_SEC_ORDER;", body, 6, ["f.Out", "f.Status"], 10.0)
    out = _col(rows, "f.Out")
    assert out[0] == 0.0
    # (s/2 + 1)/(s/10 + 1) = (5s + 10)/(s + 10); step: 1 + (10/2 - 1) e^(-10 t) = 1 + 4 e^(-10 t)
    for k in range(1, 6):
        assert out[k] == pytest.approx(1 + 4 * math.exp(-10 * 0.01 * k), rel=1e-6)
    assert set(_ints(rows, "f.Status")) == {0}


def test_ldl2_second_order_step(tmp_path: Path) -> None:
    body = (
        "f.WLead := 10.0; f.WLag := 20.0; f.ZetaLead := 0.0; f.ZetaLag := 1.0; f.Order := 2;\n"
        + STEP
        + "LDL2(f);"
    )
    rows = _run(tmp_path, "f : LEAD_LAG_SEC_ORDER;", body, 8, ["f.Out", "f.Status"], 10.0)
    out = _col(rows, "f.Out")
    # (s^2/a^2 + 1) w^2/(s + w)^2 with a = 10, w = 20 (ZetaLag 1: a double pole). Step:
    # 1 - e^(-w t)(1 + w t) + (w^2/a^2) e^(-w t)(1 - w t)   [L^-1 of s/(s+w)^2 = e^(-wt)(1 - wt)]
    for k in range(1, 8):
        t = 0.01 * k
        e = math.exp(-20 * t)
        want = 1 - e * (1 + 20 * t) + 4 * e * (1 - 20 * t)
        assert out[k] == pytest.approx(want, rel=1e-5, abs=1e-6)
    assert set(_ints(rows, "f.Status")) == {0}


def test_ldl2_ratio_damping_and_order_limits(tmp_path: Path) -> None:
    # order 1, WLag 30 > 40 x WLead 0.5 = 20: WLagRatioInv (bit 6) + fault = 65, WLag 20:
    # step 1 + (20/0.5 - 1) e^(-20 t) = 1 + 39 e^(-20 t)
    body = "f.WLead := 0.5; f.WLag := 30.0; f.Order := 1;\n" + STEP + "LDL2(f);"
    rows = _run(tmp_path, "f : LEAD_LAG_SEC_ORDER;", body, 2, ["f.Out", "f.Status",
                "f.WLagRatioInv"], 10.0)  # fmt: skip
    assert _col(rows, "f.Out")[1] == pytest.approx(1 + 39 * math.exp(-0.2), rel=1e-6)
    assert _ints(rows, "f.Status") == [65, 65] and rows[1]["f.WLagRatioInv"] == "1"
    # order 2: ZetaLead 5 > 4 (ZetaLeadInv, bit 3), ZetaLag 0.01 < 0.05 (ZetaLagInv, bit 4),
    # WLead 100 > 0.36 / 0.01 = 36 (WLeadInv, bit 1): 1 + 2 + 8 + 16 = 27
    body = "f.WLead := 100.0; f.WLag := 20.0; f.ZetaLead := 5.0; f.ZetaLag := 0.01; f.Order := 2;\nLDL2(f);"
    rows = _run(tmp_path, "f : LEAD_LAG_SEC_ORDER;", body, 2, ["f.Status"], 10.0)
    assert _ints(rows, "f.Status")[1] == 27
    # Order 3: OrderInv (bit 5) + fault = 33; WLag 0 with DeltaT 0.01 raised to its low
    # limit: WLagInv (bit 2) = 37 on scan 2
    body = "f.WLead := 1.0; f.Order := 3; f.In := 2.0;\nLDL2(f);"
    rows = _run(tmp_path, "f : LEAD_LAG_SEC_ORDER;", body, 2, ["f.Status", "f.OrderInv"], 10.0)
    assert _ints(rows, "f.Status") == [37, 37] and rows[1]["f.OrderInv"] == "1"


# ------------------------------------------------------------------ NTCH
def _notch_terms(t: float) -> tuple[float, float]:
    """For w = 20, Q = 2: alpha = w/2Q = 5, wd = w sqrt(1 - 1/4Q^2) = 5 sqrt15.
    g(t) = L^-1 of 1/((s + alpha)^2 + wd^2) = e^(-alpha t) sin(wd t)/wd;
    f'(t) with f = L^-1 of 1/((s + alpha)^2 + wd^2)^2 = e^(-alpha t)(sin wd t - wd t cos wd t)/2wd^3
    (the standard pair for 1/(s^2 + b^2)^2, shifted)."""
    a, wd = 5.0, 5.0 * math.sqrt(15.0)
    e, sn, cs = math.exp(-a * t), math.sin(wd * t), math.cos(wd * t)
    g = e * sn / wd
    fp = e * (-a * (sn - wd * t * cs) + wd * wd * t * sn) / (2 * wd**3)
    return g, fp


def test_ntch_second_order_step(tmp_path: Path) -> None:
    body = "f.WNotch := 20.0; f.QFactor := 2.0; f.Order := 2;\n" + STEP + "NTCH(f);"
    rows = _run(tmp_path, "f : FILTER_NOTCH;", body, 10, ["f.Out", "f.Status"], 10.0)
    out = _col(rows, "f.Out")
    # H = 1 - (w/Q) s / (s^2 + (w/Q) s + w^2): step = 1 - (w/Q) g(t), w/Q = 10
    for k in range(1, 10):
        assert out[k] == pytest.approx(1 - 10 * _notch_terms(0.01 * k)[0], rel=1e-5, abs=1e-6)
    assert set(_ints(rows, "f.Status")) == {0}


def test_ntch_fourth_order_step(tmp_path: Path) -> None:
    body = "f.WNotch := 20.0; f.QFactor := 2.0; f.Order := 4;\n" + STEP + "NTCH(f);"
    rows = _run(tmp_path, "f : FILTER_NOTCH;", body, 10, ["f.Out", "f.Status"], 10.0)
    out = _col(rows, "f.Out")
    # H^2 = (1 - G)^2 = 1 - 2G + G^2, G = (w/Q) s / D: step = 1 - 2 (w/Q) g + (w/Q)^2 f'
    for k in range(1, 10):
        g, fp = _notch_terms(0.01 * k)
        assert out[k] == pytest.approx(1 - 20 * g + 100 * fp, rel=1e-5, abs=1e-6)
    assert set(_ints(rows, "f.Status")) == {0}


def test_ntch_invalid_inputs(tmp_path: Path) -> None:
    # Order 3: OrderInv (bit 3); QFactor 0 < 0.5: QFactorInv (bit 2); WNotch 50 > 36:
    # WNotchInv (bit 1); with the fault: 15. A new tag's Order is 2 (no OrderInv).
    body = "f.WNotch := 50.0; f.Order := 3; f.In := 1.0;\nNTCH(f);"
    rows = _run(tmp_path, "f : FILTER_NOTCH;", body, 2, ["f.Out", "f.Status", "f.WNotchInv",
                "f.QFactorInv", "f.OrderInv"], 10.0)  # fmt: skip
    assert _ints(rows, "f.Status")[1] == 15
    assert [rows[1][f"f.{m}"] for m in ("WNotchInv", "QFactorInv", "OrderInv")] == ["1"] * 3
    assert _col(rows, "f.Out") == [1.0, 1.0]  # steady on a constant In: DC gain 1
    rows = _run(tmp_path, "f : FILTER_NOTCH;", "f.WNotch := 5.0; f.QFactor := 1.0;\nNTCH(f);", 1,
                ["f.Status"], 10.0)  # fmt: skip
    assert _ints(rows, "f.Status") == [0]


def test_a_change_of_order_reinitialises(tmp_path: Path) -> None:
    # NTCH at rest on In 2 with order 2, switched to order 4: the new (larger) state starts
    # from the steady state of In, so Out stays 2 instead of jumping on stale states
    body = "f.WNotch := 10.0; f.QFactor := 1.0; f.In := 2.0;\nIF n > 2 THEN f.Order := 4; END_IF;\nNTCH(f);"
    rows = _run(tmp_path, "f : FILTER_NOTCH;", body, 4, ["f.Out", "f.Status"], 10.0)
    assert _col(rows, "f.Out") == pytest.approx([2.0] * 4, rel=1e-6)
    assert set(_ints(rows, "f.Status")) == {0}


def test_exact_at_the_high_frequency_limit() -> None:
    # 1 ms periodic task, third-order LPF at its highest valid WLag 0.36 / 0.001 = 360 rad/s:
    # the samples still follow 1 - e^(-w t) - (2/sqrt3) e^(-w t/2) sin(sqrt3 w t/2)
    ix = struct_type("FILTER_LOW_PASS").index
    s = new_struct("FILTER_LOW_PASS", WLag=360.0, Order=3)
    ctx = ExecContext(task_period_ms=1.0)
    fb.lpf(ctx, True, s)  # initialises on In 0
    s[ix["IN"]] = 1.0
    for k in range(1, 11):
        fb.lpf(ctx, True, s)
        t = 0.001 * k
        want = (
            1
            - math.exp(-360 * t)
            - 2 / math.sqrt(3) * math.exp(-180 * t) * math.sin(math.sqrt(3) * 180 * t)
        )
        assert s[ix["OUT"]] == pytest.approx(want, abs=1e-6)
    assert s[ix["STATUS"]] == 0
