"""``POST /api/design`` with load cases: the chassis plate's deflection bound answered as a
deflection in mm (the direct solve of the same spec), and bad load cases as 422 naming the
TOML path of the field (the spec parser's and ``Problem.from_spec``'s own checks)."""

from __future__ import annotations

import copy
import re
from typing import Any

import pytest
from fastapi.testclient import TestClient

from .test_design_api import alive, client, direct_design, spec_of, without_timings

__all__ = ["client"]  # the module's app fixture


def _chassis(**changes: Any) -> dict[str, Any]:
    """The chassis plate's spec with keys of its deflection bound changed (None: removed)."""
    spec = copy.deepcopy(spec_of("chassis_plate.toml"))
    d = spec["constraints"]["deflection"][0]
    for key, value in changes.items():
        if value is None:
            d.pop(key, None)
        else:
            d[key] = value
    return spec


def test_the_chassis_plate_answers_with_its_deflection_in_mm(client: TestClient) -> None:
    spec = spec_of("chassis_plate.toml")
    r = client.post("/api/design", json=spec)
    assert r.status_code == 200, r.text
    design = r.json()["design"]
    assert without_timings(design) == direct_design(spec)
    assert design["status"] == "optimal" and design["certified"] is True
    (c,) = [c for c in design["constraints"] if c["name"] == "constraints.deflection[0].max"]
    assert (c["unit"], c["sense"], c["test"], c["load_N"]) == ("mm", "max", "three-point", 10.0)
    assert c["bound"] == pytest.approx(1.0) and 0 < c["value"] <= 1.0
    assert c["margin"] == pytest.approx(c["bound"] - c["value"])
    assert c["value"] * c["stiffness_N_per_mm"] == pytest.approx(10.0)  # delta x P/delta = P
    (span,) = [c for c in design["constraints"] if c["name"] == "constraints.deflection[0].span"]
    assert span["unit"] == "mm" and span["value"] >= 120.0  # the panel reaches the supports


@pytest.mark.parametrize(
    ("body", "field", "words"),
    [
        (_chassis(load="0 N"), "constraints.deflection[0].load", "out of range"),
        (_chassis(load="-3 N"), "constraints.deflection[0].load", "out of range"),
        (_chassis(load="3 mm"), "constraints.deflection[0].load", "wrong dimension"),
        (_chassis(load=None), "constraints.deflection[0].load", "missing"),
        (_chassis(max="0 mm"), "constraints.deflection[0].max", "out of range"),
        (_chassis(span="0 mm"), "constraints.deflection[0].span", "out of range"),
        (_chassis(span="-5 mm"), "constraints.deflection[0].span", "out of range"),
        (_chassis(test="five-point"), "constraints.deflection[0].test", "'platens'"),
        (_chassis(test=None), "constraints.deflection[0].test", "missing"),
        (_chassis(test="platens"), "constraints.deflection[0].span", "no span for platens"),
        (_chassis(support="clamped"), "constraints.deflection[0].support", "'frame'"),
        (
            {
                **_chassis(),
                "layers": "identical",
                "layout": {"shape": "circle"},
                "constraints": {
                    "diameter": {"min": "70 mm", "max": "80 mm"},
                    "deflection": [{"test": "three-point", "load": "1 N", "max": "1 mm"}],
                },
            },
            "constraints.deflection[0].test",
            "square or rectangle",
        ),
        (
            {
                **_chassis(),
                "constraints": {
                    "inplane_stiffness": [{"min": "10 N/mm", "test": "three-point"}],
                },
            },
            "constraints.inplane_stiffness[0].test",
            "not a test of inplane_stiffness",
        ),
        (
            {
                **_chassis(),
                "constraints": {
                    "flexural_rigidity": [{"min": "10 mN*m^2", "test": "platens"}],
                },
            },
            "constraints.flexural_rigidity[0].test",
            "not a test of flexural_rigidity",
        ),
    ],
)
def test_bad_load_cases_get_422_naming_the_field(
    client: TestClient, body: dict[str, Any], field: str, words: str
) -> None:
    r = client.post("/api/design", json=body)
    assert r.status_code == 422, r.text
    d = r.json()
    assert d["field"] == field, d
    assert words in d["detail"], d["detail"]
    alive(client)


# ---- POST /api/analyze with a load case: the CLI's `analyze --test --load --span` ----------

