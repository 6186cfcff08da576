"""Path geometry of coordinated moves (interpreter/motion/path_geometry.py).

Expected values are hand geometry, worked in the comments.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from interpreter.motion.path_geometry import (
    CircleDirection,
    CircleError,
    CircleType,
    GeometryError,
    Segment,
    SegmentTable,
    circle,
    line,
)
from stdlib import catalog


def test_line_points_tangent_and_exact_end() -> None:
    # (1, 2) -> (4, 6): chord (3, 4), length 5, unit direction (0.6, 0.8)
    seg = line([1.0, 2.0], [4.0, 6.0])
    assert seg.length == 5.0
    assert not seg.is_arc
    pts = seg.points(np.array([0.0, 2.5, 5.0]))
    # s = 2.5: (1 + 0.6*2.5, 2 + 0.8*2.5) = (2.5, 4.0)
    np.testing.assert_allclose(pts[1], [2.5, 4.0], rtol=0, atol=1e-12)
    assert pts[0].tolist() == [1.0, 2.0]
    assert pts[2].tolist() == [4.0, 6.0]
    np.testing.assert_allclose(seg.tangent(np.array([1.0])), [[0.6, 0.8]], atol=1e-15)


def test_zero_length_line_stays_at_its_point() -> None:
    seg = line([1.0, 1.0, 1.0], [1.0, 1.0, 1.0])
    assert seg.length == 0.0
    assert seg.points(np.array([0.0, 3.0])).tolist() == [[1.0, 1.0, 1.0]] * 2


def test_table_evaluates_lines_and_arcs_together() -> None:
    # row 0: line (0,0) -> (3,4); row 1: quarter circle about (0,0) from (1,0) CCW to (0,1)
    t = SegmentTable.of(
        [line([0.0, 0.0], [3.0, 4.0]), circle([1.0, 0.0], [0.0, 1.0], [0.0, 0.0], 1, 1, 2)]
    )
    rows = np.array([0, 0, 1, 1])
    s = np.array([2.5, 5.0, math.pi / 4, math.pi / 2])
    p = t.points(rows, s)
    # line at s = 2.5: (1.5, 2.0); arc at 45 degrees: (cos 45, sin 45)
    h = math.sqrt(0.5)
    np.testing.assert_allclose(p[0], [1.5, 2.0, 0.0], atol=1e-12)
    assert p[1].tolist() == [3.0, 4.0, 0.0]
    np.testing.assert_allclose(p[2], [h, h, 0.0], atol=1e-12)
    assert p[3].tolist() == [0.0, 1.0, 0.0]
    # tangents: line (0.6, 0.8); arc at 45 degrees CCW: (-sin 45, cos 45)
    tg = t.tangents(np.array([0, 1]), np.array([1.0, math.pi / 4]))
    np.testing.assert_allclose(tg, [[0.6, 0.8, 0.0], [-h, h, 0.0]], atol=1e-12)


# ------------------------------------------------------------------------------- arcs
#
# The tilted 3D circle used below: centre C = (1, 2, 3), radius 5, in the plane spanned by
# the unit vectors E1 = (0.6, 0, 0.8) and E2 = (0, 1, 0) (orthogonal: 0.6*0 + 0*1 + 0.8*0).
# Point at angle t: C + 5 (cos t E1 + sin t E2), so
#   t = 0    -> (1 + 3, 2, 3 + 4)   = (4, 2, 7)
#   t = 90   -> (1, 2 + 5, 3)       = (1, 7, 3)
#   t = 180  -> (1 - 3, 2, 3 - 4)   = (-2, 2, -1)
#   t = 270  -> (1, 2 - 5, 3)       = (1, -3, 3)
# Its normal E1 x E2 = (0*0 - 0.8*1, 0.8*0 - 0.6*0, 0.6*1 - 0*0) = (-0.8, 0, 0.6).

C3 = np.array([1.0, 2.0, 3.0])
E1 = np.array([0.6, 0.0, 0.8])
E2 = np.array([0.0, 1.0, 0.0])
N3 = np.array([-0.8, 0.0, 0.6])


def on_tilted(t_deg: float) -> np.ndarray:
    t = math.radians(t_deg)
    return C3 + 5.0 * (math.cos(t) * E1 + math.sin(t) * E2)


def assert_arc(
    seg: Segment | GeometryError,
    *,
    start: list[float] | np.ndarray,
    end: list[float] | np.ndarray,
    centre: list[float] | np.ndarray,
    radius: float,
    sweep: float,
    mid: list[float] | np.ndarray,
    side: int = 0,
    normal: np.ndarray | None = None,
) -> Segment:
    """Check an arc against its hand-computed geometry.

    side: +1 when the arc lies left of the chord start -> end (seen from +Z in 2D, from
    `normal` in 3D), -1 right, 0 not checked (full circles). Going counter-clockwise the
    centre is on the left, so a CCW arc (short or long) lies right of its chord: -1.
    """
    assert isinstance(seg, Segment), seg
    centre = np.asarray(centre, dtype=float)
    assert seg.is_arc
    np.testing.assert_allclose(seg.centre, centre, rtol=0, atol=1e-9 * radius)
    assert seg.radius == pytest.approx(radius, rel=1e-12)
    assert seg.sweep == pytest.approx(sweep, rel=1e-12)
    assert seg.length == pytest.approx(abs(sweep) * radius, rel=1e-12)
    s = np.linspace(0.0, seg.length, 2001)
    p = seg.points(s)
    # every traced point on the circle, within 1e-6 relative
    dist = np.linalg.norm(p - centre, axis=1)
    assert np.max(np.abs(dist - radius)) <= 1e-6 * radius
    if normal is not None:
        # and in the circle's plane
        assert np.max(np.abs((p - centre) @ normal)) <= 1e-6 * radius
    # start and end exact
    assert p[0].tolist() == list(map(float, start))
    assert p[-1].tolist() == list(map(float, end))
    assert seg.end.tolist() == list(map(float, end))
    # consecutive samples are the same chord apart: the angle advances uniformly
    steps = np.linalg.norm(np.diff(p, axis=0), axis=1)
    chord = 2.0 * radius * math.sin(abs(sweep) / 2000 / 2)
    np.testing.assert_allclose(steps, chord, rtol=1e-6)
    np.testing.assert_allclose(seg.points(np.array([seg.length / 2]))[0], mid, atol=1e-9 * radius)
    if side:
        st = np.asarray(start, dtype=float)
        ch = np.asarray(end, dtype=float) - st
        rel = p[1:-1] - st
        if normal is None:
            cross = ch[0] * rel[:, 1] - ch[1] * rel[:, 0]
        else:
            cross = np.cross(ch, rel) @ normal
        assert np.all(np.sign(cross) == side)
    # tangents: unit, perpendicular to the radius, turning the way the sweep says
    tg = seg.tangent(s)
    np.testing.assert_allclose(np.linalg.norm(tg, axis=1), 1.0, rtol=1e-12)
    assert np.max(np.abs(np.sum(tg * (p - centre), axis=1))) <= 1e-6 * radius
    return seg


R2 = math.sqrt(0.5)  # cos 45 = sin 45


# 2D Center, start (10, 0), end (0, 10), centre (0, 0): the end is 90 deg CCW of the start.
# CCW: +90 deg, length 10*pi/2, midpoint at 45 deg = (7.0711, 7.0711), right of the chord.
# CW: the other way round, -270 deg, length 10*3pi/2, midpoint at -135 deg, left.
# CW Full / CCW Full: one turn back to (10, 0); quarter of the way at -90 / +90 deg.
@pytest.mark.parametrize(
    ("direction", "sweep", "mid", "quarter", "side"),
    [
        (1, math.pi / 2, [10 * R2, 10 * R2], [], -1),
        (0, -3 * math.pi / 2, [-10 * R2, -10 * R2], [], 1),
        (2, -2 * math.pi, [-10.0, 0.0], [0.0, -10.0], 0),
        (3, 2 * math.pi, [-10.0, 0.0], [0.0, 10.0], 0),
    ],
    ids=["ccw", "cw", "cw-full", "ccw-full"],
)
def test_2d_centre_each_direction(
    direction: int, sweep: float, mid: list[float], quarter: list[float], side: int
) -> None:
    full = direction >= 2
    seg = assert_arc(
        circle([10.0, 0.0], [0.0, 10.0], [0.0, 0.0], 1, direction, 2),
        start=[10.0, 0.0],
        end=[10.0, 0.0] if full else [0.0, 10.0],
        centre=[0.0, 0.0],
        radius=10.0,
        sweep=sweep,
        mid=mid,
        side=side,
    )
    if quarter:
        q = seg.points(np.array([seg.length / 4]))[0]
        np.testing.assert_allclose(q, quarter, atol=1e-9)


@pytest.mark.parametrize(("direction", "sweep"), [(0, -2 * math.pi), (1, 2 * math.pi)])
def test_2d_centre_end_equal_start_is_a_full_circle_in_any_direction(
    direction: int, sweep: float
) -> None:
    # start = end = (10, 0) about (0, 0): one turn; half way is the far side (-10, 0)
    assert_arc(
        circle([10.0, 0.0], [10.0, 0.0], [0.0, 0.0], 1, direction, 2),
        start=[10.0, 0.0],
        end=[10.0, 0.0],
        centre=[0.0, 0.0],
        radius=10.0,
        sweep=sweep,
        mid=[-10.0, 0.0],
    )


def test_2d_centre_semicircle_both_senses() -> None:
    # start (0, 0), end (10, 0), centre (5, 0): CCW goes below the chord through (5, -5)
    # (start angle 180 deg, +90 deg -> 270 deg), CW above through (5, 5)
    assert_arc(
        circle([0.0, 0.0], [10.0, 0.0], [5.0, 0.0], 1, 1, 2),
        start=[0.0, 0.0],
        end=[10.0, 0.0],
        centre=[5.0, 0.0],
        radius=5.0,
        sweep=math.pi,
        mid=[5.0, -5.0],
        side=-1,
    )
    assert_arc(
        circle([0.0, 0.0], [10.0, 0.0], [5.0, 0.0], 1, 0, 2),
        start=[0.0, 0.0],
        end=[10.0, 0.0],
        centre=[5.0, 0.0],
        radius=5.0,
        sweep=-math.pi,
        mid=[5.0, 5.0],
        side=1,
    )


@pytest.mark.parametrize("move_type", [0, 1])
def test_2d_centre_incremental_is_relative_to_the_start_for_both_move_types(
    move_type: int,
) -> None:
    # start (10, 5), centre increment (-10, 0) -> centre (0, 5); end (0, 15) is 90 deg CCW
    # of the start (radius 10); midpoint (10 cos 45, 5 + 10 sin 45)
    assert_arc(
        circle([10.0, 5.0], [0.0, 15.0], [-10.0, 0.0], 3, 1, 2, move_type=move_type),
        start=[10.0, 5.0],
        end=[0.0, 15.0],
        centre=[0.0, 5.0],
        radius=10.0,
        sweep=math.pi / 2,
        mid=[10 * R2, 5 + 10 * R2],
        side=-1,
    )


def test_2d_centre_under_incremental_move_type_is_relative_to_the_start() -> None:
    # same circle as above with Circle Type Center: the centre operand (-10, 0) is an
    # increment from the start (10, 5) because the move is Incremental -> (0, 5)
    assert_arc(
        circle([10.0, 5.0], [0.0, 15.0], [-10.0, 0.0], 1, 1, 2, move_type=1),
        start=[10.0, 5.0],
        end=[0.0, 15.0],
        centre=[0.0, 5.0],
        radius=10.0,
        sweep=math.pi / 2,
        mid=[10 * R2, 5 + 10 * R2],
        side=-1,
    )
    # and absolute under Absolute: centre (-10, 0) is then 20.6 from the start and 18.0 from
    # the end -> |R1 - R2| = 2.6 <= 0.15 * 20.6 = 3.1: no error, but a different circle
    seg = circle([10.0, 5.0], [0.0, 15.0], [-10.0, 0.0], 1, 1, 2, move_type=0)
    assert isinstance(seg, Segment)
    assert seg.radius > 15.0


def test_centre_with_unequal_radii_moves_the_centre_onto_the_bisector() -> None:
    # start (10, 0), end (0, 11), centre (0, 0): R1 = 10, R2 = 11, 10 % apart (allowed).
    # Decision 0120: the centre becomes the point of the chord's perpendicular bisector
    # nearest the programmed one. Chord d = (-10, 11), |d|^2 = 221, midpoint m = (5, 5.5);
    # (c - m).d = (-5)(-10) + (-5.5)(11) = 50 - 60.5 = -10.5;
    # c' = c - (-10.5 / 221) d = (-105/221, 115.5/221) = (-0.475113, 0.522624).
    # r^2 = (10 + 105/221)^2 + (115.5/221)^2 = 109.7280 + 0.2731 = 110.0011 (and the same
    # from the end: (105/221)^2 + (11 - 115.5/221)^2 = 0.2257 + 109.7754).
    c = np.array([-105 / 221, 115.5 / 221])
    r = math.sqrt((10 + 105 / 221) ** 2 + (115.5 / 221) ** 2)
    # CCW from the start's angle to the end's, both about c'
    a0 = math.atan2(0 - c[1], 10 - c[0])
    a1 = math.atan2(11 - c[1], 0 - c[0])
    am = (a0 + a1) / 2
    assert_arc(
        circle([10.0, 0.0], [0.0, 11.0], [0.0, 0.0], 1, 1, 2),
        start=[10.0, 0.0],
        end=[0.0, 11.0],
        centre=c,
        radius=r,
        sweep=a1 - a0,
        mid=c + r * np.array([math.cos(am), math.sin(am)]),
        side=-1,
    )


# 2D Radius, start (0, 0), end (10, 0): half chord 5; |R| = 13 -> centre 12 off the chord
# (5-12-13 triangle), centres (5, 12) and (5, -12); the short arc spans 2 atan(5/12).
# CCW short: centre left of the chord (+y), (5, 12); mid = (5, 12 - 13) = (5, -1), below.
# CCW long (R < 0): centre (5, -12); mid = (5, -12 - 13) = (5, -25), below.
# CW short: centre (5, -12); mid (5, 1), above. CW long: centre (5, 12); mid (5, 25).
SHORT = 2 * math.atan(5 / 12)


@pytest.mark.parametrize(
    ("direction", "radius", "centre", "sweep", "mid", "side"),
    [
        (1, 13.0, [5.0, 12.0], SHORT, [5.0, -1.0], -1),
        (1, -13.0, [5.0, -12.0], 2 * math.pi - SHORT, [5.0, -25.0], -1),
        (0, 13.0, [5.0, -12.0], -SHORT, [5.0, 1.0], 1),
        (0, -13.0, [5.0, 12.0], -(2 * math.pi - SHORT), [5.0, 25.0], 1),
    ],
    ids=["ccw-short", "ccw-long", "cw-short", "cw-long"],
)
def test_2d_radius_sign_picks_the_arc(
    direction: int,
    radius: float,
    centre: list[float],
    sweep: float,
    mid: list[float],
    side: int,
) -> None:
    assert_arc(
        circle([0.0, 0.0], [10.0, 0.0], radius, 2, direction, 2),
        start=[0.0, 0.0],
        end=[10.0, 0.0],
        centre=centre,
        radius=13.0,
        sweep=sweep,
        mid=mid,
        side=side,
    )


@pytest.mark.parametrize("radius", [5.0, -5.0, 5.0 - 1e-9])
@pytest.mark.parametrize(("direction", "mid", "side"), [(1, [5.0, -5.0], -1), (0, [5.0, 5.0], 1)])
def test_2d_radius_exact_semicircle_valid_for_both_signs(
    radius: float, direction: int, mid: list[float], side: int
) -> None:
    # |R| = chord / 2 = 5: centre the chord's midpoint (5, 0); CCW below, CW above
    assert_arc(
        circle([0.0, 0.0], [10.0, 0.0], [radius], 2, direction, 2),
        start=[0.0, 0.0],
        end=[10.0, 0.0],
        centre=[5.0, 0.0],
        radius=5.0,
        sweep=math.pi if direction == 1 else -math.pi,
        mid=mid,
        side=side,
    )


@pytest.mark.parametrize(
    ("direction", "radius", "centre", "sweep"),
    [(3, 13.0, [5.0, 12.0], 2 * math.pi), (2, 13.0, [5.0, -12.0], -2 * math.pi)],
)
def test_2d_radius_full_circle(
    direction: int, radius: float, centre: list[float], sweep: float
) -> None:
    # Position (10, 0) only places the circle (as for the short arc above); the move turns
    # once back to (0, 0); half way is the point opposite the start: 2 c - start
    c = np.array(centre)
    assert_arc(
        circle([0.0, 0.0], [10.0, 0.0], radius, 2, direction, 2),
        start=[0.0, 0.0],
        end=[0.0, 0.0],
        centre=c,
        radius=13.0,
        sweep=sweep,
        mid=2 * c,
    )


# 2D Via: the via point decides the sense; the Direction operand only says full or not.
@pytest.mark.parametrize("direction", [0, 1])
def test_2d_via_sense_comes_from_the_via_point(direction: int) -> None:
    # (10, 0) through (0, 10) to (-10, 0): centre (0, 0), CCW half turn, midpoint = via
    assert_arc(
        circle([10.0, 0.0], [-10.0, 0.0], [0.0, 10.0], 0, direction, 2),
        start=[10.0, 0.0],
        end=[-10.0, 0.0],
        centre=[0.0, 0.0],
        radius=10.0,
        sweep=math.pi,
        mid=[0.0, 10.0],
        side=-1,
    )
    # (10, 0) through (0, -10) to (0, 10): clockwise three quarters, midpoint at -135 deg
    assert_arc(
        circle([10.0, 0.0], [0.0, 10.0], [0.0, -10.0], 0, direction, 2),
        start=[10.0, 0.0],
        end=[0.0, 10.0],
        centre=[0.0, 0.0],
        radius=10.0,
        sweep=-3 * math.pi / 2,
        mid=[-10 * R2, -10 * R2],
        side=1,
    )


def test_2d_via_off_origin_circle() -> None:
    # circle centre (3, -2), radius 5 (3-4-5 offsets): start (8, -2) at 0 deg, via
    # (6, 2) = (3 + 3, -2 + 4) at atan2(4, 3) = 53.13 deg, end (-1, 1) = (3 - 4, -2 + 3) at
    # atan2(3, -4) = 143.13 deg: CCW, sweep 2.49809 rad; midpoint at half that angle
    t = math.atan2(3, -4)
    assert_arc(
        circle([8.0, -2.0], [-1.0, 1.0], [6.0, 2.0], 0, 0, 2),
        start=[8.0, -2.0],
        end=[-1.0, 1.0],
        centre=[3.0, -2.0],
        radius=5.0,
        sweep=t,
        mid=[3 + 5 * math.cos(t / 2), -2 + 5 * math.sin(t / 2)],
        side=-1,
    )


@pytest.mark.parametrize(("direction", "move_type"), [(2, 0), (3, 0), (2, 1)])
def test_2d_via_full_circle(direction: int, move_type: int) -> None:
    # start (10, 0), via (0, 10), Position (-10, 0): CCW, one whole turn back to (10, 0);
    # under Incremental the via operand (-10, 10) is added to the start -> (0, 10)
    via = [-10.0, 10.0] if move_type else [0.0, 10.0]
    seg = assert_arc(
        circle([10.0, 0.0], [-10.0, 0.0], via, 0, direction, 2, move_type=move_type),
        start=[10.0, 0.0],
        end=[10.0, 0.0],
        centre=[0.0, 0.0],
        radius=10.0,
        sweep=2 * math.pi,
        mid=[-10.0, 0.0],
    )
    np.testing.assert_allclose(seg.points(np.array([seg.length / 4]))[0], [0.0, 10.0], atol=1e-9)


# ------------------------------------------------------------------------------- 3D


@pytest.mark.parametrize(
    ("direction", "end_deg", "sweep", "mid_deg", "quarter_deg", "axis", "side"),
    [
        # Shortest: +90 deg about N3, midpoint at 45 deg, right of the chord seen from N3
        (0, 90, math.pi / 2, 45, None, 1, -1),
        # Longest: the other way, 270 deg about -N3, midpoint at -135 deg, left
        (1, 90, 3 * math.pi / 2, -135, None, -1, 1),
        # Shortest Full: one turn about N3 (the end 90 deg away sets the sense)
        (2, 90, 2 * math.pi, 180, 90, 1, 0),
        # Longest Full: one turn about -N3, a quarter of the way is at -90 deg
        (3, 90, 2 * math.pi, 180, -90, -1, 0),
    ],
    ids=["shortest", "longest", "shortest-full", "longest-full"],
)
def test_3d_centre_each_direction(
    direction: int,
    end_deg: float,
    sweep: float,
    mid_deg: float,
    quarter_deg: float | None,
    axis: int,
    side: int,
) -> None:
    start = on_tilted(0)  # (4, 2, 7)
    end = on_tilted(end_deg)  # (1, 7, 3)
    full = direction >= 2
    seg = assert_arc(
        circle(start, end, C3, 1, direction, 3),
        start=start,
        end=start if full else end,
        centre=C3,
        radius=5.0,
        sweep=sweep,
        mid=on_tilted(mid_deg),
        side=side,
        normal=N3,
    )
    np.testing.assert_allclose(seg.normal, axis * N3, atol=1e-12)
    if quarter_deg is not None:
        q = seg.points(np.array([seg.length / 4]))[0]
        np.testing.assert_allclose(q, on_tilted(quarter_deg), atol=1e-9)


@pytest.mark.parametrize(("ctype", "move_type"), [(1, 1), (3, 0), (3, 1)])
def test_3d_centre_increment(ctype: int, move_type: int) -> None:
    # centre C3 given as the increment from the start (4, 2, 7): (-3, 0, -4)
    start = on_tilted(0)
    end = on_tilted(90)
    assert_arc(
        circle(start, end, [-3.0, 0.0, -4.0], ctype, 0, 3, move_type=move_type),
        start=start,
        end=end,
        centre=C3,
        radius=5.0,
        sweep=math.pi / 2,
        mid=on_tilted(45),
        side=-1,
        normal=N3,
    )


def test_3d_arc_through_a_via_point() -> None:
    # (4, 2, 7) at 0 deg through (1, 7, 3) at 90 deg to (-2, 2, -1) at 180 deg: half turn
    # about N3 with the via point as midpoint
    seg = assert_arc(
        circle(on_tilted(0), on_tilted(180), on_tilted(90), 0, 0, 3),
        start=on_tilted(0),
        end=on_tilted(180),
        centre=C3,
        radius=5.0,
        sweep=math.pi,
        mid=on_tilted(90),
        side=-1,
        normal=N3,
    )
    np.testing.assert_allclose(seg.normal, N3, atol=1e-12)


def test_3d_via_point_makes_the_long_way_round() -> None:
    # start at 0 deg, via at 200 deg (= -160), end at 90 deg (= -270): the via is only
    # reached turning negatively about N3, so the arc turns 270 deg about -N3 and its
    # midpoint is at -135 deg
    seg = assert_arc(
        circle(on_tilted(0), on_tilted(90), on_tilted(200), 0, 1, 3),
        start=on_tilted(0),
        end=on_tilted(90),
        centre=C3,
        radius=5.0,
        sweep=3 * math.pi / 2,
        mid=on_tilted(-135),
        side=1,
        normal=N3,
    )
    np.testing.assert_allclose(seg.normal, -N3, atol=1e-12)
    # the via point itself is on the traced path: at 160/270 of the length
    np.testing.assert_allclose(
        seg.points(np.array([seg.length * 160 / 270]))[0], on_tilted(200), atol=1e-9
    )


@pytest.mark.parametrize("direction", [2, 3])
def test_3d_via_full_circle(direction: int) -> None:
    # start 0 deg, via 90 deg, Position 180 deg: one turn about N3 whatever the Full kind
    assert_arc(
        circle(on_tilted(0), on_tilted(180), on_tilted(90), 0, direction, 3),
        start=on_tilted(0),
        end=on_tilted(0),
        centre=C3,
        radius=5.0,
        sweep=2 * math.pi,
        mid=on_tilted(180),
        normal=N3,
    )


def test_3d_system_with_planar_data_is_still_a_3d_arc() -> None:
    # a 3-axis system moving in z = 0 uses the 3D directions: Longest from (10, 0, 0) to
    # (0, 10, 0) about the origin is the 270 deg way, through (-7.07, -7.07, 0)
    assert_arc(
        circle([10.0, 0.0, 0.0], [0.0, 10.0, 0.0], [0.0, 0.0, 0.0], 1, 1, 3),
        start=[10.0, 0.0, 0.0],
        end=[0.0, 10.0, 0.0],
        centre=[0.0, 0.0, 0.0],
        radius=10.0,
        sweep=3 * math.pi / 2,
        mid=[-10 * R2, -10 * R2, 0.0],
        normal=np.array([0.0, 0.0, 1.0]),
    )


# ----------------------------------------------------------------------------- errors


def err(result: Segment | GeometryError) -> int:
    assert isinstance(result, GeometryError), result
    assert result.detail
    return result.err


def test_error_44_collinear() -> None:
    # via (5, 5) on the line from (0, 0) to (10, 10)
    assert err(circle([0.0, 0.0], [10.0, 10.0], [5.0, 5.0], 0, 0, 2)) == 44
    # the via beyond the end, still on the line
    assert err(circle([0.0, 0.0, 0.0], [1.0, 2.0, 3.0], [2.0, 4.0, 6.0], 0, 0, 3)) == 44
    # 3D centre on the chord (a 3D semicircle has no plane): start 0 deg, end 180 deg
    assert err(circle(on_tilted(0), on_tilted(180), C3, 1, 0, 3)) == 44


def test_error_45_end_equals_start() -> None:
    assert err(circle([1.0, 2.0], [1.0, 2.0], [5.0, 5.0], 0, 0, 2)) == 45  # via
    assert err(circle([1.0, 2.0], [1.0, 2.0], [5.0, 5.0], 0, 2, 2)) == 45  # via, full
    assert err(circle([1.0, 2.0], [1.0, 2.0], 5.0, 2, 1, 2)) == 45  # radius
    assert err(circle([1.0, 2.0], [1.0, 2.0], 5.0, 2, 3, 2)) == 45  # radius, full
    assert err(circle(on_tilted(0), on_tilted(0), C3, 1, 0, 3)) == 45  # 3D centre


def test_error_46_radius_mismatch() -> None:
    # centre (0, 0): R1 = 10 to (10, 0), R2 = 12 to (0, 12); 2 > 0.15 * 10 = 1.5
    assert err(circle([10.0, 0.0], [0.0, 12.0], [0.0, 0.0], 1, 1, 2)) == 46
    # R2 = 11.4: 1.4 <= 1.5 is allowed
    assert isinstance(circle([10.0, 0.0], [0.0, 11.4], [0.0, 0.0], 1, 1, 2), Segment)
    # 3D: start (4, 2, 7) radius 5, end C3 + 6 E2 = (1, 8, 3) radius 6; 1 > 0.75
    assert err(circle(on_tilted(0), C3 + 6 * E2, C3, 1, 0, 3)) == 46
    # the mismatch is measured against the start radius: R1 = 10, R2 = 8.4 -> 1.6 > 1.5
    # (Center Incremental: (-10, 0) from the start (10, 0) is the origin)
    assert err(circle([10.0, 0.0], [0.0, 8.4], [-10.0, 0.0], 3, 1, 2)) == 46


def test_error_47_via_on_start_or_end() -> None:
    # only two distinct points: infinitely many circles pass through them
    assert err(circle([0.0, 0.0], [10.0, 0.0], [0.0, 0.0], 0, 0, 2)) == 47
    assert err(circle([0.0, 0.0, 0.0], [10.0, 0.0, 0.0], [10.0, 0.0, 0.0], 0, 0, 3)) == 47


def test_error_48_not_finite() -> None:
    assert err(circle([0.0, 0.0], [10.0, float("nan")], [5.0, 0.0], 1, 0, 2)) == 48
    assert err(circle([0.0, 0.0], [10.0, 0.0], float("inf"), 2, 0, 2)) == 48


def test_error_49_radius_too_small_or_too_short() -> None:
    # Radius type: |R| = 4 cannot span a chord of 10 (needs at least 5), either sign
    assert err(circle([0.0, 0.0], [10.0, 0.0], 4.0, 2, 0, 2)) == 49
    assert err(circle([0.0, 0.0], [10.0, 0.0], -4.0, 2, 1, 2)) == 49
    # |R| below 0.001
    assert err(circle([0.0, 0.0], [0.0005, 0.0], 0.0005, 2, 0, 2)) == 49
    assert err(circle([0.0, 0.0], [10.0, 0.0], 0.0, 2, 0, 2)) == 49
    # a centre 0.0005 from the start
    assert err(circle([0.0, 0.0], [0.0, 0.0], [0.0005, 0.0], 1, 0, 2)) == 49
    # a via circle through (0,0,0), (0.0005, 0.0005, 0), (0.001, 0, 0): radius 0.0005
    assert err(circle([0.0, 0.0, 0.0], [0.001, 0.0, 0.0], [0.0005, 0.0005, 0.0], 0, 0, 3)) == 49


def test_error_25_radius_type_in_3d() -> None:
    assert err(circle([0.0, 0.0, 0.0], [10.0, 0.0, 0.0], 13.0, 2, 0, 3)) == 25


# ---------------------------------------------------------------------- vectorised rows


def test_table_rows_match_their_segments() -> None:
    # a mix of 2D and 3D lines and arcs evaluated in one call agrees with each segment,
    # including the exact end at s = length and the clipping beyond it
    segs: list[Segment] = [
        line([0.0, 0.0], [3.0, 4.0]),
        line([1.0, 2.0, 3.0], [4.0, 6.0, 3.0]),
    ]
    for r in (
        circle([10.0, 0.0], [0.0, 10.0], [0.0, 0.0], 1, 0, 2),
        circle([0.0, 0.0], [10.0, 0.0], -13.0, 2, 1, 2),
        circle(on_tilted(0), on_tilted(90), on_tilted(200), 0, 1, 3),
        circle(on_tilted(0), on_tilted(90), C3, 1, 3, 3),
    ):
        assert isinstance(r, Segment)
        segs.append(r)
    table = SegmentTable.of(segs).resized(len(segs) + 2)
    assert len(table) == len(segs) + 2
    fractions = np.array([0.0, 0.13, 0.5, 0.77, 1.0, 1.5])
    rows = np.repeat(np.arange(len(segs)), fractions.size)
    s = np.concatenate([seg.length * fractions for seg in segs])
    p = table.points(rows, s)
    tg = table.tangents(rows, s)
    for i, seg in enumerate(segs):
        k = seg.ndim
        block = slice(i * fractions.size, (i + 1) * fractions.size)
        np.testing.assert_allclose(p[block, :k], seg.points(s[block]), rtol=0, atol=1e-12)
        np.testing.assert_allclose(tg[block, :k], seg.tangent(s[block]), rtol=0, atol=1e-12)
        assert np.all(p[block, k:] == 0.0)
        # fractions 1.0 and 1.5 give the end point bit for bit
        assert p[block][4, :k].tolist() == seg.end.tolist()
        assert p[block][5, :k].tolist() == seg.end.tolist()
    # the two added rows are zero-length lines at the origin
    assert table.points(np.array([len(segs)]), np.array([1.0])).tolist() == [[0.0, 0.0, 0.0]]


# ----------------------------------------------------------------------- catalog facts


def test_error_numbers_and_enumerations_are_the_catalogs() -> None:
    cat = catalog()
    for e in CircleError:
        name = cat.motion_errors[e.value].name.lower()
        assert set(e.name.lower().split("_")) <= set(name.split()), (e, name)
    for enum, cat_name in ((CircleType, "CircleType"), (CircleDirection, "CircleDirection")):
        texts = {(v.text.lower().replace(" ", "_"), v.value) for v in cat.enum(cat_name).values}
        mine = {(name.lower(), int(m)) for name, m in enum.__members__.items()}
        assert mine == texts


def test_tolerance_point_is_where_the_straight_distance_to_the_end_reaches_it() -> None:
    # line (0,0) -> (3,4), length 5: within 1 of the end from s = 4
    ln = line([0.0, 0.0], [3.0, 4.0])
    assert ln.tolerance_point(1.0) == pytest.approx(4.0)
    assert ln.tolerance_point(7.0) == 0.0
    # quarter circle r = 10 CCW from (10, 0) to (0, 10): a chord of 10 spans 60 deg
    # (2 * 10 * sin 30 = 10), so the point is 30 deg along: s = 10 * (pi/2 - pi/3) = 10 pi/6,
    # at (10 cos 30, 10 sin 30) = (8.660, 5), whose distance to (0, 10) is sqrt(75 + 25) = 10
    q = circle([10.0, 0.0], [0.0, 10.0], [0.0, 0.0], 1, 1, 2)
    assert isinstance(q, Segment)
    s = q.tolerance_point(10.0)
    assert s == pytest.approx(10 * math.pi / 6)
    np.testing.assert_allclose(np.linalg.norm(q.points(np.array([s]))[0] - q.end), 10.0)
    # 15 is more than the chord (14.14): within it from the start
    assert q.tolerance_point(15.0) == 0.0
    # the 270 deg CW arc between the same points: 15 pi - 10 pi/3 (it is within 15 at the
    # start too, but leaves it)
    lg = circle([10.0, 0.0], [0.0, 10.0], [0.0, 0.0], 1, 0, 2)
    assert isinstance(lg, Segment)
    assert lg.tolerance_point(10.0) == pytest.approx(15 * math.pi - 10 * math.pi / 3)
    assert lg.tolerance_point(15.0) == pytest.approx(15 * math.pi - 20 * math.asin(0.75))
    # full circle r = 10: only a diameter (20) or more covers all of it
    f = circle([10.0, 0.0], [10.0, 0.0], [0.0, 0.0], 1, 1, 2)
    assert isinstance(f, Segment)
    assert f.tolerance_point(10.0) == pytest.approx(20 * math.pi - 10 * math.pi / 3)
    assert f.tolerance_point(20.0) == 0.0
    # the table gives the same per row
    table = SegmentTable.of([ln, q, lg, f])
    got = table.tolerance_points(np.array([0, 1, 2, 3, 1]), np.array([1.0, 10.0, 10.0, 20.0, 15]))
    np.testing.assert_allclose(
        got,
        [4.0, 10 * math.pi / 6, 15 * math.pi - 10 * math.pi / 3, 0.0, 0.0],
        atol=1e-12,
    )


# ------------------------------------------------------------------ random circles
# Circles generated from a known centre, radius, plane and angles; the geometry must give
# them back. 200 seeded cases each, angles at least 0.05 rad apart.


def _on(c: np.ndarray, r: float, e1: np.ndarray, e2: np.ndarray, t: float) -> np.ndarray:
    return c + r * (math.cos(t) * e1 + math.sin(t) * e2)


def _random_frame(rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
    while True:
        a, b = rng.normal(size=3), rng.normal(size=3)
        e1 = a / np.linalg.norm(a)
        b = b - (b @ e1) * e1
        if np.linalg.norm(b) > 0.1:
            return e1, b / np.linalg.norm(b)


def test_random_3d_via_circles_come_back() -> None:
    rng = np.random.default_rng(120)
    for _ in range(200):
        c = rng.uniform(-100, 100, 3)
        r = float(rng.uniform(0.05, 100))
        e1, e2 = _random_frame(rng)
        t_via = float(rng.uniform(0.05, 2 * math.pi - 0.1))
        t_end = float(rng.uniform(t_via + 0.05, 2 * math.pi - 0.05))
        seg = circle(
            _on(c, r, e1, e2, 0), _on(c, r, e1, e2, t_end), _on(c, r, e1, e2, t_via), 0, 0, 3
        )
        assert isinstance(seg, Segment)
        tol = 1e-6 * max(r, 1.0)
        np.testing.assert_allclose(seg.centre, c, rtol=0, atol=tol)
        assert seg.radius == pytest.approx(r, rel=1e-6)
        assert seg.sweep == pytest.approx(t_end, rel=1e-6)
        np.testing.assert_allclose(seg.normal, np.cross(e1, e2), atol=1e-6)
        s = np.linspace(0, seg.length, 101)
        np.testing.assert_allclose(
            seg.points(s),
            np.array([_on(c, r, e1, e2, t) for t in t_end * s / seg.length]),
            atol=tol,
        )
        assert seg.points(np.array([seg.length]))[0].tolist() == _on(c, r, e1, e2, t_end).tolist()


def test_random_2d_radius_arcs_follow_sign_and_direction() -> None:
    rng = np.random.default_rng(121)
    for _ in range(200):
        p0 = rng.uniform(-100, 100, 2)
        p1 = rng.uniform(-100, 100, 2)
        half = float(np.linalg.norm(p1 - p0)) / 2
        radius = float(rng.uniform(1.0, 3.0)) * half * float(rng.choice([-1.0, 1.0]))
        direction = int(rng.integers(0, 2))
        seg = circle(p0, p1, radius, 2, direction, 2)
        assert isinstance(seg, Segment)
        # through both points with radius |R|
        assert seg.radius == pytest.approx(abs(radius), rel=1e-9)
        assert np.linalg.norm(p1 - seg.centre) == pytest.approx(abs(radius), rel=1e-9)
        # sense from the direction (CW < 0, CCW > 0), size from the sign (R > 0 up to a
        # half turn, R < 0 at least a half turn)
        assert (seg.sweep > 0) == (direction == 1)
        if radius > 0:
            assert abs(seg.sweep) <= math.pi
        else:
            assert abs(seg.sweep) >= math.pi
        # the chord subtends 2 asin(half / |R|) on the short side
        short = 2 * math.asin(half / abs(radius))
        assert abs(seg.sweep) == pytest.approx(short if radius > 0 else 2 * math.pi - short)
