"""Predefined MESSAGE, PID, ALARM_DIGITAL and ALARM_ANALOG tags (docs/decisions/0053-process-types.md)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from interpreter.cli import main
from interpreter.runtime.loader import load
from interpreter.semantics.types import ArrayType, StructType, TypeTable

FIX = Path(__file__).parent / "fixtures"
PROCESS = FIX / "process_types.L5X"


def test_types_have_the_documented_members() -> None:
    types = TypeTable()
    msg, pid, almd, alma = (
        types.get(n) for n in ("MESSAGE", "PID", "ALARM_DIGITAL", "ALARM_ANALOG")
    )
    assert isinstance(msg, StructType) and isinstance(pid, StructType)
    assert isinstance(almd, StructType) and isinstance(alma, StructType)
    # 1756-RM003: FLAGS, ERR, EXERR, REQ_LEN, DN_LEN, then the status bits EW ER DN ST EN TO EN_CC
    assert [m for m, _ in msg.members[:12]] == [
        "FLAGS",
        "ERR",
        "EXERR",
        "REQ_LEN",
        "DN_LEN",
        "EW",
        "ER",
        "DN",
        "ST",
        "EN",
        "TO",
        "EN_CC",
    ]
    assert str(msg.member("Path")[1]) == "STRING" and str(msg.member("Instance")[1]) == "DINT"  # type: ignore[index]
    # PID: CTL word, 21 bits, 28 REALs from SP to MAXTIE, then DATA REAL[17] (plus logixst's
    # hidden working storage, which no program can name)
    visible = [m for m, _ in pid.members if m.upper() not in pid.hidden]
    assert len(visible) == 1 + 21 + 28 + 1
    data = pid.member("DATA")[1]  # type: ignore[index]
    assert isinstance(data, ArrayType) and data.dims == (17,) and str(data.elem) == "REAL"
    assert str(almd.member("ProgTime")[1]) == "LINT" and str(alma.member("In")[1]) == "REAL"  # type: ignore[index]
    assert almd.defaults["SEVERITY"] == 500 and almd.defaults["CONDITION"] is True


def test_process_tags_check_clean_and_read_their_exported_parameters(
    capsys: pytest.CaptureFixture[str],
) -> None:
    capsys.readouterr()
    assert main(["check", str(PROCESS)]) == 0
    assert capsys.readouterr().out.strip() == "0 error(s), 0 warning(s)"
    argv = ["run", str(PROCESS), "--scans", "2", "--json"]
    for w in (
        "Sev",
        "Span",
        "Loop.SP",
        "Done",
        "Alm.Condition",
        "Alm.Latched",
        "Alm.EnableIn",
        "Ana.In",
        "Ana.LSeverity",
    ):
        argv += ["--watch", w]
    assert main(argv) == 0
    tags = json.loads(capsys.readouterr().out)["tags"]
    assert tags == {
        "Sev": 1650,  # Alm.Severity 750 + Ana.HHSeverity 900, from the Alarm parameters
        "Span": 95.0,  # HHLimit 90.0 - LLLimit -5.0
        "Loop.SP": 55.0,  # decorated SP 50.0 + KP 2.5, twice
        "Done": 2,  # DN and ER stay clear: nothing executes MSG
        "Alm.Condition": False,
        "Alm.Latched": True,
        "Alm.EnableIn": False,  # exported, not the defaults
        "Ana.In": 12.5,
        "Ana.LSeverity": 500,  # not exported: the documented default
    }


def test_defaults_and_unknown_members_in_st(tmp_path: Path) -> None:
    src = tmp_path / "p.st"
    src.write_text(
        "VAR d : ALARM_DIGITAL; a : ALARM_ANALOG; m : MESSAGE; p : PID; s : DINT; b : BOOL; END_VAR\n"
        "s := d.Severity + a.ROCNegSeverity;\nb := d.AckRequired AND m.EN_CC = 0;\np.Nope := 1.0;\n"
    )
    assert [d.code for d in load([src]).diagnostics] == ["E102"]


def test_the_instructions_are_in_the_catalog(tmp_path: Path) -> None:
    # decision 0031-0035: MSG, PID, ALMD and ALMA are catalog instructions now; 0 for the
    # unused PID operands and immediate 0/1 for BOOL operands are accepted as in Logix
    src = tmp_path / "p.rll"
    src.write_text(
        "VAR m : MESSAGE; p : PID; d : ALARM_DIGITAL; x : REAL; y : REAL; END_VAR\n"
        "MSG(m);\nALMD(d,0,0,0,0);\nPID(p,x,0,y,0,0,0);\n"
    )
    assert [d.code for d in load([src]).diagnostics] == []
