"""Design requests per second of the web app with 1 and with 4 clients.

Run by hand (a few minutes on 2 cores)::

    .venv/bin/python benchmarks/web_throughput.py [--requests 4] [--processes N]

It starts ``uvicorn`` with the app (:func:`corrugate.web.create_app`) in a child process on a free
port of 127.0.0.1, waits until it answers, sends one design to warm it up, then posts
``examples/blimp_gripper.toml`` as JSON to ``/api/design`` from 1 client (``--requests`` designs one
after another) and from 4 clients at once (``--requests`` designs each), and prints the designs per
second of each, their ratio, and how many cores the server (with its worker processes) kept busy
meanwhile: its CPU seconds per wall second, which shows what a shared, loaded machine left it. ``--jobs`` runs
each design through the job API instead (``POST /api/jobs/design``, then its server-sent events until
it ends). ``--processes`` is the app's pool of worker processes
(default: one per core, at least 2), which run every computation.

Every answer must be 200 with a certified optimum and files; anything else stops the run.

Reading the numbers: designs per second = (cores the server kept busy) / (CPU seconds of one
design, about 6 s for this spec). The ratio of 4 clients to 1 shows the pool only when the server
can get more than one core. On a shared Linux machine with ``kernel.sched_autogroup_enabled = 1``
each session gets an equal share of the CPU however many processes it runs, so while other
sessions are busy the server's share stays well under one core and the ratio stays near 1; the
"busy on N cores" column says so.
"""

from __future__ import annotations

import argparse
import json
import os
import socket
import subprocess
import sys
import threading
import time
import tomllib
import urllib.request
from pathlib import Path

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
SPEC = EXAMPLES / "blimp_gripper.toml"

#: The server, run as ``python -c``: the app with the requested design pool, on the given port.
SERVER = """
import sys
import uvicorn
from corrugate.web import WebSettings, create_app
processes = None if sys.argv[2] == "default" else int(sys.argv[2])
settings = WebSettings(processes=processes, timeout_s=600.0, max_pending=64)
uvicorn.run(create_app(settings), host="127.0.0.1", port=int(sys.argv[1]), log_level="warning")
"""


