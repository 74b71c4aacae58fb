"""A real uvicorn server: 20 concurrent analyses and 20 concurrent designs get their own answers;
raw path tricks fail."""

from __future__ import annotations

import http.client
import json
import threading
import tomllib
from concurrent.futures import ThreadPoolExecutor
from typing import Any
from urllib.parse import urlsplit

import pytest

from data_files import PAPER_CASE_STUDY

from .conftest import direct, served_files
from .conftest import post_json as post
from .test_design_api import direct_design, without_timings


def raw_get(base: str, target: str) -> tuple[int, bytes]:
    """GET with the request target sent exactly as given (no client-side normalisation)."""
    parts = urlsplit(base)
    conn = http.client.HTTPConnection(parts.hostname, parts.port, timeout=30)
    try:
        conn.putrequest("GET", target, skip_accept_encoding=True)
        conn.endheaders()
        response = conn.getresponse()
        return response.status, response.read()
    finally:
        conn.close()


def bodies() -> list[dict[str, Any]]:
    """Twenty different designs: sizes, crease counts, models, layouts and directions."""
    out = []
    for i in range(20):
        body: dict[str, Any] = {
            "W": 6 + 0.5 * i,
            "n": 6 + i % 7,
            "alpha": 50 + 3 * i,
            "material": ["dura-lar", "mylar", "kapton", "petg"][i % 4],
            "model": ["paper", "xia", "refined"][i % 3],
            "eta": [0, 15 * (i % 6), 90],
        }
        if i % 5 == 0:
            body |= {"layout": "rectangle", "W2": 5 + i, "n2": 7}
        out.append(body)
    return out


def test_twenty_concurrent_requests_get_their_own_answers(live_server: str) -> None:
    designs = bodies()
    start = threading.Barrier(len(designs), timeout=30)

    def one(body: dict[str, Any]) -> tuple[int, Any]:
        start.wait()  # all twenty are sent at once
        return post(live_server, "/api/analyze", body)

    with ThreadPoolExecutor(max_workers=len(designs)) as pool:
        answers = list(pool.map(one, designs))
    for body, (status, answer) in zip(designs, answers, strict=True):
        assert status == 200
        assert answer == direct(body), body
    assert len({json.dumps(a) for _, a in answers}) == len(designs)


def test_concurrent_meshes_get_separate_results(live_server: str) -> None:
    designs = [{"W": 8, "n": 6 + i, "alpha": 84} for i in range(6)]
    with ThreadPoolExecutor(max_workers=len(designs)) as pool:
        results = list(pool.map(lambda b: post(live_server, "/api/mesh", b)[1], designs))
    assert len({r["id"] for r in results}) == len(designs)
    sizes = set()
    for r in results:
        url = next(f["url"] for f in r["files"] if f["name"] == "assembly.glb")
        status, content = raw_get(live_server, url)
        assert status == 200 and content[:4] == b"glTF"
        sizes.add(len(content))
    assert len(sizes) == len(designs)  # more creases, more faces: every file is its own


def test_raw_path_tricks_get_4xx_and_the_server_keeps_serving(live_server: str) -> None:
    _, result = post(live_server, "/api/mesh", {"W": 8, "n": 8, "alpha": 84})
    rid = result["id"]
    tricks = [
        f"/api/results/{rid}/../../../../../../etc/passwd",
        f"/api/results/{rid}/..%2f..%2f..%2f..%2fetc%2fpasswd",
        f"/api/results/{rid}/%2e%2e/%2e%2e/%2e%2e/etc/passwd",
        f"/api/results/{rid}/%252e%252e%252fetc%252fpasswd",
        f"/api/results/{rid}//etc/passwd",
        "/api/results/../../../../etc/passwd",
        "/api/results/%2Fetc%2Fpasswd/x",
        "/static/../../../../../../etc/passwd",
        "/static/%2e%2e/%2e%2e/%2e%2e/%2e%2e/etc/passwd",
        "/static/..%2f..%2f..%2f..%2fetc%2fpasswd",
        "/static//etc/passwd",
        "/static/vendor/../app.py",
        "/static/%2e%2e/app.py",
    ]
    for target in tricks:
        status, content = raw_get(live_server, target)
        assert 400 <= status < 500, (target, status)
        assert b"root:" not in content and b"def create_app" not in content, target
    status, content = raw_get(live_server, f"/api/results/{rid}/assembly.glb")
    assert status == 200 and content[:4] == b"glTF"
    status, content = raw_get(live_server, "/api/materials")
    assert status == 200 and b"dura-lar" in content


