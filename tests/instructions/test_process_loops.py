"""SCL and PID against hand-worked numbers (1756-RM006 SCL formula, 1756-RM003 PID equations).

Decision 0031. PID numbers use the values Studio's PID dialog proposes unless a test sets
others: MINS 0 / MAXS 100 and MINI 0 / MAXI 100 (so PV is unscaled and 1 EU is 1 % of span),
MINCV 0 / MAXCV 100 (so CV equals OUT), MINO 0 / MAXO 100.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from interpreter.instructions import process_loops as pl
from interpreter.semantics.types import DINT, REAL
from interpreter.vm.context import ExecContext
from interpreter.vm.refs import Ref
from interpreter.vm.values import f32
from tests.instructions.run_cli import trace
from tests.instructions.structs import new_struct, struct_type

S = struct_type("SCALE").index
P = struct_type("PID").index


# ------------------------------------------------------------------ SCL
def _scl(**members: object) -> list:
    s = new_struct("SCALE", **members)
    pl.scl(ExecContext(), True, s)
    return s


def test_scl_maps_the_raw_range_linearly() -> None:
    s = _scl(In=2048.0, InRawMin=0.0, InRawMax=4095.0, InEUMin=0.0, InEUMax=100.0)
    # 2048 x 100 / 4095 = 50.01221...
    assert s[S["OUT"]] == pytest.approx(50.012210, rel=1e-6)
    assert (s[S["MAXALARM"]], s[S["MINALARM"]], s[S["STATUS"]], s[S["ENABLEOUT"]]) == (0, 0, 0, 1)


def test_scl_matches_a_real_controller_snapshot() -> None:
    # A SCALE tag exported from a running project (reh3376/acd-l5x-tool-lib, Mashing01 FBD
    # program) holds In 183.42, raw 0..50000, EU 1..50000 and the controller's Out 184.41632:
    # 183.42 x 49999 / 50000 + 1 = 184.4163...
    s = _scl(In=f32(183.42), InRawMin=0.0, InRawMax=50000.0, InEUMin=1.0, InEUMax=50000.0)
    assert s[S["OUT"]] == pytest.approx(184.41632, abs=1e-4)


def test_scl_reversed_engineering_range() -> None:
    # 4..20 mA onto 100..0 %: (8 - 4) x (0 - 100) / 16 + 100 = 75
    s = _scl(In=8.0, InRawMin=4.0, InRawMax=20.0, InEUMin=100.0, InEUMax=0.0)
    assert s[S["OUT"]] == 75.0


def test_scl_alarms_and_limiting() -> None:
    # In 25 above the raw range: (25 - 4) x (0 - 100) / 16 + 100 = -31.25 unlimited
    s = _scl(In=25.0, InRawMin=4.0, InRawMax=20.0, InEUMin=100.0, InEUMax=0.0)
    assert (s[S["OUT"]], s[S["MAXALARM"]], s[S["MINALARM"]]) == (-31.25, 1, 0)
    # with Limiting the alarmed output is held at InEUMax (0), below the range at InEUMin (100)
    s = _scl(In=25.0, InRawMin=4.0, InRawMax=20.0, InEUMin=100.0, InEUMax=0.0, Limiting=1)
    assert (s[S["OUT"]], s[S["MAXALARM"]]) == (0.0, 1)
    s = _scl(In=2.0, InRawMin=4.0, InRawMax=20.0, InEUMin=100.0, InEUMax=0.0, Limiting=1)
    assert (s[S["OUT"]], s[S["MINALARM"]], s[S["MAXALARM"]]) == (100.0, 1, 0)


def test_scl_invalid_raw_range_leaves_out_alone() -> None:
    s = _scl(In=3.0, InRawMin=5.0, InRawMax=5.0, InEUMax=10.0, Out=7.5)
    assert (s[S["OUT"]], s[S["INRAWRANGEINV"]], s[S["STATUS"]]) == (7.5, 1, 2)


def test_scl_through_run(tmp_path: Path) -> None:
    src = (
        "VAR s : SCALE; out : REAL; END_VAR\n"
        "s.In := 12.0; s.InRawMin := 4.0; s.InRawMax := 20.0; s.InEUMin := 0.0; s.InEUMax := 250.0;\n"
        "SCL(s);\nout := s.Out;\n"
    )
    rows, report = trace(tmp_path, src, ".st", 1, ["out"])
    assert rows[0]["out"] == "125.0"  # (12 - 4) x 250 / 16
    assert report["diagnostics"] == []


def test_scl_enable_out_may_be_written_and_scl_sets_it_again(tmp_path: Path) -> None:
    # W-P-I/FunctionBlocks PF525_V2 (v33) writes `ScaleSP.EnableOut := EnableOut;` and Studio
    # verified it: the member is writable. Written 0 it reads 0 until SCL executes, which
    # sets it to 1 (ST always executes the block).
    src = (
        "VAR s : SCALE; before, after : BOOL; END_VAR\n"
        "s.EnableOut := 0; before := s.EnableOut; s.InRawMax := 1.0;\n"
        "SCL(s);\nafter := s.EnableOut;\n"
    )
    rows, report = trace(tmp_path, src, ".st", 1, ["before", "after"])
    assert (rows[0]["before"], rows[0]["after"]) == ("0", "1")
    assert report["diagnostics"] == []


def test_scl_out_stays_read_only(tmp_path: Path) -> None:
    src = "VAR s : SCALE; END_VAR\ns.Out := 1.0;\n"
    _rows, report = trace(tmp_path, src, ".st", 1, [], expect_code=1)
    assert [d["code"] for d in report["diagnostics"]] == ["E120"]


# ------------------------------------------------------------------ PID
def _pid(**members: object) -> list:
    dialog: dict[str, object] = {"MAXS": 100.0, "MAXI": 100.0, "MAXO": 100.0, "MAXCV": 100.0}
    return new_struct("PID", **(dialog | {"MAXTIE": 100.0} | members))


def _exec(p: list, pv: float, ctx: ExecContext | None = None, cv_type=REAL) -> float:  # type: ignore[no-untyped-def]
    cell = [0]
    pl.pid(ctx or ExecContext(), True, p, pv, 0, Ref(cell, 0, cv_type), None, 0, 0)
    return cell[0]  # type: ignore[no-any-return]


def test_pid_independent_pi() -> None:
    p = _pid(KP=2.0, KI=0.5, UPD=0.1, SP=50.0)
    # E = 50 - 40 = 10; P = 2 x 10 = 20; I grows by KI x E x UPD = 0.5 x 10 x 0.1 = 0.5 a time
    assert [_exec(p, 40.0) for _ in range(3)] == pytest.approx([20.5, 21.0, 21.5])
    assert (p[P["PV"]], p[P["ERR"]], p[P["OUT"]]) == (40.0, 10.0, 21.5)
    assert p[P["INI"]] == 1 and p[P["EN"]] == 1


def test_pid_derivative_of_error_and_of_pv() -> None:
    # KD 0.2 s: the first execution has no derivative; then PV 40 -> 38: E 10 -> 12
    # P = 24, I = 0.5 + 0.5 x 12 x 0.1 = 1.1, D = 0.2 x (12 - 10) / 0.1 = 4 -> 29.1
    for doe in (0, 1):  # with a fixed SP both derivatives agree
        p = _pid(KP=2.0, KI=0.5, KD=0.2, UPD=0.1, SP=50.0, DOE=doe)
        assert _exec(p, 40.0) == pytest.approx(20.5)
        assert _exec(p, 38.0) == pytest.approx(29.1)
    # a setpoint step 50 -> 60 with PV 40: E 10 -> 20; P = 40, I = 0.5 + 1.0 = 1.5
    # DOE=1: D = 0.2 x 10 / 0.1 = 20 -> 61.5; DOE=0 (PV): no kick -> 41.5
    for doe, expected in ((1, 61.5), (0, 41.5)):
        p = _pid(KP=2.0, KI=0.5, KD=0.2, UPD=0.1, SP=50.0, DOE=doe)
        _exec(p, 40.0)
        p[P["SP"]] = 60.0
        assert _exec(p, 40.0) == pytest.approx(expected)


def test_pid_dependent_gains() -> None:
    # PE=1: Kc 2, Ti 0.5 min/repeat, Td 0.01 min, UPD 1 s. E = 10:
    # P = 20, I = 2 / (0.5 x 60) x 10 x 1 = 0.6667 -> 20.6667
    p = _pid(PE=1, KP=2.0, KI=0.5, KD=0.01, UPD=1.0, SP=50.0)
    assert _exec(p, 40.0) == pytest.approx(20.0 + 2 / 30 * 10, rel=1e-6)
    # PV 38, E 12: P = 24, I = 0.6667 + 2/30 x 12 = 1.4667, D = 2 x 0.01 x 60 x 2 / 1 = 2.4
    assert _exec(p, 38.0) == pytest.approx(24.0 + 2 / 30 * 22 + 2.4, rel=1e-6)


def test_pid_reverse_action() -> None:
    p = _pid(KP=2.0, UPD=0.1, SP=50.0, CA=1, BIAS=50.0)
    # CA=1: E = PV - SP = 60 - 50 = 10 -> OUT = 2 x 10 + 50 = 70
    assert _exec(p, 60.0) == pytest.approx(70.0)
    assert p[P["ERR"]] == 10.0


def test_pid_output_limit_without_windup() -> None:
    p = _pid(KP=10.0, KI=0.5, UPD=0.1, SP=50.0, MAXO=80.0)
    # E 10: 100 + 0.5 > 80: OUT held at 80, OLH set, the integral does not grow
    assert _exec(p, 40.0) == 80.0 and p[P["OLH"]] == 1
    assert _exec(p, 40.0) == 80.0
    # PV 45, E 5: P = 50, I = 0 + 0.5 x 5 x 0.1 = 0.25 -> 50.25 (a wound-up I would add 1.0)
    assert _exec(p, 45.0) == pytest.approx(50.25)
    assert (p[P["OLH"]], p[P["OLL"]]) == (0, 0)
    # E = -10: -100 + ... below MINO 0: OUT 0, OLL
    assert _exec(p, 60.0) == 0.0 and p[P["OLL"]] == 1


def test_pid_software_manual_and_bumpless_return() -> None:
    p = _pid(KP=2.0, KI=0.5, UPD=0.1, SP=50.0, SWM=1, SO=30.0)
    assert _exec(p, 40.0) == 30.0  # manual: OUT = SO
    # back to auto: the integral was set to 30 - P(20) = 10, so OUT = 20 + 10 + 0.5 = 30.5
    p[P["SWM"]] = 0
    assert _exec(p, 40.0) == pytest.approx(30.5)
    # NOBC set: no bias calculation, the integral starts from 0 again: 20 + 0.5
    p = _pid(KP=2.0, KI=0.5, UPD=0.1, SP=50.0, SWM=1, SO=30.0, NOBC=1)
    _exec(p, 40.0)
    p[P["SWM"]] = 0
    assert _exec(p, 40.0) == pytest.approx(20.5)


def test_pid_station_manual_follows_tieback() -> None:
    p = _pid(KP=2.0, UPD=0.1, SP=50.0, MO=1, MINTIE=0.0, MAXTIE=4000.0)
    cell = [0.0]
    pl.pid(ExecContext(), True, p, 40.0, 1000, Ref(cell, 0, REAL), None, 0, 0)
    assert cell[0] == 25.0  # 1000 of 0..4000 = 25 %


def test_pid_deadband_with_and_without_zero_crossing() -> None:
    # NOZC=1: |E| 1.5 <= DB 2 counts as 0 (EWD); P and I act on 0
    p = _pid(KP=2.0, UPD=0.1, SP=50.0, DB=2.0, NOZC=1)
    assert _exec(p, 48.5) == 0.0 and p[P["EWD"]] == 1 and p[P["ERR"]] == 1.5
    # zero crossing: inside the band only after the error has crossed zero
    p = _pid(KP=2.0, UPD=0.1, SP=50.0, DB=2.0)
    ewd = []
    for pv in (45.0, 48.5, 51.0, 48.5, 47.0):  # E = 5, 1.5, -1, 1.5, 3
        _exec(p, pv)
        ewd.append(p[P["EWD"]])
    assert ewd == [0, 0, 1, 1, 0]


def test_pid_scales_pv_and_cv() -> None:
    # PV 0..4095 counts onto 0..200 EU; SP 100 EU; span 200 EU: 1 EU = 0.5 %
    # PV 1638 counts = 80.0 EU (1638 x 200 / 4095); E = 20 EU = 10 %; KP 1 -> OUT 10 %
    # CV 0..4000: 10 % = 400
    p = _pid(KP=1.0, UPD=0.1, SP=100.0, MAXI=4095.0, MAXS=200.0, MAXCV=4000.0)
    assert _exec(p, 1638, cv_type=DINT) == 400
    assert p[P["PV"]] == pytest.approx(80.0)


def test_pid_alarms_with_deadband() -> None:
    p = _pid(UPD=0.1, SP=50.0, PVH=90.0, PVL=10.0, PVDB=2.0, DVP=20.0, DVN=-20.0, DVDB=1.0)
    seen = []
    for pv in (91.0, 89.0, 87.9, 9.0, 11.5, 12.1, 29.5, 30.0, 31.5):
        _exec(p, pv)
        seen.append((p[P["PVHA"]], p[P["PVLA"]], p[P["DVPA"]], p[P["DVNA"]]))
    # ERR = SP - PV: -41 (DVNA), -39, -37.9, 41 (DVPA), 38.5, 37.9, 20.5, 20, 18.5
    # PVHA holds down to 88, PVLA up to 12; DVPA holds down to 19
    assert seen == [
        (1, 0, 0, 1),
        (1, 0, 0, 1),
        (0, 0, 0, 1),
        (0, 1, 1, 0),
        (0, 1, 1, 0),
        (0, 0, 1, 0),
        (0, 0, 1, 0),
        (0, 0, 1, 0),
        (0, 0, 0, 0),
    ]


def test_pid_matches_a_real_controller_snapshot() -> None:
    # A PID exported from a running project (reh3376/acd-l5x-tool-lib, Cookers_PID_Logic,
    # TCV_2025A): software manual, SO 0.05, input 50..250 scaled to 50..215, SP in use
    # 199.98505 (DATA[4]), alarm limits all 0. The export shows PV 127.86931, ERR 72.11574,
    # OUT 0.05, PVHA 1, PVLA 0, DVPA 1, DVNA 0 and SPOR 0 for that SP.
    raw = (127.86931 - 50.0) / 0.825 + 50.0  # the input that scales to that PV
    p = new_struct(
        "PID",
        SWM=1,
        SO=0.05,
        KP=7.5,
        KI=2.0,
        MAXS=215.0,
        MINS=50.0,
        MAXI=250.0,
        MINI=50.0,
        MAXO=99.0,
        MINO=0.05,
        UPD=0.25,
        MAXCV=100.0,
        MAXTIE=100.0,
        SP=f32(199.98505),
    )
    assert _exec(p, raw) == pytest.approx(0.05)
    assert p[P["PV"]] == pytest.approx(127.86931, abs=1e-4)
    assert p[P["ERR"]] == pytest.approx(72.11574, abs=1e-4)
    assert (p[P["PVHA"]], p[P["PVLA"]], p[P["DVPA"]], p[P["DVNA"]], p[P["SPOR"]]) == (1, 0, 1, 0, 0)


def test_pid_zero_update_time_is_a_minor_fault() -> None:
    ctx = ExecContext()
    p = _pid(KP=2.0, UPD=0.0, SP=50.0, OUT=12.0)
    _exec(p, 40.0, ctx)
    assert p[P["OUT"]] == 12.0
    assert [(f.type, f.code) for f in ctx.minor_faults.values()] == [(4, 35)]


def test_pid_ladder_false_rung_clears_en(tmp_path: Path) -> None:
    p = _pid(KP=2.0, UPD=0.1, SP=50.0)
    _exec(p, 40.0)
    cell = [5.0]
    pl.pid(ExecContext(), False, p, 40.0, 0, Ref(cell, 0, REAL), None, 0, 0)
    assert (p[P["EN"]], p[P["INI"]]) == (0, 0) and cell[0] == 5.0


def test_pid_ladder_through_run_at_the_update_time(tmp_path: Path) -> None:
    src = (
        "VAR p : PID; pv : REAL := 40.0; cv : REAL; END_VAR\n"
        "MOV(2.0,p.KP)MOV(0.5,p.KI)MOV(0.1,p.UPD)MOV(50.0,p.SP);\n"
        "PID(p,pv,0,cv,0,0,0);\n"
    )
    # scans every 100 ms = UPD: the same sequence as test_pid_independent_pi
    rows, _ = trace(tmp_path, src, ".rll", 3, ["cv"], period_ms=100.0)
    assert [float(r["cv"]) for r in rows] == pytest.approx([20.5, 21.0, 21.5])


def test_pid_cascade_slave_takes_sp_from_master() -> None:
    master = _pid(OUT=40.0)
    slave = _pid(KP=1.0, UPD=0.1, CL=1, MAXS=200.0, MAXI=200.0)  # PV 50 raw = 50 EU
    cell = [0.0]
    pl.pid(ExecContext(), True, slave, 50.0, 0, Ref(cell, 0, REAL), master, 0, 0)
    # SP = 40 % of 0..200 = 80; E = 30 EU = 15 % -> OUT 15
    assert slave[P["SP"]] == 80.0 and cell[0] == pytest.approx(15.0)


def test_tank_sample_settles_at_the_setpoint() -> None:
    # samples/tank_pid.st: a PI loop on an integrating tank settles with no offset, where
    # filling (valve x 10 %/s) equals the 4 %/s demand: level 60 %, valve 40 %. The Low alarm
    # fired once at the start (level 5 % < 20 %); the report MSG failed after its 30 s.
    import io
    import json
    from contextlib import redirect_stdout

    from interpreter.cli import main

    sample = Path(__file__).resolve().parents[2] / "samples" / "tank_pid.st"
    watch = ["Level", "Valve", "LevelAlarm.LAlarmCount", "LevelAlarm.LInAlarm", "Report.ERR"]
    argv = ["run", str(sample), "--scan-period", "100", "--duration", "60", "--json"]
    for w in watch:
        argv += ["--watch", w]
    buf = io.StringIO()
    with redirect_stdout(buf):
        assert main(argv) == 0
    tags = json.loads(buf.getvalue())["tags"]
    assert tags["Level"] == pytest.approx(60.0, abs=0.05)
    assert tags["Valve"] == pytest.approx(40.0, abs=0.1)
    assert (tags["LevelAlarm.LAlarmCount"], tags["LevelAlarm.LInAlarm"]) == (1, False)
    assert tags["Report.ERR"] == 1


def test_pid_trusts_upd_not_the_time_between_executions(tmp_path: Path) -> None:
    # The loop integrates KI x E x UPD per execution whatever the real period (RM003: run it
    # at the UPD rate). UPD 0.1 s but 10 ms scans: after 10 scans (0.1 s of simulated time)
    # I = 10 x 0.5 x 10 x 0.1 = 5, so OUT = 20 + 5 = 25, not the 20.5 that 0.1 s of real
    # integral action would give.
    src = (
        "VAR p : PID; pv : REAL := 40.0; cv : REAL; END_VAR\n"
        "MOV(2.0,p.KP)MOV(0.5,p.KI)MOV(0.1,p.UPD)MOV(50.0,p.SP);\n"
        "PID(p,pv,0,cv,0,0,0);\n"
    )
    rows, _ = trace(tmp_path, src, ".rll", 10, ["cv"], period_ms=10.0)
    assert float(rows[-1]["cv"]) == pytest.approx(25.0)


def test_pid_new_tag_ranges_are_not_applied() -> None:
    # every member 0 (as Studio creates the tag), UPD set: no scaling, no limits, CV = OUT
    p = new_struct("PID", KP=20.0, UPD=0.1, SP=50.0)
    # E = 50 - 40 = 10 -> OUT = 200, beyond 100 % but no limits are configured
    assert _exec(p, 40.0) == 200.0 and (p[P["OLH"]], p[P["OLL"]]) == (0, 0)


def test_pid_new_tag_without_update_time_faults() -> None:
    ctx = ExecContext()
    _exec(new_struct("PID", KP=2.0), 40.0, ctx)
    assert [(f.type, f.code) for f in ctx.minor_faults.values()] == [(4, 35)]
