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


# ------------------------------------------------------------------ POSP
PI = struct_type("POSITION_PROP").index


def posp(s: list, ctx: ExecContext | None = None, **members: object) -> list:
    for name, v in members.items():
        s[PI[name.upper()]] = v
    tp.posp(ctx or ExecContext(), True, s)
    return s


def gp(s: list, *names: str) -> tuple[object, ...]:
    return tuple(s[PI[n.upper()]] for n in names)


def _valve(**members: object) -> list:
    base: dict[str, object] = dict(
        PositionEUMax=200.0, CycleTime=4.0, OpenRate=10.0, CloseRate=5.0,
        MaxOnTime=4.0, MinOnTime=0.5, Deadtime=0.25,
    )  # fmt: skip
    return new_struct("POSITION_PROP", **(base | members))


def test_open_pulse_through_run(tmp_path: Path) -> None:
    src = (
        "VAR v : POSITION_PROP; END_VAR\n"
        "v.SP := 100.0; v.Position := 60.0; v.PositionEUMax := 200.0; v.CycleTime := 4.0;\n"
        "v.OpenRate := 10.0; v.CloseRate := 5.0; v.MaxOnTime := 4.0; v.MinOnTime := 0.5;\n"
        "v.Deadtime := 0.25;\nPOSP(v);\n"
    )
    watch = ["v.OpenOut", "v.CloseOut", "v.OpenTime", "v.SPPercent", "v.PositionPercent"]
    rows, report = trace(tmp_path, src, ".st", 17, watch, 250.0)
    # SP 100 of 0..200 = 50 %, position 60 = 30 %: 20 % to open at 10 %/s = 2 s, + 0.25 s
    # dead time = 2.25 s of the 4 s cycle. 250 ms scans: timer 0 .. 2.0 below 2.25 (9 scans
    # on), 2.25 .. 3.75 off (7), then the next cycle starts at 4 s
    assert [r["v.OpenOut"] for r in rows] == ["1"] * 9 + ["0"] * 7 + ["1"]
    assert {r["v.CloseOut"] for r in rows} == {"0"}
    assert {(r["v.OpenTime"], r["v.SPPercent"], r["v.PositionPercent"]) for r in rows} == {
        ("2.25", "50.0", "30.0")
    }
    assert report["diagnostics"] == []


def test_close_pulse_limits_and_end_feedbacks() -> None:
    s = _valve(SP=40.0, Position=100.0)  # 20 % - 50 % = -30 %: close 30 / 5 + .25 = 6.25 s
    posp(s)
    assert gp(s, "CloseTime", "OpenTime", "CloseOut") == (4.0, 0.0, 1)  # limited to 4 s
    posp(s, ClosedFB=1)  # already fully closed: no close pulse
    assert gp(s, "CloseOut", "CloseTime") == (0, 4.0)
    posp(s, ClosedFB=0, SP=99.0)  # 49.5 - 50 = -0.5 %: 0.1 + 0.25 = 0.35 s < MinOnTime 0.5
    assert gp(s, "CloseTime", "CloseOut") == (0.0, 0)
    posp(s, SP=160.0, OpenedFB=1)  # 80 - 50 = 30 %: 3 + .25 s to open, but fully open
    assert gp(s, "OpenTime", "OpenOut") == (3.25, 0)


def test_posp_invalid_settings() -> None:
    s = _valve(SP=120.0, Position=100.0)
    posp(s, OpenRate=0.0)  # OpenRateInv bit 2 + InstructFault = 5; no open pulse
    assert gp(s, "Status", "OpenOut") == (5, 0)
    posp(s, OpenRate=10.0, CloseRate=-1.0)  # bit 3 -> 9
    assert gp(s, "Status", "OpenOut") == (9, 1)
    posp(s, CloseRate=5.0, MaxOnTime=9.0)  # above the 4 s cycle: bit 4 -> 17, uses 4 s
    assert gp(s, "Status") == (17,)
    posp(s, MaxOnTime=1.0, MinOnTime=2.0)  # min above max: bit 5 -> 33, uses 0
    # 10 % / 10 + .25 = 1.25 s, limited to MaxOnTime 1 s
    assert gp(s, "Status", "OpenTime") == (33, 1.0)
    posp(s, MinOnTime=0.0, Deadtime=-1.0)  # bit 6 -> 65, dead time 0: 1 s
    assert gp(s, "Status", "OpenTime") == (65, 1.0)
    posp(s, Deadtime=0.0, Position=220.0)  # 110 %: PositionPctInv bit 7 -> 129
    assert gp(s, "Status", "PositionPercent") == (129, 110.0)
    posp(s, Position=100.0, SP=-20.0)  # -10 %: SPPercentInv bit 8 -> 257
    assert gp(s, "Status", "SPPercent") == (257, -10.0)
    posp(s, SP=100.0, PositionEUMin=200.0)  # no span: bit 9 -> 513, no pulses
    assert gp(s, "Status", "OpenOut", "CloseOut") == (513, 0, 0)
    posp(s, PositionEUMin=0.0, CycleTime=-4.0)  # CycleTimeInv bit 1 -> 3, outputs off
    assert gp(s, "Status", "OpenOut", "CloseOut") == (3, 0, 0)
