"""The job API (``/api/jobs``): a design that runs in the worker pool with its progress streamed as
server-sent events, a cancel that kills its worker and leaves no result folder, bounded and
expiring jobs, and bad input refused before anything is queued.

The SSE stream is read from a real uvicorn server (:func:`conftest.serve`) and parsed as the
``text/event-stream`` format defines it (fields ``event``, ``data``, ``id``; a blank line ends an
event; lines starting with ``:`` are comments).
"""

from __future__ import annotations

import asyncio
import copy
import json
import os
import time
import tomllib
import urllib.error
import urllib.request
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from fastapi import FastAPI

from corrugate.web import WebSettings
from corrugate.web.app import JOB_WALL_PER_CPU, LOOPBACK_NAMES
from corrugate.web.jobs import Job, JobTable
from corrugate.web.workers import ServerBusyError

from .conftest import post_json, serve, served_files, wait_for
from .test_design_api import spec_of, without_timings

Event = tuple[str, dict[str, Any]]

#: The chassis plate of issue 24 (benchmarks/specs/chassis_independent.toml, the spec
#: benchmarks/solve.py times): 120 x 80 mm, 0.25 mm polypropylene, independent layers, W 5-30 mm
#: step 1, n 6-200, alpha 40-120 deg step 1, sides 78-82 and 118-122 mm, thickness <= 15 mm,
#: EI(0) >= 360 mN m^2.
CHASSIS: dict[str, Any] = tomllib.loads(
    (
        Path(__file__).resolve().parents[2] / "benchmarks" / "specs" / "chassis_independent.toml"
    ).read_text(encoding="utf-8")
)


def parse_sse(lines: Iterator[bytes]) -> Iterator[tuple[str, str, str | None]]:
    """The events of a ``text/event-stream``: (event name, data, id), as the format defines."""
    kind, data, ident = "message", [], None
    for raw in lines:
        line = raw.decode("utf-8").rstrip("\r\n")
        if not line:
            if data:
                yield kind, "\n".join(data), ident
            kind, data, ident = "message", [], None
            continue
        if line.startswith(":"):
            continue
        name, _, value = line.partition(":")
        value = value.removeprefix(" ")
        if name == "event":
            kind = value
        elif name == "data":
            data.append(value)
        elif name == "id":
            ident = value


def events(base: str, job_id: str, timeout: float = 600) -> list[Event]:
    """Every event of a job's stream until the server ends it."""
    with urllib.request.urlopen(f"{base}/api/jobs/{job_id}/events", timeout=timeout) as r:
        assert r.status == 200
        assert r.headers["content-type"].startswith("text/event-stream")
        out = []
        for kind, data, ident in parse_sse(r):
            payload = json.loads(data)
            if kind == "progress":
                assert ident == str(payload["seq"])  # resumable: the id is the sequence number
            out.append((kind, payload))
        return out


def request(base: str, path: str, method: str = "GET") -> tuple[int, Any]:
    req = urllib.request.Request(base + path, method=method)
    try:
        with urllib.request.urlopen(req, timeout=60) as r:
            return r.status, json.loads(r.read())
    except urllib.error.HTTPError as exc:
        return exc.code, json.loads(exc.read())


