"""Answers first: ``POST /api/design`` answers without files; ``POST /api/designs/{id}/files``
makes them on demand, once per design (:mod:`corrugate.web.ondemand`, docs/web.md)."""

from __future__ import annotations

import copy
import hashlib
import json
import threading
import tomllib
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from fastapi.testclient import TestClient

from corrugate.solver import Problem, solve
from corrugate.spec.schema import parse_spec
from corrugate.web import WebSettings, create_app

from .conftest import post_json, serve

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def blimp(ei_min: str | None = None) -> dict[str, Any]:
    """The blimp gripper's spec, with another EI bound if given."""
    with (EXAMPLES / "blimp_gripper.toml").open("rb") as f:
        spec = tomllib.load(f)
    if ei_min is not None:
        spec = copy.deepcopy(spec)
        spec["constraints"]["flexural_rigidity"][0]["min"] = ei_min
    return spec


def digests(client: TestClient, result: dict[str, Any]) -> dict[str, str]:
    """SHA-256 of every file of a stored result, and of its zip, as downloaded."""
    out = {
        f["name"]: hashlib.sha256(client.get(f["url"]).content).hexdigest() for f in result["files"]
    }
    zipped = client.get(f"/api/results/{result['id']}/all.zip")
    assert zipped.status_code == 200
    out["all.zip"] = hashlib.sha256(zipped.content).hexdigest()
    return out


@pytest.fixture(scope="module")
def client() -> Iterator[TestClient]:
    with TestClient(create_app()) as c:
        yield c


def test_the_answer_comes_without_files_and_the_files_once_on_demand(
    client: TestClient,
) -> None:
    app: Any = client.app
    store = app.state.store
    made_before = store.designs.files_made
    results_before = len(store)
    r = client.post("/api/design", json=blimp())
    assert r.status_code == 200, r.text
    answer = r.json()
    # the design is the solver's own (a second method: solve called here), with no file made
    sol = solve(Problem.from_spec(parse_spec(blimp())))
    assert answer["design"]["design"] == json.loads(json.dumps(sol.to_dict()))["design"]
    assert answer["result"] is None and answer["files_url"].endswith("/files")
    assert len(store) == results_before and store.designs.files_made == made_before

    first = client.post(answer["files_url"])
    assert first.status_code == 200, first.text
    again = client.post(answer["files_url"])
    # the same request again: the same design id, its files already made, answered with them
    repeated = client.post("/api/design", json=blimp()).json()
    assert repeated["design_id"] == answer["design_id"]
    assert repeated["result"] == first.json() == again.json()
    assert store.designs.files_made == made_before + 1  # made once
    names = {f["name"] for f in first.json()["files"]}
    assert {"design.json", "report.html", "cut-1.dxf", "pattern.pdf"} <= names
    # the bytes served are those of the one set made: the same digests on every download
    assert digests(client, first.json()) == digests(client, again.json())
    record = client.get(f"/api/results/{first.json()['id']}/design.json").json()
    assert record["design"] == answer["design"]["design"]


def test_another_design_gets_other_files(client: TestClient) -> None:
    one = client.post("/api/design", json=blimp()).json()
    # EI >= 100 mN*m^2 needs another design (the solver, called here: n 13, not 9)
    stiffer_spec = blimp("100 mN*m^2")
    sol = solve(Problem.from_spec(parse_spec(stiffer_spec)))
    assert sol.assembly is not None and sol.assembly.layer1.n != 9
    other = client.post("/api/design", json=stiffer_spec).json()
    assert other["design_id"] != one["design_id"]
    a = client.post(one["files_url"]).json()
    b = client.post(other["files_url"]).json()
    assert a["id"] != b["id"]
    da, db = digests(client, a), digests(client, b)
    assert da["design.json"] != db["design.json"] and da["cut-1.dxf"] != db["cut-1.dxf"]
    record = client.get(f"/api/results/{b['id']}/design.json").json()
    assert record["design"]["layers"][0]["n"] == sol.assembly.layer1.n


def test_the_same_spec_with_other_output_options_is_another_design_id(
    client: TestClient,
) -> None:
    one = client.post("/api/design", json=blimp()).json()
    laser = client.post("/api/design", json={**blimp(), "cutter": "laser:200x200"}).json()
    assert laser["design"]["design"] == one["design"]["design"]
    assert laser["design_id"] != one["design_id"]
    names = {f["name"] for f in client.post(laser["files_url"]).json()["files"]}
    assert "cut-1.svg" in names  # a laser's cut files, not the cameo's


@pytest.mark.parametrize("design_id", ["0" * 32, "nope", "%2e%2e"])
def test_the_files_of_an_unknown_design_are_404_saying_so(
    client: TestClient, design_id: str
) -> None:
    r = client.post(f"/api/designs/{design_id}/files")
    assert r.status_code == 404
    body = r.json()
    assert body["field"] == "design_id" and "no such design" in body["detail"]


def test_a_path_trick_for_a_design_is_404(client: TestClient) -> None:
    assert client.post("/api/designs/..%2F..%2Fetc/files").status_code == 404


def test_an_infeasible_spec_has_no_files_to_make(client: TestClient) -> None:
    with (EXAMPLES / "infeasible.toml").open("rb") as f:
        spec = tomllib.load(f)
    answer = client.post("/api/design", json=spec).json()
    assert answer["design"]["status"] == "infeasible"
    assert answer["result"] is None and answer["files_url"] is None
    assert answer["design_id"] is None


def test_concurrent_requests_for_one_design_make_its_files_once() -> None:
    with serve(WebSettings()) as (base, app):
        status, answer = post_json(base, "/api/design", blimp("85 mN*m^2"))
        assert status == 200 and answer["files_url"]
        got: list[tuple[int, Any]] = []
        lock = threading.Lock()
        start = threading.Barrier(6)

        def ask() -> None:
            start.wait()
            out = post_json(base, answer["files_url"], {}, timeout=300)
            with lock:
                got.append(out)

        threads = [threading.Thread(target=ask) for _ in range(6)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        assert [s for s, _ in got] == [200] * 6, got
        assert len({json.dumps(r, sort_keys=True) for _, r in got}) == 1  # one stored result
        assert app.state.store.designs.files_made == 1  # made by one run of the files job


def test_a_robust_designs_files_keep_its_robust_answer_and_its_recipe_stays_small(
    client: TestClient,
) -> None:
    """The recipe leaves out the robust search's Monte Carlo samples (about 1 MB pickled for
    this example): the files need the solution and the answer, whose ``robust`` entry
    design.json still carries."""
    from corrugate.web.app import design_job
    from corrugate.web.schemas import DesignBody

    with (EXAMPLES / "blimp_gripper_robust.toml").open("rb") as f:
        spec = tomllib.load(f)
    _, recipe = design_job(DesignBody.model_validate(spec), WebSettings())
    assert recipe is not None and len(recipe) < 100_000
    answer = client.post("/api/design", json=spec).json()
    made = client.post(answer["files_url"]).json()
    record = client.get(f"/api/results/{made['id']}/design.json").json()
    assert record["robust"] == answer["design"]["robust"] and record["certified"] is False
