"""Shared pieces of the fuzz suite (issue 14): the budget, a deep-stack runner, invariants.

Budget: the default (CI) mode is bounded to a few seconds per component; set
LOGIXST_FUZZ_LONG=1 for the long mode (300 times the cases, about 20 minutes on 2 cores, for
runs on demand), or LOGIXST_FUZZ_SCALE=N to multiply the default case counts by N (it also sets
the long mode's multiplier, e.g. 500 for a run of about 35 minutes).
"""

from __future__ import annotations

import os
import struct
import sys
import threading
from collections.abc import Callable
from pathlib import Path
from typing import TypeVar

from interpreter.runtime.controller import Controller
from interpreter.runtime.loader import InputError, load
from interpreter.semantics.types import ArrayType, Elementary, Kind

ROOT = Path(__file__).resolve().parents[2]
LONG = os.environ.get("LOGIXST_FUZZ_LONG", "") not in ("", "0")
SCALE = int(os.environ.get("LOGIXST_FUZZ_SCALE", "300" if LONG else "1"))

T = TypeVar("T")


def deep(fn: Callable[[], T]) -> T:
    """Run fn as the CLI runs commands (large stack, high recursion limit); re-raise its error."""
    from interpreter.cli import _RECURSION_LIMIT, _STACK_BYTES

    result: list[object] = []
    old_limit = sys.getrecursionlimit()
    sys.setrecursionlimit(_RECURSION_LIMIT)
    old_size = threading.stack_size(_STACK_BYTES)

    def run() -> None:
        try:
            result.append(("ok", fn()))
        except BaseException as exc:  # noqa: BLE001 - handed to the caller
            result.append(("error", exc))

    try:
        worker = threading.Thread(target=run)
        worker.start()
        worker.join()
    finally:
        threading.stack_size(old_size)
        sys.setrecursionlimit(old_limit)
    kind, value = result[0]  # type: ignore[misc]
    if kind == "error":
        raise value  # type: ignore[misc]
    return value  # type: ignore[return-value]


def check_and_run(paths: list[Path], scans: int = 3) -> str:
    """What the CLI would do with the files; any Python exception other than InputError
    (a one-line usage error in the CLI) escapes and fails the calling test.

    Returns "input-error", "errors" (verification errors, nothing runs) or "ran"; after a run
    every elementary tag value fits its type (integers in range, REALs float32).
    """

    def go() -> str:
        try:
            loaded = load(paths)
        except InputError:
            return "input-error"
        if any(d.severity.value == "error" for d in loaded.diagnostics):
            return "errors"
        ctl = Controller(loaded, watchdog=20_000)
        ok = ctl.prescan()
        for _ in range(scans if ok else 0):
            if not ctl.scan():
                break  # a major fault is a Logix outcome, not a crash
        for tag in ctl.model.tags.values():
            if tag.alias_of is None and tag.slot >= 0:
                assert_fits(tag.qualified, ctl.T[tag.slot], tag.type)
        return "ran"

    return deep(go)


def assert_fits(name: str, value: object, t: object) -> None:
    """Integer values inside their type's range, REAL values exactly representable in float32."""
    if isinstance(t, Elementary):
        if t.kind is Kind.BOOL:
            assert value in (0, 1, False, True), (name, value)
        elif t.kind is Kind.INT:
            assert isinstance(value, int), (name, value)
            lo, hi = (
                (-(1 << (t.bits - 1)), (1 << (t.bits - 1)) - 1)
                if t.signed
                else (0, (1 << t.bits) - 1)
            )
            assert lo <= value <= hi, (name, value, t.name)
        elif t.kind is Kind.REAL:
            assert isinstance(value, float), (name, value)
            if t.bits == 32 and value == value:  # NaN has no single float32 image to compare
                assert struct.unpack("f", struct.pack("f", value))[0] == value, (name, value)
    elif isinstance(t, ArrayType) and isinstance(value, list):
        for i, v in enumerate(value[:64]):  # the first elements: generated programs touch few
            assert_fits(f"{name}[{i}]", v, t.elem)
    # structures are left out: their BOOL members may share a host integer, and motion
    # structures hold planner state; the generated programs write elementary tags and arrays
