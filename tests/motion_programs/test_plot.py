"""`logixst run --plot` (SPEC 6, docs/decisions/0102-plot.md)."""

from __future__ import annotations

import sys

import pytest

from interpreter.plot import unit_of

SRC = """VAR
  X, Y : AXIS_VIRTUAL := (MaximumSpeed := 100.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0);
  XY : COORDINATE_SYSTEM := (Axes := [X, Y], MaximumSpeed := 100.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0);
  c1, c2 : MOTION_INSTRUCTION;
  k : DINT;
END_VAR
IF k = 0 THEN
  MAJ(X, c1, forward, 10.0, unitspersec, 100.0, unitspersec2, 100.0, unitspersec2, trapezoidal, 0.0, 0.0, unitspersec3, disabled, programmed, 0.0, none);
  MAJ(Y, c2, forward, 5.0, unitspersec, 100.0, unitspersec2, 100.0, unitspersec2, trapezoidal, 0.0, 0.0, unitspersec3, disabled, programmed, 0.0, none);
END_IF;
k := k + 1;
"""
WATCH = [
    "--watch",
    "X.ActualPosition",
    "--watch",
    "y.actualposition",
    "--watch",
    "X.CommandVelocity",
    "--watch",
    "c1.IP",
    "--watch",
    "k",
]
PNG = b"\x89PNG\r\n\x1a\n"


def test_units_group_the_subplots() -> None:
    assert (
        unit_of("Axis1.ActualPosition", "real")
        == unit_of("b.CommandPosition", "real")
        == "position [units]"
    )
    assert unit_of("Axis1.PositionError", "real") == "position [units]"
    assert (
        unit_of("Axis1.CommandVelocity", "real")
        == unit_of("a.AverageVelocity", "real")
        == "velocity [units/s]"
    )
    assert unit_of("a.CommandAcceleration", "real") == "acceleration [units/s²]"
    assert unit_of("ctl.IP", "bool") == unit_of("d.5", "bool") == "bits"
    assert unit_of("ctl.ERR", "int") == "integers" and unit_of("r", "real") == "values"


@pytest.mark.parametrize("with_trace", [False, True])
def test_plot_written_with_or_without_trace(mp, tmp_path, with_trace: bool) -> None:
    png = tmp_path / "out.png"
    extra = ["--trace", str(tmp_path / "t.csv")] if with_trace else []
    code, _, err = mp.run(SRC, ["--scans", "200", "--plot", str(png), *WATCH, *extra])
    assert code == 0, err
    data = png.read_bytes()
    assert data.startswith(PNG) and len(data) > 10_000
    assert (tmp_path / "t.csv").exists() == with_trace


def test_xy_path_of_a_watched_coordinate_system(mp, tmp_path) -> None:
    from interpreter.cli import _coordinate_paths
    from interpreter.runtime.controller import Controller
    from interpreter.runtime.loader import load

    p = tmp_path / "cs.st"
    p.write_text(SRC)
    ctl = Controller(load([p]))
    assert _coordinate_paths(ctl, ["x.ActualPosition", "Y.ActualPosition"]) == [
        ("XY", ["x.ActualPosition", "Y.ActualPosition"])
    ]
    assert _coordinate_paths(ctl, ["X.CommandPosition", "Y.CommandPosition", "k"]) == [
        ("XY", ["X.CommandPosition", "Y.CommandPosition"])
    ]
    assert _coordinate_paths(ctl, ["X.ActualPosition", "k"]) == []


def test_missing_matplotlib_is_one_line_and_nothing_runs(mp, tmp_path, monkeypatch) -> None:
    monkeypatch.setitem(sys.modules, "matplotlib", None)  # import matplotlib -> ImportError
    trace = tmp_path / "t.csv"
    code, out, err = mp.run(
        SRC, ["--scans", "5", "--plot", str(tmp_path / "o.png"), "--trace", str(trace)]
    )
    assert code == 2 and out == ""
    lines = err.strip().splitlines()
    assert len(lines) == 1 and 'pip install -e ".[plot]"' in lines[0] and "Traceback" not in err
    assert not trace.exists()


def test_plot_file_must_be_png(mp, tmp_path) -> None:
    code, _, err = mp.run(SRC, ["--scans", "5", "--plot", str(tmp_path / "o.jpg")])
    assert code == 2 and ".png" in err


@pytest.mark.parametrize(("n", "views"), [(2, ["X-Y"]), (3, ["X-Y", "X-Z", "Y-Z"])])
def test_coordinate_path_views(tmp_path, monkeypatch, n: int, views: list[str]) -> None:
    # a 2-axis system is drawn in its X-Y plane; a 3-axis one in the three planes
    import matplotlib.figure

    from interpreter.plot import PlotData, Series, write_plot

    titles: list[str] = []
    save = matplotlib.figure.Figure.savefig

    def spy(fig, *args, **kwargs):  # noqa: ANN001, ANN002, ANN003, ANN202
        titles.extend(ax.get_title() for ax in fig.axes)
        return save(fig, *args, **kwargs)

    monkeypatch.setattr(matplotlib.figure.Figure, "savefig", spy)
    names = ["X.CommandPosition", "Y.CommandPosition", "Z.CommandPosition"][:n]
    t = [0.0, 0.1, 0.2, 0.3]
    series = [Series(name, [0.0, 1.0, 0.0, -1.0], "real") for name in names]
    write_plot(tmp_path / "p.png", PlotData("p", t, series, [("CS", names)]))
    assert [x for x in titles if x.startswith("coordinate")] == [
        f"coordinate system path ({v})" for v in views
    ]
