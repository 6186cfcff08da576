"""MAPC position cams through `logixst run` (decision 0128).

Profile P: (0, 0) (10, 5) (20, 8), linear: P(x) = x/2 up to 10, then 5 + 0.3 (x - 10); net
change 8. The slave starts at 3; the master jogs at 10 u/s (at speed after one update) and
expectations are computed from the traced master position:
slave = 3 + Dir * SlaveScaling * (P(x) - P(CamLock) + passes * 8),
x = CamLock + (master - lock) / MasterScaling. 1 ms scans and coarse update; the
instructions run in scan 0 and apply at the update of t = 1 ms, where the master is at 0.
"""

from __future__ import annotations

import math

import pytest
from motion_trace import Runner

ARGS = ["--coarse-update", "1"]
WATCH = [
    "M.CommandPosition",
    "S.CommandPosition",
    "S.PositionCamStatus",
    "S.PositionCamLockStatus",
    "S.PositionCamPendingStatus",
    "mp.IP",
    "mp.PC",
    "mp.ER",
    "mp.ERR",
    "mp.EXERR",
]


def P(x: float) -> float:
    x = min(max(x, 0.0), 20.0)
    return x / 2 if x <= 10 else 5 + 0.3 * (x - 10)


def jog(direction: str, ctl: str = "mj") -> str:
    return (
        f"MAJ(M, {ctl}, {direction}, 10.0, unitspersec, 1000000.0, unitspersec2, 1000000.0, "
        "unitspersec2, trapezoidal, 0.0, 0.0, unitspersec3, disabled, programmed, 0.0, none);"
    )


def program(mapc: str, body: str = "", master_at: float = 0.0, direction: str = "forward") -> str:
    return f"""VAR
  M : AXIS_VIRTUAL := (ActualPosition := {master_at});
  S : AXIS_VIRTUAL := (ActualPosition := 3.0);
  mj, mj2, mp, mp2, ms : MOTION_INSTRUCTION;
  prof : CAM_PROFILE[3] := [(Master := 0.0, Slave := 0.0, SegmentType := 0), (Master := 10.0, Slave := 5.0, SegmentType := 0), (Master := 20.0, Slave := 8.0, SegmentType := 0)];
  k : DINT;
END_VAR
IF k = 0 THEN
  {jog(direction)}
  MAPC(S, M, mp, {mapc});
END_IF;
{body}
k := k + 1;
"""


def rows(tr, t0: float = 0.0, t1: float = math.inf):
    for r in tr.rows:
        if t0 - 1e-9 <= r[0] <= t1 + 1e-9:
            yield {n: r[i] for i, n in enumerate(tr.names)}


def test_immediate_once_completes_past_the_end(mp: Runner):
    tr = mp.trace(
        program("same, prof[0], 2.0, 1.0, once, immediate, 0.0, 0.0, command, bidirectional"),
        WATCH,
        2500,
        ARGS,
    )
    for r in rows(tr, 0.0, 1.99):
        assert r["S.CommandPosition"] == pytest.approx(3 + 2 * P(r["M.CommandPosition"]), abs=2e-4)
        assert r["S.PositionCamStatus"] == 1 and r["S.PositionCamLockStatus"] == (r["time"] > 0)
        assert r["mp.IP"] == 1 and r["mp.PC"] == 0
    for r in rows(tr, 2.01):  # past 20: PC, the slave holds 3 + 2 * 8
        assert r["S.CommandPosition"] == pytest.approx(19.0, abs=1e-4)
        assert r["mp.PC"] == 1 and r["mp.IP"] == 0 and r["S.PositionCamStatus"] == 0


def test_continuous_adds_the_net_change_each_pass(mp: Runner):
    tr = mp.trace(
        program(
            "opposite, prof[0], 1.0, 1.0, continuous, immediate, 0.0, 0.0, command, bidirectional"
        ),
        WATCH,
        4500,
        ARGS,
    )
    for r in rows(tr, 0.0):
        m = r["M.CommandPosition"]
        k = math.floor(m / 20.0)
        if abs(m - 20 * round(m / 20)) < 1e-3 and m > 1:
            continue  # at a pass boundary the float32 master decides the pass
        assert r["S.CommandPosition"] == pytest.approx(3 - (P(m - 20 * k) + 8 * k), abs=3e-4)
        assert r["mp.IP"] == 1 and r["S.PositionCamStatus"] == 1


