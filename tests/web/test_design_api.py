"""``POST /api/design`` in process: the CLI's design and files, spec errors by TOML path, limits."""

from __future__ import annotations

import asyncio
import copy
import io
import json
import tomllib
import xml.etree.ElementTree as ET
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import ezdxf
import pytest
import trimesh
from fastapi.testclient import TestClient

import corrugate.cli
from corrugate import Assembly, Layer, analyze, get_material
from corrugate.solver import Problem, solve
from corrugate.spec.schema import SpecError, parse_spec
from corrugate.web import WebSettings, create_app
from corrugate.web.app import _output_options
from corrugate.web.schemas import BLIMP_GRIPPER, DesignBody
from corrugate.workflow import output_options, write_design_files

from .conftest import with_files

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def spec_of(name: str) -> dict[str, Any]:
    """An example spec, as a JSON object with the keys of its TOML file."""
    with (EXAMPLES / name).open("rb") as f:
        return tomllib.load(f)


def without_timings(design: dict[str, Any]) -> dict[str, Any]:
    """A design answer without the solver's times (they differ from run to run) and the CPU
    seconds its budget allowed (the web's is a share of its time limit, the CLI's --budget)."""
    out = copy.deepcopy(design)
    out["solver"] = {k: v for k, v in out["solver"].items() if not k.endswith("_seconds")}
    if "budget" in out["solver"]:
        budget = out["solver"]["budget"]
        out["solver"]["budget"] = {k: v for k, v in budget.items() if not k.endswith("_seconds")}
    return out


def direct_design(spec: dict[str, Any]) -> dict[str, Any]:
    """What ``design`` must be: :func:`corrugate.solver.solve` called directly, through JSON."""
    sol = solve(Problem.from_spec(parse_spec(spec)))
    decoded: dict[str, Any] = json.loads(json.dumps(sol.to_dict()))
    return without_timings(decoded)


@pytest.fixture(scope="module")
def client() -> Iterator[TestClient]:
    """One app for the module: the blimp gripper is designed once and its result reused."""
    with TestClient(create_app()) as c:
        yield c


@pytest.fixture(scope="module")
def blimp(client: TestClient) -> dict[str, Any]:
    r = client.post("/api/design", json=spec_of("blimp_gripper.toml"))
    assert r.status_code == 200, r.text
    assert r.headers["cache-control"] == "no-store"
    answer: dict[str, Any] = with_files(client, r.json())  # the page asks for them next
    return answer


def alive(client: TestClient) -> None:
    r = client.get("/api/materials")
    assert r.status_code == 200 and any(m["id"] == "dura-lar" for m in r.json())


# ---- the answer -------------------------------------------------------------------------------


def test_the_blimp_gripper_is_the_examples_design(blimp: dict[str, Any]) -> None:
    d = blimp["design"]
    assert d["status"] == "optimal" and d["certified"] is True
    assert d["model"] == "refined"
    # a second method: the refined model's EI(0) of the answer meets the 80 mN m^2 bound
    layer = d["design"]["layers"][0]
    a = Assembly.identical(
        Layer(layer["W_mm"], layer["n"], layer["alpha_deg"], get_material("dura-lar"), 0.125)
    )
    assert analyze(a, "refined", [0.0]).stiffness[0].EI >= 80_000.0
    assert without_timings(d) == direct_design(spec_of("blimp_gripper.toml"))


def test_the_design_is_what_the_cli_prints(
    blimp: dict[str, Any], capsys: pytest.CaptureFixture[str]
) -> None:
    with pytest.raises(SystemExit) as exc:
        corrugate.cli.main(["design", str(EXAMPLES / "blimp_gripper.toml"), "--json"])
    assert exc.value.code in (0, None)
    cli = json.loads(capsys.readouterr().out)
    assert without_timings(blimp["design"]) == without_timings(cli)


