"""Motion instructions in ladder are transitional (SPEC 3.2, HELPERS contract): they execute
on the rung's false-to-true transition only; a false rung clears EN once DN or ER is set."""

from __future__ import annotations

SRC = """VAR
  lin : CAM_PROFILE[2] := [(Master := 0.0, Slave := 0.0, SegmentType := 0), (Master := 1.0, Slave := 10.0, SegmentType := 0)];
  A : AXIS_VIRTUAL;
  c1 : MOTION_INSTRUCTION;
  go : BOOL;
  k : DINT;
END_VAR
XIC(go)MATC(A,c1,0,lin,1.0,1.0,Once,Immediate,0.0,None,Time Driven Mode);
ADD(k,1,k);
[GEQ(k,100)LES(k,200),GEQ(k,300)]OTE(go);
"""


def test_transitional_matc_in_ladder(mp) -> None:
    # go is true in the scans 100..199 and from 300 on (set at the end of scans 99 and 299)
    tr = mp.trace(
        SRC,
        ["c1.EN", "c1.DN", "c1.IP", "c1.ER", "c1.ERR", "A.CommandPosition"],
        scans=400,
        name="prog.rll",
    )
    # executed once in scan 100; the rung staying true does not execute it again (no error 23)
    assert [tr.at(t, "c1.EN") for t in (0.099, 0.1, 0.199)] == [0, 1, 1]
    assert set(tr.col("c1.ER")[100:300]) == {0.0}
    # started at the update 0.102: 10 units/s
    assert abs(tr.at(0.15, "A.CommandPosition") - 0.48) < 1e-4
    # rung false: EN cleared (DN was set), DN and IP unchanged
    assert [tr.at(0.2, n) for n in ("c1.EN", "c1.DN", "c1.IP")] == [0, 1, 1]
    # true again in scan 300 while the cam (0.102..1.102) is still active: executes, error 23
    assert [tr.at(0.3, n) for n in ("c1.EN", "c1.ER", "c1.ERR", "c1.DN")] == [1, 1, 23, 0]


LADDER_EVENTS = """VAR
  A : AXIS_VIRTUAL := (MaximumSpeed := 20.0, MaximumAccel := 1000.0, MaximumDecel := 1000.0);
  G : MOTION_GROUP;
  cw, cr, cs, cj : MOTION_INSTRUCTION;
  go, stop : BOOL;
  k : DINT;
END_VAR
XIC(go)MAW(A,cw,Forward,0.2)MAR(A,cr,Positive_Edge,Disabled,0,0,1)MAJ(A,cj,Forward,10.0,Units per sec,1000.0,Units per sec2,1000.0,Units per sec2,Trapezoidal,0.0,0.0,Units per sec3,Disabled,Programmed,0.0,None);
XIC(stop)MGSD(G,cs);
ADD(k,1,k);
GEQ(k,10)OTE(go);
GEQ(k,100)OTE(stop);
"""


def test_watch_registration_and_group_shutdown_in_ladder(mp) -> None:
    # go from scan 10: the jog starts at the update 0.012; its accel phase (0.01 s) covers
    # 0.05, then 10/s: 0.2 is passed at clock 0.01 + 0.15/10 = 0.025, i.e. t = 0.037, so at
    # the update 0.038. MGSD in scan 100 ends the jog at the update 0.102.
    tr = mp.trace(
        LADDER_EVENTS,
        ["cw.EN", "cw.PC", "A.WatchEventStatus", "cr.IP", "A.RegEvent1ArmedStatus",
         "cs.DN", "A.ShutdownStatus", "A.CommandVelocity", "cj.IP"],
        scans=120,
        name="prog.rll",
    )  # fmt: skip
    assert tr.at(0.009, "cw.EN") == 0 and tr.at(0.01, "cw.EN") == 1
    assert tr.first("cw.PC", lambda v: v == 1) == 0.038
    assert tr.at(0.038, "A.WatchEventStatus") == 1
    assert tr.at(0.099, "cr.IP") == 1 and tr.at(0.099, "A.RegEvent1ArmedStatus") == 1
    assert tr.at(0.1, "cs.DN") == 1 and tr.at(0.1, "A.ShutdownStatus") == 1
    assert tr.at(0.102, "A.CommandVelocity") == 0 and tr.at(0.102, "cj.IP") == 0
