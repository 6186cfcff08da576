"""Drive instructions on the simulated axes (SPEC 9.32, docs/decisions/0077-drive-instructions.md):
MDO/MDF (direct drive on/off), MDS (drive start), MRAT/MAAT (axis tuning) and MRHD/MAHD
(hookup diagnostics).

They talk to a drive, so they are not U diagnostics: they run as on a controller whose
drive axes are the servo model of docs 0101 and whose virtual axes have no drive at all.
- A virtual axis is not an axis data type these instructions accept: error 38 at once.
- MDO enables the drive of an axis whose loop is open (Axis Ready) and holds its output at
  the requested level; nothing is wired to that output, so the axis does not move. As for
  MSO, the drive message takes one planner update: DriveEnableStatus and DN are set then
  (the reference sets DN when the drive enable is active). The drive stays enabled until
  MDF, MSO, MSF or a shutdown ends the direct drive state; MDF's drive-off and DN likewise
  come at the next update.
- MDS needs a drive that supports the ramp attributes of direct velocity control; the servo
  model is a position-loop drive without them, so MDS is refused with error 86.
- Tuning and hookup tests are services of a real drive with a motor; the simulated drive
  does not carry them out, so the request fails at the next update with error 12.
Operand checks (error 13, EXERR = faceplate index; the enumerated operands are immediates
the checker already holds to their values, E109) and the state checks (shutdown 7, loop
closed 4) come first, as for the other motion instructions.
"""

from __future__ import annotations

import math
import weakref
from dataclasses import dataclass, field
from functools import cache

from stdlib import catalog

from ..motion import MotionError
from ..runtime.motion import Axis, MotionRuntime
from ..runtime.motion_layout import set_bits, set_error
from ..vm.context import ExecContext
from .motion_common import begin, clear_on_prescan, configured, fail, runtime, whole
from .motion_state import set_tag_bits
from .registry import implements, prescan

# highest DriveOutput: the analog servo output spans +-10 V; in percent, +-100 % of it
_MAX_VOLTS = 10.0
_MAX_PERCENT = 100.0
# extended code of error 12 when the axis is shut down (the MAAT table: object mode conflict)
_OBJECT_MODE_CONFLICT = 12


@cache
def _error(name: str) -> int:
    """An error number by its name in stdlib/motion_errors.toml (stated once, there)."""
    for code, err in catalog().motion_errors.items():
        if err.name == name:
            return code
    raise KeyError(name)


@dataclass(slots=True)
class _Direct:
    """Per runtime: how many requests have ended direct drive on each axis (an MDO whose
    drive message is still under way when one of them executes does not enable the drive)."""

    ends: dict[int, int] = field(default_factory=dict)


_direct: weakref.WeakKeyDictionary[MotionRuntime, _Direct] = weakref.WeakKeyDictionary()


def _state(rt: MotionRuntime) -> _Direct:
    st = _direct.get(rt)
    if st is None:
        st = _direct[rt] = _Direct()
    return st


def end_direct_drive(rt: MotionRuntime, ax: Axis) -> None:
    """MDF, MSO, MSF and a shutdown end the direct drive state of MDO (the core clears it
    for MSO, MSF and shutdowns too); an MDO still waiting for its drive message then does
    not enable the drive any more."""
    st = _state(rt)
    ax.group.core.direct_drive[ax.index] = False
    st.ends[id(ax)] = st.ends.get(id(ax), 0) + 1


def _hold(ax: Axis) -> None:
    """The drive is enabled under direct control: the axis status shows it from now on."""
    ax.group.core.direct_drive[ax.index] = True
    set_tag_bits(ax, DriveEnableStatus=1)


def _enable_next_update(rt: MotionRuntime, ax: Axis, ctl: list) -> None:
    """MDO's drive message: the drive is enabled, and DN set, at the next planner update."""
    st = _state(rt)
    ends = st.ends.get(id(ax), 0)
    g = ax.group
    handle = rt.token(g)
    rt.own(ctl, g, handle)

    def enabled() -> None:
        if st.ends.get(id(ax), 0) == ends and not g.core.servo_on[ax.index]:
            _hold(ax)
        if rt.owns(ctl, g, handle):
            set_bits(ctl, DN=1)

    rt.after_update(g, enabled)


def _drive_axis(rt: MotionRuntime, ctl: list, axis: list) -> Axis | None:
    """The drive axis an instruction names: error 11 when unknown, 38 for a virtual axis."""
    ax = configured(rt, ctl, rt.axis(axis))
    if ax is not None and ax.group.core.virtual[ax.index]:
        fail(rt, ctl, _error("Illegal Axis Data Type"))
        return None
    return ax


