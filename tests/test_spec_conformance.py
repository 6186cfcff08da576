"""SPEC conformance through the `logixst` command, grouped by SPEC section.

Each test drives `cli.main` (the `st` fixture) or `python -m interpreter.cli` and names the
SPEC sentence it checks in its docstring. Expected values are worked out by hand in the
comments. Requirements already shown elsewhere are listed in the audit report, not repeated.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from interpreter import cli

L5X = Path(__file__).parent / "l5x" / "fixtures"


# ------------------------------------------------------------------ 2.1 .st files
def test_program_wrapper_shorthand_arrays_and_multi_name_initialiser(st) -> None:
    """SPEC 2.1 / 9.11: PROGRAM wrapper, `DINT[10]` = `ARRAY[0..9] OF DINT`, `a, b : BOOL := TRUE`."""
    src = """
    PROGRAM Demo
    TYPE Pt : STRUCT x : DINT; y : REAL; END_STRUCT; END_TYPE
    VAR
      a, b : BOOL := TRUE;
      iec : ARRAY[0..9] OF DINT;
      short : DINT[10];
      p : Pt := (y := 2.5);
      t : FBD_TIMER := (PRE := 500);
    END_VAR
    iec[9] := 3;
    short[9] := iec[9] * 2;
    END_PROGRAM
    """
    t = st.tags(src, "a", "b", "iec[9]", "short[9]", "p", "t.PRE")
    # both names get TRUE; index 9 is the last of 10 in both forms; 3 * 2 = 6; y by member, x default 0
    assert t == {
        "a": True,
        "b": True,
        "iec[9]": 3,
        "short[9]": 6,
        "p": {"x": 0, "y": 2.5},
        "t.PRE": 500,
    }


@pytest.mark.parametrize(("init", "given"), [("[1, 2]", 2), ("[1, 2, 3, 4]", 4)])
def test_wrong_element_count_is_a_verification_error(st, init: str, given: int) -> None:
    """SPEC 2.1: wrong element counts are verification errors (decision 0080: too few as too many)."""
    r = st.run(f"VAR arr : DINT[3] := {init}; END_VAR\narr[0] := 1;\n", "arr")
    assert r.code == 1
    (d,) = r.json["diagnostics"]
    assert (d["code"], d["line"], d["column"]) == ("E118", 1, 22)  # the list starts in column 22
    assert d["message"] == f"{given} elements given for an array of 3"


def test_unknown_member_in_initialiser_is_an_error(st) -> None:
    """SPEC 2.1: unknown members in an initialiser are verification errors."""
    r = st.check("VAR t : FBD_TIMER := (PRE := 5, Bogus := 1); END_VAR\nt.PRE := 1;\n")
    assert r.code == 1
    assert [(d["code"], d["column"]) for d in r.json] == [
        ("E118", 33)
    ]  # `Bogus` starts in column 33


# ------------------------------------------------------------------ 2.2 .rll files / 9.18
RLL_FORMS = """\
VAR a : BOOL := TRUE; b, o1, o2 : BOOL; n, m : DINT; t : TIMER := (PRE := 5); END_VAR
// a plain comment between rungs
RC: "Seal; in -- the comment holds a semicolon";
N: XIC(a)OTE(o1);
XIO(a)
   OTE(o2);
N: [ XIC(b) ,
     XIO(b) ] ADD(n, 1, n);
