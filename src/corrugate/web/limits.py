"""Bounds that make the web app safe to leave running: request body size and computation time.

* :class:`BodySizeLimit` is a pure ASGI middleware: it reads a request body (up to the limit) before
  the app sees it and answers 413 past the limit, whether or not the client sent Content-Length.
* :class:`Runner` runs computations on a small thread pool, raises :class:`ServerBusyError` when
  too many are in flight (including abandoned ones still running) and
  :class:`ComputeTimeoutError` past the time limit.
  A Python thread cannot be killed: a computation that times out runs on in the background, holds
  its slot until it ends, and its result is dropped. After each computation the thread returns
  freed memory to the system (:func:`release_memory`), so that the resident size stays bounded
  (``benchmarks/web_memory.py`` measures it).
* :class:`CatchAll` is the innermost middleware: an exception no handler took (a bug, or an input
  that still got past the limits of :mod:`corrugate.limits`) becomes one clean JSON error, 422
  (or 503 for a server-side OS error or lack of memory), never a 500 or a dropped connection;
  the traceback goes to the log.
"""

from __future__ import annotations

import asyncio
import ctypes
import gc
import json
import logging
import threading
from collections.abc import Awaitable, Callable, MutableMapping
from concurrent.futures import Future, ThreadPoolExecutor
from typing import Any, TypeVar

__all__ = [
    "BodySizeLimit",
    "CatchAll",
    "ComputeTimeoutError",
    "HostCheck",
    "Runner",
    "ServerBusyError",
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
            from ..errors import CorrugateError, describe

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


class Runner:
    """Run blocking computations on ``workers`` threads with a time limit of ``timeout_s``.

    At most ``max_pending`` computations may be queued or running at once (a timed-out one counts
    until it really ends); past that :meth:`run` raises :class:`ServerBusyError` at once.
    """

    def __init__(self, workers: int, max_pending: int, timeout_s: float) -> None:
        self.timeout_s = timeout_s
        self._pool = ThreadPoolExecutor(max_workers=workers, thread_name_prefix="corrugate-web")
        self._slots = threading.BoundedSemaphore(max_pending)
        self._done = 0

    async def run(self, fn: Callable[[], T]) -> T:
        """The result of ``fn()``, computed on the pool; its exceptions propagate."""
        if not self._slots.acquire(blocking=False):
            raise ServerBusyError("the server is busy with other computations; try again shortly")
        try:
            future: Future[T] = self._pool.submit(fn)
        except BaseException:
            self._slots.release()
            raise
        future.add_done_callback(lambda _: self._slots.release())
        self._done += 1
        full = self._done % 32 == 0
        future.add_done_callback(lambda _: release_memory(full))  # after the answer is sent
        try:
            return await asyncio.wait_for(asyncio.wrap_future(future), self.timeout_s)
        except TimeoutError:
            raise ComputeTimeoutError(self.timeout_s) from None

    def shutdown(self) -> None:
        """Drop queued computations; running ones finish in their threads."""
        self._pool.shutdown(wait=False, cancel_futures=True)
