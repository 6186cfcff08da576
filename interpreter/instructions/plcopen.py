"""PLCopen camming blocks: MC_CamTableSelect and MC_CamIn (CODESYS semantics, SPEC 5, 9.29,
9.30), on the position cam core (interpreter/motion/poscam.py). Decisions 0126-0128.

The blocks are called IEC style with named parameters (`camIn(Master := M, ...)`). The
compiler stores the elementary inputs into the instance and passes the axis and CAM-array
inputs after it as (member index, value) pairs. Like a PLCopen function block, a block acts
only when it is called: a rising Execute starts it, and its outputs are refreshed at every
call from the state of its coupling. Outputs that report an end (Done, Error,
CommandAborted) stay set while Execute is TRUE; with Execute FALSE they are shown for one
call. EndOfProfile is TRUE in the call after a profile end was passed (one scan when the
block is called every scan).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from ..motion.cam import CamProfile, calculate_cam_profile
from ..motion.errors import MotionParameterError
from ..motion.poscam import (
    CamInError,
    CamLaw,
    CamStartMode,
    Coupling,
    CouplingState,
    switch_table,
    validate_law,
)
from ..runtime.motion import Axis, MotionRuntime
from ..runtime.motion_layout import CAM_MASTER, CAM_SEGMENT, CAM_SLAVE, struct_type
from ..semantics.types import Elementary
from ..vm.context import ExecContext
from ..vm.refs import ArrayRef
from .motion_common import runtime
from .registry import implements

_SEL = struct_type("MC_CAMTABLESELECT").index
_CIN = struct_type("MC_CAMIN").index
_SEL_EXECUTE = _SEL["EXECUTE"]
_CIN_EXECUTE, _CIN_TABLE = _CIN["EXECUTE"], _CIN["CAMTABLEID"]
# the MC_CamIn outputs in member order (the catalog declares them together): one slice store
_CIN_OUT = ("INSYNC", "BUSY", "COMMANDABORTED", "ERROR", "ERRORID", "ENDOFPROFILE")
_OUT = slice(_CIN["INSYNC"], _CIN["ENDOFPROFILE"] + 1)
assert [_CIN[m] for m in _CIN_OUT] == list(range(_OUT.start, _OUT.stop)), "MC_CamIn output order"
_IDLE = (0, 0, 0, 0, 0, 0)
# the compiler passes one (member index, value) pair per axis or array input given
# (st_compiler.fb_call); the block functions take as many pairs as parameters
_SEL_PAIRS = sum(not isinstance(t, Elementary) for _, t in struct_type("MC_CAMTABLESELECT").members)
_CIN_PAIRS = sum(not isinstance(t, Elementary) for _, t in struct_type("MC_CAMIN").members)
assert (_SEL_PAIRS, _CIN_PAIRS) == (3, 2), "MC_CamTableSelect/MC_CamIn reference inputs"


@dataclass(frozen=True, slots=True)
class _Selection:
    """What MC_CamTableSelect handed out under one CamTableID."""

    profile: CamProfile
    periodic: bool
    master_absolute: bool
    slave_absolute: bool
    master: Axis
    slave: Axis


@dataclass(slots=True)
class _CamInState:
    execute: bool = False  # Execute at the previous call (edge detection)
    coupling: Coupling | None = None
    table: int = 0  # CamTableID the coupling runs
    error: CamInError = CamInError.NONE  # an error found at execution (no coupling)
    ends_seen: int = 0
    shown: bool = False  # a terminal state was shown in a call with Execute FALSE
    written: tuple[int, ...] = _IDLE  # the outputs last stored (stored again only on change)
    # Steady: the last call had Execute TRUE, the coupling in `seen_state` with `seen_error`,
    # no EndOfProfile shown. While Execute stays TRUE, the table input stays and the
    # coupling reports the same, a call changes nothing and returns after these comparisons.
    steady: bool = False
    seen_state: int = -1
    seen_error: int = 0


@dataclass(slots=True)
class _Blocks:
    """PLCopen state of one program run: selections and the state of each instance."""

    tables: dict[int, _Selection] = field(default_factory=dict)
    next_id: int = 1
    selects: dict[int, bool] = field(default_factory=dict)  # instance -> previous Execute
    camins: dict[int, _CamInState] = field(default_factory=dict)


# (runtime, its blocks): every call of a scan asks for the same, so the block functions
# compare ctx.motion with _last[0] in line before calling _blocks
_last: list = [None, None]


def _blocks(rt: MotionRuntime) -> _Blocks:
    if _last[0] is rt:
        return _last[1]  # type: ignore[no-any-return]
    b = rt.extensions.get("plcopen")
    if b is None:
        b = rt.extensions["plcopen"] = _Blocks()
    assert isinstance(b, _Blocks)
    _last[0], _last[1] = rt, b
    return b


def _refs(pairs: tuple[object, ...]) -> dict[int, object]:
    """The (member index, value) pairs of a call as a dict; a pair not passed is (None,
    None). The blocks take the pairs as parameters with defaults rather than *pairs: a
    call of a function with *args costs about twice a plain call, and the scan calls
    every block every time."""
    return {
        int(pairs[i]): pairs[i + 1]  # type: ignore[call-overload]
        for i in range(0, len(pairs), 2)
        if pairs[i] is not None
    }


def _axes(
    rt: MotionRuntime, refs: dict[int, object], ix: dict[str, int]
) -> tuple[Axis, Axis] | CamInError:
    m, s = refs.get(ix["MASTER"]), refs.get(ix["SLAVE"])
    ma = rt.axis(m) if isinstance(m, list) else None
    sa = rt.axis(s) if isinstance(s, list) else None
    if ma is None or sa is None or ma.group is not sa.group:
        return CamInError.INVALID_AXIS
    if ma is sa:
        return CamInError.SAME_AXIS
    return ma, sa


def _table_profile(table: object) -> CamProfile | CamInError:
    """The cam of a whole CAM array (every element a point), as MCCP with slopes 0."""
    if not isinstance(table, ArrayRef):
        return CamInError.INVALID_CAM_TABLE
    points = [table.get(k) for k in range(len(table))]
    try:
        return calculate_cam_profile(
            [p[CAM_MASTER] for p in points],  # type: ignore[index]
            [p[CAM_SLAVE] for p in points],  # type: ignore[index]
            [p[CAM_SEGMENT] for p in points],  # type: ignore[index]
        )
    except MotionParameterError:
        return CamInError.INVALID_CAM_TABLE


@implements("MC_CamTableSelect")
def mc_cam_table_select(
    ctx: ExecContext,
    rung: bool,
    inst: list,
    k0: object = None,
    v0: object = None,
    k1: object = None,
    v1: object = None,
    k2: object = None,
    v2: object = None,
) -> None:
    """Master, Slave and CamTable come as up to three (member index, value) pairs."""
    b = _last[1] if _last[0] is ctx.motion else _blocks(runtime(ctx))  # see _blocks
    key = id(inst)
    if inst[_SEL_EXECUTE] and b.selects.get(key, False):
        return  # outputs stay as they are while Execute stays TRUE
    rt = runtime(ctx)
    ix = _SEL
    execute = bool(inst[_SEL_EXECUTE])
    b.selects[key] = execute
    if not execute:  # the result was shown while Execute was TRUE (it completes at once)
        for name in ("DONE", "BUSY", "ERROR"):
            inst[ix[name]] = 0
        inst[ix["ERRORID"]] = 0
        return
    refs = _refs((k0, v0, k1, v1, k2, v2))
    axes = _axes(rt, refs, ix)
    profile = _table_profile(refs.get(ix["CAMTABLE"])) if not isinstance(axes, CamInError) else axes
    if isinstance(axes, CamInError) or isinstance(profile, CamInError):
        err = axes if isinstance(axes, CamInError) else profile
        assert isinstance(err, CamInError)
        inst[ix["DONE"]], inst[ix["BUSY"]], inst[ix["ERROR"]] = 0, 0, 1
        inst[ix["ERRORID"]] = int(err)
        return
    tid = b.next_id
    b.next_id += 1
    b.tables[tid] = _Selection(
        profile,
        bool(inst[ix["PERIODIC"]]),
        bool(inst[ix["MASTERABSOLUTE"]]),
        bool(inst[ix["SLAVEABSOLUTE"]]),
        axes[0],
        axes[1],
    )
    inst[ix["CAMTABLEID"]] = tid
    inst[ix["DONE"]], inst[ix["BUSY"]], inst[ix["ERROR"]], inst[ix["ERRORID"]] = 1, 0, 0, 0


def _law(sel: _Selection, inst: list) -> CamLaw:
    ix = _CIN
    mode = int(inst[ix["STARTMODE"]])
    return CamLaw(
        sel.profile,
        periodic=sel.periodic,
        master_absolute=sel.master_absolute,
        slave_absolute=sel.slave_absolute,
        master_scaling=float(inst[ix["MASTERSCALING"]]),
        master_offset=float(inst[ix["MASTEROFFSET"]]),
        slave_scaling=float(inst[ix["SLAVESCALING"]]),
        slave_offset=float(inst[ix["SLAVEOFFSET"]]),
        start_mode=CamStartMode(mode) if 0 <= mode <= 4 else CamStartMode.ABSOLUTE,
        velocity_diff=float(inst[ix["VELOCITYDIFF"]]),
        acceleration=float(inst[ix["ACCELERATION"]]),
        deceleration=float(inst[ix["DECELERATION"]]),
    )


def _start(rt: MotionRuntime, b: _Blocks, st: _CamInState, inst: list, refs: dict) -> None:
    ix = _CIN
    st.coupling, st.error, st.shown = None, CamInError.NONE, False
    axes = _axes(rt, refs, ix)
    if isinstance(axes, CamInError):
        st.error = axes
        return
    tid = int(inst[ix["CAMTABLEID"]])
    sel = b.tables.get(tid)
    if sel is None or sel.master is not axes[0] or sel.slave is not axes[1]:
        st.error = CamInError.INVALID_CAM_TABLE_ID
        return
    if not 0 <= int(inst[ix["STARTMODE"]]) <= 4:
        st.error = CamInError.INVALID_PARAMETER
        return
    master, slave = axes
    st.table = tid
    st.coupling = slave.group.core.start_position_cam(slave.index, master.index, _law(sel, inst))
    st.ends_seen = 0


@implements("MC_CamIn")
def mc_cam_in(
    ctx: ExecContext,
    rung: bool,
    inst: list,
    k0: object = None,
    v0: object = None,
    k1: object = None,
    v1: object = None,
) -> None:
    """Master and Slave come as up to two (member index, value) pairs."""
    b = _last[1] if _last[0] is ctx.motion else _blocks(runtime(ctx))  # see _blocks
    st = b.camins.get(id(inst))
    if st is not None and st.steady and inst[_CIN_EXECUTE] and inst[_CIN_TABLE] == st.table:
        c = st.coupling
        if (
            c is not None
            and c.state == st.seen_state
            and c.error == st.seen_error
            and c.ends == st.ends_seen
        ):
            return  # no edge, same table, nothing new to report: the outputs stand
    rt = runtime(ctx)
    if st is None:
        st = b.camins[id(inst)] = _CamInState()
    execute = bool(inst[_CIN_EXECUTE])
    rising = execute and not st.execute
    st.execute = execute
    if rising:
        _start(rt, b, st, inst, _refs((k0, v0, k1, v1)))
    c = st.coupling
    if c is not None and not rising and inst[_CIN_TABLE] != st.table and c.busy:
        tid = int(inst[_CIN_TABLE])
        sel = b.tables.get(tid)
        if tid != st.table and sel is not None and sel.slave.index == c.slave:
            # another table selected while coupled: it takes over at the next profile end
            law = _law(sel, inst)
            if validate_law(law) == CamInError.NONE:
                assert c is not None
                switch_table(sel.slave.group.core.position_cams, c, law)
                st.table = tid
    _outputs(st, inst, execute)


def _outputs(st: _CamInState, inst: list, execute: bool) -> None:
    c = st.coupling
    if c is not None:
        state, error, ends = c.state, c.error, c.ends
    else:  # not started (all FALSE) or refused at execution
        error = st.error
        state = CouplingState.ERROR if error != CamInError.NONE else CouplingState.ENDED
        ends = st.ends_seen
    eop = int(ends > st.ends_seen)
    st.ends_seen = ends
    if state >= CouplingState.ENDED and state != CouplingState.ARMED and not execute:
        if st.shown:  # a terminal state shown once with Execute FALSE: back to idle
            state, error = CouplingState.ENDED, CamInError.NONE
            st.coupling, st.error = None, CamInError.NONE
        st.shown = True
    out = (
        int(state == CouplingState.IN_SYNC),
        int(state <= CouplingState.IN_SYNC),  # starting, ramping or in sync: busy
        int(state == CouplingState.ABORTED),
        int(state == CouplingState.ERROR),
        int(error) if state == CouplingState.ERROR else 0,
        eop,
    )
    if out != st.written:
        inst[_OUT] = out
        st.written = out
    # the next call may take the fast path when it would compute these same outputs
    st.steady = execute and st.coupling is not None and not eop
    st.seen_state, st.seen_error = state, error
