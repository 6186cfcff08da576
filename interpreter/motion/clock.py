"""Master distance for master-driven motion (MDAC), with the MATC/MAM lock directions."""

from __future__ import annotations

import math
from dataclasses import dataclass

from interpreter.motion.enums import LockDirection, MasterReference
from interpreter.motion.rotary import travel


@dataclass(slots=True)
class MasterClock:
    """Turns master positions, one per update, into the slave's clock (master distance).

    Forward/reverse-only locks ratchet: the clock is the furthest distance reached in the
    locked direction, so the slave stops while the master backs up and resumes when the
    master passes that point again (TimeCamLockStatus follows `following`).
    """

    master: int
    reference: MasterReference
    lock_direction: LockDirection = LockDirection.NONE
    lock_position: float = 0.0
    start: float | None = None  # master position the distance counts from (None: not locked)
    prev: float | None = None
    peak: float = 0.0
    following: bool = False
    value: float = 0.0
    unwind: float = 0.0  # the master's unwind (0: linear); prev and start are then unwrapped

    def advance(self, pos: float) -> float:
        """Feed the master position of this update; returns the master distance."""
        ld = self.lock_direction
        prev = self.prev
        u = self.unwind
        if u > 0.0 and prev is not None:  # a rotary master: count travel through the wrap
            pos = prev + travel(pos, prev, u)
        self.prev = pos
        if self.start is None:
            if ld in (LockDirection.POSITION_FORWARD, LockDirection.POSITION_REVERSE):
                lp = self.lock_position
                forward = ld == LockDirection.POSITION_FORWARD
                if u > 0.0:  # a rotary master passes the lock position once per revolution
                    turns = math.floor if forward else math.ceil
                    lp += u * turns((pos - lp) / u)
                crossed = prev is not None and (
                    (forward and prev < lp <= pos) or (not forward and prev > lp >= pos)
                )
                if not crossed:
                    return 0.0
                self.start = lp  # count from the lock point itself, not the sampled position
            else:
                self.start = pos
        backward = ld in (LockDirection.IMMEDIATE_REVERSE_ONLY, LockDirection.POSITION_REVERSE)
        rel = self.start - pos if backward else pos - self.start
        if ld == LockDirection.NONE:
            self.following = True
            self.value = rel
        else:
            self.following = rel >= self.peak
            self.peak = max(self.peak, rel)
            self.value = self.peak
        return self.value

    def shift(self, axis: int, delta: float) -> None:
        """Axis `axis` was redefined by delta (MRP, MAH): if it is the master, the distance
        keeps counting travel, so the slave does not see the jump."""
        if self.master == axis:
            self.start = None if self.start is None else self.start + delta
            self.prev = None if self.prev is None else self.prev + delta

    @property
    def locked(self) -> bool:
        return self.start is not None and self.following
