"""Hostile-input regression tests (issue 14): each case runs the real `logixst` entry point
in a child process with a wall-clock timeout and an address-space limit, so a hang or a
memory blow-up fails the test instead of the machine."""

from __future__ import annotations

import os
import resource
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
# The entry point reserves a 512 MB thread stack (address space, not memory) and imports
# numpy for `run`: 2 GB of address space is the bound every case is held to here.
MEMORY_BOUND = 2 * 1024**3


@dataclass
class Outcome:
    code: int
    out: str
    err: str
    seconds: float

    def one_line_error(self, *fragments: str) -> str:
        """The single `logixst: error:` line (SPEC 6: a clear message, no traceback)."""
        assert "Traceback" not in self.err, self.err
        lines = self.err.strip().splitlines()
        assert len(lines) == 1, self.err
        for f in fragments:
            assert f in lines[0], (f, lines[0])
        return lines[0]


def _limit_memory() -> None:
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY_BOUND, MEMORY_BOUND))


def logixst(*argv: str | Path, timeout: float = 60.0, cwd: Path | None = None) -> Outcome:
    """`logixst ARGV` through `interpreter.cli.entry` (the console script's code path)."""
    start = time.monotonic()
    r = subprocess.run(
        [sys.executable, "-c", "from interpreter.cli import entry; entry()", *map(str, argv)],
        capture_output=True,
        text=True,
        timeout=timeout,
        cwd=cwd or ROOT,
        preexec_fn=_limit_memory,
        # one BLAS thread: numpy reserves address space per thread, which on a many-core
        # machine alone could approach the bound
        env={
            **os.environ,
            "PYTHONPATH": str(ROOT),
            "OPENBLAS_NUM_THREADS": "1",
            "OMP_NUM_THREADS": "1",
        },
    )
    return Outcome(r.returncode, r.stdout, r.stderr, time.monotonic() - start)
