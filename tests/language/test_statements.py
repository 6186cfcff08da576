"""IF, CASE, FOR, WHILE, REPEAT, EXIT; bits, arrays, UDTs, initialisers, [:=], S:FS, JSR."""

from __future__ import annotations


def test_if_elsif_else(st) -> None:
    src = """
    VAR x : DINT := 5; r1, r2, r3 : DINT; END_VAR
    IF x > 10 THEN r1 := 1; ELSIF x > 3 THEN r1 := 2; ELSE r1 := 3; END_IF;
    IF x > 10 THEN r2 := 1; ELSIF x > 7 THEN r2 := 2; ELSE r2 := 3; END_IF;
    IF x = 5 THEN r3 := 1; END_IF;
    """
    assert st.tags(src, "r1", "r2", "r3") == {"r1": 2, "r2": 3, "r3": 1}


def test_case_lists_ranges_else(st) -> None:
    src = """
    VAR i, one, list, neg, other : DINT; END_VAR
    FOR i := -6 TO 10 DO
      CASE i OF
        1: one := one + 1;
        2, 3, 7..8: list := list + 1;
        -5..-1: neg := neg + 1;
      ELSE
        other := other + 1;
      END_CASE;
    END_FOR;
    """
    t = st.tags(src, "one", "list", "neg", "other")
    assert t["one"] == 1  # i = 1
    assert t["list"] == 4  # i = 2, 3, 7, 8
    assert t["neg"] == 5  # i = -5, -4, -3, -2, -1
    # ELSE: -6, 0, 4, 5, 6, 9, 10 (17 values - 1 - 4 - 5 = 7)
    assert t["other"] == 7


def test_case_first_matching_arm_only(st) -> None:
    src = """
    VAR sel : DINT := 3; hits : DINT; END_VAR
    CASE sel OF
      1..5: hits := hits + 1;
      3: hits := hits + 10;
    END_CASE;
    """
    assert st.tags(src, "hits")["hits"] == 1  # only the first arm whose labels match runs


def test_for_negative_by(st) -> None:
    src = """
    VAR i, n, last, sum : DINT; END_VAR
    FOR i := 10 TO 1 BY -3 DO
      n := n + 1;
      last := i;
      sum := sum + i;
    END_FOR;
    """
    t = st.tags(src, "i", "n", "last", "sum")
    assert t["n"] == 4  # i = 10, 7, 4, 1
    assert t["last"] == 1
    assert t["sum"] == 22  # 10 + 7 + 4 + 1
    assert t["i"] == -2  # the index is stepped once more before the test fails: 1 - 3


def test_for_by_two_and_empty_range(st) -> None:
    src = """
    VAR i, n, sum, e : DINT; END_VAR
    FOR i := 0 TO 9 BY 2 DO
      n := n + 1;
      sum := sum + i;
    END_FOR;
    FOR i := 5 TO 4 DO
      e := e + 1;
    END_FOR;
    """
    t = st.tags(src, "n", "sum", "e")
    assert t["n"] == 5  # 0, 2, 4, 6, 8
    assert t["sum"] == 20  # 0 + 2 + 4 + 6 + 8
    assert t["e"] == 0  # start > end with a positive step: body never runs


def test_repeat_runs_once_when_condition_true(st) -> None:
    src = """
    VAR n, k : DINT; END_VAR
    REPEAT
      n := n + 1;
    UNTIL TRUE
    END_REPEAT;
    REPEAT
      k := k + 2;
    UNTIL k >= 7
    END_REPEAT;
    """
    t = st.tags(src, "n", "k")
    assert t["n"] == 1  # body first, then the test
    assert t["k"] == 8  # 2, 4, 6, 8 -> 8 >= 7 stops


def test_while(st) -> None:
    src = """
    VAR i, never : DINT; END_VAR
    WHILE i < 5 DO
      i := i + 1;
    END_WHILE;
    WHILE FALSE DO
      never := 1;
    END_WHILE;
    """
    assert st.tags(src, "i", "never") == {"i": 5, "never": 0}


def test_exit_leaves_innermost_loop_only(st) -> None:
    src = """
    VAR i, j, inner, outer, w : DINT; END_VAR
    FOR i := 1 TO 3 DO
      FOR j := 1 TO 10 DO
        IF j = 2 THEN EXIT; END_IF;
        inner := inner + 1;
      END_FOR;
      outer := outer + 1;
    END_FOR;
    WHILE TRUE DO
      w := w + 1;
      REPEAT
        EXIT;
      UNTIL FALSE END_REPEAT;
      IF w >= 4 THEN EXIT; END_IF;
    END_WHILE;
    """
    t = st.tags(src, "inner", "outer", "j", "w")
    assert t["inner"] == 3  # j = 1 once per outer iteration
    assert t["outer"] == 3  # the outer loop is not left
    assert t["j"] == 2  # EXIT leaves with the index as it was
    assert t["w"] == 4  # the REPEAT's EXIT only leaves the REPEAT


