"""MAJ's Direction given as a tag (Logix: "immediate or tag"), through `logixst run`.

Jog used below (speed 10, accel 1000, started in scan 0, so at the update t0 = 2 ms; timing
as in test_shutdown_watch.py): the accel phase lasts 10/1000 = 0.01 s and covers
1000 * 0.01**2 / 2 = 0.05; after that the axis gains 10 per second. At the update of
t = 0.1 s the jog's own clock is 0.098, so it has covered 0.05 + 10 * (0.098 - 0.01) = 0.93.
"""

from __future__ import annotations

F32 = 1e-4
HEAD = """VAR
  X : AXIS_VIRTUAL := (MaximumSpeed := 20.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0);
  c1 : MOTION_INSTRUCTION;
  dir : DINT := {d};
  k : DINT;
END_VAR
IF k = 0 THEN
  MAJ(X, c1, dir, 10.0, unitspersec, 1000.0, unitspersec2, 1000.0, unitspersec2, trapezoidal,
      0.0, 0.0, unitspersec3, disabled, programmed, 0.0, none);
END_IF;
k := k + 1;
"""
WATCH = ["X.CommandPosition", "c1.IP", "c1.ER", "c1.ERR", "c1.EXERR"]


def test_a_direction_tag_holding_1_jogs_in_reverse(mp) -> None:
    tr = mp.trace(HEAD.format(d=1), WATCH, scans=120)
    assert tr.at(0.05, "c1.IP") == 1 and tr.at(0.05, "c1.ER") == 0
    assert abs(tr.at(0.1, "X.CommandPosition") - (-0.93)) < F32


def test_a_direction_tag_holding_0_jogs_forward(mp) -> None:
    tr = mp.trace(HEAD.format(d=0), WATCH, scans=120)
    assert abs(tr.at(0.1, "X.CommandPosition") - 0.93) < F32


def test_a_direction_tag_outside_0_and_1_is_error_13_on_operand_2(mp) -> None:
    # an immediate 2 is refused by `check` (E109); from a tag it reaches the instruction,
    # which refuses it as a parameter out of range (ERR 13) naming Direction, the third
    # operand (EXERR counts from 0), and the axis stays where it is
    tr = mp.trace(HEAD.format(d=2), WATCH, scans=20)
    assert tr.at(0.0, "c1.ER") == 1 and tr.at(0.0, "c1.ERR") == 13
    assert tr.at(0.0, "c1.EXERR") == 2
    assert tr.at(0.019, "X.CommandPosition") == 0


def test_an_immediate_direction_still_takes_the_words_and_numbers_only(mp) -> None:
    code, _out, err = mp.run(HEAD.format(d=0).replace("c1, dir,", "c1, 2,"), ["--scans", "1"])
    assert code == 1 and "E109" in err
