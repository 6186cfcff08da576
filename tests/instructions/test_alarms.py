"""ALMD and ALMA traced scan by scan (decision 0032; 1756-RM003 alarm chapter).

Executions are 100 ms apart unless a test says otherwise; timestamps are the wall clock of
ladder_system (EPOCH_US + virtual microseconds).
"""

from __future__ import annotations

from pathlib import Path

from interpreter.instructions import alarms as al
from interpreter.instructions.ladder_system import EPOCH_US
from interpreter.vm.context import ExecContext
from tests.instructions.run_cli import trace
from tests.instructions.structs import new_struct, struct_type

D = struct_type("ALARM_DIGITAL").index
A = struct_type("ALARM_ANALOG").index


def _almd(ctx: ExecContext, a: list, t: float, x: int, ack: int = 0, reset: int = 0,
          disable: int = 0, enable: int = 0) -> tuple[int, int, int, int]:  # fmt: skip
    ctx.now_ms = t
    al.almd_st(ctx, True, a, x, ack, reset, disable, enable)
    return a[D["INALARM"]], a[D["ACKED"]], a[D["INALARMUNACK"]], a[D["ALARMCOUNT"]]


def test_almd_activation_return_to_normal_and_ack() -> None:
    ctx, a = ExecContext(), new_struct("ALARM_DIGITAL")
    assert _almd(ctx, a, 0, 0) == (0, 1, 0, 0)  # nothing to acknowledge yet
    assert _almd(ctx, a, 100, 1) == (1, 0, 1, 1)  # In = Condition: active, unacknowledged
    assert a[D["INALARMTIME"]] == EPOCH_US + 100_000
    assert _almd(ctx, a, 200, 0) == (0, 0, 0, 1)  # back to normal, still unacknowledged
    assert a[D["RETTONORMALTIME"]] == EPOCH_US + 200_000
    assert _almd(ctx, a, 300, 0, ack=1) == (0, 1, 0, 1)  # ProgAck rising edge
    assert a[D["ACKTIME"]] == EPOCH_US + 300_000
    assert _almd(ctx, a, 400, 1, ack=1) == (1, 0, 1, 2)  # active again: a new acknowledgement
    assert _almd(ctx, a, 500, 1, ack=1) == (1, 0, 1, 2)  # ProgAck held: no edge, no ack
    assert _almd(ctx, a, 600, 1, ack=0) == (1, 0, 1, 2)
    assert _almd(ctx, a, 700, 1, ack=1) == (1, 1, 0, 2)  # edge: acknowledged while active


def test_almd_latched_needs_ack_then_reset() -> None:
    ctx, a = ExecContext(), new_struct("ALARM_DIGITAL", Latched=1)
    assert _almd(ctx, a, 0, 1) == (1, 0, 1, 1)
    assert _almd(ctx, a, 100, 0) == (1, 0, 1, 1)  # latched: stays active
    assert _almd(ctx, a, 200, 0, reset=1) == (1, 0, 1, 1)  # not acknowledged: no reset
    assert _almd(ctx, a, 300, 0, ack=1) == (1, 1, 0, 1)
    assert _almd(ctx, a, 400, 0, ack=1, reset=0) == (1, 1, 0, 1)
    assert _almd(ctx, a, 500, 0, reset=1) == (0, 1, 0, 1)  # reset edge: back to normal


def test_almd_condition_false_and_no_ack_required() -> None:
    ctx, a = ExecContext(), new_struct("ALARM_DIGITAL", Condition=0, AckRequired=0)
    assert _almd(ctx, a, 0, 1) == (0, 1, 0, 0)
    assert _almd(ctx, a, 100, 0) == (1, 1, 0, 1)  # In = Condition (false); acked by itself


