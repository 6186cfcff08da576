"""Verification: resolve names and types, check statements and instruction calls (SPEC 7).

Produces an Analysis (types of expressions, enumeration numbers, catalog entries of calls)
that the compiler lowers, plus diagnostics. Never executes anything.
"""

from __future__ import annotations

import difflib
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from functools import cache
from typing import Any

from stdlib import Instruction, Operand, catalog

from ..diagnostics import Diagnostic, diag
from ..instructions.registry import LOWERED, has_implementation
from ..limits import MAX_TAG_ELEMENTS
from ..syntax import nodes as n
from ..syntax.literals import literal_problem
from . import time_types
from .aoi import Aoi, same_shape
from .ladder_check import LadderChecks
from .limits_check import routine_limits, storage_limit
from .motion_config import config_problem
from .program import ProgramModel, Tag, const_number, module_tag_note, scoped_programs
from .suggest import NameIndex
from .types import (
    BOOL,
    DINT,
    ELEMENTARY,
    LREAL,
    REAL,
    ArrayType,
    DataType,
    Elementary,
    Kind,
    StructType,
    is_axis,
    is_unknown,
    promote,
)

SYSTEM_FLAGS = {"S:FS": "FS", "S:N": "N", "S:Z": "Z", "S:V": "V", "S:C": "C", "S:MINOR": "MINOR"}
ST_SYSTEM_FLAGS = {"S:FS"}
LVALUES = (n.Name, n.Member, n.Index, n.Bit, n.IndirectBit)
BITS = (n.Bit, n.IndirectBit)
COMPUTED = (n.Binary, n.Call)
OPERATIONS = (n.Unary, n.Binary, n.Call)  # what _is_expression can be true for


@dataclass(slots=True)
class FBCall:
    """An IEC-style function block call on an instance tag: `camIn(Master := X, ...)`."""

    instruction: Instruction
    instance: n.Name
    inputs: list[tuple[int, DataType, n.Expr]]  # member index, member type, value
    outputs: list[tuple[int, DataType, n.Expr]]  # member index, member type, target


@dataclass(slots=True)
class Analysis:
    type_of: dict[int, DataType] = field(default_factory=dict)
    enum_of: dict[int, int] = field(default_factory=dict)
    call_of: dict[int, Instruction] = field(default_factory=dict)
    fb_of: dict[int, FBCall] = field(default_factory=dict)
    tag_of: dict[int, Tag] = field(default_factory=dict)
    system_of: dict[int, str] = field(default_factory=dict)
    diags: list[Diagnostic] = field(default_factory=list)
    # statements and ladder instructions that use a tag which is not simulated (U306: module
    # data not in the export): they do not execute (SPEC 9.32), the rung condition passes on
    unsimulated: set[int] = field(default_factory=set)
    # ST literals TRUE/FALSE where the scope declares a tag of that name: the tag (decision 0160)
    bool_tag_of: dict[int, n.Name] = field(default_factory=dict)


def type_matches(t: DataType, accepted: tuple[str, ...]) -> bool:
    for a in accepted:
        if a == "ANY":
            return True
        if isinstance(t, Elementary):
            if a == "ANY_ELEMENTARY" or a == t.name:
                return True
            if a == "ANY_INT" and t.is_integer:
                return True
            if a == "ANY_REAL" and t.is_real:
                return True
            if a == "ANY_NUM" and (t.is_integer or t.is_real):
                return True
            if a == "ANY_BIT" and (t.is_integer or t.is_bool):
                return True
            if a == "ANY_TIME" and t.is_time:
                return True
        elif isinstance(t, StructType):
            if a == t.name or (a == "AXIS" and is_axis(t)):
                return True
            if a in ("STRING", "STRING_FAMILY") and t.is_string:
                return True
        elif isinstance(t, ArrayType) and (a.startswith("ANY") or type_matches(t.elem, (a,))):
            return True
    return False


@cache
def _elementary_accepted(accepted: tuple[str, ...]) -> frozenset[str]:
    """Names of the elementary types type_matches accepts for these catalog types.

    For an elementary type its answer depends on the name alone (the only elementary types
    are those of types.ELEMENTARY), so a set lookup can stand in for it on the hot path.
    """
    return frozenset(name for name, t in ELEMENTARY.items() if type_matches(t, accepted))


def block_reference_fits(mt: DataType, vt: DataType) -> bool:
    """A function-block input passed by reference: an axis for an axis parameter, a whole
    one-dimensional array of the parameter's structure (a CAM table) for a structure one."""
    if is_axis(mt):
        return is_axis(vt)
    return isinstance(vt, ArrayType) and vt.elem == mt and len(vt.dims) == 1


def unimplemented(ins: Instruction, language: str) -> bool:
    """U304: a catalog instruction that has no implementation in this language yet."""
    if ins.name in LOWERED or ins.family == "aoi":  # compiled inline (JSR SBR RET TND in ST too)
        return False
    return not has_implementation(ins.name, language)


def unsupported_message(ins: Instruction) -> str:
    """The U304 message: the catalog's reason why the instruction is not simulated."""
    reason = ins.unsupported or "this version cannot execute it yet"
    return f"{ins.name} is recognised but not simulated: {reason}"


def is_cam_profile_array(t: DataType) -> bool:
    return (
        isinstance(t, ArrayType) and isinstance(t.elem, StructType) and t.elem.name == "CAM_PROFILE"
    )


def cam_points(init: n.ArrayInit) -> list[tuple[float, float, int]]:
    """(Master, Slave, SegmentType) of each CAM-form element of a verified initialiser."""
    out = []
    for item in init.items:
        vals = {"MASTER": 0.0, "SLAVE": 0.0, "SEGMENTTYPE": 0}
        if isinstance(item, n.StructInit):
            for mname, _, value in item.members:
                v = const_number(value)
                if v is not None:
                    vals[mname.upper()] = v
        out.append((float(vals["MASTER"]), float(vals["SLAVE"]), int(vals["SEGMENTTYPE"])))
    return out


def int_literal_for_real(e: n.Expr, t: DataType, accepted: tuple[str, ...]) -> bool:
    """An integer (literal or tag) given for an input that takes only REAL/LREAL: Logix
    converts it (SPEC 9.15 for literals, decision 0054 for tags), so it is passed as a REAL."""
    return (
        isinstance(t, Elementary)
        and t.is_integer
        and not type_matches(t, accepted)
        and any(a in ("REAL", "LREAL", "ANY_REAL") for a in accepted)
    )


INTEGERS = frozenset(name for name, t in ELEMENTARY.items() if t.is_integer)


def converted_inputs(ins: Instruction, op: Operand, accepted: frozenset[str]) -> frozenset[str]:
    """The elementary types an input operand takes once Logix's conversions are counted
    (decision 0054): any integer where a number is taken (a DINT for MAM's REAL Speed, an INT
    for COP's DINT Length)."""
    if op.dir != "in" or op.enum is not None or not accepted - {"BOOL"}:
        return accepted
    return accepted | INTEGERS


def describe(t: DataType | None) -> str:
    return "unknown" if t is None else str(t)


# cache marker: "not looked up yet" (None means "no such tag"); Any, so a cache .get() with it
# as default still types as a Tag | None for mypy
_UNRESOLVED: Any = object()


@dataclass(frozen=True, slots=True)
class _OperandCheck:
    """Which of Checker.operand's checks apply to one catalog operand in one language.

    Worked out once per instruction (see _Plan): most operands are plain values or tags, and
    for them the checks for enumerations, routines, labels, object names and arrays are
    skipped with one test instead of six.
    """

    op: Operand
    special: bool  # enumeration, routine, label, nullable, array or GSV/SSV InstanceName
    no_expression: bool  # ladder: takes a tag or a literal, not an expression
    memory: bool  # format memory: a tag or element, not a bit
    tag: bool  # format tag or memory: must be a tag
    immediate: bool  # format immediate: must not be a tag
    written: bool  # dir out or inout, and not immediate: must be a tag
    elementary: frozenset[str]  # names of the elementary types it accepts (_elementary_accepted)

    @staticmethod
    def of(ins: Instruction, op: Operand, language: str) -> _OperandCheck:
        fmt = op.format
        special = (
            op.enum is not None
            or fmt in ("routine", "label", "array", "array_or_value", "task")
            or op.nullable
            or fmt == "object"
            or op.types == ("MODULE",)
        )
        return _OperandCheck(
            op,
            special,
            language == "rll" and not op.expression,
            fmt == "memory",
            fmt in ("tag", "memory"),
            fmt == "immediate",
            op.dir in ("out", "inout") and fmt != "immediate",
            converted_inputs(ins, op, _elementary_accepted(op.types)),
        )


