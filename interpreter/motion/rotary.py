"""Rotary axes: positions that wrap at the axis's unwind (decision 0115).

A rotary axis keeps its command and actual positions in [0, unwind); a linear axis has
unwind 0. MotionGroup.unwind holds the unwind per axis and the group wraps both position
arrays at the end of every update, before the sets' end_update, so a process set sees the
final positions already wrapped. Whoever derives motion from two positions of the same
axis (a master's travel, a following error, a velocity, a crossing) takes their
difference with `travel`: the short way round on a rotary axis, so the wrap is no jump.
That holds while an axis moves less than half an unwind per coarse update and lags its
command by less than half an unwind, which any real machine does.
"""

from __future__ import annotations

import math

import numpy as np


def wrap_array(pos: np.ndarray, unwind: np.ndarray, rotary: np.ndarray) -> None:
    """Bring the positions of the rotary axes (a bool mask, or an index array) into
    [0, unwind) in place."""
    u = unwind[rotary]
    p = pos[rotary] % u
    pos[rotary] = np.where(p >= u, 0.0, p)  # -1e-20 % 360 rounds to 360.0


def wrap(x: float, unwind: float) -> float:
    """One position into [0, unwind) (unchanged on a linear axis: unwind 0)."""
    if unwind > 0.0:
        x = math.fmod(x, unwind)
        if x < 0.0:
            x += unwind
        if x >= unwind:
            x = 0.0
    return x


def travel(new: float, old: float, unwind: float) -> float:
    """Signed distance from old to new: the short way round on a rotary axis, in
    [-unwind/2, unwind/2)."""
    d = new - old
    if unwind > 0.0:
        d -= unwind * math.floor(d / unwind + 0.5)
    return d


def travel_array(new: np.ndarray, old: np.ndarray, unwind: np.ndarray) -> np.ndarray:
    """`travel` for arrays (unwind 0 leaves the plain difference)."""
    d = new - old
    rot = unwind > 0.0
    if not rot.any():
        return d
    u = np.where(rot, unwind, 1.0)
    return np.where(rot, d - u * np.floor(d / u + 0.5), d)


def rotary_travel(move_type: int, target: float, current: float, unwind: float) -> float:
    """Travel of a rotary move type (MAM 2, 3, 4) from `current` to `target`, both in
    [0, unwind): Shortest Path goes the short way (half a turn: forward), Positive only
    forward, Negative only in reverse; each less than one revolution, 0 when there."""
    ahead = math.fmod(target - current, unwind)
    if ahead < 0.0:
        ahead += unwind
    if move_type == 2:
        return ahead - unwind if ahead > unwind / 2 else ahead
    if move_type == 3:
        return ahead
    return ahead - unwind if ahead > 0.0 else 0.0
