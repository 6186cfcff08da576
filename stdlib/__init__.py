"""The instruction and data-type catalog: TOML data files plus this small loader.

Everything that knows an instruction's operands, an enumeration's texts or a predefined
structure's members reads it from here (see docs/decisions/0001-catalog-schema.md).
"""

from __future__ import annotations

import tomllib
from dataclasses import dataclass, field
from functools import cache
from pathlib import Path

_ROOT = Path(__file__).parent

OPERAND_FORMATS = frozenset(
    {"tag", "immediate", "value", "array", "memory", "routine", "label", "task", "object"}
)
OPERAND_DIRS = frozenset({"in", "out", "inout"})


def enum_key(text: str) -> str:
    """Normalise enumeration text: no spaces or hyphens, lower case (`S-Curve` -> `scurve`)."""
    return "".join(ch for ch in text.lower() if ch not in " -_\t")


@dataclass(frozen=True, slots=True)
class EnumValue:
    text: str
    value: int
    doc: str = ""

    @property
    def label(self) -> str:
        """Completion label: the documented text in lower case, written as ST accepts it."""
        return self.text.lower().replace(" ", "")


@dataclass(frozen=True, slots=True)
class Enumeration:
    name: str
    values: tuple[EnumValue, ...]
    counts: bool = False  # any positive number is accepted too (FAL/FSC Mode: elements per scan)

    def lookup(self, text: str) -> EnumValue | None:
        key = enum_key(text)
        for v in self.values:
            if enum_key(v.text) == key:
                return v
        return None

    def by_value(self, value: int) -> EnumValue | None:
        for v in self.values:
            if v.value == value:
                return v
        return None


@dataclass(frozen=True, slots=True)
class Operand:
    name: str
    types: tuple[str, ...]
    format: str
    dir: str
    enum: str | None = None
    optional: bool = False
    doc: str = ""
    nullable: bool = False  # a literal 0 means "not used" (the implementation gets None)
    placeholder: bool = False  # ladder may write `?` or leave it empty: the value lives in the tag
    expression: bool = False  # takes an expression (CMP, CPT, FAL, FSC), not just a tag or literal


@dataclass(frozen=True, slots=True)
class UnconnectedCase:
    """Further members set on while an enumerated operand has one value (ROUT Negative)."""

    operand: str
    value: str
    on: tuple[str, ...]


@dataclass(frozen=True, slots=True)
class Unconnected:
    """What a safety instruction shows on a controller whose safety I/O is not connected
    (decision 0078): members of its instance tag held off and members set on."""

    off: tuple[str, ...]
    on: tuple[str, ...]
    cases: tuple[UnconnectedCase, ...] = ()


@dataclass(frozen=True, slots=True)
class Instruction:
    name: str
    aliases: tuple[str, ...]
    languages: frozenset[str]
    kind: str
    transitional: bool
    doc: str
    operands: tuple[Operand, ...]
    family: str
    variadic: bool = False
    input: bool = False  # ladder input instruction: it can make the rung condition false
    # Why the simulator does not execute it (U304 names this reason); "" when it runs.
    unsupported: str = ""
    # A rule of this instruction beyond its operand table: the name of a check in
    # semantics/checker.py INSTRUCTION_CHECKS ("" for none); completion and hover read the
    # same entry, so no tool has its own `if name == ...`.
    check: str = ""
    # kind = "function": the result type when it is not the argument's (REAL, BOOL).
    result: str = ""
    # A safety instruction shown as with its safety I/O not connected (decision 0078): the
    # members of its instance tag held off and set on; None for every other instruction.
    unconnected: Unconnected | None = None

    @property
    def key(self) -> str:
        """Unique id: name plus language set (ladder SQR and ST SQRT are different entries)."""
        return f"{self.name}@{'+'.join(sorted(self.languages))}"