RC: "timer with placeholders";
TON(t,?,?);
GEQ(n, 2) MOVE(7, m);
;
"""


def test_rll_forms_mix_and_empty_rung(st) -> None:
    """SPEC 2.2 / 9.18: `N:`/`RC:` lines mix with plain rungs and comments, `RC:` may hold `;`,
    line breaks inside a rung are insignificant, `?` placeholders, v36+ mnemonics; `;` alone is
    an empty rung (an error)."""
    p = st.write("forms.rll", RLL_FORMS)
    r = st.cli("check", str(p), "--format", "json")
    assert r.code == 1
    # the only diagnostic is the empty rung: rung numbers count from 0, `;` is the 7th rung
    assert [(d["code"], d["line"], d["column"], d["severity"]) for d in r.json] == [
        ("E129", 12, 1, "error")
    ]
    p.write_text(RLL_FORMS.replace("\n;\n", "\n"))
    r = st.cli(
        "run",
        str(p),
        "--scans",
        "3",
        "--json",
        "--watch",
        "o1",
        "--watch",
        "o2",
        "--watch",
        "n",
        "--watch",
        "m",
        "--watch",
        "t.ACC",
    )
    assert r.code == 0, r.err
    # a is TRUE: o1 on, o2 off; the branch XIC(b) OR XIO(b) is always true: n counts 3 scans;
    # GEQ(n, 2) is true from the second scan: m = 7; TON ACC: scans at 0, 1, 2 ms -> 2 ms
    assert r.tags == {"o1": True, "o2": False, "n": 3, "m": 7, "t.ACC": 2}


def test_rll_branch_may_start_a_rung_and_legs_may_be_empty(st) -> None:
    """SPEC 2.2: branches may start a rung and legs may be empty; SPEC 7/9.10: a shorted
    branch is a warning, so the program still runs."""
    p = st.write("b.rll", "VAR a, o : BOOL; END_VAR\n[XIC(a),]OTE(o);\n")
    r = st.cli("run", str(p), "--scans", "1", "--json", "--watch", "o")
    assert r.code == 0
    # a is FALSE, but the empty leg passes the incoming TRUE: o = TRUE
    assert r.tags == {"o": True}
    assert [(d["code"], d["severity"]) for d in r.json["diagnostics"]] == [("W202", "warning")]


# ------------------------------------------------------------------ 2.3 L5X / 9.9
def test_l5x_st_positions_are_file_positions_and_name_the_routine(st) -> None:
    """SPEC 2.3 / 9.9: positions in the .L5X file itself; the message names program, routine
    and the ST line, 0-based as Studio shows it."""
    path = L5X / "st_errors.L5X"
    r = st.cli("check", str(path), "--format", "json")
    assert r.code == 1
    e101 = next(d for d in r.json if d["code"] == "E101")
    # file line 16 is `<![CDATA[  Missing := 2;]]>`: 9 characters of `<![CDATA[` and two
    # spaces put `Missing` at column 12, end exclusive 12 + 7 = 19. It is Studio's line 1.
    assert (e101["line"], e101["column"], e101["endLine"], e101["endColumn"]) == (16, 12, 16, 19)
    assert e101["message"].endswith("(program Line1, routine Main, line 1)")


def test_l5x_rung_diagnostic_names_the_rung(st) -> None:
    """SPEC 9.9: an RLL diagnostic names the Studio rung number (0-based)."""
    r = st.cli("check", str(L5X / "rll_project.L5X"), "--format", "json")
    s006 = next(d for d in r.json if d["code"] == "S006")
    # rll_project.L5X: the third <Rung> (Number="2") has an unclosed branch
    assert (
        "rung 2" in s006["message"]
        and "routine" in s006["message"]
        and "program" in s006["message"]
    )


# ------------------------------------------------------------------ 2.4 several files / 9.16
def test_several_files_one_program_jsr_by_name_and_unreached_routines(st) -> None:
    """SPEC 2.4 / 9.16: routine name = file stem, the first file is main, one shared scope,
    JSR by name; a routine never reached by JSR does not run."""
    main = st.write("main.st", "VAR n, m, k : DINT; END_VAR\nn := n + 1;\nJSR(Sub);\n")
    sub = st.write("Sub.rll", "ADD(m, 10, m);\n")
    never = st.write("Never.st", "k := 99;\n")
    r = st.cli(
        "run",
        str(main),
        str(sub),
        str(never),
        "--scans",
        "3",
        "--json",
        "--watch",
        "n",
        "--watch",
        "m",
        "--watch",
        "k",
    )
    assert r.code == 0, r.err
    # main runs 3 times (n = 3) and calls Sub each time (m = 3 x 10); Never is not reached
    assert r.tags == {"n": 3, "m": 30, "k": 0}


# ------------------------------------------------------------------ 3.2 ladder semantics / 9.1
def test_ladder_prescan_table(st) -> None:
    """SPEC 3.2 / 9.1: prescan: ONS sets its storage (no pulse on the first scan although the
    rung is true), TOF sets ACC = PRE, OTE clears; no plain instruction runs in prescan."""
    src = """\
