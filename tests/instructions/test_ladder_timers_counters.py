"""TON / TOF / RTO / CTU / CTD / RES called directly; scans simulated by stepping ctx.now_ms.

Expected bit tables follow the 1756-RM003 flow charts (decision 0030).
"""

from __future__ import annotations

from interpreter.instructions import ladder_timers_counters as tc
from interpreter.vm.context import ExecContext
from tests.instructions.structs import new_struct

MAX = 2**31 - 1
MIN = -(2**31)


def _run(
    fn, ctx: ExecContext, t: list, steps: list[tuple[float, bool]]
) -> list[tuple[int, int, int, int]]:  # noqa: ANN001
    """Execute at each (scan start time, rung); record (ACC, EN, TT, DN) after each."""
    out = []
    for now, rung in steps:
        ctx.now_ms = now
        fn(ctx, rung, t, None, None)
        out.append((t[tc.ACC], t[tc.EN], t[tc.TT], t[tc.DN]))
    return out


# ------------------------------------------------------------------ TON
def test_ton_bit_table_10ms_scans() -> None:
    t = new_struct("TIMER", PRE=30)
    rec = _run(
        tc.ton,
        ExecContext(),
        t,
        [(0, True), (10, True), (20, True), (30, True), (40, True), (50, False)],
    )
    assert rec == [
        (0, 1, 1, 0),  # first true scan: EN, TT set, time remembered, ACC not advanced
        (10, 1, 1, 0),  # 10 ms later
        (20, 1, 1, 0),
        (30, 1, 0, 1),  # ACC 30 >= PRE 30: DN set, TT cleared
        (30, 1, 0, 1),  # done: nothing changes while the rung stays true
        (0, 0, 0, 0),  # false rung: everything cleared
    ]


def test_ton_acc_is_not_clamped_when_a_scan_overshoots() -> None:
    t = new_struct("TIMER", PRE=25)
    rec = _run(tc.ton, ExecContext(), t, [(0, True), (10, True), (20, True), (30, True)])
    # 0, 10, 20, then 20 + 10 = 30 >= 25: DN with ACC 30 (Logix adds the whole elapsed time)
    assert rec[-1] == (30, 1, 0, 1)


def test_ton_false_rung_mid_timing_restarts_from_zero() -> None:
    t = new_struct("TIMER", PRE=100)
    ctx = ExecContext()
    _run(tc.ton, ctx, t, [(0, True), (10, True), (20, True)])  # ACC 20
    rec = _run(tc.ton, ctx, t, [(30, False), (40, True), (50, True)])
    # cleared at 30; new first true scan at 40 (ACC 0); 10 ms later ACC 10
    assert rec == [(0, 0, 0, 0), (0, 1, 1, 0), (10, 1, 1, 0)]


def test_ton_sub_millisecond_scans_carry_the_fraction() -> None:
    t = new_struct("TIMER", PRE=100)
    ctx = ExecContext(scan_period_ms=0.4)
    rec = _run(tc.ton, ctx, t, [(0.4 * k, True) for k in range(9)])
    # after the first scan, k further scans = 0.4 k ms: ACC = floor(0.4 k)
    # k = 1..8 -> 0.4 0.8 1.2 1.6 2.0 2.4 2.8 3.2 -> 0 0 1 1 2 2 2 3
    assert [r[0] for r in rec] == [0, 0, 0, 1, 1, 2, 2, 2, 3]


def test_ton_acc_saturates_at_dint_max() -> None:
    t = new_struct("TIMER", PRE=MAX, ACC=MAX - 5, EN=1, TT=1, LastTime=0.0)
    rec = _run(tc.ton, ExecContext(), t, [(20, True)])
    # MAX - 5 + 20 overflows: ACC = 2147483647 = PRE -> done
    assert rec == [(MAX, 1, 0, 1)]


