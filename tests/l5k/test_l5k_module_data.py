"""Module connection data of an .L5K export: the I/O tags whose layout the MODULE block shows
in its ExtendedProp, with the block's InputData/OutputData as their values (decision 0070)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from interpreter.cli import main
from interpreter.runtime.loader import load
from interpreter.syntax.l5k import read_l5k

MODULE_DATA = Path(__file__).parent / "fixtures" / "module_data.L5K"


def test_layouts_from_extended_properties_declare_the_io_tags() -> None:
    p, diags = read_l5k(MODULE_DATA.read_bytes(), str(MODULE_DATA))
    assert diags == [] and p is not None
    types = {t.name: [(m.names[0][0], m.type.name) for m in t.members] for t in p.types}
    # BIT members are BOOL members, as the Decorated data of an L5X shows them; the hidden
    # pad DINT is not a member
    assert types == {
        "AB:Example_Drive:I:0": [
            ("Status", "INT"),
            ("Ready", "BOOL"),
            ("Active", "BOOL"),
            ("Faulted", "BOOL"),
            ("Speed", "INT"),
        ],
        "AB:Example_Drive:O:0": [
            ("Command", "INT"),
            ("Stop", "BOOL"),
            ("Run", "BOOL"),
            ("SpeedRef", "INT"),
        ],
    }
    # Pump is reached over Ethernet: named by itself. Inputs (Local slot 2) shows no layout
    # in its block: its place is known, its tag is not declared (the checker names it once)
    assert [d.names[0][0] for d in p.tags if ":" in d.names[0][0]] == ["Pump:I", "Pump:O"]
    assert p.modules == {
        "LOCAL": "Local",
        "LOCAL:1": "Enet",
        "PUMP": "Pump",
        "LOCAL:2": "Inputs",
    }


def test_connection_data_are_the_initial_values(capsys: pytest.CaptureFixture[str]) -> None:
    assert [d.text() for d in load([MODULE_DATA]).diagnostics] == []
    argv = ["run", str(MODULE_DATA), "--scans", "3", "--json"]
    for w in ("Pump:I", "Pump:O", "Speed", "Ready", "Active", "Faulted"):
        argv += ["--watch", w]
    capsys.readouterr()
    assert main(argv) == 0
    tags = json.loads(capsys.readouterr().out)["tags"]
    # InputData [0, 5, 1200]: pad 0 (hidden), Status 5 = 2#101 -> Ready (bit 0) and Faulted
    # (bit 2) set, Active (bit 1) clear; Speed 1200. The strings in the block that look like
    # `InputData := [...]` (a description, a member comment) are not data.
    assert tags["Pump:I"] == {
        "Status": 5,
        "Ready": True,
        "Active": False,
        "Faulted": True,
        "Speed": 1200,
    }
    assert (tags["Speed"], tags["Ready"], tags["Active"], tags["Faulted"]) == (1200, 1, 0, 1)
    # OutputData [2, 600]: Command 2 = 2#10 -> Run (bit 1) set, Stop (bit 0) clear; SpeedRef
    # 600 + 10 per scan = 630 after 3 scans; Stop := Run copies the set bit
    out = tags["Pump:O"]
    assert (out["Run"], out["SpeedRef"], out["Stop"]) == (True, 630, True)


@pytest.mark.parametrize(
    ("old", "new"),
    [
        # escaped XML that is not well-formed, a bit number that is not a number, a member
        # without a type: the layout cannot be read, so no type and no I/O tag (no traceback)
        ("&lt;/Members&gt;&lt;/DataType&gt;</InputDataTag>", "&lt;/Members&gt;</InputDataTag>"),
        ("BitNumber=$Q2$Q", "BitNumber=$Qtwo$Q"),
        ("Name=$QSpeed$Q DataType=$QINT$Q", "Name=$QSpeed$Q"),
    ],
)
def test_unreadable_layouts_declare_nothing(tmp_path: Path, old: str, new: str) -> None:
    text = MODULE_DATA.read_text()
    assert text.count(old) == 1
    path = tmp_path / "bad_layout.L5K"
    path.write_text(text.replace(old, new))
    p, diags = read_l5k(path.read_bytes(), str(path))
    assert diags == [] and p is not None
    assert [t.name for t in p.types] == ["AB:Example_Drive:O:0"]
    assert [d.names[0][0] for d in p.tags if ":" in d.names[0][0]] == ["Pump:O"]


def test_connection_data_that_does_not_parse_is_one_diagnostic(tmp_path: Path) -> None:
    # `InputData (...)` not followed by `:=`: one S008 where the value stands (line 40, after
    # the attribute list's `)`), the rest of the file read
    text = MODULE_DATA.read_text().replace(":= [0,5,1200];", "[0,5,1200];")
    path = tmp_path / "bad_data.L5K"
    path.write_text(text)
    p, diags = read_l5k(path.read_bytes(), str(path))
    assert p is not None
    assert [(d.code, d.span.line, d.message) for d in diags] == [
        ("S008", 40, "expected ':=' after InputData, found '[0,5,1200];'")
    ]
    assert [prog.name for prog in p.programs] == ["MainProgram"]