VAR a : BOOL := TRUE; os : BOOL; o : BOOL := TRUE; n, pulses : DINT; t : TIMER := (PRE := 50); END_VAR
XIC(a)ONS(os)ADD(pulses, 1, pulses);
XIO(a)TOF(t,?,?);
XIO(a)OTE(o);
ADD(n, 1, n);
"""
    r = st.run(src, "pulses", "t.ACC", "t.DN", "o", "n", scans=3, name="p.rll")
    assert r.code == 0, r.err
    # ONS storage set by prescan: a stays TRUE, so no false-to-true edge is ever seen -> 0
    # TOF prescan ACC = PRE = 50, DN clear; its rung stays false, so nothing times -> 50
    # o starts TRUE but its rung is false: cleared; ADD ran only in the 3 normal scans
    assert r.tags == {"pulses": 0, "t.ACC": 50, "t.DN": False, "o": False, "n": 3}


def test_st_prescan_runs_only_non_retentive_resets(st) -> None:
    """SPEC 3.1 / 9.1: `[:=]` targets are zeroed on entering Run; plain `:=` does not run in prescan."""
    src = "VAR n : DINT := 5; k : DINT := 7; END_VAR\nn := n + 1;\nk [:=] k + 1;\n"
    # n: 5 + 2 normal scans = 7; k: zeroed by prescan, then + 1 in each of 2 scans = 2
    assert st.tags(src, "n", "k", scans=2) == {"n": 7, "k": 2}


# ------------------------------------------------------------------ 4 execution model / 9.17
def test_first_scan_flag_only_in_the_first_normal_scan(st) -> None:
    """SPEC 4 / 9.17: `S:FS` is true in the first normal scan only, readable in ST and ladder."""
    st_src = "VAR n, first, seen : DINT; END_VAR\nn := n + 1;\nIF S:FS THEN first := n; seen := seen + 1; END_IF;\n"
    assert st.tags(st_src, "first", "seen", scans=4) == {"first": 1, "seen": 1}
    r = st.run(
        "VAR seen : DINT; END_VAR\nXIC(S:FS)ADD(seen, 1, seen);\n", "seen", scans=4, name="fs.rll"
    )
    assert r.tags == {"seen": 1}


def test_math_status_flags_are_ladder_only(st) -> None:
    """SPEC 9.17: S:N S:Z S:V S:C are an error in ST, readable in ladder."""
    r = st.check("VAR b : BOOL; END_VAR\nb := S:N;\n")
    assert r.code == 1
    assert [(d["code"], d["line"], d["column"]) for d in r.json] == [("E123", 2, 6)]
    # ladder: SUB(0, 1, x) gives -1, so S:N is set after it on the same scan
    r = st.run(
        "VAR x : DINT; neg : BOOL; END_VAR\nSUB(0, 1, x);\nXIC(S:N)OTE(neg);\n", "neg", name="n.rll"
    )
    assert r.code == 0 and r.tags == {"neg": True}


def test_timers_accumulate_virtual_milliseconds(st) -> None:
    """SPEC 4: timers accumulate virtual milliseconds (scan period 10 ms, not wall time)."""
    src = "VAR t : FBD_TIMER := (PRE := 1000); END_VAR\nt.TimerEnable := TRUE;\nTONR(t);\n"
    # scans start at 0, 10, ..., 90 ms; the first scan starts timing at ACC 0 -> 90 ms at the 10th
    r = st.run(src, "t.ACC", scans=10, args=("--scan-period", "10"))
    assert r.tags == {"t.ACC": 90}


# ------------------------------------------------------------------ 3.4 / 9.5 faults
FAULTS = """VAR n, z, q : DINT; a : DINT[3]; END_VAR
n := n + 1;
q := 7 / z;
IF n > 2 THEN
  a[n] := 1;
