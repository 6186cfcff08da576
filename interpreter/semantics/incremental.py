"""An export analysed again after an edit inside one routine's text (decision 0117).

The language server re-analyses an `.L5X` after every pause in typing. When the text differs
from the last analysed text only inside the CDATA text of one program routine's element (a
rung's text or comment, an ST line) and the edit moves nothing else (the line count of that
text is unchanged and nothing else starts on the line where the edit ends), every other
position in the file, every declaration and every other routine are as they were. Then only
that routine is read again (from the elements the last read kept) and verified again, with
the state the routines before it left (W203 control tags, U306 modules); the other routines'
diagnostics are kept. Anything else, or a routine whose check leaves a different state for
the routines after it, is a full analysis: the result always equals `analyse_project` on the
same text (tests/language_server/test_incremental.py).
"""

from __future__ import annotations

import re
from bisect import bisect_right
from collections.abc import Iterator
from dataclasses import dataclass, field

from ..syntax import nodes as n
from ..syntax.l5x import ParseMemo, read_routine_again
from ..syntax.xml_reader import XElem
from .checker import Checker
from .document import Loaded, ProjectAnalysis, analyse_export, record_checks
from .locate import walk

_CDATA_OPEN = b"<![CDATA["
_CDATA_CLOSE = b"]]>"
_NOT_XML = re.compile("[^\t\n\r\x20-\ud7ff\ue000-\ufffd\U00010000-\U0010ffff]")
# What may follow a CDATA section on its line without holding a position: its end, the rest
# of the element's text and closing tags.
_LINE_REST = re.compile(rb"\]\]>[^<]*(?:</[^<>]*>\s*)*")
_ENCODING = re.compile(rb"""encoding\s*=\s*["']([^"']*)""")


@dataclass(slots=True)
class _Texts:
    """The leaf elements with text of the program routines, in document order, and the byte
    range of their text in the current document (kept up to date across edits)."""

    starts: list[int]
    ends: list[int]  # where `]]>` begins (-1: the text is no CDATA section)
    elements: list[XElem]
    sources: list[int]  # index in ParseMemo.sources


@dataclass(slots=True)
class ExportState:
    """One open export: its last analysed bytes and analysis, and what the read kept."""

    path: str
    data: bytes
    memo: ParseMemo
    result: ProjectAnalysis
    texts: _Texts | None = field(default=None)

    @staticmethod
    def read(path: str, data: bytes, memo: ParseMemo | None = None) -> ExportState:
        memo = memo if memo is not None else ParseMemo()
        return ExportState(path, data, memo, analyse_export(path, data, memo))

    @property
    def loaded(self) -> Loaded:
        return self.result.loaded

    def update(self, data: bytes) -> Loaded | None:
        """The analysis of `data` by patching the last one; None when it needs a full read
        (then this state is stale: the caller reads afresh)."""
        if data == self.data:
            return self.result.loaded
        if not self._patchable():
            return None
        texts = self._texts()
        old = self.data
        a, old_b, new_b = changed(old, data)
        k = bisect_right(texts.starts, a) - 1
        if k < 0 or old_b > texts.ends[k]:
            return None  # not inside one text (a declaration, the XML structure ...)
        start, end, elem = texts.starts[k], texts.ends[k], texts.elements[k]
        if old[start - len(_CDATA_OPEN) : start] != _CDATA_OPEN:
            return None
        close = old.find(b"<", end + len(_CDATA_CLOSE))
        if close < 0 or old[close : close + 2] != b"</":
            return None
        tail = old[end + len(_CDATA_CLOSE) : close]  # after the CDATA: part of the text too
        delta = new_b - old_b
        try:
            before = old[start:end].decode("utf-8")
            after = data[start : end + delta].decode("utf-8")
            rest = tail.decode("utf-8")
        except UnicodeDecodeError:
            return None
        if b"&" in tail or elem.text != _as_xml_reads(before + rest):
            return None  # the element's text is not exactly this one CDATA section
        if (
            "]]>" in after
            or _NOT_XML.search(after)
            or after.count("\n") != before.count("\n")  # the file's lines
            or _as_xml_reads(after).count("\n") != _as_xml_reads(before).count("\n")  # as read
        ):
            return None  # would end the section early, not be XML, or move lines
        line_end = data.find(b"\n", new_b)
        line_end = len(data) if line_end < 0 else line_end
        if line_end > end + delta and not _LINE_REST.fullmatch(data, end + delta, line_end):
            return None  # something after it on this line would change column
        return self._patch(data, k, _as_xml_reads(after + rest), delta)

    def _patchable(self) -> bool:
        loaded = self.result.loaded
        if loaded.project is None or self.memo.reader is None:
            return False  # an .L5K export, or one that could not be read
        if not self.path.lower().endswith(".l5x"):
            return False
        m = _ENCODING.search(self.data, 0, 512)
        return m is None or m.group(1).lower() in (b"utf-8", b"utf8")

    def _texts(self) -> _Texts:
        """Built once per full read (its element offsets are offsets in `self.data` then)."""
        if self.texts is None:
            found: list[tuple[int, XElem, int]] = []
            for i, source in enumerate(self.memo.sources):
                stack = [source.element]
                while stack:
                    e = stack.pop()
                    if e.children:
                        stack.extend(e.children)
                    elif e.text_offset >= 0:
                        found.append((e.text_offset, e, i))
            found.sort(key=lambda x: x[0])
            self.texts = _Texts(
                [x[0] for x in found],
                [self.data.find(_CDATA_CLOSE, x[0]) for x in found],
                [x[1] for x in found],
                [x[2] for x in found],
            )
        return self.texts

    def _patch(self, data: bytes, k: int, text: str, delta: int) -> Loaded | None:
        texts = self._texts()
        result, loaded = self.result, self.result.loaded
        model, project = loaded.model, loaded.project
        assert project is not None
        source = self.memo.sources[texts.sources[k]]
        program = project.programs[source.program]
        old_routine = program.routines[source.index]
        unit = next((i for i, r in enumerate(model.routines) if r is old_routine), None)
        if unit is None:
            return None
        texts.elements[k].parts[:] = [text]
        routine, read_diags = read_routine_again(self.memo, source)
        if routine is None:
            return None
        # Verify it with what the routines before it left, and keep the result only if it
        # leaves the same for the routines after it (else their diagnostics could change).
        checker = Checker(model)
        motion, modules = checker.carried()
        for c in result.checks[:unit]:
            motion.update(c.motion)
            modules.update(c.modules)

        def step() -> Iterator[None]:
            checker.routine(routine, routine.program_name)
            yield None

        (check,) = record_checks(checker, step(), project.annotate)
        previous = result.checks[unit]
        if check.motion != previous.motion or check.modules != previous.modules:
            return None
        # Commit: the routine, its analysis entries, its diagnostics, the text positions.
        program.routines[source.index] = routine
        model.routines[unit] = routine
        _replace_analysis(loaded, old_routine, checker)
        loaded.analysis.diags = [d for c in result.checks for d in c.raw]
        result.checks[unit] = check
        lo, hi = source.diags
        result.read_diags[lo:hi] = read_diags
        moved = len(read_diags) - (hi - lo)
        source.diags = (lo, lo + len(read_diags))
        if moved:
            for other in self.memo.sources:
                if other is not source and other.diags[0] >= hi:
                    other.diags = (other.diags[0] + moved, other.diags[1] + moved)
        if delta:
            texts.ends[k] += delta
            starts, ends = texts.starts, texts.ends
            for i in range(k + 1, len(starts)):
                starts[i] += delta
                if ends[i] >= 0:
                    ends[i] += delta
        self.data = data
        result.loaded = Loaded(model, loaded.analysis, [], project)
        result.loaded.diagnostics = result.diagnostics()
        return result.loaded


