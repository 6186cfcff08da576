"""`logixst check` on a generated 2 MB Studio 5000 export (issue 3 target: under 1.5 s).

Run as a script (`python tests/benchmarks/bench_l5x.py [MB]`) or with pytest pointed at this
file. The export has what real projects carry: a UDT with BOOL members, a few hundred
controller tags with Decorated data (timers, counters, arrays), several programs whose RLL
routines hold typical rungs (contacts, branches, timers, counters, compares, moves, math,
comments and descriptions) and an ST routine each.
"""

from __future__ import annotations

import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))  # run from anywhere

from load_timing import best_load  # noqa: E402

from interpreter.runtime.loader import load  # noqa: E402

TARGET_S = 1.5

HEAD = """<?xml version="1.0" encoding="UTF-8" standalone="yes"?>
<RSLogix5000Content SchemaRevision="1.0" SoftwareRevision="33.01" TargetName="Bench" TargetType="Controller" ContainsContext="false">
<Controller Use="Target" Name="Bench" ProcessorType="1756-L83E" MajorRev="33" MinorRev="11">
<DataTypes>
<DataType Name="Motor" Family="NoFamily" Class="User">
<Members>
<Member Name="ZZZZZZZZZZMotor0" DataType="SINT" Dimension="0" Radix="Decimal" Hidden="true"/>
<Member Name="Run" DataType="BIT" Dimension="0" Radix="Decimal" Hidden="false" Target="ZZZZZZZZZZMotor0" BitNumber="0"/>
<Member Name="Fault" DataType="BIT" Dimension="0" Radix="Decimal" Hidden="false" Target="ZZZZZZZZZZMotor0" BitNumber="1"/>
<Member Name="Speed" DataType="REAL" Dimension="0" Radix="Float" Hidden="false"/>
<Member Name="Starts" DataType="DINT" Dimension="0" Radix="Decimal" Hidden="false"/>
</Members>
</DataType>
</DataTypes>
<Tags>
"""

TAGS = """<Tag Name="M{i}" TagType="Base" DataType="Motor" Constant="false" ExternalAccess="Read/Write">
<Description><![CDATA[Motor {i} of the line]]></Description>
</Tag>
<Tag Name="T{i}" TagType="Base" DataType="TIMER" Constant="false" ExternalAccess="Read/Write">
<Data Format="Decorated">
<Structure DataType="TIMER">
<DataValueMember Name="PRE" DataType="DINT" Radix="Decimal" Value="{pre}"/>
<DataValueMember Name="ACC" DataType="DINT" Radix="Decimal" Value="0"/>
<DataValueMember Name="EN" DataType="BOOL" Value="0"/>
<DataValueMember Name="TT" DataType="BOOL" Value="0"/>
<DataValueMember Name="DN" DataType="BOOL" Value="0"/>
</Structure>
</Data>
</Tag>
<Tag Name="C{i}" TagType="Base" DataType="COUNTER" Constant="false" ExternalAccess="Read/Write"/>
<Tag Name="V{i}" TagType="Base" DataType="DINT" Dimensions="8" Radix="Decimal" Constant="false" ExternalAccess="Read/Write">
<Data Format="Decorated">
<Array DataType="DINT" Dimensions="8" Radix="Decimal">
<Element Index="[0]" Value="1"/><Element Index="[1]" Value="2"/><Element Index="[2]" Value="3"/><Element Index="[3]" Value="4"/>
<Element Index="[4]" Value="5"/><Element Index="[5]" Value="6"/><Element Index="[6]" Value="7"/><Element Index="[7]" Value="8"/>
</Array>
</Data>
</Tag>
<Tag Name="B{i}" TagType="Base" DataType="BOOL" Radix="Decimal" Constant="false" ExternalAccess="Read/Write"/>
<Tag Name="R{i}" TagType="Base" DataType="REAL" Radix="Float" Constant="false" ExternalAccess="Read/Write"/>
"""

RUNGS = [
    "XIC(B{i})XIO(M{i}.Fault)OTE(M{i}.Run);",
    "[XIC(M{i}.Run) ,XIC(B{j}) ]XIO(T{i}.DN)TON(T{i},?,?);",
    "XIC(T{i}.DN)CTU(C{i},?,?);",
    "GRT(R{i},50.0)LES(V{i}[2],100)MOV(V{i}[3],V{i}[4]);",
    "XIC(M{i}.Run)[ADD(M{i}.Starts,1,M{i}.Starts) ,MUL(R{i},1.5,M{i}.Speed) ];",
    "XIC(C{i}.DN)RES(C{i});",
    "[XIC(B{i})OTL(B{j}) ,XIO(B{i})OTU(B{j}) ];",
    "CPT(R{j},R{i}*2.0+V{i}[1]/4.0);",
]

