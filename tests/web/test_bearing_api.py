"""``POST /api/design`` with a load case's ``bearing`` width (docs/load_cases.md 10.5): bad
widths get 422 naming the path, in one line."""

from __future__ import annotations

import copy
from collections.abc import Iterator
from typing import Any

import pytest
from fastapi.testclient import TestClient

from corrugate.web import create_app

SPEC: dict[str, Any] = {
    "material": {"name": "polypropylene", "thickness": "0.25 mm"},
    "layout": {"shape": "square"},
    "joint": "band-edges",
    "constraints": {
        "side": {"min": "100 mm", "max": "120 mm"},
        "deflection": [{"test": "three-point", "load": "1 N", "max": "5 mm"}],
    },
}


@pytest.fixture(scope="module")
def client() -> Iterator[TestClient]:
    with TestClient(create_app()) as c:
        yield c


@pytest.mark.parametrize(
    ("bearing", "words"),
    [
        ("0 mm", "is out of range: allowed > 0 mm"),
        ("-1 mm", "is out of range: allowed > 0 mm"),
        ("nan mm", "cannot be read as a quantity"),
        ("130 mm", "at most the panel's longest length, 120 mm"),
        ("10 N", "bearing"),
    ],
    ids=["zero", "negative", "nan", "longer-than-the-panel", "wrong-dimension"],
)
def test_bad_bearings_get_422_naming_the_path(client: TestClient, bearing: str, words: str) -> None:
    body = copy.deepcopy(SPEC)
    body["constraints"]["deflection"][0]["bearing"] = bearing
    r = client.post("/api/design", json=body)
    assert r.status_code == 422, r.text
    d = r.json()
    assert d["field"] == "constraints.deflection[0].bearing"
    assert words in d["detail"] and "\n" not in d["detail"]