def test_ton_prescan_writes_pseudo_operands_then_clears() -> None:
    t = new_struct("TIMER", PRE=7, ACC=3, EN=1, TT=1, DN=1)
    tc.ton_prescan(ExecContext(), True, t, 500, 40)
    # Preset 500 written into PRE; prescan clears EN TT DN and ACC (the Accum 40 included)
    assert (t[tc.PRE], t[tc.ACC], t[tc.EN], t[tc.TT], t[tc.DN]) == (500, 0, 0, 0, 0)
    t[tc.PRE] = 9
    tc.ton_prescan(ExecContext(), True, t, None, None)  # `?` placeholders keep the tag's values
    assert t[tc.PRE] == 9


# ------------------------------------------------------------------ TOF
def test_tof_bit_table_10ms_scans() -> None:
    t = new_struct("TIMER")
    ctx = ExecContext()
    tc.tof_prescan(ctx, True, t, 20, 0)
    assert (t[tc.PRE], t[tc.ACC]) == (20, 20)  # prescan: ACC = PRE, bits clear
    rec = _run(
        tc.tof, ctx, t, [(0, False), (10, True), (20, False), (30, False), (40, False), (50, False)]
    )
    assert rec == [
        (20, 0, 0, 0),  # false rung with DN clear: nothing (no run-on at start-up)
        (0, 1, 0, 1),  # true: EN, DN set, TT clear, ACC cleared
        (0, 0, 1, 1),  # first false scan: EN cleared, TT set, time remembered
        (10, 0, 1, 1),  # 10 ms later
        (20, 0, 0, 0),  # ACC 20 >= PRE 20: DN and TT cleared
        (20, 0, 0, 0),  # stays timed out
    ]


def test_tof_true_rung_during_timing_restarts() -> None:
    t = new_struct("TIMER", PRE=50)
    ctx = ExecContext()
    _run(tc.tof, ctx, t, [(0, True), (10, False), (20, False)])  # ACC 10, timing
    rec = _run(tc.tof, ctx, t, [(30, True), (40, False), (50, False)])
    # true again: ACC 0, DN held; then a new off-delay from 40: ACC 0, then 10
    assert rec == [(0, 1, 0, 1), (0, 0, 1, 1), (10, 0, 1, 1)]


# ------------------------------------------------------------------ RTO
def test_rto_retains_acc_over_a_false_rung_until_res() -> None:
    t = new_struct("TIMER", PRE=30)
    ctx = ExecContext()
    rec = _run(
        tc.rto,
        ctx,
        t,
        [(0, True), (10, True), (20, False), (30, True), (40, True), (50, True), (60, False)],
    )
    assert rec == [
        (0, 1, 1, 0),
        (10, 1, 1, 0),
        (10, 0, 0, 0),  # false: EN, TT cleared, ACC kept
        (10, 1, 1, 0),  # new true period: time remembered, ACC not advanced
        (20, 1, 1, 0),
        (30, 1, 0, 1),  # 20 + 10 = 30 >= 30
        (30, 0, 0, 1),  # false: DN and ACC kept
    ]
    tc.res(ctx, True, t)
    assert (t[tc.ACC], t[tc.EN], t[tc.TT], t[tc.DN]) == (0, 0, 0, 0)


def test_rto_prescan_keeps_acc() -> None:
    t = new_struct("TIMER", PRE=30, ACC=12, EN=1, TT=1, DN=0)
    tc.rto_prescan(ExecContext(), True, t, None, None)
    assert (t[tc.ACC], t[tc.EN], t[tc.TT], t[tc.DN]) == (12, 0, 0, 0)


# ------------------------------------------------------------------ CTU / CTD
def _counts(fn, c: list, rungs: list[bool]) -> list[tuple[int, int, int]]:  # noqa: ANN001
    out = []
    for r in rungs:
        fn(ExecContext(), r, c, None, None)
        out.append((c[tc.C_ACC], c[tc.C_DN], c[tc.CU] if fn is tc.ctu else c[tc.CD]))
    return out


