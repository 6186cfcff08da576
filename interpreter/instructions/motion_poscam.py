"""MAPC: a Logix position cam on the position cam core (interpreter/motion/poscam.py).

Like MATC (SPEC 9.22): DN and IP are set in the executing scan, PositionCamStatus shows on
the slave at once (PositionCamPendingStatus for a Pending cam) and the profile's Status
counts the cam as a user while it runs (SPEC 9.23). A Once cam sets PC when the master
leaves the profile's range; MAS (All, Position Cam) and MGS end it without PC.
Decision 0128.
"""

from __future__ import annotations

from ..motion import MotionError
from ..motion.poscam import PositionCamSchedule
from ..runtime.motion import Tracked
from ..runtime.motion_layout import set_bits
from ..vm.context import ExecContext
from ..vm.refs import ArrayRef
from .motion_common import (
    begin,
    clear_on_prescan,
    fail,
    failed,
    real,
    runtime,
    set_axis_status,
    whole,
)
from .registry import implements, prescan

# faceplate indices (EXERR): Slave 0, Master 1, MotionControl 2, Direction 3, CamProfile 4
_MAPC_MASTER, _MAPC_PROFILE = 1, 4


@implements("MAPC")
def mapc(
    ctx: ExecContext, rung: bool, slave: list, master: list, ctl: list, direction: int,
    cam_profile: ArrayRef, slave_scaling: float, master_scaling: float, execution_mode: int,
    execution_schedule: int, master_lock_position: float, cam_lock_position: float,
    master_reference: int, master_direction: int,
) -> None:  # fmt: skip
    if not begin(ctl, rung):
        return
    rt = runtime(ctx)
    sa, ma = rt.axis(slave), rt.axis(master)
    if sa is None or ma is None:
        fail(rt, ctl, MotionError.AXIS_NOT_CONFIGURED)
        return
    if sa.group is not ma.group:  # the master must be in the slave's planner
        fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, _MAPC_MASTER)
        return
    if cam_profile.start != 0:  # only element [0] carries the profile's Status
        fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, _MAPC_PROFILE)
        return
    elements = cam_profile.elements
    schedule = whole(execution_schedule)
    r = sa.group.core.start_mapc(
        sa.index, ma.index, rt.load_profile(elements), whole(direction), real(slave_scaling),
        real(master_scaling), whole(execution_mode), schedule, real(master_lock_position),
        real(cam_lock_position), whole(master_reference), whole(master_direction),
    )  # fmt: skip
    if failed(rt, ctl, r):
        return
    tr = Tracked(ctl, (sa,), pc=True, profile=elements[0])
    rt.track(sa.group, r.handle, tr)
    if schedule == PositionCamSchedule.PENDING:
        set_axis_status(sa, PositionCamPendingStatus=1)
    else:  # in use from its execution on, locked or not
        rt.count(tr, +1)
        set_axis_status(sa, PositionCamStatus=1)
    set_bits(ctl, DN=1, IP=1)


@prescan("MAPC")
def _prescan_mapc(
    ctx: ExecContext, rung: bool, slave: list, master: list, ctl: list, *rest: object
) -> None:
    clear_on_prescan(ctl)
