"""Lower checked ST routines to bytecode (see bytecode.py)."""

from __future__ import annotations

from stdlib import Instruction

from ..semantics.checker import Analysis, FBCall, int_literal_for_real, unimplemented
from ..semantics.program import ProgramModel, const_number
from ..semantics.types import (
    BOOL,
    DINT,
    LREAL,
    REAL,
    ArrayType,
    DataType,
    Elementary,
    StructType,
    promote,
)
from ..syntax import nodes as n
from .bytecode import Code, Ins, Op

_CMP = {"=", "<>", "<", "<=", ">", ">="}
_LOGIC = {"AND", "OR", "XOR"}


class RoutineCompiler:
    def __init__(
        self, model: ProgramModel, analysis: Analysis, routine: n.Routine, sites: list | None = None
    ) -> None:
        self.model = model
        self.a = analysis
        self.r = routine
        self.code = Code(routine.name, routine.path)
        if sites is not None:
            self.code.sites = sites  # one site table shared by all routines of a program
        self.ops = self.code.ops
        self.site_span: n.Span | None = None  # when set, every fault site points here

    # ------------------------------------------------------------ helpers
    def emit(self, op: Op, arg: object = None, span: n.Span | None = None) -> None:
        if span is not None and self.site_span is not None:
            span = self.site_span
        site = self.code.site(self.r.path, span) if span is not None else -1
        self.ops.append(Ins(op, arg, site))

    def type_of(self, e: n.Expr) -> DataType:
        return self.a.type_of[id(e)]

    def temp(self) -> int:
        self.code.temps += 1
        return self.code.temps - 1

    # ------------------------------------------------------------ statements
    def compile(self) -> Code:
        self.block(self.r.body, in_loop=False)
        self.prescan(self.r.body)
        return self.code

    def block(self, body: list[n.Stmt], in_loop: bool, loop: n.Span | None = None) -> None:
        simple = sum(1 for s in body if not isinstance(s, n.Empty))
        if in_loop:
            # An iteration without statements counts one (SPEC 9.4 counts loop iterations), so
            # `WHILE TRUE DO END_WHILE;` trips the watchdog instead of hanging; it is located at the loop.
            self.emit(Op.STEP, (max(simple, 1), True), body[0].span if simple else loop)
        elif simple:
            self.emit(Op.STEP, (simple, False))
        for s in body:
            self.stmt(s)

    def stmt(self, s: n.Stmt) -> None:
        if id(s) in self.a.unsimulated:  # uses a tag that is not simulated (U306): skipped
            return
        if isinstance(s, n.Assign):
            self.place(s.target)
            self.value(s.value, self.type_of(s.target))
            self.emit(Op.STORE, self.type_of(s.target), s.span)
        elif isinstance(s, n.CallStmt):
            self.call(s.call)
        elif isinstance(s, n.If):
            for i, (cond, body) in enumerate(s.branches):
                if i:
                    self.emit(Op.ELSE)
                self.cond(cond)
                self.emit(Op.IF)
                self.block(body, False)
            if s.else_body is not None:
                self.emit(Op.ELSE)
                self.block(s.else_body, False)
            for _ in s.branches:
                self.emit(Op.END)
        elif isinstance(s, n.Case):
            self.case(s)
        elif isinstance(s, n.For):
            self.for_loop(s)
        elif isinstance(s, n.While):
            self.emit(Op.LOOP)
            self.cond(s.cond)
            self.emit(Op.BREAK_IFNOT)
            self.block(s.body, True, s.span)
            self.emit(Op.END)
        elif isinstance(s, n.Repeat):
            self.emit(Op.LOOP)
            self.block(s.body, True, s.span)
            self.cond(s.cond)
            self.emit(Op.NOT, BOOL)
            self.emit(Op.BREAK_IFNOT)
            self.emit(Op.END)
        elif isinstance(s, n.Exit):
            self.emit(Op.BREAK)

    def cond(self, e: n.Expr) -> None:
        self.value(e, BOOL)

    def case(self, s: n.Case) -> None:
        sel_t = self.type_of(s.selector)
        k = self.temp()
        self.value(s.selector, sel_t)
        self.emit(Op.TSET, k)
        opened = 0
        for i, arm in enumerate(s.arms):
            if i:
                self.emit(Op.ELSE)
            first = True
            for label in arm.labels:
                if isinstance(label, n.CaseRange):
                    self.emit(Op.TGET, (k, sel_t))
                    self.const(label.low, sel_t)
                    self.emit(Op.CMP, (">=", sel_t))
                    self.emit(Op.TGET, (k, sel_t))
                    self.const(label.high, sel_t)
                    self.emit(Op.CMP, ("<=", sel_t))
                    self.emit(Op.BIN, ("AND", BOOL))
                else:
                    self.emit(Op.TGET, (k, sel_t))
                    self.const(label, sel_t)
                    self.emit(Op.CMP, ("=", sel_t))
                if not first:
                    self.emit(Op.BIN, ("OR", BOOL))
                first = False
            self.emit(Op.IF)
            opened += 1
            self.block(arm.body, False)
        if s.else_body is not None:
            if opened:
                self.emit(Op.ELSE)
                self.block(s.else_body, False)
            else:
                self.block(s.else_body, False)
        for _ in range(opened):
            self.emit(Op.END)

    def const(self, e: n.Expr, t: DataType) -> None:
        v = const_number(e)
        self.emit(Op.CONST, (v, DINT if isinstance(v, int) else t))
        src = DINT if isinstance(v, int) else t
        if src is not t:
            self.emit(Op.CONV, (src, t))

    def for_loop(self, s: n.For) -> None:
        var_t = self.type_of(s.var)
        assert isinstance(var_t, Elementary)
        end_k, step_k = self.temp(), self.temp()
        self.place(s.var)
        self.value(s.start, var_t)
        self.emit(Op.STORE, var_t, s.span)
        self.value(s.end, var_t)
        self.emit(Op.TSET, end_k)
        if s.step is None:
            self.emit(Op.CONST, (1, var_t))
        else:
            self.value(s.step, var_t)
        self.emit(Op.TSET, step_k)
        self.emit(Op.LOOP)
        # continue while (step >= 0 and i <= end) or (step < 0 and i >= end)
        step_const = const_number(s.step) if s.step is not None else 1
        if isinstance(step_const, int | float):
            self.place(s.var)
            self.emit(Op.LOAD, var_t)
            self.emit(Op.TGET, (end_k, var_t))
            self.emit(Op.CMP, ("<=" if step_const >= 0 else ">=", var_t))
        else:
            self.emit(Op.TGET, (step_k, var_t))
            self.emit(Op.CONST, (0, var_t))
            self.emit(Op.CMP, (">=", var_t))
            self.emit(Op.IF)
            self.place(s.var)
            self.emit(Op.LOAD, var_t)
            self.emit(Op.TGET, (end_k, var_t))
            self.emit(Op.CMP, ("<=", var_t))
            self.emit(Op.BREAK_IFNOT)
            self.emit(Op.ELSE)
            self.place(s.var)
            self.emit(Op.LOAD, var_t)
            self.emit(Op.TGET, (end_k, var_t))
            self.emit(Op.CMP, (">=", var_t))
            self.emit(Op.BREAK_IFNOT)
            self.emit(Op.END)
            self.emit(Op.CONST, (1, BOOL))
        self.emit(Op.BREAK_IFNOT)
        self.block(s.body, True, s.span)
        self.place(s.var)
        self.place(s.var)
        self.emit(Op.LOAD, var_t)
        self.emit(Op.TGET, (step_k, var_t))
        self.emit(Op.BIN, ("+", var_t), s.span)
        self.emit(Op.STORE, var_t, s.span)
        self.emit(Op.END)

    # ------------------------------------------------------------ calls
    def call(self, c: n.Call) -> None:
        fb = self.a.fb_of.get(id(c))
        if fb is not None:
            self.fb_call(c, fb)
            return
        ins = self.a.call_of[id(c)]
        if ins.name in ("JSR", "SBR", "RET", "TND"):
            self.program_control(ins.name, [a.value for a in c.args], c.span)
            return
        if unimplemented(ins, "st"):  # U304: not simulated, its operands keep their values
            return
        count = self.operands(c, ins)
        self.emit(Op.CALL, (ins.key, count, True), c.span)

    def operands(self, c: n.Call, ins: Instruction) -> int:
        for i, arg in enumerate(c.args):
            op = ins.operands[min(i, len(ins.operands) - 1)]
            e = arg.value
            if isinstance(e, n.Placeholder):  # ladder `?`: the implementation reads the tag
                self.emit(Op.CONST, (None, None))
                continue
            if id(e) in self.a.enum_of:
                self.emit(Op.CONST, (self.a.enum_of[id(e)], DINT))
                continue
            if op.format in ("routine", "task"):
                self.emit(Op.CONST, (e.ident if isinstance(e, n.Name) else "", None))
                continue
            if op.nullable and const_number(e) == 0:
                self.emit(Op.CONST, (None, None))  # optional array not used
                continue
            t = self.a.type_of.get(id(e))
            if op.format == "memory":
                self.place(e)
                if isinstance(t, ArrayType):  # whole array: walk from element 0
                    self.emit(Op.AREF, (t.elem, t.dims, False))
                else:
                    base_t = self.a.type_of.get(id(e.base)) if isinstance(e, n.Index) else None
                    dims = base_t.dims if isinstance(base_t, ArrayType) else ()
                    self.emit(Op.AREF, (t, dims, True))
                continue
            if op.format == "array" or (
                op.format == "array_or_value"
                and (isinstance(t, ArrayType) or isinstance(e, n.Index))
            ):
                arr_t = self.a.type_of[id(e.base)] if isinstance(e, n.Index) else t
                assert isinstance(arr_t, ArrayType)
                self.place(e)
                self.emit(Op.AREF, (arr_t.elem, arr_t.dims, isinstance(e, n.Index)))
                continue
            if isinstance(t, StructType | ArrayType):
                self.place(e)
                self.emit(Op.VALUE)
            elif op.dir in ("out", "inout") and isinstance(t, Elementary):
                self.place(e)
                self.emit(Op.REF, t)
            else:
                assert isinstance(t, Elementary)
                # an integer literal for a REAL operand is passed as REAL (SPEC 9.15)
                self.value(e, REAL if int_literal_for_real(e, t, op.types) else t)
        return len(c.args)

    # ------------------------------------------------------------ subroutines
    def program_control(self, name: str, args: list[n.Expr], span: n.Span) -> None:
        """JSR with parameters, SBR, RET and TND, shared by ST and ladder."""
        if name == "JSR":
            self.jsr(args, span)
        elif name == "RET":
            for e in args:
                t = self.type_of(e)
                self.value(e, t)
            self.emit(
                Op.SETRV, len(args)
            )  # RET() hands back no values: a JSR expecting some faults
            self.emit(Op.RETURN)
        elif name == "TND":
            self.emit(Op.RETURN)
        # SBR does nothing where it stands: the calling JSR stores the parameters into it.

    def jsr(self, args: list[n.Expr], span: n.Span) -> None:
        target = args[0]
        assert isinstance(target, n.Name)
        routine = self.model.routine(target.ident, self.r.program_name)  # L5X: within the program
        assert routine is not None
        count = const_number(args[1]) if len(args) > 1 else 0
        count = count if isinstance(count, int) and count > 0 else 0
        inputs, returns = args[2 : 2 + count], args[2 + count :]
        params = sbr_params(routine, self.a)
        saved, self.site_span = self.site_span, span  # parameter places live in the callee's file
        if len(inputs) < len(params):
            # 1756-RM003: a JSR with fewer input parameters than the SBR faults (4/31); more
            # are allowed, the extra ones are not received (decision 0073)
            self.emit(
                Op.FAULT,
                (
                    4,
                    31,
                    f"JSR passes {len(inputs)} parameter(s), the SBR of {routine.name} takes {len(params)}",
                ),
                span,
            )
        inputs = inputs[: len(params)]
        temps = []
        for e, p in zip(inputs, params, strict=False):  # evaluate every input before storing any
            k = self.temp()
            self.value(e, self.type_of(p))
            self.emit(Op.TSET, k)
            temps.append(k)
        for k, p in zip(temps, params, strict=False):
            pt = self.type_of(p)
            self.place(p)
            self.emit(Op.TGET, (k, pt))
            self.emit(Op.STORE, pt, span)
        self.emit(Op.JSR, routine.name, span)
        if returns:
            self.emit(Op.RETN, len(returns), span)
            self.emit(Op.IF)
            for i, e in enumerate(returns):
                t = self.type_of(e)
                self.place(e)
                self.emit(Op.RETV, (i, t))
                self.emit(Op.STORE, t, span)
            self.emit(Op.END)
        self.site_span = saved

    def fb_call(self, c: n.Call, fb: FBCall) -> None:
        """Elementary inputs are stored into the instance; axis and CAM-array inputs are
        references: the implementation gets them after the instance as (member index,
        value) pairs (an axis's storage list, an ArrayRef for an array)."""
        refs: list[tuple[int, DataType, n.Expr]] = []
        for idx, mt, value in fb.inputs:
            if not isinstance(mt, Elementary):
                refs.append((idx, mt, value))
                continue
            self.place(fb.instance)
            self.emit(Op.MEMBER, idx)
            self.value(value, mt)
            self.emit(Op.STORE, mt, value.span)
        self.place(fb.instance)
        self.emit(Op.VALUE)
        for idx, _mt, value in refs:
            self.emit(Op.CONST, (idx, None))
            t = self.type_of(value)
            self.place(value)
            if isinstance(t, ArrayType):
                self.emit(Op.AREF, (t.elem, t.dims, False))
            else:
                self.emit(Op.VALUE)
        self.emit(Op.CALL, (fb.instruction.key, 1 + 2 * len(refs), True), c.span)
        for idx, mt, target in fb.outputs:
            tt = self.type_of(target)
            self.place(target)
            self.place(fb.instance)
            self.emit(Op.MEMBER, idx)
            self.emit(Op.LOAD, mt)
            self.convert(mt, tt)
            self.emit(Op.STORE, tt, target.span)

    # ------------------------------------------------------------ expressions
    def place(self, e: n.Expr) -> None:
        if isinstance(e, n.Name) and id(e) in self.a.system_of:  # OTU(S:V) in ladder
            self.emit(Op.SYSPLACE, self.a.system_of[id(e)])
            return
        if isinstance(e, n.Name):
            tag = self.a.tag_of[id(e)]
            self.emit(Op.TAG, tag.slot)
            for pos in tag.access:  # AOI frame members, alias paths
                self.emit(Op.MEMBER, pos)
            if tag.bit is not None:  # an alias of one bit (semantics/alias.py)
                self.emit(Op.BIT, tag.bit)
        elif isinstance(e, n.Member):
            self.place(e.base)
            bt = self.type_of(e.base)
            assert isinstance(bt, StructType)
            self.emit(Op.MEMBER, bt.index[e.name.upper()])
        elif isinstance(e, n.Index):
            self.place(e.base)
            bt = self.type_of(e.base)
            assert isinstance(bt, ArrayType)
            for i in e.indices:
                self.value(i, DINT)
            self.emit(Op.INDEX, bt.dims, e.span)
        elif isinstance(e, n.Bit):
            self.place(e.base)
            self.emit(Op.BIT, (e.bit, self.type_of(e.base)))
        elif isinstance(e, n.IndirectBit):
            self.place(e.base)
            self.value(e.index, DINT)
            bt = self.type_of(e.base)
            assert isinstance(bt, Elementary)
            self.emit(Op.IBIT, bt, e.span)
        else:
            raise AssertionError(f"not a place: {e}")

    def value(self, e: n.Expr, want: DataType) -> None:
        """Push the value of `e` converted to `want` (elementary targets only)."""
        if isinstance(e, n.Literal) and isinstance(e.value, float) and want is LREAL:
            self.emit(Op.CONST, (e.value, LREAL))  # a REAL literal keeps double precision in LREAL
            return
        t = self.expr(e)
        if isinstance(want, Elementary) and isinstance(t, Elementary):
            self.convert(t, want)

    def convert(self, src: DataType, dst: DataType) -> None:
        if src is not dst and isinstance(src, Elementary) and isinstance(dst, Elementary):
            self.emit(Op.CONV, (src, dst))

    def expr(self, e: n.Expr) -> DataType:
        t = self.type_of(e)
        if id(e) in self.a.enum_of:
            self.emit(Op.CONST, (self.a.enum_of[id(e)], DINT))
            return DINT
        if isinstance(e, n.Literal):
            tag_name = self.a.bool_tag_of.get(id(e))
            if tag_name is not None:  # TRUE/FALSE naming a tag of the project
                return self.expr(tag_name)
            self.emit(Op.CONST, (e.value, t))
            return t
        if isinstance(e, n.Name) and id(e) in self.a.system_of:
            self.emit(Op.SYS, self.a.system_of[id(e)])
            return BOOL
        if isinstance(e, n.Name | n.Member | n.Index | n.Bit | n.IndirectBit):
            self.place(e)
            if isinstance(t, Elementary):
                self.emit(Op.LOAD, t)
            else:
                self.emit(Op.VALUE)
            return t
        if isinstance(e, n.Unary):
            assert isinstance(t, Elementary)
            self.value(e.operand, t)
            self.emit(Op.NEG if e.op == "-" else Op.NOT, t)
            return t
        if isinstance(e, n.Binary):
            return self.binary(e, t)
        if isinstance(e, n.Call):
            ins = self.a.call_of[id(e)]
            if unimplemented(ins, "st"):  # U304: a function not simulated reads as 0
                assert isinstance(t, Elementary)
                self.emit(Op.CONST, (0, t))
                return t
            for a in e.args:  # one argument, two for ATAN2
                self.value(a.value, self.type_of(a.value))
            self.emit(Op.FN, (ins.key, t, len(e.args)), e.span)
            return t
        raise AssertionError(f"cannot compile {e}")

    def binary(self, e: n.Binary, t: DataType) -> DataType:
        lt, rt = self.type_of(e.left), self.type_of(e.right)
        if e.op in _CMP:
            if isinstance(lt, StructType):  # STRING comparison
                self.expr(e.left)
                self.expr(e.right)
                self.emit(Op.CMP, (e.op, lt))
                return BOOL
            assert isinstance(lt, Elementary) and isinstance(rt, Elementary)
            ot = promote(lt, rt)
            self.value(e.left, ot)
            self.value(e.right, ot)
            self.emit(Op.CMP, (e.op, ot))
            return BOOL
        assert isinstance(t, Elementary)
        self.value(e.left, t)
        self.value(e.right, t)
        self.emit(Op.BIN, (e.op, t), e.span)
        return t

    # ------------------------------------------------------------ prescan
    def prescan(self, body: list[n.Stmt]) -> None:
        """Zero `[:=]` targets and run instructions' prescan actions (SPEC 3.2)."""
        from ..instructions.registry import lookup_prescan

        main_ops = self.ops
        self.ops = self.code.prescan
        for s in _walk(body):
            if id(s) in self.a.unsimulated:  # uses a tag that is not simulated (U306)
                continue
            if isinstance(s, n.Assign) and s.nonretentive:
                t = self.type_of(s.target)
                self.place(s.target)
                self.emit(Op.CONST, (0, DINT))
                if isinstance(t, Elementary):
                    self.convert(DINT, t)
                self.emit(Op.STORE, t, s.span)
            elif isinstance(s, n.CallStmt) and id(s.call) in self.a.call_of:
                ins = self.a.call_of[id(s.call)]
                if ins.name != "JSR" and (
                    ins.family == "aoi" or lookup_prescan(ins.name, "st") is not None
                ):
                    count = self.operands(s.call, ins)
                    self.emit(Op.PRESCAN, (ins.key, count), s.span)
        self.ops = main_ops


