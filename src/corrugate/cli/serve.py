"""``corrugate serve``: run the local web app (needs the ``web`` extra).

Registered by :mod:`corrugate.cli` (see :data:`COMMANDS`). FastAPI and uvicorn are imported only when the command
runs, so the rest of the command line works without them.
"""

from __future__ import annotations

from types import FrameType
from typing import Annotated, Any

import typer

__all__ = ["COMMANDS", "HEAD_TIMEOUT_S", "LOOPBACK_HOSTS", "MAX_CONNECTIONS", "serve_cmd"]

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
            help="CPU seconds the solver may spend on one design job (the page's designs, POST /api/jobs/design; a client may ask for up to 600 or this, whichever is more): the job is stopped after 4 wall seconds per budget second.",
        ),
    ] = 120.0,
) -> None:
    """Serve the web app and its JSON API (open http://HOST:PORT/, API docs at /docs).

    Example: corrugate serve --port 8000
    """
    from corrugate.core.extras import require_extra
    from corrugate.core.limits import check

    require_extra("web", "the web app")
    require_extra("fab", "the web app's files")

    from corrugate.web import WebSettings, create_app
    from corrugate.web.app import LOOPBACK_NAMES

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
    settings = WebSettings(
        timeout_s=timeout,
        solver_budget_s=budget,
        job_budget_s=job_budget,
        max_job_budget_s=max(job_budget, WebSettings().max_job_budget_s),
        allowed_hosts=LOOPBACK_NAMES if loopback else None,
    )
    shown = f"[{host}]" if ":" in host else host
    typer.echo(f"corrugate: serving on http://{shown}:{port}/ (API docs at /docs); Ctrl-C stops")
    app = create_app(settings)
    server = _server(app, host, port)
    server.run()


#: A request's head must arrive within this many seconds of its connection (or of the previous
#: answer on a kept-alive one), else 408 and the connection is closed.
HEAD_TIMEOUT_S = 10.0

#: Open connections at most (uvicorn answers 503 past it). A connection whose request head is
#: still arriving lasts at most HEAD_TIMEOUT_S, so slow clients hold few of them for long.
MAX_CONNECTIONS = 1000


def _server(app: Any, host: str, port: int) -> Any:
    """The uvicorn server of ``app``: slow request heads timed out
    (:func:`corrugate.web.guards.slow_client_protocol`), idle connections closed after 5 s, and on
    SIGTERM or Ctrl-C the app's worker processes killed at once (their requests get 503) before
    uvicorn's graceful shutdown, which waits at most 5 s for answers still on their way."""
    import uvicorn

    from corrugate.web.guards import slow_client_protocol

    runner = app.state.runner

    class Server(uvicorn.Server):
        def handle_exit(self, sig: int, frame: FrameType | None) -> None:
            runner.kill_workers()
            super().handle_exit(sig, frame)

    config = uvicorn.Config(
        app,
        host=host,
        port=port,
        log_level="info",
        http=slow_client_protocol(HEAD_TIMEOUT_S),
        limit_concurrency=MAX_CONNECTIONS,
        timeout_keep_alive=5,
        timeout_graceful_shutdown=5,
    )
    return Server(config)


#: The commands of this module, by name (registered by :mod:`corrugate.cli`).
COMMANDS = {"serve": serve_cmd}
