"""Tag data of an L5X export turned into initialiser AST (the same nodes `.st` VAR blocks use).

Decorated data (`DataValue`, `Structure`, `Array`, `Element`, `DataValueMember`,
`StructureMember`, `ArrayMember`) maps one to one onto Literal / StructInit / ArrayInit;
`<Data Format="String">` becomes a STRING literal, `<Data Format="Alarm">` parameters a
structure initialiser; L5K text (`[1,2,[3,4]]`) is the fallback
for exports without decorated data. Spans point at the data's place in the .L5X file.
"""

from __future__ import annotations

import calendar
import math
import re
from dataclasses import dataclass
from datetime import datetime

from . import nodes as n
from .literals import parse_number, parse_string
from .xml_reader import Positions, XElem

ELEMENTARY = {
    "BOOL",
    "SINT",
    "INT",
    "DINT",
    "LINT",
    "USINT",
    "UINT",
    "UDINT",
    "ULINT",
    "REAL",
    "LREAL",
    "TIME32",
    "TIME",
    "LTIME",
    "DT",
    "LDT",
}
# Types whose values do not fit a DINT literal
_WIDE = frozenset(("LINT", "ULINT", "UDINT", "TIME", "LTIME", "DT", "LDT"))
_UNSIGNED = frozenset(("USINT", "UINT", "UDINT", "ULINT"))


@dataclass(slots=True)
class RawMember:
    """A UDT member as exported, hidden SINT bit hosts included (for L5K data layout)."""

    name: str
    type: str
    dims: int
    hidden: bool
    target: str = ""
    bit: int = 0


# `DT#2022-02-22-06:00:00.000_000Z` (Radix Date/Time, microseconds) and
# `LDT#1970-01-01-00:00:00.000_000_000Z` (Radix Date/Time (ns), nanoseconds): a LINT shown
# as a UTC date and time. The fraction may be shorter; a `(UTC+hh:mm)` offset replaces the Z.
_DATE_TIME = re.compile(
    r"(L?)DT#(\d{4})-(\d{1,2})-(\d{1,2})-(\d{1,2}):(\d{1,2}):(\d{1,2})(?:\.([\d_]*))?"
    r"\s*(?:Z|\(UTC([+-])(\d{1,2}):(\d{2})\))?",
    re.IGNORECASE,
)


def parse_date_time(text: str) -> int | None:
    """The LINT a `DT#` / `LDT#` value stands for: time since 1970-01-01 00:00 UTC, in
    microseconds for DT# and nanoseconds for LDT# (decision 0045); None if malformed."""
    m = _DATE_TIME.fullmatch(text.strip())
    if m is None:
        return None
    ns, year, month, day, hour, minute, sec, frac, sign, oh, om = m.groups()
    try:
        when = datetime(int(year), int(month), int(day), int(hour), int(minute), int(sec))
    except ValueError:
        return None
    seconds = calendar.timegm(when.timetuple())
    if sign:  # local time at that offset from UTC
        offset = (int(oh) * 60 + int(om)) * 60
        seconds -= offset if sign == "+" else -offset
    digits = 9 if ns else 6
    frac = (frac or "").replace("_", "")
    if len(frac) > digits:
        return None
    return seconds * 10**digits + int(frac.ljust(digits, "0") or "0")


# `T#-2h_3m_4s_1us` (TIME, Radix "Time (us)"), `T32#35m_47s_483ms_647us` (TIME32),
# `LT#10d_7h_35m_47s_621us_879ns` (LTIME, nanoseconds): a signed duration written as parts
# from days down to the type's unit, joined by `_` (decision 0072).
_DURATION = re.compile(
    r"(LT|T32|T)#([+-]?)(\d+(?:d|h|ms|m|s|us|ns)(?:_?\d+(?:d|h|ms|m|s|us|ns))*)", re.IGNORECASE
)
_PART = re.compile(r"(\d+)(d|h|ms|m|s|us|ns)", re.IGNORECASE)
_NS = {"d": 86_400 * 10**9, "h": 3_600 * 10**9, "m": 60 * 10**9, "s": 10**9}
_NS.update({"ms": 10**6, "us": 10**3, "ns": 1})