def test_almd_minimum_duration() -> None:
    ctx, a = ExecContext(), new_struct("ALARM_DIGITAL", MinDurationPRE=250)
    seen = []
    for t in (0, 100, 200, 300, 400):
        seen.append((_almd(ctx, a, t, 1)[0], a[D["MINDURATIONACC"]]))
    # held 0, 100, 200 ms: waiting; 300 >= 250: active, nothing waits any more
    assert seen == [(0, 0), (0, 100), (0, 200), (1, 0), (1, 0)]
    _almd(ctx, a, 500, 0)
    assert a[D["MINDURATIONACC"]] == 0
    assert _almd(ctx, a, 600, 1)[0] == 0  # a new activation waits again (InAlarm cleared at 500)


def test_almd_disable_enable_and_operator_requests() -> None:
    ctx, a = ExecContext(), new_struct("ALARM_DIGITAL")
    _almd(ctx, a, 0, 1)
    assert _almd(ctx, a, 100, 1, disable=1) == (0, 1, 0, 1) and a[D["DISABLED"]] == 1
    assert _almd(ctx, a, 200, 1, disable=1, enable=1) == (1, 0, 1, 2)  # enable wins
    a[D["OPERACK"]] = 1
    assert _almd(ctx, a, 300, 1) == (1, 1, 0, 2)
    assert a[D["OPERACK"]] == 0  # an operator request is cleared once handled
    a[D["OPERDISABLE"]] = 1
    _almd(ctx, a, 400, 1)
    assert (a[D["DISABLED"]], a[D["OPERDISABLE"]]) == (1, 0)
    _almd(ctx, a, 500, 1)
    assert a[D["DISABLED"]] == 1  # stays disabled until an enable
    a[D["ALARMCOUNTRESET"]] = 1
    _almd(ctx, a, 600, 1, enable=1)
    assert (a[D["ALARMCOUNT"]], a[D["INALARM"]]) == (1, 1)  # counts reset, then counted again


def test_almd_shelve_expires_in_simulated_time() -> None:
    ctx, a = ExecContext(), new_struct("ALARM_DIGITAL", ShelveDuration=1)
    a[D["OPERSHELVE"]] = 1
    _almd(ctx, a, 0, 0)
    assert a[D["SHELVED"]] == 1 and a[D["UNSHELVETIME"]] - a[D["SHELVETIME"]] == 60_000_000
    _almd(ctx, a, 59_900, 0)
    assert a[D["SHELVED"]] == 1
    _almd(ctx, a, 60_000, 0)  # one minute later
    assert a[D["SHELVED"]] == 0


def test_almd_ladder_rung_is_the_input(tmp_path: Path) -> None:
    src = (
        "VAR a : ALARM_DIGITAL; n : DINT; x : BOOL; END_VAR\n"
        "ADD(n,1,n);\nGEQ(n,3)LEQ(n,4)OTE(x);\nXIC(x)ALMD(a,0,0,0,0);\n"
    )
    rows, _ = trace(tmp_path, src, ".rll", 5, ["a.InAlarm", "a.AlarmCount", "a.InAlarmUnack"])
    seen = [(r["a.InAlarm"], r["a.AlarmCount"], r["a.InAlarmUnack"]) for r in rows]
    # n = 1..5: x on for n = 3 and 4
    assert seen == [
        ("0", "0", "0"),
        ("0", "0", "0"),
        ("1", "1", "1"),
        ("1", "1", "1"),
        ("0", "1", "0"),
    ]


# ------------------------------------------------------------------ ALMA
def _alma(ctx: ExecContext, a: list, t: float, x: float, ack_all: int = 0) -> None:
    ctx.now_ms = t
    al.alma(ctx, True, a, x, ack_all, 0, 0)


def _levels(a: list) -> tuple[int, int, int, int]:
    return tuple(a[A[f"{c}INALARM"]] for c in ("HH", "H", "L", "LL"))  # type: ignore[return-value]


def _analog(**members: object) -> list:
    config: dict[str, object] = {
        "HHEnabled": 1,
        "HEnabled": 1,
        "LEnabled": 1,
        "LLEnabled": 1,
        "HHLimit": 90.0,
        "HLimit": 80.0,
        "LLimit": 20.0,
        "LLLimit": 10.0,
        "Deadband": 2.0,
    }
    return new_struct("ALARM_ANALOG", **(config | members))