def test_every_file_is_listed_downloads_and_parses(
    client: TestClient, blimp: dict[str, Any], tmp_path: Path
) -> None:
    result = blimp["result"]
    files = {f["name"]: f for f in result["files"]}
    # Exactly the files `corrugate design --out` writes, the report included.
    sol = solve(Problem.from_spec(parse_spec(spec_of("blimp_gripper.toml"))))
    assert sol.analysis is not None
    expected = [
        p.name
        for p in write_design_files(
            sol.analysis,
            tmp_path,
            output_options("cameo4-12x12", "solid"),
            report="<!doctype html>",
        )
    ]
    assert [f["name"] for f in result["files"]] == expected
    assert "report.html" in files
    for kind in ("sheet-1.svg", "cut-1.dxf", "pattern.pdf", "layer1.fold", "layer2.fold"):
        assert kind in files
    assert {"assembly.glb", "assembly.stl", "design.json"} <= set(files)
    for name, f in files.items():
        assert f["url"] == f"/api/results/{result['id']}/{name}"
        r = client.get(f["url"])
        assert r.status_code == 200, name
        assert r.headers["content-type"].split(";")[0] == f["media_type"].split(";")[0], name
        assert len(r.content) == f["bytes"] > 0, name
        disposition = "inline" if name.endswith(".html") else "attachment"
        assert r.headers["content-disposition"].startswith(disposition), name
        assert r.headers["content-security-policy"] == "sandbox"
        content = r.content
        if name.endswith(".dxf"):
            doc = ezdxf.read(io.StringIO(content.decode("utf-8")))
            assert not doc.audit().has_errors, name
            assert len(doc.modelspace()) > 0
        elif name.endswith(".svg"):
            assert ET.fromstring(content).tag.endswith("svg"), name
        elif name.endswith(".fold"):
            fold = json.loads(content)
            assert fold["faces_vertices"] and fold["vertices_coords"], name
        elif name.endswith(".pdf"):
            assert content.startswith(b"%PDF"), name
        elif name.endswith(".glb"):
            mesh = trimesh.load(io.BytesIO(content), file_type="glb", force="mesh")
            assert len(mesh.faces) > 0
        elif name.endswith(".stl"):
            mesh = trimesh.load(io.BytesIO(content), file_type="stl", force="mesh")
            assert len(mesh.faces) > 0
        elif name.endswith(".png"):
            assert content.startswith(b"\x89PNG"), name
        elif name.endswith(".html"):
            assert b"<html" in content.lower(), name
        elif name == "design.json":
            record = json.loads(content)
            assert record["design"] == blimp["design"]["design"]
            assert record["files"] == [f["name"] for f in result["files"]]
        elif name.endswith(".md"):
            assert content.decode("utf-8").startswith("#"), name


def test_an_infeasible_spec_has_a_diagnosis_and_no_files(client: TestClient, cli: Any) -> None:
    r = client.post("/api/design", json=spec_of("infeasible.toml"))
    assert r.status_code == 200
    d = r.json()
    assert d["result"] is None
    assert d["design"]["status"] == "infeasible" and d["design"]["design"] is None
    assert d["design"]["diagnosis"]
    # the hint the page shows is the command line's "hint:" line for the same spec
    code, out, _ = cli(["design", str(EXAMPLES / "infeasible.toml")])
    assert code == 1
    (line,) = [ln for ln in out.splitlines() if ln.startswith("hint: ")]
    assert d["design"]["hint"] == line.removeprefix("hint: ")
    assert without_timings(d["design"]) == direct_design(spec_of("infeasible.toml"))


def test_output_options_are_the_clis() -> None:
    cases: list[tuple[dict[str, Any], tuple[str, str, str | None, str | None]]] = [
        ({}, ("cameo4-12x12", "machine", None, None)),
        ({"cutter": "maker-12x24", "fold_style": "scored"}, ("maker-12x24", "scored", None, None)),
        (
            {"cutter": "laser:300x200", "fold_style": "perforated", "cut": 1.5, "gap": "0.04 in"},
            ("laser:300x200", "perforated", "1.5", "0.04 in"),
        ),
    ]
    for options, (cutter, style, cut, gap) in cases:
        body = DesignBody.model_validate({**BLIMP_GRIPPER, **options})
        assert _output_options(body) == output_options(cutter, style, cut, gap)


def test_perforated_fold_lines_reach_the_files(client: TestClient) -> None:
    body = {**spec_of("blimp_gripper.toml"), "fold_style": "perforated", "cut": 1, "gap": "1 mm"}
    r = client.post("/api/design", json=body)
    assert r.status_code == 200, r.text
    made = with_files(client, r.json())["result"]
    url = next(f["url"] for f in made["files"] if f["name"] == "design.json")
    record = client.get(url).json()
    assert record["fold_style"] == {"kind": "perforated", "cut_mm": 1.0, "gap_mm": 1.0}


def test_the_openapi_document_lists_the_design_endpoint(client: TestClient) -> None:
    spec = client.get("/openapi.json").json()
    assert "/api/design" in spec["paths"]
    props = spec["components"]["schemas"]["DesignBody"]["properties"]
    assert {"material", "variables", "constraints", "cutter", "fold_style"} <= set(props)


