"""Core pieces of gearing (GearSet, MotionGroup.start_gear), position redefinition, homing
rules and dynamics changes, against hand formulas."""

from __future__ import annotations

import math

import numpy as np
import pytest

from interpreter.motion import (
    AxisKind,
    EventKind,
    MotionError,
    MotionGroup,
    MoveType,
    calculate_cam_profile,
)
from interpreter.motion.enums import GeneratorKind, HomeMode, HomeSequence, MasterReference
from interpreter.motion.gear import GearSet
from interpreter.motion.homing import homing_error

CUP = 0.001


def run(g: MotionGroup, n: int) -> list:
    out = []
    for _ in range(n):
        out += g.update()
    return out


# ------------------------------------------------------------------ GearSet
def test_gearset_locked_row_adds_ratio_times_master_travel() -> None:
    # two gears on one master at 0 (command reference): ratios 2 and -0.5; master moves to 3
    gs = GearSet()
    gs.add(1, 1, 0, MasterReference.COMMAND, 2.0, math.inf, 0.0, 0.0)
    gs.add(2, 2, 0, MasterReference.COMMAND, -0.5, math.inf, 0.0, 0.0)
    cmd = np.array([3.0, 0.0, 0.0])
    vel = np.array([1000.0, 0.0, 0.0])  # 3 units in 3 ms
    step = gs.step(0.003, None, (np.zeros(3), cmd), (np.zeros(3), vel))
    assert step.axis.tolist() == [1, 2]
    assert step.dpos.tolist() == [6.0, -1.5]
    assert step.vel.tolist() == [2000.0, -500.0]


def test_gearset_clutch_ramp_is_exact_for_constant_acceleration() -> None:
    # master at 10 units/s, ratio 2 -> geared speed 20; clutch 100 units/s^2, cup 1 ms:
    # v after k updates = 0.1 k, position = 50 (k cup)^2 exactly; locks at k = 200 (v/a = 0.2 s)
    gs = GearSet()
    gs.add(1, 1, 0, MasterReference.COMMAND, 2.0, 100.0, 0.0, 10.0)
    assert not gs.locked[0]
    pos, m = 0.0, 0.0
    for k in range(1, 301):
        m += 10.0 * CUP
        st = gs.step(
            CUP, None, (np.zeros(2), np.array([m, 0.0])), (np.zeros(2), np.array([10.0, 0.0]))
        )
        pos += float(st.dpos[0])
        if k <= 200:
            assert pos == pytest.approx(50.0 * (k * CUP) ** 2, abs=1e-9)
            assert bool(gs.locked[0]) == (k == 200)
    # locked from 0.2 s: 2 + 20 (t - 0.2)
    assert pos == pytest.approx(2.0 + 20.0 * 0.1, abs=1e-9)


def test_gearset_shift_master_keeps_the_travel() -> None:
    gs = GearSet()
    gs.add(1, 1, 0, MasterReference.COMMAND, 1.0, math.inf, 5.0, 0.0)
    gs.shift_master(0, 100.0)  # master redefined from 5 to 105
    st = gs.step(CUP, None, (np.zeros(2), np.array([106.0, 0.0])), (np.zeros(2), np.zeros(2)))
    assert st.dpos.tolist() == [1.0]


def test_gear_chain_masters_before_slaves_in_one_update() -> None:
    # A geared 2:1 to M, B geared 3:1 to A: B = 6 x M travel at every update (no lag)
    g = MotionGroup(CUP)
    m, a, b = g.add_axis("M"), g.add_axis("A"), g.add_axis("B")
    assert g.start_gear(a, m, 0, 2.0).ok
    assert g.start_gear(b, a, 0, 3.0).ok
    g.start_jog(m, 0, 10.0, 1000.0, 1000.0)
    for _ in range(50):
        g.update()
        assert g.command_position[b] == pytest.approx(6.0 * g.command_position[m], abs=1e-12)
    assert g.command_position[m] > 0.3


