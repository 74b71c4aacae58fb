"""Background jobs of the web app: a design or an FE verification that runs in the worker pool
while the client follows its progress, and can be cancelled.

A :class:`Job` is created by ``POST /api/jobs/design`` or ``POST /api/jobs/verify`` (after its
input is validated: a bad value is 422 at once, never a failed job), runs as an asyncio task that
awaits :meth:`corrugate.web.workers.Runner.run` with the job's own time limit, and collects the
progress events its worker sends (:func:`corrugate.web.workers.send_progress`): for a design, the
branch and bound's iterations, gap and best value (:func:`solver_progress`, a reporter of
:mod:`corrugate.solver.progress` throttled to :data:`PROGRESS_INTERVAL_S`), for a verification
one line per CalculiX run. Clients read them with ``GET /api/jobs/{id}`` (the last one) or
``GET /api/jobs/{id}/events`` (all of them, as server-sent events, :func:`sse`).

:class:`JobTable` keeps at most ``max_jobs`` jobs, a finished one for ``ttl_s`` seconds (then it
is forgotten; its stored result lives as long as the result store keeps it), at most
``max_active`` of them running or queued (a job past that is refused at submission, 503 with
``Retry-After``, never accepted and failed later), and cancels them all when the app stops. ``DELETE /api/jobs/{id}`` cancels a job: its worker is killed and
replaced (the runner's kill and replace, with the programs it started) and the result folder it
was writing is discarded.
"""

from __future__ import annotations

import asyncio
import json
import math
import secrets
import time
from collections import deque
from collections.abc import Iterator
from contextlib import contextmanager, suppress
from dataclasses import dataclass, field
from typing import Any

from corrugate.web.workers import ServerBusyError, send_progress

__all__ = [
    "FINISHED",
    "MAX_EVENTS",
    "PROGRESS_INTERVAL_S",
    "QUEUE_RETRY_AFTER_S",
    "Job",
    "JobTable",
    "solver_progress",
    "sse",
]

#: The states a job ends in.
FINISHED = ("done", "failed", "cancelled")
#: Progress events a job keeps (the oldest go first; the stream says how many were dropped).
MAX_EVENTS = 2000
#: Shortest time between two solver progress events of one job (s, wall).
PROGRESS_INTERVAL_S = 0.25


@dataclass(eq=False)
class Job:
    """One background computation: its ``id`` (opaque), ``kind`` (``design``, ``verify``), the
    ``limits`` it runs under (stated to the client), ``status`` (``queued``, ``running``, then one
    of :data:`FINISHED`), its progress ``events`` (each with its sequence number ``seq``), and
    when finished its ``result`` or its ``error`` (``{"status": HTTP status, "body": ErrorBody}``).
    Lives on the event loop: only the loop's thread changes it."""

    id: str
    kind: str
    limits: dict[str, Any]
    created: float = field(default_factory=time.time)
    status: str = "queued"
    events: deque[dict[str, Any]] = field(default_factory=lambda: deque(maxlen=MAX_EVENTS))
    seq: int = 0
    result: Any = None
    error: dict[str, Any] | None = None
    finished_at: float | None = None
    task: asyncio.Task[None] | None = None
    _wake: asyncio.Event = field(default_factory=asyncio.Event)

    @property
    def finished(self) -> bool:
        return self.status in FINISHED

    def _notify(self) -> None:
        wake, self._wake = self._wake, asyncio.Event()
        wake.set()

    async def changed(self, timeout: float) -> None:
        """Wait until the job changes (a new event, its end) or ``timeout`` seconds pass."""
        wake = self._wake
        if self.finished:
            return
        with suppress(TimeoutError):
            await asyncio.wait_for(wake.wait(), timeout)

    def progress(self, event: dict[str, Any]) -> None:
        """Record a progress event (the job is running from its first one)."""
        if self.finished:
            return
        self.status = "running"
        self.seq += 1
        self.events.append({"seq": self.seq, "t_s": round(time.time() - self.created, 3), **event})
        self._notify()

    def end(self, status: str, result: Any = None, error: dict[str, Any] | None = None) -> None:
        """Finish the job as ``status`` (one of :data:`FINISHED`) with its result or error."""
        if self.finished:
            return
        self.status, self.result, self.error = status, result, error
        self.finished_at = time.time()
        self._notify()

    def events_after(self, seq: int) -> list[dict[str, Any]]:
        """The events kept whose sequence number is above ``seq``."""
        return [e for e in self.events if e["seq"] > seq]

    def as_dict(self) -> dict[str, Any]:
        """The job's status as ``GET /api/jobs/{id}`` answers it."""
        return {
            "id": self.id,
            "kind": self.kind,
            "status": self.status,
            "limits": self.limits,
            "created": self.created,
            "elapsed_s": round((self.finished_at or time.time()) - self.created, 3),
            "events": self.seq,
            "progress": self.events[-1] if self.events else None,
            "result": self.result,
            "error": self.error,
            "links": {
                "status": f"/api/jobs/{self.id}",
                "events": f"/api/jobs/{self.id}/events",
            },
        }


