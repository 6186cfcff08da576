"""Rotary axes through `logixst run` (decision 0115): positions wrap at PositionUnwind, and
moves, jogs, time cams, gears and watch positions carry on through the wrap.

Timing (motion_trace.py): an instruction executed in the scan at t = 0 takes effect at the
update at t0 = 2 ms; a trace row shows the state after the latest update at or before its
time, tu = 2 ms * floor(t / 2 ms). Expected positions are the unwrapped closed form taken
modulo the unwind; they are compared round the circle (359.99 and 0.01 are 0.02 apart).
Move durations: trapezoid with speed V, accel = decel = A reaching V over distance D:
T = D/V + V/A; with V = 100, A = 1000: T = D/100 + 0.1 s.
"""

from __future__ import annotations

import math

import pytest
from motion_trace import CUP, Trace

from interpreter.syntax.l5x import axis_rotary

T0 = 0.002
F32 = 1e-3  # float32 rounding of positions below 360
U = 360.0
DYN = "MaximumSpeed := 1000.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0"
HEAD = f"""VAR
  R : AXIS_VIRTUAL := (RotaryAxis := 1, PositionUnwind := 360.0, {DYN});
  L : AXIS_VIRTUAL := ({DYN});
  c1, c2, c3 : MOTION_INSTRUCTION;
  k : DINT;
"""
JOG = (
    "MAJ({axis}, {ctl}, {dir}, {v}, unitspersec, 1.0E30, unitspersec2, 1.0E30, unitspersec2,"
    " trapezoidal, 0.0, 0.0, unitspersec3, disabled, programmed, 0.0, none);"
)


def prog(decls: str, body: str) -> str:
    return HEAD + decls + "END_VAR\n" + body + "\nk := k + 1;\n"


def mam(axis: str, ctl: str, move_type: int | str, pos: float) -> str:
    return (
        f"MAM({axis}, {ctl}, {move_type}, {pos}, 100.0, unitspersec, 1000.0, unitspersec2,"
        " 1000.0, unitspersec2, trapezoidal, 0.0, 0.0, unitspersec3, disabled, programmed,"
        " 0.0, none, 0, 0);"
    )


def update_time(t: float) -> float:
    return CUP * math.floor(t / CUP + 1e-9)


def round_gap(a: float, b: float, u: float = U) -> float:
    """Distance of two positions round the circle."""
    d = abs(a - b) % u
    return min(d, u - d)


def check_wrapped(tr: Trace, name: str, unwrapped, tol: float, t0: float = 0.0) -> None:  # noqa: ANN001
    """Every row (from t0 on) lies in [0, 360) and matches unwrapped(tu) mod 360."""
    j = tr.names.index(name)
    for r in tr.rows:
        assert 0.0 <= r[j] < U, (name, r[0], r[j])
        if r[0] >= t0 - 1e-9:
            want = unwrapped(update_time(r[0])) % U
            assert round_gap(r[j], want) <= tol, (name, r[0], r[j], want)


def test_jog_runs_through_the_wrap(mp) -> None:
    # 100 u/s from 0, started at t0 (no ramp: accel 1e30): p(t) = 100 (tu - t0) mod 360;
    # the row at 5.002 s shows 100 * 5.0 = 500 -> 140
    src = prog("", "IF k = 0 THEN " + JOG.format(axis="R", ctl="c1", dir=0, v=100.0) + " END_IF;")
    tr = mp.trace(
        src,
        ["R.ActualPosition", "R.CommandPosition", "R.ActualVelocity", "R.AverageVelocity"],
        scans=5003,
    )
    for name in ("R.ActualPosition", "R.CommandPosition"):
        check_wrapped(tr, name, lambda t: 100.0 * max(t - T0, 0.0), F32)
    assert tr.at(5.002, "R.ActualPosition") == pytest.approx(140.0, abs=F32)
    # the wrap is no jump: velocity 100 at every update after the start, AverageVelocity
    # (0.25 s window by default... any window) also 100 once the window is past the start
    tr.check("R.ActualVelocity", lambda t: 100.0, 1e-3, t0=0.004)
    tr.check("R.AverageVelocity", lambda t: 100.0, 1e-3, t0=1.0)


