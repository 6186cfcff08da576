"""Position cams with rotary axes through `logixst run` (decision 0137): MC_CamIn and MAPC
follow a rotary master through its wrap as they follow a linear one, a rotary slave follows
the same law modulo its unwind, and ramp_in_pos / ramp_in_neg on a rotary slave compensate
forward only / in reverse only (seed MC_CamTableSelect-MC_CamIn).

Timing: 1 ms scans and coarse update. Everything runs in scan 0 and applies at the update
of t = 1 ms; a jog with a near-infinite acceleration then moves its master from the next
update on, so the master's travel is U(t) = V (t - 0.001), V = 200 u/s (the rotary master R
shows U mod 360, the linear master M shows U). Couplings are made at t = 1 ms with the
masters at 0 (R2 at 300).

Cams (linear segments, period 360):
  A: (0,0) (90,30) (180,0) (270,-30) (360,0)   A(x) piecewise linear, A(0) = A(360) = 0
  B: (0,0) (120,60) (360,360)                  B(x) = x/2 up to 120, then 60 + 1.25 (x-120)
Expected slave positions come from these by hand; the rotary ones are compared round the
circle (359.99 and 0.01 are 0.02 apart). REAL tags are float32, hence tolerances of 1e-3.
"""

from __future__ import annotations

import math

import pytest
from motion_trace import Runner

ARGS = ["--coarse-update", "1"]
U_ = 360.0
V = 200.0
T0 = 0.001
TOL = 1e-3
DYN = "MaximumSpeed := 1000.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0"
ROT = f"RotaryAxis := 1, PositionUnwind := 360.0, {DYN}"
A_PTS = [(0.0, 0.0), (90.0, 30.0), (180.0, 0.0), (270.0, -30.0), (360.0, 0.0)]
B_PTS = [(0.0, 0.0), (120.0, 60.0), (360.0, 360.0)]


def points(pts: list[tuple[float, float]]) -> str:
    return ", ".join(f"(Master := {m}, Slave := {s}, SegmentType := 0)" for m, s in pts)


def interp(pts: list[tuple[float, float]], x: float) -> float:
    for (x0, y0), (x1, y1) in zip(pts, pts[1:], strict=False):
        if x <= x1:
            return y0 + (y1 - y0) * (x - x0) / (x1 - x0)
    return pts[-1][1]


def cam_a(x: float) -> float:
    """A over a periodic master: one cycle per 360 of X."""
    return interp(A_PTS, x % U_)


def cam_b_unwound(x: float) -> float:
    """B periodic and relative: each pass adds B(360) = 360 (B(0) = 0: no jump)."""
    return U_ * math.floor(x / U_) + interp(B_PTS, x % U_)


def round_gap(a: float, b: float) -> float:
    d = abs(a - b) % U_
    return min(d, U_ - d)


def jog(axis: str, ctl: str) -> str:
    return (
        f"MAJ({axis}, {ctl}, forward, {V}, unitspersec, 1.0E30, unitspersec2, 1.0E30, "
        "unitspersec2, trapezoidal, 0.0, 0.0, unitspersec3, disabled, programmed, 0.0, none);"
    )


def select(name: str, master: str, slave: str, table: str, slave_abs: str) -> str:
    return (
        f"{name}(Master := {master}, Slave := {slave}, CamTable := {table}, Execute := TRUE, "
        f"Periodic := TRUE, MasterAbsolute := TRUE, SlaveAbsolute := {slave_abs});"
    )


def cam_in(name: str, sel: str, master: str, slave: str, extra: str = "") -> str:
    return (
        f"{name}(Master := {master}, Slave := {slave}, Execute := {sel}.Done, "
        f"CamTableID := {sel}.CamTableID{extra});"
    )


