"""Fixture `mp`: runs ST motion programs through the CLI (helpers in motion_trace.py)."""

from __future__ import annotations

from pathlib import Path

import pytest
from motion_trace import Runner


@pytest.fixture
def mp(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> Runner:
    return Runner(tmp_path, capsys)
