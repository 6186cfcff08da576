"""Lower checked ladder routines to the shared bytecode (DESIGN: no second interpreter).

The rung condition is an ordinary value: it starts true, input instructions AND into it,
a branch ORs its legs, and it is kept in a temporary wherever an output needs it (SPEC
3.2). Contacts, coils, compares, MOV, CPT, CMP, FAL, FSC and program control are lowered
here to inline bytecode; every other instruction is an RCALL of its implementation that
passes the rung condition and takes the rung-out back. Decisions: docs/decisions/0020-0023.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from stdlib import Instruction, catalog

from ..instructions.registry import LOWERED, lookup_prescan
from ..semantics.checker import Analysis, unimplemented
from ..semantics.ladder_check import rung_instructions
from ..semantics.program import ProgramModel, const_number
from ..semantics.types import BOOL, DINT, LREAL, Elementary, StructType, promote
from ..syntax import nodes as n
from .bytecode import Code, Op
from .st_compiler import RoutineCompiler

COMPARE = {"EQU": "=", "NEQ": "<>", "GRT": ">", "GEQ": ">=", "LES": "<", "LEQ": "<="}
PURE = frozenset({"XIC", "XIO", "CMP", "AFI", "NOP", *COMPARE})  # inputs with no side effect
FAL_ALL, FAL_INC = 0, -1  # FAL_Mode enumeration values; a positive number = elements per scan
_SKIP_ALL = 1 << 30  # pc value past every segment: skip the rest of the pass (backward JMP)


@dataclass(slots=True)
class _Jumps:
    """Where the routine's labels are: rungs are grouped into segments that start at an LBL."""

    segment_of: list[int] = field(default_factory=list)  # rung index -> segment
    label_segment: dict[str, int] = field(default_factory=dict)  # upper-case label -> segment
    backward: bool = False  # some JMP targets its own or an earlier segment: a loop is needed
    pc: int = -1  # temporaries: next segment to run, pending backward target
    back: int = -1


def _label(e: n.Expr | None) -> str:
    return e.ident.upper() if isinstance(e, n.Name) else ""


