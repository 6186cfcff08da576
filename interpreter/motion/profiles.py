"""Move, jog and stop profiles: closed-form planning into piecewise constant-jerk segments.

A profile is a table of segments (start time, position, velocity, acceleration, jerk); the
last segment runs forever (velocity 0 for moves and stops, the jog speed for jogs).
"Time" is seconds for time-driven motion and master distance for master-driven motion.
"""

from __future__ import annotations

import math
from bisect import bisect_right
from dataclasses import dataclass, field

import numpy as np

from interpreter.motion.enums import ProfileShape

_EPS = 1e-12


@dataclass(frozen=True, slots=True)
class Limits:
    """Dynamics of one move: speed, accel, decel, and jerks (inf for trapezoidal)."""

    speed: float
    accel: float
    decel: float
    accel_jerk: float = math.inf
    decel_jerk: float = math.inf

    @staticmethod
    def of(
        speed: float,
        accel: float,
        decel: float,
        shape: ProfileShape = ProfileShape.TRAPEZOIDAL,
        accel_jerk: float = math.inf,
        decel_jerk: float = math.inf,
    ) -> Limits:
        if shape == ProfileShape.TRAPEZOIDAL:
            return Limits(speed, accel, decel)
        return Limits(speed, accel, decel, accel_jerk, decel_jerk)


