"""Calling an Add-On Instruction: build the frame, copy parameters, run the compiled Logic routine.

The implementation follows the registry convention `impl(ctx, rung, instance, *required)`:
Input arguments arrive as values, Output arguments as Ref/BitRef, InOut arguments as
Ref/BitRef (elementary) or the structure/array object itself (see semantics/aoi.py).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from ..semantics.aoi import Aoi
from ..semantics.types import Elementary
from ..vm.refs import BitRef, Ref
from ..vm.values import convert, copy_value

Routine = Callable[[list, Any], None]


class Cell:
    """An elementary InOut argument seen as a one-element container: `frame[j][0]`."""

    __slots__ = ("ref",)

    def __init__(self, ref: Ref | BitRef) -> None:
        self.ref = ref

    def __getitem__(self, key: int) -> object:
        return self.ref.get()

    def __setitem__(self, key: int, value: object) -> None:
        self.ref.set(value)


@dataclass(slots=True)
class AoiRoutines:
    """The compiled scan-mode routines of one definition (filled in after translation)."""

    logic: Routine | None = None
    logic_prescan: Routine | None = None
    enable_in_false: Routine | None = None


def make_impls(aoi: Aoi, code: AoiRoutines) -> tuple[Callable[..., bool], Callable[..., None]]:
    """The call and prescan implementations of one add-on instruction."""
    ei = aoi.type.index.get("ENABLEIN")
    eo = aoi.type.index.get("ENABLEOUT")
    spec = [(p.usage, p.member, p.type) for p in aoi.required]

    def frame_for(inst: list, args: tuple) -> list:
        frame: list = [inst]
        for (usage, member, t), a in zip(spec, args, strict=True):
            if usage == "Input":
                inst[member] = convert(a, t) if isinstance(t, Elementary) else copy_value(a)
            elif usage == "InOut":
                frame.append(Cell(a) if isinstance(a, Ref | BitRef) else a)
        return frame

    mirrors = aoi.mirrors

    def mirror_in(inst: list) -> None:
        """Alias parameters of a local member or bit: what the outside set reaches the local."""
        for member, path, bit in mirrors:
            _set_place(inst, path, bit, inst[member])

    def mirror_out(inst: list) -> None:
        for member, path, bit in mirrors:
            inst[member] = _get_place(inst, path, bit)

    def copy_out(inst: list, args: tuple) -> None:
        for (usage, member, _), a in zip(spec, args, strict=True):
            if usage == "Output" and isinstance(a, Ref | BitRef):
                a.set(inst[member])

    def call(ctx: Any, rung: object, inst: list, *args: object) -> bool:
        frame = frame_for(inst, args)
        if mirrors:
            mirror_in(inst)
        if ei is not None:
            inst[ei] = 1 if rung else 0
        if rung:
            if eo is not None:
                inst[eo] = 1  # EnableOut follows EnableIn unless the logic writes it
            if code.logic is not None:
                code.logic(frame, ctx)
        else:
            if eo is not None:
                inst[eo] = 0
            if code.enable_in_false is not None:
                code.enable_in_false(frame, ctx)
        if mirrors:
            mirror_out(inst)
        copy_out(inst, args)
        return bool(inst[eo]) if eo is not None else bool(rung)

    def prescan(ctx: Any, rung: object, inst: list, *args: object) -> None:
        frame = frame_for(inst, args)
        if mirrors:
            mirror_in(inst)
        if code.logic_prescan is not None:
            code.logic_prescan(frame, ctx)
        if mirrors:
            mirror_out(inst)

    return call, prescan


def _get_place(inst: list, path: tuple[int, ...], bit: tuple[int, Elementary] | None) -> object:
    value: Any = inst
    for pos in path:
        value = value[pos]
    return (value >> bit[0]) & 1 if bit is not None else copy_value(value)


def _set_place(
    inst: list, path: tuple[int, ...], bit: tuple[int, Elementary] | None, value: object
) -> None:
    holder: Any = inst
    for pos in path[:-1]:
        holder = holder[pos]
    last = path[-1]
    if bit is None:
        holder[last] = copy_value(value)
        return
    n, t = bit
    word = holder[last] | (1 << n) if value else holder[last] & ~(1 << n)
    holder[last] = convert(word, t)