class LadderCompiler(RoutineCompiler):
    def __init__(
        self,
        model: ProgramModel,
        analysis: Analysis,
        routine: n.Routine,
        sites: list | None = None,
        instance_edges: dict[int, int] | None = None,
    ) -> None:
        super().__init__(model, analysis, routine, sites)
        # An add-on instruction's routine keeps its edges in hidden members of the instance
        # (frame slot 0): id(instruction) -> member index (semantics/aoi.py, decision 0024).
        self.instance_edges = instance_edges or {}
        self.code.language = "rll"
        self.cat = catalog()
        self.rung_temps: list[int] = []  # rung condition per branch depth
        self.acc_temps: list[int] = []  # OR of the legs per branch depth
        self.edge_of: dict[int, int] = {}  # id(instruction) -> edge bit (transitional call sites)
        self.mcr: int | None = None  # temporary holding the MCR zone state
        self.jumps: _Jumps | None = None
        self.rung_index = 0

    # ------------------------------------------------------------ routine
    def compile(self) -> Code:
        rungs = self.r.rungs
        if any(i.name.upper() == "MCR" for r in rungs for i in rung_instructions(r.elements)):
            self.mcr = self.temp()
            self.emit(Op.CONST, (1, BOOL))
            self.emit(Op.TSET, self.mcr)
        self.jumps = self.plan_jumps(rungs)
        j = self.jumps
        if j is None:
            for i, rung in enumerate(rungs):
                self.rung_index = i
                self.rung(rung)
        else:
            self.emit(Op.CONST, (0, DINT))
            self.emit(Op.TSET, j.pc)
            if j.backward:
                self.emit(Op.CONST, (-1, DINT))
                self.emit(Op.TSET, j.back)
                self.emit(Op.LOOP)
            for i, rung in enumerate(rungs):
                self.emit(Op.TGET, (j.pc, DINT))  # skipped by a JMP: the rung is not scanned at all
                self.emit(Op.CONST, (j.segment_of[i], DINT))
                self.emit(Op.CMP, ("<=", DINT))
                self.emit(Op.IF)
                self.rung_index = i
                self.rung(rung)
                self.emit(Op.END)
            if j.backward:  # a backward JMP ran: start again at its label's segment
                self.emit(Op.TGET, (j.back, DINT))
                self.emit(Op.CONST, (0, DINT))
                self.emit(Op.CMP, (">=", DINT))
                self.emit(Op.BREAK_IFNOT)
                self.emit(Op.TGET, (j.back, DINT))
                self.emit(Op.TSET, j.pc)
                self.emit(Op.CONST, (-1, DINT))
                self.emit(Op.TSET, j.back)
                self.emit(Op.END)
        self.site_span = None
        self.prescan_rungs(rungs)
        return self.code

    def plan_jumps(self, rungs: list[n.Rung]) -> _Jumps | None:
        j = _Jumps()
        seg = 0
        targets: list[tuple[int, str]] = []
        for i, rung in enumerate(rungs):
            for k, ins in enumerate(rung_instructions(rung.elements)):
                name = ins.name.upper()
                if name == "LBL" and ins.operands:
                    if k == 0 and i > 0:
                        seg += 1
                    j.label_segment.setdefault(_label(ins.operands[0]), seg)
                elif name == "JMP" and ins.operands:
                    targets.append((i, _label(ins.operands[0])))
            j.segment_of.append(seg)
        if not targets:
            return None
        j.backward = any(
            j.label_segment.get(lbl, _SKIP_ALL) <= j.segment_of[i] for i, lbl in targets
        )
        j.pc = self.temp()
        j.back = self.temp() if j.backward else -1
        return j

    def rung(self, rung: n.Rung) -> None:
        count = sum(1 for _ in rung_instructions(rung.elements))
        if not count:
            return
        self.emit(Op.STEP, (count, False))  # SPEC 9.4: one step per ladder instruction
        has_mcr = any(i.name.upper() == "MCR" for i in rung_instructions(rung.elements))
        if self.mcr is not None and not has_mcr:
            self.emit(Op.TGET, (self.mcr, BOOL))  # inside a false MCR zone every rung starts false
        else:
            self.emit(Op.CONST, (1, BOOL))
        *head, tail = rung.elements
        self.elements(head, 0)
        if isinstance(tail, n.Branch) and not self.is_pure([tail]):
            self.branch(tail, 0, result=False)  # nothing follows: the legs' OR is not needed
        else:
            self.elements([tail], 0)
        self.emit(Op.POP)
        self.site_span = None

    # ------------------------------------------------------------ rung logic
    def rung_temp(self, depth: int) -> int:
        while len(self.rung_temps) <= depth:
            self.rung_temps.append(self.temp())
        return self.rung_temps[depth]

    def acc_temp(self, depth: int) -> int:
        while len(self.acc_temps) <= depth:
            self.acc_temps.append(self.temp())
        return self.acc_temps[depth]

    def hold(self, depth: int) -> int:
        """Keep the rung condition (top of stack) in this depth's temporary; leave it there too."""
        last = self.ops[-1] if self.ops else None
        if last is not None and last.op is Op.TGET and last.arg[1] is BOOL:  # type: ignore[index]
            # Already a temporary of this or an outer depth, which nothing at this depth
            # reassigns before the rung moves on: use it as it is.
            return last.arg[0]  # type: ignore[index, no-any-return]
        k = self.rung_temp(depth)
        self.emit(Op.TSET, k)
        self.emit(Op.TGET, (k, BOOL))
        return k

    def elements(self, elements: list[n.LadderElement], depth: int) -> None:
        for el in elements:
            if isinstance(el, n.Branch):
                self.branch(el, depth)
            else:
                self.instruction(el, depth)

    def is_pure(self, elements: list[n.LadderElement]) -> bool:
        for el in elements:
            if isinstance(el, n.Branch):
                if not all(self.is_pure(leg) for leg in el.legs):
                    return False
            elif self.name_of(el) not in PURE:
                return False
        return True

    def branch(self, b: n.Branch, depth: int, result: bool = True) -> None:
        if all(self.is_pure(leg) for leg in b.legs):
            # Inputs only: in AND (leg1 OR leg2 ...), one expression, nothing stored.
            for i, leg in enumerate(b.legs):
                self.emit(Op.CONST, (1, BOOL))
                self.elements(leg, depth + 1)
                if i:
                    self.emit(Op.LOR)
            self.emit(Op.LAND)
            return
        k_in = self.rung_temp(depth)
        acc = self.acc_temp(depth)
        self.emit(Op.TSET, k_in)
        for i, leg in enumerate(b.legs):
            self.emit(Op.TGET, (k_in, BOOL))  # every leg starts with the incoming condition
            self.elements(leg, depth + 1)
            if not result:
                self.emit(Op.POP)
                continue
            if i:
                self.emit(Op.TGET, (acc, BOOL))
                self.emit(Op.LOR)
            self.emit(Op.TSET, acc)
        self.emit(Op.TGET, (acc, BOOL) if result else (k_in, BOOL))

    def name_of(self, ins: n.LadderInstr) -> str:
        cat = self.catalog_entry(ins)
        return cat.name if cat is not None else ins.name.upper()

    def catalog_entry(self, ins: n.LadderInstr) -> Instruction | None:
        return self.a.call_of.get(id(ins)) or self.cat.instruction(ins.name, "rll")

    # ------------------------------------------------------------ instructions
    def instruction(self, ins: n.LadderInstr, depth: int) -> None:  # noqa: C901
        cat = self.catalog_entry(ins)
        assert cat is not None, f"unchecked ladder instruction {ins.name}"
        if id(ins) in self.a.unsimulated:
            return  # uses a tag that is not simulated (U306): the rung condition passes on
        name = cat.name
        ops = ins.operands
        self.site_span = ins.span  # faults inside an instruction point at the instruction
        if name in ("XIC", "XIO"):
            self.value(ops[0], BOOL)
            if name == "XIO":
                self.emit(Op.NOT, BOOL)
            self.emit(Op.LAND)
        elif name in COMPARE:
            self.compare(ops[0], ops[1], COMPARE[name])
            self.emit(Op.LAND)
        elif name == "CMP":
            self.value(ops[0], BOOL)
            self.emit(Op.LAND)
        elif name == "AFI":
            self.emit(Op.POP)
            self.emit(Op.CONST, (0, BOOL))
        elif name in ("NOP", "LBL", "SBR"):
            pass
        elif name in ("OTE", "OTL", "OTU"):
            k = self.hold(depth)
            self.emit(Op.IF)
            self.store_bit(ops[0], 0 if name == "OTU" else 1)
            if name == "OTE":
                self.emit(Op.ELSE)
                self.store_bit(ops[0], 0)
            self.emit(Op.END)
            self.emit(Op.TGET, (k, BOOL))
        elif name in ("MOV", "CPT"):
            src, dest = (ops[0], ops[1]) if name == "MOV" else (ops[1], ops[0])
            self.when_true(depth, lambda: self.move(src, dest, ins.span, checked=name == "CPT"))
        elif name == "MCR":
            k = self.hold(depth)
            assert self.mcr is not None
            self.emit(Op.TSET, self.mcr)
            self.emit(Op.TGET, (k, BOOL))
        elif name == "JMP":
            self.when_true(depth, lambda: self.jump(_label(ops[0]), ins.span))
        elif name in ("TND", "RET", "JSR"):
            self.when_true(depth, lambda: self.program_control(name, list(ops), ins.span))
        elif name == "FOR":
            self.when_true(depth, lambda: self.ladder_for(list(ops), ins.span))
        elif name == "BRK":
            self.when_true(depth, self.brk)
        elif name in ("FAL", "FSC"):
            self.file_op(name, ins, depth)
        elif unimplemented(cat, "rll"):
            pass  # U304: not simulated; the rung condition passes on, operands keep their values
        elif cat.transitional:
            self.transitional(ins, cat, depth)
        else:
            count = self.operands(self.as_call(ins), cat)
            self.emit(Op.RCALL, (cat.key, count), ins.span)

    def ladder_for(self, ops: list[n.Expr], span: n.Span) -> None:
        """FOR(Routine, Index, Initial, Terminal, Step): the routine runs while Index has not
        passed Terminal (above it for Step >= 0, below it for Step < 0), Index += Step after
        each pass; Terminal and Step are read before every pass, as the tags may change. A
        BRK in the routine sets the break flag and returns: the loop ends (decision 0033)."""
        target, index, initial, terminal, step = ops
        assert isinstance(target, n.Name)
        routine = self.model.routine(target.ident, self.r.program_name)
        assert routine is not None  # the checker reported an unknown routine (E124)
        self.place(index)
        self.value(initial, DINT)
        self.emit(Op.STORE, DINT, span)
        self.emit(Op.LOOP)
        self.emit(Op.STEP, (1, True), span)  # every pass counts for the watchdog (SPEC 9.4)
        # (Step >= 0 AND Index <= Terminal) OR (Step < 0 AND Index >= Terminal)
        for rel, idx_rel in ((">=", "<="), ("<", ">=")):
            self.value(step, DINT)
            self.emit(Op.CONST, (0, DINT))
            self.emit(Op.CMP, (rel, DINT))
            self.value(index, DINT)
            self.value(terminal, DINT)
            self.emit(Op.CMP, (idx_rel, DINT))
            self.emit(Op.BIN, ("AND", BOOL))
        self.emit(Op.BIN, ("OR", BOOL))
        self.emit(Op.BREAK_IFNOT)
        self.emit(Op.SETSYS, ("BRK", 0))
        self.emit(Op.JSR, routine.name, span)
        self.emit(Op.SYS, "BRK")
        self.emit(Op.IF)
        self.emit(Op.SETSYS, ("BRK", 0))
        self.emit(Op.BREAK)
        self.emit(Op.END)
        self.place(index)
        self.value(index, DINT)
        self.value(step, DINT)
        self.emit(Op.BIN, ("+", DINT))
        self.emit(Op.STORE, DINT, span)
        self.emit(Op.END)

    def brk(self) -> None:
        """BRK: end the routine a FOR called and tell the FOR to stop (decision 0033)."""
        self.emit(Op.SETSYS, ("BRK", 1))
        self.emit(Op.RETURN)

    def as_call(self, ins: n.LadderInstr) -> n.Call:
        return n.Call(
            ins.name, [n.Arg(e, None, e.span) for e in ins.operands], ins.span, ins.name_span
        )

    def when_true(self, depth: int, body) -> None:  # type: ignore[no-untyped-def]
        """An output acting only on a true rung; the rung passes through unchanged."""
        k = self.hold(depth)
        self.emit(Op.IF)
        body()
        self.emit(Op.END)
        self.emit(Op.TGET, (k, BOOL))

    def store_bit(self, e: n.Expr, bit: int) -> None:
        self.place(e)
        self.emit(Op.CONST, (bit, BOOL))
        self.emit(Op.STORE, BOOL, e.span)

    def compare(self, a: n.Expr, b: n.Expr, op: str) -> None:
        lt, rt = self.type_of(a), self.type_of(b)
        if isinstance(lt, StructType):  # STRING compare
            self.expr(a)
            self.expr(b)
            self.emit(Op.CMP, (op, lt))
            return
        assert isinstance(lt, Elementary) and isinstance(rt, Elementary)
        ot = promote(lt, rt)  # exactly the type an ST comparison uses
        self.value(a, ot)
        self.value(b, ot)
        self.emit(Op.CMP, (op, ot))

    def move(self, src: n.Expr, dest: n.Expr, span: n.Span, checked: bool = False) -> None:
        """dest := src converted like an ST assignment; S:N S:Z S:V from the stored value.

        `checked` (CPT, FAL): an overflow in any operation of the expression also sets S:V
        (decision 0025)."""
        t = self.type_of(dest)
        self.place(dest)
        if isinstance(t, StructType):  # MOV of a string (tag or literal): as ST's s := 'text'
            self.value(src, t)
            self.emit(Op.STORE, t, span)
            return
        if isinstance(src, n.Literal) and isinstance(src.value, float) and t is LREAL:
            self.emit(
                Op.CONST, (src.value, LREAL)
            )  # a REAL literal keeps double precision in LREAL
        else:
            if checked:
                self.emit(Op.OVF, True)
            self.expr(src)  # in its own (promoted) type: STOREF converts at the end (SPEC 9.19)
            if checked:
                self.emit(Op.OVF, False)
        self.emit(Op.STOREF, t, span)

    def jump(self, label: str, span: n.Span) -> None:
        j = self.jumps
        assert j is not None
        target = j.label_segment.get(label)
        if target is None:  # the checker reports unknown labels; nothing runs then
            return
        if target > j.segment_of[self.rung_index]:  # forward: the rungs in between are skipped
            self.emit(Op.CONST, (target, DINT))
            self.emit(Op.TSET, j.pc)
            return
        # Backward: the loop's continue. Skip the rest of this pass, restart at the label's
        # segment; the watchdog is checked at every backward jump (SPEC 9.4).
        self.emit(Op.CONST, (target, DINT))
        self.emit(Op.TSET, j.back)
        self.emit(Op.CONST, (_SKIP_ALL, DINT))
        self.emit(Op.TSET, j.pc)
        self.emit(Op.STEP, (0, True), span)

    def edge(self, ins: n.LadderInstr) -> None:
        """Push the place of the bit remembering the rung `ins` saw last time."""
        member = self.instance_edges.get(id(ins))
        if member is not None:  # per add-on instruction instance
            self.emit(Op.TAG, 0)
            self.emit(Op.MEMBER, member)
            return
        e = self.edge_of.setdefault(id(ins), len(self.code.edges))
        if e == len(self.code.edges):
            self.code.edges.append(0)
        self.emit(Op.EDGE, e)

    def transitional(self, ins: n.LadderInstr, cat: Instruction, depth: int) -> None:
        """Call with True on the rung's rising edge, with False on every false rung, not otherwise."""
        call = self.as_call(ins)
        k = self.hold(depth)
        self.emit(Op.IF)
        self.edge(ins)
        self.emit(Op.LOAD, BOOL)
        self.emit(Op.NOT, BOOL)
        self.emit(Op.IF)
        self.edge(ins)
        self.emit(Op.CONST, (1, BOOL))
        self.emit(Op.STORE, BOOL)
        count = self.operands(call, cat)
        self.emit(Op.CALL, (cat.key, count, True), ins.span)
        self.emit(Op.END)
        self.emit(Op.ELSE)
        self.edge(ins)
        self.emit(Op.CONST, (0, BOOL))
        self.emit(Op.STORE, BOOL)
        count = self.operands(call, cat)
        self.emit(Op.CALL, (cat.key, count, False), ins.span)
        self.emit(Op.END)
        self.emit(Op.TGET, (k, BOOL))

    # ------------------------------------------------------------ FAL / FSC
    def member(self, ctl: n.Expr, name: str) -> Elementary:
        """Push the place of CONTROL member `name`; returns its type."""
        ct = self.type_of(ctl)
        assert isinstance(ct, StructType)
        idx, mt = ct.index[name], ct.members[ct.index[name]][1]
        self.place(ctl)
        self.emit(Op.MEMBER, idx)
        assert isinstance(mt, Elementary)
        return mt

    def load_member(self, ctl: n.Expr, name: str) -> None:
        self.emit(Op.LOAD, self.member(ctl, name))

    def set_member(self, ctl: n.Expr, name: str, value: int) -> None:
        t = self.member(ctl, name)
        self.emit(Op.CONST, (value, t))
        self.emit(Op.STORE, t)

    def file_mode(self, e: n.Expr) -> int:
        mode = self.a.enum_of.get(id(e))
        if mode is None:
            num = const_number(e)
            mode = num if isinstance(num, int) else FAL_ALL
        return mode

    def file_op(self, name: str, ins: n.LadderInstr, depth: int) -> None:
        """FAL and FSC on a CONTROL (docs/decisions/0022-fal-fsc.md)."""
        ctl, mode = ins.operands[0], self.file_mode(ins.operands[3])
        k = self.hold(depth)
        self.emit(Op.IF)
        self.load_member(ctl, "ER")  # an error stops the instruction until the program clears ER
        self.emit(Op.NOT, BOOL)
        if name == "FSC":
            self.load_member(ctl, "IN")  # a match inhibits the search until IN is cleared
            self.emit(Op.NOT, BOOL)
            self.emit(Op.BIN, ("AND", BOOL))
        self.emit(Op.IF)
        # INC: one element per false-to-true transition (EN holds the last rung state);
        # ALL and numeric mode: until done (DN), ALL in one scan, numeric N per scan.
        self.load_member(ctl, "EN" if mode == FAL_INC else "DN")
        self.emit(Op.NOT, BOOL)
        self.emit(Op.IF)
        self.file_elements(name, ins, None if mode == FAL_ALL else max(1, mode))
        self.emit(Op.END)
        self.emit(Op.END)
        self.set_member(ctl, "EN", 1)
        self.emit(Op.ELSE)
        self.set_member(ctl, "EN", 0)
        self.load_member(ctl, "DN")  # a false rung after completion re-arms the instruction
        self.emit(Op.IF)
        self.set_member(ctl, "DN", 0)
        self.set_member(ctl, "POS", 0)
        self.emit(Op.END)
        self.emit(Op.END)
        self.emit(Op.TGET, (k, BOOL))

    def bump_pos(self, ctl: n.Expr) -> None:
        self.member(ctl, "POS")
        self.load_member(ctl, "POS")
        self.emit(Op.CONST, (1, DINT))
        self.emit(Op.BIN, ("+", DINT))
        self.emit(Op.STORE, DINT)

    def pos_vs_len(self, ctl: n.Expr, op: str) -> None:
        self.load_member(ctl, "POS")
        self.load_member(ctl, "LEN")
        self.emit(Op.CMP, (op, DINT))

    def file_elements(self, name: str, ins: n.LadderInstr, limit: int | None) -> None:
        ctl = ins.operands[0]
        # LEN <= 0 or POS < 0 is an error (ER) and nothing is processed.
        self.load_member(ctl, "LEN")
        self.emit(Op.CONST, (0, DINT))
        self.emit(Op.CMP, ("<=", DINT))
        self.load_member(ctl, "POS")
        self.emit(Op.CONST, (0, DINT))
        self.emit(Op.CMP, ("<", DINT))
        self.emit(Op.BIN, ("OR", BOOL))
        self.emit(Op.IF)
        self.set_member(ctl, "ER", 1)
        self.emit(Op.ELSE)
        if name == "FSC":  # resuming after a match: continue with the next element
            self.load_member(ctl, "FD")
            self.emit(Op.IF)
            self.set_member(ctl, "FD", 0)
            self.bump_pos(ctl)
            self.emit(Op.END)
        left = -1
        if limit is not None:
            left = self.temp()
            self.emit(Op.CONST, (limit, DINT))
            self.emit(Op.TSET, left)
        self.emit(Op.LOOP)
        self.emit(Op.STEP, (1, True), ins.span)  # each element counts for the watchdog
        self.pos_vs_len(ctl, "<")
        self.emit(Op.BREAK_IFNOT)
        if limit is not None:
            self.emit(Op.TGET, (left, DINT))
            self.emit(Op.CONST, (0, DINT))
            self.emit(Op.CMP, (">", DINT))
            self.emit(Op.BREAK_IFNOT)
            self.emit(Op.TGET, (left, DINT))
            self.emit(Op.CONST, (1, DINT))
            self.emit(Op.BIN, ("-", DINT))
            self.emit(Op.TSET, left)
        if name == "FAL":
            dest, expr = ins.operands[4], ins.operands[5]
            self.move(expr, dest, ins.span, checked=True)
            self.emit(Op.SYS, "V")  # overflow: ER, stop on this element
            self.emit(Op.IF)
            self.set_member(ctl, "ER", 1)
            self.emit(Op.BREAK)
            self.emit(Op.END)
        else:
            self.value(ins.operands[4], BOOL)
            self.emit(Op.IF)  # a match: FD and IN, POS stays on the element
            self.set_member(ctl, "FD", 1)
            self.set_member(ctl, "IN", 1)
            self.emit(Op.BREAK)
            self.emit(Op.END)
        self.bump_pos(ctl)
        self.emit(Op.END)
        self.pos_vs_len(ctl, ">=")
        self.emit(Op.IF)
        self.set_member(ctl, "DN", 1)
        self.emit(Op.END)
        self.emit(Op.END)

    # ------------------------------------------------------------ prescan
    def prescan_rungs(self, rungs: list[n.Rung]) -> None:
        """SPEC 3.2 / 9.1: the rung is false; OTE clears, edges reset, prescan actions run."""
        main_ops = self.ops
        self.ops = self.code.prescan
        for rung in rungs:
            for ins in rung_instructions(rung.elements):
                cat = self.catalog_entry(ins)
                if cat is None or id(ins) in self.a.unsimulated:  # U306/U305: not executed
                    continue
                self.site_span = ins.span
                ops = ins.operands
                if cat.name == "OTE":
                    self.store_bit(ops[0], 0)
                elif cat.name in ("FAL", "FSC"):
                    ctl = ops[0]
                    for bit in ("EN", "DN", "ER") + (("FD", "IN") if cat.name == "FSC" else ()):
                        self.set_member(ctl, bit, 0)
                    for member, e in (
                        ("LEN", ops[1]),
                        ("POS", ops[2]),
                    ):  # the operands mirror LEN/POS
                        v = const_number(e)
                        if isinstance(v, int):
                            self.set_member(ctl, member, v)
                elif id(ins) in self.edge_of or id(ins) in self.instance_edges:
                    self.edge(ins)  # a rung true in the first scan is a transition
                    self.emit(Op.CONST, (0, BOOL))
                    self.emit(Op.STORE, BOOL)
                if cat.name not in LOWERED and (
                    cat.family == "aoi" or lookup_prescan(cat.name, "rll") is not None
                ):
                    # an add-on instruction's prescan runs its Logic routine's prescan (as in ST)
                    count = self.operands(self.as_call(ins), cat)
                    self.emit(Op.PRESCAN, (cat.key, count, False), ins.span)
        self.site_span = None
        self.ops = main_ops


def compile_ladder(
    model: ProgramModel,
    analysis: Analysis,
    routine: n.Routine,
    sites: list | None = None,
    instance_edges: dict[int, int] | None = None,
) -> Code:
    return LadderCompiler(model, analysis, routine, sites, instance_edges).compile()
