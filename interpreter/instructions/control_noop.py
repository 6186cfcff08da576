"""UID, UIE and IOT: instructions that have nothing to act on in logixst.

- UID/UIE bracket a section that higher-priority tasks must not interrupt. logixst's
  scheduler (runtime/tasks.py) runs each task to its end before starting another, so no
  task is ever interrupted and the bracket changes nothing.
- IOT asks for a module's outputs to be sent at once. With no module connected (SPEC 9.32)
  the request goes nowhere; the output tag itself is untouched by IOT on a controller too.
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
