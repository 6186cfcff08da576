"""PIDE through `logixst run`, against hand-worked numbers (decision 0190).

Unless a test says otherwise the loop has Studio's defaults for a new PIDE tag: PV span
0..100 (so 1 EU is 1 %), CV span 0..100 (CVEU = CV), CV limits 0..100, SP limits 0..100,
reverse acting (E = SP - PV), derivative on PV. Most programs use TimingMode 1 (oversample)
so DeltaT is OversampleDT whatever the scan period. `n` counts the scans: scan k sees n = k.
The first execution is the instruction first scan: CV is initialised from CVInitValue.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.instructions.run_cli import trace

HEAD = "VAR p : PID_ENHANCED; n : DINT; END_VAR\nn := n + 1;\n"


def run(tmp_path: Path, body: str, scans: int, watch: list[str], period_ms: float = 100.0):  # noqa: ANN201
    rows, report = trace(tmp_path, HEAD + body, ".st", scans, [f"p.{w}" for w in watch], period_ms)
    assert report["diagnostics"] == []
    return [{w: r[f"p.{w}"] for w in watch} for r in rows]


def num(rows: list[dict[str, str]], member: str) -> list[float]:
    return [float(r[member]) for r in rows]


def bits(rows: list[dict[str, str]], member: str) -> list[int]:
    return [1 if r[member] in ("true", "1") else 0 for r in rows]


AUTO_PROG = "p.ProgProgReq := 1; p.ProgAutoReq := 1;\n"


def test_p_only_step_moves_cv_by_gain_times_error_change(tmp_path: Path) -> None:
    body = (
        "p.TimingMode := 1; p.OversampleDT := 0.1; p.PGain := 2.0; p.CVInitValue := 30.0;\n"
        + AUTO_PROG
        + "p.PV := 40.0; IF n < 3 THEN p.SPProg := 40.0; ELSE p.SPProg := 50.0; END_IF;\nPIDE(p);\n"
    )
    rows = run(tmp_path, body, 4, ["CV", "CVEU", "E", "EPercent", "Auto", "CVInitializing"])
    # scan 1 initialises CV = CVInitValue 30 %; scan 2: E unchanged (0) -> CV 30;
    # scan 3: E goes 0 -> 10 %, dCV = PGain x dE = 2 x 10 = 20 -> 50; scan 4: dE 0 -> 50
    assert num(rows, "CV") == [30.0, 30.0, 50.0, 50.0]
    assert num(rows, "CVEU") == [30.0, 30.0, 50.0, 50.0]
    assert num(rows, "E") == [0.0, 0.0, 10.0, 10.0]
    assert bits(rows, "Auto") == [1, 1, 1, 1]
    assert bits(rows, "CVInitializing") == [1, 0, 0, 0]


def test_pv_proportional_gives_no_kick_on_a_setpoint_step(tmp_path: Path) -> None:
    body = (
        "p.TimingMode := 1; p.OversampleDT := 0.1; p.PGain := 2.0; p.CVInitValue := 30.0;\n"
        "p.PVEProportional := 1;\n" + AUTO_PROG + "IF n < 3 THEN p.SPProg := 40.0; p.PV := 40.0;\n"
        "ELSIF n = 3 THEN p.SPProg := 50.0; ELSE p.PV := 45.0; END_IF;\nPIDE(p);\n"
    )
    rows = run(tmp_path, body, 4, ["CV"])
    # scan 3: SP step only, proportional acts on -PV: no change; scan 4: PV 40 -> 45,
    # dCV = 2 x -(45 - 40) = -10 -> 20
    assert num(rows, "CV") == [30.0, 30.0, 30.0, 20.0]


def test_integral_ramp_in_a_periodic_task(tmp_path: Path) -> None:
    prog = (
        "p.PGain := 0.0; p.IGain := 60.0; p.SPProg := 50.0; p.PV := 40.0;\n"
        "p.ProgProgReq := 1; p.ProgAutoReq := 1;\nPIDE(p);"
    )
    lines = "".join(
        f'<Line Number="{k}"><![CDATA[{t}]]></Line>\n' for k, t in enumerate(prog.splitlines())
    )
    src = (
        '<?xml version="1.0" encoding="UTF-8" standalone="yes"?>\n'
        '<RSLogix5000Content SchemaRevision="1.0" SoftwareRevision="35.00" TargetName="Loop" '
        'TargetType="Controller" ContainsContext="false">\n'
        '<Controller Use="Target" Name="Loop" ProcessorType="1756-L83E" MajorRev="35" MinorRev="11">\n'
        '<Tags>\n<Tag Name="p" TagType="Base" DataType="PID_ENHANCED" ExternalAccess="Read/Write"/>\n'
        "</Tags>\n<Programs>\n"
        '<Program Name="Control" MainRoutineName="Main" Disabled="false">\n<Tags/>\n<Routines>\n'
        f'<Routine Name="Main" Type="ST">\n<STContent>\n{lines}</STContent>\n</Routine>\n'
        "</Routines>\n</Program>\n</Programs>\n<Tasks>\n"
        '<Task Name="Loop100ms" Type="PERIODIC" Rate="100" Priority="5" Watchdog="500" '
        'DisableUpdateOutputs="false" InhibitTask="false">\n'
        '<ScheduledPrograms>\n<ScheduledProgram Name="Control"/>\n</ScheduledPrograms>\n</Task>\n'
        "</Tasks>\n</Controller>\n</RSLogix5000Content>\n"
    )
    rows, report = trace(tmp_path, src, ".L5X", 6, ["p.CV", "p.DeltaT"], period_ms=100.0)
    assert report["diagnostics"] == []
    # periodic task of 100 ms: DeltaT = 0.1 s (TimingMode 0). Scan 1 initialises CV to
    # CVInitValue 0; then each scan dCV = IGain / 60 x E x dt = 60 / 60 x 10 x 0.1 = 1 %
    assert [float(r["p.CV"]) for r in rows] == pytest.approx([0.0, 1.0, 2.0, 3.0, 4.0, 5.0])
    assert [float(r["p.DeltaT"]) for r in rows] == pytest.approx([0.1] * 6)


@pytest.mark.parametrize(
    ("dependent", "expected"),
    [
        # independent: step dCV = 2 x 10 + 0.5 / 60 x 10 x 6 = 20 + 0.5 -> 50.5; then +0.5
        (0, [30.0, 30.0, 50.5, 51.0]),
        # dependent (Kc 2, Ti 0.5 min/repeat): 2 x (10 + 6 / (60 x 0.5) x 10) = 2 x 12 = 24
        # -> 54; then 2 x (0 + 2) = 4 -> 58
        (1, [30.0, 30.0, 54.0, 58.0]),
    ],
)
def test_dependent_and_independent_gains(
    tmp_path: Path, dependent: int, expected: list[float]
) -> None:
    body = (
        "p.TimingMode := 1; p.OversampleDT := 6.0; p.PGain := 2.0; p.IGain := 0.5;\n"
        f"p.DependIndepend := {dependent}; p.CVInitValue := 30.0; p.PV := 40.0;\n"
        + AUTO_PROG
        + "IF n < 3 THEN p.SPProg := 40.0; ELSE p.SPProg := 50.0; END_IF;\nPIDE(p);\n"
    )
    rows = run(tmp_path, body, 4, ["CV"])
    assert num(rows, "CV") == pytest.approx(expected)


@pytest.mark.parametrize(
    ("smoothing", "expected"),
    [
        # D = 60 x DGain x d(-PV)/dt = 6 x (-1) / 1 = -6 while PV ramps 1 %/s, 0 when it
        # stops. CV = 50 + D: scans 3, 4 on the ramp -> 44, 44; scan 5 PV still -> 50
        (0, [50.0, 50.0, 44.0, 44.0, 50.0]),
        # smoothed, Tf = 0.1 x 6 = 0.6 s, D(n) = (0.6 D(n-1) + 6 dx) / (0.6 + 1):
        # D3 = -6 / 1.6 = -3.75; D4 = (0.6 x -3.75 - 6) / 1.6 = -5.15625;
        # D5 = 0.6 x -5.15625 / 1.6 = -1.93359375
        (1, [50.0, 50.0, 46.25, 44.84375, 48.06640625]),
    ],
)
def test_derivative_on_pv_and_smoothing(
    tmp_path: Path, smoothing: int, expected: list[float]
) -> None:
    body = (
        "p.TimingMode := 1; p.OversampleDT := 1.0; p.DGain := 0.1; p.CVInitValue := 50.0;\n"
        f"p.DSmoothing := {smoothing}; p.SPProg := 60.0;\n"
        + AUTO_PROG
        + "IF n <= 2 THEN p.PV := 40.0;\n"
        "ELSIF n = 3 THEN p.PV := 41.0; ELSE p.PV := 42.0; END_IF;\nPIDE(p);\n"
    )
    rows = run(tmp_path, body, 5, ["CV"])
    assert num(rows, "CV") == pytest.approx(expected)


def test_cv_high_limit_and_windup_flags(tmp_path: Path) -> None:
    body = (
        "p.TimingMode := 1; p.OversampleDT := 1.0; p.PGain := 1.0; p.IGain := 60.0;\n"
        "p.CVHLimit := 60.0; p.CVInitValue := 30.0; p.PV := 40.0;\n"
        + AUTO_PROG
        + "IF n <= 4 THEN p.SPProg := 50.0; ELSE p.SPProg := 35.0; END_IF;\n"
        "PIDE(p);\n"
    )
    rows = run(tmp_path, body, 6, ["CV", "CVHAlarm", "WindupHOut", "WindupLOut"])
    # integral: IGain / 60 x E x dt = 1 x 10 x 1 = 10 % per scan from 30:
    # scan 2 -> 40, 3 -> 50, 4 -> 60 (at the limit), scan 5: E 10 -> -5, dCV =
    # 1 x (-15) + 1 x (-5) = -20 -> 60 - 20 = 40 at once (velocity form: no windup);
    # scan 6: -5 -> 35
    assert num(rows, "CV") == [30.0, 40.0, 50.0, 60.0, 40.0, 35.0]
    # scan 4 asked for 60 exactly: not above the limit. Reverse acting: CV high -> WindupHOut
    assert bits(rows, "CVHAlarm") == [0, 0, 0, 0, 0, 0]
    rows = run(
        tmp_path,
        body.replace("p.CVHLimit := 60.0", "p.CVHLimit := 55.0"),
        5,
        ["CV", "CVHAlarm", "WindupHOut", "WindupLOut"],
    )
    # scan 4 asks for 60 > 55: limited to 55, CVHAlarm and WindupHOut; scan 5: 55 - 20 = 35
    assert num(rows, "CV") == [30.0, 40.0, 50.0, 55.0, 35.0]
    assert bits(rows, "CVHAlarm") == [0, 0, 0, 1, 0]
    assert bits(rows, "WindupHOut") == [0, 0, 0, 1, 0]
    assert bits(rows, "WindupLOut") == [0, 0, 0, 0, 0]


def test_direct_acting_low_limit_sets_windup_high(tmp_path: Path) -> None:
    body = (
        "p.TimingMode := 1; p.OversampleDT := 1.0; p.IGain := 60.0; p.ControlAction := 1;\n"
        "p.CVInitValue := 15.0; p.PV := 40.0; p.SPProg := 50.0;\n" + AUTO_PROG + "PIDE(p);\n"
    )
    rows = run(tmp_path, body, 3, ["CV", "E", "CVLAlarm", "WindupHOut", "WindupLOut"])
    # E = PV - SP = -10: -10 % per scan: 15 -> 5 -> -5 limited to 0 (CVLAlarm); direct
    # acting: CV down drives PV up, so the low limit stops PV rising: WindupHOut
    assert num(rows, "E") == [-10.0, -10.0, -10.0]
    assert num(rows, "CV") == [15.0, 5.0, 0.0]
    assert bits(rows, "CVLAlarm") == [0, 0, 1]
    assert bits(rows, "WindupHOut") == [0, 0, 1]
    assert bits(rows, "WindupLOut") == [0, 0, 0]


def test_windup_inputs_stop_cv_in_their_direction(tmp_path: Path) -> None:
    body = (
        "p.TimingMode := 1; p.OversampleDT := 1.0; p.IGain := 60.0; p.CVInitValue := 30.0;\n"
        "p.PV := 40.0; p.SPProg := 50.0; p.WindupHIn := n >= 3; p.WindupLIn := 1;\n"
        + AUTO_PROG
        + "PIDE(p);\n"
    )
    rows = run(tmp_path, body, 4, ["CV"])
    # +10 % per scan; WindupLIn only blocks decreases; from scan 3 WindupHIn holds CV
    assert num(rows, "CV") == [30.0, 40.0, 40.0, 40.0]


def test_cv_rate_of_change_limit(tmp_path: Path) -> None:
    body = (
        "p.TimingMode := 1; p.OversampleDT := 0.5; p.PGain := 4.0; p.CVROCLimit := 10.0;\n"
        "p.CVInitValue := 20.0; p.PV := 40.0;\n"
        + AUTO_PROG
        + "IF n < 2 THEN p.SPProg := 40.0; ELSE p.SPProg := 50.0; END_IF;\nPIDE(p);\n"
    )
    rows = run(tmp_path, body, 4, ["CV", "CVROCAlarm"])
    # the step asks for +4 x 10 = 40 %; 10 %/s x 0.5 s allows 5 % per scan; the request is
    # not remembered (velocity form): scan 3 and 4 have dE = 0 -> CV stays at 25
    assert num(rows, "CV") == [20.0, 25.0, 25.0, 25.0]
    assert bits(rows, "CVROCAlarm") == [0, 1, 0, 0]


def test_feed_forward_adds_its_change(tmp_path: Path) -> None:
    body = (
        "p.TimingMode := 1; p.OversampleDT := 1.0; p.CVInitValue := 30.0; p.PV := 40.0;\n"
        "p.SPProg := 40.0;\n" + AUTO_PROG + "IF n >= 3 THEN p.FF := 5.0; END_IF;\n"
        "IF n = 4 THEN p.FFSetPrevious := 1; p.FFPrevious := 2.0; ELSE p.FFSetPrevious := 0; END_IF;\n"
        "PIDE(p);\n"
    )
    rows = run(tmp_path, body, 4, ["CV"])
    # scan 3: FF 0 -> 5: +5 -> 35; scan 4: FF(n-1) forced to 2: +3 -> 38
    assert num(rows, "CV") == [30.0, 30.0, 35.0, 38.0]


def test_manual_to_auto_is_bumpless(tmp_path: Path) -> None:
    body = (
        "p.TimingMode := 1; p.OversampleDT := 1.0; p.PGain := 1.0; p.IGain := 6.0;\n"
        "p.PV := 40.0; p.SPProg := 45.0; p.CVProg := 35.0; p.ProgProgReq := 1;\n"
        "p.ProgManualReq := n <= 2; p.ProgAutoReq := n >= 3;\nPIDE(p);\n"
    )
    rows = run(tmp_path, body, 4, ["CV", "Manual", "Auto", "CVOper"])
    # Manual: CV = CVProg 35 (scan 1 initialises to CVInitValue 0 first). Auto from scan 3:
    # E constant 5 %, no proportional step; integral 6 / 60 x 5 x 1 = 0.5 % per scan
    assert num(rows, "CV") == [0.0, 35.0, 35.5, 36.0]
    assert bits(rows, "Manual") == [1, 1, 0, 0]
    assert bits(rows, "Auto") == [0, 0, 1, 1]
    # the operator's manual value follows CV so Operator Manual would start from it
    assert num(rows, "CVOper") == [0.0, 35.0, 35.5, 36.0]


def test_request_handshake(tmp_path: Path) -> None:
    body = (
        "p.TimingMode := 1; p.OversampleDT := 1.0;\n"
        "IF n = 1 THEN p.OperAutoReq := 1; END_IF;\n"  # operator control (default): Auto
        "IF n = 2 THEN p.ProgProgReq := 1; p.OperManualReq := 1; END_IF;\n"  # program control
        "IF n = 3 THEN p.ProgManualReq := 1; p.ProgValueReset := 1; END_IF;\n"
        "PIDE(p);\n"
    )
    watch = [
        "ProgOper",
        "Auto",
        "Manual",
        "OperAutoReq",
        "OperManualReq",
        "ProgProgReq",
        "ProgManualReq",
    ]
    rows = run(tmp_path, body, 4, watch)
    # scan 1: operator Auto, the request is cleared by the block. Scan 2: ProgProgReq takes
    # Program control, the operator's Manual request is ignored there and cleared; the
    # program request stays set. Scan 3: ProgManualReq -> Manual; ProgValueReset clears
    # both program requests; Program control stays.
    assert bits(rows, "ProgOper") == [0, 1, 1, 1]
    assert bits(rows, "Auto") == [1, 1, 0, 0]
    assert bits(rows, "Manual") == [0, 0, 1, 1]
    assert bits(rows, "OperAutoReq") == [0, 0, 0, 0]
    assert bits(rows, "OperManualReq") == [0, 0, 0, 0]
    assert bits(rows, "ProgProgReq") == [0, 1, 0, 0]
    assert bits(rows, "ProgManualReq") == [0, 0, 0, 0]


def test_cascade_ratio_needs_allow_and_uses_ratio(tmp_path: Path) -> None:
    body = (
        "p.TimingMode := 1; p.OversampleDT := 1.0; p.SPCascade := 30.0; p.UseRatio := 1;\n"
        "p.RatioHLimit := 2.0; p.RatioLLimit := 0.5; p.RatioOper := 1.5; p.SPOper := 10.0;\n"
        "p.OperCasRatReq := 1; p.AllowCasRat := n >= 2;\nPIDE(p);\n"
    )
    rows = run(tmp_path, body, 3, ["CasRat", "Manual", "SP", "Ratio", "InitPrimary", "SPOper"])
    # scan 1: AllowCasRat clear, the request is ignored (first scan: Manual), SP = SPOper 10.
    # scan 2: Cascade/Ratio, SP = SPCascade x Ratio = 30 x 1.5 = 45; SPOper follows it
    assert bits(rows, "CasRat") == [0, 1, 1]
    assert num(rows, "SP") == [10.0, 45.0, 45.0]
    assert num(rows, "Ratio") == [1.5, 1.5, 1.5]
    assert bits(rows, "InitPrimary") == [1, 0, 0]
    assert num(rows, "SPOper") == [10.0, 45.0, 45.0]


def test_override_and_hand(tmp_path: Path) -> None:
    body = (
        "p.TimingMode := 1; p.OversampleDT := 1.0; p.CVOverride := 80.0; p.HandFB := 42.0;\n"
        "p.ProgOverrideReq := n = 2 OR n = 3; p.ProgHandReq := n = 3;\n"
        "PIDE(p);\n"
    )
    rows = run(tmp_path, body, 4, ["CV", "Override", "Hand", "Manual"])
    # scan 1 initialises CV to CVInitValue 0; scan 2 Override -> 80; scan 3 Hand wins over
    # Override -> HandFB 42; scan 4 released -> Manual (operator), CV = CVOper, which
    # followed CV: 42
    assert num(rows, "CV") == [0.0, 80.0, 42.0, 42.0]
    assert bits(rows, "Override") == [0, 1, 0, 0]
    assert bits(rows, "Hand") == [0, 0, 1, 0]
    assert bits(rows, "Manual") == [1, 0, 0, 1]


def test_pv_alarms_with_deadband(tmp_path: Path) -> None:
    body = (
        "p.TimingMode := 1; p.OversampleDT := 1.0; p.PVHLimit := 80.0; p.PVHHLimit := 90.0;\n"
        "p.PVLLimit := 20.0; p.PVDeadband := 5.0;\n"
        "CASE n OF 1: p.PV := 79.0; 2: p.PV := 80.0; 3: p.PV := 77.0; 4: p.PV := 74.9;\n"
        "5: p.PV := 20.0; 6: p.PV := 24.0; 7: p.PV := 25.1; END_CASE;\nPIDE(p);\n"
    )
    rows = run(tmp_path, body, 7, ["PVHAlarm", "PVHHAlarm", "PVLAlarm"])
    # PVHAlarm set at PV >= 80, kept down to 80 - 5 = 75, cleared at 74.9;
    # PVLAlarm set at PV <= 20, kept up to 25, cleared at 25.1; PVHHAlarm never
    assert bits(rows, "PVHAlarm") == [0, 1, 1, 0, 0, 0, 0]
    assert bits(rows, "PVLAlarm") == [0, 0, 0, 0, 1, 1, 0]
    assert bits(rows, "PVHHAlarm") == [0] * 7


def test_deviation_alarms(tmp_path: Path) -> None:
    body = (
        "p.TimingMode := 1; p.OversampleDT := 1.0; p.SPOper := 50.0; p.DevHLimit := 5.0;\n"
        "p.DevLLimit := 8.0; p.DevDeadband := 1.0;\n"
        "CASE n OF 1: p.PV := 55.0; 2: p.PV := 54.0; 3: p.PV := 53.9; 4: p.PV := 42.0; END_CASE;\n"
        "PIDE(p);\n"
    )
    rows = run(tmp_path, body, 4, ["DevHAlarm", "DevLAlarm"])
    # PV - SP: 5 (>= 5: on), 4 (>= 5 - 1: stays), 3.9 (off), -8 (<= -8: low alarm)
    assert bits(rows, "DevHAlarm") == [1, 1, 0, 0]
    assert bits(rows, "DevLAlarm") == [0, 0, 0, 1]


def test_zero_crossing_deadband_holds_cv(tmp_path: Path) -> None:
    body = (
        "p.TimingMode := 1; p.OversampleDT := 1.0; p.IGain := 60.0; p.ZCDeadband := 2.0;\n"
        "p.CVInitValue := 30.0; p.SPProg := 50.0;\n"
        + AUTO_PROG
        + "CASE n OF 1, 2: p.PV := 45.0; 3: p.PV := 49.0; 4: p.PV := 51.0; 5: p.PV := 49.5;\n"
        "6: p.PV := 53.0; END_CASE;\nPIDE(p);\n"
    )
    rows = run(tmp_path, body, 6, ["CV", "ZCDeadbandOn"])
    # integral only, 1 x E % per scan: scan 2 E 5 -> 35; scan 3 E 1 (inside the band but not
    # crossed yet) -> 36; scan 4 E -1 crossed zero: deadband on, CV held; scan 5 E 0.5
    # still inside: held; scan 6 E -3 leaves the band: 36 - 3 = 33
    assert num(rows, "CV") == [30.0, 35.0, 36.0, 36.0, 36.0, 33.0]
    assert bits(rows, "ZCDeadbandOn") == [0, 0, 0, 1, 1, 0]


def test_cv_init_request_and_cveu_scaling(tmp_path: Path) -> None:
    body = (
        "p.TimingMode := 1; p.OversampleDT := 1.0; p.CVEUMin := 4.0; p.CVEUMax := 20.0;\n"
        "p.CVInitValue := 12.0; p.CVInitReq := n = 3; p.ManualAfterInit := 1;\n"
        "IF n = 1 THEN p.CVOper := 25.0; END_IF;\n"
        "p.OperAutoReq := n = 2;\nPIDE(p);\n"
    )
    rows = run(tmp_path, body, 4, ["CV", "CVEU", "CVInitializing", "Auto", "Manual", "InitPrimary"])
    # CVInitValue 12 in 4..20 -> (12 - 4) x 100 / 16 = 50 %; scan 2 Auto holds 50 (E 0). Scan 3 CVInitReq: 50 %, ManualAfterInit -> Manual;
    # scan 4 Operator Manual: CV = CVOper, which initialisation and Auto set to CV (the 25
    # written before scan 1 was replaced by the initialised 50)
    assert num(rows, "CV") == [50.0, 50.0, 50.0, 50.0]
    assert num(rows, "CVEU") == [12.0, 12.0, 12.0, 12.0]
    assert bits(rows, "CVInitializing") == [1, 0, 1, 0]
    assert bits(rows, "Auto") == [0, 1, 0, 0]
    assert bits(rows, "InitPrimary") == [1, 1, 1, 1]
    body = (
        "p.TimingMode := 1; p.OversampleDT := 1.0; p.CVEUMin := 4.0; p.CVEUMax := 20.0;\n"
        "p.CVInitValue := 12.0; p.CVOper := 75.0;\nPIDE(p);\n"
    )
    rows = run(tmp_path, body, 2, ["CVEU", "CVOper", "Manual"])
    # the first scan initialises CV and sets CVOper to it; the program writes CVOper 75
    # again before scan 2, and Operator Manual uses it: 75 % -> 4 + 0.75 x 16 = 16
    assert num(rows, "CVEU") == [12.0, 16.0]
    assert num(rows, "CVOper") == [50.0, 75.0]
    assert bits(rows, "Manual") == [1, 1]


def test_status_words_and_forced_manual(tmp_path: Path) -> None:
    body = (
        "p.TimingMode := 1; p.OversampleDT := 1.0; p.CVInitValue := 30.0;\n"
        "p.OperAutoReq := n = 2; p.PVFault := n = 3; p.CVFault := n = 4;\n"
        "IF n = 5 THEN p.PVEUMax := 0.0; p.PGain := -1.0; END_IF;\n"
        "IF n = 6 THEN p.PVEUMax := 100.0; p.PGain := 0.0; p.TimingMode := 7; END_IF;\nPIDE(p);\n"
    )
    rows = run(tmp_path, body, 6, ["Status1", "Status2", "Auto", "Manual", "InstructFault"])
    # scan 2 Auto. Scan 3 PVFaulted (bit 1) + InstructFault (bit 0) = 3 and Manual;
    # scan 4 CVFaulted (bit 2) + bit 0 = 5; scan 5 PVSpanInv (bit 4) and PGainInv (bit 22)
    # + bit 0 = 2^22 + 16 + 1 = 4194321, and SPLimitsInv (bit 8: SPHLimit 100 > PVEUMax 0)
    # = 4194321 + 256 = 4194577; scan 6 TimingModeInv Status2 bit 27 = 134217728, bit 0 of
    # Status1 = 1
    assert num(rows, "Status1") == [0, 0, 3, 5, 4194577, 1]
    assert num(rows, "Status2") == [0, 0, 0, 0, 0, 134217728]
    assert bits(rows, "Auto") == [0, 1, 0, 0, 0, 0]
    assert bits(rows, "Manual") == [1, 0, 1, 1, 1, 1]


def test_setpoint_limits_and_alarms(tmp_path: Path) -> None:
    body = (
        "p.TimingMode := 1; p.OversampleDT := 1.0; p.SPHLimit := 80.0; p.SPLLimit := 10.0;\n"
        "CASE n OF 1: p.SPOper := 90.0; 2: p.SPOper := 5.0; 3: p.SPOper := 50.0; END_CASE;\n"
        "PIDE(p);\n"
    )
    rows = run(tmp_path, body, 3, ["SP", "SPHAlarm", "SPLAlarm", "Status1"])
    # SP limited to 80 / 10 with its alarm; SPOperInv is Status1 bit 6 (+ bit 0) = 65
    assert num(rows, "SP") == [80.0, 10.0, 50.0]
    assert bits(rows, "SPHAlarm") == [1, 0, 0]
    assert bits(rows, "SPLAlarm") == [0, 1, 0]
    assert num(rows, "Status1") == [65, 65, 0]


def test_program_operator_precedence(tmp_path: Path) -> None:
    body = (
        "p.TimingMode := 1; p.OversampleDT := 1.0;\n"
        "p.ProgProgReq := n = 1 OR n = 2; p.ProgOperReq := n = 2;\n"  # both: Operator wins
        "p.OperProgReq := n = 3 OR n = 4; p.OperOperReq := n = 4;\n"
        "p.OperOperReq := p.OperOperReq OR n = 5; p.ProgProgReq := p.ProgProgReq OR n = 5;\n"
        "PIDE(p);\n"
    )
    rows = run(tmp_path, body, 5, ["ProgOper"])
    # 1 Program; 2 ProgOperReq beats ProgProgReq; 3 the operator asks for Program; 4 the
    # operator asks for both: Operator; 5 ProgProgReq beats the operator's OperOperReq
    assert bits(rows, "ProgOper") == [1, 0, 1, 0, 1]


def test_pv_tracking_in_manual(tmp_path: Path) -> None:
    body = (
        "p.TimingMode := 1; p.OversampleDT := 1.0; p.PVTracking := 1; p.PGain := 1.0;\n"
        "p.CVInitValue := 20.0; p.OperAutoReq := n = 3;\n"
        "IF n = 1 THEN p.SPOper := 70.0; END_IF;\n"
        "CASE n OF 1: p.PV := 40.0; 2: p.PV := 42.0; 3, 4: p.PV := 43.0; END_CASE;\nPIDE(p);\n"
    )
    rows = run(tmp_path, body, 4, ["SP", "SPOper", "E", "CV", "Auto"])
    # Operator Manual: SP and SPOper follow PV (40, 42); scan 3 Auto with SP left at 42:
    # E = 42 - 43 = -1 (E(n-1) was 0): dCV = 1 x -1 -> CV 19; scan 4 unchanged
    assert num(rows, "SP") == [40.0, 42.0, 42.0, 42.0]
    assert num(rows, "SPOper") == [40.0, 42.0, 42.0, 42.0]
    assert num(rows, "E") == [0.0, 0.0, -1.0, -1.0]
    assert num(rows, "CV") == [20.0, 20.0, 19.0, 19.0]


def test_pv_rate_of_change_alarms(tmp_path: Path) -> None:
    body = (
        "p.TimingMode := 1; p.OversampleDT := 1.0; p.PVROCPeriod := 2.0;\n"
        "p.PVROCPosLimit := 3.0; p.PVROCNegLimit := 4.0;\n"
        "CASE n OF 1: p.PV := 10.0; 2: p.PV := 14.0; 3: p.PV := 17.0; 4: p.PV := 18.0;\n"
        "5: p.PV := 19.0; 6: p.PV := 15.0; 7: p.PV := 10.0; END_CASE;\nPIDE(p);\n"
    )
    rows = run(tmp_path, body, 7, ["PVROCPosAlarm", "PVROCNegAlarm"])
    # periods of 2 s from scan 1 (PV 10): at scan 3 (17 - 10) / 2 = 3.5 >= 3 -> positive
    # alarm; at scan 5 (19 - 17) / 2 = 1 -> cleared; at scan 7 (10 - 19) / 2 = -4.5 <= -4
    assert bits(rows, "PVROCPosAlarm") == [0, 0, 1, 1, 0, 0, 0]
    assert bits(rows, "PVROCNegAlarm") == [0, 0, 0, 0, 0, 0, 1]


def test_real_time_sampling_computes_only_on_new_stamps(tmp_path: Path) -> None:
    body = (
        "p.TimingMode := 2; p.RTSTime := 100; p.IGain := 60.0; p.CVInitValue := 10.0;\n"
        "p.SPProg := 50.0; p.PV := 40.0;\n"
        + AUTO_PROG
        + "CASE n OF 1, 2: p.RTSTimeStamp := 1000; 3: p.RTSTimeStamp := 1100;\n"
        "4: p.RTSTimeStamp := 1300; END_CASE;\nPIDE(p);\n"
    )
    rows = run(tmp_path, body, 4, ["CV", "DeltaT", "RTSMissed", "Status2"])
    # scan 1 first stamp (DeltaT 0, initialisation 10); scan 2 same stamp: not executed;
    # scan 3 100 ms: +1 x 10 x 0.1 = 1 -> 11; scan 4 200 ms > RTSTime: RTSMissed
    # (Status2 bit 28 = 268435456), +1 x 10 x 0.2 = 2 -> 13
    assert num(rows, "CV") == pytest.approx([10.0, 10.0, 11.0, 13.0])
    assert num(rows, "DeltaT") == pytest.approx([0.0, 0.0, 0.1, 0.2])
    assert bits(rows, "RTSMissed") == [0, 0, 0, 1]
    assert num(rows, "Status2") == [0, 0, 0, 268435456]


def test_manual_limiting_and_hand_feedback_fault(tmp_path: Path) -> None:
    body = (
        "p.TimingMode := 1; p.OversampleDT := 1.0; p.CVHLimit := 70.0; p.CVROCLimit := 20.0;\n"
        "p.CVManLimiting := n <= 3; p.HandFB := 30.0; p.ProgHandReq := n >= 4;\n"
        "p.HandFBFault := n = 5;\n"
        "CASE n OF 1: p.CVOper := 10.0; 2, 3: p.CVOper := 90.0; END_CASE;\nPIDE(p);\n"
    )
    rows = run(tmp_path, body, 5, ["CV", "CVHAlarm", "CVROCAlarm", "Status1"])
    # scan 1 initialisation (CVInitValue 0, so CVOper 0 too); scan 2: the operator asks 90,
    # above CVHLimit 70 (CVOperInv, Status1 bit 13 + bit 0 = 8193) and at most 20 %/s x 1 s
    # from 0: 20; scan 3 (CVOper 90 again): 40. Scan 4 Hand: HandFB 30, no ROC limit in
    # Hand; scan 5 HandFBFault (Status1 bit 3 + bit 0 = 9): CV held at 30
    assert num(rows, "CV") == [0.0, 20.0, 40.0, 30.0, 30.0]
    assert bits(rows, "CVHAlarm") == [0, 1, 1, 0, 0]
    assert bits(rows, "CVROCAlarm") == [0, 1, 1, 0, 0]
    assert num(rows, "Status1") == [0, 8193, 8193, 0, 9]


def test_ratio_limits_and_cascade_setpoint_invalid(tmp_path: Path) -> None:
    body = (
        "p.TimingMode := 1; p.OversampleDT := 1.0; p.AllowCasRat := 1; p.UseRatio := 1;\n"
        "p.RatioHLimit := 2.0; p.RatioLLimit := 0.5; p.OperCasRatReq := 1;\n"
        "CASE n OF 1: p.RatioOper := 3.0; p.SPCascade := 40.0;\n"
        "2: p.RatioOper := 1.0; p.SPCascade := 120.0; END_CASE;\nPIDE(p);\n"
    )
    rows = run(tmp_path, body, 2, ["SP", "Ratio", "RatioHAlarm", "SPHAlarm", "Status1"])
    # scan 1: ratio 3 limited to 2 (RatioHAlarm, RatioOperInv bit 10): SP = 40 x 2 = 80;
    # Status1 = 1024 + 1 = 1025. Scan 2: SPCascade 120 above SPHLimit 100: SPCascadeInv
    # (bit 7) and limited to 100: SP = 100 x 1 = 100; Status1 = 128 + 1 = 129
    assert num(rows, "Ratio") == [2.0, 1.0]
    assert num(rows, "SP") == [80.0, 100.0]
    assert bits(rows, "RatioHAlarm") == [1, 0]
    assert bits(rows, "SPHAlarm") == [0, 0]
    assert num(rows, "Status1") == [1025, 129]


def test_reversed_cv_span(tmp_path: Path) -> None:
    body = (
        "p.TimingMode := 1; p.OversampleDT := 1.0; p.CVEUMin := 100.0; p.CVEUMax := 0.0;\n"
        "p.CVInitValue := 75.0; p.CVOper := 40.0;\nPIDE(p);\n"
    )
    rows = run(tmp_path, body, 2, ["CV", "CVEU"])
    # CVInitValue 75 on 100..0 is (75 - 100) x 100 / (0 - 100) = 25 %; then CVOper 40 %
    # -> CVEU = 100 + 40 x (0 - 100) / 100 = 60
    assert num(rows, "CV") == [25.0, 40.0]
    assert num(rows, "CVEU") == [75.0, 60.0]


def test_prescan_makes_the_next_execution_a_first_scan() -> None:
    from interpreter.instructions.pide import pide, pide_prescan
    from interpreter.vm.context import ExecContext
    from tests.instructions.structs import new_struct, struct_type

    ix = struct_type("PID_ENHANCED").index
    s = new_struct("PID_ENHANCED", TimingMode=1, OversampleDT=1.0, CVInitValue=30.0, CVOper=55.0)
    ctx = ExecContext()
    pide(ctx, True, s)
    assert (s[ix["CV"]], s[ix["CVINITIALIZING"]], s[ix["ENABLEOUT"]]) == (30.0, 1, 1)
    s[ix["CVOPER"]] = 55.0
    pide(ctx, True, s)
    assert (s[ix["CV"]], s[ix["CVINITIALIZING"]]) == (55.0, 0)  # Operator Manual
    pide_prescan(ctx, False, s)
    pide(ctx, True, s)
    assert (s[ix["CV"]], s[ix["CVINITIALIZING"]]) == (30.0, 1)  # initialised again


def test_closed_loop_settles_on_the_setpoint(tmp_path: Path) -> None:
    body = (
        "p.TimingMode := 1; p.OversampleDT := 0.1; p.PGain := 1.0; p.IGain := 12.0;\n"
        "p.SPProg := 60.0;\n" + AUTO_PROG + "PIDE(p);\n"
        "p.PV := p.PV + (1.5 * p.CV - p.PV) * 0.1 / 5.0;\n"  # tank: gain 1.5, lag 5 s
    )
    rows = run(tmp_path, body, 900, ["PV", "CV", "E"])
    # PI on a first-order process: the closed loop s^2 + 0.5 s + 0.06 has its poles at
    # -0.2 and -0.3 1/s, so after 90 s the transient is below e^-18 of the step. The
    # integral leaves no offset: PV = SP = 60 and CV = 60 / 1.5 = 40
    last = rows[-1]
    assert float(last["PV"]) == pytest.approx(60.0, abs=1e-3)
    assert float(last["CV"]) == pytest.approx(40.0, abs=1e-3)
    assert max(num(rows, "PV")) < 60.0 + 0.5  # real poles: no overshoot beyond rounding


def test_an_autotune_operand_is_rejected_in_structured_text(tmp_path: Path) -> None:
    # decision 0191: only a function block diagram can attach a PIDE_AUTOTUNE tag
    src = "VAR p : PID_ENHANCED; tune : PIDE_AUTOTUNE; END_VAR\nPIDE(p, tune);\n"
    _, report = trace(tmp_path, src, ".st", 1, [], expect_code=1)
    [d] = report["diagnostics"]
    assert (d["code"], d["line"], d["column"]) == ("E104", 2, 1)
    assert "PIDE takes 1 operand, 2 given" in d["message"]


def test_dependent_gains_scale_the_derivative_by_the_controller_gain(tmp_path: Path) -> None:
    body = (
        "p.TimingMode := 1; p.OversampleDT := 1.0; p.DependIndepend := 1; p.PGain := 2.0;\n"
        "p.DGain := 0.1; p.CVInitValue := 50.0; p.SPProg := 60.0;\n"
        + AUTO_PROG
        + "IF n <= 2 THEN p.PV := 40.0; ELSE p.PV := 41.0; END_IF;\nPIDE(p);\n"
    )
    rows = run(tmp_path, body, 4, ["CV"])
    # IGain 0: no integral. Scan 3, PV 40 -> 41: dE = -1, D = 60 x 0.1 x (-1) / 1 = -6;
    # dCV = Kc (dE + dD) = 2 x (-1 - 6) = -14 -> 36. Scan 4: dE 0, D back to 0:
    # 2 x (0 + 6) = +12 -> 48
    assert num(rows, "CV") == pytest.approx([50.0, 50.0, 36.0, 48.0])


def test_a_pv_that_is_not_a_number_is_bad_health() -> None:
    import math

    from interpreter.instructions.pide import pide
    from interpreter.vm.context import ExecContext
    from tests.instructions.structs import new_struct, struct_type

    ix = struct_type("PID_ENHANCED").index
    s = new_struct(
        "PID_ENHANCED", TimingMode=1, OversampleDT=1.0, IGain=60.0, PV=40.0, SPOper=50.0,
        CVInitValue=30.0, OperAutoReq=1, PVHLimit=10.0,
    )  # fmt: skip
    ctx = ExecContext()
    pide(ctx, True, s)
    assert (s[ix["AUTO"]], s[ix["CV"]], s[ix["PVHALARM"]]) == (1, 30.0, 1)
    s[ix["PV"]] = math.nan
    pide(ctx, True, s)
    # Auto is left for Manual, CV stays where it was (CVOper followed it), the PV alarms are
    # cleared; no Status bit names it (PVFault was not set)
    assert (s[ix["AUTO"]], s[ix["MANUAL"]], s[ix["CV"]], s[ix["PVHALARM"]]) == (0, 1, 30.0, 0)
    assert s[ix["STATUS1"]] == 0
    s[ix["PV"]], s[ix["OPERAUTOREQ"]] = 45.0, 1
    pide(ctx, True, s)
    # back in Auto: the integral moves from 30 by 1 x 5 x 1 = 5, with no memory of the NaN
    assert (s[ix["AUTO"]], s[ix["CV"]]) == (1, 35.0)
