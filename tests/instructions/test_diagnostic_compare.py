"""FBC and DDT (diagnostic_compare.py, decision 0184): bit numbers worked out by hand from the
arrays' values (bit n = bit n mod 32 of DINT n div 32)."""

from __future__ import annotations

from pathlib import Path

import pytest

from interpreter.instructions import diagnostic_compare as dc
from interpreter.semantics.types import BOOL, DINT
from interpreter.vm.context import ExecContext, MajorFault
from interpreter.vm.refs import ArrayRef
from tests.instructions.run_cli import trace
from tests.instructions.structs import new_control, struct_type

C = struct_type("CONTROL").index


def dints(*values: int, size: int | None = None) -> ArrayRef:
    v = [*values] + [0] * ((size or len(values)) - len(values))
    return ArrayRef(v, 0, DINT, (len(v),))


def ctl(**members: object) -> list:
    return new_control(**members)


def cg(c: list, *names: str) -> tuple[object, ...]:
    return tuple(c[C[n]] for n in names)


def run(fn, src, ref, res, cmp, rc, rung=True):  # type: ignore[no-untyped-def]
    fn(ExecContext(), rung, src, ref, res, cmp, None, None, rc)


def test_fbc_all_mismatches_through_run(tmp_path: Path) -> None:
    src = (
        "VAR src : ARRAY[0..1] OF DINT := [16#A0, 1]; ref : ARRAY[0..1] OF DINT;\n"
        "  res : ARRAY[0..9] OF DINT; c : CONTROL; r : CONTROL; k : DINT; END_VAR\n"
        "ADD(k,1,k);\n"
        "LES(k,3)FBC(src,ref,res,c,40,0,r,10,0);\n"
    )
    watch = ["res[0]", "res[1]", "res[2]", "c.POS", "c.DN", "c.FD", "c.EN", "r.POS", "ref[0]"]
    rows, report = trace(tmp_path, src, ".rll", 3, watch)
    # 16#A0 = bits 5 and 7 of element 0; element 1 = 1 is bit 32. Reference all 0: three
    # mismatches found in the first scan, all 40 bits compared -> DN, FD, result POS 3
    first = rows[0]
    assert [first[f"res[{i}]"] for i in range(3)] == ["5", "7", "32"]
    assert (first["c.POS"], first["c.DN"], first["c.FD"], first["r.POS"]) == ("40", "1", "1", "3")
    assert first["ref[0]"] == "0"  # FBC leaves the reference alone
    # rung held true (scan 2): nothing new; rung false (scan 3): EN, DN and FD cleared
    assert rows[1]["c.EN"] == "1" and rows[1]["r.POS"] == "3"
    assert (rows[2]["c.EN"], rows[2]["c.DN"], rows[2]["c.FD"]) == ("0", "0", "0")
    assert report["diagnostics"] == []


def test_ddt_reports_each_change_once() -> None:
    src, ref, res = dints(0b1010, 0), dints(0b0011, 0), dints(size=8)
    cmp, rc = ctl(LEN=8), ctl(LEN=8)
    run(dc.ddt, src, ref, res, cmp, rc)
    # 1010 vs 0011: bits 0 and 3 differ; DDT copies them into the reference -> 1010
    assert res.elements[:2] == [0, 3] and ref.elements[0] == 0b1010
    assert cg(cmp, "POS", "DN", "FD") == (8, 1, 1) and cg(rc, "POS") == (2,)
    run(dc.ddt, src, ref, res, cmp, rc, rung=False)
    src.elements[0] = 0b1000  # bit 1 drops
    run(dc.ddt, src, ref, res, cmp, rc)  # restart: positions cleared, only bit 1 is new
    assert res.elements[0] == 1 and cg(rc, "POS") == (1,) and ref.elements[0] == 0b1000
    run(dc.ddt, src, ref, res, cmp, rc, rung=False)
    run(dc.ddt, src, ref, res, cmp, rc)  # nothing changed: no mismatch, FD clear
    assert cg(cmp, "DN", "FD") == (1, 0) and cg(rc, "POS") == (0,)