@dataclass(frozen=True, slots=True)
class Member:
    name: str
    type: str
    doc: str = ""
    bit: int | None = None
    hidden: bool = False
    readonly: bool = False
    default: object = None


@dataclass(frozen=True, slots=True)
class TypeDef:
    name: str
    aliases: tuple[str, ...]
    doc: str
    members: tuple[Member, ...]
    group: str


@dataclass(frozen=True, slots=True)
class MotionError:
    code: int
    name: str
    doc: str = ""


_ELEMENTARY = frozenset(
    {"BOOL", "SINT", "INT", "DINT", "LINT", "USINT", "UINT", "UDINT", "ULINT", "REAL", "LREAL"}
)
SYSTEM_ACCESS = frozenset({"get", "set"})
SYSTEM_INSTANCES = frozenset({"none", "name", "tag"})


@dataclass(frozen=True, slots=True)
class SystemAttribute:
    """One GSV/SSV attribute of a controller object class (stdlib/system_objects.toml)."""

    name: str
    type: str
    access: frozenset[str]  # "get" and/or "set": what the controller allows
    simulated: frozenset[str]  # the part of access logixst executes
    doc: str = ""
    member: str = ""  # the value lives in this member of the instance tag ("" if not a tag)


@dataclass(frozen=True, slots=True)
class SystemClass:
    name: str
    instance: str  # "none", "name" or "tag": what InstanceName names
    doc: str
    attributes: tuple[SystemAttribute, ...]
    members_of: str = ""  # data type whose members are attributes (motion object classes)

    def attribute(self, name: str) -> SystemAttribute | None:
        key = name.upper()
        for a in self.attributes:
            if a.name.upper() == key:
                return a
        return None


@dataclass(slots=True)
class Catalog:
    instructions: list[Instruction] = field(default_factory=list)
    enums: dict[str, Enumeration] = field(default_factory=dict)
    types: dict[str, TypeDef] = field(default_factory=dict)
    motion_errors: dict[int, MotionError] = field(default_factory=dict)
    system_classes: dict[str, SystemClass] = field(default_factory=dict)  # by upper-case name
    _by_name: dict[tuple[str, str], Instruction] = field(default_factory=dict)

    def instruction(self, name: str, language: str) -> Instruction | None:
        """The instruction called `name` (or an alias) in `language` ('st' or 'rll')."""
        return self._by_name.get((name.upper(), language))

    def instruction_any(self, name: str) -> Instruction | None:
        return self.instruction(name, "st") or self.instruction(name, "rll")

    def type(self, name: str) -> TypeDef | None:
        return self.types.get(name.upper())

    def enum(self, name: str) -> Enumeration:
        return self.enums[name]

    def system_attribute(self, class_name: str, attribute: str) -> SystemAttribute | None:
        """The GSV/SSV attribute `attribute` of object class `class_name` (any case)."""
        cls = self.system_classes.get(class_name.upper())
        return cls.attribute(attribute) if cls is not None else None


class CatalogError(Exception):
    """A catalog data file is malformed (a bug in the shipped data, not user input)."""


def _instruction(raw: dict, family: str, where: str) -> Instruction:
    ops = []
    for o in raw.get("operands", []):
        fmt = o.get("format", "value")
        direction = o.get("dir", "in")
        if fmt not in OPERAND_FORMATS or direction not in OPERAND_DIRS:
            raise CatalogError(f"{where}: {raw.get('name')}.{o.get('name')}: bad format/dir")
        ops.append(
            Operand(
                name=o["name"],
                types=tuple(t.upper() for t in o.get("types", ["ANY"])),
                format=fmt,
                dir=direction,
                enum=o.get("enum"),
                optional=bool(o.get("optional", False)),
                doc=o.get("doc", ""),
                nullable=bool(o.get("nullable", False)),
                placeholder=bool(o.get("placeholder", False)),
                expression=bool(o.get("expression", False)),
            )
        )
    return Instruction(
        name=raw["name"].upper(),
        aliases=tuple(a.upper() for a in raw.get("aliases", [])),
        languages=frozenset(raw.get("languages", ["st", "rll"])),
        kind=raw.get("kind", "instruction"),
        transitional=bool(raw.get("transitional", False)),
        doc=raw.get("doc", ""),
        operands=tuple(ops),
        family=family,
        variadic=bool(raw.get("variadic", False)),
        input=bool(raw.get("input", False)),
        unsupported=str(raw.get("unsupported", "")),
        check=str(raw.get("check", "")),
        result=str(raw.get("result", "")).upper(),
        unconnected=_unconnected(raw.get("unconnected")),
    )


