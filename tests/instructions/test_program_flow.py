"""Ladder FOR/BRK and EVENT through `logixst run` (decisions 0033, 0034)."""

from __future__ import annotations

from pathlib import Path

from tests.instructions.run_cli import trace

MAIN = "VAR i : DINT; sum : DINT; passes : DINT; END_VAR\nMOV(0,sum)MOV(0,passes);\n"
BODY = "ADD(sum,i,sum)ADD(passes,1,passes);\n"


def _for(tmp_path: Path, call: str, body: str = BODY, code: int = 0) -> dict[str, object]:
    _, report = trace(
        tmp_path,
        MAIN + call,
        ".rll",
        2,
        ["i", "sum", "passes"],
        files={"body.rll": body},
        expect_code=code,
    )
    return report


def test_for_runs_the_routine_from_initial_to_terminal(tmp_path: Path) -> None:
    # Index 1, 4, 7, 10 (13 > 10 ends the loop): sum 22 in 4 passes, every scan afresh
    r = _for(tmp_path, "FOR(body,i,1,10,3);\n")
    assert r["tags"] == {"i": 13, "sum": 22, "passes": 4}


def test_for_with_a_negative_step(tmp_path: Path) -> None:
    # 10, 6, 2 (-2 < 1 ends it): sum 18
    r = _for(tmp_path, "FOR(body,i,10,1,-4);\n")
    assert r["tags"] == {"i": -2, "sum": 18, "passes": 3}


def test_for_not_entered_and_false_rung(tmp_path: Path) -> None:
    assert _for(tmp_path, "FOR(body,i,5,4,1);\n")["tags"] == {"i": 5, "sum": 0, "passes": 0}
    r = _for(tmp_path, "XIC(passes.0)FOR(body,i,1,10,1);\n")  # passes is 0: rung false
    assert r["tags"] == {"i": 0, "sum": 0, "passes": 0}


def test_brk_ends_the_loop_before_the_index_steps(tmp_path: Path) -> None:
    # passes at 1, 4, 7; BRK at 7 leaves the routine and the loop: i stays 7
    r = _for(tmp_path, "FOR(body,i,1,10,3);\n", BODY + "GEQ(i,7)BRK();\nADD(sum,100,sum);\n")
    assert r["tags"] == {"i": 7, "sum": 1 + 100 + 4 + 100 + 7, "passes": 3}


def test_for_with_step_zero_trips_the_watchdog(tmp_path: Path) -> None:
    r = _for(tmp_path, "FOR(body,i,1,10,0);\n", code=3)
    assert [(f["type"], f["code"], f["line"]) for f in r["faults"]] == [(6, 1, 3)]  # type: ignore[index, union-attr]


# ------------------------------------------------------------------ EVENT
def _program(name: str, routine_st: str) -> str:
    lines = "".join(
        f'<Line Number="{k}"><![CDATA[{text}]]></Line>\n'
        for k, text in enumerate(routine_st.splitlines())
    )
    return (
        f'<Program Name="{name}" MainRoutineName="Main" Disabled="false">\n<Tags/>\n<Routines>\n'
        f'<Routine Name="Main" Type="ST">\n<STContent>\n{lines}</STContent>\n</Routine>\n'
        "</Routines>\n</Program>\n"
    )


def _task(name: str, kind: str, priority: int, program: str, rate: float = 10.0) -> str:
    info = '<EventInfo EventTrigger="EVENT Instruction Only" EnableTimeout="false"/>\n'
    return (
        f'<Task Name="{name}" Type="{kind}" Rate="{rate}" Priority="{priority}" Watchdog="500" '
        'DisableUpdateOutputs="false" InhibitTask="false">\n'
        + (info if kind == "EVENT" else "")
        + f'<ScheduledPrograms>\n<ScheduledProgram Name="{program}"/>\n</ScheduledPrograms>\n</Task>\n'
    )


def _project(tags: list[str], programs: str, tasks: str) -> str:
    tag_xml = "".join(
        f'<Tag Name="{t}" TagType="Base" DataType="DINT" ExternalAccess="Read/Write"/>\n'
        for t in tags
    )
    return (
        '<?xml version="1.0" encoding="UTF-8" standalone="yes"?>\n'
        '<RSLogix5000Content SchemaRevision="1.0" SoftwareRevision="35.00" TargetName="Ev" '
        'TargetType="Controller" ContainsContext="false">\n'
        '<Controller Use="Target" Name="Ev" ProcessorType="1756-L83E" MajorRev="35" MinorRev="11">\n'
        f"<Tags>\n{tag_xml}</Tags>\n<Programs>\n{programs}</Programs>\n<Tasks>\n{tasks}</Tasks>\n"
        "</Controller>\n</RSLogix5000Content>\n"
    )


def test_event_task_preempts_the_continuous_task(tmp_path: Path) -> None:
    main = "n := n + 1;\nIF n = 2 OR n = 3 THEN EVENT(EvTask); END_IF;\nseen := ev_runs;"
    src = _project(
        ["n", "ev_runs", "seen"],
        _program("MainProgram", main) + _program("EvProgram", "ev_runs := ev_runs + 1;"),
        _task("MainTask", "CONTINUOUS", 10, "MainProgram")
        + _task("EvTask", "EVENT", 5, "EvProgram"),
    )
    rows, report = trace(tmp_path, src, ".L5X", 4, ["ev_runs", "seen"])
    # scans 2 and 3 trigger; the event task runs inside EVENT, so `seen` already counts it
    assert [(r["ev_runs"], r["seen"]) for r in rows] == [
        ("0", "0"),
        ("1", "1"),
        ("2", "2"),
        ("2", "2"),
    ]
    assert report["diagnostics"] == []


def test_lower_priority_event_waits_and_overlaps_are_dropped(tmp_path: Path) -> None:
    fast = "EVENT(SlowEv);\nEVENT(SlowEv);\nfast_seen := slow_runs;"
    src = _project(
        ["slow_runs", "fast_seen"],
        _program("FastProgram", fast) + _program("SlowProgram", "slow_runs := slow_runs + 1;"),
        _task("Fast", "PERIODIC", 3, "FastProgram", rate=10.0)
        + _task("SlowEv", "EVENT", 8, "SlowProgram"),
    )
    rows, _ = trace(tmp_path, src, ".L5X", 3, ["slow_runs", "fast_seen"], period_ms=10.0)
    # priority 8 < 3: queued until Fast has finished; the second EVENT is an overlap. So
    # each Fast run sees the count before its own trigger runs, and one run per Fast run
    assert [(r["slow_runs"], r["fast_seen"]) for r in rows] == [("1", "0"), ("2", "1"), ("3", "2")]


def test_event_naming_no_task_is_e124(tmp_path: Path) -> None:
    from interpreter.cli import main

    src = _project(
        ["n"],
        _program("MainProgram", "EVENT(Nowhere);"),
        _task("MainTask", "CONTINUOUS", 10, "MainProgram"),
    )
    path = tmp_path / "p.L5X"
    path.write_text(src)
    assert main(["check", str(path)]) == 1
