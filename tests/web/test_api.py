"""The JSON API in process (FastAPI's TestClient): answers, validation, limits and downloads."""

from __future__ import annotations

import asyncio
import io
import json
import os
import signal
import subprocess
import sys
import threading
import time
import urllib.error
import urllib.request
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import trimesh
from fastapi.testclient import TestClient

import corrugate.web.app as web_app
from corrugate import Assembly, Layer, get_material
from corrugate.core.errors import InputError
from corrugate.export.writers import WRITERS
from corrugate.fabrication.build import build_pattern
from corrugate.fabrication.folded import folded_mesh
from corrugate.web import WebSettings, create_app
from corrugate.web.app import STATIC_DIR
from corrugate.web.schemas import AnalyzeBody
from corrugate.web.workers import (
    ComputeTimeoutError,
    Runner,
    ServerBusyError,
    WorkerLostError,
)

from .conftest import CASE1, direct


def alive(client: TestClient) -> None:
    """The app still answers normally."""
    r = client.get("/api/materials")
    assert r.status_code == 200 and any(m["id"] == "dura-lar" for m in r.json())


# ---- answers ------------------------------------------------------------------------------


def test_analyze_returns_the_cli_json_object(client: TestClient) -> None:
    r = client.post("/api/analyze", json=CASE1)
    assert r.status_code == 200
    d = r.json()
    assert d == direct(CASE1)
    assert d["stiffness"][0]["EI_Nmm2"] / 1000 == pytest.approx(87.84, abs=0.005)  # Table 1
    assert r.headers["cache-control"] == "no-store"


def test_analyze_equals_the_cli_json(
    client: TestClient, capsys: pytest.CaptureFixture[str]
) -> None:
    """The same options, some with units, give the very object `corrugate analyze --json` prints."""
    from corrugate.cli import main

    body = {
        "W": "0.3 in",
        "n": "9",
        "alpha": "1.4 rad",
        "E": "2.7GPa",
        "nu": 0.43,
        "density": "1.39 g/cm^3",
        "thickness": "5 mil",
        "W2": 6,
        "n2": 12,
        "layout": "rectangle",
        "model": "xia",
        "eta": [0, "30 deg", 90],
    }
    args = ["analyze", "--json"]
    for key, value in body.items():
        for v in value if isinstance(value, list) else [value]:
            args += [f"--{key}", str(v)]
    with pytest.raises(SystemExit) as exc:
        main(args)
    assert exc.value.code in (0, None)
    cli = json.loads(capsys.readouterr().out)
    r = client.post("/api/analyze", json=body)
    assert r.status_code == 200
    assert r.json() == cli
    assert [s["eta_deg"] for s in cli["stiffness"]] == [0, 30, 90]


def test_materials_and_models(client: TestClient) -> None:
    materials = client.get("/api/materials").json()
    dura = next(m for m in materials if m["id"] == "dura-lar")
    assert dura["default_thickness_mm"] == 0.125
    models = client.get("/api/models").json()
    assert models["default"] == "refined"
    assert {m["name"] for m in models["models"]} == {"paper", "xia", "refined"}


def test_formats_are_the_writers_registry(client: TestClient) -> None:
    r = client.get("/api/formats")
    assert r.status_code == 200 and r.headers["cache-control"] == "no-store"
    keys = ("name", "pattern", "media_type", "extra", "description", "order")
    assert r.json() == [{k: getattr(w, k) for k in keys} for w in WRITERS]
    # documented in the OpenAPI document, with the fields of each entry
    spec = client.get("/openapi.json").json()
    answer = spec["paths"]["/api/formats"]["get"]["responses"]["200"]["content"]
    ref = answer["application/json"]["schema"]["items"]["$ref"]
    schema = spec["components"]["schemas"][ref.rsplit("/", 1)[-1]]
    assert set(schema["properties"]) == set(keys)
    assert all(schema["properties"][k].get("description") for k in keys)