def _names(raw: dict, key: str) -> tuple[str, ...]:
    return tuple(str(n) for n in raw.get(key, []))


def _unconnected(raw: dict | None) -> Unconnected | None:
    if raw is None:
        return None
    cases = tuple(
        UnconnectedCase(str(c["operand"]), str(c["is"]), _names(c, "on"))
        for c in raw.get("cases", [])
    )
    return Unconnected(_names(raw, "off"), _names(raw, "on"), cases)


def _load_file(path: Path) -> dict:
    try:
        with path.open("rb") as fh:
            return tomllib.load(fh)
    except tomllib.TOMLDecodeError as exc:
        raise CatalogError(f"{path.name}: {exc}") from exc


@cache
def catalog() -> Catalog:
    """Load and validate the whole catalog once."""
    cat = Catalog()
    for path in sorted((_ROOT / "instructions").glob("*.toml")):
        data = _load_file(path)
        for e in data.get("enum", []):
            values = tuple(
                EnumValue(str(v["text"]), int(v["value"]), v.get("doc", "")) for v in e["values"]
            )
            if e["name"] in cat.enums:  # facts once: a second definition would silently win
                raise CatalogError(f"{path.name}: enumeration {e['name']} defined twice")
            cat.enums[e["name"]] = Enumeration(e["name"], values, bool(e.get("counts", False)))
        for raw in data.get("instruction", []):
            ins = _instruction(raw, path.stem, path.name)
            cat.instructions.append(ins)
            for lang in ins.languages:
                for name in (ins.name, *ins.aliases):
                    if (name, lang) in cat._by_name:
                        raise CatalogError(f"{path.name}: {name} defined twice for {lang}")
                    cat._by_name[(name, lang)] = ins
    for path in sorted((_ROOT / "types").glob("*.toml")):
        for raw in _load_file(path).get("type", []):
            members = tuple(
                Member(
                    name=m["name"],
                    type=m["type"].upper(),
                    doc=m.get("doc", ""),
                    bit=m.get("bit"),
                    hidden=bool(m.get("hidden", False)),
                    readonly=bool(m.get("readonly", False)),
                    default=m.get("default"),
                )
                for m in raw.get("members", [])
            )
            td = TypeDef(
                raw["name"].upper(),
                tuple(a.upper() for a in raw.get("aliases", [])),
                raw.get("doc", ""),
                members,
                path.stem,
            )
            for name in (td.name, *td.aliases):
                cat.types[name] = td
    errors = _ROOT / "motion_errors.toml"
    if errors.exists():
        for raw in _load_file(errors).get("error", []):
            cat.motion_errors[int(raw["code"])] = MotionError(
                int(raw["code"]), raw["name"], raw.get("doc", "")
            )
    _load_system_objects(cat)
    for ins in cat.instructions:
        for op in ins.operands:
            if op.enum is not None and op.enum not in cat.enums:
                raise CatalogError(f"{ins.name}.{op.name}: unknown enum {op.enum}")
        if ins.unconnected is not None:
            _check_unconnected(cat, ins)
    return cat


