"""Path geometry of coordinated moves (interpreter/motion/path_geometry.py).

Expected values are hand geometry, worked in the comments.
"""

from __future__ import annotations

import math

import numpy as np

from interpreter.motion.path_geometry import SegmentTable, circle, line


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
