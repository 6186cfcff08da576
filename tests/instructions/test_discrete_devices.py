"""D2SD and D3SD (discrete_devices.py, decision 0182), expected values worked by hand from
the rules in the decision (1756-RM006 tables for program, operator, override and hand
control, fault timer and mode alarm)."""

from __future__ import annotations

from pathlib import Path

from interpreter.instructions import discrete_devices as dd
from interpreter.vm.context import ExecContext
from tests.instructions.run_cli import trace
from tests.instructions.structs import new_struct, struct_type

I2 = struct_type("DISCRETE_2STATE").index
I3 = struct_type("DISCRETE_3STATE").index


def d2(s: list, ctx: ExecContext | None = None, **members: object) -> list:
    for name, v in members.items():
        s[I2[name.upper()]] = v
    dd.d2sd(ctx or ExecContext(), True, s)
    return s


def g2(s: list, *names: str) -> tuple[object, ...]:
    return tuple(s[I2[n.upper()]] for n in names)


def test_d2sd_feedback_timeout_through_run(tmp_path: Path) -> None:
    src = (
        "VAR p : DISCRETE_2STATE; k : DINT; END_VAR\n"
        "p.ProgProgReq := 1; p.ProgCommand := 1; p.State0Perm := 1; p.State1Perm := 1;\n"
        "p.FB0State1 := 1; p.FaultTime := 0.5;\n"
        "D2SD(p);\n"
    )
    rows, report = trace(tmp_path, src, ".st", 7, ["p.Out", "p.FaultAlarm", "p.Device1State"], 100)
    # program control, command 1 from the first scan (t = 0): the fault timer starts; the
    # running feedback FB0 never comes, so at t = 500 ms (scan 5) FaultTime 0.5 s has run out
    assert [r["p.Out"] for r in rows] == ["1"] * 7
    assert [r["p.FaultAlarm"] for r in rows] == ["0"] * 5 + ["1"] * 2
    assert {r["p.Device1State"] for r in rows} == {"0"}
    assert report["diagnostics"] == []


def test_d2sd_feedback_in_time_and_uncommanded_change() -> None:
    ctx = ExecContext(now_ms=0.0)
    s = new_struct("DISCRETE_2STATE", ProgOper=1, State0Perm=1, State1Perm=1, FaultTime=2.0)
    s[I2["FB0STATE1"]] = 1  # running: FB0 on; stopped: FB0 off (FB1 unused, 0 in both)
    d2(s, ctx, ProgCommand=1)
    assert g2(s, "CommandStatus", "Out", "Device0State", "Device1State") == (1, 1, 1, 0)
    ctx.now_ms = 1500.0
    d2(s, ctx, FB0=1)  # confirmed within 2 s: timer stopped, no alarm
    assert g2(s, "Device1State", "FaultAlarm") == (1, 0)
    ctx.now_ms = 9000.0
    d2(s, ctx)  # long after: still fine
    assert g2(s, "FaultAlarm") == (0,)
    d2(s, ctx, FB0=0)  # the motor stopped by itself: no timer running -> alarm at once
    assert g2(s, "FaultAlarm", "Device1State") == (1, 0)
    d2(s, ctx, FB0=1)  # back in the commanded state: cleared (not latched)
    assert g2(s, "FaultAlarm") == (0,)


def test_d2sd_latched_fault_needs_unlatch() -> None:
    ctx = ExecContext(now_ms=0.0)
    s = new_struct("DISCRETE_2STATE", ProgOper=1, State1Perm=1, FaultTime=1.0, FaultAlarmLatch=1)
    s[I2["FB0STATE1"]] = 1
    d2(s, ctx, ProgCommand=1)
    ctx.now_ms = 1000.0
    d2(s, ctx)  # 1 s without feedback
    assert g2(s, "FaultAlarm") == (1,)
    d2(s, ctx, FB0=1)  # feedback now good, but latched
    assert g2(s, "FaultAlarm") == (1,)
    d2(s, ctx, FaultAlmUnlatch=1)  # unlatch with no fault present: cleared, request cleared
    assert g2(s, "FaultAlarm", "FaultAlmUnlatch") == (0, 0)