# ---- errors: 422 naming the spec path, and the app keeps serving -------------------------------


def _with(path: str, value: Any) -> dict[str, Any]:
    """The blimp gripper spec with the value at a dotted ``path`` replaced (None: removed)."""
    spec = copy.deepcopy(spec_of("blimp_gripper.toml"))
    keys = path.split(".")
    node = spec
    for k in keys[:-1]:
        node = node[int(k)] if isinstance(node, list) else node.setdefault(k, {})
    if value is None:
        del node[keys[-1]]
    else:
        node[keys[-1]] = value
    return spec


@pytest.mark.parametrize(
    ("body", "field", "words"),
    [
        (_with("constraints.sid", {"min": 1}), "constraints.sid", "not a known key"),
        (_with("surprise", 1), "surprise", "output option: cutter"),
        (_with("variables.W.stpe", "1 mm"), "variables.W.stpe", "not a known key"),
        (_with("constraints.side.min", "48 MPa"), "constraints.side.min", "wrong dimension"),
        (_with("constraints.side.min", "48 blorps"), "constraints.side.min", "unknown unit"),
        (
            _with("constraints.flexural_rigidity.0.min", "80 mm"),
            "constraints.flexural_rigidity[0].min",
            "wrong dimension",
        ),
        (
            _with("constraints.flexural_rigidity.0.min", 80),
            "constraints.flexural_rigidity[0].min",
            'has no unit: write it with one, e.g. "80 mN*m^2" (or "80 N*mm^2")',
        ),
        (
            _with("constraints.flexural_rigidity.0.min", "80"),
            "constraints.flexural_rigidity[0].min",
            "= 80 has no unit",
        ),
        (_with("constraints.mass", {"max": 2}), "constraints.mass.max", 'e.g. "2 g"'),
        (_with("constraints.side.min", "70 mm"), "constraints.side.min", "greater than max"),
        (_with("variables.W.min", "40 mm"), "variables.W.min", "greater than max"),
        (_with("variables.n.max", 2.5), "variables.n.max", "not an integer"),
        (_with("variables.n.max", 5000), "variables.n.max", "in the web app"),
        (_with("material.name", "unobtainium"), "material.name", "is unknown"),
        (_with("model", "magic"), "model", "not allowed"),
        (_with("layout.shape", "hexagon"), "layout.shape", "not allowed"),
        (_with("constraints.diameter", {"min": 1}), "constraints.diameter", "square layout"),
        (
            _with("constraints.inplane_stiffness", [{"min": "1 N/mm", "test": "wheel"}]),
            "constraints.inplane_stiffness[0].test",
            "is not a test of a square",
        ),
        (_with("cutter", "plotter"), "cutter", "is unknown"),
        (_with("cutter", 5), "cutter", "wrong type"),
        (_with("fold_style", "zigzag"), "fold_style", "is unknown"),
        ({**_with("fold_style", "perforated"), "cut": 1}, "gap", "is missing"),
        ({**_with("fold_style", "perforated"), "cut": "1 MPa", "gap": 1}, "cut", "wrong dimension"),
        (_with("paper", "a3"), "paper", "is unknown"),
        (_with("paper", 4), "paper", "wrong type"),
        (_with("tolerances", {"alpha": "-3 deg"}), "tolerances.alpha", "out of range"),
        (_with("tolerances", {"t": "nan"}), "tolerances.t", "out of range"),
        (_with("tolerances", {"W": "1 N"}), "tolerances.W", "wrong dimension"),
        (_with("tolerances", {"fold": 3}), "tolerances.fold", "not a known key"),
        (_with("tolerances", "some"), "tolerances", "is not a table or 'none'"),
    ],
)
def test_bad_specs_get_422_naming_the_path(
    client: TestClient, body: dict[str, Any], field: str, words: str
) -> None:
    r = client.post("/api/design", json=body)
    assert r.status_code == 422, r.text
    d = r.json()
    assert d["field"] == field
    assert words in d["detail"], d["detail"]
    alive(client)


def test_a_plain_rigidity_gets_the_clis_words(client: TestClient) -> None:
    """422 with the very line the CLI prints (the same parser), naming the TOML path."""
    body = _with("constraints.flexural_rigidity.0.min", 80)
    with pytest.raises(SpecError) as info:
        parse_spec(body)
    r = client.post("/api/design", json=body)
    assert r.status_code == 422
    d = r.json()
    assert d["detail"] == str(info.value)
    assert d["detail"] == (
        "constraints.flexural_rigidity[0].min = 80 has no unit: write it with one, e.g. "
        '"80 mN*m^2" (or "80 N*mm^2")'
    )
    assert d["field"] == "constraints.flexural_rigidity[0].min"
    alive(client)


