"""Cam profiles (MCCP): linear segments and clamped cubic splines, evaluated vectorised."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from interpreter.motion.enums import ExecutionMode
from interpreter.motion.errors import MotionError, MotionParameterError

LINEAR = 0
CUBIC = 1

# MCCP faceplate operand indices for EXERR: MotionControl 0, Cam 1, Length 2,
# StartSlope 3, EndSlope 4, CamProfile 5.
_OP_CAM, _OP_LENGTH = 1, 2


@dataclass(frozen=True, slots=True)
class CamProfile:
    """Calculated cam: knots x and per-segment cubic coefficients in u = x - x[i]."""

    x: np.ndarray  # master values, strictly increasing, n >= 2
    coef: np.ndarray  # shape (n-1, 4): c0 + c1 u + c2 u^2 + c3 u^3
    segment_type: np.ndarray  # per segment, 0 linear / 1 cubic

    @property
    def start(self) -> float:
        return float(self.x[0])

    @property
    def end(self) -> float:
        return float(self.x[-1])

    @property
    def span(self) -> float:
        return float(self.x[-1] - self.x[0])

    @property
    def p_start(self) -> float:
        return float(self.coef[0, 0])

    @property
    def p_end(self) -> float:
        h = float(self.x[-1] - self.x[-2])
        c = self.coef[-1]
        return float(c[0] + h * (c[1] + h * (c[2] + h * c[3])))

    @property
    def net(self) -> float:
        """Slave change over one pass, P(end) - P(start)."""
        return self.p_end - self.p_start

    def evaluate(self, x: np.ndarray | float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Slave position, slope and curvature at master values x (held outside the range)."""
        xx = np.clip(np.asarray(x, dtype=float), self.x[0], self.x[-1])
        i = np.clip(np.searchsorted(self.x, xx, side="right") - 1, 0, len(self.x) - 2)
        u = xx - self.x[i]
        c = self.coef[i]
        c0, c1, c2, c3 = c[..., 0], c[..., 1], c[..., 2], c[..., 3]
        pos = c0 + u * (c1 + u * (c2 + u * c3))
        vel = c1 + u * (2.0 * c2 + 3.0 * u * c3)
        acc = 2.0 * c2 + 6.0 * u * c3
        return pos, vel, acc


def calculate_cam_profile(
    master: np.ndarray | list[float],
    slave: np.ndarray | list[float],
    segment_type: np.ndarray | list[int],
    start_slope: float = 0.0,
    end_slope: float = 0.0,
) -> CamProfile:
    """MCCP: segment_type[i] shapes the segment from point i to i+1 (the last entry is unused).

    Errors follow the Logix table: 26 fewer than 2 points, 29 master values not strictly
    increasing, 28 a segment type other than 0/1, 13 a non-finite slave value.
    """
    xm = np.asarray(master, dtype=float)
    ys = np.asarray(slave, dtype=float)
    st = np.asarray(segment_type, dtype=int)
    n = len(xm)
    if n < 2 or len(ys) != n or len(st) < n - 1:
        raise MotionParameterError(
            MotionError.ILLEGAL_CAM_LENGTH, _OP_LENGTH, "a cam needs at least 2 points"
        )
    if not np.all(np.isfinite(ys)):
        raise MotionParameterError(
            MotionError.PARAMETER_OUT_OF_RANGE, _OP_CAM, "cam slave values must be finite"
        )
    if not np.all(np.isfinite(xm)) or np.any(np.diff(xm) <= 0):
        raise MotionParameterError(
            MotionError.ILLEGAL_CAM_ORDER, _OP_CAM, "cam master values must increase"
        )
    seg = st[: n - 1]
    if np.any((seg != LINEAR) & (seg != CUBIC)):
        raise MotionParameterError(
            MotionError.ILLEGAL_CAM_TYPE, _OP_CAM, "segment type must be 0 or 1"
        )
    h = np.diff(xm)
    delta = np.diff(ys) / h  # chord slope of each segment
    m = np.empty(n)  # knot slopes: one per point
    m[:-1] = delta
    m[-1] = delta[-1]
    i = 0
    while i < n - 1:
        if seg[i] != CUBIC:
            i += 1
            continue
        a = i
        while i < n - 1 and seg[i] == CUBIC:
            i += 1
        b = i  # cubic run covers points a..b
        # the joint slope with a neighbouring linear segment is that segment's slope
        left = start_slope if a == 0 else delta[a - 1]
        right = end_slope if b == n - 1 else delta[b]
        m[a : b + 1] = _clamped_spline_slopes(h[a:b], delta[a:b], left, right)
    coef = np.zeros((n - 1, 4))
    coef[:, 0] = ys[:-1]
    lin = seg == LINEAR
    cub = ~lin
    coef[lin, 1] = delta[lin]
    # Hermite form of a cubic with end slopes m_i, m_i+1 over width h
    mi, mj, hh, dd = m[:-1][cub], m[1:][cub], h[cub], delta[cub]
    coef[cub, 1] = mi
    coef[cub, 2] = (3.0 * dd - 2.0 * mi - mj) / hh
    coef[cub, 3] = (mi + mj - 2.0 * dd) / (hh * hh)
    return CamProfile(x=xm.copy(), coef=coef, segment_type=seg.copy())


