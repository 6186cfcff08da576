"""GSV / SSV: controller object attributes a simulator can honour (decision 0030).

ClassName and AttributeName arrive as the private numbers of the catalog enumerations
(stdlib/instructions/special.toml); InstanceName is not needed by any simulated attribute.
Dest (GSV) and Source (SSV) arrive as raw memory from the element named, so a DINT[7] is
written from `dt[0]` on, and a 64-bit value goes into a LINT or into two DINTs (low word
first), as on the controller.

Simulated attributes:
- WALLCLOCKTIME: the clock reads EPOCH (2024-01-01 00:00:00 UTC) plus the virtual time, so
  runs are reproducible. CurrentValue (LINT, µs since 1970-01-01 UTC), DateTime and
  LocalDateTime (DINT[7]: year, month, day, hour, minute, second, µs), UTCOffset (LINT µs,
  default 0), DSTAdjustment (INT minutes, default 0) and ApplyDST (SINT, default 0). SSV
  of any of them is kept for the rest of the run: setting the time moves the clock, which
  then keeps running with the virtual time. LocalDateTime = UTC + UTCOffset (+ the DST
  adjustment while ApplyDST is set). CSTOffset (LINT) is CurrentValue minus CST; setting
  it moves the clock to CST + the value.
- CST CurrentValue: µs since the controller started (the virtual time).
- TASK: Rate, LastScanTime and MaxScanTime are the scan period in µs (every simulated scan
  takes one period); Watchdog is the watchdog budget expressed as time (5,000,000
  statements = 500 ms, so budget / 10 µs); StartTime is CurrentValue at the start of the
  scan; OverlapCount is 0. SSV of MaxScanTime / OverlapCount (a reset) is accepted.
- PROGRAM: LastScanTime and MaxScanTime as for the task; SSV of MaxScanTime is accepted.
- FAULTLOG: MinorEvents counts the minor faults recorded so far, MinorFaultBits has bit T
  set for each fault type T among them; SSV of either (any value) clears them, as the usual
  "clear minor faults" rung does. Major faults stop a run, so MajorEvents/MajorFaultBits
  read 0 and SSV of them (the "clear major faults" rung) has nothing to clear.
- AXIS, MOTIONGROUP, COORDINATESYSTEM: every member of the object's tag is an attribute
  (stdlib/system_objects.toml `members_of`): GSV reads the member of the tag named as
  InstanceName, SSV writes a writable one (a new axis limit applies to the next motion
  instruction, as a write to the tag member does).
Which pairs are simulated is data (stdlib/system_objects.toml, `simulated`); everything else
is reported by `check` as U303 (see `unsupported`) and has no effect.
"""

from __future__ import annotations

from datetime import UTC, datetime, timedelta
from functools import cache

from stdlib import SystemAttribute, catalog

from ..runtime.motion import Axis, MotionRuntime
from ..runtime.motion_layout import struct_type
from ..semantics.types import Elementary, TypeTable
from ..vm.context import ExecContext
from ..vm.values import convert
from .file_ops import _block
from .registry import implements

EPOCH = datetime(2024, 1, 1, tzinfo=UTC)
UNIX = datetime(1970, 1, 1, tzinfo=UTC)
EPOCH_US = (EPOCH - UNIX) // timedelta(microseconds=1)


@cache
def _attribute(key: tuple[str, str]) -> SystemAttribute | None:
    return catalog().system_attribute(*key)  # a GSV in a loop should not rescan the table


def _shape(a: SystemAttribute) -> str:
    """How the value is laid out in memory: "LINT" (64-bit), "DINT7", or a scalar type name."""
    return "DINT7" if a.type == "DINT[7]" else a.type


def unsupported(class_name: str, attribute: str, write: bool) -> bool:
    """True when GSV (write=False) / SSV (write=True) of this pair is not simulated (U303)."""
    a = _attribute((class_name.upper(), attribute.upper()))
    return a is None or ("set" if write else "get") not in a.simulated


def attribute_names(cls: int, attr: int) -> tuple[str, str]:
    cat = catalog()
    c = cat.enum("GSV_ClassName").by_value(int(cls))
    a = cat.enum("GSV_AttributeName").by_value(int(attr))
    return (c.text.upper() if c else "", a.text.upper() if a else "")