def test_alma_levels_with_deadband() -> None:
    ctx, a = ExecContext(), _analog()
    seen = []
    for k, x in enumerate((50.0, 85.0, 91.0, 89.0, 87.9, 79.0, 77.0, 15.0, 5.0, 11.0, 12.5)):
        _alma(ctx, a, 100.0 * k, x)
        seen.append(_levels(a))
    assert seen == [
        (0, 0, 0, 0),
        (0, 1, 0, 0),  # 85 >= H 80
        (1, 1, 0, 0),  # 91 >= HH 90
        (1, 1, 0, 0),  # 89: HH holds until below 90 - 2
        (0, 1, 0, 0),  # 87.9 < 88
        (0, 1, 0, 0),  # 79: H holds until below 78
        (0, 0, 0, 0),  # 77
        (0, 0, 1, 0),  # 15 <= L 20
        (0, 0, 1, 1),  # 5 <= LL 10
        (0, 0, 1, 1),  # 11: LL holds until above 12
        (0, 0, 1, 0),  # 12.5
    ]
    assert [a[A[f"{c}ALARMCOUNT"]] for c in ("HH", "H", "L", "LL")] == [1, 1, 1, 1]
    assert a[A["INALARM"]] == 1 and a[A["ANYINALARMUNACK"]] == 1
    assert a[A["HACKED"]] == 0 and a[A["LLACKED"]] == 0
    _alma(ctx, a, 1100.0, 12.5, ack_all=1)
    assert [a[A[f"{c}ACKED"]] for c in ("HH", "H", "L", "LL")] == [1, 1, 1, 1]
    assert a[A["ANYINALARMUNACK"]] == 0 and a[A["INALARM"]] == 1


def test_alma_rate_of_change() -> None:
    ctx = ExecContext()
    a = new_struct("ALARM_ANALOG", ROCPeriod=1.0, ROCPosLimit=5.0, ROCNegLimit=5.0)
    seen = []
    for t, x in ((0, 50.0), (500, 60.0), (1000, 57.0), (2000, 58.0), (3000, 50.0)):
        _alma(ctx, a, t, x)
        seen.append((a[A["ROC"]], a[A["ROCPOSINALARM"]], a[A["ROCNEGINALARM"]]))
    # samples at 0, 1000, 2000, 3000 ms: (57-50)/1 = 7 >= 5; (58-57) = 1; (50-58) = -8 <= -5
    assert seen == [(0.0, 0, 0), (0.0, 0, 0), (7.0, 1, 0), (1.0, 0, 0), (-8.0, 0, 1)]
    assert (a[A["ROCPOSINALARMCOUNT"]], a[A["ROCNEGALARMCOUNT"]]) == (1, 1)


def test_alma_minimum_duration_per_level() -> None:
    ctx, a = ExecContext(), _analog(HHMinDurationEnable=0, MinDurationPRE=200)
    seen = []
    for t in (0, 100, 200):
        _alma(ctx, a, t, 95.0)
        seen.append((_levels(a), a[A["MINDURATIONACC"]]))
    # HH (its minimum duration turned off) at once; H (on by default) after 200 ms
    assert seen == [((1, 0, 0, 0), 0), ((1, 0, 0, 0), 100), ((1, 1, 0, 0), 0)]


def test_alma_invalid_limits_and_false_rung() -> None:
    ctx, a = ExecContext(), _analog(HLimit=5.0)  # H below L and LL: out of order
    _alma(ctx, a, 0, 95.0)
    assert a[A["ALARMLIMITSINV"]] == 1 and a[A["STATUS"]] == 0b1000
    assert _levels(a) == (0, 0, 0, 0)
    a = _analog()
    al.alma(ctx, False, a, 95.0, 0, 0, 0)  # ladder: a false rung does not evaluate
    assert (a[A["ENABLEOUT"]], a[A["INALARM"]], a[A["IN"]]) == (0, 0, 0.0)