END_IF;
"""


def test_fault_entries_keys_minor_count_and_major_stop(st) -> None:
    """SPEC 3.4 / 9.5: `faults` entries have type, code, major, message, file, line, column;
    a minor 4/4 is one entry per location with `count`; a major fault stops the run in that
    scan, the report still gives the tag values then, exit 3."""
    r = st.run(FAULTS, "n", "q", scans=10)
    assert r.code == 3
    minor, major = r.json["faults"]
    path = str(st.tmp / "main.st")
    # scans 0, 1, 2 divide by zero (n = 1, 2, 3); in scan 2 (n = 3) a[3] is out of range
    assert {k: v for k, v in minor.items() if k != "message"} == {
        "type": 4,
        "code": 4,
        "major": False,
        "file": path,
        "line": 3,
        "column": 6,
        "count": 3,
    }
    assert set(major) == {"type", "code", "major", "message", "file", "line", "column"}
    assert (major["type"], major["code"], major["major"], major["line"], major["column"]) == (
        4,
        20,
        True,
        5,
        3,
    )
    assert r.json["scans"] == 3 and r.tags == {"n": 3, "q": 7}  # integer / 0 keeps Source A
    r = st.cli("run", str(st.tmp / "main.st"), "--scans", "10")
    assert r.code == 3
    assert f"{path}:5:3: major fault type 4 code 20" in r.err


# ------------------------------------------------------------------ 6 command line
def test_watch_forms_control_bit_array_element_and_bit(st) -> None:
    """SPEC 6: `--watch` takes `ctl.PC`, `arr[2]`, `d.5`, repeatable, keyed by the expression as given."""
    src = "VAR ctl : MOTION_INSTRUCTION; arr : DINT[3]; d : DINT := 37; END_VAR\narr[2] := d + 1;\n"
    # 37 = 2#100101: bit 5 is 1; arr[2] = 38; a fresh MOTION_INSTRUCTION has PC clear
    assert st.tags(src, "ctl.PC", "arr[2]", "d.5", "d.4") == {
        "ctl.PC": False,
        "arr[2]": 38,
        "d.5": True,
        "d.4": False,
    }


def test_json_value_kinds(st) -> None:
    """SPEC 6: BOOL as true/false, integers as ints, REAL as floats, STRING as text, a structure as an object."""
    src = "VAR b : BOOL; i : INT; r : REAL; s : STRING; t : TIMER; END_VAR\nb := TRUE; i := -3; r := 2; s := 'ok'; t.PRE := 4;\n"
    r = st.run(src, "b", "i", "r", "s", "t")
    tags = json.loads(
        r.out, parse_int=lambda x: ("int", int(x)), parse_float=lambda x: ("float", float(x))
    )["tags"]
    assert tags["b"] is True
    assert tags["i"] == ("int", -3)
    assert tags["r"] == ("float", 2.0)
    assert tags["s"] == "ok"
    assert tags["t"]["PRE"] == ("int", 4) and tags["t"]["DN"] is False


def _slow_progress(monkeypatch: pytest.MonkeyPatch) -> None:
    """A terminal on stderr and a clock that makes every scan look like a wall second."""
    monkeypatch.setattr(sys.stderr, "isatty", lambda: True, raising=False)
    ticks = iter(range(10**9))
    monkeypatch.setattr(cli.time, "monotonic", lambda: float(next(ticks)))


def test_progress_bar_on_a_terminal_but_never_with_json(
    st, monkeypatch: pytest.MonkeyPatch
) -> None:
    """SPEC 6: a long run shows a progress bar on a terminal, never in --json output."""
    p = st.write("main.st", "VAR n : DINT; END_VAR\nn := n + 1;\n")
    _slow_progress(monkeypatch)
    r = st.cli("run", str(p), "--scans", "1024", "--watch", "n")
    assert r.code == 0 and "scan 1024/1024" in r.err  # the bar, on stderr
    r = st.cli("run", str(p), "--scans", "1024", "--watch", "n", "--json")
    assert r.code == 0 and r.err == "" and json.loads(r.out)["tags"] == {"n": 1024}


def test_no_progress_bar_when_not_a_terminal(tmp_path: Path) -> None:
    """SPEC 6: never a progress bar when stderr is not a TTY (the real entry point, piped)."""
    p = tmp_path / "main.st"
    p.write_text("VAR n : DINT; END_VAR\nn := n + 1;\n")
    env = dict(os.environ, PYTHONPATH=str(Path(__file__).resolve().parents[1]))
    proc = subprocess.run(
        [sys.executable, "-m", "interpreter.cli", "run", str(p), "--scans", "3000", "--watch", "n"],
        capture_output=True,
        text=True,
        env=env,
        timeout=120,
        check=False,
    )
    assert proc.returncode == 0
    assert proc.stderr == ""
    assert proc.stdout.split() == ["n", "3000"]


# ------------------------------------------------------------------ 7 / 9.7 / 9.10 check
def test_check_json_columns_are_one_based_end_exclusive(st) -> None:
    """SPEC 9.7: check json keys, 1-based, end exclusive; severity error."""
    r = st.check("VAR x : DINT; END_VAR\nx := yy + 1;\n")
    assert r.code == 1
    # `yy` occupies columns 6 and 7 of line 2: column 6, endColumn 8 (one past the last)
    assert r.json == [
        {
            "path": str(st.tmp / "main.st"),
            "line": 2,
            "column": 6,
            "endLine": 2,
            "endColumn": 8,
            "severity": "error",
            "code": "E101",
            "message": r.json[0]["message"],
        }
    ]
    assert "yy" in r.json[0]["message"]


def test_check_text_sorted_lines_then_summary(st) -> None:
    """SPEC 6 / 9.7: text format `path:line:col: error|warning CODE message`, sorted, then a summary line."""
    src = "VAR i, x : DINT; END_VAR\nx := zz;\nFOR i := 0 TO 3 DO\n  i := 1;\nEND_FOR;\nx := yy;\n"
    r = st.check(src, fmt="text")
    assert r.code == 1  # errors present
    lines = r.out.splitlines()
    path = str(st.tmp / "main.st")
    assert [ln.split(" ", 3)[:3] for ln in lines[:-1]] == [
        [f"{path}:2:6:", "error", "E101"],
        [f"{path}:4:3:", "warning", "W201"],
        [f"{path}:6:6:", "error", "E101"],
    ]
    assert lines[-1] == "2 error(s), 1 warning(s)"


def test_check_exit_0_with_warnings_only(st) -> None:
    """SPEC 6: check exits 0 when there are warnings but no errors."""
    r = st.check("VAR i : DINT; END_VAR\nFOR i := 0 TO 3 DO\n  i := i + 1;\nEND_FOR;\n", fmt="text")
    assert r.code == 0
    assert r.out.splitlines()[-1] == "0 error(s), 1 warning(s)"


def test_check_directory_is_one_program(st) -> None:
    """SPEC 9.8: a directory is one program of its .st/.rll files (shared scope, JSR by name)."""
    d = st.tmp / "prog"
    d.mkdir()
    (d / "main.st").write_text("VAR n, m : DINT; END_VAR\nn := n + 1;\nJSR(Sub);\n")
    (d / "Sub.rll").write_text("ADD(m, 10, m);\n")
    r = st.cli("check", str(d))
    assert (r.code, r.out.strip()) == (0, "0 error(s), 0 warning(s)")
    # the same files checked separately are two programs: main's JSR and Sub's tags are unknown
    r = st.cli("check", str(d / "Sub.rll"), "--format", "json")
    assert r.code == 1 and {x["code"] for x in r.json} == {"E101"}
    r = st.cli("check", str(d / "main.st"), "--format", "json")
    assert r.code == 1 and [x["code"] for x in r.json] == ["E124"]


def test_check_missing_path_exit_2(st) -> None:
    """SPEC 9.7: a missing path is exit 2."""
    r = st.cli("check", str(st.tmp / "nope.st"))
    assert r.code == 2 and r.err.startswith("logixst: error:") and "Traceback" not in r.err


SEVERITIES = """\
VAR i, x : DINT; s : STRING; ax : AXIS_VIRTUAL; mc : MOTION_INSTRUCTION; b : BOOL; END_VAR
FOR i := 0 TO 3 DO
  i := 1;
