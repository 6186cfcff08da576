"""MCCD through `logixst run`, against closed forms (decision 0185).

Timing as everywhere (motion_trace.py): the MCLM executed in the scan at 0 starts at the
update t0 = 2 ms; an MCCD executed in the scan at t takes effect at the update t + 2 ms,
whose clock is 0 for the re-planned profile. The moves are the line from (0, 0) to
(30, 40), L = 50, at V = 10 and A = D = 100 (system MaximumSpeed 20, MaximumAccel 1000).
Trapezoid cruising at V after its ramp: s(t) = V (t - t0) - V^2 / (2A); at the MCCD
update tc = t + 2 ms, s(tc) = 10 (t) - 0.5 for t = 1 or 2 s.
A speed change from v to w at rate R lasts |w - v| / R and covers (v + w)/2 of that.
"""

from __future__ import annotations

import math

import pytest
from motion_trace import CUP
from test_coordinated import F32, T0, assert_completes, mclm, once, pc_time, prog

L = 50.0


def mccd(
    ctl: str = "c4",
    *,
    speed: float | None = None,
    accel: float | None = None,
    decel: float | None = None,
    aj: float | None = None,
    dj: float | None = None,
    su: str = "unitspersec",
    au: str = "unitspersec2",
    ju: str = "unitspersec3",
    scope: str = "activemotion",
    mtype: str = "coordinatedmove",
) -> str:
    def part(x: float | None) -> str:
        return f"{'no' if x is None else 'yes'}, {0.0 if x is None else x}"

    return (
        f"MCCD(XY, {ctl}, {mtype}, {part(speed)}, {su}, {part(accel)}, {au}, {part(decel)}, "
        f"{au}, {part(aj)}, {part(dj)}, {ju}, {scope});"
    )


def at_scan(k: int, stmt: str) -> str:
    return f"IF k = {k} THEN {stmt} END_IF;"


def max_step(tr, name: str, t0: float = 0.0, t1: float = math.inf) -> float:  # noqa: ANN001
    """Largest change of a traced value between consecutive rows in [t0, t1]."""
    times, col = tr.time(), tr.col(name)
    return max(abs(b - a) for ta, a, b in zip(times, col, col[1:], strict=False) if t0 <= ta <= t1)


def test_lower_speed_decelerates_at_the_new_decel_and_keeps_the_end_point(mp) -> None:
    # MCCD at 2 s: speed 5, decel 50. At tc = 2.002, s = 19.5; 10 -> 5 at 50 takes 0.1 s over
    # 0.75; the final 5 -> 0 at 50 takes 0.1 s over 0.25; cruise (50 - 19.5 - 1) / 5 = 5.9 s:
    # the move completes at 2.002 + 0.1 + 5.9 + 0.1 = 8.102 s
    body = once(mclm("c1", "p1")) + at_scan(2000, mccd("c2", speed=5.0, decel=50.0))
    watch = [
        "X.CommandPosition", "Y.CommandPosition", "XY.VectorCommandVelocity", "c1.IP",
        "c1.PC", "c1.DECEL", "c1.ACCEL", "XY.DecelStatus", "XY.AccelStatus", "XY.MoveStatus",
        "c2.DN", "c2.IP", "c2.PC", "c2.ER",
    ]  # fmt: skip
    tr = mp.trace(prog("", body), watch, scans=8200)
    assert_completes(tr, "c1", 2.002 + 0.1 + 5.9 + 0.1)
    assert tr.col("X.CommandPosition")[-1] == 30.0
    assert tr.col("Y.CommandPosition")[-1] == 40.0
    # executing scan: DN only (no IP, no PC), no error
    assert [tr.at(2.0, n) for n in ("c2.DN", "c2.IP", "c2.PC", "c2.ER")] == [1, 0, 0, 0]
    assert tr.at(1.999, "c2.DN") == 0
    # s(2.002) = 19.5 is where the change starts: 11.7 on X
    assert tr.at(2.002, "X.CommandPosition") == pytest.approx(0.6 * 19.5, abs=F32)
    # halfway through the 0.1 s ramp (2.052): 7.5 units/s, decelerating, the move in process
    assert tr.at(2.052, "XY.VectorCommandVelocity") == pytest.approx(7.5, abs=1e-4)
    ramp = ("c1.DECEL", "XY.DecelStatus", "c1.ACCEL", "XY.AccelStatus", "c1.IP", "XY.MoveStatus")
    assert [tr.at(2.052, n) for n in ramp] == [1, 1, 0, 0, 1, 1]
    # then the new cruise speed; the last ramp (5 -> 0 at 50) starts at 8.002
    assert tr.at(5.0, "XY.VectorCommandVelocity") == pytest.approx(5.0, abs=1e-4)
    assert [tr.at(5.0, n) for n in ("c1.DECEL", "XY.DecelStatus")] == [0, 0]
    assert tr.at(8.052, "XY.VectorCommandVelocity") == pytest.approx(2.5, abs=1e-4)
    # the speed profile stays continuous: no step above the steepest rate (100) per update
    assert max_step(tr, "XY.VectorCommandVelocity") <= 100.0 * CUP + 1e-4
    # and during the change the rate is the new decel, 50: 0.1 per update
    assert max_step(tr, "XY.VectorCommandVelocity", 2.001, 2.2) == pytest.approx(50 * CUP, abs=1e-4)
    # still the same line
    for x, y in zip(tr.col("X.CommandPosition"), tr.col("Y.CommandPosition"), strict=True):
        assert y == pytest.approx(4.0 / 3.0 * x, abs=F32)