# ------------------------------------------------------------------ clock
def _utc_us(ctx: ExecContext, at_ms: float | None = None) -> int:
    ms = ctx.now_ms if at_ms is None else at_ms
    return EPOCH_US + round(ms * 1000) + int(ctx.system.get("clock_offset_us", 0))


def _local_shift_us(ctx: ExecContext) -> int:
    dst = int(ctx.system.get("dst_minutes", 0)) if ctx.system.get("apply_dst", 0) else 0
    return int(ctx.system.get("utc_offset_us", 0)) + dst * 60_000_000


def _to_fields(us: int) -> list[int]:
    t = UNIX + timedelta(microseconds=us)
    return [t.year, t.month, t.day, t.hour, t.minute, t.second, t.microsecond]


def _from_fields(words: list[int]) -> int | None:
    try:
        y, mo, d, h, mi, s, us = (int(w) for w in words[:7])
        t = datetime(y, mo, d, h, mi, s, us, tzinfo=UTC)
    except (ValueError, TypeError, OverflowError):  # also fewer than 7 words
        return None  # not a valid date: the clock is left alone
    return (t - UNIX) // timedelta(microseconds=1)


def _cst_us(ctx: ExecContext) -> int:
    """Coordinated system time: µs since the controller started (the virtual time)."""
    return round(ctx.now_ms * 1000)


def _set_clock(ctx: ExecContext, utc_us: int) -> None:
    ctx.system["clock_offset_us"] = utc_us - EPOCH_US - round(ctx.now_ms * 1000)


# ------------------------------------------------------------------ fault log
def _minor_by_type(ctx: ExecContext) -> dict[int, int]:
    counts: dict[int, int] = {}
    for f in ctx.minor_faults.values():
        counts[f.type] = counts.get(f.type, 0) + f.count
    return counts


def _minor_since_clear(ctx: ExecContext) -> dict[int, int]:
    base: dict[int, int] = ctx.system.get("minor_base", {})
    return {t: n - base.get(t, 0) for t, n in _minor_by_type(ctx).items() if n > base.get(t, 0)}


# ------------------------------------------------------------------ values
def _read_value(ctx: ExecContext, key: tuple[str, str]) -> int | list[int]:
    cls, attr = key
    period_us = round(ctx.scan_period_ms * 1000)
    if cls == "WALLCLOCKTIME":
        if attr == "CURRENTVALUE":
            return _utc_us(ctx)
        if attr == "DATETIME":
            return _to_fields(_utc_us(ctx))
        if attr == "LOCALDATETIME":
            return _to_fields(_utc_us(ctx) + _local_shift_us(ctx))
        if attr == "UTCOFFSET":
            return int(ctx.system.get("utc_offset_us", 0))
        if attr == "DSTADJUSTMENT":
            return int(ctx.system.get("dst_minutes", 0))
        if attr == "CSTOFFSET":  # the clock is CST plus this offset
            return _utc_us(ctx) - _cst_us(ctx)
        return int(ctx.system.get("apply_dst", 0))
    if cls == "CST":
        return _cst_us(ctx)
    if cls == "FAULTLOG":
        since = _minor_since_clear(ctx)
        if attr == "MINOREVENTS":
            return sum(since.values())
        if attr == "MINORFAULTBITS":
            bits = 0
            for t in since:
                bits |= 1 << t
            return bits
        return 0  # MAJOREVENTS / MAJORFAULTBITS: a major fault ends the run
    if attr == "WATCHDOG":
        return ctx.budget // 10
    if attr == "STARTTIME":
        return _utc_us(ctx)
    if attr == "OVERLAPCOUNT":
        return 0
    return period_us  # RATE, LASTSCANTIME, MAXSCANTIME


