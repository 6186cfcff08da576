"""The one intermediate representation for ST and ladder: a typed, structured stack bytecode.

A routine is a flat list of `Ins`. Values and *places* (storage locations) live on an
operand stack. Control flow is structured (IF/ELSE/END, LOOP/BREAK/END) rather than jumps,
so a VM tier can translate it to Python code objects one-to-one; ladder JMP/LBL is lowered
by the ladder compiler onto the same LOOP/BREAK forms. `site` indexes the routine's site
table (file, span) for faults.

Places:
  TAG slot            push the place of tag `slot`
  MEMBER i            place -> its member i
  INDEX sizes         pop len(sizes) subscripts; place -> element (bounds checked, fault 4/20)
  BIT (b, type)       place -> bit b of the integer (of `type`) at place
  IBIT type           pop a bit number; place -> that bit (checked 0..bits-1, fault 4/20)
Values:
  CONST v type        push a constant
  SYS name            push a system flag (S:FS ...)
  LOAD type           pop place, push its value
  STORE type          pop value, pop place, convert the value to `type` and store it
  REF type            pop place, push a reference object (Ref/BitRef) for an instruction
  AREF type dims      pop place of an array element, push an ArrayRef from that element
  VALUE               pop place, push the structure/array object itself (by reference)
  CONV (from, to)     convert the top value
  NEG type, NOT type  unary operators
  BIN (op, type)      pop b, a; push a op b computed in `type` (wraps, float32 rounding)
  CMP (op, type)      pop b, a; push BOOL
  FN (key, type)      pop the argument, call the catalog function, push the result as `type`
Statements:
  CALL (key, n, rung) pop n operands, call the instruction implementation
  PRESCAN (key, n)    same, the instruction's prescan action
  JSR name            call another routine of the program
  IF / ELSE / END     pop a condition; structured blocks
  LOOP / END          an endless loop left by BREAK
  BREAK, BREAK_IFNOT  leave the innermost LOOP (BREAK_IFNOT pops a condition)
  TSET k / TGET k     temporaries (CASE selector, FOR bounds)
  STEP n loop         count n statements for the watchdog (loop=True also checks the budget)
"""

from __future__ import annotations

from dataclasses import dataclass, field
from enum import Enum

from ..syntax.nodes import Span


class Op(Enum):
    TAG = "TAG"
    MEMBER = "MEMBER"
    INDEX = "INDEX"
    BIT = "BIT"
    IBIT = "IBIT"
    CONST = "CONST"
    SYS = "SYS"
    LOAD = "LOAD"
    STORE = "STORE"
    REF = "REF"
    AREF = "AREF"
    VALUE = "VALUE"
    CONV = "CONV"
    NEG = "NEG"
    NOT = "NOT"
    BIN = "BIN"
    CMP = "CMP"
    FN = "FN"
    CALL = "CALL"
    PRESCAN = "PRESCAN"
    JSR = "JSR"
    IF = "IF"
    ELSE = "ELSE"
    END = "END"
    LOOP = "LOOP"
    BREAK = "BREAK"
    BREAK_IFNOT = "BREAK_IFNOT"
    TSET = "TSET"
    TGET = "TGET"
    STEP = "STEP"


@dataclass(frozen=True, slots=True)
class Ins:
    op: Op
    arg: object = None
    site: int = -1

    def __str__(self) -> str:
        arg = "" if self.arg is None else f" {self.arg}"
        return f"{self.op.value}{arg}"


@dataclass(slots=True)
class Code:
    """Bytecode of one routine plus its site table and its prescan code."""

    name: str
    path: str
    ops: list[Ins] = field(default_factory=list)
    prescan: list[Ins] = field(default_factory=list)
    sites: list[tuple[str, Span]] = field(default_factory=list)
    temps: int = 0

    def site(self, path: str, span: Span) -> int:
        self.sites.append((path, span))
        return len(self.sites) - 1

    def dump(self) -> str:
        return "\n".join(str(i) for i in self.ops)
