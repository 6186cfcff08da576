"""MC_CamTableSelect + MC_CamIn through `logixst run` (SPEC 3.1, 5, 9.29, 9.30).

Timing: 1 ms scans and a 1 ms coarse update. The master jogs at 10 u/s (MAJ with an
acceleration so high that it is at speed after one update). Expectations are the law
X = MasterScaling * master + MasterOffset, Y = SlaveScaling * CAM(X) + SlaveOffset applied
to the traced master position (REAL tags: float32, hence the tolerances). The ErrorID
numbers are read from the catalog (facts stated once).
"""

from __future__ import annotations

import math

import pytest
from motion_trace import Runner

from stdlib import catalog

ARGS = ["--coarse-update", "1"]
ERROR_ID = {v.text: v.value for v in catalog().enum("MC_ErrorID").values}

# LIN: CAM(x) = 2x on [0, 10]; OFF: CAM(x) = 1 + 0.2x on [0, 10]; TRI: 0 -> 5 -> 0 on [0, 20]
CAMS = """
  lin : CAM[2] := [(Master := 0.0, Slave := 0.0, SegmentType := 0), (Master := 10.0, Slave := 20.0, SegmentType := 0)];
  off : CAM[2] := [(Master := 0.0, Slave := 1.0, SegmentType := 0), (Master := 10.0, Slave := 3.0, SegmentType := 0)];
  tri : CAM[3] := [(Master := 0.0, Slave := 0.0, SegmentType := 0), (Master := 10.0, Slave := 5.0, SegmentType := 0), (Master := 20.0, Slave := 0.0, SegmentType := 0)];
"""

JOG = (
    "MAJ(M, mj, {dir}, 10.0, unitspersec, 1000000.0, unitspersec2, 1000000.0, unitspersec2, "
    "trapezoidal, 0.0, 0.0, unitspersec3, disabled, programmed, 0.0, none);"
)


def program(
    table: str = "lin",
    select: str = "Periodic := TRUE, MasterAbsolute := TRUE, SlaveAbsolute := TRUE",
    camin: str = "",
    body: str = "",
    slave_at: float = 0.0,
    master_at: float = 0.0,
    jog: str = "forward",
) -> str:
    return f"""VAR
  M : AXIS_VIRTUAL := (ActualPosition := {master_at});
  S : AXIS_VIRTUAL := (ActualPosition := {slave_at});
  mj, ms : MOTION_INSTRUCTION;
  sel : MC_CamTableSelect;
  camIn : MC_CamIn;
  go : BOOL := TRUE;
  k : DINT;
{CAMS}
END_VAR
sel(Master := M, Slave := S, CamTable := {table}, Execute := go, {select});
camIn(Master := M, Slave := S, Execute := go AND sel.Done, CamTableID := sel.CamTableID{camin});
IF k = 0 THEN {JOG.format(dir=jog)} END_IF;
{body}
k := k + 1;
"""


WATCH = [
    "M.CommandPosition",
    "S.CommandPosition",
    "camIn.InSync",
    "camIn.Busy",
    "camIn.Error",
    "camIn.ErrorID",
    "camIn.EndOfProfile",
    "camIn.CommandAborted",
]


def rows(tr, t0: float = 0.0):
    names = tr.names
    for r in tr.rows:
        if r[0] >= t0 - 1e-9:
            yield {n: r[i] for i, n in enumerate(names)}


def lin(x: float) -> float:
    return 2.0 * x


def wrap(x: float, start: float, span: float) -> float:
    return x - span * math.floor((x - start) / span)


