"""Cams: MCCP (calculate a cam profile), MATC (time cam), MDAC (master-driven link) and
MCSV (evaluate a profile at one master value).

MCCP completes in the executing scan (SPEC 9.21). MATC sets DN and IP in the executing
scan and shows TimeCamStatus (Immediate) or TimeCamPendingStatus (Pending) on the axis at
once (SPEC 9.22); Status of the profile's element [0] counts the cams using it (SPEC 9.23).
MDAC stores a pending master for the slave's next master-driven motion (SPEC 9.24); its
IP stays set until the link is broken, AC while a master-driven motion of the link runs.
"""

from __future__ import annotations

import math

from ..motion import MotionError, MotionParameterError, calculate_cam_profile
from ..runtime.motion import Tracked
from ..runtime.motion_layout import CAM_MASTER, CAM_SEGMENT, CAM_SLAVE, CP_STATUS, set_bits
from ..vm.context import ExecContext
from ..vm.refs import ArrayRef, Ref
from .motion_common import (
    begin,
    clear_on_prescan,
    fail,
    failed,
    real,
    runtime,
    set_axis_status,
    start_on_axis,
    whole,
)
from .registry import implements, prescan

# faceplate indices (EXERR): MCCP MotionControl 0, Cam 1, Length 2, StartSlope 3, EndSlope 4,
# CamProfile 5; MATC CamProfile 3; MDAC MasterAxis 1
_MCCP_START, _MCCP_END, _MCCP_PROFILE, _MATC_PROFILE, _MDAC_MASTER = 3, 4, 5, 3, 1


@implements("MCCP")
def mccp(
    ctx: ExecContext, rung: bool, ctl: list, cam: ArrayRef, length: int, start_slope: float,
    end_slope: float, cam_profile: ArrayRef,
) -> None:  # fmt: skip
    if not begin(ctl, rung):
        return
    rt = runtime(ctx)
    count = whole(length)
    if count is None or not 2 <= count <= len(cam):
        fail(rt, ctl, MotionError.ILLEGAL_CAM_LENGTH)
        return
    if cam_profile.start != 0:
        fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, _MCCP_PROFILE)
        return
    elements = cam_profile.elements
    if len(elements) < count:
        fail(rt, ctl, MotionError.ILLEGAL_CAM_PROFILE_LENGTH)
        return
    if elements[0][CP_STATUS] > 2:  # a running cam still uses this profile
        fail(rt, ctl, MotionError.CAM_PROFILE_BEING_USED)
        return
    ss, es = real(start_slope), real(end_slope)
    for value, index in ((ss, _MCCP_START), (es, _MCCP_END)):
        if not math.isfinite(value):
            fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, index)
            return
    points = [cam.get(k) for k in range(count)]
    try:
        profile = calculate_cam_profile(
            [p[CAM_MASTER] for p in points],  # type: ignore[index]
            [p[CAM_SLAVE] for p in points],  # type: ignore[index]
            [p[CAM_SEGMENT] for p in points],  # type: ignore[index]
            ss,
            es,
        )
    except MotionParameterError as exc:
        fail(rt, ctl, exc.error, exc.exerr)
        return
    rt.store_profile(elements, profile)
    set_bits(ctl, DN=1)


