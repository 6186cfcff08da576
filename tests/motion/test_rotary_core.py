"""Rotary pieces of the core (decision 0115): wrapping, travel the short way round, the
rotary move types' travel, master clocks and MRP on a rotary axis. Expectations are hand
arithmetic on a 360-unit circle."""

from __future__ import annotations

import numpy as np
import pytest

from interpreter.motion import LockDirection, MasterReference, MotionError, MotionGroup
from interpreter.motion.clock import MasterClock
from interpreter.motion.rotary import rotary_travel, travel, travel_array, wrap, wrap_array


def test_wrap_and_travel() -> None:
    assert wrap(370.0, 360.0) == 10.0
    assert wrap(-90.0, 360.0) == 270.0
    assert wrap(-1e-20, 360.0) == 0.0  # would round to 360.0, outside [0, 360)
    assert wrap(-5.0, 0.0) == -5.0  # linear: unchanged
    assert travel(10.0, 350.0, 360.0) == pytest.approx(20.0)
    assert travel(350.0, 10.0, 360.0) == pytest.approx(-20.0)
    assert travel(10.0, 350.0, 0.0) == -340.0
    pos = np.array([365.0, -1.0, 720.0, 500.0])
    wrap_array(pos, np.array([360.0, 360.0, 360.0, 0.0]), np.array([0, 1, 2]))
    assert pos.tolist() == [5.0, 359.0, 0.0, 500.0]
    d = travel_array(np.array([1.0, 1.0]), np.array([359.0, 359.0]), np.array([360.0, 0.0]))
    assert d.tolist() == pytest.approx([2.0, -358.0])


@pytest.mark.parametrize(
    ("move_type", "target", "current", "expected"),
    [
        (2, 10.0, 350.0, 20.0),
        (2, 300.0, 350.0, -50.0),
        (2, 180.0, 0.0, 180.0),  # half a turn: forward
        (2, 350.0, 350.0, 0.0),
        (3, 340.0, 350.0, 350.0),
        (3, 350.0, 350.0, 0.0),  # already there: no turn
        (4, 10.0, 350.0, -340.0),
        (4, 340.0, 350.0, -10.0),
        (4, 350.0, 350.0, 0.0),
    ],
)
def test_rotary_travel(move_type: int, target: float, current: float, expected: float) -> None:
    assert rotary_travel(move_type, target, current, 360.0) == pytest.approx(expected)


def test_master_clock_counts_travel_through_the_wrap() -> None:
    clock = MasterClock(0, MasterReference.COMMAND)
    clock.unwind = 360.0
    # master 350 -> 10 -> 100 -> 250 -> 359 -> 5 (each step under half a turn):
    # travel 0, 20, 110, 260, 369, 375
    got = [clock.advance(p) for p in (350.0, 10.0, 100.0, 250.0, 359.0, 5.0)]
    assert got == pytest.approx([0.0, 20.0, 110.0, 260.0, 369.0, 375.0])


def test_master_clock_lock_position_once_per_revolution() -> None:
    # forward lock at 5: the master starts at 100, so it passes 5 only after the wrap:
    # 100 -> 250 -> 355 -> 2 -> 10: locked between 2 and 10, counted from 5 -> 5, then 45
    clock = MasterClock(0, MasterReference.COMMAND, LockDirection.POSITION_FORWARD, 5.0)
    clock.unwind = 360.0
    got = [clock.advance(p) for p in (100.0, 250.0, 355.0, 2.0, 10.0, 50.0)]
    assert got == pytest.approx([0.0, 0.0, 0.0, 0.0, 5.0, 45.0])
    # the lock position passed in the sample that wraps: forward at 358, 340 -> 350 -> 2
    # (travel 12: 358 is passed) -> 12: distance from 358: 4, then 14
    fwd = MasterClock(0, MasterReference.COMMAND, LockDirection.POSITION_FORWARD, 358.0)
    fwd.unwind = 360.0
    got = [fwd.advance(p) for p in (340.0, 350.0, 2.0, 12.0)]
    assert got == pytest.approx([0.0, 0.0, 4.0, 14.0])
    # reverse at 2: 20 -> 10 -> 355 (travel -15: 2 is passed): distance from 2: 7
    rev = MasterClock(0, MasterReference.COMMAND, LockDirection.POSITION_REVERSE, 2.0)
    rev.unwind = 360.0
    assert [rev.advance(p) for p in (20.0, 10.0, 355.0)] == pytest.approx([0.0, 0.0, 7.0])


def test_group_wraps_at_every_update_and_mrp() -> None:
    g = MotionGroup(cup=0.01)
    a = g.add_axis("R", unwind=360.0, position=370.0)
    assert g.command_position[a] == pytest.approx(10.0)  # wrapped when the axis is added
    assert g.start_jog(a, 0, 1000.0, 1e30, 1e30).ok
    for _ in range(40):  # 10 u per update after the start update
        g.update()
        assert 0.0 <= g.command_position[a] < 360.0
        assert 0.0 <= g.actual_position[a] < 360.0
    # 39 updates of 10 u after the start update: 10 + 390 = 400 -> 40
    assert g.command_position[a] == pytest.approx(40.0)
    assert g.actual_velocity[a] == pytest.approx(1000.0)
    assert g.redefine_position(a, False, MasterReference.COMMAND, 725.0).ok
    g.update()  # MRP to 725 -> 5, then the jog's 10 u of this update -> 15
    assert g.command_position[a] == pytest.approx(15.0)
    # a rotary move type on a linear axis: error 17; off the circle: 13 / Position
    b = g.add_axis("L")
    assert g.start_move(b, 2, 10.0, 10.0, 100.0, 100.0).error == MotionError.AXIS_MODE_NOT_ROTARY
    r = g.start_move(a, 3, 360.0, 10.0, 100.0, 100.0)
    assert (r.error, r.exerr) == (MotionError.PARAMETER_OUT_OF_RANGE, 3)
