"""Every public Studio 5000 export in /work/l5x-corpus/ (or $LOGIXST_L5X_CORPUS) reads with
zero syntax (S) diagnostics. The corpus is downloaded locally and not committed (licences);
docs/l5x-corpus.md lists what was tested. Skipped when the directory does not exist."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from interpreter.runtime.loader import load

CORPUS = Path(os.environ.get("LOGIXST_L5X_CORPUS", "/work/l5x-corpus"))
FILES = sorted(p for p in CORPUS.glob("*") if p.suffix.lower() == ".l5x") if CORPUS.is_dir() else []


@pytest.mark.skipif(not FILES, reason=f"no L5X corpus in {CORPUS}")
@pytest.mark.parametrize("path", FILES, ids=[p.name for p in FILES])
def test_public_export_has_no_syntax_diagnostics(path: Path) -> None:
    loaded = load([path])
    syntax = [d.text() for d in loaded.diagnostics if d.code.startswith("S")]
    assert syntax == []