def test_reverse_jog_wraps_below_zero(mp) -> None:
    # -50 u/s from 0: p = -50 (tu - t0) mod 360; at 1.002 s: -50 -> 310
    src = prog("", "IF k = 0 THEN " + JOG.format(axis="R", ctl="c1", dir=1, v=50.0) + " END_IF;")
    tr = mp.trace(src, ["R.CommandPosition"], scans=2000)
    check_wrapped(tr, "R.CommandPosition", lambda t: -50.0 * max(t - T0, 0.0), F32)
    assert tr.at(1.002, "R.CommandPosition") == pytest.approx(310.0, abs=F32)


@pytest.mark.parametrize(
    ("move_type", "target", "travel"),
    [
        (2, 10.0, 20.0),  # shortest path from 350 to 10: +20 through 0
        (2, 300.0, -50.0),  # shortest path from 350 to 300: -50
        (2, 170.0, 180.0),  # exactly half a turn: forward
        (3, 340.0, 350.0),  # positive from 350 to 340: almost a whole turn forward
        (4, 10.0, -340.0),  # negative from 350 to 10: backwards through 0
        (0, -90.0, -440.0),  # absolute -90 from 350 (the unwound axis): -440, ends at 270
        (0, 400.0, 50.0),  # absolute 400: +50, ends at 40
        (1, 30.0, 30.0),  # incremental: +30, ends at 20
    ],
)
def test_move_types_on_a_rotary_axis(mp, move_type: int, target: float, travel: float) -> None:
    src = prog(
        "",
        "IF k = 0 THEN " + mam("S", "c1", move_type, target) + " END_IF;",
    ).replace(
        "VAR\n",
        f"VAR\n  S : AXIS_VIRTUAL := (RotaryAxis := 1, PositionUnwind := 360.0, ActualPosition := 350.0, {DYN});\n",
        1,
    )
    d = abs(travel)
    dur = d / 100.0 + 0.1  # trapezoid at 100 u/s, ramps 0.1 s covering 10 units in all
    scans = round((T0 + dur) / 0.001) + 20
    tr = mp.trace(src, ["S.CommandPosition", "S.CommandVelocity", "c1.PC", "c1.ER"], scans=scans)
    assert tr.at(0.0, "c1.ER") == 0
    pc = tr.first("c1.PC", lambda v: v == 1)
    assert T0 + dur - 1e-9 <= pc <= T0 + dur + CUP + 1e-9, (pc, T0 + dur)
    end = tr.rows[-1][tr.names.index("S.CommandPosition")]
    assert round_gap(end, (350.0 + travel) % U) <= F32
    assert 0.0 <= end < U
    # the direction: half way through the cruise the velocity is 100 with travel's sign
    mid = update_time(T0 + dur / 2)
    assert tr.at(mid, "S.CommandVelocity") == pytest.approx(math.copysign(100.0, travel))
    # and the position there is the closed form: half the travel done
    assert round_gap(tr.at(mid, "S.CommandPosition"), 350.0 + travel / 2) <= 0.2 + F32