def test_persistent_holds_outside_and_resumes(mp: Runner):
    body = f"IF k = 2500 THEN {jog('reverse', 'mj2')} END_IF;"  # back from 25 at t = 2.5 s
    tr = mp.trace(
        program(
            "same, prof[0], 1.0, 1.0, persistent, immediate, 0.0, 0.0, command, bidirectional", body
        ),
        WATCH,
        4500,
        ARGS,
    )
    outside = 0
    for r in rows(tr, 0.01):
        m = r["M.CommandPosition"]
        assert r["S.CommandPosition"] == pytest.approx(3 + P(m), abs=3e-4)
        assert r["S.PositionCamStatus"] == 1 and r["mp.IP"] == 1 and r["mp.PC"] == 0
        if m > 20.02:
            outside += 1
            assert r["S.PositionCamLockStatus"] == 0
        elif m < 19.98:
            assert r["S.PositionCamLockStatus"] == 1
    assert outside > 500


def test_master_scaling_and_cam_lock(mp: Runner):
    # MasterScaling 2: the profile is stretched over 40 master units; CamLock 4 at master 0
    tr = mp.trace(
        program("same, prof[0], 1.0, 2.0, once, immediate, 0.0, 4.0, command, bidirectional"),
        WATCH,
        3000,
        ARGS,
    )
    for r in rows(tr, 0.0, 2.99):
        x = 4.0 + r["M.CommandPosition"] / 2.0
        assert r["S.CommandPosition"] == pytest.approx(3 + P(x) - P(4.0), abs=2e-4)


def test_forward_only_schedule_locks_at_the_lock_position(mp: Runner):
    tr = mp.trace(
        program("same, prof[0], 2.0, 1.0, once, forwardonly, 5.0, 0.0, command, bidirectional"),
        WATCH,
        1500,
        ARGS,
    )
    for r in rows(tr, 0.0, 0.499):
        assert r["S.CommandPosition"] == 3.0 and r["S.PositionCamLockStatus"] == 0
        assert r["S.PositionCamStatus"] == 1 and r["mp.IP"] == 1
    for r in rows(tr, 0.51):
        m = r["M.CommandPosition"]
        assert r["S.CommandPosition"] == pytest.approx(3 + 2 * P(m - 5.0), abs=2e-4)
        assert r["S.PositionCamLockStatus"] == 1


@pytest.mark.parametrize("schedule", ["reverseonly", "bidirectional"])
def test_reverse_crossing_locks_reverse_only_and_bidirectional(mp: Runner, schedule):
    # master from 30 in reverse; lock at 25 with CamLock 20 (the profile's end): x = M - 5
    src = program(
        f"same, prof[0], 1.0, 1.0, once, {schedule}, 25.0, 20.0, command, bidirectional",
        master_at=30.0,
        direction="reverse",
    )
    tr = mp.trace(src, WATCH, 3000, ARGS)
    for r in rows(tr, 0.0, 0.499):
        assert r["S.CommandPosition"] == 3.0
    for r in rows(tr, 0.51, 2.49):
        x = r["M.CommandPosition"] - 5.0
        assert r["S.CommandPosition"] == pytest.approx(3 + P(x) - 8.0, abs=2e-4)
    last = list(rows(tr, 2.51))  # x < 0 at master 5: complete, holding 3 - 8
    assert all(
        r["mp.PC"] == 1 and r["S.CommandPosition"] == pytest.approx(-5.0, abs=1e-4) for r in last
    )


def test_forward_only_does_not_lock_in_reverse(mp: Runner):
    src = program(
        "same, prof[0], 1.0, 1.0, once, forwardonly, 25.0, 20.0, command, bidirectional",
        master_at=30.0,
        direction="reverse",
    )
    tr = mp.trace(src, WATCH, 1500, ARGS)
    assert all(
        r["S.CommandPosition"] == 3.0 and r["S.PositionCamLockStatus"] == 0 for r in rows(tr)
    )


def test_pending_takes_over_at_the_end(mp: Runner):
    # Once cam, then a pending Continuous one: it starts at master 20 from the slave there
    body = "IF k = 100 THEN MAPC(S, M, mp2, same, prof[0], 1.0, 1.0, continuous, pending, 0.0, 0.0, command, bidirectional); END_IF;"
    watch = [*WATCH, "mp2.IP", "mp2.DN"]
    tr = mp.trace(
        program("same, prof[0], 1.0, 1.0, once, immediate, 0.0, 0.0, command, bidirectional", body),
        watch,
        4500,
        ARGS,
    )
    for r in rows(tr, 0.101, 1.99):
        assert r["S.PositionCamPendingStatus"] == 1 and r["mp2.DN"] == 1
    for r in rows(tr, 2.01):
        m = r["M.CommandPosition"] - 20.0
        k = math.floor(m / 20.0)
        if abs(m - 20 * round(m / 20)) < 1e-3:
            continue
        assert r["S.CommandPosition"] == pytest.approx(3 + 8 + P(m - 20 * k) + 8 * k, abs=3e-4)
        assert r["mp.PC"] == 1 and r["mp2.IP"] == 1 and r["S.PositionCamPendingStatus"] == 0
        assert r["S.PositionCamStatus"] == 1