def test_one_mismatch_at_a_time() -> None:
    src, ref, res = dints(0b10010001), dints(0), dints(size=4)
    cmp, rc = ctl(LEN=32, IN=1), ctl(LEN=4)
    run(dc.fbc, src, ref, res, cmp, rc)  # first mismatch: bit 0; POS past it
    assert res.elements[0] == 0 and cg(cmp, "POS", "FD", "DN") == (1, 1, 0)
    run(dc.fbc, src, ref, res, cmp, rc)  # rung still true: no further search
    assert cg(cmp, "POS") == (1,)
    run(dc.fbc, src, ref, res, cmp, rc, rung=False)
    run(dc.fbc, src, ref, res, cmp, rc)  # next transition: bit 4
    assert res.elements[1] == 4 and cg(cmp, "POS") == (5,)
    run(dc.fbc, src, ref, res, cmp, rc, rung=False)
    run(dc.fbc, src, ref, res, cmp, rc)  # bit 7
    run(dc.fbc, src, ref, res, cmp, rc, rung=False)
    run(dc.fbc, src, ref, res, cmp, rc)  # no more: the rest compared, DN, no FD
    assert res.elements[:3] == [0, 4, 7] and cg(cmp, "POS", "DN", "FD") == (32, 1, 0)


def test_full_result_stops_and_continues_after_the_next_transition() -> None:
    src, ref, res = dints(0b111), dints(0), dints(size=2)
    cmp, rc = ctl(LEN=3), ctl(LEN=2)
    run(dc.fbc, src, ref, res, cmp, rc)  # bits 0 and 1 fill the result: its DN, stop
    assert res.elements == [0, 1] and cg(rc, "POS", "DN") == (2, 1)
    assert cg(cmp, "POS", "DN", "FD") == (2, 0, 1)
    run(dc.fbc, src, ref, res, cmp, rc, rung=False)
    run(dc.fbc, src, ref, res, cmp, rc)  # the full result is emptied; bit 2 goes first
    assert res.elements == [2, 1] and cg(rc, "POS", "DN") == (1, 0)
    assert cg(cmp, "POS", "DN") == (3, 1)


def test_bool_arrays_and_errors() -> None:
    bsrc = ArrayRef([0, 1, 0, 1], 0, BOOL, (4,))
    bref = ArrayRef([0, 0, 0, 1], 0, BOOL, (4,))
    res = dints(size=4)
    cmp, rc = ctl(LEN=4), ctl(LEN=4)
    run(dc.ddt, bsrc, bref, res, cmp, rc)  # only element 1 differs
    assert res.elements[0] == 1 and bref.elements == [0, 1, 0, 1] and cg(rc, "POS") == (1,)
    cmp, rc = ctl(LEN=-1), ctl(LEN=4)
    run(dc.fbc, bsrc, bref, res, cmp, rc)  # negative length: ER, nothing searched
    assert cg(cmp, "ER", "DN") == (1, 0)
    run(dc.fbc, bsrc, bref, res, cmp, rc, rung=False)
    cmp[C["LEN"]] = 4
    run(dc.fbc, bsrc, bref, res, cmp, rc)  # ER stays until the program clears it
    assert cg(cmp, "ER", "DN") == (1, 0)
    cmp[C["ER"]] = 0
    run(dc.fbc, bsrc, bref, res, cmp, rc, rung=False)
    run(dc.fbc, bsrc, bref, res, cmp, rc)
    assert cg(cmp, "ER", "DN") == (0, 1)
    with pytest.raises(MajorFault) as e:  # 40 bits from a 1-DINT array
        run(dc.fbc, dints(0), dints(0), res, ctl(LEN=40), ctl(LEN=4))
    assert (e.value.type, e.value.code) == (4, 20)
