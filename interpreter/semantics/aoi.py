"""Add-On Instructions: the instance data type, the call signature and the Logic routine's scope.

Lowering (docs/decisions/0042-aoi-lowering.md): the Logic routine is checked and compiled
once per definition against a *frame*: frame[0] is the instance (a structure value whose
members are EnableIn, EnableOut, the Input/Output parameters and the local tags), frame[1..]
the InOut arguments of the current call (structures and arrays by object, elementary ones
through a reference cell). A parameter or local tag is therefore a Tag with slot 0 and an
access path (member index); an InOut is slot j. A call is an ordinary catalog-style
instruction whose implementation builds the frame and runs the compiled routine.

State the ladder compiler keeps between scans (the rung each transitional instruction saw
last) lives in hidden BOOL members of the instance, one per call site, so every instance
has its own, as every Logix instance has its own backing tag (docs/decisions/0024).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from stdlib import Instruction, Operand, catalog

from ..diagnostics import Diagnostic, diag
from ..syntax import nodes as n
from ..syntax.l5x import AliasDecl, AoiDecl
from .alias import AliasRequest, resolve_aliases
from .ladder_check import rung_instructions
from .program import Tag, const_number, resolve_typeref
from .types import BOOL, ArrayType, DataType, Elementary, StructType, TypeTable, is_unknown

SCAN_ROUTINES = ("LOGIC", "PRESCAN", "ENABLEINFALSE", "POSTSCAN")
COMPILED_ROUTINES = ("LOGIC", "ENABLEINFALSE")  # the scan modes the controller runs
# Consecutive underscores are not allowed in a Logix tag name: no local tag can clash.
EDGE_MEMBER = "__Edge{}"


@dataclass(slots=True)
class AoiParam:
    name: str
    usage: str  # Input | Output | InOut
    type: DataType
    member: int  # index in the instance structure (-1 for InOut)
    frame: int  # frame slot for InOut (0 otherwise)


@dataclass(slots=True)
class Aoi:
    name: str
    type: StructType
    path: str
    instruction: Instruction | None = None
    tags: dict[str, Tag] = field(default_factory=dict)  # upper name -> frame-bound tag
    required: list[AoiParam] = field(default_factory=list)  # call operands after the instance
    routines: dict[str, n.Routine] = field(default_factory=dict)  # LOGIC, PRESCAN, ...
    edges: dict[int, int] = field(default_factory=dict)  # id(ladder instruction) -> hidden member
    # alias parameters of a member or bit of a local tag, seen from outside: (instance
    # member, the local place's access path, bit); runtime/aoi.py keeps the two in step
    mirrors: list[tuple[int, tuple[int, ...], tuple[int, Elementary] | None]] = field(
        default_factory=list
    )


def define_aoi(
    types: TypeTable,
    decl: AoiDecl,
    st: StructType,
    path: str,
    diags: list[Diagnostic],
    aoi_names: frozenset[str] = frozenset(),
) -> Aoi:
    """Fill the (already declared) instance type `st` and build the call signature.

    `aoi_names` (upper case) are the project's add-on instructions: a call of one of them is
    never a catalog instruction, even when the names are the same.
    """
    aoi = _define(types, decl, st, path, diags)
    _edge_members(types, aoi, aoi_names)
    return aoi


def _edge_members(types: TypeTable, aoi: Aoi, aoi_names: frozenset[str]) -> None:
    """One hidden BOOL member per transitional ladder instruction of the compiled routines."""
    cat = catalog()
    for name in COMPILED_ROUTINES:
        r = aoi.routines.get(name)
        if r is None or r.language != "rll":
            continue
        for rung in r.rungs:
            for ins in rung_instructions(rung.elements):
                entry = None if ins.name.upper() in aoi_names else cat.instruction(ins.name, "rll")
                if entry is not None and entry.transitional:
                    aoi.edges[id(ins)] = len(aoi.type.members)
                    key = EDGE_MEMBER.format(len(aoi.edges) - 1)
                    types.add_member(aoi.type, key, BOOL)
                    aoi.type.hidden.add(key.upper())


def _define(
    types: TypeTable, decl: AoiDecl, st: StructType, path: str, diags: list[Diagnostic]
) -> Aoi:
    aoi = Aoi(decl.name, st, path)
    frame = 1
    operands = [Operand("Instance", (st.name,), "tag", "inout", doc=f"{decl.name} instance tag")]
    for p in decl.params:
        t = resolve_typeref(types, p.decl.type, path, diags)
        sp = p.decl.names[0][1]
        key = p.name.upper()
        if key in aoi.tags:
            diags.append(diag("E117", f"parameter '{p.name}' is declared twice", path, sp))
            continue
        if p.usage == "InOut":
            access = () if isinstance(t, StructType | ArrayType) else (0,)
            aoi.tags[key] = Tag(p.name, t, sp, path, slot=frame, access=access)
            param = AoiParam(p.name, "InOut", t, -1, frame)
            frame += 1
        else:
            idx = len(st.members)
            types.add_member(st, p.name, t)
            value = const_number(p.decl.init) if p.decl.init is not None else None
            if value is not None:
                st.defaults[key] = value
            aoi.tags[key] = Tag(
                p.name, t, sp, path, p.decl.init, slot=0, access=(idx,), init_path=path
            )
            param = AoiParam(p.name, p.usage, t, idx, 0)
        if p.required and key not in ("ENABLEIN", "ENABLEOUT"):
            aoi.required.append(param)
            operands.append(_operand(param))
    for d in decl.locals:
        t = resolve_typeref(types, d.type, path, diags)
        for lname, sp in d.names:
            key = lname.upper()
            if key in aoi.tags:
                diags.append(diag("E117", f"local tag '{lname}' is already declared", path, sp))
                continue
            idx = len(st.members)
            types.add_member(st, lname, t)
            st.hidden.add(key)  # local tags are not reachable through the instance from outside
            value = const_number(d.init) if d.init is not None else None
            if value is not None:
                st.defaults[key] = value
            aoi.tags[key] = Tag(lname, t, sp, path, d.init, slot=0, access=(idx,), init_path=path)
    _alias_params(types, aoi, decl, path, diags, operands)
    for r in decl.routines:
        aoi.routines[r.name.upper()] = r
    if "LOGIC" not in aoi.routines and decl.routines:
        diags.append(
            diag("E124", f"add-on instruction '{decl.name}' has no Logic routine", path, decl.span)
        )
    aoi.instruction = Instruction(
        name=decl.name.upper(),
        aliases=(),
        languages=frozenset({"st", "rll"}),
        kind="instruction",
        transitional=False,
        doc=f"Add-On Instruction {decl.name}",
        operands=tuple(operands),
        family="aoi",
    )
    return aoi


def _alias_params(
    types: TypeTable,
    aoi: Aoi,
    decl: AoiDecl,
    path: str,
    diags: list[Diagnostic],
    operands: list[Operand],
) -> None:
    """Alias parameters name a local tag, one of its members or bits (semantics/alias.py).

    Inside the logic the alias reaches the local tag's storage. From outside, an alias of a
    whole local tag is that member of the instance (`Tank.Level` reads the local tag `Acc`).
    An alias of a member or a bit (`Sts_Running` for `_bSts.0`) gets an instance member of
    its own that the call copies into the local place before the logic and back after it,
    so between calls the outside sees and sets what the logic sees (runtime/aoi.py).
    """
    requests: dict[str, AliasRequest] = {}
    by_name: dict[str, AliasDecl] = {}
    for a in decl.aliases:
        key = a.name.upper()
        if key in aoi.tags or key in requests:
            diags.append(diag("E117", f"parameter '{a.name}' is already declared", path, a.span))
            continue
        requests[key] = AliasRequest(a.name, a.target, a.span)
        by_name[key] = a

    def lookup(ident: str, program: str | None) -> Tag | AliasRequest | None:
        return aoi.tags.get(ident.upper()) or requests.get(ident.upper())

    resolved = resolve_aliases(list(requests.values()), lookup, path, diags)
    for key, req in requests.items():
        tag = resolved.get(id(req))
        if tag is None:
            continue
        aoi.tags[key] = tag
        if key in aoi.type.index:
            continue
        if len(tag.access) == 1 and tag.bit is None:
            member = aoi.type.index[key] = tag.access[0]  # the local tag's member position
        else:
            member = len(aoi.type.members)
            aoi.mirrors.append((member, tag.access, tag.bit))
            types.add_member(aoi.type, req.name, tag.type)
            host = aoi.type.defaults.get(aoi.type.members[tag.access[0]][0].upper())
            if tag.bit is not None and len(tag.access) == 1 and isinstance(host, int):
                aoi.type.defaults[key] = (host >> tag.bit[0]) & 1  # the local's default bit
        alias = by_name[key]
        if alias.required and alias.usage in ("Input", "Output"):
            param = AoiParam(req.name, alias.usage, tag.type, member, 0)
            aoi.required.append(param)
            operands.append(_operand(param))
    if any(by_name[k].required for k in requests):
        # call operands follow the declared order of the parameters, aliases among them
        order = {name.upper(): i for i, name in enumerate(decl.param_order)}
        aoi.required.sort(key=lambda p: order.get(p.name.upper(), len(order)))
        operands[1:] = sorted(operands[1:], key=lambda o: order.get(o.name.upper(), len(order)))


def _operand(p: AoiParam) -> Operand:
    t = p.type
    if is_unknown(t):  # reported where declared (E119/U306): any argument goes
        types: tuple[str, ...] = ("ANY",)
    elif isinstance(t, Elementary) and p.usage != "InOut":
        # Input/Output arguments of another elementary type are converted, as Logix does.
        types = ("ANY_ELEMENTARY",)
    else:
        types = ((t.elem if isinstance(t, ArrayType) else t).name,)  # type: ignore[union-attr]
    if p.usage == "Input":
        return Operand(p.name, types, "value", "in")
    return Operand(p.name, types, "tag", "out" if p.usage == "Output" else "inout")


def same_shape(arg: DataType, param: DataType) -> bool:
    """An InOut argument must have the parameter's type (arrays: element type and dimensions)."""
    if is_unknown(param):
        return True  # the parameter's type is reported where declared
    if isinstance(param, ArrayType):
        return (
            isinstance(arg, ArrayType)
            and arg.elem is param.elem
            and len(arg.dims) == len(param.dims)
        )
    return arg is param or (
        isinstance(arg, Elementary) and isinstance(param, Elementary) and arg.name == param.name
    )
