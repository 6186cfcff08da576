"""The simulated controller: virtual clock, prescan, scans, watched values, faults (SPEC 4)."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from ..compiler.ladder_compiler import compile_ladder
from ..compiler.st_compiler import RoutineCompiler, compile_routine
from ..semantics.aoi import Aoi
from ..semantics.checker import ST_SYSTEM_FLAGS, SYSTEM_FLAGS, Checker
from ..semantics.types import BOOL, ArrayType, DataType, Elementary, Kind, StructType
from ..syntax import nodes as n
from ..syntax.st_parser import parse_expression
from ..vm.codegen import HELPERS, Translator
from ..vm.context import DEFAULT_WATCHDOG, ExecContext, MajorFault
from ..vm.values import set_string, string_text
from .aoi import AoiRoutines, make_impls
from .loader import InputError, Loaded
from .motion import MotionRuntime, watched_members
from .storage import allocate
from .tasks import Schedule


@dataclass(slots=True)
class Fault:
    type: int
    code: int
    major: bool
    message: str
    file: str
    line: int
    column: int
    count: int = 1

    def to_json(self) -> dict[str, object]:
        d: dict[str, object] = {
            "type": self.type,
            "code": self.code,
            "major": self.major,
            "message": self.message,
            "file": self.file,
            "line": self.line,
            "column": self.column,
        }
        if not self.major:
            d["count"] = self.count
        return d

    def text(self) -> str:
        kind = "major" if self.major else "minor"
        return f"{self.file}:{self.line}:{self.column}: {kind} fault type {self.type} code {self.code}: {self.message}"


class WatchError(ValueError):
    """A --watch/--set expression does not name a valid tag reference."""


def _not_simulated(T: object, ctx: object) -> None:
    """The body of a routine that is not simulated: nothing happens, its tags keep their values."""


class Controller:
    """Holds tag storage and the translated routines; `scan()` runs one program scan."""

    def __init__(
        self,
        loaded: Loaded,
        scan_period_ms: float = 1.0,
        watchdog: int = DEFAULT_WATCHDOG,
        coarse_update_ms: float | None = None,
    ) -> None:
        self.model = loaded.model
        self.analysis = loaded.analysis
        self.T = allocate(self.model)
        self.ctx = ExecContext(scan_period_ms=scan_period_ms, budget=watchdog, program=self.model)
        # the motion planner runs before each scan (SPEC 9.3); its details live in the bridge
        self.ctx.motion = MotionRuntime(self.model, self.T, coarse_update_ms)
        self.sites: list[tuple[str, n.Span]] = []
        self.aoi_impls: dict[str, Callable[..., object]] = {}
        self.aoi_prescans: dict[str, Callable[..., object]] = {}
        self.ns = self._namespace()
        self.prescans: list[Callable[..., None]] = []
        self._compile_aois()
        if self.model.programs:
            # One namespace per L5X program: JSR names resolve among that program's routines.
            self.routines: dict[str, Callable[..., None]] = {}
            mains: dict[str, Callable[..., None]] = {}
            for key, info in self.model.programs.items():
                ns = self._namespace()
                own = [r for r in self.model.routines if (r.program_name or "").upper() == key]
                compiled = self._compile_routines(own, ns, f"_{len(mains)}")
                if info.main.upper() in compiled:
                    mains[key] = compiled[info.main.upper()]
            self.schedule = Schedule.for_project(self.model, mains)
        else:
            self.routines = self._compile_routines(self.model.routines, self.ns, "")
            main = self.routines.get(self.model.main.upper())
            # An export without programs (an Add-On Instruction export) has nothing to scan.
            self.schedule = Schedule.single(main) if main is not None else Schedule()
        self.scans = 0
        self.major_fault: Fault | None = None

    def _namespace(self) -> dict[str, Any]:
        ns: dict[str, Any] = dict(HELPERS)
        ns["_R"] = {}
        ns["_AOI"] = self.aoi_impls
        ns["_AOI_PRE"] = self.aoi_prescans
        return ns

    def _compile_routines(
        self, routines: list[n.Routine], ns: dict[str, Any], tag: str
    ) -> dict[str, Callable[..., None]]:
        compiled: dict[str, Callable[..., None]] = {}
        for i, r in enumerate(routines):
            if r.language == "st":
                code = compile_routine(self.model, self.analysis, r, self.sites)
            elif r.language == "rll":
                code = compile_ladder(self.model, self.analysis, r, self.sites)
            else:  # FBD/SFC/protected (U301/U302): a JSR to it runs nothing (SPEC 9.32)
                compiled[r.name.upper()] = _not_simulated
                continue
            # program routines always run on self.T (JSR and the schedule pass it)
            compiled[r.name.upper()] = self._translate(
                code, code.ops, f"_routine{tag}_{i}", ns, self.T
            )
            self.prescans.append(
                self._translate(code, code.prescan, f"_prescan{tag}_{i}", ns, self.T)
            )
        ns["_R"].update(compiled)
        return compiled

    def _compile_aois(self) -> None:
        """Implementations first (calls may nest), then each definition's routines once."""
        done: list[tuple[Aoi, AoiRoutines]] = []
        for aoi in self.model.aois.values():
            assert isinstance(aoi, Aoi) and aoi.instruction is not None
            routines = AoiRoutines()
            call, pre = make_impls(aoi, routines)
            self.aoi_impls[aoi.instruction.key] = call
            self.aoi_prescans[aoi.instruction.key] = pre
            done.append((aoi, routines))
        for k, (aoi, routines) in enumerate(done):
            for name, r in aoi.routines.items():
                if name not in ("LOGIC", "ENABLEINFALSE"):
                    continue
                if r.language == "rll":
                    code = compile_ladder(self.model, self.analysis, r, self.sites, aoi.edges)
                else:
                    code = compile_routine(self.model, self.analysis, r, self.sites)
                fn = self._translate(code, code.ops, f"_aoi{k}_{name.lower()}", self.ns)
                if name == "LOGIC":
                    routines.logic = fn
                    routines.logic_prescan = self._translate(
                        code, code.prescan, f"_aoi{k}_prescan", self.ns
                    )
                else:
                    routines.enable_in_false = fn

    def _translate(
        self,
        code: Any,
        ops: list,
        name: str,
        ns: dict[str, Any] | None = None,
        tags: list | None = None,
    ) -> Callable[..., None]:
        ns = self.ns if ns is None else ns
        src = Translator(code, ns, name, ops, tags).translate()
        try:
            compiled = compile(src, f"<logix {code.path}:{name}>", "exec")
        except (SyntaxError, RecursionError):  # Python's limits: 100 nested blocks, parser depth
            raise InputError(
                f"{code.path}: routine '{code.name}' nests statements too deeply to run "
                f"(the limit is about 90 levels)"
            ) from None
        exec(compiled, ns)  # noqa: S102
        return ns[name]  # type: ignore[no-any-return]

    # ------------------------------------------------------------ running
    def prescan(self) -> bool:
        """Prescan every routine once (SPEC 3.2); False when it major-faulted (a bad subscript)."""
        self.ctx.steps = 0
        try:
            for p in self.prescans:
                p(self.T, self.ctx)
        except MajorFault as f:
            self.major_fault = self._fault(f.type, f.code, True, f.message, f.site)
            return False
        return True

    def scan(self) -> bool:
        """Run one normal scan; False when the controller major-faulted."""
        ctx = self.ctx
        ctx.now_ms = self.scans * ctx.scan_period_ms
        ctx.first_scan = self.scans == 0
        ctx.steps = 0
        if ctx.motion is not None:
            ctx.motion.before_scan(ctx.now_ms)
        try:
            self.schedule.run(self.T, ctx)
        except MajorFault as f:
            self.major_fault = self._fault(f.type, f.code, True, f.message, f.site)
            return False
        except RecursionError:
            self.major_fault = self._fault(
                4, 84, True, "stack overflow: JSR calls nested too deep", ctx.site
            )
            return False
        finally:
            self.scans += 1
        if ctx.steps > ctx.budget:
            # SPEC 9.4: any scan over the budget faults, also one with no loop (the loop heads
            # check on the way, decision 0005; straight-line code is only counted here)
            self.major_fault = self._fault(
                6, 1, True, "task watchdog: the scan executed too many statements", -1
            )
            return False
        return True

    def _fault(
        self, type_: int, code: int, major: bool, message: str, site: int, count: int = 1
    ) -> Fault:
        if 0 <= site < len(self.sites):
            path, span = self.sites[site]
        else:
            path, span = (
                (self.model.routines[0].path if self.model.routines else self.model.name),
                n.Span(1, 1, 1, 1),
            )
        project = self.model.extra.get("l5x")
        where = (
            project.context.get(span.line)  # type: ignore[attr-defined]
            if project is not None and path == project.path  # type: ignore[attr-defined]
            else None
        )
        if where:
            message = f"{message} ({where})"
        return Fault(type_, code, major, message, path, span.line, span.col, count)

    def faults(self) -> list[Fault]:
        out = [
            self._fault(f.type, f.code, False, f.message, f.site, f.count)
            for f in self.ctx.minor_faults.values()
        ]
        out.sort(key=lambda f: (f.file, f.line, f.column))
        if self.major_fault is not None:
            out.append(self.major_fault)
        return out

    # ------------------------------------------------------------ watching and setting
    def reference(
        self, text: str, as_ref: bool = False
    ) -> tuple[Callable[[], object], DataType, Callable[[object], None]]:
        """Getter, type and setter for a tag reference such as `Axis1.ActualPosition`
        (as_ref: the getter gives the elementary storage location, a Ref or BitRef)."""
        flag = self._system_flag(text)
        if flag is not None:
            return flag
        try:
            expr = parse_expression(text.strip())
        except ValueError as exc:
            raise WatchError(str(exc)) from None
        if isinstance(expr, n.Literal) and expr.type == "BOOL" and expr.text.isalpha():
            expr = n.Name(expr.text, expr.span)  # a tag named TRUE or FALSE (decision 0054)
        if not isinstance(expr, n.Name | n.Member | n.Index | n.Bit | n.IndirectBit):
            raise WatchError(f"'{text}' is not a tag reference")
        expr = _qualify(expr)
        checker = Checker(self.model)
        checker.a = self.analysis
        before = len(self.analysis.diags)
        t = checker.expr(expr)
        new = self.analysis.diags[before:]
        del self.analysis.diags[before:]
        if t is None or new:
            raise WatchError(f"'{text}': {new[0].message if new else 'not a tag reference'}")
        if self.ctx.motion is not None:  # axis attributes are written when somebody reads them
            self.ctx.motion.demand(watched_members(expr, t))
        rc = RoutineCompiler(
            self.model, self.analysis, n.Routine("watch", "st", "<watch>"), self.sites
        )
        rc.place(expr)
        place_ops = list(rc.ops)
        from ..compiler.bytecode import Ins, Op

        last = Op.REF if as_ref else Op.LOAD
        getter_ops = place_ops + [Ins(last, t) if isinstance(t, Elementary) else Ins(Op.VALUE)]
        tr = Translator(rc.code, self.ns, "_w", getter_ops)
        for ins in getter_ops:
            tr.op(ins)
        value_expr = tr.pop_val().expr
        body = "\n".join(tr.lines).replace("\n        ", "\n    ")
        fname = f"_watch{len(self.ns)}"
        src = (
            f"def {fname}(T, ctx):\n{body}\n    return {value_expr}\n"
            if tr.lines
            else f"def {fname}(T, ctx):\n    return {value_expr}\n"
        )
        exec(compile(src, "<watch>", "exec"), self.ns)  # noqa: S102
        fn = self.ns[fname]

        def setter(value: object) -> None:
            if isinstance(t, StructType) and t.is_string:
                if not isinstance(value, bytes):
                    raise WatchError(f"'{text}' is a STRING: give a quoted literal such as 'abc'")
                if len(value) > len(fn(self.T, self.ctx)[1]):  # type: ignore[index]
                    raise WatchError(
                        f"'{text}': '{value.decode('latin-1')}' is longer than the tag's "
                        f"{len(fn(self.T, self.ctx)[1])} characters"
                    )  # type: ignore[index]
                set_string(fn(self.T, self.ctx), value)  # type: ignore[arg-type]  # the live structure
                return
            if not isinstance(t, Elementary):
                raise WatchError(f"'{text}' is a {t}: only elementary tags and strings can be set")
            _check_settable(text, value, t)
            store_ops = place_ops + [
                Ins(Op.CONST, (value, _literal_type(value, t))),
                Ins(Op.STORE, t),
            ]
            tr2 = Translator(rc.code, self.ns, "_s", store_ops)
            tr2.indent = 1
            for ins in store_ops:
                tr2.op(ins)
            sname = f"_set{len(self.ns)}"
            exec(
                compile(f"def {sname}(T, ctx):\n" + "\n".join(tr2.lines) + "\n", "<set>", "exec"),
                self.ns,
            )  # noqa: S102
            self.ns[sname](self.T, self.ctx)

        return (lambda: fn(self.T, self.ctx)), t, setter

    def _system_flag(
        self, text: str
    ) -> tuple[Callable[[], object], DataType, Callable[[object], None]] | None:
        """`S:FS`, `S:N` ... as a watch (SPEC 9.17, docs/decisions/0131-cli-system-flags.md).

        A watch reads the flag as it stands at the end of the scan, as any watched tag. S:FS
        is readable for every program; the arithmetic flags only where ladder sets them.
        The controller owns every flag: `--set` of one is refused, never ignored.
        """
        key = text.strip().upper()
        if key not in SYSTEM_FLAGS:
            return None
        name = SYSTEM_FLAGS[key]
        if key not in ST_SYSTEM_FLAGS and not any(
            r.language == "rll" for r in self.model.all_routines()
        ):
            raise WatchError(
                f"'{text}' is available in ladder only, and this program has no ladder routine"
            )
        ctx = self.ctx

        def getter() -> object:
            return ctx.first_scan if name == "FS" else ctx.status.get(name, 0)

        def setter(value: object) -> None:
            raise WatchError(f"'{text}' is a status flag the controller sets: it cannot be set")

        return getter, BOOL, setter


