"""MATC time cams and MDAC master-driven motion against analytic values."""

from __future__ import annotations

import numpy as np
import pytest

from interpreter.motion import (
    AxisKind,
    CamDirection,
    EventKind,
    ExecutionMode,
    ExecutionSchedule,
    InstructionMode,
    LockDirection,
    MasterReference,
    MotionError,
    MotionGroup,
    MotionType,
    MoveType,
    StopType,
    calculate_cam_profile,
)

ONCE, CONT = ExecutionMode.ONCE, ExecutionMode.CONTINUOUS
PENDING = ExecutionSchedule.PENDING
MD = InstructionMode.MASTER_DRIVEN

# linear ramp: P(x) = 2 + 3x on [0, 1] (P(0) = 2, net change 3)
RAMP = calculate_cam_profile([0.0, 1.0], [2.0, 5.0], [0, 0])
# smoothstep rise 0 -> 1 over [0, 1]
RISE = calculate_cam_profile([0.0, 1.0], [0.0, 1.0], [1, 1])


def kinds(events, handle):
    return [e.kind for e in events if e.handle == handle]


def smooth(s: float) -> float:
    return 3 * s * s - 2 * s**3


def test_once_scaled_holds_and_completes():
    # DS = 2, TS = 4: contribution 2 * (P(t/4) - P(0)) = 6 t / 4 = 1.5 t until t = 4, then 6
    g = MotionGroup(0.01)
    a = g.add_axis("x")
    r = g.start_time_cam(a, RAMP, distance_scaling=2.0, time_scaling=4.0)
    assert r.ok
    for k in range(500):
        ev = g.update()
        t = k * 0.01
        assert g.command_position[a] == pytest.approx(1.5 * min(t, 4.0), abs=1e-9)
        if k == 0:
            assert kinds(ev, r.handle) == [EventKind.IN_PROCESS]
        if k < 400:
            assert g.status["TimeCamStatus"][a]
            assert g.command_velocity[a] == pytest.approx(1.5)
        if k == 400:
            assert kinds(ev, r.handle) == [EventKind.COMPLETE]
            assert not g.status["TimeCamStatus"][a]
    assert g.command_velocity[a] == 0.0


def test_continuous_adds_net_change_each_pass():
    g = MotionGroup(0.01)
    a = g.add_axis("x")
    g.start_time_cam(a, RISE, execution_mode=CONT, time_scaling=0.5)
    for k in range(251):
        g.update()
        x = (k * 0.01) / 0.5
        n = np.floor(x)
        assert g.command_position[a] == pytest.approx(n + smooth(x - n), abs=1e-9)


def test_directions_same_opposite_reverse_unchanged():
    def final(dirs):
        g = MotionGroup(0.01)
        a = g.add_axis("x")
        out = []
        for d in dirs:
            p0 = g.command_position[a]
            assert g.start_time_cam(a, RAMP, direction=d).ok
            for _ in range(101):
                g.update()
            out.append(round(float(g.command_position[a] - p0), 9))
        return out

    D = CamDirection
    assert final([D.REVERSE]) == [-3.0]  # first time Reverse: Opposite
    assert final([D.UNCHANGED]) == [3.0]  # first time Unchanged: Same
    assert final([D.OPPOSITE, D.UNCHANGED, D.REVERSE, D.REVERSE]) == [-3.0, -3.0, 3.0, -3.0]
    assert final([D.SAME, D.REVERSE, D.SAME]) == [3.0, -3.0, 3.0]


def test_immediate_while_active_is_err_23_pending_is_allowed():
    g = MotionGroup(0.01)
    a = g.add_axis("x")
    assert g.start_time_cam(a, RAMP).ok
    assert g.start_time_cam(a, RAMP).error == MotionError.ILLEGAL_DYNAMIC_CHANGE
    g.update()
    assert g.start_time_cam(a, RAMP).error == MotionError.ILLEGAL_DYNAMIC_CHANGE
    assert g.start_time_cam(a, RAMP, execution_schedule=PENDING).ok


