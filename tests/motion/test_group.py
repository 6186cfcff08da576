"""MotionGroup: timing rule, servo model, superposition, stops, merges, errors."""

from __future__ import annotations

import math

import numpy as np
import pytest

from interpreter.motion import (
    AxisKind,
    EventKind,
    MergeMode,
    MotionError,
    MotionGroup,
    MoveType,
    ProfileShape,
    StopType,
)


def kinds(events, handle):
    return [e.kind for e in events if e.handle == handle]


def run(g: MotionGroup, n: int) -> list:
    out = []
    for _ in range(n):
        out += g.update()
    return out


def trapezoid_pos(t: float) -> float:
    """D=10, v=10, a=20, d=40 (see test_profiles): accel to 0.5, cruise to 1.125, stop 1.375."""
    if t <= 0.5:
        return 10.0 * t * t
    if t <= 1.125:
        return 2.5 + 10.0 * (t - 0.5)
    if t <= 1.375:
        r = 1.375 - t
        return 10.0 - 20.0 * r * r
    return 10.0


def test_move_follows_hand_profile_and_timing_rule():
    g = MotionGroup(0.001)
    a = g.add_axis("x")
    run(g, 3)  # updates at t = 0, 1 ms, 2 ms
    r = g.start_move(a, MoveType.INCREMENTAL, 10.0, 10.0, 20.0, 40.0)
    assert r.ok and r.handle > 0
    ev = g.update()  # t = 3 ms: the move's own clock is 0, no motion yet
    assert kinds(ev, r.handle)[0] == EventKind.IN_PROCESS
    assert g.command_position[a] == 0.0
    assert g.status["MoveStatus"][a]
    for k in range(1, 1400):
        ev = g.update()
        assert g.command_position[a] == pytest.approx(trapezoid_pos(k * 0.001), abs=1e-9)
        if EventKind.COMPLETE in kinds(ev, r.handle):
            assert k == 1375
    assert not g.status["MoveStatus"][a]
    assert g.command_position[a] == 10.0
    assert g.actual_position[a] == 10.0  # virtual: actual = command


def test_absolute_move_and_accel_decel_status():
    g = MotionGroup(0.01)
    a = g.add_axis("x", position=4.0)
    r = g.start_move(a, MoveType.ABSOLUTE, 1.0, 1.0, 1.0, 1.0)
    ev = run(g, 2)
    assert g.status["AccelStatus"][a] and not g.status["DecelStatus"][a]
    assert EventKind.ACCEL in kinds(ev, r.handle)
    # 3 units back at speed 1 with a = d = 1: accel 1 s (0.5), cruise 2 s, decel 1 s (0.5)
    ev = run(g, 308)  # t = 3.09: decelerating
    assert g.status["DecelStatus"][a] and not g.status["AccelStatus"][a]
    assert EventKind.DECEL in kinds(ev, r.handle)
    assert g.command_position[a] == pytest.approx(1.0 + 0.5 * 0.91**2, abs=1e-9)
    ev = run(g, 91)  # t = 4.0
    assert EventKind.COMPLETE in kinds(ev, r.handle)
    assert g.command_position[a] == pytest.approx(1.0, abs=1e-12)


def test_motion_status_word_bits():
    g = MotionGroup(0.01)
    a = g.add_axis("x")
    g.start_jog(a, 0, 1.0, 10.0, 10.0)
    run(g, 2)
    word = int(g.motion_status_word()[a])
    assert word & (1 << 3)  # JogStatus
    assert word & (1 << 0)  # AccelStatus


def test_servo_axis_needs_mso_and_lags_command():
    cup, tau, v = 0.001, 0.004, 10.0
    g = MotionGroup(cup)
    s = g.add_axis("s", AxisKind.CIP_DRIVE, tau=tau)
    r = g.start_jog(s, 0, v, 1e6, 1e6)
    assert r.error == MotionError.SERVO_OFF_STATE
    g.servo_on_axis(s)
    assert g.start_jog(s, 0, v, 1e6, 1e6).ok
    run(g, 500)
    # first-order lag: e = (1 - alpha)(e + v cup) at steady state, alpha = 1 - exp(-cup/tau)
    q = math.exp(-cup / tau)
    err = q * v * cup / (1 - q)
    assert g.command_position[s] - g.actual_position[s] == pytest.approx(err, rel=1e-6)
    assert g.actual_velocity[s] == pytest.approx(v, rel=1e-6)


