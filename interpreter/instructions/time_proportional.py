"""SRTP (split range time proportional), 1756-RM006; decision 0183.

- A free-running cycle timer counts 0..CycleTime seconds, advanced by DeltaT, the virtual
  time since the block's previous execution (0 on the first); it wraps at CycleTime.
  CycleTime 0 (or invalid: negative, used as 0) clears the timer and both outputs.
- Heat and cool on-times are recomputed at every execution from where In lies in its
  range: HeatTime = (In - MinHeatIn) / (MaxHeatIn - MinHeatIn) x CycleTime, limited to
  0..CycleTime (MaxCoolIn below MinCoolIn makes a falling In cool more). A time shorter than
  MinHeatTime is 0; a longer one than MaxHeatTime is MaxHeatTime. The same for cooling.
- MaxHeatTime negative or above a CycleTime > 0 is invalid and CycleTime is used; MinHeatTime outside
  0..MaxHeatTime is invalid and 0 is used (the reference's substitutions). MaxHeatIn =
  MinHeatIn is HeatSpanInv and heating stays off; likewise for cooling.
- HeatOut is on from the start of each cycle while the timer is below HeatTime;
  HeatTimePercent = HeatTime / CycleTime x 100 (the share of the cycle HeatOut is on).
"""

from __future__ import annotations

from ..runtime.motion_layout import packed_words, struct_type
from ..vm.context import ExecContext
from ..vm.values import f32
from .process_blocks import pack_status
from .registry import implements, prescan

_S = struct_type("SPLIT_RANGE").index
_S_WORDS = packed_words("SPLIT_RANGE")
_S_INVS = tuple(
    _S[b]
    for b in (
        "CYCLETIMEINV",
        "MAXHEATTIMEINV",
        "MINHEATTIMEINV",
        "MAXCOOLTIMEINV",
        "MINCOOLTIMEINV",
        "HEATSPANINV",
        "COOLSPANINV",
    )
)


def _on_time(s: list, side: str, x: float, cycle: float) -> float:
    """On-time in seconds of one side (HEAT or COOL) within a cycle; sets its Inv bits."""
    hi_in, lo_in = s[_S[f"MAX{side}IN"]], s[_S[f"MIN{side}IN"]]
    max_t, min_t = s[_S[f"MAX{side}TIME"]], s[_S[f"MIN{side}TIME"]]
    # (with CycleTime 0 the outputs are off anyway: only a negative time is invalid then)
    s[_S[f"MAX{side}TIMEINV"]] = bad_max = int(max_t < 0.0 or (cycle > 0.0 and max_t > cycle))
    if bad_max:
        max_t = cycle
    s[_S[f"MIN{side}TIMEINV"]] = bad_min = int(not 0.0 <= min_t <= max_t)
    if bad_min:
        min_t = 0.0
    s[_S[f"{side}SPANINV"]] = no_span = int(hi_in == lo_in)
    if no_span or cycle <= 0.0:
        return 0.0
    t = min(max((x - lo_in) / (hi_in - lo_in), 0.0), 1.0) * cycle
    if t < min_t:
        return 0.0
    return min(t, max_t)


@implements("SRTP")
def srtp(ctx: ExecContext, rung: bool, s: list) -> None:
    last, s[_S["LASTRUN"]] = s[_S["LASTRUN"]], ctx.now_ms
    dt = 0.0 if last < 0 else max(0.0, ctx.now_ms - last) / 1000.0
    cycle = s[_S["CYCLETIME"]]
    s[_S["CYCLETIMEINV"]] = int(cycle < 0)
    cycle = max(cycle, 0.0)
    x = s[_S["IN"]]
    heat = _on_time(s, "HEAT", x, cycle)
    cool = _on_time(s, "COOL", x, cycle)
    if cycle <= 0.0:
        s[_S["CYCLETIMER"]] = 0.0
        s[_S["HEATOUT"]] = s[_S["COOLOUT"]] = 0
        s[_S["HEATTIMEPERCENT"]] = s[_S["COOLTIMEPERCENT"]] = 0.0
    else:
        timer = s[_S["CYCLETIMER"]] + dt
        timer = timer % cycle if timer >= cycle else timer
        s[_S["CYCLETIMER"]] = timer
        s[_S["HEATOUT"]] = int(timer < heat)
        s[_S["COOLOUT"]] = int(timer < cool)
        s[_S["HEATTIMEPERCENT"]] = f32(heat / cycle * 100.0)
        s[_S["COOLTIMEPERCENT"]] = f32(cool / cycle * 100.0)
    s[_S["INSTRUCTFAULT"]] = int(any(s[i] for i in _S_INVS))
    pack_status(s, _S_WORDS)
    s[_S["ENABLEOUT"]] = 1


@prescan("SRTP")
def srtp_prescan(ctx: ExecContext, rung: bool, s: list) -> None:
    # Instruction first scan: a new cycle starts at the next execution.
    s[_S["CYCLETIMER"]] = 0.0
    s[_S["LASTRUN"]] = -1.0
