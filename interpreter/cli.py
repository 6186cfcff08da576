"""`logixst` command line: run and check (SPEC 6)."""

from __future__ import annotations

import argparse
import csv
import json
import math
import sys
import time
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import TYPE_CHECKING

from .diagnostics import Diagnostic, Severity, has_errors
from .limits import (
    MAX_COARSE_UPDATE_MS,
    MAX_SCAN_PERIOD_MS,
    MAX_SCANS,
    MIN_COARSE_UPDATE_MS,
    MIN_SCAN_PERIOD_MS,
)
from .plot import PlotData, Series, require_matplotlib, write_plot
from .runtime.loader import SUFFIXES, InputError, is_project, load
from .semantics.types import DataType, Elementary, StructType
from .syntax.literals import LiteralError, parse_number, parse_string
from .vm.context import DEFAULT_WATCHDOG

if TYPE_CHECKING:
    from .runtime.controller import Controller

EXIT_OK, EXIT_VERIFY, EXIT_USAGE, EXIT_FAULT = 0, 1, 2, 3
_RECURSION_LIMIT = 60_000  # AST walks take about three frames per level
_STACK_BYTES = 512 * 1024 * 1024  # reserved address space; only the pages used are touched


def _json(obj: object, indent: int | None = None) -> str:
    """Strict JSON: tag values arrive with non-finite REALs as text (to_json_value), so a
    NaN or infinity left anywhere else is a bug that must fail loudly, not print `NaN`."""
    return json.dumps(obj, indent=indent, allow_nan=False)


class UsageError(Exception):
    pass


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> None:  # type: ignore[override]
        raise UsageError(message)


def _version() -> str:
    """The installed distribution's version (pyproject.toml is its one source)."""
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("logixst")
    except PackageNotFoundError:  # run from a source tree that was never installed
        return "(not installed)"


def build_parser() -> argparse.ArgumentParser:
    p = _Parser(
        prog="logixst", description="Run and verify Logix 5000 Structured Text off the controller."
    )
    p.add_argument("--version", action="version", version=f"logixst {_version()}")
    sub = p.add_subparsers(dest="command", required=True, parser_class=_Parser)
    run = sub.add_parser(
        "run",
        help="run a program on simulated time",
        description="Verify, then run a program (files named together form one program) "
        "on simulated time and print the watched tag values.",
    )
    run.add_argument(
        "programs",
        nargs="+",
        type=Path,
        metavar="PROGRAM",
        help=".st/.rll files of one program, or one .L5X/.L5K export",
    )
    length = run.add_mutually_exclusive_group()
    length.add_argument(
        "--duration",
        type=float,
        metavar="S",
        help=f"simulated seconds (default 1; at most {MAX_SCANS:,} scans in all)",
    )
    length.add_argument(
        "--scans", type=int, metavar="N", help=f"number of normal scans (0 to {MAX_SCANS:,})"
    )
    run.add_argument(
        "--scan-period",
        type=float,
        default=1.0,
        metavar="MS",
        help=f"task period in milliseconds (default 1; {MIN_SCAN_PERIOD_MS:g} to {MAX_SCAN_PERIOD_MS:,.0f})",
    )
    run.add_argument(
        "--coarse-update",
        type=float,
        default=None,
        metavar="MS",
        help="motion planner period in milliseconds, "
        f"{MIN_COARSE_UPDATE_MS:g} to {MAX_COARSE_UPDATE_MS:g} (default: the MOTION_GROUP's, else 2)",
    )
    run.add_argument(
        "--set",
        action="append",
        default=[],
        metavar="TAG=VALUE",
        help="give a tag an ST literal value before the first scan (repeatable)",
    )
    run.add_argument(
        "--watch",
        action="append",
        default=[],
        metavar="EXPR",
        help="a tag reference to report, e.g. Axis1.ActualPosition, arr[2], d.5 "
        "(repeatable; default all elementary program tags)",
    )
    run.add_argument(
        "--trace",
        type=Path,
        metavar="FILE.csv",
        help="write the watched values of every scan as CSV (never over an input file)",
    )
    run.add_argument(
        "--plot",
        type=Path,
        metavar="FILE.png",
        help="draw the traced signals as a PNG image (needs the plot extra)",
    )
    run.add_argument(
        "--json", action="store_true", help="print one JSON report instead of the table"
    )
    run.add_argument(
        "--watchdog",
        type=int,
        default=DEFAULT_WATCHDOG,
        metavar="N",
        help=f"statements/instructions one scan may execute before fault 6/1 (default {DEFAULT_WATCHDOG:,})",
    )
    run.add_argument(
        "--tags",
        type=Path,
        metavar="FILE.L5X",
        help="controller tags and data types (an .L5X or .L5K export) for .st/.rll files",
    )
    check = sub.add_parser(
        "check",
        help="verify without running",
        description="Verify programs without running them: one diagnostic per line, "
        "exit 0 without errors, 1 with errors, 2 for a usage or input-file error.",
    )
    check.add_argument(
        "paths",
        nargs="+",
        type=Path,
        metavar="PATH",
        help=".st/.rll files (one program), directories (one program each) or .L5X/.L5K exports",
    )
    check.add_argument(
        "--format",
        choices=["text", "json", "github", "sarif"],
        default="text",
        help="output format (default text)",
    )
    check.add_argument(
        "--tags",
        type=Path,
        metavar="FILE.L5X",
        help="controller tags and data types (an .L5X or .L5K export) for .st/.rll files",
    )
    lsp = sub.add_parser(
        "lsp",
        help="language server for editors (stdio unless --tcp)",
        description="Language server (LSP) for editors, on stdio unless --tcp is given.",
    )
    lsp.add_argument(
        "--tcp",
        metavar="HOST:PORT",
        help="listen on a TCP port instead of stdio (e.g. 127.0.0.1:2087)",
    )
    return p


