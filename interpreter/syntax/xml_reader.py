"""A hardened XML reader that keeps file positions (for L5X exports).

Built on the standard library's expat parser with handlers that refuse any DOCTYPE, entity
or notation declaration before it takes effect, so entity expansion (billion laughs) and
external entities can never happen (docs/decisions/0040-l5x-xml-reader.md). Every element
keeps the byte offset of its `<` and of its first text (CDATA content included), turned
into 1-based line/column on demand, so AST spans can point into the .L5X file itself.
"""

from __future__ import annotations

import re
from bisect import bisect_right
from dataclasses import dataclass, field
from xml.parsers import expat

from .nodes import Span


class XmlRejected(Exception):
    """The document is not acceptable XML (malformed, or uses DTD/entity declarations)."""

    def __init__(self, message: str, line: int, col: int) -> None:
        super().__init__(message)
        self.message = message
        self.line = line
        self.col = col


@dataclass(slots=True)
class XElem:
    tag: str
    attrs: dict[str, str]
    offset: int  # byte offset of the element's '<'
    children: list[XElem] = field(default_factory=list)
    parts: list[str] = field(default_factory=list)
    text_offset: int = -1  # byte offset of the first character of text (CDATA content)

    @property
    def text(self) -> str:
        return "".join(self.parts)

    def get(self, name: str, default: str = "") -> str:
        return self.attrs.get(name, default)

    def child(self, tag: str) -> XElem | None:
        for c in self.children:
            if c.tag == tag:
                return c
        return None

    def all(self, tag: str) -> list[XElem]:
        return [c for c in self.children if c.tag == tag]


class Positions:
    """Byte offset -> 1-based (line, column in characters) for one document."""

    def __init__(self, data: bytes) -> None:
        self.data = data
        self.ascii = data.isascii()
        starts = [0]
        i = data.find(b"\n")
        while i >= 0:
            starts.append(i + 1)
            i = data.find(b"\n", i + 1)
        self.starts = starts

    def at(self, offset: int) -> tuple[int, int]:
        line = bisect_right(self.starts, offset)
        ls = self.starts[line - 1]
        if self.ascii:
            return line, offset - ls + 1
        return line, len(self.data[ls:offset].decode("utf-8", "replace")) + 1

    def span(self, offset: int, length: int = 1) -> Span:
        line, col = self.at(max(0, offset))
        return Span(line, col, line, col + length)

    def elem_span(self, e: XElem) -> Span:
        """The element's start tag name (`<Tag`), a compact place to point at."""
        return self.span(e.offset, len(e.tag) + 1)


_CDATA_OPEN = len(b"<![CDATA[")
_ENCODING = re.compile(rb"""(encoding\s*=\s*["'])([^"']*)""")  # the XML declaration's encoding


def parse_xml(data: bytes) -> tuple[XElem, Positions]:
    """Parse a whole document; raises XmlRejected with a position on any problem."""
    pos = Positions(data)
    p = expat.ParserCreate()
    p.buffer_text = False
    stack: list[XElem] = []
    root: list[XElem] = []
    cdata_start = [-1]

    def reject(what: str) -> None:
        line, col = p.CurrentLineNumber, p.CurrentColumnNumber + 1
        raise XmlRejected(
            f"{what} are not accepted in a project export (possible entity attack)", line, col
        )

    def start(tag: str, attrs: dict[str, str]) -> None:
        e = XElem(tag, attrs, p.CurrentByteIndex)
        if stack:
            stack[-1].children.append(e)
        else:
            root.append(e)
        stack.append(e)

    def end(tag: str) -> None:
        stack.pop()

    def chars(text: str) -> None:
        if not stack:
            return
        e = stack[-1]
        if e.text_offset < 0:
            e.text_offset = cdata_start[0] if cdata_start[0] >= 0 else p.CurrentByteIndex
        e.parts.append(text)

    def cdata_open() -> None:
        if stack and not "".join(stack[-1].parts).strip():
            stack[-1].parts.clear()  # whitespace before a CDATA section is layout, not content
            stack[-1].text_offset = -1
        cdata_start[0] = p.CurrentByteIndex + _CDATA_OPEN

    def cdata_close() -> None:
        if stack and stack[-1].text_offset < 0:
            stack[-1].text_offset = cdata_start[0]  # an empty CDATA section
        cdata_start[0] = -1

    p.StartElementHandler = start
    p.EndElementHandler = end
    p.CharacterDataHandler = chars
    p.StartCdataSectionHandler = cdata_open
    p.EndCdataSectionHandler = cdata_close
    p.StartDoctypeDeclHandler = lambda *a: reject("DOCTYPE declarations")
    p.EntityDeclHandler = lambda *a: reject("ENTITY declarations")
    p.UnparsedEntityDeclHandler = lambda *a: reject("ENTITY declarations")
    p.NotationDeclHandler = lambda *a: reject("NOTATION declarations")
    p.ExternalEntityRefHandler = lambda *a: reject("external entities")  # type: ignore[assignment, return-value]
    p.SetParamEntityParsing(expat.XML_PARAM_ENTITY_PARSING_NEVER)
    try:
        p.Parse(data, True)
    except expat.ExpatError as exc:
        msg = expat.ErrorString(exc.code) if exc.code is not None else str(exc)
        line, col = exc.lineno, exc.offset + 1
        if line <= len(pos.starts):
            line, col = pos.at(pos.starts[line - 1] + exc.offset)
        raise XmlRejected(f"malformed XML: {msg}", line, col) from None
    except (LookupError, ValueError):
        # Expat reads UTF-8/16, ASCII and Latin-1 itself and asks Python's codecs for any other
        # declared encoding; those raise for unknown names, multi-byte or non-text codecs.
        m = _ENCODING.search(data, 0, 512)
        line, col = pos.at(m.end(1)) if m else (1, 1)
        name = m.group(2).decode("ascii", "replace") if m else "?"
        raise XmlRejected(
            f"malformed XML: the declared encoding '{name}' cannot be read (exports are UTF-8)",
            line,
            col,
        ) from None
    finally:
        # The handlers are closures over `p` and `p` holds them: a cycle that would keep the
        # whole element tree alive until the cyclic collector runs. Unbinding `p` breaks it.
        p = None  # type: ignore[assignment]
    if not root:
        raise XmlRejected("no XML element found", 1, 1)
    return root[0], pos