def parse_duration(text: str) -> int | None:
    """The count a `T#` / `T32#` (microseconds) or `LT#` (nanoseconds) value stands for; None
    if malformed or finer than the type's unit."""
    m = _DURATION.fullmatch(text.strip().replace(" ", ""))
    if m is None:
        return None
    prefix, sign, body = m.groups()
    ns = sum(int(k) * _NS[u.lower()] for k, u in _PART.findall(body))
    if prefix.upper() != "LT":
        if ns % 1000:
            return None  # nanoseconds in a microsecond type
        ns //= 1000
    return -ns if sign == "-" else ns


def parse_value(text: str, radix: str, dtype: str) -> int | float | None:
    """A decorated `Value` attribute in its `Radix` (Decimal, Hex, Binary, Octal, ASCII, Float,
    Date/Time...)."""
    t = text.strip()
    if not t:
        return None
    up = t.upper()
    if up.startswith(("DT#", "LDT#")):
        return parse_date_time(t)
    if up.startswith(("T#", "LT#", "T32#")):
        return parse_duration(t)
    if dtype in ("REAL", "LREAL") or radix in ("Float", "Exponential"):
        # v17-v20 exports print non-finite REALs the C runtime's way: `1.#QNAN`, `-1.#IND`
        # (NaN) and `1.$` (+INF, the raw bytes 16#7F80_0000 show it; decision 0045)
        if "INF" in up or up.endswith(".$"):
            return -math.inf if up.startswith("-") else math.inf
        if "NAN" in up or "#IND" in up:
            return math.nan
        try:
            return float(t)
        except ValueError:
            return None
    if radix == "ASCII" or (t.startswith("'") and t.endswith("'")):
        raw = parse_string(t if t.startswith("'") else f"'{t}'")
        return int.from_bytes(raw, "big", signed=False) if raw else 0
    neg = t.startswith("-")
    try:
        value, kind = parse_number(t[1:] if neg else t)
    except ValueError:
        return None
    if isinstance(value, float):
        return None
    if value < 0 and "#" in t and dtype in _UNSIGNED:
        # parse_number reads a radix pattern as signed at its own width (16#ffff_0000 is
        # -65536); an unsigned tag holds the pattern's unsigned value (a v35 UDINT mask)
        value %= 1 << (64 if kind in ("LINT", "ULINT") else 32)
    return -value if neg else value