def main(argv: Sequence[str] | None = None) -> int:
    try:
        args = build_parser().parse_args(argv)
        if args.command == "run":
            return cmd_run(args)
        if args.command == "lsp":
            return cmd_lsp(args)
        return cmd_check(args)
    except UsageError as exc:
        print(f"logixst: error: {exc}", file=sys.stderr)
        return EXIT_USAGE
    except InputError as exc:
        print(f"logixst: error: {exc}", file=sys.stderr)
        return EXIT_USAGE
    except KeyboardInterrupt:
        return 130
    except SystemExit as exc:  # argparse ends --help and --version with exit(0)
        return exc.code if isinstance(exc.code, int) else EXIT_USAGE
    except RecursionError:  # beyond even _with_deep_stack's limit: refuse, never a traceback
        print(
            "logixst: error: the program nests expressions, statements or branches too deeply to analyse",
            file=sys.stderr,
        )
        return EXIT_USAGE


def cmd_lsp(args: argparse.Namespace) -> int:
    if args.tcp is not None:
        host, sep, port = args.tcp.rpartition(":")
        if not sep or not port.isdecimal() or not 0 < int(port) < 65536:
            raise UsageError(f"--tcp expects HOST:PORT, got '{args.tcp}'")
    from lsp.server import run

    run(args.tcp)
    return EXIT_OK


