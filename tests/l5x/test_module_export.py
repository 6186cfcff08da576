"""A module export without context: the target <Module> straight under the root
(docs/decisions/0070-module-exports-and-l5k-module-data.md)."""

from __future__ import annotations

from pathlib import Path

import pytest
from test_project import run  # the run-and-read-tags helper (tests/l5x is on sys.path)

from interpreter.syntax.l5x import read_l5x

MODULE = Path(__file__).parent / "fixtures" / "module_export.L5X"


def test_module_export_is_read_as_its_module() -> None:
    project, diags = read_l5x(MODULE.read_bytes(), str(MODULE))
    assert diags == [] and project is not None
    assert project.target_type == "Module"
    # an Ethernet adapter is named by itself: <Module>:I and <Module>:O (decision 0052); the
    # ConfigTag has L5K data only, so no layout and no tag
    assert [d.names[0][0] for d in project.tags] == ["Scale_Adapter:I", "Scale_Adapter:O"]
    assert project.modules == {"SCALE_ADAPTER": "Scale_Adapter"}
    assert project.programs == [] and project.tasks == []


def test_module_export_runs_nothing_and_keeps_its_data(
    capsys: pytest.CaptureFixture[str],
) -> None:
    # no task: the scans execute nothing, the connection data stays what the file holds
    tags = run(capsys, MODULE, 100, "Scale_Adapter:I", "Scale_Adapter:O")
    assert tags == {"Scale_Adapter:I": {"Data": [12, -3]}, "Scale_Adapter:O": {"Data": [7]}}


@pytest.mark.parametrize(
    "root",
    [
        # a module target without its <Module>, and a program target without <Controller>:
        # neither is something Studio writes
        '<RSLogix5000Content SchemaRevision="1.0" TargetType="Module"/>',
        '<RSLogix5000Content SchemaRevision="1.0" TargetType="Program"><Module Name="M"/>'
        "</RSLogix5000Content>",
    ],
)
def test_other_roots_without_controller_are_refused(tmp_path: Path, root: str) -> None:
    path = tmp_path / "x.L5X"
    path.write_text('<?xml version="1.0" encoding="UTF-8"?>\n' + root + "\n")
    project, diags = read_l5x(path.read_bytes(), str(path))
    assert project is None
    assert [(d.code, d.message) for d in diags] == [
        ("S007", "the export has no <Controller> element")
    ]
