"""Logix data types: elementary types, structures (predefined, catalog, UDT) and arrays."""

from __future__ import annotations

from dataclasses import dataclass, field
from enum import Enum

from stdlib import catalog


class Kind(Enum):
    BOOL = "bool"
    INT = "int"
    REAL = "real"
    STRUCT = "struct"
    ARRAY = "array"


@dataclass(frozen=True, slots=True)
class Elementary:
    name: str
    kind: Kind
    bits: int
    signed: bool
    rank: int

    @property
    def is_integer(self) -> bool:
        return self.kind is Kind.INT

    @property
    def is_real(self) -> bool:
        return self.kind is Kind.REAL

    @property
    def is_bool(self) -> bool:
        return self.kind is Kind.BOOL

    @property
    def is_numeric(self) -> bool:
        return self.kind is not Kind.STRUCT

    def __str__(self) -> str:
        return self.name


BOOL = Elementary("BOOL", Kind.BOOL, 1, False, 0)
SINT = Elementary("SINT", Kind.INT, 8, True, 1)
USINT = Elementary("USINT", Kind.INT, 8, False, 2)
INT = Elementary("INT", Kind.INT, 16, True, 3)
UINT = Elementary("UINT", Kind.INT, 16, False, 4)
DINT = Elementary("DINT", Kind.INT, 32, True, 5)
UDINT = Elementary("UDINT", Kind.INT, 32, False, 6)
LINT = Elementary("LINT", Kind.INT, 64, True, 7)
ULINT = Elementary("ULINT", Kind.INT, 64, False, 8)
REAL = Elementary("REAL", Kind.REAL, 32, True, 9)
LREAL = Elementary("LREAL", Kind.REAL, 64, True, 10)

ELEMENTARY: dict[str, Elementary] = {
    t.name: t for t in (BOOL, SINT, USINT, INT, UINT, DINT, UDINT, LINT, ULINT, REAL, LREAL)
}


@dataclass(eq=False, slots=True)
class StructType:
    name: str
    members: list[tuple[str, DataType]] = field(default_factory=list)
    index: dict[str, int] = field(default_factory=dict)  # upper-case member name -> position
    hidden: set[str] = field(default_factory=set)
    readonly: set[str] = field(default_factory=set)
    defaults: dict[str, object] = field(default_factory=dict)
    docs: dict[str, str] = field(default_factory=dict)
    doc: str = ""
    builtin: bool = True
    group: str = ""
    # a declared type this tool could not resolve (reported once where declared): uses of a
    # tag of it accept any member, index, bit and operand, so nothing cascades (decision 0054)
    unknown: bool = False

    @property
    def kind(self) -> Kind:
        return Kind.STRUCT

    @property
    def is_string(self) -> bool:
        return self.name == "STRING" or (
            [m for m, _ in self.members] == ["LEN", "DATA"]
            and isinstance(self.members[1][1], ArrayType)
            and self.members[1][1].elem is SINT
        )

    def member(self, name: str) -> tuple[int, DataType] | None:
        i = self.index.get(name.upper())
        if i is None:
            return None
        return i, self.members[i][1]

    def member_name(self, name: str) -> str:
        return self.members[self.index[name.upper()]][0]

    def __str__(self) -> str:
        return self.name


@dataclass(frozen=True, slots=True)
class ArrayType:
    elem: DataType
    dims: tuple[int, ...]  # sizes, outermost first

    @property
    def kind(self) -> Kind:
        return Kind.ARRAY

    @property
    def size(self) -> int:
        n = 1
        for d in self.dims:
            n *= d
        return n

    def __str__(self) -> str:
        return f"{self.elem}[{','.join(str(d) for d in self.dims)}]"


DataType = Elementary | StructType | ArrayType


def unknown_type(name: str) -> StructType:
    """The stand-in for a declared type that could not be resolved (see StructType.unknown)."""
    return StructType(name, builtin=False, unknown=True)


def is_unknown(t: DataType | None) -> bool:
    return isinstance(t, StructType) and t.unknown


def is_axis(t: DataType) -> bool:
    return isinstance(t, StructType) and t.name.startswith("AXIS_")


def promote(a: Elementary, b: Elementary) -> Elementary:
    """Operation type of a binary arithmetic operation (SPEC 3.3 rank order)."""
    if a is BOOL and b is BOOL:
        return BOOL
    a = DINT if a is BOOL else a
    b = DINT if b is BOOL else b
    return a if a.rank >= b.rank else b


class TypeTable:
    """All data types visible to one program: elementary, catalog structures, UDTs."""

    def __init__(self) -> None:
        self._types: dict[str, DataType] = dict(ELEMENTARY)
        self._pending: dict[str, object] = {}
        cat = catalog()
        for name in cat.types:
            self._pending[name] = cat.types[name]

    def get(self, name: str) -> DataType | None:
        key = name.upper()
        if (
            key == "AXIS"
        ):  # axis references in catalog members (COORDINATE_SYSTEM.Axes, MC_CamIn.Master)
            key = "AXIS_CIP_DRIVE"
        t = self._types.get(key)
        if t is not None:
            return t
        td = self._pending.get(key)
        if td is None:
            return None
        return self._build_catalog(key, td)

    def _build_catalog(self, key: str, td: object) -> StructType:
        from stdlib import TypeDef

        assert isinstance(td, TypeDef)
        st = StructType(td.name, doc=td.doc, builtin=True, group=td.group)
        self._types[key] = st
        self._types[td.name] = st
        for m in td.members:
            mt = self.parse_type_text(m.type)
            if mt is None:
                raise ValueError(f"catalog type {td.name}.{m.name}: unknown type {m.type}")
            self._add_member(st, m.name, mt)
            if m.hidden:
                st.hidden.add(m.name.upper())
            if m.readonly:
                st.readonly.add(m.name.upper())
            if m.default is not None:
                st.defaults[m.name.upper()] = m.default
            st.docs[m.name.upper()] = m.doc
        return st

    @staticmethod
    def _add_member(st: StructType, name: str, mt: DataType) -> None:
        st.index[name.upper()] = len(st.members)
        st.members.append((name, mt))

    def parse_type_text(self, text: str) -> DataType | None:
        """`SINT[82]` or `REAL` as written in catalog data."""
        text = text.strip().upper()
        if text.endswith("]") and "[" in text:
            base, dims = text[:-1].split("[", 1)
            bt = self.get(base)
            if bt is None:
                return None
            return ArrayType(bt, tuple(int(d) for d in dims.split(",")))
        return self.get(text)

    def declare_udt(self, name: str) -> StructType:
        st = StructType(name, builtin=False)
        self._types[name.upper()] = st
        return st

    def declare_unknown(self, name: str) -> StructType:
        """Record a type reported as missing, so later references to it are not reported again."""
        st = unknown_type(name)
        self._types[name.upper()] = st
        return st

    def add_member(self, st: StructType, name: str, mt: DataType) -> None:
        self._add_member(st, name, mt)

    def is_known(self, name: str) -> bool:
        return self.get(name) is not None

    def names(self) -> list[str]:
        return sorted(set(self._types) | set(self._pending))

    def user_types(self) -> list[StructType]:
        """The UDTs (and add-on instruction types) declared so far, in declaration order."""
        return [t for t in self._types.values() if isinstance(t, StructType) and not t.builtin]
