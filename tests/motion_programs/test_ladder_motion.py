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