def test_master_direction_forward_only_pauses_while_the_master_backs_up(mp: Runner):
    body = f"IF k = 800 THEN {jog('reverse', 'mj2')} END_IF;\nIF k = 1200 THEN {jog('forward', 'mj2')} END_IF;"
    tr = mp.trace(
        program("same, prof[0], 1.0, 1.0, once, immediate, 0.0, 0.0, command, forwardonly", body),
        WATCH,
        2200,
        ARGS,
    )
    furthest = 0.0
    for r in rows(tr, 0.0):
        m = r["M.CommandPosition"]
        new_ground = m > furthest + 1e-3  # clearly beyond every earlier position
        furthest = max(furthest, m)
        assert r["S.CommandPosition"] == pytest.approx(3 + P(furthest), abs=2e-4)
        if m < furthest - 1e-3:  # backing up: the slave waits, not locked
            assert r["S.PositionCamLockStatus"] == 0, r
        elif new_ground and r["time"] > 0.01:
            assert r["S.PositionCamLockStatus"] == 1, r


def test_mas_ends_the_cam_without_pc(mp: Runner):
    body = "IF k = 300 THEN MAS(S, ms, positioncam, 1, 1000.0, unitspersec2, 0, 0.0, unitspersec3); END_IF;"
    tr = mp.trace(
        program(
            "same, prof[0], 1.0, 1.0, continuous, immediate, 0.0, 0.0, command, bidirectional", body
        ),
        WATCH,
        600,
        ARGS,
    )
    held = [r for r in rows(tr, 0.302)]
    assert all(r["mp.IP"] == 0 and r["mp.PC"] == 0 and r["S.PositionCamStatus"] == 0 for r in held)
    # the slave stops (decelerating at 1000 from 5 u/s: 2.5 ms) and stays near P(3) + 3
    assert held[-1]["S.CommandPosition"] == pytest.approx(held[-2]["S.CommandPosition"])
    assert held[-1]["S.CommandPosition"] == pytest.approx(3 + P(3.0), abs=0.05)


@pytest.mark.parametrize(
    ("operands", "err", "exerr"),
    [
        ("same, prof[0], 1.0, 0.0, once, immediate, 0.0, 0.0, command, bidirectional", 13, 6),
        ("same, prof[0], 1.0, 1.0, once, immediate, 0.0, 25.0, command, bidirectional", 13, 10),
        ("same, bad[0], 1.0, 1.0, once, immediate, 0.0, 0.0, command, bidirectional", 32, 0),
    ],
)
def test_errors(mp: Runner, operands, err, exerr):
    src = program(operands).replace("  k : DINT;", "  k : DINT;\n  bad : CAM_PROFILE[3];")
    tr = mp.trace(src, WATCH, 3, ARGS)
    r = next(rows(tr))
    assert (r["mp.ER"], r["mp.ERR"], r["mp.EXERR"]) == (1, err, exerr)


def test_immediate_while_active_is_err_23(mp: Runner):
    body = "IF k = 50 THEN MAPC(S, M, mp2, same, prof[0], 1.0, 1.0, once, immediate, 0.0, 0.0, command, bidirectional); END_IF;"
    tr = mp.trace(
        program("same, prof[0], 1.0, 1.0, once, immediate, 0.0, 0.0, command, bidirectional", body),
        ["mp2.ER", "mp2.ERR"],
        60,
        ARGS,
    )
    assert tr.rows[-1][1:] == [1.0, 23.0]


def test_mgs_ends_the_cam_without_pc(mp: Runner):
    body = "IF k = 300 THEN MGS(grp, mg, programmed); END_IF;"
    src = program(
        "same, prof[0], 1.0, 1.0, continuous, immediate, 0.0, 0.0, command, bidirectional", body
    )
    src = src.replace(
        "  k : DINT;", "  k : DINT;\n  grp : MOTION_GROUP;\n  mg : MOTION_INSTRUCTION;"
    )
    tr = mp.trace(src, WATCH, 600, ARGS)
    assert all(r["mp.IP"] == 1 and r["S.PositionCamStatus"] == 1 for r in rows(tr, 0.01, 0.3))
    held = list(rows(tr, 0.302))
    assert all(r["mp.IP"] == 0 and r["mp.PC"] == 0 and r["S.PositionCamStatus"] == 0 for r in held)