def _clamped_spline_slopes(
    h: np.ndarray, delta: np.ndarray, left: float, right: float
) -> np.ndarray:
    """Knot slopes of the C2 cubic spline with clamped end slopes (tridiagonal, Thomas)."""
    k = len(h)  # segments; k + 1 knots, unknown interior slopes 1..k-1
    m = np.empty(k + 1)
    m[0], m[-1] = left, right
    if k == 1:
        return m
    # second-derivative continuity at knot i:
    # m[i-1]/h[i-1] + 2 (1/h[i-1] + 1/h[i]) m[i] + m[i+1]/h[i] = 3 (delta[i-1]/h[i-1] + delta[i]/h[i])
    sub = 1.0 / h[:-1]
    sup = 1.0 / h[1:]
    diag = 2.0 * (sub + sup)
    rhs = 3.0 * (delta[:-1] / h[:-1] + delta[1:] / h[1:])
    rhs[0] -= sub[0] * left
    rhs[-1] -= sup[-1] * right
    nn = k - 1
    c = np.empty(nn)
    d = np.empty(nn)
    c[0] = sup[0] / diag[0]
    d[0] = rhs[0] / diag[0]
    for i in range(1, nn):
        w = diag[i] - sub[i] * c[i - 1]
        c[i] = sup[i] / w
        d[i] = (rhs[i] - sub[i] * d[i - 1]) / w
    x = np.empty(nn)
    x[-1] = d[-1]
    for i in range(nn - 2, -1, -1):
        x[i] = d[i] - c[i] * x[i + 1]
    m[1:-1] = x
    return m