ST_LINES = [
    "// ST part of program {p}",
    "IF M{i}.Run AND NOT M{i}.Fault THEN",
    "  R{i} := R{i} * 0.95 + M{i}.Speed * 0.05;",
    "ELSE",
    "  R{i} := 0.0;",
    "END_IF;",
]


def export(target_bytes: int, per_program: int = 40) -> str:
    n_tags = 200
    parts = [HEAD]
    for i in range(n_tags):
        parts.append(TAGS.format(i=i, pre=1000 + i))
    parts.append("</Tags>\n<Programs>\n")
    size = sum(len(p) for p in parts)
    p = 0
    programs: list[str] = []
    while size < target_bytes - 2000:
        body = [
            f'<Program Name="P{p}" TestEdits="false" MainRoutineName="Main" Disabled="false">\n<Routines>\n',
            '<Routine Name="Main" Type="RLL">\n<RLLContent>\n',
        ]
        for r in range(per_program):
            i, j = (p * per_program + r) % n_tags, (p * per_program + r + 7) % n_tags
            text = RUNGS[r % len(RUNGS)].format(i=i, j=j)
            comment = (
                f"<Comment>\n<![CDATA[Rung {r}: station {i}]]>\n</Comment>\n" if r % 3 == 0 else ""
            )
            body.append(
                f'<Rung Number="{r}" Type="N">\n{comment}<Text>\n<![CDATA[{text}]]>\n</Text>\n</Rung>\n'
            )
        body.append("</RLLContent>\n</Routine>\n")
        body.append('<Routine Name="Calc" Type="ST">\n<STContent>\n')
        for k, line in enumerate(ST_LINES):
            body.append(
                f'<Line Number="{k}">\n<![CDATA[{line.format(p=p, i=p % n_tags)}]]>\n</Line>\n'
            )
        body.append("</STContent>\n</Routine>\n</Routines>\n</Program>\n")
        chunk = "".join(body)
        parts.append(chunk)
        programs.append(f'<ScheduledProgram Name="P{p}"/>')
        size += len(chunk)
        p += 1
    parts.append("</Programs>\n<Tasks>\n")
    parts.append(
        '<Task Name="Main" Type="CONTINUOUS" Priority="10" Watchdog="500">\n<ScheduledPrograms>\n'
    )
    parts.append("\n".join(programs))
    parts.append(
        "\n</ScheduledPrograms>\n</Task>\n</Tasks>\n</Controller>\n</RSLogix5000Content>\n"
    )
    return "".join(parts)


def bench(megabytes: float = 2.0, repeat: int = 3) -> dict[str, float]:
    text = export(int(megabytes * 1_000_000))
    with tempfile.TemporaryDirectory() as d:
        path = Path(d) / "bench.L5X"
        path.write_text(text)
        load([path])  # grammar compilation and catalog loading are one-time costs
        best, loaded = best_load(path, repeat)
        errors = [d for d in loaded.diagnostics if d.severity.value == "error"]
        assert not errors, errors[:3]
        cli = float("inf")
        for _ in range(repeat):  # the whole command, as a user runs it: start-up, grammars, exit
            t0 = time.perf_counter()
            done = subprocess.run(
                [sys.executable, "-m", "interpreter.cli", "check", str(path)],
                capture_output=True,
                text=True,
                check=False,
                cwd=ROOT,
            )
            cli = min(cli, time.perf_counter() - t0)
            assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    rungs = text.count("<Rung ")
    return {"bytes": len(text.encode()), "rungs": rungs, "seconds": best, "cli": cli}


def test_l5x_check_benchmark() -> None:
    r = bench()
    print(
        f"\ncheck {r['bytes'] / 1e6:.2f} MB export ({r['rungs']:.0f} rungs): load {r['seconds']:.2f} s, "
        f"whole `logixst check` command {r['cli']:.2f} s"
    )


if __name__ == "__main__":
    mb = float(sys.argv[1]) if len(sys.argv) > 1 else 2.0
    r = bench(mb)
    verdict = "meets" if r["seconds"] < TARGET_S else "misses"
    verdict_cli = "meets" if r["cli"] < TARGET_S else "misses"
    print(
        f"check of a {r['bytes'] / 1e6:.2f} MB export with {r['rungs']:.0f} rungs: best of 3 "
        f"load {r['seconds']:.2f} s ({verdict} the {TARGET_S} s target); whole `logixst check` "
        f"command {r['cli']:.2f} s ({verdict_cli})"
    )
