"""Real .L5K exports of the local corpus (/work/l5x-corpus or $LOGIXST_L5X_CORPUS, not
committed): zero syntax diagnostics, and the diagnostics of the .L5X of the same project
where the corpus has both (same stem). Skipped when there is no corpus or no L5K in it.

The one known difference (decision 0048): an L5K export has no module-defined types
(`AB:1756_DI:I:0`), so the comparison leaves out what follows from them: diagnostics naming
a module I/O tag or module type (a name holding ':'), uses of tags and AOI parameters of
such a type (E101), and the operand count of AOIs having such parameters (E104).
"""

from __future__ import annotations

import os
import re
from collections import Counter
from pathlib import Path

import pytest

from interpreter.diagnostics import Diagnostic
from interpreter.runtime.loader import load
from interpreter.syntax.l5k import read_l5k

CORPUS = Path(os.environ.get("LOGIXST_L5X_CORPUS") or "/nonexistent")  # opt-in (test_corpus.py)
FILES = sorted(CORPUS.glob("*")) if CORPUS.is_dir() else []
L5K = [p for p in FILES if p.suffix.lower() == ".l5k"]
L5X = {p.stem.lower(): p for p in FILES if p.suffix.lower() == ".l5x"}
PAIRS = [(k, L5X[k.stem.lower()]) for k in L5K if k.stem.lower() in L5X]
_MODULE_NAME = re.compile(r"'[^' ]*:[^' ]*'")  # `'Local:1:I'`, `'AB:1756_DI:I:0'`


@pytest.mark.skipif(not L5K, reason=f"no L5K export in {CORPUS}")
@pytest.mark.parametrize("path", L5K, ids=[p.name for p in L5K])
def test_l5k_export_has_no_syntax_diagnostics(path: Path) -> None:
    loaded = load([path])
    assert [d.text() for d in loaded.diagnostics if d.code.startswith("S")] == []


@pytest.mark.skipif(not PAIRS, reason=f"no L5K/L5X pair in {CORPUS}")
@pytest.mark.parametrize("pair", PAIRS, ids=[k.name for k, _ in PAIRS])
def test_l5k_and_l5x_of_one_project_agree(pair: tuple[Path, Path]) -> None:
    k, x = pair
    project, _ = read_l5k(k.read_bytes(), str(k))
    assert project is not None
    decls = [*project.tags, *(t for p in project.programs for t in p.tags)]
    decls += [q.decl for a in project.aois for q in a.params]
    module_typed = {d.names[0][0].upper() for d in decls if ":" in d.type.name}
    aois = {a.name.upper() for a in project.aois if any(":" in q.decl.type.name for q in a.params)}

    def follows_from_module_types(d: Diagnostic) -> bool:
        undefined = re.match(r"undefined tag '([^'.\[]+)", d.message)
        return bool(
            _MODULE_NAME.search(d.message)
            or (undefined and undefined.group(1).upper() in module_typed)
            or (d.code == "E104" and d.message.split()[0].upper() in aois)
        )

    def seen(path: Path) -> Counter[tuple[str, str]]:
        diags = load([path]).diagnostics
        return Counter((d.code, d.message) for d in diags if not follows_from_module_types(d))

    assert seen(k) == seen(x)
