"""The 23 safety instructions shown as with their safety I/O not connected (decision 0078).

SPEC 9.32: safety instructions are not U diagnostics; they run as on a controller with
nothing connected. A GuardLogix whose safety input connections are missing puts their data
at 0 (the safe state) and their status bits at 0 (fault); nothing is there to energize. The
expectations below are that rule applied by hand to each instruction's documented outputs:

- every output that energizes something or reports progress is off (O1, O2, TC, ML, ...);
- an instruction with an InputStatus or OutputStatus operand sees it off: fault present (FP);
- ESTOP, RIN, ENPEN and LC see both channels at 0, which is their inactive (stop) state, not
  a fault: II (inputs inactive) on, FP off; LC also shows the curtain blocked (LCB);
- DIN and THRS have diverse contacts (one normally open, one normally closed per device):
  all of them at 0 disagree, a fault: FP (DIN also CI, cycle the inputs before a reset);
- ROUT with Negative feedback expects its feedbacks at 1 while its outputs are off: at 0 it
  reports both feedback failures and FP; with Positive feedback, 0 agrees with off;
- the clutch/brake mode instructions (CBCM, CBIM, CBSSM) have no fault bit: O1 (and CA) off.
The engine does not simulate the full state machines, so the picture is the same whatever
the program passes: the second run drives every BOOL operand (statuses included) to 1.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from interpreter.cli import main
from stdlib import catalog
from tests.instructions.run_cli import trace

EQ = "E-Stop,Equivalent - Active High,30,Manual,Manual"


def _b(n: int) -> str:
    """n BOOL operands, all the tag `i` (0 = nothing connected; the program may set it)."""
    return ",".join(["i"] * n)


# (instruction, instance type, operands after the tag, members off, members on)
TABLE = [
    ("ESTOP", "EMERGENCY_STOP", "Manual," + _b(4), "O1 CI CRHO FP", "II"),
    ("RIN", "REDUNDANT_INPUT", "Manual," + _b(4), "O1 CI CRHO FP", "II"),
    ("ENPEN", "ENABLE_PENDANT", "Manual," + _b(4), "O1 CI CRHO FP", "II"),
    ("LC", "LIGHT_CURTAIN", "Manual,i,i,100,i,i,i", "O1 CI CRHO LCM FP", "LCB II"),
    ("DIN", "DIVERSE_INPUT", "Manual," + _b(4), "O1 CRHO II", "CI FP"),
    ("ROUT", "REDUNDANT_OUTPUT", "Positive," + _b(4), "O1 O2 O1FF O2FF FP", ""),
    ("DCST", "DCI_STOP_TEST", f"{EQ},{_b(5)}", "O1 TC", "FP"),
    ("DCSTL", "DCI_STOP_TEST_LOCK", f"{EQ},{_b(8)}", "O1 TC ULC", "FP"),
    ("DCSTM", "DCI_STOP_TEST_MUTE", f"{EQ},1,100,{_b(7)}", "O1 TC ML SS", "FP"),
    ("SMAT", "SAFETY_MAT", "Manual,50," + _b(4), "O1 SRCA SRCB", "FP"),
    ("THRS", "TWO_HAND_RUN_STATION", "1," + _b(6), "BP SA BT CB SAF RBF LBF", "FP"),
    ("THRSE", "THRS_ENHANCED", "500," + _b(8), "O1 BR SB", "FP"),
    ("TSAM", "MUTING_TWO_SENSOR_ASYM", "Manual,100,100,1000,1000," + _b(8), "O1 ML CA", "FP"),
    ("TSSM", "MUTING_TWO_SENSOR_SYM", "Manual,100,100,200,1000,1000," + _b(8), "O1 ML CA", "FP"),
    (
        "FSBM",
        "MUTING_FOUR_SENSOR_BIDIR",
        "Manual,100,100,100,100,1000,1000,1," + _b(10),
        "O1 ML CA",
        "FP",
    ),
    ("AVC", "AUX_VALVE_CONTROL", "Positive,100,1,100," + _b(7), "O1", "FP"),
    ("MVC", "MAIN_VALVE_CONTROL", "Positive,100," + _b(6), "O1 O2", "FP"),
    ("MMVC", "MANUAL_VALVE_CONTROL", _b(9), "O1", "FP"),
    ("CBCM", "CB_CONTINUOUS_MODE", f"1,1,1,{_b(8)},1,i", "O1 CA", ""),
    ("CBIM", "CB_INCH_MODE", f"1,500,{_b(6)},1,i", "O1", ""),
    ("CBSSM", "CB_SINGLE_STROKE_MODE", f"1,1,{_b(6)},1,i", "O1", ""),
    ("CPM", "CB_CRANKSHAFT_POS_MONITOR", "prof," + _b(8), "TZ DZ UZ", "FP"),
    ("CSM", "CAMSHAFT_MONITOR", "100,200," + _b(5), "O1", "FP"),
]


def _program(level: int) -> str:
    tags = "; ".join(f"t{n} : {typ}" for n, typ, *_ in TABLE)
    lines = [f"VAR {tags}; prof : DINT[10]; i : BOOL; END_VAR"]
    if level:
        lines.append("OTL(i);")
    lines += [f"{n}(t{n},{ops});" for n, _, ops, *_ in TABLE]
    return "\n".join(lines) + "\n"


@pytest.mark.parametrize("level", [0, 1], ids=["inputs-0", "inputs-1"])
def test_each_instruction_shows_outputs_off_and_its_fault(tmp_path: Path, level: int) -> None:
    watch, expected = [], {}
    for n, _, _, off, on in TABLE:
        for m in off.split():
            watch.append(f"t{n}.{m}")
            expected[f"t{n}.{m}"] = False
        for m in on.split():
            watch.append(f"t{n}.{m}")
            expected[f"t{n}.{m}"] = True
    _, report = trace(tmp_path, _program(level), ".rll", 2, watch, period_ms=10.0)
    assert report["diagnostics"] == [] and report["unsupported"] == []
    assert report["faults"] == []
    assert report["tags"] == expected


def test_rout_negative_feedback_reads_0_as_both_feedbacks_failed(tmp_path: Path) -> None:
    # Negative: a feedback shows 1 while its output is off; nothing connected reads 0
    src = "VAR r : REDUNDANT_OUTPUT; i : BOOL; END_VAR\nROUT(r,Negative,i,i,i,i);\n"
    watch = ["r.O1", "r.O2", "r.O1FF", "r.O2FF", "r.FP"]
    _, report = trace(tmp_path, src, ".rll", 1, watch, period_ms=10.0)
    assert report["tags"] == {
        "r.O1": False,
        "r.O2": False,
        "r.O1FF": True,
        "r.O2FF": True,
        "r.FP": True,
    }


def test_false_rung_keeps_the_fault_and_a_reset_does_not_clear_it(tmp_path: Path) -> None:
    # scan 1 true rung: FP; scan 2 false rung: EnableIn 0, FP and II kept (a fault is kept,
    # as for DCS); scans 3-4 true again with Reset (i) on from scan 3: an off-to-on reset,
    # but the I/O is still missing, so FP stays.
    src = (
        "VAR t : DCI_STOP_TEST; e : EMERGENCY_STOP; n : DINT; go, i : BOOL; END_VAR\n"
        "ADD(n,1,n);\nNEQ(n,2)OTE(go);\nGEQ(n,3)OTE(i);\n"
        f"XIC(go)DCST(t,{EQ},0,0,0,0,i);\n"
        "XIC(go)ESTOP(e,Manual,0,0,0,i);\n"
    )
    watch = ["t.EnableIn", "t.O1", "t.FP", "t.Reset", "e.O1", "e.II"]
    rows, _ = trace(tmp_path, src, ".rll", 4, watch, period_ms=10.0)
    got = [tuple(int(r[w]) for w in watch) for r in rows]
    assert got == [
        (1, 0, 1, 0, 0, 1),
        (0, 0, 1, 0, 0, 1),
        (1, 0, 1, 1, 0, 1),
        (1, 0, 1, 1, 0, 1),
    ]


def test_backing_tag_mirrors_plain_operands(tmp_path: Path) -> None:
    # BOOL and number operands are copied into members of the same name; the enumerated
    # ResetType is not (decision 0076)
    src = (
        "VAR l : LIGHT_CURTAIN; c : CAMSHAFT_MONITOR; a, z : BOOL; END_VAR\nOTL(a);\n"
        "LC(l,Automatic,a,z,120,a,z,a);\nCSM(c,100,250,a,z,a,a,z);\n"
    )
    watch = ["l.ChannelA", "l.ChannelB", "l.InputFilterTime", "l.ResetType", "l.FaultReset"]
    watch += ["c.MaxPulsePeriod", "c.MotionRequest", "c.InputStatus", "c.EnableOut"]
    _, report = trace(tmp_path, src, ".rll", 1, watch, period_ms=10.0)
    assert report["tags"] == {
        "l.ChannelA": True,
        "l.ChannelB": False,
        "l.InputFilterTime": 120,
        "l.ResetType": False,
        "l.FaultReset": True,
        "c.MaxPulsePeriod": 250,
        "c.MotionRequest": True,
        "c.InputStatus": True,
        "c.EnableOut": True,
    }


def _call(ins_name: str) -> str:
    """A call of a catalog safety instruction with an operand of a fitting kind each."""
    ins = catalog().instruction(ins_name, "rll")
    ops = []
    for op in ins.operands[1:]:
        if op.enum is not None:
            ops.append(catalog().enum(op.enum).values[0].text)
        elif op.format == "array":
            ops.append("prof")
        elif op.types == ("BOOL",):
            ops.append("i")
        else:
            ops.append("10")
    return f"{ins_name}(t{ins_name},{','.join(ops)});"


def test_no_safety_instruction_is_u304(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    safety = [i for i in catalog().instructions if i.family == "safety"]
    assert len(safety) == 29  # 6 simulated in full + the 23 above
    tags = "; ".join(f"t{i.name} : {i.operands[0].types[0]}" for i in safety)
    prog = tmp_path / "all.rll"
    body = "\n".join(_call(i.name) for i in safety)
    prog.write_text(f"VAR {tags}; prof : DINT[10]; i : BOOL; END_VAR\n{body}\n")
    capsys.readouterr()
    assert main(["check", str(prog)]) == 0
    out = capsys.readouterr().out
    assert "U304" not in out and out.strip() == "0 error(s), 0 warning(s)", out


def test_every_output_bit_is_held_by_the_catalog() -> None:
    # each BOOL of an instance tag that is not a copy of an operand (nor EnableIn/Out or a
    # reserved member) is an output: the nothing-connected entry must say what it shows
    for ins in catalog().instructions:
        u = ins.unconnected
        if u is None:
            continue
        operands = {o.name for o in ins.operands}
        td = catalog().types[ins.operands[0].types[0]]
        outputs = {
            m.name
            for m in td.members
            if m.type == "BOOL"
            and not m.hidden
            and m.name not in operands
            and m.name not in ("EnableIn", "EnableOut")
            and not m.name.startswith("Reserved")
        }
        named = {*u.off, *u.on, *(n for c in u.cases for n in c.on)}
        assert named == outputs, ins.name
