"""Which programs run in a scan: the continuous task and periodic tasks (SPEC 9.16).

Interleaving (docs/decisions/0043-task-scheduling.md): a scan starts at t = k x scan
period. First every periodic task whose next due time is <= t runs, highest priority
(lowest number) first, once per due time it has reached (a task faster than the scan period
catches up), with the virtual clock reading its due time; then the continuous task runs its
programs in scheduled order at time t. Due times are 0, Rate, 2 Rate, ... Event tasks,
inhibited tasks, disabled programs and programs no task schedules do not run.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from ..semantics.program import ProgramModel

Main = Callable[[list, Any], None]
EPS = 1e-9


@dataclass(slots=True)
class Periodic:
    name: str
    rate_ms: float
    priority: int
    mains: list[Main]
    next_due: float = 0.0


@dataclass(slots=True)
class Schedule:
    continuous: list[Main] = field(default_factory=list)
    periodic: list[Periodic] = field(default_factory=list)

    @classmethod
    def single(cls, main: Main) -> Schedule:
        """A `.st`/`.rll` program: its main routine is the continuous task."""
        return cls([main])

    @classmethod
    def for_project(cls, model: ProgramModel, mains: dict[str, Main]) -> Schedule:
        sched = cls()
        for task in model.tasks:
            if task.inhibited:
                continue
            runnable = []
            for pname in task.programs:
                info = model.programs.get(pname.upper())
                fn = mains.get(pname.upper())
                if info is not None and not info.disabled and fn is not None:
                    runnable.append(fn)
            if task.type == "CONTINUOUS":
                sched.continuous.extend(runnable)
            elif task.type == "PERIODIC":
                sched.periodic.append(Periodic(task.name, task.rate_ms, task.priority, runnable))
        sched.periodic.sort(key=lambda p: (p.priority, p.name.upper()))
        return sched

    def run(self, T: list, ctx: Any) -> None:
        now = ctx.now_ms
        for task in self.periodic:
            while task.next_due <= now + EPS:
                ctx.now_ms = task.next_due
                for fn in task.mains:
                    fn(T, ctx)
                task.next_due += task.rate_ms
        ctx.now_ms = now
        for fn in self.continuous:
            fn(T, ctx)
