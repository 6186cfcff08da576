"""Language-server message fuzzing against the real `logixst lsp` process (issue 14).

Raw JSON-RPC over stdio (no client library, so malformed frames can be sent): bodies that
are not JSON, JSON that is not a request, unknown methods, requests for documents never
opened, positions far outside the text, NaN where a number belongs, changes with ranges
beyond the end, a document of NULs, and a fast stream of edits. After every batch the server
must still answer a well-formed request; every message it sends must be strict JSON (no
NaN/Infinity tokens, decision 0132); it must exit cleanly on shutdown/exit; and it must log
no error (an internal failure of a handler, or a request left unanswered). Budget: SCALE x 40 random messages after the fixed ones.
"""

from __future__ import annotations

import json
import random
import subprocess
import sys
import threading
import time
from typing import Any

from tests.fuzz.common import ROOT, SCALE

SAMPLE = (ROOT / "samples" / "batching.st").read_text()


def strict(text: str) -> Any:
    def refuse(token: str) -> None:
        raise ValueError(f"non-JSON constant {token}")

    return json.loads(text, parse_constant=refuse)


class RawClient:
    def __init__(self) -> None:
        self.proc = subprocess.Popen(
            [sys.executable, "-c", "from interpreter.cli import entry; entry()", "lsp"],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            cwd=ROOT,
        )
        self.messages: list[Any] = []
        self.lock = threading.Condition()
        self.reader = threading.Thread(target=self._read, daemon=True)
        self.reader.start()
        # pygls logs each malformed message with its traceback on stderr: drained here, or
        # the pipe fills up and the server blocks on its next log line
        self.stderr: list[bytes] = []
        self.drain = threading.Thread(target=self._drain, daemon=True)
        self.drain.start()
        self.next_id = 1000
        self.asked: list[int] = []  # ids of every request sent: each must get an answer

    def _drain(self) -> None:
        assert self.proc.stderr is not None
        for chunk in iter(lambda: self.proc.stderr.read1(65536), b""):  # type: ignore[union-attr]
            self.stderr.append(chunk)

    def _read(self) -> None:
        out = self.proc.stdout
        assert out is not None
        while True:
            length = None
            while True:
                line = out.readline()
                if not line:
                    return
                if line in (b"\r\n", b"\n"):
                    break
                name, _, value = line.decode("ascii").partition(":")
                if name.strip().lower() == "content-length":
                    length = int(value)
            assert length is not None
            body = out.read(length).decode("utf-8")
            message = strict(body)  # raises in this thread: recorded below as a failure
            with self.lock:
                self.messages.append(message)
                self.lock.notify_all()

    def raw(self, body: bytes, header: bytes | None = None) -> None:
        assert self.proc.stdin is not None
        head = header if header is not None else b"Content-Length: %d\r\n\r\n" % len(body)
        self.proc.stdin.write(head + body)
        self.proc.stdin.flush()

    def send(self, message: dict[str, Any]) -> None:
        self.raw(json.dumps({"jsonrpc": "2.0", **message}).encode())  # allow_nan: on purpose

    def ask(self, method: str, params: Any) -> int:
        """Send a request without waiting; its answer is checked at the end."""
        self.next_id += 1
        self.asked.append(self.next_id)
        self.send({"id": self.next_id, "method": method, "params": params})
        return self.next_id

    def unanswered(self) -> list[int]:
        with self.lock:
            answered = {
                m.get("id") for m in self.messages if isinstance(m, dict) and "method" not in m
            }
        return [i for i in self.asked if i not in answered]

    def request(self, method: str, params: Any, timeout: float = 30.0) -> Any:
        rid = self.ask(method, params)
        deadline = time.monotonic() + timeout
        with self.lock:
            while True:
                for m in self.messages:
                    if isinstance(m, dict) and m.get("id") == rid and "method" not in m:
                        return m
                left = deadline - time.monotonic()
                assert left > 0, f"no answer to {method} within {timeout} s"
                self.lock.wait(left)


def doc(name: str) -> dict[str, str]:
    return {"uri": (ROOT / "samples" / name).as_uri()}


def probe(client: RawClient) -> None:
    """A well-formed request the server must still answer."""
    r = client.request(
        "textDocument/hover",
        {"textDocument": doc("fuzz_probe.st"), "position": {"line": 0, "character": 0}},
    )
    assert "result" in r or "error" in r


