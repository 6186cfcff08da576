"""Position cams (poscam.py, the MC_CamIn core) against values worked out by hand.

The master is placed with set_position before each update, so the law is read at known
master positions: X = MasterScaling * (master - m0) + MasterOffset,
Y = SlaveScaling * CAM(X) + offset (SPEC 5, 9.30; decision 0127).
"""

from __future__ import annotations

import numpy as np
import pytest

from interpreter.motion import EventKind, MotionGroup, StopType, calculate_cam_profile
from interpreter.motion.poscam import (
    CamInError,
    CamLaw,
    CamStartMode,
    CouplingState,
    ramp_time,
    slave_gap,
    switch_table,
    validate_law,
)

CUP = 0.001
# P(x) = 2x on [0, 10]: P(0) = 0, P(10) = 20
LIN = calculate_cam_profile([0.0, 10.0], [0.0, 20.0], [0, 0])
# P(x) = 1 + 0.2x on [0, 10]: starts at 1 (a relative start jumps by 1)
OFF = calculate_cam_profile([0.0, 10.0], [1.0, 3.0], [0, 0])
# triangle 0 -> 5 -> 0 over [0, 20]
TRI = calculate_cam_profile([0.0, 10.0, 20.0], [0.0, 5.0, 0.0], [0, 0, 0])
# a range that does not contain 0
HIGH = calculate_cam_profile([2.0, 10.0], [0.0, 8.0], [0, 0])


def setup(slave_at: float = 0.0, master_at: float = 0.0) -> tuple[MotionGroup, int, int]:
    g = MotionGroup(CUP)
    m = g.add_axis("m")
    s = g.add_axis("s")
    g.set_position(m, master_at)
    g.set_position(s, slave_at)
    return g, m, s


def at(g: MotionGroup, m: int, s: int, master: float) -> float:
    """Place the master, run one update, return the slave's command position."""
    g.set_position(m, master)
    g.update()
    return float(g.command_position[s])


def test_scaling_and_offsets_formula():
    g, m, s = setup()
    law = CamLaw(LIN, master_scaling=2.0, master_offset=1.0, slave_scaling=3.0, slave_offset=4.0)
    c = g.start_position_cam(s, m, law)
    g.update()  # coupling at master 0: X = 1
    assert c.state == CouplingState.IN_SYNC
    for master in (0.5, 1.0, 2.25, 4.0):
        x = 2.0 * master + 1.0  # X = MasterScaling * master + MasterOffset
        assert at(g, m, s, master) == pytest.approx(3.0 * (2.0 * x) + 4.0, abs=1e-12)


# StartMode x SlaveAbsolute (the seed's table) on OFF with the slave at 7 and the master
# moved from 0 (coupling) to 5: CAM(5) = 2, CAM(0) = 1.
#   absolute:          Y = CAM(X)             -> 2 (a jump from 7 to CAM(0) = 1 at once)
#   relative:          Y = CAM(X) + 7         -> 9 (a jump of CAM(0) = 1)
#   ramp_in absolute:  Y = CAM(X), no jump    -> 2 once the ramp is done
#   ramp_in relative:  Y = CAM(X) + 7, no jump -> 9 once the ramp is done
CASES = [
    (CamStartMode.ABSOLUTE, True, 2.0, 1.0),
    (CamStartMode.ABSOLUTE, False, 9.0, 8.0),
    (CamStartMode.RELATIVE, True, 9.0, 8.0),
    (CamStartMode.RELATIVE, False, 9.0, 8.0),
    (CamStartMode.RAMP_IN, True, 2.0, 7.0),
    (CamStartMode.RAMP_IN, False, 9.0, 7.0),
    (CamStartMode.RAMP_IN_POS, True, 2.0, 7.0),
    (CamStartMode.RAMP_IN_POS, False, 9.0, 7.0),
    (CamStartMode.RAMP_IN_NEG, True, 2.0, 7.0),
    (CamStartMode.RAMP_IN_NEG, False, 9.0, 7.0),
]


