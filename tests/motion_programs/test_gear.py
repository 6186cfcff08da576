"""MAG (electronic gearing) and MCD (change dynamics) through the VM, against hand formulas.

Master jog used below (as in test_mdac): MAJ forward 10 units/s, accel 1000 units/s^2,
executed at t = 0, so it starts at the update t0 = 2 ms and reaches speed after 10 ms having
covered 0.05 units:
    m(t) = 500 (t - t0)^2 for t <= 0.012, else 0.05 + 10 (t - 0.012).
A gear executed in the same scan engages at the same update (master at 0, at rest), so a
gear of ratio r gives the slave s(t) = r m(t) exactly (no clutch needed from rest).
A trace row at t shows the values of the latest update at or before t: expectations are
evaluated at upd(t).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import pytest
from motion_trace import CUP

F32 = 1e-4
HEAD = """VAR
  M, S, T : AXIS_VIRTUAL := (MaximumSpeed := 1000.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0);
  c1, c2, c3, c4, c5, cj : MOTION_INSTRUCTION;
  k : DINT;
"""
JOG_M = "MAJ(M, cj, forward, 10.0, unitspersec, 1000.0, unitspersec2, 1000.0, unitspersec2, trapezoidal, 0.0, 0.0, unitspersec3, disabled, programmed, 0.0, none);"


def prog(decls: str, body: str) -> str:
    return HEAD + decls + "END_VAR\n" + body + "\nk := k + 1;\n"


def upd(t: float) -> float:
    """Time of the latest planner update at or before t."""
    return math.floor(t / CUP + 1e-9) * CUP


def at_update(f: Callable[[float], float]) -> Callable[[float], float]:
    return lambda t: f(upd(t))


def m(t: float) -> float:
    t0 = 0.002
    if t <= t0:
        return 0.0
    if t <= 0.012:
        return 500.0 * (t - t0) ** 2
    return 0.05 + 10.0 * (t - 0.012)


def mag(slave: str, ctl: str, direction: str, ratio: float, *, sc: int = 1, mc: int = 1,
        ref: str = "command", fmt: str = "real", clutch: str = "disabled", accel: float = 0.0,
        units: str = "unitspersec2") -> str:  # fmt: skip
    return f"MAG({slave}, M, {ctl}, {direction}, {ratio}, {sc}, {mc}, {ref}, {fmt}, {clutch}, {accel}, {units});"


def test_ratio_two_slave_is_twice_the_master_travel(mp) -> None:
    # engaged at the master's start: s(t) = 2 m(t); steady slave speed 2 x 10 = 20 units/s
    body = f"IF k = 0 THEN {JOG_M} {mag('S', 'c1', 'same', 2.0)} END_IF;"
    tr = mp.trace(
        prog("", body),
        [
            "S.CommandPosition",
            "S.CommandVelocity",
            "c1.DN",
            "c1.IP",
            "c1.PC",
            "S.GearingStatus",
            "S.GearingLockStatus",
        ],
        scans=400,
    )
    tr.check("S.CommandPosition", at_update(lambda t: 2.0 * m(t)), F32)
    assert abs(tr.at(0.3, "S.CommandVelocity") - 20.0) < 1e-3
    assert (tr.at(0.0, "c1.DN"), tr.at(0.0, "c1.IP")) == (1, 1)
    # status from the engaging update on; MAG never completes
    assert (tr.at(0.001, "S.GearingStatus"), tr.at(0.002, "S.GearingStatus")) == (0, 1)
    assert tr.at(0.002, "S.GearingLockStatus") == 1
    assert (tr.at(0.399, "c1.IP"), tr.at(0.399, "c1.PC")) == (1, 0)


def test_fraction_of_counts_and_opposite_direction(mp) -> None:
    # Fraction 3 slave counts per 4 master counts; ConversionConstant (counts per unit)
    # slave 2, master 8: 1 master unit = 8 counts -> 6 slave counts = 3 slave units.
    # Opposite: s(t) = -3 m(t).
    decls = (
        "  A : AXIS_VIRTUAL := (ConversionConstant := 2.0);\n"
        "  B : AXIS_VIRTUAL := (ConversionConstant := 8.0, MaximumSpeed := 1000.0, "
        "MaximumAccel := 1000.0, MaximumDecel := 1000.0);\n  cb : MOTION_INSTRUCTION;\n"
    )
    jog_b = JOG_M.replace("MAJ(M, cj", "MAJ(B, cb")
    gear = mag("A", "c1", "opposite", 0.0, sc=3, mc=4, fmt="fractionslavemastercounts")
    body = f"IF k = 0 THEN {jog_b} {gear.replace(', M,', ', B,')} END_IF;"
    tr = mp.trace(prog(decls, body), ["A.CommandPosition", "c1.ER"], scans=300)
    assert tr.at(0.0, "c1.ER") == 0
    tr.check("A.CommandPosition", at_update(lambda t: -3.0 * m(t)), 3 * F32)


@pytest.mark.parametrize(("accel", "units"), [(100.0, "unitspersec2"), (10.0, "%ofmaximum")])
def test_clutch_ramps_to_the_geared_speed_then_locks(mp, accel: float, units: str) -> None:
    # MAG at t = 0.1 (engages at the update 0.102) on a master at 10 units/s, ratio 2, clutch
    # 100 units/s^2 (or 10 % of S.MaximumAccel 1000): the slave ramps 0 -> 20 units/s in
    # v/a = 0.2 s, covering 20^2 / 200 = 2,
    #   s(t) = 50 (t - 0.102)^2 until 0.302, then locked: 2 + 2 (m(t) - m(0.302)).
    gear = mag("S", "c1", "same", 2.0, clutch="enabled", accel=accel, units=units)
    body = f"""IF k = 0 THEN {JOG_M} END_IF;
