"""SPEC 9.32: U diagnostics are warnings; `run` runs the rest and skips what is not simulated."""

from __future__ import annotations

from pathlib import Path

import pytest

from stdlib import catalog

# PFL (phase failure) is in the catalog with an `unsupported` reason: equipment phases are
# not simulated (decision 0061).
REASON = catalog().instruction("PFL", "st").unsupported  # type: ignore[union-attr]


def test_st_instruction_not_simulated_is_skipped_and_listed(st) -> None:  # type: ignore[no-untyped-def]
    # Each scan reaches PFL (skipped, f keeps its value) and counts n: 5 scans give n = 5.
    r = st.run(
        """VAR f : DINT := 7; n : DINT; END_VAR
        IF n >= 0 THEN PFL(f); END_IF;
        n := n + 1;
        """,
        "n",
        "f",
        scans=5,
    )
    assert r.code == 0
    assert r.tags == {"n": 5, "f": 7}
    [u] = r.json["unsupported"]
    assert (u["code"], u["line"]) == ("U304", 2)
    assert REASON in u["message"]
    assert [d["severity"] for d in r.json["diagnostics"]] == ["warning"]


def test_ladder_instruction_not_simulated_passes_the_rung_on(tmp_path: Path, capsys) -> None:  # type: ignore[no-untyped-def]
    import json

    from interpreter.cli import main

    prog = tmp_path / "p.rll"
    prog.write_text("VAR f : DINT; go, out : BOOL; END_VAR\nXIC(go)PFL(f)OTE(out);\n")
    capsys.readouterr()
    # go = 1: the rung is true through the skipped PFL, so OTE sets out.
    code = main(["run", str(prog), "--scans", "2", "--set", "go=1", "--json", "--watch", "out"])
    report = json.loads(capsys.readouterr().out)
    assert code == 0
    assert report["tags"] == {"out": True}
    assert [u["code"] for u in report["unsupported"]] == ["U304"]


@pytest.mark.parametrize("fmt", ["text", "json"])
def test_check_passes_with_only_u_diagnostics(tmp_path: Path, capsys, fmt: str) -> None:  # type: ignore[no-untyped-def]
    from interpreter.cli import main

    prog = tmp_path / "p.st"
    prog.write_text("VAR f : DINT; END_VAR\nIF 1 THEN PFL(f); END_IF;\n")
    assert main(["check", str(prog), "--format", fmt]) == 0
    assert "U304" in capsys.readouterr().out