def check_monotone(progress: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """The solver's events of a design job: sequence numbers, iterations and CPU seconds only
    grow, and the CPU seconds stay within the budget the job states; returns them."""
    seqs = [e["seq"] for e in progress]
    assert seqs == sorted(seqs) and len(set(seqs)) == len(seqs)
    solving = [e for e in progress if e["stage"] == "solving"]
    its = [e["iterations"] for e in solving]
    assert its == sorted(its) and len(set(its)) == len(its), its  # a new event, new iterations
    runs = [e["runs"] for e in solving]
    assert runs == sorted(runs) and runs[0] >= 1
    cpu = [e["cpu_s"] for e in solving]
    assert cpu == sorted(cpu)
    assert all(e["budget_s"] == solving[0]["budget_s"] and e["cpu_s"] >= 0 for e in solving)
    for e in solving:
        assert e["gap"] is None or e["gap"] >= 0
    return solving


@pytest.fixture(scope="module")
def served() -> Iterator[tuple[str, FastAPI]]:
    settings = WebSettings(max_pending=16, timeout_s=120, processes=2, allowed_hosts=LOOPBACK_NAMES)
    with serve(settings) as (base, app):
        yield base, app


def test_a_design_job_streams_progress_and_ends_with_the_answer_of_post_design(
    served: tuple[str, FastAPI],
) -> None:
    base, app = served
    spec = spec_of("blimp_gripper.toml")
    status, job = post_json(base, "/api/jobs/design", spec)
    assert status == 202, job
    assert job["status"] in ("queued", "running") and job["kind"] == "design"
    settings: WebSettings = app.state.settings
    assert job["limits"]["budget_s"] == settings.job_budget_s
    assert job["limits"]["time_limit_s"] == pytest.approx(settings.job_budget_s * JOB_WALL_PER_CPU)
    stream = events(base, job["id"])
    *progress, (last, final) = stream
    assert last == "done" and final["status"] == "done"
    assert {k for k, _ in progress} == {"progress"}
    solving = check_monotone([e for _, e in progress])
    assert len(solving) >= 2  # the first iteration's event and the search's last (flushed)
    # each event names the solve's step (corrugate.solver.progress.stage), in the solve's order
    steps = list(dict.fromkeys(e["step"] for e in solving))
    assert steps[0] == "searching"
    order = ["searching", "explaining: binding checks", "explaining: runner-ups"]
    assert [order.index(step) for step in steps] == sorted(order.index(step) for step in steps)
    assert solving[-1]["budget_s"] == settings.job_budget_s
    # answers first: the job makes no files (they are made on demand, test_ondemand.py)
    assert progress[0][1]["stage"] == "reading" and progress[-1][1]["stage"] == "solving"
    # the answer is POST /api/design's (the synchronous API keeps working) ...
    status, sync = post_json(base, "/api/design", spec, timeout=300)
    assert status == 200
    answer = final["result"]
    assert without_timings(answer["design"]) == without_timings(sync["design"])
    assert answer["design"]["solver"]["budget"]["cpu_seconds"] == settings.job_budget_s
    # its files are made when asked for and served; the job's state says the same as the
    # stream's end
    assert answer["result"] is None and answer["files_url"] == sync["files_url"]  # one design
    made = served_files(base, answer)["result"]
    record = next(f for f in made["files"] if f["name"] == "design.json")
    with urllib.request.urlopen(base + record["url"], timeout=60) as r:
        assert json.loads(r.read())["design"] == answer["design"]["design"]
    status, state = request(base, f"/api/jobs/{job['id']}")
    assert status == 200 and state["status"] == "done" and state["result"] == answer
    assert state["progress"] == progress[-1][1] and state["events"] == progress[-1][1]["seq"]
    # a client that reconnects with Last-Event-ID gets only what followed
    req = urllib.request.Request(
        f"{base}/api/jobs/{job['id']}/events", headers={"last-event-id": str(solving[-1]["seq"])}
    )
    with urllib.request.urlopen(req, timeout=60) as r:
        rest = [(k, json.loads(d)) for k, d, _ in parse_sse(r)]
    assert [e["seq"] for k, e in rest if k == "progress"] == [
        e["seq"] for _, e in progress if e["seq"] > solving[-1]["seq"]
    ]
    assert rest[-1][0] == "done"


@pytest.mark.parametrize("last", ["9" * 5000, "\u00b2", "-1", "1e3"])
def test_a_last_event_id_it_did_not_give_replays_the_stream(
    last: str, served: tuple[str, FastAPI]
) -> None:
    """A Last-Event-ID that is no id of the stream (5000 digits, beyond int(); "²", a digit to
    str.isdigit that int() refuses: both a 422 "internal error (ValueError ...)" and a traceback
    in the server's log before) replays the stream from its first event, as a missing one."""
    base, _ = served
    status, job = post_json(base, "/api/jobs/design", spec_of("blimp_gripper.toml"))
    assert status == 202, job
    whole = events(base, job["id"])
    req = urllib.request.Request(
        f"{base}/api/jobs/{job['id']}/events", headers={"last-event-id": last}
    )
    with urllib.request.urlopen(req, timeout=60) as r:
        assert r.status == 200
        again = [(k, json.loads(d)) for k, d, _ in parse_sse(r)]
    assert [e.get("seq") for k, e in again if k == "progress"] == [
        e["seq"] for k, e in whole if k == "progress"
    ]
    assert again[-1][0] == "done"


def test_bad_input_is_422_before_anything_is_queued(served: tuple[str, FastAPI]) -> None:
    base, app = served
    before = len(app.state.jobs)
    bad = copy.deepcopy(spec_of("blimp_gripper.toml"))
    bad["constraints"]["side"]["min"] = "-5 mm"
    status, answer = post_json(base, "/api/jobs/design", bad)
    assert status == 422 and answer["field"] == "constraints.side.min", answer
    status, answer = post_json(
        base, "/api/jobs/design?budget=100000", spec_of("blimp_gripper.toml")
    )
    assert status == 422 and answer["field"] == "budget" and "600" in answer["detail"], answer
    status, answer = post_json(base, "/api/jobs/verify", {"result": "nope", "mesh": "2"})
    assert status in (422, 503), answer  # 503: no CalculiX on this machine
    if status == 422:
        assert answer["field"] == "result"
        status, answer = post_json(base, "/api/jobs/verify", {"result": "nope", "mesh": "2,32"})
        assert status == 422 and answer["field"] == "mesh" and "16" in answer["detail"]
    assert len(app.state.jobs) == before
    for method, path in (("GET", ""), ("GET", "/events"), ("DELETE", "")):
        status, answer = request(base, f"/api/jobs/no-such-job{path}", method)
        assert status == 404 and "no such job" in answer["detail"]


def _ended(pid: int) -> bool:
    """Whether process ``pid`` is gone (or a zombie waiting for its parent to reap it)."""
    try:
        with open(f"/proc/{pid}/stat", encoding="ascii") as f:
            return f.read().rsplit(")", 1)[1].split()[0] == "Z"
    except FileNotFoundError:
        return True


def test_cancel_kills_the_worker_replaces_it_and_leaves_no_folder(
    served: tuple[str, FastAPI],
) -> None:
    """The chassis plate (tens of CPU seconds) is cancelled once the solver reports: the
    worker running it is killed and replaced; no result folder is made (answers first)."""
    base, app = served
    runner, store = app.state.runner, app.state.store
    wait_for(lambda: len(runner.worker_pids()) == runner.processes, 120, "workers up")
    pids = set(runner.worker_pids())
    folders = set(store.root.iterdir())
    status, job = post_json(base, "/api/jobs/design", CHASSIS)
    assert status == 202, job
    url = f"{base}/api/jobs/{job['id']}/events"
    with urllib.request.urlopen(url, timeout=300) as r:
        for kind, data, _ in parse_sse(r):
            assert kind == "progress", data
            if json.loads(data)["stage"] == "solving":
                break
    assert set(store.root.iterdir()) == folders  # the job makes no files while it solves
    status, state = request(base, f"/api/jobs/{job['id']}", "DELETE")
    assert status == 200 and state["status"] == "cancelled"
    stream = events(base, job["id"])
    assert stream[-1][0] == "cancelled"
    # its worker was killed and another took its place; the others kept running
    wait_for(
        lambda: len(runner.worker_pids()) == runner.processes and set(runner.worker_pids()) != pids,
        120,
        "a worker replaced",
    )
    gone = pids - set(runner.worker_pids())
    assert len(gone) == 1
    (killed,) = gone
    wait_for(lambda: _ended(killed), 10, "the killed worker ended")
    assert set(store.root.iterdir()) == folders  # no result folder left
    assert request(base, f"/api/jobs/{job['id']}")[1]["result"] is None
    # a cancelled job stays cancelled; the server designs on
    status, state = request(base, f"/api/jobs/{job['id']}", "DELETE")
    assert status == 200 and state["status"] == "cancelled"
    status, _ = post_json(base, "/api/analyze", {"W": 8, "n": 8, "alpha": 84})
    assert status == 200
    assert all(os.path.exists(f"/proc/{p}") for p in runner.worker_pids())


@pytest.mark.slow  # starts an app with its worker processes
def test_a_job_past_its_time_limit_fails_with_504_and_keeps_nothing() -> None:
    """The time limit of a design job is JOB_WALL_PER_CPU times its solver budget: a budget of
    0.05 s stops the case study's design at 0.2 s wall. Its variables are pinned to one design,
    so the search certifies it well inside the budget (about 0.01 s of CPU), and its robust
    check's Monte Carlo of 10^6 samples takes some 2 s (1.95 s of wall measured in a worker's
    process alone): the job is stopped in it, never answered early by a search that ran out of
    its budget without a design."""
    settings = WebSettings(processes=1, job_budget_s=0.05, allowed_hosts=LOOPBACK_NAMES)
    assert JOB_WALL_PER_CPU == 4.0 and settings.job_time_limit_s(0.05) == pytest.approx(0.2)
    spec = spec_of("blimp_gripper.toml")
    spec["variables"] = {
        "W": {"min": "8 mm", "max": "8 mm", "step": "1 mm"},
        "n": {"min": 9, "max": 9},
        "alpha": {"min": "78 deg", "max": "78 deg", "step": "1 deg"},
    }
    spec["robust"] = {"W": "0.1 mm", "alpha": "1 deg", "samples": 10**6, "probability": 0.5}
    with serve(settings) as (base, app):
        status, job = post_json(base, "/api/jobs/design", spec)
        assert status == 202 and job["limits"]["time_limit_s"] == pytest.approx(0.2)
        kind, final = events(base, job["id"])[-1]
        assert kind == "failed" and final["error"]["status"] == 504
        assert "time limit of 0.2 s" in final["error"]["body"]["detail"]
        assert not any(app.state.store.root.iterdir())


def test_jobs_are_bounded_and_expire() -> None:
    async def scenario() -> None:
        table = JobTable(max_jobs=2, ttl_s=3600)
        a, b = table.new("design", {}), table.new("design", {})
        with pytest.raises(ServerBusyError):
            table.new("design", {})  # both still running: refused, never dropped
        a.end("done", {"x": 1})
        c = table.new("design", {})  # the finished one makes room
        assert table.get(a.id) is None and table.get(b.id) is b and table.get(c.id) is c
        table.cancel(b)
        assert b.status == "cancelled"
        b.end("done", {"late": True})  # a cancelled job stays cancelled
        assert b.status == "cancelled" and b.result is None
        short = JobTable(max_jobs=5, ttl_s=0.0)
        d, e = short.new("design", {}), short.new("verify", {})
        d.end("failed", error={"status": 504})
        await asyncio.sleep(0.01)
        assert short.get(d.id) is None and short.get(e.id) is e  # finished and past its time

    asyncio.run(scenario())


def test_a_job_keeps_its_last_events_and_numbers_them() -> None:
    from corrugate.web.jobs import MAX_EVENTS

    job = Job("x", "design", {})
    for i in range(MAX_EVENTS + 5):
        job.progress({"stage": "solving", "iterations": i + 1})
    assert job.status == "running" and job.seq == MAX_EVENTS + 5
    assert len(job.events) == MAX_EVENTS and job.events[0]["seq"] == 6
    assert [e["seq"] for e in job.events_after(MAX_EVENTS + 3)] == [MAX_EVENTS + 4, MAX_EVENTS + 5]
    assert job.as_dict()["progress"]["iterations"] == MAX_EVENTS + 5


def test_an_fe_job_sets_its_own_memory_cap_and_calculix_inherits_it() -> None:
    """A worker capped at 1 GiB beyond its start-up mapping, with a 3 GiB ceiling: inside
    ``memory_cap(2 GiB)`` a program it starts (as CalculiX is started) sees the 2 GiB cap (plus
    the mapping), the ceiling bounds a larger request, and the worker's own cap comes back after."""
    import subprocess
    import sys

    code = """
import subprocess
from corrugate.web import workers
GiB = 1024**3
workers._cap_memory(1 * GiB, 3 * GiB)
base = workers._MAPPED_AT_CAP
def child():
    return int(subprocess.run(["sh", "-c", "ulimit -v"], capture_output=True, text=True).stdout)
print(base, child())
with workers.memory_cap(2 * GiB) as cap:
    print(cap, child())
with workers.memory_cap(5 * GiB) as cap:
    print(cap, child())
print(child())
"""
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True, timeout=120
    ).stdout.split("\n")
    gib = 1024**3
    base, before = map(int, out[0].split())
    assert before == (base + 1 * gib) // 1024  # ulimit -v is in KiB
    cap, inside = map(int, out[1].split())
    assert cap == base + 2 * gib and inside == cap // 1024
    cap, ceiling = map(int, out[2].split())
    assert cap == base + 3 * gib and ceiling == cap // 1024  # no more than the ceiling
    assert int(out[3]) == before