IF k = 100 THEN {gear} END_IF;"""

    def s(t: float) -> float:
        if t <= 0.102:
            return 0.0
        if t <= 0.302:
            return 50.0 * (t - 0.102) ** 2
        return 2.0 + 2.0 * (m(t) - m(0.302))

    tr = mp.trace(
        prog("", body),
        ["S.CommandPosition", "S.CommandVelocity", "S.GearingStatus", "S.GearingLockStatus"],
        scans=500,
    )
    tr.check("S.CommandPosition", at_update(s), F32)
    assert abs(tr.at(0.202, "S.CommandVelocity") - 10.0) < 1e-3  # halfway up the ramp
    assert tr.at(0.102, "S.GearingStatus") == 1
    # clutching: not locked; locks at the update where the ramp reaches 20 units/s
    assert tr.first("S.GearingLockStatus", lambda v: v == 1) == 0.302


def test_gear_superimposes_on_a_move_of_the_slave(mp) -> None:
    # gearing stays active through the slave's own moves: slave = 2 m(t) + its MAM
    # (incremental 1, V 10, A = Dc = 1000: T = 0.1 + 0.01 = 0.11 s, started at 0.202)
    move = "MAM(S, c2, incremental, 1.0, 10.0, unitspersec, 1000.0, unitspersec2, 1000.0, unitspersec2, trapezoidal, 0.0, 0.0, unitspersec3, disabled, programmed, 0.0, none, 0, 0);"
    body = f"IF k = 0 THEN {JOG_M} {mag('S', 'c1', 'same', 2.0)} END_IF;\nIF k = 200 THEN {move} END_IF;"
    tr = mp.trace(prog("", body), ["S.CommandPosition", "c1.IP", "c2.PC"], scans=400)
    assert abs(tr.at(0.399, "S.CommandPosition") - (2.0 * m(0.398) + 1.0)) < F32
    assert (tr.at(0.399, "c1.IP"), tr.at(0.312, "c2.PC")) == (1, 1)


def test_mas_gear_brings_the_slave_to_rest(mp) -> None:
    # locked at 20 units/s; MAS Gear at t = 0.2 (update 0.202), decel 100 units/s^2:
    # 0.2 s and 20^2 / 200 = 2 units from s(0.202) = 2 m(0.202); MAS PC at 0.402.
    stop = "MAS(S, c2, gear, yes, 100.0, unitspersec2, no, 0.0, unitspersec3);"
    body = f"IF k = 0 THEN {JOG_M} {mag('S', 'c1', 'same', 2.0)} END_IF;\nIF k = 200 THEN {stop} END_IF;"

    def s(t: float) -> float:
        if t <= 0.202:
            return 2.0 * m(t)
        tau = min(t, 0.402) - 0.202
        return 2.0 * m(0.202) + 20.0 * tau - 50.0 * tau * tau

    tr = mp.trace(
        prog("", body),
        ["S.CommandPosition", "c1.IP", "c2.PC", "S.GearingStatus", "S.StoppingStatus"],
        scans=500,
    )
    tr.check("S.CommandPosition", at_update(s), F32)
    assert (tr.at(0.201, "c1.IP"), tr.at(0.202, "c1.IP"), tr.at(0.202, "S.GearingStatus")) == (
        1,
        0,
        0,
    )
    assert (tr.at(0.401, "c2.PC"), tr.at(0.402, "c2.PC")) == (0, 1)


def test_new_mag_changes_the_ratio_and_reverse_flips_the_direction(mp) -> None:
    # ratio 2 from the start; at t = 0.2 (update 0.202) MAG Reverse ratio 1 (no clutch):
    # s(t) = 2 m(0.202) - (m(t) - m(0.202)); the first MAG ends (IP cleared), the second runs
    body = f"""IF k = 0 THEN {JOG_M} {mag("S", "c1", "same", 2.0)} END_IF;