@pytest.mark.parametrize(
    ("decls", "body", "err", "exerr"),
    [
        # a rotary move type on a linear axis: error 17 (Axis Mode Not Rotary)
        ("", mam("L", "c1", 2, 10.0), 17, 0),
        ("", mam("L", "c1", 3, 10.0), 17, 0),
        ("", mam("L", "c1", 4, 10.0), 17, 0),
        # the target of a rotary move lies on the circle: 0 <= Position < unwind, else
        # error 13 with the Position operand's index (3)
        ("", mam("R", "c1", 2, 360.0), 13, 3),
        ("", mam("R", "c1", 3, -1.0), 13, 3),
        # a rotary axis needs an unwind > 0: not configured, error 11, whatever the motion
        (f"  Z : AXIS_VIRTUAL := (RotaryAxis := 1, PositionUnwind := 0.0, {DYN});\n", mam("Z", "c1", 0, 10.0), 11, 0),
        (f"  Z : AXIS_VIRTUAL := (RotaryAxis := 1, PositionUnwind := 0.0, {DYN});\n", JOG.format(axis="Z", ctl="c1", dir=0, v=1.0), 11, 0),
    ],
)  # fmt: skip
def test_rotary_errors(mp, decls: str, body: str, err: int, exerr: int) -> None:
    src = prog(decls, "IF k = 0 THEN " + body + " END_IF;")
    tr = mp.trace(src, ["c1.ER", "c1.ERR", "c1.EXERR", "c1.IP"], scans=5)
    assert [tr.at(0.0, n) for n in ("c1.ER", "c1.ERR", "c1.EXERR", "c1.IP")] == [1, err, exerr, 0]


def test_linear_axis_with_unwind_does_not_wrap(mp) -> None:
    # PositionUnwind alone (RotaryAxis 0) changes nothing: a linear axis counts on
    src = prog(
        f"  P : AXIS_VIRTUAL := (PositionUnwind := 360.0, {DYN});\n",
        "IF k = 0 THEN " + JOG.format(axis="P", ctl="c1", dir=0, v=100.0) + " END_IF;",
    )
    tr = mp.trace(src, ["P.CommandPosition"], scans=5003)
    assert tr.at(5.002, "P.CommandPosition") == pytest.approx(500.0, abs=F32)


def test_time_cam_runs_through_the_wrap(mp) -> None:
    # continuous time cam, linear (0,0)-(1,90): 90 u per 1 s pass, p = 90 (tu - t0) mod 360
    src = prog(
        """  lin : CAM_PROFILE[2] := [(Master := 0.0, Slave := 0.0, SegmentType := 0),
                           (Master := 1.0, Slave := 90.0, SegmentType := 0)];
""",
        "IF k = 0 THEN MATC(R, c1, 0, lin, 1.0, 1.0, continuous, immediate, 0.0, none,"
        " timedrivenmode); END_IF;",
    )
    tr = mp.trace(src, ["R.CommandPosition", "R.CommandVelocity", "c1.ER"], scans=6000)
    assert tr.at(0.0, "c1.ER") == 0
    check_wrapped(tr, "R.CommandPosition", lambda t: 90.0 * max(t - T0, 0.0), 2e-3)
    tr.check("R.CommandVelocity", lambda t: 90.0, 1e-3, t0=0.004)


def test_servo_follows_through_the_wrap(mp) -> None:
    # AXIS_CIP_DRIVE, PositionLoopBandwidth 40 Hz: tau = 1/(2 pi 40), alpha = 1 - exp(-cup/tau)
    # (servo.py). A ramp command of v per second settles to a following error
    # e = (1 - alpha) v cup / alpha (from e = (1 - alpha)(e + v cup)); the wrap of the
    # command or of the actual position must not show in it.
    src = prog(
        f"  D : AXIS_CIP_DRIVE := (RotaryAxis := 1, PositionUnwind := 360.0, PositionLoopBandwidth := 40.0, {DYN});\n",
        "IF k = 0 THEN MSO(D, c2); " + JOG.format(axis="D", ctl="c1", dir=0, v=200.0) + " END_IF;",
    )
    tr = mp.trace(
        src,
        ["D.PositionError", "D.ActualPosition", "D.CommandPosition", "D.ActualVelocity"],
        scans=4000,
    )
    tau = 1.0 / (2.0 * math.pi * 40.0)
    alpha = 1.0 - math.exp(-CUP / tau)
    e = (1.0 - alpha) * 200.0 * CUP / alpha
    tr.check("D.PositionError", lambda t: e, 1e-3, t0=0.2)
    tr.check("D.ActualVelocity", lambda t: 200.0, 1e-2, t0=0.2)
    # actual = command - e, both wrapped
    check_wrapped(tr, "D.ActualPosition", lambda t: 200.0 * (t - T0) - e, 2e-3, t0=0.2)
    check_wrapped(tr, "D.CommandPosition", lambda t: 200.0 * max(t - T0, 0.0), F32)


