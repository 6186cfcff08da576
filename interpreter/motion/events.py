"""Watch-position events (MAW/MDW): one armed watch per axis, checked at every coarse update.

A watch fires when the axis's actual position passes the watch position in the armed
direction between two updates: forward when last < W <= now, reverse when last > W >= now
(`last` is the position at arming, then at the previous update). An axis standing beyond
the position when armed does not fire until it comes back and crosses it
(docs/decisions/0065-motion-shutdown-watch-strobe.md).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from interpreter.motion.enums import EventKind


@dataclass(slots=True)
class Watch:
    handle: int
    axis: int
    position: float
    forward: bool
    last: float  # actual position at arming, then at the latest update


@dataclass(slots=True)
class WatchSet:
    armed: dict[int, Watch] = field(default_factory=dict)  # by axis

    def arm(self, watch: Watch) -> Watch | None:
        """Arm a watch; returns the watch it replaces on the same axis, if any."""
        old = self.armed.get(watch.axis)
        self.armed[watch.axis] = watch
        return old

    def disarm(self, axis: int) -> Watch | None:
        return self.armed.pop(axis, None)

    def check(self, actual: np.ndarray, ev: list[tuple[int, EventKind, int]]) -> None:
        """Fire (COMPLETE) and disarm every watch whose position was passed this update."""
        for axis, w in list(self.armed.items()):
            now = float(actual[axis])
            hit = w.last < w.position <= now if w.forward else w.last > w.position >= now
            w.last = now
            if hit:
                del self.armed[axis]
                ev.append((w.handle, EventKind.COMPLETE, axis))
