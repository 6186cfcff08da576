"""What an instruction implementation may touch while it runs."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

DEFAULT_WATCHDOG = 5_000_000  # statements or ladder instructions per scan (SPEC 9.4)


class MajorFault(Exception):
    """A major fault stops the scan; `site` locates it in the source (set by the VM)."""

    def __init__(self, type_: int, code: int, message: str, site: int = -1) -> None:
        super().__init__(message)
        self.type = type_
        self.code = code
        self.message = message
        self.site = site


@dataclass(slots=True)
class MinorFault:
    type: int
    code: int
    message: str
    site: int
    count: int = 1


@dataclass(slots=True)
class ExecContext:
    """Per-controller execution state shared by the VM and instruction implementations."""

    now_ms: float = 0.0  # virtual time at the start of the current scan
    scan_period_ms: float = 1.0
    # period of the periodic task running now; None in the continuous task and event tasks
    # (the time-based process blocks take their DeltaT from it, block_timing.py)
    task_period_ms: float | None = None
    first_scan: bool = False
    steps: int = 0  # statements executed in this scan (watchdog)
    budget: int = 5_000_000
    site: int = -1  # call site of the instruction being executed
    minor_faults: dict[tuple[int, int, int], MinorFault] = field(default_factory=dict)
    motion: Any = None  # the motion runtime (interpreter.runtime.motion), when present
    program: Any = None  # the loaded program (tags, types, routines)
    tasks: Any = None  # the task scheduler (runtime/tasks.py), for EVENT to trigger a task
    # Work the controller does on its own between scans, by name (MSG transfers in progress):
    # each is called with the context at the start of every scan.
    background: dict[str, Any] = field(default_factory=dict)
    status: dict[str, int] = field(default_factory=dict)  # S:N S:Z S:V S:C ...
    rv: list[Any] | None = None  # values the last RET handed back to its JSR (None: no RET)
    system: dict[str, Any] = field(default_factory=dict)  # attributes set by SSV (clock offset ...)
    # An operation inside the ladder CPT/FAL expression being evaluated overflowed; the
    # flag-setting store (STOREF) turns it into S:V and clears it (decision 0025).
    overflow: bool = False

    def minor(self, type_: int, code: int, message: str, site: int | None = None) -> None:
        where = self.site if site is None else site
        key = (type_, code, where)
        f = self.minor_faults.get(key)
        if f is None:
            self.minor_faults[key] = MinorFault(type_, code, message, where)
        else:
            f.count += 1

    def major(self, type_: int, code: int, message: str) -> MajorFault:
        return MajorFault(type_, code, message, self.site)
