"""EVENT: trigger one run of an event task (decision 0034).

FOR and BRK are lowered by the ladder compiler (ladder_compiler.ladder_for / brk, decision
0033). EVENT asks the task scheduler (runtime/tasks.py), which runs a higher-priority event
task at once and queues any other until the triggering task has finished. Naming a task
that is not an event task of the project does nothing (a lone routine file has no tasks);
the checker reports a name that is no task at all (E124).
"""

from __future__ import annotations

from ..vm.context import ExecContext
from .registry import implements


@implements("EVENT")
def event(ctx: ExecContext, rung: bool, task: str) -> None:
    if rung and ctx.tasks is not None:
        ctx.tasks.trigger(task, ctx)
