"""Fixtures of the web tests: an in-process client and a real uvicorn server on a free port."""

from __future__ import annotations

import json
import socket
import threading
import time
import urllib.error
import urllib.request
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

import pytest
import uvicorn
from fastapi import FastAPI
from fastapi.testclient import TestClient

from corrugate import Assembly, Layer, analyze, get_material, make_layout
from corrugate.web import WebSettings, create_app
from corrugate.web.app import LOOPBACK_NAMES

#: The paper's Table 1, case 1 (EI(0) = 87.84 mN m^2 with the paper's formulas).
CASE1: dict[str, Any] = {
    "W": 8,
    "n": 8,
    "alpha": 84,
    "material": "dura-lar",
    "model": "paper",
    "eta": [0, 90],
}


def post_json(base: str, path: str, body: dict[str, Any], timeout: float = 60) -> tuple[int, Any]:
    """POST ``body`` as JSON to a served app: its status and JSON answer (errors included)."""
    request = urllib.request.Request(
        base + path,
        data=json.dumps(body).encode(),
        headers={"content-type": "application/json"},
        method="POST",
    )
    try:
        with urllib.request.urlopen(request, timeout=timeout) as response:
            return response.status, json.loads(response.read())
    except urllib.error.HTTPError as exc:
        return exc.code, json.loads(exc.read())


def with_files(client: TestClient, answer: dict[str, Any]) -> dict[str, Any]:
    """A design answer with its files made: ``POST /api/design`` answers first, its files are
    made on demand by ``POST files_url`` (docs/web.md); ``result`` is then that stored result."""
    if answer["result"] is not None or answer["files_url"] is None:
        return answer
    r = client.post(answer["files_url"])
    assert r.status_code == 200, r.text
    return {**answer, "result": r.json()}


def served_files(base: str, answer: dict[str, Any], timeout: float = 900) -> dict[str, Any]:
    """:func:`with_files` for a served app (``base`` its URL); ``timeout`` only guards against a
    hang (files asked for by many clients at once queue behind one worker on a loaded machine)."""
    if answer["result"] is not None or answer["files_url"] is None:
        return answer
    status, made = post_json(base, answer["files_url"], {}, timeout=timeout)
    assert status == 200, made
    return {**answer, "result": made}


def direct(body: dict[str, Any]) -> dict[str, Any]:
    """What the API must answer for a numeric ``body`` (W, n, alpha, material and optionally W2,
    n2, layout, model, eta): :func:`corrugate.analyze` called directly on the objects, through
    JSON."""
    m = get_material(body.get("material", "dura-lar"))
    layer1 = Layer(float(body["W"]), int(body["n"]), float(body["alpha"]), m)
    layer2 = Layer(
        float(body.get("W2", body["W"])), int(body.get("n2", body["n"])), float(body["alpha"]), m
    )
    assembly = Assembly(layer1, layer2, make_layout(body.get("layout", "square")))
    etas = [float(e) for e in body.get("eta", [0, 90])]
    result = analyze(assembly, body.get("model", "refined"), etas).to_dict()
    decoded: dict[str, Any] = json.loads(json.dumps(result))
    return decoded


#: Fixtures that start an app with its design worker processes: each process imports the package
#: (about 1 s of CPU, which --durations does not show), so their tests are ``slow``.
APP_FIXTURES = {"client", "live_server", "served"}


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    """Mark ``slow`` every test that uses an app of :data:`APP_FIXTURES` (``make test-fast``
    leaves them out; ``make test`` runs them)."""
    for item in items:
        if APP_FIXTURES & set(getattr(item, "fixturenames", ())):
            item.add_marker(pytest.mark.slow)


@pytest.fixture
def client() -> Iterator[TestClient]:
    """A client of a fresh app (its own workers and result store), lifespan included; its tests
    are marked slow (:func:`pytest_collection_modifyitems`)."""
    with TestClient(create_app()) as c:
        yield c


def wait_for(condition: Any, seconds: float, what: str) -> None:
    """Poll ``condition`` every 0.05 s until it holds; fail the test after ``seconds``."""
    deadline = time.monotonic() + seconds
    while not condition():
        if time.monotonic() > deadline:
            pytest.fail(f"not within {seconds} s: {what}")
        time.sleep(0.05)


def _wait(condition: Any, what: str, thread: threading.Thread) -> None:
    for _ in range(1000):  # at most about 10 s
        if condition():
            return
        if not thread.is_alive():
            break
        time.sleep(0.01)
    pytest.fail(f"the test server did not {what}")


@contextmanager
def serve(settings: WebSettings) -> Iterator[tuple[str, FastAPI]]:
    """A real uvicorn server of a fresh app with ``settings`` on 127.0.0.1 (a free port, bound
    before it starts) in a thread: yields its base URL and the app, and stops it after."""
    sock = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    sock.bind(("127.0.0.1", 0))
    port = sock.getsockname()[1]
    app = create_app(settings)
    config = uvicorn.Config(app, host="127.0.0.1", port=port, log_level="warning", lifespan="on")
    server = uvicorn.Server(config)
    thread = threading.Thread(target=server.run, kwargs={"sockets": [sock]}, daemon=True)
    thread.start()
    try:
        _wait(lambda: server.started, "start", thread)
        yield f"http://127.0.0.1:{port}", app
    finally:
        server.should_exit = True
        thread.join(timeout=10)
        sock.close()
        assert not thread.is_alive(), "the test server did not stop"


@pytest.fixture(scope="module")
def live_server() -> Iterator[str]:
    """A real uvicorn server on 127.0.0.1 (:func:`serve`); yields its base URL and shuts itself
    down after the module's tests."""
    # A generous time limit: twenty designs queue behind the workers on a slow machine (the
    # limit itself is tested in test_api.py and test_server.py).
    settings = WebSettings(max_pending=64, timeout_s=120, allowed_hosts=LOOPBACK_NAMES)
    with serve(settings) as (base, _):
        yield base
