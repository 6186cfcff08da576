"""Completion: classify the cursor (context.py), then list candidates for that place only.

Returns plain `Item`s; lsp/server.py turns them into protocol objects.
"""

from __future__ import annotations

from dataclasses import dataclass

from interpreter.semantics.checker import block_reference_fits, type_matches
from interpreter.semantics.program import ProgramModel, Tag
from interpreter.semantics.types import ArrayType, DataType, Elementary, StructType
from stdlib import Instruction, Operand, catalog

from ..workspace import Analysed
from .context import Context, Where, classify, offset_of
from .fblock import Block, block, member_line, named_parameter
from .resolve import find_instruction, program_at, type_of_operand, visible_tags

# ST statement keywords (the statement forms of SPEC 3.1).
ST_KEYWORDS = (
    "IF", "THEN", "ELSIF", "ELSE", "END_IF", "CASE", "OF", "END_CASE", "FOR", "TO", "BY",
    "DO", "END_FOR", "WHILE", "END_WHILE", "REPEAT", "UNTIL", "END_REPEAT", "EXIT",
    "AND", "OR", "XOR", "NOT", "MOD", "TRUE", "FALSE", "VAR", "END_VAR",
)  # fmt: skip
ELEMENTARY_TYPES = (
    "BOOL", "SINT", "INT", "DINT", "LINT", "USINT", "UINT", "UDINT", "ULINT", "REAL", "LREAL",
    "STRING",
)  # fmt: skip


class Kind:
    """Completion item kinds (the LSP numbers, so the server passes them through)."""

    FUNCTION = 3
    FIELD = 5
    VARIABLE = 6
    CLASS = 7
    VALUE = 12
    KEYWORD = 14
    SNIPPET = 15
    ENUM_MEMBER = 20
    STRUCT = 22


@dataclass(frozen=True, slots=True)
class Item:
    label: str
    kind: int
    detail: str = ""
    documentation: str = ""
    insert_text: str | None = None
    snippet: bool = False
    sort: str = "5"  # rank: lower sorts first


MAX_ITEMS = 300  # more is never read; the editor asks again as the user types


def complete(an: Analysed, line: int, character: int) -> list[Item]:
    """Candidates at 0-based (line, character), those matching the typed prefix first, at
    most MAX_ITEMS (see `is_incomplete`)."""
    items, _ = complete_list(an, line, character)
    return items


def complete_list(an: Analysed, line: int, character: int) -> tuple[list[Item], bool]:
    """(items, incomplete): incomplete when candidates were left out by the MAX_ITEMS cap."""
    doc = an.document
    ctx = classify(doc.text, offset_of(doc.text, line, character), doc.language or "st")
    items = _candidates(an, line, ctx)
    if ctx.prefix and ctx.where is not Where.OPERAND:
        # a half-typed word narrows the list (enumeration texts keep all: ladder forms have
        # spaces, and an operand has few values)
        key = ctx.prefix.lower()
        items = [i for i in items if i.label.lower().startswith(key)] or items
    if len(items) > MAX_ITEMS:
        items = sorted(items, key=lambda i: (i.sort, i.label.lower()))[:MAX_ITEMS]
        return items, True
    return items, False


def _candidates(an: Analysed, line: int, ctx: Context) -> list[Item]:
    model = an.loaded.model
    program = program_at(an, line + 1)
    if ctx.where is Where.NONE:
        return []
    if ctx.where is Where.MEMBER:
        return members(type_of_operand(model, ctx.base, program))
    if ctx.where is Where.OPERAND:
        return operand_items(model, ctx, program)
    if ctx.where is Where.TYPE:
        return type_items(model)
    if ctx.where is Where.VALUE:
        return tag_items(visible_tags(model, program)) + [
            Item(k, Kind.KEYWORD, sort="6") for k in ("TRUE", "FALSE", "NOT")
        ]
    return statement_items(model, program, ctx.language)


def members(t: DataType | None) -> list[Item]:
    if isinstance(t, ArrayType):
        return []
    if isinstance(t, Elementary):
        if t.is_integer:  # bit numbers of an integer tag
            return [
                Item(str(b), Kind.VALUE, f"bit {b} of a {t}", sort=f"{b:03d}")
                for b in range(t.bits)
            ]
        return []
    if not isinstance(t, StructType):
        return []
    items = []
    for i, (name, mt) in enumerate(t.members):
        if name.upper() in t.hidden:
            continue
        items.append(Item(name, Kind.FIELD, str(mt), t.docs.get(name.upper(), ""), sort=f"{i:04d}"))
    return items


def operand_items(model: ProgramModel, ctx: Context, program: str | None) -> list[Item]:
    if ctx.language == "st":
        fb = block(model, ctx.instruction, program)
        if fb is not None:
            return block_items(model, fb, ctx, program)
    ins = find_instruction(model, ctx.instruction, ctx.language)
    if ins is None or not ins.operands:
        return []
    op = ins.operands[min(ctx.index, len(ins.operands) - 1)]
    if ctx.index >= len(ins.operands) and not ins.variadic:
        return []
    items: list[Item] = []
    if op.enum is not None:
        items.extend(enum_items(op, ctx.language == "rll"))
        if op.format == "immediate":
            return items
    if op.format in ("routine", "label"):
        return items
    fitting = [t for t in visible_tags(model, program) if _fits(t.type, op)]
    items.extend(tag_items(fitting, sort="3" if op.enum is None else "7"))
    return items