IF k = 200 THEN {mag("S", "c2", "reverse", 1.0)} END_IF;"""

    def s(t: float) -> float:
        return 2.0 * m(t) if t <= 0.202 else 2.0 * m(0.202) - (m(t) - m(0.202))

    tr = mp.trace(prog("", body), ["S.CommandPosition", "c1.IP", "c2.IP"], scans=400)
    tr.check("S.CommandPosition", at_update(s), F32)
    assert (tr.at(0.202, "c1.IP"), tr.at(0.202, "c2.IP")) == (0, 1)


def test_mag_errors(mp) -> None:
    # Logix motion error table: 10 Master Axis Conflict (slave = master), 13 Parameter Out Of
    # Range with EXERR = faceplate index (MasterCounts 6, clutch accel 10), 5 Servo Off State
    # (drive slave without MSO)
    decls = "  D : AXIS_CIP_DRIVE;\n"
    body = f"""IF k = 0 THEN
  MAG(M, M, c1, same, 1.0, 1, 1, command, real, disabled, 0.0, unitspersec2);
  {mag("S", "c2", "same", 0.0, mc=0, fmt="fractionslavemastercounts")}
  {mag("S", "c3", "same", 1.0, clutch="enabled", accel=0.0)}
  {mag("D", "c4", "same", 1.0)}
