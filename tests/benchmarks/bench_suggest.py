"""`logixst check` of a generated export with 5,000 tags and 2,000 undefined names (issue 9
target: at most 2 s for the whole command).

Each undefined name gets a did-you-mean (E101). Comparing each one with every tag costs
undefined names x tags; the index of semantics/suggest.py (decision 0055) keeps it to a few
candidates per name. Half of the undefined names are one-character typos of real tags (each
must get its suggestion), half are names close to nothing.

Run as a script (`python tests/benchmarks/bench_suggest.py`) or with pytest pointed at this
file.
"""

from __future__ import annotations

import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))  # run from anywhere

TARGET_S = 2.0
TAGS = 5000
UNDEFINED = 2000

AREAS = [
    "Line",
    "Mixer",
    "Oven",
    "Press",
    "Filler",
    "Capper",
    "Wrap",
    "Pallet",
    "Boiler",
    "Chiller",
]
DEVICES = ["Pump", "Valve", "Motor", "Fan", "Heater", "Sensor", "Gate", "Belt", "Door", "Lamp"]
SIGNALS = ["Run", "Fault", "Open", "Closed", "Speed", "Temp", "Level", "Ready", "Alarm", "Reset"]

HEAD = """<?xml version="1.0" encoding="UTF-8" standalone="yes"?>
<RSLogix5000Content SchemaRevision="1.0" SoftwareRevision="33.01" TargetName="Suggest" TargetType="Controller">
<Controller Use="Target" Name="Suggest" ProcessorType="1756-L83E" MajorRev="33" MinorRev="11">
<Tags>
"""
PROGRAM = """</Tags>
<Programs>
<Program Name="Main" MainRoutineName="Logic">
<Routines>
<Routine Name="Logic" Type="RLL">
<RLLContent>
"""
TAIL = """</RLLContent>
</Routine>
</Routines>
</Program>
</Programs>
<Tasks>
<Task Name="T" Type="CONTINUOUS" Priority="10" Watchdog="500">
<ScheduledPrograms><ScheduledProgram Name="Main"/></ScheduledPrograms>
</Task>
</Tasks>
</Controller>
</RSLogix5000Content>
"""


def tag_names() -> list[str]:
    names = []
    for k in range(TAGS):
        area, dev, sig = AREAS[k % 10], DEVICES[(k // 10) % 10], SIGNALS[(k // 100) % 10]
        names.append(f"{area}{k // 1000 + 1}_{dev}{k % 97}_{sig}")
    return sorted(set(names))


def undefined_names(tags: list[str]) -> list[tuple[str, str | None]]:
    """(name, the tag it is a typo of, or None), all distinct and none a tag."""
    known = {t.lower() for t in tags}
    out: list[tuple[str, str | None]] = []
    seen: set[str] = set()
    k = 0
    while len(out) < UNDEFINED:
        if k % 2 == 0:  # drop one character in the middle of a real tag
            tag = tags[(k * 7) % len(tags)]
            cut = len(tag) // 2
            name, source = tag[:cut] + tag[cut + 1 :], tag
        else:  # close to nothing
            name, source = f"Qz{k}xWvJ{k % 13}", None
        k += 1
        if name.lower() in known or name.lower() in seen:
            continue
        seen.add(name.lower())
        out.append((name, source))
    return out


def export() -> tuple[str, list[tuple[str, str | None]]]:
    tags = tag_names()
    undefined = undefined_names(tags)
    parts = [HEAD]
    parts += [f'<Tag Name="{t}" TagType="Base" DataType="BOOL"/>\n' for t in tags]
    parts.append(PROGRAM)
    for r in range(0, len(undefined), 4):
        contacts = "".join(f"XIC({name})" for name, _ in undefined[r : r + 4])
        text = f"{contacts}OTE({tags[r % len(tags)]});"
        parts.append(f'<Rung Number="{r // 4}" Type="N"><Text><![CDATA[{text}]]></Text></Rung>\n')
    parts.append(TAIL)
    return "".join(parts), undefined


def bench(repeat: int = 3) -> dict[str, float]:
    text, undefined = export()
    with tempfile.TemporaryDirectory() as d:
        path = Path(d) / "suggest.L5X"
        path.write_text(text)
        best = float("inf")
        out = ""
        for _ in range(repeat):  # the whole command, as a user runs it
            t0 = time.perf_counter()
            done = subprocess.run(
                [sys.executable, "-m", "interpreter.cli", "check", str(path)],
                capture_output=True,
                text=True,
                check=False,
                cwd=ROOT,
            )
            best = min(best, time.perf_counter() - t0)
            out = done.stdout
            assert done.returncode == 1, done.stderr[-2000:]
    found = re.findall(r"E101 undefined tag '([^']*)'(?: \(did you mean '([^']*)'\?\))?", out)
    assert len(found) == UNDEFINED, len(found)
    expected = dict(undefined)
    suggested = dict(found)
    for name, source in expected.items():
        if source is not None:  # a one-character typo is always found
            assert suggested[name] == source, (name, suggested[name], source)
    far = sum(1 for name, source in expected.items() if source is None and suggested[name])
    return {"seconds": best, "far_suggested": far, "bytes": len(text.encode())}


def test_suggest_benchmark() -> None:
    r = bench()
    print(
        f"\ncheck with {TAGS} tags and {UNDEFINED} undefined names: whole `logixst check` "
        f"command {r['seconds']:.2f} s"
    )
    assert r["seconds"] <= TARGET_S


if __name__ == "__main__":
    r = bench()
    verdict = "meets" if r["seconds"] <= TARGET_S else "misses"
    print(
        f"check of an export with {TAGS} tags and {UNDEFINED} undefined names "
        f"({r['bytes'] / 1e6:.2f} MB): best of 3 whole `logixst check` command "
        f"{r['seconds']:.2f} s ({verdict} the {TARGET_S} s target)"
    )
