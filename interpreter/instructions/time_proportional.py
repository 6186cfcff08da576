"""SRTP (split range time proportional) and POSP (position proportional), 1756-RM006;
decision 0183. Both pulse on/off outputs at the start of each cycle
of a free-running cycle timer.

SRTP:
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


def _cycle(ctx: ExecContext, s: list, ix: dict[str, int]) -> tuple[float, float | None]:
    """(CycleTime in use, the cycle timer after this execution or None when CycleTime is
    0). DeltaT is the virtual time since the previous execution; sets CycleTimeInv."""
    last, s[ix["LASTRUN"]] = s[ix["LASTRUN"]], ctx.now_ms
    dt = 0.0 if last < 0 else max(0.0, ctx.now_ms - last) / 1000.0
    cycle = s[ix["CYCLETIME"]]
    s[ix["CYCLETIMEINV"]] = int(cycle < 0)
    cycle = max(cycle, 0.0)
    if cycle <= 0.0:
        s[ix["CYCLETIMER"]] = 0.0
        return cycle, None
    timer = s[ix["CYCLETIMER"]] + dt
    s[ix["CYCLETIMER"]] = timer = timer % cycle if timer >= cycle else timer
    return cycle, timer


@implements("SRTP")
def srtp(ctx: ExecContext, rung: bool, s: list) -> None:
    cycle, timer = _cycle(ctx, s, _S)
    x = s[_S["IN"]]
    heat = _on_time(s, "HEAT", x, cycle)
    cool = _on_time(s, "COOL", x, cycle)
    if timer is None:
        s[_S["HEATOUT"]] = s[_S["COOLOUT"]] = 0
        s[_S["HEATTIMEPERCENT"]] = s[_S["COOLTIMEPERCENT"]] = 0.0
    else:
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


# ------------------------------------------------------------------ POSP
_P = struct_type("POSITION_PROP").index
_P_WORDS = packed_words("POSITION_PROP")
_P_INVS = tuple(
    _P[b]
    for b in (
        "CYCLETIMEINV",
        "OPENRATEINV",
        "CLOSERATEINV",
        "MAXONTIMEINV",
        "MINONTIMEINV",
        "DEADTIMEINV",
        "POSITIONPCTINV",
        "SPPERCENTINV",
        "POSITIONSPANINV",
    )
)


@implements("POSP")
def posp(ctx: ExecContext, rung: bool, s: list) -> None:
    """Open/close pulses proportional to the position error, decision 0183:
    OpenTime = (SPPercent - PositionPercent) / OpenRate + Deadtime when SP is above the
    position, CloseTime likewise with CloseRate below it; a time under MinOnTime is 0, over
    MaxOnTime is MaxOnTime. Recomputed every execution (the pulse ends early as the position
    comes in); OpenedFB / ClosedFB keep the matching output off."""
    cycle, timer = _cycle(ctx, s, _P)
    hi, lo = s[_P["POSITIONEUMAX"]], s[_P["POSITIONEUMIN"]]
    s[_P["POSITIONSPANINV"]] = no_span = int(hi == lo)
    open_rate, close_rate = s[_P["OPENRATE"]], s[_P["CLOSERATE"]]
    s[_P["OPENRATEINV"]] = int(not open_rate > 0.0)
    s[_P["CLOSERATEINV"]] = int(not close_rate > 0.0)
    max_on, min_on, dead = s[_P["MAXONTIME"]], s[_P["MINONTIME"]], s[_P["DEADTIME"]]
    s[_P["MAXONTIMEINV"]] = bad = int(max_on < 0.0 or (cycle > 0.0 and max_on > cycle))
    if bad:
        max_on = cycle
    s[_P["MINONTIMEINV"]] = bad = int(not 0.0 <= min_on <= max_on)
    if bad:
        min_on = 0.0
    s[_P["DEADTIMEINV"]] = bad = int(dead < 0.0 or (cycle > 0.0 and dead > cycle))
    if bad:
        dead = 0.0

    open_t = close_t = 0.0
    if not no_span:
        pos = (s[_P["POSITION"]] - lo) / (hi - lo) * 100.0
        sp = (s[_P["SP"]] - lo) / (hi - lo) * 100.0
        s[_P["POSITIONPERCENT"]], s[_P["SPPERCENT"]] = f32(pos), f32(sp)
        s[_P["POSITIONPCTINV"]] = int(not 0.0 <= pos <= 100.0)
        s[_P["SPPERCENTINV"]] = int(not 0.0 <= sp <= 100.0)
        err = min(max(sp, 0.0), 100.0) - min(max(pos, 0.0), 100.0)
        if err > 0.0 and not s[_P["OPENRATEINV"]]:
            open_t = err / open_rate + dead
        elif err < 0.0 and not s[_P["CLOSERATEINV"]]:
            close_t = -err / close_rate + dead
    else:
        s[_P["POSITIONPCTINV"]] = s[_P["SPPERCENTINV"]] = 0

    def limit(t: float) -> float:
        return 0.0 if t < min_on else min(t, max_on)

    open_t, close_t = limit(open_t), limit(close_t)
    if timer is None:
        open_t = close_t = 0.0
    s[_P["OPENTIME"]], s[_P["CLOSETIME"]] = f32(open_t), f32(close_t)
    s[_P["OPENOUT"]] = int(timer is not None and timer < open_t and not s[_P["OPENEDFB"]])
    s[_P["CLOSEOUT"]] = int(timer is not None and timer < close_t and not s[_P["CLOSEDFB"]])
    s[_P["INSTRUCTFAULT"]] = int(any(s[i] for i in _P_INVS))
    pack_status(s, _P_WORDS)
    s[_P["ENABLEOUT"]] = 1


@prescan("POSP")
def posp_prescan(ctx: ExecContext, rung: bool, s: list) -> None:
    s[_P["CYCLETIMER"]] = 0.0
    s[_P["LASTRUN"]] = -1.0
