"""TONR / TOFR / RTOR / CTUD / OSRI / OSFI called directly, scans simulated with ctx.now_ms."""

from __future__ import annotations

from interpreter.instructions import fbd_timers as fb
from interpreter.vm.context import ExecContext
from tests.instructions.structs import new_struct, struct_type


def _new(type_name: str, **members: object) -> tuple[list, dict[str, int]]:
    """The value and its member index (tests set members by name between executions)."""
    return new_struct(type_name, **members), struct_type(type_name).index


def _run(fn, ctx: ExecContext, v: list, times: list[float]) -> list[tuple[int, int, int, int]]:
    """Execute once per given scan start time; record (ACC, EN, TT, DN) after each."""
    out = []
    for now in times:
        ctx.now_ms = now
        fn(ctx, True, v)
        out.append((v[fb.T_ACC], v[fb.T_EN], v[fb.T_TT], v[fb.T_DN]))
    return out


# ------------------------------------------------------------------ TONR
def test_tonr_reaches_preset_on_51st_execution_and_clamps() -> None:
    t, _ = _new("FBD_TIMER", PRE=500, TimerEnable=1)
    ctx = ExecContext(scan_period_ms=10.0)
    # PRE 500, 10 ms scans: ACC = 0, 10, ..., 500 -> 500 at the 51st execution (t = 500 ms).
    rec = _run(fb.tonr, ctx, t, [10.0 * k for k in range(53)])
    assert rec[0] == (0, 1, 1, 0)
    assert rec[49] == (490, 1, 1, 0)
    assert rec[50] == (500, 1, 0, 1)
    # two more scans: ACC stays at PRE (clamped), DN stays on
    assert rec[52] == (500, 1, 0, 1)
    assert t[fb.T_EOUT] == 1 and t[fb.T_STATUS] == 0


def test_tonr_acc_stops_at_preset_when_a_scan_overshoots() -> None:
    t, _ = _new("FBD_TIMER", PRE=25, TimerEnable=1)
    # 10 ms scans: 0, 10, 20, then 20 + 10 = 30 > PRE 25 -> ACC held at 25, DN on
    rec = _run(fb.tonr, ExecContext(), t, [0.0, 10.0, 20.0, 30.0, 40.0])
    assert [r[0] for r in rec] == [0, 10, 20, 25, 25]
    assert rec[3] == (25, 1, 0, 1)


def test_tonr_disable_resets_and_reset_mid_way() -> None:
    t, idx = _new("FBD_TIMER", PRE=100, TimerEnable=1)
    ctx = ExecContext()
    _run(fb.tonr, ctx, t, [0.0, 10.0, 20.0, 30.0])  # ACC 0,10,20,30
    assert t[fb.T_ACC] == 30
    t[idx["RESET"]] = 1
    rec = _run(fb.tonr, ctx, t, [40.0])
    # Reset: EN, TT, DN cleared and ACC = 0 although TimerEnable is still set
    assert rec[-1] == (0, 0, 0, 0)
    t[idx["RESET"]] = 0
    # Reset released with TimerEnable set: timing begins again from 0 (RM003)
    rec = _run(fb.tonr, ctx, t, [50.0, 60.0])
    assert rec == [(0, 1, 1, 0), (10, 1, 1, 0)]
    t[idx["TIMERENABLE"]] = 0
    assert _run(fb.tonr, ctx, t, [70.0]) == [(0, 0, 0, 0)]


def test_tonr_sub_millisecond_scans_carry_the_fraction() -> None:
    t, _ = _new("FBD_TIMER", PRE=10, TimerEnable=1)
    ctx = ExecContext(scan_period_ms=0.4)
    # 0.4 ms scans: after k further executions 0.4*k ms have passed; ACC = floor(0.4*k)
    # k = 5 -> 2.0 ms -> ACC 2; k = 7 -> 2.8 ms -> ACC 2; k = 8 -> 3.2 ms -> ACC 3.
    rec = _run(fb.tonr, ctx, t, [0.4 * k for k in range(9)])
    assert [r[0] for r in rec] == [0, 0, 0, 1, 1, 2, 2, 2, 3]


def test_tonr_zero_preset_is_done_at_once() -> None:
    t, _ = _new("FBD_TIMER", PRE=0, TimerEnable=1)
    # PRE 0: ACC 0 >= PRE 0 on the first enabled execution
    assert _run(fb.tonr, ExecContext(), t, [0.0]) == [(0, 1, 0, 1)]


def test_tonr_negative_preset_sets_status_and_does_not_run() -> None:
    t, idx = _new("FBD_TIMER", PRE=-1, TimerEnable=1)
    ctx = ExecContext()
    rec = _run(fb.tonr, ctx, t, [0.0, 10.0])
    assert rec[-1] == (0, 0, 0, 0)  # nothing executed
    # Status = PresetInv (bit 1) + InstructFault (bit 0) = 2 + 1 = 3
    assert t[fb.T_STATUS] == 3 and t[fb.T_FAULT] == 1 and t[fb.T_PRESET_INV] == 1
    assert t[fb.T_EOUT] == 0
    t[idx["PRE"]] = 20
    rec = _run(fb.tonr, ctx, t, [20.0])
    assert rec[-1] == (0, 1, 1, 0) and t[fb.T_STATUS] == 0 and t[fb.T_PRESET_INV] == 0


