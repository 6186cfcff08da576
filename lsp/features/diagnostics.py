"""Verifier diagnostics as editor diagnostics: same codes, ranges and messages as `check`."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from interpreter.diagnostics import Diagnostic, Severity

# docs/diagnostics.md has one section per code; its anchor is the lower-case title.
DOCS = (Path(__file__).resolve().parents[2] / "docs" / "diagnostics.md").as_uri()
SEVERITY = {Severity.ERROR: 1, Severity.WARNING: 2, Severity.INFO: 3}


@dataclass(frozen=True, slots=True)
class EditorDiagnostic:
    line: int  # 0-based, as LSP
    character: int
    end_line: int
    end_character: int
    severity: int
    code: str
    message: str
    href: str


def anchor(code: str) -> str:
    """The markdown anchor of a code's section (`## E101 undefined tag` -> `e101-undefined-tag`)."""
    from interpreter.diagnostics import REGISTRY

    title = f"{code} {REGISTRY[code].title}".lower()
    return "".join(c for c in title if c.isalnum() or c in " -_").replace(" ", "-")


def docs_link(d: Diagnostic) -> str:
    return f"{DOCS}#{anchor(d.code)}"


def to_editor(d: Diagnostic) -> EditorDiagnostic:
    s = d.span
    return EditorDiagnostic(
        s.line - 1,
        s.col - 1,
        s.end_line - 1,
        s.end_col - 1,
        SEVERITY[d.severity],
        d.code,
        d.message,
        docs_link(d),
    )
