"""MCCP cam profiles against closed forms: linear exact, smoothstep, clamped spline checks."""

from __future__ import annotations

import numpy as np
import pytest

from interpreter.motion import (
    ExecutionMode,
    MotionError,
    MotionParameterError,
    calculate_cam_profile,
    time_cam_trajectory,
)
from interpreter.motion.cam import ProfileBank


def test_linear_segments_exact():
    p = calculate_cam_profile([0, 1, 3], [0, 2, 0], [0, 0, 0])
    x = np.array([0.0, 0.5, 1.0, 2.0, 3.0])
    pos, vel, acc = p.evaluate(x)
    assert pos == pytest.approx([0.0, 1.0, 2.0, 1.0, 0.0], abs=1e-15)
    assert vel == pytest.approx([2.0, 2.0, -1.0, -1.0, -1.0])
    assert acc == pytest.approx([0.0] * 5)


def test_single_cubic_with_zero_slopes_is_smoothstep():
    # cubic through (0,0) and (1,1) with slopes 0 at both ends: 3s^2 - 2s^3
    p = calculate_cam_profile([0, 1], [0, 1], [1, 0])
    s = np.linspace(0, 1, 11)
    pos, vel, acc = p.evaluate(s)
    assert pos == pytest.approx(3 * s**2 - 2 * s**3, abs=1e-14)
    assert vel == pytest.approx(6 * s - 6 * s**2, abs=1e-14)
    assert acc == pytest.approx(6 - 12 * s, abs=1e-14)


def test_scaled_smoothstep_with_slopes():
    # over [2, 6] from 1 to 9 with start slope 0.5, end slope 3: Hermite cubic
    p = calculate_cam_profile([2, 6], [1, 9], [1, 1], start_slope=0.5, end_slope=3.0)
    h, y0, y1, m0, m1 = 4.0, 1.0, 9.0, 0.5, 3.0
    u = np.linspace(0, 1, 9)
    herm = (
        (2 * u**3 - 3 * u**2 + 1) * y0
        + (u**3 - 2 * u**2 + u) * h * m0
        + (-2 * u**3 + 3 * u**2) * y1
        + (u**3 - u**2) * h * m1
    )
    assert p.evaluate(2 + h * u)[0] == pytest.approx(herm, abs=1e-13)


def test_cubic_run_continuity_and_end_slopes():
    xm = [0.0, 0.7, 1.5, 2.0, 3.2]
    ys = [0.0, 1.0, -0.5, 2.0, 2.5]
    p = calculate_cam_profile(xm, ys, [1, 1, 1, 1, 1], start_slope=1.5, end_slope=-2.0)
    eps = 1e-9
    for k in xm[1:-1]:
        lo = p.evaluate(np.array([k - eps]))
        hi = p.evaluate(np.array([k + eps]))
        for q in range(3):  # position, velocity and acceleration continuous at knots
            assert lo[q][0] == pytest.approx(hi[q][0], abs=1e-6)
    assert p.evaluate(np.array(xm))[0] == pytest.approx(ys, abs=1e-12)
    assert p.evaluate(np.array([0.0]))[1][0] == pytest.approx(1.5)
    assert p.evaluate(np.array([3.2]))[1][0] == pytest.approx(-2.0)


def test_uniform_spline_matches_hand_solution():
    # knots 0,1,2 with y 0,1,0, clamped slopes 0: the middle slope m solves
    # m0 + 4 m1 + m2 = 3 (y2 - y0) = 0 -> m1 = 0; so each half is a smoothstep
    p = calculate_cam_profile([0, 1, 2], [0, 1, 0], [1, 1, 1])
    s = np.linspace(0, 1, 5)
    assert p.evaluate(s)[0] == pytest.approx(3 * s**2 - 2 * s**3, abs=1e-14)
    assert p.evaluate(1 + s)[0] == pytest.approx(1 - (3 * s**2 - 2 * s**3), abs=1e-14)


