"""Language server on IEC function-block calls (SPEC 3.1): parameter names inside
`camIn(`, an input's values after `Name :=`, output members after `camIn.`, hover and
signature help. The expected names come from SPEC 9.29."""

from __future__ import annotations

from pathlib import Path

from lsp.features.completion import complete
from lsp.features.hover import hover
from lsp.features.signature import signature
from lsp.workspace import Workspace

HEAD = """VAR
  M, S : AXIS_VIRTUAL;
  table : CAM[4];
  sel : MC_CamTableSelect;
  camIn : MC_CamIn;
  go : BOOL;
  n : DINT;
END_VAR
"""

CAMIN_INPUTS = [
    "Master", "Slave", "Execute", "MasterOffset", "SlaveOffset", "MasterScaling",
    "SlaveScaling", "StartMode", "VelocityDiff", "Acceleration", "Deceleration", "CamTableID",
]  # fmt: skip
CAMIN_OUTPUTS = ["InSync", "Busy", "CommandAborted", "Error", "ErrorID", "EndOfProfile"]


def analysed(tmp_path: Path, body: str):  # type: ignore[no-untyped-def]
    """The document HEAD + body analysed; the `|` marks the cursor (line, character)."""
    text = HEAD + body
    at = text.index("|")
    text = text.replace("|", "")
    line = text.count("\n", 0, at)
    col = at - (text.rfind("\n", 0, at) + 1)
    ws = Workspace()
    uri = (tmp_path / "a.st").as_uri()
    ws.open(uri, text)
    an = ws.analyse(uri)
    assert an is not None
    return an, line, col


def test_parameter_names_inside_the_call(tmp_path: Path) -> None:
    an, line, col = analysed(tmp_path, "camIn(Master := M, |\n")
    items = complete(an, line, col)
    assert [i.label for i in items] == CAMIN_INPUTS
    master = items[0]
    assert master.insert_text == "Master := " and "required" in master.detail
    assert not any(i.label in CAMIN_OUTPUTS for i in items)


def test_values_of_an_input(tmp_path: Path) -> None:
    an, line, col = analysed(tmp_path, "camIn(StartMode := |\n")
    labels = [i.label for i in complete(an, line, col)]
    assert labels == ["absolute", "relative", "ramp_in", "ramp_in_pos", "ramp_in_neg"]
    an, line, col = analysed(tmp_path, "camIn(Slave := |\n")
    assert sorted(i.label for i in complete(an, line, col)) == ["M", "S"]  # axes only
    an, line, col = analysed(tmp_path, "sel(CamTable := |\n")
    assert [i.label for i in complete(an, line, col)] == ["table"]  # the CAM array


def test_output_members_after_the_dot(tmp_path: Path) -> None:
    an, line, col = analysed(tmp_path, "go := camIn.|\n")
    labels = [i.label for i in complete(an, line, col)]
    assert all(o in labels for o in CAMIN_OUTPUTS)


def test_signature_help_follows_the_named_parameter(tmp_path: Path) -> None:
    an, line, col = analysed(tmp_path, "camIn(Master := M, VelocityDiff := |\n")
    sig = signature(an, line, col)
    assert sig is not None
    assert sig.label.startswith("camIn(Master := , Slave := , Execute := ")
    assert [p[0] for p in sig.parameters] == [f"{n} := " for n in CAMIN_INPUTS]
    assert sig.active == CAMIN_INPUTS.index("VelocityDiff")


def test_hover_on_block_parameter_and_value(tmp_path: Path) -> None:
    an, line, col = analysed(tmp_path, "camIn(Master := M, StartMode := ramp_in);\n|")
    md = hover(an, line - 1, 1)  # on `camIn`
    assert md is not None and "MC_CAMIN" in md and "| CamTableID | DINT | input" in md
    assert "| InSync | BOOL | output" in md
    md = hover(an, line - 1, len("camIn(Master := M, Sta"))
    assert md is not None and md.startswith("**MC_CAMIN.StartMode**") and "2 ramp_in" in md
    md = hover(an, line - 1, len("camIn(Master := M, StartMode := ram"))
    assert md is not None and md.startswith("**ramp_in** = 2")