def test_mesh_is_the_folded_assembly_as_glb(client: TestClient) -> None:
    r = client.post("/api/mesh", json=CASE1)
    assert r.status_code == 200
    result = r.json()
    files = {f["name"]: f for f in result["files"]}
    assert set(files) == {"assembly.glb", "assembly.stl"}
    glb = client.get(files["assembly.glb"]["url"])
    assert glb.status_code == 200
    assert glb.headers["content-type"] == "model/gltf-binary"
    assert glb.content[:4] == b"glTF" and len(glb.content) == files["assembly.glb"]["bytes"]
    layer = Layer(8, 8, 84, get_material("dura-lar"))
    a = Assembly.identical(layer)
    vertices, faces = folded_mesh(a, build_pattern(a).parts)
    loaded = trimesh.load(io.BytesIO(glb.content), file_type="glb", force="mesh", process=False)
    assert len(loaded.faces) == len(faces)
    assert np.asarray(loaded.bounds).ravel() == pytest.approx(
        np.concatenate([vertices.min(axis=0), vertices.max(axis=0)])
    )


def test_two_meshes_get_two_ids(client: TestClient) -> None:
    a = client.post("/api/mesh", json=CASE1).json()
    b = client.post("/api/mesh", json={**CASE1, "n": 10}).json()
    assert a["id"] != b["id"]
    ga = client.get(a["files"][0]["url"]).content
    gb = client.get(b["files"][0]["url"]).content
    assert ga != gb


def test_docs_work_offline(client: TestClient) -> None:
    """Swagger UI comes from the package, not a CDN, and the OpenAPI document lists the API."""
    html = client.get("/docs").text
    assert "cdn" not in html.lower() and "https://" not in html
    for asset in (
        "/static/vendor/swagger-ui/swagger-ui-bundle.js",
        "/static/vendor/swagger-ui/swagger-ui.css",
    ):
        assert asset in html
        assert client.get(asset).status_code == 200
    spec = client.get("/openapi.json").json()
    assert {"/api/analyze", "/api/mesh", "/api/materials", "/api/models", "/api/formats"} <= set(
        spec["paths"]
    )
    schema = spec["components"]["schemas"]["AnalyzeBody"]
    assert {"W", "n", "alpha", "material", "W2", "eta", "model"} <= set(schema["properties"])


def test_page_and_its_files_are_served_locally(client: TestClient) -> None:
    r = client.get("/")
    assert r.status_code == 200 and 'id="analyze-form"' in r.text
    assert "script-src 'self' 'sha256-" in r.headers["content-security-policy"]
    for path in (
        "/static/app.js",
        "/static/style.css",
        "/static/vendor/three/build/three.module.min.js",
        "/static/vendor/three/build/three.core.min.js",
        "/static/vendor/three/examples/jsm/loaders/GLTFLoader.js",
        "/static/vendor/three/examples/jsm/controls/OrbitControls.js",
    ):
        assert client.get(path).status_code == 200, path
    for source in [*STATIC_DIR.glob("*.html"), *STATIC_DIR.glob("*.js")]:
        assert "https://" not in source.read_text(encoding="utf-8"), source


# ---- validation: 4xx naming the field, and the app keeps serving -------------------------------