def free_port() -> int:
    """A TCP port of 127.0.0.1 that nothing listens on (just now)."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def post_design(base: str, body: bytes) -> float:
    """Post one design; the seconds it took. Fails unless it is a certified optimum with files."""
    request = urllib.request.Request(
        f"{base}/api/design", data=body, headers={"content-type": "application/json"}
    )
    start = time.perf_counter()
    with urllib.request.urlopen(request, timeout=900) as response:
        answer = json.loads(response.read())
        status = response.status
    took = time.perf_counter() - start
    design = answer["design"]
    if status != 200 or design["status"] != "optimal" or not answer["result"]["files"]:
        raise RuntimeError(f"unexpected answer: {status} {design['status']}")
    return took


def post_design_job(base: str, body: bytes) -> float:
    """Run one design as a job (``POST /api/jobs/design``, then its server-sent events until the
    job ends); the seconds it took. Fails unless it is a certified optimum with files."""
    request = urllib.request.Request(
        f"{base}/api/jobs/design", data=body, headers={"content-type": "application/json"}
    )
    start = time.perf_counter()
    with urllib.request.urlopen(request, timeout=900) as response:
        job = json.loads(response.read())
        if response.status != 202:
            raise RuntimeError(f"unexpected answer: {response.status}")
    final: dict[str, object] | None = None
    kind = ""
    with urllib.request.urlopen(f"{base}{job['links']['events']}", timeout=900) as stream:
        for raw in stream:
            line = raw.decode().rstrip("\r\n")
            if line.startswith("event: "):
                kind = line[7:]
            elif line.startswith("data: ") and kind in ("done", "failed", "cancelled"):
                final = json.loads(line[6:])
    took = time.perf_counter() - start
    answer = final.get("result") if final else None
    if not isinstance(answer, dict) or answer["design"]["status"] != "optimal":
        raise RuntimeError(f"unexpected end of the job: {kind} {final}")
    if not answer["result"]["files"]:
        raise RuntimeError("the job's design has no files")
    return took


def wait_until_up(base: str, server: subprocess.Popen[bytes], seconds: float = 120.0) -> None:
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        if server.poll() is not None:
            raise RuntimeError(f"the server exited with code {server.returncode}")
        try:
            with urllib.request.urlopen(f"{base}/api/models", timeout=5) as r:
                if r.status == 200:
                    return
        except OSError:
            time.sleep(0.2)
    raise RuntimeError("the server did not start")


def tree_cpu_seconds(root: int) -> float | None:
    """CPU seconds (user + system) used so far by process ``root`` and all its descendants (the
    server, the forkserver and the design workers); None where /proc is missing."""
    proc = Path("/proc")
    if not proc.is_dir():
        return None
    parent: dict[int, int] = {}
    ticks: dict[int, int] = {}
    for entry in proc.iterdir():
        if not entry.name.isdigit():
            continue
        try:
            text = (entry / "stat").read_text()
        except OSError:
            continue
        fields = text[text.rindex(")") + 2 :].split()
        pid = int(entry.name)
        parent[pid] = int(fields[1])
        ticks[pid] = int(fields[11]) + int(fields[12])
    total = 0
    for pid in ticks:
        p = pid
        while p > 1 and p != root:
            p = parent.get(p, 0)
        if p == root:
            total += ticks[pid]
    return total / os.sysconf("SC_CLK_TCK")


def throughput(
    base: str, body: bytes, clients: int, per_client: int, server: int, jobs: bool = False
) -> tuple[float, float, float | None]:
    """Designs per second with ``clients`` clients sending ``per_client`` designs each, the
    median seconds of one request, and the server's CPU seconds per wall second meanwhile (how
    many cores it kept busy; None without /proc)."""
    times: list[float] = []
    errors: list[BaseException] = []
    lock = threading.Lock()

    def client() -> None:
        try:
            for _ in range(per_client):
                took = (post_design_job if jobs else post_design)(base, body)
                with lock:
                    times.append(took)
        except BaseException as exc:  # reported below
            errors.append(exc)

    threads = [threading.Thread(target=client) for _ in range(clients)]
    cpu0 = tree_cpu_seconds(server)
    start = time.perf_counter()
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    elapsed = time.perf_counter() - start
    cpu1 = tree_cpu_seconds(server)
    if errors:
        raise errors[0]
    times.sort()
    busy = None if cpu0 is None or cpu1 is None else (cpu1 - cpu0) / elapsed
    return len(times) / elapsed, times[len(times) // 2], busy


def measure(processes: str, per_client: int, jobs: bool = False) -> dict[int, float]:
    """Start a server with design pool ``processes``; designs per second by number of clients."""
    port = free_port()
    base = f"http://127.0.0.1:{port}"
    env = dict(os.environ)
    src = str(Path(__file__).resolve().parents[1] / "src")
    env["PYTHONPATH"] = src + os.pathsep + env.get("PYTHONPATH", "")
    server = subprocess.Popen([sys.executable, "-c", SERVER, str(port), processes], env=env)
    try:
        wait_until_up(base, server)
        with SPEC.open("rb") as f:
            body = json.dumps(tomllib.load(f)).encode()
        warm = [threading.Thread(target=post_design, args=(base, body)) for _ in range(2)]
        for t in warm:  # both workers (or threads) have made one design before timing
            t.start()
        for t in warm:
            t.join()
        rates: dict[int, float] = {}
        for clients in (1, 4):
            rate, median, busy = throughput(base, body, clients, per_client, server.pid, jobs)
            rates[clients] = rate
            cores = "" if busy is None else f", server busy on {busy:.2f} cores"
            print(
                f"design pool {processes:>7}: {clients} client(s) x {per_client} designs: "
                f"{rate:.3f} designs/s (median request {median:.2f} s{cores})",
                flush=True,
            )
        print(f"design pool {processes:>7}: 4 clients / 1 client = {rates[4] / rates[1]:.2f}")
        return rates
    finally:
        server.terminate()
        server.wait(timeout=60)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--requests", type=int, default=4, help="Designs per client.")
    parser.add_argument(
        "--processes",
        default="default",
        help="Worker processes (default: one per core, at least 2).",
    )
    parser.add_argument(
        "--jobs",
        action="store_true",
        help="Run each design as a job (POST /api/jobs/design, then its event stream).",
    )
    args = parser.parse_args()
    route = "/api/jobs/design (jobs, followed to their end)" if args.jobs else "/api/design"
    print(f"{os.cpu_count()} cores; {SPEC.name} posted to {route}")
    measure(args.processes, args.requests, args.jobs)


if __name__ == "__main__":
    main()