def _walk(body: list[n.Stmt]):  # type: ignore[no-untyped-def]
    for s in body:
        yield s
        if isinstance(s, n.If):
            for _, b in s.branches:
                yield from _walk(b)
            if s.else_body:
                yield from _walk(s.else_body)
        elif isinstance(s, n.Case):
            for arm in s.arms:
                yield from _walk(arm.body)
            if s.else_body:
                yield from _walk(s.else_body)
        elif isinstance(s, n.For | n.While | n.Repeat):
            yield from _walk(s.body)


def sbr_params(routine: n.Routine, analysis: Analysis) -> list[n.Expr]:
    """The operands of the first SBR of a routine (its input parameters), or []."""
    if routine.language == "st":
        for s in _walk(routine.body):
            if isinstance(s, n.CallStmt) and s.call.name.upper() == "SBR":
                return [a.value for a in s.call.args]
        return []
    stack: list[object] = [el for rung in routine.rungs for el in rung.elements]
    stack.reverse()
    while stack:
        el = stack.pop()
        if isinstance(el, n.Branch):
            stack.extend(reversed([x for leg in el.legs for x in leg]))
        elif isinstance(el, n.LadderInstr) and el.name.upper() == "SBR":
            return list(el.operands)
    return []


def compile_routine(
    model: ProgramModel, analysis: Analysis, routine: n.Routine, sites: list | None = None
) -> Code:
    return RoutineCompiler(model, analysis, routine, sites).compile()