@implements("MATC")
def matc(
    ctx: ExecContext, rung: bool, axis: list, ctl: list, direction: int, cam_profile: ArrayRef,
    distance_scaling: float, time_scaling: float, execution_mode: int, execution_schedule: int,
    lock_position: float, lock_direction: int, instruction_mode: int,
) -> None:  # fmt: skip
    started = start_on_axis(ctx, rung, axis, ctl)
    if started is None:
        return
    rt, ax = started
    if cam_profile.start != 0:  # only element [0] carries the profile's Status
        fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, _MATC_PROFILE)
        return
    elements = cam_profile.elements
    schedule = whole(execution_schedule)
    r = ax.group.core.start_time_cam(
        ax.index, rt.load_profile(elements), whole(direction), real(distance_scaling),
        real(time_scaling), whole(execution_mode), schedule, real(lock_position),
        whole(lock_direction), whole(instruction_mode),
    )  # fmt: skip
    if failed(rt, ctl, r):
        return
    tr = Tracked(ctl, (ax,), pc=True, profile=elements[0])
    rt.track(ax.group, r.handle, tr)
    if schedule == 1:
        set_axis_status(ax, TimeCamPendingStatus=1)
    else:  # an immediate cam is in use from its execution on
        rt.count(tr, +1)
        set_axis_status(ax, TimeCamStatus=1)
    set_bits(ctl, DN=1, IP=1)


@implements("MDAC")
def mdac(
    ctx: ExecContext, rung: bool, slave: list, master: list, ctl: list, motion_type: int,
    master_reference: int,
) -> None:  # fmt: skip
    if not begin(ctl, rung):
        return
    rt = runtime(ctx)
    sa, ma = rt.axis(slave), rt.axis(master)
    if sa is None or ma is None:
        fail(rt, ctl, MotionError.AXIS_NOT_CONFIGURED)
        return
    if sa.group is not ma.group:  # a link needs both axes in one planner
        fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, _MDAC_MASTER)
        return
    r = sa.group.core.assign_master(sa.index, ma.index, whole(motion_type), whole(master_reference))
    if failed(rt, ctl, r):
        return
    rt.track(sa.group, r.handle, Tracked(ctl, (sa,), link=True))
    set_axis_status(sa, CoordinatedMotionStatus=1)
    set_bits(ctl, DN=1, IP=1)


@prescan("MCCP")
def _prescan_mccp(ctx: ExecContext, rung: bool, ctl: list, *rest: object) -> None:
    clear_on_prescan(ctl)


@prescan("MATC")
def _prescan_matc(ctx: ExecContext, rung: bool, axis: list, ctl: list, *rest: object) -> None:
    clear_on_prescan(ctl)


@prescan("MDAC")
def _prescan_mdac(
    ctx: ExecContext, rung: bool, slave: list, master: list, ctl: list, *rest: object
) -> None:
    clear_on_prescan(ctl)


# ------------------------------------------------------------------ MCSV
# faceplate indices (EXERR): MotionControl 0, CamProfile 1, MasterValue 2
_MCSV_PROFILE, _MCSV_MASTER = 1, 2


@implements("MCSV")
def mcsv(
    ctx: ExecContext, rung: bool, ctl: list, cam_profile: ArrayRef, master: object,
    slave: Ref, slope: Ref, slope2: Ref,
) -> None:  # fmt: skip
    """Evaluate a calculated profile at MasterValue: slave value and first and second
    derivatives (the segment polynomial and its derivatives). Completes at once; a profile
    not calculated is error 32, a master value outside the profile's range error 13
    (docs/decisions/0065-motion-shutdown-watch-strobe.md)."""
    if not begin(ctl, rung):
        return
    rt = runtime(ctx)
    if cam_profile.start != 0:
        fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, _MCSV_PROFILE)
        return
    profile = rt.load_profile(cam_profile.elements)
    if profile is None:
        fail(rt, ctl, MotionError.CAM_PROFILE_NOT_CALCULATED)
        return
    x = real(master)
    if not (math.isfinite(x) and profile.start <= x <= profile.end):
        fail(rt, ctl, MotionError.PARAMETER_OUT_OF_RANGE, _MCSV_MASTER)
        return
    p, v, a = profile.evaluate(x)
    slave.set(float(p))
    slope.set(float(v))
    slope2.set(float(a))
    set_bits(ctl, DN=1)


@prescan("MCSV")
def _prescan_mcsv(ctx: ExecContext, rung: bool, ctl: list, *rest: object) -> None:
    clear_on_prescan(ctl)