@pytest.mark.parametrize(
    ("change", "field", "words"),
    [
        ({"alpha": 190}, "alpha", "0 < alpha < 180"),
        ({"alpha2": "200 deg"}, "alpha2", "0 < alpha < 180"),
        ({"W": "8 MPa"}, "W", "wrong dimension"),  # a modulus for a length
        ({"thickness": "2 GPa"}, "thickness", "wrong dimension"),
        ({"material": None, "E": "3 mm", "nu": 0.4, "density": 1.2}, "E", "wrong dimension"),
        ({"material": None, "E": 2700, "nu": 0.4}, "density", "is missing"),
        ({"n": 8.5}, "n", "not an integer"),
        ({"n": "1e9"}, "n", "1 <= n <= 5000"),
        ({"n": "2000"}, "n", "in the web app"),
        ({"W": "8 blorps"}, "W", "unknown unit"),
        ({"material": "unobtainium"}, "material", "is unknown"),
        ({"material2": "unobtainium"}, "material2", "is unknown"),
        ({"model": "magic"}, "model", "is unknown"),
        ({"layout": "hexagon"}, "layout", "is unknown"),
        ({"layout": "polygon", "vertices": "0,0 1"}, "vertices", "cannot be read"),
        ({"W2": 6}, "layout", "rectangle"),
        ({"eta": ["north"]}, "eta", "cannot be read"),
        ({"eta": ["nan"]}, "eta", "is not a number (NaN): allowed -360 <= eta <= 360 deg"),
        ({"eta": [0, "400 deg"]}, "eta", "-360 <= eta <= 360 deg"),
        ({"W": True}, "W", "wrong type"),
        ({"W": [8]}, "W", "wrong type"),
        ({"surprise": 1}, "surprise", "not a field"),
        ({"W": None}, "W", "wrong type"),
        ({"W": 1e300}, "W", "0.01 <= W <= 10000 mm"),
        ({"W": "1e300 m"}, "W", "0.01 <= W <= 10000 mm"),
        ({"W": 1e-320}, "W", "0.01 <= W <= 10000 mm"),
        ({"W2": "2 m", "layout": "rectangle"}, "W2", "in the web app"),
        (
            {"E": 1e306, "nu": 0.3, "density": 1, "thickness": 0.1, "material": None},
            "E",
            "0.001 <= E <= 1e+07 MPa",
        ),
        ({"n": "9" * 100}, "n", "at most 64 characters"),
        ({"eta": list(range(500))}, "eta", "at most 181 items"),
    ],
)
def test_bad_values_get_422_naming_the_field(
    client: TestClient, change: dict[str, Any], field: str, words: str
) -> None:
    body = {k: v for k, v in {**CASE1, **change}.items() if v is not None or k != "material"}
    r = client.post("/api/analyze", json=body)
    assert r.status_code == 422, r.text
    d = r.json()
    assert d["field"] == field
    assert d["errors"][0]["field"] == field
    assert words in d["detail"]
    alive(client)


#: Unit texts that made pint compute (an exponent tower held the interpreter lock and froze every
#: route) or fail outside InputError (422 "internal error" with ``field: null``).
HOSTILE_UNITS = [
    ("1 mm**9**9**9", "exponent of an exponent"),
    ("1 mm^9^9", "exponent of an exponent"),
    ("1 mm/0", "divides its unit by zero"),
    ("1 mm**(1/0)", "parenthesised exponent"),
    ("1 mm**-0", "wrong dimension"),
    ("1 (mm", "unbalanced parenthesis"),
]


@pytest.mark.parametrize(("W", "words"), HOSTILE_UNITS)
def test_hostile_units_get_422_naming_the_field_quickly(
    client: TestClient, W: str, words: str
) -> None:
    assert client.post("/api/analyze", json=CASE1).status_code == 200  # the workers are ready
    start = time.perf_counter()
    r = client.post("/api/analyze", json={"W": W, "n": 8, "alpha": 84})
    assert time.perf_counter() - start < 2
    assert r.status_code == 422, r.text
    d = r.json()
    assert d["field"] == "W" and d["errors"][0]["field"] == "W"
    assert words in d["detail"] and "internal error" not in d["detail"]
    alive(client)


def test_the_page_answers_while_an_exponent_tower_is_posted(live_server: str) -> None:
    """A real server: ``GET /`` keeps answering within 1 s while exponent towers are posted (they
    are refused at once; before the unit grammar one froze every route)."""
    answers: list[tuple[int, Any]] = []

    def post_towers() -> None:
        for _ in range(5):
            request = urllib.request.Request(
                live_server + "/api/analyze",
                data=json.dumps({"W": "1 mm**9**9**9", "n": 8, "alpha": 84}).encode(),
                headers={"content-type": "application/json"},
                method="POST",
            )
            try:
                urllib.request.urlopen(request, timeout=30)
            except urllib.error.HTTPError as exc:
                answers.append((exc.code, json.loads(exc.read())))

    poster = threading.Thread(target=post_towers, daemon=True)
    poster.start()
    pages = 0
    while poster.is_alive() or pages < 3:
        start = time.perf_counter()
        with urllib.request.urlopen(live_server + "/", timeout=1) as response:
            assert response.status == 200
            response.read()
        assert time.perf_counter() - start < 1
        pages += 1
    poster.join(timeout=30)
    assert [code for code, _ in answers] == [422] * 5
    assert all(body["field"] == "W" for _, body in answers)