END_IF;"""
    names = ["c1.ERR", "c2.ERR", "c2.EXERR", "c3.ERR", "c3.EXERR", "c4.ERR", "c4.ER"]
    tr = mp.trace(prog(decls, body), names, scans=2)
    assert [tr.at(0.0, n) for n in names] == [10, 13, 6, 13, 10, 5, 1]


# ------------------------------------------------------------------ MCD
MOVE_T = (
    "MAM(T, c1, incremental, 20.0, 10.0, unitspersec, 100.0, unitspersec2, 100.0, unitspersec2, "
    "trapezoidal, 0.0, 0.0, unitspersec3, disabled, programmed, 0.0, none, 0, 0);"
)
JOG_T = (
    "MAJ(T, c1, forward, 10.0, unitspersec, 100.0, unitspersec2, 100.0, unitspersec2, "
    "trapezoidal, 0.0, 0.0, unitspersec3, disabled, programmed, 0.0, none);"
)


def mcd(
    kind: str,
    speed: float | None = None,
    accel: float | None = None,
    ctl: str = "c2",
    speed_units: str = "unitspersec",
) -> str:
    cs, sp = ("yes", speed) if speed is not None else ("no", 0.0)
    ca, ac = ("yes", accel) if accel is not None else ("no", 0.0)
    return (
        f"MCD(T, {ctl}, {kind}, {cs}, {sp}, {ca}, {ac}, no, 0.0, no, 0.0, no, 0.0, "
        f"{speed_units}, unitspersec2, unitspersec2, unitspersec3);"
    )


def x_move(t: float) -> float:
    """MAM 20 at V 10, A = Dc = 100 from the update 0.002, before any change: 0.1 s ramps
    covering 0.5 each, so x = 50 (t - 0.002)^2, then 0.5 + 10 (t - 0.102)."""
    if t <= 0.002:
        return 0.0
    if t <= 0.102:
        return 50.0 * (t - 0.002) ** 2
    return 0.5 + 10.0 * (t - 0.102)


@pytest.mark.parametrize(("speed", "units"), [(20.0, "unitspersec"), (2.0, "%ofmaximum")])
def test_mcd_raises_the_speed_of_a_move_which_keeps_its_end_point(
    mp, speed: float, units: str
) -> None:
    # MCD Move speed 20 (or 2 % of T.MaximumSpeed 1000) at t = 0.5 (update 0.502, x = 4.5 at
    # 10 units/s, 15.5 to go): accel 10 -> 20 in 0.1 s (1.5 units), decel 20 -> 0 in 0.2 s
    # (2 units), cruise 15.5 - 3.5 = 12 at 20 units/s (0.6 s): PC at 0.502 + 0.9 = 1.402.
    change = mcd("move", speed=speed, speed_units=units)
    body = f"IF k = 0 THEN {MOVE_T} END_IF;\nIF k = 500 THEN {change} END_IF;"

    def x(t: float) -> float:
        if t <= 0.502:
            return x_move(t)
        tau = t - 0.502
        if tau <= 0.1:
            return 4.5 + 10.0 * tau + 50.0 * tau * tau
        if tau <= 0.7:
            return 6.0 + 20.0 * (tau - 0.1)
        r = min(tau, 0.9) - 0.7
        return 18.0 + 20.0 * r - 50.0 * r * r

    tr = mp.trace(
        prog("", body),
        ["T.CommandPosition", "T.CommandVelocity", "c1.IP", "c1.PC", "c2.DN", "c2.IP"],
        scans=1600,
    )
    tr.check("T.CommandPosition", at_update(x), F32)
    assert abs(tr.at(0.8, "T.CommandVelocity") - 20.0) < 1e-3
    assert (tr.at(1.401, "c1.PC"), tr.at(1.402, "c1.PC"), tr.at(1.402, "c1.IP")) == (0, 1, 0)
    # MCD completes in the executing scan: DN at once, no process of its own
    assert (tr.at(0.5, "c2.DN"), tr.at(0.5, "c2.IP")) == (1, 0)


def test_mcd_changes_jog_speed_and_acceleration(mp) -> None:
    # jog at 10 (accel 100: at speed from 0.102, x = 0.5 + 10 (t - 0.102)); at t = 0.5
    # (update 0.502) MCD speed 20, accel 50: 0.2 s ramp covering 3, then 20 units/s.
    body = f"IF k = 0 THEN {JOG_T} END_IF;\nIF k = 500 THEN {mcd('jog', speed=20.0, accel=50.0)} END_IF;"

    def x(t: float) -> float:
        if t <= 0.502:
            return x_move(t)
        tau = min(t - 0.502, 0.2)
        return 4.5 + 10.0 * tau + 25.0 * tau * tau + 20.0 * (t - 0.502 - tau)

    tr = mp.trace(prog("", body), ["T.CommandPosition", "c1.IP", "T.JogStatus"], scans=900)
    tr.check("T.CommandPosition", at_update(x), F32)
    assert (tr.at(0.899, "c1.IP"), tr.at(0.899, "T.JogStatus")) == (1, 1)


def test_mcd_speed_zero_pauses_a_jog_and_errors(mp) -> None:
    # speed 0: the jog decelerates at its decel (100) from 10 in 0.1 s covering 0.5 and stays
    # in process. Negative speed: ERR 13, EXERR 4 (Speed). Nothing running: no effect, DN.
    body = f"""IF k = 0 THEN {JOG_T} {mcd("move", speed=5.0, ctl="c4")} END_IF;