def _qualify(e: n.Expr) -> n.Expr:
    """`Program:Main.Tag...` parses as member Tag of `Program:Main`: make the root one name."""
    if (
        isinstance(e, n.Member)
        and isinstance(e.base, n.Name)
        and e.base.ident.upper().startswith("PROGRAM:")
    ):
        return n.Name(f"{e.base.ident}.{e.name}", e.span)
    for attr in ("base",):
        inner = getattr(e, attr, None)
        if inner is not None:
            q = _qualify(inner)
            if q is not inner:
                setattr(e, attr, q)
    return e


def _check_settable(text: str, value: object, t: Elementary) -> None:
    """--set never wraps silently: the value must fit the tag's type (SPEC 9.12)."""
    if isinstance(value, bytes | str):
        raise WatchError(f"'{text}' is {t.name}: a string cannot be stored in it")
    if t.kind is Kind.BOOL and value not in (0, 1):
        raise WatchError(f"'{text}' is BOOL: use 1/0 or TRUE/FALSE, not {value!r}")
    if t.kind is Kind.INT:
        lo, hi = (
            (-(1 << (t.bits - 1)), (1 << (t.bits - 1)) - 1) if t.signed else (0, (1 << t.bits) - 1)
        )
        if not lo <= value <= hi:  # type: ignore[operator]  # a REAL literal is rounded later, as by ':='
            raise WatchError(f"'{text}' is {t.name}: {value} is outside {lo}..{hi}")