class DataReader:
    """Decodes the `<Data>` children of tags and DefaultData of AOI parameters."""

    def __init__(self, pos: Positions, udts: dict[str, list[RawMember]]) -> None:
        self.pos = pos
        self.udts = udts

    def span(self, e: XElem) -> n.Span:
        return self.pos.elem_span(e)

    def literal(self, e: XElem, value: object, dtype: str, text: str) -> n.Literal:
        typ = (
            "REAL" if isinstance(value, float) else "STRING" if isinstance(value, bytes) else "DINT"
        )
        if dtype in _WIDE and isinstance(value, int):
            typ = "LINT"
        return n.Literal(value, typ, text, self.span(e))

    # ------------------------------------------------------------ entry
    def tag_init(self, tag: XElem, data_tag: str = "Data") -> n.Init | None:
        """Initial value of a tag (or AOI parameter, with data_tag="DefaultData")."""
        datas = tag.all(data_tag)
        by_format = {d.get("Format"): d for d in datas}
        deco = by_format.get("Decorated")
        if deco is not None and deco.children:
            return self.decorated(deco.children[0])
        string = by_format.get("String")
        if string is not None:
            dims = _dims(tag.get("Dimensions") or tag.get("Dimension"))
            if dims:
                return self.string_array(tag.get("DataType"), dims, string, by_format.get(""))
            return self.string_literal(string)
        alarm = by_format.get("Alarm")
        if alarm is not None and alarm.children:
            return self.parameters(alarm.children[0])
        l5k = by_format.get("L5K")
        if l5k is not None and l5k.text.strip():
            return self.l5k(
                l5k, tag.get("DataType"), _dims(tag.get("Dimensions") or tag.get("Dimension"))
            )
        return None

    def parameters(self, e: XElem) -> n.StructInit:
        """`<AlarmDigitalParameters Severity="500" Condition="true" .../>`: attributes named
        after members (true/false and numbers); the rest (DT# timestamps) keep defaults."""
        span = self.span(e)
        members: list[tuple[str, n.Span, n.Init]] = []
        for name, text in e.attrs.items():
            low = text.strip().lower()
            value: int | float | None = (
                (1 if low == "true" else 0)
                if low in ("true", "false")
                else _l5k_number(text.strip())
            )
            if value is not None:
                members.append(
                    (
                        name,
                        span,
                        n.Literal(
                            value, "REAL" if isinstance(value, float) else "DINT", text, span
                        ),
                    )
                )
        return n.StructInit(members, span)

    # ------------------------------------------------------------ decorated
    def decorated(self, e: XElem) -> n.Init | None:
        tag = e.tag
        if tag in ("DataValue", "DataValueMember"):
            dtype = e.get("DataType").upper()
            if (
                dtype == "STRING"
                or e.get("Radix") == "ASCII"
                and e.text_offset >= 0
                and not e.get("Value")
            ):
                return self.string_literal(e)
            text = e.get("Value")
            value = parse_value(text, e.get("Radix"), dtype)
            return None if value is None else self.literal(e, value, dtype, text)
        if tag in ("Structure", "StructureMember"):
            if e.get("DataType").upper() == "STRING" or _is_string_structure(e):
                data = next((c for c in e.children if c.get("Name").upper() == "DATA"), None)
                if data is not None:
                    return self.string_literal(data)
            members: list[tuple[str, n.Span, n.Init]] = []
            known = self._builtin_members(e.get("DataType"))
            for c in e.children:
                name = c.get("Name")
                if not name:
                    continue
                init = self.decorated(c)
                if init is None:
                    continue
                if known is not None and name.upper() not in known and _is_zero(init):
                    # a member Studio writes for a built-in type that logixst does not model
                    # (MOTION_INSTRUCTION's TrackingMaster, v33), at its default: nothing lost
                    continue
                members.append((name, self.span(c), init))
            return n.StructInit(members, self.span(e))
        if tag in ("Array", "ArrayMember"):
            return self.array(e)
        if tag == "Element":
            if e.children:
                return self.decorated(e.children[0])
            text = e.get("Value")
            value = parse_value(text, e.get("Radix"), e.get("DataType").upper())
            return None if value is None else self.literal(e, value, "", text)
        return None

    def _builtin_members(self, dtype: str) -> frozenset[str] | None:
        """Upper-case member names of a catalog (built-in) structure type, else None."""
        if not dtype or dtype.upper() in self.udts:
            return None
        from stdlib import catalog  # the syntax layer reads the catalog as l5x.py does

        td = catalog().type(dtype)
        return None if td is None else frozenset(m.name.upper() for m in td.members)

    def array(self, e: XElem) -> n.ArrayInit:
        dims = _dims(e.get("Dimensions"))
        elem_type = e.get("DataType").upper()
        radix = e.get("Radix")
        items: dict[int, n.Init] = {}
        for el in e.all("Element"):
            flat = _flat_index(el.get("Index"), dims)
            if flat is None:
                continue
            if el.children:
                init = self.decorated(el.children[0])
            else:
                text = el.get("Value")
                value = parse_value(text, radix, elem_type)
                init = None if value is None else self.literal(el, value, elem_type, text)
            if init is not None:
                items[flat] = init
        span = self.span(e)
        out: list[n.Init] = []
        for i in range(max(items) + 1 if items else 0):
            out.append(items.get(i) or _zero(elem_type, span))
        return n.ArrayInit(out, span)

    def string_array(
        self, dtype: str, dims: tuple[int, ...], string: XElem, raw: XElem | None
    ) -> n.ArrayInit:
        """A STRING array as Studio writes it without decorated data (v17 to v20 exports):
        `<Data Format="String">` holds element [0] only; the raw `<Data>` (hex bytes) holds
        every element as LEN (DINT, little-endian) then DATA, padded to 4 bytes."""
        cap = self._string_capacity(dtype)
        count = math.prod(dims)
        if raw is not None and cap is not None:
            size = 4 + (cap + 3) // 4 * 4
            try:
                data = bytes.fromhex(raw.text)
            except ValueError:
                data = b""
            if len(data) == size * count:
                span = self.pos.span(raw.text_offset) if raw.text_offset >= 0 else self.span(raw)
                items: list[n.Init] = []
                for k in range(count):
                    elem = data[k * size : (k + 1) * size]
                    length = max(0, min(cap, int.from_bytes(elem[:4], "little", signed=True)))
                    text = elem[4 : 4 + length]
                    items.append(n.Literal(text, "STRING", repr(text), span))
                return n.ArrayInit(items, span)
        # no raw bytes: element [0] is all the export tells; the others start empty
        first = self.string_literal(string)
        rest = [n.Literal(b"", "STRING", "''", first.span) for _ in range(count - 1)]
        return n.ArrayInit([first, *rest], first.span)

    def _string_capacity(self, dtype: str) -> int | None:
        """Characters a STRING (82) or string-family type holds (its DATA member's size)."""
        if dtype.upper() == "STRING":
            return 82
        members = self.udts.get(dtype.upper())
        data = next((m for m in members or [] if m.name.upper() == "DATA"), None)
        return data.dims if data is not None and data.dims > 0 else None

    def string_literal(self, e: XElem) -> n.Literal:
        raw = e.text.strip()
        if len(raw) >= 2 and raw[0] == "'" and raw[-1] == "'":
            value = parse_string(raw)
        else:
            value = raw.encode("latin-1", "replace")
        span = (
            self.pos.span(e.text_offset, max(1, len(raw))) if e.text_offset >= 0 else self.span(e)
        )
        return n.Literal(value, "STRING", raw, span)

    # ------------------------------------------------------------ L5K
    def l5k(self, e: XElem, dtype: str, dims: tuple[int, ...]) -> n.Init | None:
        span = self.pos.span(e.text_offset) if e.text_offset >= 0 else self.span(e)
        return self.from_l5k_text(e.text, dtype, dims, span)

    def from_l5k_text(
        self, text: str, dtype: str, dims: tuple[int, ...], span: n.Span
    ) -> n.Init | None:
        """L5K data text (`[0,500,0]`, `16#ff`, `[3,'abc$00']`) as an initialiser; also the
        tag values of .L5K exports (syntax/l5k.py). None when the text cannot be read."""
        try:
            tree = _L5KParser(text).parse()
        except ValueError:
            return None  # unreadable data: the tag keeps its default value
        return self._from_l5k(tree, dtype.upper(), dims, span)

    def _from_l5k(
        self, v: object, dtype: str, dims: tuple[int, ...], span: n.Span
    ) -> n.Init | None:
        if dims:
            if not isinstance(v, list):
                return None
            items = [self._from_l5k(x, dtype, (), span) for x in v]
            return n.ArrayInit([i if i is not None else _zero(dtype, span) for i in items], span)
        if isinstance(v, list):
            if len(v) == 2 and isinstance(v[0], int) and isinstance(v[1], bytes):
                # [LEN, 'text$00...']: STRING and string-family types alike (as Decorated
                # data of a LEN/DATA structure reads as one STRING literal)
                return n.Literal(v[1][: max(0, v[0])], "STRING", "", span)
            if dtype in self.udts:
                return self._udt_from_l5k(v, self.udts[dtype], span)
            layout = _PACKED.get(dtype)
            if layout is not None and len(v) == 3 and all(isinstance(x, int) for x in v):
                word_bits, names = layout
                members: list[tuple[str, n.Span, n.Init]] = [
                    (name, span, n.Literal(v[i + 1], "DINT", str(v[i + 1]), span))
                    for i, name in enumerate(names)
                ]
                for bname, bit in word_bits:
                    bitval = (int(v[0]) >> bit) & 1
                    members.append((bname, span, n.Literal(bitval, "DINT", str(bitval), span)))
                return n.StructInit(members, span)
            return None  # predefined layouts other than the packed ones keep their defaults
        if isinstance(v, bytes):
            return n.Literal(v, "STRING", "", span)
        if isinstance(v, int | float):
            return n.Literal(v, "REAL" if isinstance(v, float) else "DINT", str(v), span)
        return None

    def _udt_from_l5k(self, values: list, members: list[RawMember], span: n.Span) -> n.StructInit:
        out: list[tuple[str, n.Span, n.Init]] = []
        hosts: dict[str, int] = {}
        i = 0
        for m in members:
            if m.type == "BIT":
                host = hosts.get(m.target.upper(), 0)
                bitval = (host >> m.bit) & 1
                out.append((m.name, span, n.Literal(bitval, "DINT", str(bitval), span)))
                continue
            if i >= len(values):
                break
            v = values[i]
            i += 1
            # a BIT member's host: a hidden SINT in a UDT, a visible INT/DINT in a
            # module-defined type (`LogicCommand` and its `Stop`, `Start` ... bits)
            hosts[m.name.upper()] = v if isinstance(v, int) else 0
            if m.hidden:
                continue
            init = self._from_l5k(v, m.type.upper(), (m.dims,) if m.dims else (), span)
            if init is not None:
                out.append((m.name, span, init))
        return n.StructInit(out, span)


