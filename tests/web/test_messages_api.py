"""Messages of hostile input through the web API (issue 37 item 5; the CLI's cases are
``tests/system/test_messages.py``): 422 naming the key the body wrote and its value, cut short,
without control characters.

The app runs in-process (FastAPI's TestClient); ``slow`` (the app starts its worker processes).
"""

from __future__ import annotations

import copy
import re
from collections.abc import Iterator
from typing import Any

import pytest
from fastapi.testclient import TestClient

from corrugate.web import WebSettings, create_app
from corrugate.web.schemas import BLIMP_GRIPPER

pytestmark = pytest.mark.slow

LAYER: dict[str, Any] = {"W": 8, "n": 8, "alpha": 84, "material": "dura-lar"}


@pytest.fixture(scope="module")
def api() -> Iterator[TestClient]:
    with TestClient(create_app(WebSettings()), raise_server_exceptions=False) as c:
        yield c


def refused(api: TestClient, route: str, body: dict[str, Any], field: str) -> str:
    r = api.post(route, json=body)
    assert r.status_code == 422, (route, r.status_code, r.text[:400])
    answer = r.json()
    assert answer["field"] == field, answer
    assert "internal error" not in answer["detail"], answer
    return str(answer["detail"])


def spec(**changes: Any) -> dict[str, Any]:
    body = copy.deepcopy(BLIMP_GRIPPER)
    for path, value in changes.items():
        *parents, last = path.split("__")
        d = body
        for p in parents:
            d = d.setdefault(p, {})
        d[last] = value
    return body


def test_a_4000_digit_laser_bed_is_named_by_its_key(api: TestClient) -> None:
    body = spec(fabrication__machine="laser:" + "9" * 4000 + "x300")
    detail = refused(api, "/api/design", body, "fabrication.machine")
    assert "inf" not in detail and "characters)" in detail and len(detail) < 300


def test_a_direction_beyond_one_turn_is_422(api: TestClient) -> None:
    body = spec()
    body["constraints"]["flexural_rigidity"] = [{"min": "80 mN*m^2", "eta": "1e300 deg"}]
    detail = refused(api, "/api/design", body, "constraints.flexural_rigidity[0].eta")
    assert "1e300 deg" in detail and "360" in detail


def test_analyze_refuses_a_direction_beyond_one_turn(api: TestClient) -> None:
    refused(api, "/api/analyze", LAYER | {"eta": [0, 1e300]}, "eta")


@pytest.mark.parametrize(("field", "value"), [("W", "８"), ("n", "９"), ("alpha", "８４ deg")])
def test_full_width_digits_are_422(api: TestClient, field: str, value: str) -> None:
    detail = refused(api, "/api/analyze", LAYER | {field: value}, field)
    assert "digits other than 0-9" in detail


def test_a_name_with_control_characters_is_answered_without_them(api: TestClient) -> None:
    body = spec(name="grip\x1b[31mper\x07")
    r = api.post("/api/design", json=body)
    assert r.status_code == 200, r.text[:300]
    text = r.text
    assert not re.search(r"\\u001b|\\u0007|\x1b|\x07", text)
    assert r.json()["design"]["name"] == "grip[31mper"