@pytest.mark.parametrize(("mode", "slave_absolute", "final", "first"), CASES)
def test_start_mode_times_slave_absolute(mode, slave_absolute, final, first):
    g, m, s = setup(slave_at=7.0)
    law = CamLaw(
        OFF, slave_absolute=slave_absolute, start_mode=mode,
        velocity_diff=5.0, acceleration=50.0, deceleration=50.0,
    )  # fmt: skip
    c = g.start_position_cam(s, m, law)
    g.update()  # coupled at master 0; the slave still at 7
    assert g.command_position[s] == 7.0
    # first update after coupling, master still at 0: the law's value, or no jump for a ramp
    # (the ramp has moved for one update: at most 0.5 * 50 * 0.001^2)
    assert at(g, m, s, 0.0) == pytest.approx(first, abs=3e-5)
    for _ in range(3000):  # ramps of 6 or 1 units at 5 u/s end within 1.3 s
        at(g, m, s, 5.0)
    assert g.command_position[s] == pytest.approx(final, abs=1e-12)
    assert c.state == CouplingState.IN_SYNC


def test_periodic_absolute_evaluates_each_pass_as_it_is():
    g, m, s = setup(slave_at=3.0)
    c = g.start_position_cam(s, m, CamLaw(LIN, periodic=True))
    g.update()
    assert at(g, m, s, 25.0) == pytest.approx(10.0)  # X = 25 -> pass 2, local 5: 2 * 5
    assert c.ends == 2  # two profile ends passed in that update
    assert at(g, m, s, -3.0) == pytest.approx(14.0)  # pass -1, local 7
    assert c.ends == 5  # back over the ends at 20, 10 and 0
    assert c.state == CouplingState.IN_SYNC


def test_periodic_relative_adds_the_end_value_each_pass():
    g, m, s = setup(slave_at=3.0)
    c = g.start_position_cam(s, m, CamLaw(LIN, periodic=True, slave_absolute=False))
    g.update()
    # Y = 2 * local + 3 + k * CAM(end): pass 2 -> 10 + 3 + 40
    assert at(g, m, s, 25.0) == pytest.approx(53.0)
    assert at(g, m, s, -3.0) == pytest.approx(14.0 + 3.0 - 20.0)
    assert c.state == CouplingState.IN_SYNC


def test_non_periodic_end_holds_the_last_value_and_completes():
    g, m, s = setup()
    c = g.start_position_cam(s, m, CamLaw(TRI))
    g.update()
    assert at(g, m, s, 15.0) == pytest.approx(2.5)
    g.set_position(m, 21.0)
    ev = g.update()
    assert g.command_position[s] == pytest.approx(0.0)  # TRI(20): the last value
    assert (c.handle, EventKind.COMPLETE) in [(e.handle, e.kind) for e in ev]
    assert c.state == CouplingState.ENDED and c.error == CamInError.NONE and c.ends == 1
    assert at(g, m, s, 5.0) == pytest.approx(0.0)  # no longer coupled: it holds
    assert not g.position_cams.rows


def test_master_relative_counts_from_the_coupling_position():
    g, m, s = setup(master_at=13.0)
    c = g.start_position_cam(s, m, CamLaw(LIN, master_absolute=False))
    g.update()
    assert c.state == CouplingState.IN_SYNC
    assert at(g, m, s, 16.0) == pytest.approx(6.0)  # X = 16 - 13 = 3 -> 2 * 3


def test_master_out_of_range_errors():
    # MasterAbsolute TRUE: master 13 is beyond LIN's range [0, 10]
    g, m, s = setup(master_at=13.0)
    c = g.start_position_cam(s, m, CamLaw(LIN))
    g.update()
    assert c.state == CouplingState.ERROR and c.error == CamInError.MASTER_OUT_OF_RANGE
    # MasterAbsolute FALSE: evaluation starts at X = 0, outside HIGH's range [2, 10]
    g, m, s = setup(master_at=5.0)
    c = g.start_position_cam(s, m, CamLaw(HIGH, master_absolute=False))
    g.update()
    assert c.error == CamInError.MASTER_OUT_OF_RANGE
    # periodic: any master position maps into the range
    g, m, s = setup(master_at=13.0)
    c = g.start_position_cam(s, m, CamLaw(LIN, periodic=True))
    g.update()
    assert c.state == CouplingState.IN_SYNC
    assert g.command_position[s] == 0.0  # coupled, moving from the next update on
    assert at(g, m, s, 13.0) == pytest.approx(6.0)  # local 3