# Predefined structures whose L5K form is [control word, a, b]: (bits of the word, names of a, b).
_PACKED: dict[str, tuple[tuple[tuple[str, int], ...], tuple[str, str]]] = {
    "TIMER": ((("EN", 31), ("TT", 30), ("DN", 29)), ("PRE", "ACC")),
    "COUNTER": ((("CU", 31), ("CD", 30), ("DN", 29), ("OV", 28), ("UN", 27)), ("PRE", "ACC")),
    "CONTROL": (
        (
            ("EN", 31),
            ("EU", 30),
            ("DN", 29),
            ("EM", 28),
            ("ER", 27),
            ("UL", 26),
            ("IN", 25),
            ("FD", 24),
        ),
        ("LEN", "POS"),
    ),
}


def _is_zero(init: n.Init) -> bool:
    return isinstance(init, n.Literal) and init.value == 0


def _is_string_structure(e: XElem) -> bool:
    names = [c.get("Name").upper() for c in e.children]
    return names == ["LEN", "DATA"] and e.children[1].get("Radix") == "ASCII"


def _zero(dtype: str, span: n.Span) -> n.Init:
    if dtype in ELEMENTARY:
        return n.Literal(0, "DINT", "0", span)
    return n.StructInit([], span)


def _dims(text: str) -> tuple[int, ...]:
    """`10`, `4 3 2` or `4,3,2`; `0` or empty means a scalar."""
    parts = [p for p in re.split(r"[\s,]+", text.strip()) if p]
    try:
        dims = tuple(int(p) for p in parts)
    except ValueError:
        return ()
    return () if not dims or dims == (0,) else dims


