"""SPEC audit of section 5 (Motion) and 9.20-9.30 (session 6): one test per concrete SPEC
statement that tests/motion_programs/ and tests/motion/ do not already show through the
`logixst` command (they cover most of it; this file fills the gaps the acceptance suite
would probe: MCCM geometry run end to end, enumeration words, link breaking, PLCopen
output conventions, ...).

Each docstring quotes the SPEC item; the expected values are worked out by hand in the
comments from SPEC's words, the seeds and closed-form geometry, never taken from the
program's output.

Timing used throughout (SPEC 9.1-9.3): 1 ms scans, planner updates every 2 ms before the
scan starting then; an instruction executed in the scan at t = 0 takes effect at the update
t0 = 2 ms. A trace row holds the values at the end of its scan.
"""

from __future__ import annotations

import csv
import math
from pathlib import Path

import pytest

T0 = 0.002  # start update of an instruction executed in scan 0
CUP = 0.002  # coarse update period, s
# The circles of the MCCM tests have L = 20 pi and run at 10 units/s with 100 units/s^2: the
# quarter point s = 5 pi is reached at t0 + 0.1 + (5 pi - 0.5)/10 = 1.6228 s; the update
# nearest it (|dt| <= 1 ms: 0.01 units along the path)
QUARTER = round((T0 + 0.1 + (5 * math.pi - 0.5) / 10.0) / CUP) * CUP
F32 = 2e-4  # float32 rounding of positions below ~100 units


class Tr:
    """A `--trace` CSV read back: columns by watch expression, rows by scan."""

    def __init__(self, rows: list[list[str]]) -> None:
        self.names = rows[0]
        self.rows = [[float(x) for x in r] for r in rows[1:]]

    def col(self, name: str) -> list[float]:
        j = self.names.index(name)
        return [r[j] for r in self.rows]

    def at(self, t: float, name: str) -> float:
        """Value in the row of the scan starting at t seconds (1 ms scans)."""
        row = self.rows[round(t / 0.001)]
        assert abs(row[0] - t) < 1e-9, (t, row[0])
        return row[self.names.index(name)]

    def first(self, name: str, value: float) -> float:
        """Start time of the first scan whose row shows `name` == value."""
        j = self.names.index(name)
        for r in self.rows:
            if r[j] == value:
                return r[0]
        raise AssertionError(f"{name} never became {value}")

    def points(self, *names: str) -> list[tuple[float, ...]]:
        return list(zip(*(self.col(n) for n in names), strict=True))


def trace(st, src: str, scans: int, *watch: str) -> Tr:  # type: ignore[no-untyped-def]
    """Run `src` through `logixst run --trace --json`; it must run (exit 0)."""
    p = st.write("m.st", src)
    out = Path(st.tmp) / "trace.csv"
    argv = ["run", str(p), "--scans", str(scans), "--trace", str(out), "--json"]
    for w in watch:
        argv += ["--watch", w]
    r = st.cli(*argv)
    assert r.code == 0, (r.code, r.err, r.out[:2000])
    assert "Traceback" not in r.err
    with out.open(newline="") as fh:
        return Tr(list(csv.reader(fh)))


# ------------------------------------------------------------------------- MCCM geometry
# Two independent 2D systems XY and UV (and 3D XYZ / UVW): one run shows two cases.
# Vector profile of every MCCM below: V = 10 units/s, A = D = 100 units/s^2 (trapezoid):
# each ramp lasts V/A = 0.1 s and covers V^2/(2A) = 0.5 units, so a path of length L takes
# T = L/V + V/A; executed at t = 0 it starts at t0 = 2 ms and reaches the arc length s at
# t0 + 0.1 + (s - 0.5)/V while at speed.
CS_HEAD = """VAR
  X, Y, Z, U, V, W : AXIS_VIRTUAL := (MaximumSpeed := 100.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0);
  XY : COORDINATE_SYSTEM := (Axes := [X, Y], MaximumSpeed := 20.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0);
  UV : COORDINATE_SYSTEM := (Axes := [U, V], MaximumSpeed := 20.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0);
  c1, c2, c3, c4 : MOTION_INSTRUCTION;
  k : DINT;
"""
CS3_HEAD = """VAR
  X, Y, Z, U, V, W : AXIS_VIRTUAL := (MaximumSpeed := 100.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0);
  XYZ : COORDINATE_SYSTEM := (Axes := [X, Y, Z], MaximumSpeed := 20.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0);
  UVW : COORDINATE_SYSTEM := (Axes := [U, V, W], MaximumSpeed := 20.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0);
  c1, c2, c3, c4 : MOTION_INSTRUCTION;
  k : DINT;
"""


def mccm(cs: str, ctl: str, pos: str, ctype: int, aux: str, direction: int, mtype: int = 0) -> str:
    return (
        f"MCCM({cs}, {ctl}, {mtype}, {pos}, {ctype}, {aux}, {direction}, 10.0, unitspersec, 100.0, "
        "unitspersec2, 100.0, unitspersec2, trapezoidal, 100.0, 100.0, %oftime, 1, disabled, "
        "programmed, 0.0, 0, none, 0, 0);"
    )


def cs_prog(head: str, decls: str, body: str) -> str:
    return head + decls + "END_VAR\n" + body + "\nk := k + 1;\n"


def _pc_time(t0: float, length: float) -> float:
    """First update at or after the end of a path of `length` started at update t0."""
    return t0 + math.ceil((length / 10.0 + 0.1) / CUP - 1e-6) * CUP


def _xy_uv(st, decls: str, body: str):  # noqa: ANN001, ANN202
    """6.45 s of the 2D systems XY and UV (both run the same circle length, 20 pi)."""
    watch = [f"{a}.CommandPosition" for a in "XYUV"]
    return trace(
        st, cs_prog(CS_HEAD, decls, body), 6450, *watch, "c1.PC", "c2.PC", "c1.ER", "c2.ER"
    )


def _on_circle(pts: list[tuple[float, ...]], centre: tuple[float, ...], r: float) -> None:
    for p in pts:
        assert math.dist(p, centre) == pytest.approx(r, abs=F32), (p, centre, r)


def test_mccm_2d_cw_and_ccw_seen_from_plus_z(st) -> None:
    """SPEC 5: Direction 2D 0 CW, 1 CCW (CW/CCW seen from +Z of the XY plane); Circle Type 1
    Center."""
    # start (0, 0), centre (10, 0), end (20, 0): a half circle, L = 10 pi = 31.416.
    # Clockwise seen from +Z about (10, 0), the leftmost point moves up: CW passes (10, +10),
    # CCW passes (10, -10). PC at the first update >= t0 + 3.1416 + 0.1 = 3.2436 -> 3.244
    decls = "  e : REAL[2] := [20.0, 0.0];\n  ctr : REAL[2] := [10.0, 0.0];\n"
    body = (
        "IF k = 0 THEN " + mccm("XY", "c1", "e", 1, "ctr", 0) + mccm("UV", "c2", "e", 1, "ctr", 1)
    )
    body += " END_IF;"
    tr = trace(st, cs_prog(CS_HEAD, decls, body), 3300, "X.CommandPosition",
               "Y.CommandPosition", "U.CommandPosition", "V.CommandPosition", "c1.PC", "c2.PC",
               "c1.ER", "c2.ER")  # fmt: skip
    assert tr.at(0.0, "c1.ER") == 0 and tr.at(0.0, "c2.ER") == 0
    cw, ccw = (
        tr.points("X.CommandPosition", "Y.CommandPosition"),
        tr.points("U.CommandPosition", "V.CommandPosition"),
    )
    _on_circle(cw, (10.0, 0.0), 10.0)
    _on_circle(ccw, (10.0, 0.0), 10.0)
    assert min(y for _, y in cw) >= -F32 and max(y for _, y in cw) == pytest.approx(10.0, abs=1e-3)
    assert max(y for _, y in ccw) <= F32 and min(y for _, y in ccw) == pytest.approx(
        -10.0, abs=1e-3
    )
    assert cw[-1] == (20.0, 0.0) and ccw[-1] == (20.0, 0.0)
    assert tr.first("c1.PC", 1) == pytest.approx(_pc_time(T0, 10 * math.pi))
    assert tr.first("c2.PC", 1) == pytest.approx(_pc_time(T0, 10 * math.pi))


def test_mccm_2d_full_directions_make_one_revolution_back_to_the_start(st) -> None:
    """SPEC 5 / 9.28: Direction 2 CW Full, 3 CCW Full: the move is one whole revolution back
    to the start point (Position only helps define the circle)."""
    # start (0, 0), centre (10, 0), Position (20, 0): the circle of radius 10; L = 20 pi,
    # T = 2 pi + 0.1; PC at the first update >= 0.002 + 6.3832 -> 6.384.
    # A quarter of the way (s = 5 pi, at t0 + 0.1 + (5 pi - 0.5)/10 = 1.6228 s): CW at
    # (10, +10), CCW at (10, -10); half way (s = 10 pi, t = 3.2436 s) both at (20, 0)
    decls = "  e : REAL[2] := [20.0, 0.0];\n  ctr : REAL[2] := [10.0, 0.0];\n"
    body = (
        "IF k = 0 THEN " + mccm("XY", "c1", "e", 1, "ctr", 2) + mccm("UV", "c2", "e", 1, "ctr", 3)
    )
    body += " END_IF;"
    tr = _xy_uv(st, decls, body)
    row = QUARTER
    assert tr.at(row, "X.CommandPosition") == pytest.approx(10.0, abs=0.02)
    assert tr.at(row, "Y.CommandPosition") == pytest.approx(10.0, abs=1e-3)
    assert tr.at(row, "U.CommandPosition") == pytest.approx(10.0, abs=0.02)
    assert tr.at(row, "V.CommandPosition") == pytest.approx(-10.0, abs=1e-3)
    t_h = round((T0 + 0.1 + (10 * math.pi - 0.5) / 10.0) / CUP) * CUP
    assert tr.at(t_h, "X.CommandPosition") == pytest.approx(20.0, abs=1e-3)
    assert tr.at(t_h, "U.CommandPosition") == pytest.approx(20.0, abs=1e-3)
    for name in ("X", "Y", "U", "V"):
        assert tr.col(f"{name}.CommandPosition")[-1] == pytest.approx(0.0, abs=1e-6)
    assert tr.first("c1.PC", 1) == pytest.approx(_pc_time(T0, 20 * math.pi))
    assert tr.first("c2.PC", 1) == pytest.approx(_pc_time(T0, 20 * math.pi))