# ------------------------------------------------------------------ run
def parse_set_value(text: str, target: DataType | None = None) -> object:
    """An ST literal for --set: numbers (any radix), TRUE/FALSE, 'strings'.

    A radix literal is a bit pattern, as in an ST assignment: for an integer `target` it is
    read at the target's width (`16#FFFF_FFFF` is 4294967295 in a UDINT, `16#FF` is -1 in
    a SINT); a pattern wider than the target is left for the range check to refuse.
    """
    t = text.strip()
    if t.upper() in ("TRUE", "FALSE"):
        return 1 if t.upper() == "TRUE" else 0
    if t.startswith("'") and t.endswith("'") and len(t) >= 2:
        return parse_string(t)
    neg = t.startswith("-")
    digits = t[1:] if neg or t.startswith("+") else t
    try:
        value, _ = parse_number(digits)
    except LiteralError as exc:  # a number no Logix type holds, as the checker's E133 says
        raise UsageError(f"--set: {exc}") from None
    except ValueError:
        raise UsageError(f"--set: '{text}' is not an ST literal") from None
    if (
        "#" in digits
        and isinstance(target, Elementary)
        and target.is_integer
        and isinstance(value, int)
    ):
        pattern = int(
            digits.replace("_", "").split("#", 1)[1].rstrip("uUlL"), int(digits.split("#", 1)[0])
        )
        if pattern < 1 << target.bits:
            value = (
                pattern - (1 << target.bits)
                if target.signed and pattern >= 1 << (target.bits - 1)
                else pattern
            )
    return -value if neg else value


def cmd_run(args: argparse.Namespace) -> int:
    # The controller (and numpy, for motion) is imported here so `check` starts faster.
    from .runtime.controller import Controller, WatchError

    _check_run_options(args)
    scans = args.scans if args.scans is not None else _scan_count(args.duration, args.scan_period)
    _refuse_overwriting_inputs(args)
    if args.plot is not None:  # refuse before running (docs/decisions/0102-plot.md)
        if args.plot.suffix.lower() != ".png":
            raise UsageError(f"--plot writes a PNG image: '{args.plot}' should end in .png")
        missing = require_matplotlib()
        if missing is not None:
            raise UsageError(missing)
    loaded = load(args.programs, args.tags)
    if has_errors(loaded.diagnostics):
        _print_diags(loaded.diagnostics)
        if args.json:
            print(
                _json(
                    {
                        "time": 0.0,
                        "scans": 0,
                        "tags": {},
                        "faults": [],
                        "diagnostics": [d.to_json() for d in loaded.diagnostics],
                        "unsupported": _unsupported(loaded.diagnostics),
                    }
                )
            )
        return EXIT_VERIFY
    _print_diags(loaded.diagnostics)  # warnings only
    ctl = Controller(
        loaded,
        scan_period_ms=args.scan_period,
        watchdog=args.watchdog,
        coarse_update_ms=args.coarse_update,
    )
    watches = _watches(ctl, args.watch)
    for item in args.set:
        name, sep, value = item.partition("=")
        if not sep:
            raise UsageError(f"--set expects TAG=VALUE, got '{item}'")
        try:
            _, target, setter = ctl.reference(name)
            setter(parse_set_value(value, target))
        except WatchError as exc:
            raise UsageError(f"--set {exc}") from None
    trace_rows: list[list[object]] = []
    record = args.trace is not None or args.plot is not None
    ok = ctl.prescan()
    progress = _Progress(scans, enabled=sys.stderr.isatty() and not args.json)
    for k in range(scans if ok else 0):
        ok = ctl.scan()
        if record:
            trace_rows.append(
                [_seconds(k, args.scan_period)] + [_csv_value(g(), t) for _, g, t in watches]
            )
        if not ok:
            break
        progress.update(k + 1)
    progress.done()
    if args.trace is not None:
        _write_trace(args.trace, [w for w, _, _ in watches], trace_rows)
    if args.plot is not None:
        _write_plot(args.plot, ctl, args.programs, watches, trace_rows)
    faults = ctl.faults()
    tags = {w: _tag_json(g, t) for w, g, t in watches}
    sim_time = _seconds(ctl.scans, args.scan_period)
    if args.json:
        print(
            _json(
                {
                    "time": sim_time,
                    "scans": ctl.scans,
                    "tags": tags,
                    "faults": [f.to_json() for f in faults],
                    "diagnostics": [d.to_json() for d in loaded.diagnostics],
                    "unsupported": _unsupported(loaded.diagnostics),
                }
            )
        )
    else:
        _print_table(tags, {w: t for w, _, t in watches})
        for f in faults:
            print(f.text(), file=sys.stderr)
    return EXIT_OK if ok else EXIT_FAULT