def test_law_with_scalings_and_offsets(mp: Runner):
    src = program(
        camin=", MasterScaling := 0.5, MasterOffset := 1.0, SlaveScaling := 2.0, SlaveOffset := 3.0"
    )
    tr = mp.trace(src, WATCH, 3000, ARGS)  # the master runs to 30: X wraps twice
    checked = 0
    for r in rows(tr, 0.005):
        x = 0.5 * r["M.CommandPosition"] + 1.0
        expect = 2.0 * lin(wrap(x, 0.0, 10.0)) + 3.0
        if abs(wrap(x, 0.0, 10.0)) < 1e-3 or abs(wrap(x, 0.0, 10.0) - 10) < 1e-3:
            continue  # at a wrap the float32 master decides the side
        assert r["S.CommandPosition"] == pytest.approx(expect, abs=2e-4), r
        assert r["camIn.InSync"] == 1 and r["camIn.Busy"] == 1
        checked += 1
    assert checked > 2900


# (StartMode, SlaveAbsolute, expected slave as a function of the master) with the slave at
# 7 when it couples and OFF: CAM(x) = 1 + 0.2 x. A relative law adds 7. Ramps use
# VelocityDiff 50, so they are done within 0.3 s; compared from t = 0.5 s.
MODES = [
    ("absolute", "TRUE", lambda m: 1 + 0.2 * m),
    ("absolute", "FALSE", lambda m: 8 + 0.2 * m),
    ("relative", "TRUE", lambda m: 8 + 0.2 * m),
    ("relative", "FALSE", lambda m: 8 + 0.2 * m),
    ("ramp_in", "TRUE", lambda m: 1 + 0.2 * m),
    ("ramp_in", "FALSE", lambda m: 8 + 0.2 * m),
    ("ramp_in_pos", "TRUE", lambda m: 1 + 0.2 * m),
    ("ramp_in_pos", "FALSE", lambda m: 8 + 0.2 * m),
    ("ramp_in_neg", "TRUE", lambda m: 1 + 0.2 * m),
    ("ramp_in_neg", "FALSE", lambda m: 8 + 0.2 * m),
]


@pytest.mark.parametrize(("mode", "slave_abs", "law"), MODES, ids=[f"{a}-{b}" for a, b, _ in MODES])
def test_start_mode_and_slave_absolute(mp: Runner, mode, slave_abs, law):
    src = program(
        table="off",
        select=f"Periodic := FALSE, MasterAbsolute := TRUE, SlaveAbsolute := {slave_abs}",
        camin=f", StartMode := {mode}, VelocityDiff := 50.0, Acceleration := 1000.0, Deceleration := 1000.0",
        slave_at=7.0,
    )
    tr = mp.trace(src, WATCH, 900, ARGS)
    first = next(rows(tr, 0.001))  # coupled at the update of t = 1 ms: the slave is still at 7
    assert first["S.CommandPosition"] == pytest.approx(7.0, abs=1e-6)
    for r in rows(tr, 0.5):
        assert r["S.CommandPosition"] == pytest.approx(law(r["M.CommandPosition"]), abs=1e-4)
        assert r["camIn.InSync"] == 1
    if mode.startswith("ramp"):  # no jump: the slave moves by at most 50 u/s * 1 ms a scan
        s = [r["S.CommandPosition"] for r in rows(tr)]
        m = [r["M.CommandPosition"] for r in rows(tr)]
        for i in range(1, len(s)):
            assert abs((s[i] - s[i - 1]) - 0.2 * (m[i] - m[i - 1])) <= 0.05 + 1e-5
    else:  # the law at once (a jump)
        r = next(rows(tr, 0.003))
        assert r["S.CommandPosition"] == pytest.approx(law(r["M.CommandPosition"]), abs=1e-4)


