"""Crashes the long fuzz mode found (tests/fuzz, decision 0134), each replayed through the CLI."""

from __future__ import annotations

from pathlib import Path

from tests.hardening.harness import ROOT, logixst

ALIASES = ROOT / "tests" / "l5x" / "fixtures" / "aliases.L5X"


def test_jsr_inside_an_add_on_instruction_is_a_verification_error(tmp_path: Path) -> None:
    # aliases.L5X mutant seed 877696727: a line `JSR(Rungs);` copied into the AOI's Logic
    # routine. The program has a routine Rungs, so the call checked clean, and `run` then
    # failed inside the AOI with KeyError('RUNGS'): an AOI's logic has no routines to call.
    text = ALIASES.read_text(encoding="utf-8")
    anchor = "<![CDATA[Full := Level >= 20;        // Status.0]]>\n</Line>\n"
    assert anchor in text
    mutant = tmp_path / "aoi_jsr.L5X"
    mutant.write_text(
        text.replace(anchor, anchor + '<Line Number="8">\n<![CDATA[JSR(Rungs);]]>\n</Line>\n'),
        encoding="utf-8",
    )
    line = text[: text.index(anchor)].count("\n") + 4  # the CDATA line of the JSR
    for cmd in ("check", "run"):
        r = logixst(cmd, mutant, timeout=60)
        assert r.code == 1 and "Traceback" not in r.err, r.err
        out = r.out if cmd == "check" else r.err
        assert (
            f"aoi_jsr.L5X:{line}:14: error E124 an add-on instruction cannot call a routine" in out
        )


def test_superscript_digits_in_l5k_dimensions_are_a_syntax_error(tmp_path: Path) -> None:
    # sections.L5K mutant seed 3260529364 (a byte flip): `DINT[3]` became `DINT[²]`. '²' is a
    # digit to str.isdigit() but not to int(): the reader raised ValueError. Every reader's
    # digit test is now str.isdecimal(), which accepts exactly what int() reads.
    text = (ROOT / "tests" / "l5k" / "fixtures" / "sections.L5K").read_text(encoding="utf-8")
    assert "Counts : DINT[3]" in text
    mutant = tmp_path / "sup.L5K"
    mutant.write_text(text.replace("Counts : DINT[3]", "Counts : DINT[\u00b2]"), encoding="utf-8")
    line = text[: text.index("Counts : DINT[3]")].count("\n") + 1
    r = logixst("check", mutant, timeout=60)
    assert r.code == 1 and "Traceback" not in r.err, r.err
    assert f"sup.L5K:{line}:" in r.out and "array dimensions must be whole numbers" in r.out
