"""The words the motion runtime collects to find which axis attributes a program can read
(runtime.motion.program_demand) are those of every node semantics.locate.walk visits: the
runtime's own walk (field names looked up once per node type) is checked against a direct
use of locate.walk on ST, ladder, L5X and L5K programs."""

from __future__ import annotations

from dataclasses import fields
from pathlib import Path

import pytest

from interpreter.runtime.loader import load
from interpreter.runtime.motion import _collect_words
from interpreter.semantics.locate import walk
from interpreter.syntax import nodes as n

ROOT = Path(__file__).resolve().parents[1]
PROGRAMS = [
    "golden/state_machine/program.st",
    "golden/array_udt_math/program.st",
    "l5x/fixtures/st_project.L5X",
    "l5x/fixtures/rll_project.L5X",
    "l5x/fixtures/studio_features.L5X",
    "l5x/fixtures/aliases.L5X",
    "l5k/fixtures/gear_home_project.L5K",
    "motion_programs/fixtures/coordinated_project.L5X",
]


def _reference(node: object) -> set[str]:
    out: set[str] = set()
    for x in walk(node):
        if isinstance(x, n.Member):
            out.add(x.name.upper())
        elif isinstance(x, n.Name):
            out.add(x.ident.upper().rsplit(".", 1)[-1])
        else:
            for f in fields(x):  # type: ignore[arg-type]
                value = getattr(x, f.name)
                if isinstance(value, str):
                    out.add(value.upper())
    return out


@pytest.mark.parametrize("rel", PROGRAMS)
def test_runtime_words_are_the_words_of_every_walked_node(rel: str) -> None:
    model = load([ROOT / rel]).model
    routines = list(model.all_routines())
    assert routines
    for r in routines:
        node = (r.body, r.rungs, r.decls)
        words: set[str] = set()
        _collect_words(node, words)
        assert words == _reference(node), r.name
        assert words or not (r.body or r.rungs)  # a routine with code has words