def test_stop_gear_hands_the_velocity_to_a_stop_and_reverse_direction() -> None:
    g = MotionGroup(CUP)
    m, s = g.add_axis("M"), g.add_axis("S")
    r1 = g.start_gear(s, m, 0, 2.0)
    g.start_jog(m, 0, 10.0, math.inf, math.inf)  # a velocity step: 10 units/s at once
    run(g, 10)
    assert g.command_velocity[s] == pytest.approx(20.0)
    r2 = g.start_gear(s, m, 2, 1.0)  # Reverse of Same: -1
    ev = run(g, 2)
    assert (r1.handle, EventKind.ENDED, s) in [(e.handle, e.kind, e.axis) for e in ev]
    assert g.command_velocity[s] == pytest.approx(-10.0)
    assert g.status["GearingStatus"][s] and g.status["GearingLockStatus"][s]
    r3 = g.stop(s, 3, 100.0)  # MAS Gear: from -10 units/s at 100 units/s^2 -> 0.1 s
    ev = run(g, 1)
    kinds = [(e.handle, e.kind) for e in ev]
    assert (r2.handle, EventKind.ENDED) in kinds and (r3.handle, EventKind.IN_PROCESS) in kinds
    assert not g.status["GearingStatus"][s]
    ev = run(g, 100)
    assert (r3.handle, EventKind.COMPLETE) in [(e.handle, e.kind) for e in ev]
    assert g.command_velocity[s] == 0.0


def test_start_gear_errors() -> None:
    g = MotionGroup(CUP)
    m, s = g.add_axis("M"), g.add_axis("S")
    assert g.start_gear(s, s, 0, 1.0).error == MotionError.MASTER_AXIS_CONFLICT
    assert (g.start_gear(s, m, 4, 1.0).error, g.start_gear(s, m, 4, 1.0).exerr) == (13, 3)
    assert g.start_gear(s, m, 0, math.nan).exerr == 4
    assert g.start_gear(s, m, 0, 1.0, 2).exerr == 7
    assert g.start_gear(s, m, 0, 1.0, 1, 0.0).exerr == 10


# ------------------------------------------------------------------ MRP
def test_redefining_the_master_of_a_master_driven_move_does_not_move_the_slave() -> None:
    # slave S: master-driven incremental move of 100 at 1 unit per master unit; the master
    # jogs at 10 units/s (velocity step). Redefining the master by +500 must not advance the
    # master distance: S keeps equal to the master's travel (accel/decel 1e9: no ramps)
    g = MotionGroup(CUP)
    m, s = g.add_axis("M"), g.add_axis("S")
    assert g.assign_master(s, m).ok
    g.start_move(s, MoveType.INCREMENTAL, 100.0, 1.0, 1e9, 1e9, master_driven=True)
    g.start_jog(m, 0, 10.0, math.inf, math.inf)
    run(g, 20)
    travel = float(g.command_position[m])
    assert g.command_position[s] == pytest.approx(travel, abs=1e-6)
    assert g.redefine_position(m, False, MasterReference.COMMAND, 500.0).ok
    run(g, 20)
    assert g.command_position[m] == pytest.approx(500.0 + 20 * 0.01, abs=1e-9)
    assert g.command_position[s] == pytest.approx(travel + 20 * 0.01, abs=1e-6)
    assert g.shift[m] == 0.0  # only the update that applies it reports the shift


def test_redefine_position_relative_and_errors() -> None:
    g = MotionGroup(CUP)
    a = g.add_axis("A", position=3.0)
    r = g.redefine_position(a, True, MasterReference.ACTUAL, -1.0)
    ev = g.update()
    assert (r.handle, EventKind.COMPLETE) in [(e.handle, e.kind) for e in ev]
    assert (g.actual_position[a], g.command_position[a], g.shift[a]) == (2.0, 2.0, -1.0)
    assert g.redefine_position(a, False, 3, 0.0).exerr == 3
    assert g.redefine_position(a, False, 0, math.inf).exerr == 4