def _group_members(pgid: int) -> list[int]:
    """The processes of process group ``pgid`` other than its leader (and not zombies)."""
    found = []
    for entry in os.listdir("/proc"):
        if not entry.isdigit() or int(entry) == pgid:
            continue
        try:
            with open(f"/proc/{entry}/stat", encoding="ascii") as f:
                state, _, group = f.read().rsplit(")", 1)[1].split()[:3]
        except (FileNotFoundError, ProcessLookupError):
            continue
        if int(group) == pgid and state != "Z":
            found.append(int(entry))
    return found


@pytest.mark.fea
def test_cancelling_a_verification_kills_its_calculix(
    served: tuple[str, FastAPI], ccx: str
) -> None:
    """A verification cancelled while CalculiX runs: the worker and the ccx it started (in the
    worker's own process group) are killed; the job ends cancelled."""
    base, app = served
    runner = app.state.runner
    status, answer = post_json(base, "/api/design", spec_of("blimp_gripper.toml"), timeout=300)
    assert status == 200
    result = served_files(base, answer)["result"]["id"]  # the files, made on demand
    status, job = post_json(base, "/api/jobs/verify", {"result": result, "mesh": "2,4,8"})
    assert status == 202, job
    assert job["limits"]["meshes"] == [2, 4, 8] and job["limits"]["memory_bytes"] == 8 * 1024**3
    children: list[int] = []
    with urllib.request.urlopen(f"{base}/api/jobs/{job['id']}/events", timeout=600) as r:
        for kind, data, _ in parse_sse(r):
            assert kind == "progress", data
            if json.loads(data).get("run", 0) >= 2:  # the 4-per-facet run (seconds of ccx)
                break
    deadline = time.monotonic() + 60
    while not children and time.monotonic() < deadline:
        children = [c for p in runner.worker_pids() for c in _group_members(p)]
        time.sleep(0.02)
    assert children, "no CalculiX process seen in a worker's process group"
    status, state = request(base, f"/api/jobs/{job['id']}", "DELETE")
    assert status == 200 and state["status"] == "cancelled"
    for child in children:
        wait_for(lambda c=child: _ended(c), 10, f"CalculiX ({child}) killed")


