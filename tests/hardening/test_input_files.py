"""Issue 14, inputs that are not regular files and the size limits, through the real entry point.

Bounds: each case is refused from the file's `stat`, before reading (a FIFO would block the
open, /dev/zero would be read until memory runs out), so it ends within 20 s under the 2 GB
address-space limit of harness.logixst.
"""

from __future__ import annotations

import os
import socket
from pathlib import Path

import pytest

from interpreter.limits import MAX_PROJECT_BYTES, MAX_SOURCE_BYTES
from tests.hardening.harness import logixst


@pytest.mark.parametrize("command", ["run", "check"])
@pytest.mark.parametrize(("device", "name"), [("/dev/zero", "z.st"), ("/dev/urandom", "u.L5X")])
def test_device_behind_a_symlink(tmp_path: Path, command: str, device: str, name: str) -> None:
    link = tmp_path / name
    link.symlink_to(device)
    r = logixst(command, link, timeout=20)
    assert r.code == 2
    r.one_line_error(f"{link}: is a device, not a regular file")


def test_device_as_tags_export(tmp_path: Path) -> None:
    prog = tmp_path / "p.st"
    prog.write_text("x := 1;\n")
    link = tmp_path / "tags.L5X"
    link.symlink_to("/dev/zero")
    r = logixst("check", prog, "--tags", link, timeout=20)
    assert r.code == 2
    r.one_line_error("tags.L5X: is a device, not a regular file")


@pytest.mark.parametrize("command", ["run", "check"])
def test_fifo(tmp_path: Path, command: str) -> None:
    fifo = tmp_path / "f.st"
    os.mkfifo(fifo)
    r = logixst(command, fifo, timeout=20)  # nobody writes: reading it would block forever
    assert r.code == 2
    r.one_line_error(f"{fifo}: is a FIFO, not a regular file")


def test_socket(tmp_path: Path) -> None:
    path = tmp_path / "s.st"
    sock = socket.socket(socket.AF_UNIX)
    try:
        sock.bind(str(path))
        r = logixst("check", path, timeout=20)
    finally:
        sock.close()
    assert r.code == 2
    r.one_line_error(f"{path}: is a socket, not a regular file")


def test_source_file_size_limit(tmp_path: Path) -> None:
    # 5 MB of comment, beyond the 1 MB limit of a .st file; the message states the limit
    big = tmp_path / "big.st"
    big.write_bytes(b"// padding\n" * (5 * 1024 * 1024 // 11))
    assert big.stat().st_size > MAX_SOURCE_BYTES
    r = logixst("run", big, timeout=20)
    assert r.code == 2
    r.one_line_error(f"{big}: file is too large", "the limit is 1 MB")


def test_project_size_limit_states_the_limit(tmp_path: Path) -> None:
    big = tmp_path / "big.L5X"
    with big.open("wb") as fh:  # a sparse file: 64 MB + 1 byte without writing them
        fh.truncate(MAX_PROJECT_BYTES + 1)
    r = logixst("check", big, timeout=20)
    assert r.code == 2
    r.one_line_error(f"{big}: file is too large", "the limit is 64 MB")


def test_fifty_megabyte_source_is_refused_from_its_size(tmp_path: Path) -> None:
    # a sparse 50 MB .st file: refused from stat, nothing is read (it used to never finish)
    big = tmp_path / "fifty.st"
    with big.open("wb") as fh:
        fh.truncate(50 * 1024 * 1024)
    r = logixst("check", big, timeout=20)
    assert r.code == 2
    r.one_line_error(f"{big}: file is too large (52,428,800 bytes; the limit is 1 MB)")
