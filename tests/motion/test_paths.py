"""The coordinated path set of the core (motion/paths.py), against closed forms.

Trapezoid along a path of length L at speed V with accel = decel A (reaching V):
  s(t) = A t^2 / 2 (t <= V/A), V/(2A) V + V (t - V/A) (cruise), L - A (T - t)^2 / 2 (decel),
  T = L/V + V/A.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from interpreter.motion import AxisKind, EventKind, MotionGroup
from interpreter.motion.path_geometry import Segment, circle, line
from interpreter.motion.path_moves import path_trajectory
from interpreter.motion.profiles import Limits, plan_move

CUP = 0.001


def s_trap(t: float, length: float, v: float, a: float) -> float:
    total = length / v + v / a
    t = min(max(t, 0.0), total)
    if t <= v / a:
        return a * t * t / 2.0
    if t <= total - v / a:
        return v * v / (2.0 * a) + v * (t - v / a)
    return length - a * (total - t) ** 2 / 2.0


def run(g: MotionGroup, updates: int) -> list[tuple[float, int, EventKind]]:
    out = []
    for _ in range(updates):
        for ev in g.update():
            out.append((g.time, ev.handle, ev.kind))
    return out


def group(n_axes: int, kind: AxisKind = AxisKind.VIRTUAL) -> tuple[MotionGroup, list[int]]:
    g = MotionGroup(CUP)
    return g, [g.add_axis(f"a{i}", kind) for i in range(n_axes)]


def test_line_follows_the_trapezoid_across_chunks() -> None:
    # L = 13 (5, 12), V 10, A 100: T = 1.3 + 0.1 = 1.4 s, far more updates than one chunk
    g, axes = group(2)
    cs = g.add_coordinate_system(axes)
    seg = line(g.path_start_point(cs), [5.0, 12.0])
    r = g.start_path(cs, seg, Limits(10.0, 100.0, 100.0), 1, 0.1, 0, False)
    assert r.ok
    events = []
    for k in range(1500):
        events += [(g.time, e.handle, e.kind) for e in g.update()]
        s = s_trap(k * CUP, 13.0, 10.0, 100.0)  # the move's clock is 0 at the first update
        assert g.command_position[0] == pytest.approx(5.0 / 13.0 * s, abs=1e-9)
        assert g.command_position[1] == pytest.approx(12.0 / 13.0 * s, abs=1e-9)
    done = [t for t, h, kind in events if h == r.handle and kind is EventKind.COMPLETE]
    assert done == [pytest.approx(1.4)]
    assert list(g.command_position) == [5.0, 12.0]  # the end point exactly


def test_three_dimensional_arc_through_a_via_point() -> None:
    # start (10, 0, 0), via (0, 10, 0)... a circle of radius 10 about the origin tilted out
    # of XY: via (0, 10/sqrt2, 10/sqrt2) and end (-10, 0, 0): a half circle, L = 10 pi
    g, axes = group(3)
    for a in axes:
        g.set_position(a, 10.0 if a == 0 else 0.0)
    cs = g.add_coordinate_system(axes)
    h = 10.0 / math.sqrt(2.0)
    seg = circle(g.path_start_point(cs), [-10.0, 0.0, 0.0], [0.0, h, h], 0, 0, 3)
    assert isinstance(seg, Segment)
    assert seg.length == pytest.approx(10.0 * math.pi)
    r = g.start_path(cs, seg, Limits(20.0, 200.0, 200.0), 1, 0.1, 0, False)
    assert r.ok
    total = 10.0 * math.pi / 20.0 + 20.0 / 200.0
    for _ in range(round(total / CUP) + 5):
        g.update()
        p = g.command_position
        assert float(np.linalg.norm(p)) == pytest.approx(10.0, rel=1e-9)
        assert p[1] == pytest.approx(p[2], abs=1e-9)  # in the plane y = z
        assert p[1] >= -1e-9  # on the via point's side
    # the increments of the updates add up to the end point (to rounding)
    assert np.allclose(g.command_position, [-10.0, 0.0, 0.0], rtol=0.0, atol=1e-12)


def test_whole_trajectory_in_one_call() -> None:
    seg = line([0.0, 0.0], [30.0, 40.0])
    prof = plan_move(50.0, Limits(10.0, 100.0, 100.0))
    t = np.linspace(0.0, 5.1, 511)
    pts, speed = path_trajectory(seg, prof, t)
    s = np.array([s_trap(x, 50.0, 10.0, 100.0) for x in t])
    assert np.allclose(pts[:, 0], 0.6 * s, atol=1e-9)
    assert np.allclose(pts[:, 1], 0.8 * s, atol=1e-9)
    assert speed.max() == pytest.approx(10.0)


def test_sixteen_systems_step_together() -> None:
    # 16 systems of 2 axes, system c moves (c + 1, 0) ... different lengths, same dynamics
    g, axes = group(32)
    systems = [g.add_coordinate_system([axes[2 * c], axes[2 * c + 1]]) for c in range(16)]
    handles = {}
    for c, cs in enumerate(systems):
        seg = line(g.path_start_point(cs), [c + 1.0, 0.0])
        handles[g.start_path(cs, seg, Limits(10.0, 100.0, 100.0), 1, 0.1, 0, False).handle] = c
    events = run(g, 2000)
    for t, h, kind in events:
        if kind is EventKind.COMPLETE:
            length = handles[h] + 1.0
            # L >= V^2/A = 1 reaches V: T = L/V + V/A (the smallest, L = 1, just does)
            assert t == pytest.approx(math.ceil((length / 10.0 + 0.1) / CUP - 1e-9) * CUP)
    assert sum(kind is EventKind.COMPLETE for _, _, kind in events) == 16
    assert list(g.command_position[0::2]) == [c + 1.0 for c in range(16)]


def test_actual_tolerance_waits_for_the_drive() -> None:
    # termination 0 on drive axes (first-order lag): the command reaches the end at
    # T = 0.5 + 0.1 s; PC comes at the first update from then on where the actual position
    # is within ActualTolerance of the end (seed: interpolation complete and in tolerance)
    g, axes = group(2, AxisKind.CIP_DRIVE)
    for a in axes:
        g.servo_on_axis(a)
    cs = g.add_coordinate_system(axes)
    g.paths.systems[cs].actual_tolerance = 0.001
    seg = line(g.path_start_point(cs), [3.0, 4.0])
    r = g.start_path(cs, seg, Limits(10.0, 100.0, 100.0), 0, 0.1, 0, False)
    expected = None
    done = None
    for _ in range(1000):
        events = g.update()
        err = float(np.linalg.norm(g.actual_position - np.array([3.0, 4.0])))
        if expected is None and g.time >= 0.6 - 1e-9 and err <= 0.001:
            expected = g.time
        if any(e.handle == r.handle and e.kind is EventKind.COMPLETE for e in events):
            done = g.time
    assert expected is not None and expected > 0.6 + 1e-9  # the drive lags the command
    assert done == pytest.approx(expected)
    assert g.paths.system_status(cs)["ActualPosToleranceStatus"] is True
    assert g.paths._settling == 0  # nothing left waiting: the set is idle again


def test_servo_off_ends_the_path_and_the_queue() -> None:
    g, axes = group(2, AxisKind.CIP_DRIVE)
    for a in axes:
        g.servo_on_axis(a)
    cs = g.add_coordinate_system(axes)
    lim = Limits(10.0, 100.0, 100.0)
    r1 = g.start_path(cs, line(g.path_start_point(cs), [30.0, 40.0]), lim, 1, 0.1, 0, False)
    r2 = g.start_path(cs, line(g.path_start_point(cs), [0.0, 0.0]), lim, 1, 0.1, 0, False)
    run(g, 100)
    g.servo_off_axis(axes[1])
    events = run(g, 5)
    ended = {h for _, h, kind in events if kind is EventKind.ENDED}
    assert ended == {r1.handle, r2.handle}
    assert not g.paths.busy(axes[0])


def test_stop_all_on_a_member_axis_brings_the_system_to_rest() -> None:
    # MAS All on one axis: the path decelerates at the system's MaximumDecel (here 50):
    # 10^2 / (2 * 50) = 1 unit further along the path, both axes together
    g, axes = group(2)
    cs = g.add_coordinate_system(axes)
    g.paths.systems[cs].max_decel = 50.0
    r = g.start_path(cs, line(g.path_start_point(cs), [300.0, 400.0]),
                     Limits(10.0, 100.0, 100.0), 1, 0.1, 0, False)  # fmt: skip
    run(g, 1000)
    at_stop = g.command_position.copy()
    g.stop(axes[0])
    events = run(g, 400)
    travel = g.command_position - at_stop
    assert float(np.linalg.norm(travel)) == pytest.approx(1.0 + 10.0 * CUP, abs=1e-9)
    assert travel[1] == pytest.approx(4.0 / 3.0 * travel[0])  # still on the line
    assert (r.handle, EventKind.ENDED) in [(h, k) for _, h, k in events]
