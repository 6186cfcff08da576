"""Membership of a process set kept in struct-of-arrays form (time cams, position cams).

A set evaluates its running processes as numpy rows; between rebuilds the per-process state
lives in the arrays, so before the membership changes (or a caller reads the processes of
an axis) the state is copied back into the process objects. `STATE` names what is copied:
(object attribute, array attribute, conversion). A subclass rebuilds its arrays from `rows`
when `_dirty` is set and clears it.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, ClassVar, Generic, TypeVar

R = TypeVar("R")


class RowSet(Generic[R]):
    STATE: ClassVar[tuple[tuple[str, str, Callable[[Any], object]], ...]] = ()
    AXIS: ClassVar[str] = "axis"  # the row attribute naming the axis the process drives

    def __init__(self) -> None:
        self.rows: list[R] = []
        self._dirty = True

    def _sync_out(self) -> None:
        """Copy the array state back into the row objects before the rows change."""
        if self._dirty or not self.rows:
            return
        for name, array, conv in self.STATE:
            values = getattr(self, array)
            for k, row in enumerate(self.rows):
                setattr(row, name, conv(values[k]))

    def add(self, row: R) -> None:
        self._sync_out()
        self.rows.append(row)
        self._dirty = True

    def remove(self, gone: list[R]) -> None:
        self._sync_out()
        ids = {id(r) for r in gone}
        self.rows = [r for r in self.rows if id(r) not in ids]
        self._dirty = True

    def on_axis(self, axis: int) -> list[R]:
        self._sync_out()
        return [r for r in self.rows if getattr(r, self.AXIS) == axis]
