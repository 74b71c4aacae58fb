"""Design requests per second of the web app with 4 and 16 concurrent clients, each request a
different spec; this tree beside another (``--base main``) in one interleaved run.

Run by hand (a few minutes on 2 cores)::

    .venv/bin/python benchmarks/web_throughput.py --base main [--clients 4,16] [--requests 4]
        [--rounds 1] [--files] [--processes N] [--jobs]

It starts ``uvicorn`` with the app (:func:`corrugate.web.create_app`) of this tree, and with
``--base REF`` that of ``git archive REF`` unpacked into a temporary folder, each in a child
process on a free port of 127.0.0.1 (``PYTHONPATH`` the tree's ``src``), waits until they answer
and sends two designs to each to warm them up. Then, for each round and each number of clients,
it measures the base tree and this one one after the other (so a change in the machine's load
touches both): every client posts ``--requests`` designs to ``/api/design``, one after another,
each a different spec: ``examples/blimp_gripper.toml`` with its flexural-rigidity bound varied
(60 to 100 mN*m^2, a new value for every request of the run), so that no cache can answer one.

For each it prints the designs per second, the median and 95th-percentile seconds of one
request, how many cores the server (with its worker processes) kept busy meanwhile (its CPU
seconds per wall second: what a shared, loaded machine left it) and its CPU seconds per design,
of which the server's own process (the event loop: HTTP, validation, JSON) and the solver
(search and explanation, the answers' ``solver.budget.used_cpu_seconds``).
Designs per second = cores busy / CPU seconds per design: on a loaded machine the first is what
the machine gave, the second what the code costs.

A tree whose ``/api/design`` answers first (its answer has ``files_url``, the files made on
demand) is timed on the answer alone; with ``--files`` each client then also asks for the
design's files (``POST files_url``), the page's whole flow, so that it compares with a tree that
writes them in the request. ``--jobs`` runs each design through the job API instead (``POST
/api/jobs/design``, then its server-sent events until it ends). ``--processes`` is the app's job
pool (default: one per core, at least 2); ``/api/design`` runs in the quick lane of two workers,
of which designs hold one at a time (docs/web.md).

Every answer must be 200 with a certified optimum (and files, or a ``files_url``); anything
else stops the run.
"""

from __future__ import annotations

import argparse
import contextlib
import copy
import itertools
import json
import os
import socket
import subprocess
import sys
import tempfile
import threading
import time
import tomllib
import urllib.request
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SPEC = ROOT / "examples" / "blimp_gripper.toml"

#: The server, run as ``python -c``: the app with the requested job pool, on the given port.
SERVER = """
import sys
import uvicorn
from corrugate.web import WebSettings, create_app
processes = None if sys.argv[2] == "default" else int(sys.argv[2])
settings = WebSettings(processes=processes, timeout_s=600.0, max_pending=64)
uvicorn.run(create_app(settings), host="127.0.0.1", port=int(sys.argv[1]), log_level="warning")
"""

#: A new flexural-rigidity bound (mN*m^2) for every request of a run: 60 to 100, none repeated
#: within 292 requests (0.137 * 292 > 40).
_BOUNDS = (60.0 + (0.137 * i) % 40.0 for i in itertools.count())
_BOUNDS_LOCK = threading.Lock()


def next_body() -> bytes:
    """The blimp gripper's spec as JSON with the next flexural-rigidity bound."""
    with SPEC.open("rb") as f:
        spec = tomllib.load(f)
    with _BOUNDS_LOCK:
        bound = next(_BOUNDS)
    spec = copy.deepcopy(spec)
    spec["constraints"]["flexural_rigidity"][0]["min"] = f"{bound:.4f} mN*m^2"
    return json.dumps(spec).encode()