def _unsupported(diags: list[Diagnostic]) -> list[dict[str, object]]:
    """SPEC 9.32: each place that is recognised but not simulated (a U diagnostic), once."""
    out: list[dict[str, object]] = []
    seen: set[tuple[str, str, int, int]] = set()
    for d in diags:
        key = (d.code, d.path, d.span.line, d.span.col)
        if d.code.startswith("U") and key not in seen:
            seen.add(key)
            out.append(
                {
                    "code": d.code,
                    "message": d.message,
                    "file": d.path,
                    "line": d.span.line,
                    "column": d.span.col,
                }
            )
    return out


def _check_run_options(args: argparse.Namespace) -> None:
    """Every numeric option in its range before anything is read (docs/limits.md)."""
    if not MIN_SCAN_PERIOD_MS <= args.scan_period <= MAX_SCAN_PERIOD_MS:  # also rejects nan
        raise UsageError(
            f"--scan-period {args.scan_period:g} ms is outside "
            f"{MIN_SCAN_PERIOD_MS:g}..{MAX_SCAN_PERIOD_MS:,.0f} ms"
        )
    if args.scans is not None and not 0 <= args.scans <= MAX_SCANS:
        raise UsageError(f"--scans {args.scans} is outside 0..{MAX_SCANS:,}")
    if args.duration is not None and not 0 <= args.duration < math.inf:
        raise UsageError("--duration must be a finite number >= 0")
    if args.watchdog <= 0:
        raise UsageError("--watchdog must be > 0")
    if args.coarse_update is not None and not (
        MIN_COARSE_UPDATE_MS <= args.coarse_update <= MAX_COARSE_UPDATE_MS
    ):
        raise UsageError(
            f"--coarse-update {args.coarse_update:g} ms is outside "
            f"{MIN_COARSE_UPDATE_MS:g}..{MAX_COARSE_UPDATE_MS:g} ms (the coarse update periods Logix allows)"
        )


def _seconds(scans: int, scan_period_ms: float) -> float:
    """Start time of scan `scans` in seconds (SPEC 9.1: k x scan period), without binary noise:
    0.1 ms x 3 is reported as 0.0003, not 0.00030000000000000003 (nanosecond resolution)."""
    return round(scans * scan_period_ms / 1000.0, 9)


def _scan_count(duration: float | None, scan_period_ms: float) -> int:
    """Scans in `duration` simulated seconds, at most MAX_SCANS (docs/limits.md)."""
    seconds = 1.0 if duration is None else duration
    total = seconds * 1000.0 / scan_period_ms
    if not total <= MAX_SCANS:  # also an overflow to inf
        raise UsageError(
            f"--duration {seconds:g} s at a {scan_period_ms:g} ms scan period is too many scans "
            f"(the limit is {MAX_SCANS:,})"
        )
    return round(total)


def _refuse_overwriting_inputs(args: argparse.Namespace) -> None:
    """--trace and --plot never write over a program or export named on the command line."""
    inputs = [*args.programs, *([args.tags] if args.tags is not None else [])]
    for option, out in (("--trace", args.trace), ("--plot", args.plot)):
        if out is None:
            continue
        for p in inputs:
            if _same_file(out, p):
                raise UsageError(f"{option} {out} would overwrite the input file {p}")


def _same_file(a: Path, b: Path) -> bool:
    try:
        return a.exists() and b.exists() and a.samefile(b)
    except OSError:
        return a.resolve() == b.resolve()


