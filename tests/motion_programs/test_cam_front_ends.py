"""One cam core, three front ends (issue 13): the same cam run through a master-driven MATC
(MDAC), through MAPC and through MC_CamIn (absolute), each slave at rest at 0 and the cam
starting at slave 0, coupled at the same update with the master at 0, gives one slave
trajectory. The master makes an S-curve move 0 -> 25, beyond the cam's end (20), where all
three hold the cam's last value, 6."""

from __future__ import annotations

from motion_trace import Runner

POINTS = "(Master := 0.0, Slave := 0.0, SegmentType := 1), (Master := 4.0, Slave := 3.0, SegmentType := 1), (Master := 12.0, Slave := 1.0, SegmentType := 1), (Master := 20.0, Slave := 6.0, SegmentType := 1)"

SRC = f"""VAR
  M, S1, S2, S3 : AXIS_VIRTUAL;
  mm, md, mt, mp : MOTION_INSTRUCTION;
  prof : CAM_PROFILE[4] := [{POINTS}];
  table : CAM[4] := [{POINTS}];
  sel : MC_CamTableSelect;
  camIn : MC_CamIn;
  k : DINT;
END_VAR
sel(Master := M, Slave := S3, CamTable := table, Execute := TRUE, Periodic := FALSE,
    MasterAbsolute := TRUE, SlaveAbsolute := TRUE);
camIn(Master := M, Slave := S3, Execute := sel.Done, CamTableID := sel.CamTableID, StartMode := absolute);
IF k = 0 THEN
  MDAC(S1, M, md, timecam, command);
  MATC(S1, mt, 0, prof[0], 1.0, 1.0, once, immediate, 0.0, none, masterdrivenmode);
  MAPC(S2, M, mp, same, prof[0], 1.0, 1.0, once, immediate, 0.0, 0.0, command, bidirectional);
END_IF;
IF k = 5 THEN
  MAM(M, mm, absolute, 25.0, 10.0, unitspersec, 20.0, unitspersec2, 20.0, unitspersec2, scurve, 100.0, 100.0, unitspersec3, disabled, programmed, 0.0, none, 0, 0);
END_IF;
k := k + 1;
"""


def test_same_trajectory_through_matc_mapc_and_camin(mp: Runner):
    watch = [
        "M.CommandPosition",
        "S1.CommandPosition",
        "S2.CommandPosition",
        "S3.CommandPosition",
        "camIn.InSync",
        "mt.ER",
        "mp.ER",
        "mm.ER",
    ]
    tr = mp.trace(SRC, watch, 4500, ["--coarse-update", "1"])
    s1, s2, s3 = (tr.col(f"S{i}.CommandPosition") for i in (1, 2, 3))
    assert max(abs(a - b) for a, b in zip(s1, s2, strict=True)) < 1e-9
    assert max(abs(a - c) for a, c in zip(s1, s3, strict=True)) < 1e-9
    assert tr.col("mm.ER")[-1] == 0 and tr.col("mt.ER")[-1] == 0 and tr.col("mp.ER")[-1] == 0
    assert tr.col("M.CommandPosition")[-1] == 25.0
    assert abs(s1[-1] - 6.0) < 1e-6  # the cam's last value once past 20
    assert max(s1) > 3.0  # it went through the cam's hump