def test_mccm_2d_centre_end_equal_start_is_a_full_circle_cw_too(st) -> None:
    """SPEC 9.28: 2D Center with end = start is a full circle in any direction (CW 0 and
    CW Full 2 here; tests/motion_programs covers CCW)."""
    # start = end = (0, 0), centre (10, 0): L = 20 pi; CW: at the quarter point (10, +10)
    decls = "  e : REAL[2];\n  ctr : REAL[2] := [10.0, 0.0];\n"
    body = (
        "IF k = 0 THEN " + mccm("XY", "c1", "e", 1, "ctr", 0) + mccm("UV", "c2", "e", 1, "ctr", 2)
    )
    body += " END_IF;"
    tr = _xy_uv(st, decls, body)
    assert tr.at(0.0, "c1.ER") == 0 and tr.at(0.0, "c2.ER") == 0
    row = QUARTER
    for a, b in (("X", "Y"), ("U", "V")):
        assert tr.at(row, f"{a}.CommandPosition") == pytest.approx(10.0, abs=0.02)
        assert tr.at(row, f"{b}.CommandPosition") == pytest.approx(10.0, abs=1e-3)
        _on_circle(tr.points(f"{a}.CommandPosition", f"{b}.CommandPosition"), (10.0, 0.0), 10.0)
    assert tr.first("c1.PC", 1) == pytest.approx(_pc_time(T0, 20 * math.pi))
    assert tr.first("c2.PC", 1) == pytest.approx(_pc_time(T0, 20 * math.pi))


def test_mccm_negative_radius_takes_the_long_arc(st) -> None:
    """SPEC 5: Circle Type 2 Radius: radius > 0 arc <= 180 deg, < 0 arc >= 180 deg."""
    # (0, 0) -> (10, 10), R = -10. The two circles of radius 10 through both points have
    # centres (10, 0) and (0, 10).
    # CW (XY): about (0, 10) the start is the bottom and the end the right point; clockwise
    #   bottom -> left -> top -> right is 270 deg: the long arc, through (-10, 10).
    # CCW (UV): about (10, 0) the start is the left point and the end the top; counter-
    #   clockwise left -> bottom -> right -> top is 270 deg, through (10, -10) and (20, 0).
    # L = 1.5 pi * 10 = 15 pi; PC at the first update >= 0.002 + 4.7124 + 0.1 -> 4.816
    decls = "  e : REAL[2] := [10.0, 10.0];\n"
    body = (
        "IF k = 0 THEN "
        + mccm("XY", "c1", "e", 2, "-10.0", 0)
        + mccm("UV", "c2", "e", 2, "-10.0", 1)
    )
    body += " END_IF;"
    tr = trace(st, cs_prog(CS_HEAD, decls, body), 4850, "X.CommandPosition",
               "Y.CommandPosition", "U.CommandPosition", "V.CommandPosition", "c1.PC", "c2.PC")  # fmt: skip
    cw = tr.points("X.CommandPosition", "Y.CommandPosition")
    ccw = tr.points("U.CommandPosition", "V.CommandPosition")
    _on_circle(cw, (0.0, 10.0), 10.0)
    _on_circle(ccw, (10.0, 0.0), 10.0)
    assert min(x for x, _ in cw) == pytest.approx(-10.0, abs=1e-3)
    assert min(y for _, y in ccw) == pytest.approx(-10.0, abs=1e-3)
    assert max(x for x, _ in ccw) == pytest.approx(20.0, abs=1e-3)
    assert cw[-1] == (10.0, 10.0) and ccw[-1] == (10.0, 10.0)
    assert tr.first("c1.PC", 1) == pytest.approx(_pc_time(T0, 15 * math.pi))
    assert tr.first("c2.PC", 1) == pytest.approx(_pc_time(T0, 15 * math.pi))


def test_mccm_exact_semicircle_radius_is_valid_for_both_signs(st) -> None:
    """SPEC 9.28: an exact semicircle with Radius type (|R| = chord/2) is valid for both
    signs."""
    # (0, 0) -> (20, 0), |R| = 10 = chord / 2: the only circle has centre (10, 0); CW (0)
    # passes the top (10, 10) for +10 and -10 alike; L = 10 pi
    decls = "  e : REAL[2] := [20.0, 0.0];\n"
    body = (
        "IF k = 0 THEN "
        + mccm("XY", "c1", "e", 2, "10.0", 0)
        + mccm("UV", "c2", "e", 2, "-10.0", 0)
    )
    body += " END_IF;"
    tr = trace(st, cs_prog(CS_HEAD, decls, body), 3300, "X.CommandPosition",
               "Y.CommandPosition", "U.CommandPosition", "V.CommandPosition", "c1.PC", "c2.PC",
               "c1.ER", "c2.ER")  # fmt: skip
    assert tr.at(0.0, "c1.ER") == 0 and tr.at(0.0, "c2.ER") == 0
    for a, b in (("X", "Y"), ("U", "V")):
        pts = tr.points(f"{a}.CommandPosition", f"{b}.CommandPosition")
        _on_circle(pts, (10.0, 0.0), 10.0)
        assert max(y for _, y in pts) == pytest.approx(10.0, abs=1e-3)
        assert pts[-1] == (20.0, 0.0)
    assert tr.first("c1.PC", 1) == pytest.approx(_pc_time(T0, 10 * math.pi))
    assert tr.first("c2.PC", 1) == pytest.approx(_pc_time(T0, 10 * math.pi))


@pytest.mark.parametrize(
    ("decls", "call", "err"),
    [
        # via type with end = start (2D): 45
        ("  e : REAL[2];\n  a : REAL[2] := [10.0, 10.0];\n", ("e", 0, "a", 0), 45),
        # radius type with end = start: 45
        ("  e : REAL[2];\n", ("e", 2, "10.0", 0), 45),
        # centre (10, 0): R1 = |start - c| = 10, R2 = |(20, 10) - c| = 14.14;
        # |R1 - R2| = 4.14 > 0.15 * 10 = 1.5: 46
        ("  e : REAL[2] := [20.0, 10.0];\n  a : REAL[2] := [10.0, 0.0];\n", ("e", 1, "a", 0), 46),
        # via point on the start point: every circle through start and end passes it, so
        # no single circle is defined: 47 (Circular Infinite Solution, the Logix table)
        ("  e : REAL[2] := [20.0, 0.0];\n  a : REAL[2];\n", ("e", 0, "a", 0), 47),
        # radius below 0.001: 49
        ("  e : REAL[2] := [10.0, 10.0];\n", ("e", 2, "0.0005", 0), 49),
        # chord |(10, 10)| = 14.14 > 2 |R| = 10: the radius cannot span the points: 49
        ("  e : REAL[2] := [10.0, 10.0];\n", ("e", 2, "5.0", 0), 49),
        ("  e : REAL[2] := [10.0, 10.0];\n", ("e", 2, "-5.0", 1), 49),
    ],
)
def test_mccm_geometry_errors(st, decls: str, call: tuple, err: int) -> None:  # type: ignore[type-arg]
    """SPEC 5: geometry errors (44..49) 45 end = start where not allowed, 46 start/end radius
    mismatch (|R1-R2| > 0.15 R1), 47 via point on the start, 49 radius too small (< 0.001 or cannot span the points); reported
    in the executing scan (ER, no DN), nothing moves."""
    pos, ctype, aux, direction = call
    body = "IF k = 0 THEN " + mccm("XY", "c1", pos, ctype, aux, direction) + " END_IF;"
    tr = trace(st, cs_prog(CS_HEAD, decls, body), 10, "c1.ER", "c1.ERR", "c1.DN", "c1.IP",
               "X.CommandPosition", "Y.CommandPosition")  # fmt: skip
    assert [tr.at(0.0, n) for n in ("c1.ER", "c1.ERR", "c1.DN", "c1.IP")] == [1, err, 0, 0]
    assert tr.col("X.CommandPosition")[-1] == 0.0 and tr.col("Y.CommandPosition")[-1] == 0.0


def test_mccm_radius_mismatch_within_15_percent_is_accepted(st) -> None:
    """SPEC 5: 46 only when |R1-R2| > 0.15 R1: a smaller mismatch runs to the end point."""
    # centre (10, 0): R1 = 10, end (20, 5): R2 = sqrt(100 + 25) = 11.18, |R1 - R2| = 1.18
    # <= 1.5: no error, and the move ends exactly at the programmed end point
    decls = "  e : REAL[2] := [20.0, 5.0];\n  a : REAL[2] := [10.0, 0.0];\n"
    body = "IF k = 0 THEN " + mccm("XY", "c1", "e", 1, "a", 0) + " END_IF;"
    tr = trace(st, cs_prog(CS_HEAD, decls, body), 4000, "c1.ER", "c1.PC",
               "X.CommandPosition", "Y.CommandPosition")  # fmt: skip
    assert tr.at(0.0, "c1.ER") == 0 and tr.col("c1.PC")[-1] == 1
    assert tr.col("X.CommandPosition")[-1] == pytest.approx(20.0, abs=1e-5)
    assert tr.col("Y.CommandPosition")[-1] == pytest.approx(5.0, abs=1e-5)


