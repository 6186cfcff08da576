"""Write a Markdown report of what `logixst` says about every corpus export.

    python tests/l5x/corpus/report_corpus.py [--out REPORT.md] [--no-run] [FILE ...]

For every file of manifest.toml present in the corpus directory ($LOGIXST_L5X_CORPUS or
/work/l5x-corpus) it runs `logixst check FILE --format json` and, on kind = "project",
`logixst run FILE --scans 100 --json`, both as subprocesses with this checkout first on
PYTHONPATH (so the report describes this worktree's code, not an installed copy). The report
gives per file the counts by code, then the unknown instruction names (E103), unknown type
names (E119), the most frequent messages of the resolution codes grouped by pattern (names
and numbers replaced), every S diagnostic with the text of its line, and the `run` outcome
of each project. Not run by the test suite: it takes minutes.
"""

from __future__ import annotations

import argparse
import json
import os
import re
import subprocess
import sys
import time
import tomllib
from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[3]
MANIFEST = Path(__file__).with_name("manifest.toml")
CORPUS = Path(os.environ.get("LOGIXST_L5X_CORPUS", "/work/l5x-corpus"))
GROUPED = ("E101", "E102", "E105", "E106", "E107", "E108")
RUN_TIMEOUT_S = 600


@dataclass(slots=True)
class Result:
    entry: dict[str, Any]
    diags: list[dict[str, Any]] = field(default_factory=list)
    check_error: str = ""
    check_s: float = 0.0
    run: str = ""


def _env() -> dict[str, str]:
    env = dict(os.environ)
    env["PYTHONPATH"] = str(ROOT) + os.pathsep + env.get("PYTHONPATH", "")
    return env


def _logixst(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "interpreter.cli", *args],
        capture_output=True,
        text=True,
        env=_env(),
        cwd=ROOT,
        timeout=RUN_TIMEOUT_S,
    )


def check(path: Path) -> tuple[list[dict[str, Any]], str, float]:
    t0 = time.perf_counter()
    proc = _logixst("check", str(path), "--format", "json")
    took = time.perf_counter() - t0
    try:
        return json.loads(proc.stdout), "", took
    except json.JSONDecodeError:
        tail = (proc.stderr or proc.stdout).strip().splitlines()[-1:] or ["no output"]
        return [], f"exit {proc.returncode}: {tail[0][:200]}", took


def run(path: Path) -> str:
    t0 = time.perf_counter()
    try:
        proc = _logixst("run", str(path), "--scans", "100", "--json")
    except subprocess.TimeoutExpired:
        return f"timeout after {RUN_TIMEOUT_S} s"
    took = time.perf_counter() - t0
    out = f"exit {proc.returncode} ({took:.1f} s)"
    try:
        j = json.loads(proc.stdout.strip().splitlines()[-1])
    except (json.JSONDecodeError, IndexError):
        tail = proc.stderr.strip().splitlines()[-1:] or ["no output"]
        return f"{out}: {tail[0][:200]}"
    if proc.returncode == 1:
        codes = Counter(str(d["code"]) for d in j["diagnostics"] if d["severity"] == "error")
        return f"{out}: not run, {_counts(codes)}"
    faults = "; ".join(str(f.get("message", f)) for f in j["faults"])[:300]
    return f"{out}: {j['scans']} scans" + (f", faults: {faults}" if faults else "")


def _counts(c: Counter[str]) -> str:
    return ", ".join(f"{k}×{v}" for k, v in sorted(c.items())) or "none"


def _quoted(msg: str) -> str:
    m = re.search(r"'([^']*)'", msg)
    return m.group(1) if m else msg


def pattern(msg: str) -> str:
    p = re.sub(r"'[^']*'", "'…'", msg)
    return re.sub(r"\b\d+\b", "N", p)


def _line_text(path: Path, line: int) -> str:
    try:
        with path.open(encoding="utf-8-sig", errors="replace") as fh:
            for k, text in enumerate(fh, start=1):
                if k == line:
                    return text.strip()[:160]
    except OSError:
        pass
    return ""