def _replace_analysis(loaded: Loaded, old: n.Routine, checker: Checker) -> None:
    """The old routine's entries out of the project's analysis (its nodes are gone, and their
    ids may be reused), the new routine's in."""
    a, new = loaded.analysis, checker.a
    maps = (a.type_of, a.enum_of, a.call_of, a.fb_of, a.tag_of, a.system_of)
    for node in walk(old):
        key = id(node)
        for m in maps:
            m.pop(key, None)  # type: ignore[attr-defined]
        a.unsimulated.discard(key)
    a.type_of.update(new.type_of)
    a.enum_of.update(new.enum_of)
    a.call_of.update(new.call_of)
    a.fb_of.update(new.fb_of)
    a.tag_of.update(new.tag_of)
    a.system_of.update(new.system_of)
    a.unsimulated |= new.unsimulated


def _as_xml_reads(text: str) -> str:
    """XML reads CR LF and a lone CR as LF (exports written on Windows have CR LF)."""
    return text.replace("\r\n", "\n").replace("\r", "\n") if "\r" in text else text


def changed(old: bytes, new: bytes) -> tuple[int, int, int]:
    """The edit that turns `old` into `new`: (start, end in old, end in new), by the longest
    common prefix and then the longest common suffix of what is left."""
    n_ = min(len(old), len(new))
    a = _common_prefix(old, new, n_)
    s = _common_suffix(old, new, n_ - a)
    return a, len(old) - s, len(new) - s


def _common_prefix(x: bytes, y: bytes, limit: int) -> int:
    if x[:limit] == y[:limit]:
        return limit
    lo, hi = 0, limit  # x[:lo] == y[:lo], x[:hi] != y[:hi]
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if x[lo:mid] == y[lo:mid]:
            lo = mid
        else:
            hi = mid
    return lo


def _common_suffix(x: bytes, y: bytes, limit: int) -> int:
    lx, ly = len(x), len(y)
    if x[lx - limit :] == y[ly - limit :]:
        return limit
    lo, hi = 0, limit  # the last lo bytes agree, the last hi do not
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if x[lx - mid : lx - lo] == y[ly - mid : ly - lo]:
            lo = mid
        else:
            hi = mid
    return lo