def test_servo_off_ends_motion_and_command_tracks_actual():
    g = MotionGroup(0.001)
    s = g.add_axis("s", AxisKind.CIP_DRIVE, tau=0.002)
    g.servo_on_axis(s)
    r = g.start_jog(s, 0, 5.0, 100.0, 100.0)
    run(g, 300)
    g.servo_off_axis(s)
    ev = run(g, 1)
    assert EventKind.ENDED in kinds(ev, r.handle)
    held = g.actual_position[s]
    run(g, 10)
    assert g.actual_position[s] == held
    assert g.command_position[s] == held
    assert not g.status["ServoActionStatus"][s]


def test_virtual_axis_mso_msf_have_no_effect():
    g = MotionGroup(0.01)
    a = g.add_axis("v")
    assert g.servo_off_axis(a).ok and g.servo_on[a]
    assert g.start_jog(a, 1, 1.0, 100.0, 100.0).ok


def test_superposition_and_selective_stop():
    g = MotionGroup(0.01)
    a = g.add_axis("x")
    jog = g.start_jog(a, 0, 2.0, 1e9, 1e9)  # effectively a step to 2 u/s
    mv = g.start_move(a, MoveType.INCREMENTAL, 1.0, 1.0, 1e9, 1e9)
    run(g, 102)  # t = 0 .. 1.01 s: jog 2 u/s, move of 1 done just after t = 1
    assert g.command_position[a] == pytest.approx(1.0 + 2 * 1.01, abs=1e-6)
    assert g.command_velocity[a] == pytest.approx(2.0)
    stop = g.stop(a, StopType.MOVE)  # nothing to stop: completes at the next update
    ev = g.update()
    assert kinds(ev, stop.handle)[-1] == EventKind.COMPLETE
    assert jog.handle not in [e.handle for e in ev if e.kind == EventKind.ENDED]
    assert mv.handle not in [e.handle for e in ev]


def test_stop_decelerates_with_given_decel():
    g = MotionGroup(0.001)
    a = g.add_axis("x")
    jog = g.start_jog(a, 0, 10.0, 1e9, 1e9)
    run(g, 100)
    p0 = g.command_position[a]
    st = g.stop(a, StopType.JOG, decel=20.0)
    ev = g.update()  # stop begins here at 10 u/s: v^2/2d = 2.5 further, 0.5 s
    assert EventKind.ENDED in kinds(ev, jog.handle)
    assert g.status["StoppingStatus"][a] and not g.status["JogStatus"][a]
    assert g.command_velocity[a] == pytest.approx(10.0)
    ev = run(g, 500)
    assert EventKind.COMPLETE in kinds(ev, st.handle)
    assert g.command_position[a] - p0 == pytest.approx(10.0 * 0.001 + 2.5, abs=1e-9)
    assert not g.status["StoppingStatus"][a]


def test_s_curve_stop_uses_jerk():
    g = MotionGroup(0.001)
    a = g.add_axis("x")
    g.start_jog(a, 0, 10.0, 1e9, 1e9)
    run(g, 10)
    p0 = g.command_position[a]
    st = g.stop(a, StopType.ALL, decel=20.0, decel_jerk=100.0)
    ev = run(g, 2000)
    done = [i for i, e in enumerate(ev) if e.handle == st.handle and e.kind == EventKind.COMPLETE]
    assert done
    # S-curve stop from 10: T = v/D + D/J = 0.7 s, distance v/2 * T = 3.5
    assert g.command_position[a] - p0 == pytest.approx(0.01 + 3.5, abs=1e-9)