END_FOR;
CASE x OF
  i: x := 1;
END_CASE;
x := s + 1;
MSO(ax, mc);
IF b THEN MSF(ax, mc); END_IF;
RETURN;
"""


def test_severities(st) -> None:
    """SPEC 9.10: warnings are FOR index assigned, transitional reached every scan, a
    MOTION_INSTRUCTION's second and later uses; CASE label, STRING mix, RETURN are errors."""
    r = st.check(SEVERITIES)
    got = [(d["line"], d["code"], d["severity"]) for d in r.json]
    assert got == [
        (3, "W201", "warning"),  # i := 1 inside FOR i
        (6, "E114", "error"),  # CASE label `i` is not a literal
        (8, "E116", "error"),  # STRING + number
        (9, "W204", "warning"),  # MSO with no enclosing IF/CASE/loop
        (10, "W203", "warning"),  # mc's second use (MSF), not its first (MSO)
        (11, "E115", "error"),  # RETURN
    ]


def test_goto_is_an_error(st) -> None:
    """SPEC 3.1 / 9.10: GOTO is not Logix ST (error)."""
    r = st.check("VAR x : DINT; END_VAR\nGOTO done;\n")
    assert r.code == 1 and [(d["code"], d["severity"]) for d in r.json] == [("E115", "error")]