_CASE_STUDY = {"W": 8, "n": 8, "alpha": "84 deg", "material": "dura-lar", "eta": [0, 90]}


def test_analyze_states_a_load_case_as_the_cli_does(client: TestClient) -> None:
    """Second route: the web's load_case is the object ``corrugate analyze --json`` prints for
    the same options (the shared :mod:`corrugate.analysis.load_case`), and its deflection is
    load / (P / delta) with P / delta below the pure-bending 48 EI / L^3 (shear adds
    compliance)."""
    from corrugate.analysis.load_case import load_case_dict, load_case_of, load_case_rows
    from corrugate.spec.inputs import analysis_request

    body = {**_CASE_STUDY, "test": "three-point", "load": "10 N", "span": "40 mm"}
    r = client.post("/api/analyze", json=body)
    assert r.status_code == 200, r.text
    got = r.json()["load_case"]
    req = analysis_request(W=8, n=8, alpha="84 deg", material="dura-lar", eta=[0, 90])
    res = req.run()
    case = load_case_of("three-point", "10 N", "40 mm")
    assert case is not None
    assert got == load_case_dict(case, load_case_rows(res, case))  # JSON keeps floats exactly
    for row, st in zip(got["directions"], res.stiffness, strict=True):
        assert row["span_mm"] == 40.0
        assert row["deflection_mm"] == pytest.approx(10.0 / row["stiffness_N_per_mm"])
        assert row["stiffness_N_per_mm"] < 48 * st.D * st.span / 40.0**3


@pytest.mark.parametrize(
    ("extra", "field"),
    [
        ({"load": 10}, "load"),  # a load without a test
        ({"span": "30 mm"}, "span"),
        ({"test": "bending"}, "test"),  # unknown test
        ({"test": "three-point"}, "load"),  # a test without a load
        ({"test": "three-point", "load": 0}, "load"),
        ({"test": "three-point", "load": "10 mm"}, "load"),  # not a force
        ({"test": "three-point", "load": 10, "span": -5}, "span"),
        ({"test": "three-point", "load": 10, "span": "1 m"}, "span"),  # longer than the panel
        ({"test": "platens", "load": 10, "span": 20}, "span"),  # no span between platens
    ],
)
def test_analyze_bad_load_cases_get_422_naming_the_field(
    client: TestClient, extra: dict[str, Any], field: str
) -> None:
    r = client.post("/api/analyze", json={**_CASE_STUDY, **extra})
    assert r.status_code == 422, r.text
    body = r.json()
    assert body["field"] == field, body
    assert field in body["detail"]
    alive(client)


def test_load_cases_are_the_registry_and_documented() -> None:
    """``GET /api/load-cases`` (the page's test menus) is every load case of the registry of
    behaviours in its order, each field the entry's; the OpenAPI document describes every
    field. No lifespan: the route needs no worker."""
    from corrugate.mechanics.behaviours import load_cases
    from corrugate.web import create_app

    c = TestClient(create_app())
    r = c.get("/api/load-cases")
    assert r.status_code == 200 and r.headers["cache-control"] == "no-store"
    assert r.json() == [
        {
            "name": b.name,
            "label": b.choice or b.name,
            "kind": b.form.kind,
            "own": b.form.kind == "inplane" and b.form.factor is None,
            "deflection": not b.stiffness_only,
            "layouts": list(b.layouts),
            "text": b.text,
        }
        for b in load_cases()
        if b.form is not None
    ]
    # the page's list of load cases before its script rewrites it from this answer names
    # registered tests only, in the registry's order (a new test needs no edit of the page)
    page = c.get("/").text
    shown = re.search(r'id="d-load-case-names">([^<]*)<', page)
    assert shown is not None
    labels = [x["label"] for x in r.json() if x["deflection"]]
    static = " ".join(shown.group(1).split()).split(", ")
    assert static == [label for label in labels if label in static] and len(static) >= 4
    spec = c.get("/openapi.json").json()
    answer = spec["paths"]["/api/load-cases"]["get"]["responses"]["200"]["content"]
    ref = answer["application/json"]["schema"]["items"]["$ref"]
    schema = spec["components"]["schemas"][ref.rsplit("/", 1)[-1]]
    assert set(schema["properties"]) == set(r.json()[0])
    assert all(p.get("description") for p in schema["properties"].values())
