"""DeltaT of the time-based blocks (block_timing.py, decision 0139), by hand: every expected
value below is worked out from the timing-mode rules in the decision, not from the code."""

from __future__ import annotations

import pytest

from interpreter.instructions.block_timing import restart, sample, timing_layout
from interpreter.runtime.motion_layout import struct_type
from interpreter.vm.context import ExecContext
from interpreter.vm.values import default_value

TYPE = "FILTER_LOW_PASS"
T = timing_layout(TYPE)
IX = struct_type(TYPE).index


def block(**members: object) -> list:
    s = default_value(struct_type(TYPE))
    assert isinstance(s, list)
    for name, v in members.items():
        s[IX[name.upper()]] = v
    return s


def test_periodic_task_uses_the_task_period() -> None:
    ctx = ExecContext(now_ms=40.0, task_period_ms=20.0)
    s = block()
    assert sample(ctx, s, T) == pytest.approx(0.020)  # 20 ms task -> 0.020 s, even the first time
    assert s[IX["DELTAT"]] == pytest.approx(0.020)


def test_continuous_task_uses_the_time_since_the_previous_execution() -> None:
    ctx = ExecContext(now_ms=10.0)
    s = block()
    assert sample(ctx, s, T) == 0.0  # first execution: no previous one
    ctx.now_ms = 17.0
    assert sample(ctx, s, T) == pytest.approx(0.007)  # 17 - 10 = 7 ms
    ctx.now_ms = 30.0
    assert sample(ctx, s, T) == pytest.approx(0.013)  # 30 - 17 = 13 ms
    restart(s, T)
    assert sample(ctx, s, T) == 0.0  # after prescan the series starts again


def test_oversample_takes_oversample_dt_and_checks_its_range() -> None:
    ctx = ExecContext(now_ms=5.0, task_period_ms=10.0)
    s = block(TimingMode=1, OversampleDT=0.25)
    assert sample(ctx, s, T) == pytest.approx(0.25)
    s[IX["OVERSAMPLEDT"]] = 5000.0  # above 4194.303 s
    assert sample(ctx, s, T) is None and s[IX["DELTATINV"]] == 1
    s[IX["OVERSAMPLEDT"]] = -1.0
    assert sample(ctx, s, T) is None and s[IX["DELTATINV"]] == 1
    s[IX["OVERSAMPLEDT"]] = 1.0
    assert sample(ctx, s, T) == 1.0 and s[IX["DELTATINV"]] == 0  # the flag clears again


def test_real_time_sampling_follows_the_stamps() -> None:
    ctx = ExecContext()
    s = block(TimingMode=2, RTSTime=10, RTSTimeStamp=100)
    assert sample(ctx, s, T) == 0.0  # first stamp starts the series
    assert sample(ctx, s, T) is None  # same stamp: no new sample
    s[IX["RTSTIMESTAMP"]] = 110
    assert sample(ctx, s, T) == pytest.approx(0.010) and s[IX["RTSMISSED"]] == 0
    s[IX["RTSTIMESTAMP"]] = 130  # 20 ms later: one 10 ms sample was lost
    assert sample(ctx, s, T) == pytest.approx(0.020) and s[IX["RTSMISSED"]] == 1
    s[IX["RTSTIMESTAMP"]] = 2  # wrapped: (2 - 130) mod 32768 = 32768 - 128 = 32640 ms
    assert sample(ctx, s, T) == pytest.approx(32.640)
    s[IX["RTSTIMESTAMP"]] = 12  # 12 - 2 = 10 ms, on time again
    assert sample(ctx, s, T) == pytest.approx(0.010) and s[IX["RTSMISSED"]] == 0


@pytest.mark.parametrize(
    ("members", "flag"),
    [
        ({"TimingMode": 3}, "TIMINGMODEINV"),
        ({"TimingMode": -1}, "TIMINGMODEINV"),
        ({"TimingMode": 2, "RTSTime": 0, "RTSTimeStamp": 5}, "RTSTIMEINV"),
        ({"TimingMode": 2, "RTSTime": 32768, "RTSTimeStamp": 5}, "RTSTIMEINV"),
        ({"TimingMode": 2, "RTSTime": 10, "RTSTimeStamp": 32768}, "RTSTIMESTAMPINV"),
        ({"TimingMode": 2, "RTSTime": 10, "RTSTimeStamp": -1}, "RTSTIMESTAMPINV"),
    ],
)
def test_invalid_timing_inputs_set_their_flag_and_stop_the_block(
    members: dict[str, object], flag: str
) -> None:
    s = block(**members)
    assert sample(ExecContext(), s, T) is None
    assert s[IX[flag]] == 1


def test_every_timed_type_has_the_timing_members() -> None:
    from stdlib import catalog

    timed = [
        t.name for t in catalog().types.values() if any(m.name == "TimingMode" for m in t.members)
    ]
    assert len(timed) >= 17
    for name in timed:
        timing_layout(name)  # raises KeyError when a member is missing
