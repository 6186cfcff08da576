"""Go to definition, references and rename of tags (protocol-free: paths and spans)."""

from __future__ import annotations

from dataclasses import dataclass

from interpreter.semantics.locate import names_in
from interpreter.semantics.program import Tag
from interpreter.semantics.types import StructType
from interpreter.syntax import nodes as n

from ..workspace import Analysed
from .context import offset_of
from .resolve import find_tag, program_at, type_of_operand, word_at


@dataclass(frozen=True, slots=True)
class Location:
    path: str
    span: n.Span


class RenameRefused(Exception):
    """The name is not one the user may rename here (a predefined name, or declared elsewhere)."""


def _routines(an: Analysed) -> list[n.Routine]:
    return an.loaded.model.all_routines()


def definition(an: Analysed, line: int, character: int) -> list[Location]:
    text = an.document.text
    start, end = word_at(text, offset_of(text, line, character))
    word = text[start:end]
    if not word:
        return []
    model = an.loaded.model
    program = program_at(an, line + 1)
    if text[start - 1 : start] == ".":  # a member: its UDT declaration
        base_end = start - 1
        base_start = base_end
        while base_start > 0 and (
            text[base_start - 1].isalnum() or text[base_start - 1] in "_.:[]"
        ):
            base_start -= 1
        t = type_of_operand(model, text[base_start:base_end], program)
        if isinstance(t, StructType):
            return _member_decl(an, t.name, word)
        return []
    routine = model.routine(word, program)
    if routine is not None and text[end:].lstrip()[:1] != "(":
        return [Location(routine.path, routine.span)]
    tag = find_tag(model, word, program)
    if tag is not None:
        return [Location(tag.path, _name_span(tag))]
    for r in _routines(an):
        for td in r.types:
            if td.name.upper() == word.upper():
                return [Location(r.path, td.name_span)]
    return []


def _member_decl(an: Analysed, type_name: str, member: str) -> list[Location]:
    for r in _routines(an):
        for td in r.types:
            if td.name.upper() != type_name.upper():
                continue
            for decl in td.members:
                for name, span in decl.names:
                    if name.upper() == member.upper():
                        return [Location(r.path, span)]
    return []


def _name_span(tag: Tag) -> n.Span:
    s = tag.span
    return n.Span(s.line, s.col, s.line, s.col + len(tag.name)) if s.line == s.end_line else s


def _tag_at(an: Analysed, line: int, character: int) -> Tag | None:
    text = an.document.text
    start, end = word_at(text, offset_of(text, line, character))
    if not text[start:end] or text[start - 1 : start] == ".":
        return None
    return find_tag(an.loaded.model, text[start:end], program_at(an, line + 1))


def references(an: Analysed, line: int, character: int, declaration: bool = True) -> list[Location]:
    tag = _tag_at(an, line, character)
    if tag is None:
        return []
    tag_of = an.loaded.analysis.tag_of
    found = [Location(tag.path, _name_span(tag))] if declaration else []
    for routine, name in names_in(_routines(an)):
        if tag_of.get(id(name)) is tag:
            s = name.span
            found.append(
                Location(routine.path, n.Span(s.line, s.col, s.line, s.col + len(name.ident)))
            )
    return found


def rename(
    an: Analysed, line: int, character: int, new_name: str, editable: set[str]
) -> list[Location]:
    """Every place to rewrite; refused for names not declared in the open `editable` files."""
    tag = _tag_at(an, line, character)
    if tag is None:
        raise RenameRefused("only tags can be renamed here")
    if tag.path not in editable or tag.alias_of is not None:
        raise RenameRefused(
            f"'{tag.name}' is declared in {tag.path}, which is not a file open here"
        )
    if not new_name.replace("_", "a").isalnum() or new_name[0].isdigit():
        raise RenameRefused(f"'{new_name}' is not a tag name")
    return references(an, line, character, declaration=True)
