"""L5K project exports (Studio 5000's text format) -> the project model the L5X reader builds.

An .L5K file carries what an .L5X carries, written as keyword blocks (`CONTROLLER ...
END_CONTROLLER`, `DATATYPE`, `MODULE`, `ADD_ON_INSTRUCTION_DEFINITION`, `TAG`, `PROGRAM`,
`ROUTINE`, `ST_ROUTINE`, `TASK` ...), attribute lists `(Name := value, ...)` and statements
ending in `;`. This reader walks those blocks with a cursor over the text and builds the same
L5XProject as syntax/l5x.py (docs/decisions/0047-l5k-reader.md): data types with BIT members
over hidden SINTs, tags whose initialisers come from their L5K data (the data parser the L5X
reader uses for its L5K fallback), AOIs, programs, ST routines (the `'` lines joined with
newlines), ladder rungs (`N: text;`, `RC: "comment";`) and tasks. Spans are positions in the
.L5K file; `context` names program / routine / rung or ST line like the L5X reader does.
Blocks the model has no place for (CONFIG, TREND, QUICK_WATCH, PARAMETER_CONNECTION ...) are
skipped to their END_ keyword (decision 0048); module connection data declare I/O tags only
where the MODULE block shows their layout (decision 0070).
"""

from __future__ import annotations

import html
import re
from bisect import bisect_right
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from functools import partial

from stdlib import catalog

from ..diagnostics import Diagnostic, diag
from . import nodes as n
from .l5x import (
    _AXIS_ENUM_PARAMS,
    _AXIS_PARAMS,
    AliasDecl,
    AoiDecl,
    AoiParam,
    L5XProject,
    ProgramDecl,
    TaskDecl,
    rotary_members,
)
from .l5x import _remap as remap_spans
from .l5x_data import DataReader, RawMember, _l5k_number
from .literals import decode_text
from .st_parser import parse_st
from .xml_reader import Positions, XmlRejected, parse_xml

_WORD = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
# Type and module names may hold ':' (module-defined `AB:1756_DI:I:0`, `Ctrl:Partner`).
_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*(?::[A-Za-z0-9_]+)*")
_MODULE = re.compile(r"\$?[A-Za-z_][A-Za-z0-9_]*(?::[A-Za-z0-9_]+)*")  # `$NoName`: unnamed
_KEY = re.compile(r"([^,;()\"'\n]*?)\s*:=")
_INT = re.compile(r"[+-]?\d+")
_WS = re.compile(r"(?:\s+|\(\*.*?\*\))*", re.S)
_QUOTED = {
    '"': re.compile(r'"(?:\$.|[^"$])*"', re.S),
    "'": re.compile(r"'(?:\$.|[^'$])*'", re.S),
}
_SHOWN = re.compile(r"\S{1,20}")
_TARGET = re.compile(r"[^\s(;]+")
_RC = re.compile(r"RC\s*:", re.I)
# What a skip must step over whole: strings, `'` lines of ST, [[[___ raw XML ___]]].
_SKIP = re.compile(
    r"\"(?:\$.|[^\"$])*\"|^[ \t]*'[^\n]*|\[\[\[___.*?___\]\]\]|(?<![A-Za-z0-9_])END_[A-Za-z0-9_]+",
    re.M | re.S,
)
_STATEMENT = re.compile(r"\"(?:\$.|[^\"$])*\"|'(?:\$.|[^'$\n])*'|\[\[\[___.*?___\]\]\]|;", re.S)
_VALUE = re.compile(r"\"(?:\$.|[^\"$])*\"|'(?:\$.|[^'$\n])*'|[\[\](){},;]")
_RUNG_TYPE = re.compile(r"(N|I|D|R|IR|RR|RI|RN|E|ER)\s*:(?!=)", re.I)
_NOT_MEMBERS = {"DESCRIPTION", "RADIX", "CONSTANT", "EXTERNALACCESS", "USAGE", "REQUIRED"}
_MOTION = ("MOTION_GROUP", "COORDINATE_SYSTEM")
# In a MODULE block: the raw XML of ExtendedProp, the module-defined types it may show, and
# the statements that carry connection data (strings and raw XML matched whole, to skip them).
_RAW = re.compile(r"\[\[\[___.*?___\]\]\]", re.S)
_DATA_TAG = re.compile(r"<(Input|Output)DataTag>(.*?)</\1DataTag>", re.S)
_MODULE_ITEM = re.compile(
    r"\"(?:\$.|[^\"$])*\"|\[\[\[___.*?___\]\]\]"
    r"|(?<![A-Za-z0-9_.])(CONNECTION|InputData|OutputData)(?![A-Za-z0-9_])",
    re.S,
)


class _Fatal(Exception):
    """The file cannot be read on (a block never ends, a string never closes...)."""

    def __init__(self, message: str, offset: int) -> None:
        super().__init__(message)
        self.message = message
        self.offset = offset


class _Bad(_Fatal):
    """One statement or block header is malformed: report it and skip that piece."""