@pytest.mark.parametrize("W", [1e300, 1e20, "1e6 mm", 1e-300])
def test_mesh_sizes_are_bounded_or_quick(client: TestClient, W: object) -> None:
    """A huge part would need millions of glue tabs: refused at once, never a hung worker."""
    r = client.post("/api/mesh", json={"W": W, "n": 8, "alpha": 84})
    assert r.status_code in (200, 422), r.text
    if r.status_code == 422:
        assert r.json()["field"] == "W"


def test_missing_fields_are_all_named(client: TestClient) -> None:
    r = client.post("/api/analyze", json={"W": 8})
    assert r.status_code == 422
    assert [e["field"] for e in r.json()["errors"]] == ["n", "alpha"]


@pytest.mark.parametrize(
    "raw",
    [b"{bad json", b'{"W": 8,', b"", b"\xff\xfe\x00", b"[1, 2]", b"null", b'"W"', b"NaN"],
)
def test_malformed_json_is_4xx(client: TestClient, raw: bytes) -> None:
    r = client.post("/api/analyze", content=raw, headers={"content-type": "application/json"})
    assert 400 <= r.status_code < 500, (raw, r.status_code, r.text)
    assert r.json()["field"] == "body"
    alive(client)


def test_wrong_content_type_is_4xx(client: TestClient) -> None:
    r = client.post("/api/analyze", content=b"W=8&n=8", headers={"content-type": "text/plain"})
    assert 400 <= r.status_code < 500
    alive(client)


def test_huge_bodies_get_413(client: TestClient) -> None:
    big = json.dumps({**CASE1, "vertices": "0,0 " * 50_000}).encode()
    assert len(big) > 64 * 1024
    r = client.post("/api/analyze", content=big, headers={"content-type": "application/json"})
    assert r.status_code == 413 and "limit" in r.json()["detail"]

    def chunks() -> Iterator[bytes]:  # no Content-Length: the limit counts what arrives
        for _ in range(100):
            yield b" " * 1024

    r = client.post("/api/analyze", content=chunks(), headers={"content-type": "application/json"})
    assert r.status_code == 413
    r = client.post("/api/analyze", content=b"{}", headers={"content-length": "99999999999"})
    assert r.status_code == 413
    alive(client)


def test_a_body_just_under_the_limit_is_read() -> None:
    with TestClient(create_app(WebSettings(max_body_bytes=1000))) as c:
        body = json.dumps(CASE1).encode()
        padded = body[:-1] + b" " * (1000 - len(body)) + b"}"
        assert len(padded) == 1000
        r = c.post("/api/analyze", content=padded, headers={"content-type": "application/json"})
        assert r.status_code == 200


# ---- downloads: only files the app made ------------------------------------------------------


@pytest.mark.slow
def test_path_tricks_in_download_urls_are_4xx(client: TestClient) -> None:
    result = client.post("/api/mesh", json=CASE1).json()
    rid = result["id"]
    tricks = [
        f"/api/results/{rid}/../../../../etc/passwd",
        f"/api/results/{rid}/..%2F..%2F..%2Fetc%2Fpasswd",
        f"/api/results/{rid}/%2e%2e%2f%2e%2e%2fetc%2fpasswd",
        f"/api/results/{rid}/%2Fetc%2Fpasswd",
        "/api/results/%2Fetc/passwd",
        "/api/results/..%2F..%2F..%2Fetc/passwd",
        f"/api/results/{rid}/assembly.glb%00.txt",
        f"/api/results/{rid}/ASSEMBLY.GLB",
        f"/api/results/{rid}/.",
        f"/api/results/{rid.upper()}/assembly.glb",
        "/api/results/00000000000000000000000000000000/assembly.glb",
        f"/api/results/{rid}/{web_app.__file__}",
        "/static/../app.py",
        "/static/%2e%2e/app.py",
        "/static/..%2f..%2f..%2fetc%2fpasswd",
    ]
    for url in tricks:
        r = client.get(url)
        assert 400 <= r.status_code < 500, (url, r.status_code)
        assert b"root:" not in r.content and b"def create_app" not in r.content, url
    assert client.get(result["files"][0]["url"]).status_code == 200
    alive(client)