def test_gear_counts_master_travel_through_the_wrap(mp) -> None:
    # a linear slave geared 1:1 to a rotary master jogging at 100 u/s: the slave counts the
    # master's travel, not its wrapped position: 100 (tu - t0), the gear engaged at the
    # update the jog starts at (both executed in scan 0), the master at 0 then
    src = prog(
        "",
        "IF k = 0 THEN "
        + JOG.format(axis="R", ctl="c1", dir=0, v=100.0)
        + " MAG(L, R, c2, same, 1.0, 1, 1, command, real, disabled, 0.0, unitspersec2); END_IF;",
    )
    tr = mp.trace(src, ["L.CommandPosition", "R.CommandPosition", "c2.ER"], scans=6000)
    assert tr.at(0.0, "c2.ER") == 0
    tr.check("L.CommandPosition", lambda t: 100.0 * max(update_time(t) - T0, 0.0), 2e-3)
    assert tr.at(5.0, "L.CommandPosition") > U  # more than a turn, counted on


def test_watch_position_crossed_by_the_wrap(mp) -> None:
    # jog at 100 u/s from 0 (0.2 per update); MAW forward to 359.9 armed at t = 1 s
    # (position 99.8): the axis passes 359.9 in the update that wraps it (359.8 -> 0.0),
    # at unwrapped travel 360.0: t = t0 + 3.6 = 3.602 s
    src = prog(
        "",
        "IF k = 0 THEN " + JOG.format(axis="R", ctl="c1", dir=0, v=100.0) + " END_IF;\n"
        "IF k = 1000 THEN MAW(R, c2, forward, 359.9); END_IF;",
    )
    tr = mp.trace(src, ["c2.PC", "R.ActualPosition", "c2.ER"], scans=5000)
    assert tr.at(1.0, "c2.ER") == 0
    fired = tr.first("c2.PC", lambda v: v == 1)
    assert fired == pytest.approx(3.602, abs=1e-6)


def test_axis_rotary_from_the_export() -> None:
    # older axes: PositionUnwind in feedback counts, ConversionConstant counts per unit
    assert axis_rotary(
        {"ROTARYAXIS": "Rotary", "POSITIONUNWIND": "360000", "CONVERSIONCONSTANT": "1000.0"}
    ) == (True, 360.0)
    assert axis_rotary({"ROTARYAXIS": "Linear", "POSITIONUNWIND": "8000"}) == (False, 0.0)
    # CIP axes: TravelMode Cyclic, the unwind in position units as a fraction
    assert axis_rotary(
        {"TRAVELMODE": "Cyclic", "POSITIONUNWINDNUMERATOR": "20.0",
         "POSITIONUNWINDDENOMINATOR": "2.0", "ROTARYAXIS": "Linear"}
    ) == (True, 10.0)  # fmt: skip
    assert axis_rotary({"TRAVELMODE": "Unlimited", "POSITIONUNWINDNUMERATOR": "1.0"}) == (
        False,
        0.0,
    )
    assert axis_rotary({"MAXIMUMSPEED": "10"}) is None