def _watches(ctl: Controller, exprs: list[str]) -> list[tuple[str, Callable[[], object], DataType]]:
    if not exprs:
        # SPEC 3.3 counts STRING among the elementary types, so a STRING tag is listed too
        exprs = [
            t.qualified
            for t in ctl.model.tags.values()
            if isinstance(t.type, Elementary)
            or (isinstance(t.type, StructType) and t.type.is_string)
        ]
    from .runtime.controller import WatchError

    out = []
    for w in exprs:
        try:
            if w.lower().endswith(EDGES):
                out.append((w, _edge_watch(ctl, w), _edge_type(ctl, w)))
                continue
            getter, t, _ = ctl.reference(w)
        except WatchError as exc:
            raise UsageError(f"--watch {exc}") from None
        out.append((w, getter, t))
    return out


EDGES = "@edges"  # --watch OUT@edges / OUT.n@edges: output cam switch instants (decision 0113)


def _edge_type(ctl: Controller, w: str) -> DataType:
    return ctl.reference(w[: -len(EDGES)])[1]


def _edge_watch(ctl: Controller, w: str) -> Callable[[], object]:
    from .instructions.motion_outputcam import EdgeWatch

    location, t, _ = ctl.reference(w[: -len(EDGES)], as_ref=True)
    if ctl.ctx.motion is None or not (isinstance(t, Elementary) and (t.is_bool or t.is_integer)):
        raise UsageError(
            f"--watch {w}: {EDGES} takes an output cam's Output word or one of its bits"
        )
    return EdgeWatch(ctl.ctx.motion, location())  # type: ignore[arg-type]


def _tag_json(getter: Callable[[], object], t: DataType) -> object:
    from .runtime.controller import to_json_value

    edges = getattr(getter, "json", None)  # an @edges watch: every switch instant
    return edges() if edges is not None else to_json_value(getter(), t)


def _csv_value(v: object, t: object) -> object:
    from .runtime.controller import to_json_value

    if isinstance(v, str):  # an @edges cell
        return v
    j = to_json_value(v, t)  # type: ignore[arg-type]
    if isinstance(j, bool):
        return 1 if j else 0
    if isinstance(j, dict | list):
        return _json(j)
    return j


def _edge_steps(g: object, t0: float) -> tuple[list[float], list[float]]:
    """An @edges bit watch as a step series: the state before the first edge, then each edge."""
    edges: list[tuple[float, int, int]] = g.edges  # type: ignore[attr-defined]
    times = [t0] + [e[0] for e in edges]
    values = [float(1 - edges[0][2]) if edges else 0.0] + [float(e[2]) for e in edges]
    return times, values


def _write_trace(path: Path, names: list[str], rows: list[list[object]]) -> None:
    try:
        with path.open("w", newline="") as fh:
            w = csv.writer(fh)
            w.writerow(["time", *names])
            w.writerows(rows)
    except OSError as exc:
        raise InputError(f"{path}: cannot write trace: {exc.strerror}") from exc


def _write_plot(
    path: Path,
    ctl: Controller,
    programs: list[Path],
    watches: list[tuple[str, Callable[[], object], DataType]],
    rows: list[list[object]],
) -> None:
    series = []
    for j, (name, g, t) in enumerate(watches, start=1):
        if not isinstance(t, Elementary):
            continue  # structures and strings are not drawn
        if name.lower().endswith(EDGES):
            if getattr(g, "bit", None) is not None:  # a bit: a lane stepped at the exact instants
                times, values = _edge_steps(g, float(rows[0][0]) if rows else 0.0)  # type: ignore[arg-type]
                series.append(Series(name, values, "bool", times))
            continue
        kind = "bool" if t.is_bool else "int" if t.is_integer or t.is_time else "real"
        series.append(Series(name, [float(r[j]) for r in rows], kind))  # type: ignore[arg-type]
    data = PlotData(
        ", ".join(p.name for p in programs),
        [float(r[0]) for r in rows],  # type: ignore[arg-type]
        series,
        _coordinate_paths(ctl, [w for w, _, _ in watches]),
    )
    try:
        write_plot(path, data)
    except OSError as exc:
        raise InputError(f"{path}: cannot write plot: {exc.strerror or exc}") from exc