def test_the_openapi_document_lists_the_job_api(served: tuple[str, FastAPI]) -> None:
    base, _ = served
    with urllib.request.urlopen(base + "/openapi.json", timeout=60) as r:
        paths = json.loads(r.read())["paths"]
    assert set(paths["/api/jobs/design"]) == {"post"} and set(paths["/api/jobs/verify"]) == {"post"}
    assert set(paths["/api/jobs/{job_id}"]) == {"get", "delete"}
    assert (
        "text/event-stream"
        in paths["/api/jobs/{job_id}/events"]["get"]["responses"]["200"]["content"]
    )
    assert "202" in paths["/api/jobs/design"]["post"]["responses"]
    assert "budget" in [p["name"] for p in paths["/api/jobs/design"]["post"]["parameters"]]
    assert set(paths["/api/fea"]) == {"get"}


@pytest.mark.slow  # starts an app with its worker processes
def test_a_job_is_accepted_while_the_pool_is_busy() -> None:
    """With one worker busy on the chassis plate, a second design job is read (by the job API's
    own worker) and accepted at once, queued behind it; a bad one is refused at once."""
    settings = WebSettings(processes=1, allowed_hosts=LOOPBACK_NAMES)
    with serve(settings) as (base, app):
        status, first = post_json(base, "/api/jobs/design", CHASSIS)
        assert status == 202
        url = f"{base}/api/jobs/{first['id']}/events"
        with urllib.request.urlopen(url, timeout=300) as r:
            for _, data, _ in parse_sse(r):
                if json.loads(data)["stage"] == "solving":
                    break
        status, second = post_json(base, "/api/jobs/design", spec_of("blimp_gripper.toml"))
        assert status == 202 and second["status"] == "queued"
        bad = copy.deepcopy(spec_of("blimp_gripper.toml"))
        bad["variables"]["n"]["max"] = 5000
        status, answer = post_json(base, "/api/jobs/design", bad)
        assert status == 422 and answer["field"] == "variables.n.max", answer
        assert request(base, f"/api/jobs/{first['id']}")[1]["status"] == "running"
        assert request(base, f"/api/jobs/{second['id']}")[1]["status"] == "queued"
        assert app.state.quick.worker_pids() and not set(app.state.quick.worker_pids()) & set(
            app.state.runner.worker_pids()
        )
        for job in (first, second):  # cancelled queued or running: both end, nothing kept
            status, state = request(base, f"/api/jobs/{job['id']}", "DELETE")
            assert status == 200 and state["status"] == "cancelled"
        assert not any(app.state.store.root.iterdir())
