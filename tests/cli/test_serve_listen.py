"""``corrugate serve`` on a host or port it cannot listen on: one line naming the option, exit 2,
before the app starts its worker processes. Before, uvicorn logged the OS's words and exited with
its own code 3, which is corrugate's exit code for a bug."""

from __future__ import annotations

import socket
import subprocess
import sys

import pytest


def serve(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "corrugate", "serve", *args],
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
    )


def test_a_port_in_use_is_one_line_naming_the_port() -> None:
    with socket.socket() as held:
        held.bind(("127.0.0.1", 0))
        held.listen()
        port = held.getsockname()[1]
        r = serve("--port", str(port))
    assert r.returncode == 2, (r.returncode, r.stderr)
    assert r.stderr == (
        f"corrugate: error: --port = {port} is in use on this machine: allowed a free TCP port\n"
    )
    assert r.stdout == ""  # nothing said about serving


@pytest.mark.parametrize(
    ("host", "reason"),
    [
        ("no-such-host.invalid", "cannot be resolved"),  # RFC 2606: never resolves
        ("192.0.2.1", "cannot be listened on"),  # RFC 5737 TEST-NET-1: no machine's address
    ],
)
def test_a_host_it_cannot_listen_on_is_one_line_naming_the_host(host: str, reason: str) -> None:
    r = serve("--host", host, "--port", "8000")
    assert r.returncode == 2, (r.returncode, r.stderr)
    assert r.stderr.startswith(f"corrugate: error: --host = {host} {reason}"), r.stderr
    assert r.stderr.count("\n") == 1, r.stderr  # not even the warning about other machines
