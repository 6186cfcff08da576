"""A real editor: Emacs (batch mode) with eglot attaches `logixst lsp` with the README's
Emacs snippet and receives the diagnostics and the enumeration completion."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
from pathlib import Path

import pytest
from lsp_client import ROOT, logixst_shim

SNIPPET = ROOT / "editors" / "emacs" / "logixst.el"
PROBE = Path(__file__).with_name("eglot_probe.el")
EMACS = shutil.which("emacs")


def _has_eglot() -> bool:
    if EMACS is None:
        return False
    probe = '(progn (let ((default-directory "/usr/share/emacs/site-lisp/elpa/")) (when (file-directory-p default-directory) (normal-top-level-add-subdirs-to-load-path))) (kill-emacs (if (require \'eglot nil t) 0 1)))'
    done = subprocess.run(
        [EMACS, "--batch", "-Q", "--eval", probe], capture_output=True, timeout=60
    )
    return done.returncode == 0


pytestmark = pytest.mark.skipif(
    not _has_eglot(),
    reason="Emacs with eglot is not installed (.ci/run installs the Debian packages emacs-nox and elpa-eglot)",
)


def test_readme_shows_the_tested_snippet() -> None:
    assert SNIPPET.read_text().strip() in (ROOT / "README.md").read_text()


def test_eglot_receives_diagnostics_and_enumeration_completion(tmp_path: Path) -> None:
    work = tmp_path / "project"  # alone in its directory: no sibling routines
    work.mkdir()
    prog = work / "cam.st"
    prog.write_text(
        "VAR ax : AXIS_VIRTUAL; c : MOTION_INSTRUCTION; p : CAM_PROFILE[3]; END_VAR\n"
        "MATC(ax, c, 0, p, 1.0, 1.0, Once, Immediate, 0.0, 0, TimeDrivenMode);\n"
        "x := 1;\n"
    )
    out = tmp_path / "probe.json"
    env = dict(
        os.environ,
        LOGIXST_SNIPPET=str(SNIPPET),
        LOGIXST_PROBE_FILE=str(prog),
        LOGIXST_PROBE_OUT=str(out),
        LOGIXST_PROBE_LINE="1",
        LOGIXST_PROBE_CHAR=str(len("MATC(ax, c, 0, p, 1.0, 1.0, ")),
        PATH=f"{logixst_shim(tmp_path / 'bin')}{os.pathsep}{os.environ.get('PATH', '')}",
    )
    subprocess.run(
        [EMACS, "--batch", "-Q", "-l", str(PROBE)],  # type: ignore[list-item]
        cwd=work,
        env=env,
        timeout=120,
        check=False,
        capture_output=True,
    )
    report = json.loads(out.read_text())
    # check says of this file: W204 on line 2 (MATC reached every scan), E101 on line 3 (`x`)
    assert sorted((d["code"], d["line"]) for d in report["diagnostics"]) == [
        ("E101", 3),
        ("W204", 2),
    ]
    assert [c["label"] for c in report["completion"]] == ["once", "continuous"]
    assert report["completion"][0]["detail"].startswith("0")