def _coordinate_paths(ctl: Controller, watched: list[str]) -> list[tuple[str, list[str]]]:
    """Coordinate systems whose axis positions are all watched (actual preferred to command)."""
    norm = {w.replace(" ", "").upper(): w for w in watched}
    out = []
    for tag in ctl.model.tags.values():
        st = tag.type
        if not isinstance(st, StructType) or st.name != "COORDINATE_SYSTEM" or tag.alias_of:
            continue
        value = ctl.T[tag.slot]
        assert isinstance(value, list)
        axes = [a for a in value[st.index["AXES"]] if isinstance(a, str)]
        for member in ("ACTUALPOSITION", "COMMANDPOSITION"):
            exprs = [norm.get(f"{a.upper()}.{member}") for a in axes]
            if len(axes) >= 2 and all(exprs):
                out.append((tag.name, [e for e in exprs if e]))
                break
    return out


def _print_table(tags: dict[str, object], types: dict[str, DataType]) -> None:
    if not tags:
        print("(no elementary tags to show; use --watch)")
        return
    width = max(len(k) for k in tags)
    for k, v in tags.items():
        t = types.get(k)
        real = isinstance(t, Elementary) and t.is_real  # Infinity/NaN: a number, not a STRING
        shown = _json(v) if not isinstance(v, str) else v if real else repr(v)
        print(f"{k.ljust(width)}  {shown}")


class _Progress:
    """A progress bar on stderr for runs longer than a couple of wall seconds (TTY only)."""

    def __init__(self, total: int, enabled: bool) -> None:
        self.total, self.enabled = total, enabled
        self.start = time.monotonic()
        self.shown = False
        self.last = 0.0

    def update(self, done: int) -> None:
        if not self.enabled or done % 256:
            return
        now = time.monotonic()
        if now - self.start < 2.0 or now - self.last < 0.2:
            return
        self.last, self.shown = now, True
        frac = done / max(1, self.total)
        bar = "#" * int(frac * 30)
        print(
            f"\r[{bar:<30}] {frac:6.1%} scan {done}/{self.total}",
            end="",
            file=sys.stderr,
            flush=True,
        )

    def done(self) -> None:
        if self.shown:
            print(file=sys.stderr)


# ------------------------------------------------------------------ check
def cmd_check(args: argparse.Namespace) -> int:
    groups: list[list[Path]] = []
    files: list[Path] = []
    for p in args.paths:
        if not p.exists():
            raise InputError(f"{p}: no such file or directory")
        if p.is_dir():
            members = sorted(x for x in p.iterdir() if x.suffix.lower() in SUFFIXES)
            projects = [[x] for x in sorted(p.iterdir()) if is_project(x)]
            if not members and not projects:  # "0 error(s)" would claim something was checked
                raise UsageError(f"{p}: no .st, .rll, .L5X or .L5K files in this directory")
            if members:
                groups.append(members)
            groups.extend(projects)
        elif is_project(p):
            groups.append([p])  # each .L5X or .L5K is one project (SPEC 9.8)
        else:
            files.append(p)
    if files:
        groups.insert(0, files)
    diags: list[Diagnostic] = []
    for g in groups:
        diags.extend(load(g, None if is_project(g[0]) else args.tags).diagnostics)
    diags.sort(key=lambda d: d.sort_key())
    _emit_check(diags, args.format)
    return EXIT_VERIFY if has_errors(diags) else EXIT_OK


def _emit_check(diags: list[Diagnostic], fmt: str) -> None:
    if fmt == "json":
        print(_json([d.to_json() for d in diags], indent=2))
    elif fmt == "github":
        for d in diags:
            kind = (
                "error"
                if d.severity is Severity.ERROR
                else "warning"
                if d.severity is Severity.WARNING
                else "notice"
            )
            # exactly the three properties SPEC 6 names; the code leads the message
            print(
                f"::{kind} file={_gh(d.path, True)},line={d.span.line},col={d.span.col}"
                f"::{_gh(f'{d.code} {d.message}')}"
            )
    elif fmt == "sarif":
        print(_json(_sarif(diags), indent=2))
    else:
        for d in diags:
            print(d.text())
        errors = sum(1 for d in diags if d.severity is Severity.ERROR)
        warnings = sum(1 for d in diags if d.severity is Severity.WARNING)
        print(f"{errors} error(s), {warnings} warning(s)")