#: The ``Retry-After`` (s) of a job refused because the queue is full: a queued job waits for a
#: running one, which takes minutes, so retrying within seconds would be refused again.
QUEUE_RETRY_AFTER_S = 30


class JobTable:
    """The jobs of one app: at most ``max_jobs`` kept, a finished one for ``ttl_s`` seconds, and
    at most ``max_active`` not yet ended (running or queued; None: no bound but ``max_jobs``).

    A job counts as active until its task has ended, a cancelled one too (its worker is still
    being killed): so the runner, given ``max_active`` slots, never refuses a job this table
    accepted (:meth:`check_room`)."""

    def __init__(self, max_jobs: int, ttl_s: float, max_active: int | None = None) -> None:
        self.max_jobs = max_jobs
        self.ttl_s = ttl_s
        self.max_active = max_active
        self._jobs: dict[str, Job] = {}

    def __len__(self) -> int:
        return len(self._jobs)

    def active(self) -> int:
        """The jobs not yet ended: running, queued, or cancelled while their task still ends."""
        return sum(
            1
            for j in self._jobs.values()
            if not j.finished or (j.task is not None and not j.task.done())
        )

    def check_room(self) -> None:
        """:class:`ServerBusyError` (503, ``Retry-After`` :data:`QUEUE_RETRY_AFTER_S`) when
        ``max_active`` jobs are active: the queue is full."""
        if self.max_active is None:
            return
        active = self.active()
        if active >= self.max_active:
            raise ServerBusyError(
                f"the job queue is full ({active} jobs run or wait, at most {self.max_active}); "
                f"try again in {QUEUE_RETRY_AFTER_S} s",
                retry_after_s=QUEUE_RETRY_AFTER_S,
            )

    def _expire(self) -> None:
        now = time.time()
        for job_id, job in list(self._jobs.items()):
            if job.finished_at is not None and now - job.finished_at > self.ttl_s:
                del self._jobs[job_id]

    def new(self, kind: str, limits: dict[str, Any]) -> Job:
        """A new queued job; :class:`ServerBusyError` (503) when the queue is full
        (:meth:`check_room`); the oldest finished job goes to make room, and
        :class:`ServerBusyError` when every kept job is still running."""
        self._expire()
        self.check_room()
        if len(self._jobs) >= self.max_jobs:
            done = [j for j in self._jobs.values() if j.finished]
            if not done:
                raise ServerBusyError(
                    f"the server already runs {len(self._jobs)} jobs; try again when one ends"
                )
            oldest = min(done, key=lambda j: j.finished_at or 0.0)
            del self._jobs[oldest.id]
        job = Job(secrets.token_urlsafe(12), kind, limits)
        self._jobs[job.id] = job
        return job

    def get(self, job_id: str) -> Job | None:
        """The job ``job_id``, None if there is none (never was, or expired)."""
        self._expire()
        return self._jobs.get(job_id)

    def cancel(self, job: Job) -> None:
        """Stop ``job`` if it has not finished: its task is cancelled (which kills its worker)."""
        if job.finished:
            return
        if job.task is not None:
            job.task.cancel()
        job.end("cancelled")

    def close(self) -> None:
        """Cancel every job (the app is stopping)."""
        for job in list(self._jobs.values()):
            self.cancel(job)


