"""docs/limits.md lists every limit of interpreter/limits.py with its value (issue 14)."""

from __future__ import annotations

from pathlib import Path

from interpreter import limits

DOC = Path(__file__).resolve().parents[2] / "docs" / "limits.md"


def shown(name: str, value: float) -> str:
    """The value as the table writes it: 1 MB, 10,000,000, 0.1, 2,000,000."""
    if name.endswith("_BYTES"):
        return limits.mb(int(value))
    number = int(value) if value == int(value) else value
    return f"{number:,}"


def test_every_limit_is_in_the_table_with_its_value() -> None:
    rows = [line for line in DOC.read_text(encoding="utf-8").splitlines() if line.startswith("| `")]
    names = [n for n in dir(limits) if n.startswith(("MAX_", "MIN_"))]
    assert names, "interpreter/limits.py defines no limits"
    for name in names:
        row = next((r for r in rows if f"`{name}`" in r), None)
        assert row is not None, f"{name} is not in docs/limits.md"
        value = getattr(limits, name)
        assert shown(name, value) in row, (name, value, row)