def test_mccm_center_incremental_is_relative_to_the_start_for_both_move_types(st) -> None:
    """SPEC 5: Circle Type 3 Center Incremental (the centre counted from the start point
    whatever the Move Type); Move Type 1 Incremental with Center counts the centre and the end
    from the start too."""
    # MCLM to (10, 0) first on both systems (L = 10, T = 1.1 s, done by 1.104 s); at
    # k = 1200 (t = 1.2 s) from (10, 0):
    #   XY: Move Type 0, Center Incremental [10, 0], Position (30, 0): centre (20, 0)
    #   UV: Move Type 1, Center [10, 0], Position [20, 0]: centre (20, 0), end (30, 0)
    # both the CW half circle (10, 0) -> (20, 10) -> (30, 0), L = 10 pi, starting at the
    # update 1.202 s: PC at the first update >= 1.202 + 3.2416 -> 4.444
    decls = (
        "  p : REAL[2] := [10.0, 0.0];\n  e1 : REAL[2] := [30.0, 0.0];\n"
        "  e2 : REAL[2] := [20.0, 0.0];\n  a : REAL[2] := [10.0, 0.0];\n"
    )
    line = (
        "MCLM({cs}, {c}, 0, p, 10.0, unitspersec, 100.0, unitspersec2, 100.0, unitspersec2, "
        "trapezoidal, 100.0, 100.0, %oftime, 1, disabled, programmed, 0.0, 0, none, 0, 0);"
    )
    body = (
        "IF k = 0 THEN " + line.format(cs="XY", c="c3") + line.format(cs="UV", c="c4") + " END_IF;\n"
        "IF k = 1200 THEN " + mccm("XY", "c1", "e1", 3, "a", 0, 0)
        + mccm("UV", "c2", "e2", 1, "a", 0, 1) + " END_IF;"
    )  # fmt: skip
    tr = trace(st, cs_prog(CS_HEAD, decls, body), 4500, "X.CommandPosition",
               "Y.CommandPosition", "U.CommandPosition", "V.CommandPosition", "c1.PC", "c2.PC",
               "c1.ER", "c2.ER")  # fmt: skip
    assert tr.at(1.2, "c1.ER") == 0 and tr.at(1.2, "c2.ER") == 0
    for a, b in (("X", "Y"), ("U", "V")):
        pts = tr.points(f"{a}.CommandPosition", f"{b}.CommandPosition")[1200:]
        _on_circle(pts, (20.0, 0.0), 10.0)
        assert max(y for _, y in pts) == pytest.approx(10.0, abs=1e-3)
        assert pts[-1] == (30.0, 0.0)
    assert tr.first("c1.PC", 1) == pytest.approx(_pc_time(1.202, 10 * math.pi))
    assert tr.first("c2.PC", 1) == pytest.approx(_pc_time(1.202, 10 * math.pi))


def test_mccm_3d_shortest_and_longest(st) -> None:
    """SPEC 5: 3 primary axes; 3D Direction 0 Shortest, 1 Longest (Circle Type Center)."""
    # start (0, 0, 0), centre (10, 0, 0), end (10, 0, 10): a circle of radius 10 in the XZ
    # plane. Shortest: the 90 deg arc through c + 10 (-1, 0, 1)/sqrt 2 = (2.93, 0, 7.07),
    # L = 5 pi, PC at the first update >= 0.002 + 1.5708 + 0.1 -> 1.674.
    # Longest: the 270 deg arc the other way round, through (10, 0, -10) and (20, 0, 0),
    # L = 15 pi, PC -> 4.816
    decls = "  e : REAL[3] := [10.0, 0.0, 10.0];\n  a : REAL[3] := [10.0, 0.0, 0.0];\n"
    body = "IF k = 0 THEN " + mccm("XYZ", "c1", "e", 1, "a", 0) + mccm("UVW", "c2", "e", 1, "a", 1)
    body += " END_IF;"
    names = [f"{n}.CommandPosition" for n in "XYZUVW"]
    tr = trace(st, cs_prog(CS3_HEAD, decls, body), 4850, *names, "c1.PC", "c2.PC", "c1.ER",
               "c2.ER")  # fmt: skip
    assert tr.at(0.0, "c1.ER") == 0 and tr.at(0.0, "c2.ER") == 0
    short, long_ = tr.points(*names[:3]), tr.points(*names[3:])
    _on_circle(short, (10.0, 0.0, 0.0), 10.0)
    _on_circle(long_, (10.0, 0.0, 0.0), 10.0)
    assert all(abs(p[1]) < 1e-9 for p in short + long_)
    assert min(p[2] for p in short) >= -F32 and max(p[0] for p in short) <= 10.0 + F32
    assert min(p[2] for p in long_) == pytest.approx(-10.0, abs=1e-3)
    assert max(p[0] for p in long_) == pytest.approx(20.0, abs=1e-3)
    assert short[-1] == (10.0, 0.0, 10.0) and long_[-1] == (10.0, 0.0, 10.0)
    assert tr.first("c1.PC", 1) == pytest.approx(_pc_time(T0, 5 * math.pi))
    assert tr.first("c2.PC", 1) == pytest.approx(_pc_time(T0, 15 * math.pi))


def test_mccm_3d_full_circles(st) -> None:
    """SPEC 5 / 9.28: 3D Direction 2 Shortest Full, 3 Longest Full: one whole revolution
    back to the start point; Position fixes the circle and which way round is "shortest"."""
    # the circle of the test above; L = 20 pi, PC -> 6.384; at the quarter point
    # (s = 5 pi, t = 1.6228 s) Shortest Full is at the Position (10, 0, 10) (the short way
    # first), Longest Full at the opposite side (10, 0, -10)
    decls = "  e : REAL[3] := [10.0, 0.0, 10.0];\n  a : REAL[3] := [10.0, 0.0, 0.0];\n"
    body = "IF k = 0 THEN " + mccm("XYZ", "c1", "e", 1, "a", 2) + mccm("UVW", "c2", "e", 1, "a", 3)
    body += " END_IF;"
    names = [f"{n}.CommandPosition" for n in "XYZUVW"]
    tr = trace(st, cs_prog(CS3_HEAD, decls, body), 6450, *names, "c1.PC", "c2.PC")
    row = QUARTER
    assert tr.at(row, "X.CommandPosition") == pytest.approx(10.0, abs=0.02)
    assert tr.at(row, "Z.CommandPosition") == pytest.approx(10.0, abs=1e-3)
    assert tr.at(row, "U.CommandPosition") == pytest.approx(10.0, abs=0.02)
    assert tr.at(row, "W.CommandPosition") == pytest.approx(-10.0, abs=1e-3)
    for n in names:
        assert tr.col(n)[-1] == pytest.approx(0.0, abs=1e-6)
    assert tr.first("c1.PC", 1) == pytest.approx(_pc_time(T0, 20 * math.pi))
    assert tr.first("c2.PC", 1) == pytest.approx(_pc_time(T0, 20 * math.pi))


def test_mccm_3d_via_point_decides_the_way_round(st) -> None:
    """SPEC 5: Circle Type 0 Via in 3D: the arc passes the via point."""
    # (0, 0, 0) -> (20, 0, 0) via (10, 7.0710678, 7.0710678), 10 from (10, 0, 0): the circle
    # has that centre, radius 10, and lies in the plane y = z; the half circle through the via;
    # L = 10 pi, half way (t = 0.002 + 0.1 + (5 pi - 0.5)/10 = 1.6228 s) at the via point
    decls = "  e : REAL[3] := [20.0, 0.0, 0.0];\n  a : REAL[3] := [10.0, 7.0710678, 7.0710678];\n"
    body = "IF k = 0 THEN " + mccm("XYZ", "c1", "e", 0, "a", 0) + " END_IF;"
    names = [f"{n}.CommandPosition" for n in "XYZ"]
    tr = trace(st, cs_prog(CS3_HEAD, decls, body), 3300, *names, "c1.PC", "c1.ER")
    assert tr.at(0.0, "c1.ER") == 0
    pts = tr.points(*names)
    _on_circle(pts, (10.0, 0.0, 0.0), 10.0)
    assert all(abs(p[1] - p[2]) < F32 for p in pts)
    row = QUARTER
    assert tr.at(row, "Y.CommandPosition") == pytest.approx(7.0711, abs=1e-3)
    assert pts[-1] == (20.0, 0.0, 0.0)
    assert tr.first("c1.PC", 1) == pytest.approx(_pc_time(T0, 10 * math.pi))


@pytest.mark.parametrize(
    ("e", "a", "ctype", "err"),
    [
        # 3D centre collinear with start and end: no plane: 44
        ("[20.0, 0.0, 0.0]", "[10.0, 0.0, 0.0]", 1, 44),
        # 3D centre with end = start: 45 (only 2D allows it)
        ("[0.0, 0.0, 0.0]", "[10.0, 0.0, 0.0]", 1, 45),
        # 3D via collinear: 44
        ("[20.0, 0.0, 0.0]", "[10.0, 0.0, 0.0]", 0, 44),
        # Radius type in a 3D system: the seed's circle table makes Radius 2D only, and its
        # validation error there is 25 (Illegal Instruction)
        ("[20.0, 0.0, 0.0]", "[10.0, 0.0, 0.0]", 2, 25),
    ],
)
def test_mccm_3d_geometry_errors(st, e: str, a: str, ctype: int, err: int) -> None:
    """SPEC 5: 44 collinear, 45 end = start where not allowed (3D Center); Radius is 2D only
    (MCCM seed)."""
    decls = f"  e : REAL[3] := {e};\n  a : REAL[3] := {a};\n"
    body = "IF k = 0 THEN " + mccm("XYZ", "c1", "e", ctype, "a", 0) + " END_IF;"
    tr = trace(st, cs_prog(CS3_HEAD, decls, body), 4, "c1.ER", "c1.ERR", "c1.DN")
    assert [tr.at(0.0, n) for n in ("c1.ER", "c1.ERR", "c1.DN")] == [1, err, 0]


def test_coordinate_system_tolerance_defaults(st) -> None:
    """SPEC 9.28: COORDINATE_SYSTEM members CommandTolerance and ActualTolerance default to
    0.1 and 0.01 units."""
    src = cs_prog(CS_HEAD, "", "")
    r = st.run(src, "XY.CommandTolerance", "XY.ActualTolerance")
    assert r.code == 0, r.err
    assert r.tags["XY.CommandTolerance"] == pytest.approx(0.1)
    assert r.tags["XY.ActualTolerance"] == pytest.approx(0.01)


# ------------------------------------------------------------------------- MATC / MCCP
MATC_HEAD = """VAR
  A, B : AXIS_VIRTUAL := (MaximumSpeed := 1000.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0);
  c1, c2, c3, c4, cc : MOTION_INSTRUCTION;
  k : DINT;
"""


