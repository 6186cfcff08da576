"""Structure values for calling instruction impls directly, as the VM passes them.

A structure operand is its live member list in declaration order (registry docstring):
these build one from the type's defaults with some members set by name.
"""

from __future__ import annotations

from interpreter.semantics.types import StructType, TypeTable
from interpreter.vm.values import default_value


def struct_type(type_name: str) -> StructType:
    t = TypeTable().get(type_name)
    assert isinstance(t, StructType), type_name
    return t


def new_struct(type_name: str, **members: object) -> list:
    """A default `type_name` value with the named members (any case) set."""
    t = struct_type(type_name)
    v = default_value(t)
    assert isinstance(v, list)
    for name, value in members.items():
        v[t.index[name.upper()]] = value
    return v


def new_control(**members: object) -> list:
    return new_struct("CONTROL", **members)
