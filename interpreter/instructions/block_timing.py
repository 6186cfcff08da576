"""DeltaT of the time-based process and drives blocks (LPF, INTG, PIDE, TOT, ...), decision 0139.

Every block whose instance type has TimingMode works over the time since its previous
sample. The three timing modes of the process-control reference (1756-RM006):
- 0 periodic: in a periodic task DeltaT is the task's period; in the continuous task (and
  event tasks) it is the virtual time since the block's previous execution, 0 on its first.
- 1 oversample: DeltaT is OversampleDT (seconds), whatever the task.
- 2 real-time sampling: the block samples only when RTSTimeStamp (ms, 0..32767, wrapping)
  has changed since its previous execution; DeltaT is the stamp difference. A difference
  larger than RTSTime (the input module's sample period, 1..32767 ms) means a sample was
  lost: RTSMissed. The first stamp seen only starts the series (DeltaT 0).
Invalid values set their Status bit (TimingModeInv, RTSTimeInv, RTSTimeStampInv,
DeltaTInv for DeltaT outside 0..4194.303 s) and the block must not compute; `sample`
returns None then, and also when a real-time-sampling block sees no new stamp.

The block keeps the previous execution time and stamp in two hidden members (LastRun,
LastStamp, -1 before the first). The Status bits are written as the BOOL members; the block
packs its Status words afterwards (runtime/motion_layout.packed_words and pack).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache

from ..runtime.motion_layout import struct_type
from ..vm.context import ExecContext
from ..vm.values import f32

MAX_DELTA_T = 4194.303  # seconds: the largest DeltaT (and OversampleDT) the blocks accept
STAMP_MODULUS = 32768  # RTSTimeStamp counts 0..32767 ms and wraps
PERIODIC, OVERSAMPLE, REAL_TIME_SAMPLING = 0, 1, 2


@dataclass(frozen=True, slots=True)
class TimingLayout:
    """Member positions of the timing inputs, outputs and flags in one block type."""

    mode: int
    oversample_dt: int
    rts_time: int
    rts_stamp: int
    delta_t: int
    last_run: int
    last_stamp: int
    mode_inv: int
    rts_missed: int
    rts_time_inv: int
    rts_stamp_inv: int
    delta_t_inv: int


@cache
def timing_layout(type_name: str) -> TimingLayout:
    ix = struct_type(type_name).index
    return TimingLayout(
        *(
            ix[m]
            for m in (
                "TIMINGMODE",
                "OVERSAMPLEDT",
                "RTSTIME",
                "RTSTIMESTAMP",
                "DELTAT",
                "LASTRUN",
                "LASTSTAMP",
                "TIMINGMODEINV",
                "RTSMISSED",
                "RTSTIMEINV",
                "RTSTIMESTAMPINV",
                "DELTATINV",
            )
        )
    )


def sample(ctx: ExecContext, s: list, t: TimingLayout) -> float | None:
    """This execution's DeltaT in seconds (also written to the DeltaT member), or None when
    the block must not compute now. Sets the five timing flags; returns None with a flag
    set when a timing input is invalid."""
    for flag in (t.mode_inv, t.rts_missed, t.rts_time_inv, t.rts_stamp_inv, t.delta_t_inv):
        s[flag] = 0
    mode = s[t.mode]
    last_run, s[t.last_run] = s[t.last_run], ctx.now_ms
    if mode == PERIODIC:
        if ctx.task_period_ms is not None:
            dt = ctx.task_period_ms / 1000.0
        else:
            dt = 0.0 if last_run < 0 else max(0.0, ctx.now_ms - last_run) / 1000.0
    elif mode == OVERSAMPLE:
        dt = float(s[t.oversample_dt])
    elif mode == REAL_TIME_SAMPLING:
        rts_time, stamp = s[t.rts_time], s[t.rts_stamp]
        if not 1 <= rts_time <= STAMP_MODULUS - 1:
            s[t.rts_time_inv] = 1
        if not 0 <= stamp <= STAMP_MODULUS - 1:
            s[t.rts_stamp_inv] = 1
        if s[t.rts_time_inv] or s[t.rts_stamp_inv]:
            return None
        last_stamp = s[t.last_stamp]
        if stamp == last_stamp:
            return None  # no new sample from the module: nothing to compute
        s[t.last_stamp] = stamp
        if last_stamp < 0:
            dt = 0.0
        else:
            diff_ms = (stamp - last_stamp) % STAMP_MODULUS
            s[t.rts_missed] = int(diff_ms > rts_time)
            dt = diff_ms / 1000.0
    else:
        s[t.mode_inv] = 1
        return None
    if not 0.0 <= dt <= MAX_DELTA_T:
        s[t.delta_t_inv] = 1
        return None
    s[t.delta_t] = f32(dt)
    return dt


def restart(s: list, t: TimingLayout) -> None:
    """Forget the previous execution (prescan): the next DeltaT starts a new series."""
    s[t.last_run] = -1.0
    s[t.last_stamp] = -1