def test_matc_contribution_is_relative_to_the_profile_start_value(st) -> None:
    """SPEC 5: MATC position contribution `dir * DistanceScaling * (P(t / TimeScaling) -
    P(0))` added to the command position; 9.22 Continuous: each pass adds P(end) - P(0)."""
    # profile (0, 5) (1, 15): P(0) = 5, net 10 per pass; the axes start at 0 and do not jump
    # to 5. A: Same, DS 2, TS 1, Once: 2 (P(t) - 5) = 20 t, held at 20 after 1 s.
    # B: Opposite, DS 1, TS 0.5, Continuous: -(P(2t) - 5) per pass, passes of 0.5 s adding
    # -10 each: -20 t. Cams start at t0 = 2 ms; t counts from there.
    decls = """  off : CAM_PROFILE[2] := [(Master := 0.0, Slave := 5.0, SegmentType := 0),
                           (Master := 1.0, Slave := 15.0, SegmentType := 0)];
"""
    body = """IF k = 0 THEN
  MATC(A, c1, 0, off, 2.0, 1.0, once, immediate, 0.0, none, timedrivenmode);
  MATC(B, c2, 1, off, 1.0, 0.5, continuous, immediate, 0.0, none, timedrivenmode);
END_IF;"""
    tr = trace(st, cs_prog(MATC_HEAD, decls, body), 1300, "A.CommandPosition",
               "B.CommandPosition")  # fmt: skip
    for t in (0.0, 0.002, 0.252, 0.502, 0.752, 1.002, 1.2, 1.298):  # update instants
        a = 20.0 * min(max(t - T0, 0.0), 1.0)
        b = -20.0 * max(t - T0, 0.0)
        assert tr.at(t, "A.CommandPosition") == pytest.approx(a, abs=1e-4), t
        assert tr.at(t, "B.CommandPosition") == pytest.approx(b, abs=1e-4), t


def test_matc_ended_by_a_stop_gives_its_profile_use_back(st) -> None:
    """SPEC 9.23: Profile Status +1 when a cam using it becomes active, -1 when it completes
    or is terminated; 9.26: MAS All ends time cams (IP and TimeCamStatus cleared, PC not set)
    -- here also MAS Time Cam (StopType 7)."""
    # lin calculated: Status 2; two continuous cams (A, B) in use: 4; MAS All on A at scan 100
    # (update 0.102): 3; MAS Time Cam on B at scan 200 (update 0.202): 2
    decls = """  lin : CAM_PROFILE[2] := [(Master := 0.0, Slave := 0.0, SegmentType := 0),
                           (Master := 1.0, Slave := 10.0, SegmentType := 0)];
"""
    body = """IF k = 0 THEN
  MATC(A, c1, 0, lin, 1.0, 1.0, continuous, immediate, 0.0, none, timedrivenmode);
  MATC(B, c2, 0, lin, 1.0, 1.0, continuous, immediate, 0.0, none, timedrivenmode);
END_IF;
IF k = 100 THEN MAS(A, c3, 0, 1, 1000.0, 0, 0, 0.0, 0); END_IF;
IF k = 200 THEN MAS(B, c4, 7, 1, 1000.0, 0, 0, 0.0, 0); END_IF;"""
    tr = trace(st, cs_prog(MATC_HEAD, decls, body), 300, "lin[0].Status", "c1.IP", "c1.PC",
               "c2.IP", "c2.PC", "A.TimeCamStatus", "B.TimeCamStatus")  # fmt: skip
    assert [tr.at(t, "lin[0].Status") for t in (0.05, 0.101, 0.102, 0.201, 0.202, 0.299)] == [
        4, 4, 3, 3, 2, 2,
    ]  # fmt: skip
    assert [tr.at(0.102, n) for n in ("c1.IP", "c1.PC", "A.TimeCamStatus")] == [0, 0, 0]
    assert [tr.at(0.202, n) for n in ("c2.IP", "c2.PC", "B.TimeCamStatus")] == [0, 0, 0]


def test_camming_ignores_the_axis_maximum_speed_and_accel(st) -> None:
    """SPEC 9.25: camming ignores the axis's maximum speed/accel (seed)."""
    # axis limits 1 unit/s and 1 unit/s^2; the cam asks for 10 units/s at once: followed
    # exactly, 10 (t - t0) for 1 s
    decls = """  C : AXIS_VIRTUAL := (MaximumSpeed := 1.0, MaximumAccel := 1.0, MaximumDecel := 1.0);
  lin : CAM_PROFILE[2] := [(Master := 0.0, Slave := 0.0, SegmentType := 0),
                           (Master := 1.0, Slave := 10.0, SegmentType := 0)];
"""
    body = "IF k = 0 THEN MATC(C, c1, 0, lin, 1.0, 1.0, once, immediate, 0.0, none, 0); END_IF;"
    tr = trace(st, cs_prog(MATC_HEAD, decls, body), 1100, "C.CommandPosition", "c1.ER",
               "c1.PC")  # fmt: skip
    assert tr.at(0.0, "c1.ER") == 0
    for t in (0.102, 0.502, 1.002):
        assert tr.at(t, "C.CommandPosition") == pytest.approx(10.0 * (t - T0), abs=1e-4)
    assert tr.at(1.002, "c1.PC") == 1


def test_mccp_cubic_run_meeting_a_linear_segment(st) -> None:
    """SPEC 9.20: cubic segments form a clamped cubic spline (position, velocity, acceleration
    continuous within the run) with the given start/end slopes; where a cubic run meets a
    linear segment the joint slope is the linear segment's slope. 9.21: MCCP(MotionControl,
    Cam, Length, StartSlope, EndSlope, CamProfile), DN in its scan, slopes ignored at linear
    ends."""
    # pts: (0, 0) cubic, (1, 1) cubic, (2, 3) linear, (3, 5): a cubic run on [0, 2] and a line
    # of slope 2 on [2, 3]. Slopes: m0 = StartSlope 0, m2 = 2 (the line's), m1 from equal
    # second derivatives at x = 1 (unit Hermite segments):
    #   6 (p0 - p1) + 2 m0 + 4 m1 = 6 (p2 - p1) - 4 m1 - 2 m2
    #   -> m1 = (6 (p2 - p0) - 2 m0 - 2 m2) / 8 = (18 - 0 - 4) / 8 = 1.75
    # Hermite at u = 0.5 (h00 = h01 = 0.5, h10 = 0.125, h11 = -0.125):
    #   P(0.5) = 0.5 * 0 + 0.125 * 0 + 0.5 * 1 - 0.125 * 1.75 = 0.28125
    #   P(1.5) = 0.5 * 1 + 0.125 * 1.75 + 0.5 * 3 - 0.125 * 2 = 1.96875
    #   P(2.5) = 3 + 2 * 0.5 = 4 (the EndSlope 9 is ignored: the end is linear)
    # lin2: two linear points with slopes 5 / 5: ignored, P(x) = 2 x
    # The cams (TS = DS = 1) start at t0 = 2 ms: P(x) is read at t = x + 0.002
    decls = """  pts : CAM[4] := [(Master := 0.0, Slave := 0.0, SegmentType := 1),
                   (Master := 1.0, Slave := 1.0, SegmentType := 1),
                   (Master := 2.0, Slave := 3.0, SegmentType := 0),
                   (Master := 3.0, Slave := 5.0, SegmentType := 0)];
  l2 : CAM[2] := [(Master := 0.0, Slave := 0.0, SegmentType := 0), (Master := 1.0, Slave := 2.0, SegmentType := 0)];
  prof : CAM_PROFILE[4];
  prof2 : CAM_PROFILE[2];
"""
    body = """IF k = 0 THEN
  MCCP(cc, pts, 4, 0.0, 9.0, prof);
  MCCP(c3, l2, 2, 5.0, 5.0, prof2);
  MATC(A, c1, 0, prof, 1.0, 1.0, once, immediate, 0.0, none, 0);
  MATC(B, c2, 0, prof2, 1.0, 1.0, once, immediate, 0.0, none, 0);
END_IF;"""
    tr = trace(st, cs_prog(MATC_HEAD, decls, body), 3100, "A.CommandPosition",
               "B.CommandPosition", "cc.DN", "c3.DN", "prof[0].Status")  # fmt: skip
    assert [tr.at(0.0, n) for n in ("cc.DN", "c3.DN")] == [1, 1]
    got = [tr.at(t, "A.CommandPosition") for t in (0.502, 1.002, 1.502, 2.002, 2.502, 3.002)]
    assert got == pytest.approx([0.28125, 1.0, 1.96875, 3.0, 4.0, 5.0], abs=1e-4)
    assert [tr.at(t, "B.CommandPosition") for t in (0.252, 0.502)] == pytest.approx(
        [0.5, 1.0], abs=1e-4
    )


# ------------------------------------------------------------------------- MDAC
MD_HEAD = """VAR
  big : CAM_PROFILE[2] := [(Master := 0.0, Slave := 0.0, SegmentType := 0),
                           (Master := 100.0, Slave := 200.0, SegmentType := 0)];
  M, M2, S, T, U : AXIS_VIRTUAL := (MaximumSpeed := 1000.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0);
  c1, c2, c3, c4, c5, c6 : MOTION_INSTRUCTION;
  G : MOTION_GROUP;
  k : DINT;
"""


def test_mdac_master_offset_move_type_by_text_and_number(st) -> None:
    """SPEC 5 / 9.24: MDAC Motion Type Master Offset Move(4), accepted as text
    `masteroffsetmove` and as the number; Master Reference Actual(0)/Command(1) as text or
    number. The MDAC is IP while its link stands."""
    body = (
        """IF k = 0 THEN MDAC(S, M, c1, masteroffsetmove, actual); MDAC(T, M2, c2, 4, 0); END_IF;"""
    )
    r = st.run(cs_prog(MD_HEAD, "", body), "c1.IP", "c1.ER", "c2.IP", "c2.ER", "c1.DN", scans=5)
    assert r.code == 0, r.err
    assert r.tags == {"c1.IP": True, "c1.ER": False, "c2.IP": True, "c2.ER": False, "c1.DN": True}


