"""A real editor: headless Neovim attaches `logixst lsp` with the README's Lua snippet."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
from pathlib import Path

import pytest
from lsp_client import logixst_shim

ROOT = Path(__file__).resolve().parents[2]
SNIPPET = ROOT / "editors" / "nvim" / "logixst.lua"
PROBE = Path(__file__).with_name("nvim_probe.lua")
NVIM = shutil.which("nvim")

pytestmark = pytest.mark.skipif(
    NVIM is None, reason="Neovim is not installed (.ci/run installs the Debian package neovim)"
)


def test_readme_shows_the_tested_snippet() -> None:
    assert SNIPPET.read_text().strip() in (ROOT / "README.md").read_text()


def test_neovim_receives_diagnostics_and_enumeration_completion(tmp_path: Path) -> None:
    prog = tmp_path / "cam.st"
    text = (
        "VAR ax : AXIS_VIRTUAL; c : MOTION_INSTRUCTION; p : CAM_PROFILE[3]; END_VAR\n"
        "MATC(ax, c, 0, p, 1.0, 1.0, Once, Immediate, 0.0, 0, TimeDrivenMode);\n"
        "x := 1;\n"
    )
    prog.write_text(text)
    out = tmp_path / "probe.json"
    env = dict(
        os.environ,
        LOGIXST_PROBE_FILE=str(prog),
        LOGIXST_PROBE_OUT=str(out),
        LOGIXST_PROBE_LINE="1",
        LOGIXST_PROBE_CHAR=str(len("MATC(ax, c, 0, p, 1.0, 1.0, ")),
        PATH=f"{logixst_shim(tmp_path / 'bin')}{os.pathsep}{os.environ.get('PATH', '')}",
    )
    subprocess.run(
        [
            NVIM,
            "--headless",
            "-u",
            "NONE",
            "-n",
            "-c",
            f"luafile {SNIPPET}",
            "-c",
            f"luafile {PROBE}",
        ],  # type: ignore[list-item]
        cwd=tmp_path,
        env=env,
        timeout=120,
        check=False,
        capture_output=True,
    )
    report = json.loads(out.read_text())
    codes = sorted({d["code"] for d in report["diagnostics"]})
    assert "E101" in codes  # `x` is undefined
    e101 = next(d for d in report["diagnostics"] if d["code"] == "E101")
    assert (e101["line"], e101["col"]) == (2, 0)
    labels = [c["label"] for c in report["completion"]]
    assert labels[:2] == ["once", "continuous"] or {"once", "continuous"} <= set(labels)
    once = next(c for c in report["completion"] if c["label"] == "once")
    assert once["detail"].startswith("0")
