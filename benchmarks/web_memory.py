"""Benchmark: the web server's resident memory (RSS) under a stream of design requests.

Run by hand: ``PYTHONPATH=src .venv/bin/python benchmarks/web_memory.py [REQUESTS] [CONCURRENCY]``
(default 200 requests, 2 at a time). Starts a real uvicorn server on a free port, measures its
RSS when idle, then posts ``REQUESTS`` design requests of a cheap spec (the blimp gripper on a
small grid: about a second of solving, every file written) and downloads one file of each, and
prints the RSS after every 10 requests, the peak and the growth. The bound the server keeps
(issue 12): RSS <= :data:`BOUND_MIB` per process (the server, and each design worker of its
process pool, one per core) after any number of requests (the result store keeps files on disk,
not in memory; freed memory is handed back to the system).
"""

from __future__ import annotations

import json
import os
import socket
import subprocess
import sys
import time
import tomllib
import urllib.request
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
BOUND_MIB = 400.0


def cheap_spec() -> dict[str, object]:
    spec = tomllib.loads((ROOT / "examples" / "blimp_gripper.toml").read_text())
    spec["variables"] = {
        "W": {"min": "8 mm", "max": "10 mm", "step": "1 mm"},
        "n": {"min": 6, "max": 10},
        "alpha": {"min": "60 deg", "max": "100 deg", "step": "1 deg"},
    }
    return spec


def rss_mib(pid: int) -> float:
    try:
        for line in Path(f"/proc/{pid}/status").read_text().splitlines():
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024
    except OSError:
        pass
    return 0.0


def descendants(pid: int) -> list[int]:
    """The processes started under ``pid`` (the design workers and their forkserver)."""
    out: list[int] = []
    try:
        tasks = list(Path(f"/proc/{pid}/task").iterdir())
    except OSError:
        return out
    for task in tasks:
        try:
            kids = [int(k) for k in (task / "children").read_text().split()]
        except OSError:
            continue
        for k in kids:
            out += [k, *descendants(k)]
    return out


def workers_mib(pid: int) -> tuple[float, float]:
    """(largest, total) RSS of the server's descendant processes, MiB."""
    sizes = [rss_mib(k) for k in descendants(pid)]
    return (max(sizes, default=0.0), sum(sizes))


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def post(url: str, body: dict[str, object]) -> dict[str, object]:
    req = urllib.request.Request(
        url, json.dumps(body).encode(), {"content-type": "application/json"}
    )
    with urllib.request.urlopen(req, timeout=600) as r:
        return json.loads(r.read())  # type: ignore[no-any-return]


def main() -> None:
    requests = int(sys.argv[1]) if len(sys.argv) > 1 else 200
    concurrency = int(sys.argv[2]) if len(sys.argv) > 2 else 2
    port = free_port()
    code = (
        "import uvicorn; from corrugate.web import WebSettings, create_app; "
        f"uvicorn.run(create_app(WebSettings(timeout_s=3600)), host='127.0.0.1', port={port}, "
        "log_level='warning')"
    )
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src")}
    server = subprocess.Popen([sys.executable, "-c", code], env=env)
    base = f"http://127.0.0.1:{port}"
    try:
        for _ in range(300):
            try:
                urllib.request.urlopen(base + "/api/models", timeout=2).read()
                break
            except OSError:
                time.sleep(0.1)
        idle = rss_mib(server.pid)
        print(f"idle RSS {idle:.0f} MiB")
        spec = cheap_spec()
        t0 = time.monotonic()
        peak = idle
        worker_peak = 0.0
        done = 0

        errors = 0

        def one(_: int) -> int:
            nonlocal errors
            try:
                answer = post(base + "/api/design", spec)
            except OSError as exc:  # HTTPError included: counted, the run goes on
                errors += 1
                print(f"error: {exc}", flush=True)
                return 0
            files_url = answer.get("files_url")
            if isinstance(files_url, str):  # answers first: the files made on demand
                answer = {**answer, "result": post(base + files_url, {})}
            result = answer.get("result")
            if isinstance(result, dict):
                url = result["files"][0]["url"]  # type: ignore[index]
                urllib.request.urlopen(base + url, timeout=60).read()
            return 1

        with ThreadPoolExecutor(concurrency) as ex:
            for _ in ex.map(one, range(requests)):
                done += 1
                rss = rss_mib(server.pid)
                peak = max(peak, rss)
                largest, total = workers_mib(server.pid)
                worker_peak = max(worker_peak, largest)
                if done % 10 == 0 or done == requests:
                    print(
                        f"{done:4d} requests  server RSS {rss:6.0f} MiB  peak {peak:6.0f} MiB  "
                        f"workers: largest {largest:5.0f} MiB, all {total:5.0f} MiB  "
                        f"{time.monotonic() - t0:6.0f} s",
                        flush=True,
                    )
        final = rss_mib(server.pid)
        largest, total = workers_mib(server.pid)
        ok = peak <= BOUND_MIB and worker_peak <= BOUND_MIB
        print(
            f"after {requests} design requests ({errors} errors): server RSS {final:.0f} MiB "
            f"(idle {idle:.0f}, peak {peak:.0f}); design workers: largest {largest:.0f} MiB now, "
            f"{worker_peak:.0f} at most, all {total:.0f}; bound {BOUND_MIB:.0f} MiB per process: "
            f"{'within' if ok else 'EXCEEDED'}"
        )
    finally:
        server.terminate()
        server.wait(10)


if __name__ == "__main__":
    main()
