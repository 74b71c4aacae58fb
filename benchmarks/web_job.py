"""The issue-24 chassis plate as a web design job: its progress events, CPU and wall time.

Run by hand (a minute or more on 2 cores)::

    .venv/bin/python benchmarks/web_job.py [--budget SECONDS] [--every N]

Starts the app (:func:`corrugate.web.create_app`) with uvicorn on a free port of 127.0.0.1 in a
thread, posts the chassis plate of issue 24 (a 120 x 80 mm plate, 0.25 mm polypropylene, layers
independent, W 5-30 mm step 1, n 6-200, alpha 40-120 deg step 1 per layer; side_x 78-82, side_y
118-122 mm; thickness <= 15 mm; EI(0) >= 360 mN m^2) to ``POST /api/jobs/design``, reads its
server-sent events to the end and prints every ``--every``-th progress event, the number of events,
the wall seconds to the answer and the solver's CPU seconds of its budget (``solver.budget`` of
the answer), whose ratio shows what a shared machine left the job.
"""

from __future__ import annotations

import argparse
import json
import socket
import threading
import time
import tomllib
import urllib.request
from pathlib import Path
from typing import Any

import uvicorn

from corrugate.web import WebSettings, create_app
from corrugate.web.app import LOOPBACK_NAMES

#: The chassis plate of issue 24, the spec benchmarks/solve.py times.
CHASSIS: dict[str, Any] = tomllib.loads(
    (Path(__file__).resolve().parent / "specs" / "chassis_independent.toml").read_text(
        encoding="utf-8"
    )
)


def events(url: str) -> Any:
    """(event name, data) of a server-sent event stream, until the server ends it."""
    kind, data = "message", []
    with urllib.request.urlopen(url, timeout=3600) as r:
        for raw in r:
            line = raw.decode().rstrip("\r\n")
            if not line:
                if data:
                    yield kind, json.loads("\n".join(data))
                kind, data = "message", []
            elif not line.startswith(":"):
                name, _, value = line.partition(":")
                if name == "event":
                    kind = value.strip()
                elif name == "data":
                    data.append(value.removeprefix(" "))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--budget", type=float, default=None, help="Solver CPU seconds.")
    parser.add_argument("--every", type=int, default=20, help="Print every N-th event.")
    args = parser.parse_args()
    sock = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    sock.bind(("127.0.0.1", 0))
    base = f"http://127.0.0.1:{sock.getsockname()[1]}"
    app = create_app(WebSettings(allowed_hosts=LOOPBACK_NAMES))
    server = uvicorn.Server(uvicorn.Config(app, log_level="warning", lifespan="on"))
    thread = threading.Thread(target=server.run, kwargs={"sockets": [sock]}, daemon=True)
    thread.start()
    try:
        while not server.started:
            time.sleep(0.05)
        query = "" if args.budget is None else f"?budget={args.budget:g}"
        request = urllib.request.Request(
            f"{base}/api/jobs/design{query}",
            data=json.dumps(CHASSIS).encode(),
            headers={"content-type": "application/json"},
        )
        start = time.perf_counter()
        with urllib.request.urlopen(request, timeout=600) as r:
            job = json.loads(r.read())
        print(f"202 after {time.perf_counter() - start:.2f} s; limits {job['limits']}")
        count = 0
        for kind, data in events(base + job["links"]["events"]):
            if kind == "progress":
                count += 1
                if count % args.every == 1 or data["stage"] != "solving":
                    print(data)
                continue
            wall = time.perf_counter() - start
            print(f"{kind} after {wall:.1f} s wall, {count} progress events")
            if data["result"]:
                d = data["result"]["design"]
                budget = d["solver"]["budget"]
                print(
                    f"status {d['status']}, mass {d['mass_g']:.4g} g, certified {d['certified']}; "
                    f"solver {budget['used_cpu_seconds']:.1f} s CPU of {budget['cpu_seconds']:g} "
                    f"({budget['used_cpu_seconds'] / wall:.2f} CPU s per wall s)"
                )
            else:
                print(data["error"])
    finally:
        server.should_exit = True
        thread.join(timeout=30)


if __name__ == "__main__":
    main()
