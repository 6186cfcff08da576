"""L5X project exports (Studio 5000 XML) -> the AST plus tags, types, AOIs, programs and tasks.

Reading is syntax only: data types become TypeDecl nodes, tags VarDecl nodes whose
initialisers come from the export's data (l5x_data.py), ST routines are parsed with
parse_st and RLL rungs with parse_rung. Every span is a position in the .L5X file itself
(SPEC 9.9); `context` maps file lines back to program / routine / rung or ST line so
diagnostics can name them. Elements this tool does not know are ignored.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass, field, fields, is_dataclass
from typing import TypeVar

from stdlib import catalog

from ..diagnostics import Diagnostic, diag
from . import nodes as n
from .l5x_data import DataReader, RawMember, _dims
from .l5x_modules import ModuleReader
from .st_parser import parse_st
from .xml_reader import Positions, XElem, XmlRejected, parse_xml

_T = TypeVar("_T")

ROOT = "RSLogix5000Content"
_BIT_ALIAS = re.compile(r"\.\d+$")  # an alias for a bit: `_bSts.1`


@dataclass(slots=True)
class AliasDecl:
    name: str
    target: str
    span: n.Span
    usage: str = ""  # AOI alias parameters: Input | Output
    required: bool = False  # AOI alias parameters: a call operand


@dataclass(slots=True)
class AoiParam:
    name: str
    usage: str  # "Input" | "Output" | "InOut"
    required: bool
    decl: n.VarDecl


@dataclass(slots=True)
class AoiDecl:
    name: str
    span: n.Span
    params: list[AoiParam] = field(default_factory=list)
    locals: list[n.VarDecl] = field(default_factory=list)
    routines: list[n.Routine] = field(default_factory=list)
    aliases: list[AliasDecl] = field(default_factory=list)  # parameters aliasing local tags
    param_order: list[str] = field(default_factory=list)  # every parameter name, as declared


@dataclass(slots=True)
class ProgramDecl:
    name: str
    span: n.Span
    main: str
    tags: list[n.VarDecl] = field(default_factory=list)
    aliases: list[AliasDecl] = field(default_factory=list)
    routines: list[n.Routine] = field(default_factory=list)
    disabled: bool = False


@dataclass(slots=True)
class TaskDecl:
    name: str
    type: str  # CONTINUOUS | PERIODIC | EVENT
    rate_ms: float
    priority: int
    programs: list[tuple[str, n.Span]]
    inhibited: bool
    span: n.Span


@dataclass(slots=True)
class L5XProject:
    path: str
    controller: str = ""
    revision: str = ""
    target_type: str = ""
    types: list[n.TypeDecl] = field(default_factory=list)
    aois: list[AoiDecl] = field(default_factory=list)
    tags: list[n.VarDecl] = field(default_factory=list)
    aliases: list[AliasDecl] = field(default_factory=list)
    programs: list[ProgramDecl] = field(default_factory=list)
    tasks: list[TaskDecl] = field(default_factory=list)
    axis_groups: dict[str, str] = field(default_factory=dict)  # axis tag -> motion group tag
    coarse_update_us: float | None = None
    modules: dict[str, str] = field(
        default_factory=dict
    )  # upper I/O tag prefix (`LOCAL:1`) -> module name
    context: dict[int, str] = field(
        default_factory=dict
    )  # file line -> "program P, routine R, rung N"

    def annotate(self, d: Diagnostic) -> Diagnostic:
        """Name program, routine and rung / ST line in a diagnostic inside a routine."""
        where = self.context.get(d.span.line)
        if d.path != self.path or where is None or where in d.message:
            return d
        return Diagnostic(d.code, f"{d.message} ({where})", d.path, d.span)


# Axis parameters in the export -> members of our axis and coordinate-system types.
_AXIS_PARAMS = {
    "MAXIMUMSPEED": "MaximumSpeed",
    "MAXIMUMACCELERATION": "MaximumAccel",
    "MAXIMUMDECELERATION": "MaximumDecel",
    "MAXIMUMACCELERATIONJERK": "MaximumAccelJerk",
    "MAXIMUMDECELERATIONJERK": "MaximumDecelJerk",
    "CONVERSIONCONSTANT": "ConversionConstant",
    "POSITIONERRORTOLERANCE": "PositionErrorTolerance",
    "MAXIMUMPOSITIVETRAVEL": "MaximumPositiveTravel",
    "MAXIMUMNEGATIVETRAVEL": "MaximumNegativeTravel",
    "AVERAGEVELOCITYTIMEBASE": "AverageVelocityTimebase",
    "POSITIONLOOPBANDWIDTH": "PositionLoopBandwidth",
    "COMMANDTOLERANCE": "CommandTolerance",
    "ACTUALTOLERANCE": "ActualTolerance",
    "HOMEPOSITION": "HomePosition",
    "HOMEOFFSET": "HomeOffset",
    "HOMESPEED": "HomeSpeed",
    "HOMERETURNSPEED": "HomeReturnSpeed",
}


def axis_rotary(attrs: dict[str, str]) -> tuple[bool, float] | None:
    """Rotary or linear and the unwind in position units, from an axis's exported
    parameters (upper-case names; decision 0115), or None when they say nothing.

    A CIP drive axis says `TravelMode="Cyclic"` (else Unlimited or Limited: linear) and
    gives its unwind in position units as PositionUnwindNumerator / Denominator. Older
    axes say `RotaryAxis="Rotary"` (or Linear) with PositionUnwind in feedback counts,
    ConversionConstant counts per position unit. A rotary axis whose unwind cannot be
    read keeps 0, which the runtime reports as not configured (error 11)."""

    def num(key: str) -> float | None:
        try:
            return float(attrs[key])
        except (KeyError, ValueError):
            return None

    travel = attrs.get("TRAVELMODE")
    if travel is not None:
        if travel.strip().lower() != "cyclic":
            return False, 0.0
        top, bottom = num("POSITIONUNWINDNUMERATOR"), num("POSITIONUNWINDDENOMINATOR")
        return True, (top / bottom if top is not None and bottom else 0.0)
    mode = attrs.get("ROTARYAXIS")
    if mode is None:
        return None
    if mode.strip().lower() != "rotary":
        return False, 0.0
    counts, per_unit = num("POSITIONUNWIND"), num("CONVERSIONCONSTANT")
    return True, (counts / per_unit if counts is not None and per_unit else 0.0)


def rotary_members(attrs: dict[str, str], sp: n.Span) -> list[tuple[str, n.Span, n.Init]]:
    """RotaryAxis and PositionUnwind initialisers for an axis tag (see axis_rotary)."""
    found = axis_rotary(attrs)
    if found is None:
        return []
    rotary, unwind = found
    return [
        ("RotaryAxis", sp, n.Literal(int(rotary), "BOOL", str(int(rotary)), sp)),
        ("PositionUnwind", sp, n.Literal(unwind, "REAL", repr(unwind), sp)),
    ]


# Axis parameters written as enumeration text (`HomeMode="Active"`): member and catalog enum.
_AXIS_ENUM_PARAMS = {
    "HOMEMODE": "HomeMode",
    "HOMESEQUENCE": "HomeSequence",
    "HOMEDIRECTION": "HomeDirection",
}


@dataclass(slots=True)
class ParseMemo:
    """Routine pieces parsed by the previous read of the same document.

    The language server reads an export again after every change; a rung or ST routine
    whose text and position are unchanged is taken from here instead of being parsed again
    (downstream, only the checker rewrites a ladder operand `True`/`False` into the tag or
    the literal, by the current tags, so a kept rung follows them). Only the pieces of the
    last read are kept.
    """

    previous: dict[tuple[object, ...], object] = field(default_factory=dict)
    current: dict[tuple[object, ...], object] = field(default_factory=dict)
    # The last read itself, so that one program routine can be read again alone after an
    # edit inside its text (read_routine_again, decision 0117): its reader and the elements
    # its program routines came from. Only the routines' elements are kept, not the tree.
    reader: _Reader | None = None
    sources: list[RoutineSource] = field(default_factory=list)

    def get(self, key: tuple[object, ...], parse: Callable[[], _T]) -> _T:
        hit = self.previous.get(key)
        value: _T = hit if hit is not None else parse()  # type: ignore[assignment]
        self.current[key] = value
        return value

    def rotate(self) -> None:
        self.previous, self.current = self.current, {}


@dataclass(slots=True)
class RoutineSource:
    """Where the last read found one program routine."""

    program: int  # index in L5XProject.programs
    index: int  # index in that program's routines
    element: XElem  # its <Routine> (or <EncodedData>) element
    owner: str  # "program P", as diagnostics name it
    diags: tuple[int, int]  # its slice of the read's diagnostics (reading and parsing it)


def read_routine_again(
    memo: ParseMemo, source: RoutineSource
) -> tuple[n.Routine | None, list[Diagnostic]]:
    """Read one program routine of the last read again, after its elements' text changed
    (the caller has checked that nothing else moved); diagnostics come annotated."""
    reader = memo.reader
    assert reader is not None
    start = len(reader.diags)
    routine = reader.routine(source.element, source.owner)
    if routine is not None:
        routine.program_name = reader.project.programs[source.program].name
    diags = [reader.project.annotate(d) for d in reader.diags[start:]]
    del reader.diags[start:]
    memo.previous.update(memo.current)  # keep the pieces of the last full read as well
    memo.current.clear()
    return routine, diags


def read_l5x(
    data: bytes, path: str, memo: ParseMemo | None = None
) -> tuple[L5XProject | None, list[Diagnostic]]:
    """Parse an export; None (with an S007 diagnostic) when it is not a usable L5X file."""
    try:
        root, pos = parse_xml(data)
    except XmlRejected as exc:
        return None, [
            diag("S007", exc.message, path, n.Span(exc.line, exc.col, exc.line, exc.col + 1))
        ]
    if root.tag != ROOT:
        return None, [
            diag(
                "S007",
                f"not a Studio 5000 export: the root element is <{root.tag}>, expected <{ROOT}>",
                path,
                pos.elem_span(root),
            )
        ]
    ctl = root.child("Controller")
    if ctl is None and root.get("TargetType") == "Module" and root.child("Module") is not None:
        # A module export without context (ContainsContext="false") puts the target <Module>
        # straight under the root: one module and its connection data, no controller, no
        # program, nothing to scan (decision 0070).
        ctl = root
    if ctl is None:
        return None, [
            diag("S007", "the export has no <Controller> element", path, pos.elem_span(root))
        ]
    reader = _Reader(path, pos, memo or ParseMemo())
    reader.memo.sources = []
    project = reader.read(root, ctl)
    if memo is not None:
        memo.rotate()
        memo.reader = reader
    return project, [project.annotate(d) for d in reader.diags]


class _Reader:
    def __init__(self, path: str, pos: Positions, memo: ParseMemo) -> None:
        self.path = path
        self.pos = pos
        self.memo = memo
        self.diags: list[Diagnostic] = []
        self.udt_raw: dict[str, list[RawMember]] = {}
        self.data = DataReader(pos, self.udt_raw)
        self.project = L5XProject(path)

    def span(self, e: XElem) -> n.Span:
        return self.pos.elem_span(e)

    def err(self, code: str, msg: str, span: n.Span) -> None:
        self.diags.append(diag(code, msg, self.path, span))

    def name_of(self, e: XElem, what: str) -> str | None:
        name = e.get("Name").strip()
        if not name:
            self.err("S007", f"<{e.tag}> {what} has no Name attribute", self.span(e))
            return None
        return name

    # ------------------------------------------------------------ top level
    def read(self, root: XElem, ctl: XElem) -> L5XProject:
        p = self.project
        p.controller = ctl.get("Name")
        p.revision = root.get("SoftwareRevision") or f"{ctl.get('MajorRev')}.{ctl.get('MinorRev')}"
        p.target_type = root.get("TargetType")
        for sec in ctl.all("DataTypes"):
            for e in sec.all("DataType"):
                self.datatype(e)
        # the module sections: <Controller><Modules>, or the root itself of a module export
        for sec in ctl.all("Modules") if ctl.tag == "Controller" else [ctl]:
            mods = ModuleReader(self.pos, self.data).read(sec)
            p.types.extend(mods.types)
            p.tags.extend(mods.tags)
            p.modules.update(mods.modules)
        for sec in ctl.all("AddOnInstructionDefinitions"):
            for e in sec.children:
                if e.tag == "AddOnInstructionDefinition":
                    self.aoi(e)
                elif e.tag == "EncodedData":
                    self.protected_aoi(e)
        # module tags (`Local:1:I`) the module sections declared: with ExportOptions IOTags
        # Studio lists them again among the controller tags, where the module's own stand
        io_tags = {nm.upper() for d in p.tags for nm, _ in d.names if ":" in nm}
        for sec in ctl.all("Tags"):
            tags, aliases = self.tags(sec)
            if io_tags:
                tags = [d for d in tags if not any(nm.upper() in io_tags for nm, _ in d.names)]
            p.tags.extend(tags)
            p.aliases.extend(aliases)
        for sec in ctl.all("Programs"):
            for e in sec.children:
                if e.tag == "Program":
                    self.program(e)
                elif e.tag == "EncodedData":
                    self.encoded(e, "program")
        for sec in ctl.all("Tasks"):
            for e in sec.all("Task"):
                self.task(e)
        return p

    def encoded(self, e: XElem, what: str) -> None:
        name = e.get("Name") or "?"
        self.err(
            "U302",
            f"{what} '{name}' is protected (encoded); its content cannot be read",
            self.span(e),
        )

    # ------------------------------------------------------------ data types
    def datatype(self, e: XElem) -> None:
        name = self.name_of(e, "data type")
        if name is None:
            return
        raw: list[RawMember] = []
        decls: list[n.VarDecl] = []
        members = e.child("Members")
        for m in members.all("Member") if members is not None else []:
            mname = self.name_of(m, "member")
            dtype = m.get("DataType").strip()
            if mname is None:
                continue
            if not dtype:
                self.err(
                    "S007", f"member '{mname}' of '{name}' has no DataType attribute", self.span(m)
                )
                continue
            dims = _dims(m.get("Dimension"))
            hidden = m.get("Hidden").lower() == "true"
            bit = int(m.get("BitNumber") or 0) if m.get("BitNumber").isdecimal() else 0
            raw.append(
                RawMember(
                    mname, dtype.upper(), dims[0] if dims else 0, hidden, m.get("Target"), bit
                )
            )
            if hidden:
                continue  # the SINT that hosts BOOL members: each BIT member is a BOOL of its own here
            tname = "BOOL" if dtype.upper() == "BIT" else dtype
            sp = self.span(m)
            decls.append(
                n.VarDecl(
                    [(mname, sp)],
                    n.TypeRef(tname.upper(), [(0, d - 1) for d in dims], sp),
                    None,
                    sp,
                )
            )
        described = e.get("Class") in ("ProductDefined", "IO")
        if not (described and name.upper() in self.udt_raw):
            self.udt_raw[name.upper()] = raw
        sp = self.span(e)
        self.project.types.append(n.TypeDecl(name, decls, sp, sp, described))

    # ------------------------------------------------------------ tags
    def tags(self, sec: XElem) -> tuple[list[n.VarDecl], list[AliasDecl]]:
        decls: list[n.VarDecl] = []
        aliases: list[AliasDecl] = []
        for e in sec.children:
            if e.tag == "EncodedData":
                self.encoded(e, "tag")
                continue
            if e.tag != "Tag":
                continue
            name = self.name_of(e, "tag")
            if name is None:
                continue
            sp = self.span(e)
            if e.get("TagType") == "Alias":
                aliases.append(AliasDecl(name, e.get("AliasFor"), sp))
                continue
            if e.get("Use") == "Reference" and not e.get("DataType"):
                # the context of a program export names another program's tag it uses
                # (`\Other.Tag`) without describing it: the tag lives outside the export
                continue
            decl = self.var(e, name, "tag")
            if decl is not None:
                decls.append(decl)
        return decls, aliases

    def var(self, e: XElem, name: str, what: str, data_tag: str = "Data") -> n.VarDecl | None:
        sp = self.span(e)
        dtype = e.get("DataType").strip()
        if not dtype:
            self.err("S007", f"{what} '{name}' has no DataType attribute", sp)
            return None
        dims = _dims(e.get("Dimensions") or e.get("Dimension"))
        tref = n.TypeRef(dtype.upper(), [(0, d - 1) for d in dims], sp)
        init = self.motion_data(e, name, dtype.upper()) if data_tag == "Data" else None
        if init is None:
            init = self.data.tag_init(e, data_tag)
        return n.VarDecl(
            [(name, sp)], tref, init, sp, block="VAR_GLOBAL" if what == "tag" else "VAR"
        )

    def motion_data(self, e: XElem, name: str, dtype: str) -> n.Init | None:
        """Axis, motion group and coordinate-system tags carry parameters, not decorated data."""
        for d in e.all("Data"):
            fmt = d.get("Format")
            if fmt not in ("Axis", "MotionGroup", "CoordinateSystem") or not d.children:
                continue
            params = d.children[0]
            sp = self.span(params)
            members: list[tuple[str, n.Span, n.Init]] = []
            if fmt == "MotionGroup":
                cup = params.get("CoarseUpdatePeriod")
                if cup:
                    try:
                        us = float(cup)
                    except ValueError:
                        us = None
                    if us is not None:
                        self.project.coarse_update_us = us
                        members.append(
                            ("CoarseUpdatePeriod", sp, n.Literal(int(us), "DINT", cup, sp))
                        )
                return n.StructInit(members, sp)
            group = params.get("MotionGroup")
            if group and fmt == "Axis":
                self.project.axis_groups[name.upper()] = group
            for attr, value in params.attrs.items():
                member = _AXIS_PARAMS.get(attr.upper())
                enum_member = _AXIS_ENUM_PARAMS.get(attr.upper())
                if enum_member is not None:  # the catalog enumeration gives the number
                    ev = catalog().enum(enum_member).lookup(value)
                    if ev is not None:
                        members.append(
                            (enum_member, sp, n.Literal(ev.value, "DINT", str(ev.value), sp))
                        )
                    continue
                if member is None:
                    continue
                try:
                    num = float(value)
                except ValueError:
                    continue
                members.append((member, sp, n.Literal(num, "REAL", value, sp)))
            if fmt == "Axis":
                members += rotary_members({k.upper(): v for k, v in params.attrs.items()}, sp)
            if fmt == "CoordinateSystem":
                members.extend(self.coordinate_system(params, sp))
            return n.StructInit(members, sp)
        return None

    def coordinate_system(self, params: XElem, sp: n.Span) -> list[tuple[str, n.Span, n.Init]]:
        """A coordinate system's tolerances and primary axes. Studio lists the axes in the
        `Axes` attribute with their `CoordinationMode`; only Primary axes span the Cartesian
        system (orientation and ancillary axes of robots do not), and a system keeps them
        only when there are 2 or 3 (else MCLM/MCCM report it, error 13)."""
        out: list[tuple[str, n.Span, n.Init]] = []
        for attr, member in (
            ("ActualPositionTolerance", "ActualTolerance"),
            ("CommandPositionTolerance", "CommandTolerance"),
        ):
            text = params.get(attr)
            try:
                out.append((member, sp, n.Literal(float(text), "REAL", text, sp)))
            except ValueError:
                continue
        names = params.get("Axes").split()
        modes = params.get("CoordinationMode").split()
        if modes and len(modes) == len(names):
            names = [a for a, m in zip(names, modes, strict=True) if m.lower() == "primary"]
        items: list[n.Init] = [n.Name(a, sp) for a in names]
        if not items:  # older exports name the axes in child elements
            items = [
                n.Name(a.get("Name"), self.span(a))
                for a in _walk(params)
                if a.tag in ("Axis", "AxisName", "CoordinateSystemAxis") and a.get("Name")
            ]
        if 2 <= len(items) <= 3:
            out.append(("Axes", sp, n.ArrayInit(items, sp)))
        return out

    # ------------------------------------------------------------ add-on instructions
    def protected_aoi(self, e: XElem) -> None:
        """A source-protected AOI: its parameters are exported in clear, its local tags and
        routines are encrypted. It is declared from its parameters, so its instance tags and
        calls check as for any AOI; a call runs no logic (decision 0057)."""
        if e.get("EncodedType") != "AddOnInstructionDefinition" or e.child("Parameters") is None:
            self.encoded(e, "add-on instruction")
            return
        name = e.get("Name") or "?"
        self.err(
            "U302",
            f"add-on instruction '{name}' is protected (encoded): calls are checked against its"
            " parameters, and its logic does not run",
            self.span(e),
        )
        self.aoi(e, protected=True)

    def aoi(self, e: XElem, protected: bool = False) -> None:
        name = self.name_of(e, "add-on instruction")
        if name is None:
            return
        aoi = AoiDecl(name, self.span(e))
        params = e.child("Parameters")
        for pe in params.all("Parameter") if params is not None else []:
            pname = self.name_of(pe, "parameter")
            if pname is None:
                continue
            usage = pe.get("Usage") or "Input"
            required = pe.get("Required").lower() == "true" or usage == "InOut"
            aoi.param_order.append(pname)
            if pe.get("TagType") == "Alias" and protected:
                # its target is an encrypted local tag: the parameter stays visible from
                # outside with its own storage; only a bit alias (`_bSts.1`) shows its type
                if not _BIT_ALIAS.search(pe.get("AliasFor")):
                    continue
                sp = self.span(pe)
                bit = n.VarDecl([(pname, sp)], n.TypeRef("BOOL", [], sp), None, sp, block="VAR")
                aoi.params.append(AoiParam(pname, usage, required, bit))
                continue
            if pe.get("TagType") == "Alias":
                aoi.aliases.append(
                    AliasDecl(pname, pe.get("AliasFor"), self.span(pe), usage, required)
                )
                continue
            decl = self.var(pe, pname, "parameter", data_tag="DefaultData")
            if decl is None:
                continue
            aoi.params.append(AoiParam(pname, usage, required, decl))
        local = e.child("LocalTags")
        for le in local.all("LocalTag") if local is not None else []:
            lname = self.name_of(le, "local tag")
            if lname is None:
                continue
            decl = self.var(le, lname, "local tag", data_tag="DefaultData")
            if decl is not None:
                aoi.locals.append(decl)
        for sec in e.all("Routines"):
            for re_ in sec.children:
                r = self.routine(re_, f"add-on instruction {name}")
                if r is not None:
                    aoi.routines.append(r)
        if not protected and e.child("EncodedData") is not None:
            self.encoded(e.child("EncodedData"), f"add-on instruction {name}")  # type: ignore[arg-type]
        self.project.aois.append(aoi)

    # ------------------------------------------------------------ programs and routines
    def program(self, e: XElem) -> None:
        name = self.name_of(e, "program")
        if name is None:
            return
        prog = ProgramDecl(
            name,
            self.span(e),
            e.get("MainRoutineName"),
            disabled=e.get("Disabled").lower() == "true",
        )
        for sec in e.all("Tags"):
            tags, aliases = self.tags(sec)
            prog.tags.extend(tags)
            prog.aliases.extend(aliases)
        for sec in e.all("Routines"):
            for re_ in sec.children:
                start = len(self.diags)
                r = self.routine(re_, f"program {name}")
                if r is not None:
                    r.program_name = name
                    self.memo.sources.append(
                        RoutineSource(
                            len(self.project.programs),
                            len(prog.routines),
                            re_,
                            f"program {name}",
                            (start, len(self.diags)),
                        )
                    )
                    prog.routines.append(r)
        self.project.programs.append(prog)

    def routine(self, e: XElem, owner: str) -> n.Routine | None:
        if e.tag == "EncodedData":  # a protected routine: JSR finds it, and it runs nothing
            self.encoded(e, "routine")
            encoded_name = e.get("Name")
            if not encoded_name:
                return None
            return n.Routine(encoded_name, "unsupported", self.path, span=self.span(e))
        if e.tag != "Routine":
            return None
        name = self.name_of(e, "routine")
        if name is None:
            return None
        where = f"{owner}, routine {name}"
        if e.child("EncodedData") is not None:
            self.encoded(e.child("EncodedData"), f"routine '{name}' of {owner}; it")  # type: ignore[arg-type]
            return n.Routine(name, "unsupported", self.path, span=self.span(e))
        kind = e.get("Type").upper()
        if kind == "ST":
            return self.st_routine(e, name, where)
        if kind == "RLL":
            return self.rll_routine(e, name, where)
        label = {"FBD": "function block diagram", "SFC": "sequential function chart"}.get(
            kind, kind or "untyped"
        )
        self.err("U301", f"{label} routine '{name}' ({owner}) is not supported", self.span(e))
        return n.Routine(name, "unsupported", self.path, span=self.span(e))

    def st_routine(self, e: XElem, name: str, where: str) -> n.Routine:
        content = e.child("STContent")
        lines = content.all("Line") if content is not None else []
        # Joined line k (1-based) -> (file line, column offset of its first character).
        line_map: list[tuple[int, int]] = []
        texts: list[str] = []
        for i, le in enumerate(lines):
            text = le.text
            number = le.get("Number")
            st_line = int(number) if number.isdecimal() else i
            if le.text_offset >= 0:
                fl, fc = self.pos.at(le.text_offset)
            else:
                fl, fc = self.pos.at(le.offset)
            for j, part in enumerate(text.split("\n")):
                line_map.append((fl + j, fc - 1 if j == 0 else 0))
                self.project.context.setdefault(fl + j, f"{where}, line {st_line}")
                texts.append(part)
        if not line_map:
            sp = self.span(e)
            line_map.append((sp.line, sp.col - 1))
            texts.append("")
        joined = "\n".join(texts)

        def parse() -> tuple[n.Routine, list[Diagnostic]]:
            routine, diags = parse_st(joined, self.path, name)

            def remap(s: n.Span) -> n.Span:
                a = line_map[min(max(s.line, 1), len(line_map)) - 1]
                b = line_map[min(max(s.end_line, 1), len(line_map)) - 1]
                return n.Span(a[0], s.col + a[1], b[0], s.end_col + b[1])

            _remap(routine, remap)
            return routine, [Diagnostic(d.code, d.message, d.path, remap(d.span)) for d in diags]

        routine, diags = self.memo.get(("st", name, joined, tuple(line_map)), parse)
        self.diags.extend(diags)
        routine.span = self.span(e)
        return routine

    def rll_routine(self, e: XElem, name: str, where: str) -> n.Routine:
        from .rll_parser import parse_rung

        routine = n.Routine(name, "rll", self.path, span=self.span(e))
        content = e.child("RLLContent")
        for i, re_ in enumerate(content.all("Rung") if content is not None else []):
            if re_.get("Type").upper().startswith("D"):
                continue  # a rung marked for deletion by pending edits
            number_text = re_.get("Number")
            number = int(number_text) if number_text.isdecimal() else i
            text_e = re_.child("Text")
            if text_e is None:
                self.err("S007", f"rung {number} of {where} has no <Text>", self.span(re_))
                continue
            text = text_e.text
            off = text_e.text_offset if text_e.text_offset >= 0 else text_e.offset
            line, col = self.pos.at(off)
            label = f"{where}, rung {number}"
            for k in range(text.count("\n") + 1):
                self.project.context.setdefault(line + k, label)
            rung, diags = self.memo.get(
                ("rung", text, number, line, col),
                lambda: parse_rung(text, self.path, number, line, col),  # noqa: B023 (called now)
            )
            self.diags.extend(diags)
            if rung is not None:
                comment = re_.child("Comment")
                if comment is not None:
                    rung.comment = comment.text.strip()
                routine.rungs.append(rung)
        return routine

    # ------------------------------------------------------------ tasks
    def task(self, e: XElem) -> None:
        name = self.name_of(e, "task")
        if name is None:
            return
        kind = (e.get("Type") or "CONTINUOUS").upper()
        try:
            rate = float(e.get("Rate") or 10.0)
            priority = int(e.get("Priority") or 10)
        except ValueError:
            self.err(
                "S007", f"task '{name}' has a Rate or Priority that is not a number", self.span(e)
            )
            return
        if kind == "PERIODIC" and rate <= 0:
            self.err("S007", f"periodic task '{name}' needs a Rate > 0 ms", self.span(e))
            return
        progs: list[tuple[str, n.Span]] = []
        for sec in e.all("ScheduledPrograms"):
            for sp in sec.all("ScheduledProgram"):
                pname = self.name_of(sp, "scheduled program")
                if pname is not None:
                    progs.append((pname, self.span(sp)))
        inhibited = e.get("InhibitTask").lower() == "true"
        self.project.tasks.append(
            TaskDecl(name, kind, rate, priority, progs, inhibited, self.span(e))
        )


def _walk(e: XElem):  # type: ignore[no-untyped-def]
    for c in e.children:
        yield c
        yield from _walk(c)


def _remap(x: object, fn) -> object:  # type: ignore[no-untyped-def]
    """Replace every Span inside an AST (in place where the containers allow it)."""
    if isinstance(x, n.Span):
        return fn(x)
    if isinstance(x, list):
        for i, item in enumerate(x):
            x[i] = _remap(item, fn)
        return x
    if isinstance(x, tuple):
        return tuple(_remap(item, fn) for item in x)
    if is_dataclass(x) and not isinstance(x, type):
        for f in fields(x):
            v = getattr(x, f.name)
            if isinstance(v, n.Span | list | tuple) or is_dataclass(v):
                setattr(x, f.name, _remap(v, fn))
    return x
