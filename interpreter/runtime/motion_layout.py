"""Where motion data lives inside tag storage: member positions, packed status words,
MOTION_INSTRUCTION control bits and the CAM_PROFILE element format.

Storage keeps every structure member separately (docs/decisions/0003); a BOOL member that
Logix packs into a DINT word (MotionStatus, AxisStatus, FLAGS, ...) is kept twice: as the
BOOL member and as its bit in the word. Everything here keeps the two in step.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache

import numpy as np

from stdlib import catalog

from ..motion import CamProfile
from ..semantics.types import StructType, TypeTable
from ..vm.values import f32, wrap


def struct_type(name: str) -> StructType:
    t = TypeTable().get(name)
    assert isinstance(t, StructType), name
    return t


@cache
def packed_words(type_name: str) -> tuple[tuple[int, tuple[tuple[int, int], ...]], ...]:
    """(word member index, ((bool member index, bit), ...)) for every packed word of a type.

    In the catalog a packed word is a DINT member followed by the BOOL members that carry
    a `bit` (MotionStatus then AccelStatus bit 0, DecelStatus bit 1, ...).
    """
    td = catalog().type(type_name)
    assert td is not None, type_name
    st = struct_type(type_name)
    out: list[tuple[int, tuple[tuple[int, int], ...]]] = []
    word: int | None = None
    bits: list[tuple[int, int]] = []
    for m in td.members:
        if m.type.upper() == "BOOL" and m.bit is not None and word is not None:
            bits.append((st.index[m.name.upper()], m.bit))
            continue
        if word is not None and bits:
            out.append((word, tuple(bits)))
        word, bits = (st.index[m.name.upper()], []) if m.type.upper() == "DINT" else (None, [])
    if word is not None and bits:
        out.append((word, tuple(bits)))
    return tuple(out)


def pack(value: list, word: int, bits: tuple[tuple[int, int], ...]) -> None:
    """Recompute a packed DINT word from its BOOL members."""
    w = 0
    for idx, bit in bits:
        if value[idx]:
            w |= 1 << bit
    value[word] = wrap(w, 32, True)


# ------------------------------------------------------------------ MOTION_INSTRUCTION
_MI = struct_type("MOTION_INSTRUCTION").index
EN, DN, ER, PC, IP, AC = _MI["EN"], _MI["DN"], _MI["ER"], _MI["PC"], _MI["IP"], _MI["AC"]
ACCEL, DECEL, ERR, EXERR, FLAGS = _MI["ACCEL"], _MI["DECEL"], _MI["ERR"], _MI["EXERR"], _MI["FLAGS"]
SEGMENT = _MI["SEGMENT"]
_MI_WORD = packed_words("MOTION_INSTRUCTION")[0]


def set_bits(ctl: list, **bits: int) -> None:
    """Write control bits by name (EN=1, IP=0, ...) and keep FLAGS in step."""
    for name, v in bits.items():
        ctl[_MI[name]] = 1 if v else 0
    pack(ctl, *_MI_WORD)


def set_error(ctl: list, err: int, exerr: int = 0) -> None:
    ctl[ERR] = wrap(int(err), 16, True)
    ctl[EXERR] = wrap(int(exerr), 8, True)
    set_bits(ctl, ER=1, DN=0, IP=0, PC=0)


# ------------------------------------------------------------------ axes
@dataclass(frozen=True, slots=True, eq=False)  # one cached instance per type: identity hash
class AxisLayout:
    """Member positions of an AXIS_* structure (all AXIS types share one member list)."""

    index: dict[str, int]  # upper-case member name -> position
    bits: dict[str, int]  # bit number of each packed BOOL member, by upper-case name

    @staticmethod
    @cache
    def of(type_name: str) -> AxisLayout:
        st = struct_type(type_name)
        bits = {}
        for _, members in packed_words(st.name):
            for idx, bit in members:
                bits[st.members[idx][0].upper()] = bit
        return AxisLayout(dict(st.index), bits)

    def get(self, value: list, name: str) -> float:
        return float(value[self.index[name.upper()]])


# ------------------------------------------------------------------ CAM_PROFILE
_CP = struct_type("CAM_PROFILE").index
CP_STATUS, CP_TYPE, CP_MASTER = _CP["STATUS"], _CP["TYPE"], _CP["MASTER"]
CP_C = (_CP["C0"], _CP["C1"], _CP["C2"], _CP["C3"])
_CAM = struct_type("CAM").index
CAM_MASTER, CAM_SLAVE, CAM_SEGMENT = _CAM["MASTER"], _CAM["SLAVE"], _CAM["SEGMENTTYPE"]

Signature = tuple[tuple[float, ...], ...]


def write_profile(elements: list, profile: CamProfile, users: int = 0) -> Signature:
    """Store a calculated profile in CAM_PROFILE elements (REAL members round to float32).

    Element i holds the master value of point i and the polynomial of segment i; the last
    point's element holds its master value and end position. Status: element [0] 2 + users,
    the other points 2, unused elements 0 (so the stored length can be read back).
    """
    n = len(profile.x)
    for i in range(n):
        e = elements[i]
        e[CP_STATUS] = 2
        e[CP_MASTER] = f32(float(profile.x[i]))
        if i < n - 1:
            e[CP_TYPE] = int(profile.segment_type[i])
            for k in range(4):
                e[CP_C[k]] = f32(float(profile.coef[i, k]))
        else:
            e[CP_TYPE] = 0
            e[CP_C[0]] = f32(profile.p_end)
            for k in (1, 2, 3):
                e[CP_C[k]] = 0.0
    elements[0][CP_STATUS] = 2 + users
    for e in elements[n:]:
        e[CP_STATUS] = 0
    return signature(elements, n)


def stored_length(elements: list) -> int:
    """Points of the stored profile: element [0] calculated, then every calculated element."""
    if not elements or elements[0][CP_STATUS] < 2:
        return 0
    n = 1
    while n < len(elements) and elements[n][CP_STATUS] != 0:
        n += 1
    return n


def signature(elements: list, n: int) -> Signature:
    idx = (CP_TYPE, CP_MASTER, *CP_C)
    return tuple(tuple(float(elements[i][k]) for k in idx) for i in range(n))


def read_profile(elements: list, n: int) -> CamProfile | None:
    """Rebuild a profile from stored elements (None when they do not form one)."""
    x = np.array([float(elements[i][CP_MASTER]) for i in range(n)])
    if n < 2 or not np.all(np.isfinite(x)) or np.any(np.diff(x) <= 0):
        return None
    coef = np.array([[float(elements[i][c]) for c in CP_C] for i in range(n - 1)])
    seg = np.array([int(elements[i][CP_TYPE]) for i in range(n - 1)])
    if not np.all(np.isfinite(coef)) or np.any((seg != 0) & (seg != 1)):
        return None
    return CamProfile(x=x, coef=coef, segment_type=seg)
