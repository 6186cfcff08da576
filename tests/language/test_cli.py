"""`logixst run` options, report shapes and exit codes (SPEC 6, 9.1, 9.2, 9.6, 9.12)."""

from __future__ import annotations

import csv
import math

import pytest

COUNTER = """
VAR n : DINT; b : BOOL; r : REAL; arr : DINT[3]; END_VAR
n := n + 1;
b := NOT b;
r := r + 0.5;
arr[1] := n * 10;
"""


def test_scans_and_time(st) -> None:
    r = st.run(COUNTER, "n", scans=7)
    assert r.code == 0
    assert r.json["scans"] == 7
    assert r.json["time"] == pytest.approx(0.007)  # 7 scans x 1 ms
    assert r.tags == {"n": 7}
    assert set(r.json) == {"time", "scans", "tags", "faults", "diagnostics", "unsupported"}
    assert r.json["faults"] == [] and r.json["diagnostics"] == []


def test_zero_scans(st) -> None:
    r = st.run(COUNTER, "n", scans=0)
    assert r.code == 0
    assert (r.json["scans"], r.json["tags"]["n"]) == (0, 0)


@pytest.mark.parametrize(
    ("duration", "period", "scans"),
    [
        ("0.01", "1", 10),  # 10 ms / 1 ms
        ("0.01", "3", 3),  # 10 / 3 = 3.33 -> 3
        ("0.0107", "1", 11),  # 10.7 -> 11
        ("0.02", "2.5", 8),  # 20 / 2.5 = 8
        ("1", "10", 100),  # 1000 / 10
    ],
)
def test_duration_rounds_to_scans(st, duration: str, period: str, scans: int) -> None:
    p = st.write("main.st", COUNTER)
    r = st.cli(
        "run", str(p), "--duration", duration, "--scan-period", period, "--json", "--watch", "n"
    )
    assert r.code == 0, r.err
    assert r.json["scans"] == scans
    assert r.tags["n"] == scans


def test_default_duration_is_one_second(st) -> None:
    p = st.write("main.st", COUNTER)
    r = st.cli("run", str(p), "--json", "--watch", "n", "--scan-period", "10")
    assert r.json["scans"] == 100  # 1 s / 10 ms
    assert r.json["time"] == pytest.approx(1.0)


def test_watch_members_elements_bits(st) -> None:
    src = """
    TYPE Pt : STRUCT x : DINT; y : REAL; END_STRUCT END_TYPE
    VAR p : Pt; a : Pt[2]; d : DINT := 5; m : DINT[2,2]; END_VAR
    p.x := 3;
    a[1].y := 2.5;
    m[1,0] := 9;
    """
    t = st.tags(src, "p.x", "a[1].y", "a[1]", "d.0", "d.1", "d.2", "m[1,0]", "p")
    assert t["p.x"] == 3
    assert t["a[1].y"] == 2.5
    assert t["a[1]"] == {"x": 0, "y": 2.5}
    assert (t["d.0"], t["d.1"], t["d.2"]) == (True, False, True)  # 5 = 2#101
    assert t["m[1,0]"] == 9
    assert t["p"] == {"x": 3, "y": 0.0}


def test_watch_is_case_insensitive_and_keeps_expression_text(st) -> None:
    t = st.tags(COUNTER, "N", "Arr[1]", scans=2)
    assert t == {"N": 2, "Arr[1]": 20}


def test_set_values(st) -> None:
    src = """
    VAR d : DINT; b : BOOL; r : REAL; h : DINT; s : SINT; arr : DINT[3]; out : DINT; neg : DINT; x : DINT; END_VAR
    out := d + h + arr[2];
    """
    args = (
        "--set",
        "d=41",
        "--set",
        "b=TRUE",
        "--set",
        "r=1.25",
        "--set",
        "h=16#10",
        "--set",
        "s=-5",
        "--set",
        "arr[2]=1",
        "--set",
        "neg=-2_000",
        "--set",
        "x.3=1",
    )
    t = st.tags(src, "d", "b", "r", "h", "s", "arr", "out", "neg", "x", args=args)
    assert t["d"] == 41
    assert t["b"] is True
    assert t["r"] == 1.25
    assert t["h"] == 16  # 16#10
    assert t["s"] == -5
    assert t["arr"] == [0, 0, 1]
    assert t["out"] == 58  # 41 + 16 + 1
    assert t["neg"] == -2000
    assert t["x"] == 8  # bit 3


