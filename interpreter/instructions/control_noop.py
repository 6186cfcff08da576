"""UID, UIE, IOT and LV: instructions that have nothing to act on in logixst.

- UID/UIE bracket a section that higher-priority tasks must not interrupt. logixst's
  scheduler (runtime/tasks.py) runs each task to its end before starting another, so no
  task is ever interrupted and the bracket changes nothing.
- IOT asks for a module's outputs to be sent at once. With no module connected (SPEC 9.32)
  the request goes nowhere; the output tag itself is untouched by IOT on a controller too.
- LV asks whether the controller holds an execution license (source protection). The
  simulated controller holds none, so LV is always false, as on a controller without it.
"""

from __future__ import annotations

from ..vm.context import ExecContext
from .registry import implements


@implements("UID", "UIE")
def interrupt_bracket(ctx: ExecContext, rung: bool) -> None:
    return None


@implements("IOT")
def iot(ctx: ExecContext, rung: bool, target: object) -> None:
    return None


@implements("LV")
def lv(ctx: ExecContext, rung: bool, vendor: int, product: int) -> bool:
    """No license is installed in the simulated controller: the rung goes false."""
    return False
