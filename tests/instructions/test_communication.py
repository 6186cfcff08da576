"""MSG and the ASCII instructions on a controller with nothing connected (decision 0035).

SPEC 9.32: not U diagnostics; the documented bits and codes, scan by scan. MSG fails with a
connection failure (ERR 16#0001) and unconnected-request timeout (EXERR 16#0204) once
UnconnectedTimeout has passed; serial writes complete, serial reads wait for ever.
"""

from __future__ import annotations

from pathlib import Path

from interpreter.instructions import communication as cm
from interpreter.vm.context import ExecContext
from interpreter.vm.values import set_string
from tests.instructions.run_cli import trace
from tests.instructions.structs import new_struct, struct_type

M = struct_type("MESSAGE").index
C = struct_type("SERIAL_PORT_CONTROL").index
MSG_BITS = ["m.EN", "m.EW", "m.ST", "m.DN", "m.ER", "m.ERR", "m.EXERR"]


def test_msg_ladder_scan_by_scan(tmp_path: Path) -> None:
    src = (
        "VAR m : MESSAGE; n : DINT; go : BOOL; END_VAR\n"
        "MOV(50000,m.UnconnectedTimeout)ADD(n,1,n);\n"
        "LES(n,8)OTE(go);\nGEQ(n,10)OTL(go);\nXIC(go)MSG(m);\n"
    )
    rows, report = trace(tmp_path, src, ".rll", 11, MSG_BITS, period_ms=10.0)
    got = [tuple(int(r[k]) for k in MSG_BITS) for r in rows]
    pending, sent, failed = (1, 1, 0, 0, 0, 0, 0), (1, 0, 1, 0, 0, 0, 0), (1, 0, 0, 0, 1, 1, 0x204)
    assert got == [
        pending,  # t 0: rung true, EN clear: queued (EN, EW)
        sent,  # t 10: sent (ST), waiting for an answer that never comes
        sent,
        sent,
        sent,
        failed,  # t 50 = 50 000 us: ER, connection failure 16#0001 / 16#0204
        failed,  # rung still true: EN stays, no new start
        (0, 0, 0, 0, 1, 1, 0x204),  # t 70: rung false clears EN; ER and the codes stay
        (0, 0, 0, 0, 1, 1, 0x204),
        pending,  # t 90: rung true again: a new start clears ER and the codes
        sent,
    ]
    assert report["diagnostics"] == [] and report["faults"] == []


def test_msg_default_timeout_is_30_s() -> None:
    ctx, m = ExecContext(), new_struct("MESSAGE")
    cm.msg_ladder(ctx, True, m)
    ctx.now_ms = 29_999.0
    cm.msg_ladder(ctx, True, m)
    assert (m[M["ST"]], m[M["ER"]]) == (1, 0)
    ctx.now_ms = 30_000.0
    cm.msg_ladder(ctx, True, m)
    assert (m[M["ST"]], m[M["ER"]], m[M["ERR"]], m[M["EXERR"]]) == (0, 1, 1, 0x204)


def test_msg_st_restarts_after_completion() -> None:
    ctx, m = ExecContext(), new_struct("MESSAGE", UnconnectedTimeout=1000)
    for t in (0.0, 1.0):  # queued, then failed after 1 ms
        ctx.now_ms = t
        cm.msg_st(ctx, True, m)
    assert (m[M["EN"]], m[M["ER"]]) == (1, 1)
    ctx.now_ms = 2.0
    cm.msg_st(ctx, True, m)  # ST: the next call after DN/ER starts the message again
    assert (m[M["EN"]], m[M["EW"]], m[M["ER"]], m[M["ERR"]]) == (1, 1, 0, 0)


def _string(text: bytes) -> list:
    s = new_struct("STRING")
    set_string(s, text)
    return s


def test_ascii_writes_complete_with_nothing_attached() -> None:
    ctx, src = ExecContext(), _string(b"HELLO")
    c = new_struct("SERIAL_PORT_CONTROL")
    cm.awt(ctx, True, 0, src, c)  # LEN 0: the string's own 5 characters
    assert (c[C["EN"]], c[C["EU"]], c[C["DN"]], c[C["ER"]], c[C["POS"]]) == (1, 1, 1, 0, 5)
    c = new_struct("SERIAL_PORT_CONTROL", LEN=3)
    cm.awt(ctx, True, 0, src, c)
    assert c[C["POS"]] == 3
    c = new_struct("SERIAL_PORT_CONTROL")
    cm.awa(ctx, True, 0, src, c)  # + $r$l
    assert (c[C["DN"]], c[C["POS"]]) == (1, 7)
    c = new_struct("SERIAL_PORT_CONTROL", LEN=83)  # more than STRING's 82 characters
    cm.awt(ctx, True, 0, src, c)
    assert (c[C["DN"]], c[C["ER"]]) == (0, 1)


def test_ascii_reads_wait_and_acl_clears_them() -> None:
    ctx = ExecContext()
    first = new_struct("SERIAL_PORT_CONTROL", LEN=10)
    second = new_struct("SERIAL_PORT_CONTROL", LEN=4)
    cm.read(ctx, True, 0, _string(b""), first)
    cm.read(ctx, True, 0, _string(b""), second)
    bits = ("EN", "EU", "RN", "DN", "ER", "POS")
    assert tuple(first[C[b]] for b in bits) == (1, 1, 1, 0, 0, 0)  # running, no character
    assert tuple(second[C[b]] for b in bits) == (1, 1, 0, 0, 0, 0)  # waiting in the queue
    cm.read(ctx, True, 0, _string(b""), first)  # executed again while pending: nothing new
    assert tuple(first[C[b]] for b in bits) == (1, 1, 1, 0, 0, 0)
    cm.acl(ctx, True, 0, 1, 0)
    for c in (first, second):
        assert tuple(c[C[b]] for b in bits) == (1, 0, 0, 0, 1, 0)