def _frame(kind: str, data: dict[str, Any], seq: int | None = None) -> bytes:
    head = f"id: {seq}\n" if seq is not None else ""
    return f"{head}event: {kind}\ndata: {json.dumps(data, allow_nan=False)}\n\n".encode()


async def sse(job: Job, after: int = 0, keepalive_s: float = 15.0) -> Any:
    """The job as server-sent events (``text/event-stream``): every kept ``progress`` event after
    sequence number ``after`` (its ``id:`` is its number, so a client that reconnects with
    ``Last-Event-ID`` resumes), then one final event named as the job ended (``done``,
    ``failed``, ``cancelled``) carrying :meth:`Job.as_dict`; a comment line every
    ``keepalive_s`` seconds while nothing happens. An async generator of byte chunks."""
    seq = after
    yield b"retry: 2000\n\n"
    while True:
        for event in job.events_after(seq):
            seq = event["seq"]
            yield _frame("progress", event, seq)
        if job.finished:
            yield _frame(job.status, job.as_dict())
            return
        before = job.seq
        await job.changed(keepalive_s)
        if job.seq == before and not job.finished:
            yield b": keep-alive\n\n"


class _SolverEvents:
    """A :mod:`corrugate.solver.progress` reporter that sends (:func:`send_progress`) at most one
    event per ``interval_s`` seconds: ``iterations`` (every branch-and-bound iteration of the job
    so far, all runs: the search and its explanation's re-solves), ``runs`` (branch-and-bound runs
    started), the current run's relative ``gap`` (null while no feasible point is known) and
    ``best`` objective value, the budget's ``cpu_s`` spent of ``budget_s`` and the solve's
    ``step`` (:func:`corrugate.solver.progress.stage`: ``searching``, ``explaining: runner-ups``,
    ...; the event's ``stage`` stays ``solving``). An iteration
    held back by the throttle is sent by :meth:`flush` (when the search is over), so the last
    event shows where the search ended, not where it was up to ``interval_s`` before."""

    def __init__(self, interval_s: float) -> None:
        self.interval_s = interval_s
        self.iterations = 0
        self.runs = 0
        self.next_t = 0.0
        self.pending: dict[str, Any] | None = None
        self.step = "searching"

    def on_stage(self, step: str) -> None:
        """The solve entered the stage ``step`` (shown with the next iteration's event)."""
        self.step = step

    def flush(self) -> None:
        """Send the last iteration's event if the throttle held it back."""
        if self.pending is not None:
            send_progress(self.pending)
            self.pending = None

    def __call__(self, iterations: int, gap: float, best: float | None) -> None:
        from corrugate.solver.budget import current_budget

        self.iterations += 1
        if iterations == 1:
            self.runs += 1
        budget = current_budget()
        self.pending = {
            "stage": "solving",
            "step": self.step,
            "iterations": self.iterations,
            "runs": self.runs,
            "gap": gap if math.isfinite(gap) else None,
            "best": best if best is not None and math.isfinite(best) else None,
            "cpu_s": None if budget is None else round(budget.used_seconds, 3),
            "budget_s": None if budget is None else budget.seconds,
        }
        now = time.monotonic()
        if now >= self.next_t:
            self.next_t = now + self.interval_s
            self.flush()


@contextmanager
def solver_progress(interval_s: float = PROGRESS_INTERVAL_S) -> Iterator[_SolverEvents]:
    """(In a worker process.) Send the branch and bound's progress of the block to the server,
    throttled to one event per ``interval_s`` seconds (:class:`_SolverEvents`); the block calls
    the reporter's ``flush`` when its search is over."""
    from corrugate.solver.progress import reporting

    events = _SolverEvents(interval_s)
    with reporting(events, events.on_stage):
        yield events
