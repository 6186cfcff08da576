"""Moves and jogs of many axes are stepped together (decision 0104): each axis still follows
its own profile in closed form and completes at its own update.

Set-up: virtual axes (actual = command), 1 ms coarse update. All requests are made before
the first update, so every generator starts there with its own clock 0 and reads
t = k * 1 ms at the k-th update after it.

Incremental MAM of D at speed V = 10, accel = decel = A = 100 (trapezoid when D > V²/A = 1):
  ramp time V/A = 0.1 s covering 0.5; total time T = D/V + V/A;
  p(t) = 50 t²                      for t <= 0.1
       = 0.5 + 10 (t - 0.1)         for 0.1 <= t <= T - 0.1
       = D - 50 (T - t)²            for T - 0.1 <= t <= T,  then D.
MAJ forward at 5 with accel 100: ramp 0.05 s covering 0.125; p(t) = 50 t², then
0.125 + 5 (t - 0.05).
"""

from __future__ import annotations

import pytest

from interpreter.motion import EventKind, MotionGroup


def move_position(d: float, t: float) -> float:
    total = d / 10.0 + 0.1
    if t <= 0.1:
        return 50.0 * t * t
    if t <= total - 0.1:
        return 0.5 + 10.0 * (t - 0.1)
    if t <= total:
        return d - 50.0 * (total - t) ** 2
    return d


def jog_position(t: float) -> float:
    return 50.0 * t * t if t <= 0.05 else 0.125 + 5.0 * (t - 0.05)


# T = D/10 + 0.1 falls between updates (0.30004 s, ...), so "the first update whose clock
# reaches T" is not a rounding tie: updates 301, 401, 551, 701 and 826
DISTANCES = [2.0004, 3.0007, 4.5002, 6.0001, 7.2503]


def test_many_moves_and_a_jog_follow_their_own_profiles() -> None:
    g = MotionGroup(0.001)
    axes = [g.add_axis(f"m{i}") for i in range(len(DISTANCES))]
    jog = g.add_axis("j")
    handles = {}
    for ax, d in zip(axes, DISTANCES, strict=True):
        r = g.start_move(ax, 1, d, 10.0, 100.0, 100.0)
        assert r.ok
        handles[r.handle] = d
    assert g.start_jog(jog, 0, 5.0, 100.0, 100.0).ok
    g.update()  # applies every request: own clocks 0, positions 0
    assert list(g.command_position) == [0.0] * (len(DISTANCES) + 1)
    done_at: dict[float, int] = {}
    for k in range(1, 900):
        t = k * 0.001
        for ev in g.update():
            if ev.kind is EventKind.COMPLETE:
                done_at[handles[ev.handle]] = k
        for ax, d in zip(axes, DISTANCES, strict=True):
            assert g.command_position[ax] == pytest.approx(move_position(d, t), abs=1e-9)
        assert g.command_position[jog] == pytest.approx(jog_position(t), abs=1e-9)
    # each move completes at the first update whose clock reaches its T = D/10 + 0.1
    assert [done_at[d] for d in DISTANCES] == [301, 401, 551, 701, 826]
    assert g.status["MoveStatus"][axes].tolist() == [False] * len(DISTANCES)
    assert bool(g.status["JogStatus"][jog])