def test_missing_end_if_position_and_message(st) -> None:
    """SPEC 9.10: a missing END_IF is reported where the parser expected it (end of file here:
    just after the last `;`) and names the IF's line."""
    r = st.check("VAR x : DINT; END_VAR\nIF x > 0 THEN\n  x := 1;\nx := 2;\n")
    (d,) = r.json
    # line 4 is `x := 2;`: its `;` is column 7, so END_IF was expected at column 8
    assert (d["code"], d["line"], d["column"]) == ("S002", 4, 8)
    assert d["message"] == "missing END_IF for IF at line 2"
    # inside an enclosing block, at the token where the closer was expected
    r = st.check(
        "VAR x : DINT; END_VAR\nWHILE x > 0 DO\n  IF x > 1 THEN\n    x := 1;\nEND_WHILE;\n"
    )
    (d,) = r.json
    assert (d["code"], d["line"], d["column"]) == ("S002", 5, 1)
    assert d["message"] == "missing END_IF for IF at line 3"


def test_diagnostics_doc_has_one_section_per_code() -> None:
    """SPEC 9.10: docs/diagnostics.md has one section per code, titled with the code."""
    from interpreter.diagnostics import REGISTRY

    text = (Path(__file__).resolve().parents[1] / "docs" / "diagnostics.md").read_text()
    titles = [ln.split()[1] for ln in text.splitlines() if ln.startswith("## ")]
    assert sorted(titles) == sorted(REGISTRY)


# ------------------------------------------------------------------ 9.12 --set
def test_set_literals_radix_suffix_real_bool_and_string(st) -> None:
    """SPEC 9.12: `--set TAG=VALUE` takes an ST literal; radix literals are bit patterns of the
    tag's type (decision 0080); strings with `$` escapes set STRING tags."""
    src = "VAR u : UDINT; s : SINT; d : DINT; l : LINT; r : REAL; b, c : BOOL; txt : STRING; END_VAR\n"
    args = (
        "--set",
        "u=16#FFFF_FFFF",
        "--set",
        "s=16#FF",
        "--set",
        "d=2#1010",
        "--set",
        "l=5L",
        "--set",
        "r=1.5e3",
        "--set",
        "b=TRUE",
        "--set",
        "c=1",
        "--set",
        "txt='it$'s $41$N'",
    )
    t = st.tags(src, "u", "s", "d", "l", "r", "b", "c", "txt", scans=0, args=args)
    # 16#FFFF_FFFF in 32 unsigned bits = 4294967295; 16#FF in a SINT = -1; 2#1010 = 10
    assert t == {
        "u": 4294967295,
        "s": -1,
        "d": 10,
        "l": 5,
        "r": 1500.0,
        "b": True,
        "c": True,
        "txt": "it's A\n",
    }


def test_set_rejects_a_pattern_wider_than_the_tag(st) -> None:
    """SPEC 9.12 / decision 0007: `--set` never wraps: 16#1FF (9 bits) does not fit a SINT."""
    r = st.run("VAR s : SINT; END_VAR\n", "s", scans=0, args=("--set", "s=16#1FF"))
    assert r.code == 2 and "-128..127" in r.err


# ------------------------------------------------------------------ 9.13 arithmetic
def test_power_precedence_types_and_float32(st) -> None:
    """SPEC 9.13: `-2 ** 2` = -4; `**` is REAL when an operand is REAL, else integer;
    every REAL operation rounds to float32, LREAL keeps double."""
    src = """VAR a, p : DINT; r, third, big : REAL; lr : LREAL; END_VAR
    a := -2 ** 2;
    p := 2 ** 3;
    r := 2 ** 0.5;
    third := 1.0 / 3.0;
    big := 16777216.0;
    big := big + 1.0;
    lr := 1.0;
    lr := lr / 3.0;
    """
    t = st.tags(src, "a", "p", "r", "third", "big", "lr")
    assert t["a"] == -4 and t["p"] == 8  # -(2**2); integer power stays an integer
    # float32(sqrt 2) = 1.41421353816986083984375; float32(1/3) = 0.3333333432674407958984375
    assert t["r"] == 1.41421353816986083984375
    assert t["third"] == 0.3333333432674407958984375
    assert t["big"] == 16777216.0  # 2**24 + 1 is not a float32: rounds back to 2**24
    assert t["lr"] == 1.0 / 3.0  # double precision


