"""Bounds that make the web app safe to leave running: request body size and computation time.

* :class:`BodySizeLimit` is a pure ASGI middleware: it reads a request body (up to the limit) before
  the app sees it and answers 413 past the limit, whether or not the client sent Content-Length.
* :class:`Runner` runs computations on a small thread pool (:meth:`Runner.run`) or on a pool of
  worker processes, one per core (:meth:`Runner.run_process`: the designs, whose solver holds the
  GIL), raises :class:`ServerBusyError` when too many are in flight (including abandoned ones
  still running) and :class:`ComputeTimeoutError` past the time limit.
  A running computation is not killed: one that times out runs on in the background, holds its
  slot until it ends, and its result is dropped. After each computation on a thread, freed memory
  is returned to the system (:func:`release_memory`), so that the resident size stays bounded
  (``benchmarks/web_memory.py`` measures it).
* :class:`CatchAll` is the innermost middleware: an exception no handler took (a bug, or an input
  that still got past the limits of :mod:`corrugate.core.limits`) becomes one clean JSON error, 422
  (or 503 for a server-side OS error or lack of memory), never a 500 or a dropped connection;
  the traceback goes to the log.
"""

from __future__ import annotations

import asyncio
import ctypes
import gc
import json
import logging
import multiprocessing
import os
import threading
from collections.abc import Awaitable, Callable, MutableMapping
from concurrent.futures import Executor, Future, ProcessPoolExecutor, ThreadPoolExecutor
from typing import Any, TypeVar

__all__ = [
    "BodySizeLimit",
    "CatchAll",
    "ComputeTimeoutError",
    "HostCheck",
    "Runner",
    "ServerBusyError",
    "core_count",
    "host_name",
    "release_memory",
]

_log = logging.getLogger("corrugate.web")

T = TypeVar("T")

Scope = MutableMapping[str, Any]
Message = MutableMapping[str, Any]
Receive = Callable[[], Awaitable[Message]]
Send = Callable[[Message], Awaitable[None]]
ASGIApp = Callable[[Scope, Receive, Send], Awaitable[None]]


class ServerBusyError(Exception):
    """Too many computations are in flight; try again later (HTTP 503)."""


class ComputeTimeoutError(Exception):
    """A computation did not finish within the time limit (HTTP 504)."""

    def __init__(self, seconds: float) -> None:
        self.seconds = seconds
        super().__init__(f"the computation did not finish within {seconds:g} s and was abandoned")


class BodySizeLimit:
    """ASGI middleware: HTTP request bodies longer than ``max_bytes`` get 413 and never reach the app.

    The body is read whole (at most ``max_bytes``) and replayed to the app, so a client that lies in
    Content-Length or streams chunks cannot get past the limit.
    """

    def __init__(self, app: ASGIApp, max_bytes: int) -> None:
        self.app = app
        self.max_bytes = max_bytes

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        for key, value in scope.get("headers", []):
            if key == b"content-length":
                try:
                    declared = int(value)
                except ValueError:
                    await self._reject(send, 400, "Content-Length is not a number")
                    return
                if declared > self.max_bytes:
                    await self._too_large(send)
                    return
        chunks: list[bytes] = []
        size = 0
        while True:
            message = await receive()
            if message["type"] == "http.disconnect":
                return
            body = message.get("body", b"")
            size += len(body)
            if size > self.max_bytes:
                await self._too_large(send)
                return
            chunks.append(body)
            if not message.get("more_body", False):
                break
        replayed = False
        whole = b"".join(chunks)

        async def replay() -> Message:
            nonlocal replayed
            if not replayed:
                replayed = True
                return {"type": "http.request", "body": whole, "more_body": False}
            return await receive()

        await self.app(scope, replay, send)

    async def _too_large(self, send: Send) -> None:
        await self._reject(
            send, 413, f"the request body is larger than the limit of {self.max_bytes} bytes"
        )

    @staticmethod
    async def _reject(send: Send, status: int, detail: str, field: str | None = "body") -> None:
        body = json.dumps({"detail": detail, "field": field, "errors": []}).encode()
        await send(
            {
                "type": "http.response.start",
                "status": status,
                "headers": [
                    (b"content-type", b"application/json"),
                    (b"content-length", str(len(body)).encode()),
                    (b"connection", b"close"),
                ],
            }
        )
        await send({"type": "http.response.body", "body": body})