IF k = 500 THEN {mcd("jog", speed=0.0)} {mcd("jog", speed=-1.0, ctl="c3")} END_IF;"""
    tr = mp.trace(
        prog("", body),
        ["T.CommandPosition", "c1.IP", "c3.ERR", "c3.EXERR", "c4.DN", "c4.ER"],
        scans=800,
    )
    assert abs(tr.at(0.799, "T.CommandPosition") - 5.0) < F32  # 4.5 + 0.5
    assert tr.at(0.799, "c1.IP") == 1
    assert (tr.at(0.5, "c3.ERR"), tr.at(0.5, "c3.EXERR")) == (13, 4)
    assert (tr.at(0.0, "c4.DN"), tr.at(0.0, "c4.ER")) == (1, 0)
    assert CUP == 0.002


def test_mcd_units_of_the_other_mode_are_a_units_conflict(mp) -> None:
    # a time-driven jog changed with Units per MasterUnit: 94 MDSC Units Conflict; mixing
    # the modes among the changed values is 94 as well
    md = mcd("jog", speed=2.0, ctl="c3", speed_units="unitspermasterunit")
    mixed = (
        "MCD(T, c4, jog, yes, 2.0, yes, 5.0, no, 0.0, no, 0.0, no, 0.0, "
        "unitspersec, unitspermasterunit2, unitspersec2, unitspersec3);"
    )
    body = f"IF k = 0 THEN {JOG_T} END_IF;\nIF k = 10 THEN {md} {mixed} END_IF;"
    tr = mp.trace(prog("", body), ["c3.ERR", "c4.ERR", "c1.IP"], scans=12)
    assert (tr.at(0.01, "c3.ERR"), tr.at(0.01, "c4.ERR"), tr.at(0.011, "c1.IP")) == (94, 94, 1)


def test_actual_reference_follows_a_drive_masters_actual_position(mp) -> None:
    # D is a drive (servo lag). S is geared 1.5:1 to D's actual position, T to its command
    # position, both engaged at rest (update 0.002, D at 0), D jogs from the update 0.004:
    # S = 1.5 Dact and T = 1.5 Dcmd at every update. In steady state at 10 units/s the drive
    # lags by e = v cup q / (1 - q), q = exp(-cup / tau), tau = 1/(2 pi 20 Hz) (decision
    # 0100), so T - S = 1.5 e.
    decls = "  D : AXIS_CIP_DRIVE := (MaximumSpeed := 1000.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0);\n  co : MOTION_INSTRUCTION;\n"
    jog_d = JOG_M.replace("MAJ(M, cj", "MAJ(D, cj")
    act = mag("S", "c1", "same", 1.5, ref="actual").replace(", M,", ", D,")
    cmd = mag("T", "c2", "same", 1.5, ref="command").replace(", M,", ", D,")
    body = f"IF k = 0 THEN MSO(D, co); {act} {cmd} END_IF;\nIF k = 2 THEN {jog_d} END_IF;"
    names = ["S.CommandPosition", "T.CommandPosition", "D.ActualPosition", "D.CommandPosition"]
    tr = mp.trace(prog(decls, body), names, scans=400)
    for t in (0.01, 0.05, 0.2, 0.399):
        assert abs(tr.at(t, "S.CommandPosition") - 1.5 * tr.at(t, "D.ActualPosition")) < 3e-4
        assert abs(tr.at(t, "T.CommandPosition") - 1.5 * tr.at(t, "D.CommandPosition")) < 3e-4
    tau = 1.0 / (2.0 * math.pi * 20.0)
    q = math.exp(-CUP / tau)
    e = 10.0 * CUP * q / (1.0 - q)
    lead = tr.at(0.399, "T.CommandPosition") - tr.at(0.399, "S.CommandPosition")
    assert abs(lead - 1.5 * e) < 1e-3