# ------------------------------------------------------------------ 9.14 strings
def test_string_escapes(st) -> None:
    """SPEC 9.14: `$$ $' $L $N $R $T $P $hh`."""
    src = """VAR a, b, c, d, e : STRING; END_VAR
    a := '$$ $'';
    b := '$L$N';
    c := '$R$T$P';
    d := '$41$7e';
    e := '$l$n$r$t$p';
    """
    t = st.tags(src, "a", "b", "c", "d", "e")
    assert t == {"a": "$ '", "b": "\n\n", "c": "\r\t\f", "d": "A~", "e": "\n\n\r\t\f"}


# ------------------------------------------------------------------ 9.15 namespaces
def test_tag_and_type_namespaces_and_integer_literals_for_real(st) -> None:
    """SPEC 9.15: tag names and type names are separate namespaces; integer literals are
    accepted for REAL operands."""
    src = """VAR cam_profile : CAM_PROFILE[3]; timer : TIMER; dint : DINT; real : REAL; x : REAL; END_VAR
    dint := dint + 1;
    real := 2;
    x := ABS(-3);
    """
    r = st.run(src, "dint", "real", "x", scans=2)
    assert r.code == 0, r.err
    assert r.tags == {"dint": 2, "real": 2.0, "x": 3.0}
    r = st.run("VAR r : REAL; END_VAR\nMOV(3, r);\nDIV(r, 2, r);\n", "r", name="lit.rll")
    assert r.code == 0 and r.tags == {"r": 1.5}  # 3 / 2 in REAL


# ------------------------------------------------------------------ 9.16 --tags
def test_tags_file_gives_controller_tags_and_types_only(st) -> None:
    """SPEC 9.16: `--tags FILE.L5X` takes its controller tags and data types only (no programs run)."""
    project = L5X / "st_project.L5X"
    p = st.write("bare.st", "Speed := Speed + V1.Count;\n")
    r = st.cli("run", str(p), "--tags", str(project), "--scans", "2", "--json", "--watch", "Speed")
    # Speed starts at 7 in the export and V1.Count at 3; only bare.st runs (the project's
    # own routines would add 2 a scan): 7 + 3 + 3 = 13
    assert r.code == 0, r.err
    assert r.tags == {"Speed": 13}
    p.write_text("Result := 1.0;\n")  # a program tag of the project's MainProgram
    r = st.cli("check", str(p), "--tags", str(project), "--format", "json")
    assert r.code == 1 and [d["code"] for d in r.json] == ["E101"]


# ------------------------------------------------------------------ 9.19 ladder math
def test_lim_circular_div_real_dest_and_cpt_promoted_type(st) -> None:
    """SPEC 9.19: LIM with Low > High tests the circular range; ladder DIV with a REAL
    destination divides in REAL; CPT evaluates in the operands' promoted type."""
    src = """VAR a, b, c, d : BOOL; x : DINT := 5; y : DINT := 15; q : DINT; r : REAL; c1 : DINT; c2 : REAL; END_VAR
LIM(10, x, 0) OTE(a);
LIM(10, y, 0) OTE(b);
LIM(0, x, 10) OTE(c);
LIMIT(0, y, 10) OTE(d);
DIV(7, 2, r);
DIV(7, 2, q);
CPT(c1, 7 / 2 * 2);
CPT(c2, 7 / 2);
"""
    r = st.run(src, "a", "b", "c", "d", "r", "q", "c1", "c2", name="m.rll")
    assert r.code == 0, r.err
    # circular (Low 10 > High 0): true when x >= 10 or x <= 0: 5 no, 15 yes
    # normal 0..10: 5 yes, 15 no; 7 / 2 in REAL = 3.5; integer DIV truncates = 3
    # CPT in DINT: 7 / 2 = 3, * 2 = 6; then 3 converted to REAL = 3.0
    assert r.tags == {
        "a": False,
        "b": True,
        "c": True,
        "d": False,
        "r": 3.5,
        "q": 3,
        "c1": 6,
        "c2": 3.0,
    }
