"""ONS / OSR / OSF called directly with BOOL Refs and a BitRef, rung by rung."""

from __future__ import annotations

from interpreter.instructions import ladder_bits as lb
from interpreter.semantics.types import BOOL, DINT
from interpreter.vm.context import ExecContext
from interpreter.vm.refs import BitRef, Ref


def _bit() -> Ref:
    return Ref([0], 0, BOOL)


def test_ons_pulses_once_per_rising_edge_and_not_after_prescan() -> None:
    ctx, storage = ExecContext(), _bit()
    lb.ons_prescan(ctx, True, storage)
    assert storage.get() == 1  # prescan sets the storage bit
    rungs = [True, True, False, True, True, False, False, True]
    outs = [lb.ons(ctx, r, storage) for r in rungs]
    # rung already true at start-up: no pulse; the pulse comes one scan after each 0 -> 1
    assert outs == [False, False, False, True, False, False, False, True]
    assert storage.get() == 1


def test_ons_storage_in_a_dint_bit() -> None:
    word = [0b1000_0000]
    storage = BitRef(word, 0, 3, DINT)  # d.3
    ctx = ExecContext()
    assert lb.ons(ctx, True, storage) is True
    assert word == [0b1000_1000]  # bit 3 set, bit 7 untouched
    assert lb.ons(ctx, False, storage) is False
    assert word == [0b1000_0000]


def test_osr_output_true_for_one_scan_and_rung_passes_on() -> None:
    ctx, storage, out = ExecContext(), _bit(), _bit()
    out.set(1)
    lb.osr_prescan(ctx, True, storage, out)
    assert (storage.get(), out.get()) == (1, 0)
    seen = []
    for r in [True, False, True, True, True, False]:
        assert lb.osr(ctx, r, storage, out) is None  # OSR does not change the rung
        seen.append((storage.get(), out.get()))
    # T after prescan: no pulse; F clears both; T: pulse; held T: output back to 0
    assert seen == [(1, 0), (0, 0), (1, 1), (1, 0), (1, 0), (0, 0)]


def test_osf_output_true_for_one_scan_after_the_rung_falls() -> None:
    ctx, storage, out = ExecContext(), _bit(), _bit()
    storage.set(1)
    lb.osf_prescan(ctx, True, storage, out)
    assert (storage.get(), out.get()) == (0, 0)  # prescan clears the storage bit
    seen = []
    for r in [False, True, False, False, True, False]:
        lb.osf(ctx, r, storage, out)
        seen.append(out.get())
    # F at start-up: no pulse (storage was cleared); T then F: pulse; held F: 0
    assert seen == [0, 0, 1, 0, 0, 1]