@dataclass(slots=True)
class _Plan:
    """What the checker needs of one instruction name in one language, worked out once.

    A project checks the same few dozen instructions tens of thousands of times; the catalog
    lookup and what is checked of each operand do not change in between.
    """

    ins: Instruction | None  # None: unknown here (every call is reported, with a suggestion)
    required: int = 0  # operands that are not optional
    checks: tuple[_OperandCheck, ...] = ()  # one per operand of ins, in order
    unimplemented: bool = False  # U304: cannot run in this language (see unimplemented)


class Checker(LadderChecks):
    """One pass over a ProgramModel's routines.

    The model does not change while it is checked, so name resolutions are cached: tags per
    scope (see `scope`), instruction entries and their operand checks per language. Every
    diagnostic is still raised at each place it applies.
    """

    def __init__(self, model: ProgramModel) -> None:
        self.model = model
        self.a = Analysis()
        self.cat = catalog()
        self.path = ""
        self.language = "st"
        self.loop_depth = 0
        self.guard_depth = 0
        self.for_vars: list[str] = []
        self.motion_uses: dict[str, int] = {}
        self._scope: str | None = None
        self._aoi: Aoi | None = None
        # tag lookups by identifier as written, one cache per (program, AOI) scope: the same
        # name may be a different tag (or none) in another program or inside an AOI. Programs
        # without tags of their own see just the controller scope and share its cache.
        self._visible_by_scope: dict[tuple[str | None, str | None], dict[str, Tag | None]] = {}
        self._scoped_programs = scoped_programs(model.tags)
        self._visible: dict[str, Tag | None] = self._visible_cache()
        self._plans: dict[tuple[str, str], _Plan] = {}  # (name as written, language) -> plan
        self._literal_types: dict[str, DataType | None] = {}  # Literal.type -> its data type
        self._modules_reported: set[str] = set()  # U306 given for these modules (upper prefix)
        self._vague = False  # the statement or instruction being checked uses such a tag
        self._name_index: dict[tuple[str | None, str | None], NameIndex] = {}  # per scope
        self._hints: dict[str, str] = {}  # unknown instruction name -> its did-you-mean

    @property
    def scope(self) -> str | None:
        """The L5X program whose routine (or tag data) is being checked."""
        return self._scope

    @scope.setter
    def scope(self, program: str | None) -> None:
        self._scope = program
        self._visible = self._visible_cache()

    @property
    def aoi(self) -> Aoi | None:
        """The add-on instruction whose routine is being checked."""
        return self._aoi

    @aoi.setter
    def aoi(self, aoi: Aoi | None) -> None:
        self._aoi = aoi
        self._visible = self._visible_cache()

    def _visible_cache(self) -> dict[str, Tag | None]:
        key: tuple[str | None, str | None]
        if self._aoi is not None:  # its parameters and locals only, whatever the program
            key = (None, self._aoi.name.upper())
        elif self._scope is not None and self._scope.upper() in self._scoped_programs:
            key = (self._scope.upper(), None)
        else:  # file scope, the controller scope or a program without tags of its own
            key = (None, None)
        return self._visible_by_scope.setdefault(key, {})

    def lookup(self, name: str) -> Tag | None:
        """A tag visible here: AOI parameters and locals inside an AOI, else program then controller."""
        tag = self._visible.get(name, _UNRESOLVED)
        if tag is _UNRESOLVED:
            if self._aoi is not None:
                tag = self._aoi.tags.get(name.upper())
            else:
                tag = self.model.tag(name, self._scope)
            self._visible[name] = tag
        return tag

    def find_instruction(self, name: str) -> Instruction | None:
        """A project's add-on instruction, else the catalog instruction of this language."""
        aoi = self.model.aois.get(name.upper())
        if aoi is not None:
            return aoi.instruction  # type: ignore[attr-defined, no-any-return]
        return self.cat.instruction(name, self.language)

    # ------------------------------------------------------------ entry
    def run(self) -> Analysis:
        for _ in self.each_routine():
            pass
        return self.a

    def each_routine(self) -> Iterator[n.Routine | None]:
        """Check routine by routine, yielding each one once checked, then None after the tag
        data: the language server keeps what each routine added (decision 0117)."""
        projects = bool(self.model.programs)
        beyond = storage_limit(self.model.tags.values())
        if beyond is not None:  # refused before `run` allocates it (docs/limits.md)
            tag, total = beyond
            self.a.diags.append(
                diag(
                    "E132",
                    f"tag '{tag.name}' takes the program's storage to {total:,} values: "
                    f"the limit is {MAX_TAG_ELEMENTS:,} for all tags together",
                    tag.path,
                    tag.span,
                )
            )
        for r in self.model.routines:
            self.routine(r, r.program_name if projects else None)
            yield r
        for aoi in self.model.aois.values():
            self.aoi = aoi  # type: ignore[assignment]
            for r in aoi.routines.values():  # type: ignore[attr-defined]
                self.routine(r, None)
                yield r
            self.aoi = None
        if "l5x" in self.model.extra or "tag_data" in self.model.extra:
            self.check_tag_data()
        yield None

    def carried(self) -> tuple[dict[str, int], set[str]]:
        """What checking a routine leaves for the routines after it: the first line of each
        motion control tag (W203) and the modules whose U306 was given."""
        return self.motion_uses, self._modules_reported

    def routine(self, r: n.Routine, scope: str | None) -> None:
        self.path = r.path
        self.language = r.language
        self.scope = scope
        self.check_initialisers(r)
        beyond = routine_limits(r)  # measured first: the walks below recurse (docs/limits.md)
        for message, span in beyond:
            self.err("E132", message, span)
        if beyond:
            return
        if r.language == "st":
            self.stmts(r.body)
        elif r.language == "rll":
            self.rungs(r.rungs)

    def check_tag_data(self) -> None:
        """L5X tags (and AOI parameter defaults): exported data must fit the declared type."""
        source = self.model.extra.get("tag_data")  # --tags: only the tags that came from it
        tags = [t for t in self.model.tags.values() if source is None or t.init_path == source]
        for aoi in self.model.aois.values():
            tags.extend(aoi.tags.values())  # type: ignore[attr-defined]
        for tag in tags:
            if tag.init is not None and tag.alias_of is None:
                self.path = tag.init_path or tag.path
                self.scope = tag.program
                self.check_init(tag.init, tag.type)
        self.scope = None

    def err(self, code: str, msg: str, span: n.Span) -> None:
        self.a.diags.append(diag(code, msg, self.path, span))

    # ------------------------------------------------------------ declarations
    def check_initialisers(self, r: n.Routine) -> None:
        for d in r.decls:
            if d.init is None:
                continue
            for name, _ in d.names:
                tag = self.lookup(name)
                if tag is not None and tag.init_path == r.path:
                    self.check_init(d.init, tag.type)
                    break

    def check_init(self, init: n.Init, t: DataType) -> None:
        if is_unknown(t):
            return  # the type is reported where declared; its data cannot be verified
        if isinstance(init, n.ArrayInit) and is_cam_profile_array(t):
            self.cam_profile_init(init, t)
            return
        if isinstance(init, n.ArrayInit):
            if not isinstance(t, ArrayType):
                if isinstance(t, StructType) and t.name == "COORDINATE_SYSTEM":
                    return
                self.err("E118", f"a list initialiser needs an array, not {t}", init.span)
                return
            # SPEC 2.1: a wrong element count is an error, too few or too many; a CAM point
            # list may be shorter than its array (MCCP's Length says how many are used).
            short_ok = isinstance(t.elem, StructType) and t.elem.name == "CAM"
            if len(init.items) > t.size or (len(init.items) < t.size and not short_ok):
                self.err(
                    "E118", f"{len(init.items)} elements given for an array of {t.size}", init.span
                )
            for item in init.items:
                self.check_init(item, t.elem)
            return
        if isinstance(init, n.StructInit):
            if not isinstance(t, StructType):
                self.err("E118", f"a structure initialiser needs a structure, not {t}", init.span)
                return
            for mname, mspan, value in init.members:
                m = t.member(mname)
                if m is None:
                    self.err(
                        "E118",
                        f"'{t.name}' has no member '{mname}'{self.suggest(mname, [x for x, _ in t.members])}",
                        mspan,
                    )
                    continue
                mt = m[1]
                if (
                    isinstance(value, n.ArrayInit)
                    and isinstance(mt, ArrayType)
                    and is_axis(mt.elem)
                ):
                    for item in value.items:
                        tag = self.lookup(item.ident) if isinstance(item, n.Name) else None
                        if tag is None or not is_axis(tag.type):
                            self.err(
                                "E118", "Axes must name axis tags of this program", _init_span(item)
                            )
                    if not 2 <= len(value.items) <= 3:
                        self.err("E118", "a coordinate system has 2 or 3 axes", value.span)
                    continue
                self.check_init(value, mt)
                number = const_number(value)
                problem = None if number is None else config_problem(t.name, mname, number)
                if problem is not None:
                    self.err("E118", problem, _init_span(value))
            return
        # a single value
        if isinstance(t, ArrayType):
            self.err(
                "E118", f"an array of {t.size} needs a list initialiser [..]", _init_span(init)
            )
            return
        if isinstance(t, StructType):
            if t.is_string and isinstance(init, n.Literal) and init.type == "STRING":
                self.string_fits(t, init)
                return
            self.err(
                "E118",
                f"a {t.name} needs a structure initialiser (member := value)",
                _init_span(init),
            )
            return
        if isinstance(init, n.Literal) and init.type == "STRING":
            self.err("E116", f"a STRING cannot initialise a {t}", init.span)
            return
        literal = init.operand if isinstance(init, n.Unary) else init
        if isinstance(literal, n.Literal):
            self.literal_limits(literal)
        number = const_number(init)
        if number is None:
            self.err("E118", "an initial value must be a literal", _init_span(init))
        elif isinstance(t, Elementary) and (why := _out_of_range(init, number, t)) is not None:
            self.err("E118", why, _init_span(init))

    def cam_profile_init(self, init: n.ArrayInit, t: DataType) -> None:
        """CAM_PROFILE arrays are initialised with cam points (CAM form), calculated at load."""
        assert isinstance(t, ArrayType)
        cam = self.model.types.get("CAM")
        assert cam is not None
        if len(init.items) > t.size:
            self.err(
                "E118", f"{len(init.items)} cam points given for a profile of {t.size}", init.span
            )
            return
        if len(init.items) < 2:
            self.err("E118", "a cam profile needs at least 2 points", init.span)
            return
        before = len(self.a.diags)
        for item in init.items:
            self.check_init(item, cam)
        if len(self.a.diags) > before:
            return
        points = cam_points(init)
        for k in range(1, len(points)):
            if not points[k][0] > points[k - 1][0]:
                self.err("E118", "cam point Master values must increase", _init_span(init.items[k]))
                return
        for k, (_, _, seg) in enumerate(points[:-1]):
            if seg not in (0, 1):
                self.err(
                    "E118",
                    "cam point SegmentType must be 0 (linear) or 1 (cubic)",
                    _init_span(init.items[k]),
                )
                return

    # ------------------------------------------------------------ statements
    def stmts(self, body: list[n.Stmt]) -> None:
        for s in body:
            self.stmt(s)

    def stmt(self, s: n.Stmt) -> None:
        self._vague = False
        if isinstance(s, n.Assign):
            self.assign(s)
            self.settle(s)
        elif isinstance(s, n.CallStmt):
            self.call_stmt(s.call)
            self.settle(s)
        elif isinstance(s, n.If):
            self.guard_depth += 1
            for cond, body in s.branches:
                self._vague = False
                self.condition(cond)
                self.settle(s)
                self.stmts(body)
            if s.else_body is not None:
                self.stmts(s.else_body)
            self.guard_depth -= 1
        elif isinstance(s, n.Case):
            self.case(s)
        elif isinstance(s, n.For):
            self.for_loop(s)
        elif isinstance(s, n.While):
            self.condition(s.cond)
            self.settle(s)
            self.loop_body(s.body)
        elif isinstance(s, n.Repeat):
            self.loop_body(s.body)
            self._vague = False
            self.condition(s.cond)
            self.settle(s)
        elif isinstance(s, n.Exit):
            if self.loop_depth == 0:
                self.err("E127", "EXIT is only allowed inside FOR, WHILE or REPEAT", s.span)
        elif isinstance(s, n.Unsupported):
            self.err("E115", f"{s.keyword} is not part of Logix Structured Text", s.span)

    def settle(self, s: n.Stmt) -> None:
        """Mark `s` as not executed when what was just checked of it uses a tag that is not
        simulated (its condition, for IF/CASE/loops: the whole statement is skipped)."""
        if self._vague:
            self.a.unsimulated.add(id(s))
            self._vague = False

    def loop_body(self, body: list[n.Stmt]) -> None:
        self.loop_depth += 1
        self.guard_depth += 1
        self.stmts(body)
        self.loop_depth -= 1
        self.guard_depth -= 1

    def condition(self, e: n.Expr) -> None:
        t = self.expr(e)
        if t is not None and not (isinstance(t, Elementary)):
            self.err("E121", f"a condition must be BOOL or a number, not {t}", e.span)

    def case(self, s: n.Case) -> None:
        t = self.expr(s.selector)
        self.settle(s)
        if t is not None and not (isinstance(t, Elementary) and (t.is_integer or t.is_bool)):
            self.err("E121", f"a CASE selector must be an integer, not {t}", s.selector.span)
        self.guard_depth += 1
        for arm in s.arms:
            for label in arm.labels:
                parts = [label.low, label.high] if isinstance(label, n.CaseRange) else [label]
                for p in parts:
                    if const_number(p) is None:
                        self.err("E114", "CASE labels must be literal numbers", p.span)
                    else:
                        self.expr(p)
            self.stmts(arm.body)
        if s.else_body is not None:
            self.stmts(s.else_body)
        self.guard_depth -= 1

    def for_loop(self, s: n.For) -> None:
        t = self.expr(s.var)
        if t is not None and not (isinstance(t, Elementary) and t.is_integer):
            self.err("E121", f"a FOR index must be an integer tag, not {t}", s.var.span)
        if not isinstance(s.var, LVALUES):
            self.err("E120", "a FOR index must be a tag", s.var.span)
        for e in (s.start, s.end, s.step):
            if e is not None:
                et = self.expr(e)
                if et is not None and not (isinstance(et, Elementary) and et.is_numeric):
                    self.err("E121", f"FOR bounds must be numbers, not {et}", e.span)
        self.settle(s)
        self.for_vars.append(_text(s.var).upper())
        self.loop_body(s.body)
        self.for_vars.pop()

    def assign(self, s: n.Assign) -> None:
        tt = self.target(s.target)
        vt = self.expr(s.value)
        if _text(s.target).upper() in self.for_vars:
            self.a.diags.append(
                diag(
                    "W201",
                    f"FOR index '{_text(s.target)}' is assigned inside its loop",
                    self.path,
                    s.target.span,
                )
            )
        if tt is None or vt is None:
            return
        self.string_fits(tt, s.value)
        if isinstance(tt, Elementary) and isinstance(vt, Elementary) and (tt.unit or vt.unit):
            why = time_types.assignable(tt, vt, isinstance(s.value, n.Literal))
            if why is not None:
                self.err("E121", why, s.value.span)
            return
        self.check_assignable(tt, vt, s.value.span)

    def string_fits(self, tt: DataType, value: object) -> None:
        """E133: a string literal longer than the target STRING type holds (never truncated)."""
        if not (
            isinstance(value, n.Literal)
            and isinstance(value.value, bytes)
            and isinstance(tt, StructType)
            and tt.is_string
        ):
            return
        data = tt.members[1][1]
        capacity = data.size if isinstance(data, ArrayType) else 0
        if len(value.value) > capacity:
            self.err(
                "E133",
                f"string literal of {len(value.value)} characters: a {tt.name} holds {capacity}",
                value.span,
            )

    def check_assignable(self, tt: DataType, vt: DataType, span: n.Span) -> None:
        t_str = isinstance(tt, StructType) and tt.is_string
        v_str = isinstance(vt, StructType) and vt.is_string
        if t_str and v_str:
            return
        if t_str or v_str:
            self.err("E116", f"cannot assign {vt} to {tt}", span)
            return
        if isinstance(tt, Elementary) and isinstance(vt, Elementary):
            return
        if tt is vt or (isinstance(tt, ArrayType) and tt == vt):
            self.err("E121", f"structures and arrays are copied with COP, not ':=' ({tt})", span)
            return
        self.err("E121", f"cannot assign {vt} to {tt}", span)

    def target(self, e: n.Expr) -> DataType | None:
        if not isinstance(e, LVALUES):
            self.err("E120", "only a tag, member, element or bit can be assigned", e.span)
            self.expr(e)
            return None
        t = self.expr(e)
        if isinstance(e, n.Member):
            bt = self.a.type_of.get(id(e.base))
            if isinstance(bt, StructType) and e.name.upper() in bt.readonly:
                self.err("E120", f"{bt.name}.{bt.member_name(e.name)} is read-only", e.name_span)
        if isinstance(e, n.Name) and id(e) in self.a.system_of:
            self.err("E120", f"{e.ident} is read-only", e.span)
        return t

    # ------------------------------------------------------------ calls
    def call_stmt(self, c: n.Call) -> None:
        tag = self.lookup(c.name)
        if tag is not None and isinstance(tag.type, StructType):
            if tag.type.unknown:  # a block of a type reported where declared: no cascade
                for a in c.args:
                    self.loose(a.value)
                return
            ins = self.cat.instruction(tag.type.name, "st")
            # `PID(PID, pv, ...)`: a tag named like the instruction it is the type of, called
            # with positional operands, is that instruction's Logix call (a v35 AOI's PID)
            positional = bool(c.args) and c.args[0].name is None
            own_name = ins is not None and c.name.upper() in (
                ins.name.upper(),
                *(a.upper() for a in ins.aliases),
            )
            if ins is not None and not (positional and own_name):
                self.fb_call(c, tag, ins)
                return
        named = next((a for a in c.args if a.name is not None), None)
        self.instruction(c, c.name, c.name_span, c.span, [a.value for a in c.args], named)

    def ladder_instr(self, i: n.LadderInstr) -> None:
        ops = i.operands
        for k, e in enumerate(ops):
            if (e.__class__ is n.Literal and e.type == "BOOL") or (  # type: ignore[attr-defined]
                e.__class__ is n.Name and e.ident.upper() in ("TRUE", "FALSE")  # type: ignore[attr-defined]
            ):
                ops[k] = self.bool_tag(e)  # type: ignore[arg-type]
        self._vague = False
        self.instruction(i, i.name, i.name_span, i.span, ops, None)
        if self._vague:
            self.a.unsimulated.add(id(i))

    def bool_tag(self, e: n.Literal | n.Name) -> n.Expr:
        """`True` / `False` as a ladder operand: a tag when the project declares one of that name.

        Studio allows tags named TRUE and FALSE, and ladder has no BOOL literals of its own
        (decision 0054): `OTE(True)` writes the tag. Without such a tag the word is the
        literal it was read as. The rung's operand list is rewritten either way, so a rung
        kept between analyses (the language server's parse memo) follows the current tags."""
        text = e.text if isinstance(e, n.Literal) else e.ident
        if self.lookup(text) is not None:
            return e if isinstance(e, n.Name) else n.Name(text, e.span)
        if isinstance(e, n.Literal):
            return e
        return n.Literal(1 if text.upper() == "TRUE" else 0, "BOOL", text, e.span)

    def instruction(
        self,
        node: n.Call | n.LadderInstr,
        name: str,
        name_span: n.Span,
        span: n.Span,
        args: list[n.Expr],
        named: n.Arg | None,
    ) -> None:
        """An instruction call, ST statement or ladder element alike: catalog entry and operands."""
        plan = self.plan(name)
        ins = plan.ins
        if ins is None:
            other = self.cat.instruction_any(name)
            if other is not None:
                self.err(
                    "E126",
                    f"{name} is not available in {'Structured Text' if self.language == 'st' else 'ladder'}",
                    name_span,
                )
            else:
                hint = self._hints.get(name)
                if hint is None:  # one suggestion per name, however often it is called
                    names = sorted({i.name for i in self.cat.instructions})
                    hint = self._hints[name] = self.suggest(name, names)
                self.err("E103", f"unknown instruction '{name}'{hint}", name_span)
            for e in args:
                self.loose(e)
            return
        if ins.kind == "function":
            self.err("E126", f"{ins.name} is a function: use it in an expression", name_span)
            return
        self.a.call_of[id(node)] = ins
        if named is not None:
            self.err("E130", "named parameters are only for function block instances", named.span)
        else:
            self.operands(ins, args, span, plan)
            if ins.family == "aoi":
                self.aoi_arguments(name, args)
        if plan.unimplemented:  # require_implementation, answered once per plan
            self.require_implementation(ins, name_span)
        if ins.transitional and self.language == "st" and self.guard_depth == 0:
            self.a.diags.append(
                diag(
                    "W204",
                    f"{ins.name} runs every scan here: guard it with IF or an edge",
                    self.path,
                    span,
                )
            )

    def loose(self, e: n.Expr) -> None:
        """An operand whose expected kind is unknown (the instruction or block was already
        reported): a word that is not a tag may be an enumeration, so it is not an error."""
        if isinstance(e, n.Placeholder | n.EnumText):
            return
        if _enum_text(e) is not None and not (
            isinstance(e, n.Name) and (":" in e.ident or self.lookup(e.ident) is not None)
        ):
            return
        self.expr(e)

    def plan(self, name: str) -> _Plan:
        """The cached catalog (or AOI) entry of an instruction name in the current language."""
        key = (name, self.language)
        plan = self._plans.get(key)
        if plan is None:
            ins = self.find_instruction(name)
            if ins is None:
                plan = _Plan(None)
            else:
                required = sum(1 for o in ins.operands if not o.optional)
                checks = tuple(_OperandCheck.of(ins, o, self.language) for o in ins.operands)
                plan = _Plan(ins, required, checks, unimplemented(ins, self.language))
            self._plans[key] = plan
        return plan

    def fb_call(self, c: n.Call, tag: Tag, ins: Instruction) -> None:
        """`camIn(Master := X, Execute := go, ...)`: every parameter by name, elementary inputs
        stored into the instance, axis and CAM-array inputs passed by reference, enumeration
        words for enumerated inputs, outputs (readonly members) only read; the catalog marks
        the inputs every call must give (SPEC 3.1, decision 0126)."""
        st = tag.type
        assert isinstance(st, StructType)
        inst = n.Name(c.name, c.name_span)
        self.a.tag_of[id(inst)] = tag
        self.a.type_of[id(inst)] = st
        fb = FBCall(ins, inst, [], [])
        td = self.cat.type(st.name)
        info = {m.name.upper(): m for m in td.members} if td is not None else {}
        given: set[str] = set()
        for a in c.args:
            if isinstance(a.value, n.Placeholder):
                self.err(
                    "E128",
                    f"function block call '{c.name}': an empty parameter is not allowed; give parameters by name",
                    a.span,
                )
                continue
            if a.name is None:
                self.err(
                    "E130", "function block parameters are given by name (Name := value)", a.span
                )
                given.add("")  # reported: no missing-parameter error on top
                continue
            out = a.name.endswith("=>")
            mname = a.name[:-2] if out else a.name
            m = st.member(mname)
            if m is None:
                names = [x for x, _ in st.members]
                self.err(
                    "E102",
                    f"'{st.name}' has no parameter '{mname}'{self.suggest(mname, names)}",
                    a.span,
                )
                self.loose(a.value)
                continue
            mi = info.get(mname.upper())
            if out:
                vt = self.target(a.value)
                if vt is not None:
                    self.check_assignable(vt, m[1], a.span)
                fb.outputs.append((m[0], m[1], a.value))
                continue
            given.add(mname.upper())
            if mi is not None and mi.readonly:
                self.err(
                    "E120", f"{st.member_name(mname)} is an output of {st.name}: read it", a.span
                )
                self.loose(a.value)
                continue
            if mi is not None and mi.enum is not None:
                op = Operand(mi.name, ("DINT",), "value", "in", enum=mi.enum)
                if self.enum_operand(ins, op, a.value):
                    fb.inputs.append((m[0], m[1], a.value))
                    continue
            vt = self.expr(a.value)
            if isinstance(m[1], Elementary):
                if vt is not None:
                    self.check_assignable(m[1], vt, a.value.span)
            elif vt is not None and not self.fb_reference(m[1], vt, a.value):
                what = "an axis tag" if is_axis(m[1]) else f"a whole {m[1]} array tag"
                self.err(
                    "E105",
                    f"{st.name} parameter {st.member_name(mname)} needs {what}, not {vt}",
                    a.value.span,
                )
            fb.inputs.append((m[0], m[1], a.value))
        missing = [m.name for m in info.values() if m.required and m.name.upper() not in given]
        if missing and "" not in given:
            self.err(
                "E104",
                f"call of '{c.name}' ({st.name}) is missing {', '.join(missing)}",
                c.name_span,
            )
        self.a.fb_of[id(c)] = fb
        self.require_implementation(ins, c.name_span)

    @staticmethod
    def fb_reference(mt: DataType, vt: DataType, e: n.Expr) -> bool:
        return isinstance(e, n.Name | n.Member) and block_reference_fits(mt, vt)

    def aoi_arguments(self, name: str, args: list[n.Expr]) -> None:
        """InOut arguments are passed by reference: they need the parameter's exact type."""
        aoi = self.model.aois[name.upper()]
        ops = aoi.instruction.operands[1:]  # type: ignore[attr-defined]
        for p, op, e in zip(aoi.required, ops, args[1:], strict=False):  # type: ignore[attr-defined]
            t = self.a.type_of.get(id(e))
            if (
                p.usage == "InOut"
                and t is not None
                and type_matches(t, op.types)  # else the operand check said it already
                and not same_shape(t, p.type)
            ):
                name_ = aoi.name  # type: ignore[attr-defined]
                self.err(
                    "E105", f"{name_} InOut parameter {p.name} needs a {p.type}, not {t}", e.span
                )

    def require_implementation(
        self, ins: Instruction, span: n.Span, language: str | None = None
    ) -> None:
        if unimplemented(ins, language or self.language):
            self.err("U304", unsupported_message(ins), span)

    def operands(self, ins: Instruction, args: list[n.Expr], span: n.Span, plan: _Plan) -> None:
        ops, checks, required = ins.operands, plan.checks, plan.required
        given, known = len(args), len(ops)
        if given < required or (given > known and not ins.variadic):
            expect = f"{required}" if required == known else f"{required} to {known}"
            self.err(
                "E104",
                f"{ins.name} takes {expect} operand{'' if expect == '1' else 's'}, {given} given",
                span,
            )
            words = any(o.enum for o in ops)
            for e in args:
                # with the operands miscounted, a bare word may be an enumeration text of a
                # shifted operand: no "undefined tag" for it, the count error is the finding
                if not words or not (
                    isinstance(e, n.EnumText)
                    or (isinstance(e, n.Name) and self.lookup(e.ident) is None)
                ):
                    self.expr(e)
            return
        rule = INSTRUCTION_CHECKS.get(ins.check) if ins.check else None
        if rule is not None and rule.operands:
            rule.fn(self, ins, args, checks)  # the rule lays out the operands itself (JSR)
        else:
            for check, e in zip(checks, args, strict=False):
                self.operand(ins, check, e)
            if given > known:
                for e in args[known:]:  # the last operand repeats (variadic)
                    self.operand(ins, checks[-1], e)
        if ins.family == "compare" and given >= 2:
            self.compare_kinds(ins, args)
        types = [self.a.type_of.get(id(e)) for e in args]
        if any(isinstance(t, Elementary) and t.unit for t in types):  # decision 0072
            why = time_types.instruction_error(
                ins.name,
                [t if isinstance(t, Elementary) else None for t in types],
                [isinstance(e, n.Literal) for e in args],
            )
            if why is not None:
                self.err("E105", why, span)
        if rule is not None and not rule.operands:
            rule.fn(self, ins, args, checks)

    # ------------------------------------------------------------ instruction rules
    # Each is named by its instruction's catalog entry (`check = "..."`, INSTRUCTION_CHECKS).
    def jsr_parameters(
        self, ins: Instruction, args: list[n.Expr], checks: tuple[_OperandCheck, ...]
    ) -> None:
        """JSR(Routine, n, n input parameters..., return parameters...)."""
        inputs_end = len(ins.operands)
        if len(args) > 1:
            count = const_number(args[1])
            inputs_end = 2 + (count if isinstance(count, int) and count > 0 else 0)
        for i, e in enumerate(args):
            self.operand(ins, checks[i if i < 2 else 2 if i < inputs_end else 3], e)

    def distinct_axes(
        self, ins: Instruction, args: list[n.Expr], checks: tuple[_OperandCheck, ...]
    ) -> None:
        """MDAC: a master must be another axis than its slave."""
        if len(args) >= 2 and _text(args[0]).upper() == _text(args[1]).upper():
            self.err(
                "E112", "the master axis must be a different axis from the slave", args[1].span
            )

    def system_read(
        self, ins: Instruction, args: list[n.Expr], checks: tuple[_OperandCheck, ...]
    ) -> None:
        if len(args) >= 3:
            self.system_attribute(ins, args, write=False)

    def system_write(
        self, ins: Instruction, args: list[n.Expr], checks: tuple[_OperandCheck, ...]
    ) -> None:
        if len(args) >= 3:
            self.system_attribute(ins, args, write=True)

    def compare_kinds(self, ins: Instruction, args: list[n.Expr]) -> None:
        """Ladder compares take two numbers or two STRINGs (each operand alone accepts either)."""
        a, b = (self.a.type_of.get(id(e)) for e in args[:2])
        if a is None or b is None:
            return
        a_str = isinstance(a, StructType) and a.is_string
        b_str = isinstance(b, StructType) and b.is_string
        if a_str != b_str:
            self.err("E116", f"{ins.name} cannot compare a STRING with a number", args[1].span)

    def same_kind_move(
        self, ins: Instruction, args: list[n.Expr], checks: tuple[_OperandCheck, ...]
    ) -> None:
        """MOV takes a STRING (tag or literal) into a STRING, or a number into a number."""
        if len(args) < 2:
            return
        a, b = (self.a.type_of.get(id(e)) for e in args[:2])
        if a is None or b is None:
            return
        a_str = isinstance(a, StructType) and a.is_string
        b_str = isinstance(b, StructType) and b.is_string
        if a_str != b_str:
            self.err("E116", f"MOV cannot move {a} into {b}", args[1].span)

    def system_attribute(self, ins: Instruction, args: list[n.Expr], write: bool) -> None:
        """U303 for a GSV/SSV class and attribute pair the simulator does not model."""
        from ..instructions.ladder_system import attribute_names, unsupported

        cls, attr = self.a.enum_of.get(id(args[0])), self.a.enum_of.get(id(args[2]))
        if cls is None or attr is None:
            return
        c, a = attribute_names(cls, attr)
        if unsupported(c, a, write=write):
            what = "set" if write else "read"
            known = catalog().system_attribute(c, a) is not None  # stdlib/system_objects.toml
            self.err(
                "U303",
                f"{ins.name}: {_text(args[0])} attribute {_text(args[2])} cannot be {what} in the simulated controller"
                if known
                else f"{ins.name}: {_text(args[2])} is not an attribute logixst knows for class {_text(args[0])}; it is not simulated",
                args[2].span,
            )

    def operand(self, ins: Instruction, check: _OperandCheck, e: n.Expr) -> None:
        op = check.op
        if isinstance(e, n.Placeholder):
            if not op.placeholder:
                what = (
                    "cannot be left empty"
                    if self.language == "st"
                    else "needs a value here, not a placeholder"
                )
                self.err("E128", f"{ins.name} operand {op.name} {what}", e.span)
            return
        if check.special:
            if self.special_operand(ins, check, e):
                return
        elif check.no_expression and isinstance(e, OPERATIONS) and _is_expression(e):  # tags first
            self.expression_operand(ins, op, e)
            return
        t = self.expr(e)
        is_tag = isinstance(e, LVALUES) and id(e) not in self.a.enum_of
        if check.memory and isinstance(e, BITS):
            self.err(
                "E106", f"{ins.name} operand {op.name} must be a tag or element, not a bit", e.span
            )
            return
        if check.tag and not is_tag:
            self.err("E106", f"{ins.name} operand {op.name} must be a tag", e.span)
            return
        if check.immediate and is_tag:
            self.err("E107", f"{ins.name} operand {op.name} must be an immediate value", e.span)
            return
        if check.written and not is_tag:
            self.err("E106", f"{ins.name} operand {op.name} is written: it must be a tag", e.span)
            return
        if t is None:
            return
        if not (
            t.name in check.elementary if isinstance(t, Elementary) else type_matches(t, op.types)
        ):
            if int_literal_for_real(e, t, op.types) and op.dir == "in":
                return  # SPEC 9.15: integer literals are accepted for REAL operands
            if "BOOL" in op.types and const_number(e) in (0, 1) and not is_tag:
                return  # an immediate 0/1 for a BOOL operand (PID Inhold bit, ALMD ProgAck)
            if op.expression and "BOOL" in op.types and isinstance(const_number(e), int):
                return  # FSC(..., 0): a constant condition, as Studio accepts (decision 0054)
            if any(x == "AXIS" for x in op.types) or is_axis(t):
                self.err("E113", f"{ins.name} operand {op.name} needs an axis, not {t}", e.span)
            else:
                self.err(
                    "E105",
                    f"{ins.name} operand {op.name} does not accept {t} (accepts {', '.join(op.types)})",
                    e.span,
                )
            return
        if isinstance(t, StructType) and t.name == "MOTION_INSTRUCTION":
            key = _text(e).upper()
            if key in self.motion_uses:
                self.a.diags.append(
                    diag(
                        "W203",
                        f"{_text(e)} is also the control tag of another instruction (line {self.motion_uses[key]})",
                        self.path,
                        e.span,
                    )
                )
            else:
                self.motion_uses[key] = e.span.line

    def expression_operand(self, ins: Instruction, op: Operand, e: n.Expr) -> None:
        self.err(
            "E106",
            f"{ins.name} operand {op.name} takes a tag or a literal, not an expression (only CMP, CPT, FAL and FSC compute)",
            e.span,
        )
        self.expr(e)

    def special_operand(self, ins: Instruction, check: _OperandCheck, e: n.Expr) -> bool:
        """The checks of an operand that is not a plain value or tag (_OperandCheck.special), in
        Checker.operand's order; True when the operand is done with."""
        op = check.op
        if op.enum is not None and self.enum_operand(ins, op, e):
            return True
        if check.no_expression and _is_expression(e):
            self.expression_operand(ins, op, e)
            return True
        fmt = op.format
        if fmt == "routine":
            if not isinstance(e, n.Name):
                self.err("E124", "JSR needs a routine name", e.span)
            elif self.aoi is not None:  # its logic has no routines to call (no real AOI does)
                self.err("E124", "an add-on instruction cannot call a routine", e.span)
            elif self.model.routine(e.ident, self.scope) is None:
                names = [
                    r.name
                    for r in self.model.routines
                    if self.scope is None or r.program_name == self.scope
                ]
                self.err(
                    "E124", f"no routine named '{e.ident}'{self.suggest(e.ident, names)}", e.span
                )
            return True
        if fmt == "label":
            return True
        if fmt == "task":
            self.task_operand(e)
            return True
        if fmt == "object" and isinstance(e, n.Name) and self.lookup(e.ident) is None:
            self.a.enum_of[id(e)] = 0  # an object's name (task, program, THIS), not a tag
            self.a.type_of[id(e)] = DINT
            return True
        if op.types == ("MODULE",) and isinstance(e, n.Name):
            tag = self.lookup(e.ident)
            if tag is None or not (isinstance(tag.type, StructType) and tag.type.name == "MODULE"):
                # a module's name (an AOI's MODULE InOut: `IO_Status(Inst, Rack1, ...)`), not a
                # tag, even where a tag has the same name (decision 0054)
                self.a.enum_of[id(e)] = 0
                self.a.type_of[id(e)] = DINT
                return True
        if op.nullable and const_number(e) == 0:
            return True  # a literal 0 means the optional array is not used
        if fmt == "array":
            self.array_operand(ins, op, e)
            return True
        if fmt == "array_or_value" and self.names_array(e):
            self.array_operand(ins, op, e)
            return True
        return False

    def names_array(self, e: n.Expr) -> bool:
        """Is the operand an array tag or one of its elements (format array_or_value)?"""
        if isinstance(e, n.Index):
            return True
        tag = self.lookup(e.ident) if isinstance(e, n.Name) else None
        return tag is not None and isinstance(tag.type, ArrayType)

    def task_operand(self, e: n.Expr) -> None:
        """EVENT's Task: a task of the project (a lone routine file has no tasks to check)."""
        if not isinstance(e, n.Name):
            self.err("E124", "EVENT needs a task name", e.span)
            return
        tasks = self.model.tasks
        if tasks and not any(t.name.upper() == e.ident.upper() for t in tasks):
            names = [t.name for t in tasks]
            self.err("E124", f"no task named '{e.ident}'{self.suggest(e.ident, names)}", e.span)

    def array_operand(self, ins: Instruction, op: Operand, e: n.Expr) -> None:
        base = e.base if isinstance(e, n.Index) else e
        t = self.expr(e)
        bt = self.a.type_of.get(id(base)) if isinstance(e, n.Index) else t
        if not isinstance(bt, ArrayType):
            if t is not None:
                self.err(
                    "E105", f"{ins.name} operand {op.name} needs an array tag, not {t}", e.span
                )
            return
        if (
            isinstance(bt.elem, StructType)
            and bt.elem.name == "CAM_PROFILE"
            and isinstance(e, n.Index)
        ):
            if any(const_number(i) != 0 for i in e.indices):
                self.err(
                    "E111",
                    f"{ins.name} operand {op.name}: a CAM_PROFILE array is given as element [0]",
                    e.span,
                )
        if not type_matches(bt.elem, op.types):
            self.err(
                "E105",
                f"{ins.name} operand {op.name} does not accept {bt} (accepts {', '.join(op.types)})",
                e.span,
            )

    def enum_operand(self, ins: Instruction, op: Operand, e: n.Expr) -> bool:
        """Resolve enumeration text or number; True when `e` was handled as an enumeration."""
        assert op.enum is not None
        en = self.cat.enum(op.enum)
        text = _enum_text(e)
        if text is not None:
            if (
                isinstance(e, n.Name)
                and self.lookup(e.ident) is not None
                and en.lookup(text) is None
            ):
                return False  # a tag, checked as a value below
            v = en.lookup(text)
            if v is None:
                labels = [x.label for x in en.values]
                self.err(
                    "E108",
                    f"'{text}' is not a value of {ins.name} {op.name}{self.suggest(text.lower(), labels)}",
                    e.span,
                )
            else:
                self.a.enum_of[id(e)] = v.value
                self.a.type_of[id(e)] = DINT
            return True
        num = const_number(e)
        if isinstance(num, int):
            if en.by_value(num) is None and not (en.counts and num > 0):
                vals = ", ".join(f"{x.value} {x.label}" for x in en.values)
                self.err("E109", f"{num} is not a value of {ins.name} {op.name} ({vals})", e.span)
            else:
                self.a.enum_of[id(e)] = num
                self.a.type_of[id(e)] = DINT
            return True
        return False

    def suggest_tag(self, ident: str) -> str:
        """Did-you-mean for an undefined tag: the closest tag visible here (bounded cost)."""
        if self._aoi is not None:
            key: tuple[str | None, str | None] = (None, self._aoi.name.upper())
        else:
            key = (self._scope.upper() if self._scope is not None else None, None)
        index = self._name_index.get(key)
        if index is None:
            if self._aoi is not None:
                names = [t.name for t in self._aoi.tags.values()]
            else:
                names = [
                    t.name
                    for t in self.model.tags.values()
                    if t.program is None or (key[0] is not None and t.program.upper() == key[0])
                ]
            index = self._name_index[key] = NameIndex(names)
        best = index.best(ident)
        return f" (did you mean '{best}'?)" if best is not None else ""

    @staticmethod
    def suggest(word: str, options: list[str]) -> str:
        close = difflib.get_close_matches(word, options, n=1, cutoff=0.6)
        if not close:
            lowered = {o.lower(): o for o in options}
            close = [
                lowered[x]
                for x in difflib.get_close_matches(word.lower(), list(lowered), n=1, cutoff=0.6)
            ]
        return f" (did you mean '{close[0]}'?)" if close else ""

    # ------------------------------------------------------------ expressions
    def expr(self, e: n.Expr) -> DataType | None:
        check = _EXPR_CHECKS.get(type(e))  # one dict lookup instead of an isinstance chain
        t = check(self, e) if check is not None else self._expr(e)
        if t is not None:
            self.a.type_of[id(e)] = t
        return t

    def _expr(self, e: n.Expr) -> DataType | None:
        """The check for a node that is not exactly one of the node classes (a subclass)."""
        for cls, check in _EXPR_CHECKS.items():
            if isinstance(e, cls):
                return check(self, e)
        return None

    def index(self, e: n.Index) -> DataType | None:
        bt = self.expr(e.base)
        for i in e.indices:
            it = self.expr(i)
            if it is not None and not (
                isinstance(it, Elementary) and (it.is_integer or it.is_bool)
            ):
                self.err("E121", f"a subscript must be an integer, not {it}", i.span)
        if bt is None:
            return None
        if not isinstance(bt, ArrayType):
            self.err("E110", f"{_text(e.base)} is not an array", e.span)
            return None
        if len(e.indices) != len(bt.dims):
            self.err(
                "E110",
                f"{_text(e.base)} has {len(bt.dims)} dimension(s), {len(e.indices)} subscript(s) given",
                e.span,
            )
            return None
        for i, size in zip(e.indices, bt.dims, strict=True):
            v = const_number(i)
            if isinstance(v, int) and not 0 <= v < size:
                self.err("E122", f"subscript {v} is outside 0..{size - 1}", i.span)
        return bt.elem

    def bit(self, e: n.Bit) -> DataType | None:
        bt = self.expr(e.base)
        if bt is None:
            return None
        if not (isinstance(bt, Elementary) and bt.is_integer):
            self.err("E121", f"bit access needs an integer, not {bt}", e.span)
            return None
        if not 0 <= e.bit < bt.bits:
            self.err("E122", f"bit {e.bit} is outside 0..{bt.bits - 1} of a {bt}", e.span)
            return None
        return BOOL

    def indirect_bit(self, e: n.IndirectBit) -> DataType | None:
        bt = self.expr(e.base)
        it = self.expr(e.index)
        if it is not None and not (isinstance(it, Elementary) and it.is_integer):
            self.err("E121", f"a bit number must be an integer, not {it}", e.index.span)
        if bt is None:
            return None
        if not (isinstance(bt, Elementary) and bt.is_integer):
            self.err("E121", f"bit access needs an integer, not {bt}", e.span)
            return None
        return BOOL

    def unary(self, e: n.Unary) -> DataType | None:
        t = self.expr(e.operand)
        if t is None:
            return None
        if not isinstance(t, Elementary):
            self.err(
                "E116" if isinstance(t, StructType) and t.is_string else "E121",
                f"{e.op} cannot be applied to {t}",
                e.span,
            )
            return None
        if t.unit and (e.op == "NOT" or t.absolute):  # decision 0072: '-' negates a duration
            self.err("E121", f"{e.op} cannot be applied to {t}", e.span)
            return None
        if e.op == "NOT":
            if t.is_real:
                self.err("E121", "NOT needs BOOL or an integer, not a REAL", e.span)
                return None
            return t
        return DINT if t.is_bool else t

    def enum_text(self, e: n.EnumText) -> DataType | None:
        self.err("E108", f"'{e.text}' is only valid as an enumerated operand", e.span)
        return None

    def placeholder(self, e: n.Placeholder) -> DataType | None:
        return None

    def literal(self, e: n.Literal) -> DataType | None:
        if e.type == "BOOL" and e.text.upper() in ("TRUE", "FALSE") and self.lookup(e.text):
            # a project's tag named TRUE or FALSE: the word reads the tag, as in ladder
            # (decision 0054); v33 AOIs declare them and set them (decision 0160)
            name = n.Name(e.text, e.span)
            self.a.bool_tag_of[id(e)] = name
            return self.expr(name)
        if len(e.text) > 18:  # shorter integer texts always fit 64 bits: no second parse
            self.literal_limits(e)
        t = self._literal_types.get(e.type, _UNRESOLVED)  # a handful of names: BOOL DINT REAL...
        if t is _UNRESOLVED:
            t = self._literal_types[e.type] = self.model.types.get(e.type)
        return t

    def literal_limits(self, e: n.Literal) -> None:
        """E133 for a literal no Logix type holds (docs/decisions/0133-literal-limits.md)."""
        problem = literal_problem(e.text) if e.type not in ("STRING", "BOOL") else None
        if problem is not None:
            self.err("E133", problem, e.span)

    def member(self, e: n.Member) -> DataType | None:
        bt = self.expr(e.base)
        if bt is None:
            return None
        if not isinstance(bt, StructType):
            self.err("E102", f"{_text(e.base)} is a {bt}: it has no member '{e.name}'", e.name_span)
            return None
        key = e.name.upper()
        i = bt.index.get(key)  # StructType.member, without upper-casing the name twice
        if bt.unknown:
            return None  # (a member of) a type reported where declared: anything goes
        if i is None or key in bt.hidden:
            names = [x for x, _ in bt.members if x.upper() not in bt.hidden]
            self.err(
                "E102",
                f"'{bt.name}' has no member '{e.name}'{self.suggest(e.name, names)}",
                e.name_span,
            )
            return None
        mt = bt.members[i][1]
        if isinstance(mt, StructType) and mt.unknown:
            self._vague = True
            return None
        return mt

    def name(self, e: n.Name) -> DataType | None:
        ident = e.ident
        if ":" in ident:  # every system flag has one (S:N): plain tag names skip the upper()
            key = ident.upper()
            if key in SYSTEM_FLAGS:
                if self.language == "st" and key not in ST_SYSTEM_FLAGS:
                    self.err("E123", f"{e.ident} is available in ladder only", e.span)
                    return None
                self.a.system_of[id(e)] = SYSTEM_FLAGS[key]
                return BOOL
        tag = self._visible.get(ident, _UNRESOLVED)  # self.lookup, inlined: a cache hit mostly
        if tag is _UNRESOLVED:
            tag = self.lookup(ident)
        if tag is None:
            note = module_tag_note(self.model, ident)
            if note:  # a module's I/O tag: one U306 per module, not an error at each use
                module = ident.rsplit(":", 1)[0].upper()
                if module not in self._modules_reported:
                    self._modules_reported.add(module)
                    self.err("U306", f"module I/O tag '{ident}'{note}; it is not simulated", e.span)
                self._vague = True
                return None
            self.err("E101", f"undefined tag '{ident}'{self.suggest_tag(ident)}", e.span)
            return None
        self.a.tag_of[id(e)] = tag
        t = tag.type
        if t.__class__ is StructType and t.unknown:  # type: ignore[union-attr]
            self._vague = True
            return None  # its type was reported where declared: its uses are not checked
        return t

    def binary(self, e: n.Binary) -> DataType | None:
        lt = self.expr(e.left)
        rt = self.expr(e.right)
        if lt is None or rt is None:
            return None
        l_str = isinstance(lt, StructType) and lt.is_string
        r_str = isinstance(rt, StructType) and rt.is_string
        if l_str or r_str:
            if l_str and r_str and e.op in ("=", "<>", "<", "<=", ">", ">="):
                return BOOL
            self.err(
                "E116",
                f"'{e.op}' cannot mix STRING and numbers"
                if l_str != r_str
                else f"'{e.op}' is not defined for STRING",
                e.span,
            )
            return None
        if not isinstance(lt, Elementary) or not isinstance(rt, Elementary):
            bad = lt if not isinstance(lt, Elementary) else rt
            self.err("E121", f"'{e.op}' cannot be applied to {bad}", e.span)
            return None
        op = e.op
        if lt.unit or rt.unit:  # time and date types (decision 0072)
            r = time_types.binary_type(
                op, lt, rt, isinstance(e.left, n.Literal), isinstance(e.right, n.Literal)
            )
            if isinstance(r, str):
                self.err("E121", r, e.span)
                return None
            return BOOL if op in ("=", "<>", "<", "<=", ">", ">=") else r
        if op in ("=", "<>", "<", "<=", ">", ">="):
            return BOOL
        if op in ("AND", "OR", "XOR"):
            if lt.is_real or rt.is_real:
                self.err("E121", f"{op} needs BOOL or integers, not REAL", e.span)
                return None
            return promote(lt, rt)
        if op == "**":
            if lt.is_real or rt.is_real:
                return LREAL if LREAL in (lt, rt) else REAL
            return promote(lt, rt) if not (lt.is_bool and rt.is_bool) else DINT
        t = promote(lt, rt)
        if op == "MOD" and t.is_real:
            return t
        return DINT if t.is_bool else t

    def st_function(self, name: str) -> Instruction | None:
        """The catalog entry for a name called in an expression; ladder mnemonics (SQR) map to
        the function their rung instruction names as alias (SQRT)."""
        ins = self.cat.instruction(name, "st")
        if (ins is None or ins.kind != "function") and self.language == "rll":
            rung_ins = self.cat.instruction(name, "rll")
            for other in (rung_ins.name, *rung_ins.aliases) if rung_ins is not None else ():
                f = self.cat.instruction(other, "st")
                if f is not None and f.kind == "function":
                    return f
        return ins

    def function(self, c: n.Call) -> DataType | None:
        ins = self.st_function(c.name)
        if ins is None or ins.kind != "function":
            for a in c.args:
                self.expr(a.value)
            if ins is not None:
                self.err(
                    "E126", f"{ins.name} is an instruction: call it as a statement", c.name_span
                )
            else:
                fnames = sorted({i.name for i in self.cat.instructions if i.kind == "function"})
                self.err(
                    "E103",
                    f"unknown function '{c.name}'{self.suggest(c.name.upper(), fnames)}",
                    c.name_span,
                )
            return None
        self.a.call_of[id(c)] = ins
        self.require_implementation(ins, c.name_span, "st")  # functions are ST entries, in CPT too
        if len(c.args) != len(ins.operands):
            self.err(
                "E104",
                f"{ins.name} takes {len(ins.operands)} argument(s), {len(c.args)} given",
                c.span,
            )
            return None
        arg_types: list[Elementary] = []
        for a in c.args:  # ATAN2 takes two numbers, every other function one
            at = self.expr(a.value)
            if at is None:
                return None
            if not (isinstance(at, Elementary) and not at.is_bool):
                self.err("E105", f"{ins.name} needs a number, not {at}", a.span)
                return None
            arg_types.append(at)
        t = LREAL if len(arg_types) > 1 and LREAL in arg_types else arg_types[0]
        if ins.result == "REAL":  # the catalog's result type (LREAL in, LREAL out)
            return LREAL if t is LREAL else REAL
        if ins.result == "BOOL":
            return BOOL
        return t


