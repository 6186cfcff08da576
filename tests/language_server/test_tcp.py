"""`logixst lsp --tcp HOST:PORT` serves the same protocol on a loopback socket; bad values
for --tcp are usage errors."""

from __future__ import annotations

import json
import socket
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def _frame(obj: dict[str, object]) -> bytes:
    body = json.dumps(obj).encode()
    return f"Content-Length: {len(body)}\r\n\r\n".encode() + body


def _read_message(sock: socket.socket) -> dict[str, object]:
    data = b""
    while b"\r\n\r\n" not in data:
        data += sock.recv(4096)
    head, rest = data.split(b"\r\n\r\n", 1)
    length = int(
        next(h for h in head.split(b"\r\n") if h.lower().startswith(b"content-length")).split(b":")[
            1
        ]
    )
    while len(rest) < length:
        rest += sock.recv(4096)
    return json.loads(rest[:length])  # type: ignore[no-any-return]


def test_lsp_over_tcp_answers_initialize() -> None:
    port = _free_port()
    code = f"import sys; from interpreter.cli import main; sys.exit(main(['lsp', '--tcp', '127.0.0.1:{port}']))"
    server = subprocess.Popen([sys.executable, "-c", code], cwd=ROOT, stderr=subprocess.DEVNULL)
    try:
        deadline = time.monotonic() + 30
        while True:
            try:
                sock = socket.create_connection(("127.0.0.1", port), timeout=10)
                break
            except OSError:
                if time.monotonic() > deadline:
                    raise
                time.sleep(0.1)
        with sock:
            sock.sendall(
                _frame(
                    {
                        "jsonrpc": "2.0",
                        "id": 1,
                        "method": "initialize",
                        "params": {"capabilities": {}},
                    }
                )
            )
            reply = _read_message(sock)
            while "id" not in reply:  # skip notifications such as window/logMessage
                reply = _read_message(sock)
        assert reply["id"] == 1
        caps = reply["result"]["capabilities"]  # type: ignore[index]
        assert caps["completionProvider"]["triggerCharacters"]  # type: ignore[index]
        assert caps["hoverProvider"]  # type: ignore[index]
    finally:
        server.kill()
        server.wait(timeout=10)


def test_bad_tcp_address_is_a_usage_error(capsys) -> None:  # type: ignore[no-untyped-def]
    from interpreter.cli import main

    assert main(["lsp", "--tcp", "localhost"]) == 2
    assert "--tcp expects HOST:PORT" in capsys.readouterr().err