@pytest.mark.parametrize("raw", [b"{bad json", b"", b"[1, 2]", b"null", b'"spec"'])
def test_malformed_json_is_4xx(client: TestClient, raw: bytes) -> None:
    r = client.post("/api/design", content=raw, headers={"content-type": "application/json"})
    assert 400 <= r.status_code < 500, (raw, r.status_code)
    assert r.json()["field"] == "body"
    alive(client)


def test_huge_specs_get_413(client: TestClient) -> None:
    body = {**spec_of("blimp_gripper.toml"), "name": "x" * 70_000}
    r = client.post("/api/design", json=body)
    assert r.status_code == 413
    alive(client)


def test_path_tricks_on_design_results_are_4xx(client: TestClient, blimp: dict[str, Any]) -> None:
    rid = blimp["result"]["id"]
    tricks = [
        f"/api/results/{rid}/../../../../etc/passwd",
        f"/api/results/{rid}/..%2F..%2F..%2Fetc%2Fpasswd",
        f"/api/results/{rid}/%2e%2e%2f%2e%2e%2fetc%2fpasswd",
        f"/api/results/{rid}/%2Fetc%2Fpasswd",
        f"/api/results/{rid}/cut-1.dxf%00.txt",
        f"/api/results/{rid}/SHEET-1.DXF",
        f"/api/results/{rid}/.",
        f"/api/results/{rid}/",
        f"/api/results/{rid}/{rid}",
        f"/api/results/{rid.upper()}/design.json",
        f"/api/results/{rid[:-1]}/design.json",
        f"/api/results/{rid}%2Fdesign.json/x",
        f"/api/results/{rid}/.staging",
    ]
    for url in tricks:
        r = client.get(url)
        assert 400 <= r.status_code < 500, (url, r.status_code)
        assert b"root:" not in r.content and b"def create_app" not in r.content, url
    assert client.get(f"/api/results/{rid}/design.json").status_code == 200
    alive(client)


def test_a_robust_spec_is_answered_as_the_cli_does(
    client: TestClient, capsys: pytest.CaptureFixture[str]
) -> None:
    path = EXAMPLES / "blimp_gripper_robust.toml"
    with pytest.raises(SystemExit):
        corrugate.cli.main(["design", str(path), "--json"])
    cli = json.loads(capsys.readouterr().out)
    r = client.post("/api/design", json=spec_of(path.name))
    assert r.status_code == 200, r.text
    d = r.json()["design"]
    assert "robust" in d and d["certified"] is False
    assert without_timings(d) == without_timings(cli)


@pytest.mark.slow
def test_a_slow_design_gets_504() -> None:
    """A design runs in a worker process; past the time limit the request gets 504, the server
    answers on and keeps no result of it. The work: the case study with a 10^6-sample robust
    check (about 2 s in a worker, tests/web/test_jobs_api.py), 40 times the limit of 0.05 s: since
    the web answers before it makes files, the plain case study may finish inside 0.05 s."""
    spec = spec_of("blimp_gripper.toml")
    spec["robust"] = {"W": "0.1 mm", "alpha": "1 deg", "samples": 10**6, "probability": 0.5}
    with TestClient(create_app(WebSettings(timeout_s=0.05, solver_budget_s=600, processes=1))) as c:
        r = c.post("/api/design", json=spec)
        assert r.status_code == 504 and "time limit of 0.05 s" in r.json()["detail"]
        alive(c)
        assert len(c.app.state.store) == 0
        assert not any(c.app.state.store.root.iterdir())  # its folder went at once


@pytest.mark.slow
def test_a_design_past_its_solver_budget_is_answered_not_certified() -> None:
    """The solver's CPU budget of a design request is a share of the time limit (or
    ``solver_budget_s``): past it the answer is 'not certified within the budget' with the
    search's own words, as ``corrugate design --budget`` exits 4 with, not a 504."""
    settings = WebSettings(timeout_s=60, solver_budget_s=0.01, processes=1)
    assert WebSettings(timeout_s=30).design_budget_s == pytest.approx(0.6 * 30)
    with TestClient(create_app(settings)) as c:
        # the wheel needs over 0.01 s of CPU time (the case study's search no longer does)
        r = c.post("/api/design", json=spec_of("wheel_circle.toml"))
        assert r.status_code == 200, r.text
        design = r.json()["design"]
        assert design["status"] == "not-certified" and design["certified"] is False
        assert design["solver"]["budget"]["exhausted"] is True
        assert "budget of 0.01 s" in json.dumps(design["warnings"])