def _literal_type(value: object, target: Elementary) -> Elementary:
    from ..semantics.types import DINT, LREAL

    return LREAL if isinstance(value, float) else DINT


NON_FINITE = {math.inf: "Infinity", -math.inf: "-Infinity"}


def json_real(x: float) -> float | str:
    """A REAL for JSON: itself when finite, else the text "Infinity", "-Infinity" or "NaN".

    Strict JSON has no token for them (docs/decisions/0132-non-finite-reals-in-json.md);
    the texts are those JavaScript and Python print, so `float(text)` reads them back.
    """
    if math.isfinite(x):
        return x
    return "NaN" if x != x else NON_FINITE[x]


def to_json_value(value: object, t: DataType | None) -> object:
    """JSON form of a tag value: BOOL true/false, integers, floats, STRING text, objects."""
    if isinstance(t, Elementary):
        if t.kind is Kind.BOOL:
            return bool(value)
        if t.kind is Kind.REAL:
            return json_real(float(value))  # type: ignore[arg-type]
        return int(value)  # type: ignore[call-overload]
    if isinstance(t, StructType):
        assert isinstance(value, list)
        if t.is_string:
            return string_text(value).decode("latin-1")
        return {
            name: to_json_value(v, mt)
            for (name, mt), v in zip(t.members, value, strict=True)
            if name.upper() not in t.hidden
        }
    if isinstance(t, ArrayType):
        assert isinstance(value, list)
        flat = [to_json_value(v, t.elem) for v in value]
        for size in reversed(t.dims[1:]):  # row-major storage: nest from the last subscript out
            flat = [flat[i : i + size] for i in range(0, len(flat), size)]
        return flat
    return value if isinstance(value, int | float | str | bool) or value is None else str(value)
