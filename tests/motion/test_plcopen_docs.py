"""docs/plcopen.md lists the ErrorIDs of the PLCopen blocks as the catalog states them."""

from __future__ import annotations

import re
from pathlib import Path

from stdlib import catalog

DOC = Path(__file__).resolve().parents[2] / "docs" / "plcopen.md"


def test_error_id_table_equals_the_catalog():
    rows = re.findall(r"^\| (\d+) \| (.+) \|$", DOC.read_text(), re.M)
    documented = {int(n): text for n, text in rows}
    stated = {v.value: v.doc for v in catalog().enum("MC_ErrorID").values}
    assert documented == stated