def _check_unconnected(cat: Catalog, ins: Instruction) -> None:
    """Every member an `unconnected` entry names is a BOOL of the instance type, and every
    case names an enumerated operand and one of its texts."""
    u = ins.unconnected
    assert u is not None
    td = cat.types.get(ins.operands[0].types[0]) if ins.operands else None
    bools = {m.name for m in td.members if m.type == "BOOL"} if td is not None else set()
    names = [*u.off, *u.on, *(n for c in u.cases for n in c.on)]
    for n in names:
        if n not in bools:
            raise CatalogError(f"{ins.name}: unconnected names {n}, not a BOOL of its tag")
    ops = {o.name: o for o in ins.operands}
    for c in u.cases:
        op = ops.get(c.operand)
        if op is None or op.enum is None or cat.enums[op.enum].lookup(c.value) is None:
            raise CatalogError(f"{ins.name}: unconnected case {c.operand} = {c.value}")


def _access(text: str, where: str) -> frozenset[str]:
    words = frozenset(text.split())
    if not words <= SYSTEM_ACCESS:
        raise CatalogError(f"system_objects.toml: {where}: access must be 'get' and/or 'set'")
    return words


def _load_system_objects(cat: Catalog) -> None:
    """GSV/SSV object classes and attributes, and the ClassName/AttributeName enumerations
    built from them (numbered in file order; the numbers are private to logixst)."""
    classes: list[EnumValue] = []
    attributes: dict[str, EnumValue] = {}
    for raw in _load_file(_ROOT / "system_objects.toml").get("class", []):
        name = str(raw["name"])
        if raw.get("instance") not in SYSTEM_INSTANCES:
            raise CatalogError(f"system_objects.toml: {name}: bad instance kind")
        attrs: list[SystemAttribute] = []
        members_of = str(raw.get("members_of", "")).upper()
        td = cat.types.get(members_of) if members_of else None
        if members_of and td is None:
            raise CatalogError(f"system_objects.toml: {name}: unknown type {members_of}")
        member_names = {m.name.upper() for m in td.members} if td is not None else set()
        for a in raw.get("attributes", []):
            where = f"{name}.{a['name']}"
            member = str(a.get("member", ""))
            if not member and a["name"].upper() in member_names:
                continue  # the tag has this member now: the member entry below describes it
            if member and member.upper() not in member_names:
                raise CatalogError(f"system_objects.toml: {where}: no member {member}")
            access = _access(str(a["access"]), where)
            simulated = _access(str(a.get("simulated", "")), where)
            if not simulated <= access:
                raise CatalogError(f"system_objects.toml: {where}: simulates what it cannot access")
            attrs.append(
                SystemAttribute(
                    a["name"], str(a["type"]).upper(), access, simulated, a.get("doc", ""), member
                )
            )
        listed = {a.name.upper() for a in attrs}
        for m in td.members if td is not None else ():
            base, _, dims = m.type.partition("[")
            if m.hidden or base not in _ELEMENTARY or m.name.upper() in listed:
                continue  # internal data, strings and axis references are not attributes
            access = frozenset({"get"} if m.readonly or dims else {"get", "set"})
            attrs.append(SystemAttribute(m.name, m.type, access, access, m.doc, m.name))
        cls = SystemClass(
            name,
            str(raw["instance"]),
            raw.get("doc", ""),
            tuple(attrs),
            str(members_of or "").upper(),
        )
        cat.system_classes[name.upper()] = cls
        classes.append(EnumValue(name, len(classes) + 1, cls.doc))
        for a in cls.attributes:
            if a.name.upper() not in attributes:
                attributes[a.name.upper()] = EnumValue(
                    a.name, len(attributes) + 1, f"{name}: {a.doc}"
                )
    for built in ("GSV_ClassName", "GSV_AttributeName"):
        if built in cat.enums:
            raise CatalogError(f"enumeration {built} is built from system_objects.toml")
    cat.enums["GSV_ClassName"] = Enumeration("GSV_ClassName", tuple(classes))
    cat.enums["GSV_AttributeName"] = Enumeration("GSV_AttributeName", tuple(attributes.values()))