def fixed_cases(c: RawClient) -> None:
    uri = doc("fuzz_probe.st")
    c.send(
        {
            "method": "textDocument/didOpen",
            "params": {"textDocument": {**uri, "languageId": "st", "version": 1, "text": SAMPLE}},
        }
    )
    c.raw(b"{ this is not json")
    c.raw(b"[]")
    c.raw(b"42")
    c.raw(b'"a string"')
    c.raw(b'{"jsonrpc": "2.0"}')
    c.raw(b'{"jsonrpc": "2.0", "id": 7}')
    c.raw(b"\xff\xfe\x00garbage")
    c.ask("no/such/method", {})
    c.send({"method": "no/such/notification", "params": None})
    probe(c)
    for method in ("hover", "completion", "definition", "references", "signatureHelp"):
        for line, char in ((10**9, 0), (0, 10**9), (-1, -1), (float("nan"), 0), (1.5, 2)):
            params: dict[str, Any] = {
                "textDocument": doc("never_opened.st"),
                "position": {"line": line, "character": char},
            }
            if method == "references":
                params["context"] = {"includeDeclaration": True}
            c.ask(f"textDocument/{method}", params)
            c.ask(f"textDocument/{method}", {**params, "textDocument": uri})
    probe(c)
    c.send(
        {
            "method": "textDocument/didChange",
            "params": {
                "textDocument": {**uri, "version": 2},
                "contentChanges": [
                    {
                        "range": {
                            "start": {"line": 10**6, "character": 5},
                            "end": {"line": 10**6 + 1, "character": 0},
                        },
                        "text": "x := 1;",
                    }
                ],
            },
        }
    )
    c.send(
        {
            "method": "textDocument/didChange",
            "params": {
                "textDocument": {**uri, "version": 3},
                "contentChanges": [{"text": "\x00" * 100}],
            },
        }
    )
    c.send({"method": "textDocument/didClose", "params": {"textDocument": doc("never_opened.st")}})
    probe(c)


def random_cases(c: RawClient, rng: random.Random) -> None:
    uri = doc("fuzz_probe.st")
    text = SAMPLE
    for version in range(4, 4 + 40 * SCALE):
        kind = rng.randrange(5)
        if kind == 0:  # a fast edit: replace a random slice
            a = rng.randrange(len(text) + 1)
            b = min(len(text), a + rng.randrange(20))
            piece = rng.choice(["(", ")", "END_IF;", "IF x THEN", "'", "(*", "\n", "é", "16#", ""])
            text = text[:a] + piece + text[b:]
            c.send(
                {
                    "method": "textDocument/didChange",
                    "params": {
                        "textDocument": {**uri, "version": version},
                        "contentChanges": [{"text": text}],
                    },
                }
            )
        elif kind == 1:  # a truncated frame body followed by a good one
            body = json.dumps({"jsonrpc": "2.0", "method": "x", "params": {}}).encode()
            c.raw(body[: rng.randrange(len(body))] + b"}")
        elif kind == 2:  # a request at a random (possibly absurd) position
            line = rng.choice([0, 5, 10**7, -3])
            c.ask(
                rng.choice(
                    ["textDocument/hover", "textDocument/completion", "textDocument/definition"]
                ),
                {"textDocument": uri, "position": {"line": line, "character": line}},
            )
        elif kind == 3:  # params of the wrong shape
            c.ask("textDocument/documentSymbol", rng.choice([None, [], "x", {"textDocument": 5}]))
        else:
            c.ask(
                "textDocument/semanticTokens/full",
                {"textDocument": rng.choice([uri, doc("nope.rll")])},
            )
    probe(c)


def test_lsp_survives_hostile_messages() -> None:
    c = RawClient()
    try:
        init = c.request(
            "initialize", {"processId": None, "rootUri": ROOT.as_uri(), "capabilities": {}}
        )
        assert "result" in init
        c.send({"method": "initialized", "params": {}})
        fixed_cases(c)
        random_cases(c, random.Random(14 if SCALE == 1 else time.time_ns()))
        assert "result" in c.request("shutdown", None)
        c.send({"method": "exit"})
        assert c.proc.wait(timeout=30) == 0
    finally:
        if c.proc.poll() is None:
            c.proc.kill()
    # the reader ends at EOF (not on a non-JSON message); after the process exits it may
    # still be handing over the last frames on a busy machine, so it is given time to finish
    c.reader.join(timeout=30)
    assert c.reader.is_alive() is False
    # every request got an answer (a result or a JSON-RPC error), none is left waiting
    assert c.unanswered() == []
    # malformed frames are reported by pygls (a showMessage, a traceback on stderr); the
    # server's own handlers never fail (lsp/server.py `guarded` logs "internal error")
    errors = [
        m["params"]["message"]
        for m in c.messages
        if isinstance(m, dict)
        and m.get("method") == "window/logMessage"
        and "internal error" in m["params"]["message"]
    ]
    assert errors == [], errors[0][-3000:]
