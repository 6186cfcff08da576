"""Major faults (subscript 4/20, watchdog 6/1) and minor divide-by-zero 4/4 (SPEC 3.4, 9.4, 9.5)."""

from __future__ import annotations

import json
import time

import pytest


def test_subscript_out_of_range_faults(st) -> None:
    src = """
    VAR a : DINT[5]; i : DINT := 5; before, after, scans : DINT; END_VAR
    scans := scans + 1;
    before := 1;
      after := a[ i ];
    after := 2;
    """
    r = st.run(src, "before", "after", "scans", scans=5)
    assert r.code == 3
    rep = r.json
    assert rep["scans"] == 1  # the major fault stops the run in the first scan
    assert rep["tags"] == {"before": 1, "after": 0, "scans": 1}  # values at the fault
    (f,) = rep["faults"]
    path = str(st.tmp / "main.st")
    # source lines: 1 blank (dedent keeps the leading newline), 2 VAR, 3 scans, 4 before, 5 after
    assert f == {
        "type": 4,
        "code": 20,
        "major": True,
        "message": f["message"],
        "file": path,
        "line": 5,
        "column": 12,
    }  # column of 'a[ i ]' in "  after := a[ i ];"


def test_subscript_fault_in_multi_dimensional_store(st) -> None:
    src = """
    VAR m : DINT[2,3]; j : DINT := 3; END_VAR
    m[1, j] := 7;
    """
    r = st.run(src, "m")
    assert r.code == 3
    f = r.json["faults"][-1]
    # j = 3 is outside 0..2 of the second dimension; located at 'm[1, j]' (line 3, col 1)
    assert (f["type"], f["code"], f["major"], f["line"], f["column"]) == (4, 20, True, 3, 1)
    assert r.json["tags"]["m"] == [[0, 0, 0], [0, 0, 0]]


def test_each_dimension_checked_separately(st) -> None:
    src = """
    VAR m : DINT[2,3]; j : DINT := -1; END_VAR
    m[1, j] := 7;
    """
    r = st.run(src, "m")
    # m[1,-1] flattens to 1*3 - 1 = 2, inside the storage; it must still fault (j < 0)
    assert r.code == 3
    assert r.json["faults"][-1]["code"] == 20
    assert r.json["tags"]["m"] == [[0, 0, 0], [0, 0, 0]]


def test_endless_loop_watchdog(st) -> None:
    src = """
    VAR n : DINT; END_VAR
    WHILE TRUE DO
      n := n + 1;
    END_WHILE;
    """
    r = st.run(src, "n", scans=3, args=("--watchdog", "100000"))
    assert r.code == 3
    (f,) = r.json["faults"]
    assert (f["type"], f["code"], f["major"]) == (6, 1, True)
    assert f["line"] == 4  # the statement that exceeded the budget
    assert r.json["scans"] == 1
    # the budget counts statements: at most 100000 of them ran before the fault
    assert 0 < r.json["tags"]["n"] <= 100000


def test_endless_loop_default_budget(st) -> None:
    src = """
    VAR n : DINT; END_VAR
    WHILE TRUE DO n := n + 1; END_WHILE;
    """
    t0 = time.monotonic()
    r = st.run(src, "n")
    assert time.monotonic() - t0 < 10
    assert r.code == 3
    assert (r.json["faults"][0]["type"], r.json["faults"][0]["code"]) == (6, 1)
    assert 1_000_000 < r.json["tags"]["n"] <= 5_000_000  # default budget 5,000,000 statements


@pytest.mark.parametrize(
    ("loop", "column"),
    [
        ("WHILE TRUE DO\nEND_WHILE;", 1),
        ("REPEAT ; UNTIL FALSE END_REPEAT;", 1),
        ("n := 0; FOR i := 0 TO 2147483646 DO END_FOR;", 9),  # the FOR starts after "n := 0; "
    ],
)
def test_loop_without_statements_trips_the_watchdog(st, loop: str, column: int) -> None:
    # An empty body used to count nothing, so the scan never ended (a hang, found by fuzzing).
    # Each iteration now counts one; with a budget of 1000 the 1001st faults, located at the loop.
    src = "VAR i, n : DINT; END_VAR\n" + loop + "\n"
    r = st.run(src, "n", scans=3, args=("--watchdog", "1000"))
    assert r.code == 3
    (f,) = r.json["faults"]
    assert (f["type"], f["code"], f["major"], f["line"], f["column"]) == (6, 1, True, 2, column)
    assert r.json["scans"] == 1


def test_watchdog_not_tripped_by_bounded_loop(st) -> None:
    src = """
    VAR i, n : DINT; END_VAR
    FOR i := 1 TO 1000 DO n := n + 1; END_FOR;
    """
    # about 2 statements per iteration -> ~2000 per scan, far below the budget of 100000
    r = st.run(src, "n", scans=5, args=("--watchdog", "100000"))
    assert r.code == 0
    assert r.tags["n"] == 5000  # 1000 per scan x 5 scans


def test_divide_by_zero_minor_fault(st) -> None:
    src = """
    VAR a : DINT := 7; z : DINT; q, m, after : DINT; rz : REAL; pinf, ninf, nan : REAL; END_VAR
    q := a / z;
    m := a MOD z;
    pinf := 1.0 / rz;
    ninf := -1.0 / rz;
    nan := rz / rz;
    after := after + 1;
    """
    r = st.run(src, "q", "m", "pinf", "ninf", "nan", "after", scans=3)
    assert r.code == 0  # minor faults do not stop the controller
    t = r.tags
    assert t["q"] == 7  # integer / 0: result is Source A
    assert t["m"] == 0  # MOD 0: result 0
    # non-finite REALs are JSON strings (docs/decisions/0132)
    assert t["pinf"] == "Infinity"  # IEEE: 1 / +0 = +inf
    assert t["ninf"] == "-Infinity"  # -1 / +0 = -inf
    assert t["nan"] == "NaN"  # 0 / 0 = NaN
    assert t["after"] == 3  # execution continued in every scan
    faults = r.json["faults"]
    assert len(faults) == 5  # one entry per location
    for f in faults:
        assert (f["type"], f["code"], f["major"], f["count"]) == (4, 4, False, 3)  # once per scan
    assert [(f["line"], f["column"]) for f in faults] == [(3, 6), (4, 6), (5, 9), (6, 9), (7, 8)]


def test_minor_fault_in_text_output(st) -> None:
    p = st.write(
        "main.st",
        """
    VAR a, z : DINT; END_VAR
    a := 1 / z;
    """,
    )
    r = st.cli("run", str(p), "--scans", "2", "--watch", "a")
    assert r.code == 0
    assert "minor fault type 4 code 4" in r.err
    assert "a" in r.out and "1" in r.out  # the table: a = Source A = 1


def test_endless_jsr_recursion_is_a_stack_overflow_fault(st) -> None:
    # main calls itself through sub: Logix faults with type 4 code 84 (stack overflow).
    main = st.write("main.st", "VAR depth : DINT; END_VAR depth := depth + 1; JSR(sub);")
    sub = st.write("sub.st", "JSR(main);")
    r = st.cli("run", str(main), str(sub), "--scans", "1", "--json", "--watch", "depth")
    assert r.code == 3, r.err
    fault = json.loads(r.out)["faults"][-1]
    assert (fault["type"], fault["code"], fault["major"]) == (4, 84, True)
    assert fault["file"].endswith(("main.st", "sub.st"))