def test_d2sd_permissives_operator_requests_and_out_reverse() -> None:
    s = new_struct("DISCRETE_2STATE", State0Perm=1, State1Perm=0, OutReverse=1)
    d2(s, Oper1Req=1)  # operator control (a new tag), state 1 not permitted: stays 0
    assert g2(s, "ProgOper", "CommandStatus", "Out", "Oper1Req") == (0, 0, 1, 0)
    d2(s, State1Perm=1, Oper1Req=1)  # permitted now; Out is reversed: 0
    assert g2(s, "CommandStatus", "Out") == (1, 0)
    d2(s, Oper0Req=1, Oper1Req=1)  # both: OperReqInv (bit 2) + InstructFault = 5, hold 1
    assert g2(s, "CommandStatus", "Status", "OperReqInv") == (1, 5, 1)
    d2(s, ProgCommand=1)  # program command ignored in operator control; Status clean again
    d2(s, Oper0Req=1)
    assert g2(s, "CommandStatus", "Status") == (0, 0)


def test_d2sd_override_and_hand() -> None:
    s = new_struct("DISCRETE_2STATE", ProgOper=1, State0Perm=1, State1Perm=0)
    d2(s, ProgOverrideReq=1, OverrideState=1)  # override ignores the permissive
    assert g2(s, "Override", "Hand", "CommandStatus") == (1, 0, 1)
    d2(s, ProgHandReq=1, HandFB=0)  # hand wins over override; follows the hand switch
    assert g2(s, "Override", "Hand", "CommandStatus") == (0, 1, 0)
    d2(s, HandFB=1)
    assert g2(
        s,
        "CommandStatus",
    ) == (1,)
    d2(s, ProgHandReq=0, ProgOverrideReq=0, State1Perm=1)  # back to program: ProgCommand 0
    assert g2(s, "Override", "Hand", "CommandStatus") == (0, 0, 0)


def test_d2sd_override_on_fault_and_on_init() -> None:
    ctx = ExecContext(now_ms=0.0)
    s = new_struct("DISCRETE_2STATE", ProgOper=1, State1Perm=1, State0Perm=1, FaultTime=1.0)
    s[I2["FB0STATE1"]] = 1
    s[I2["OVERRIDEONFAULT"]] = 1  # OverrideState 0: a faulted device is stopped
    d2(s, ctx, ProgCommand=1)
    ctx.now_ms = 1000.0
    d2(s, ctx)  # fault
    assert g2(s, "FaultAlarm", "Override") == (1, 0)
    d2(s, ctx)  # FaultAlarm with OverrideOnFault: override to state 0
    assert g2(s, "Override", "CommandStatus", "Out") == (1, 0, 0)
    s2 = new_struct("DISCRETE_2STATE", ProgOper=1, State1Perm=1, OverrideOnInit=1)
    dd.d2sd_prescan(ctx, True, s2)
    d2(s2, ctx, ProgCommand=1, OverrideState=0)  # first execution after prescan: override
    assert g2(s2, "Override", "CommandStatus") == (1, 0)
    d2(s2, ctx)  # then program control
    assert g2(s2, "Override", "CommandStatus") == (0, 1)


def test_d2sd_fault_time_invalid_and_mode_alarm() -> None:
    s = new_struct("DISCRETE_2STATE", State0Perm=1, State1Perm=1, FaultTime=-1.0)
    d2(s)
    # FaultTimeInv (bit 1) + InstructFault = 3; treated as 0: no fault checking
    assert g2(s, "Status", "FaultTimeInv", "FaultAlarm") == (3, 1, 0)
    d2(s, FaultTime=0.0, ProgCommand=1)  # operator control in state 0, program asks for 1
    assert g2(s, "ModeAlarm", "CommandStatus") == (1, 0)
    d2(s)  # no new change: the alarm stays
    assert g2(s, "ModeAlarm") == (1,)
    d2(s, ProgCommand=0)  # program command equals the commanded state: cleared
    assert g2(s, "ModeAlarm") == (0,)
    d2(s, ProgCommand=1, ProgProgReq=1)  # in program control: no mode alarm
    assert g2(s, "ModeAlarm", "ProgOper", "CommandStatus") == (0, 1, 1)
    d2(s, ProgValueReset=1)  # program requests cleared after the execution
    assert g2(s, "ProgProgReq", "ProgOper") == (0, 1)


