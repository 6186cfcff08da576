"""MCCD in the core: change_path_dynamics and PathSet.replan against closed forms.

The line of test_paths.py: L = 13 along (5, 12), V 10, A = D 100, 1 ms updates; the move's
clock is 0 at the first update, so a change requested after N updates is applied at the end
of update N + 1, at the move's clock N ms (s there from the trapezoid of test_paths.s_trap).
"""

from __future__ import annotations

import numpy as np
import pytest

from interpreter.motion import AxisKind, EventKind, MotionGroup
from interpreter.motion.path_geometry import line
from interpreter.motion.profiles import Limits, plan_move

CUP = 0.001

L = 13.0


def group(n_axes: int) -> tuple[MotionGroup, list[int]]:
    g = MotionGroup(CUP)
    return g, [g.add_axis(f"a{i}", AxisKind.VIRTUAL) for i in range(n_axes)]


def run(g: MotionGroup, updates: int) -> list[tuple[float, int, EventKind]]:
    return [(g.time, ev.handle, ev.kind) for _ in range(updates) for ev in g.update()]


def _start(tt: int = 1, queued: Limits | None = None, lim: Limits | None = None):  # noqa: ANN202
    g, axes = group(2)
    cs = g.add_coordinate_system(axes)
    first = g.start_path(
        cs, line(g.path_start_point(cs), [5.0, 12.0]), lim or Limits(10.0, 100.0, 100.0), tt,
        0.1, 0, False,
    )  # fmt: skip
    second = None
    if queued is not None:
        second = g.start_path(
            cs, line(g.path_start_point(cs), [10.0, 24.0]), queued, 1, 0.1, 0, False
        )
    return g, cs, first, second


def _completed(events, handle: int) -> list[float]:  # noqa: ANN001
    return [t for t, h, k in events if h == handle and k is EventKind.COMPLETE]


def test_plan_move_from_an_acceleration_first_brings_it_to_zero() -> None:
    # from v 1.25 and a 50 with J 1000: a reaches 0 after 50/1000 = 0.05 s at v = 2.5
    lim = Limits(20.0, 100.0, 100.0, 1000.0, 1000.0)
    prof = plan_move(10.0, lim, 1.25, 50.0)
    assert (prof.a0[0], prof.j[0]) == (50.0, -1000.0)
    assert prof.at(0.05)[1:] == pytest.approx((2.5, 0.0), abs=1e-12)
    t = np.linspace(0.0, prof.duration, 20001)
    _, v, a = prof.evaluate(t)
    assert np.max(np.abs(np.diff(a))) <= 1000.0 * (t[1] - t[0]) * (1 + 1e-9)
    assert prof.end_position == 10.0
    assert v[-1] == pytest.approx(0.0, abs=1e-9)
    # trapezoidal limits: the acceleration is not carried (it steps anyway)
    assert plan_move(10.0, Limits(20.0, 100.0, 100.0), 1.25, 50.0).a0[0] == 100.0


def test_a_lower_speed_and_decel_replan_the_rest_of_the_line() -> None:
    # applied at clock 0.5: s = 0.5 + 10 * 0.4 = 4.5; 10 -> 5 at 50 (0.1 s, 0.75), cruise
    # (13 - 4.5 - 0.75 - 0.25) / 5 = 1.5 s, 5 -> 0 at 50 (0.1 s, 0.25): done at 2.2
    g, cs, first, _ = _start()
    run(g, 500)
    assert g.change_path_dynamics(cs, 5.0, None, 50.0, None, None, False).ok
    events = run(g, 2300)
    assert _completed(events, first.handle) == [pytest.approx(2.2)]
    assert list(g.command_position) == [5.0, 12.0]


def test_a_move_in_its_final_decel_keeps_its_profile_when_it_could_not_stop() -> None:
    # at clock 1.35 (v 5, 0.125 left) a decel of 10 would need 5^2/20 = 1.25: the profile
    # runs on and the move ends at 1.4 on its end point
    g, cs, first, _ = _start()
    run(g, 1350)
    g.change_path_dynamics(cs, None, None, 10.0, None, None, False)
    events = run(g, 200)
    assert _completed(events, first.handle) == [pytest.approx(1.4)]
    assert list(g.command_position) == [5.0, 12.0]


def test_the_no_decel_blend_point_follows_the_new_speed() -> None:
    # termination 3 blends where the final deceleration starts: from 5 at 100 that is
    # 5^2 / 200 = 0.125 before the end (it was 10^2 / 200 = 0.5)
    g, cs, first, _ = _start(tt=3, queued=Limits(10.0, 100.0, 100.0))
    run(g, 2)
    lead = g.paths.systems[cs].lead
    assert lead is not None and lead.blend_s == pytest.approx(L - 0.5)
    g.change_path_dynamics(cs, 5.0, None, None, None, None, False)
    run(g, 1)
    assert lead.blend_s == pytest.approx(L - 0.125)


@pytest.mark.parametrize("pending", [False, True])
def test_scope_and_percent_of_time_jerk_per_move(pending: bool) -> None:
    # S-curve moves: the queued one at speed 4; the new accel jerk A^2/V (100 % of Time)
    # is taken with each move's own speed: 100^2/10 = 1000 and 100^2/4 = 2500
    s_curve = Limits(10.0, 100.0, 100.0, 500.0, 500.0)
    g, cs, _, _ = _start(lim=s_curve, queued=Limits(4.0, 100.0, 100.0, 500.0, 500.0))
    run(g, 300)
    g.change_path_dynamics(cs, None, None, None, lambda a, v: a * a / v, None, pending)
    run(g, 1)
    system = g.paths.systems[cs]
    assert system.lead is not None and system.lead.limits.accel_jerk == 1000.0
    assert system.queue[0].limits.accel_jerk == (2500.0 if pending else 500.0)
    assert system.lead.limits.decel_jerk == 500.0  # not changed


def test_nothing_running_is_left_alone() -> None:
    g, axes = group(2)
    cs = g.add_coordinate_system(axes)
    assert g.change_path_dynamics(cs, 5.0, 10.0, 10.0, None, None, True).ok
    assert run(g, 3) == []
    assert list(g.command_position) == [0.0, 0.0]


def test_a_move_held_at_speed_0_does_not_blend_into_the_queued_one() -> None:
    # termination 3 blends at the final deceleration; a move stopped by speed 0 never gets
    # there: the queued move waits until the speed comes back. At clock 0.3 (s = 2.5)
    # speed 0 stops it after 10^2/200 = 0.5, at s = 3 (a rest 10 short of the end)
    g, cs, first, second = _start(tt=3, queued=Limits(10.0, 100.0, 100.0))
    assert second is not None
    run(g, 300)
    g.change_path_dynamics(cs, 0.0, None, None, None, None, False)
    events = run(g, 2000)
    assert not [e for e in events if e[1] == second.handle]
    assert list(g.command_position) == pytest.approx([5.0 / 13.0 * 3.0, 12.0 / 13.0 * 3.0])
    # speed 10 again at clock 2.3: 10 left, 0.1 s up over 0.5, 0.9 s at 10, 0.1 s down:
    # done at 3.4; the queued move (L 13, 1.4 s) starts at the decel point, 3.3, ends 4.7
    g.change_path_dynamics(cs, 10.0, None, None, None, None, False)
    events = run(g, 2500)
    assert _completed(events, first.handle) == [pytest.approx(3.4)]
    assert _completed(events, second.handle) == [pytest.approx(4.7)]
    assert list(g.command_position) == [10.0, 24.0]