# ------------------------------------------------------------------ homing
@pytest.mark.parametrize(
    ("virtual", "servo", "mode", "seq", "expected"),
    [
        (True, True, HomeMode.ACTIVE, HomeSequence.IMMEDIATE, (MotionError.OK, False)),
        (True, True, HomeMode.PASSIVE, HomeSequence.IMMEDIATE, (MotionError.OK, False)),
        (True, True, HomeMode.ACTIVE, HomeSequence.MARKER, (41, False)),
        (True, True, HomeMode.ABSOLUTE, HomeSequence.IMMEDIATE, (41, False)),
        (False, True, HomeMode.ACTIVE, HomeSequence.IMMEDIATE, (MotionError.OK, False)),
        (False, False, HomeMode.ACTIVE, HomeSequence.IMMEDIATE, (5, False)),
        (False, True, HomeMode.ACTIVE, HomeSequence.SWITCH, (84, False)),
        (False, True, HomeMode.PASSIVE, HomeSequence.SWITCH_MARKER, (84, False)),
        (False, True, HomeMode.ACTIVE, HomeSequence.TORQUE_LEVEL, (41, False)),
        (False, False, HomeMode.PASSIVE, HomeSequence.MARKER, (MotionError.OK, True)),
        (False, False, HomeMode.ABSOLUTE, HomeSequence.IMMEDIATE, (MotionError.OK, False)),
        (False, True, HomeMode.ABSOLUTE, HomeSequence.IMMEDIATE, (4, False)),
        (False, False, HomeMode.ABSOLUTE, HomeSequence.MARKER, (41, False)),
        (False, True, 7, HomeSequence.IMMEDIATE, (41, False)),
    ],
)
def test_homing_rules(virtual, servo, mode, seq, expected) -> None:  # noqa: ANN001
    assert homing_error(virtual, servo, mode, seq) == expected


def test_active_homing_of_a_drive_keeps_the_following_error() -> None:
    # drive with tau 10 ms jogging: at the homing update the actual position becomes the home
    # position and the command keeps its lead over the actual; then the jog is ended
    g = MotionGroup(CUP)
    d = g.add_axis("D", kind=AxisKind.CIP_DRIVE, tau=0.01)
    g.servo_on_axis(d)
    g.start_jog(d, 0, 10.0, math.inf, math.inf)
    run(g, 200)
    err = float(g.command_position[d] - g.actual_position[d])
    r = g.home(d, HomeMode.ACTIVE, HomeSequence.IMMEDIATE, 7.0)
    ev = g.update()
    assert [e.kind for e in ev if e.handle == r.handle] == [
        EventKind.IN_PROCESS,
        EventKind.COMPLETE,
    ]
    # actual := 7, command := 7 + err; then one servo step towards the held command
    alpha = -math.expm1(-CUP / 0.01)
    assert g.actual_position[d] == pytest.approx(7.0 + alpha * err, abs=1e-9)
    assert g.status["AxisHomedStatus"][d] and not g.status["JogStatus"][d]


# ------------------------------------------------------------------ MCD
def test_change_dynamics_lower_decel_of_a_move_keeps_its_end_point() -> None:
    # move 10 at V 10, A = Dc = 100 (trapezoid); at 0.5 s it cruises at 10 with x = 4.5 (the
    # ramp covered 0.5 in 0.1 s). MCD decel 25 applies at the next update (0.501 s, x = 4.51,
    # own clock 0 there): the stop now takes 0.4 s covering 2, the cruise covers
    # 10 - 4.51 - 2 = 3.49 at 10 (0.349 s): complete 0.749 s after that update, i.e. at the
    # 750th update counted from it (one more if the summed durations round up)
    g = MotionGroup(CUP)
    a = g.add_axis("A")
    r = g.start_move(a, MoveType.INCREMENTAL, 10.0, 10.0, 100.0, 100.0)
    run(g, 501)  # start update + 500 updates: t = 0.5 s on the move's clock
    assert g.command_position[a] == pytest.approx(4.5, abs=1e-9)
    assert g.change_dynamics(a, GeneratorKind.MOVE, decel=25.0).ok
    done = None
    for k in range(1, 1000):
        ev = g.update()
        if (r.handle, EventKind.COMPLETE) in [(e.handle, e.kind) for e in ev]:
            done = k
            break
    assert done in (750, 751)
    assert g.command_position[a] == pytest.approx(10.0, abs=1e-9)


def test_change_dynamics_bad_values() -> None:
    g = MotionGroup(CUP)
    a = g.add_axis("A")
    assert g.change_dynamics(a, GeneratorKind.JOG, speed=-1.0).exerr == 4
    assert g.change_dynamics(a, GeneratorKind.JOG, accel=0.0).exerr == 6
    assert g.change_dynamics(a, GeneratorKind.JOG, decel=-2.0).exerr == 8
    assert g.change_dynamics(a, GeneratorKind.JOG, accel_jerk=0.0).exerr == 10
    assert g.change_dynamics(a, GeneratorKind.JOG, decel_jerk=0.0).exerr == 12