def block_items(model: ProgramModel, fb: Block, ctx: Context, program: str | None) -> list[Item]:
    """Inside `camIn(`: the input names (`Name := `); after `Name :=`, that input's values."""
    param = named_parameter(ctx.arg_text)
    if param is None:
        return [
            Item(
                m.name,
                Kind.FIELD,
                member_line(m),
                m.doc,
                f"{m.name} := ",
                sort=f"{0 if m.required else 1}{i:03d}",
            )  # fmt: skip
            for i, m in enumerate(fb.inputs)
        ]
    m = fb.member(param)
    if m is None or m.readonly:
        return []
    if m.enum is not None:
        op = Operand(m.name, ("DINT",), "value", "in", enum=m.enum)
        return enum_items(op, False)
    st = fb.tag.type
    assert isinstance(st, StructType)
    found = st.member(m.name)
    assert found is not None
    want = found[1]
    tags = visible_tags(model, program)
    if isinstance(want, Elementary):
        fitting = [t for t in tags if isinstance(t.type, Elementary)]
        extra = [Item(k, Kind.KEYWORD, sort="6") for k in ("TRUE", "FALSE")] if want.is_bool else []
        return tag_items(fitting, sort="3") + extra
    fitting = [t for t in tags if block_reference_fits(want, t.type)]
    return tag_items(fitting, sort="3")


def enum_items(op: Operand, ladder: bool) -> list[Item]:
    """The operand's own enumeration values, labelled with the documented text in lower case
    (SPEC 9.31): in ST without spaces (`unitspersec`, an ST name), in ladder with them
    (`units per sec`, as neutral text writes it; decision 0150)."""
    enum = catalog().enum(op.enum)  # type: ignore[arg-type]
    return [
        Item(
            v.text.lower() if ladder else v.label,
            Kind.ENUM_MEMBER,
            f"{v.value}: {v.doc}" if v.doc else str(v.value),
            f"{op.name} = {v.value} ({v.text})",
            sort=f"1{i:03d}",
        )
        for i, v in enumerate(enum.values)
    ]


def _fits(t: DataType, op: Operand) -> bool:
    if type_matches(t, op.types):
        return True
    # An array operand (CAM_PROFILE[], CAM[] ...) names the array; the catalog gives its element.
    return (
        isinstance(t, ArrayType)
        and op.format in ("array", "array_or_value", "memory")
        and type_matches(t.elem, op.types)
    )


def tag_items(tags: list[Tag], sort: str = "4") -> list[Item]:
    shown: dict[
        DataType, str
    ] = {}  # a type's text, once per type (an export has thousands of tags)
    items = []
    for t in tags:
        detail = shown.get(t.type)
        if detail is None:
            detail = shown[t.type] = str(t.type)
        items.append(Item(t.name, Kind.VARIABLE, detail, sort=sort))
    return items


def type_items(model: ProgramModel) -> list[Item]:
    items = [Item(name, Kind.KEYWORD, "elementary type", sort="1") for name in ELEMENTARY_TYPES]
    items += [
        Item(td.name, Kind.STRUCT, "predefined structure", td.doc, sort="3")
        for name, td in sorted(catalog().types.items())
        if name == td.name
    ]
    items += [
        Item(t.name, Kind.STRUCT, "user-defined type", sort="2") for t in model.types.user_types()
    ]
    return items


def snippet(ins: Instruction) -> str:
    ops = ", ".join(f"${{{i}:{op.name}}}" for i, op in enumerate(ins.operands, start=1))
    return f"{ins.name}({ops})"


def instruction_items(model: ProgramModel, language: str) -> list[Item]:
    seen: set[str] = set()
    items = []
    for ins in catalog().instructions:
        if language not in ins.languages or ins.name in seen:
            continue
        seen.add(ins.name)
        if ins.kind == "function" and language == "st":
            items.append(
                Item(ins.name, Kind.FUNCTION, "function", ins.doc, snippet(ins), True, "6")
            )
            continue
        items.append(Item(ins.name, Kind.SNIPPET, "instruction", ins.doc, snippet(ins), True, "5"))
    for aoi in model.aois.values():
        defined: Instruction | None = getattr(aoi, "instruction", None)
        if defined is not None:
            ins = defined
            items.append(
                Item(ins.name, Kind.CLASS, "add-on instruction", ins.doc, snippet(ins), True, "5")
            )
    return items


def statement_items(model: ProgramModel, program: str | None, language: str) -> list[Item]:
    items = instruction_items(model, language)
    items += tag_items(visible_tags(model, program))
    if language == "st":
        items += [Item(k, Kind.KEYWORD, sort="2") for k in ST_KEYWORDS]
    return items
