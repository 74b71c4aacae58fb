"""Bounds that make the web app safe to leave running: request size, reading time and hosts.

* :class:`BodySizeLimit` is a pure ASGI middleware: it reads a request body (up to the limit,
  within a time limit) before the app sees it and answers 413 past the size limit, whether or not
  the client sent Content-Length, 408 when the body does not arrive in time, and 422 naming the
  key to a JSON body holding an integer beyond ``int()``'s 4300 digits (which FastAPI's reader
  answers 400, naming no key).
* :func:`slow_client_protocol` is uvicorn's HTTP/1.1 protocol with a deadline for each request
  head: a connection that has not sent a complete head within it gets 408 and is closed, so
  clients that trickle bytes cannot hold the server's connections.
* :func:`long_integers` (a dependency of every route) answers 422 naming the key to a JSON body
  holding an integer of more than 30 digits, before pydantic converts it to a float.
* :class:`HostCheck` answers 400 to a Host header that is not this server's (DNS rebinding).
* :class:`CatchAll` is the innermost middleware: an exception no handler took (a bug, or an input
  that still got past the limits of :mod:`corrugate.core.limits`) becomes one clean JSON error, 422
  (or 503 for a server-side OS error or lack of memory), never a 500 or a dropped connection;
  the traceback goes to the log.

The computations themselves run in killable worker processes: :mod:`corrugate.web.workers`.
"""

from __future__ import annotations

import asyncio
import json
import logging
import re
import time
from collections.abc import Awaitable, Callable, MutableMapping
from typing import Any, TypeVar

from starlette.requests import Request
from uvicorn.protocols.http.h11_impl import H11Protocol

from corrugate.core.errors import InputError
from corrugate.core.limits import MAX_INT_DIGITS, check_integer

__all__ = [
    "BodySizeLimit",
    "CatchAll",
    "HostCheck",
    "host_name",
    "long_integers",
    "slow_client_protocol",
]

_log = logging.getLogger("corrugate.web")

T = TypeVar("T")

Scope = MutableMapping[str, Any]
Message = MutableMapping[str, Any]
Receive = Callable[[], Awaitable[Message]]
Send = Callable[[Message], Awaitable[None]]
ASGIApp = Callable[[Scope, Receive, Send], Awaitable[None]]


class BodySizeLimit:
    """ASGI middleware: HTTP request bodies longer than ``max_bytes`` get 413 and never reach the app;
    a body not complete within ``timeout_s`` of the request's head gets 408 (and the connection
    is closed).

    The body is read whole (at most ``max_bytes``) and replayed to the app, so a client that lies in
    Content-Length or streams chunks cannot get past the limit.
    """

    def __init__(self, app: ASGIApp, max_bytes: int, timeout_s: float | None = None) -> None:
        self.app = app
        self.max_bytes = max_bytes
        self.timeout_s = timeout_s

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
        deadline = None if self.timeout_s is None else time.monotonic() + self.timeout_s
        while True:
            try:
                left = None if deadline is None else max(0.0, deadline - time.monotonic())
                message = await asyncio.wait_for(receive(), left)
            except TimeoutError:
                await self._reject(
                    send, 408, f"the request body did not arrive within {self.timeout_s:g} s"
                )
                return
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
        beyond = _beyond_int(whole)  # FastAPI's JSON reader would answer 400, naming no key
        if beyond is not None:
            await self._reject(send, 422, str(beyond), field=beyond.field)
            return

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


#: The answer to a client whose request head is late (then the connection is closed).
_HEAD_LATE = b"the request head did not arrive in time"
_REQUEST_TIMEOUT = (
    b"HTTP/1.1 408 Request Timeout\r\ncontent-type: text/plain; charset=utf-8\r\n"
    b"connection: close\r\ncontent-length: %d\r\n\r\n%s" % (len(_HEAD_LATE), _HEAD_LATE)
)
#: The answer to a connection past the server's limit (then it is closed at once).
_FULL = b"too many open connections; try again shortly"
_TOO_MANY = (
    b"HTTP/1.1 503 Service Unavailable\r\ncontent-type: text/plain; charset=utf-8\r\n"
    b"retry-after: 1\r\nconnection: close\r\ncontent-length: %d\r\n\r\n%s" % (len(_FULL), _FULL)
)