def time_cam_trajectory(
    profile: CamProfile,
    t: np.ndarray | float,
    distance_scaling: float = 1.0,
    time_scaling: float = 1.0,
    mode: ExecutionMode = ExecutionMode.ONCE,
    direction: float = 1.0,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Contribution of one time cam at cam times t: dir*DS*(P(t/TS) - P(0)) (+ net per pass)."""
    x = np.asarray(t, dtype=float) / time_scaling
    span = profile.span
    k = np.floor(x / span) if mode == ExecutionMode.CONTINUOUS else np.zeros_like(x)
    local = profile.start + x - k * span
    p, v, a = profile.evaluate(local)
    g = direction * distance_scaling
    pos = g * (p - profile.p_start + k * profile.net)
    if mode == ExecutionMode.ONCE:  # outside the range the slave holds: no motion
        outside = (x < 0) | (x > span)
        v = np.where(outside, 0.0, v)
        a = np.where(outside, 0.0, a)
    return pos, g * v / time_scaling, g * a / time_scaling**2


class ProfileBank:
    """Several profiles laid end to end on one axis so one searchsorted serves all cams."""

    __slots__ = (
        "profiles", "base", "knots", "knot_rows", "coef", "table", "first_seg", "last_seg",
        "key",
    )  # fmt: skip

    def __init__(self, profiles: list[CamProfile]) -> None:
        self.profiles = profiles
        self.key = tuple(id(p) for p in profiles)
        bases, knots, coefs, first, last = [], [], [], [], []
        offset, nseg = 0.0, 0
        for p in profiles:
            # each profile occupies [offset, offset + span]; a gap of 1 keeps them apart
            bases.append(offset)
            # segment start knots, then the end knot opening a zero "separator" segment
            knots.append(p.x[:-1] - p.x[0] + offset)
            knots.append(np.array([offset + p.span]))
            coefs.append(p.coef)
            coefs.append(np.zeros((1, 4)))
            first.append(nseg)
            nseg += len(p.x) - 1
            last.append(nseg - 1)
            offset += p.span + 1.0
            nseg += 1
        self.base = np.array(bases)
        self.knots = np.concatenate(knots) if knots else np.zeros(1)
        # the segment tables one row down (an unused row 0): searchsorted(knots, g, "right")
        # is then the row of g's segment itself, one subtraction less per evaluation
        self.knot_rows = np.concatenate(([0.0], self.knots))
        coefs.insert(0, np.zeros((1, 4)))
        coef = np.concatenate(coefs)
        # a fifth column 2 c2 (exact: a doubling) saves evaluate_rows two multiplications
        self.coef = np.hstack((coef, 2.0 * coef[:, 2:3]))
        # the knots and coefficients as rows, so evaluate_rows gathers a row's segment data
        # with one take and every column it reads is contiguous (an empty bank has one knot
        # and no segment: its table is the unused row 0)
        knot_rows = self.knot_rows[: len(self.coef)]
        self.table = np.ascontiguousarray(np.column_stack((knot_rows, self.coef)).T)
        self.first_seg = np.array(first, dtype=np.intp) + 1  # rows of knot_rows and coef
        self.last_seg = np.array(last, dtype=np.intp) + 1

    def evaluate(self, prof: np.ndarray, local: np.ndarray) -> np.ndarray:
        """Evaluate profile prof[k] at local master offset local[k] (0..span) for every k:
        (position, velocity, acceleration) rows, see evaluate_rows."""
        return self.evaluate_rows(self.base[prof], self.first_seg[prof], self.last_seg[prof], local)

    def evaluate_rows(
        self, base: np.ndarray, first: np.ndarray, last: np.ndarray, local: np.ndarray
    ) -> np.ndarray:
        """evaluate() with the per-row profile data gathered beforehand (base[prof], ...).

        Returns one (3, rows) array: position, velocity and acceleration (unpack it as a
        tuple). The arithmetic is the same as the plain expressions in the comments,
        operation for operation (IEEE sums and products commute exactly), written in place
        into that array: on a few dozen rows a numpy call costs far more than its work."""
        g = local + base
        # local >= 0 keeps g at or after the profile's first knot (base itself), so only the
        # end needs a clamp: local = span may round onto the separator segment
        i = np.searchsorted(self.knots, g, side="right")
        np.minimum(i, last, out=i)
        c = self.table.take(i, axis=1)  # one gather: knot, c0, c1, c2, c3, 2 c2 per row
        c3, c2x2 = c[4], c[5]
        u = g
        u -= c[0]  # u = g - knot
        out = np.empty((3, len(u)))
        pos, vel, acc = out[0], out[1], out[2]
        # pos = c0 + u * (c1 + u * (c2 + u * c3))
        np.multiply(u, c3, out=pos)
        pos += c[3]
        pos *= u
        pos += c[2]
        pos *= u
        pos += c[1]
        # vel = c1 + u (2 c2 + 3 u c3), acc = 2 c2 + 6 u c3, with 6 u c3 = 2 (3 u c3):
        # doublings are exact, so these are the same numbers with fewer operations
        m = 3.0 * u
        m *= c3  # m = 3.0 * u * c3
        np.add(c2x2, m, out=vel)
        vel *= u
        vel += c[2]  # vel = c1 + u * (c2x2 + m)
        m += m
        np.add(c2x2, m, out=acc)  # acc = c2x2 + (m + m)
        return out