def _gh(text: str, prop: bool = False) -> str:
    """Escape a workflow-command value as GitHub's runner decodes it: `%`, CR and LF always,
    and in a property also `:` and `,` (a message with `% of Maximum`, a path with a comma)."""
    text = text.replace("%", "%25").replace("\r", "%0D").replace("\n", "%0A")
    return text.replace(":", "%3A").replace(",", "%2C") if prop else text


def _sarif(diags: list[Diagnostic]) -> dict[str, object]:
    from .diagnostics import REGISTRY

    level = {Severity.ERROR: "error", Severity.WARNING: "warning", Severity.INFO: "note"}
    return {
        "version": "2.1.0",
        "$schema": "https://json.schemastore.org/sarif-2.1.0.json",
        "runs": [
            {
                "tool": {
                    "driver": {
                        "name": "logixst",
                        "rules": [
                            {"id": c.code, "shortDescription": {"text": c.title}}
                            for c in REGISTRY.values()
                        ],
                    }
                },
                "results": [
                    {
                        "ruleId": d.code,
                        "level": level[d.severity],
                        "message": {"text": d.message},
                        "locations": [
                            {
                                "physicalLocation": {
                                    "artifactLocation": {"uri": _uri_reference(d.path)},
                                    "region": {
                                        "startLine": d.span.line,
                                        "startColumn": d.span.col,
                                        "endLine": d.span.end_line,
                                        "endColumn": d.span.end_col,
                                    },
                                }
                            }
                        ],
                    }
                    for d in diags
                ],
            }
        ],
    }


def _uri_reference(path: str) -> str:
    """SARIF's `uri` is a URI reference: the path as given (relative paths stay relative to
    the directory `check` ran in, as code scanning wants them), with `/` separators and the
    characters a URI cannot hold (a space, `%`, `#`) percent-encoded."""
    from urllib.parse import quote

    return quote(Path(path).as_posix(), safe="/:")  # as_posix: `\\` to `/` on Windows only


def _print_diags(diags: list[Diagnostic]) -> None:
    for d in diags:
        print(d.text(), file=sys.stderr)


def _with_deep_stack(fn: Callable[[], int]) -> int:
    """Run the command in a thread with a large stack and a high recursion limit.

    The checker and compiler walk the AST recursively, and a sum of a few hundred terms or a
    few hundred nested branches is as deep an AST; CPython's default limit (1,000 frames)
    and the main thread's 8 MB stack are too small for that. Ctrl+C still reaches the main
    thread, which waits here.
    """
    import threading

    sys.setrecursionlimit(_RECURSION_LIMIT)
    threading.stack_size(_STACK_BYTES)
    result = [EXIT_USAGE]

    def run() -> None:
        try:
            result[0] = fn()
        except SystemExit as exc:  # argparse's --help and --version end with exit(0)
            result[0] = exc.code if isinstance(exc.code, int) else EXIT_USAGE

    worker = threading.Thread(target=run, name="logixst", daemon=True)
    worker.start()
    try:
        worker.join()
    except KeyboardInterrupt:
        return 130
    return result[0]


def entry() -> None:
    """Console-script entry point: `main`, then exit without tearing down the object graph.

    A large project's AST and tag model take a noticeable fraction of a second to free one
    object at a time; the process is ending anyway. Output is flushed first, and files
    the command wrote are already closed.
    """
    import os

    code = _with_deep_stack(main)
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError):  # closed by the peer (an editor ending `logixst lsp`)
            pass
    os._exit(code)


if __name__ == "__main__":
    entry()