def report(results: list[Result]) -> str:
    out: list[str] = []
    w = out.append
    files = len(results)
    repos = len({r.entry["repo"] for r in results})
    w("# Corpus report: what `logixst check` says about real Studio 5000 exports\n")
    w(
        f"Generated {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())} by "
        "`tests/l5x/corpus/report_corpus.py` from this worktree's code; "
        f"{files} files from {repos} repositories (manifest: tests/l5x/corpus/manifest.toml).\n"
    )
    total: Counter[str] = Counter()
    for r in results:
        total.update(str(d["code"]) for d in r.diags)
    w("## Totals by code\n")
    w("| code | count | files |\n|---|---|---|")
    for code, n in sorted(total.items()):
        nf = sum(1 for r in results if any(d["code"] == code for d in r.diags))
        w(f"| {code} | {n} | {nf} |")
    w("")
    w("## Per file\n")
    w("| file | version | kind | KB | check s | S | E | W | U | codes |")
    w("|---|---|---|---|---|---|---|---|---|---|")
    for r in results:
        c = Counter(str(d["code"]) for d in r.diags)
        by = {k: sum(v for code, v in c.items() if code.startswith(k)) for k in "SEWU"}
        e = r.entry
        codes = r.check_error or _counts(c)
        w(
            f"| {e['file']} | {e['version']} | {e['kind']} | {int(e['bytes']) // 1024} | "
            f"{r.check_s:.1f} | {by['S']} | {by['E']} | {by['W']} | {by['U']} | {codes} |"
        )
    w("")
    for code, title in (("E103", "Unknown instructions (E103)"), ("E119", "Unknown types (E119)")):
        names: Counter[str] = Counter()
        where: dict[str, set[str]] = {}
        for r in results:
            for d in r.diags:
                if d["code"] == code:
                    name = _quoted(str(d["message"]))
                    names[name] += 1
                    where.setdefault(name, set()).add(str(r.entry["file"]).split("__")[0])
        w(f"## {title}\n")
        w("| name | count | owners of the files |\n|---|---|---|")
        for name, k in names.most_common():
            w(f"| {name} | {k} | {', '.join(sorted(where[name]))} |")
        w("")
    w("## Resolution messages by pattern (E101 E102 E105 E106 E107 E108)\n")
    for code in GROUPED:
        pats: Counter[str] = Counter()
        example: dict[str, str] = {}
        for r in results:
            for d in r.diags:
                if d["code"] == code:
                    p = pattern(str(d["message"]))
                    pats[p] += 1
                    example.setdefault(p, f"{r.entry['file']}:{d['line']}: {d['message']}")
        if not pats:
            continue
        w(f"### {code} ({sum(pats.values())})\n")
        w("| count | pattern | first example |\n|---|---|---|")
        for p, k in pats.most_common(25):
            w(f"| {k} | {p} | {example[p][:220]} |")
        w("")
    failed = [r for r in results if r.check_error]
    if failed:
        w("## Files `check` could not read\n")
        for r in failed:
            w(f"- `{r.entry['file']}`: {r.check_error}")
        w("")
    w("## S diagnostics\n")
    any_s = False
    for r in results:
        path = CORPUS / str(r.entry["file"])
        for d in r.diags:
            if str(d["code"]).startswith("S"):
                any_s = True
                text = _line_text(path, int(d["line"]))
                w(f"- `{r.entry['file']}:{d['line']}:{d['column']}` {d['code']} {d['message']}")
                w(f"  - line text: `{text}`")
    if not any_s:
        w("None.")
    w("")
    w("## `run --scans 100` on kind = project\n")
    w("| file | outcome |\n|---|---|")
    for r in results:
        if r.run:
            w(f"| {r.entry['file']} | {r.run} |")
    w("")
    return "\n".join(out)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=CORPUS / "REPORT.md")
    ap.add_argument("--no-run", action="store_true", help="skip `run` on project files")
    ap.add_argument("--json-out", type=Path, help="also write the raw diagnostics as JSON")
    ap.add_argument("only", nargs="*", help="local file names to report (default: all)")
    args = ap.parse_args(argv)
    entries = tomllib.loads(MANIFEST.read_text(encoding="utf-8"))["file"]
    results: list[Result] = []
    for e in entries:
        path = CORPUS / e["file"]
        if not path.is_file() or (args.only and e["file"] not in args.only):
            continue
        r = Result(e)
        r.diags, r.check_error, r.check_s = check(path)
        if e["kind"] == "project" and not args.no_run:
            r.run = run(path)
        print(f"{e['file']}: {len(r.diags)} diagnostics {r.run}", file=sys.stderr)
        results.append(r)
    args.out.write_text(report(results), encoding="utf-8")
    if args.json_out:
        raw = {r.entry["file"]: {"diags": r.diags, "run": r.run} for r in results}
        args.json_out.write_text(json.dumps(raw), encoding="utf-8")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
