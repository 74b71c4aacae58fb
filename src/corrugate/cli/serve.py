"""``corrugate serve``: run the local web app (needs the ``web`` extra).

Registered by :mod:`corrugate.cli` (see :data:`COMMANDS`). FastAPI and uvicorn are imported only when the command
runs, so the rest of the command line works without them.
"""

from __future__ import annotations

from typing import Annotated

import typer

__all__ = ["COMMANDS", "LOOPBACK_HOSTS", "serve_cmd"]

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
        float, typer.Option(min=0.1, help="Longest computation of one request (s).")
    ] = 30.0,
) -> None:
    """Serve the web app and its JSON API (open http://HOST:PORT/, API docs at /docs).

    Example: corrugate serve --port 8000
    """
    from corrugate.core.extras import require_extra

    require_extra("web", "the web app")
    require_extra("fab", "the web app's files")
    import uvicorn

    from corrugate.web import WebSettings, create_app
    from corrugate.web.app import LOOPBACK_NAMES

    loopback = host in LOOPBACK_HOSTS
    if not loopback:
        typer.echo(
            f"corrugate: warning: serving on {host}: other machines can reach this app",
            err=True,
        )
    # On a loopback address only this machine's names are answered (no DNS rebinding).
    settings = WebSettings(timeout_s=timeout, allowed_hosts=LOOPBACK_NAMES if loopback else None)
    shown = f"[{host}]" if ":" in host else host
    typer.echo(f"corrugate: serving on http://{shown}:{port}/ (API docs at /docs); Ctrl-C stops")
    # At most 100 open connections (uvicorn answers 503 past that), idle ones closed after 5 s.
    uvicorn.run(
        create_app(settings),
        host=host,
        port=port,
        log_level="info",
        limit_concurrency=100,
        timeout_keep_alive=5,
    )


#: The commands of this module, by name (registered by :mod:`corrugate.cli`).
COMMANDS = {"serve": serve_cmd}