def test_timer_counts_time_between_executions_even_if_skipped() -> None:
    t, _ = _new("FBD_TIMER", PRE=1000, TimerEnable=1)
    # executed at 0 and then at 250 ms (not reached in between): ACC = 250 - 0 = 250
    assert _run(fb.tonr, ExecContext(), t, [0.0, 250.0])[-1][0] == 250


# ------------------------------------------------------------------ RTOR
def test_rtor_retains_acc_across_off_periods() -> None:
    t, idx = _new("FBD_TIMER", PRE=50, TimerEnable=1)
    ctx = ExecContext()
    _run(fb.rtor, ctx, t, [0.0, 10.0, 20.0])  # ACC 0, 10, 20
    t[idx["TIMERENABLE"]] = 0
    rec = _run(fb.rtor, ctx, t, [30.0, 40.0, 90.0])
    # off: ACC kept at 20, EN/TT off; the 70 ms spent off are not counted
    assert rec == [(20, 0, 0, 0)] * 3
    t[idx["TIMERENABLE"]] = 1
    rec = _run(fb.rtor, ctx, t, [100.0, 110.0, 120.0, 130.0, 140.0])
    # back on at 100: first execution restarts the clock (ACC 20), then +10 per scan:
    # 20, 30, 40, 50 (= PRE, done), then clamped at 50
    assert [r[0] for r in rec] == [20, 30, 40, 50, 50]
    assert rec[3] == (50, 1, 0, 1)
    t[idx["TIMERENABLE"]] = 0
    # DN is retained while disabled
    assert _run(fb.rtor, ctx, t, [150.0]) == [(50, 0, 0, 1)]
    t[idx["RESET"]] = 1
    assert _run(fb.rtor, ctx, t, [160.0]) == [(0, 0, 0, 0)]


# ------------------------------------------------------------------ TOFR
def test_tofr_off_delay() -> None:
    t, idx = _new("FBD_TIMER", PRE=30, TimerEnable=1)
    ctx = ExecContext()
    assert _run(fb.tofr, ctx, t, [0.0]) == [(0, 1, 0, 1)]  # on: EN and DN set, ACC 0
    t[idx["TIMERENABLE"]] = 0
    rec = _run(fb.tofr, ctx, t, [10.0, 20.0, 30.0, 40.0, 50.0])
    # falling edge at 10 ms: ACC 0, TT on; then 10, 20, 30 (= PRE at t = 40): DN off
    assert rec == [(0, 0, 1, 1), (10, 0, 1, 1), (20, 0, 1, 1), (30, 0, 0, 0), (30, 0, 0, 0)]


def test_tofr_reenable_restarts_and_reset_with_input_off_stays_idle() -> None:
    t, idx = _new("FBD_TIMER", PRE=30, TimerEnable=1)
    ctx = ExecContext()
    _run(fb.tofr, ctx, t, [0.0])
    t[idx["TIMERENABLE"]] = 0
    _run(fb.tofr, ctx, t, [10.0, 20.0])  # ACC 0 then 10
    t[idx["TIMERENABLE"]] = 1
    assert _run(fb.tofr, ctx, t, [30.0]) == [(0, 1, 0, 1)]  # back on: ACC 0, DN on
    t[idx["TIMERENABLE"]] = 0
    t[idx["RESET"]] = 1
    assert _run(fb.tofr, ctx, t, [40.0]) == [(0, 0, 0, 0)]
    t[idx["RESET"]] = 0
    # RM003: TimerEnable off while Reset set -> timing does not begin when Reset clears
    assert _run(fb.tofr, ctx, t, [50.0, 60.0]) == [(0, 0, 0, 0)] * 2


def test_timer_prescans() -> None:
    ctx = ExecContext()
    t, _ = _new("FBD_TIMER", PRE=40, ACC=25, EN=1, TT=1, DN=1)
    fb.tonr_prescan(ctx, True, t)
    assert (t[fb.T_ACC], t[fb.T_EN], t[fb.T_TT], t[fb.T_DN]) == (0, 0, 0, 0)
    t, _ = _new("FBD_TIMER", PRE=40, ACC=25, EN=1, TT=1, DN=1)
    fb.rtor_prescan(ctx, True, t)
    assert (t[fb.T_ACC], t[fb.T_EN], t[fb.T_TT], t[fb.T_DN]) == (25, 0, 0, 0)
    t, _ = _new("FBD_TIMER", PRE=40, ACC=25, EN=1, TT=1, DN=1)
    fb.tofr_prescan(ctx, True, t)
    assert (t[fb.T_ACC], t[fb.T_EN], t[fb.T_TT], t[fb.T_DN]) == (40, 0, 0, 0)


# ------------------------------------------------------------------ CTUD
def _pulse(c: list, idx: dict[str, int], member: str, ctx: ExecContext) -> None:
    c[idx[member]] = 1
    fb.ctud(ctx, True, c)
    c[idx[member]] = 0
    fb.ctud(ctx, True, c)


