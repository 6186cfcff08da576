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
  SYSPLACE name       push the place of a status flag (ladder OTU(S:V) writes it)
  SETSYS (name, v)    set the controller flag `name` to v (ladder FOR/BRK: the break flag)
  LOAD type           pop place, push its value
  STORE type          pop value, pop place, convert the value to `type` and store it
                      (a structure or array value is copied element by element)
  REF type            pop place, push a reference object (Ref/BitRef) for an instruction
  AREF type dims      pop place of an array element, push an ArrayRef from that element
  VALUE               pop place, push the structure/array object itself (by reference)
  CONV (from, to)     convert the top value
  NEG type, NOT type  unary operators
  BIN (op, type)      pop b, a; push a op b computed in `type` (wraps, float32 rounding)
  CMP (op, type)      pop b, a; push BOOL
  FN (key, type, n)   pop n arguments (2 for ATAN2, else 1), call the catalog function, push the result as `type`
  RETV (i, type)      push return value i of the last JSR, converted to `type`
  RETN n              push whether the last JSR's routine returned values (RET); a RET with
                      another count than n is major fault 4/31
Statements:
  CALL (key, n, rung) pop n operands, call the instruction implementation with the literal
                      rung condition `rung` (True in ST; ladder transitional calls pass
                      True on the rung's rising edge and False on a false rung)
  PRESCAN (key, n)    same, the instruction's prescan action (rung True in ST, False in ladder)
  JSR name            call another routine of the program (clears the return values first)
  SETRV n             pop n values: the return values handed back to the calling JSR (RET)
  RETURN              leave the routine at once (RET, TND)
  FAULT (t, c, text)  raise major fault type t code c
  IF / ELSE / END     pop a condition; structured blocks
  LOOP / END          an endless loop left by BREAK
  BREAK, BREAK_IFNOT  leave the innermost LOOP (BREAK_IFNOT pops a condition)
  TSET k / TGET k     temporaries (CASE selector, FOR bounds)
  STEP n loop         count n statements for the watchdog (loop=True also checks the budget)
  POP                 drop the top value (a pure expression)

Ladder (ladder_compiler.py). The rung condition is a value like any other: it flows on the
stack as a pure expression and is kept in a temporary (TSET/TGET) wherever an output
instruction needs it. Rung values are truthy (0/1/True/False); stores normalise them.
  LAND, LOR           pop b, a; push the rung condition a AND b / a OR b (b is not read when
                      a decides the result: a false rung does not execute its inputs)
  RCALL (key, n)      pop n operands and the rung condition beneath them; call the ladder
                      implementation impl(ctx, rung, *operands); push the rung-out (its
                      result, or the rung when it returns None)
  EDGE k              push the place of edge bit k (BOOL) of this routine: the rung state a
                      transitional instruction's call site saw last time
  STOREF type         STORE that also sets the math status flags S:N, S:Z and S:V (the
                      value did not fit `type`, or an operation between OVF True and the
                      store overflowed) from the stored value (ladder MOV, CPT, FAL)
  OVF on              on=True: until OVF False, BIN, NEG and FN results that do not fit
                      their type (integer out of range, REAL not finite, division by zero)
                      note an overflow for the next STOREF (ladder CPT and FAL expressions)
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
    SYSPLACE = "SYSPLACE"
    SETSYS = "SETSYS"
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
    POP = "POP"
    RETV = "RETV"
    RETN = "RETN"
    SETRV = "SETRV"
    RETURN = "RETURN"
    FAULT = "FAULT"
    LAND = "LAND"
    LOR = "LOR"
    RCALL = "RCALL"
    EDGE = "EDGE"
    STOREF = "STOREF"
    OVF = "OVF"


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
    language: str = "st"  # which implementation of a two-language instruction calls use
    edges: list[int] = field(default_factory=list)  # edge bits of transitional call sites (EDGE k)

    def site(self, path: str, span: Span) -> int:
        self.sites.append((path, span))
        return len(self.sites) - 1

    def dump(self) -> str:
        return "\n".join(str(i) for i in self.ops)
