"""GSV / SSV called directly with the catalog's enumeration numbers and memory ArrayRefs."""

from __future__ import annotations

from interpreter.instructions import ladder_system as sv
from interpreter.semantics.types import DINT, INT, LINT
from interpreter.vm.context import ExecContext
from interpreter.vm.refs import ArrayRef
from stdlib import catalog


def _cls(text: str) -> int:
    v = catalog().enum("GSV_ClassName").lookup(text)
    assert v is not None
    return v.value


def _attr(text: str) -> int:
    v = catalog().enum("GSV_AttributeName").lookup(text)
    assert v is not None
    return v.value


def _mem(values: list, t, start: int = 0) -> ArrayRef:  # noqa: ANN001
    return ArrayRef(values, start, t, (len(values),))


def _scalar(t, value: int = 0) -> ArrayRef:  # noqa: ANN001
    return ArrayRef([value], 0, t, ())  # a non-array tag as the VM passes it


def _gsv(ctx: ExecContext, cls: str, attr: str, dest: ArrayRef) -> None:
    sv.gsv(ctx, True, _cls(cls), 0, _attr(attr), dest)


def _ssv(ctx: ExecContext, cls: str, attr: str, source: ArrayRef) -> None:
    sv.ssv(ctx, True, _cls(cls), 0, _attr(attr), source)


# 2024-01-01T00:00:00Z: 54 years after 1970-01-01 = 54 * 365 + 13 leap days (1972..2020) = 19723 days
EPOCH_US = 19723 * 86400 * 1_000_000


def test_wall_clock_starts_at_the_fixed_epoch_and_follows_virtual_time() -> None:
    ctx = ExecContext(now_ms=1500.0)
    x = _scalar(LINT)
    _gsv(ctx, "WallClockTime", "CurrentValue", x)
    assert x.elements[0] == EPOCH_US + 1_500_000
    dt = [0] * 7
    _gsv(ctx, "WALLCLOCKTIME", "DateTime", _mem(dt, DINT))
    assert dt == [2024, 1, 1, 0, 0, 1, 500000]


def test_current_value_into_two_dints_low_word_first() -> None:
    ctx = ExecContext(now_ms=0.0)
    words = [0, 0]
    _gsv(ctx, "WallClockTime", "CurrentValue", _mem(words, DINT))
    high, low = divmod(EPOCH_US, 2**32)
    low = low - 2**32 if low >= 2**31 else low  # stored as a signed DINT
    assert words == [low, high]


def test_ssv_date_time_moves_the_clock_which_keeps_running() -> None:
    ctx = ExecContext(now_ms=1000.0)
    _ssv(ctx, "WallClockTime", "DateTime", _mem([2030, 6, 15, 12, 0, 0, 0], DINT))
    ctx.now_ms = 3000.0
    dt = [0] * 7
    _gsv(ctx, "WallClockTime", "DateTime", _mem(dt, DINT))
    assert dt == [2030, 6, 15, 12, 0, 2, 0]  # 2 s of virtual time later


def test_local_date_time_applies_the_utc_offset_and_dst() -> None:
    ctx = ExecContext(now_ms=0.0)
    _ssv(ctx, "WallClockTime", "UTCOffset", _scalar(LINT, 3_600_000_000))  # +1 h
    dt = [0] * 7
    _gsv(ctx, "WallClockTime", "LocalDateTime", _mem(dt, DINT))
    assert dt[:4] == [2024, 1, 1, 1]
    _ssv(ctx, "WallClockTime", "DSTAdjustment", _scalar(INT, 60))
    _gsv(ctx, "WallClockTime", "LocalDateTime", _mem(dt, DINT))
    assert dt[3] == 1  # DST adjustment ignored while ApplyDST is 0
    _ssv(ctx, "WallClockTime", "ApplyDST", _scalar(INT, 1))
    _gsv(ctx, "WallClockTime", "LocalDateTime", _mem(dt, DINT))
    assert dt[3] == 2


