"""The limits logixst enforces, in one place (docs/limits.md lists them; a test compares).

Each limit is checked early, where the input exceeds it, with a one-line message that
states the limit: a hostile or mistaken input is refused, never allowed to run the machine
out of memory or time (docs/decisions/0130-limits.md).
"""

from __future__ import annotations

import os
import stat
from pathlib import Path

# ---- input files
MAX_PROJECT_BYTES = 64 * 1024 * 1024  # one .L5X / .L5K export
MAX_SOURCE_BYTES = 1024 * 1024  # one .st / .rll file (about 80,000 statements)

# ---- run length and timing (CLI)
MAX_SCANS = 10_000_000  # normal scans in one run (2.8 h of simulated time at 1 ms)
MIN_SCAN_PERIOD_MS = 0.1  # the shortest periodic task period Logix accepts
MAX_SCAN_PERIOD_MS = 2_000_000.0  # the longest (2,000 s)
MIN_COARSE_UPDATE_MS = 1.0  # motion group coarse update period, as Logix allows
MAX_COARSE_UPDATE_MS = 32.0

# ---- tag storage (per program, or per project for an export)
MAX_ARRAY_ELEMENTS = 2_000_000  # elements of one array tag or array member
MAX_TAG_ELEMENTS = 4_000_000  # elementary values of all tags together

# ---- literals
MAX_LITERAL_DIGITS = 1_000  # characters of one numeric literal (digits and separators)
MAX_STRING_CHARS = 82  # a STRING's capacity: a longer literal does not fit

# ---- nesting and size of code (the generated Python allows about 100 nested blocks and
# 20 nested loops; the recursive passes handle some 10,000 levels of expression)
MAX_BLOCK_NESTING = 64  # IF/CASE/FOR/WHILE/REPEAT blocks inside one another
MAX_LOOP_NESTING = 16  # FOR/WHILE/REPEAT loops inside one another
MAX_EXPRESSION_DEPTH = 5_000  # operators, calls and subscripts nested in one expression
MAX_RUNG_ELEMENTS = 10_000  # instructions and branches in one rung
MAX_BRANCH_NESTING = 1_000  # ladder branches inside one another
MAX_ROUTINE_ELEMENTS = 50_000  # statements (ST) or instructions and branches (ladder) per routine


class LimitError(ValueError):
    """An input exceeds one of the limits above; the message states the limit."""


def mb(n: int) -> str:
    """A byte count as the limits table writes it: whole megabytes, else bytes."""
    return f"{n // (1024 * 1024)} MB" if n % (1024 * 1024) == 0 else f"{n:,} bytes"


def read_limited(path: Path, limit: int) -> bytes:
    """The bytes of a regular file of at most `limit` bytes.

    A device (`/dev/zero` behind a `.st` symlink), FIFO or socket is refused from its
    `stat`, before it is opened (opening a FIFO would block); the read itself stops one byte
    past the limit, so a file that grows while being read cannot exceed it either.
    """
    st = os.stat(path)  # follows symlinks: the target's kind counts
    if not stat.S_ISREG(st.st_mode):
        kind = (
            "a device"
            if stat.S_ISCHR(st.st_mode) or stat.S_ISBLK(st.st_mode)
            else "a FIFO"
            if stat.S_ISFIFO(st.st_mode)
            else "a socket"
            if stat.S_ISSOCK(st.st_mode)
            else "a special file"
        )
        raise LimitError(f"is {kind}, not a regular file: logixst reads regular files only")
    if st.st_size > limit:
        raise LimitError(f"file is too large ({st.st_size:,} bytes; the limit is {mb(limit)})")
    with open(path, "rb") as fh:
        data = fh.read(limit + 1)
    if len(data) > limit:
        raise LimitError(f"file is too large (over {mb(limit)}; the limit is {mb(limit)})")
    return data