def test_higher_speed_in_percent_of_maximum_accelerates(mp) -> None:
    # at 1 s: Speed 100 % of MaximumSpeed 20 = 20, AccelRate 20 % of MaximumAccel 1000 = 200.
    # tc = 1.002, s = 9.5; 10 -> 20 at 200: 0.05 s over 0.75; 20 -> 0 at the unchanged 100:
    # 0.2 s over 2; cruise (50 - 9.5 - 2.75) / 20 = 1.8875 s: end 1.002 + 0.05 + 1.8875 + 0.2
    stmt = mccd("c2", speed=100.0, accel=20.0, su="%ofmaximum", au="%ofmaximum")
    body = once(mclm("c1", "p1")) + at_scan(1000, stmt)
    watch = ["XY.VectorCommandVelocity", "c1.PC", "c1.ACCEL", "XY.AccelStatus", "c2.DN"]
    tr = mp.trace(prog("", body), watch, scans=3300)
    assert_completes(tr, "c1", 1.002 + 0.05 + 1.8875 + 0.2)
    assert [tr.at(1.026, n) for n in ("c1.ACCEL", "XY.AccelStatus")] == [1, 1]
    assert tr.at(1.026, "XY.VectorCommandVelocity") == pytest.approx(10 + 200 * 0.024, abs=1e-4)
    assert tr.at(2.0, "XY.VectorCommandVelocity") == pytest.approx(20.0, abs=1e-4)
    assert [tr.at(2.0, n) for n in ("c1.ACCEL", "XY.AccelStatus")] == [0, 0]
    assert max_step(tr, "XY.VectorCommandVelocity", 1.001, 1.1) == pytest.approx(
        200 * CUP, abs=1e-4
    )


@pytest.mark.parametrize(("scope", "t2"), [("activemotion", 5.1), ("activeandpendingmotion", 2.7)])
def test_scope_changes_the_queued_move_too(mp, scope: str, t2: float) -> None:
    # c2 (to p2, L = 50) waits behind c1. MCCD at 1 s, speed 20 (accel unchanged 100):
    # c1 from s = 9.5: 10 -> 20 in 0.1 s over 1.5, 20 -> 0 in 0.2 s over 2, cruise
    # (50 - 9.5 - 3.5) / 20 = 1.85 s: PC at 1.002 + 0.1 + 1.85 + 0.2 = 3.152.
    # c2 starts where c1 completes (termination 1) and lasts L/V + V/A: 50/10 + 0.1 = 5.1
    # with its own speed (Active Motion), 50/20 + 0.2 = 2.7 with 20 (Active and Pending)
    body = once(mclm("c1", "p1") + mclm("c2", "p2")) + at_scan(1000, mccd(speed=20.0, scope=scope))
    tr = mp.trace(prog("", body), ["c1.PC", "c2.PC", "c4.DN"], scans=8400)
    assert_completes(tr, "c1", 1.002 + 0.1 + 1.85 + 0.2)
    assert_completes(tr, "c2", pc_time(tr, "c1") + t2)


def test_speed_zero_holds_the_move_on_its_path_until_a_new_speed(mp) -> None:
    # at 1 s speed 0: from s = 9.5, 10 -> 0 at 100 covers 0.5: rest at s = 10, (6, 8); the
    # move stays in process. At 2 s speed 10 again: 0 -> 10 -> 0 ramps cover 0.5 each,
    # cruise (40 - 1) / 10 = 3.9 s: PC at 2.002 + 0.1 + 3.9 + 0.1 = 6.102
    body = (
        once(mclm("c1", "p1"))
        + at_scan(1000, mccd("c2", speed=0.0))
        + at_scan(2000, mccd("c3", speed=10.0))
    )
    watch = ["X.CommandPosition", "Y.CommandPosition", "c1.IP", "c1.PC", "XY.MoveStatus"]
    tr = mp.trace(prog("", body), watch, scans=6300)
    assert tr.at(1.5, "X.CommandPosition") == pytest.approx(6.0, abs=F32)
    assert tr.at(1.999, "Y.CommandPosition") == pytest.approx(8.0, abs=F32)
    assert [tr.at(1.5, n) for n in ("c1.IP", "c1.PC", "XY.MoveStatus")] == [1, 0, 1]
    assert_completes(tr, "c1", 2.002 + 0.1 + 3.9 + 0.1)
    assert tr.col("X.CommandPosition")[-1] == 30.0


