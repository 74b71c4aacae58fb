"""``corrugate serve``: run the local web app (needs the ``web`` extra).

Registered by :mod:`corrugate.cli` (see :data:`COMMANDS`). FastAPI and uvicorn are imported only when the command
runs, so the rest of the command line works without them.
"""

from __future__ import annotations

from types import FrameType
from typing import Annotated, Any

import typer

__all__ = [
    "COMMANDS",
    "HEAD_TIMEOUT_S",
    "LOOPBACK_HOSTS",
    "MAX_CONNECTIONS",
    "RESERVED_FDS",
    "check_listen",
    "connection_limit",
    "serve_cmd",
]

#: Hosts that only this machine can reach.
LOOPBACK_HOSTS = ("127.0.0.1", "localhost", "::1")


def serve_cmd(
    host: Annotated[
        str,
        typer.Option(
            metavar="HOST", help="Address to listen on; 127.0.0.1 keeps it on this machine."
        ),
    ] = "127.0.0.1",
    port: Annotated[int, typer.Option(min=1, max=65535, help="TCP port.")] = 8000,
    timeout: Annotated[
        float,
        typer.Option(
            min=0.1,
            help="Longest computation of one request (s): past it the request gets 504 and the worker process computing it is killed.",
        ),
    ] = 30.0,
    budget: Annotated[
        float | None,
        typer.Option(
            metavar="SECONDS",
            help="CPU seconds the solver may spend on one design, explanation included (default: 60 % of --timeout): past it the design is answered 'not certified within the budget' with the best design found so far.",
        ),
    ] = None,
    job_budget: Annotated[
        float,
        typer.Option(
            metavar="SECONDS",
            help="CPU seconds the solver may spend on one design job (the page's designs, POST /api/jobs/design) unless the client asks for another budget: the job is stopped after 4 wall seconds per budget second.",
        ),
    ] = 120.0,
    max_job_budget: Annotated[
        float,
        typer.Option(
            metavar="SECONDS",
            help="Largest solver budget a client may ask of a design job (query budget; more is refused with 422 naming budget and the range); at least --job-budget.",
        ),
    ] = 600.0,
    max_queued_jobs: Annotated[
        int,
        typer.Option(
            min=0,
            max=1000,
            metavar="N",
            help="Jobs that may wait for a worker of the job pool; past them a new job is refused at once with 503 and Retry-After (never accepted, then failed).",
        ),
    ] = 16,
) -> None:
    """Serve the web app and its JSON API (open http://HOST:PORT/, API docs at /docs).

    Limits: requests (analyses, meshes, patterns, spec files, POST /api/design) run in a quick
    lane of 2 worker processes, designs in at most one of them, so an analysis never waits
    behind a design or a job; jobs (POST /api/jobs/...) run in a pool of their own (one worker
    per core, at least 2), with at most --max-queued-jobs waiting. A request head must arrive
    within 10 s of its connection (else 408 and the connection is closed); at most 1000
    connections are open at once (fewer if the open-file limit is lower: each needs a file
    descriptor), a connection past them gets 503 and is closed at once. CalculiX work folders
    that no running process owns are removed at start-up (docs: corrugate docs fea).

    Example: corrugate serve --port 8000
    """
    from corrugate.core.extras import require_extra
    from corrugate.core.limits import check

    require_extra("web", "the web app")
    require_extra("fab", "the web app's files")

    from corrugate.web import WebSettings, create_app
    from corrugate.web.app import LOOPBACK_NAMES

    check_listen(host, port)  # before the worker processes start, and before any warning
    loopback = host in LOOPBACK_HOSTS
    if not loopback:
        typer.echo(
            f"corrugate: warning: serving on {host}: other machines can reach this app",
            err=True,
        )
    # On a loopback address only this machine's names are answered (no DNS rebinding).
    if budget is not None:
        check("budget", budget, "--budget")
    check("budget", job_budget, "--job-budget")
    check("budget", max_job_budget, "--max-job-budget")
    if job_budget > max_job_budget:
        from corrugate.core.errors import InputError

        raise InputError(
            "--job-budget",
            f"{job_budget:g}",
            f"at most --max-job-budget ({max_job_budget:g} s)",
        )
    settings = WebSettings(
        timeout_s=timeout,
        solver_budget_s=budget,
        job_budget_s=job_budget,
        max_job_budget_s=max_job_budget,
        max_queued_jobs=max_queued_jobs,
        allowed_hosts=LOOPBACK_NAMES if loopback else None,
    )
    shown = f"[{host}]" if ":" in host else host
    typer.echo(f"corrugate: serving on http://{shown}:{port}/ (API docs at /docs); Ctrl-C stops")
    app = create_app(settings)
    server = _server(app, host, port)
    server.run()