def test_ramp_in_velocity_difference_and_acceleration_within_limits():
    """Slave at 6, cam LIN absolute with the master moving at 1 u/s from 0: the law is
    Y = 2 * master; the slave's excess over the law is a trapezoid from 6 to 0 with
    VelocityDiff 2, Acceleration 10, Deceleration 5: T = 2/10 + 2/5 + (6 - 0.6)/2 = 3.3 s."""
    g, m, s = setup(slave_at=6.0)
    law = CamLaw(
        LIN, periodic=True, start_mode=CamStartMode.RAMP_IN,
        velocity_diff=2.0, acceleration=10.0, deceleration=5.0,
    )  # fmt: skip
    assert ramp_time(6.0, 2.0, 10.0, 5.0) == pytest.approx(3.3)
    c = g.start_position_cam(s, m, law)
    g.update()
    diff, sync_at = [6.0], None
    for k in range(1, 4000):
        master = 1.0 * k * CUP
        slave = at(g, m, s, master)
        diff.append(slave - 2.0 * master)  # the master stays below 10: one pass
        if sync_at is None and c.state == CouplingState.IN_SYNC:
            sync_at = k * CUP
    d = np.array(diff)
    v = np.diff(d) / CUP
    a = np.diff(v) / CUP
    assert np.all(np.abs(v) <= 2.0 + 1e-9)
    assert np.all(a <= 10.0 + 1e-6) and np.all(a >= -10.0 - 1e-6)
    assert np.abs(v).max() == pytest.approx(2.0)
    assert sync_at == pytest.approx(3.3, abs=CUP + 1e-9)
    assert d[-1] == pytest.approx(0.0, abs=1e-12)


def test_short_ramp_is_a_triangle():
    # 0.2 units with V 2, A 10, D 10: peak sqrt(2 * 0.2 * 10 * 10 / 20) = sqrt(2) < 2
    vp = np.sqrt(2.0)
    assert ramp_time(0.2, 2.0, 10.0, 10.0) == pytest.approx(2 * vp / 10.0)


def test_stop_and_a_second_coupling_abort():
    g, m, s = setup()
    c = g.start_position_cam(s, m, CamLaw(LIN, periodic=True))
    g.update()
    assert g.stop(s, StopType.ALL).ok
    ev = g.update()
    assert c.state == CouplingState.ABORTED
    assert (c.handle, EventKind.ENDED) in [(e.handle, e.kind) for e in ev]
    c1 = g.start_position_cam(s, m, CamLaw(LIN, periodic=True))
    g.update()
    c2 = g.start_position_cam(s, m, CamLaw(TRI, periodic=True))
    g.update()
    assert c1.state == CouplingState.ABORTED and c2.state == CouplingState.IN_SYNC


def test_move_stop_does_not_end_a_cam():
    g, m, s = setup()
    c = g.start_position_cam(s, m, CamLaw(LIN, periodic=True))
    g.update()
    assert g.stop(s, StopType.MOVE).ok
    g.update()
    assert c.state == CouplingState.IN_SYNC


def test_table_switch_at_the_pass_end():
    """LIN periodic, then TRI (master relative) selected: at the pass end (master 10) TRI
    takes over with its master zero at 10: master 13 -> TRI(3) = 1.5."""
    g, m, s = setup()
    c = g.start_position_cam(s, m, CamLaw(LIN, periodic=True))
    g.update()
    assert at(g, m, s, 9.0) == pytest.approx(18.0)
    assert switch_table(g.position_cams, c, CamLaw(TRI, master_absolute=False)) == 0
    assert at(g, m, s, 9.5) == pytest.approx(19.0)  # still LIN
    at(g, m, s, 11.0)  # crosses the end: the switch happens in this update
    assert at(g, m, s, 13.0) == pytest.approx(1.5)
    assert c.state == CouplingState.IN_SYNC and c.ends == 1


def test_parameter_errors():
    assert validate_law(CamLaw(LIN, master_scaling=0.0)) == CamInError.INVALID_PARAMETER
    assert validate_law(CamLaw(LIN, slave_offset=float("nan"))) == CamInError.INVALID_PARAMETER
    ramp = CamLaw(LIN, start_mode=CamStartMode.RAMP_IN, velocity_diff=1.0, acceleration=1.0)
    assert validate_law(ramp) == CamInError.INVALID_PARAMETER  # Deceleration 0
    g, m, s = setup()
    assert g.start_position_cam(s, s, CamLaw(LIN)).error == CamInError.SAME_AXIS


