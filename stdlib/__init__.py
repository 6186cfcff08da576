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
    {"tag", "immediate", "value", "array", "memory", "routine", "label", "task"}
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


@dataclass(slots=True)
class Catalog:
    instructions: list[Instruction] = field(default_factory=list)
    enums: dict[str, Enumeration] = field(default_factory=dict)
    types: dict[str, TypeDef] = field(default_factory=dict)
    motion_errors: dict[int, MotionError] = field(default_factory=dict)
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
    )


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
    for ins in cat.instructions:
        for op in ins.operands:
            if op.enum is not None and op.enum not in cat.enums:
                raise CatalogError(f"{ins.name}.{op.name}: unknown enum {op.enum}")
    return cat