def test_mdac_links_broken_by_shutdowns_of_slave_or_master(st) -> None:
    """SPEC 5: MDAC link broken by MASD/MGSD on the slave, MASD/MGSD on the master; 9.24: a
    broken link clears the MDAC's IP."""
    # S <- M (c1), T <- M2 (c2), U <- M2 (c3). MASD on the slave S in scan 10: c1's IP
    # clears at the next update (0.012); MASD on the master M2 in scan 20: c2 and c3 clear at
    # 0.022. A second run: MGSD of the group in scan 10 breaks every link (0.012).
    body = """IF k = 0 THEN MDAC(S, M, c1, all, command); MDAC(T, M2, c2, all, command);
  MDAC(U, M2, c3, move, command); END_IF;
IF k = 10 THEN MASD(S, c4); END_IF;
IF k = 20 THEN MASD(M2, c5); END_IF;"""
    tr = trace(st, cs_prog(MD_HEAD, "", body), 30, "c1.IP", "c2.IP", "c3.IP")
    assert [tr.at(t, "c1.IP") for t in (0.0, 0.011, 0.012)] == [1, 1, 0]
    assert [tr.at(t, "c2.IP") for t in (0.0, 0.021, 0.022)] == [1, 1, 0]
    assert [tr.at(t, "c3.IP") for t in (0.0, 0.021, 0.022)] == [1, 1, 0]
    body = """IF k = 0 THEN MDAC(S, M, c1, all, command); END_IF;
IF k = 10 THEN MGSD(G, c4); END_IF;"""
    tr = trace(st, cs_prog(MD_HEAD, "", body), 20, "c1.IP")
    assert [tr.at(t, "c1.IP") for t in (0.0, 0.011, 0.012)] == [1, 1, 0]


def test_mdac_time_scaling_scales_master_distance(st) -> None:
    """SPEC 9.24: master distance counts from the master's position when the slave's
    master-driven motion starts; TimeScaling scales master distance in master-driven mode."""
    # master M jogs 10 units/s with accel 1e6 (at speed within the first update): it starts
    # at the update 0.002 and m(t) = 10 (t - 0.002) - 0.5e-5... taken as 10 (t - t0) within
    # 1e-4. The MATC (master-driven, TS 2, DS 1) runs big: P(x) = 2 x against master
    # distance d / TS: slave = 2 * d / 2 = d = m(t) - m(start). It is executed in scan 100
    # and starts at the update 0.102 where m = 1.0: slave = m(t) - 1.
    body = """IF k = 0 THEN
  MAJ(M, c2, forward, 10.0, unitspersec, 1000000.0, unitspersec2, 1000000.0, unitspersec2, trapezoidal, 0.0, 0.0, unitspersec3, disabled, programmed, 0.0, none);
  MDAC(S, M, c1, timecam, command);
END_IF;
IF k = 100 THEN MATC(S, c3, 0, big, 1.0, 2.0, continuous, immediate, 0.0, none, masterdrivenmode); END_IF;"""
    tr = trace(st, cs_prog(MD_HEAD, "", body), 600, "M.CommandPosition", "S.CommandPosition",
               "c3.ER")  # fmt: skip
    assert tr.at(0.1, "c3.ER") == 0
    m_start = tr.at(0.102, "M.CommandPosition")
    assert m_start == pytest.approx(1.0, abs=1e-4)
    for t in (0.102, 0.2, 0.4, 0.599):
        m = tr.at(t, "M.CommandPosition")
        assert tr.at(t, "S.CommandPosition") == pytest.approx(m - m_start, abs=1e-4), t


# ------------------------------------------------------------------------- PLCopen
PLC_HEAD = """VAR
  M : AXIS_VIRTUAL;
  S : AXIS_VIRTUAL := (ActualPosition := 7.0);
  mj : MOTION_INSTRUCTION;
  sel : MC_CamTableSelect;
  camIn : MC_CamIn;
  go : BOOL := TRUE;
  k : DINT;
  off : CAM[2] := [(Master := 0.0, Slave := 1.0, SegmentType := 0), (Master := 10.0, Slave := 3.0, SegmentType := 0)];
END_VAR
"""
PLC_JOG = (
    "IF k = 0 THEN MAJ(M, mj, forward, 10.0, unitspersec, 1000000.0, unitspersec2, 1000000.0, "
    "unitspersec2, trapezoidal, 0.0, 0.0, unitspersec3, disabled, programmed, 0.0, none); END_IF;\n"
)


def test_camin_start_mode_numbers_and_relative_offset(st) -> None:
    """SPEC 9.29: StartMode words absolute 0, relative 1, ... (the number works as the word);
    9.30: relative start: effective slave offset = SlaveOffset + the slave's position at
    coupling; MC_CamTableSelect gives Done and a CamTableID."""
    # OFF: CAM(x) = 1 + 0.2 x on [0, 10], non-periodic, MasterAbsolute, SlaveAbsolute FALSE
    # (the interaction table keeps relative relative). Slave at 7 when it couples,
    # SlaveOffset 2: Y = CAM(X) + 2 + 7 = 10 + 0.2 master
    src = PLC_HEAD + (
        "sel(Master := M, Slave := S, CamTable := off, Execute := go, Periodic := FALSE, "
        "MasterAbsolute := TRUE, SlaveAbsolute := FALSE);\n"
        "camIn(Master := M, Slave := S, Execute := go AND sel.Done, CamTableID := sel.CamTableID, "
        "StartMode := 1, SlaveOffset := 2.0);\n" + PLC_JOG + "k := k + 1;\n"
    )
    tr = trace(st, src, 600, "M.CommandPosition", "S.CommandPosition", "camIn.InSync",
               "camIn.Error", "sel.Done", "sel.Error", "sel.CamTableID")  # fmt: skip
    assert tr.at(0.0, "sel.Done") == 1 and tr.at(0.0, "sel.Error") == 0
    assert tr.at(0.0, "sel.CamTableID") != 0
    for t in (0.1, 0.3, 0.599):
        m = tr.at(t, "M.CommandPosition")
        assert tr.at(t, "S.CommandPosition") == pytest.approx(10.0 + 0.2 * m, abs=1e-4), t
        assert tr.at(t, "camIn.InSync") == 1 and tr.at(t, "camIn.Error") == 0


# ------------------------------------------------------------------------- MAOC
def test_maoc_cam_range_ends_are_inclusive(st) -> None:
    """SPEC 9.27: range ends inclusive: a cam armed at CamArm = CamEnd with the axis at rest is
    inside its range (locked, in process, no PC for a Once cam)."""
    src = """VAR
  A : AXIS_VIRTUAL;
  arm : MOTION_INSTRUCTION;
  cam : OUTPUT_CAM[1] := [(OutputBit := 0, LatchType := 1, UnlatchType := 1, Left := 10.0, Right := 20.0)];
  comp : OUTPUT_COMPENSATION[1];
  outw, inw, k : DINT;
END_VAR
IF k = 0 THEN MAOC(A, 0, arm, outw, inw, cam, 0.0, 100.0, comp, once, immediate, 0.0, 100.0, actual); END_IF;
k := k + 1;
"""
    r = st.run(src, "arm.ER", "arm.IP", "arm.PC", "A.OutputCamLockStatus", "A.OutputCamStatus",
               scans=10)  # fmt: skip
    assert r.code == 0, r.err
    assert r.tags == {
        "arm.ER": False,
        "arm.IP": True,
        "arm.PC": False,
        "A.OutputCamLockStatus": 1,
        "A.OutputCamStatus": 1,
    }


def test_mcs_with_no_system_decel_is_error_54_naming_the_system(st) -> None:
    """SPEC 9.26: MCS has MAS's operands with a coordinate system (StopType, ChangeDecel
    0 No / 1 Yes, DecelRate, ...). With ChangeDecel No the system's MaximumDecel is used; a
    system whose MaximumDecel is 0 cannot stop: error 54, and the MCCM seed's EXERR -1 (the
    coordinate system, not one of its axes). With ChangeDecel Yes the operand is used."""
    src = """VAR
  S, T, S2, T2 : AXIS_VIRTUAL := (MaximumSpeed := 100.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0);
  ST : COORDINATE_SYSTEM := (Axes := [S, T]);
  ST2 : COORDINATE_SYSTEM := (Axes := [S2, T2]);
  c1, c2 : MOTION_INSTRUCTION;
  k : DINT;
END_VAR
IF k = 0 THEN
  MCS(ST, c1, 0, 0, 0.0, 0, 0, 0.0, 0);
  MCS(ST2, c2, 0, 1, 100.0, 0, 0, 0.0, 0);
END_IF;
k := k + 1;
"""
    r = st.run(src, "c1.ER", "c1.ERR", "c1.EXERR", "c2.ER", "c2.DN", scans=3)
    assert r.code == 0, r.err
    assert r.tags == {"c1.ER": True, "c1.ERR": 54, "c1.EXERR": -1, "c2.ER": False, "c2.DN": True}


def test_mcs_all_stops_member_axes_and_breaks_links_at_the_next_update(st) -> None:
    """SPEC 9.26 / 9.3: MCS (MAS's operands with a coordinate system) StopType All also stops
    the single-axis motion of the system's axes -- and, per the MDAC seed, MCS All on the
    slave breaks its MDAC link while MCS Coordinated Move does not; all of it takes effect at
    the next planner update after the executing scan."""
    # S jogs at 10 units/s (accel 1000: at speed from 0.012). MCS All on ST = [S, T] in
    # scan 100: at the update 0.102 the jog's stop starts with S's MaximumDecel 1000, so
    # v(0.104) = 10 - 1000 * 0.002 = 8 and v = 0 from 0.112. MDAC S <- M (c1) breaks at
    # 0.102; MDAC S2 <- M (c2) survives MCS Coordinated Move on ST2.
    src = """VAR
  M, S, T, S2, T2 : AXIS_VIRTUAL := (MaximumSpeed := 100.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0);
  ST : COORDINATE_SYSTEM := (Axes := [S, T], MaximumDecel := 1000.0);
  ST2 : COORDINATE_SYSTEM := (Axes := [S2, T2], MaximumDecel := 1000.0);
  c1, c2, cj, cs1, cs2 : MOTION_INSTRUCTION;
  k : DINT;
END_VAR
IF k = 0 THEN
  MDAC(S, M, c1, all, command); MDAC(S2, M, c2, all, command);
  MAJ(S, cj, forward, 10.0, unitspersec, 1000.0, unitspersec2, 1000.0, unitspersec2, trapezoidal, 0.0, 0.0, unitspersec3, disabled, programmed, 0.0, none);
END_IF;
IF k = 100 THEN
  MCS(ST, cs1, all, no, 0.0, unitspersec2, no, 0.0, unitspersec3);
  MCS(ST2, cs2, coordinatedmove, no, 0.0, unitspersec2, no, 0.0, unitspersec3);
END_IF;
k := k + 1;
"""
    tr = trace(st, src, 130, "S.CommandVelocity", "cj.IP", "c1.IP", "c2.IP", "cs1.DN",
               "cs1.ER", "cs2.ER")  # fmt: skip
    assert [tr.at(0.1, n) for n in ("cs1.DN", "cs1.ER", "cs2.ER")] == [1, 0, 0]
    assert [tr.at(t, "S.CommandVelocity") for t in (0.1, 0.102, 0.104, 0.106)] == pytest.approx(
        [10.0, 10.0, 8.0, 6.0], abs=1e-4
    )
    assert tr.at(0.112, "S.CommandVelocity") == 0.0 and tr.at(0.101, "cj.IP") == 1
    assert tr.at(0.102, "cj.IP") == 0  # the stop ends the jog's process at once
    assert [tr.at(t, "c1.IP") for t in (0.101, 0.102)] == [1, 0]
    assert tr.at(0.129, "c2.IP") == 1


