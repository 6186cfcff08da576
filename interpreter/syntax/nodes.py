"""AST for Logix Structured Text, ladder rungs and declarations.

Every node carries `span`: (line, column, end_line, end_column), 1-based, end exclusive,
in the coordinates of the file the user opened (for L5X: the .L5X file itself).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import NamedTuple


class Span(NamedTuple):
    line: int
    col: int
    end_line: int
    end_col: int

    def to(self, other: Span) -> Span:
        return Span(self.line, self.col, other.end_line, other.end_col)


NOWHERE = Span(1, 1, 1, 1)


# ---------------------------------------------------------------- expressions
@dataclass(slots=True)
class Literal:
    value: object  # int, float, bytes (STRING) or bool
    type: str  # DINT, LINT, UDINT, ULINT, REAL, STRING, BOOL
    text: str
    span: Span


@dataclass(slots=True)
class Name:
    ident: str
    span: Span


@dataclass(slots=True)
class Member:
    base: Expr
    name: str
    span: Span
    name_span: Span


@dataclass(slots=True)
class Index:
    base: Expr
    indices: list[Expr]
    span: Span


@dataclass(slots=True)
class Bit:
    base: Expr
    bit: int
    span: Span


@dataclass(slots=True)
class IndirectBit:
    base: Expr
    index: Expr
    span: Span


@dataclass(slots=True)
class Unary:
    op: str  # "-", "NOT"
    operand: Expr
    span: Span


@dataclass(slots=True)
class Binary:
    op: str  # "+","-","*","/","MOD","**","=","<>","<","<=",">",">=","AND","OR","XOR"
    left: Expr
    right: Expr
    span: Span


@dataclass(slots=True)
class Call:
    name: str
    args: list[Arg]
    span: Span
    name_span: Span


@dataclass(slots=True)
class EnumText:
    """An operand written as enumeration text that is not an identifier (`%ofTime`, `S-Curve`)."""

    text: str
    span: Span


@dataclass(slots=True)
class Placeholder:
    """Ladder `?` or an empty operand: the value lives in the tag."""

    span: Span


Expr = (
    Literal
    | Name
    | Member
    | Index
    | Bit
    | IndirectBit
    | Unary
    | Binary
    | Call
    | EnumText
    | Placeholder
)


@dataclass(slots=True)
class Arg:
    value: Expr
    name: str | None = None  # IEC named parameter (`Master := X`)
    span: Span = NOWHERE


# ---------------------------------------------------------------- statements
@dataclass(slots=True)
class Assign:
    target: Expr
    value: Expr
    nonretentive: bool
    span: Span


@dataclass(slots=True)
class CallStmt:
    call: Call
    span: Span


@dataclass(slots=True)
class If:
    branches: list[tuple[Expr, list[Stmt]]]
    else_body: list[Stmt] | None
    span: Span


@dataclass(slots=True)
class CaseRange:
    low: Expr
    high: Expr
    span: Span


@dataclass(slots=True)
class CaseArm:
    labels: list[Expr | CaseRange]
    body: list[Stmt]
    span: Span


@dataclass(slots=True)
class Case:
    selector: Expr
    arms: list[CaseArm]
    else_body: list[Stmt] | None
    span: Span


@dataclass(slots=True)
class For:
    var: Expr
    start: Expr
    end: Expr
    step: Expr | None
    body: list[Stmt]
    span: Span


@dataclass(slots=True)
class While:
    cond: Expr
    body: list[Stmt]
    span: Span


@dataclass(slots=True)
class Repeat:
    body: list[Stmt]
    cond: Expr
    span: Span


@dataclass(slots=True)
class Exit:
    span: Span


@dataclass(slots=True)
class Unsupported:
    """A statement that parses but is not Logix ST (RETURN, GOTO ...): a verification error."""

    keyword: str
    span: Span


@dataclass(slots=True)
class Empty:
    span: Span


Stmt = Assign | CallStmt | If | Case | For | While | Repeat | Exit | Unsupported | Empty


# ---------------------------------------------------------------- ladder
@dataclass(slots=True)
class LadderInstr:
    name: str
    operands: list[Expr]
    span: Span
    name_span: Span


@dataclass(slots=True)
class Branch:
    legs: list[list[LadderElement]]
    span: Span


LadderElement = LadderInstr | Branch


@dataclass(slots=True)
class Rung:
    elements: list[LadderElement]
    span: Span
    number: int = 0
    comment: str | None = None


# ---------------------------------------------------------------- declarations
@dataclass(slots=True)
class TypeRef:
    name: str
    dims: list[tuple[int, int]]  # (low, high) per dimension, outermost first
    span: Span


@dataclass(slots=True)
class ArrayInit:
    items: list[Init]
    span: Span


@dataclass(slots=True)
class StructInit:
    members: list[tuple[str, Span, Init]]
    span: Span


Init = Expr | ArrayInit | StructInit


@dataclass(slots=True)
class VarDecl:
    names: list[tuple[str, Span]]
    type: TypeRef
    init: Init | None
    span: Span
    block: str = "VAR"


@dataclass(slots=True)
class TypeDecl:
    name: str
    members: list[VarDecl]
    span: Span
    name_span: Span
    # an L5X DataType of Class ProductDefined or IO: Studio's description of a built-in or
    # module-defined type (ExportOptions ProductDefinedTypes, IOTags), not a user's definition
    described: bool = False


@dataclass(slots=True)
class Comment:
    text: str
    span: Span


@dataclass(slots=True)
class Routine:
    """One routine: a parsed `.st` or `.rll` file, or an L5X routine."""

    name: str
    language: str  # "st" | "rll"
    path: str
    body: list[Stmt] = field(default_factory=list)
    rungs: list[Rung] = field(default_factory=list)
    types: list[TypeDecl] = field(default_factory=list)
    decls: list[VarDecl] = field(default_factory=list)
    comments: list[Comment] = field(default_factory=list)
    program_name: str | None = None
    span: Span = NOWHERE