def check_listen(host: str, port: int) -> None:
    """Refuse ``--host`` and ``--port`` the server could not listen on, one
    :class:`~corrugate.core.errors.InputError` line each: a name that does not resolve, an
    address that is not this machine's, a port in use or one this user may not bind (below 1024).
    Each address the name resolves to is bound once and released, as uvicorn's listener binds
    them (``SO_REUSEADDR``); uvicorn itself logs such an error and exits with its code 3, which
    is corrugate's exit code for a bug."""
    import errno
    import socket

    from corrugate.core.errors import InputError

    try:
        found = socket.getaddrinfo(host, port, type=socket.SOCK_STREAM, flags=socket.AI_PASSIVE)
    except (socket.gaierror, UnicodeError) as exc:
        why = exc.strerror if isinstance(exc, socket.gaierror) else "not a host name"
        raise InputError(
            "--host",
            host,
            "a name or address of this machine, e.g. 127.0.0.1, ::1 or 0.0.0.0",
            reason=f"cannot be resolved ({why})",
        ) from None
    for family, kind, proto, _, address in found:
        with socket.socket(family, kind, proto) as sock:
            sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
            if family == socket.AF_INET6 and hasattr(socket, "IPPROTO_IPV6"):
                sock.setsockopt(socket.IPPROTO_IPV6, socket.IPV6_V6ONLY, 1)
            try:
                sock.bind(address)
            except OSError as exc:
                if exc.errno == errno.EADDRINUSE:
                    raise InputError(
                        "--port", port, "a free TCP port", reason="is in use on this machine"
                    ) from None
                if exc.errno == errno.EACCES:
                    raise InputError(
                        "--port",
                        port,
                        "a port this user may listen on (1024 to 65535 without privileges)",
                        reason=f"cannot be listened on ({exc.strerror})",
                    ) from None
                raise InputError(
                    "--host",
                    host,
                    "an address of this machine, e.g. 127.0.0.1, ::1 or 0.0.0.0",
                    reason=f"cannot be listened on ({exc.strerror})",
                ) from None


#: A request's head must arrive within this many seconds of its connection (or of the previous
#: answer on a kept-alive one), else 408 and the connection is closed.
HEAD_TIMEOUT_S = 10.0

#: Open connections at most (a connection past them gets 503 and is closed at once). A
#: connection whose request head is still arriving lasts at most HEAD_TIMEOUT_S, so slow clients
#: hold few of them for long.
MAX_CONNECTIONS = 1000

#: File descriptors kept for the server's own use beyond its connections (its listening socket,
#: event loop, worker pipes, the forkserver, logs, files being served or zipped).
RESERVED_FDS = 64


def connection_limit(wanted: int = MAX_CONNECTIONS) -> int:
    """The open connections the server can hold: ``wanted``, or fewer when the open-file limit
    (``RLIMIT_NOFILE``, raised to its hard limit first) leaves fewer than ``wanted`` after
    :data:`RESERVED_FDS` (at least 8). A server out of file descriptors stops accepting, and a
    connection not accepted is under no deadline: the head deadline holds only within this."""
    try:
        import resource

        soft, hard = resource.getrlimit(resource.RLIMIT_NOFILE)
        goal = wanted + RESERVED_FDS
        if soft != resource.RLIM_INFINITY and soft < goal:
            raised = goal if hard == resource.RLIM_INFINITY else min(goal, hard)
            if raised > soft:
                resource.setrlimit(resource.RLIMIT_NOFILE, (raised, hard))
                soft = raised
    except (ImportError, ValueError, OSError):
        return wanted
    if soft == resource.RLIM_INFINITY:
        return wanted
    return max(8, min(wanted, soft - RESERVED_FDS))


def _server(app: Any, host: str, port: int) -> Any:
    """The uvicorn server of ``app``: slow request heads timed out and connections bounded by
    the file descriptors the process may open (:func:`corrugate.web.guards.slow_client_protocol`,
    :func:`connection_limit`), idle connections closed after 5 s, and on SIGTERM or Ctrl-C the
    app's worker processes killed at once (their requests get 503) before uvicorn's graceful
    shutdown, which waits at most 5 s for answers still on their way."""
    import uvicorn

    from corrugate.web.guards import slow_client_protocol

    runners = (app.state.quick, app.state.runner)

    class Server(uvicorn.Server):
        def handle_exit(self, sig: int, frame: FrameType | None) -> None:
            for runner in runners:
                runner.kill_workers()
            super().handle_exit(sig, frame)

    limit = connection_limit()
    config = uvicorn.Config(
        app,
        host=host,
        port=port,
        log_level="info",
        http=slow_client_protocol(HEAD_TIMEOUT_S, limit),
        limit_concurrency=limit,
        timeout_keep_alive=5,
        timeout_graceful_shutdown=5,
    )
    return Server(config)


#: The commands of this module, by name (registered by :mod:`corrugate.cli`).
COMMANDS = {"serve": serve_cmd}
