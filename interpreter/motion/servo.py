"""Servo model of AXIS_CIP_DRIVE axes: actual follows command through a first-order lag.

actual[k] = actual[k-1] + alpha * (command[k] - actual[k-1]),  alpha = 1 - exp(-cup / tau)
(the exact discretisation of tau * x' + x = command with command held over the update).
tau = 0 gives actual = command. With the servo off the drive holds its actual position
and the command position tracks it, as on a controller.
"""

from __future__ import annotations

import numpy as np

DEFAULT_TAU = 0.004  # seconds; a stiff but visibly lagging loop


def lag_alpha(tau: np.ndarray, cup: float) -> np.ndarray:
    """Per-axis blend factor for one coarse update."""
    tau = np.asarray(tau, dtype=float)
    with np.errstate(divide="ignore"):
        return np.where(tau > 0.0, -np.expm1(-cup / np.where(tau > 0, tau, 1.0)), 1.0)


def servo_step(
    command: np.ndarray,
    actual: np.ndarray,
    alpha: np.ndarray,
    servo_on: np.ndarray,
    idx: np.ndarray | slice,
) -> None:
    """Advance the actual positions of axes idx in place (command too, for servo-off axes)."""
    cmd = command[idx]
    act = actual[idx]
    on = servo_on[idx]
    stepped = act + alpha[idx] * (cmd - act)
    if on.all():  # every loop closed (always so for virtual axes): the command stays
        actual[idx] = stepped
        return
    new_act = np.where(on, stepped, act)
    actual[idx] = new_act
    command[idx] = np.where(on, cmd, new_act)
