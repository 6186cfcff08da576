"""MAVE and MSTD (statistical_blocks.py, decision 0179), expected values by hand.

The storage array is a shift register, newest sample in element 0; the first execution
after prescan fills the N samples with In. MSTD's Out is the sample standard deviation
sqrt(sum((x - mean)^2) / (N - 1)).
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from interpreter.instructions import statistical_blocks as sb
from interpreter.semantics.types import REAL
from interpreter.vm.context import ExecContext
from interpreter.vm.refs import ArrayRef
from tests.instructions.run_cli import trace
from tests.instructions.structs import new_struct, struct_type

AV = struct_type("MOVING_AVERAGE").index
SD = struct_type("MOVING_STD_DEV").index


def arr(*values: float, size: int = 10) -> ArrayRef:
    v = [*values] + [0.0] * (size - len(values))
    return ArrayRef(v, 0, REAL, (size,))


def test_average_and_std_dev_of_a_ramp_through_run(tmp_path: Path) -> None:
    src = (
        "VAR m : MOVING_AVERAGE; d : MOVING_STD_DEV; st : ARRAY[0..9] OF REAL;\n"
        "  w : ARRAY[0..9] OF REAL; sd : ARRAY[0..9] OF REAL; x : REAL; END_VAR\n"
        "x := x + 1.0;\n"
        "m.In := x; m.NumberOfSamples := 4; m.SampleEnable := 1; MAVE(m, st, w);\n"
        "d.In := x; d.NumberOfSamples := 4; d.SampleEnable := 1; MSTD(d, sd);\n"
    )
    watch = ["m.Out", "d.Average", "d.Out", "st[0]", "st[3]"]
    rows, report = trace(tmp_path, src, ".st", 6, watch)
    # In = 1, 2, 3, ... The first execution fills 4 samples with 1; then
    #   [2 1 1 1] mean 1.25, squares .5625 + 3 x .0625 = .75, / 3 -> sd .5
    #   [3 2 1 1] mean 1.75, squares 1.5625 + .0625 + 2 x .5625 = 2.75, / 3 -> sd .957427
    #   [k k-1 k-2 k-3] mean k - 1.5, squares 2.25 + .25 + .25 + 2.25 = 5 -> sd sqrt(5/3)
    means = [1.0, 1.25, 1.75, 2.5, 3.5, 4.5]
    sds = [0.0, 0.5, math.sqrt(2.75 / 3), math.sqrt(5 / 3), math.sqrt(5 / 3), math.sqrt(5 / 3)]
    assert [float(r["m.Out"]) for r in rows] == means
    assert [float(r["d.Average"]) for r in rows] == means
    assert [float(r["d.Out"]) for r in rows] == pytest.approx(sds, rel=1e-6)
    # the newest sample in element 0, the oldest of the 4 in element 3
    assert [(r["st[0]"], r["st[3]"]) for r in rows][-1] == ("6.0", "3.0")
    assert report["diagnostics"] == []


def test_weighted_average() -> None:
    s = new_struct("MOVING_AVERAGE", NumberOfSamples=3, SampleEnable=1, UseWeights=1)
    st, w = arr(), arr(0.5, 0.3, 0.2)
    for x in (10.0, 20.0, 40.0):
        s[AV["IN"]] = x
        sb.mave(ExecContext(), True, s, st, w)
    # samples newest first [40 20 10]: 0.5 x 40 + 0.3 x 20 + 0.2 x 10 = 20 + 6 + 2 = 28
    assert s[AV["OUT"]] == pytest.approx(28.0)
    # the weights are not normalised: doubling them doubles Out
    sb.mave(ExecContext(), True, s, st, arr(1.0, 0.6, 0.4))
    assert st.elements[:3] == [40.0, 40.0, 20.0]  # the execution sampled In 40 again
    assert s[AV["OUT"]] == pytest.approx(1.0 * 40 + 0.6 * 40 + 0.4 * 20)  # 72


def test_sample_enable_initialize_and_in_fault() -> None:
    s = new_struct("MOVING_AVERAGE", NumberOfSamples=2, SampleEnable=1, In=4.0)
    st = arr()
    sb.mave(ExecContext(), True, s, st, arr())  # fills [4 4]
    s[AV["IN"]] = 8.0
    sb.mave(ExecContext(), True, s, st, arr())  # [8 4] -> 6
    assert s[AV["OUT"]] == 6.0
    s[AV["SAMPLEENABLE"]] = 0
    s[AV["IN"]] = 100.0
    sb.mave(ExecContext(), True, s, st, arr())  # no sample: still 6
    assert s[AV["OUT"]] == 6.0 and st.elements[:2] == [8.0, 4.0]
    s[AV["SAMPLEENABLE"]], s[AV["INFAULT"]] = 1, 1
    sb.mave(ExecContext(), True, s, st, arr())  # faulted input not sampled; InFaulted bit 1
    assert (s[AV["OUT"]], s[AV["INFAULTED"]], s[AV["STATUS"]]) == (6.0, 1, 2)
    s[AV["INFAULT"]], s[AV["INITIALIZE"]], s[AV["IN"]] = 0, 1, 3.0
    sb.mave(ExecContext(), True, s, st, arr())  # Initialize: [3 3] -> 3
    assert (s[AV["OUT"]], s[AV["STATUS"]]) == (3.0, 0) and st.elements[:2] == [3.0, 3.0]


def test_number_of_samples_must_fit_the_arrays() -> None:
    s = new_struct("MOVING_AVERAGE", NumberOfSamples=0, SampleEnable=1, In=1.0, Out=9.0)
    sb.mave(ExecContext(), True, s, arr(), arr())
    # NumberOfSampInv (bit 2) + InstructFault (bit 0) = 5; Out held
    assert (s[AV["STATUS"]], s[AV["NUMBEROFSAMPINV"]], s[AV["OUT"]]) == (5, 1, 9.0)
    s[AV["NUMBEROFSAMPLES"]] = 11  # the storage array has 10 elements
    sb.mave(ExecContext(), True, s, arr(), arr())
    assert s[AV["STATUS"]] == 5
    s[AV["NUMBEROFSAMPLES"]], s[AV["USEWEIGHTS"]] = 5, 1  # weights hold only 4
    sb.mave(ExecContext(), True, s, arr(), arr(size=4))
    assert s[AV["STATUS"]] == 5
    s[AV["USEWEIGHTS"]] = 0  # unweighted, 5 fits the storage
    sb.mave(ExecContext(), True, s, arr(), arr(size=4))
    assert (s[AV["STATUS"]], s[AV["OUT"]]) == (0, 1.0)


def test_std_dev_closed_form_and_prescan_refill() -> None:
    s = new_struct("MOVING_STD_DEV", NumberOfSamples=5, SampleEnable=1)
    st = arr()
    for x in (0.0, 2.0, 4.0, 4.0, 4.0, 5.0, 5.0, 7.0, 9.0):
        s[SD["IN"]] = x
        sb.mstd(ExecContext(), True, s, st)
    # last five samples 4 5 5 7 9: mean 30 / 5 = 6; squares 4 + 1 + 1 + 1 + 9 = 16;
    # 16 / (5 - 1) = 4 -> Out 2
    assert (s[SD["AVERAGE"]], s[SD["OUT"]], s[SD["STATUS"]]) == (6.0, 2.0, 0)
    sb.mstd_prescan(ExecContext(), True, s, st)
    s[SD["IN"]] = 1.5
    sb.mstd(ExecContext(), True, s, st)  # first after prescan: [1.5] x 5 -> mean 1.5, sd 0
    assert (s[SD["AVERAGE"]], s[SD["OUT"]]) == (1.5, 0.0)
    s[SD["NUMBEROFSAMPLES"]] = 1
    sb.mstd(ExecContext(), True, s, st)  # one sample: no spread
    assert (s[SD["AVERAGE"]], s[SD["OUT"]], s[SD["STATUS"]]) == (1.5, 0.0, 0)
    s[SD["NUMBEROFSAMPLES"]] = -3
    sb.mstd(ExecContext(), True, s, st)
    assert (s[SD["STATUS"]], s[SD["NUMBEROFSAMPINV"]], s[SD["INSTRUCTFAULT"]]) == (5, 1, 1)


def test_mave_without_weight_array_through_run(tmp_path: Path) -> None:
    # WeightArray is optional in ST (1756-RM006 marks it so; Studio accepts
    # `MAVE(tag, storage);`). An unweighted average needs no weights: In = 2, 4, 6, 8 with
    # N = 2 gives [2 2] -> 2, [4 2] -> 3, [6 4] -> 5, [8 6] -> 7. With UseWeights set and no
    # weight array, no NumberOfSamples fits: NumberOfSampInv (Status.2) and InstructFault
    # (Status.0) are set, Status = 1 + 4 = 5, and Out holds its last value (7).
    src = (
        "VAR m : MOVING_AVERAGE; st : ARRAY[0..4] OF REAL; x : REAL; k : DINT; END_VAR\n"
        "x := x + 2.0; k := k + 1;\n"
        "IF k = 5 THEN m.UseWeights := 1; END_IF;\n"
        "m.In := x; m.NumberOfSamples := 2; m.SampleEnable := 1; MAVE(m, st);\n"
    )
    rows, report = trace(tmp_path, src, ".st", 5, ["m.Out", "m.Status", "m.NumberOfSampInv"])
    assert [float(r["m.Out"]) for r in rows] == [2.0, 3.0, 5.0, 7.0, 7.0]
    assert [r["m.Status"] for r in rows] == ["0", "0", "0", "0", "5"]
    assert report["diagnostics"] == []


def test_mave_with_one_operand_is_still_refused(tmp_path: Path) -> None:
    src = "VAR m : MOVING_AVERAGE; END_VAR\nMAVE(m);\n"
    _rows, report = trace(tmp_path, src, ".st", 1, ["m.Out"], expect_code=1)
    assert [d["code"] for d in report["diagnostics"]] == ["E104"]
