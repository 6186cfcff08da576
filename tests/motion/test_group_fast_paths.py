"""The update's shortcuts compute exactly what the general path computes (decision 0138).

Up to 16 time-driven moves, jogs and stops are stepped on Python floats
(generators._step_few) instead of numpy arrays, and the numpy path keeps the profile
segments in use until a clock reaches the next segment start instead of searching them every
update. IEEE doubles give the same bits either way, so the same requests run through each
path must give identical axis arrays and events at every update, through trapezoids,
S-curves, a merge, a stop and a jog reversal.
"""

from __future__ import annotations

import numpy as np
import pytest

from interpreter.motion import MotionGroup, generators
from interpreter.motion.generators import ProfileSet


def _run(
    few: int, monkeypatch: pytest.MonkeyPatch, search_always: bool = False
) -> tuple[list[np.ndarray], list, int]:
    monkeypatch.setattr(generators, "_FEW", few)
    if search_always:  # forget the kept segments before every step: searched every update
        step = ProfileSet.step

        def forgetful(self: ProfileSet, *args: object) -> object:
            self._next_start = None
            return step(self, *args)  # type: ignore[arg-type]

        monkeypatch.setattr(ProfileSet, "step", forgetful)
    calls = 0
    step_few = ProfileSet._step_few

    def counted(self: ProfileSet, *args: object) -> object:
        nonlocal calls
        calls += 1
        return step_few(self, *args)  # type: ignore[arg-type]

    monkeypatch.setattr(ProfileSet, "_step_few", counted)
    g = MotionGroup(0.001)
    a, b, c = (g.add_axis(n) for n in "abc")
    g.add_axis("d", tau=0.004)  # a drive axis: the servo lags, nothing moves it
    more = [g.add_axis(f"m{i}") for i in range(17)]  # 20 generators in all
    trace: list[np.ndarray] = []
    events: list = []
    for k in range(1500):
        if k == 0:
            assert g.start_move(a, 0, 7.3, 20.0, 150.0, 90.0).ok  # trapezoid, absolute
            assert g.start_move(b, 1, -4.1, 15.0, 80.0, 120.0, 1, 900.0, 700.0).ok  # S-curve
            assert g.start_jog(c, 0, 12.5, 60.0, 60.0, 1, 500.0, 500.0).ok
            for i, ax in enumerate(more):  # trapezoids and S-curves ending at different times
                assert g.start_move(ax, 1, 0.5 + 0.37 * i, 8.0, 50.0, 70.0, i % 2, 400.0, 300.0).ok
        if k == 400:  # merge: a new move takes over the running one on axis a
            assert g.start_move(a, 1, 2.2, 9.0, 40.0, 40.0, 0, merge=1).ok
        if k == 700:  # reverse the jog (a merge again)
            assert g.start_jog(c, 1, 6.0, 30.0, 45.0, merge=1).ok
        if k == 1100:
            assert g.stop(c, 0, 25.0).ok
        events.extend((e.kind, e.axis) for e in g.update())
        trace.append(
            np.concatenate(
                (
                    g.command_position,
                    g.command_velocity,
                    g.command_acceleration,
                    g.actual_position,
                    g.actual_velocity,
                )
            )  # fmt: skip
        )
    return trace, events, calls


def test_few_generators_on_floats_match_the_numpy_path(monkeypatch: pytest.MonkeyPatch) -> None:
    fast, fast_events, fast_calls = _run(100, monkeypatch)
    kept, kept_events, kept_calls = _run(0, monkeypatch)
    slow, slow_events, slow_calls = _run(0, monkeypatch, search_always=True)
    assert fast_calls > 1000 and kept_calls == slow_calls == 0  # the paths meant
    assert fast_events == kept_events == slow_events
    assert len(fast_events) > 10  # accel/decel/constant changes, completions
    for k, (x, y, z) in enumerate(zip(fast, kept, slow, strict=True)):
        assert np.array_equal(x, z), f"update {k}: floats"
        assert np.array_equal(y, z), f"update {k}: kept segments"
