"""`logixst check` on the largest real export of the corpus, and on generated exports of growing size.

    python tests/benchmarks/bench_corpus.py [--repeat N] [--sizes 1,2,4,8]

(a) The largest file of tests/l5x/corpus/manifest.toml present in the corpus directory
    ($LOGIXST_L5X_CORPUS or /work/l5x-corpus; see tests/l5x/corpus/fetch_corpus.py): the whole
    `logixst check FILE` command as a user runs it (a fresh interpreter: start-up, grammars,
    catalog, exit), best of N runs. Issue 9 target: 1.5 s.
(b) Generated exports of 1, 2, 4 and 8 MB (the generator of bench_l5x.py: tags with
    Decorated data, RLL programs with typical rungs, an ST routine each): the whole command
    and the in-process `load`, with seconds per MB, so a growth worse than linear shows.

Not collected by pytest (tests/benchmarks is outside the test paths); pytest pointed at this
file runs `test_corpus_benchmark`, which prints the same figures. The machine is shared:
run it once, not in a loop.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))  # run from anywhere

from bench_l5x import export  # noqa: E402
from load_timing import best_load  # noqa: E402

from interpreter.runtime.loader import load  # noqa: E402

TARGET_S = 1.5
MANIFEST = ROOT / "tests" / "l5x" / "corpus" / "manifest.toml"
CORPUS = Path(os.environ.get("LOGIXST_L5X_CORPUS", "/work/l5x-corpus"))


def command_seconds(path: Path, repeat: int) -> tuple[float, int]:
    """Best wall time of `logixst check PATH` in a fresh interpreter, and its exit status."""
    env = dict(os.environ)
    env["PYTHONPATH"] = str(ROOT) + os.pathsep + env.get("PYTHONPATH", "")
    best, code = float("inf"), -1
    for _ in range(repeat):
        t0 = time.perf_counter()
        done = subprocess.run(
            [sys.executable, "-m", "interpreter.cli", "check", str(path)],
            capture_output=True,
            text=True,
            check=False,
            cwd=ROOT,
            env=env,
        )
        best = min(best, time.perf_counter() - t0)
        code = done.returncode
        # 0 = clean, 1 = diagnostics reported; anything else is a crash or a usage error
        assert code in (0, 1), done.stderr[-2000:]
    return best, code


def _logic(path: Path) -> int:
    """Rungs and ST lines: how much logic an export holds (most real bytes are tag data)."""
    data = path.read_bytes()
    return data.count(b"<Rung ") + data.count(b"<Line ")


def corpus_files() -> list[tuple[str, Path, dict[str, object]]]:
    """The largest L5X export of the corpus by bytes, and the one with the most logic."""
    entries = tomllib.loads(MANIFEST.read_text(encoding="utf-8"))["file"]
    present = [
        e for e in entries if (CORPUS / e["file"]).is_file() and e["file"].lower().endswith(".l5x")
    ]
    if not present:
        return []
    biggest = max(present, key=lambda x: int(x["bytes"]))
    most = max(present, key=lambda x: _logic(CORPUS / x["file"]))
    out = [("largest corpus export", CORPUS / biggest["file"], biggest)]
    if most is not biggest:
        out.append(("corpus export with the most logic", CORPUS / most["file"], most))
    return out


def bench_largest(repeat: int) -> list[str]:
    found = corpus_files()
    if not found:
        return [f"(a) no corpus file in {CORPUS}: run tests/l5x/corpus/fetch_corpus.py first"]
    rows = []
    for label, path, e in found:
        load([path])  # warm this process's grammar and catalog caches for the in-process figure
        inproc, _ = best_load(path, repeat)
        cmd, code = command_seconds(path, repeat)
        verdict = "meets" if cmd <= TARGET_S else "misses"
        mb = int(str(e["bytes"])) / 1e6
        rows.append(
            f"(a) {label} {e['file']} ({mb:.2f} MB, {_logic(path)} rungs and ST lines, "
            f"Studio {e['version']}): whole `logixst check` {cmd:.2f} s best of {repeat} "
            f"(exit {code}; {verdict} the {TARGET_S} s target), in-process load {inproc:.2f} s"
        )
    return rows


def bench_sizes(sizes: list[float], repeat: int) -> list[str]:
    rows = ["(b) generated exports: MB, rungs, whole command s, s/MB, in-process load s, s/MB"]
    with tempfile.TemporaryDirectory() as d:
        for mb in sizes:
            text = export(int(mb * 1_000_000))
            path = Path(d) / f"bench_{mb:g}MB.L5X"
            path.write_text(text)
            real_mb = len(text.encode()) / 1e6
            load([path])
            inproc, _ = best_load(path, repeat)
            cmd, code = command_seconds(path, repeat)
            assert code == 0, f"the generated {mb} MB export should check clean"
            rows.append(
                f"    {real_mb:5.2f} MB {text.count('<Rung '):6d} rungs  command {cmd:5.2f} s "
                f"({cmd / real_mb:.3f} s/MB)  load {inproc:5.2f} s ({inproc / real_mb:.3f} s/MB)"
            )
    return rows


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--sizes", default="1,2,4,8", help="generated export sizes in MB")
    args = ap.parse_args(argv)
    for row in bench_largest(args.repeat):
        print(row, flush=True)
    for row in bench_sizes([float(s) for s in args.sizes.split(",")], args.repeat):
        print(row, flush=True)
    return 0


def test_corpus_benchmark() -> None:
    main(["--repeat", "3"])


if __name__ == "__main__":
    raise SystemExit(main())