@dataclass(slots=True)
class _Attr:
    key: str  # as written
    text: str  # a quoted value without its quotes (escapes kept), else the value as written
    quoted: bool
    offset: int


def read_l5k(data: bytes, path: str) -> tuple[L5XProject | None, list[Diagnostic]]:
    """Parse an .L5K export; None (with an S008 diagnostic) when it is not a usable L5K file."""
    if data.startswith(b"\xef\xbb\xbf"):
        data = data[3:]
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError:
        text = data.decode("latin-1")
    reader = _Reader(text, path)
    try:
        project = reader.read()
    except _Fatal as exc:
        return None, [*map(reader.project.annotate, reader.diags), reader.error(exc)]
    return project, [project.annotate(d) for d in reader.diags]


class _Reader:
    def __init__(self, text: str, path: str) -> None:
        self.t = text
        self.i = 0
        self.path = path
        self.starts = [0] + [m.end() for m in re.finditer("\n", text)]
        self.diags: list[Diagnostic] = []
        self.udt_raw: dict[str, list[RawMember]] = {}
        self.data = DataReader(Positions(b""), self.udt_raw)  # only its L5K data conversion
        self.project = L5XProject(path)

    # ------------------------------------------------------------ positions and diagnostics
    def at(self, offset: int) -> tuple[int, int]:
        line = bisect_right(self.starts, offset)
        return line, offset - self.starts[line - 1] + 1

    def span(self, offset: int, length: int = 1) -> n.Span:
        line, col = self.at(min(max(0, offset), len(self.t)))
        return n.Span(line, col, line, col + max(1, length))

    def error(self, exc: _Fatal) -> Diagnostic:
        return diag("S008", exc.message, self.path, self.span(exc.offset))

    def bad(self, exc: _Fatal) -> None:
        self.diags.append(self.error(exc))

    def err(self, code: str, msg: str, span: n.Span) -> None:
        self.diags.append(diag(code, msg, self.path, span))

    def line_of(self, offset: int) -> int:
        return self.at(offset)[0]

    # ------------------------------------------------------------ lexing
    def ws(self) -> None:
        """Skip white space and `(* ... *)` comments (the export's header is one)."""
        self.i = _WS.match(self.t, self.i).end()  # type: ignore[union-attr]  # matches empty
        if self.t.startswith("(*", self.i):
            raise _Fatal("comment '(*' is not closed", self.i)

    def peek(self, s: str) -> bool:
        self.ws()
        return self.t.startswith(s, self.i)

    def peek_word(self) -> str:
        self.ws()
        m = _WORD.match(self.t, self.i)
        return m.group(0) if m else ""

    def word(self, what: str, pattern: re.Pattern[str] = _WORD) -> tuple[str, int]:
        self.ws()
        m = pattern.match(self.t, self.i)
        if m is None:
            raise _Bad(f"expected {what}, found {self.found()}", self.i)
        self.i = m.end()
        return m.group(0), m.start()

    def found(self) -> str:
        if self.i >= len(self.t):
            return "the end of the file"
        m = _SHOWN.match(self.t, self.i)
        return f"'{m.group(0)}'" if m else "white space"

    def expect(self, s: str, where: str) -> None:
        if not self.peek(s) or (s == ":" and self.t.startswith(":=", self.i)):
            raise _Bad(f"expected '{s}' {where}, found {self.found()}", self.i)
        self.i += len(s)

    def integer(self, what: str) -> int:
        text, off = self.word(what, _INT)
        return int(text)

    def quoted_end(self, start: int) -> int:
        """Offset after the `"..."` (or `'...'`) string starting at `start` ($ escapes)."""
        m = _QUOTED[self.t[start]].match(self.t, start)
        if m is None:
            raise _Fatal("string is not closed", start)
        return m.end()

    def attrs(self) -> dict[str, _Attr]:
        """`(Name := value, ...)` when one follows; keys upper-cased, values as written."""
        out: dict[str, _Attr] = {}
        if not self.peek("("):
            return out
        self.i += 1
        while True:
            self.ws()
            if self.t.startswith(")", self.i):
                self.i += 1
                return out
            m = _KEY.match(self.t, self.i)
            if m is None or not m.group(1).strip():
                raise _Bad(
                    f"expected 'Name := value' in an attribute list, found {self.found()}", self.i
                )
            key = m.group(1).strip()
            self.i = m.end()
            self.ws()
            start = self.i
            if self.t.startswith('"', start):
                end = self.quoted_end(start)
                out[key.upper()] = _Attr(key, self.t[start + 1 : end - 1], True, start)
                self.i = end
            else:
                end = self.value_end(start, ",)")
                out[key.upper()] = _Attr(key, self.t[start:end].strip(), False, start)
                self.i = end
            self.ws()
            if self.t.startswith(",", self.i):
                self.i += 1
            elif not self.t.startswith(")", self.i):
                raise _Bad(
                    f"expected ',' or ')' in an attribute list, found {self.found()}", self.i
                )

    def value_end(self, start: int, stops: str) -> int:
        """Where a value ends: the first of `stops` outside brackets and strings."""
        depth = 0
        for m in _VALUE.finditer(self.t, start):
            c = m.group(0)
            if len(c) > 1:
                continue  # a string
            if depth == 0 and c in stops:
                return m.start()
            if c in "[({":
                depth += 1
            elif c in "])}":
                depth -= 1
                if depth < 0:
                    raise _Bad(f"unbalanced '{c}'", m.start())
            elif c == ";":
                raise _Bad("a value ends before its ';'", m.start())
        raise _Fatal("the file ends inside a value", start)

    def skip_statement(self) -> None:
        """Step past the next `;` (strings and raw XML stepped over whole)."""
        for m in _STATEMENT.finditer(self.t, self.i):
            if m.group(0) == ";":
                self.i = m.end()
                return
        raise _Fatal("the file ends inside a statement (no ';')", self.i)

    def skip_to_end(self, kw: str, opened: int) -> None:
        """Step past `END_<kw>`: a block whose content the project model has no place for."""
        end = "END_" + kw.upper()
        for m in _SKIP.finditer(self.t, self.i):
            if m.group(0).upper() == end:
                self.i = m.end()
                return
        raise _Fatal(self.unclosed(kw, opened), len(self.t))

    def skip_unknown(self, kw: str, opened: int) -> None:
        """A keyword this reader has no use for: a block is skipped to its END_ keyword
        (decision 0048); anything else is reported and skipped to its ';'."""
        end = re.compile(rf"(?<![A-Za-z0-9_])END_{kw}(?![A-Za-z0-9_])")
        if end.search(self.t, self.i) is not None:
            self.skip_to_end(kw, opened)
            return
        self.bad(_Bad(f"unknown statement '{kw}' skipped", opened))
        self.skip_statement()

    def unclosed(self, kw: str, opened: int) -> str:
        return f"{kw} opened at line {self.line_of(opened)} is not closed: the file ends before END_{kw}"

    def items(self, kw: str, opened: int) -> Iterator[tuple[str, int]]:
        """Each keyword (or name) starting a statement or block in kw's body, until END_kw."""
        end = "END_" + kw
        while True:
            self.ws()
            if self.i >= len(self.t):
                raise _Fatal(self.unclosed(kw, opened), len(self.t))
            m = _WORD.match(self.t, self.i)
            if m is None:
                exc = _Bad(f"unexpected {self.found()} in {kw}", self.i)
                self.bad(exc)
                start = self.i
                self.skip_statement()
                if self.i <= start:
                    raise exc
                continue
            if m.group(0) == end:
                self.i = m.end()
                return
            if m.group(0) in _ENDS:  # a tag may be called END_POS; END_PROGRAM ends a block
                raise _Fatal(
                    f"{m.group(0)} where END_{kw} was expected (opened at line {self.line_of(opened)})",
                    m.start(),
                )
            self.i = m.end()
            yield m.group(0), m.start()

    def guarded(self, kw: str, off: int, read: Callable[[], object]) -> None:
        """Read one block; a malformed header or body is reported and the block skipped."""
        try:
            read()
        except _Bad as exc:
            self.bad(exc)
            self.skip_to_end(kw, off)

    # ------------------------------------------------------------ top level
    def read(self) -> L5XProject:
        p = self.project
        header = re.search(r"Version\s*:=[^\n]*?(\d+\.\d+)", self.t[:2000])
        self.ws()
        if self.peek_word() == "IE_VER":
            self.word("IE_VER")
            self.expect(":=", "after IE_VER")
            self.i = self.value_end(self.i, ";") + 1
        word = self.peek_word()
        if word != "CONTROLLER":
            raise _Fatal(
                "not a Studio 5000 L5K export: expected IE_VER and CONTROLLER at the top, "
                f"found {self.found()}",
                self.i,
            )
        _, off = self.word("CONTROLLER")
        try:
            p.controller, _ = self.word("the controller name", _NAME)
            attrs = self.attrs()
        except _Bad as exc:
            raise _Fatal(exc.message, exc.offset) from None
        major = attrs.get("MAJOR")
        p.revision = header.group(1) if header else (major.text if major else "")
        p.target_type = "Controller"
        for kw, koff in self.items("CONTROLLER", off):
            handler = {
                "DATATYPE": self.datatype,
                "MODULE": self.module,
                "ADD_ON_INSTRUCTION_DEFINITION": self.aoi,
                "ENCODED_DATA": self.encoded,
                "TAG": self.controller_tags,
                "PROGRAM": self.program,
                "TASK": self.task,
            }.get(kw)
            if handler is None:
                self.skip_unknown(kw, koff)  # CONFIG, TREND, QUICK_WATCH, PARAMETER_CONNECTION ...
                continue
            self.guarded(kw, koff, partial(handler, koff))
        self.ws()
        if self.i < len(self.t):
            self.bad(_Bad(f"text after END_CONTROLLER: {self.found()}", self.i))
        return p

    def encoded(self, off: int) -> n.Routine | None:
        """`ENCODED_DATA (EncodedType := ..., Name := ...) <cipher> END_ENCODED_DATA`: U302.
        A protected routine stays a routine that runs nothing, so JSR still finds it (as
        the L5X reader keeps it)."""
        attrs = self.attrs()
        name = attrs["NAME"].text if "NAME" in attrs else "?"
        kind = attrs["ENCODEDTYPE"].text.upper() if "ENCODEDTYPE" in attrs else ""
        what = {
            "ADD_ON_INSTRUCTION_DEFINITION": "add-on instruction",
            "ROUTINE": "routine",
            "PROGRAM": "program",
        }.get(kind, "content")
        self.skip_to_end("ENCODED_DATA", off)
        self.err(
            "U302",
            f"{what} '{name}' is protected (encoded); its content cannot be read",
            self.span(off, len("ENCODED_DATA")),
        )
        if kind != "ROUTINE" or "NAME" not in attrs or not name:
            return None
        return n.Routine(name, "unsupported", self.path, span=self.span(off, len("ENCODED_DATA")))

    # ------------------------------------------------------------ data types
    def datatype(self, off: int) -> None:
        name, noff = self.word("a data type name", _NAME)
        self.attrs()
        raw: list[RawMember] = []
        decls: list[n.VarDecl] = []
        for kw, koff in self.items("DATATYPE", off):
            try:
                if kw == "BIT":  # BIT <name> <host SINT> : <bit> (attrs);
                    mname, moff = self.word("a member name")
                    host, _ = self.word("the member holding the bit")
                    self.expect(":", "before the bit number")
                    bit = self.integer("a bit number")
                    self.attrs()
                    self.expect(";", "after the member")
                    raw.append(RawMember(mname, "BIT", 0, False, host, bit))
                    sp = self.span(moff, len(mname))
                    decls.append(n.VarDecl([(mname, sp)], n.TypeRef("BOOL", [], sp), None, sp))
                    continue
                self.i = koff  # <type> <name>[dims] (attrs);
                dtype, toff = self.word("a member type", _NAME)
                mname, moff = self.word("a member name")
                dims = self.dims()
                attrs = self.attrs()
                self.expect(";", "after the member")
            except _Bad as exc:
                self.bad(exc)
                self.skip_statement()
                continue
            hidden = "HIDDEN" in attrs and attrs["HIDDEN"].text.lower() in ("1", "yes", "true")
            raw.append(RawMember(mname, dtype.upper(), dims[0] if dims else 0, hidden))
            if hidden:
                continue  # the SINT that hosts BIT members: each BIT member is a BOOL here
            sp = self.span(moff, len(mname))
            tref = n.TypeRef(dtype.upper(), [(0, d - 1) for d in dims], self.span(toff, len(dtype)))
            decls.append(n.VarDecl([(mname, sp)], tref, None, sp))
        self.udt_raw[name.upper()] = raw
        sp = self.span(noff, len(name))
        self.project.types.append(n.TypeDecl(name, decls, self.span(off, 8), sp))

    def dims(self) -> tuple[int, ...]:
        if not self.t.startswith("[", self.i):
            return ()
        close = self.t.find("]", self.i)
        if close < 0:
            raise _Bad("'[' of the array dimensions is not closed", self.i)
        parts = [p.strip() for p in self.t[self.i + 1 : close].split(",")]
        if not all(p.isdecimal() for p in parts):
            raise _Bad("array dimensions must be whole numbers", self.i)
        self.i = close + 1
        dims = tuple(int(p) for p in parts)
        return () if dims == (0,) else dims

    # ------------------------------------------------------------ modules
    def module(self, off: int) -> None:
        """The module's place (the names of its I/O tags, decision 0048) and, where the block
        shows the layout of its connection data, its I/O tags with that data (decision 0070):
        an L5K export gives connection data as bare values, and only some module profiles
        write their module-defined types into `ExtendedProp`."""
        name, _ = self.word("a module name", _MODULE)
        attrs = self.attrs()
        body = self.i
        self.skip_to_end("MODULE", off)
        if name.startswith("$"):
            return  # a module without a name of its own (a drive's peripheral): no I/O tags
        parent = attrs["PARENT"].text.strip() if "PARENT" in attrs else ""
        slot = attrs["SLOT"].text.strip() if "SLOT" in attrs else ""
        node = attrs["NODEADDRESS"].text.strip() if "NODEADDRESS" in attrs else ""
        label = attrs["PORTLABEL"].text.upper() if "PORTLABEL" in attrs else ""
        networked = bool(node) and "BACKPLANE" not in label
        prefix = name
        if slot.isdecimal() and parent and parent != name and not networked:
            prefix = f"{parent}:{int(slot)}"
        self.project.modules[prefix.upper()] = name
        self.module_data(prefix, body, self.i)

    def module_data(self, prefix: str, start: int, end: int) -> None:
        """I/O tags `<prefix>:I` / `:O` of the connections whose type `ExtendedProp` shows; a
        connection without one stays undeclared (the checker names its module, once)."""
        layouts: dict[str, str] = {}  # "INPUT"/"OUTPUT" -> module-defined type name
        raw = _RAW.search(self.t, start, end)
        if raw is not None:
            for m in _DATA_TAG.finditer(raw.group(0)):
                tname = self.module_type(m.group(2), raw.start() + m.start(2))
                if tname:
                    layouts[m.group(1).upper()] = tname
        if not layouts:
            return
        saved = self.i
        suffixes = {"INPUT": "I", "OUTPUT": "O"}
        try:
            for m in _MODULE_ITEM.finditer(self.t, start, end):
                word = m.group(1)
                if word is None:
                    continue  # a string or raw XML, stepped over whole
                self.i = m.end()
                if word == "CONNECTION":
                    self.word("a connection name")
                    cattrs = self.attrs()
                    for kind in suffixes:
                        sfx = cattrs.get(kind + "TAGSUFFIX")
                        suffixes[kind] = sfx.text.strip() if sfx and sfx.text.strip() else kind[0]
                    continue
                kind = word[: -len("Data")].upper()  # InputData / OutputData
                self.attrs()  # Description, COMMENT.<member> ...
                self.expect(":=", f"after {word}")
                self.ws()
                vstart = self.i
                text = self.t[vstart : self.value_end(vstart, ";")]
                if kind in layouts:
                    tag = f"{prefix}:{suffixes[kind]}"
                    self.module_tag(tag, layouts[kind], text, m.start(1), vstart)
        except _Bad as exc:
            self.bad(exc)  # the block is read up to here; its END_MODULE was found already
        finally:
            self.i = saved

    def module_type(self, escaped: str, off: int) -> str:
        """Declare the module-defined type `ExtendedProp` shows (`<DataType Name=...>` as
        escaped XML, `$Q` for its quotes); its name, or "" when it cannot be read."""
        xml = html.unescape(escaped.replace("$Q", '"')).encode("utf-8")
        try:
            root, _ = parse_xml(xml)
        except XmlRejected:
            return ""
        tname = root.get("Name").strip()
        members = root.child("Members")
        if root.tag != "DataType" or ":" not in tname or members is None:
            return ""
        key = tname.upper()
        if key in self.udt_raw:
            return key  # another module of this profile declared it already
        sp = self.span(off)
        raw: list[RawMember] = []
        decls: list[n.VarDecl] = []
        for e in members.all("Member"):
            mname, mtype = e.get("Name").strip(), e.get("DataType").strip().upper()
            if not mname or not mtype:
                return ""
            dim, bit = e.get("Dimension").strip() or "0", e.get("BitNumber").strip() or "0"
            if not dim.isdecimal() or not bit.isdecimal():
                return ""  # not a layout we can read: the module stays without its I/O tags
            dims = int(dim)
            hidden = e.get("Hidden").lower() in ("1", "true")
            if mtype == "BIT":
                raw.append(RawMember(mname, "BIT", 0, False, e.get("Target"), int(bit)))
                mtype = "BOOL"  # a bit of its target member, shown as a BOOL (as Decorated data)
            else:
                raw.append(RawMember(mname, mtype, dims, hidden))
            if not hidden:
                tref = n.TypeRef(mtype, [(0, dims - 1)] if dims else [], sp)
                decls.append(n.VarDecl([(mname, sp)], tref, None, sp))
        self.udt_raw[key] = raw
        self.project.types.append(n.TypeDecl(tname, decls, sp, sp))
        return key

    def module_tag(self, tag: str, tname: str, text: str, off: int, doff: int) -> None:
        if any(d.names[0][0].upper() == tag.upper() for d in self.project.tags):
            return  # a second connection with the same suffix: Studio keeps one tag
        sp = self.span(off, len(tag))
        init = self.data.from_l5k_text(text, tname, (), self.span(doff))
        decl = n.VarDecl([(tag, sp)], n.TypeRef(tname, [], sp), init, sp, block="VAR_GLOBAL")
        self.project.tags.append(decl)

    # ------------------------------------------------------------ tags
    def controller_tags(self, off: int) -> None:
        tags, aliases = self.tag_block("TAG", off, "tag")
        self.project.tags.extend(tags)
        self.project.aliases.extend(aliases)

    def tag_block(
        self, kw: str, off: int, what: str, aoi: AoiDecl | None = None
    ) -> tuple[list[n.VarDecl], list[AliasDecl]]:
        decls: list[n.VarDecl] = []
        aliases: list[AliasDecl] = []
        for name, noff in self.items(kw, off):
            if name == "ENCODED_DATA":
                self.encoded(noff)
                continue
            if self.nested_block(name):
                self.skip_to_end(name, noff)  # ALARM_CONDITION ... of tag-based alarms
                continue
            try:
                self.tag(name, noff, what, decls, aliases, aoi)
            except _Bad as exc:
                self.bad(exc)
                self.skip_statement()
        return decls, aliases

    def nested_block(self, word: str) -> bool:
        """An upper-case keyword not followed by ` : ` or `OF`, whose END_ comes later: a
        block among the tag statements (tag names may be upper-case too, so check both)."""
        if not word.isupper() or self.peek(":") or self.peek_word() == "OF":
            return False
        end = re.compile(rf"(?<![A-Za-z0-9_])END_{word}(?![A-Za-z0-9_])")
        return end.search(self.t, self.i) is not None

    def tag(
        self,
        name: str,
        noff: int,
        what: str,
        decls: list[n.VarDecl],
        aliases: list[AliasDecl],
        aoi: AoiDecl | None,
    ) -> None:
        """`name : TYPE[dims] (attrs) := data, TagForceData := ...;` or `name OF base (attrs);`"""
        sp = self.span(noff, len(name))
        if self.peek_word() == "OF":
            self.word("OF")
            self.ws()
            m = _TARGET.match(self.t, self.i)
            if m is None:
                raise _Bad(f"alias '{name}' names no base tag", self.i)
            target = m.group(0)
            self.i = m.end()
            self.attrs()
            self.expect(";", "after the alias")
            aliases.append(AliasDecl(name, target, sp))
            return
        self.expect(":", f"after the {what} name '{name}'")
        dtype, toff = self.word(f"the data type of '{name}'", _NAME)
        dims = self.dims()
        attrs = self.attrs()
        text, doff = "", -1
        if self.peek(":="):
            self.i += 2
            self.ws()
            doff = self.i
            end = self.value_end(doff, ",;")
            text = self.t[doff:end].strip()
            self.i = end
        if self.peek(","):  # `, TagForceData := [...]`: forces are not simulated
            self.skip_statement()
        else:
            self.expect(";", f"after the {what} '{name}'")
        if what != "tag":
            default = attrs.get("DEFAULTDATA")
            if default is not None:
                text, doff = default.text, default.offset + (1 if default.quoted else 0)
        tref = n.TypeRef(dtype.upper(), [(0, d - 1) for d in dims], self.span(toff, len(dtype)))
        init = self.motion_or_alarm(name, dtype.upper(), attrs, sp) if what == "tag" else None
        if init is None and text:
            init = self.data.from_l5k_text(text, dtype, dims, self.span(doff))
        decl = n.VarDecl(
            [(name, sp)], tref, init, sp, block="VAR_GLOBAL" if what == "tag" else "VAR"
        )
        if aoi is not None and what == "parameter":
            usage_attr = attrs.get("USAGE") or attrs.get("TYPE")
            usage = usage_attr.text if usage_attr else "Input"
            req = attrs.get("REQUIRED")
            required = (
                req is not None and req.text.lower() in ("yes", "true", "1")
            ) or usage == "InOut"
            aoi.params.append(AoiParam(name, usage, required, decl))
            return
        decls.append(decl)

    def motion_or_alarm(
        self, name: str, dtype: str, attrs: dict[str, _Attr], sp: n.Span
    ) -> n.Init | None:
        """Axis, motion group and alarm tags: their configuration is the attribute list."""
        members: list[tuple[str, n.Span, n.Init]] = []
        if dtype == "MOTION_GROUP":
            cup = attrs.get("COARSEUPDATEPERIOD")
            us = _l5k_number(cup.text) if cup is not None else None
            if us is not None:
                self.project.coarse_update_us = float(us)
                members.append(("CoarseUpdatePeriod", sp, n.Literal(int(us), "DINT", cup.text, sp)))  # type: ignore[union-attr]
            return n.StructInit(members, sp)
        if dtype.startswith("AXIS_") or dtype in _MOTION:
            group = attrs.get("MOTIONGROUP")
            if group is not None and dtype.startswith("AXIS_") and group.text:
                self.project.axis_groups[name.upper()] = group.text
            for key, attr in attrs.items():
                enum_member = _AXIS_ENUM_PARAMS.get(key)
                if enum_member is not None:  # `HomeMode := Active`: the catalog gives the number
                    ev = catalog().enum(enum_member).lookup(attr.text.strip())
                    if ev is not None:
                        lit = n.Literal(ev.value, "DINT", str(ev.value), sp)
                        members.append((enum_member, sp, lit))
                    continue
                member = _AXIS_PARAMS.get(key)
                num = _l5k_number(attr.text) if member else None
                if member and num is not None:
                    members.append((member, sp, n.Literal(float(num), "REAL", attr.text, sp)))
            if dtype.startswith("AXIS_"):
                members += rotary_members({k: a.text.strip() for k, a in attrs.items()}, sp)
            return n.StructInit(members, sp)
        if dtype.startswith("ALARM_"):
            for key, attr in attrs.items():
                low = attr.text.strip().lower()
                if key in _NOT_MEMBERS or "." in key or ":" in key or attr.quoted:
                    continue
                value = (
                    (1 if low == "true" else 0)
                    if low in ("true", "false")
                    else _l5k_number(attr.text)
                )
                if value is not None:
                    typ = "REAL" if isinstance(value, float) else "DINT"
                    members.append((attr.key, sp, n.Literal(value, typ, attr.text, sp)))
            return n.StructInit(members, sp)
        return None

    # ------------------------------------------------------------ add-on instructions
    def aoi(self, off: int) -> None:
        name, noff = self.word("an add-on instruction name")
        self.attrs()
        aoi = AoiDecl(name, self.span(noff, len(name)))
        owner = f"add-on instruction {name}"
        for kw, koff in self.items("ADD_ON_INSTRUCTION_DEFINITION", off):
            if kw == "PARAMETERS":
                _, aliases = self.tag_block("PARAMETERS", koff, "parameter", aoi)
                aoi.aliases.extend(aliases)
            elif kw == "LOCAL_TAGS":
                decls, _ = self.tag_block("LOCAL_TAGS", koff, "local tag")
                aoi.locals.extend(decls)
            elif kw in _ROUTINES or kw == "ENCODED_DATA":
                r = self.encoded(koff) if kw == "ENCODED_DATA" else self.routine(kw, koff, owner)
                if r is not None:
                    aoi.routines.append(r)
            else:
                self.skip_unknown(kw, koff)  # HISTORY_ENTRY ...
        self.project.aois.append(aoi)

    # ------------------------------------------------------------ programs and routines
    def program(self, off: int) -> None:
        name, noff = self.word("a program name")
        attrs = self.attrs()
        main = attrs.get("MAIN")
        flag = attrs.get("DISABLEFLAG")
        prog = ProgramDecl(
            name,
            self.span(noff, len(name)),
            main.text if main else "",
            disabled=flag is not None and flag.text.lower() in ("1", "yes", "true"),
        )
        owner = f"program {name}"
        for kw, koff in self.items("PROGRAM", off):
            if kw == "TAG":
                tags, aliases = self.tag_block("TAG", koff, "tag")
                prog.tags.extend(tags)
                prog.aliases.extend(aliases)
            elif kw in _ROUTINES or kw == "ENCODED_DATA":
                r = self.encoded(koff) if kw == "ENCODED_DATA" else self.routine(kw, koff, owner)
                if r is not None:
                    r.program_name = name
                    prog.routines.append(r)
            else:
                self.skip_unknown(kw, koff)  # CHILD_PROGRAMS ...
        self.project.programs.append(prog)

    def routine(self, kw: str, off: int, owner: str) -> n.Routine | None:
        result: list[n.Routine | None] = [None]

        def read() -> None:
            name, noff = self.word("a routine name")
            self.attrs()
            where = f"{owner}, routine {name}"
            if kw == "ROUTINE":
                result[0] = self.rll_routine(name, off, where)
            elif kw == "ST_ROUTINE":
                result[0] = self.st_routine(name, off, where)
            else:
                label = _ROUTINES[kw]
                self.skip_to_end(kw, off)
                sp = self.span(noff, len(name))
                self.err("U301", f"{label} routine '{name}' ({owner}) is not supported", sp)
                result[0] = n.Routine(name, "unsupported", self.path, span=sp)

        self.guarded(kw, off, read)
        return result[0]

    def rll_routine(self, name: str, off: int, where: str) -> n.Routine:
        from .rll_parser import parse_rung

        routine = n.Routine(name, "rll", self.path, span=self.span(off, len("ROUTINE")))
        comment: list[str] = []
        number = 0
        for kw, koff in self.items("ROUTINE", off):
            self.i = koff
            rc = _RC.match(self.t, koff)
            if rc is not None:
                self.i = rc.end()
                try:
                    comment.append(self.rung_comment())
                except _Bad as exc:
                    self.bad(exc)
                    self.skip_statement()
                continue
            m = _RUNG_TYPE.match(self.t, koff)
            if m is None:
                self.i = koff + len(kw)
                self.skip_unknown(kw, koff)  # LOGIC blocks of pending edits ...
                continue
            start = m.end()
            self.i = start
            self.skip_statement()
            text = self.t[start : self.i]
            lead = len(text) - len(text.lstrip())
            kind = m.group(1).upper()
            this = number
            number += 1
            if kind.startswith("D"):
                comment = []
                continue  # a rung marked for deletion by pending edits
            line, col = self.at(start + lead)
            label = f"{where}, rung {this}"
            for k in range(text.count("\n", lead) + 1):
                self.project.context.setdefault(line + k, label)
            rung, diags = parse_rung(text[lead:], self.path, this, line, col)
            self.diags.extend(diags)
            if rung is not None:
                if comment:
                    rung.comment = "\n".join(comment).strip()
                routine.rungs.append(rung)
            comment = []
        return routine

    def rung_comment(self) -> str:
        """`RC: "text" "more text";`: one or more quoted pieces joined."""
        parts: list[str] = []
        while True:
            self.ws()
            if self.t.startswith(";", self.i):
                self.i += 1
                return "".join(parts)
            if not self.t.startswith('"', self.i):
                raise _Bad(f"expected a quoted rung comment, found {self.found()}", self.i)
            end = self.quoted_end(self.i)
            parts.append(decode_text(self.t[self.i : end]))
            self.i = end

    def st_lines(self, kw: str, off: int, lines: list[tuple[int, str]]) -> None:
        """Collect the `'` lines of a routine body until END_kw; LOGIC blocks of online edits
        keep the original logic only (the controller runs it until the edits are accepted)."""
        t = self.t
        while True:
            self.ws()
            if self.i >= len(t):
                raise _Fatal(self.unclosed(kw, off), len(t))
            if t.startswith("'", self.i):
                nl = t.find("\n", self.i)
                end = len(t) if nl < 0 else nl
                lines.append((self.i + 1, t[self.i + 1 : end].rstrip("\r")))
                self.i = end
                continue
            word, woff = self.word(f"a `'` line or END_{kw}")
            if word == "END_" + kw:
                return
            if word == "LOGIC":
                attrs = self.attrs()
                kind = attrs["ONLINE_EDIT_TYPE"].text.upper() if "ONLINE_EDIT_TYPE" in attrs else ""
                if kind in ("", "ORIG", "ORIGINAL"):
                    self.st_lines("LOGIC", woff, lines)
                else:
                    self.skip_to_end("LOGIC", woff)
                continue
            raise _Bad(f"unexpected '{word}' in the ST routine", woff)

    def st_routine(self, name: str, off: int, where: str) -> n.Routine:
        lines: list[tuple[int, str]] = []
        self.st_lines("ST_ROUTINE", off, lines)
        # Joined line k (1-based) -> (file line, column offset of its first character).
        line_map: list[tuple[int, int]] = []
        for k, (start, _) in enumerate(lines):
            fl, fc = self.at(start)
            line_map.append((fl, fc - 1))
            self.project.context.setdefault(fl, f"{where}, line {k}")
        if not line_map:
            sp = self.span(off)
            line_map.append((sp.line, sp.col - 1))
        routine, diags = parse_st("\n".join(text for _, text in lines), self.path, name)

        def remap(s: n.Span) -> n.Span:
            a = line_map[min(max(s.line, 1), len(line_map)) - 1]
            b = line_map[min(max(s.end_line, 1), len(line_map)) - 1]
            return n.Span(a[0], s.col + a[1], b[0], s.end_col + b[1])

        remap_spans(routine, remap)
        for d in diags:
            self.diags.append(Diagnostic(d.code, d.message, d.path, remap(d.span)))
        routine.span = self.span(off, len("ST_ROUTINE"))
        return routine

    # ------------------------------------------------------------ tasks
    def task(self, off: int) -> None:
        name, noff = self.word("a task name")
        attrs = self.attrs()
        sp = self.span(noff, len(name))
        kind = attrs["TYPE"].text.upper() if "TYPE" in attrs else "CONTINUOUS"
        progs: list[tuple[str, n.Span]] = []
        for prog, poff in self.items("TASK", off):
            self.expect(";", f"after the scheduled program '{prog}'")
            progs.append((prog, self.span(poff, len(prog))))
        rate_text = attrs["RATE"].text if "RATE" in attrs else "10"
        prio_text = attrs["PRIORITY"].text if "PRIORITY" in attrs else "10"
        try:
            rate = float(rate_text)
            priority = int(prio_text)
        except ValueError:
            self.err("S008", f"task '{name}' has a Rate or Priority that is not a number", sp)
            return
        if kind == "PERIODIC" and rate <= 0:
            self.err("S008", f"periodic task '{name}' needs a Rate > 0 ms", sp)
            return
        inhibit = attrs.get("INHIBITTASK")
        inhibited = inhibit is not None and inhibit.text.lower() in ("yes", "1", "true")
        self.project.tasks.append(TaskDecl(name, kind, rate, priority, progs, inhibited, sp))


_ENDS = {
    "END_" + kw
    for kw in (
        "CONTROLLER DATATYPE MODULE ADD_ON_INSTRUCTION_DEFINITION PARAMETERS LOCAL_TAGS TAG "
        "PROGRAM ROUTINE ST_ROUTINE FBD_ROUTINE SFC_ROUTINE TASK ENCODED_DATA CONNECTION "
        "CHILD_PROGRAMS LOGIC CONFIG TREND QUICK_WATCH PARAMETER_CONNECTION"
    ).split()
}
_ROUTINES = {
    "ROUTINE": "ladder",
    "ST_ROUTINE": "structured text",
    "FBD_ROUTINE": "function block diagram",
    "SFC_ROUTINE": "sequential function chart",
}
