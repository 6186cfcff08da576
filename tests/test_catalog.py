"""The catalog is the single source of truth: every entry documented, every entry executable.

An instruction the simulator does not execute says why in its catalog entry (`unsupported`);
the checker reports U304 with that reason instead of running it. Every other entry has an
implementation in each of its languages (or is lowered by the compiler).
"""

from __future__ import annotations

import pytest

from interpreter.instructions.registry import lookup
from interpreter.semantics.types import TypeTable
from stdlib import catalog


def _pending(ins) -> bool:  # type: ignore[no-untyped-def]
    return bool(ins.unsupported)


def test_every_instruction_has_docs() -> None:
    for ins in catalog().instructions:
        assert len(ins.doc) > 40, f"{ins.key}: doc paragraph missing"
        for op in ins.operands:
            assert op.doc, f"{ins.key}.{op.name}: operand doc missing"


def test_every_type_and_enum_is_documented() -> None:
    cat = catalog()
    for td in cat.types.values():
        assert td.doc, f"type {td.name}: doc missing"
    for en in cat.enums.values():
        assert en.values, f"enum {en.name} has no values"


# Lowered by the compilers to inline bytecode rather than dispatched to an implementation
# (ladder contacts, coils, compares, moves, expressions, file loops and program control).
INTRINSICS = {
    "XIC",
    "XIO",
    "OTE",
    "OTL",
    "OTU",
    "EQU",
    "NEQ",
    "GRT",
    "GEQ",
    "LES",
    "LEQ",
    "MOV",
    "JMP",
    "LBL",
    "MCR",
    "AFI",
    "NOP",
    "TND",
    "JSR",
    "SBR",
    "RET",
    "CPT",
    "CMP",
    "FAL",
    "FSC",
    "FOR",
    "BRK",
}


def test_intrinsics_are_the_compiler_lowered_set_and_have_no_implementation() -> None:
    from interpreter.instructions.registry import LOWERED

    assert INTRINSICS == LOWERED
    for name in INTRINSICS:
        ins = catalog().instruction(name, "rll")
        assert ins is not None, name
        assert lookup(name, "rll") is None, f"{name} is lowered: an implementation would never run"


@pytest.mark.parametrize(
    "ins",
    [i for i in catalog().instructions if not _pending(i) and i.name not in INTRINSICS],
    ids=lambda i: i.key,
)
def test_instruction_is_implemented(ins) -> None:  # type: ignore[no-untyped-def]
    for lang in sorted(ins.languages):
        assert lookup(ins.name, lang) is not None, f"{ins.key} has no implementation for {lang}"


@pytest.mark.parametrize(
    "ins", [i for i in catalog().instructions if _pending(i)], ids=lambda i: i.key
)
def test_unsupported_instruction_has_no_implementation(ins) -> None:  # type: ignore[no-untyped-def]
    """A reason for not simulating it goes when the implementation comes."""
    assert len(ins.unsupported) > 20, ins.key
    for lang in sorted(ins.languages):
        assert lookup(ins.name, lang) is None, f"{ins.key} runs: drop its 'unsupported' reason"


def test_pending_instruction_is_reported_not_run(tmp_path) -> None:  # type: ignore[no-untyped-def]
    from interpreter.runtime.loader import load

    src = tmp_path / "p.st"
    src.write_text("VAR f : DINT; END_VAR\nIF 1 THEN PFL(f); END_IF;\n")
    diags = load([src]).diagnostics
    assert [d.code for d in diags] == ["U304"]  # equipment phases are not simulated
    assert catalog().instruction("PFL", "st").unsupported in diags[0].message
    src.write_text(
        "VAR ax : AXIS_VIRTUAL; c : MOTION_INSTRUCTION; END_VAR\nIF 1 THEN MSO(ax, c); END_IF;\n"
    )
    assert [d.code for d in load([src]).diagnostics] == []  # MSO runs since issue 4


def test_catalog_types_build() -> None:
    types = TypeTable()
    for name in catalog().types:
        assert types.get(name) is not None, name


def test_enum_text_matching_ignores_spaces_hyphens_case() -> None:
    cat = catalog()
    profile = next(e for e in cat.enums.values() if e.lookup("S-Curve") is not None)
    # 'S-Curve', 'scurve' and 'S Curve' are one enumeration word (SPEC 2.2, 3.1)
    assert profile.lookup("scurve") is profile.lookup("S Curve") is profile.lookup("S-CURVE")


def test_implementation_index_is_what_the_modules_register() -> None:
    """`check` answers U304 from implemented.py (registry.has_implementation) without importing
    the implementation modules; after adding an implementation, run registry.write_index()."""
    from interpreter.instructions import registry
    from interpreter.instructions.implemented import IMPLEMENTED

    registry.load_all()
    assert IMPLEMENTED == frozenset(registry.IMPLEMENTATIONS), (
        "implemented.py is stale: run registry.write_index()"
    )
    for ins in catalog().instructions:
        for lang in sorted(ins.languages):
            assert registry.has_implementation(ins.name, lang) == (
                lookup(ins.name, lang) is not None
            ), (ins.key, lang)


def test_check_imports_no_implementation_module(tmp_path) -> None:  # type: ignore[no-untyped-def]
    """`check` only verifies: the implementation modules (and numpy behind motion) are for `run`."""
    import subprocess
    import sys
    from pathlib import Path

    root = Path(__file__).resolve().parents[1]
    # a timer and a motion instruction (GSV/SSV would read ladder_system's attribute table: U303)
    src = tmp_path / "p.rll"
    src.write_text(
        "VAR t : TIMER; ax : AXIS_VIRTUAL; mc : MOTION_INSTRUCTION; END_VAR\nTON(t,100,0);\nXIC(t.DN)MSO(ax,mc);\n"
    )
    probe = (
        "import sys\nfrom interpreter.cli import main\ncode = main(['check', sys.argv[1]])\n"
        "print(code, sorted(m for m in sys.modules if m.startswith('interpreter.instructions.') or m in ('numpy', 'interpreter.motion')))\n"
    )
    done = subprocess.run(
        [sys.executable, "-c", probe, str(src)],
        capture_output=True,
        text=True,
        cwd=root,
        check=False,
    )
    assert (
        done.stdout.splitlines()[-1]
        == "0 ['interpreter.instructions.implemented', 'interpreter.instructions.registry']"
    ), done.stdout + done.stderr


def test_instruction_rules_named_by_the_catalog_exist_and_are_used() -> None:
    """An instruction's special rule is named by its catalog entry (`check`), never found by
    an `if name == ...` in the checker: each name is a rule, and each rule is named."""
    from interpreter.semantics.checker import INSTRUCTION_CHECKS

    named = {ins.check for ins in catalog().instructions if ins.check}
    assert named == set(INSTRUCTION_CHECKS)


def test_function_results_are_catalog_data() -> None:
    # Trigonometry, logarithms and DEG/RAD return REAL for any numeric argument (1756-RM003);
    # IsINF/IsNAN return BOOL; ABS and TRUNC keep the argument's type (no `result`).
    results = {i.name: i.result for i in catalog().instructions if i.kind == "function"}
    assert results["SIN"] == results["LN"] == results["RAD"] == results["ATAN2"] == "REAL"
    assert results["ISINF"] == results["ISNAN"] == "BOOL"
    assert results["ABS"] == results["TRUNC"] == ""