def test_ctud_counts_edges_only() -> None:
    c, idx = _new("FBD_COUNTER", PRE=2)
    ctx = ExecContext()
    c[idx["CUENABLE"]] = 1
    for _ in range(3):  # held true for 3 executions: one rising edge -> ACC 1
        fb.ctud(ctx, True, c)
    assert c[fb.C_ACC] == 1 and c[fb.C_CU] == 1 and c[fb.C_DN] == 0
    c[idx["CUENABLE"]] = 0
    fb.ctud(ctx, True, c)
    _pulse(c, idx, "CUENABLE", ctx)  # second edge: ACC 2 >= PRE 2 -> DN
    assert c[fb.C_ACC] == 2 and c[fb.C_DN] == 1
    _pulse(c, idx, "CDENABLE", ctx)  # down edge: ACC 1 < 2 -> DN off
    assert c[fb.C_ACC] == 1 and c[fb.C_DN] == 0
    # both rise in the same execution: +1 then -1 -> ACC unchanged (1)
    c[idx["CUENABLE"]] = c[idx["CDENABLE"]] = 1
    fb.ctud(ctx, True, c)
    assert c[fb.C_ACC] == 1 and c[fb.C_CU] == 1 and c[fb.C_CD] == 1


def test_ctud_overflow_and_underflow_wrap() -> None:
    c, idx = _new("FBD_COUNTER", PRE=0, ACC=2147483647)
    ctx = ExecContext()
    _pulse(c, idx, "CUENABLE", ctx)
    # 2147483647 + 1 wraps to -2147483648 and sets OV; DN: -2147483648 >= 0 is false
    assert c[fb.C_ACC] == -2147483648 and c[fb.C_OV] == 1 and c[fb.C_DN] == 0
    _pulse(c, idx, "CDENABLE", ctx)
    # counting back down across the limit cancels the overflow: ACC 2147483647, OV off
    assert c[fb.C_ACC] == 2147483647 and c[fb.C_OV] == 0 and c[fb.C_UN] == 0

    c, idx = _new("FBD_COUNTER", PRE=0, ACC=-2147483648)
    _pulse(c, idx, "CDENABLE", ctx)
    # -2147483648 - 1 wraps to 2147483647 and sets UN; DN: 2147483647 >= 0
    assert c[fb.C_ACC] == 2147483647 and c[fb.C_UN] == 1 and c[fb.C_DN] == 1


def test_ctud_reset_clears_history_so_held_input_counts_again() -> None:
    c, idx = _new("FBD_COUNTER", PRE=5, CUEnable=1)
    ctx = ExecContext()
    fb.ctud(ctx, True, c)  # ACC 1
    c[idx["RESET"]] = 1
    fb.ctud(ctx, True, c)
    assert c[fb.C_ACC] == 0 and c[fb.C_CU] == 0 and c[fb.C_UP_PREV] == 0
    c[idx["RESET"]] = 0
    fb.ctud(ctx, True, c)  # CUEnable still 1, history cleared by Reset -> counts: ACC 1
    assert c[fb.C_ACC] == 1


def test_ctud_prescan_blocks_count_of_input_true_at_start() -> None:
    c, _ = _new("FBD_COUNTER", PRE=5, CUEnable=1)
    ctx = ExecContext()
    fb.ctud_prescan(ctx, True, c)
    fb.ctud(ctx, True, c)
    assert c[fb.C_ACC] == 0


# ------------------------------------------------------------------ OSRI / OSFI
def test_osri_pulses_once_over_three_executions() -> None:
    o, _ = _new("FBD_ONESHOT", InputBit=1)
    ctx = ExecContext()
    outs = []
    for _ in range(3):
        fb.osri(ctx, True, o)
        outs.append(o[fb.O_OUT])
    assert outs == [1, 0, 0]  # rising edge only in the first execution
    o[fb.O_IN] = 0
    fb.osri(ctx, True, o)
    o[fb.O_IN] = 1
    fb.osri(ctx, True, o)
    assert o[fb.O_OUT] == 1 and o[fb.O_EOUT] == 1  # a new edge after the input dropped


def test_osri_prescan_suppresses_pulse_for_input_true_at_run() -> None:
    o, _ = _new("FBD_ONESHOT", InputBit=1, OutputBit=1)
    ctx = ExecContext()
    fb.osri_prescan(ctx, True, o)
    assert o[fb.O_OUT] == 0
    fb.osri(ctx, True, o)
    assert o[fb.O_OUT] == 0


def test_osfi_pulses_on_falling_edge() -> None:
    o, _ = _new("FBD_ONESHOT")
    ctx = ExecContext()
    fb.osfi_prescan(ctx, True, o)
    outs = []
    for bit in (0, 1, 1, 0, 0, 1, 0):
        o[fb.O_IN] = bit
        fb.osfi(ctx, True, o)
        outs.append(o[fb.O_OUT])
    # falls at the 4th and 7th executions only
    assert outs == [0, 0, 0, 1, 0, 0, 1]
