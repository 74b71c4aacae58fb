"""A request cannot take the server with it (issue 22, item 3), on real servers: ``corrugate serve``
in a child process (its worker processes are its grandchildren, under the forkserver) and uvicorn
in a thread for the slow-client deadlines.

* hostile bodies (an exponent tower, a perforation bomb) get 4xx within the request's time limit
  while ``GET /`` keeps answering within 1 s;
* a design past the time limit gets 504 naming the limit, the worker computing it is killed and
  replaced, and the next request is served;
* SIGTERM or Ctrl-C stops the server and every worker, even with a computation in flight; after
  SIGKILL of the server no worker is left either (``PR_SET_PDEATHSIG``);
* 120 sockets trickling a byte a second do not deny service, and a late request head or body
  gets 408.
"""

from __future__ import annotations

import copy
import json
import os
import signal
import socket
import subprocess
import sys
import threading
import time
import tomllib
import urllib.error
import urllib.request
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import pytest
import uvicorn

from corrugate.cli.serve import HEAD_TIMEOUT_S
from corrugate.web import WebSettings, create_app
from corrugate.web.guards import slow_client_protocol
from corrugate.web.schemas import BLIMP_GRIPPER
from corrugate.web.workers import core_count

from .conftest import CASE1, direct
from .conftest import post_json as post

pytestmark = [
    pytest.mark.slow,
    pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="reads /proc"),
]

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"

#: The time limit of the served app (``corrugate serve --timeout``).
LIMIT_S = 2.0

#: The worker processes of ``corrugate serve``: the quick lane's and the job pool's (one per
#: core, at least 2).
WORKERS = WebSettings().quick_processes + max(2, core_count())

TOWER = {"W": "1 mm**9**9**9", "n": 8, "alpha": 84}
PERFORATION_BOMB = {
    "W": 8,
    "n": 8,
    "alpha": 84,
    "fold_style": "perforated",
    "cut": 1e-9,
    "gap": 1e-9,
}


def slow_spec() -> dict[str, Any]:
    """The shipped wheel with a 68.9 mm axle hole in its 70-80 mm disc (a 0.55 mm ligament):
    minutes of branch and bound (issue 22), far past :data:`LIMIT_S`."""
    with (EXAMPLES / "wheel_circle.toml").open("rb") as f:
        spec = tomllib.load(f)
    spec["layout"]["holes"][0]["diameter"] = "68.9 mm"
    return spec


def _processes() -> dict[int, tuple[int, str]]:
    """Every process: pid -> (parent pid, state letter)."""
    out = {}
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                fields = (entry / "stat").read_text().rsplit(")", 1)[1].split()
            except (OSError, IndexError):
                continue
            out[int(entry.name)] = (int(fields[1]), fields[0])
    return out


def descendants(pid: int) -> dict[int, int]:
    """The live (not zombie) processes under ``pid``: pid -> depth (1: its children)."""
    children: dict[int, list[int]] = {}
    for child, (parent, state) in _processes().items():
        if state != "Z":
            children.setdefault(parent, []).append(child)
    found: dict[int, int] = {}
    frontier = [(pid, 0)]
    while frontier:
        here, depth = frontier.pop()
        for child in children.get(here, []):
            found[child] = depth + 1
            frontier.append((child, depth + 1))
    return found


def workers(pid: int) -> set[int]:
    """The worker processes of the server ``pid``: the children of its forkserver."""
    return {p for p, depth in descendants(pid).items() if depth == 2}


def running(pids: set[int]) -> set[int]:
    """Those of ``pids`` still running (zombies have ended)."""
    table = _processes()
    return {p for p in pids if p in table and table[p][1] != "Z"}


def wait_for(condition: Any, seconds: float) -> bool:
    deadline = time.monotonic() + seconds
    while not condition():
        if time.monotonic() > deadline:
            return False
        time.sleep(0.05)
    return True


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def page_time(base: str) -> float:
    """Seconds ``GET /`` takes (it must be 200)."""
    start = time.monotonic()
    with urllib.request.urlopen(base + "/", timeout=5) as response:
        assert response.status == 200
        response.read()
    return time.monotonic() - start


