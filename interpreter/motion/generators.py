"""Profile-driven generators (move, jog, stop): each adds its position change per update."""

from __future__ import annotations

from dataclasses import dataclass

from interpreter.motion.clock import MasterClock
from interpreter.motion.enums import EventKind, GeneratorKind
from interpreter.motion.profiles import MoveProfile


@dataclass(slots=True)
class ProfileGen:
    """A planned profile run on one axis by time (clock None) or by master distance."""

    handle: int
    kind: GeneratorKind
    axis: int
    profile: MoveProfile
    clock: MasterClock | None = None
    link: int = 0  # MDAC handle driving this generator (0: time driven)
    owner: int = 0  # MGS handle for stops started by a group stop
    t: float = -1.0  # own clock; < 0 until the first update
    n: int = 0  # updates since the start (time-driven clock = n * cup, without drift)
    last_p: float = 0.0
    v_native: float = 0.0  # velocity in profile units (per s, or per master unit)
    v: float = 0.0  # velocity in units/s
    a: float = 0.0
    phase: EventKind | None = None

    def step(self, cup: float, master_pos: float, master_vel: float) -> float:
        """Advance the own clock one update; returns the position change."""
        if self.clock is None:
            self.n += 1
            self.t = self.n * cup
        else:
            self.t = self.clock.advance(master_pos)
        p, v, a = self.profile.at(self.t)
        self.v_native = v
        if self.clock is None:
            self.v, self.a = v, a
        else:  # chain rule with the master velocity; master acceleration is neglected
            self.v, self.a = v * master_vel, a * master_vel * master_vel
        dp = p - self.last_p
        self.last_p = p
        return dp

    @property
    def finished(self) -> bool:
        return self.t >= self.profile.duration

    def current_phase(self) -> EventKind:
        if self.v * self.a > 1e-12 or (abs(self.v) <= 1e-12 and abs(self.a) > 1e-12):
            return EventKind.ACCEL
        if self.v * self.a < -1e-12:
            return EventKind.DECEL
        return EventKind.CONSTANT
