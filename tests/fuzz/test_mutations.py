"""Mutation fuzzing of the samples, the committed exports and the test fixtures (issue 14).

Each input is mutated the way files get damaged or hand-edited: random byte flips,
truncation, a closing token deleted, a NUL inserted, invalid UTF-8, a BOM, CRLF or CR-only
line ends, deep nesting and huge literals spliced in. For every mutant, loading and checking
never raise (an input error is the CLI's one-line refusal), and a mutant that still verifies
runs a few scans without a Python exception, its integer and REAL tags in range.

Budget: SCALE x 8 mutants per file (about 400 cases, some seconds); LOGIXST_FUZZ_LONG=1
for hundreds per file. With LOGIXST_L5X_CORPUS set, the real exports under 400 KB join in. The mutations are seeded: a failure names the seed to replay.
"""

from __future__ import annotations

import os
import random
import re
from pathlib import Path

import pytest

from tests.fuzz.common import ROOT, SCALE, check_and_run

SUFFIXES = {".st", ".rll", ".l5x", ".l5k"}
INPUTS = sorted(
    p
    for folder in (ROOT / "samples", ROOT / "tests")
    for p in folder.rglob("*")
    if p.suffix.lower() in SUFFIXES
    and p.is_file()
    and p.stat().st_size < 400_000
    and "fuzz" not in p.parts
)
# the real-export corpus (not in git) joins when its folder is given, as for its own test
_CORPUS = os.environ.get("LOGIXST_L5X_CORPUS", "")
if _CORPUS and Path(_CORPUS).is_dir():
    INPUTS += sorted(
        p
        for p in Path(_CORPUS).iterdir()
        if p.suffix.lower() in SUFFIXES and p.stat().st_size < 400_000
    )
CLOSERS = re.compile(
    rb"END_IF|END_CASE|END_FOR|END_WHILE|END_REPEAT|END_VAR|END_STRUCT|END_TYPE|\]|\)|</\w+>|;"
)


def mutate(data: bytes, rng: random.Random) -> bytes:
    kind = rng.randrange(11)
    if kind == 0:  # byte flips
        b = bytearray(data)
        for _ in range(rng.randint(1, 8)):
            if b:
                b[rng.randrange(len(b))] ^= 1 << rng.randrange(8)
        return bytes(b)
    if kind == 1:  # truncation
        return data[: rng.randrange(len(data) + 1)]
    if kind == 2:  # a closing token deleted
        found = list(CLOSERS.finditer(data))
        if found:
            m = rng.choice(found)
            return data[: m.start()] + data[m.end() :]
        return data
    if kind == 3:  # NUL
        at = rng.randrange(len(data) + 1)
        return data[:at] + b"\x00" + data[at:]
    if kind == 4:  # invalid UTF-8
        at = rng.randrange(len(data) + 1)
        return data[:at] + rng.choice([b"\xff\xfe", b"\xc3", b"\xed\xa0\x80", b"\x80"]) + data[at:]
    if kind == 5:
        return b"\xef\xbb\xbf" + data  # BOM
    if kind == 6:
        return data.replace(b"\r\n", b"\n").replace(b"\n", b"\r\n")  # CRLF
    if kind == 7:
        return data.replace(b"\r\n", b"\n").replace(b"\n", b"\r")  # CR only
    at = _line_start(data, rng)
    if kind == 8:  # deep nesting of parentheses or blocks
        depth = rng.choice([200, 3_000, 20_000])
        piece = rng.choice(
            [
                b"x := " + b"(" * depth + b"1" + b")" * depth + b";\n",
                b"IF TRUE THEN\n" * (depth // 20) + b"END_IF;\n" * (depth // 20),
                b"[" * depth + b"XIC(b)" + b"]" * depth + b"OTE(b);\n",
            ]
        )
        return data[:at] + piece + data[at:]
    if kind == 9:  # huge literals
        piece = rng.choice(
            [b"9" * 100_000, b"16#" + b"F" * 40, b"1.0E" + b"9" * 50, b"'" + b"a" * 5_000 + b"'"]
        )
        return data[:at] + b"x := " + piece + b";\n" + data[at:]
    # a random slice of the file duplicated somewhere else
    a = rng.randrange(len(data) + 1)
    b = min(len(data), a + rng.randrange(200))
    return data[:at] + data[a:b] + data[at:]


def _line_start(data: bytes, rng: random.Random) -> int:
    starts = [0] + [m.end() for m in re.finditer(rb"\n", data)]
    return rng.choice(starts)


@pytest.mark.parametrize("source", INPUTS, ids=lambda p: p.name)
def test_mutants_never_crash(tmp_path: Path, source: Path) -> None:
    data = source.read_bytes()
    for k in range(8 * SCALE):
        seed = hash((source.name, k)) & 0xFFFF_FFFF if SCALE > 1 else k
        rng = random.Random(f"{source.name}:{seed}")
        mutant = tmp_path / f"m{k}{source.suffix}"
        mutant.write_bytes(mutate(data, rng))
        try:
            check_and_run([mutant], scans=2)
        except Exception as exc:  # the seed replays it: random.Random(f"{name}:{seed}")
            raise AssertionError(f"{source.name} mutant seed {seed}: {exc!r}") from exc
