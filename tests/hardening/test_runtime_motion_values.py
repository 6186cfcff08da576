"""Motion configuration written by the program at run time (issue 14). Initialisers and
exported data are range-checked by `check` (E118, decision 0133); a value the logic writes
later cannot be checked before the run. The planner then reads a maximum that is negative,
infinite or NaN as "not configured", exactly as 0 (decision 0101: no limit), so the run
goes on with a defined result and never with a Python error."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from tests.hardening.harness import logixst

PROGRAM = """VAR
  ax : AXIS_VIRTUAL;
  on, mv : MOTION_INSTRUCTION;
  bad : REAL;
  ed, cd : REAL[1];
  go : BOOL := TRUE;
END_VAR
ax.MaximumSpeed := bad;
ax.MaximumAccel := bad;
ax.MaximumDecel := bad;
IF go THEN
  MSO(ax, on);
  (* absolute trapezoid move to 100 at 100 units/s, accel and decel 1000 units/s^2 *)
  MAM(ax, mv, 0, 100.0, 100.0, 0, 1000.0, 0, 1000.0, 0, 0, 0, 0, 0, 0, 0, 0, 0, ed, cd);
  go := FALSE;
END_IF;
"""


@pytest.mark.parametrize("bad", ["-5.0", "1.0E39", "-1.0E39", "0.0"])
def test_bad_maxima_written_at_run_time_mean_not_configured(tmp_path: Path, bad: str) -> None:
    # 1.0E39 overflows REAL to +inf (and -1.0E39 to -inf) when stored. Each value counts as
    # "not configured", so the move is not limited by it and runs its own profile: 0.1 s of
    # acceleration to 100 units/s (5 units), 0.9 s at speed (90 units), 0.1 s of deceleration
    # (5 units) = 100 units in 1.1 s; after 1.5 s the move is complete at 100.
    prog = tmp_path / "p.st"
    prog.write_text(PROGRAM.replace("bad : REAL;", f"bad : REAL := {bad};"))
    r = logixst(
        "run", prog, "--duration", "1.5", "--json", "--watch", "mv.PC", "--watch",
        "ax.CommandPosition", "--watch", "ax.MaximumSpeed", timeout=120,
    )  # fmt: skip
    assert r.code == 0 and "Traceback" not in r.err, r.err
    report = json.loads(r.out)
    assert report["faults"] == []
    assert report["tags"]["mv.PC"] is True
    assert report["tags"]["ax.CommandPosition"] == pytest.approx(100.0)