def _flat_index(text: str, dims: tuple[int, ...]) -> int | None:
    parts = [p for p in re.split(r"[\s,\[\]]+", text) if p]
    try:
        idx = [int(p) for p in parts]
    except ValueError:
        return None
    if not dims or len(idx) != len(dims):
        return idx[0] if len(idx) == 1 else None
    flat = 0
    for i, size in zip(idx, dims, strict=True):
        if not 0 <= i < size:
            return None
        flat = flat * size + i
    return flat


class _L5KParser:
    """`[1,2.5,[3,4],'text']` -> nested lists of ints, floats and bytes."""

    _TOKEN = re.compile(r"\s*(?:(\[)|(\])|(,)|('(?:\$.|[^'])*')|([^\s,\[\]']+))")

    def __init__(self, text: str) -> None:
        self.tokens = [m for m in self._TOKEN.finditer(text) if m.group(0).strip()]
        self.i = 0

    def parse(self) -> object:
        v = self.value()
        if self.i != len(self.tokens):
            raise ValueError("trailing L5K data")
        return v

    def value(self) -> object:
        if self.i >= len(self.tokens):
            raise ValueError("L5K data ends early")
        m = self.tokens[self.i]
        self.i += 1
        if m.group(1):
            items: list[object] = []
            if self.i < len(self.tokens) and self.tokens[self.i].group(2):
                self.i += 1
                return items
            while True:
                items.append(self.value())
                if self.i >= len(self.tokens):
                    raise ValueError("unclosed [")
                t = self.tokens[self.i]
                self.i += 1
                if t.group(2):
                    return items
                if not t.group(3):
                    raise ValueError("expected ','")
        if m.group(4):
            return parse_string(m.group(4))
        if m.group(5):
            word = m.group(5)
            value = _l5k_number(word)
            if value is None:
                raise ValueError(f"bad L5K value {word}")
            return value
        raise ValueError("unexpected L5K token")


def _l5k_number(word: str) -> int | float | None:
    up = word.upper()
    if up.startswith(("DT#", "LDT#")):
        return parse_date_time(word)
    if up.startswith(("T#", "LT#", "T32#")):
        return parse_duration(word)
    if "INF" in up or "NAN" in up:
        return parse_value(word, "Float", "REAL")
    neg = word.startswith("-")
    try:
        value, _ = parse_number(word[1:] if neg else word)
    except ValueError:
        return None
    return -value if neg else value