@pytest.mark.slow
def test_designs_run_in_worker_processes_and_their_errors_come_back() -> None:
    """The pool is processes (not the server's), one per core (at least 2) by default, and an
    error raised in a worker arrives as the same error (422 naming the field)."""
    import os

    from corrugate.web.workers import Runner, core_count

    runner = Runner(max_pending=4, timeout_s=60)
    try:
        assert runner.processes == max(2, core_count())
        pid = asyncio.run(runner.run(os.getpid))
        assert pid != os.getpid()
    finally:
        runner.shutdown()
    bad = copy.deepcopy(spec_of("blimp_gripper.toml"))
    bad["constraints"]["side"]["min"] = "-5 mm"
    with TestClient(create_app(WebSettings(processes=1))) as c:
        r = c.post("/api/design", json=bad)
        assert r.status_code == 422, r.text
        assert r.json()["field"].startswith("constraints.side")
        assert not any(c.app.state.store.root.iterdir())  # its folder went too


def test_report_and_preview_show_the_plan_of_the_files(client: TestClient, tmp_path: Path) -> None:
    """Non-default cutter and fold style: report.html and the sheet-N.svg files (the page's
    preview) hold one plan, and the tiles for the chosen paper are among the files."""
    from plan_readers import Tables, sheet_rows, svg_parts

    body = {
        **spec_of("blimp_gripper.toml"),
        "cutter": "laser:130x80",
        "fold_style": "perforated",
        "cut": "1.5 mm",
        "gap": 1,
        "paper": "letter",
    }
    r = client.post("/api/design", json=body)
    assert r.status_code == 200, r.text
    files = {f["name"]: f["url"] for f in with_files(client, r.json())["result"]["files"]}
    for name, url in files.items():
        (tmp_path / name).write_bytes(client.get(url).content)
    in_files, sizes = svg_parts(tmp_path)
    assert len(sizes) > 1 and all(size == (130.0, 80.0) for size in sizes)
    report = (tmp_path / "report.html").read_text(encoding="utf-8")
    rows = sheet_rows(report)
    assert [(s, n) for s, n, _, _ in sorted(rows)] == [(s, n) for s, n, _, _ in in_files]
    for (_, _, x, y), (_, _, x2, y2) in zip(sorted(rows), in_files, strict=True):
        assert abs(x - x2) < 0.01 and abs(y - y2) < 0.01
    parsed = Tables()
    parsed.feed(report)
    assert len([a for a, _ in parsed.images if a.startswith("sheet ")]) == len(sizes)
    assert "perforated (1.5 mm cut, 1 mm gap)" in report
    assert "pattern.pdf" in files and "pattern-letter.pdf" in files
    assert (tmp_path / "pattern-letter.pdf").read_bytes().startswith(b"%PDF-")


def test_download_all_is_a_zip_of_exactly_the_result_files(
    client: TestClient, blimp: dict[str, Any]
) -> None:
    import io
    import zipfile

    result = blimp["result"]
    r = client.get(f"/api/results/{result['id']}/all.zip")
    assert r.status_code == 200 and r.headers["content-type"] == "application/zip"
    assert "attachment" in r.headers["content-disposition"]
    archive = zipfile.ZipFile(io.BytesIO(r.content))
    assert archive.testzip() is None
    assert sorted(archive.namelist()) == sorted(f["name"] for f in result["files"])
    for f in result["files"]:  # byte for byte the files served one by one
        assert archive.read(f["name"]) == client.get(f["url"]).content, f["name"]
    assert client.get("/api/results/" + "0" * 32 + "/all.zip").status_code == 404


def test_a_cutter_too_small_for_every_design_is_an_infeasible_answer(client: TestClient) -> None:
    """The request's cutter is in the solve (as design --machine is): on a 30 x 30 mm bed no
    case-study design fits, so the answer is a certified "infeasible" whose diagnosis names the
    machine and the size the parts need, not a file error."""
    r = client.post("/api/design", json=_with("cutter", "laser:30x30"))
    assert r.status_code == 200, r.text
    d = r.json()["design"]
    assert d["status"] == "infeasible" and d["certified"]
    text = " ".join(x["message"] for x in d["diagnosis"])
    assert "fabrication.machine (laser:30x30" in text and "any cutter whose" in text
    assert 'fabrication.machine = "laser:' in text  # the hint is a TOML edit at its key