def test_s_curve_accel_jerk_in_percent_of_time_uses_the_new_speed(mp) -> None:
    # S-curve at 100 % of Time: J = A^2/V = 1000; the ramp to 10 lasts 2V/A = 0.2 s over
    # V^2/A = 1, so at tc = 2.002: s = 10 (2.0 - 0.2) + 1 = 19.
    # MCCD: speed 20, AccelJerk 100 % of Time of the new speed: J = 100^2 / 20 = 500. The
    # change dv = 10 is below A^2/J = 20, so the accel peaks at sqrt(dv J) = 70.7 < 100,
    # after sqrt(dv/J) = 0.1414 s, and lasts 0.2828 s over 15 * 0.2828 = 4.243.
    # The decel jerk stays 1000: 20 -> 0 reaches 100 (dv 20 >= 10), 0.2 + 0.1 = 0.3 s over 3.
    # Cruise (50 - 19 - 4.243 - 3) / 20 = 1.1879 s: PC at 2.002 + 0.2828 + 1.1879 + 0.3
    stmt = mccd("c2", speed=20.0, aj=100.0, ju="%oftime")
    body = once(mclm("c1", "p1", shape="s-curve")) + at_scan(2000, stmt)
    tr = mp.trace(prog("", body), ["XY.VectorCommandVelocity", "c1.PC"], scans=3900)
    ramp = 2 * math.sqrt(10 / 500)
    cruise = (50 - 19 - 15 * ramp - 3) / 20
    assert_completes(tr, "c1", 2.002 + ramp + cruise + 0.3)
    # the steepest step of the speed-up is the peak accel 70.7 per s (with 1000: 100)
    step = max_step(tr, "XY.VectorCommandVelocity", 2.001, 2.3)
    assert math.sqrt(10 * 500) * CUP * 0.95 <= step <= math.sqrt(10 * 500) * CUP + 1e-4


def test_a_change_during_an_s_curve_ramp_keeps_the_acceleration_continuous(mp) -> None:
    # S-curve at 100 % of Time: J = A^2/V = 1000 both ways. MCCD at 0.05 s (speed 20) takes
    # effect at 0.052, 0.05 s into the first jerk phase: a = J t = 50, v = J t^2/2 = 1.25,
    # s = J t^3/6 = 0.0208333. The acceleration first goes back to 0 at J: 0.05 s, v gains
    # a^2/(2J) = 1.25 (to 2.5) over 1.25*0.05 + 50*0.05^2/2 - J*0.05^3/6 = 0.1041667.
    # Then 2.5 -> 20: dv 17.5 >= A^2/J = 10 reaches A: dv/A + A/J = 0.275 s over
    # (2.5 + 20)/2 * 0.275 = 3.09375; 20 -> 0 at the decel jerk 1000: 0.3 s over 3.
    # Cruise (50 - 0.0208333 - 0.1041667 - 3.09375 - 3) / 20; PC at 0.052 + 0.05 + 0.275 +
    # cruise + 0.3.
    body = once(mclm("c1", "p1", shape="s-curve")) + at_scan(50, mccd("c2", speed=20.0))
    tr = mp.trace(prog("", body), ["XY.VectorCommandVelocity", "c1.PC"], scans=3000)
    cruise = (50 - 0.0208333 - 0.1041667 - 3.09375 - 3) / 20
    assert_completes(tr, "c1", 0.052 + 0.05 + 0.275 + cruise + 0.3)
    # the speed per update; its second difference is the jerk: at most J CUP^2 = 0.004
    # (a step of the acceleration from 50 to 0 would show 0.1)
    v = [r for t, r in zip(tr.time(), tr.col("XY.VectorCommandVelocity"), strict=True)
         if round(t / CUP, 6).is_integer()]  # fmt: skip
    second = [abs(v[i + 1] - 2 * v[i] + v[i - 1]) for i in range(1, len(v) - 1)]
    assert max(second) <= 1000.0 * CUP * CUP + 1e-4
    # the speed after the acceleration is back to 0 (0.102 s): 2.5
    assert tr.at(0.102, "XY.VectorCommandVelocity") == pytest.approx(2.5, abs=1e-4)


def test_a_trapezoidal_move_ignores_jerk_changes(mp) -> None:
    # L/V + V/A = 5.1 s as if no MCCD ran
    body = once(mclm("c1", "p1")) + at_scan(1000, mccd(aj=5.0, dj=5.0))
    tr = mp.trace(prog("", body), ["c1.PC", "c4.DN"], scans=5200)
    assert_completes(tr, "c1", T0 + 5.1)
    assert tr.at(1.0, "c4.DN") == 1


