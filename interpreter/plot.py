"""`logixst run --plot FILE.png`: traced signals against time, one subplot per unit, plus the
XY path of every coordinate system whose axes are watched (SPEC 6).

matplotlib is the optional `plot` extra: it is imported only here, only when plotting, and
`require_matplotlib` lets the CLI refuse the option up front when it is missing
(docs/decisions/0102-plot.md).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

INSTALL_HINT = 'pip install -e ".[plot]" (from the repository root)'

# last member name (upper case) -> unit group, in the order the subplots appear
_UNITS: tuple[tuple[str, str], ...] = (
    ("POSITION", "position [units]"),
    ("POSITIONERROR", "position [units]"),
    ("VELOCITY", "velocity [units/s]"),
    ("ACCELERATION", "acceleration [units/s²]"),
)
_ORDER = [
    "position [units]",
    "velocity [units/s]",
    "acceleration [units/s²]",
    "values",
    "integers",
    "bits",
]


@dataclass(slots=True)
class Series:
    name: str  # the watch expression as given
    values: list[float]
    kind: str  # "bool", "int" or "real"
    times: list[float] | None = None  # own instants (an @edges watch), else the rows' times


@dataclass(slots=True)
class PlotData:
    title: str
    times: list[float]
    series: list[Series]
    # coordinate systems: (name, [watch expression of each axis position, in axis order])
    paths: list[tuple[str, list[str]]] = field(default_factory=list)


def require_matplotlib() -> str | None:
    """None when matplotlib can be imported, else the one-line reason."""
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        return f"--plot needs matplotlib, which is not installed: {INSTALL_HINT}"
    return None


def unit_of(expr: str, kind: str) -> str:
    """Unit group of a watched expression: from the member name for axis attributes
    (ActualPosition, CommandVelocity, ...), else by data type."""
    if kind == "bool":
        return "bits"
    last = expr.rsplit(".", 1)[-1].split("[", 1)[0].upper()
    for suffix, unit in _UNITS:
        if last.endswith(suffix):
            return unit
    return "integers" if kind == "int" else "values"


def write_plot(path: Path, data: PlotData) -> None:
    """Render to PNG (raises OSError when the file cannot be written)."""
    import matplotlib

    matplotlib.use("Agg")  # no display needed
    import matplotlib.pyplot as plt

    groups: dict[str, list[Series]] = {}
    for s in data.series:
        groups.setdefault(unit_of(s.name, s.kind), []).append(s)
    units = [u for u in _ORDER if u in groups]
    by_name = {s.name: s for s in data.series}
    paths = [
        (n, [by_name[e] for e in exprs])
        for n, exprs in data.paths
        if all(e in by_name for e in exprs)
    ]
    rows = len(units) + (1 if paths else 0)
    if rows == 0:
        rows, units = 1, []
    heights = [2.2 if u != "bits" else 0.5 + 0.35 * len(groups[u]) for u in units] + (
        [4.0] if paths else []
    )
    fig, axes = plt.subplots(
        rows,
        1,
        figsize=(10, max(3.0, sum(heights) + 1.0)),
        gridspec_kw={"height_ratios": heights or [1]},
        squeeze=False,
    )
    t = data.times
    time_axes = []
    for ax, unit in zip(axes[:, 0], units, strict=False):
        time_axes.append(ax)
        if unit == "bits":
            _bits(ax, t, groups[unit])
        else:
            for s in groups[unit]:
                ax.plot(
                    t,
                    s.values,
                    label=s.name,
                    linewidth=1.2,
                    drawstyle="steps-post" if s.kind == "int" else "default",
                )
            ax.set_ylabel(unit)
            ax.legend(loc="best", fontsize="small")
        ax.grid(True, alpha=0.3)
    for ax in time_axes[:-1]:
        ax.sharex(time_axes[-1])
        ax.tick_params(labelbottom=False)
    if time_axes:
        time_axes[-1].set_xlabel("time [s]")
    if paths:
        _paths(fig, axes[-1, 0], paths)
    if not units and not paths:
        axes[0, 0].text(0.5, 0.5, "no numeric signals to plot", ha="center", va="center")
    fig.suptitle(data.title)
    fig.tight_layout()
    try:
        fig.savefig(path, dpi=110)
    finally:
        plt.close(fig)


_PLANES = ((0, 1, "X", "Y"), (0, 2, "X", "Z"), (1, 2, "Y", "Z"))


def _paths(fig, slot, paths: list[tuple[str, list[Series]]]) -> None:  # type: ignore[no-untyped-def]
    """The path of each coordinate system in its plane: X-Y for 2D systems, the X-Y, X-Z
    and Y-Z views side by side when a system has three axes."""
    planes = _PLANES if any(len(ss) >= 3 for _, ss in paths) else _PLANES[:1]
    if len(planes) > 1:
        spec = slot.get_subplotspec().subgridspec(1, len(planes), wspace=0.35)
        slot.remove()
        views = [fig.add_subplot(spec[0, k]) for k in range(len(planes))]
    else:
        views = [slot]
    for ax, (i, j, hx, hy) in zip(views, planes, strict=True):
        for name, ss in paths:
            if len(ss) > j:
                label = f"{name}: {ss[j].name} over {ss[i].name}"
                ax.plot(ss[i].values, ss[j].values, label=label, linewidth=1.4)
        ax.set_xlabel(f"{hx} [units]")
        ax.set_ylabel(f"{hy} [units]")
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_title(f"coordinate system path ({hx}-{hy})", fontsize="medium")
        if len(planes) == 1:
            ax.legend(loc="best", fontsize="small")
        ax.grid(True, alpha=0.3)


def _bits(ax, t: list[float], series: list[Series]) -> None:  # type: ignore[no-untyped-def]
    """BOOL signals as stacked steps, one lane each, labelled on the y axis."""
    lanes = list(reversed(series))
    for i, s in enumerate(lanes):
        ts = s.times if s.times is not None else t
        if s.times is not None and t:  # exact edges: hold the last state to the end
            ts, vs = [*ts, t[-1]], [*s.values, s.values[-1]]
        else:
            vs = s.values
        ax.fill_between(ts, i, [i + 0.8 * v for v in vs], step="post", alpha=0.6)
        ax.step(ts, [i + 0.8 * v for v in vs], where="post", linewidth=1.0)
    ax.set_yticks([i + 0.4 for i in range(len(lanes))])
    ax.set_yticklabels([s.name for s in lanes], fontsize="small")
    ax.set_ylim(-0.2, len(lanes))
    ax.set_ylabel("bits")