def test_cam_errors():
    g = MotionGroup(0.01)
    a = g.add_axis("x")
    assert g.start_time_cam(a, None).error == MotionError.CAM_PROFILE_NOT_CALCULATED
    r = g.start_time_cam(a, RAMP, time_scaling=0.0)
    assert (r.error, r.exerr) == (MotionError.PARAMETER_OUT_OF_RANGE, 5)
    assert g.start_time_cam(a, RAMP, direction=4).exerr == 2
    assert g.start_time_cam(a, RAMP, execution_mode=2).exerr == 6
    assert g.start_time_cam(a, RAMP, lock_direction=7).exerr == 9
    for ld in (1, 2, 3, 4):  # time driven with a lock direction
        r = g.start_time_cam(a, RAMP, lock_direction=ld)
        assert r.error == MotionError.LOCK_DIRECTION_CONFLICT
    r = g.start_time_cam(a, RAMP, execution_schedule=PENDING, lock_direction=3)
    assert r.error == MotionError.LOCK_DIRECTION_CONFLICT
    assert g.start_time_cam(a, RAMP, instruction_mode=MD).error == MotionError.MDSC_NOT_ACTIVATED
    s = g.add_axis("s", AxisKind.CIP_DRIVE)
    assert g.start_time_cam(s, RAMP).error == MotionError.SERVO_OFF_STATE


def test_pending_after_once_carries_leftover_time():
    # cup 0.3 does not divide the 1 s pass: at t = 1.2 the first cam (x -> x, net 1) is done
    # and the pending cam (2 per 0.5 s) has run 0.2 s: 1 + 2 * 0.2 / 0.5 = 1.8
    lin1 = calculate_cam_profile([0, 1], [0, 1], [0, 0])
    lin2 = calculate_cam_profile([0, 0.5], [0, 2], [0, 0])
    g = MotionGroup(0.3)
    a = g.add_axis("x")
    first = g.start_time_cam(a, lin1)
    second = g.start_time_cam(a, lin2, execution_schedule=PENDING, execution_mode=CONT)
    ev = []
    for _ in range(4):  # t = 0, .3, .6, .9
        ev += g.update()
    assert g.status["TimeCamPendingStatus"][a]
    assert g.command_position[a] == pytest.approx(0.9)
    ev = g.update()  # t = 1.2
    assert kinds(ev, first.handle) == [EventKind.COMPLETE]
    assert EventKind.PENDING_STARTED in kinds(ev, second.handle)
    assert g.command_position[a] == pytest.approx(1.8, abs=1e-12)
    assert not g.status["TimeCamPendingStatus"][a] and g.status["TimeCamStatus"][a]
    g.update()  # t = 1.5: 1 + 4 * 0.5 = 3
    assert g.command_position[a] == pytest.approx(3.0, abs=1e-12)
    g.update()  # t = 1.8: second pass of the pending cam, 1 + 2 + 4 * 0.3
    assert g.command_position[a] == pytest.approx(4.2, abs=1e-12)


def test_pending_after_continuous_ends_it_without_completion():
    g = MotionGroup(0.01)
    a = g.add_axis("x")
    first = g.start_time_cam(a, RISE, execution_mode=CONT)
    ev = []
    for _ in range(150):  # into the second pass (t = 1.49)
        ev += g.update()
    second = g.start_time_cam(a, RAMP, execution_schedule=PENDING, direction=CamDirection.SAME)
    for _ in range(60):  # hand-over at t = 2.0, then 0.09 s of the ramp (3 per s)
        ev += g.update()
    assert kinds(ev, first.handle) == [EventKind.IN_PROCESS, EventKind.ENDED]
    assert EventKind.PENDING_STARTED in kinds(ev, second.handle)
    assert g.command_position[a] == pytest.approx(2.0 + 3 * 0.09, abs=1e-9)


def test_pending_without_active_cam_waits_for_an_immediate_one():
    g = MotionGroup(0.01)
    a = g.add_axis("x")
    pend = g.start_time_cam(a, RAMP, execution_schedule=PENDING)
    for _ in range(50):
        g.update()
    assert g.command_position[a] == 0.0 and g.status["TimeCamPendingStatus"][a]
    g.start_time_cam(a, RISE)
    ev = []
    for _ in range(150):  # rise done at t = 1.5 (started at 0.5), ramp 0.49 s after
        ev += g.update()
    assert EventKind.PENDING_STARTED in kinds(ev, pend.handle)
    assert g.command_position[a] == pytest.approx(1.0 + 3 * 0.49, abs=1e-9)


def test_mas_all_ends_time_cam_and_decelerates():
    g = MotionGroup(0.001)
    a = g.add_axis("x")
    cam = g.start_time_cam(a, RAMP, execution_mode=CONT)  # 3 u/s
    for _ in range(100):
        g.update()
    p0 = g.command_position[a]
    st = g.stop(a, StopType.ALL, decel=30.0)
    ev = g.update()
    assert kinds(ev, cam.handle) == [EventKind.ENDED]
    assert not g.status["TimeCamStatus"][a]
    assert g.status["StoppingStatus"][a]
    for _ in range(200):
        ev += g.update()
    assert EventKind.COMPLETE in kinds(ev, st.handle)
    # one more cam update (3 mm), then 3^2 / (2 * 30) = 0.15 to stop
    assert g.command_position[a] - p0 == pytest.approx(0.003 + 0.15, abs=1e-9)


