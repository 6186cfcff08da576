"""Planner timing through the CLI (SPEC 4, 9.3): coarse update period from --coarse-update,
the MOTION_GROUP tag or the 2 ms default; updates before the scan starting at their time;
an instruction takes effect at the next update, strictly later; prescan clears the bits."""

from __future__ import annotations

import pytest

# jog at 10 units/s with an acceleration high enough to be at speed within one update:
# accel 1e6 reaches 10 units/s in 10 us (5e-5 units), so p = 10 (t - start) - 5e-5
HEAD = """VAR
{group}  X : AXIS_VIRTUAL := (MaximumSpeed := 100.0, MaximumAccel := 1000000.0, MaximumDecel := 1000000.0);
  c : MOTION_INSTRUCTION;
  k : DINT;
END_VAR
IF k = {at} THEN MAJ(X, c, forward, 10.0, unitspersec, 1000000.0, unitspersec2, 1000000.0, unitspersec2, trapezoidal, 0.0, 0.0, unitspersec3, disabled, programmed, 0.0, none); END_IF;
k := k + 1;
"""


def jog_src(group: str = "", at: int = 0) -> str:
    return HEAD.format(group=group, at=at)


def starts(tr) -> list[float]:  # noqa: ANN001
    """Row times at which the position changes."""
    p = tr.col("X.CommandPosition")
    return [tr.rows[i][0] for i in range(1, len(p)) if p[i] != p[i - 1]]


@pytest.mark.parametrize(
    ("group", "args", "cup"),
    [
        ("", (), 0.002),  # implicit group: 2 ms
        ("", ("--coarse-update", "5"), 0.005),
        ("  grp : MOTION_GROUP := (CoarseUpdatePeriod := 4000);\n", (), 0.004),  # microseconds
        (
            "  grp : MOTION_GROUP := (CoarseUpdatePeriod := 4000);\n",
            ("--coarse-update", "5"),
            0.005,
        ),  # CLI wins
    ],
)
def test_coarse_update_period(mp, group: str, args: tuple[str, ...], cup: float) -> None:
    tr = mp.trace(jog_src(group), ["X.CommandPosition"], scans=40, args=args)
    # executed in the scan at 0 (after the update at 0): starts at the update at cup, moves
    # from the next one on, and changes only at update instants
    ch = starts(tr)
    assert ch[0] == pytest.approx(2 * cup)
    assert all(abs(t / cup - round(t / cup)) < 1e-9 for t in ch)
    assert tr.at(0.039, "X.CommandPosition") == pytest.approx(
        10.0 * (cup * (0.039 // cup) - cup) - 5e-5, abs=1e-4
    )


def test_motion_group_tag_shows_the_period_in_use(mp) -> None:
    tr = mp.trace(
        jog_src("  grp : MOTION_GROUP := (CoarseUpdatePeriod := 4000);\n"),
        ["grp.CoarseUpdatePeriod"],
        scans=2,
        args=("--coarse-update", "2.5"),
    )
    assert tr.col("grp.CoarseUpdatePeriod") == [2500.0, 2500.0]


def test_takes_effect_strictly_at_the_next_update(mp) -> None:
    # executed in the scan at 2 ms, which starts right after the update at 2 ms: the jog
    # starts at the update at 4 ms (own clock 0 there) and has moved at 6 ms
    tr = mp.trace(jog_src(at=2), ["X.CommandPosition", "X.JogStatus"], scans=10)
    assert [tr.at(t, "X.JogStatus") for t in (0.002, 0.003, 0.004)] == [0, 0, 1]
    assert tr.at(0.005, "X.CommandPosition") == 0.0
    assert tr.at(0.006, "X.CommandPosition") == pytest.approx(0.02 - 5e-5, abs=1e-5)


def test_several_updates_between_long_scans(mp) -> None:
    # 5 ms scans, 2 ms updates: before the scan at 5 ms the updates at 2 and 4 ms have run;
    # the jog executed at 0 started at 2 ms: 10 * (4 - 2) ms - 5e-5
    tr = mp.trace(jog_src(), ["X.CommandPosition"], scans=3, args=("--scan-period", "5"))
    assert tr.col("X.CommandPosition")[1] == pytest.approx(0.02 - 5e-5, abs=1e-5)
    assert tr.col("X.CommandPosition")[2] == pytest.approx(
        0.08 - 5e-5, abs=1e-5
    )  # updates at 6, 8, 10


def test_prescan_clears_the_motion_bits(mp) -> None:
    # SPEC 3.2: EN DN ER IP cleared on entering Run (the instruction is never executed here)
    src = """VAR
  X : AXIS_VIRTUAL;
  c : MOTION_INSTRUCTION := (EN := TRUE, DN := TRUE, ER := TRUE, IP := TRUE, PC := TRUE);
  never : BOOL;
END_VAR
IF never THEN MSO(X, c); END_IF;
"""
    tr = mp.trace(src, ["c.EN", "c.DN", "c.ER", "c.IP", "c.PC"], scans=1)
    assert [tr.at(0.0, n) for n in ("c.EN", "c.DN", "c.ER", "c.IP", "c.PC")] == [0, 0, 0, 0, 1]


@pytest.mark.parametrize("bad", ["0", "-2", "nan", "inf"])
def test_bad_coarse_update_is_a_usage_error(mp, bad: str) -> None:
    code, _, err = mp.run(jog_src(), ["--coarse-update", bad])
    assert code == 2 and "--coarse-update" in err and "Traceback" not in err