def test_set_bool_as_number_and_real_rounding(st) -> None:
    src = """
    VAR b : BOOL; r : REAL; END_VAR
    """
    t = st.tags(src, "b", "r", args=("--set", "b=1", "--set", "r=16777217.0"))
    assert t["b"] is True
    assert t["r"] == 16777216.0  # --set stores through the REAL rounding too


def test_trace_csv(st, tmp_path) -> None:
    out = tmp_path / "t.csv"
    p = st.write("main.st", COUNTER)
    r = st.cli(
        "run",
        str(p),
        "--scans",
        "4",
        "--scan-period",
        "2.5",
        "--watch",
        "n",
        "--watch",
        "b",
        "--watch",
        "r",
        "--watch",
        "arr[1]",
        "--trace",
        str(out),
    )
    assert r.code == 0, r.err
    rows = list(csv.reader(out.open()))
    assert rows[0] == ["time", "n", "b", "r", "arr[1]"]
    assert len(rows) == 5  # header + one row per scan
    # time = scan start k * 2.5 ms; values at the end of the scan; BOOL as 1/0
    expected = [
        (0.0, 1, 1, 0.5, 10),
        (0.0025, 2, 0, 1.0, 20),
        (0.005, 3, 1, 1.5, 30),
        (0.0075, 4, 0, 2.0, 40),
    ]
    for row, (tm, n, b, rv, a1) in zip(rows[1:], expected, strict=True):
        assert float(row[0]) == pytest.approx(tm)
        assert (int(row[1]), int(row[2]), float(row[3]), int(row[4])) == (n, b, rv, a1)


def test_trace_stops_at_major_fault(st, tmp_path) -> None:
    out = tmp_path / "t.csv"
    p = st.write(
        "main.st",
        """
    VAR n : DINT; a : DINT[3]; END_VAR
    n := n + 1;
    a[n] := 1;
    """,
    )
    r = st.cli("run", str(p), "--scans", "10", "--watch", "n", "--trace", str(out), "--json")
    assert r.code == 3
    rows = list(csv.reader(out.open()))
    # scan 0: n=1 ok; scan 1: n=2 ok; scan 2: n=3 -> a[3] faults; that scan's row is written
    assert [r[1] for r in rows[1:]] == ["1", "2", "3"]


def test_table_output_without_json(st) -> None:
    p = st.write("main.st", COUNTER)
    r = st.cli("run", str(p), "--scans", "3")
    assert r.code == 0
    lines = dict(line.split(None, 1) for line in r.out.splitlines())
    # all elementary tags when nothing is watched; the array is not elementary
    assert lines["n"].strip() == "3"
    assert lines["b"].strip() == "true"  # toggled 3 times from FALSE
    assert lines["r"].strip() == "1.5"
    assert "arr" not in lines


# ------------------------------------------------------------------ exit codes
def test_verification_error_exit_1(st) -> None:
    src = """
    VAR x : DINT; END_VAR
    x := y + 1;
    """
    r = st.run(src, "x")
    assert r.code == 1
    assert ":3:6: error E101" in r.err  # path:line:col: error CODE message on stderr
    rep = r.json
    assert rep["tags"] == {}
    assert rep["scans"] == 0
    (d,) = rep["diagnostics"]
    assert set(d) == {
        "path",
        "line",
        "column",
        "endLine",
        "endColumn",
        "severity",
        "code",
        "message",
    }
    assert (d["code"], d["line"], d["column"], d["endLine"], d["endColumn"]) == ("E101", 3, 6, 3, 7)


def test_verification_error_without_json(st) -> None:
    p = st.write("main.st", "VAR x : DINT; END_VAR\nx := 1 +;\n")
    r = st.cli("run", str(p))
    assert r.code == 1
    assert r.out == ""
    assert "error S001" in r.err


def _one_line_error(r) -> None:  # noqa: ANN001
    assert r.code == 2
    assert "Traceback" not in r.err
    lines = r.err.strip().splitlines()
    assert len(lines) == 1, r.err
    assert lines[0].startswith("logixst: error: ")


def test_missing_file(st) -> None:
    r = st.cli("run", str(st.tmp / "nope.st"))
    _one_line_error(r)
    assert "nope.st" in r.err


def test_directory(st) -> None:
    r = st.cli("run", str(st.tmp))
    _one_line_error(r)


def test_binary_file(st) -> None:
    p = st.tmp / "bin.st"
    p.write_bytes(b"\x7fELF\x00\x01\x02\x03" * 64)
    _one_line_error(st.cli("run", str(p)))


def test_empty_file(st) -> None:
    p = st.tmp / "empty.st"
    p.write_text("")
    _one_line_error(st.cli("run", str(p)))
    p.write_text("  \n\n")
    _one_line_error(st.cli("run", str(p)))