def blimp_spec(rigidity_mNm2: float, name: str) -> dict[str, Any]:
    """The blimp gripper spec under the paper's model (tests/data/paper_case_study.toml) named ``name``, asking for another flexural rigidity (mN m^2)."""
    with PAPER_CASE_STUDY.open("rb") as f:
        spec = tomllib.load(f)
    spec["constraints"]["flexural_rigidity"][0]["min"] = f"{rigidity_mNm2:g} mN*m^2"
    spec["name"] = name
    return spec


@pytest.mark.slow
def test_twenty_concurrent_designs_get_their_own_answers_and_files(live_server: str) -> None:
    # Twenty rigidities, 40 ... 277.5 mN m^2: twenty questions, several different optima.
    specs = [blimp_spec(40.0 + 12.5 * i, f"gripper-{i}") for i in range(20)]
    start = threading.Barrier(len(specs), timeout=30)

    def one(spec: dict[str, Any]) -> tuple[int, Any]:
        start.wait()  # all twenty are sent at once
        # Twenty designs with all their files share two cores: the last answer can take minutes on
        # a loaded CI machine. The timeout only guards against a hang; speed is measured in
        # benchmarks/pipeline.py, not here.
        status, answer = post(live_server, "/api/design", spec, timeout=900)
        if status != 200:
            return status, answer
        return status, served_files(live_server, answer)  # the page asks for them next

    with ThreadPoolExecutor(max_workers=len(specs)) as pool:
        answers = list(pool.map(one, specs))
    ids = set()
    for spec, (status, answer) in zip(specs, answers, strict=True):
        assert status == 200
        assert without_timings(answer["design"]) == direct_design(spec), spec["name"]
        result = answer["result"]
        ids.add(result["id"])
        # The files are this request's: its design.json has its name and its optimum.
        url = next(f["url"] for f in result["files"] if f["name"] == "design.json")
        code, content = raw_get(live_server, url)
        record = json.loads(content)
        assert code == 200 and record["name"] == spec["name"]
        assert record["design"] == answer["design"]["design"]
    assert len(ids) == len(specs)
    optima = {json.dumps(a["design"]["design"]["layers"]) for _, a in answers}
    assert len(optima) >= 8  # the rigidities really ask for different designs


def test_path_tricks_on_design_results_get_4xx(live_server: str) -> None:
    _, answer = post(live_server, "/api/design", blimp_spec(80, "tricks"), timeout=120)
    rid = served_files(live_server, answer)["result"]["id"]
    for target in (
        f"/api/results/{rid}/../../../../../../etc/passwd",
        f"/api/results/{rid}/..%2f..%2f..%2fetc%2fpasswd",
        f"/api/results/{rid}/%2e%2e/{rid}/design.json",
        f"/api/results/{rid}/cut-1.dxf/../../../etc/passwd",
        f"/api/results/{rid}/.%2fdesign.json",
        f"/api/results/{rid}//design.json",
        f"/api/results/{rid}/design.json%2500",
        f"/api/results/%2e%2e/{rid}/design.json",
    ):
        status, content = raw_get(live_server, target)
        assert 400 <= status < 500, (target, status)
        assert b"root:" not in content, target
    status, content = raw_get(live_server, f"/api/results/{rid}/cut-1.dxf")
    assert status == 200 and b"SECTION" in content