def test_one_cam_core_three_front_ends():
    """The same cam (slave 0 at 0, cubic) through a master-driven MATC (MDAC), MAPC and
    MC_CamIn (absolute), all coupled at the same update with the master at rest at 0 and then
    moving 0 -> 25 (beyond the cam's end): the three slaves follow one trajectory."""
    from interpreter.motion import InstructionMode, MotionType, MoveType

    cam = calculate_cam_profile([0.0, 4.0, 12.0, 20.0], [0.0, 3.0, 1.0, 6.0], [1, 1, 1, 1])
    g = MotionGroup(CUP)
    m = g.add_axis("m")
    s1, s2, s3 = g.add_axis("s1"), g.add_axis("s2"), g.add_axis("s3")
    assert g.assign_master(s1, m, MotionType.TIME_CAM).ok
    assert g.start_time_cam(s1, cam, instruction_mode=InstructionMode.MASTER_DRIVEN).ok
    assert g.start_mapc(s2, m, cam).ok
    c = g.start_position_cam(s3, m, CamLaw(cam))
    g.update()  # all three couple here, master at rest at 0
    assert g.start_move(m, MoveType.ABSOLUTE, 25.0, 10.0, 20.0, 20.0).ok
    trail = []
    for _ in range(4000):
        g.update()
        trail.append(g.command_position[[s1, s2, s3]].copy())
    t = np.array(trail)
    assert np.abs(t[:, 0] - t[:, 1]).max() < 1e-9
    assert np.abs(t[:, 0] - t[:, 2]).max() < 1e-9
    # and the trajectory is the cam of the master (the end value 6 once past 20)
    assert t[-1, 0] == pytest.approx(6.0, abs=1e-12)
    assert c.state == CouplingState.ENDED


# -- rotary axes (decision 0137) -------------------------------------------------------
# P(x) = 2x over one turn [0, 360]: periodic and relative, each pass adds P(360) = 720, so
# the slave is 2 * (the master's travel since coupling) however often the master wraps
DOUBLE = calculate_cam_profile([0.0, 360.0], [0.0, 720.0], [0, 0])
# P(x) = x on [0, 100]
UNIT = calculate_cam_profile([0.0, 100.0], [0.0, 100.0], [0, 0])


def rotary_setup(master_at: float, slave_rotary: bool = False) -> tuple[MotionGroup, int, int]:
    g, m, s = setup(master_at=master_at)
    g.set_unwind(m, 360.0)
    if slave_rotary:
        g.set_unwind(s, 360.0)
    return g, m, s


def test_rotary_master_travel_runs_through_the_wrap():
    g, m, s = rotary_setup(300.0)
    c = g.start_position_cam(s, m, CamLaw(DOUBLE, periodic=True, slave_absolute=False))
    g.update()  # coupled at 300: X = 300 (master absolute), relative base 0
    assert c.state == CouplingState.IN_SYNC
    travel = 0.0
    for step in (40.0, 40.0, 50.0, 170.0, 100.0, 100.0):  # wraps at 360 and at 720
        travel += step
        got = at(g, m, s, (300.0 + travel) % 360.0)
        # relative law: slave = 0 + P(X mod 360) + 720 * passes = 2 * (300 + travel) (the
        # relative start jumps by P(300) = 600, as the seed says)
        assert got == pytest.approx(2.0 * (300.0 + travel), abs=1e-9), (travel, got)


def test_rotary_master_redefined_keeps_counting_travel():
    # master relative (MasterAbsolute FALSE): MRP on the master is no travel
    law = CamLaw(DOUBLE, periodic=True, master_absolute=False, slave_absolute=False)
    g, m, s = rotary_setup(350.0)
    g.start_position_cam(s, m, law)
    g.update()
    assert at(g, m, s, 10.0) == pytest.approx(40.0, abs=1e-9)  # travel 20 through 0
    g.shift_position(m, -200.0)  # the master now shows 170 (10 - 200 + 360)
    assert float(g.command_position[m]) == pytest.approx(170.0)
    assert at(g, m, s, 180.0) == pytest.approx(60.0, abs=1e-9)  # travel 20 + 10


