"""Move/jog/stop planning against hand formulas (working in the comments)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from interpreter.motion.profiles import Limits, change_time, plan_jog, plan_move, plan_stop


def test_trapezoid_reaches_speed():
    # v=10, a=20, d=40, D=10: t_acc = v/a = 0.5, d_acc = v^2/2a = 2.5,
    # t_dec = v/d = 0.25, d_dec = v^2/2d = 1.25, cruise = (10 - 3.75)/10 = 0.625
    # total = D/v + v/2a + v/2d = 1 + 0.25 + 0.125 = 1.375
    p = plan_move(10.0, Limits(10.0, 20.0, 40.0))
    assert p.duration == pytest.approx(1.375, abs=1e-12)
    assert p.phase_durations() == pytest.approx([0.5, 0.625, 0.25], abs=1e-12)
    pos, vel, acc = p.evaluate(np.array([0.5, 1.125, 1.375, 5.0]))
    assert pos == pytest.approx([2.5, 8.75, 10.0, 10.0], abs=1e-12)
    assert vel == pytest.approx([10.0, 10.0, 0.0, 0.0], abs=1e-12)


def test_trapezoid_triangular_when_too_short():
    # D=2, a=20, d=40: vp^2/2a + vp^2/2d = D -> vp^2 (1/40 + 1/80) = 2 -> vp^2 = 160/3
    vp = math.sqrt(160.0 / 3.0)
    p = plan_move(2.0, Limits(10.0, 20.0, 40.0))
    assert p.duration == pytest.approx(vp / 20 + vp / 40, abs=1e-12)
    _, v, _ = p.evaluate(np.array([vp / 20]))
    assert v[0] == pytest.approx(vp, rel=1e-12)
    assert p.end_position == 2.0


def test_negative_move_mirrors():
    p = plan_move(-10.0, Limits(10.0, 20.0, 40.0))
    pos, vel, _ = p.evaluate(np.array([0.5, 1.375]))
    assert pos == pytest.approx([-2.5, -10.0])
    assert vel[0] == pytest.approx(-10.0)


def test_scurve_saturated_phases():
    # A=20, J=100: A^2/J = 4 <= v=10 so full accel is reached: ramps of A/J = 0.2 s,
    # constant accel for v/A - A/J = 0.3 s; accel time 0.7 s, distance v/2 * 0.7 = 3.5 each
    # side; cruise (10 - 7)/10 = 0.3 s; total 1.7 s
    p = plan_move(10.0, Limits(10.0, 20.0, 20.0, 100.0, 100.0))
    assert p.phase_durations() == pytest.approx([0.2, 0.3, 0.2, 0.3, 0.2, 0.3, 0.2], abs=1e-12)
    assert p.duration == pytest.approx(1.7, abs=1e-12)
    _, v, a = p.evaluate(np.array([0.2, 0.7, 0.85]))
    assert a[0] == pytest.approx(20.0)
    assert v[1] == pytest.approx(10.0)
    assert v[2] == pytest.approx(10.0) and a[2] == pytest.approx(0.0, abs=1e-12)


def test_scurve_not_reaching_accel():
    # v=1, A=20, J=100: dv = 1 < A^2/J = 4, so peak accel sqrt(dv J) = 10 and the ramp lasts
    # 2 sqrt(dv/J) = 0.2 s, distance 0.1 each side; D=1: cruise 0.8 s, total 1.2 s
    p = plan_move(1.0, Limits(1.0, 20.0, 20.0, 100.0, 100.0))
    assert p.duration == pytest.approx(1.2, abs=1e-12)
    _, _, a = p.evaluate(np.array([0.1]))
    assert a[0] == pytest.approx(10.0)


def test_scurve_short_move_peak_closed_form():
    # both ramps saturated: vp^2 (1/2A + 1/2D) + vp (A/2J + D/2J) = dist; A=D=20, J=100,
    # dist=2: vp^2/20 + 0.2 vp - 2 = 0 -> vp = (-4 + sqrt(176))/2
    vp = (-4 + math.sqrt(176.0)) / 2
    p = plan_move(2.0, Limits(10.0, 20.0, 20.0, 100.0, 100.0))
    assert p.duration == pytest.approx(2 * (vp / 20 + 0.2), abs=1e-12)
    assert p.end_position == 2.0


def test_scurve_short_move_unsaturated_closed_form():
    # both ramps below full accel: dist = vp^1.5 (1/sqrt(Ja) + 1/sqrt(Jd)); Ja=Jd=100, dist=0.2
    # -> vp^1.5 = 0.2 / 0.2 = 1 -> vp = 1 (< A^2/J = 4), each ramp 2 sqrt(1/100) = 0.2 s
    p = plan_move(0.2, Limits(10.0, 20.0, 20.0, 100.0, 100.0))
    assert p.duration == pytest.approx(0.4, abs=1e-12)
    _, v, _ = p.evaluate(np.array([0.2]))
    assert v[0] == pytest.approx(1.0, abs=1e-12)


def test_scurve_asymmetric_mixed_case():
    # accel ramp saturated (A=10, Ja=1000: knee 0.1), decel ramp not (D=10, Jd=1: knee 100);
    # the planner's peak must make the distances add up: D(vp) = vp/2 (vp/A + A/Ja + 2 sqrt(vp/Jd))
    lim = Limits(100.0, 10.0, 10.0, 1000.0, 1.0)
    p = plan_move(5.0, lim)
    vp = float(np.max(p.evaluate(np.linspace(0, p.duration, 20001))[1]))
    expected = vp / 2 * (vp / 10 + 0.01 + 2 * math.sqrt(vp / 1.0))
    assert expected == pytest.approx(5.0, rel=1e-6)
    assert p.duration == pytest.approx(vp / 10 + 0.01 + 2 * math.sqrt(vp), rel=1e-9)


def test_evaluate_matches_scalar_and_is_continuous():
    p = plan_move(7.0, Limits(4.0, 3.0, 5.0, 20.0, 11.0))
    t = np.linspace(0, p.duration, 4001)
    pos, vel, acc = p.evaluate(t)
    for k in range(0, 4001, 397):
        assert p.at(float(t[k])) == pytest.approx((pos[k], vel[k], acc[k]), abs=1e-12)
    # S-curve: acceleration continuous, so velocity differences are smooth
    assert np.max(np.abs(np.diff(acc))) < 20.0 * (t[1] - t[0]) * 1.01
    assert np.max(np.abs(np.diff(pos))) <= 4.0 * (t[1] - t[0]) * 1.0001
    assert pos[-1] == 7.0


def test_merge_from_moving_keeps_velocity():
    lim = Limits(10.0, 20.0, 20.0)
    p = plan_move(20.0, lim, v0=5.0)
    # from 5 to 10: 0.25 s covering 1.875; stop: 0.5 s covering 2.5; cruise (20-4.375)/10
    assert p.duration == pytest.approx(0.25 + 0.5 + 15.625 / 10, abs=1e-12)
    assert p.at(0.0)[1] == 5.0


def test_merge_overshoot_comes_back():
    # moving at 10 towards a target 1 ahead with decel 20: stopping takes 2.5 > 1, so the
    # axis stops 1.5 past the target (0.5 s) and moves back 1.5 as a rest-to-rest move
    lim = Limits(10.0, 20.0, 20.0)
    p = plan_move(1.0, lim, v0=10.0)
    back = 2 * math.sqrt(1.5 / 20)  # symmetric triangle over 1.5: t = 2 sqrt(d/a)
    assert p.duration == pytest.approx(0.5 + back, abs=1e-12)
    assert p.evaluate(np.array([0.5]))[0][0] == pytest.approx(2.5)
    assert p.end_position == 1.0


def test_jog_and_stop():
    j = plan_jog(-8.0, Limits(8.0, 4.0, 2.0))
    assert j.duration == math.inf
    assert j.at(2.0)[1] == pytest.approx(-8.0)  # 8/4 = 2 s ramp
    assert j.at(3.0)[0] == pytest.approx(-8.0 - 8.0)  # 8 during the ramp, then 8 per s
    s = plan_stop(6.0, Limits(0.0, 3.0, 3.0))
    assert s.duration == pytest.approx(2.0)  # 6 / 3
    assert s.end_position == pytest.approx(6.0)  # 6^2 / (2*3)


def test_change_time_formula():
    assert change_time(10.0, 20.0, math.inf) == pytest.approx(0.5)
    assert change_time(10.0, 20.0, 100.0) == pytest.approx(0.7)
    assert change_time(1.0, 20.0, 100.0) == pytest.approx(0.2)


def test_ruckig_oracle_durations():
    import ruckig  # a test extra (pyproject)

    cases = [
        (10.0, Limits(10.0, 20.0, 20.0), math.inf),
        (2.0, Limits(10.0, 20.0, 20.0), math.inf),
        (10.0, Limits(10.0, 20.0, 20.0, 100.0, 100.0), 100.0),
        (2.0, Limits(10.0, 20.0, 20.0, 100.0, 100.0), 100.0),
        (0.2, Limits(10.0, 20.0, 20.0, 100.0, 100.0), 100.0),
        (37.0, Limits(3.0, 7.0, 7.0, 11.0, 11.0), 11.0),
    ]
    for dist, lim, jerk in cases:
        inp = ruckig.InputParameter(1)
        inp.current_position = [0.0]
        inp.target_position = [dist]
        inp.max_velocity = [lim.speed]
        inp.max_acceleration = [lim.accel]
        inp.max_jerk = [jerk if math.isfinite(jerk) else 1e12]
        traj = ruckig.Trajectory(1)
        res = ruckig.Ruckig(1).calculate(inp, traj)
        assert res == ruckig.Result.Working
        tol = 1e-6 if math.isfinite(jerk) else 1e-5  # 1e12 stands in for infinite jerk
        assert plan_move(dist, lim).duration == pytest.approx(traj.duration, abs=tol)
