"""The job queue cannot starve the page (issue 37, item 2), on ``corrugate serve`` in a child
process:

* two design jobs at the largest budget run and 50 short ones are submitted: those past the
  queue's bound get 503 with ``Retry-After`` at once, the others are queued, none fails busy,
  and ``POST /api/analyze`` answers within 2 s all along (the quick lane);
* no CalculiX work folder outlives its job: a cancel, a worker killed with SIGKILL, the job's time
  limit, the server's shutdown (CalculiX stubbed by a program that sleeps), and those left by a
  killed server are swept at the next start;
* a connection that sends part of a request head is closed at the head deadline, however many
  there are, even when the server may open fewer files than that (the defect: a server out of
  file descriptors stops accepting, and a connection waiting to be accepted is under no
  deadline).
"""

from __future__ import annotations

import asyncio
import json
import os
import resource
import signal
import socket
import subprocess
import sys
import time
import tomllib
import urllib.error
import urllib.request
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import pytest

from corrugate.cli.serve import HEAD_TIMEOUT_S
from corrugate.fea.workdirs import owner
from corrugate.web.jobs import QUEUE_RETRY_AFTER_S, JobTable
from corrugate.web.workers import ComputeTimeoutError, Runner, ServerBusyError, Share

from .conftest import CASE1, direct
from .test_server import WORKERS, descendants, free_port, running, slow_spec, wait_for, workers

ROOT = Path(__file__).resolve().parents[2]

pytestmark = pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="reads /proc")


def call(
    base: str, path: str, body: Any = None, method: str = "POST", timeout: float = 60
) -> tuple[int, Any, dict[str, str]]:
    """A request to a served app: its status, JSON answer and headers (errors included)."""
    data = None if body is None else json.dumps(body).encode()
    request = urllib.request.Request(
        base + path, data=data, headers={"content-type": "application/json"}, method=method
    )
    try:
        with urllib.request.urlopen(request, timeout=timeout) as r:
            return r.status, json.loads(r.read()), {k.lower(): v for k, v in r.headers.items()}
    except urllib.error.HTTPError as exc:
        return exc.code, json.loads(exc.read()), {k.lower(): v for k, v in exc.headers.items()}


def _answers(base: str) -> bool:
    try:
        with urllib.request.urlopen(base + "/", timeout=5) as r:
            return r.status == 200
    except OSError:
        return False


@contextmanager
def serving(
    tmp_path: Path, *options: str, env: dict[str, str] | None = None, files: int | None = None
) -> Iterator[tuple[subprocess.Popen[bytes], str]]:
    """``corrugate serve OPTIONS`` on a free port with ``env`` added to its environment and at
    most ``files`` open files (``RLIMIT_NOFILE``, soft and hard); its workers up. Killed, with
    every process it started, at the end."""
    port = free_port()
    log = (tmp_path / f"serve-{port}.log").open("wb")

    def limit() -> None:
        if files is not None:
            resource.setrlimit(resource.RLIMIT_NOFILE, (files, files))

    server = subprocess.Popen(
        [sys.executable, "-m", "corrugate", "serve", "--port", str(port), *options],
        stdout=log,
        stderr=subprocess.STDOUT,
        env={**os.environ, "PYTHONPATH": str(ROOT / "src"), **(env or {})},
        preexec_fn=limit,
    )
    base = f"http://127.0.0.1:{port}"
    seen: set[int] = set()
    try:
        assert wait_for(lambda: _answers(base), 120), "the server did not start"
        assert wait_for(lambda: len(workers(server.pid)) == WORKERS, 120), "workers not up"
        assert call(base, "/api/analyze", CASE1)[0] == 200
        seen = set(descendants(server.pid))
        yield server, base
    finally:
        seen |= set(descendants(server.pid))
        if server.poll() is None:
            server.kill()
        server.wait(30)
        log.close()
        for pid in running(seen):
            os.kill(pid, signal.SIGKILL)


def blimp() -> dict[str, Any]:
    with (ROOT / "examples" / "blimp_gripper.toml").open("rb") as f:
        return tomllib.load(f)


def status_of(base: str, job_id: str) -> str:
    return str(call(base, f"/api/jobs/{job_id}", method="GET")[1]["status"])