def test_ramp_in_velocity_difference_and_in_sync_time(mp: Runner):
    """Slave at 6, LIN absolute (law 2 * master). The compensation 6 -> 0 is a trapezoid with
    VelocityDiff 2, Acceleration 10, Deceleration 5: T = 0.2 + 0.4 + (6 - 0.6) / 2 = 3.3 s
    from the coupling update (t = 1 ms). InSync is read in the scan after that update."""
    src = program(
        camin=", StartMode := ramp_in, VelocityDiff := 2.0, Acceleration := 10.0, Deceleration := 5.0",
        slave_at=6.0,
        jog="reverse",
        body="",
    )
    # the master jogs in reverse at 10 u/s: the periodic law wraps (LIN's end value 20)
    tr = mp.trace(src, WATCH, 3600, ARGS)
    diffs = []
    for r in rows(tr, 0.001):
        law = lin(wrap(r["M.CommandPosition"], 0.0, 10.0))
        diffs.append((r["time"], r["S.CommandPosition"] - law, r["camIn.InSync"]))
    # ignore rows at a wrap of the float32 master
    for (t0, d0, _), (t1, d1, _) in zip(diffs, diffs[1:], strict=False):
        if abs(d1 - d0) > 1.0:
            continue
        assert abs(d1 - d0) / (t1 - t0) <= 2.0 + 0.02
    sync = next(t for t, _, s in diffs if s == 1)
    assert sync == pytest.approx(0.001 + 3.3, abs=0.0011)
    assert all(abs(d) < 1e-3 for t, d, _ in diffs if t > 3.31 and abs(d) < 10)


def test_non_periodic_end_of_profile(mp: Runner):
    """TRI non-periodic: the master leaves [0, 20] at t = 2 s; the slave holds TRI(20) = 0,
    EndOfProfile is TRUE in one scan, InSync and Busy go FALSE, no error."""
    src = program(
        table="tri", select="Periodic := FALSE, MasterAbsolute := TRUE, SlaveAbsolute := TRUE"
    )
    tr = mp.trace(src, WATCH, 2500, ARGS)
    eop = [r["time"] for r in rows(tr) if r["camIn.EndOfProfile"] == 1]
    assert len(eop) == 1 and eop[0] == pytest.approx(2.0, abs=0.0025)
    last = list(rows(tr, 2.1))
    assert all(r["S.CommandPosition"] == pytest.approx(0.0, abs=1e-4) for r in last)
    assert all(r["camIn.InSync"] == 0 and r["camIn.Busy"] == 0 for r in last)
    assert all(r["camIn.Error"] == 0 for r in rows(tr))
    mid = next(rows(tr, 0.5))  # TRI(5) = 2.5
    assert mid["S.CommandPosition"] == pytest.approx(mid["M.CommandPosition"] / 2.0, abs=1e-4)


def test_periodic_end_of_profile_each_pass(mp: Runner):
    tr = mp.trace(program(), WATCH, 3500, ARGS)  # the master passes 10, 20, 30
    eop = [r["time"] for r in rows(tr) if r["camIn.EndOfProfile"] == 1]
    assert len(eop) == 3
    for t, expect in zip(eop, (1.0, 2.0, 3.0), strict=True):
        assert t == pytest.approx(expect, abs=0.0025)


def test_master_relative_counts_from_coupling(mp: Runner):
    src = program(
        select="Periodic := FALSE, MasterAbsolute := FALSE, SlaveAbsolute := TRUE", master_at=13.0
    )
    tr = mp.trace(src, WATCH, 500, ARGS)
    for r in rows(tr, 0.01):
        assert r["S.CommandPosition"] == pytest.approx(lin(r["M.CommandPosition"] - 13.0), abs=2e-4)


def test_master_out_of_range_is_an_error_and_stays_while_execute(mp: Runner):
    src = program(
        select="Periodic := FALSE, MasterAbsolute := TRUE, SlaveAbsolute := TRUE",
        master_at=13.0,
        body="IF k = 50 THEN go := FALSE; END_IF;",
    )
    tr = mp.trace(src, WATCH, 60, ARGS)
    r = next(rows(tr, 0.010))
    assert r["camIn.Error"] == 1 and r["camIn.ErrorID"] == ERROR_ID["master out of range"]
    assert r["camIn.Busy"] == 0 and r["S.CommandPosition"] == 0.0
    assert all(r["camIn.Error"] == 1 for r in rows(tr, 0.003) if r["time"] < 0.049)
    # Execute FALSE from scan 50: shown once more, then cleared
    assert all(r["camIn.Error"] == 0 and r["camIn.ErrorID"] == 0 for r in rows(tr, 0.052))