def _write_value(ctx: ExecContext, key: tuple[str, str], value: int | list[int]) -> None:
    cls, attr = key
    if cls == "WALLCLOCKTIME":
        if attr == "CURRENTVALUE":
            _set_clock(ctx, int(value))  # type: ignore[arg-type]
        elif attr in ("DATETIME", "LOCALDATETIME"):
            us = _from_fields(value if isinstance(value, list) else [value])
            if us is not None:
                _set_clock(ctx, us - (_local_shift_us(ctx) if attr == "LOCALDATETIME" else 0))
        elif attr == "UTCOFFSET":
            ctx.system["utc_offset_us"] = int(value)  # type: ignore[arg-type]
        elif attr == "DSTADJUSTMENT":
            ctx.system["dst_minutes"] = int(value)  # type: ignore[arg-type]
        elif attr == "CSTOFFSET":
            _set_clock(ctx, _cst_us(ctx) + int(value))  # type: ignore[arg-type]
        else:
            ctx.system["apply_dst"] = int(value)  # type: ignore[arg-type]
    elif cls == "FAULTLOG" and attr in ("MINOREVENTS", "MINORFAULTBITS"):
        ctx.system["minor_base"] = _minor_by_type(ctx)
    # FAULTLOG MajorEvents/MajorFaultBits: a major fault ends the run, so there is never a
    # major fault to clear and both keep reading 0.
    # TASK/PROGRAM MaxScanTime, OverlapCount: every simulated scan takes one period, so a
    # reset has nothing to clear.


# ------------------------------------------------------------------ memory access
def _put(dest: object, shape: str, value: int | list[int]) -> None:
    elements, start, etype, avail = _block(dest, "Dest")
    if not isinstance(etype, Elementary) or avail <= 0:
        return
    if isinstance(value, int) and shape == "LINT" and etype.bits < 64:
        value = [value & 0xFFFFFFFF, (value >> 32) & 0xFFFFFFFF]  # two DINTs, low word first
    words = value if isinstance(value, list) else [value]
    for i, w in enumerate(words[:avail]):
        elements[start + i] = convert(w, etype)


def _get(source: object, shape: str) -> int | list[int]:
    elements, start, etype, avail = _block(source, "Source")
    words = [int(elements[start + i]) for i in range(max(0, avail))]
    if shape == "DINT7":
        return words[:7]
    if shape == "LINT" and isinstance(etype, Elementary) and etype.bits < 64 and len(words) >= 2:
        return (words[0] & 0xFFFFFFFF) | (words[1] << 32)
    return words[0] if words else 0


def _member(ctx: ExecContext, cls: str, instance: object, name: str) -> tuple[list, int] | None:
    """(tag storage, member index) of a motion object attribute (AXIS, MOTIONGROUP, ...)."""
    if not isinstance(instance, list):
        return None  # InstanceName did not name a tag of the class
    system_class = catalog().system_classes.get(cls)
    if system_class is None or not system_class.members_of:
        return None
    axis = _axis_of(ctx, instance)
    index = axis.layout.index if axis is not None else struct_type(system_class.members_of).index
    at = index.get(name)
    return (instance, at) if at is not None and at < len(instance) else None


def _axis_of(ctx: ExecContext, instance: list) -> Axis | None:
    rt = ctx.motion
    return rt.axis(instance) if isinstance(rt, MotionRuntime) else None


@implements("GSV")
def gsv(ctx: ExecContext, rung: bool, cls: int, instance: object, attr: int, dest: object) -> None:
    if not rung:
        return
    key = attribute_names(cls, attr)
    a = _attribute(key)
    if a is None or "get" not in a.simulated:
        return  # U303: not simulated, the destination keeps its value
    if a.member:
        where = _member(ctx, key[0], instance, a.member.upper())
        if where is not None:
            value = where[0][where[1]]
            _put(dest, a.type, list(value) if isinstance(value, list) else value)
        return
    _put(dest, _shape(a), _read_value(ctx, key))


@implements("SSV")
def ssv(
    ctx: ExecContext, rung: bool, cls: int, instance: object, attr: int, source: object
) -> None:
    if not rung:
        return
    key = attribute_names(cls, attr)
    a = _attribute(key)
    if a is None or "set" not in a.simulated:
        return
    if a.member:
        where = _member(ctx, key[0], instance, a.member.upper())
        if where is not None and isinstance(a_type := TypeTable().get(a.type), Elementary):
            storage, at = where
            elements, start, _, avail = _block(source, "Source")
            if avail > 0:  # the element as it is (a REAL stays a REAL)
                storage[at] = convert(elements[start], a_type)
            rt = ctx.motion
            axis = rt.axis(storage) if isinstance(rt, MotionRuntime) else None
            if axis is not None:  # a new limit applies to the next motion instruction
                rt.refresh(axis)  # type: ignore[union-attr]
        return
    _write_value(ctx, key, _get(source, _shape(a)))
