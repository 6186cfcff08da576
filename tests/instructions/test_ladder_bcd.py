"""TOD (TO_BCD) and FRD (BCD_TO): ladder boxes and expression forms (1756-RM003, decision 0063)."""

from __future__ import annotations

from interpreter.instructions import ladder_bcd as bcd
from interpreter.semantics.types import DINT, INT, SINT
from interpreter.vm.context import ExecContext
from interpreter.vm.refs import Ref


def _dest(t, value: int = 0) -> Ref:  # noqa: ANN001
    return Ref([value], 0, t)


def _flags(ctx: ExecContext) -> tuple[int, int, int]:
    return ctx.status["N"], ctx.status["Z"], ctx.status["V"]


def _faults(ctx: ExecContext) -> int:
    return sum(f.count for f in ctx.minor_faults.values() if (f.type, f.code) == (4, 4))


def test_tod_writes_decimal_digits_as_nibbles() -> None:
    ctx, d = ExecContext(), _dest(DINT)
    bcd.tod(ctx, True, 1234, d)
    assert d.get() == 0x1234 == 4660  # digits 1,2,3,4 -> 0001 0010 0011 0100
    assert _flags(ctx) == (0, 0, 0)


def test_tod_largest_source_is_a_negative_dint_without_overflow() -> None:
    ctx, d = ExecContext(), _dest(DINT)
    bcd.tod(ctx, True, 99_999_999, d)
    # 16#9999_9999 = 2576980377; as a DINT bit pattern 2576980377 - 2**32 = -1717986919
    assert d.get() == -1717986919
    assert _flags(ctx) == (1, 0, 0) and _faults(ctx) == 0


def test_tod_negative_source_clears_dest_with_fault() -> None:
    ctx, d = ExecContext(), _dest(DINT, 77)
    bcd.tod(ctx, True, -5, d)
    assert d.get() == 0 and _flags(ctx) == (0, 1, 1) and _faults(ctx) == 1


def test_tod_source_above_eight_digits_leaves_dest() -> None:
    ctx, d = ExecContext(), _dest(DINT, 77)
    bcd.tod(ctx, True, 100_000_000, d)
    assert d.get() == 77 and ctx.status["V"] == 1 and _faults(ctx) == 1


def test_tod_pattern_wider_than_dest_overflows() -> None:
    ctx, d = ExecContext(), _dest(INT)
    bcd.tod(ctx, True, 12345, d)
    # 16#1_2345 does not fit 16 bits: low word 16#2345 = 9029 kept, S:V set
    assert d.get() == 0x2345 and ctx.status["V"] == 1
    ctx, d = ExecContext(), _dest(SINT)
    bcd.tod(ctx, True, 99, d)
    assert d.get() == -103 and ctx.status["V"] == 0  # 16#99 = 153 -> SINT pattern 153 - 256


def test_tod_false_rung_does_nothing() -> None:
    ctx, d = ExecContext(), _dest(DINT, 5)
    bcd.tod(ctx, False, 12, d)
    assert d.get() == 5


def test_frd_reads_nibbles_as_digits() -> None:
    ctx, d = ExecContext(), _dest(DINT)
    bcd.frd(ctx, True, 0x1234, d)
    assert d.get() == 1234 and _flags(ctx) == (0, 0, 0)
    ctx, d = ExecContext(), _dest(DINT)
    bcd.frd(ctx, True, -1717986919, d)  # the DINT holding 16#9999_9999
    assert d.get() == 99_999_999


def test_frd_rejects_a_non_bcd_nibble() -> None:
    ctx, d = ExecContext(), _dest(DINT, 3)
    bcd.frd(ctx, True, 0x12A4, d)  # nibble A is no decimal digit
    assert d.get() == 3 and ctx.status["V"] == 1 and _faults(ctx) == 1


def test_expression_forms() -> None:
    ctx = ExecContext()
    assert bcd.tod_fn(ctx, True, 12) == 0x12 == 18
    assert bcd.frd_fn(ctx, True, 0x99) == 99
    assert not ctx.minor_faults
    assert bcd.frd_fn(ctx, True, 0xF) == 0 and _faults(ctx) == 1


def test_tod_frd_and_their_v36_names_in_a_ladder_routine(st) -> None:  # noqa: ANN001
    src = """
    VAR a, b, c, d, e : DINT; END_VAR
    MOV(1234,a) TOD(a,b) FRD(b,c);
    TO_BCD(56,d) BCD_TO(d,e);
    CPT(a, BCD_TO(16#99) + TOD(12));
    """
    r = st.run(src, "a", "b", "c", "d", "e", name="main.rll")
    assert r.code == 0, r.err
    # b = 16#1234 = 4660, c = 1234, d = 16#56 = 86, e = 56, a = 99 + 16#12 (18) = 117
    assert r.tags == {"a": 117, "b": 4660, "c": 1234, "d": 86, "e": 56}


# ------------------------------------------------------------------ DTR (special chapter)
def test_dtr_is_true_once_per_change_of_the_masked_bits() -> None:
    from interpreter.instructions import ladder_dtr

    ctx, ref = ExecContext(), _dest(DINT)
    ladder_dtr.dtr_prescan(ctx, True, 0x1234, 0x00FF, ref)
    assert ref.get() == 0x34  # prescan: Reference = 16#1234 AND 16#00FF = 16#34
    outs = []
    for source in (0x1234, 0x5634, 0x5635, 0x5635):
        outs.append(ladder_dtr.dtr(ctx, True, source, 0x00FF, ref))
    # masked: 34 (same), 34 (only a blocked bit changed), 35 (changed), 35 (same)
    assert outs == [False, False, True, False] and ref.get() == 0x35
    assert ladder_dtr.dtr(ctx, False, 0x00AB, 0x00FF, ref) is False
    assert ref.get() == 0xAB  # false rung: Reference follows the masked Source silently


def test_dtr_in_a_ladder_routine_counts_changes(st) -> None:  # noqa: ANN001
    src = """
    VAR s : DINT; r : DINT; hits : DINT; END_VAR
    ADD(s,1,s);
    DTR(s,16#FFFC,r)ADD(hits,1,hits);
    """
    # s = 1..12; masked by 16#FFFC (low two bits dropped): 0,0,0,4,4,4,4,8,8,8,8,12.
    # Prescan left r = 0, so the rung is true at s = 4, 8 and 12: three hits.
    assert st.run(src, "hits", "r", scans=12, name="main.rll").tags == {"hits": 3, "r": 12}