@pytest.mark.slow  # a served app with its workers, two minutes-long searches
def test_two_long_jobs_and_fifty_queued_do_not_starve_analyze(tmp_path: Path) -> None:
    queued = 40
    with serving(tmp_path, "--max-queued-jobs", str(queued)) as (_, base):
        # two jobs at the largest budget a client may ask (600 CPU s: 2400 s of wall) ...
        long_jobs = []
        for _ in range(2):
            status, job, _ = call(base, "/api/jobs/design?budget=600", slow_spec())
            assert status == 202 and job["limits"]["time_limit_s"] == 2400, job
            long_jobs.append(job["id"])
        assert wait_for(lambda: all(status_of(base, j) == "running" for j in long_jobs), 60)
        # ... a larger budget is refused at once, naming it and the range
        status, answer, _ = call(base, "/api/jobs/design?budget=601", blimp())
        assert status == 422 and answer["field"] == "budget" and "<= 600" in answer["detail"]
        # 50 short ones: the queue takes `queued`, the rest are refused at once, never accepted
        short, refused = [], []
        for _ in range(50):
            status, job, headers = call(base, "/api/jobs/design?budget=3", blimp())
            if status == 202:
                assert job["status"] == "queued"
                short.append(job["id"])
            else:
                refused.append((status, job, headers))
        assert len(short) == queued and len(refused) == 50 - queued
        for status, answer, headers in refused:
            assert status == 503 and "queue is full" in answer["detail"], answer
            assert headers["retry-after"] == str(QUEUE_RETRY_AFTER_S)
        # the quick lane answers while both job workers are busy and 40 jobs wait
        for _ in range(3):
            start = time.monotonic()
            status, answer, _ = call(base, "/api/analyze", CASE1, timeout=30)
            assert status == 200 and answer == direct(CASE1)
            assert time.monotonic() - start < 2.0
        states = [status_of(base, j) for j in long_jobs + short]
        assert states == ["running"] * 2 + ["queued"] * queued, states
        # the long ones cancelled: queued jobs take their workers, none fails busy
        for job_id in long_jobs:
            assert call(base, f"/api/jobs/{job_id}", method="DELETE")[1]["status"] == "cancelled"
        assert wait_for(lambda: status_of(base, short[0]) in ("running", "done"), 60)
        for job_id in short:
            state = call(base, f"/api/jobs/{job_id}", method="DELETE")[1]
            assert state["status"] in ("cancelled", "done"), state
        status, job, _ = call(base, "/api/jobs/design?budget=3", blimp())
        assert status == 202  # room again


def test_the_queue_counts_a_cancelled_job_until_its_task_ends() -> None:
    """A cancelled job still holds its runner slot while its worker is killed: the table does
    not admit another in its place before that (else the runner would refuse it, busy)."""

    async def scenario() -> None:
        table = JobTable(max_jobs=10, ttl_s=3600, max_active=2)
        release = asyncio.Event()
        a, b = table.new("design", {}), table.new("design", {})
        a.task = asyncio.get_running_loop().create_task(release.wait())
        b.task = asyncio.get_running_loop().create_task(release.wait())
        with pytest.raises(ServerBusyError) as info:
            table.new("design", {})
        assert info.value.retry_after_s == QUEUE_RETRY_AFTER_S
        a.end("cancelled")  # finished, but its task still runs
        with pytest.raises(ServerBusyError):
            table.check_room()
        release.set()
        await asyncio.sleep(0.01)
        table.new("design", {})  # its task ended: room for one

    asyncio.run(scenario())


def test_a_share_keeps_its_kind_to_its_workers_and_refuses_past_its_queue() -> None:
    async def scenario() -> None:
        share = Share(limit=1, max_waiting=1)
        order: list[str] = []
        gate = asyncio.Event()

        async def one(name: str) -> None:
            async with share.turn():
                order.append(f"{name} in")
                await gate.wait()
                order.append(f"{name} out")

        first = asyncio.create_task(one("a"))
        await asyncio.sleep(0.01)
        second = asyncio.create_task(one("b"))
        await asyncio.sleep(0.01)
        assert order == ["a in"]  # one at a time
        with pytest.raises(ServerBusyError):
            async with share.turn():
                pass
        gate.set()
        await asyncio.gather(first, second)
        assert order == ["a in", "a out", "b in", "b out"]

    asyncio.run(scenario())


@pytest.mark.slow  # starts two worker processes
def test_a_worker_past_its_time_limit_and_at_shutdown_is_swept(tmp_path: Path) -> None:
    """A runner whose workers each own a work folder (named with the worker's pid, as a
    verification's CalculiX folders are): the worker killed at a job's time limit has its
    folder swept once it has ended, the other's stays; at shutdown the other's goes too."""
    from corrugate.fea.workdirs import sweep_owned

    reaped: list[int] = []

    def reap(pid: int) -> None:  # runs in the runner's reaping thread: sweep, then tell
        sweep_owned(pid, tmp_path)
        reaped.append(pid)

    runner = Runner(4, 60.0, processes=2, reap=reap)
    runner.start_processes()
    try:
        assert wait_for(lambda: len(runner.worker_pids()) == 2, 120)
        pids = set(runner.worker_pids())
        folders = {pid: tmp_path / f"corrugate-ccx-{pid}-abc" for pid in pids}
        for folder in folders.values():
            folder.mkdir()
        with pytest.raises(ComputeTimeoutError):
            asyncio.run(runner.run(time.sleep, 30, timeout_s=0.5))
        assert wait_for(lambda: len(reaped) == 1, 20)
        (killed,) = reaped
        assert killed in pids and not folders[killed].exists()
        (other,) = pids - {killed}
        assert folders[other].exists()
    finally:
        runner.shutdown()
    assert not folders[other].exists() and other in reaped


def _stub_ccx(tmp_path: Path) -> Path:
    stub = tmp_path / "ccx"
    stub.write_text("#!/bin/sh\nexec sleep 120\n")
    stub.chmod(0o755)
    return stub