# ---- time and load bounds ---------------------------------------------------------------------


def _gone(pid: int) -> bool:
    """The process has ended (no longer listed, or a zombie its parent has not reaped yet)."""
    try:
        return Path(f"/proc/{pid}/stat").read_text().split(") ")[1][0] == "Z"
    except (OSError, IndexError):
        return True


def _wait_gone(pid: int, seconds: float = 10) -> bool:
    deadline = time.monotonic() + seconds
    while not _gone(pid):
        if time.monotonic() > deadline:
            return False
        time.sleep(0.05)
    return True


@pytest.mark.slow
def test_a_job_past_the_time_limit_is_killed_and_its_worker_replaced() -> None:
    """Issue 22, item 3: the 504 kills its job. The worker running a job past the time limit is
    killed at once (not left computing), a fresh worker takes its place and serves the next
    job; while a job runs, a job past ``max_pending`` is refused at once."""
    runner = Runner(max_pending=1, timeout_s=1.0, processes=1)

    async def scenario() -> None:
        first = await runner.run(os.getpid)
        assert first != os.getpid() and runner.worker_pids() == (first,)
        start = time.monotonic()
        with pytest.raises(ComputeTimeoutError, match="time limit of 1 s"):
            await runner.run(time.sleep, 120)
        assert time.monotonic() - start < 10
        assert _wait_gone(first), "the worker of the job past its limit still runs"
        second = await runner.run(os.getpid)
        assert second != first and runner.worker_pids() == (second,)
        running = asyncio.ensure_future(runner.run(time.sleep, 0.5))
        await asyncio.sleep(0.1)
        with pytest.raises(ServerBusyError):
            await runner.run(os.getpid)
        assert await running is None
        assert await runner.run(os.getpid) == second  # a job within its limit keeps its worker

    try:
        asyncio.run(scenario())
        last = runner.worker_pids()
    finally:
        runner.shutdown()
    assert last and all(_wait_gone(pid) for pid in last), "shutdown left a worker running"


@pytest.mark.slow
def test_the_limit_counts_from_a_jobs_start_and_a_job_that_stops_waiting_loses_no_worker() -> None:
    """Three 1 s jobs queued behind one worker all finish within a 1.5 s limit (their wait does
    not count); a job cancelled while it waits for a worker does not take the worker with it."""
    runner = Runner(max_pending=8, timeout_s=1.5, processes=1)

    async def scenario() -> None:
        pid = await runner.run(os.getpid)
        jobs = [asyncio.ensure_future(runner.run(time.sleep, 1.0)) for _ in range(3)]
        assert await asyncio.gather(*jobs) == [None, None, None]
        first = asyncio.ensure_future(runner.run(time.sleep, 0.5))
        waiting = asyncio.ensure_future(runner.run(os.getpid))
        await asyncio.sleep(0.1)
        waiting.cancel()
        assert await first is None
        assert await asyncio.wait_for(runner.run(os.getpid), 10) == pid

    try:
        asyncio.run(scenario())
    finally:
        runner.shutdown()