def test_joint_with_linear_segment_takes_its_slope():
    # linear 0->1 on [0,1] (slope 1), then cubic on [1,2] to 3 with end slope 0: the cubic
    # starts with slope 1, so velocity is continuous at x = 1; start slope is ignored
    p = calculate_cam_profile([0, 1, 2], [0, 1, 3], [0, 1, 0], start_slope=7.0, end_slope=0.0)
    assert p.evaluate(np.array([0.0]))[1][0] == pytest.approx(1.0)
    assert p.evaluate(np.array([1.0 + 1e-12]))[1][0] == pytest.approx(1.0, abs=1e-9)
    assert p.evaluate(np.array([2.0]))[1][0] == pytest.approx(0.0, abs=1e-12)
    # Hermite on [1,2]: y0=1, y1=3, m0=1, m1=0 at u=0.5: 0.5*1 + 0.125*1 + 0.5*3 - 0.125*0
    assert p.evaluate(np.array([1.5]))[0][0] == pytest.approx(0.5 + 0.125 + 1.5)


def test_last_point_segment_type_unused():
    a = calculate_cam_profile([0, 1, 2], [0, 1, 2], [0, 0, 1])
    b = calculate_cam_profile([0, 1, 2], [0, 1, 2], [0, 0, 0])
    x = np.linspace(0, 2, 9)
    assert a.evaluate(x)[0] == pytest.approx(b.evaluate(x)[0])


def test_bad_cams_report_the_logix_cam_errors():
    # stdlib/motion_errors.toml: 26 Illegal Cam Length, 28 Illegal Cam Type, 29 Illegal Cam Order
    with pytest.raises(MotionParameterError) as e:
        calculate_cam_profile([0, 1, 1], [0, 1, 2], [0, 0, 0])
    assert e.value.error == MotionError.ILLEGAL_CAM_ORDER and e.value.exerr == 1
    with pytest.raises(MotionParameterError) as e:
        calculate_cam_profile([0], [0], [0])
    assert e.value.error == MotionError.ILLEGAL_CAM_LENGTH and e.value.exerr == 2
    with pytest.raises(MotionParameterError) as e:
        calculate_cam_profile([0, 1], [0, 1], [2, 0])
    assert e.value.error == MotionError.ILLEGAL_CAM_TYPE
    with pytest.raises(MotionParameterError) as e:
        calculate_cam_profile([0, 1], [0, float("nan")], [0, 0])
    assert e.value.error == MotionError.PARAMETER_OUT_OF_RANGE


def test_profile_bank_matches_individual_profiles():
    p1 = calculate_cam_profile([0, 1, 2], [0, 1, 0], [1, 1, 1])
    p2 = calculate_cam_profile([5, 6, 9, 10], [1, 0, 4, 4], [0, 1, 1, 0], 0.0, 0.0)
    bank = ProfileBank([p1, p2])
    rng = np.random.default_rng(1)
    prof = rng.integers(0, 2, 200)
    spans = np.array([p1.span, p2.span])
    local = rng.random(200) * spans[prof]
    local[:4] = [0.0, spans[prof[1]], 0.0, spans[prof[3]]]  # the ends too
    pos, vel, acc = bank.evaluate(prof, local)
    for k in range(200):
        p = (p1, p2)[prof[k]]
        ref = p.evaluate(np.array([p.start + local[k]]))
        assert (pos[k], vel[k], acc[k]) == pytest.approx((ref[0][0], ref[1][0], ref[2][0]))


def test_time_cam_trajectory_once_and_continuous():
    p = calculate_cam_profile([0, 1], [2, 5], [0, 0])  # linear, P(0)=2, net 3
    t = np.array([0.0, 1.0, 2.0, 3.0, 5.0])
    once, _, _ = time_cam_trajectory(p, t, distance_scaling=2.0, time_scaling=2.0)
    # contribution 2 * (P(t/2) - 2) = 2 * 3 * t/2 = 3 t until t = 2, then held at 6
    assert once == pytest.approx([0.0, 3.0, 6.0, 6.0, 6.0])
    cont, v, _ = time_cam_trajectory(p, t, 2.0, 2.0, ExecutionMode.CONTINUOUS, direction=-1.0)
    assert cont == pytest.approx([0.0, -3.0, -6.0, -9.0, -15.0])
    assert v == pytest.approx([-3.0] * 5)