def test_ctu_counts_rising_edges_only_and_not_the_start_up_rung() -> None:
    c = new_struct("COUNTER")
    tc.ctu_prescan(ExecContext(), True, c, 2, 0)
    assert (c[tc.C_PRE], c[tc.CU]) == (2, 1)
    rec = _counts(tc.ctu, c, [True, False, True, True, False, True, True])
    # T at start-up (CU set by prescan): no count; F; T -> 1; held T; F; T -> 2 >= PRE: DN
    assert rec == [(0, 0, 1), (0, 0, 0), (1, 0, 1), (1, 0, 1), (1, 0, 0), (2, 1, 1), (2, 1, 1)]


def test_ctu_overflow_wraps_and_sets_ov() -> None:
    c = new_struct("COUNTER", PRE=10, ACC=MAX)
    tc.ctu(ExecContext(), True, c)
    # 2147483647 + 1 wraps to -2147483648; OV set; DN stays set while OV is set
    assert (c[tc.C_ACC], c[tc.OV], c[tc.UN], c[tc.C_DN]) == (MIN, 1, 0, 1)


def test_ctd_underflow_wraps_and_sets_un() -> None:
    c = new_struct("COUNTER", PRE=0, ACC=MIN)
    tc.ctd(ExecContext(), True, c)
    # -2147483648 - 1 wraps to 2147483647; UN set; DN clear while UN is set
    assert (c[tc.C_ACC], c[tc.OV], c[tc.UN], c[tc.C_DN]) == (MAX, 0, 1, 0)


def test_counting_back_over_the_wrap_undoes_the_flag() -> None:
    c = new_struct("COUNTER", PRE=5, ACC=MAX, UN=1)
    tc.ctu(ExecContext(), True, c)
    # the earlier underflow is undone: UN cleared, OV not set; -2147483648 < 5: DN clear
    assert (c[tc.C_ACC], c[tc.OV], c[tc.UN], c[tc.C_DN]) == (MIN, 0, 0, 0)


def test_ctd_counts_down_and_dn_follows_acc() -> None:
    c = new_struct("COUNTER")
    tc.ctd_prescan(ExecContext(), True, c, 0, 2)
    assert (c[tc.C_PRE], c[tc.C_ACC], c[tc.CD]) == (0, 2, 1)
    rec = _counts(tc.ctd, c, [False, True, False, True, False, True])
    # 2 -> 1 (DN: 1 >= 0) -> 0 (DN) -> -1 (DN clear)
    assert rec == [(2, 0, 0), (1, 1, 1), (1, 1, 0), (0, 1, 1), (0, 1, 0), (-1, 0, 1)]


def test_ctu_and_ctd_share_one_counter() -> None:
    c = new_struct("COUNTER", PRE=1)
    ctx = ExecContext()
    tc.ctu(ctx, True, c)  # 1
    tc.ctd(ctx, True, c)  # 0 (CD edge is separate from CU)
    tc.ctu(ctx, True, c)  # CU still set: no count
    assert (c[tc.C_ACC], c[tc.CU], c[tc.CD], c[tc.C_DN]) == (0, 1, 1, 0)


# ------------------------------------------------------------------ RES
def test_res_counter_and_control_and_false_rung() -> None:
    c = new_struct("COUNTER", PRE=3, ACC=9, CU=1, CD=1, DN=1, OV=1, UN=1)
    tc.res(ExecContext(), False, c)
    assert c[tc.C_ACC] == 9  # false rung: no action
    tc.res(ExecContext(), True, c)
    assert c == new_struct("COUNTER", PRE=3)  # PRE kept, everything else cleared
    k = new_struct("CONTROL", LEN=5, POS=3, EN=1, EU=1, DN=1, EM=1, ER=1, UL=1, IN=1, FD=1)
    tc.res(ExecContext(), True, k)
    assert k == new_struct("CONTROL", LEN=5)
    t = new_struct("TIMER", PRE=4, ACC=4, EN=1, DN=1, ACCFraction=0.5)
    tc.res(ExecContext(), True, t)
    assert (t[tc.PRE], t[tc.ACC], t[tc.EN], t[tc.DN], t[tc.FRAC]) == (4, 0, 0, 0, 0.0)
