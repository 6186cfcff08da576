"""Path geometry of coordinated moves (MCLM lines, MCCM arcs): exact, pure numpy.

A `Segment` is one planned path piece in 2 or 3 dimensions, parameterised by arc length
s in [0, length]. Lines and arcs share one closed form so that many segments evaluate in
one numpy step (`SegmentTable`):

    p(s) = start + A * f(s) + B * g(s)
    line:  A = unit direction, B = 0,          f = s,             g = 0
    arc:   A = start - centre = r u, B = r v,  f = cos(k s) - 1,  g = sin(k s),  k = sweep/length

Writing the arc relative to the start (not the centre) makes s = 0 give the start point
bit for bit; s >= length gives the stored end point, so the end point is exact too.

Arc basis: u points from the centre to the start, v = n x u with n the rotation axis, so
the arc runs from angle 0 to `sweep` in the (u, v) plane. In 2D n is +Z and the sweep is
signed (> 0 counter-clockwise seen from +Z, < 0 clockwise); in 3D n is the axis of the
motion's own rotation and the sweep is always positive.

Circle construction (`circle`) follows the seed's Circular Programming Reference Guide and
SPEC 9.28; the choices where both are silent are in docs/decisions/0120 and 0121. Errors
are returned, not raised, as `GeometryError(err, detail)` with the Logix motion error
number (the numbers are the catalog's, stdlib/motion_errors.toml; `CircleError` mirrors
them and tests/motion/test_path_geometry.py checks the mirror).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from enum import IntEnum

import numpy as np

TWO_PI = 2.0 * math.pi

# smallest radius a circle may have (seed: "R < .001" is error 49)
MIN_RADIUS = 0.001
# largest start/end radius difference around a programmed centre, relative to the start
# radius (seed: "R1 - R2 > .15 * R1" is error 46)
RADIUS_MISMATCH = 0.15
# two points closer than this, relative to the size of the coordinates (at least 1 unit),
# are the same point: positions arrive as REAL (float32, ~6e-8 relative), so a target
# copied from a tag or summed from increments may differ from the start by a few ulps
COINCIDENT = 1e-6
# three points whose sine of the angle at the start is below this are on one line (such a
# circle would have a radius of a million chords)
COLLINEAR = 1e-6


class CircleError(IntEnum):
    """Logix motion error numbers (.ERR) a circle's geometry can produce (the catalog's)."""

    ILLEGAL_INSTRUCTION = 25
    CIRCULAR_COLLINEARITY = 44
    CIRCULAR_START_END = 45
    CIRCULAR_R1_R2_MISMATCH = 46
    CIRCULAR_INFINITE_SOLUTION = 47
    CIRCULAR_NO_SOLUTIONS = 48
    CIRCULAR_SMALL_R = 49


class CircleType(IntEnum):
    """MCCM Circle Type operand (catalog enum CircleType)."""

    VIA = 0
    CENTER = 1
    RADIUS = 2
    CENTER_INCREMENTAL = 3


class CircleDirection(IntEnum):
    """MCCM Direction operand (catalog enum CircleDirection); 3D names share the values."""

    CW = 0
    CCW = 1
    CW_FULL = 2
    CCW_FULL = 3
    SHORTEST = 0
    LONGEST = 1
    SHORTEST_FULL = 2
    LONGEST_FULL = 3


@dataclass(slots=True, frozen=True)
class GeometryError:
    """Why no path could be built: Logix motion error number and a one-line reason."""

    err: int
    detail: str


@dataclass(slots=True, frozen=True, eq=False)
class Segment:
    """One path piece: a line (radius 0, sweep 0) or a circular arc, by arc length.

    Compared by identity (eq=False): its fields are numpy arrays.
    """

    start: np.ndarray  # (ndim,)
    end: np.ndarray  # (ndim,) where the motion ends (the start again for a full circle)
    length: float  # arc length
    centre: np.ndarray  # (ndim,) arcs; the start for a line
    radius: float  # 0 for a line
    u: np.ndarray  # arc: unit vector centre -> start; line: unit direction (0 if length 0)
    v: np.ndarray  # arc: unit vector n x u in the plane; line: zeros
    sweep: float  # signed swept angle in radians (2D: > 0 CCW from +Z; 3D: > 0); line 0

    @property
    def ndim(self) -> int:
        return int(self.start.shape[0])

    @property
    def is_arc(self) -> bool:
        return self.radius > 0.0

    @property
    def rate(self) -> float:
        """Angle per unit of arc length (signed, +-1/radius); 0 for a line."""
        return self.sweep / self.length if self.is_arc else 0.0

    @property
    def normal(self) -> np.ndarray:
        """Unit rotation axis u x v of an arc (3 components; +-Z for a 2D arc)."""
        u = np.zeros(3)
        v = np.zeros(3)
        u[: self.ndim] = self.u
        v[: self.ndim] = self.v
        return np.cross(u, v)

    def _ab(self) -> tuple[np.ndarray, np.ndarray]:
        if self.is_arc:
            return self.radius * self.u, self.radius * self.v
        return self.u, np.zeros_like(self.u)

    def points(self, s: np.ndarray) -> np.ndarray:
        """Points (len(s), ndim) at arc lengths s (clipped to [0, length])."""
        s = np.clip(np.asarray(s, dtype=float).reshape(-1), 0.0, self.length)
        a, b = self._ab()
        k = self.rate
        if self.is_arc:
            f = np.cos(k * s) - 1.0
            g = np.sin(k * s)
        else:
            f = s
            g = np.zeros_like(s)
        p = self.start + f[:, None] * a + g[:, None] * b
        p[s >= self.length] = self.end
        return p

    def tolerance_point(self, distance: float) -> float:
        """Arc length from which the straight distance to the end stays within `distance`.

        The Command Tolerance point: on an arc the remaining angle phi is at most
        2 asin(d / 2r) away (chord 2r sin(phi/2) <= d); a long arc or a full circle may be
        within d at its start too, but leaves it again, so this is the last entry.
        """
        d = max(float(distance), 0.0)
        if not self.is_arc:
            return max(self.length - d, 0.0)
        if d >= 2.0 * self.radius:
            return 0.0
        return max(self.length - 2.0 * self.radius * math.asin(d / (2.0 * self.radius)), 0.0)

    def tangent(self, s: np.ndarray) -> np.ndarray:
        """Unit tangents (len(s), ndim) in the direction of travel at arc lengths s."""
        s = np.clip(np.asarray(s, dtype=float).reshape(-1), 0.0, self.length)
        a, b = self._ab()
        k = self.rate
        if self.is_arc:
            df = -k * np.sin(k * s)
            dg = k * np.cos(k * s)
        else:
            df = np.ones_like(s)
            dg = np.zeros_like(s)
        return df[:, None] * a + dg[:, None] * b


def _vec(x: object, ndim: int) -> np.ndarray:
    """The first ndim components of a position operand as float64."""
    a = np.asarray(x, dtype=float).reshape(-1)
    if a.shape[0] < ndim:
        raise ValueError(f"need {ndim} coordinates, got {a.shape[0]}")
    return a[:ndim].copy()


def line(start: object, end: object) -> Segment:
    """Straight segment from start to end (any number of dimensions)."""
    p0 = np.asarray(start, dtype=float).reshape(-1).copy()
    p1 = np.asarray(end, dtype=float).reshape(-1).copy()
    if p0.shape != p1.shape:
        raise ValueError(f"start has {p0.shape[0]} coordinates, end {p1.shape[0]}")
    d = p1 - p0
    length = float(np.linalg.norm(d))
    u = d / length if length > 0.0 else np.zeros_like(d)
    return Segment(p0, p1, length, p0.copy(), 0.0, u, np.zeros_like(d), 0.0)


# ---------------------------------------------------------------------------- circles


def _pad3(p: np.ndarray) -> np.ndarray:
    out = np.zeros(3)
    out[: p.shape[0]] = p
    return out


def _angle(w: np.ndarray, u: np.ndarray, v: np.ndarray) -> float:
    """Angle of vector w in the (u, v) frame, in [0, 2 pi)."""
    t = math.atan2(float(w @ v), float(w @ u))
    return t + TWO_PI if t < 0.0 else t


def _build(
    ndim: int,
    start: np.ndarray,
    end: np.ndarray,
    centre: np.ndarray,
    n: np.ndarray,
    sweep: float,
) -> Segment:
    """Arc about `centre` from `start`, turning `sweep` (> 0) about unit axis n.

    start, end, centre and n are 3-vectors (2D padded with z = 0); the segment keeps the
    first ndim components.
    """
    w = start - centre
    r = float(np.linalg.norm(w))
    u = w / r
    v = np.cross(n, u)
    v /= float(np.linalg.norm(v))
    if ndim == 2 and n[2] < 0.0:
        # 2D arcs are described about +Z with a signed sweep
        v = -v
        sweep = -sweep
    return Segment(
        start[:ndim].copy(),
        end[:ndim].copy(),
        abs(sweep) * r,
        centre[:ndim].copy(),
        r,
        u[:ndim].copy(),
        v[:ndim].copy(),
        sweep,
    )


def circle(
    start: object,
    end: object,
    via_or_centre_or_radius: object,
    circle_type: int,
    direction: int,
    ndim: int,
    move_type: int = 0,
) -> Segment | GeometryError:
    """The MCCM arc from `start` to the absolute `end`, or the geometry error.

    via_or_centre_or_radius is the Via/Center/Radius operand: a point for Via, Center and
    Center Incremental (relative to the start when move_type is 1 Incremental, and always
    for Center Incremental), a number for Radius. With a Full direction the segment is one
    whole turn back to the start; `end` then only helps define the circle.

    Operands the runtime rejects with ERR 13 first (ndim not 2 or 3, circle type or
    direction out of range, arrays shorter than ndim) raise ValueError here.
    """
    if ndim not in (2, 3):
        raise ValueError(f"a circle needs 2 or 3 primary axes, not {ndim}")
    ctype = CircleType(circle_type)
    direction = CircleDirection(direction)
    full = direction in (CircleDirection.CW_FULL, CircleDirection.CCW_FULL)
    # 2D: odd directions are CCW; 3D: odd directions are Longest
    odd = direction in (CircleDirection.CCW, CircleDirection.CCW_FULL)
    p0 = _pad3(_vec(start, ndim))
    p1 = _pad3(_vec(end, ndim))
    if ctype == CircleType.RADIUS:
        aux_r = float(np.asarray(via_or_centre_or_radius, dtype=float).reshape(-1)[0])
        if ndim == 3:
            return GeometryError(
                CircleError.ILLEGAL_INSTRUCTION, "the Radius circle type is 2D only"
            )
        if not (np.isfinite(p0).all() and np.isfinite(p1).all() and math.isfinite(aux_r)):
            return GeometryError(CircleError.CIRCULAR_NO_SOLUTIONS, "a coordinate is not finite")
        return _radius_circle(p0, p1, aux_r, odd, full)
    aux = _pad3(_vec(via_or_centre_or_radius, ndim))
    if not (np.isfinite(p0).all() and np.isfinite(p1).all() and np.isfinite(aux).all()):
        return GeometryError(CircleError.CIRCULAR_NO_SOLUTIONS, "a coordinate is not finite")
    relative = ctype == CircleType.CENTER_INCREMENTAL or move_type == 1
    if relative:
        aux = p0 + aux
    if ctype == CircleType.VIA:
        return _via_circle(ndim, p0, p1, aux, full)
    return _centre_circle(ndim, p0, p1, aux, odd, full)


def _tolerance(*points: np.ndarray) -> float:
    scale = max(1.0, max(float(np.max(np.abs(p))) for p in points))
    return COINCIDENT * scale


def _via_circle(
    ndim: int, p0: np.ndarray, p1: np.ndarray, via: np.ndarray, full: bool
) -> Segment | GeometryError:
    tol = _tolerance(p0, p1, via)
    if float(np.linalg.norm(p1 - p0)) <= tol:
        return GeometryError(CircleError.CIRCULAR_START_END, "the end point equals the start")
    if min(float(np.linalg.norm(via - p0)), float(np.linalg.norm(via - p1))) <= tol:
        return GeometryError(
            CircleError.CIRCULAR_INFINITE_SOLUTION,
            "the via point equals the start or end point",
        )
    a = via - p0
    b = p1 - p0
    n = np.cross(a, b)
    nn = float(np.linalg.norm(n))
    if nn <= COLLINEAR * float(np.linalg.norm(a)) * float(np.linalg.norm(b)):
        return GeometryError(
            CircleError.CIRCULAR_COLLINEARITY, "start, via and end points are on one line"
        )
    n /= nn
    # circumcentre (equidistant from p0, via, p1, in their plane), with w = a x b:
    # c = p0 + (|a|^2 (b x w) + |b|^2 (w x a)) / (2 |w|^2)
    w = np.cross(a, b)
    c = p0 + (float(a @ a) * np.cross(b, w) + float(b @ b) * np.cross(w, a)) / (2.0 * float(w @ w))
    r = float(np.linalg.norm(p0 - c))
    if r < MIN_RADIUS:
        return GeometryError(CircleError.CIRCULAR_SMALL_R, f"radius {r:g} is below 0.001")
    # n = a x b is the sense start -> via -> end; the end's angle about it is the sweep
    u = (p0 - c) / r
    v = np.cross(n, u)
    sweep = TWO_PI if full else _angle(p1 - c, u, v)
    end = p0 if full else p1
    return _build(ndim, p0, end, c, n, sweep)


def _centre_circle(
    ndim: int, p0: np.ndarray, p1: np.ndarray, c: np.ndarray, odd: bool, full: bool
) -> Segment | GeometryError:
    tol = _tolerance(p0, p1, c)
    same = float(np.linalg.norm(p1 - p0)) <= tol
    if same and ndim == 3:
        return GeometryError(
            CircleError.CIRCULAR_START_END, "the end point equals the start (3D centre circle)"
        )
    r1 = float(np.linalg.norm(p0 - c))
    if r1 < MIN_RADIUS:
        return GeometryError(CircleError.CIRCULAR_SMALL_R, f"radius {r1:g} is below 0.001")
    r2 = float(np.linalg.norm(p1 - c))
    if abs(r1 - r2) > RADIUS_MISMATCH * r1:
        return GeometryError(
            CircleError.CIRCULAR_R1_R2_MISMATCH,
            f"start radius {r1:g} and end radius {r2:g} differ by more than 15%",
        )
    if not same:
        # decision 0120: the centre moves onto the chord's perpendicular bisector (in the
        # plane of start, end and centre), so the arc is a true circle through both points
        d = (p1 - p0) / float(np.linalg.norm(p1 - p0))
        m = 0.5 * (p0 + p1)
        c = c - float((c - m) @ d) * d
    if ndim == 2:
        return _planar(p0, p1, c, odd, full or same)
    n = np.cross(p0 - c, p1 - c)
    nn = float(np.linalg.norm(n))
    if nn <= COLLINEAR * float(np.linalg.norm(p0 - c)) * float(np.linalg.norm(p1 - c)):
        return GeometryError(
            CircleError.CIRCULAR_COLLINEARITY,
            "start, centre and end are on one line: the circle's plane is undefined",
        )
    n /= nn
    # about n the end is less than half a turn away: Shortest turns about n, Longest about -n
    if odd:
        n = -n
    r = float(np.linalg.norm(p0 - c))
    u = (p0 - c) / r
    v = np.cross(n, u)
    if full:
        return _build(3, p0, p0, c, n, TWO_PI)
    return _build(3, p0, p1, c, n, _angle(p1 - c, u, v))


def _planar(
    p0: np.ndarray, p1: np.ndarray, c: np.ndarray, ccw: bool, full: bool
) -> Segment | GeometryError:
    """2D arc about c from p0 to p1 (or a whole turn), CW or CCW seen from +Z."""
    z = np.array([0.0, 0.0, 1.0])
    r = float(np.linalg.norm(p0 - c))
    if r < MIN_RADIUS:
        return GeometryError(CircleError.CIRCULAR_SMALL_R, f"radius {r:g} is below 0.001")
    u = (p0 - c) / r
    v = np.cross(z, u)
    n = z if ccw else -z
    if full:
        return _build(2, p0, p0, c, n, TWO_PI)
    t = _angle(p1 - c, u, v)  # counter-clockwise angle to the end, in [0, 2 pi)
    return _build(2, p0, p1, c, n, t if ccw else TWO_PI - t)


def _radius_circle(
    p0: np.ndarray, p1: np.ndarray, radius: float, ccw: bool, full: bool
) -> Segment | GeometryError:
    if abs(radius) < MIN_RADIUS:
        return GeometryError(CircleError.CIRCULAR_SMALL_R, f"radius {radius:g} is below 0.001")
    tol = _tolerance(p0, p1)
    chord = p1 - p0
    dist = float(np.linalg.norm(chord))
    if dist <= tol:
        return GeometryError(CircleError.CIRCULAR_START_END, "the end point equals the start")
    half = 0.5 * dist
    if abs(radius) < half - tol:
        return GeometryError(
            CircleError.CIRCULAR_SMALL_R,
            f"radius {abs(radius):g} cannot span the chord of {dist:g}",
        )
    # an exact semicircle (|R| = chord/2 within tolerance) is valid for both signs
    h = math.sqrt(max(radius * radius - half * half, 0.0))
    d = chord / dist
    left = np.array([-d[1], d[0], 0.0])  # chord direction turned 90 degrees CCW
    # a short CCW arc (and a long CW one) bends around a centre left of the chord
    longer = radius < 0.0
    side = 1.0 if ccw != longer else -1.0
    c = 0.5 * (p0 + p1) + side * h * left
    return _planar(p0, p1, c, ccw, full)


# ---------------------------------------------------------------- many segments at once


@dataclass(slots=True)
class SegmentTable:
    """Struct of arrays of many segments, always 3 columns (2D segments have z = 0).

    Row i holds one segment (e.g. the active move of coordinate system i); `points(rows,
    s)` evaluates any number of (row, arc length) pairs in one numpy step.
    """

    start: np.ndarray  # (n, 3)
    end: np.ndarray  # (n, 3)
    a: np.ndarray  # (n, 3) line: unit direction; arc: start - centre
    b: np.ndarray  # (n, 3) line: 0; arc: radius * v
    rate: np.ndarray  # (n,) angle per unit length; 0 for lines
    length: np.ndarray  # (n,)
    arc: np.ndarray  # (n,) bool

    @staticmethod
    def empty(n: int) -> SegmentTable:
        z3 = np.zeros((n, 3))
        return SegmentTable(
            z3.copy(), z3.copy(), z3.copy(), z3.copy(), np.zeros(n), np.zeros(n), np.zeros(n, bool)
        )

    @staticmethod
    def of(segments: list[Segment]) -> SegmentTable:
        t = SegmentTable.empty(len(segments))
        for i, seg in enumerate(segments):
            t.set(i, seg)
        return t

    def __len__(self) -> int:
        return int(self.length.shape[0])

    def set(self, row: int, seg: Segment) -> None:
        """Put `seg` in row `row` (the caller grows the table with `resized` first)."""
        k = seg.ndim
        for arr in (self.start, self.end, self.a, self.b):
            arr[row] = 0.0
        self.start[row, :k] = seg.start
        self.end[row, :k] = seg.end
        a, b = seg._ab()
        self.a[row, :k] = a
        self.b[row, :k] = b
        self.rate[row] = seg.rate
        self.length[row] = seg.length
        self.arc[row] = seg.is_arc

    def resized(self, n: int) -> SegmentTable:
        """A copy with n rows (new rows are zero-length lines at the origin)."""
        t = SegmentTable.empty(n)
        m = min(n, len(self))
        for name in ("start", "end", "a", "b", "rate", "length", "arc"):
            getattr(t, name)[:m] = getattr(self, name)[:m]
        return t

    def points(self, rows: np.ndarray, s: np.ndarray) -> np.ndarray:
        """Points (m, 3) of segments `rows` at arc lengths `s` (clipped to [0, length])."""
        rows = np.asarray(rows, dtype=np.intp)
        length = self.length[rows]
        s = np.clip(np.asarray(s, dtype=float), 0.0, length)
        ks = self.rate[rows] * s
        f = np.where(self.arc[rows], np.cos(ks) - 1.0, s)
        g = np.sin(ks)  # 0 for lines (rate 0)
        p = self.start[rows] + f[:, None] * self.a[rows] + g[:, None] * self.b[rows]
        done = s >= length
        p[done] = self.end[rows[done]]
        return p

    def tolerance_points(self, rows: np.ndarray, distance: np.ndarray) -> np.ndarray:
        """`Segment.tolerance_point` of many rows at once (distance per row or one value)."""
        rows = np.asarray(rows, dtype=np.intp)
        d = np.maximum(np.broadcast_to(np.asarray(distance, dtype=float), rows.shape), 0.0)
        length = self.length[rows]
        arc = self.arc[rows]
        # radius of an arc row is |A| = |start - centre|; lines use the straight remainder
        r = np.where(arc, np.linalg.norm(self.a[rows], axis=1), 1.0)
        ratio = np.minimum(d / (2.0 * r), 1.0)
        on_arc = np.where(ratio >= 1.0, length, 2.0 * r * np.arcsin(ratio))
        return np.maximum(length - np.where(arc, on_arc, d), 0.0)

    def tangents(self, rows: np.ndarray, s: np.ndarray) -> np.ndarray:
        """Unit tangents (m, 3) of segments `rows` at arc lengths `s`."""
        rows = np.asarray(rows, dtype=np.intp)
        s = np.clip(np.asarray(s, dtype=float), 0.0, self.length[rows])
        k = self.rate[rows]
        ks = k * s
        df = np.where(self.arc[rows], -k * np.sin(ks), 1.0)
        dg = k * np.cos(ks)
        return df[:, None] * self.a[rows] + dg[:, None] * self.b[rows]
