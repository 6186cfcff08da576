"""Run an export for one scan through `logixst run --json` and return the watched tags."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from interpreter.cli import main


def run(path: Path, capsys: pytest.CaptureFixture[str], *watch: str) -> dict[str, object]:
    argv = ["run", str(path), "--scans", "1", "--json"]
    for w in watch:
        argv += ["--watch", w]
    capsys.readouterr()
    code = main(argv)
    out = capsys.readouterr().out
    assert code == 0, out
    return json.loads(out)["tags"]  # type: ignore[no-any-return]