def _ready(rt: MotionRuntime, ctl: list, ax: Axis) -> bool:
    """Shut down: error 7; loop closed (MSO): error 4 — these need the Axis Ready state."""
    core = ax.group.core
    if core.shutdown[ax.index]:
        fail(rt, ctl, MotionError.SHUTDOWN_STATE)
        return False
    if core.servo_on[ax.index]:
        fail(rt, ctl, MotionError.SERVO_ON_STATE)
        return False
    return True


def _done_next_update(rt: MotionRuntime, ax: Axis, ctl: list) -> None:
    g = ax.group
    handle = rt.token(g)
    rt.own(ctl, g, handle)

    def done() -> None:
        if rt.owns(ctl, g, handle):
            set_bits(ctl, DN=1)

    rt.after_update(g, done)


def _no_answer_next_update(rt: MotionRuntime, ax: Axis, ctl: list) -> None:
    """The drive does not carry out the service: Servo Message Failure at the next update."""
    g = ax.group
    handle = rt.token(g)
    rt.own(ctl, g, handle)
    code = _error("Servo Message Failure")

    def failed() -> None:
        if rt.owns(ctl, g, handle):
            rt.own(ctl)
            set_error(ctl, code)

    rt.after_update(g, failed)


@implements("MDO")
def mdo(ctx: ExecContext, rung: bool, axis: list, ctl: list, output: object, units: object) -> None:
    if not begin(ctl, rung):
        return
    rt = runtime(ctx)
    ax = _drive_axis(rt, ctl, axis)
    if ax is None:
        return
    u = whole(units)  # the checker keeps an immediate DriveUnits to 0 or 1 (E109)
    level = float(output)  # type: ignore[arg-type]
    if not (math.isfinite(level) and abs(level) <= (_MAX_PERCENT if u else _MAX_VOLTS)):
        fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, 2)
        return
    if not _ready(rt, ctl, ax):
        return
    _enable_next_update(rt, ax, ctl)


@implements("MDF")
def mdf(ctx: ExecContext, rung: bool, axis: list, ctl: list) -> None:
    if not begin(ctl, rung):
        return
    rt = runtime(ctx)
    ax = _drive_axis(rt, ctl, axis)
    if ax is None or not _ready(rt, ctl, ax):
        return
    end_direct_drive(rt, ax)
    _done_next_update(rt, ax, ctl)


@implements("MDS")
def mds(ctx: ExecContext, rung: bool, axis: list, ctl: list, speed: object, units: object) -> None:
    if not begin(ctl, rung):
        return
    rt = runtime(ctx)
    ax = _drive_axis(rt, ctl, axis)
    if ax is None:
        return
    if not math.isfinite(float(speed)):  # type: ignore[arg-type]
        fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, 2)
        return
    if ax.group.core.shutdown[ax.index]:
        fail(rt, ctl, MotionError.SHUTDOWN_STATE)
        return
    fail(rt, ctl, _error("Optional Attribute Not Supported"))


def _drive_service(ctx: ExecContext, rung: bool, axis: list, ctl: list, run: bool) -> None:
    """MRAT, MAAT, MRHD, MAHD: checks, then a request the simulated drive does not serve.

    `run`: the instruction moves the motor (MRAT, MRHD) and so needs the loop open.
    """
    if not begin(ctl, rung):
        return
    rt = runtime(ctx)
    ax = _drive_axis(rt, ctl, axis)
    if ax is None:
        return
    core = ax.group.core
    if core.shutdown[ax.index]:  # the axis object refuses: "object mode conflict" (EXERR 12)
        rt.own(ctl)
        set_error(ctl, _error("Servo Message Failure"), _OBJECT_MODE_CONFLICT)
        return
    if run and core.servo_on[ax.index]:
        fail(rt, ctl, MotionError.SERVO_ON_STATE)
        return
    _no_answer_next_update(rt, ax, ctl)


@implements("MRAT")
def mrat(ctx: ExecContext, rung: bool, axis: list, ctl: list) -> None:
    _drive_service(ctx, rung, axis, ctl, True)


@implements("MAAT")
def maat(ctx: ExecContext, rung: bool, axis: list, ctl: list) -> None:
    _drive_service(ctx, rung, axis, ctl, False)


@implements("MRHD")
def mrhd(ctx: ExecContext, rung: bool, axis: list, ctl: list, test: object) -> None:
    _drive_service(ctx, rung, axis, ctl, True)


@implements("MAHD")
def mahd(
    ctx: ExecContext, rung: bool, axis: list, ctl: list, test: object, observed: object
) -> None:
    _drive_service(ctx, rung, axis, ctl, False)


@prescan("MDO", "MDF", "MDS", "MRAT", "MAAT", "MRHD", "MAHD")
def _prescan(ctx: ExecContext, rung: bool, axis: list, ctl: list, *rest: object) -> None:
    clear_on_prescan(ctl)