def test_pending_master_driven_cam_keeps_the_active_cams_master_and_mode(st) -> None:
    """SPEC 5: MATC Pending blends at the end of the current pass; masterdrivenmode uses the
    master distance from MDAC; pending master taken at the next slave motion start. The MDAC
    seed's example: MDAC1 (S <- M), MATC1 immediate, MDAC2 (S <- M2) while MATC1 moves, MATC2
    pending: MATC2 runs with MATC1's master M. A pending cam in another instruction mode than
    the active one is an error (MATC seed: both cams in the same mode; decision 0101: 105)."""
    # M jogs at 10 units/s, M2 at 20 units/s (accel 1e6: at speed within the first update),
    # both from the update 0.002, where MATC1 (master driven) starts too. p1: slave = 2 d on
    # d in [0, 1] master units, Once. MATC2 (same profile, pending) takes over at d = 1 with
    # the leftover distance, so with M the slave is 2 d for d in [0, 2] and then holds 4
    # (with M2 it would climb at 40 units/s instead of 20). MATC3 pending in time-driven mode
    # while a master-driven cam is active: ERR 105, no DN.
    src = """VAR
  p1 : CAM_PROFILE[2] := [(Master := 0.0, Slave := 0.0, SegmentType := 0), (Master := 1.0, Slave := 2.0, SegmentType := 0)];
  M, M2, S : AXIS_VIRTUAL := (MaximumSpeed := 1000.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0);
  c1, c2, c3, d1, d2, j1, j2 : MOTION_INSTRUCTION;
  k : DINT;
END_VAR
IF k = 0 THEN
  MAJ(M, j1, forward, 10.0, unitspersec, 1000000.0, unitspersec2, 1000000.0, unitspersec2, trapezoidal, 0.0, 0.0, unitspersec3, disabled, programmed, 0.0, none);
  MAJ(M2, j2, forward, 20.0, unitspersec, 1000000.0, unitspersec2, 1000000.0, unitspersec2, trapezoidal, 0.0, 0.0, unitspersec3, disabled, programmed, 0.0, none);
  MDAC(S, M, d1, timecam, command);
  MATC(S, c1, 0, p1, 1.0, 1.0, once, immediate, 0.0, none, masterdrivenmode);
END_IF;
IF k = 10 THEN
  MDAC(S, M2, d2, timecam, command);
  MATC(S, c2, 0, p1, 1.0, 1.0, once, pending, 0.0, none, masterdrivenmode);
END_IF;
IF k = 20 THEN MATC(S, c3, 0, p1, 1.0, 1.0, once, pending, 0.0, none, timedrivenmode); END_IF;
k := k + 1;
"""
    tr = trace(st, src, 300, "M.CommandPosition", "S.CommandPosition", "c1.PC", "c2.DN",
               "c2.ER", "c2.PC", "c3.ER", "c3.ERR", "c3.DN")  # fmt: skip
    assert [tr.at(0.01, n) for n in ("c2.DN", "c2.ER")] == [1, 0]
    assert [tr.at(0.02, n) for n in ("c3.ER", "c3.ERR", "c3.DN")] == [1, 105, 0]
    m0 = tr.at(0.002, "M.CommandPosition")
    for t in [0.002 * i for i in range(1, 150)]:
        d = tr.at(t, "M.CommandPosition") - m0
        assert tr.at(t, "S.CommandPosition") == pytest.approx(2.0 * min(d, 2.0), abs=1e-3), t
    assert tr.at(0.15, "c1.PC") == 1 and tr.at(0.15, "c2.PC") == 0
    assert tr.at(0.299, "c2.PC") == 1


def test_coordinated_move_on_an_axis_that_cannot_move_names_it(st) -> None:
    """SPEC 4 / 5: a drive axis moves only with its servo on (MSO); MCLM/MCCM on a system with
    a member axis whose servo is off or that is shut down fail like the single-axis moves
    (5 Servo Off State, 7 Shutdown State), with the MCCM seed's EXERR: the index of the
    offending axis in the coordinate system. Nothing moves. Decision 0140."""
    # XY = [X, Y] drives, only X switched on (MSO in scan 0, done at the update 0.002):
    # MCLM in scan 10 -> 5 with EXERR 1 (Y). UV = [U, V] virtual, U shut down by MASD in scan
    # 0: MCCM in scan 10 -> 7 with EXERR 0 (U). After MSO(Y) (scan 20) the MCLM runs (c5).
    src = """VAR
  X, Y : AXIS_CIP_DRIVE := (MaximumSpeed := 100.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0);
  U, V : AXIS_VIRTUAL := (MaximumSpeed := 100.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0);
  XY : COORDINATE_SYSTEM := (Axes := [X, Y], MaximumSpeed := 20.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0);
  UV : COORDINATE_SYSTEM := (Axes := [U, V], MaximumSpeed := 20.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0);
  c1, c2, c3, c4, c5, c6 : MOTION_INSTRUCTION;
  p : REAL[2] := [3.0, 4.0];
  ctr : REAL[2] := [1.5, 2.0];
  k : DINT;
END_VAR
IF k = 0 THEN MSO(X, c1); MASD(U, c2); END_IF;
IF k = 10 THEN
  MCLM(XY, c3, 0, p, 10.0, unitspersec, 100.0, unitspersec2, 100.0, unitspersec2, trapezoidal, 100.0, 100.0, %oftime, 1, disabled, programmed, 0.0, 0, none, 0, 0);
  MCCM(UV, c4, 0, p, 1, ctr, 0, 10.0, unitspersec, 100.0, unitspersec2, 100.0, unitspersec2, trapezoidal, 100.0, 100.0, %oftime, 1, disabled, programmed, 0.0, 0, none, 0, 0);
END_IF;
IF k = 20 THEN MSO(Y, c6); END_IF;
IF k = 30 THEN
  MCLM(XY, c5, 0, p, 10.0, unitspersec, 100.0, unitspersec2, 100.0, unitspersec2, trapezoidal, 100.0, 100.0, %oftime, 1, disabled, programmed, 0.0, 0, none, 0, 0);
END_IF;
k := k + 1;
"""
    tr = trace(st, src, 40, "c3.ER", "c3.ERR", "c3.EXERR", "c3.DN", "c4.ER", "c4.ERR",
               "c4.EXERR", "c4.DN", "c5.ER", "c5.DN", "X.CommandPosition",
               "U.CommandPosition")  # fmt: skip
    assert [tr.at(0.01, f"c3.{m}") for m in ("ER", "ERR", "EXERR", "DN")] == [1, 5, 1, 0]
    assert [tr.at(0.01, f"c4.{m}") for m in ("ER", "ERR", "EXERR", "DN")] == [1, 7, 0, 0]
    assert tr.at(0.029, "X.CommandPosition") == 0.0 and tr.at(0.039, "U.CommandPosition") == 0.0
    assert [tr.at(0.03, n) for n in ("c5.ER", "c5.DN")] == [0, 1]
    assert tr.at(0.039, "X.CommandPosition") > 0.0


def test_actual_tolerance_termination_waits_for_the_actual_position(st) -> None:
    """SPEC 5 / 9.28: termination types 0 (Actual Tolerance: PC once interpolation is done
    and the actual position is within the system's ActualTolerance) and 1 (No Settle: PC at
    the end of interpolation); status bits per the seed: ActualPosToleranceStatus for
    type 0 only, kept after the move, cleared (like CommandPosToleranceStatus) when a new
    move starts."""
    # drive axes (their actual position lags the command, SPEC 4), servo on from 0.002; both
    # moves (0,0) -> (3,4), L = 5, V 10, A 100: T = 0.6 s from the update 0.012, so the
    # interpolation ends at 0.612. XY: ActualTolerance 0.001, type 0; UV: type 1.
    # XY's second move (back to (0, 0)) executed in scan 700 starts at the update 0.702.
    src = """VAR
  X, Y, U, V : AXIS_CIP_DRIVE := (MaximumSpeed := 100.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0);
  XY : COORDINATE_SYSTEM := (Axes := [X, Y], ActualTolerance := 0.001, MaximumSpeed := 20.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0);
  UV : COORDINATE_SYSTEM := (Axes := [U, V], MaximumSpeed := 20.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0);
  c1, c2, c3, c4, c5, c6, c7 : MOTION_INSTRUCTION;
  p : REAL[2] := [3.0, 4.0];
  o : REAL[2];
  k : DINT;
END_VAR
IF k = 0 THEN MSO(X, c1); MSO(Y, c2); MSO(U, c3); MSO(V, c4); END_IF;
IF k = 10 THEN
  MCLM(XY, c5, 0, p, 10.0, unitspersec, 100.0, unitspersec2, 100.0, unitspersec2, trapezoidal, 100.0, 100.0, %oftime, 0, disabled, programmed, 0.0, 0, none, 0, 0);
  MCLM(UV, c6, 0, p, 10.0, unitspersec, 100.0, unitspersec2, 100.0, unitspersec2, trapezoidal, 100.0, 100.0, %oftime, 1, disabled, programmed, 0.0, 0, none, 0, 0);
END_IF;
IF k = 700 THEN
  MCLM(XY, c7, 0, o, 10.0, unitspersec, 100.0, unitspersec2, 100.0, unitspersec2, trapezoidal, 100.0, 100.0, %oftime, 0, disabled, programmed, 0.0, 0, none, 0, 0);
END_IF;
k := k + 1;
"""
    tr = trace(st, src, 720, "X.ActualPosition", "Y.ActualPosition", "X.CommandPosition",
               "Y.CommandPosition", "c5.PC", "c5.IP", "c6.PC", "XY.ActualPosToleranceStatus",
               "UV.ActualPosToleranceStatus", "XY.CommandPosToleranceStatus")  # fmt: skip
    assert tr.first("c6.PC", 1) == pytest.approx(0.612)  # no settle: the interpolation end
    # type 0: the first update from 0.612 on where |actual - (3, 4)| < 0.001
    settle = next(
        t
        for t in (0.612 + 0.002 * i for i in range(40))
        if math.hypot(tr.at(t, "X.ActualPosition") - 3.0, tr.at(t, "Y.ActualPosition") - 4.0)
        < 0.001
    )
    assert settle > 0.612  # the lag really is longer than the tolerance at the end
    assert tr.first("c5.PC", 1) == pytest.approx(settle)
    assert tr.at(settle - 0.001, "c5.IP") == 1
    assert tr.first("XY.ActualPosToleranceStatus", 1) == pytest.approx(settle)
    assert tr.at(0.701, "XY.ActualPosToleranceStatus") == 1  # kept after the move
    assert set(tr.col("UV.ActualPosToleranceStatus")) == {0.0}  # type 1 never sets it
    assert tr.at(0.701, "XY.CommandPosToleranceStatus") == 1
    # the next move starts at the update 0.702: both tolerance bits cleared
    assert [tr.at(0.702, n) for n in ("XY.ActualPosToleranceStatus",
                                      "XY.CommandPosToleranceStatus")] == [0, 0]  # fmt: skip