L5X = """<?xml version="1.0" encoding="UTF-8" standalone="yes"?>
<RSLogix5000Content SchemaRevision="1.0" SoftwareRevision="32.00" TargetName="C" TargetType="Controller" ContainsContext="false">
<Controller Use="Target" Name="C" ProcessorType="1756-L83E" MajorRev="32" MinorRev="11">
<Tags>
<Tag Name="Grp" TagType="Base" DataType="MOTION_GROUP">
<Data Format="MotionGroup"><MotionGroupParameters CoarseUpdatePeriod="2000"/></Data>
</Tag>
<Tag Name="Old" TagType="Base" DataType="AXIS_VIRTUAL">
<Data Format="Axis"><AxisParameters MotionGroup="Grp" ConversionConstant="1000.0" RotaryAxis="Rotary" PositionUnwind="360000" MaximumSpeed="1000.0" MaximumAcceleration="1000.0" MaximumDeceleration="1000.0"/></Data>
</Tag>
<Tag Name="Cip" TagType="Base" DataType="AXIS_VIRTUAL">
<Data Format="Axis"><AxisParameters MotionGroup="Grp" TravelMode="Cyclic" PositionUnwindNumerator="90.0" PositionUnwindDenominator="1.0" MaximumSpeed="1000.0" MaximumAcceleration="1000.0" MaximumDeceleration="1000.0"/></Data>
</Tag>
<Tag Name="c1" TagType="Base" DataType="MOTION_INSTRUCTION"/>
<Tag Name="c2" TagType="Base" DataType="MOTION_INSTRUCTION"/>
<Tag Name="k" TagType="Base" DataType="DINT" Radix="Decimal"/>
</Tags>
<Programs>
<Program Name="Main" MainRoutineName="R">
<Routines>
<Routine Name="R" Type="ST">
<STContent>
<Line Number="0"><![CDATA[IF k = 0 THEN]]></Line>
<Line Number="1"><![CDATA[MAJ(Old, c1, 0, 100.0, 0, 1.0E30, 0, 1.0E30, 0, 0, 0.0, 0.0, 0, 0, 0, 0.0, 0);]]></Line>
<Line Number="2"><![CDATA[MAJ(Cip, c2, 0, 100.0, 0, 1.0E30, 0, 1.0E30, 0, 0, 0.0, 0.0, 0, 0, 0, 0.0, 0);]]></Line>
<Line Number="3"><![CDATA[END_IF;]]></Line>
<Line Number="4"><![CDATA[k := k + 1;]]></Line>
</STContent>
</Routine>
</Routines>
</Program>
</Programs>
<Tasks>
<Task Name="T" Type="CONTINUOUS" Priority="10" Watchdog="500">
<ScheduledPrograms><ScheduledProgram Name="Main"/></ScheduledPrograms>
</Task>
</Tasks>
</Controller>
</RSLogix5000Content>
"""


def test_rotary_axes_of_an_export(mp) -> None:
    # Old: 360000 counts / 1000 counts per unit = 360; Cip: 90 / 1 = 90. Both jog at 100 u/s
    # from t0: at 5.002 s, 500 -> 500 mod 360 = 140 and 500 mod 90 = 50.
    tr = mp.trace(
        L5X,
        ["Old.CommandPosition", "Cip.CommandPosition", "Old.PositionUnwind", "Cip.RotaryAxis"],
        scans=5003,
        name="rotary.L5X",
    )
    assert tr.at(0.0, "Old.PositionUnwind") == pytest.approx(360.0)
    assert tr.at(0.0, "Cip.RotaryAxis") == 1
    assert tr.at(5.002, "Old.CommandPosition") == pytest.approx(140.0, abs=F32)
    assert tr.at(5.002, "Cip.CommandPosition") == pytest.approx(50.0, abs=F32)


