"""The motion core's own copies of catalog facts must equal the catalog (facts stated once).

The core keeps IntEnums for the operand values it branches on (mypy sees their members) and
an IntEnum of the error numbers it reports; the catalog (stdlib/instructions/*.toml,
stdlib/motion_errors.toml, stdlib/types/motion.toml) is where those facts are stated. The
MotionStatus bit numbers are read from the catalog, so only their use is checked here.
"""

from __future__ import annotations

from enum import IntEnum

import pytest

from interpreter.motion import enums, poscam
from interpreter.motion.errors import MotionError
from interpreter.motion.group import STATUS_BITS, MotionGroup
from interpreter.motion.paths import Termination
from stdlib import catalog

# core enumeration -> catalog enumeration it mirrors
MIRRORS: list[tuple[type[IntEnum], str]] = [
    (enums.ProfileShape, "Profile"),
    (enums.MoveType, "MoveType"),
    (enums.MergeSpeed, "MergeSpeed"),
    (enums.StopType, "StopType"),
    (enums.CamDirection, "CamDirection"),
    (enums.CamDirection, "GearDirection"),
    (enums.ExecutionMode, "ExecutionMode"),
    (enums.ExecutionSchedule, "ExecutionSchedule"),
    (enums.LockDirection, "LockDirection"),
    (enums.InstructionMode, "InstructionMode"),
    (enums.MotionType, "MotionType"),
    (enums.MasterReference, "PositionReference"),
    (enums.HomeMode, "HomeMode"),
    (enums.HomeSequence, "HomeSequence"),
    (enums.MergeMode, "CoordMerge"),
    (Termination, "TerminationType"),
    (poscam.CamStartMode, "StartMode"),
    (poscam.CamInError, "MC_ErrorID"),
    (poscam.PositionCamMode, "PositionCamExecutionMode"),
    (poscam.PositionCamSchedule, "PositionCamExecutionSchedule"),
    (poscam.CamMasterDirection, "CamMasterDirection"),
]

# words the core's member names leave out of the catalog text ("Time Driven Mode")
_FILLER = {"mode", "only", "shape"}


def _words(text: str) -> set[str]:
    return {w for w in text.lower().replace("-", " ").replace("_", " ").split()} - _FILLER


@pytest.mark.parametrize(("core", "name"), MIRRORS, ids=[f"{c.__name__}-{n}" for c, n in MIRRORS])
def test_core_enumeration_equals_catalog(core: type[IntEnum], name: str) -> None:
    cat = catalog().enum(name)
    by_value: dict[int, list[str]] = {}
    for v in cat.values:
        by_value.setdefault(v.value, []).append(v.text)
    for member in core:
        texts = by_value.get(int(member))
        assert texts is not None, f"{core.__name__}.{member.name} = {int(member)} not in {name}"
        # the member is named after one of the catalog texts for its value
        assert any(_words(member.name) <= _words(t) for t in texts), (
            f"{core.__name__}.{member.name} = {int(member)}: catalog {name} says {texts}"
        )
    # the core may simulate a prefix of an enumeration (MoveType: no rotary / offset moves)
    # but never skips a value in between
    values = sorted(int(m) for m in core)
    assert values == list(range(len(values)))


def test_core_error_numbers_are_catalog_errors() -> None:
    errors = catalog().motion_errors
    for e in MotionError:
        if e == MotionError.OK:
            continue
        assert e.value in errors, f"{e.name} = {e.value} not in stdlib/motion_errors.toml"
        assert _words(e.name) <= _words(errors[e.value].name), (
            f"{e.name} = {e.value}: the catalog calls it {errors[e.value].name!r}"
        )


def test_motion_status_word_uses_catalog_bits() -> None:
    # stdlib/types/motion.toml: AccelStatus bit 0, TimeCamStatus bit 9, MaximumSpeedExceeded 27
    assert STATUS_BITS["AccelStatus"] == 0
    assert STATUS_BITS["TimeCamStatus"] == 9
    assert STATUS_BITS["MaximumSpeedExceeded"] == 27
    g = MotionGroup(0.001)
    g.add_axis("a")
    g.status["TimeCamStatus"][0] = True
    g.status["MaximumSpeedExceeded"][0] = True
    # 2**9 + 2**27 = 512 + 134217728
    assert int(g.motion_status_word()[0]) == 134_218_240