def test_mccm_full_circles_by_radius_and_by_via_point(st) -> None:
    """SPEC 9.28: with a Full direction the move is one whole revolution back to the start
    point (Position only helps define the circle) -- Radius type (Position any other point of
    the circle) and Via type (the via point decides the sense, Direction only says full)."""
    # XY: Radius +10 to Position (10, 10), CW Full (2): the circle of the short CW arc, centre
    # (10, 0) (see the radius test above); one revolution CW from (0, 0): at the quarter point
    # (10, 10). UV: Via (10, 10), Position (20, 0), CCW Full (3): the circle through the three
    # points has centre (10, 0); (0,0) -> (10,10) -> (20,0) turns clockwise, so the sense is
    # CW whatever the Direction: at the quarter point (10, 10) too. L = 20 pi for both.
    decls = "  e1 : REAL[2] := [10.0, 10.0];\n  e2 : REAL[2] := [20.0, 0.0];\n  a : REAL[2] := [10.0, 10.0];\n"
    body = (
        "IF k = 0 THEN " + mccm("XY", "c1", "e1", 2, "10.0", 2) + mccm("UV", "c2", "e2", 0, "a", 3)
    )
    body += " END_IF;"
    tr = _xy_uv(st, decls, body)
    assert tr.at(0.0, "c1.ER") == 0 and tr.at(0.0, "c2.ER") == 0
    row = QUARTER
    for a, b in (("X", "Y"), ("U", "V")):
        _on_circle(tr.points(f"{a}.CommandPosition", f"{b}.CommandPosition"), (10.0, 0.0), 10.0)
        assert tr.at(row, f"{a}.CommandPosition") == pytest.approx(10.0, abs=0.02)
        assert tr.at(row, f"{b}.CommandPosition") == pytest.approx(10.0, abs=1e-3)
        assert tr.col(f"{a}.CommandPosition")[-1] == pytest.approx(0.0, abs=1e-6)
        assert tr.col(f"{b}.CommandPosition")[-1] == pytest.approx(0.0, abs=1e-6)
    assert tr.first("c1.PC", 1) == pytest.approx(_pc_time(T0, 20 * math.pi))
    assert tr.first("c2.PC", 1) == pytest.approx(_pc_time(T0, 20 * math.pi))


def test_end_of_profile_is_one_scan_with_the_default_coarse_update(st) -> None:
    """SPEC 9.30: EndOfProfile is TRUE for one scan each time the profile end is reached --
    also when a planner update spans two scans (default 2 ms updates, 1 ms scans)."""
    # OFF periodic on [0, 10] with the master at 10 units/s from the update 0.002: the ends
    # are passed at master 10, 20, 30 (t ~ 1.002, 2.002, 3.002): three single-scan pulses
    src = PLC_HEAD + (
        "sel(Master := M, Slave := S, CamTable := off, Execute := go, Periodic := TRUE, "
        "MasterAbsolute := TRUE, SlaveAbsolute := TRUE);\n"
        "camIn(Master := M, Slave := S, Execute := go AND sel.Done, CamTableID := sel.CamTableID);\n"
        + PLC_JOG
        + "k := k + 1;\n"
    )
    tr = trace(st, src, 3500, "camIn.EndOfProfile", "camIn.InSync")
    col = tr.col("camIn.EndOfProfile")
    pulses = [i * 0.001 for i, v in enumerate(col) if v == 1]
    assert len(pulses) == 3, pulses
    for t, expect in zip(pulses, (1.0, 2.0, 3.0), strict=True):
        assert t == pytest.approx(expect, abs=0.005)


def test_mdac_one_slave_with_a_master_per_motion_type(st) -> None:
    """SPEC 5: MDAC assigns a master for a Motion Type; the MDAC seed: one slave may follow
    master X for its moves and master Y for its jogs at the same time (AC on both MDACs)."""
    # M jogs at 10 units/s, M2 at 20 (both at speed within the first update). S: a master-
    # driven MAM at 1 unit per master unit (MDAC Move -> M) and a master-driven MAJ at 1 unit
    # per master unit (MDAC Jog -> M2), superimposed (Merge Disabled): S runs at 10 + 20 = 30
    src = """VAR
  M, M2, S : AXIS_VIRTUAL := (MaximumSpeed := 1000.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0);
  c1, c2, c3, c4, j1, j2 : MOTION_INSTRUCTION;
  k : DINT;
END_VAR
IF k = 0 THEN
  MAJ(M, j1, forward, 10.0, unitspersec, 1000000.0, unitspersec2, 1000000.0, unitspersec2, trapezoidal, 0.0, 0.0, unitspersec3, disabled, programmed, 0.0, none);
  MAJ(M2, j2, forward, 20.0, unitspersec, 1000000.0, unitspersec2, 1000000.0, unitspersec2, trapezoidal, 0.0, 0.0, unitspersec3, disabled, programmed, 0.0, none);
  MDAC(S, M, c1, move, command); MDAC(S, M2, c2, jog, command);
END_IF;
IF k = 10 THEN
  MAM(S, c3, incremental, 1000.0, 1.0, unitspermasterunit, 1000000.0, unitspermasterunit2, 1000000.0, unitspermasterunit2, trapezoidal, 0.0, 0.0, unitspermasterunit3, disabled, programmed, 0.0, none, 0, 0);
  MAJ(S, c4, forward, 1.0, unitspermasterunit, 1000000.0, unitspermasterunit2, 1000000.0, unitspermasterunit2, trapezoidal, 0.0, 0.0, unitspermasterunit3, disabled, programmed, 0.0, none);
END_IF;
k := k + 1;
"""
    r = st.run(src, "S.CommandVelocity", "c1.AC", "c2.AC", "c3.IP", "c4.IP", "c3.ER", "c4.ER",
               scans=100)  # fmt: skip
    assert r.code == 0, r.err
    assert r.tags["S.CommandVelocity"] == pytest.approx(30.0, abs=1e-4)
    assert {n: r.tags[n] for n in ("c1.AC", "c2.AC", "c3.IP", "c4.IP", "c3.ER", "c4.ER")} == {
        "c1.AC": True, "c2.AC": True, "c3.IP": True, "c4.IP": True, "c3.ER": False,
        "c4.ER": False,
    }  # fmt: skip


def test_mas_all_on_a_member_axis_completes_when_the_path_is_at_rest(st) -> None:
    """SPEC 5 / 9.26: MAS All stops all motion of the axis; on a member axis of a coordinate
    system that is the path (brought to rest along it with the system's MaximumDecel, decision
    0125), and the MAS completes (PC, IP cleared) when the axis is at rest, with the axis's
    StoppingStatus set meanwhile -- not at the update where the stop starts. MGS likewise."""
    # (0,0) -> (30,40) at 10 units/s; MAS All on X in scan 1000: from the update 1.002 the
    # path decelerates at the system's MaximumDecel 100: 10/100 = 0.1 s, at rest at 1.102.
    # The same with MGS on the declared group in a second system of the same group.
    src = """VAR
  G : MOTION_GROUP;
  X, Y, U, V : AXIS_VIRTUAL := (MaximumSpeed := 100.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0);
  XY : COORDINATE_SYSTEM := (Axes := [X, Y], MaximumSpeed := 20.0, MaximumAccel := 1000.0, MaximumDecel := 100.0);
  c1, c2 : MOTION_INSTRUCTION;
  p : REAL[2] := [30.0, 40.0];
  k : DINT;
END_VAR
IF k = 0 THEN MCLM(XY, c1, 0, p, 10.0, unitspersec, 100.0, unitspersec2, 100.0, unitspersec2, trapezoidal, 100.0, 100.0, %oftime, 1, disabled, programmed, 0.0, 0, none, 0, 0); END_IF;
IF k = 1000 THEN {stop} END_IF;
k := k + 1;
"""
    for stop in ("MAS(X, c2, all, no, 0.0, unitspersec2, no, 0.0, unitspersec3);",
                 "MGS(G, c2, programmed);"):  # fmt: skip
        tr = trace(st, src.replace("{stop}", stop), 1150, "XY.VectorCommandVelocity", "c1.IP",
                   "c2.IP", "c2.PC", "X.StoppingStatus")  # fmt: skip
        assert [tr.at(1.0, n) for n in ("c2.IP", "c2.PC")] == [1, 0], stop
        assert tr.at(1.05, "XY.VectorCommandVelocity") == pytest.approx(
            5.2, abs=1e-4
        )  # 10 - 100 * 0.048
        assert [tr.at(1.05, n) for n in ("c1.IP", "c2.IP", "c2.PC", "X.StoppingStatus")] == [
            0, 1, 0, 1,
        ], stop  # fmt: skip
        assert [tr.at(t, "XY.VectorCommandVelocity") for t in (1.1, 1.102)] == pytest.approx(
            [0.2, 0.0], abs=1e-4
        )
        assert tr.first("c2.PC", 1) == pytest.approx(1.102), stop
        assert [tr.at(1.102, n) for n in ("c2.IP", "X.StoppingStatus")] == [0, 0], stop


