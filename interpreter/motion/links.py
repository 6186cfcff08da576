"""MDAC master assignments of a group: which master drives a slave's master-driven motion.

A link is pending from the MDAC until the slave's next master-driven start of that motion
type (or All) promotes it to active; MAS All, MGS, MASD and a replacing MDAC break it
(decision 0100). As a process set it moves nothing; it owns CoordinatedMotionStatus.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from interpreter.motion.enums import EventKind, MasterReference, MotionType, StopType
from interpreter.motion.errors import MotionError, StartResult, bad_operand
from interpreter.motion.process import (
    EndReason,
    Events,
    MotionlessSet,
)

if TYPE_CHECKING:  # the group calls assign_master; only the annotation needs the class
    from interpreter.motion.group import MotionGroup


@dataclass(slots=True)
class MasterLink:
    """An MDAC assignment of a master to a slave for one motion type."""

    handle: int
    slave: int
    master: int
    motion_type: MotionType
    reference: MasterReference


class LinkTable(MotionlessSet):
    def __init__(self) -> None:
        self.pending: dict[tuple[int, MotionType], MasterLink] = {}
        self.active: dict[tuple[int, MotionType], MasterLink] = {}
        self.version = 0  # bumped on every change of the tables (status cache key)
        self._status_cache: tuple[int, int, dict[str, np.ndarray]] | None = None

    def find(self, slave: int, mt: MotionType) -> MasterLink | None:
        for table in (self.pending, self.active):
            for key in ((slave, mt), (slave, MotionType.ALL)):
                if key in table:
                    return table[key]
        return None

    def take(self, slave: int, mt: MotionType, ev: Events) -> MasterLink | None:
        """Promote a pending master (if any) at a slave motion start and return the link."""
        for key in ((slave, mt), (slave, MotionType.ALL)):
            link = self.pending.pop(key, None)
            if link is not None:
                old = self.active.get(key)
                if old is not None and old is not link:
                    ev.append((old.handle, EventKind.ENDED, slave))
                self.active[key] = link
                self.version += 1
                return link
        return self.find(slave, mt)

    def break_where(self, pred: Callable[[MasterLink], bool], ev: Events) -> None:
        for table in (self.pending, self.active):
            for key in [k for k, lk in table.items() if pred(lk)]:
                ev.append((table[key].handle, EventKind.ENDED, table[key].slave))
                del table[key]
                self.version += 1

    def end_axis(self, axis: int, reason: EndReason, events: Events) -> tuple[float, bool]:
        """MAS All breaks the slave's links (MGS too, through its stops). Shutdown breaks
        the links of both ends itself (break_where)."""
        if reason != StopType.ALL:
            return 0.0, False
        before = len(self.pending) + len(self.active)
        self.break_where(lambda lk: lk.slave == axis, events)
        return 0.0, len(self.pending) + len(self.active) != before

    # -- as a process set of the group -------------------------------------------------
    def status(self, n: int) -> dict[str, np.ndarray]:
        cache = self._status_cache
        if cache is not None and cache[0] == n and cache[1] == self.version:
            return cache[2]
        cm = np.zeros(n, dtype=bool)
        cm[[lk.slave for lk in self.active.values()]] = True
        cm[[lk.slave for lk in self.pending.values()]] = True
        out = {"CoordinatedMotionStatus": cm}
        self._status_cache = (n, self.version, out)
        return out


def assign_master(
    group: MotionGroup,
    links: LinkTable,
    slave: int,
    master: int,
    motion_type: int = MotionType.ALL,
    reference: int = MasterReference.COMMAND,
) -> StartResult:
    """MDAC: a pending master for the slave's next master-driven motion of that type."""
    if slave == master:
        return bad_operand(1)
    if motion_type not in MotionType.__members__.values():
        return bad_operand(3)
    if reference not in MasterReference.__members__.values():
        return bad_operand(4)
    mt = MotionType(motion_type)
    existing = [
        lk for t in (links.pending, links.active) for lk in t.values()
        if lk.slave == slave
    ]  # fmt: skip
    # All and a specific motion type cannot be assigned to one slave at the same time
    if any((lk.motion_type == MotionType.ALL) != (mt == MotionType.ALL) for lk in existing):
        return StartResult(error=MotionError.MDSC_ALL_CONFLICT)
    eff = group.effective_reference(master, MasterReference(reference))
    if group.axis_busy(slave) and any(
        group.effective_reference(lk.master, lk.reference) != eff for lk in existing
    ):  # the master reference of a moving slave cannot change
        return StartResult(error=MotionError.MDSC_INVALID_MODE_OR_MASTER_CHANGE)
    h = group.new_handle()
    key = (slave, mt)
    old = links.pending.get(key)
    link = MasterLink(h, slave, master, MotionType(motion_type), MasterReference(reference))
    links.pending[key] = link
    links.version += 1
    if old is not None:  # a later MDAC overrides a pending one
        group.after_update(lambda ev: ev.append((old.handle, EventKind.ENDED, slave)))
    return StartResult(handle=h)