def test_bit_read_write(st) -> None:
    src = """
    VAR d : DINT := 32; b5, b4 : BOOL; e : DINT; top : DINT; s : SINT; END_VAR
    b5 := d.5;
    b4 := d.4;
    d.0 := TRUE;
    e.5 := 1;
    e.5 := 0;
    e.3 := 1;
    top.31 := TRUE;
    s.7 := 1;
    """
    t = st.tags(src, "b5", "b4", "d", "e", "top", "s", "d.5", "top.31")
    assert t["b5"] is True  # 32 = 2^5
    assert t["b4"] is False
    assert t["d"] == 33  # 32 + 2^0
    assert t["e"] == 8  # bit 5 set then cleared, bit 3 set
    assert t["top"] == -2147483648  # bit 31 is the sign bit of a DINT
    assert t["s"] == -128  # bit 7 is the sign of a SINT
    assert t["d.5"] is True
    assert t["top.31"] is True


def test_indirect_bit(st) -> None:
    src = """
    VAR d : DINT; i : DINT := 3; r, r2 : BOOL; END_VAR
    d.[i] := TRUE;
    d.[i + 1] := TRUE;
    r := d.[i];
    r2 := d.[i - 1];
    """
    t = st.tags(src, "d", "r", "r2")
    assert t["d"] == 24  # 2^3 + 2^4 = 8 + 16
    assert t["r"] is True
    assert t["r2"] is False


def test_three_dimensional_arrays_row_major(st) -> None:
    src = """
    VAR a : DINT[2,3,4]; b : ARRAY[0..1,0..2,0..3] OF DINT; i, j, k : DINT; END_VAR
    FOR i := 0 TO 1 DO
      FOR j := 0 TO 2 DO
        FOR k := 0 TO 3 DO
          a[i,j,k] := i * 100 + j * 10 + k;
          b[i,j,k] := a[i,j,k] * 2;
        END_FOR;
      END_FOR;
    END_FOR;
    """
    t = st.tags(src, "a", "a[1,2,3]", "b[1,0,2]", "b")
    # JSON nests [i][j][k] (docs/decisions/0007): 2 lists of 3 lists of 4 values
    assert [len(t["a"]), len(t["a"][0]), len(t["a"][0][0])] == [2, 3, 4]
    assert t["a"][1][0][1] == 101  # i=1, j=0, k=1 -> 100 + 0 + 1
    assert t["a"][0][1][2] == 12  # i=0, j=1, k=2 -> 0 + 10 + 2
    assert t["a"][1][2][3] == 123  # last element
    assert t["a[1,2,3]"] == 123
    assert t["b[1,0,2]"] == 204  # (100 + 0 + 2) * 2
    assert t["b"][0][1][0] == 20  # i=0, j=1, k=0 -> 10 * 2


def test_array_initialiser_and_variable_subscript(st) -> None:
    src = """
    VAR a : DINT[5] := [10, 20, 30, 0, 0]; i : DINT := 4; s, x : DINT; END_VAR
    a[i] := a[0] + a[2];
    FOR x := 0 TO 4 DO s := s + a[x]; END_FOR;
    """
    t = st.tags(src, "a", "s")
    assert t["a"] == [10, 20, 30, 0, 40]  # a[4] = 10 + 30
    assert t["s"] == 100  # 10 + 20 + 30 + 0 + 40


def test_udt_members_nested_arrays_and_initialisers(st) -> None:
    src = """
    TYPE
      Pt : STRUCT x : DINT; y : REAL; END_STRUCT;
      Seg : STRUCT a : Pt; b : Pt; len : REAL; tags : DINT[2]; END_STRUCT;
    END_TYPE
    VAR
      p : Pt := (x := 3, y := 4.5);
      segs : Seg[3] := [(a := (x := 1), len := 2.5), (b := (x := 7, y := 8.0), tags := [5, 6]), (len := 0.0)];
      total : DINT;
      i : DINT;
    END_VAR
    segs[2].a.y := p.y;
    segs[2].a.x := p.x * 10;
    segs[2].b.y := p.y + segs[1].b.y;
    segs[2].tags[1] := segs[1].tags[0] + segs[1].tags[1];
    FOR i := 0 TO 2 DO total := total + segs[i].a.x + segs[i].b.x; END_FOR;
    """
    r = st.run(src, "p", "segs[0]", "segs[2].a.x", "segs[2].b.y", "segs[2].tags[1]", "total")
    assert r.code == 0, r.err
    t = r.tags
    assert t["p"] == {"x": 3, "y": 4.5}
    assert t["segs[0]"] == {
        "a": {"x": 1, "y": 0.0},
        "b": {"x": 0, "y": 0.0},
        "len": 2.5,
        "tags": [0, 0],
    }
    assert t["segs[2].a.x"] == 30  # 3 * 10
    assert t["segs[2].b.y"] == 12.5  # 4.5 + 8.0
    assert t["segs[2].tags[1]"] == 11  # 5 + 6
    assert t["total"] == 38  # a.x: 1 + 0 + 30; b.x: 0 + 7 + 0


