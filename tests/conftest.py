"""Suite-wide pytest options and the `st` fixture that drives the real CLI (cli.main)."""

from __future__ import annotations

import json
import textwrap
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest

from interpreter.cli import main


def pytest_addoption(parser: pytest.Parser) -> None:
    parser.addoption(
        "--regen-golden",
        action="store_true",
        default=False,
        help="rewrite tests/golden/*/expected.csv from the current interpreter (review every value by hand before committing)",
    )


@dataclass
class Result:
    code: int
    out: str
    err: str

    @property
    def json(self) -> Any:
        return json.loads(self.out)

    @property
    def tags(self) -> dict[str, Any]:
        return self.json["tags"]  # type: ignore[no-any-return]


class Runner:
    def __init__(self, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
        self.tmp = tmp_path
        self.capsys = capsys

    def write(self, name: str, text: str) -> Path:
        p = self.tmp / name
        p.write_text(textwrap.dedent(text))
        return p

    def cli(self, *argv: str) -> Result:
        self.capsys.readouterr()
        code = main(list(argv))
        cap = self.capsys.readouterr()
        return Result(code, cap.out, cap.err)

    def run(
        self,
        src: str,
        *watch: str,
        scans: int = 1,
        args: tuple[str, ...] = (),
        name: str = "main.st",
    ) -> Result:
        """Run `src` for `scans` scans with `--json`, watching `watch`."""
        p = self.write(name, src)
        argv = ["run", str(p), "--scans", str(scans), "--json", *args]
        for w in watch:
            argv += ["--watch", w]
        return self.cli(*argv)

    def tags(
        self, src: str, *watch: str, scans: int = 1, args: tuple[str, ...] = ()
    ) -> dict[str, Any]:
        """Run and return the watched tag values; the run must succeed (exit 0)."""
        r = self.run(src, *watch, scans=scans, args=args)
        assert r.code == 0, (r.code, r.err, r.out)
        return r.tags

    def check(self, src: str, fmt: str = "json", name: str = "main.st") -> Result:
        p = self.write(name, src)
        return self.cli("check", str(p), "--format", fmt)


@pytest.fixture
def st(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> Runner:
    return Runner(tmp_path, capsys)