def test_move_transition_status_only_off_the_path(st) -> None:
    """SPEC 5: MCCM/MCLM status bits per the seed. MoveTransitionStatus: set when a Command
    Tolerance / No Decel termination is satisfied and the next move blends in -- not when
    blending collinear moves (the machine stays on the path); cleared when the blend ends."""
    # XY: (0,0) -> (30,40) with termination 2 (CommandTolerance 0.1), then on to (60,80):
    # collinear. UV: the same first move, then to (60,40): a corner. First move: L = 50,
    # T = 5.1 s from 0.002; the end point is 0.1 away (decelerating at 100) sqrt(2 * 0.1 /
    # 100) = 0.0447 s before its end 5.102, i.e. at 5.057: the blend runs ~5.058 .. 5.102
    src = cs_prog(
        CS_HEAD,
        "  p1 : REAL[2] := [30.0, 40.0];\n  p2 : REAL[2] := [60.0, 80.0];\n"
        "  p3 : REAL[2] := [60.0, 40.0];\n",
        "IF k = 0 THEN\n"
        + "".join(
            f"MCLM({cs}, {c}, 0, {p}, 10.0, unitspersec, 100.0, unitspersec2, 100.0, unitspersec2, "
            f"trapezoidal, 100.0, 100.0, %oftime, {tt}, disabled, programmed, 0.0, 0, none, 0, 0);\n"
            for cs, c, p, tt in (
                ("XY", "c1", "p1", 2),
                ("XY", "c2", "p2", 1),
                ("UV", "c3", "p1", 2),
                ("UV", "c4", "p3", 1),
            )
        )  # fmt: skip
        + "END_IF;",
    )
    tr = trace(st, src, 5200, "XY.MoveTransitionStatus", "UV.MoveTransitionStatus", "c2.AC",
               "c4.AC", "c1.AC", "c3.AC")  # fmt: skip
    assert [tr.at(5.08, n) for n in ("c1.AC", "c2.AC", "c3.AC", "c4.AC")] == [1, 1, 1, 1]
    assert set(tr.col("XY.MoveTransitionStatus")) == {0.0}  # collinear: always on the path
    assert tr.at(5.08, "UV.MoveTransitionStatus") == 1  # the corner is cut
    assert (
        tr.at(5.05, "UV.MoveTransitionStatus") == 0 and tr.at(5.15, "UV.MoveTransitionStatus") == 0
    )


def test_time_cam_status_bits_in_the_motion_status_word(st) -> None:
    """SPEC 5 / 9.22: MATC status bits per the seed's MotionStatus table: TimeCamStatus bit 9,
    TimeCamPendingStatus 11, TimeCamLockStatus 14 (master driven, Immediate Forward Only:
    locked as the cam starts), CoordinatedMotionStatus 16 (the slave of an MDAC). A pending
    cam may use Immediate Forward Only (seed)."""
    src = """VAR
  p1 : CAM_PROFILE[2] := [(Master := 0.0, Slave := 0.0, SegmentType := 0), (Master := 1.0, Slave := 2.0, SegmentType := 0)];
  M, S : AXIS_VIRTUAL := (MaximumSpeed := 1000.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0);
  c1, c2, c3 : MOTION_INSTRUCTION;
  k : DINT;
END_VAR
IF k = 0 THEN
  MDAC(S, M, c3, timecam, command);
  MATC(S, c1, 0, p1, 1.0, 1.0, once, immediate, 0.0, immediateforwardonly, masterdrivenmode);
  MATC(S, c2, 0, p1, 1.0, 1.0, once, pending, 0.0, immediateforwardonly, masterdrivenmode);
END_IF;
k := k + 1;
"""
    r = st.run(src, "S.MotionStatus", "S.TimeCamLockStatus", "c2.ER", "c2.DN", scans=5)
    assert r.code == 0, r.err
    # 2**9 + 2**11 + 2**14 + 2**16 = 512 + 2048 + 16384 + 65536 (the master stands still)
    assert r.tags == {
        "S.MotionStatus": 84480, "S.TimeCamLockStatus": True, "c2.ER": False, "c2.DN": True,
    }  # fmt: skip


def test_time_cam_clock_starts_at_the_profiles_first_master_value(st) -> None:
    """SPEC 5 / 9.22 with a profile that does not start at master 0 (decision 0142): the cam
    time runs from the first to the last master value, P(0) is the first point's value."""
    # (0.5, 3) (1.5, 13): slope 10, span 1 s. From the update 0.002: 10 (t - 0.002) without a
    # jump to 3 at the start, PC when the last master value is reached: 1.002, then held 10
    src = cs_prog(
        MATC_HEAD,
        "  p1 : CAM_PROFILE[2] := [(Master := 0.5, Slave := 3.0, SegmentType := 0), "
        "(Master := 1.5, Slave := 13.0, SegmentType := 0)];\n",
        "IF k = 0 THEN MATC(A, c1, 0, p1, 1.0, 1.0, once, immediate, 0.0, none, 0); END_IF;",
    )
    tr = trace(st, src, 1200, "A.CommandPosition", "c1.PC")
    for t in (0.002, 0.202, 0.502, 1.002, 1.198):
        assert tr.at(t, "A.CommandPosition") == pytest.approx(10.0 * min(t - T0, 1.0), abs=1e-4)
    assert tr.first("c1.PC", 1) == pytest.approx(1.002)


def test_master_driven_chain_has_no_update_lag(st) -> None:
    """SPEC 9.3: within one update, masters are computed before their slaves (no extra lag);
    here M drives S and S drives T (master-driven jogs at 1 unit per master unit)."""
    # The slaves' jogs are waiting for master travel from the update 0.002; M jogs from the
    # update 0.012 (accel 100). Each slave ramps to 1 unit per master unit within 1e-6 master
    # units (accel 1e6 per mu^2), losing 0.5e-6 units: S = M - 0.5e-6, T = S - 0.5e-6 at every
    # update, and the three velocities are equal in every row (a lag would show the slave one
    # update behind: 100 * 0.002 = 0.2 units/s slower while M accelerates)
    src = """VAR
  M, S, T : AXIS_VIRTUAL := (MaximumSpeed := 1000.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0);
  c1, c2, c3, c4, j1 : MOTION_INSTRUCTION;
  k : DINT;
END_VAR
IF k = 0 THEN
  MDAC(T, S, c1, jog, command); MDAC(S, M, c2, jog, command);
  MAJ(T, c3, forward, 1.0, unitspermasterunit, 1000000.0, unitspermasterunit2, 1000000.0, unitspermasterunit2, trapezoidal, 0.0, 0.0, unitspermasterunit3, disabled, programmed, 0.0, none);
  MAJ(S, c4, forward, 1.0, unitspermasterunit, 1000000.0, unitspermasterunit2, 1000000.0, unitspermasterunit2, trapezoidal, 0.0, 0.0, unitspermasterunit3, disabled, programmed, 0.0, none);
END_IF;
IF k = 10 THEN
  MAJ(M, j1, forward, 10.0, unitspersec, 100.0, unitspersec2, 100.0, unitspersec2, trapezoidal, 0.0, 0.0, unitspersec3, disabled, programmed, 0.0, none);
END_IF;
k := k + 1;
"""
    tr = trace(st, src, 200, "M.CommandPosition", "S.CommandPosition", "T.CommandPosition",
               "M.CommandVelocity", "S.CommandVelocity", "T.CommandVelocity")  # fmt: skip
    for t in (0.02, 0.05, 0.08, 0.11, 0.15, 0.199):
        m, s, u = (tr.at(t, f"{n}.CommandPosition") for n in "MST")
        assert m > 0.0
        assert s == pytest.approx(m - 0.5e-6, abs=2e-6) and u == pytest.approx(s - 0.5e-6, abs=2e-6)
        vm, vs, vt = (tr.at(t, f"{n}.CommandVelocity") for n in "MST")
        assert vs == pytest.approx(vm, abs=1e-4) and vt == pytest.approx(vm, abs=1e-4), t


def test_maoc_position_latch_is_an_edge_not_a_level(st) -> None:
    """SPEC 9.27: a Position latch is an edge (set on entering): a cam armed with its position
    already inside [Left, Right] does not set the bit until the cam enters the window."""
    # window [10, 20] on [0, 100] Continuous, CamArm 15 with the axis at 0 (Immediate):
    # cam = 15 + x. At rest the cam sits inside the window: bit 0. Jogging forward at
    # 100 units/s from the update 0.002 (accel 1e5: at speed within the update): the cam
    # leaves at 20 (x = 5), wraps at 100 (x = 85), enters at 10 (x = 95, t ~ 0.952) and
    # leaves at 20 (x = 105, t ~ 1.052): the bit is 1 at t = 1.0 and 0 again at 1.1
    src = """VAR
  A : AXIS_VIRTUAL := (MaximumSpeed := 1000.0, MaximumAccel := 100000.0, MaximumDecel := 100000.0);
  arm, jog : MOTION_INSTRUCTION;
  cam : OUTPUT_CAM[1] := [(OutputBit := 0, LatchType := 1, UnlatchType := 1, Left := 10.0, Right := 20.0)];
  comp : OUTPUT_COMPENSATION[1];
  outw, inw, k : DINT;
  go : BOOL;
END_VAR
IF k = 0 THEN MAOC(A, 0, arm, outw, inw, cam, 0.0, 100.0, comp, continuous, immediate, 0.0, 15.0, actual); END_IF;
IF go AND k = 0 THEN MAJ(A, jog, forward, 100.0, unitspersec, 100000.0, unitspersec2, 100000.0, unitspersec2, trapezoidal, 0.0, 0.0, unitspersec3, disabled, programmed, 0.0, none); END_IF;
k := k + 1;
"""
    tr = trace(st, src, 50, "outw", "arm.IP", "arm.ER")
    assert tr.at(0.0, "arm.ER") == 0 and set(tr.col("outw")) == {0.0}
    assert tr.col("arm.IP")[-1] == 1
    tr = trace(
        st, src.replace("go : BOOL;", "go : BOOL := TRUE;"), 1150, "outw", "A.ActualPosition"
    )
    assert tr.at(0.9, "outw") == 0  # x ~ 89.8: the cam (4.8) is before the window
    assert tr.at(1.0, "outw") == 1  # x ~ 99.8: cam 14.8, entered at 10
    assert tr.at(1.1, "outw") == 0  # x ~ 109.8: cam 24.8, left at 20