@pytest.mark.slow
def test_a_job_over_the_memory_cap_is_422_and_a_lost_worker_503() -> None:
    """A job that needs more than its worker's address space gets the InputError naming the
    body (422), a worker killed from outside mid-job WorkerLostError (503) naming the signal;
    both workers are replaced, and errors of a job arrive as raised."""
    runner = Runner(max_pending=4, timeout_s=60, processes=1, memory_bytes=1024**3)

    async def scenario() -> None:
        first = await runner.run(os.getpid)
        with pytest.raises(InputError, match="more than the memory of 1 GiB") as err:
            await runner.run(bytearray, 2 * 1024**3)
        assert err.value.field == "body"
        assert _wait_gone(first)
        second = await runner.run(os.getpid)
        assert second != first
        killer = threading.Timer(0.5, os.kill, (second, signal.SIGKILL))
        killer.start()
        with pytest.raises(WorkerLostError, match="signal 9"):
            await runner.run(time.sleep, 60)
        third = await runner.run(os.getpid)
        assert third not in (first, second)
        body = AnalyzeBody.model_validate({"W": "8 kg", "n": 8, "alpha": 84})
        with pytest.raises(InputError) as err:
            await runner.run(web_app.analysis_payload, body, WebSettings())
        assert err.value.field == "W"
        with pytest.raises(ModuleNotFoundError):  # a job the worker cannot load: its error
            await runner.run(_local, "x")
        assert await runner.run(os.getpid) == third

    try:
        asyncio.run(scenario())
    finally:
        runner.shutdown()


def _local(value: str) -> str:
    """A function of this test module, which a worker process cannot import."""
    return value


def test_only_local_host_names_are_answered_on_loopback() -> None:
    """DNS rebinding: a page on another name that resolves to 127.0.0.1 gets nothing."""
    settings = WebSettings(allowed_hosts=("127.0.0.1", "localhost", "[::1]"))
    with TestClient(create_app(settings), base_url="http://127.0.0.1:8000") as c:
        for host in ("127.0.0.1:8000", "localhost", "LOCALHOST:1", "[::1]:8000"):
            assert c.get("/api/models", headers={"host": host}).status_code == 200, host
        for host in ("evil.example", "evil.example:8000", "127.0.0.1.evil.example", "", "[::2]"):
            r = c.post("/api/analyze", json=CASE1, headers={"host": host})
            assert r.status_code == 400, host


def test_core_package_does_not_import_the_web_app() -> None:
    code = (
        "import sys, corrugate, corrugate.cli, corrugate.spec.inputs\n"
        "bad = [m for m in sys.modules if m.split('.')[0] in ('fastapi', 'uvicorn', 'starlette')"
        " or m.startswith('corrugate.web.') or m == 'corrugate.web']\n"
        "print(bad)\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"


def test_serve_command_runs_uvicorn_on_loopback(monkeypatch: pytest.MonkeyPatch) -> None:
    import uvicorn
    from fastapi import FastAPI

    from corrugate.cli import main
    from corrugate.cli.serve import HEAD_TIMEOUT_S, MAX_CONNECTIONS

    calls: list[Any] = []

    def fake_run(server: uvicorn.Server, sockets: Any = None) -> None:
        calls.append(server)

    monkeypatch.setattr(uvicorn.Server, "run", fake_run)
    for args in (["--port", "8123"], ["--host", "0.0.0.0", "--port", "8124", "--timeout", "5"]):
        with pytest.raises(SystemExit) as exc:
            main(["serve", *args])
        assert exc.value.code in (0, None)
    configs = [server.config for server in calls]
    assert configs[0].host == "127.0.0.1" and configs[0].port == 8123
    assert configs[0].limit_concurrency == MAX_CONNECTIONS
    assert configs[0].http.head_timeout_s == HEAD_TIMEOUT_S  # the slow-client deadline
    assert configs[0].timeout_graceful_shutdown is not None
    assert isinstance(configs[0].app, FastAPI)
    assert configs[0].app.state.settings.allowed_hosts == ("127.0.0.1", "localhost", "[::1]")
    assert configs[1].host == "0.0.0.0" and configs[1].app.state.settings.timeout_s == 5
    assert configs[1].app.state.settings.allowed_hosts is None
    for config in configs:
        config.app.state.store.close()
        config.app.state.runner.shutdown()
