"""The MOTION_INSTRUCTION handshake shared by every motion adapter (seed execution tables):
ladder false rung clears EN only after DN or ER; a true rung (and every ST execution)
sets EN and clears the result bits; FLAGS carries the bits at their Logix positions."""

from __future__ import annotations

from interpreter.instructions.motion_common import begin, clear_on_prescan
from interpreter.runtime.motion_layout import struct_type
from interpreter.vm.values import default_value

MI = struct_type("MOTION_INSTRUCTION")
IX = MI.index


def _ctl(**bits: int) -> list:
    v = default_value(MI)
    assert isinstance(v, list)
    for name, on in bits.items():
        v[IX[name]] = on
    return v


def test_false_rung_clears_en_only_after_done_or_error() -> None:
    waiting = _ctl(EN=1)  # e.g. MSO on a drive, DN comes at the next update
    assert begin(waiting, False) is False and waiting[IX["EN"]] == 1
    done = _ctl(EN=1, DN=1, IP=1)
    assert begin(done, False) is False
    assert (done[IX["EN"]], done[IX["DN"]], done[IX["IP"]]) == (0, 1, 1)  # only EN changes
    failed = _ctl(EN=1, ER=1)
    begin(failed, False)
    assert failed[IX["EN"]] == 0


def test_true_rung_sets_en_and_clears_the_results() -> None:
    c = _ctl(DN=1, ER=1, PC=1, IP=1, AC=1, ACCEL=1, DECEL=1)
    c[IX["ERR"]], c[IX["EXERR"]] = 13, 4
    assert begin(c, True) is True
    got = {
        n: c[IX[n]] for n in ("EN", "DN", "ER", "PC", "IP", "AC", "ACCEL", "DECEL", "ERR", "EXERR")
    }
    assert got == {
        "EN": 1,
        "DN": 0,
        "ER": 0,
        "PC": 0,
        "IP": 0,
        "AC": 0,
        "ACCEL": 0,
        "DECEL": 0,
        "ERR": 0,
        "EXERR": 0,
    }
    # FLAGS: EN is bit 31 of a DINT, so the word is negative: -2**31
    assert c[IX["FLAGS"]] == -(2**31)


def test_flags_word_follows_the_bits() -> None:
    from interpreter.runtime.motion_layout import set_bits

    c = _ctl()
    set_bits(c, EN=1, DN=1, IP=1, AC=1, DECEL=1)
    # bits 31, 29, 26, 23, 2 -> 0xA4800004 as a signed DINT
    assert c[IX["FLAGS"]] == 0xA4800004 - 2**32
    clear_on_prescan(c)  # EN DN ER IP cleared, the others kept
    assert c[IX["FLAGS"]] == (1 << 23) | (1 << 2)
