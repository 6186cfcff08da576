"""docs/diagnostics.md and the diagnostic REGISTRY stay in step (SPEC 7, 9.10).

Every registered code has exactly one section titled `## CODE title`, every section names
a registered code, and each `st` or `rll` example in a section really produces that section's code.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from interpreter.diagnostics import REGISTRY
from interpreter.runtime.loader import load

DOC = Path(__file__).resolve().parent.parent / "docs" / "diagnostics.md"
HEADING = re.compile(r"^## (\S+)(.*)$", re.M)


def sections() -> dict[str, str]:
    text = DOC.read_text(encoding="utf-8")
    heads = list(HEADING.finditer(text))
    out: dict[str, str] = {}
    for i, m in enumerate(heads):
        end = heads[i + 1].start() if i + 1 < len(heads) else len(text)
        assert m.group(1) not in out, f"two sections for {m.group(1)}"
        out[m.group(1)] = text[m.start() : end]
    return out


def test_every_code_has_a_section() -> None:
    missing = sorted(set(REGISTRY) - set(sections()))
    assert not missing, f"codes without a section in docs/diagnostics.md: {missing}"


def test_every_section_is_a_code() -> None:
    unknown = sorted(set(sections()) - set(REGISTRY))
    assert not unknown, f"sections for unregistered codes: {unknown}"


def test_section_titles_follow_the_registry() -> None:
    for code, body in sections().items():
        title = body.splitlines()[0][len("## ") :]
        assert title == f"{code} {REGISTRY[code].title}"


def test_every_section_has_trigger_example_and_fix() -> None:
    for code, body in sections().items():
        assert "**Trigger.**" in body and "**Fix.**" in body, code
        assert re.search(r"```(st|rll|text)\n", body), f"{code} has no example"


EXAMPLES = [
    (code, lang, block)
    for code, body in sections().items()
    for lang, block in re.findall(r"```(st|rll)\n(.*?)```", body, flags=re.S)
]


@pytest.mark.parametrize(
    ("code", "lang", "source"), EXAMPLES, ids=[f"{c}-{lang}" for c, lang, _ in EXAMPLES]
)
def test_example_produces_its_code(tmp_path: Path, code: str, lang: str, source: str) -> None:
    p = tmp_path / f"example.{lang}"
    p.write_text(source)
    codes = [d.code for d in load([p]).diagnostics]
    assert code in codes, f"the {code} example gives {codes}"