def host_name(header: str) -> str:
    """The host of a Host header, lower-case, without the port (``[::1]:8000`` -> ``[::1]``)."""
    header = header.strip().lower()
    if header.startswith("["):
        end = header.find("]")
        return header[: end + 1] if end > 0 else header
    return header.split(":", 1)[0]


class HostCheck:
    """ASGI middleware: answer 400 unless the Host header names one of ``allowed`` hosts.

    A local server bound to 127.0.0.1 is still reachable from a web page through DNS rebinding
    (a name that first resolves elsewhere, then to 127.0.0.1); the browser then sends that name
    as Host, which this refuses.
    """

    def __init__(self, app: ASGIApp, allowed: tuple[str, ...]) -> None:
        self.app = app
        self.allowed = frozenset(host_name(h) for h in allowed)

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] in ("http", "websocket"):
            host = ""
            for key, value in scope.get("headers", []):
                if key == b"host":
                    host = host_name(value.decode("latin-1"))
                    break
            if host not in self.allowed:
                await BodySizeLimit._reject(
                    send, 400, "this server does not answer to that Host", field=None
                )
                return
        await self.app(scope, receive, send)


class CatchAll:
    """ASGI middleware: any exception that reaches it becomes a JSON error (see the module)."""

    def __init__(self, app: ASGIApp) -> None:
        self.app = app

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        started = False

        async def watch(message: Message) -> None:
            nonlocal started
            if message["type"] == "http.response.start":
                started = True
            await send(message)

        try:
            await self.app(scope, receive, watch)
        except Exception as exc:
            from corrugate.core.errors import CorrugateError, describe

            if not isinstance(exc, CorrugateError):
                _log.exception("unexpected error in %s %s", scope.get("method"), scope.get("path"))
            if started:
                return  # the answer is on its way: nothing better can be sent
            server_side = isinstance(exc, MemoryError | OSError) and not isinstance(
                exc, CorrugateError
            )
            status = 503 if server_side else 422
            field = getattr(exc, "field", None)
            await BodySizeLimit._reject(send, status, describe(exc), field=field)


def release_memory(full: bool = False) -> None:
    """Collect young garbage (all of it if ``full``: some 0.3 s) and hand freed heap pages back
    to the system (glibc ``malloc_trim``, microseconds), so that the memory a large computation
    needed does not stay resident."""
    gc.collect() if full else gc.collect(1)
    try:
        libc = ctypes.CDLL(None)
        libc.malloc_trim(0)
    except (OSError, AttributeError):
        pass