def free_port() -> int:
    """A TCP port of 127.0.0.1 that nothing listens on (just now)."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def _post(url: str, body: bytes | None) -> tuple[int, dict[str, object]]:
    request = urllib.request.Request(
        url, data=body or b"", headers={"content-type": "application/json"}, method="POST"
    )
    with urllib.request.urlopen(request, timeout=900) as response:
        return response.status, json.loads(response.read())


def check_answer(answer: dict[str, object], status: int, base: str, files: bool) -> float:
    """Fail unless the answer is a certified optimum with files (or where to make them, then
    made when ``files``); the solver's CPU seconds (search and explanation: the answer's
    ``solver.budget.used_cpu_seconds``)."""
    design = answer["design"]
    assert isinstance(design, dict)
    if status != 200 or design["status"] != "optimal":
        raise RuntimeError(f"unexpected answer: {status} {design['status']}")
    solver = float(design["solver"]["budget"]["used_cpu_seconds"])
    url = answer.get("files_url")
    if isinstance(url, str):
        if files:
            code, made = _post(base + url, None)
            if code != 200 or not made.get("files"):
                raise RuntimeError(f"unexpected files: {code} {made}")
        return solver
    result = answer.get("result")
    if not isinstance(result, dict) or not result["files"]:
        raise RuntimeError("the design has no files")
    return solver


def post_design(base: str, files: bool) -> tuple[float, float]:
    """Post one design (a new spec); the seconds it took (its files' too with ``files``) and
    its solver's CPU seconds."""
    start = time.perf_counter()
    status, answer = _post(f"{base}/api/design", next_body())
    solver = check_answer(answer, status, base, files)
    return time.perf_counter() - start, solver


def post_design_job(base: str, files: bool) -> tuple[float, float]:
    """Run one design (a new spec) as a job (``POST /api/jobs/design``, then its server-sent
    events until the job ends); the seconds it took and its solver's CPU seconds."""
    start = time.perf_counter()
    status, job = _post(f"{base}/api/jobs/design", next_body())
    if status != 202:
        raise RuntimeError(f"unexpected answer: {status}")
    final: dict[str, object] | None = None
    kind = ""
    links = job["links"]
    assert isinstance(links, dict)
    with urllib.request.urlopen(f"{base}{links['events']}", timeout=900) as stream:
        for raw in stream:
            line = raw.decode().rstrip("\r\n")
            if line.startswith("event: "):
                kind = line[7:]
            elif line.startswith("data: ") and kind in ("done", "failed", "cancelled"):
                final = json.loads(line[6:])
    answer = final.get("result") if final else None
    if not isinstance(answer, dict):
        raise RuntimeError(f"unexpected end of the job: {kind} {final}")
    solver = check_answer(answer, 200, base, files)
    return time.perf_counter() - start, solver


def wait_until_up(base: str, server: subprocess.Popen[bytes], seconds: float = 180.0) -> None:
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


def tree_cpu_seconds(root: int) -> tuple[float, float] | None:
    """CPU seconds (user + system) used so far by process ``root`` and all its descendants (the
    server, the forkserver and the worker processes), and by ``root`` alone (the server's event
    loop: HTTP, validation, JSON); None where /proc is missing."""
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
    tick = os.sysconf("SC_CLK_TCK")
    return total / tick, ticks.get(root, 0) / tick


@dataclass(frozen=True)
class Measured:
    """One measurement: designs per second, median and 95th-percentile request seconds, the
    server's CPU seconds per wall second (None without /proc) and per design, of which its own
    process (the event loop) and the solver (the answers' own count)."""

    rate: float
    median_s: float
    p95_s: float
    busy: float | None
    cpu_per_design_s: float | None
    server_per_design_s: float | None
    solver_per_design_s: float


def percentile(values: list[float], q: float) -> float:
    """The ``q`` quantile (0..1) of ``values``, interpolated linearly between order statistics."""
    ordered = sorted(values)
    pos = q * (len(ordered) - 1)
    lo = int(pos)
    hi = min(lo + 1, len(ordered) - 1)
    return ordered[lo] + (ordered[hi] - ordered[lo]) * (pos - lo)


def throughput(
    base: str, clients: int, per_client: int, server: int, jobs: bool, files: bool
) -> Measured:
    """``clients`` clients sending ``per_client`` designs each (every one a new spec)."""
    times: list[float] = []
    solver: list[float] = []
    errors: list[BaseException] = []
    lock = threading.Lock()
    send = post_design_job if jobs else post_design

    def client() -> None:
        try:
            for _ in range(per_client):
                took, cpu = send(base, files)
                with lock:
                    times.append(took)
                    solver.append(cpu)
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
    cpu = None if cpu0 is None or cpu1 is None else cpu1[0] - cpu0[0]
    own = None if cpu0 is None or cpu1 is None else cpu1[1] - cpu0[1]
    return Measured(
        len(times) / elapsed,
        percentile(times, 0.5),
        percentile(times, 0.95),
        None if cpu is None else cpu / elapsed,
        None if cpu is None else cpu / len(times),
        None if own is None else own / len(times),
        sum(solver) / len(solver),
    )


@contextlib.contextmanager
def served(src: Path, processes: str) -> Iterator[tuple[str, int]]:
    """A server of the tree whose package is in ``src``: its base URL and pid."""
    port = free_port()
    base = f"http://127.0.0.1:{port}"
    env = dict(os.environ)
    env["PYTHONPATH"] = str(src) + os.pathsep + env.get("PYTHONPATH", "")
    server = subprocess.Popen([sys.executable, "-c", SERVER, str(port), processes], env=env)
    try:
        wait_until_up(base, server)
        yield base, server.pid
    finally:
        server.terminate()
        server.wait(timeout=60)


@contextlib.contextmanager
def archived(ref: str) -> Iterator[Path]:
    """``git archive ref`` of this repository unpacked into a temporary folder: its ``src``."""
    with tempfile.TemporaryDirectory(prefix="corrugate-base-") as tmp:
        archive = subprocess.run(
            ["git", "-C", str(ROOT), "archive", ref], check=True, capture_output=True
        ).stdout
        subprocess.run(["tar", "-x", "-C", tmp], input=archive, check=True)
        yield Path(tmp) / "src"


def warm(base: str, files: bool) -> None:
    """Two designs at once, so that both workers of the quick lane have made one."""
    threads = [threading.Thread(target=post_design, args=(base, files)) for _ in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--base", help="A git ref (e.g. main) measured beside this tree.")
    parser.add_argument("--clients", default="4,16", help="Numbers of concurrent clients.")
    parser.add_argument("--requests", type=int, default=4, help="Designs per client.")
    parser.add_argument("--rounds", type=int, default=1, help="Interleaved rounds.")
    parser.add_argument(
        "--files",
        action="store_true",
        help="Also fetch each design's files where the answer comes first (the page's flow).",
    )
    parser.add_argument(
        "--processes", default="default", help="Job pool (default: one per core, at least 2)."
    )
    parser.add_argument(
        "--jobs",
        action="store_true",
        help="Run each design as a job (POST /api/jobs/design, then its event stream).",
    )
    args = parser.parse_args()
    clients = [int(c) for c in args.clients.split(",")]
    route = "/api/jobs/design (jobs, followed to their end)" if args.jobs else "/api/design"
    files = " and its files" if args.files else ""
    print(f"{os.cpu_count()} cores; {SPEC.name} (a new EI bound each) posted to {route}{files}")
    with contextlib.ExitStack() as stack:
        trees: list[tuple[str, str, int]] = []
        if args.base:
            src = stack.enter_context(archived(args.base))
            trees.append((args.base, *stack.enter_context(served(src, args.processes))))
        trees.append(("this tree", *stack.enter_context(served(ROOT / "src", args.processes))))
        for _, base, _ in trees:
            warm(base, args.files)
        width = max(len(name) for name, _, _ in trees)
        for round_ in range(1, args.rounds + 1):
            for n in clients:
                for name, base, pid in trees:
                    m = throughput(base, n, args.requests, pid, args.jobs, args.files)
                    busy = "" if m.busy is None else f", busy on {m.busy:.2f} cores"
                    cpu = ""
                    if m.cpu_per_design_s is not None and m.server_per_design_s is not None:
                        cpu = (
                            f"; CPU s per design {m.cpu_per_design_s:.3f} (server process "
                            f"{m.server_per_design_s:.3f}, solver {m.solver_per_design_s:.3f})"
                        )
                    print(
                        f"round {round_} {name:>{width}}: {n:>2} clients x {args.requests}: "
                        f"{m.rate:6.2f} designs/s, median {m.median_s:6.2f} s, "
                        f"p95 {m.p95_s:6.2f} s{busy}{cpu}",
                        flush=True,
                    )


if __name__ == "__main__":
    main()