def test_change_dynamics_of_a_master_driven_jog_uses_master_units() -> None:
    # slave jogs at 1 unit per master unit (accel 1e9: a step) behind a master at 10 units/s
    # (a step too): slave speed 10. MCD speed 2 per master unit, accel 100 per master unit^2:
    # the slave's native speed ramps 1 -> 2 over 0.01 master units (1 ms of master travel),
    # then the slave runs at 2 x 10 = 20 units/s.
    g = MotionGroup(CUP)
    m, s = g.add_axis("M"), g.add_axis("S")
    assert g.assign_master(s, m).ok
    g.start_jog(s, 0, 1.0, 1e9, 1e9, master_driven=True)
    g.start_jog(m, 0, 10.0, math.inf, math.inf)
    run(g, 10)
    assert g.command_velocity[s] == pytest.approx(10.0)
    assert g.change_dynamics(s, GeneratorKind.JOG, speed=2.0, accel=100.0).ok
    run(g, 5)
    assert g.command_velocity[s] == pytest.approx(20.0)
    assert g.running_limits(s, GeneratorKind.JOG) is not None
    limits, master_driven = g.running_limits(s, GeneratorKind.JOG)  # type: ignore[misc]
    assert (limits.speed, limits.accel, master_driven) == (2.0, 100.0, True)


def test_group_stop_and_servo_off_end_gearing_and_homing() -> None:
    g = MotionGroup(CUP)
    m, s = g.add_axis("M"), g.add_axis("S")
    d = g.add_axis("D", kind=AxisKind.CIP_DRIVE)
    g.servo_on_axis(d)
    rg = g.start_gear(s, m, 0, 1.0)
    rh = g.home(d, HomeMode.PASSIVE, HomeSequence.MARKER, 0.0)
    run(g, 2)
    assert g.status["GearingStatus"][s] and g.status["HomingStatus"][d]
    rs = g.stop_group()
    ev = run(g, 2)
    ended = {(e.handle, e.kind) for e in ev}
    assert {(rg.handle, EventKind.ENDED), (rh.handle, EventKind.ENDED)} <= ended
    assert (rs.handle, EventKind.COMPLETE) in ended
    assert not g.status["GearingStatus"][s] and not g.status["HomingStatus"][d]
    # MSF of a geared drive slave ends its gear
    rg2 = g.start_gear(d, m, 0, 1.0)
    run(g, 1)
    g.servo_off_axis(d)
    assert (rg2.handle, EventKind.ENDED) in [(e.handle, e.kind) for e in run(g, 1)]


def test_gear_cycle_does_not_hang() -> None:
    # A follows B and B follows A: nothing moves, levels are capped, updates stay finite
    g = MotionGroup(CUP)
    a, b = g.add_axis("A"), g.add_axis("B")
    assert g.start_gear(a, b, 0, 1.0).ok and g.start_gear(b, a, 0, 1.0).ok
    run(g, 5)
    assert g.command_position.tolist() == [0.0, 0.0]


def test_redefine_keeps_a_running_time_cam_shape() -> None:
    # a time cam 0 -> 10 over 1 s (linear: 10 units/s) on A; MRP +100 at 0.5 s: afterwards
    # A = 100 + cam(t), the cam still completes at 1 s with A = 110
    g = MotionGroup(CUP)
    a = g.add_axis("A")
    prof = calculate_cam_profile([0.0, 1.0], [0.0, 10.0], [0, 0])
    r = g.start_time_cam(a, prof)
    run(g, 501)  # start update + 0.5 s
    assert g.command_position[a] == pytest.approx(5.0, abs=1e-9)
    g.redefine_position(a, True, MasterReference.COMMAND, 100.0)
    done = None
    for k in range(1, 600):
        ev = g.update()
        if (r.handle, EventKind.COMPLETE) in [(e.handle, e.kind) for e in ev]:
            done = k
            break
    assert done == 500
    assert g.command_position[a] == pytest.approx(110.0, abs=1e-9)