def core_count() -> int:
    """The cores this process may run on (at least 1)."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # not on Linux
        return max(1, os.cpu_count() or 1)


#: What a new worker process imports before its first job (the web app, the solver, the writers),
#: so the first design does not pay for it.
WORKER_PRELOAD = (
    "corrugate.web.app",
    "corrugate.workflow",
    "corrugate.solver",
    "corrugate.export.plan",
    "corrugate.export.files",
    "corrugate.export.files3d",
    "corrugate.export.record",
    "corrugate.fabrication.instructions",
)


def _warm_up() -> None:
    """Import :data:`WORKER_PRELOAD` in a worker process (its initializer)."""
    import importlib

    for name in WORKER_PRELOAD:
        importlib.import_module(name)


class Runner:
    """Run blocking computations with a time limit of ``timeout_s`` (from when a computation
    starts; its wait in the queue does not count): on ``workers`` threads
    (:meth:`run`) or on ``processes`` worker processes (:meth:`run_process`; None: one per core,
    0: on the threads instead).

    At most ``max_pending`` computations may be queued or running at once, on both pools together
    (a timed-out one counts until it really ends); past that :meth:`run` and :meth:`run_process`
    raise :class:`ServerBusyError` at once.

    The processes start from a fresh interpreter (``forkserver``, or ``spawn`` where there is no
    fork), never as a fork of the server with its threads; they are made on first use and each
    imports :data:`WORKER_PRELOAD` once. :meth:`start_processes` makes them ahead of the first
    request; a computation waits until they are ready before its time limit starts.
    """

    def __init__(
        self, workers: int, max_pending: int, timeout_s: float, processes: int | None = None
    ) -> None:
        self.timeout_s = timeout_s
        self.processes = core_count() if processes is None else processes
        self._pool = ThreadPoolExecutor(max_workers=workers, thread_name_prefix="corrugate-web")
        self._slots = threading.BoundedSemaphore(max_pending)
        self._process_pool: ProcessPoolExecutor | None = None
        self._warm: list[Future[None]] = []
        self._lock = threading.Lock()
        self._done = 0

    def _processes(self) -> Executor:
        """The process pool (made on first use), or the thread pool when ``processes`` is 0."""
        if self.processes <= 0:
            return self._pool
        with self._lock:
            if self._process_pool is None:
                methods = multiprocessing.get_all_start_methods()
                context = multiprocessing.get_context(
                    "forkserver" if "forkserver" in methods else "spawn"
                )
                self._process_pool = ProcessPoolExecutor(
                    max_workers=self.processes, mp_context=context, initializer=_warm_up
                )
            return self._process_pool

    def start_processes(self) -> None:
        """Start every worker process now (they import their modules in the background)."""
        pool = self._processes()
        with self._lock:
            if pool is not self._pool and not self._warm:
                self._warm = [pool.submit(_warm_up) for _ in range(self.processes)]

    async def _ready(self) -> None:
        """Wait until the worker processes have started and imported their modules (the start of
        a worker is not part of a computation's time limit)."""
        self.start_processes()
        for future in list(self._warm):
            await asyncio.wrap_future(future)

    async def run(self, fn: Callable[[], T]) -> T:
        """The result of ``fn()``, computed on the thread pool; its exceptions propagate."""
        return await self._submit(self._pool, fn)

    async def run_process(
        self, fn: Callable[..., T], *args: Any, abandoned: Callable[[], None] | None = None
    ) -> T:
        """The result of ``fn(*args)``, computed in a worker process: ``fn`` must be a module-level
        function and ``args`` and the result picklable. Its exceptions propagate (corrugate's own
        errors arrive as raised, :class:`~corrugate.core.errors.CorrugateError`). ``abandoned`` is
        called when a computation that timed out finally ends (to remove what it left behind)."""
        pool = self._processes()
        if pool is not self._pool:
            await self._ready()
        return await self._submit(pool, fn, *args, abandoned=abandoned)

    async def _submit(
        self,
        pool: Executor,
        fn: Callable[..., T],
        *args: Any,
        abandoned: Callable[[], None] | None = None,
    ) -> T:
        if not self._slots.acquire(blocking=False):
            raise ServerBusyError("the server is busy with other computations; try again shortly")
        try:
            future: Future[T] = pool.submit(fn, *args)
        except BaseException:
            self._slots.release()
            raise
        future.add_done_callback(lambda _: self._slots.release())
        if pool is self._pool:  # a computation on a thread: its garbage is in this process
            self._done += 1
            full = self._done % 32 == 0
            future.add_done_callback(lambda _: release_memory(full))
        # The time limit counts the computation, not its wait in the queue behind others.
        while not (future.running() or future.done()):
            await asyncio.sleep(0.02)
        try:
            return await asyncio.wait_for(asyncio.wrap_future(future), self.timeout_s)
        except TimeoutError:
            if abandoned is not None:
                future.add_done_callback(lambda _: abandoned())
            raise ComputeTimeoutError(self.timeout_s) from None

    def shutdown(self) -> None:
        """Drop queued computations; running ones finish in their threads or processes."""
        self._pool.shutdown(wait=False, cancel_futures=True)
        with self._lock:
            pool, self._process_pool = self._process_pool, None
            self._warm = []
        if pool is not None:
            # Not terminated: a worker killed under its pipe would break it (EPIPE; fatal to a
            # process where a library reset SIGPIPE, as gmsh does). A job that timed out ends on
            # its own, its result dropped.
            pool.shutdown(wait=False, cancel_futures=True)
