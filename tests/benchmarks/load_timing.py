"""Timing `load` for the front-end benchmarks (bench_parse.py, bench_l5x.py).

Imported as a sibling module: a benchmark run as a script has its own folder first on
sys.path, and pytest pointed at a benchmark file puts that folder there too.
"""

from __future__ import annotations

import gc
import time
from pathlib import Path

from interpreter.runtime.loader import Loaded, load


def best_load(path: Path, repeat: int) -> tuple[float, Loaded]:
    """The shortest of `repeat` loads of `path` in seconds, and the last load's result.

    The previous result is freed and garbage collected before the clock starts, so no load
    pays for releasing the one before it.
    """
    best = float("inf")
    loaded = None
    for _ in range(repeat):
        del loaded
        gc.collect()
        t0 = time.perf_counter()
        loaded = load([path])
        best = min(best, time.perf_counter() - t0)
    assert loaded is not None, "repeat must be at least 1"
    return best, loaded