def test_unsupported_extension(st) -> None:
    p = st.tmp / "prog.txt"
    p.write_text("x := 1;\n")
    _one_line_error(st.cli("run", str(p)))


@pytest.mark.parametrize(
    "extra",
    [
        [],
        ["--bogus"],
        ["--scans", "x"],
        ["--scans", "-1"],
        ["--scan-period", "0"],
        ["--scans", "1", "--duration", "1"],
        ["--set", "n"],
        ["--set", "n=abc"],
        ["--set", "nosuch=1"],
        ["--watch", "nosuch"],
        ["--watch", "n +"],
        ["--watch", "arr[7]"],
    ],
)
def test_usage_errors(st, extra: list[str]) -> None:
    p = st.write("main.st", COUNTER)
    argv = ["run", str(p), *extra] if extra else []
    _one_line_error(st.cli(*argv))


def test_usage_error_check_missing_path(st) -> None:
    _one_line_error(st.cli("check", str(st.tmp / "missing.st")))


def test_unwritable_trace(st) -> None:
    p = st.write("main.st", COUNTER)
    _one_line_error(
        st.cli("run", str(p), "--scans", "1", "--trace", str(st.tmp / "no" / "dir" / "t.csv"))
    )


def test_large_generated_program(st) -> None:
    lines = ["VAR n : DINT; a : DINT[100]; END_VAR"]
    count = 0
    size = len(lines[0])
    while size < 1_000_000:
        line = f"a[{count % 100}] := a[{count % 100}] + 1; n := n + 1; (* generated statement {count:06d} *)"
        lines.append(line)
        size += len(line) + 1
        count += 1
    p = st.tmp / "big.st"
    p.write_text("\n".join(lines) + "\n")
    assert p.stat().st_size >= 1_000_000
    r = st.cli("run", str(p), "--scans", "1", "--json", "--watch", "n", "--watch", "a[0]")
    assert r.code == 0, r.err[:500]
    assert "Traceback" not in r.err
    # n counts every generated line; a[0] gets lines 0, 100, 200, ... -> ceil(count / 100)
    assert r.tags == {"n": count, "a[0]": (count + 99) // 100}


RANGES = "VAR s : SINT; u : USINT; b : BOOL; r : REAL; END_VAR s := s; u := u;"


@pytest.mark.parametrize(
    ("setting", "fragment"),
    [
        ("s=128", "-128..127"),  # SINT is 8-bit signed: 127 is the largest
        ("s=-129", "-128..127"),
        ("u=256", "0..255"),  # USINT: 2**8 - 1 = 255
        ("u=-1", "0..255"),
        ("b=2", "BOOL"),
        ("s='x'", "string"),
    ],
)
def test_set_rejects_values_that_do_not_fit(st, setting: str, fragment: str) -> None:
    r = st.run(RANGES, "s", args=("--set", setting))
    _one_line_error(r)
    assert fragment in r.err


def test_set_accepts_the_range_ends(st) -> None:
    t = st.tags(
        RANGES, "s", "u", "r", args=("--set", "s=-128", "--set", "u=255", "--set", "r=-1.5")
    )
    assert t == {"s": -128, "u": 255, "r": -1.5}


def test_json_multi_dimensional_arrays_nest_by_dimension(st) -> None:
    # m : DINT[2,3] holds m[i,j] = 10*i + j; JSON nests the last subscript innermost.
    src = """VAR m : DINT[2,3]; c : DINT[2,2,2]; i, j : DINT; END_VAR
    FOR i := 0 TO 1 DO FOR j := 0 TO 2 DO m[i,j] := 10*i + j; END_FOR; END_FOR;
    c[1,0,1] := 7;"""
    t = st.tags(src, "m", "c")
    assert t["m"] == [[0, 1, 2], [10, 11, 12]]
    assert t["c"] == [[[0, 0], [0, 0]], [[0, 7], [0, 0]]]


def test_json_real_infinity_and_nan(st) -> None:
    # 3.0e38 * 10.0 exceeds the float32 maximum (about 3.4e38) -> +inf; inf - inf -> NaN.
    src = "VAR big, inf, nan : REAL; END_VAR big := 3.0e38; inf := big * 10.0; nan := inf - inf;"
    r = st.run(src, "inf", "nan")
    assert r.code == 0
    # strict JSON: the values as strings (docs/decisions/0132, superseding 0007's bare tokens)
    assert '"inf": "Infinity"' in r.out and '"nan": "NaN"' in r.out
    assert float(r.tags["inf"]) == math.inf and math.isnan(float(r.tags["nan"]))
