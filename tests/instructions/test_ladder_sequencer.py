"""SQI / SQO / SQL called directly on an ArrayRef, a CONTROL and Refs."""

from __future__ import annotations

import pytest

from interpreter.instructions import ladder_sequencer as sq
from interpreter.instructions.ladder_timers_counters import K_LEN, K_POS
from interpreter.semantics.types import DINT
from interpreter.vm.context import ExecContext, MajorFault
from interpreter.vm.refs import ArrayRef, Ref
from tests.instructions.structs import new_control


def _arr(values: list) -> ArrayRef:
    return ArrayRef(values, 0, DINT, (len(values),))


def test_sqo_steps_on_each_rising_edge_and_wraps_to_step_1() -> None:
    steps = _arr([0, 0x01, 0x02, 0x04])  # step 0 is the start-up position
    ctl, out = new_control(LEN=3), Ref([0xF0], 0, DINT)
    ctx = ExecContext()
    seen = []
    for rung in [True, True, False, True, False, True, False, True]:
        sq.sqo(ctx, rung, steps, 0x0F, out, ctl)
        seen.append((ctl[K_POS], out.get(), ctl[sq.DN]))
    # mask 16#0F keeps the high nibble 16#F0 and writes the step's low nibble
    assert seen == [
        (1, 0xF1, 0),
        (1, 0xF1, 0),  # held true: same step rewritten
        (1, 0xF1, 0),  # false: no change
        (2, 0xF2, 0),
        (2, 0xF2, 0),
        (3, 0xF4, 1),  # POS = LEN: DN
        (3, 0xF4, 1),
        (1, 0xF1, 0),  # POS >= LEN wraps to 1
    ]


def test_sqo_prescan_keeps_a_true_rung_from_stepping() -> None:
    steps, ctl, out = _arr([0, 7]), new_control(), Ref([0], 0, DINT)
    sq.sqo_prescan(ExecContext(), True, steps, -1, out, ctl, 1, 0)
    assert (ctl[K_LEN], ctl[K_POS], ctl[sq.EN]) == (1, 0, 1)
    sq.sqo(ExecContext(), True, steps, -1, out, ctl)
    # EN set by prescan: no step; the current step (0) is written through the mask
    assert (ctl[K_POS], out.get()) == (0, 0)


def test_sqo_invalid_length_sets_er_and_step_past_array_faults() -> None:
    ctl, out = new_control(LEN=0), Ref([5], 0, DINT)
    sq.sqo(ExecContext(), True, _arr([0, 1]), -1, out, ctl)
    assert ctl[sq.ER] == 1 and out.get() == 5
    with pytest.raises(MajorFault) as e:
        sq.sqo(
            ExecContext(), True, _arr([0, 1]), -1, out, new_control(LEN=3, POS=1)
        )  # step 2 of [0, 1]
    assert (e.value.type, e.value.code) == (4, 20)


def test_sqi_compares_masked_source_with_the_current_step() -> None:
    steps, ctx = _arr([0, 3, 5]), ExecContext()
    ctl = new_control(LEN=2, POS=2)
    assert sq.sqi(ctx, True, steps, 0xFF, 5, ctl) is True
    assert sq.sqi(ctx, True, steps, 0xFF, 4, ctl) is False
    # mask 16#FE ignores bit 0: 4 AND 16#FE = 4 = 5 AND 16#FE
    assert sq.sqi(ctx, True, steps, 0xFE, 4, ctl) is True
    assert sq.sqi(ctx, False, steps, 0xFF, 5, ctl) is False
    ctl[K_POS] = 3  # POS > LEN
    assert sq.sqi(ctx, True, steps, 0xFF, 5, ctl) is False and ctl[sq.ER] == 1


def test_sql_loads_the_step_every_true_scan() -> None:
    table, ctl = [0, 0, 0, 0], new_control(LEN=3)
    ctx = ExecContext()
    sq.sql(ctx, True, _arr(table), 7, ctl)
    assert table == [0, 7, 0, 0] and ctl[K_POS] == 1
    sq.sql(ctx, True, _arr(table), 8, ctl)
    assert table == [0, 8, 0, 0]  # still step 1: reloaded while the rung stays true
    sq.sql(ctx, False, _arr(table), 9, ctl)
    sq.sql(ctx, True, _arr(table), 9, ctl)
    assert table == [0, 8, 9, 0] and ctl[K_POS] == 2