def test_ascii_buffer_tests_handshake_and_bad_channel() -> None:
    ctx = ExecContext()
    for fn in (cm.count_buffer,):
        c = new_struct("SERIAL_PORT_CONTROL", POS=9, FD=1)
        fn(ctx, True, 0, c)
        assert (c[C["DN"]], c[C["POS"]], c[C["FD"]]) == (1, 0, 0)  # empty buffer
    c = new_struct("SERIAL_PORT_CONTROL")
    cm.handshake(ctx, True, 0, 0, 3, c)
    assert (c[C["DN"]], c[C["ER"]]) == (1, 0)
    c = new_struct("SERIAL_PORT_CONTROL")
    cm.count_buffer(ctx, True, 1, c)  # only channel 0 exists
    assert (c[C["DN"]], c[C["ER"]]) == (0, 1)


def test_ascii_ladder_write_on_the_rising_edge(tmp_path: Path) -> None:
    src = (
        "VAR s : STRING := 'HELLO WORLD'; c : SERIAL_PORT_CONTROL; n : DINT; go : BOOL; END_VAR\n"
        "ADD(n,1,n);\nLES(n,3)OTE(go);\nXIC(go)AWT(0,s,c,5,0);\n"
    )
    watch = ["c.EN", "c.DN", "c.POS", "c.LEN"]
    rows, report = trace(tmp_path, src, ".rll", 3, watch)
    # the rung's length 5 is the control's LEN; scans 1-2 true (sent at the edge), 3 false
    assert [tuple(int(r[k]) for k in watch) for r in rows] == [
        (1, 1, 5, 5),
        (1, 1, 5, 5),
        (0, 1, 5, 5),
    ]
    assert report["diagnostics"] == []


def test_ascii_ladder_arrays_and_acl_yes_no(tmp_path: Path) -> None:
    src = (
        "VAR rb : SINT[20]; tb : SINT[10]; rc, wc, bad, sc, cc : SERIAL_PORT_CONTROL;"
        " s : STRING := 'HI'; END_VAR\n"
        "ARD(0,rb[0],rc,5,?);\n"  # waits: 5 of the 20 SINTs
        "AWT(0,tb[2],wc,4,?);\n"  # 4 characters from tb[2..5]
        "AWT(0,tb[2],bad,9,?);\n"  # only 8 elements from tb[2]
        "AWT(0,s,sc,0,0);\n"  # LEN 0: the STRING's own 2 characters
        "ACB(0,cc,?);\n"
        "XIC(rc.RN)ACL(0,Yes,No);\n"  # clears the waiting read in the same scan
    )
    watch = ["rc.RN", "rc.ER", "wc.DN", "wc.POS", "bad.ER", "sc.POS", "cc.DN", "cc.POS"]
    rows, report = trace(tmp_path, src, ".rll", 1, watch)
    assert {k: int(rows[0][k]) for k in watch} == {
        "rc.RN": 0,
        "rc.ER": 1,
        "wc.DN": 1,
        "wc.POS": 4,
        "bad.ER": 1,
        "sc.POS": 2,
        "cc.DN": 1,
        "cc.POS": 0,
    }
    assert report["diagnostics"] == []


def test_msg_progresses_without_being_executed_again(tmp_path: Path) -> None:
    # ST executes MSG once (EN guards it); the transfer still moves on every scan and
    # fails once the 30 ms timeout has passed; EN stays set (ST has no false rung)
    src = (
        "VAR m : MESSAGE; END_VAR\n"
        "m.UnconnectedTimeout := 30000;\nIF NOT m.EN THEN MSG(m); END_IF;\n"
    )
    rows, _ = trace(tmp_path, src, ".st", 5, MSG_BITS, period_ms=10.0)
    got = [tuple(int(r[k]) for k in MSG_BITS) for r in rows]
    failed = (1, 0, 0, 0, 1, 1, 0x204)
    assert got == [
        (1, 1, 0, 0, 0, 0, 0),
        (1, 0, 1, 0, 0, 0, 0),
        (1, 0, 1, 0, 0, 0, 0),
        failed,
        failed,
    ]


def test_msg_on_a_one_shot_rung_clears_en_when_it_fails(tmp_path: Path) -> None:
    src = (
        "VAR m : MESSAGE; o : BOOL; n : DINT; go : BOOL; END_VAR\n"
        "MOV(20000,m.UnconnectedTimeout)ADD(n,1,n);\nGEQ(n,2)OTE(go);\nXIC(go)ONS(o)MSG(m);\n"
    )
    rows, _ = trace(tmp_path, src, ".rll", 5, MSG_BITS, period_ms=10.0)
    got = [tuple(int(r[k]) for k in MSG_BITS) for r in rows]
    # t 10 rising edge: queued; t 20 sent; t 30 failed: the false rung then clears EN at once
    assert got == [
        (0, 0, 0, 0, 0, 0, 0),
        (1, 1, 0, 0, 0, 0, 0),
        (1, 0, 1, 0, 0, 0, 0),
        (0, 0, 0, 0, 1, 1, 0x204),
        (0, 0, 0, 0, 1, 1, 0x204),
    ]


def test_msg_timeout_bit_stops_a_pending_message() -> None:
    ctx, m = ExecContext(), new_struct("MESSAGE")
    cm.msg_ladder(ctx, True, m)
    m[M["TO"]] = 1
    ctx.now_ms = 5.0
    for work in ctx.background.values():
        work(ctx)
    assert (m[M["EN"]], m[M["ST"]], m[M["ER"]], m[M["ERR"]]) == (1, 0, 1, 0)