def test_new_move_replaces_running_one_with_velocity_continuity():
    g = MotionGroup(0.001)
    a = g.add_axis("x")
    m1 = g.start_move(a, MoveType.ABSOLUTE, 100.0, 10.0, 20.0, 20.0)
    run(g, 1000)  # at speed 10 after 0.5 s
    m2 = g.start_move(a, MoveType.ABSOLUTE, 20.0, 10.0, 20.0, 20.0)
    before = g.command_velocity[a]
    ev = g.update()
    assert EventKind.ENDED in kinds(ev, m1.handle)
    assert g.command_velocity[a] == pytest.approx(before)
    vel = []
    for _ in range(3000):
        g.update()
        vel.append(g.command_velocity[a])
    assert np.max(np.abs(np.diff(vel))) <= 20.0 * 0.001 + 1e-9  # no velocity jump
    assert g.command_position[a] == pytest.approx(20.0, abs=1e-9)
    assert m2.ok


def test_incremental_replacement_adds_to_previous_end_point():
    g = MotionGroup(0.01)
    a = g.add_axis("x")
    g.start_move(a, MoveType.INCREMENTAL, 10.0, 5.0, 10.0, 10.0)
    run(g, 50)
    g.start_move(a, MoveType.INCREMENTAL, 3.0, 5.0, 10.0, 10.0)
    run(g, 1000)
    assert g.command_position[a] == pytest.approx(13.0, abs=1e-9)


def test_merge_all_takes_over_jog():
    g = MotionGroup(0.01)
    a = g.add_axis("x")
    jog = g.start_jog(a, 0, 4.0, 1e9, 1e9)
    run(g, 10)
    mv = g.start_move(a, MoveType.ABSOLUTE, 10.0, 4.0, 8.0, 8.0, merge=MergeMode.ALL)
    ev = run(g, 1000)
    assert EventKind.ENDED in kinds(ev, jog.handle)
    assert EventKind.COMPLETE in kinds(ev, mv.handle)
    assert g.command_position[a] == pytest.approx(10.0, abs=1e-9)
    assert not g.status["JogStatus"][a]


def test_parameter_errors_carry_operand_index():
    g = MotionGroup(0.01)
    a = g.add_axis("x")
    r = g.start_move(a, MoveType.ABSOLUTE, 1.0, -1.0, 1.0, 1.0)
    assert (r.error, r.exerr) == (MotionError.PARAMETER_OUT_OF_RANGE, 4)
    r = g.start_move(a, MoveType.ABSOLUTE, 1.0, 1.0, 0.0, 1.0)
    assert r.exerr == 6
    r = g.start_move(a, MoveType.ABSOLUTE, 1.0, 1.0, 1.0, 1.0, ProfileShape.S_CURVE, 0.0, 1.0)
    assert r.exerr == 11
    r = g.start_jog(a, 0, 1.0, 1.0, -2.0)
    assert r.exerr == 7
    r = g.start_jog(a, 3, 1.0, 1.0, 1.0)
    assert r.exerr == 2
    assert g.stop(a, 42).exerr == 2
    r = g.start_move(a, MoveType.ABSOLUTE, 1.0, 1.0, 1.0, 1.0, lock_direction=1)
    assert r.error == MotionError.LOCK_DIRECTION_CONFLICT
    r = g.start_move(a, MoveType.ABSOLUTE, 1.0, 1.0, 1.0, 1.0, master_driven=True)
    assert r.error == MotionError.MDSC_NOT_ACTIVATED
    assert g.assign_master(a, a).error == MotionError.PARAMETER_OUT_OF_RANGE


def test_group_stop_stops_every_axis():
    g = MotionGroup(0.01)
    a = g.add_axis("a", max_decel=10.0)
    b = g.add_axis("b", max_decel=5.0)
    g.start_jog(a, 0, 10.0, 1e9, 1e9)
    g.start_jog(b, 1, 5.0, 1e9, 1e9)
    run(g, 5)
    mgs = g.stop_group()
    ev = run(g, 200)
    done = [e for e in ev if e.handle == mgs.handle and e.kind == EventKind.COMPLETE]
    assert len(done) == 1
    assert np.all(g.command_velocity == 0.0)
    # decel 10 from 10 takes 1 s; decel 5 from 5 takes 1 s: both stop by t = 1.05
    assert not g.status["StoppingStatus"].any()
