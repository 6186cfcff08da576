"""INTG, DERV, RLIM (and the later drives blocks) through `logixst run` and on their tags
(decisions 0139, 0170, 0171). Expected values by hand: the input is constant over the
interval ending at each execution, so an integral grows by In x DeltaT per scan.

A lone .st file runs in the continuous task: the first scan's DeltaT is 0 and the block
initialises; every later DeltaT is the scan period.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from interpreter.instructions import drives_blocks as db
from interpreter.vm.context import ExecContext
from tests.instructions.run_cli import column as _col
from tests.instructions.run_cli import int_column as _ints
from tests.instructions.run_cli import run_each_scan as _run
from tests.instructions.structs import new_struct, struct_type


# ------------------------------------------------------------------ INTG
def test_intg_ramps_and_stops_at_the_high_limit(tmp_path: Path) -> None:
    body = (
        "g.IGain := 2.0; g.In := 3.0; g.InitialValue := 1.0; g.HighLimit := 3.0;"
        " g.LowLimit := -10.0;\nINTG(g);"
    )
    rows = _run(tmp_path, "g : INTEGRATOR;", body, 6, ["g.Out", "g.HighAlarm", "g.LowAlarm",
                "g.Status", "g.EnableOut"], 100.0)  # fmt: skip
    # scan 0: Out = InitialValue 1; each later scan adds 2 x 3 x 0.1 = 0.6:
    # 1.6, 2.2, 2.8, then 3.4 -> HighLimit 3 (HighAlarm), and 3.6 -> 3 again
    assert _col(rows, "g.Out") == pytest.approx([1.0, 1.6, 2.2, 2.8, 3.0, 3.0], rel=1e-6)
    assert _ints(rows, "g.HighAlarm") == [0, 0, 0, 0, 1, 1]
    assert set(_ints(rows, "g.LowAlarm")) == {0} and set(_ints(rows, "g.Status")) == {0}
    assert set(_ints(rows, "g.EnableOut")) == {1}


def test_intg_default_limits_do_not_clamp(tmp_path: Path) -> None:
    # a new INTEGRATOR tag: HighLimit / LowLimit default to the largest / most negative REAL
    rows = _run(tmp_path, "g : INTEGRATOR;", "g.IGain := 1.0; g.In := -5.0;\nINTG(g);", 3,
                ["g.Out", "g.Status"], 100.0)  # fmt: skip
    assert _col(rows, "g.Out") == pytest.approx([0.0, -0.5, -1.0], rel=1e-6)
    assert set(_ints(rows, "g.Status")) == {0}


def test_intg_hold_inputs_and_initialize(tmp_path: Path) -> None:
    body = (
        "g.IGain := 1.0; g.InitialValue := 10.0; g.HighLimit := 100.0; g.LowLimit := -100.0;\n"
        "IF n <= 3 THEN g.In := 5.0; ELSE g.In := -5.0; END_IF;\n"
        "g.HoldHigh := n = 2; g.HoldLow := n = 4; g.Initialize := n = 6;\nINTG(g);"
    )
    rows = _run(tmp_path, "g : INTEGRATOR;", body, 7, ["g.Out"], 100.0)
    # 10 | HoldHigh, In 5: stays 10 | +0.5 -> 10.5 | HoldLow, In -5: stays 10.5 |
    # -0.5 -> 10 | Initialize -> 10 | -0.5 -> 9.5
    assert _col(rows, "g.Out") == pytest.approx([10.0, 10.0, 10.5, 10.5, 10.0, 10.0, 9.5])


def test_intg_invalid_gain_and_limits(tmp_path: Path) -> None:
    body = "g.IGain := -1.0; g.In := 1.0; g.HighLimit := 100.0; g.LowLimit := -100.0;\nINTG(g);"
    rows = _run(tmp_path, "g : INTEGRATOR;", body, 3, ["g.Out", "g.Status", "g.IGainInv"], 100.0)
    assert _col(rows, "g.Out") == [0.0, 0.0, 0.0]  # IGain < 0: no integration
    assert _ints(rows, "g.Status") == [3, 3, 3] and rows[2]["g.IGainInv"] == "1"  # bits 0, 1
    # HighLimit 0 <= LowLimit 5: HighLowLimsInv (bit 2) + fault = 5, Out sits on LowLimit
    body = "g.IGain := 1.0; g.In := 1.0; g.HighLimit := 0.0; g.LowLimit := 5.0;\nINTG(g);"
    rows = _run(tmp_path, "g : INTEGRATOR;", body, 2, ["g.Out", "g.Status", "g.LowAlarm",
                "g.HighAlarm"], 100.0)  # fmt: skip
    assert _col(rows, "g.Out") == [5.0, 5.0] and _ints(rows, "g.Status") == [5, 5]
    # scan 1: InitialValue 0 <= LowLimit: LowAlarm; scan 2: 5 + 0.1 >= the (empty) top
    assert _ints(rows, "g.LowAlarm") == [1, 0] and _ints(rows, "g.HighAlarm") == [0, 1]


def test_intg_prescan_restarts_from_initial_value() -> None:
    ix = struct_type("INTEGRATOR").index
    g = new_struct("INTEGRATOR", IGain=1.0, In=2.0, InitialValue=4.0)
    ctx = ExecContext(task_period_ms=50.0)
    db.intg(ctx, True, g)
    db.intg(ctx, True, g)
    assert g[ix["OUT"]] == pytest.approx(4.1)  # 4 + 2 x 0.05
    db.intg_prescan(ctx, True, g)
    db.intg(ctx, True, g)
    assert g[ix["OUT"]] == 4.0


# ------------------------------------------------------------------ DERV
def test_derv_of_a_ramp_and_bypass(tmp_path: Path) -> None:
    body = "d.Gain := 2.0; d.In := 0.5 * n * n; d.ByPass := n = 5;\nDERV(d);"
    rows = _run(tmp_path, "d : DERIVATIVE;", body, 6, ["d.Out", "d.Status"], 100.0)
    out = _col(rows, "d.Out")
    assert out[0] == 0.0  # first execution only records In
    # scan k (n = k + 1): In goes 0.5 n^2; difference 0.5 (2n - 1), / 0.1 s, x Gain 2:
    # n=2: 0.5 x 3 / 0.1 x 2 = 30; n=3: 50; n=4: 70
    assert out[1:4] == pytest.approx([30.0, 50.0, 70.0])
    assert out[4] == 12.5  # ByPass: Out = In = 0.5 x 25
    assert out[5] == pytest.approx((18.0 - 12.5) / 0.1 * 2.0)  # back on the last In seen
    assert set(_ints(rows, "d.Status")) == {0}


def test_derv_timing_fault(tmp_path: Path) -> None:
    body = "d.Gain := 1.0; d.In := n; d.TimingMode := 7;\nDERV(d);"
    rows = _run(tmp_path, "d : DERIVATIVE;", body, 2, ["d.Out", "d.Status", "d.TimingModeInv"],
                100.0)  # fmt: skip
    assert _col(rows, "d.Out") == [0.0, 0.0]
    assert _ints(rows, "d.Status") == [2**27 + 1] * 2 and rows[1]["d.TimingModeInv"] == "1"


# ------------------------------------------------------------------ RLIM
def test_rlim_ramps_at_the_rates(tmp_path: Path) -> None:
    body = (
        "r.IncRate := 10.0; r.DecRate := 5.0;\n"
        "IF n = 1 THEN r.In := 0.0; ELSIF n <= 6 THEN r.In := 3.0; ELSE r.In := -1.0; END_IF;\n"
        "RLIM(r);"
    )
    rows = _run(tmp_path, "r : RATE_LIMITER;", body, 12, ["r.Out", "r.Status"], 100.0)
    # up by at most 10 x 0.1 = 1 per scan: 0, 1, 2, 3, 3, 3; then In -1, down by at most
    # 5 x 0.1 = 0.5 per scan: 2.5, 2, 1.5, 1, 0.5, 0
    want = [0.0, 1.0, 2.0, 3.0, 3.0, 3.0, 2.5, 2.0, 1.5, 1.0, 0.5, 0.0]
    assert _col(rows, "r.Out") == pytest.approx(want)
    assert set(_ints(rows, "r.Status")) == {0}


def test_rlim_bypass_first_scan_and_invalid_rates(tmp_path: Path) -> None:
    body = "r.IncRate := 1.0; r.DecRate := 1.0; r.In := 10.0 * n; r.ByPass := n = 3;\nRLIM(r);"
    rows = _run(tmp_path, "r : RATE_LIMITER;", body, 4, ["r.Out"], 100.0)
    # first scan: Out = In = 10; then +0.1: 10.1; ByPass: 30; then +0.1: 30.1
    assert _col(rows, "r.Out") == pytest.approx([10.0, 10.1, 30.0, 30.1])
    body = "r.IncRate := -1.0; r.DecRate := -2.0; r.In := 10.0 * n;\nRLIM(r);"
    rows = _run(tmp_path, "r : RATE_LIMITER;", body, 3, ["r.Out", "r.Status", "r.IncRateInv",
                "r.DecRateInv"], 100.0)  # fmt: skip
    # first scan initialises to In (10); then the invalid rates leave Out alone
    assert _col(rows, "r.Out") == [10.0, 10.0, 10.0]
    assert _ints(rows, "r.Status") == [7, 7, 7]  # IncRateInv bit 1, DecRateInv bit 2, fault
    assert rows[2]["r.IncRateInv"] == "1" and rows[2]["r.DecRateInv"] == "1"
