"""ruff (lint and format) and mypy are part of the test run (DESIGN: lint and type clean in CI).

They run as `python -m ...` so that a missing tool fails the test instead of skipping it:
both come with the test extra that CI installs.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _run(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", *args], capture_output=True, text=True, check=False, cwd=ROOT
    )


def test_ruff_check_clean() -> None:
    result = _run("ruff", "check", ".")
    assert result.returncode == 0, result.stdout + result.stderr


def test_ruff_format_clean() -> None:
    result = _run("ruff", "format", "--check", ".")
    assert result.returncode == 0, result.stdout + result.stderr


def test_mypy_clean() -> None:
    result = _run("mypy", "interpreter", "stdlib", "lsp")
    assert result.returncode == 0, result.stdout + result.stderr
