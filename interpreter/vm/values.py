"""Runtime value model: how tag values are held and converted (SPEC 3.3).

Elementary values are Python ints (BOOL as 0/1) and floats (REAL always float32-exact).
A structure is a Python list of member values in member order; an array is a flat Python
list of elements (row-major). STRING is a structure [LEN, DATA(list of 82 SINT)].
"""

from __future__ import annotations

import math
import struct
from array import array

from ..semantics.types import (
    BOOL,
    ArrayType,
    DataType,
    Elementary,
    Kind,
    StructType,
)

_F32 = array("f", [0.0])


def f32(x: float) -> float:
    """Round to IEEE single precision (overflow gives +-inf, as the controller)."""
    _F32[0] = x
    return _F32[0]


def wrap(v: int, bits: int, signed: bool) -> int:
    mask = (1 << bits) - 1
    if signed:
        half = 1 << (bits - 1)
        return ((v + half) & mask) - half
    return v & mask


def real_mod(a: float, b: float) -> float:
    """REAL `a MOD b` = a - TRUNC(a / b) * b, with IEEE fmod's answers where that formula has none:
    NaN for b = 0 or an infinite or NaN operand, and a itself for a finite a MOD +-inf."""
    q = a / b if b != 0.0 else math.nan
    if not math.isfinite(q):
        return math.nan
    if math.isinf(b):
        return a
    return a - math.trunc(q) * b


def real_to_int(x: float) -> int:
    """REAL -> integer: round to nearest, ties to even (Python's round does exactly that)."""
    if math.isnan(x):
        return 0
    if math.isinf(x):
        return (1 << 63) - 1 if x > 0 else -(1 << 63)
    return round(x)


def convert(v: object, t: Elementary) -> int | float:
    """Convert any elementary value for storage in type `t`."""
    if t.kind is Kind.REAL:
        x = float(v)  # type: ignore[arg-type]
        return f32(x) if t.bits == 32 else x
    if t.kind is Kind.BOOL:
        return 1 if v else 0
    if isinstance(v, float):
        v = real_to_int(v)
    return wrap(int(v), t.bits, t.signed)  # type: ignore[call-overload]


def default_value(t: DataType, init: object = None) -> object:
    """A fresh value of type `t` (structures and arrays as new lists)."""
    if isinstance(t, Elementary):
        return 0.0 if t.kind is Kind.REAL else 0
    if isinstance(t, ArrayType):
        return [default_value(t.elem) for _ in range(t.size)]
    values: list[object] = []
    for name, mt in t.members:
        d = t.defaults.get(name.upper())
        if d is not None and isinstance(mt, Elementary):
            values.append(convert(d, mt))
        else:
            values.append(default_value(mt))
    return values


def copy_value(v: object) -> object:
    if isinstance(v, list):
        return [copy_value(x) for x in v]
    return v


# ------------------------------------------------------------------ strings
def string_text(s: list) -> bytes:
    """Bytes of a STRING value (LEN characters of DATA)."""
    n = max(0, min(int(s[0]), len(s[1])))
    return bytes(b & 0xFF for b in s[1][:n])


def set_string(s: list, data: bytes) -> None:
    cap = len(s[1])
    data = data[:cap]
    s[0] = len(data)
    s[1][: len(data)] = [wrap(b, 8, True) for b in data]
    for i in range(len(data), cap):
        s[1][i] = 0


# ------------------------------------------------------------------ bytes view (COP/CPS)
_FMT = {
    ("int", 8, True): "b",
    ("int", 8, False): "B",
    ("int", 16, True): "h",
    ("int", 16, False): "H",
    ("int", 32, True): "i",
    ("int", 32, False): "I",
    ("int", 64, True): "q",
    ("int", 64, False): "Q",
    ("real", 32, True): "f",
    ("real", 64, True): "d",
}


def byte_size(t: DataType) -> int:
    """Size in bytes as Logix lays the type out (BOOL members occupy one byte here)."""
    if isinstance(t, Elementary):
        return 1 if t is BOOL else t.bits // 8
    if isinstance(t, ArrayType):
        if t.elem is BOOL:
            return ((t.size + 31) // 32) * 4
        return byte_size(t.elem) * t.size
    return sum(byte_size(mt) for _, mt in t.members)


def to_bytes(v: object, t: DataType) -> bytes:
    if isinstance(t, Elementary):
        if t is BOOL:
            return bytes([1 if v else 0])
        return struct.pack("<" + _FMT[(t.kind.value, t.bits, t.signed)], v)
    if isinstance(t, ArrayType):
        assert isinstance(v, list)
        if t.elem is BOOL:
            out = bytearray(byte_size(t))
            for i, bit in enumerate(v):
                if bit:
                    out[i // 8] |= 1 << (i % 8)
            return bytes(out)
        return b"".join(to_bytes(x, t.elem) for x in v)
    assert isinstance(t, StructType) and isinstance(v, list)
    return b"".join(to_bytes(x, mt) for x, (_, mt) in zip(v, t.members, strict=True))


def from_bytes(data: bytes, t: DataType) -> object:
    if isinstance(t, Elementary):
        if t is BOOL:
            return 1 if data[0] else 0
        return struct.unpack("<" + _FMT[(t.kind.value, t.bits, t.signed)], data[: t.bits // 8])[0]
    if isinstance(t, ArrayType):
        if t.elem is BOOL:
            return [(data[i // 8] >> (i % 8)) & 1 for i in range(t.size)]
        size = byte_size(t.elem)
        return [from_bytes(data[i * size : (i + 1) * size], t.elem) for i in range(t.size)]
    assert isinstance(t, StructType)
    out, pos = [], 0
    for _, mt in t.members:
        size = byte_size(mt)
        out.append(from_bytes(data[pos : pos + size], mt))
        pos += size
    return out