# Checker.expr's check for each expression node class (in the order an isinstance chain
# would try them, for _expr's subclass fallback)
_EXPR_CHECKS: dict[type, Callable[[Checker, Any], DataType | None]] = {
    n.Literal: Checker.literal,
    n.Name: Checker.name,
    n.Member: Checker.member,
    n.Index: Checker.index,
    n.Bit: Checker.bit,
    n.IndirectBit: Checker.indirect_bit,
    n.Unary: Checker.unary,
    n.Binary: Checker.binary,
    n.Call: Checker.function,
    n.EnumText: Checker.enum_text,
    n.Placeholder: Checker.placeholder,
}


def _is_expression(e: n.Expr) -> bool:
    """An operand that computes (a + b, ABS(x), NOT b), as opposed to a tag or a literal (-5)."""
    if isinstance(e, n.Unary):
        return not (e.op == "-" and isinstance(e.operand, n.Literal))
    return isinstance(e, COMPUTED)


def _enum_text(e: n.Expr) -> str | None:
    """Operand text that may be an enumeration word (`Once`, `%ofTime`, `S-Curve`)."""
    if isinstance(e, n.Name):
        return e.ident
    if isinstance(e, n.EnumText):
        return e.text
    if isinstance(e, n.Binary) and e.op in ("-", "/"):  # S-Curve, HIGH/LOW
        left, right = _enum_text(e.left), _enum_text(e.right)
        if left is not None and right is not None:
            return f"{left}{e.op}{right}"
    return None