@dataclass(frozen=True, slots=True)
class MoveProfile:
    """Piecewise constant-jerk motion; evaluate() is vectorised, at() is the scalar fast path."""

    t0: np.ndarray
    p0: np.ndarray
    v0: np.ndarray
    a0: np.ndarray
    j: np.ndarray
    duration: float  # time of the last segment's start (the end of a move, inf never)
    _rows: list[tuple[float, float, float, float, float]] = field(repr=False, compare=False)
    _starts: list[float] = field(repr=False, compare=False)

    @property
    def end_position(self) -> float:
        return float(self.p0[-1])

    @property
    def end_velocity(self) -> float:
        return float(self.v0[-1])

    def evaluate(self, t: np.ndarray | float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Position, velocity, acceleration at times t (clamped at 0 below)."""
        tt = np.maximum(np.asarray(t, dtype=float), 0.0)
        i = np.searchsorted(self.t0, tt, side="right") - 1
        i = np.clip(i, 0, len(self.t0) - 1)
        d = tt - self.t0[i]
        j, a, v = self.j[i], self.a0[i], self.v0[i]
        pos = self.p0[i] + d * (v + d * (a / 2.0 + d * j / 6.0))
        vel = v + d * (a + d * j / 2.0)
        acc = a + d * j
        return pos, vel, acc

    def at(self, t: float) -> tuple[float, float, float]:
        """Scalar evaluation (no numpy overhead) used by the per-update generators."""
        t = max(t, 0.0)
        i = max(bisect_right(self._starts, t) - 1, 0)
        t0, p, v, a, j = self._rows[i]
        d = t - t0
        return (
            p + d * (v + d * (a / 2.0 + d * j / 6.0)),
            v + d * (a + d * j / 2.0),
            a + d * j,
        )

    def phase_durations(self) -> list[float]:
        """Durations of the finite segments (for tests and plots)."""
        return [float(x) for x in np.diff(self.t0)]


class _Builder:
    """Integrates phases (duration, start acceleration, jerk) exactly into a segment table."""

    def __init__(self, p: float = 0.0, v: float = 0.0) -> None:
        self.t, self.p, self.v, self.a = 0.0, p, v, 0.0
        self.rows: list[tuple[float, float, float, float, float]] = []

    def phase(self, duration: float, a: float, j: float = 0.0) -> None:
        if duration <= _EPS:
            return
        self.rows.append((self.t, self.p, self.v, a, j))
        d = duration
        self.p += d * (self.v + d * (a / 2.0 + d * j / 6.0))
        self.v += d * (a + d * j / 2.0)
        self.a = a + d * j
        self.t += d

    def velocity_change(self, v_to: float, lim: Limits) -> None:
        """Jerk-limited (or trapezoidal) change of velocity from rest acceleration to v_to."""
        v_from = self.v
        if v_from * v_to < 0.0:  # through zero: decelerate to rest, then accelerate
            self.velocity_change(0.0, lim)
            self.v = 0.0
            self.velocity_change(v_to, lim)
            self.v = v_to
            return
        speeding_up = abs(v_to) > abs(v_from)
        amax, jmax = (lim.accel, lim.accel_jerk) if speeding_up else (lim.decel, lim.decel_jerk)
        dv = v_to - v_from
        s = 1.0 if dv > 0 else -1.0
        for dur, a, j in _change_phases(abs(dv), amax, jmax):
            self.phase(dur, s * a, s * j)
        self.v = v_to  # remove rounding drift; the phases reach v_to exactly in theory
        self.a = 0.0

    def finish(self, final_p: float | None, final_v: float, forever: bool = False) -> MoveProfile:
        p = self.p if final_p is None else final_p
        self.rows.append((self.t, p, final_v, 0.0, 0.0))
        arr = np.array(self.rows, dtype=float)
        dur = self.t if final_v == 0.0 and not forever else math.inf
        return MoveProfile(
            t0=arr[:, 0],
            p0=arr[:, 1],
            v0=arr[:, 2],
            a0=arr[:, 3],
            j=arr[:, 4],
            duration=dur,
            _rows=list(self.rows),
            _starts=[r[0] for r in self.rows],
        )


def _change_phases(dv: float, amax: float, jmax: float) -> list[tuple[float, float, float]]:
    """Phases (duration, start accel, jerk) raising velocity by dv >= 0 from a = 0 to a = 0."""
    if dv <= 0.0:
        return []
    if math.isinf(jmax):
        return [(dv / amax, amax, 0.0)]
    if dv >= amax * amax / jmax:  # reaches full acceleration: jerk up, constant, jerk down
        tj = amax / jmax
        return [(tj, 0.0, jmax), (dv / amax - tj, amax, 0.0), (tj, amax, -jmax)]
    ap = math.sqrt(dv * jmax)  # peak acceleration when amax is not reached
    tj = ap / jmax
    return [(tj, 0.0, jmax), (tj, ap, -jmax)]


def change_time(dv: float, amax: float, jmax: float) -> float:
    """Duration of a velocity change of |dv| (T = dv/A + A/J, or 2*sqrt(dv/J) if A unreached)."""
    return sum(p[0] for p in _change_phases(abs(dv), amax, jmax))


def change_distance(v_from: float, v_to: float, lim: Limits) -> float:
    """Distance covered by a velocity change; symmetric ramps give mean velocity x time."""
    if v_from * v_to < 0.0:
        return change_distance(v_from, 0.0, lim) + change_distance(0.0, v_to, lim)
    up = abs(v_to) > abs(v_from)
    amax, jmax = (lim.accel, lim.accel_jerk) if up else (lim.decel, lim.decel_jerk)
    return 0.5 * (v_from + v_to) * change_time(v_to - v_from, amax, jmax)


def rest_to_rest_peak(distance: float, lim: Limits) -> float:
    """Peak speed of a rest-to-rest move over distance > 0 (closed forms, see the ADR)."""
    v, a, d, ja, jd = lim.speed, lim.accel, lim.decel, lim.accel_jerk, lim.decel_jerk
    if change_distance(0.0, v, lim) + change_distance(v, 0.0, lim) <= distance:
        return v
    if math.isinf(ja) and math.isinf(jd):
        # triangle: vp^2/2a + vp^2/2d = D
        return math.sqrt(2.0 * distance * a * d / (a + d))
    # S-curve: D(vp) = vp/2 (Ta + Td) with T = vp/A + A/J (A reached) or 2 sqrt(vp/J).
    # Each of the four cases is a polynomial in u = sqrt(vp); D is monotone, so exactly one
    # case has a root consistent with its own saturation assumption.
    cands: list[float] = []
    for sat_a in (True, False):
        for sat_d in (True, False):
            # coefficients of u^4, u^3, u^2, u^1, u^0
            c = [0.0, 0.0, 0.0, 0.0, -distance]
            for sat, amax, jmax in ((sat_a, a, ja), (sat_d, d, jd)):
                if math.isinf(jmax) or sat:
                    c[0] += 0.5 / amax
                    c[2] += 0.0 if math.isinf(jmax) else 0.5 * amax / jmax
                else:
                    c[1] += 1.0 / math.sqrt(jmax)
            for r in np.roots(c):
                if abs(r.imag) > 1e-9 * max(1.0, abs(r.real)) or r.real <= 0:
                    continue
                vp = float(r.real) ** 2
                if _consistent(vp, a, ja, sat_a) and _consistent(vp, d, jd, sat_d):
                    cands.append(vp)
    if not cands:  # numerically degenerate: fall back to bisection on the monotone D(vp)
        return _bisect_peak(0.0, 0.0, v, distance, lim)
    return min(cands, key=lambda vp: abs(_dist_via(0.0, vp, lim) - distance))


def _consistent(vp: float, amax: float, jmax: float, saturated: bool) -> bool:
    """Does peak speed vp agree with the assumption that the ramp reaches amax?"""
    if math.isinf(jmax):
        return True
    knee = amax * amax / jmax  # smallest velocity change that reaches full acceleration
    return vp >= knee * (1 - 1e-9) if saturated else vp <= knee * (1 + 1e-9)


def _dist_via(v0: float, vp: float, lim: Limits) -> float:
    return change_distance(v0, vp, lim) + change_distance(vp, 0.0, lim)


def _bisect_peak(v0: float, lo: float, hi: float, distance: float, lim: Limits) -> float:
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if _dist_via(v0, mid, lim) > distance:
            hi = mid
        else:
            lo = mid
        if hi - lo <= 1e-15 * max(1.0, hi):
            break
    return 0.5 * (lo + hi)


def plan_move(distance: float, lim: Limits, v0: float = 0.0, a0: float = 0.0) -> MoveProfile:
    """Move by `distance` starting at velocity v0 (merge), ending at rest at exactly `distance`.

    A move with speed 0 dwells: it comes to rest and stays in process without reaching its
    target (Logix pauses such a move rather than completing it).
    a0: the acceleration at the start (a dynamics change in the middle of an S-curve ramp);
    with a finite jerk it is first brought to 0 at that jerk (accel jerk while speeding
    up, decel jerk while slowing down), so the acceleration stays continuous; the rest is
    planned from there. Trapezoidal limits ignore it (their acceleration steps anyway).
    """
    b = _Builder()
    b.v = v0
    if a0 != 0.0:
        speeding_up = a0 * (v0 if v0 != 0.0 else a0) > 0.0
        jerk = lim.accel_jerk if speeding_up else lim.decel_jerk
        if math.isfinite(jerk) and jerk > 0.0:
            b.phase(abs(a0) / jerk, a0, -math.copysign(jerk, a0))
            b.a = 0.0  # the phase ends at 0 in theory; drop the rounding
    if lim.speed <= 0.0 and abs(distance - b.p) > _EPS:
        b.velocity_change(0.0, lim)
        return b.finish(None, 0.0, forever=True)
    _plan_into(b, distance - b.p, lim)  # the rest, from acceleration 0
    return b.finish(distance, 0.0)


def _plan_into(b: _Builder, distance: float, lim: Limits) -> None:
    start_p = b.p
    if abs(distance) <= _EPS and abs(b.v) <= _EPS:
        return
    s = 1.0 if distance > 0 or (distance == 0 and b.v > 0) else -1.0
    w0 = b.v * s  # initial speed along the move direction
    if w0 < 0.0:  # moving away: stop first, then a rest-to-rest move covers the rest
        b.velocity_change(0.0, lim)
        _plan_into(b, distance - (b.p - start_p), lim)
        return
    d = abs(distance)
    d_stop = change_distance(w0, 0.0, lim)
    if d_stop > d + 1e-12:  # cannot stop in time: stop (overshoot), then come back
        b.velocity_change(0.0, lim)
        _plan_into(b, distance - (b.p - start_p), lim)
        return
    v = lim.speed
    if w0 == 0.0:
        vp = rest_to_rest_peak(d, lim)
    elif _dist_via(w0, v, lim) <= d:
        vp = v
    elif w0 <= v:
        vp = _bisect_peak(w0, w0, v, d, lim)
    else:
        # faster than the speed limit and too short to slow to it first: keep the current
        # speed and stop at the target (a documented simplification of merges)
        vp = w0
    b.velocity_change(s * vp, lim)
    cruise = d - (change_distance(w0, vp, lim) + change_distance(vp, 0.0, lim))
    if vp > 0 and cruise > 0:
        b.phase(cruise / vp, 0.0)
    b.velocity_change(0.0, lim)


def plan_jog(speed: float, lim: Limits, v0: float = 0.0) -> MoveProfile:
    """Ramp from v0 to the signed jog speed, then run forever."""
    b = _Builder()
    b.v = v0
    b.velocity_change(speed, lim)
    return b.finish(None, speed)


def plan_stop(v0: float, lim: Limits) -> MoveProfile:
    """Decelerate from v0 to rest with lim.decel / lim.decel_jerk."""
    b = _Builder()
    b.v = v0
    b.velocity_change(0.0, lim)
    return b.finish(None, 0.0)