@contextmanager
def serving(tmp_path: Path, timeout_s: float) -> Iterator[tuple[subprocess.Popen[bytes], str]]:
    """``corrugate serve --timeout timeout_s`` on a free port, its workers ready; killed (with
    whatever it left) at the end."""
    port = free_port()
    log = (tmp_path / f"serve-{port}.log").open("wb")
    command = [sys.executable, "-m", "corrugate", "serve", "--port", str(port)]
    # a solver budget past the time limit: a long design meets the limit (504), not its budget
    server = subprocess.Popen(
        [*command, "--timeout", f"{timeout_s:g}", "--budget", "600"],
        stdout=log,
        stderr=subprocess.STDOUT,
    )
    base = f"http://127.0.0.1:{port}"
    seen: set[int] = set()
    try:
        assert wait_for(lambda: _answers(base), 120), "the server did not start"
        assert wait_for(lambda: len(workers(server.pid)) == WORKERS, 120), "workers not up"
        assert post(base, "/api/analyze", CASE1)[0] == 200  # a worker is ready
        seen = set(descendants(server.pid))
        yield server, base
    finally:
        seen |= set(descendants(server.pid))
        if server.poll() is None:
            server.kill()
        server.wait(30)
        log.close()
        for pid in running(seen):  # a failed test leaves nothing behind
            os.kill(pid, signal.SIGKILL)


def _answers(base: str) -> bool:
    try:
        page_time(base)
    except OSError:
        return False
    return True


def test_hostile_bodies_get_4xx_in_time_and_a_design_past_the_limit_504_and_its_worker_killed(
    tmp_path: Path,
) -> None:
    with serving(tmp_path, LIMIT_S) as (server, base):
        # Hostile bodies: each refused within the time limit while the page keeps answering.
        bomb_design = copy.deepcopy(BLIMP_GRIPPER) | {
            "fold_style": "perforated",
            "cut": 1e-9,
            "gap": 1e-9,
        }
        tower_design = copy.deepcopy(BLIMP_GRIPPER)
        tower_design["constraints"]["side"]["min"] = "1 mm**9**9**9"
        hostile = [
            ("/api/analyze", TOWER, "W"),
            ("/api/mesh", TOWER, "W"),
            ("/api/pattern", TOWER, "W"),
            ("/api/pattern", PERFORATION_BOMB, "cut"),
            ("/api/design", tower_design, "constraints.side.min"),
            ("/api/design", bomb_design, "cut"),
        ]
        answers: list[tuple[str, int, Any, float]] = []

        def post_all() -> None:
            for _ in range(3):
                for route, body, _field in hostile:
                    start = time.monotonic()
                    status, answer = post(base, route, body)
                    answers.append((route, status, answer, time.monotonic() - start))

        poster = threading.Thread(target=post_all, daemon=True)
        poster.start()
        pages = []
        while poster.is_alive() or len(pages) < 5:
            pages.append(page_time(base))
        poster.join(60)
        assert max(pages) < 1, pages
        assert len(answers) == 3 * len(hostile)
        for (route, status, answer, seconds), (_, _, field) in zip(
            answers, hostile * 3, strict=True
        ):
            assert status == 422 and answer["field"] == field, (route, status, answer)
            assert seconds < LIMIT_S, (route, seconds)

        # A design past the limit: 504 naming it, its worker killed and replaced.
        before = workers(server.pid)
        assert len(before) == WORKERS
        start = time.monotonic()
        status, answer = post(base, "/api/design", slow_spec())
        assert status == 504, answer
        assert f"time limit of {LIMIT_S:g} s" in answer["detail"]
        assert time.monotonic() - start < LIMIT_S + 10
        assert wait_for(lambda: len(running(before)) == WORKERS - 1, 10), "the worker still runs"
        assert wait_for(lambda: len(workers(server.pid)) == WORKERS, 30), "no worker replaced it"
        status, answer = post(base, "/api/analyze", CASE1)
        assert status == 200 and answer == direct(CASE1)
        assert page_time(base) < 1


@pytest.mark.parametrize("how", [signal.SIGTERM, signal.SIGINT, signal.SIGKILL])
def test_no_worker_outlives_the_server(tmp_path: Path, how: signal.Signals) -> None:
    """A design in flight (it would run for minutes), then SIGTERM or SIGINT (Ctrl-C: the server
    stops its workers, the request gets 503) or SIGKILL (Linux kills the workers when their forkserver ends): in
    both cases every process the server started ends within seconds."""
    with serving(tmp_path, 600) as (server, base):
        answers: list[tuple[int, Any]] = []

        def design() -> None:
            try:
                answers.append(post(base, "/api/design", slow_spec(), timeout=60))
            except OSError as exc:  # SIGKILL: the connection goes
                answers.append((0, str(exc)))

        poster = threading.Thread(target=design, daemon=True)
        poster.start()
        busy = workers(server.pid)
        family = set(descendants(server.pid))
        assert len(busy) == WORKERS and busy <= family
        time.sleep(1.5)  # the design is computing
        server.send_signal(how)
        server.wait(30)
        assert wait_for(lambda: not running(family), 15), running(family)
        poster.join(30)
        if how != signal.SIGKILL:
            assert answers and answers[0][0] == 503, answers


