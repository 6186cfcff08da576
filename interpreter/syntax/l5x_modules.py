"""Module I/O tags of an L5X export (`<Modules>`): `Local:1:I`, `Rack2:3:C`, `Drive1:O` ...

Studio creates controller-scope tags for every module's connection data and configuration.
Their names come from where the module sits (docs/decisions/0052-module-io-tags.md):
- a module in a chassis or rail slot (its upstream port is a backplane port with a numeric
  Address) is named after its parent and slot: `<Parent>:<slot>:<suffix>`, so modules in
  the controller's own chassis are `Local:<slot>:...`;
- a module reached over a network (Ethernet, ControlNet, DeviceNet ...) uses its own name:
  `<Module>:<suffix>`.
The suffix is the connection's InputTagSuffix / OutputTagSuffix (default I / O) and C for
the ConfigTag.

We have no module profiles: the tag's structure is whatever the export's Decorated data
shows (`<Structure DataType="AB:1756_DI:I:0">` and its members, nested structures and
arrays included). Such module-defined type names always hold ':' (`AB:...:I:0`,
`_0275:1101834_...:I:0`); each becomes a structure type of that name, shared by every
module (and AOI parameter) using it. A connection without Decorated data has no layout we
could read, so its tag stays undeclared (the undefined-tag message then names the module).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from . import nodes as n
from .l5x_data import DataReader, _dims
from .xml_reader import Positions, XElem

# Upstream port types that are networks: a module reached through one is named by itself.
NETWORK_PORTS = {"ETHERNET", "CONTROLNET", "DEVICENET", "DHPLUS", "DH+", "RIO", "SERCOS", "DHRIO"}


@dataclass(slots=True)
class ModuleTags:
    """What the `<Modules>` section declares."""

    types: list[n.TypeDecl] = field(default_factory=list)
    tags: list[n.VarDecl] = field(default_factory=list)
    modules: dict[str, str] = field(
        default_factory=dict
    )  # upper tag prefix (`LOCAL:1`) -> module name


class ModuleReader:
    def __init__(self, pos: Positions, data: DataReader) -> None:
        self.pos = pos
        self.data = data
        self.out = ModuleTags()
        self._types: dict[str, n.TypeDecl] = {}  # upper type name -> declaration (members merged)
        self._tag_names: set[str] = set()

    def span(self, e: XElem) -> n.Span:
        return self.pos.elem_span(e)

    def read(self, sec: XElem) -> ModuleTags:
        for m in sec.all("Module"):
            self.module(m)
        return self.out

    @staticmethod
    def prefix(m: XElem) -> str:
        """`Parent:slot` for a module in a chassis slot, else the module's own name."""
        name = m.get("Name").strip()
        parent = m.get("ParentModule").strip()
        ports = m.child("Ports")
        for p in ports.all("Port") if ports is not None else []:
            if p.get("Upstream").lower() != "true":
                continue
            addr = p.get("Address").strip()
            if (
                p.get("Type").strip().upper() not in NETWORK_PORTS
                and addr.isdecimal()
                and parent
                and parent != name
            ):
                return f"{parent}:{int(addr)}"
        return name

    def module(self, m: XElem) -> None:
        name = m.get("Name").strip()
        comms = m.child("Communications")
        if not name or comms is None:
            return
        prefix = self.prefix(m)
        self.out.modules[prefix.upper()] = name
        config = comms.child("ConfigTag")
        if config is not None:
            self.io_tag(config, f"{prefix}:C")
        for conns in comms.all("Connections"):
            for c in conns.all("Connection"):
                for tag_elem, attr, default in (
                    ("InputTag", "InputTagSuffix", "I"),
                    ("OutputTag", "OutputTagSuffix", "O"),
                ):
                    e = c.child(tag_elem)
                    if e is not None:
                        self.io_tag(e, f"{prefix}:{c.get(attr).strip() or default}")

    def io_tag(self, e: XElem, tag: str) -> None:
        key = tag.upper()
        if key in self._tag_names:
            return  # a second connection with the same suffix: Studio keeps one tag
        deco = next(
            (d for d in e.all("Data") if d.get("Format") == "Decorated" and d.children), None
        )
        if deco is None:
            return
        top = deco.children[0]
        tref = self.type_of(top)
        if tref is None:
            return
        self._tag_names.add(key)
        sp = self.span(e)
        tref = n.TypeRef(tref.name, tref.dims, sp)
        self.out.tags.append(
            n.VarDecl([(tag, sp)], tref, self.data.decorated(top), sp, block="VAR_GLOBAL")
        )

    # ------------------------------------------------------------ module-defined types
    def type_of(self, e: XElem) -> n.TypeRef | None:
        """The type a decorated element shows, declaring module-defined structures on the way."""
        dtype = e.get("DataType").strip()
        if not dtype:
            return None
        sp = self.span(e)
        if e.tag in ("Array", "ArrayMember"):
            dims = _dims(e.get("Dimensions"))
            if not dims:
                return None
            first = next((el.children[0] for el in e.all("Element") if el.children), None)
            if ":" in dtype:
                if first is None or self.structure(first) is None:
                    return None
            return n.TypeRef(dtype.upper(), [(0, d - 1) for d in dims], sp)
        if e.tag in ("Structure", "StructureMember") and ":" in dtype:
            return self.structure(e)
        return n.TypeRef(dtype.upper(), [], sp)

    def structure(self, e: XElem) -> n.TypeRef | None:
        dtype = e.get("DataType").strip()
        if ":" not in dtype:
            return self.type_of(e)
        key = dtype.upper()
        decl = self._types.get(key)
        if decl is None:
            sp = self.span(e)
            decl = n.TypeDecl(dtype, [], sp, sp)
            self._types[key] = decl
            self.out.types.append(decl)
        known = {name.upper() for m in decl.members for name, _ in m.names}
        for c in e.children:
            mname = c.get("Name").strip()
            if not mname or mname.upper() in known:
                continue  # members another module of this type already showed
            mt = self.type_of(c)
            if mt is None:
                continue
            sp = self.span(c)
            decl.members.append(n.VarDecl([(mname, sp)], mt, None, sp))
            known.add(mname.upper())
        return n.TypeRef(key, [], self.span(e))