def test_array_initialiser_needs_one_value_per_element(st) -> None:
    """SPEC 2.1: a wrong element count is a verification error, too few as too many (decision 0080)."""
    for init, given in (("[1, 2]", 2), ("[1, 2, 3, 4]", 4)):
        r = st.check(f"VAR a : DINT[3] := {init}; END_VAR\na[0] := 1;\n")
        assert r.code == 1
        assert [(d["code"], d["message"]) for d in r.json] == [
            ("E118", f"{given} elements given for an array of 3")
        ]


def test_udt_member_default(st) -> None:
    src = """
    TYPE Cfg : STRUCT limit : DINT := 42; gain : REAL := 0.5; END_STRUCT END_TYPE
    VAR c : Cfg; o : Cfg := (limit := 7); END_VAR
    """
    t = st.tags(src, "c", "o")
    assert t["c"] == {"limit": 42, "gain": 0.5}
    assert t["o"] == {"limit": 7, "gain": 0.5}


def test_non_retentive_assignment_zeroed_in_prescan(st) -> None:
    src = """
    VAR nr : DINT := 5; plain : DINT := 5; nb : BOOL := TRUE; seen : BOOL; END_VAR
    seen := nb;
    nr [:=] nr + 1;
    plain := plain + 1;
    nb [:=] FALSE;
    """
    t = st.tags(src, "nr", "plain", "seen")
    assert t["nr"] == 1  # prescan zeroes the [:=] target: 0 + 1 (not 5 + 1)
    assert t["plain"] == 6  # plain := keeps the initial value: 5 + 1
    assert t["seen"] is False  # nb was cleared by the prescan before the first scan read it
    t = st.tags(src, "nr", "plain", args=("--set", "nr=42", "--set", "plain=42"))
    assert t["nr"] == 1  # --set happens before the prescan, which zeroes nr
    assert t["plain"] == 43


def test_first_scan_flag(st, tmp_path) -> None:
    src = """
    VAR n, scans : DINT; fs_last : BOOL; END_VAR
    IF S:FS THEN n := n + 1; END_IF;
    fs_last := S:FS;
    scans := scans + 1;
    """
    trace = tmp_path / "fs.csv"
    t = st.tags(src, "n", "fs_last", "scans", scans=3, args=("--trace", str(trace)))
    assert t == {"n": 1, "fs_last": False, "scans": 3}
    rows = trace.read_text().splitlines()
    assert rows[0] == "time,n,fs_last,scans"
    # scan k starts at k * 1 ms; S:FS true only in scan 0
    assert rows[1:] == ["0.0,1,1,1", "0.001,1,0,2", "0.002,1,0,3"]


def test_jsr_between_files(st) -> None:
    main = st.write(
        "main.st",
        """
    VAR cnt, sub_seen, other_ran : DINT; END_VAR
    JSR(sub);
    JSR(Sub);
    sub_seen := cnt;
    """,
    )
    sub = st.write(
        "sub.st",
        """
    cnt := cnt + 1;
    """,
    )
    other = st.write(
        "other.st",
        """
    other_ran := 99;
    """,
    )
    r = st.cli(
        "run",
        str(main),
        str(sub),
        str(other),
        "--scans",
        "3",
        "--json",
        "--watch",
        "cnt",
        "--watch",
        "sub_seen",
        "--watch",
        "other_ran",
    )
    assert r.code == 0, r.err
    # 2 JSRs per scan (routine names are case-insensitive) x 3 scans
    assert r.tags == {"cnt": 6, "sub_seen": 6, "other_ran": 0}  # other.st is never called


def test_jsr_unknown_routine_is_a_verification_error(st) -> None:
    main = st.write(
        "main.st",
        """
    VAR x : DINT; END_VAR
    JSR(nowhere);
    """,
    )
    r = st.cli("run", str(main), "--json")
    assert r.code == 1
    assert "E124" in r.err


def test_for_step_computed_at_run_time(st) -> None:
    src = """
    VAR i, n, last : DINT; stp : DINT := -2; END_VAR
    FOR i := 10 TO 1 BY stp DO n := n + 1; last := i; END_FOR;
    """
    t = st.tags(src, "i", "n", "last")
    assert t == {"i": 0, "n": 5, "last": 2}  # 10, 8, 6, 4, 2; then 0 < 1 ends the loop


def test_case_on_sint_with_negative_range(st) -> None:
    src = """
    VAR s : SINT := -3; c : DINT; END_VAR
    CASE s OF -5..-3: c := 1; ELSE c := 2; END_CASE;
    """
    assert st.tags(src, "c")["c"] == 1  # -3 is inside -5..-3 (ends inclusive)


def test_lint_bit_63_and_watch_indirect_bit(st) -> None:
    src = """
    VAR l : LINT; d : DINT := 10; i : DINT := 3; END_VAR
    l.63 := 1;
    """
    t = st.tags(src, "l", "d.[i]", "d.[i - 3]")
    assert t["l"] == -9223372036854775808  # bit 63 is the LINT sign bit: -2^63
    assert t["d.[i]"] is True  # 10 = 2#1010: bit 3 set
    assert t["d.[i - 3]"] is False  # bit 0 clear