def test_mapc_reverse_lock_through_the_wrap():
    # master at 20 moving back 10 per update; lock position 355 is crossed between 0 and
    # 350 (unwound -5). From there x = CamLock 50 + (master travel from -5), slave = 7 +
    # P(x) - P(50) = 7 + (x - 50)
    g, m, s = rotary_setup(20.0)
    g.set_position(s, 7.0)
    r = g.start_mapc(s, m, UNIT, execution_schedule=3, master_lock_position=355.0,
                     cam_lock_position=50.0, reference=1)  # fmt: skip
    assert r.ok
    g.update()  # armed at 20
    for pos in (10.0, 0.0):
        assert at(g, m, s, pos) == 7.0
    assert at(g, m, s, 350.0) == 7.0  # locks here (at -5); the cam moves from the next update
    for unwound in (-20.0, -30.0, -45.0):
        x = 50.0 + (unwound - -5.0)
        assert at(g, m, s, unwound % 360.0) == pytest.approx(7.0 + x - 50.0, abs=1e-9)


@pytest.mark.parametrize(
    ("mode", "slave", "law", "gap"),
    [
        # gap = slave - law as the ramp removes it; the slave moves by -gap
        (CamStartMode.RAMP_IN_POS, 300.0, 20.0, -80.0),  # forward 300 -> 380
        (CamStartMode.RAMP_IN_NEG, 300.0, 20.0, 280.0),  # back 300 -> 20
        (CamStartMode.RAMP_IN, 300.0, 20.0, -80.0),  # the short way: forward
        (CamStartMode.RAMP_IN_POS, 100.0, 20.0, -280.0),
        (CamStartMode.RAMP_IN_NEG, 100.0, 20.0, 80.0),
        (CamStartMode.RAMP_IN, 100.0, 20.0, 80.0),
        (CamStartMode.RAMP_IN_POS, 20.0, 740.0, 0.0),  # already there modulo 360
        (CamStartMode.RAMP_IN_NEG, 20.0, -340.0, 0.0),
    ],
)
def test_ramp_in_direction_on_a_rotary_slave_core(mode, slave, law, gap):
    assert slave_gap(mode, slave - law, 360.0) == pytest.approx(gap, abs=1e-9)
    # a linear slave: the automatic direction, whatever the mode
    assert slave_gap(mode, slave - law, 0.0) == slave - law


def test_absolute_start_on_a_rotary_slave_lands_on_the_law_modulo_the_unwind():
    # the law is 2 * 190 = 380 = 20 (mod 360); the slave at 350 jumps there (the short way
    # round, +30) at the update after coupling
    g, m, s = rotary_setup(190.0, slave_rotary=True)
    g.set_position(s, 350.0)
    g.start_position_cam(s, m, CamLaw(DOUBLE, periodic=True))
    g.update()
    before = float(g.command_position[s])
    after = at(g, m, s, 190.0)
    assert before == 350.0 and after == pytest.approx(20.0, abs=1e-9)


def test_table_switch_on_a_rotary_master_as_on_a_linear_one():
    # DOUBLE relative from master 300 (slave 0): slave = 2 U (U the unwound master; the
    # start jumps by P(300) = 600). HALF (P = x over a turn) is selected at U = 340 and takes
    # over at the pass end U = 360, slave 720 there: then slave = 720 + (U - 360), the
    # update crossing the end still commanding the old law (U = 380: 760), the next one
    # moving on from there (U = 400: 720 + 40 = 760, U = 420: 780, U = 800: 1160).
    half = calculate_cam_profile([0.0, 360.0], [0.0, 360.0], [0, 0])
    want = {340.0: 680.0, 380.0: 760.0, 400.0: 760.0, 420.0: 780.0, 800.0: 1160.0}
    results = []
    for rotary in (True, False):
        g, m, s = rotary_setup(300.0) if rotary else setup(master_at=300.0)
        c = g.start_position_cam(s, m, CamLaw(DOUBLE, periodic=True, slave_absolute=False))
        g.update()
        got = {}
        for u in (340.0, 380.0, 400.0, 420.0, 500.0, 600.0, 700.0, 800.0):
            got[u] = at(g, m, s, u % 360.0 if rotary else u)
            if u == 340.0:
                law = CamLaw(half, periodic=True, slave_absolute=False)
                assert switch_table(g.position_cams, c, law) == CamInError.NONE
        for u, y in want.items():
            assert got[u] == pytest.approx(y, abs=1e-9), (rotary, u, got[u])
        results.append(got)
    assert all(abs(results[0][u] - results[1][u]) < 1e-9 for u in results[0])