def test_trickling_sockets_do_not_deny_service(tmp_path: Path) -> None:
    """120 sockets sending a request head a byte a second (uvicorn answered every other
    request 503 while 100 connections were open): ``GET /`` still answers 200 within a few
    seconds all along, and the server closes the trickling sockets at its head deadline."""
    with serving(tmp_path, LIMIT_S) as (_, base):
        port = int(base.rsplit(":", 1)[1])
        socks = []
        for _ in range(120):
            s = socket.create_connection(("127.0.0.1", port), timeout=5)
            s.sendall(b"GET / HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Slow: ")
            socks.append(s)
        stop = threading.Event()
        closed: set[int] = set()

        def trickle() -> None:
            while not stop.is_set():
                for i, s in enumerate(socks):
                    if i not in closed:
                        try:
                            s.sendall(b"a")
                        except OSError:
                            closed.add(i)
                stop.wait(1)

        trickler = threading.Thread(target=trickle, daemon=True)
        trickler.start()
        try:
            start = time.monotonic()
            times = []
            while time.monotonic() - start < 6:
                times.append(page_time(base))
                time.sleep(0.2)
            assert max(times) < 3, times
            # The head deadline closes them (408), a byte a second notwithstanding.
            late = time.monotonic() + HEAD_TIMEOUT_S + 10
            answered = 0
            for s in socks:
                s.settimeout(max(0.1, late - time.monotonic()))
                try:
                    data = s.recv(100)
                except OSError:
                    continue
                answered += data.startswith(b"HTTP/1.1 408")
            assert answered == len(socks)
        finally:
            stop.set()
            trickler.join(5)
            for s in socks:
                s.close()


@pytest.fixture
def quick_deadlines() -> Iterator[int]:
    """uvicorn in a thread with a 1 s head deadline and a 1 s body deadline; yields its port."""
    sock = socket.socket()
    sock.bind(("127.0.0.1", 0))
    port = int(sock.getsockname()[1])
    app = create_app(WebSettings(body_timeout_s=1.0, processes=1))
    config = uvicorn.Config(
        app, host="127.0.0.1", port=port, log_level="warning", http=slow_client_protocol(1.0)
    )
    server = uvicorn.Server(config)
    thread = threading.Thread(target=server.run, kwargs={"sockets": [sock]}, daemon=True)
    thread.start()
    try:
        assert wait_for(lambda: server.started, 60)
        yield port
    finally:
        server.should_exit = True
        thread.join(30)
        sock.close()


def _read_all(s: socket.socket, seconds: float) -> tuple[bytes, float]:
    """Everything the server sends until it closes (at most ``seconds``), and when it closed."""
    start = time.monotonic()
    s.settimeout(seconds)
    data = b""
    while True:
        chunk = s.recv(4096)
        if not chunk:
            return data, time.monotonic() - start
        data += chunk


def test_a_late_head_or_body_gets_408_and_the_connection_is_closed(quick_deadlines: int) -> None:
    port = quick_deadlines
    with socket.create_connection(("127.0.0.1", port)) as s:  # half a head
        s.sendall(b"GET / HTTP/1.1\r\nHost: 127.0.0.1\r\n")
        data, seconds = _read_all(s, 10)
        assert data.startswith(b"HTTP/1.1 408") and 0.5 < seconds < 5, (data, seconds)
    with socket.create_connection(("127.0.0.1", port)) as s:  # nothing at all
        data, seconds = _read_all(s, 10)
        assert data == b"" and seconds < 5
    with socket.create_connection(("127.0.0.1", port)) as s:  # a head, then part of the body
        body = json.dumps(CASE1).encode()
        s.sendall(
            b"POST /api/analyze HTTP/1.1\r\nHost: 127.0.0.1\r\n"
            b"Content-Type: application/json\r\nContent-Length: %d\r\n\r\n" % len(body) + body[:5]
        )
        data, seconds = _read_all(s, 10)
        assert data.startswith(b"HTTP/1.1 408") and seconds < 5, data
        assert b"did not arrive within 1 s" in data
    with socket.create_connection(("127.0.0.1", port)) as s:  # a whole request is answered
        s.sendall(b"GET /api/models HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n")
        data, _ = _read_all(s, 10)
        assert data.startswith(b"HTTP/1.1 200")
    with socket.create_connection(("127.0.0.1", port)) as s:  # kept alive, then idle
        s.sendall(b"GET /api/models HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n")
        data, seconds = _read_all(s, 10)
        assert data.startswith(b"HTTP/1.1 200") and data.count(b"HTTP/1.1") == 1
        assert seconds < 5  # closed at the next head's deadline
