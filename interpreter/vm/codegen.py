"""VM tier: translate a routine's bytecode once into a Python function.

The operand stack is evaluated symbolically at translation time: each stack entry becomes
a Python expression, each store or call a Python statement, and the structured control ops
map onto `if`/`while`. Exact Logix arithmetic is kept by emitting the wrap / float32 /
fault helpers below (docs/decisions/0003-vm-design.md).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from itertools import accumulate, repeat
from typing import Any

from ..compiler.bytecode import Code, Ins, Op
from ..instructions.registry import lookup, lookup_prescan
from ..semantics.types import BOOL, LINT, LREAL, DataType, Elementary, Kind, StructType
from .context import ExecContext, MajorFault
from .ladder_helpers import (
    copy_into,
    over_fdiv,
    over_fmod,
    over_idiv,
    over_imod,
    over_int,
    over_ipow,
    over_real,
    return_value,
    returned,
    store_flags,
)
from .refs import ArrayRef, BitRef, Ref
from .values import f32, real_mod, real_to_int, set_string, string_text, wrap

_PY_CMP = {"=": "==", "<>": "!=", "<": "<", "<=": "<=", ">": ">", ">=": ">="}


# ------------------------------------------------------------------ runtime helpers
def _xf(site: int) -> int:
    raise MajorFault(4, 20, "array subscript out of range", site)


def _wd(site: int) -> None:
    raise MajorFault(6, 1, "task watchdog: the scan executed too many statements", site)


def _idiv(ctx: ExecContext, a: int, b: int, site: int, bits: int, signed: bool) -> int:
    if b == 0:
        ctx.minor(4, 4, "division by zero", site)
        return a  # Logix: an integer divide by zero leaves Source A (RM003)
    q = abs(a) // abs(b)
    return wrap(q if (a >= 0) == (b >= 0) else -q, bits, signed)


def _imod(ctx: ExecContext, a: int, b: int, site: int, bits: int, signed: bool) -> int:
    if b == 0:
        ctx.minor(4, 4, "MOD by zero", site)
        return 0
    q = abs(a) // abs(b)
    q = q if (a >= 0) == (b >= 0) else -q
    return wrap(a - q * b, bits, signed)


def _fdiv(ctx: ExecContext, a: float, b: float, site: int, single: bool) -> float:
    if b == 0.0:
        ctx.minor(4, 4, "division by zero", site)
        if a == 0.0 or math.isnan(a):
            r = math.nan
        else:
            r = math.copysign(math.inf, a) * math.copysign(1.0, b)
    else:
        r = a / b
    return f32(r) if single else r


def _fmod(ctx: ExecContext, a: float, b: float, site: int, single: bool) -> float:
    if b == 0.0:
        ctx.minor(4, 4, "MOD by zero", site)
        return math.nan
    r = real_mod(a, b)
    return f32(r) if single else r


def _ipow(ctx: ExecContext, a: int, b: int, site: int, bits: int, signed: bool) -> int:
    if b < 0:
        if a == 0:
            ctx.minor(4, 4, "zero raised to a negative power", site)
            return 0
        if a == 1:
            return 1
        if a == -1:
            return -1 if b % 2 else 1
        return 0
    return wrap(pow(a, b, 1 << bits), bits, signed)


def _fpow(a: float, b: float, single: bool) -> float:
    try:
        r = math.pow(a, b)
    except (ValueError, OverflowError):
        r = math.nan if a < 0 else math.inf
    return f32(r) if single else r


def _setbit(v: int, bit: int, on: object, bits: int, signed: bool) -> int:
    v = v | (1 << bit) if on else v & ~(1 << bit)
    return wrap(v, bits, signed)


def _sset(dst: list, src: object) -> None:
    set_string(dst, src if isinstance(src, bytes) else string_text(src))  # type: ignore[arg-type]


def _scmp(a: object, b: object) -> int:
    x = a if isinstance(a, bytes) else string_text(a)  # type: ignore[arg-type]
    y = b if isinstance(b, bytes) else string_text(b)  # type: ignore[arg-type]
    return (x > y) - (x < y)


def _r2i(x: float) -> int:
    return real_to_int(x)


HELPERS: dict[str, Any] = {
    "_xf": _xf,
    "_wd": _wd,
    "_idiv": _idiv,
    "_imod": _imod,
    "_fdiv": _fdiv,
    "_fmod": _fmod,
    "_ipow": _ipow,
    "_fpow": _fpow,
    "_setbit": _setbit,
    "_sset": _sset,
    "_scmp": _scmp,
    "_f32": f32,
    "_r2i": _r2i,
    "_wrap": wrap,
    "_Ref": Ref,
    "_BitRef": BitRef,
    "_ArrayRef": ArrayRef,
    "MajorFault": MajorFault,
    "_stf": store_flags,
    "_rvn": returned,
    "_rv": return_value,
    "_cpy": copy_into,
    "_vi": over_int,
    "_vr": over_real,
    "_vidiv": over_idiv,
    "_vimod": over_imod,
    "_vipow": over_ipow,
    "_vfdiv": over_fdiv,
    "_vfmod": over_fmod,
    "_INF": math.inf,
}

_TRUE = ("1", "True")
_MAX_DEPTH = 40  # CPython's parser refuses about 200 nested parentheses
_LONG = 160  # shorter expressions cannot nest _MAX_DEPTH parentheses deep with operands in them
_QUOTED = re.compile(r"b?'(?:[^'\\]|\\.)*'|b?\"(?:[^\"\\]|\\.)*\"")


_SPILL = 1000  # a longer expression is evaluated into a temporary whatever its nesting
_PAREN_STEP = {"(": 1, ")": -1}


def _nesting(expr: str) -> int:
    """Deepest parenthesis nesting of a generated expression (string literals skipped)."""
    # map/accumulate/max run in C: this is called after every op of a long expression
    steps = map(_PAREN_STEP.get, _QUOTED.sub("", expr), repeat(0))
    return max(accumulate(steps, initial=0))


_FALSE = ("0", "False")


# ------------------------------------------------------------------ translation
@dataclass(slots=True)
class _Val:
    expr: str
    type: DataType | None
    chain: str = ""  # "and"/"or": expr is one flat parenthesised chain of that operator (LAND/LOR)


@dataclass(slots=True)
class _Place:
    container: str
    key: str
    bit: str | None = None
    owner: Elementary | None = None  # type of the integer holding `bit`


def _nonzero_real_const(expr: str) -> bool:
    """A float literal emitted by CONST that is finite and not zero."""
    try:
        v = float(expr.strip("()"))
    except ValueError:
        return False
    return v != 0.0 and math.isfinite(v)


def _is_simple(expr: str) -> bool:
    return expr.replace("_", "").replace("-", "").isalnum() or (
        expr.startswith("T[") and expr.endswith("]") and expr[2:-1].isdigit()
    )


def conv_expr(x: str, src: DataType | None, dst: DataType) -> str:
    """Python expression converting `x` (of type src) for storage as dst."""
    if not isinstance(dst, Elementary) or src is dst:
        return x
    assert isinstance(src, Elementary)
    if dst.kind is Kind.REAL:
        if dst.bits == 64:
            return f"float({x})" if src.kind is not Kind.REAL else x
        return f"_f32({x})"
    if dst.kind is Kind.BOOL:
        return f"(1 if {x} else 0)"
    if src.kind is Kind.REAL:
        x = f"_r2i({x})"
    elif src.kind is Kind.BOOL:
        return x
    elif src.kind is Kind.INT and (src.bits < dst.bits and (dst.signed or not src.signed)):
        return x  # value always fits
    return _wrap_expr(x, dst)


def _wrap_expr(x: str, t: Elementary) -> str:
    mask = (1 << t.bits) - 1
    if t.signed:
        half = 1 << (t.bits - 1)
        return f"(((({x}) + {half}) & {mask}) - {half})"
    return f"(({x}) & {mask})"


class Translator:
    """Bytecode -> Python source for one routine (main code or prescan code)."""

    def __init__(
        self,
        code: Code,
        ns: dict[str, Any],
        func_name: str,
        ops: list[Ins],
        tags: list | None = None,
    ) -> None:
        # tags: the tag storage the routine is always called with (a program routine: the
        # controller's tags; None for an AOI routine, which gets its instance frame as T)
        self.tags = tags
        self.code = code
        self.ns = ns
        self.func_name = func_name
        self.ops = ops
        self.lines: list[str] = []
        self.indent = 1
        self.stack: list[_Val | _Place] = []
        self.block_has_code: list[bool] = []
        self.tmp = 0
        self.edges_name: str | None = None
        self.ovf = False  # inside OVF True .. OVF False: arithmetic notes overflows

    def const_name(self, value: object) -> str:
        name = f"_k{len(self.ns)}"
        self.ns[name] = value
        return name

    def line(self, text: str) -> None:
        self.lines.append("    " * self.indent + text)
        if self.block_has_code:
            self.block_has_code[-1] = True

    def open_block(self, header: str) -> None:
        self.line(header)
        self.indent += 1
        self.block_has_code.append(False)

    def close_block(self) -> None:
        if not self.block_has_code.pop():
            self.lines.append("    " * self.indent + "pass")
        self.indent -= 1

    def pop_val(self) -> _Val:
        v = self.stack.pop()
        assert isinstance(v, _Val), v
        return v

    def pop_place(self) -> _Place:
        p = self.stack.pop()
        assert isinstance(p, _Place), p
        return p

    def assign(self, p: _Place, value: str) -> None:
        """Emit the store of an elementary value into a place (a bit place merges the bit)."""
        target = f"{p.container}[{p.key}]"
        if p.bit is None:
            self.line(f"{target} = {value}")
            return
        pt = p.owner
        assert pt is not None
        self.line(f"{target} = _setbit({target}, {p.bit}, {value}, {pt.bits}, {pt.signed})")

    def fresh(self) -> str:
        self.tmp += 1
        return f"_t{self.tmp}"

    def checked(self, expr: str, size: int, site: int) -> str:
        if expr.lstrip("-").isdigit():
            v = int(expr)
            return expr if 0 <= v < size else f"_xf({site})"
        if _is_simple(expr):
            return f"({expr} if 0 <= {expr} < {size} else _xf({site}))"
        t = self.fresh()
        return f"({t} if 0 <= ({t} := {expr}) < {size} else _xf({site}))"

    def translate(self) -> str:
        head = [
            f"def {self.func_name}(T, ctx):",
            "    _s = 0",
            "    _W = ctx.budget - ctx.steps",
            "    try:",
        ]
        self.indent = 2
        self.block_has_code.append(False)
        for ins in self.ops:
            self.op(ins)
            top = self.stack[-1] if self.stack else None
            if (
                isinstance(top, _Val)
                and len(top.expr) > _LONG
                and (len(top.expr) > _SPILL or _nesting(top.expr) > _MAX_DEPTH)
            ):
                # a long expression (`a + b + ... + z`, a rung of nested branches): Python's
                # parser refuses about 200 nested parentheses, so evaluate the part so far now;
                # bounding the length also keeps the scan above linear in the rung's length
                # (16,000 contacts in series: 55 s when every op rescanned the whole chain)
                t = self.fresh()
                self.line(f"{t} = {top.expr}")
                self.stack[-1] = _Val(t, top.type)
        if not self.block_has_code[-1]:
            self.line("pass")
        assert not self.stack, f"stack not empty after {self.code.name}: {self.stack}"
        tail = ["    finally:", "        ctx.steps += _s"]
        return "\n".join(head + self.lines + tail) + "\n"

    def op(self, ins: Ins) -> None:  # noqa: C901
        op, site = ins.op, ins.site
        arg: Any = ins.arg
        st = self.stack
        if op is Op.TAG:
            st.append(_Place("T", str(arg)))
        elif op is Op.MEMBER:
            p = self.pop_place()
            st.append(_Place(f"{p.container}[{p.key}]", str(arg)))
        elif op is Op.INDEX:
            sizes: tuple[int, ...] = arg  # type: ignore[assignment]
            idx = [self.pop_val().expr for _ in sizes][::-1]
            p = self.pop_place()
            parts = []
            stride = 1
            for size, expr in zip(reversed(sizes), reversed(idx), strict=True):
                c = self.checked(expr, size, site)
                parts.append(c if stride == 1 else f"{c} * {stride}")
                stride *= size
            st.append(_Place(f"{p.container}[{p.key}]", " + ".join(reversed(parts))))
        elif op is Op.BIT:
            bit, owner = arg  # type: ignore[misc]
            p = self.pop_place()
            st.append(_Place(p.container, p.key, str(bit), owner))
        elif op is Op.IBIT:
            owner = arg
            bit_expr = self.pop_val().expr
            p = self.pop_place()
            st.append(_Place(p.container, p.key, self.checked(bit_expr, owner.bits, site), owner))
        elif op is Op.CONST:
            value, t = arg  # type: ignore[misc]
            if (
                isinstance(t, Elementary)
                and t.kind is Kind.REAL
                and t.bits == 32
                and isinstance(value, int | float)
            ):
                value = f32(float(value))  # first: 1.0e39 becomes inf in a REAL
            if isinstance(value, float) and (math.isinf(value) or math.isnan(value)):
                expr = self.const_name(value)
            elif isinstance(value, bytes | str):
                expr = repr(value)
            else:
                expr = repr(value)
                if isinstance(value, int) and value < 0:
                    expr = f"({expr})"
            st.append(_Val(expr, t))
        elif op is Op.SYSPLACE:
            st.append(_Place("ctx.status", repr(arg)))
        elif op is Op.SYS:
            st.append(
                _Val("ctx.first_scan" if arg == "FS" else f"ctx.status.get({arg!r}, 0)", BOOL)
            )
        elif op is Op.SETSYS:
            name, value = arg
            self.line(f"ctx.status[{name!r}] = {int(value)}")
        elif op is Op.LOAD:
            p = self.pop_place()
            if p.bit is not None:
                st.append(_Val(f"(({p.container}[{p.key}] >> {p.bit}) & 1)", BOOL))
            else:
                st.append(_Val(f"{p.container}[{p.key}]", arg))  # type: ignore[arg-type]
        elif op is Op.VALUE:
            p = self.pop_place()
            st.append(_Val(f"{p.container}[{p.key}]", None))
        elif op is Op.STORE:
            v = self.pop_val()
            p = self.pop_place()
            t = arg
            if isinstance(t, StructType) and t.is_string:
                self.line(f"_sset({p.container}[{p.key}], {v.expr})")
            elif not isinstance(t, Elementary):  # structure or array parameter: copy the value
                self.line(f"_cpy({p.container}[{p.key}], {v.expr})")
            else:
                self.assign(p, v.expr if p.bit is not None else conv_expr(v.expr, v.type, t))
        elif op is Op.REF:
            p = self.pop_place()
            t = arg  # type: ignore[assignment]
            if p.bit is not None:
                st.append(
                    _Val(
                        f"_BitRef({p.container}, {p.key}, {p.bit}, {self.const_name(p.owner)})",
                        None,
                    )
                )
            else:
                st.append(_Val(f"_Ref({p.container}, {p.key}, {self.const_name(t)})", None))
        elif op is Op.AREF:
            elem, dims, indexed = arg  # type: ignore[misc]
            p = self.pop_place()
            if indexed:
                st.append(
                    _Val(
                        f"_ArrayRef({p.container}, {p.key}, {self.const_name(elem)}, {dims!r})",
                        None,
                    )
                )
            elif (
                self.tags is not None
                and p.container == "T"
                and p.key.isdecimal()
                and isinstance(self.tags[int(p.key)], list)
            ):
                # a whole array tag: its element list is the same object for the life of
                # the controller (stores into an array copy element by element), so the
                # reference is made once, not at every execution (it is only read)
                ref = ArrayRef(self.tags[int(p.key)], 0, elem, dims)
                st.append(_Val(self.const_name(ref), None))
            else:
                st.append(
                    _Val(
                        f"_ArrayRef({p.container}[{p.key}], 0, {self.const_name(elem)}, {dims!r})",
                        None,
                    )
                )
        elif op is Op.CONV:
            src, dst = arg  # type: ignore[misc]
            v = self.pop_val()
            st.append(_Val(conv_expr(v.expr, src, dst), dst))
        elif op is Op.NEG:
            v = self.pop_val()
            t = arg  # type: ignore[assignment]
            assert isinstance(t, Elementary)
            if t.kind is Kind.REAL:
                st.append(_Val(f"(-{v.expr})", t))
            elif self.ovf:
                st.append(_Val(f"_vi(ctx, -{v.expr}, {t.bits}, {t.signed})", t))
            else:
                st.append(_Val(_wrap_expr(f"-{v.expr}", t), t))
        elif op is Op.NOT:
            v = self.pop_val()
            t = arg  # type: ignore[assignment]
            assert isinstance(t, Elementary)
            if t.kind is Kind.BOOL:
                st.append(_Val(f"(not {v.expr})", BOOL))
            else:
                st.append(_Val(_wrap_expr(f"~{v.expr}", t), t))
        elif op is Op.BIN:
            self.binary(arg, site)  # type: ignore[arg-type]
        elif op is Op.CMP:
            rel, t = arg
            b, a = self.pop_val(), self.pop_val()
            if isinstance(t, StructType):
                st.append(_Val(f"(_scmp({a.expr}, {b.expr}) {_PY_CMP[rel]} 0)", BOOL))
            else:
                st.append(_Val(f"({a.expr} {_PY_CMP[rel]} {b.expr})", BOOL))
        elif op is Op.FN:
            key, t, count = arg  # type: ignore[misc]
            fn_args = ", ".join(reversed([self.pop_val().expr for _ in range(count)]))
            fn = self.impl(key)
            call = f"{fn}(ctx, True, {fn_args})"
            if self.ovf and isinstance(t, Elementary) and t.kind is Kind.INT:
                st.append(_Val(f"_vi(ctx, {call}, {t.bits}, {t.signed})", t))  # ABS of the minimum
            elif self.ovf and isinstance(t, Elementary) and t.kind is Kind.REAL:
                st.append(_Val(f"_vr(ctx, {conv_expr(call, _result_src(t), t)})", t))  # LN(0) ...
            else:
                st.append(_Val(conv_expr(call, _result_src(t), t), t))
        elif op is Op.CALL or op is Op.PRESCAN:
            key, count = arg[0], arg[1]  # type: ignore[index]
            rung = bool(arg[2]) if len(arg) > 2 else True  # type: ignore[arg-type]
            args = [self.pop_val().expr for _ in range(count)][::-1]
            fn = self.impl(key, prescan=op is Op.PRESCAN)
            self.line(f"ctx.site = {site}")
            self.line(f"{fn}(ctx, {rung}{''.join(', ' + a for a in args)})")
        elif op is Op.JSR:
            self.line(f"ctx.site = {site}")
            self.line("ctx.rv = None")
            self.line("ctx.steps += _s; _s = 0")
            self.line(f"_R[{str(arg).upper()!r}](T, ctx)")
            self.line("_W = ctx.budget - ctx.steps")
        elif op is Op.IF:
            self.open_block(f"if {self.pop_val().expr}:")
        elif op is Op.ELSE:
            self.close_block()
            self.open_block("else:")
        elif op is Op.END:
            self.close_block()
        elif op is Op.LOOP:
            self.open_block("while True:")
        elif op is Op.BREAK:
            self.line("break")
        elif op is Op.BREAK_IFNOT:
            self.line(f"if not {self.pop_val().expr}: break")
        elif op is Op.TSET:
            expr = self.pop_val().expr
            if expr != f"_v{arg}":
                self.line(f"_v{arg} = {expr}")
        elif op is Op.TGET:
            k, t = arg  # type: ignore[misc]
            st.append(_Val(f"_v{k}", t))
        elif op is Op.STEP:
            count, in_loop = arg  # type: ignore[misc]
            if count:
                self.line(f"_s += {count}")
            if in_loop:
                self.line(f"if _s > _W: _wd({site})")
        else:
            self.ladder_op(op, arg, site)

    def ladder_op(self, op: Op, arg: Any, site: int) -> None:  # noqa: C901
        """Ops added for ladder rungs, subroutine parameters and early returns."""
        st = self.stack
        if op is Op.POP:
            st.pop()
        elif op is Op.LAND or op is Op.LOR:
            b, a = self.pop_val(), self.pop_val()
            st.append(
                _rung_logic(a, b, "and" if op is Op.LAND else "or")
            )  # translate() bounds its depth
        elif op is Op.RCALL:
            key, count = arg
            args = [self.pop_val().expr for _ in range(count)][::-1]
            rung = self.pop_val().expr
            if not _is_simple(rung):
                r = self.fresh()
                self.line(f"{r} = {rung}")
                rung = r
            flag = (
                "True"
                if rung in _TRUE
                else "False"
                if rung in _FALSE
                else f"(True if {rung} else False)"
            )
            fn = self.impl(key)
            res = self.fresh()
            self.line(f"ctx.site = {site}")
            self.line(f"{res} = {fn}(ctx, {flag}{''.join(', ' + a for a in args)})")
            st.append(_Val(f"({rung} if {res} is None else {res})", BOOL))
        elif op is Op.OVF:
            self.ovf = bool(arg)
        elif op is Op.EDGE:
            if self.edges_name is None:
                self.edges_name = self.const_name(self.code.edges)
            st.append(_Place(self.edges_name, str(arg)))
        elif op is Op.STOREF:
            v = self.pop_val()
            p = self.pop_place()
            tname = self.const_name(arg)
            self.line(f"ctx.site = {site}")  # an overflow records minor fault 4/4 here
            self.assign(p, f"_stf(ctx, {v.expr}, {tname})")
        elif op is Op.SETRV:
            vals = [self.pop_val().expr for _ in range(arg)][::-1]
            self.line(f"ctx.rv = [{', '.join(vals)}]")
        elif op is Op.RETURN:
            self.line("return")
        elif op is Op.FAULT:
            ftype, code, message = arg
            self.line(f"raise MajorFault({ftype}, {code}, {message!r}, {site})")
        elif op is Op.RETN:
            st.append(_Val(f"_rvn(ctx, {arg}, {site})", BOOL))
        elif op is Op.RETV:
            i, t = arg
            st.append(_Val(f"_rv(ctx, {i}, {self.const_name(t)})", t))
        else:  # pragma: no cover - every op is handled above  # pragma: no cover - every op is handled above
            raise AssertionError(op)

    def impl(self, key: str, prescan: bool = False) -> str:
        project = self.ns.get("_AOI_PRE" if prescan else "_AOI")  # a project's add-on instructions
        if project is not None and key in project:
            return self.const_name(project[key])
        name, _, langs = key.partition("@")
        lang = self.code.language if self.code.language in langs.split("+") else langs.split("+")[0]
        fn = lookup_prescan(name, lang) if prescan else lookup(name, lang)
        if fn is None:
            raise LookupError(f"no implementation for {key}")
        return self.const_name(fn)

    def binary(self, arg: tuple[str, Elementary], site: int) -> None:
        op, t = arg
        b, a = self.pop_val(), self.pop_val()
        x, y = a.expr, b.expr
        st = self.stack
        if op in ("AND", "OR", "XOR"):
            if t.kind is Kind.BOOL:
                expr = {"AND": f"({x} and {y})", "OR": f"({x} or {y})", "XOR": f"(({x}) != ({y}))"}[
                    op
                ]
                st.append(_Val(f"(1 if {expr} else 0)" if op != "XOR" else expr, BOOL))
            else:
                sym = {"AND": "&", "OR": "|", "XOR": "^"}[op]
                st.append(_Val(f"({x} {sym} {y})", t))
            return
        if self.ovf:
            self.checked_binary(op, t, x, y)
            return
        single = t.bits == 32
        if t.kind is Kind.REAL:
            if op in "+-*":
                e = f"({x} {op} {y})"
                st.append(_Val(f"_f32{e}" if single else e, t))
            elif op == "/" and _nonzero_real_const(y):
                e = f"({x} / {y})"  # cannot fault: inline what _fdiv would do
                st.append(_Val(f"_f32{e}" if single else e, t))
            elif op == "/":
                st.append(_Val(f"_fdiv(ctx, {x}, {y}, {site}, {single})", t))
            elif op == "MOD":
                st.append(_Val(f"_fmod(ctx, {x}, {y}, {site}, {single})", t))
            elif op == "**":
                st.append(_Val(f"_fpow({x}, {y}, {single})", t))
            return
        if op in "+-*":
            st.append(_Val(_wrap_expr(f"{x} {op} {y}", t), t))
        elif op == "/":
            st.append(_Val(f"_idiv(ctx, {x}, {y}, {site}, {t.bits}, {t.signed})", t))
        elif op == "MOD" and y.isdigit() and int(y) > 0:
            # Constant positive divisor: no fault, |result| < divisor so no wrap; the sign
            # follows the dividend (A - TRUNC(A/B)*B), unlike Python's %.
            tmp = self.fresh()
            st.append(_Val(f"({tmp} % {y} if ({tmp} := {x}) >= 0 else -(-{tmp} % {y}))", t))
        elif op == "MOD":
            st.append(_Val(f"_imod(ctx, {x}, {y}, {site}, {t.bits}, {t.signed})", t))
        elif op == "**":
            st.append(_Val(f"_ipow(ctx, {x}, {y}, {site}, {t.bits}, {t.signed})", t))

    def checked_binary(self, op: str, t: Elementary, x: str, y: str) -> None:
        """Arithmetic of a ladder CPT/FAL expression: results as `binary`, and a result that
        does not fit `t` (or a division by zero) sets ctx.overflow for the store's S:V."""
        single = t.bits == 32
        tmp = self.fresh()
        if t.kind is Kind.REAL:
            if op in "+-*":  # the common case inline; only a non-finite result calls the helper
                e = f"_f32({x} {op} {y})" if single else f"({x} {op} {y})"
                expr = f"({tmp} if -_INF < ({tmp} := {e}) < _INF else _vr(ctx, {tmp}))"
            elif op == "/":
                expr = f"_vfdiv(ctx, {x}, {y}, {single})"
            elif op == "MOD":
                expr = f"_vfmod(ctx, {x}, {y}, {single})"
            else:
                expr = f"_vr(ctx, _fpow({x}, {y}, {single}))"
        elif op in "+-*":
            lo, hi = (-(1 << (t.bits - 1)), 1 << (t.bits - 1)) if t.signed else (0, 1 << t.bits)
            expr = f"({tmp} if {lo} <= ({tmp} := {x} {op} {y}) < {hi} else _vi(ctx, {tmp}, {t.bits}, {t.signed}))"
        elif op == "/":
            expr = f"_vidiv(ctx, {x}, {y}, {t.bits}, {t.signed})"
        elif op == "MOD":
            expr = f"_vimod(ctx, {x}, {y})"
        else:
            expr = f"_vipow(ctx, {x}, {y}, {t.bits}, {t.signed})"
        self.stack.append(_Val(expr, t))


def _rung_logic(a: _Val, b: _Val, word: str) -> _Val:
    """`a AND b` / `a OR b` on rung conditions: constant ends folded, chains kept flat."""
    absorbing, neutral = (_FALSE, _TRUE) if word == "and" else (_TRUE, _FALSE)
    if a.expr in neutral:
        return b
    if b.expr in neutral or a.expr in absorbing:
        return a  # b is pure: not evaluating it changes nothing
    if a.chain == word:  # (x and y) and b -> (x and y and b)
        return _Val(f"{a.expr[:-1]} {word} {b.expr})", BOOL, word)
    return _Val(f"({a.expr} {word} {b.expr})", BOOL, word)


def _result_src(t: DataType) -> DataType:
    """Functions return Python numbers: floats for REAL results, ints otherwise."""
    return LREAL if isinstance(t, Elementary) and t.kind is Kind.REAL else LINT