def _text(e: object) -> str:
    """Canonical source text of an operand (for identity checks and messages)."""
    if isinstance(e, n.Name):
        return e.ident
    if isinstance(e, n.Member):
        return f"{_text(e.base)}.{e.name}"
    if isinstance(e, n.Index):
        return f"{_text(e.base)}[{','.join(_text(i) for i in e.indices)}]"
    if isinstance(e, n.Bit):
        return f"{_text(e.base)}.{e.bit}"
    if isinstance(e, n.IndirectBit):
        return f"{_text(e.base)}.[{_text(e.index)}]"
    if isinstance(e, n.Literal):
        return e.text
    return "?"


def _out_of_range(init: object, value: int | float, t: Elementary) -> str | None:
    """Why a literal initial value does not fit an elementary tag (None when it does).

    Studio refuses `SINT := 300` or `BOOL := 2` rather than wrapping them (as `--set` does,
    SPEC 9.12). A radix (or L5X ASCII) literal is a bit pattern read at the tag's width, so
    `SINT := 16#FF` is -1; only a pattern wider than the tag is refused.
    """
    if t.kind is Kind.BOOL:
        return None if value in (0, 1) else f"a BOOL starts as 0/1 or TRUE/FALSE, not {value}"
    if not t.is_integer or isinstance(value, float) and value != value:
        return None
    if (
        isinstance(init, n.Literal)
        and ("#" in init.text or init.text.startswith("'"))
        and isinstance(value, int)
    ):  # a radix or L5X ASCII ('$FF') literal
        # the lexer already reads a pattern of the literal's own width as signed (2#1...1 is -1)
        width = 64 if init.type in ("LINT", "ULINT") else 32
        ok = 0 <= value % (1 << width) < 1 << t.bits
    else:
        lo = -(1 << (t.bits - 1)) if t.signed else 0
        hi = (1 << (t.bits - 1 if t.signed else t.bits)) - 1
        ok = lo - 0.5 <= value < hi + 0.5 if isinstance(value, float) else lo <= value <= hi
    shown = init.text if isinstance(init, n.Literal) else value
    return None if ok else f"{shown} does not fit a {t.name}"


def _init_span(init: object) -> n.Span:
    return init.span  # type: ignore[attr-defined, no-any-return]


def check_program(model: ProgramModel) -> Analysis:
    return Checker(model).run()


@dataclass(frozen=True, slots=True)
class InstructionCheck:
    """A rule of one instruction beyond its operand table, named by its catalog entry."""

    fn: Callable[[Checker, Instruction, list[n.Expr], tuple[_OperandCheck, ...]], None]
    operands: bool = False  # it checks the operands itself (instead of one check per operand)


INSTRUCTION_CHECKS: dict[str, InstructionCheck] = {
    "jsr_parameters": InstructionCheck(Checker.jsr_parameters, operands=True),
    "same_kind_move": InstructionCheck(Checker.same_kind_move),
    "distinct_axes": InstructionCheck(Checker.distinct_axes),
    "system_read": InstructionCheck(Checker.system_read),
    "system_write": InstructionCheck(Checker.system_write),
}