# ------------------------------------------------------------------ D3SD
def d3(s: list, ctx: ExecContext | None = None, **members: object) -> list:
    for name, v in members.items():
        s[I3[name.upper()]] = v
    dd.d3sd(ctx or ExecContext(), True, s)
    return s


def g3(s: list, *names: str) -> tuple[object, ...]:
    return tuple(s[I3[n.upper()]] for n in names)


def _two_speed() -> list:
    # state 0 stop: no outputs; state 1 slow: Out0; state 2 fast: Out0 and Out1.
    # feedback FB0 = running slow, FB1 = running fast
    return new_struct(
        "DISCRETE_3STATE",
        ProgOper=1,
        State0Perm=1,
        State1Perm=1,
        State2Perm=1,
        Out0State1=1,
        Out0State2=1,
        Out1State2=1,
        FB0State1=1,
        FB1State2=1,
        FaultTime=3.0,
    )


def test_d3sd_program_commands_outputs_and_feedback() -> None:
    ctx = ExecContext(now_ms=0.0)
    s = _two_speed()
    d3(s, ctx, Prog2Command=1)
    assert g3(s, "Command0Status", "Command1Status", "Command2Status") == (0, 0, 1)
    assert g3(s, "Out0", "Out1", "Out2") == (1, 1, 0)
    ctx.now_ms = 2000.0
    d3(s, ctx, FB1=1)  # fast feedback within 3 s
    assert g3(s, "Device2State", "Device1State", "FaultAlarm") == (1, 0, 0)
    d3(s, ctx, Prog2Command=0, Prog1Command=1)  # to slow: the timer starts again at 2 s
    assert g3(s, "Command1Status", "Out0", "Out1") == (1, 1, 0)
    ctx.now_ms = 5000.0  # 3 s later, FB still says fast
    d3(s, ctx)
    assert g3(s, "FaultAlarm", "Device1State") == (1, 0)


def test_d3sd_invalid_commands_hold_the_state() -> None:
    s = _two_speed()
    d3(s, Prog1Command=1)
    d3(s, Prog2Command=1)  # two program commands: ProgCommandInv (bit 3) + bit 0 = 9
    assert g3(s, "Status", "ProgCommandInv", "Command1Status") == (9, 1, 1)
    d3(s, Prog1Command=0, Prog2Command=0)  # no command: hold, Status clean
    assert g3(s, "Status", "Command1Status") == (0, 1)
    d3(s, ProgOverrideReq=1, OverrideState=5)  # OverrideStateInv (bit 2) -> 5, no override
    assert g3(s, "Status", "Override", "Command1Status") == (5, 0, 1)
    d3(s, OverrideState=0)  # valid: override to stop
    assert g3(s, "Status", "Override", "Command0Status", "Out0") == (0, 1, 1, 0)
    d3(s, ProgHandReq=1, HandFB0=1, HandFB2=1)  # two hand feedbacks: bit 5 -> 33, hold
    assert g3(s, "Status", "HandCommandInv", "Hand", "Command0Status") == (33, 1, 1, 1)
    d3(s, HandFB0=0)  # hand switch at fast
    assert g3(s, "Status", "Command2Status", "Out1") == (0, 1, 1)
    d3(s, ProgHandReq=0, ProgOverrideReq=0, ProgOperReq=1)  # operator control
    d3(s, ProgOperReq=0, Oper0Req=1, Oper1Req=1)  # two operator requests: bit 4 -> 17
    assert g3(s, "Status", "OperReqInv", "ProgOper", "Command2Status") == (17, 1, 0, 1)
    d3(s, Oper1Req=1, State1Perm=0)  # slow not permitted: stays fast
    assert g3(s, "Command2Status", "Status") == (1, 0)
