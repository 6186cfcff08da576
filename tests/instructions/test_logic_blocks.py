"""BAND BOR BXOR BNOT MVMT BTDT DFF JKFF RESD SETD on their instance structures, with
values worked by hand from the documented truth tables and bit layouts (1756-RM003)."""

from __future__ import annotations

from interpreter.instructions import logic_blocks as lb
from interpreter.vm.context import ExecContext
from tests.instructions.structs import new_struct, struct_type


def _run(fn, type_name: str, **members: object) -> tuple[list, dict[str, int]]:  # noqa: ANN001
    v = new_struct(type_name, **members)
    fn(ExecContext(), True, v)
    return v, struct_type(type_name).index


def test_band_unwired_inputs_default_true() -> None:
    v, ix = _run(lb.band, "FBD_BOOLEAN_AND")
    assert v[ix["OUT"]] == 1  # all eight inputs default to 1
    v, ix = _run(lb.band, "FBD_BOOLEAN_AND", In5=0)
    assert v[ix["OUT"]] == 0


def test_bor_bxor_bnot_truth_tables() -> None:
    assert _run(lb.bor, "FBD_BOOLEAN_OR")[0][struct_type("FBD_BOOLEAN_OR").index["OUT"]] == 0
    v, ix = _run(lb.bor, "FBD_BOOLEAN_OR", In8=1)
    assert v[ix["OUT"]] == 1
    table = {(0, 0): 0, (0, 1): 1, (1, 0): 1, (1, 1): 0}
    for (a, b), want in table.items():
        v, ix = _run(lb.bxor, "FBD_BOOLEAN_XOR", In1=a, In2=b)
        assert v[ix["OUT"]] == want, (a, b)
    v, ix = _run(lb.bnot, "FBD_BOOLEAN_NOT", In=1)
    assert v[ix["OUT"]] == 0 and v[ix["ENABLEOUT"]] == 1


def test_mvmt_takes_masked_bits_from_source() -> None:
    v, ix = _run(lb.mvmt, "FBD_MASKED_MOVE", Source=0xFF, Mask=0x0F, Target=0x100)
    # (0xFF & 0x0F) | (0x100 & ~0x0F) = 0x00F | 0x100 = 0x10F = 271
    assert v[ix["DEST"]] == 271
    v, ix = _run(lb.mvmt, "FBD_MASKED_MOVE", Source=-1, Mask=-(2**31), Target=0)
    # only bit 31 taken from Source: 16#8000_0000 as a DINT = -2147483648
    assert v[ix["DEST"]] == -(2**31)


def test_btdt_moves_a_field() -> None:
    # Source 16#00F0: bits 4..7 set. SourceBit 4, Length 4 -> field 0b1111, placed at DestBit 8
    # into Target 16#0001: 16#0F01 = 3841
    v, ix = _run(
        lb.btdt, "FBD_BIT_FIELD_DISTRIBUTE", Source=0xF0, SourceBit=4, Length=4, DestBit=8, Target=1
    )
    assert v[ix["DEST"]] == 0x0F01
    # DestBit 30, Length 4: only bits 30 and 31 fit -> 16#C000_0000 = -1073741824
    v, ix = _run(
        lb.btdt, "FBD_BIT_FIELD_DISTRIBUTE", Source=0xF, SourceBit=0, Length=4, DestBit=30, Target=0
    )
    assert v[ix["DEST"]] == -(2**30)


def test_dff_copies_d_on_rising_clock_only() -> None:
    ix = struct_type("FLIP_FLOP_D").index
    v = new_struct("FLIP_FLOP_D", D=1)
    ctx = ExecContext()
    lb.dff(ctx, True, v)
    assert (v[ix["Q"]], v[ix["QNOT"]]) == (0, 1)  # no clock edge yet
    v[ix["CLOCK"]] = 1
    lb.dff(ctx, True, v)
    assert (v[ix["Q"]], v[ix["QNOT"]]) == (1, 0)  # rising edge: Q = D = 1
    v[ix["D"]] = 0
    lb.dff(ctx, True, v)
    assert v[ix["Q"]] == 1  # Clock still high, no new edge: Q kept
    v[ix["CLEAR"]] = 1
    lb.dff(ctx, True, v)
    assert (v[ix["Q"]], v[ix["QNOT"]]) == (0, 1)  # Clear forces Q false


def test_jkff_toggles_on_each_rising_clock() -> None:
    ix = struct_type("FLIP_FLOP_JK").index
    v = new_struct("FLIP_FLOP_JK")
    ctx = ExecContext()
    qs = []
    for clock in (1, 0, 1, 1, 0, 1):
        v[ix["CLOCK"]] = clock
        lb.jkff(ctx, True, v)
        qs.append(v[ix["Q"]])
    # rising edges at executions 1, 3 and 6: Q 1, 1, 0, 0, 0, 1
    assert qs == [1, 1, 0, 0, 0, 1]


def test_resd_and_setd_dominance() -> None:
    for fn, tname, both in ((lb.resd, "DOMINANT_RESET", 0), (lb.setd, "DOMINANT_SET", 1)):
        ix = struct_type(tname).index
        v = new_struct(tname, Set=1)
        fn(ExecContext(), True, v)
        assert (v[ix["OUT"]], v[ix["OUTNOT"]]) == (1, 0)
        v[ix["SET"]] = 0
        fn(ExecContext(), True, v)
        assert v[ix["OUT"]] == 1  # latched with neither input
        v[ix["SET"]] = v[ix["RESET"]] = 1
        fn(ExecContext(), True, v)
        assert v[ix["OUT"]] == both, tname  # reset wins in RESD, set wins in SETD
