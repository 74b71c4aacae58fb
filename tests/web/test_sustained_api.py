"""``POST /api/design`` with a sustained load case: bad durations get 422 naming the path."""

from __future__ import annotations

import copy
from collections.abc import Iterator
from typing import Any

import pytest
from fastapi.testclient import TestClient

from corrugate.web import create_app

SPEC: dict[str, Any] = {
    "material": {"name": "polycarbonate", "thickness": "0.25 mm"},
    "layout": {"shape": "square"},
    "constraints": {
        "side": {"min": "100 mm", "max": "120 mm"},
        "deflection": [{"test": "three-point", "load": "10 N", "max": "1 mm"}],
    },
}


@pytest.fixture(scope="module")
def client() -> Iterator[TestClient]:
    with TestClient(create_app()) as c:
        yield c


@pytest.mark.parametrize(
    ("material", "duration", "words"),
    [
        ("polycarbonate", "-1 h", "is out of range: allowed > 0 h"),
        ("dura-lar", "1 week", "needs creep data, which dura-lar has not"),
        ("polycarbonate", "1 year", "is beyond the creep table"),
    ],
    ids=["negative", "no-creep-data", "beyond-the-table"],
)
def test_bad_durations_get_422_naming_the_path(
    client: TestClient, material: str, duration: str, words: str
) -> None:
    body = copy.deepcopy(SPEC)
    body["material"]["name"] = material
    body["constraints"]["deflection"][0]["duration"] = duration
    r = client.post("/api/design", json=body)
    assert r.status_code == 422, r.text
    d = r.json()
    assert d["field"] == "constraints.deflection[0].duration"
    assert words in d["detail"] and "\n" not in d["detail"]