class _HeadDeadline(H11Protocol):
    """uvicorn's HTTP/1.1 protocol (h11) with a deadline for each request head, counted from the
    connection's start and from the end of each response: see :func:`slow_client_protocol`."""

    head_timeout_s = 10.0
    max_connections: int | None = None
    _head_timer: asyncio.TimerHandle | None = None
    _head_of: object = None
    _head_bytes = False

    def connection_made(self, transport: asyncio.Transport) -> None:  # type: ignore[override]
        super().connection_made(transport)
        if self.max_connections is not None and len(self.connections) > self.max_connections:
            transport.write(_TOO_MANY)  # never accepted into the server's work: closed now
            transport.close()
            return
        self._arm()

    def data_received(self, data: bytes) -> None:
        self._head_bytes = True
        super().data_received(data)

    def handle_events(self) -> None:
        super().handle_events()
        if self._head_timer is not None and self.cycle is not self._head_of:
            self._disarm()  # a new request's head is complete

    def on_response_complete(self) -> None:
        done = self.cycle
        super().on_response_complete()
        if not self.transport.is_closing() and self.cycle is done:
            self._arm()  # the next request's head is due (a keep-alive connection)

    def connection_lost(self, exc: Exception | None) -> None:
        self._disarm()
        super().connection_lost(exc)

    def _arm(self) -> None:
        self._disarm()
        self._head_of = self.cycle
        self._head_bytes = False
        self._head_timer = self.loop.call_later(self.head_timeout_s, self._expired)

    def _disarm(self) -> None:
        if self._head_timer is not None:
            self._head_timer.cancel()
            self._head_timer = None

    def _expired(self) -> None:
        self._head_timer = None
        if self.transport.is_closing() or self.cycle is not self._head_of:
            return
        if self._head_bytes:  # part of a request came: say why it is closed
            self.transport.write(_REQUEST_TIMEOUT)
        self.transport.close()


def slow_client_protocol(
    head_timeout_s: float, max_connections: int | None = None
) -> type[asyncio.Protocol]:
    """uvicorn's HTTP/1.1 protocol class (``uvicorn.run(http=...)``) with a deadline for the
    request head: a connection that has not sent a complete request head within
    ``head_timeout_s`` of its start (or of the previous response) gets 408 and is closed (one
    that sent nothing is just closed). With :class:`BodySizeLimit`'s body deadline, a client that
    trickles bytes holds a connection for a bounded time. A connection accepted while
    ``max_connections`` are open (None: no limit) gets 503 and is closed at once, so the server
    never runs out of file descriptors: while it has none, it cannot accept, and a connection
    waiting to be accepted is under no deadline."""
    return type(
        "SlowClientProtocol",
        (_HeadDeadline,),
        {"head_timeout_s": head_timeout_s, "max_connections": max_connections},
    )


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


#: A run of more digits than an integer of any input may have (a fast screen of a body's bytes).
_LONG_DIGITS = re.compile(rb"[0-9]{%d,}" % (MAX_INT_DIGITS + 1))


#: A run of more digits than Python's ``int()`` converts (``sys.get_int_max_str_digits``).
_BEYOND_INT = re.compile(rb"[0-9]{4301,}")


def _beyond_int(body: bytes) -> InputError | None:
    """The error for a JSON ``body`` holding an integer of more than 4300 digits, which
    ``json.loads`` refuses with a ValueError (FastAPI's reader then answers 400 "There was an
    error parsing the body", before any dependency runs): one
    :class:`~corrugate.core.errors.InputError` naming the key before it; None for any other body
    (one regular-expression scan; a run of digits in a string, or a body that is not JSON, is
    left to the route)."""
    m = _BEYOND_INT.search(body)
    if m is None:
        return None
    try:
        json.loads(body)
    except json.JSONDecodeError:  # not JSON at all: the route says so
        return None
    except ValueError:  # the integer beyond int()
        keys = re.findall(rb'"([^"\\]{1,80})"\s*:', body[max(0, m.start() - 400) : m.start()])
        return InputError(
            keys[-1].decode("utf-8", "replace") if keys else "body",
            f"an integer of {len(m.group(0))} digits",
            f"a number of at most {MAX_INT_DIGITS} digits",
            reason="is too long",
        )
    return None


async def long_integers(request: Request) -> None:
    """A dependency of every route, run before the body is validated: a JSON body holding an
    integer of more than :data:`~corrugate.core.limits.MAX_INT_DIGITS` digits (``10**400`` as
    ``deflection.max``, where a float conversion would overflow) is one
    :class:`~corrugate.core.errors.InputError` naming its key (``constraints.side.min``, ``W``,
    ``eta[0]``), answered 422. Bodies without such a run of digits cost one regular-expression
    scan."""
    if request.method not in ("POST", "PUT", "PATCH"):
        return
    body = await request.body()  # cached: the route reads the same bytes
    if _LONG_DIGITS.search(body) is None:
        return
    try:
        data = json.loads(body)
    except ValueError:  # malformed: the route says so (beyond int(): BodySizeLimit's 422)
        return
    stack: list[tuple[Any, str]] = [(data, "")]
    while stack:
        obj, path = stack.pop()
        if isinstance(obj, int) and not isinstance(obj, bool):
            check_integer(path or "body", obj)
        elif isinstance(obj, dict):
            stack.extend((v, f"{path}.{k}" if path else str(k)) for k, v in obj.items())
        elif isinstance(obj, list):
            stack.extend((v, f"{path}[{i}]") for i, v in enumerate(obj))