def test_task_attributes_come_from_the_scan_period_and_budget() -> None:
    ctx = ExecContext(scan_period_ms=2.5)
    for attr in ("Rate", "LastScanTime", "MaxScanTime"):
        r = _scalar(DINT)
        _gsv(ctx, "TASK", attr, r)
        assert r.elements[0] == 2500  # 2.5 ms in µs
    w = _scalar(DINT)
    _gsv(ctx, "TASK", "Watchdog", w)
    assert w.elements[0] == 500_000  # 5,000,000 statements = 500 ms


def test_faultlog_counts_minor_faults_until_cleared() -> None:
    ctx = ExecContext()
    ctx.minor(4, 4, "x", site=1)
    ctx.minor(4, 4, "x", site=1)
    ctx.minor(4, 4, "y", site=2)
    n, bits = _scalar(INT), _scalar(DINT)
    _gsv(ctx, "FAULTLOG", "MinorEvents", n)
    _gsv(ctx, "FAULTLOG", "MinorFaultBits", bits)
    assert (n.elements[0], bits.elements[0]) == (3, 1 << 4)  # three type-4 faults
    _ssv(ctx, "FAULTLOG", "MinorFaultBits", _scalar(DINT, 0))
    _gsv(ctx, "FAULTLOG", "MinorEvents", n)
    _gsv(ctx, "FAULTLOG", "MinorFaultBits", bits)
    assert (n.elements[0], bits.elements[0]) == (0, 0)
    ctx.minor(4, 4, "z", site=1)
    _gsv(ctx, "FAULTLOG", "MinorEvents", n)
    assert n.elements[0] == 1


def test_unsupported_pairs_are_reported_and_have_no_effect() -> None:
    assert sv.unsupported("TASK", "Priority", write=False)
    assert sv.unsupported("CONTROLLERDEVICE", "Status", write=False)
    assert sv.unsupported("TASK", "Rate", write=True)  # readable, not settable
    assert not sv.unsupported("wallclocktime", "currentvalue", write=True)
    ctx = ExecContext()
    r = _scalar(DINT, 77)
    _gsv(ctx, "TASK", "Priority", r)
    _gsv(ctx, "Module", "FaultCode", r)
    assert r.elements[0] == 77
    sv.gsv(ctx, False, _cls("TASK"), 0, _attr("Rate"), r)  # false rung: no action
    assert r.elements[0] == 77


def test_cst_offset_is_the_clock_minus_cst_and_setting_it_moves_the_clock() -> None:
    ctx = ExecContext(now_ms=250.0)  # CST = 250,000 µs since the controller started
    off = _scalar(LINT)
    _gsv(ctx, "WallClockTime", "CSTOffset", off)
    assert off.elements[0] == EPOCH_US  # clock EPOCH + 0.25 s minus CST 0.25 s
    # an offset of EPOCH + 1 h: the clock reads CST + that, i.e. 01:00:00.25 on 2024-01-01
    _ssv(ctx, "WallClockTime", "CSTOffset", _scalar(LINT, EPOCH_US + 3_600_000_000))
    dt = [0] * 7
    _gsv(ctx, "WallClockTime", "DateTime", _mem(dt, DINT))
    assert dt == [2024, 1, 1, 1, 0, 0, 250000]


def test_clearing_major_faults_leaves_the_minor_log() -> None:
    ctx = ExecContext()
    ctx.minor(4, 4, "x", site=1)
    _ssv(ctx, "FAULTLOG", "MajorEvents", _scalar(INT, 0))
    _ssv(ctx, "FAULTLOG", "MajorFaultBits", _scalar(DINT, 0))
    n, major = _scalar(INT), _scalar(INT, 5)
    _gsv(ctx, "FAULTLOG", "MinorEvents", n)
    _gsv(ctx, "FAULTLOG", "MajorEvents", major)
    assert (n.elements[0], major.elements[0]) == (1, 0)


def test_pairs_the_table_does_not_know_for_a_class_are_not_simulated() -> None:
    # DateTime is a WallClockTime attribute, not a Task one
    assert sv.unsupported("TASK", "DateTime", write=False)
    assert catalog().system_attribute("TASK", "DateTime") is None
