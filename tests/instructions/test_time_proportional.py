"""SRTP (time_proportional.py, decision 0183), expected values by hand. Scan periods and
cycle times are chosen as binary fractions (125 ms, 0.25 s) so the cycle timer's sums are
exact and the on/off edges fall where the arithmetic says."""

from __future__ import annotations

from pathlib import Path

from interpreter.instructions import time_proportional as tp
from interpreter.vm.context import ExecContext
from tests.instructions.run_cli import trace
from tests.instructions.structs import new_struct, struct_type

SI = struct_type("SPLIT_RANGE").index


def srtp(s: list, ctx: ExecContext | None = None, **members: object) -> list:
    for name, v in members.items():
        s[SI[name.upper()]] = v
    tp.srtp(ctx or ExecContext(), True, s)
    return s


def g(s: list, *names: str) -> tuple[object, ...]:
    return tuple(s[SI[n.upper()]] for n in names)


def test_heat_pulse_through_run(tmp_path: Path) -> None:
    src = (
        "VAR h : SPLIT_RANGE; END_VAR\n"
        "h.In := 87.5; h.CycleTime := 1.0; h.MaxHeatTime := 1.0; h.MaxCoolTime := 1.0;\n"
        "SRTP(h);\n"
    )
    watch = ["h.HeatOut", "h.CoolOut", "h.HeatTimePercent", "h.CoolTimePercent", "h.Status"]
    rows, report = trace(tmp_path, src, ".st", 17, watch, 125.0)
    # default ranges: heat 50..100 %, cool 50..0 %. In 87.5: heat (87.5 - 50) / 50 = 0.75 of
    # the 1 s cycle; cooling (87.5 - 50) / (0 - 50) < 0 -> 0. The timer is 0, .125, ... .875
    # in the first cycle: HeatOut on while below .75 (6 scans), off for 2, then again
    assert [r["h.HeatOut"] for r in rows] == (["1"] * 6 + ["0"] * 2) * 2 + ["1"]
    assert {r["h.CoolOut"] for r in rows} == {"0"}
    assert {(r["h.HeatTimePercent"], r["h.CoolTimePercent"]) for r in rows} == {("75.0", "0.0")}
    assert {r["h.Status"] for r in rows} == {"0"}
    assert report["diagnostics"] == []


def test_cooling_side_and_min_max_times() -> None:
    ctx = ExecContext(now_ms=0.0)
    s = new_struct("SPLIT_RANGE", CycleTime=2.0, MaxHeatTime=2.0, MaxCoolTime=1.0)
    srtp(s, ctx, In=0.0)  # full cooling: 2 s, limited to MaxCoolTime 1 s -> 50 %
    assert g(s, "CoolOut", "HeatOut", "CoolTimePercent") == (1, 0, 50.0)
    ctx.now_ms = 1000.0
    srtp(s, ctx)  # timer 1 s: not below 1 s -> off
    assert g(s, "CoolOut") == (0,)
    srtp(s, ctx, In=45.0, MinCoolTime=0.5)  # (45 - 50) / -50 = 0.1 x 2 s = 0.2 s < 0.5 -> 0
    assert g(s, "CoolOut", "CoolTimePercent") == (0, 0.0)
    srtp(s, ctx, In=25.0)  # 0.5 x 2 = 1 s >= 0.5: on time 1 s -> 50 %
    assert g(s, "CoolTimePercent") == (50.0,)
    ctx.now_ms = 2250.0
    srtp(s, ctx)  # timer 1 + 1.25 = 2.25 -> wraps to 0.25 < 1: on again
    assert g(s, "CoolOut") == (1,)


def test_cycle_time_zero_and_invalid_settings() -> None:
    ctx = ExecContext(now_ms=0.0)
    s = new_struct("SPLIT_RANGE", In=100.0, CycleTime=1.0, MaxHeatTime=1.0)
    srtp(s, ctx)
    assert g(s, "HeatOut", "HeatTimePercent") == (1, 100.0)
    srtp(s, ctx, CycleTime=0.0)  # CycleTime 0: both off, no fault
    assert g(s, "HeatOut", "CoolOut", "Status") == (0, 0, 0)
    srtp(s, ctx, CycleTime=-1.0)  # CycleTimeInv (bit 1) + InstructFault = 3, used as 0
    assert g(s, "HeatOut", "Status") == (0, 3)
    srtp(s, ctx, CycleTime=1.0, MaxHeatTime=5.0)  # beyond the cycle: bit 2 -> 5, uses 1 s
    assert g(s, "HeatOut", "HeatTimePercent", "Status") == (1, 100.0, 5)
    srtp(s, ctx, MaxHeatTime=0.5, MinHeatTime=0.75)  # min above max: bit 3 -> 9, uses 0
    assert g(s, "HeatTimePercent", "Status") == (50.0, 9)
    srtp(s, ctx, MinHeatTime=0.0, MaxCoolTime=-1.0, MinCoolTime=-1.0)  # bits 4, 5 -> 49
    assert g(s, "Status") == (49,)
    srtp(s, ctx, MaxCoolTime=0.0, MinCoolTime=0.0, MaxHeatIn=50.0)  # HeatSpanInv bit 6 -> 65
    assert g(s, "HeatOut", "HeatTimePercent", "Status") == (0, 0.0, 65)
    srtp(s, ctx, MaxHeatIn=100.0, MaxCoolIn=50.0)  # CoolSpanInv bit 7 -> 129
    assert g(s, "Status", "HeatOut") == (129, 1)


def test_prescan_restarts_the_cycle() -> None:
    ctx = ExecContext(now_ms=0.0)
    s = new_struct("SPLIT_RANGE", In=75.0, CycleTime=1.0, MaxHeatTime=1.0)
    srtp(s, ctx)
    ctx.now_ms = 750.0
    srtp(s, ctx)  # heat 0.5 s: timer .75 -> off
    assert g(s, "HeatOut") == (0,)
    tp.srtp_prescan(ctx, True, s)
    ctx.now_ms = 900.0
    srtp(s, ctx)  # a new cycle from 0: on
    assert g(s, "HeatOut") == (1,)
