"""Tag storage: one slot per tag in a flat list, filled with declared initial values."""

from __future__ import annotations

from ..semantics.program import ProgramModel, const_number
from ..semantics.types import ArrayType, DataType, Elementary, StructType, is_axis
from ..syntax import nodes as n
from ..vm.values import convert, default_value, set_string


def allocate(model: ProgramModel) -> list[object]:
    """Give every tag a slot and its initial value; returns the storage list T."""
    storage: list[object] = []
    for tag in model.tags.values():
        if tag.alias_of is not None:
            continue
        tag.slot = len(storage)
        value = default_value(tag.type)
        if tag.init is not None:
            value = initial_value(tag.type, tag.init, value, model, storage)
        storage.append(value)
    for tag in model.tags.values():
        if tag.alias_of is not None:  # an alias reaches its target's storage (its access path)
            tag.slot = tag.alias_of.slot
    return storage


def initial_value(
    t: DataType, init: n.Init, value: object, model: ProgramModel, storage: list[object]
) -> object:
    """Apply a (verified) initialiser to a fresh value of type t."""
    if isinstance(t, Elementary):
        v = const_number(init)
        return convert(v if v is not None else 0, t)
    if isinstance(t, StructType):
        assert isinstance(value, list)
        if t.is_string and isinstance(init, n.Literal) and isinstance(init.value, bytes):
            set_string(value, init.value)
            return value
        if isinstance(init, n.StructInit):
            for mname, _, minit in init.members:
                m = t.member(mname)
                if m is None:
                    continue
                idx, mt = m
                if (
                    isinstance(mt, ArrayType)
                    and is_axis(mt.elem)
                    and isinstance(minit, n.ArrayInit)
                ):
                    value[idx] = [_axis_ref(item, model) for item in minit.items] + [None] * (
                        mt.size - len(minit.items)
                    )
                    continue
                value[idx] = initial_value(mt, minit, value[idx], model, storage)
        return value
    assert isinstance(t, ArrayType) and isinstance(value, list)
    if isinstance(init, n.ArrayInit):
        for i, item in enumerate(init.items[: t.size]):
            value[i] = initial_value(t.elem, item, value[i], model, storage)
    return value


def _axis_ref(item: object, model: ProgramModel) -> str | None:
    """Coordinate-system axes are kept as axis tag names; the motion runtime resolves them."""
    if isinstance(item, n.Name):
        tag = model.tag(item.ident)
        return tag.name if tag is not None else None
    return None
