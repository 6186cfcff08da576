"""The one registry of diagnostic codes, shared by `check`, `run` and the language server.

Codes are a letter and three digits: S syntax, E semantic error, W warning, U recognised
but not supported. docs/diagnostics.md has one section per code (a test keeps them in step).
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import StrEnum

from .syntax.nodes import Span


class Severity(StrEnum):
    ERROR = "error"
    WARNING = "warning"
    INFO = "info"


@dataclass(frozen=True, slots=True)
class Code:
    code: str
    severity: Severity
    title: str


_TABLE: list[tuple[str, str]] = [
    # syntax
    ("S001", "unexpected text: the parser cannot continue here"),
    ("S002", "a block is not closed (missing END_IF, END_CASE, END_FOR, END_WHILE, END_REPEAT)"),
    ("S003", "a comment or string is not terminated"),
    ("S004", "a character that is not part of the language"),
    ("S005", "a statement is missing its ';'"),
    ("S006", "ladder branches are not balanced"),
    ("S007", "malformed project file (XML)"),
    ("S008", "malformed project file (L5K)"),
    # semantic errors
    ("E101", "undefined tag"),
    ("E102", "unknown structure member"),
    ("E103", "unknown instruction or function"),
    ("E104", "wrong number of operands"),
    ("E105", "operand data type not accepted"),
    ("E106", "operand must be a tag"),
    ("E107", "operand must be an immediate value"),
    ("E108", "unknown enumeration text"),
    ("E109", "enumeration number out of range"),
    ("E110", "wrong subscripts for this tag"),
    ("E111", "a CAM_PROFILE operand must be element [0]"),
    ("E112", "MDAC master axis is the slave axis"),
    ("E113", "axis type not allowed for this instruction"),
    ("E114", "CASE label is not a literal"),
    ("E115", "statement is not Logix Structured Text"),
    ("E116", "STRING mixed with numbers"),
    ("E117", "duplicate declaration"),
    ("E118", "initialiser does not match the declared type"),
    ("E119", "unknown data type"),
    ("E120", "target cannot be written"),
    ("E121", "operation not valid for this data type"),
    ("E122", "constant subscript out of range"),
    ("E123", "status flag not available in Structured Text"),
    ("E124", "JSR to an unknown routine"),
    ("E125", "invalid array declaration"),
    ("E126", "instruction used in the wrong place or language"),
    ("E127", "EXIT outside a loop"),
    ("E128", "'?' placeholder or empty operand where a value is required"),
    ("E129", "empty rung"),
    ("E130", "named parameters are only for function blocks"),
    ("E131", "ladder label missing, repeated or misplaced"),
    ("E132", "a size or nesting limit is exceeded (docs/limits.md)"),
    ("E133", "literal out of range for any Logix type, or too long"),
    # warnings
    ("W201", "FOR index assigned in the loop body"),
    ("W202", "shorted ladder branch"),
    ("W203", "MOTION_INSTRUCTION tag used by several instructions"),
    ("W204", "transitional instruction reached every scan"),
    # not supported
    ("U301", "routine type not supported (FBD/SFC)"),
    ("U302", "protected (encoded) content not supported"),
    ("U303", "system attribute not simulated"),
    ("U304", "instruction recognised but not executable yet"),
    ("U305", "alias tag not simulated"),
    ("U306", "module data not in the export"),
]

# U (recognised, not simulated) is a warning: `check` passes and `run` runs what it can (SPEC 9.32).
_SEVERITY = {"S": Severity.ERROR, "E": Severity.ERROR, "W": Severity.WARNING, "U": Severity.WARNING}

REGISTRY: dict[str, Code] = {code: Code(code, _SEVERITY[code[0]], title) for code, title in _TABLE}


@dataclass(frozen=True, slots=True)
class Diagnostic:
    code: str
    message: str
    path: str
    span: Span

    @property
    def severity(self) -> Severity:
        return REGISTRY[self.code].severity

    def text(self) -> str:
        return (
            f"{self.path}:{self.span.line}:{self.span.col}: "
            f"{self.severity.value} {self.code} {self.message}"
        )

    def to_json(self) -> dict[str, object]:
        return {
            "path": self.path,
            "line": self.span.line,
            "column": self.span.col,
            "endLine": self.span.end_line,
            "endColumn": self.span.end_col,
            "severity": self.severity.value,
            "code": self.code,
            "message": self.message,
        }

    def sort_key(self) -> tuple[str, int, int, str]:
        return (self.path, self.span.line, self.span.col, self.code)


def diag(code: str, message: str, path: str, span: Span) -> Diagnostic:
    if code not in REGISTRY:
        raise KeyError(f"unregistered diagnostic code {code}")
    return Diagnostic(code, message, path, span)


def has_errors(diags: list[Diagnostic]) -> bool:
    return any(d.severity is Severity.ERROR for d in diags)