def test_cam_superimposes_with_jog():
    g = MotionGroup(0.01)
    a = g.add_axis("x")
    g.start_time_cam(a, RAMP, execution_mode=CONT)
    g.start_jog(a, 1, 1.0, 1e9, 1e9)  # -1 u/s
    for _ in range(101):
        g.update()
    assert g.command_position[a] == pytest.approx(3.0 - 1.0, abs=1e-6)


def _master_slave(cup=0.01, reference=MasterReference.COMMAND, servo_master=False):
    g = MotionGroup(cup)
    m = g.add_axis("m", AxisKind.CIP_DRIVE if servo_master else AxisKind.VIRTUAL, tau=0.05)
    s = g.add_axis("s")
    if servo_master:
        g.servo_on_axis(m)
    link = g.assign_master(s, m, MotionType.ALL, reference)
    assert link.ok
    return g, m, s, link


def test_master_driven_cam_follows_master_distance_without_lag():
    g, m, s, link = _master_slave()
    g.set_position(m, 7.0)
    g.start_jog(m, 0, 2.0, 4.0, 4.0)  # master accelerates: non-trivial distance
    g.update()
    r = g.start_time_cam(s, RISE, distance_scaling=3.0, time_scaling=5.0, instruction_mode=MD,
                         execution_mode=CONT)  # fmt: skip
    assert r.ok
    ev = g.update()
    assert EventKind.ACTIVE in kinds(ev, link.handle)
    start = g.command_position[m]
    for _ in range(400):
        g.update()
        x = (g.command_position[m] - start) / 5.0  # same update: no lag
        n = np.floor(x)
        assert g.command_position[s] == pytest.approx(3.0 * (n + smooth(x - n)), abs=1e-9)
    assert g.status["CoordinatedMotionStatus"][s]


def test_master_driven_actual_reference_uses_lagging_actual():
    g, m, s, _ = _master_slave(reference=MasterReference.ACTUAL, servo_master=True)
    g.start_jog(m, 0, 1.0, 1e9, 1e9)
    g.start_time_cam(s, RAMP, time_scaling=10.0, instruction_mode=MD)
    start = g.actual_position[m]
    for _ in range(100):
        g.update()
    assert g.command_position[s] == pytest.approx(0.3 * (g.actual_position[m] - start))
    assert g.actual_position[m] < g.command_position[m] - 0.01  # really the lagging one


def test_forward_only_lock_ratchets():
    g, m, s, _ = _master_slave(cup=0.1)
    r = g.start_time_cam(s, RAMP, time_scaling=100.0, instruction_mode=MD,
                         lock_direction=LockDirection.IMMEDIATE_FORWARD_ONLY)  # fmt: skip
    assert r.ok
    g.update()
    path = [2.0, 5.0, 3.0, 1.0, 4.0, 6.0]  # master positions, one per update
    expect = [2.0, 5.0, 5.0, 5.0, 5.0, 6.0]  # the furthest forward distance so far
    locked = [True, True, False, False, False, True]
    for pos, e, lk in zip(path, expect, locked, strict=True):
        g.set_position(m, pos)
        g.update()
        assert g.command_position[s] == pytest.approx(0.03 * e)
        assert bool(g.status["TimeCamLockStatus"][s]) == lk


def test_position_forward_lock_counts_from_lock_position():
    g, m, s, _ = _master_slave(cup=0.1)
    g.start_time_cam(s, RAMP, time_scaling=100.0, instruction_mode=MD, lock_position=2.5,
                     lock_direction=LockDirection.POSITION_FORWARD)  # fmt: skip
    g.update()
    for pos, e in ((1.0, 0.0), (2.0, 0.0), (4.0, 1.5), (3.0, 1.5), (7.0, 4.5)):
        g.set_position(m, pos)
        g.update()
        assert g.command_position[s] == pytest.approx(0.03 * e)


