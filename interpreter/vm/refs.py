"""References handed to instruction implementations for operands they write or walk."""

from __future__ import annotations

from dataclasses import dataclass

from ..semantics.types import DataType, Elementary
from .values import convert, wrap


@dataclass(slots=True)
class Ref:
    """An elementary storage location: `container[key]`, converted on write."""

    container: list
    key: int
    type: Elementary

    def get(self) -> int | float:
        return self.container[self.key]  # type: ignore[no-any-return]

    def set(self, value: object) -> None:
        self.container[self.key] = convert(value, self.type)


@dataclass(slots=True)
class BitRef:
    """One bit of an integer location (`d.5`) or a BOOL array element."""

    container: list
    key: int
    bit: int
    type: Elementary

    def get(self) -> int:
        return (self.container[self.key] >> self.bit) & 1  # type: ignore[no-any-return]

    def set(self, value: object) -> None:
        v = self.container[self.key]
        v = v | (1 << self.bit) if value else v & ~(1 << self.bit)
        self.container[self.key] = wrap(v, self.type.bits, self.type.signed)


@dataclass(slots=True)
class ArrayRef:
    """An array operand from a start element: `arr[5]` -> (arr, 5); whole array -> (arr, 0).

    `elements` is the flat element list; `type` the element type; `dims` the array sizes.
    """

    elements: list
    start: int
    type: DataType
    dims: tuple[int, ...]

    def __len__(self) -> int:
        return len(self.elements) - self.start

    def get(self, i: int) -> object:
        return self.elements[self.start + i]

    def set(self, i: int, value: object) -> None:
        assert isinstance(self.type, Elementary)
        self.elements[self.start + i] = convert(value, self.type)