def test_nothing_running_completes_without_error(mp) -> None:
    tr = mp.trace(prog("", once(mccd(speed=5.0))), ["c4.DN", "c4.ER", "c4.IP", "c4.PC"], 4)
    assert [tr.at(0.002, n) for n in ("c4.DN", "c4.ER", "c4.IP", "c4.PC")] == [1, 0, 0, 0]


def test_a_stopping_system_keeps_its_stop(mp) -> None:
    # MCS at 1 s with the system's MaximumDecel 1000: from 10 at s = 9.5 it rests after
    # 10^2 / 2000 = 0.05; the MCCD (speed 20) in the next scan leaves the stop alone: the
    # system rests at s = 9.55 (X = 0.6 s), the move ended without PC
    body = (
        once(mclm("c1", "p1"))
        + at_scan(1000, "MCS(XY, c2, 2, no, 0.0, unitspersec2, no, 0.0, unitspersec3);")
        + at_scan(1001, mccd(speed=20.0))
    )
    tr = mp.trace(prog("", body), ["X.CommandPosition", "c1.PC", "c4.DN", "c2.PC"], 1500)
    assert tr.col("X.CommandPosition")[-1] == pytest.approx(0.6 * 9.55, abs=F32)
    assert [tr.col(n)[-1] for n in ("c1.PC", "c4.DN", "c2.PC")] == [0, 1, 1]


@pytest.mark.parametrize(
    ("stmt", "err", "exerr"),
    [
        (mccd(speed=-1.0), 13, 4),
        (mccd(accel=0.0), 13, 7),
        (mccd(decel=-5.0), 13, 10),
        (mccd(aj=0.0), 13, 13),
        (mccd(dj=150.0, ju="%oftime"), 13, 15),
        (mccd(speed=5.0, su="unitspermasterunit"), 94, 0),
    ],
)
def test_parameter_errors(mp, stmt: str, err: int, exerr: int) -> None:
    body = once(mclm("c1", "p1")) + at_scan(10, stmt)
    tr = mp.trace(prog("", body), ["c4.ER", "c4.ERR", "c4.EXERR", "c4.DN", "c1.PC"], 5200)
    assert [tr.at(0.010, n) for n in ("c4.ER", "c4.ERR", "c4.EXERR", "c4.DN")] == [
        1, err, exerr, 0,
    ]  # fmt: skip
    assert_completes(tr, "c1", T0 + 5.1)  # the move runs on unchanged


@pytest.mark.parametrize("index", [2, 3, 5, 6, 8, 9, 11, 12, 14, 16, 17])
def test_an_enumeration_literal_out_of_range_fails_verification(mp, index: int) -> None:
    # the enumerated operands are immediate: a value out of range is a verification error
    parts = mccd().replace("MCCD(", "").rstrip(");").split(", ")
    parts[index] = "7"
    code, out, err = mp.run(prog("", once("MCCD(" + ", ".join(parts) + ");")), ["--scans", "1"])
    assert code != 0
    assert "E109" in out + err


LADDER = """VAR
  X, Y : AXIS_VIRTUAL;
  XY : COORDINATE_SYSTEM := (Axes := [X, Y], MaximumSpeed := 20.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0);
  c1, c2 : MOTION_INSTRUCTION;
  p : REAL[2] := [30.0, 40.0];
  k : DINT;
END_VAR
EQU(k,0)MCLM(XY,c1,Absolute,p[0],10,Units per sec,100,Units per sec2,100,Units per sec2,Trapezoidal,100.0,100.0,% of Time,No Settle,Disabled,Programmed,0,0,None,0,0);
EQU(k,1000)MCCD(XY,c2,Coordinated Move,Yes,20,Units per sec,No,0,Units per sec2,Yes,50,Units per sec2,No,0,No,0,Units per sec3,Active and Pending Motion);
ADD(k,1,k);
"""


def test_ladder_mccd_with_the_enumeration_texts(mp) -> None:
    # at 1.002 s = 9.5; 10 -> 20 at the unchanged 100: 0.1 s over 1.5; 20 -> 0 at the new
    # decel 50: 0.4 s over 4; cruise (50 - 9.5 - 5.5) / 20 = 1.75 s: PC at 1.002 + 2.25
    tr = mp.trace(LADDER, ["c1.PC", "c2.DN", "c2.ER", "X.CommandPosition"], 3400, name="prog.rll")
    assert [tr.at(1.0, "c2.DN"), tr.at(1.0, "c2.ER")] == [1, 0]
    assert_completes(tr, "c1", 1.002 + 0.1 + 1.75 + 0.4)
    assert tr.col("X.CommandPosition")[-1] == 30.0