FOLLOW = f"""VAR
  R : AXIS_VIRTUAL := ({ROT});
  R2 : AXIS_VIRTUAL := ({ROT}, ActualPosition := 300.0);
  M : AXIS_VIRTUAL := ({DYN});
  SA, SB, SL, SP, SK : AXIS_VIRTUAL := ({DYN});
  SR, SQ : AXIS_VIRTUAL := ({ROT});
  j1, j2, j3, mp1, mp2, mp3 : MOTION_INSTRUCTION;
  camA : CAM[5] := [{points(A_PTS)}];
  camB : CAM[3] := [{points(B_PTS)}];
  profA : CAM_PROFILE[5] := [{points(A_PTS)}];
  profB : CAM_PROFILE[3] := [{points(B_PTS)}];
  selA, selB, selR, selL : MC_CamTableSelect;
  inA, inB, inR, inL : MC_CamIn;
  k : DINT;
END_VAR
{select("selA", "R", "SA", "camA", "TRUE")}
{cam_in("inA", "selA", "R", "SA", ", MasterScaling := 0.5, StartMode := absolute")}
{select("selB", "M", "SB", "camA", "TRUE")}
{cam_in("inB", "selB", "M", "SB", ", MasterScaling := 0.5, StartMode := absolute")}
{select("selR", "R", "SR", "camB", "FALSE")}
{cam_in("inR", "selR", "R", "SR", ", MasterScaling := 0.5, StartMode := relative")}
{select("selL", "M", "SL", "camB", "FALSE")}
{cam_in("inL", "selL", "M", "SL", ", MasterScaling := 0.5, StartMode := relative")}
IF k = 0 THEN
  {jog("R", "j1")}
  {jog("M", "j2")}
  {jog("R2", "j3")}
  MAPC(SP, R, mp1, same, profA[0], 1.0, 2.0, continuous, immediate, 0.0, 0.0, command, bidirectional);
  MAPC(SQ, R, mp2, same, profB[0], 1.0, 2.0, continuous, immediate, 0.0, 0.0, command, bidirectional);
  MAPC(SK, R2, mp3, same, profB[0], 1.0, 1.0, once, forwardonly, 0.0, 0.0, command, bidirectional);
END_IF;
k := k + 1;
"""

WATCH = [
    "R.CommandPosition",
    "M.CommandPosition",
    "R2.CommandPosition",
    "SA.CommandPosition",
    "SB.CommandPosition",
    "SR.CommandPosition",
    "SL.CommandPosition",
    "SP.CommandPosition",
    "SQ.CommandPosition",
    "SK.CommandPosition",
    "inA.InSync",
    "inR.InSync",
    "inA.Error",
    "inR.Error",
    "mp1.ER",
    "mp2.ER",
    "mp3.PC",
    "SK.PositionCamLockStatus",
]


@pytest.fixture
def follow(mp: Runner) -> dict[str, list[float]]:
    """FOLLOW run for 5 s: U reaches 1000, almost three turns of R."""
    tr = mp.trace(FOLLOW, WATCH, 5002, ARGS)
    return {n: tr.col(n) for n in tr.names}


def travel(t: float) -> float:
    """U(t): the jogged masters' travel (the trace row at t shows the update at t)."""
    return V * max(t - T0, 0.0)


def rows(follow: dict[str, list[float]], t0: float = 0.002):
    for i, t in enumerate(follow["time"]):
        if t >= t0 - 1e-9:
            yield t, {n: col[i] for n, col in follow.items()}


def test_the_masters_run_through_several_wraps(follow) -> None:
    for t, r in rows(follow):
        u = travel(t)
        assert r["M.CommandPosition"] == pytest.approx(u, abs=TOL)
        assert 0.0 <= r["R.CommandPosition"] < U_
        assert round_gap(r["R.CommandPosition"], u) <= TOL, (t, r["R.CommandPosition"], u)
    assert travel(follow["time"][-1]) > 2.5 * U_


def test_camin_on_a_rotary_master_follows_as_on_a_linear_one(follow) -> None:
    # SA: X = 0.5 U, slave = A(X mod 360): one cam cycle spans two turns of R, so reading
    # R's wrapped position would start the cycle again at every wrap
    checked = 0
    for t, r in rows(follow):
        expect = cam_a(0.5 * travel(t))
        assert r["SA.CommandPosition"] == pytest.approx(expect, abs=TOL), (t, r)
        assert r["SA.CommandPosition"] == pytest.approx(r["SB.CommandPosition"], abs=1e-4)
        assert r["inA.InSync"] == 1 and r["inA.Error"] == 0
        checked += 1
    assert checked > 4990
    # after the first wrap of R (U = 450 at t = 2.251) the law is A(225) = -15
    i = follow["time"].index(2.251)
    assert follow["SA.CommandPosition"][i] == pytest.approx(-15.0, abs=TOL)


def test_camin_rotary_slave_follows_modulo_its_unwind(follow) -> None:
    # SR (rotary) and SL (linear, on the linear master) relative on B with MasterScaling
    # 0.5: the unwound law 360 floor(X/360) + B(X mod 360), X = U/2; SR shows it modulo 360
    for t, r in rows(follow):
        expect = cam_b_unwound(0.5 * travel(t))
        assert r["SL.CommandPosition"] == pytest.approx(expect, abs=2 * TOL), (t, r)
        assert 0.0 <= r["SR.CommandPosition"] < U_
        assert round_gap(r["SR.CommandPosition"], expect) <= TOL, (t, r["SR.CommandPosition"])
        assert round_gap(r["SR.CommandPosition"], r["SL.CommandPosition"]) <= 2 * TOL
        assert r["inR.InSync"] == 1 and r["inR.Error"] == 0