def test_master_driven_move_profile_in_master_units():
    # slave moves 4 with speed 1 per master unit, accel/decel 0.5 per master unit^2:
    # accel over v/a = 2 master units covering v^2/2a = 1, cruise 2, decel over 2 covering 1:
    # done after 6 master units
    g, m, s, link = _master_slave(cup=0.01)
    g.start_jog(m, 0, 2.0, 1e9, 1e9)
    g.update()
    mv = g.start_move(s, MoveType.INCREMENTAL, 4.0, 1.0, 0.5, 0.5, master_driven=True)
    assert mv.ok
    ev = g.update()
    start = g.command_position[m]
    assert EventKind.ACTIVE in kinds(ev, link.handle)
    done_at = None
    for _ in range(400):
        ev = g.update()
        d = g.command_position[m] - start
        exp = 0.25 * d * d if d <= 2 else (1 + (d - 2) if d <= 4 else 4 - 0.25 * (6 - d) ** 2)
        assert g.command_position[s] == pytest.approx(exp if d < 6 else 4.0, abs=1e-9)
        if EventKind.COMPLETE in kinds(ev, mv.handle):
            done_at = d
    assert done_at == pytest.approx(6.0, abs=0.02 + 1e-9)


def test_mas_all_on_slave_breaks_link():
    g, m, s, link = _master_slave()
    g.start_time_cam(s, RAMP, instruction_mode=MD)
    g.update()
    g.stop(s, StopType.ALL)
    ev = g.update()
    assert EventKind.ENDED in kinds(ev, link.handle)
    assert not g.status["CoordinatedMotionStatus"][s]
    assert g.start_time_cam(s, RAMP, instruction_mode=MD).error == MotionError.MDSC_NOT_ACTIVATED


def test_chain_of_masters_is_computed_in_order():
    # m jogs; b cams on m's distance (P(x) = 2 + 3x, TS 1 -> 3 per master unit);
    # c cams on b's distance (same ramp, TS 3 -> 1 per b unit): c = 3 * (m distance), no lag
    g = MotionGroup(0.01)
    c = g.add_axis("c")  # added first so that index order is not the evaluation order
    b = g.add_axis("b")
    m = g.add_axis("m")
    assert g.assign_master(b, m).ok and g.assign_master(c, b).ok
    g.start_jog(m, 0, 1.0, 2.0, 2.0)
    g.start_time_cam(b, RAMP, time_scaling=1.0, instruction_mode=MD, execution_mode=CONT)
    g.start_time_cam(c, RAMP, time_scaling=3.0, instruction_mode=MD, execution_mode=CONT)
    g.update()
    start = g.command_position[m]
    for _ in range(200):
        g.update()
        d = g.command_position[m] - start
        assert g.command_position[b] == pytest.approx(3 * d, abs=1e-9)
        assert g.command_position[c] == pytest.approx(3 * d, abs=1e-9)


def test_master_driven_once_cam_holds_when_master_backs_up():
    g, m, s, _ = _master_slave(cup=0.1)
    g.start_time_cam(s, RAMP, time_scaling=10.0, instruction_mode=MD)
    g.update()
    for pos, e in ((4.0, 4.0), (-2.0, 0.0), (3.0, 3.0), (12.0, 10.0)):
        g.set_position(m, pos)
        ev = g.update()
        assert g.command_position[s] == pytest.approx(0.3 * e)
    assert not g.status["TimeCamStatus"][s]  # completed at the end of the profile
    assert any(e.kind == EventKind.COMPLETE for e in ev)


def test_group_matches_whole_trajectory_evaluation():
    from interpreter.motion import time_cam_trajectory

    prof = calculate_cam_profile([0, 0.3, 1.0, 1.4], [0, 1, -1, 0.5], [1, 1, 0, 0], 2.0, 0.0)
    g = MotionGroup(0.002)
    a = g.add_axis("x")
    g.start_time_cam(a, prof, CamDirection.OPPOSITE, 1.5, 0.7, CONT)
    got = []
    for _ in range(2000):
        g.update()
        got.append(g.command_position[a])
    t = np.arange(2000) * 0.002
    want, _, _ = time_cam_trajectory(prof, t, 1.5, 0.7, CONT, direction=-1.0)
    assert np.max(np.abs(np.array(got) - want)) < 1e-9


def test_servo_slave_actual_lags_its_cam():
    g = MotionGroup(0.001)
    s = g.add_axis("s", AxisKind.CIP_DRIVE, tau=0.01)
    g.servo_on_axis(s)
    g.start_time_cam(s, RAMP, execution_mode=CONT)  # 3 u/s
    for _ in range(1000):
        g.update()
    q = np.exp(-0.1)  # cup / tau = 0.1
    lag = 3.0 * 0.001 * q / (1 - q)
    assert g.command_position[s] - g.actual_position[s] == pytest.approx(lag, rel=1e-6)
