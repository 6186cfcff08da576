"""Which programs run in a scan: the continuous task, periodic tasks and event tasks (SPEC 9.16).

Interleaving (docs/decisions/0043-task-scheduling.md): a scan starts at t = k x scan
period. First every periodic task whose next due time is <= t runs, highest priority
(lowest number) first, once per due time it has reached (a task faster than the scan period
catches up), with the virtual clock reading its due time; then the continuous task runs its
programs in scheduled order at time t. Due times are 0, Rate, 2 Rate, ... Inhibited tasks,
disabled programs and programs no task schedules do not run.

Event tasks run only when an EVENT instruction triggers them (decision 0034): an event task
of higher priority than the task executing the EVENT runs at once, inside the instruction;
any other waits until the triggering task has finished its programs. A trigger while the
event task is waiting or running is an overlap: it is counted and dropped. The clock does
not move while an event task runs.

Before the tasks, the controller's background work runs (ctx.background: message transfers
that progress without the program executing their instruction, decision 0035).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from ..semantics.program import ProgramModel

Main = Callable[[list, Any], None]
EPS = 1e-9
CONTINUOUS_PRIORITY = 16  # below every numbered priority (1 highest .. 15 lowest)


@dataclass(slots=True)
class Periodic:
    name: str
    rate_ms: float
    priority: int
    mains: list[Main]
    next_due: float = 0.0


@dataclass(slots=True)
class EventTask:
    name: str
    priority: int
    mains: list[Main]
    waiting: bool = False
    running: bool = False
    runs: int = 0
    overlaps: int = 0


@dataclass(slots=True)
class Schedule:
    continuous: list[Main] = field(default_factory=list)
    periodic: list[Periodic] = field(default_factory=list)
    events: dict[str, EventTask] = field(default_factory=dict)
    queue: list[EventTask] = field(default_factory=list)  # triggered, waiting for their turn
    priority: int = CONTINUOUS_PRIORITY  # of the task running now
    T: list = field(default_factory=list)  # tag storage, set by run()

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
            elif task.type == "EVENT":
                sched.events[task.name.upper()] = EventTask(task.name, task.priority, runnable)
        sched.periodic.sort(key=lambda p: (p.priority, p.name.upper()))
        return sched

    def run(self, T: list, ctx: Any) -> None:
        self.T = T
        ctx.tasks = self
        for work in list(ctx.background.values()):  # communication finishing on its own
            work(ctx)
        now = ctx.now_ms
        for task in self.periodic:
            while task.next_due <= now + EPS:
                ctx.now_ms = task.next_due
                self._run_task(task.priority, task.mains, ctx, task.rate_ms)
                task.next_due += task.rate_ms
        ctx.now_ms = now
        self._run_task(CONTINUOUS_PRIORITY, self.continuous, ctx)

    def _run_task(
        self, priority: int, mains: list[Main], ctx: Any, period_ms: float | None = None
    ) -> None:
        """Run one task's programs (period_ms: a periodic task's rate), then the event tasks
        it left waiting."""
        saved, self.priority = self.priority, priority
        saved_period, ctx.task_period_ms = ctx.task_period_ms, period_ms
        try:
            for fn in mains:
                fn(self.T, ctx)
        finally:
            self.priority = saved
            ctx.task_period_ms = saved_period
        while self.queue:
            self.queue.sort(key=lambda e: e.priority)
            self._run_event(self.queue.pop(0), ctx)

    def _run_event(self, task: EventTask, ctx: Any) -> None:
        task.waiting = False
        task.running = True
        task.runs += 1
        try:
            self._run_task(task.priority, task.mains, ctx)
        finally:
            task.running = False

    def trigger(self, name: str, ctx: Any) -> bool:
        """EVENT(name): False when `name` is not an event task of this project."""
        task = self.events.get(name.upper())
        if task is None:
            return False
        if task.waiting or task.running:
            task.overlaps += 1
            return True
        if task.priority < self.priority:
            self._run_event(task, ctx)  # preempts the running task
        else:
            task.waiting = True
            self.queue.append(task)
        return True