def test_mapc_on_a_rotary_master_and_slave(follow) -> None:
    # SP: MAPC continuous, MasterScaling 2: x = U / 2, slave = A(x mod 360) - A(0) + 0 per
    # pass (A's net change is 0), the same as SA. SQ (rotary), also MasterScaling 2: B
    # unwound over x = U / 2 (net change 360 per pass), modulo 360.
    for t, r in rows(follow):
        u = travel(t)
        assert r["SP.CommandPosition"] == pytest.approx(cam_a(0.5 * u), abs=TOL), (t, r)
        assert 0.0 <= r["SQ.CommandPosition"] < U_
        assert round_gap(r["SQ.CommandPosition"], cam_b_unwound(0.5 * u)) <= TOL, (t, r)
        assert r["mp1.ER"] == 0 and r["mp2.ER"] == 0


def test_mapc_forward_lock_through_the_wrap(follow) -> None:
    # R2 starts at 300: U2 = 300 + U(t) crosses the lock position 0 (= 360) at t = 0.301.
    # From the update after the lock: slave = B(U2 - 360) - B(0), once: ends at x = 360
    # (U2 = 720, t = 2.101) holding B(360) = 360.
    for t, r in rows(follow):
        u2 = 300.0 + travel(t)
        if t <= 0.299:
            assert r["SK.CommandPosition"] == 0.0, (t, r)
            assert r["SK.PositionCamLockStatus"] == 0
        elif t >= 0.303:
            x = min(u2 - U_, U_)
            assert r["SK.CommandPosition"] == pytest.approx(interp(B_PTS, x), abs=TOL), (t, r)
        if 0.303 <= t <= 2.099:
            assert r["SK.PositionCamLockStatus"] == 1
        if t >= 2.103:
            assert r["mp3.PC"] == 1
    assert follow["mp3.PC"][-1] == 1 and follow["SK.CommandPosition"][-1] == 360.0


# Ramp-in on a rotary slave: master M at rest at 0, a periodic cam A (A(0) = 0) with
# SlaveOffset 20: the law is 20. VelocityDiff 100, Acceleration = Deceleration 1000: a
# trapezoid with 0.1 s ramps covering 5 each, so D takes T = D / 100 + 0.1 s.
# Slave at 300: forward to 380 = 20 is D = 80, in reverse D = 280; ramp_in goes the short way.
# Slave at 100: forward 280, in reverse 80 (the short way).
RAMPS = [
    ("ramp_in_pos", 300.0, 80.0),
    ("ramp_in_neg", 300.0, -280.0),
    ("ramp_in", 300.0, 80.0),
    ("ramp_in_pos", 100.0, 280.0),
    ("ramp_in_neg", 100.0, -80.0),
    ("ramp_in", 100.0, -80.0),
]


def trapezoid(t: float, dist: float) -> float:
    """Distance covered t s into the rest-to-rest trapezoid above over |dist|."""
    d, total = abs(dist), abs(dist) / 100.0 + 0.1
    if t <= 0.0:
        return 0.0
    if t <= 0.1:
        return 500.0 * t * t
    if t <= total - 0.1:
        return 5.0 + 100.0 * (t - 0.1)
    if t <= total:
        return d - 500.0 * (total - t) ** 2
    return d


@pytest.mark.parametrize(("mode", "start", "move"), RAMPS, ids=[f"{m}-{s}" for m, s, _ in RAMPS])
def test_ramp_in_direction_on_a_rotary_slave(mp: Runner, mode: str, start: float, move: float):
    src = f"""VAR
  M : AXIS_VIRTUAL := ({DYN});
  S : AXIS_VIRTUAL := ({ROT}, ActualPosition := {start});
  sel : MC_CamTableSelect;
  camIn : MC_CamIn;
  camA : CAM[5] := [{points(A_PTS)}];
END_VAR
{select("sel", "M", "S", "camA", "TRUE")}
{cam_in("camIn", "sel", "M", "S", f", SlaveOffset := 20.0, StartMode := {mode}, VelocityDiff := 100.0, Acceleration := 1000.0, Deceleration := 1000.0")}
"""
    watch = ["S.CommandPosition", "S.CommandVelocity", "camIn.InSync", "camIn.Error"]
    total = abs(move) / 100.0 + 0.1
    tr = mp.trace(src, watch, round((T0 + total) * 1000) + 200, ARGS)
    sign = 1.0 if move > 0 else -1.0
    for t, s, v, sync, err in tr.rows:
        assert err == 0
        assert 0.0 <= s < U_
        # coupled at the update of t = 1 ms; the ramp's clock counts from there
        want = start + sign * trapezoid(t - T0, move)
        assert round_gap(s, want) <= TOL, (t, s, want)
        assert sign * v >= -1e-6, (t, v)  # only ever moving the one way
        if t >= T0 + total + 0.002:
            assert sync == 1
        elif t <= T0 + total - 0.002:
            assert sync == 0
    assert round_gap(tr.rows[-1][1], 20.0) <= TOL