def test_master_driven_time_cam_follows_a_rotary_master(mp) -> None:
    # the slave L runs a continuous master-driven cam (0,0)-(360,720) on the rotary master R
    # (MDAC, time cam): it moves twice the master's travel, through the master's wraps
    # (at 3.602 s and 7.202 s): from 1 s on, L(t) - L(1) = 2 * 100 * (tu - 1)
    src = prog(
        """  big : CAM_PROFILE[2] := [(Master := 0.0, Slave := 0.0, SegmentType := 0),
                           (Master := 360.0, Slave := 720.0, SegmentType := 0)];
""",
        "IF k = 0 THEN "
        + JOG.format(axis="R", ctl="c1", dir=0, v=100.0)
        + " MDAC(L, R, c2, timecam, command);"
        " MATC(L, c3, 0, big, 1.0, 1.0, continuous, immediate, 0.0, none, masterdrivenmode);"
        " END_IF;",
    )
    tr = mp.trace(src, ["L.CommandPosition", "c3.ER"], scans=8000)
    assert tr.at(0.0, "c3.ER") == 0
    base = tr.at(1.0, "L.CommandPosition")
    tr.check("L.CommandPosition", lambda t: base + 200.0 * (update_time(t) - 1.0), 5e-3, t0=1.0)


def test_tag_shows_a_position_just_below_the_unwind_as_zero(mp) -> None:
    # an incremental move of -1e-6 from 0 ends at 360 - 1e-6 = 359.999999, which float32
    # (spacing 3.05e-5 near 360) rounds to 360.0, the unwind itself: the REAL tag shows 0.0
    src = prog("", "IF k = 0 THEN " + mam("R", "c1", "incremental", -0.000001) + " END_IF;")
    tr = mp.trace(src, ["R.ActualPosition", "R.CommandPosition", "c1.PC"], scans=100)
    assert tr.rows[-1][tr.names.index("c1.PC")] == 1
    for name in ("R.ActualPosition", "R.CommandPosition"):
        assert all(0.0 <= v < U for v in tr.col(name))
        assert tr.rows[-1][tr.names.index(name)] == 0.0


def test_reverse_watch_position_crossed_by_the_wrap(mp) -> None:
    # reverse jog at 50 u/s from 0 (-0.1 per update from the update after t0); MAW reverse
    # to 359.95 armed in the same scan (actual 0): the first moving update goes 0 -> 359.9,
    # i.e. -0.1, passing 359.95 (= -0.05): it fires at t0 + 2 ms = 0.004 s
    src = prog(
        "",
        "IF k = 0 THEN "
        + JOG.format(axis="R", ctl="c1", dir=1, v=50.0)
        + " MAW(R, c2, reverse, 359.95); END_IF;",
    )
    tr = mp.trace(src, ["c2.PC", "c2.ER", "R.ActualPosition"], scans=50)
    assert tr.at(0.0, "c2.ER") == 0
    assert tr.first("c2.PC", lambda v: v == 1) == pytest.approx(0.004, abs=1e-9)


def test_redefine_and_home_onto_the_circle(mp) -> None:
    # MRP absolute 725 at scan 0 (the update t0): 725 mod 360 = 5; MAH passive with
    # HomePosition 400 at scan 100 (the update 0.1): 400 mod 360 = 40. Nothing moves.
    src = prog(
        f"  H : AXIS_VIRTUAL := (RotaryAxis := 1, PositionUnwind := 360.0, HomeMode := 0, HomePosition := 400.0, {DYN});\n",
        "IF k = 0 THEN MRP(R, c1, absolute, actual, 725.0); END_IF;\n"
        "IF k = 100 THEN MAH(H, c2); END_IF;",
    )
    watch = ["R.ActualPosition", "R.CommandPosition", "H.ActualPosition", "c1.DN", "c2.PC"]
    tr = mp.trace(src, watch, scans=200)
    assert tr.at(0.002, "c1.DN") == 1 and tr.at(0.102, "c2.PC") == 1
    assert tr.at(0.002, "R.ActualPosition") == pytest.approx(5.0, abs=F32)
    assert tr.at(0.002, "R.CommandPosition") == pytest.approx(5.0, abs=F32)
    assert tr.at(0.102, "H.ActualPosition") == pytest.approx(40.0, abs=F32)