def _ccx_folders(tmp: Path) -> list[Path]:
    return sorted(tmp.glob("corrugate-ccx-*"))


def _verify(base: str, result: str, tmp: Path, before: set[Path]) -> tuple[str, Path]:
    """Start a verification of ``result``; its id and its CalculiX work folder once made."""
    status, job, _ = call(base, "/api/jobs/verify", {"result": result, "mesh": "2"})
    assert status == 202, job
    found: list[Path] = []
    assert wait_for(lambda: bool(found.extend(set(_ccx_folders(tmp)) - before) or found), 120)
    (folder,) = found
    return job["id"], folder


@pytest.mark.slow  # a served app with its workers, one design
def test_no_calculix_folder_outlives_its_job(tmp_path: Path) -> None:
    tmp = tmp_path / "tmp"
    tmp.mkdir()
    # left by a server killed during a verification (its owner ended), a folder kept on
    # purpose (no owner in its name) and one of a process that runs (this test's)
    ended = subprocess.Popen([sys.executable, "-c", "pass"])
    ended.wait()
    stale = tmp / f"corrugate-ccx-{ended.pid}-left"
    kept = tmp / "corrugate-ccx-kept1234"
    live = tmp / f"corrugate-ccx-{os.getpid()}-live"
    for folder in (stale, kept, live):
        folder.mkdir()
        (folder / "job.inp").write_text("*NODE\n")
    env = {"TMPDIR": str(tmp), "CORRUGATE_CCX": str(_stub_ccx(tmp_path))}
    with serving(tmp_path, env=env) as (server, base):
        assert not stale.exists() and kept.exists() and live.exists()  # swept at start-up
        before = {kept, live}
        status, answer, _ = call(base, "/api/design", blimp(), timeout=120)
        assert status == 200, answer
        status, made, _ = call(base, answer["files_url"], {}, timeout=120)  # made on demand
        assert status == 200, made
        result = made["id"]
        # cancelled: its worker (and CalculiX) killed, its folder swept
        job, folder = _verify(base, result, tmp, before)
        assert owner(folder) in workers(server.pid)
        assert call(base, f"/api/jobs/{job}", method="DELETE")[1]["status"] == "cancelled"
        assert wait_for(lambda: not folder.exists(), 15), "a cancelled job's folder is left"
        # its worker killed from outside: the job fails (503), its folder is swept
        job, folder = _verify(base, result, tmp, before)
        pid = owner(folder)
        assert pid is not None
        os.kill(pid, signal.SIGKILL)
        assert wait_for(lambda: status_of(base, job) == "failed", 30)
        assert call(base, f"/api/jobs/{job}", method="GET")[1]["error"]["status"] == 503
        assert wait_for(lambda: not folder.exists(), 15), "a killed worker's folder is left"
        # the server stopped (SIGTERM) during a verification: nothing of it is left
        job, folder = _verify(base, result, tmp, before)
        server.send_signal(signal.SIGTERM)
        server.wait(30)
        assert not folder.exists()
    assert set(_ccx_folders(tmp)) == {kept, live}


@pytest.mark.slow  # a served app with its workers, 10 s of head deadline
def test_partial_heads_are_closed_at_the_deadline_even_past_the_open_file_limit(
    tmp_path: Path,
) -> None:
    """300 connections each send ``GET / HTTP/1.1`` and a Host line, never the blank line, to a
    server that may open 256 files: every one is closed within the head deadline (and a second
    of slack) of its opening; then the page answers."""
    with serving(tmp_path, files=256) as (_, base):
        port = int(base.rsplit(":", 1)[1])
        opened: list[tuple[socket.socket, float]] = []
        try:
            for _ in range(300):
                s = socket.create_connection(("127.0.0.1", port), timeout=5)
                s.sendall(b"GET / HTTP/1.1\r\nHost: x\r\n")
                opened.append((s, time.monotonic()))
            late = []
            for s, start in opened:
                s.settimeout(max(0.1, start + HEAD_TIMEOUT_S + 1 - time.monotonic()))
                try:
                    while s.recv(4096):
                        pass
                except TimeoutError:
                    late.append(s)
                except OSError:  # reset: closed too
                    pass
            assert not late, f"{len(late)} of {len(opened)} still open past the deadline"
        finally:
            for s, _ in opened:
                s.close()
        assert _answers(base)


def test_serve_refuses_a_default_job_budget_past_the_cap_in_one_line(
    capsys: pytest.CaptureFixture[str],
) -> None:
    from corrugate.cli import main

    for args, words in (
        (["--job-budget", "700"], ("--job-budget", "700", "--max-job-budget (600 s)")),
        (["--job-budget", "50", "--max-job-budget", "40"], ("--job-budget", "at most", "40 s")),
        (["--max-job-budget", "0"], ("--max-job-budget",)),
    ):
        with pytest.raises(SystemExit) as info:
            main(["serve", *args])
        assert info.value.code == 2
        lines = capsys.readouterr().err.strip().splitlines()
        assert len(lines) == 1 and all(w in lines[0] for w in words), lines