def test_relocation_needs_zero_in_a_non_periodic_range(mp: Runner):
    src = program(
        table="tri",
        select="Periodic := FALSE, MasterAbsolute := FALSE, SlaveAbsolute := TRUE",
        camin=", MasterOffset := -1.0",  # evaluation would start at X = -1
    )
    tr = mp.trace(src, WATCH, 20, ARGS)
    r = next(rows(tr, 0.005))
    assert r["camIn.Error"] == 1 and r["camIn.ErrorID"] == ERROR_ID["master out of range"]


def test_command_aborted_by_a_stop(mp: Runner):
    src = program(
        body="IF k = 100 THEN MAS(S, ms, all, 1, 1000.0, unitspersec2, 0, 0.0, unitspersec3); END_IF;"
    )
    tr = mp.trace(src, WATCH, 300, ARGS)
    before = next(rows(tr, 0.099))
    assert before["camIn.InSync"] == 1 and before["camIn.CommandAborted"] == 0
    after = list(rows(tr, 0.103))
    assert all(r["camIn.CommandAborted"] == 1 and r["camIn.Busy"] == 0 for r in after)
    assert all(r["camIn.InSync"] == 0 and r["camIn.Error"] == 0 for r in after)


def test_bad_table_id_and_same_axis(mp: Runner):
    src = program(camin="").replace("CamTableID := sel.CamTableID", "CamTableID := 99")
    tr = mp.trace(src, WATCH, 5, ARGS)
    assert tr.rows[-1][tr.names.index("camIn.ErrorID")] == ERROR_ID["invalid cam table id"]
    src = program().replace("sel(Master := M, Slave := S", "sel(Master := M, Slave := M")
    tr = mp.trace(src, ["sel.Error", "sel.ErrorID", "sel.Done"], 5, ARGS)
    assert tr.rows[-1][1:] == [1.0, float(ERROR_ID["same axis"]), 0.0]


def test_bad_cam_table(mp: Runner):
    src = program(table="bad").replace(
        "END_VAR",
        "  bad : CAM[2] := [(Master := 5.0, Slave := 0.0), (Master := 1.0, Slave := 1.0)];\nEND_VAR",
        1,
    )
    tr = mp.trace(src, ["sel.Error", "sel.ErrorID", "sel.Done"], 5, ARGS)
    assert tr.rows[-1][1:] == [1.0, float(ERROR_ID["invalid cam table"]), 0.0]


def test_switching_table_without_restart(mp: Runner):
    """LIN periodic runs; at scan 500 (master 5) TRI is selected with MasterAbsolute FALSE
    and MC_CamIn gets its ID while it stays busy: TRI takes over at LIN's pass end (master
    10) with its master zero there: slave = TRI(master - 10)."""
    src = program(
        body="""IF k = 500 THEN sel2(Master := M, Slave := S, CamTable := tri, Execute := TRUE,
  Periodic := TRUE, MasterAbsolute := FALSE, SlaveAbsolute := TRUE); tid := sel2.CamTableID; END_IF;""",
    ).replace("CamTableID := sel.CamTableID", "CamTableID := tid")
    src = src.replace("  k : DINT;", "  k : DINT;\n  tid : DINT;\n  sel2 : MC_CamTableSelect;")
    src = src.replace(
        "camIn(Master", "IF k < 500 THEN tid := sel.CamTableID; END_IF;\ncamIn(Master"
    )
    tr = mp.trace(src, WATCH, 1500, ARGS)
    for r in rows(tr, 0.3):
        m = r["M.CommandPosition"]
        if 9.98 < m < 10.03:
            continue  # the update that crosses the end still evaluates LIN
        expect = lin(m) if m < 10 else (m - 10 if m - 10 <= 10 else 20 - (m - 10)) / 2
        assert r["S.CommandPosition"] == pytest.approx(expect, abs=2e-4), r
        assert r["camIn.Busy"] == 1 and r["camIn.CommandAborted"] == 0
