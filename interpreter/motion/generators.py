"""Profile-driven generators (move, jog, stop): each adds its position change per update."""

from __future__ import annotations

from dataclasses import dataclass

from interpreter.motion.clock import MasterClock
from interpreter.motion.enums import EventKind, GeneratorKind
from interpreter.motion.profiles import Limits, MoveProfile


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
    limits: Limits | None = None  # the dynamics it was planned with (MCD changes them)
    goal: float = 0.0  # moves: end point in profile coordinates (a dwelling move keeps it)
    direction: float = 1.0  # jogs: sign of the jog speed
    t_offset: float = 0.0  # master distance at which the current profile started (MCD)

    def step(self, cup: float, master_pos: float, master_vel: float) -> float:
        """Advance the own clock one update; returns the position change."""
        if self.clock is None:
            self.n += 1
            self.t = self.n * cup
        else:
            self.t = self.clock.advance(master_pos) - self.t_offset
        p, v, a = self.profile.at(self.t)
        self.v_native = v
        if self.clock is None:
            self.v, self.a = v, a
        else:  # chain rule with the master velocity; master acceleration is neglected
            self.v, self.a = v * master_vel, a * master_vel * master_vel
        dp = p - self.last_p
        self.last_p = p
        return dp

    def replan(self, profile: MoveProfile, limits: Limits) -> None:
        """Continue on a new profile planned from the present state (its clock starts at 0
        here); the contribution made so far is kept, the goal moves with the origin."""
        self.goal -= self.last_p
        if self.clock is None:
            self.n = 0
        else:
            self.t_offset += self.t
        self.t = 0.0
        self.profile = profile
        self.limits = limits
        self.last_p = 0.0

    @property
    def finished(self) -> bool:
        return self.t >= self.profile.duration

    def current_phase(self) -> EventKind:
        if self.v * self.a > 1e-12 or (abs(self.v) <= 1e-12 and abs(self.a) > 1e-12):
            return EventKind.ACCEL
        if self.v * self.a < -1e-12:
            return EventKind.DECEL
        return EventKind.CONSTANT
