"""Language server benchmark: the real `logixst lsp` process over stdio, timed from the client.

On a generated 5,000-line ST document and on the generated 2 MB export of bench_l5x.py:
- completion (an enumerated operand, members after `.`, a statement start): p50 and p95;
- hover and signature help: p50 and p95;
- diagnostics: time from a one-character change to the publishDiagnostics of that version
  (the debounce included);
- the server's resident memory with the document open.
Targets (issue 10): completion p95 <= 20 ms (bar 50 ms), hover and signature p95 <= 10 ms,
diagnostics <= 300 ms after a change. Run: `python tests/benchmarks/bench_lsp.py`.
"""

from __future__ import annotations

import asyncio
import statistics
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(Path(__file__).parent))

from bench_l5x import export  # noqa: E402
from bench_parse import program  # noqa: E402
from lsprotocol import types as t  # noqa: E402
from pytest_lsp import ClientServerConfig  # noqa: E402

SERVER = [
    sys.executable,
    "-c",
    "import sys; from interpreter.cli import main; sys.exit(main(['lsp']))",
]
MOTION_DECL = "  ax : AXIS_VIRTUAL; c : MOTION_INSTRUCTION; prof : CAM_PROFILE[3];\nEND_VAR\n"
MOTION_LINE = "IF done THEN MATC(ax, c, 0, prof, 1.0, 1.0, Once, Immediate, 0.0, 0, TimeDrivenMode); END_IF;\n"


def st_document(lines: int = 5000) -> str:
    text = program(lines).replace("END_VAR\n", MOTION_DECL, 1)
    return text + MOTION_LINE


def p(values: list[float], q: float) -> float:
    values = sorted(values)
    return values[min(len(values) - 1, int(q * len(values)))]


async def timed(coro) -> float:  # type: ignore[no-untyped-def]
    t0 = time.perf_counter()
    await coro
    return (time.perf_counter() - t0) * 1000.0


def rss_mb(pid: int) -> float:
    for line in Path(f"/proc/{pid}/status").read_text().splitlines():
        if line.startswith("VmRSS:"):
            return int(line.split()[1]) / 1024.0
    return float("nan")


async def measure(
    path: Path, text: str, probes: list[tuple[str, t.Position]], edit_at: t.Position
) -> dict[str, float]:
    client = await ClientServerConfig(server_command=SERVER).start()
    await client.initialize_session(t.InitializeParams(capabilities=t.ClientCapabilities()))
    uri = path.resolve().as_uri()
    t0 = time.perf_counter()
    client.text_document_did_open(
        t.DidOpenTextDocumentParams(t.TextDocumentItem(uri, "st", 1, text))
    )
    while uri not in client.diagnostics:
        await asyncio.sleep(0.002)
    open_ms = (time.perf_counter() - t0) * 1000.0
    doc = t.TextDocumentIdentifier(uri)
    comp: list[float] = []
    hov: list[float] = []
    sig: list[float] = []
    lines = text.split("\n")
    version = 1
    for round_ in range(40):
        # type one character somewhere first, as a user does between requests
        version += 1
        ch = "1" if round_ % 2 else "2"
        client.text_document_did_change(
            t.DidChangeTextDocumentParams(
                t.VersionedTextDocumentIdentifier(version=version, uri=uri),
                [
                    t.TextDocumentContentChangePartial(
                        t.Range(edit_at, t.Position(edit_at.line, edit_at.character + 1)), ch
                    )
                ],
            )
        )
        for kind, at in probes:
            if kind == "completion":
                comp.append(
                    await timed(client.text_document_completion_async(t.CompletionParams(doc, at)))
                )
            elif kind == "hover":
                hov.append(await timed(client.text_document_hover_async(t.HoverParams(doc, at))))
            else:
                sig.append(
                    await timed(
                        client.text_document_signature_help_async(t.SignatureHelpParams(doc, at))
                    )
                )
    # diagnostics latency: one change, then wait for the publish of that version
    diag: list[float] = []
    for k in range(10):
        await asyncio.sleep(2.0)  # let earlier work (debounced analyses) finish first
        version += 1
        client.diagnostics.pop(uri, None)
        t0 = time.perf_counter()
        client.text_document_did_change(
            t.DidChangeTextDocumentParams(
                t.VersionedTextDocumentIdentifier(version=version, uri=uri),
                [
                    t.TextDocumentContentChangePartial(
                        t.Range(edit_at, t.Position(edit_at.line, edit_at.character + 1)),
                        str(k % 10),
                    )
                ],
            )
        )
        while uri not in client.diagnostics:
            await asyncio.sleep(0.001)
        diag.append((time.perf_counter() - t0) * 1000.0)
    memory = rss_mb(client._server.pid)  # type: ignore[attr-defined]
    await client.shutdown_session()
    await client.stop()
    del lines
    return {
        "open_ms": open_ms,
        "completion_p50": p(comp, 0.5),
        "completion_p95": p(comp, 0.95),
        "hover_p50": p(hov, 0.5),
        "hover_p95": p(hov, 0.95),
        "signature_p50": p(sig, 0.5),
        "signature_p95": p(sig, 0.95),
        "diagnostics_median": statistics.median(diag),
        "diagnostics_max": max(diag),
        "rss_mb": memory,
    }


def position_after(text: str, needle: str, occurrence: int = 0) -> t.Position:
    at = -1
    for _ in range(occurrence + 1):
        at = text.index(needle, at + 1)
    at += len(needle)
    line = text.count("\n", 0, at)
    return t.Position(line, at - (text.rfind("\n", 0, at) + 1))


def st_case(tmp: Path) -> tuple[Path, str, list[tuple[str, t.Position]], t.Position]:
    text = st_document()
    probes = [
        ("completion", position_after(text, "prof, 1.0, 1.0, ")),  # ExecutionMode values
        ("completion", position_after(text, "st[3].")),  # members of a UDT element
        ("completion", position_after(text, "END_VAR\n")),  # statement start
        ("hover", position_after(text, "MAT")),
        ("signature", position_after(text, "prof, 1.0, ")),
    ]
    edit_at = position_after(text, "st[5].Speed * 0.9")  # the 5 of 0.95 in the middle
    path = tmp / "bench.st"
    return path, text, probes, edit_at


def l5x_case(tmp: Path) -> tuple[Path, str, list[tuple[str, t.Position]], t.Position]:
    text = export(2 * 1024 * 1024)
    probes = [
        ("completion", position_after(text, "TON(", 100)),  # a tag operand in a rung
        ("completion", position_after(text, "<![CDATA[", 500)),  # start of a rung
        ("hover", position_after(text, "<![CDATA[XIC", 300)),
        ("signature", position_after(text, "TON(", 200)),
    ]
    edit_at = position_after(text, "<![CDATA[", 1000)
    path = tmp / "bench.L5X"
    return path, text, probes, edit_at


def main() -> None:
    with tempfile.TemporaryDirectory() as d:
        tmp = Path(d)
        for name, case in (("5,000-line ST", st_case), ("2 MB L5X", l5x_case)):
            path, text, probes, edit_at = case(tmp)
            path.write_text(text)
            r = asyncio.run(measure(path, text, probes, edit_at))
            print(f"{name} ({len(text) / 1e6:.2f} MB, {text.count(chr(10))} lines):")
            for k, v in r.items():
                print(f"  {k:20s} {v:8.1f}")


if __name__ == "__main__":
    main()
