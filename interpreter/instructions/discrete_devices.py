"""D2SD and D3SD, the discrete two- and three-state device blocks of 1756-RM006; decision 0182.

One engine serves both: a device has N states (2 or 3); each execution resolves the
commanded state, drives the outputs for it and checks the feedbacks against it.

- Control: ProgOperReq or OperOperReq put the block in operator control and keep it there;
  otherwise ProgProgReq or OperProgReq put it in program control (as TOT, decision 0177).
  ProgHandReq gives Hand; otherwise ProgOverrideReq, FaultAlarm with OverrideOnFault, or
  the first execution after prescan with OverrideOnInit give Override. Hand wins over
  Override, and both over program/operator control.
- Commanded state: in Hand the state whose hand feedback is set (D2SD: HandFB set means
  state 1); in Override OverrideState (D3SD: 0..2, else OverrideStateInv and no override);
  in program control the program command (D2SD: ProgCommand false/true = state 0/1), in
  operator control the operator request. A program or operator change needs the target
  state's permissive (StateNPerm); hand and override ignore the permissives. Two or more
  commands at once (D3SD ProgCommandInv, OperReqInv, HandCommandInv) set their bit and
  hold the state; so does no command at all.
- Outputs: D2SD Out = CommandStatus, inverted by OutReverse; D3SD OutK = OutKStateN of the
  commanded state N. DeviceNState: every feedback FBj equals its FBjStateN.
- Fault: the fault timer starts when the commanded state changes (and at the first
  execution) and stops when the device reaches that state. FaultAlarm is set when the timer
  reaches FaultTime, or when the device leaves the commanded state with no timer running.
  It clears once the device is in the commanded state — unless FaultAlarmLatch, then only
  with FaultAlmUnlatch. FaultTime 0 turns fault checking off (and clears FaultAlarm);
  FaultTime < 0 sets FaultTimeInv and counts as 0.
- ModeAlarm: in operator control, set when the program changes its command to a state other
  than the commanded one; cleared when the program command equals the commanded state or
  the block is in program control, Override or Hand.
- After every execution the operator requests and FaultAlmUnlatch are cleared; with
  ProgValueReset the program requests too.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..runtime.motion_layout import packed_words, struct_type
from ..vm.context import ExecContext
from .process_blocks import pack_status
from .registry import implements, prescan


@dataclass(frozen=True, slots=True)
class Device:
    ix: dict[str, int]
    words: tuple
    states: int
    feedbacks: int
    oper_reqs: tuple[int, ...]
    perms: tuple[int, ...]
    device_states: tuple[int, ...]
    fb: tuple[int, ...]
    fb_state: tuple[tuple[int, ...], ...]  # fb_state[state][j] = FBjState<state>
    invs: tuple[int, ...]


def _device(type_name: str, states: int, feedbacks: int, invs: tuple[str, ...]) -> Device:
    ix = struct_type(type_name).index
    return Device(
        ix,
        packed_words(type_name),
        states,
        feedbacks,
        tuple(ix[f"OPER{n}REQ"] for n in range(states)),
        tuple(ix[f"STATE{n}PERM"] for n in range(states)),
        tuple(ix[f"DEVICE{n}STATE"] for n in range(states)),
        tuple(ix[f"FB{j}"] for j in range(feedbacks)),
        tuple(tuple(ix[f"FB{j}STATE{n}"] for j in range(feedbacks)) for n in range(states)),
        tuple(ix[b] for b in invs),
    )


D2 = _device("DISCRETE_2STATE", 2, 2, ("FAULTTIMEINV", "OPERREQINV"))
D3 = _device(
    "DISCRETE_3STATE",
    3,
    4,
    ("FAULTTIMEINV", "OVERRIDESTATEINV", "PROGCOMMANDINV", "OPERREQINV", "HANDCOMMANDINV"),
)
_PROG_REQS = ("PROGPROGREQ", "PROGOPERREQ", "PROGOVERRIDEREQ", "PROGHANDREQ")


def _choose(wanted: list[bool], allowed: list[bool]) -> tuple[int | None, bool]:
    """(the one wanted state if allowed, else None = hold; more than one wanted)."""
    on = [n for n, w in enumerate(wanted) if w]
    if len(on) != 1:
        return None, len(on) > 1
    return (on[0] if allowed[on[0]] else None), False


def _mask(bits: list[bool]) -> int:
    return sum(1 << n for n, b in enumerate(bits) if b)


def _run(
    ctx: ExecContext,
    s: list,
    d: Device,
    current: int | None,
    prog: list[bool],
    hand: list[bool],
    override_state: int | None,
) -> int | None:
    """Resolve control and the commanded state, check faults and ModeAlarm; returns the
    commanded state (None: none yet). Sets every flag the two blocks share."""
    ix = d.ix
    first = bool(s[ix["FIRSTRUN"]])
    s[ix["FIRSTRUN"]] = 0
    if s[ix["PROGOPERREQ"]] or s[ix["OPEROPERREQ"]]:
        s[ix["PROGOPER"]] = 0
    elif s[ix["PROGPROGREQ"]] or s[ix["OPERPROGREQ"]]:
        s[ix["PROGOPER"]] = 1
    fault_time = s[ix["FAULTTIME"]]
    s[ix["FAULTTIMEINV"]] = int(fault_time < 0)
    fault_time = max(fault_time, 0.0)

    s[ix["HAND"]] = hand_mode = int(bool(s[ix["PROGHANDREQ"]]))
    wants_override = bool(
        s[ix["PROGOVERRIDEREQ"]]
        or (s[ix["FAULTALARM"]] and s[ix["OVERRIDEONFAULT"]])
        or (first and s[ix["OVERRIDEONINIT"]])
    )
    s[ix["OVERRIDE"]] = int(not hand_mode and wants_override and override_state is not None)

    everyone = [True] * d.states
    perms = [bool(s[p]) for p in d.perms]
    prog_state, prog_inv = _choose(prog, perms)
    oper_state, oper_inv = _choose([bool(s[r]) for r in d.oper_reqs], perms)
    hand_state, hand_inv = _choose(hand, everyone)
    s[ix["OPERREQINV"]] = int(oper_inv)
    if "PROGCOMMANDINV" in ix:
        s[ix["PROGCOMMANDINV"]] = int(prog_inv)
        s[ix["HANDCOMMANDINV"]] = int(hand_inv)
    if hand_mode:
        chosen = hand_state
    elif s[ix["OVERRIDE"]]:
        chosen = override_state
    elif s[ix["PROGOPER"]]:
        chosen = prog_state
    else:
        chosen = oper_state
    state = current if chosen is None else chosen

    # feedback and fault timer
    feedback = [bool(s[f]) for f in d.fb]
    in_states = [
        all(feedback[j] == bool(s[d.fb_state[n][j]]) for j in range(d.feedbacks))
        for n in range(d.states)
    ]
    for n in range(d.states):
        s[d.device_states[n]] = int(in_states[n])
    fault = False
    reached = False
    if state is not None:
        if state != current or first:
            s[ix["FAULTTIMERSTART"]] = ctx.now_ms
        reached = in_states[state]
        start = s[ix["FAULTTIMERSTART"]]
        if reached:
            s[ix["FAULTTIMERSTART"]] = -1.0
        elif fault_time > 0:
            if start < 0:
                fault = True  # left the commanded state with no change commanded
            elif ctx.now_ms - start >= fault_time * 1000.0:
                fault = True  # the device did not get there within FaultTime
                s[ix["FAULTTIMERSTART"]] = -1.0
    if fault:
        s[ix["FAULTALARM"]] = 1
    elif reached or fault_time == 0:
        if not s[ix["FAULTALARMLATCH"]] or s[ix["FAULTALMUNLATCH"]] or fault_time == 0:
            s[ix["FAULTALARM"]] = 0

    # ModeAlarm: the program asks for something else while the operator is in control
    prog_mask = _mask(prog)
    prev = s[ix["PROGCOMMANDPREV"]]
    s[ix["PROGCOMMANDPREV"]] = prog_mask
    cmd_mask = 0 if state is None else 1 << state
    if s[ix["PROGOPER"]] or hand_mode or s[ix["OVERRIDE"]] or prog_mask == cmd_mask:
        s[ix["MODEALARM"]] = 0
    elif prev >= 0 and prog_mask != prev:
        s[ix["MODEALARM"]] = 1
    return state


def _finish(s: list, d: Device) -> None:
    ix = d.ix
    s[ix["INSTRUCTFAULT"]] = int(any(s[i] for i in d.invs))
    pack_status(s, d.words)
    for r in (*d.oper_reqs, ix["OPERPROGREQ"], ix["OPEROPERREQ"], ix["FAULTALMUNLATCH"]):
        s[r] = 0
    if s[ix["PROGVALUERESET"]]:
        for name in _PROG_REQS:
            s[ix[name]] = 0
    s[ix["ENABLEOUT"]] = 1


@implements("D2SD")
def d2sd(ctx: ExecContext, rung: bool, s: list) -> None:
    ix = D2.ix
    pc, hfb = bool(s[ix["PROGCOMMAND"]]), bool(s[ix["HANDFB"]])
    current = int(bool(s[ix["COMMANDSTATUS"]]))
    state = _run(
        ctx, s, D2, current, [not pc, pc], [not hfb, hfb], int(bool(s[ix["OVERRIDESTATE"]]))
    )
    s[ix["COMMANDSTATUS"]] = cs = int(state == 1)
    s[ix["OUT"]] = cs ^ int(bool(s[ix["OUTREVERSE"]]))
    _finish(s, D2)


_D3_CMD = tuple(D3.ix[f"COMMAND{n}STATUS"] for n in range(3))
_D3_OUT = tuple(D3.ix[f"OUT{k}"] for k in range(3))
_D3_TABLE = tuple(tuple(D3.ix[f"OUT{k}STATE{n}"] for k in range(3)) for n in range(3))


@implements("D3SD")
def d3sd(ctx: ExecContext, rung: bool, s: list) -> None:
    ix = D3.ix
    on = [n for n in range(3) if s[_D3_CMD[n]]]
    current = on[0] if len(on) == 1 else None
    ov = s[ix["OVERRIDESTATE"]]
    s[ix["OVERRIDESTATEINV"]] = int(not 0 <= ov <= 2)
    state = _run(
        ctx,
        s,
        D3,
        current,
        [bool(s[ix[f"PROG{n}COMMAND"]]) for n in range(3)],
        [bool(s[ix[f"HANDFB{n}"]]) for n in range(3)],
        None if s[ix["OVERRIDESTATEINV"]] else ov,
    )
    if state is not None:
        for n in range(3):
            s[_D3_CMD[n]] = int(n == state)
        for k in range(3):
            s[_D3_OUT[k]] = int(bool(s[_D3_TABLE[state][k]]))
    _finish(s, D3)


def _restart(s: list, d: Device) -> None:
    # Instruction first scan: the next execution is a first one (fault timer started,
    # OverrideOnInit applied, no ModeAlarm from a command seen before the restart).
    s[d.ix["FIRSTRUN"]] = 1
    s[d.ix["FAULTTIMERSTART"]] = -1.0
    s[d.ix["PROGCOMMANDPREV"]] = -1


@prescan("D2SD")
def d2sd_prescan(ctx: ExecContext, rung: bool, s: list) -> None:
    _restart(s, D2)


@prescan("D3SD")
def d3sd_prescan(ctx: ExecContext, rung: bool, s: list) -> None:
    _restart(s, D3)
