"""A JSON integer of 400 digits through the web API (issue 37, item 4): 422 naming its field,
never "internal error (OverflowError ...)" with field null, and no traceback in the server log.

The app runs in-process (FastAPI's TestClient); ``slow`` (the app starts its worker processes).
"""

from __future__ import annotations

import copy
import json
import logging
from collections.abc import Iterator
from typing import Any

import pytest
from fastapi.testclient import TestClient

from corrugate.web import WebSettings, create_app
from corrugate.web.schemas import BLIMP_GRIPPER

pytestmark = pytest.mark.slow

BIG = 10**400


@pytest.fixture(scope="module")
def api() -> Iterator[TestClient]:
    with TestClient(create_app(WebSettings()), raise_server_exceptions=False) as c:
        yield c


def _post(api: TestClient, route: str, body: dict[str, Any]) -> Any:
    # json.dumps writes the integer's 401 digits, as a client would send them
    return api.post(route, content=json.dumps(body), headers={"content-type": "application/json"})


def _design_with(path: tuple[Any, ...], value: object) -> dict[str, Any]:
    body = copy.deepcopy(BLIMP_GRIPPER)
    node: Any = body
    for key in path[:-1]:
        node = node[key]
    node[path[-1]] = value
    return body


CASES = [
    ("/api/design", _design_with(("constraints", "side", "min"), BIG), "constraints.side.min"),
    (
        "/api/design",
        _design_with(
            ("constraints", "deflection"), [{"test": "cantilever", "load": "0.5 N", "max": BIG}]
        ),
        "constraints.deflection[0].max",
    ),
    ("/api/analyze", {"W": BIG, "n": 8, "alpha": 84, "material": "dura-lar"}, "W"),
    ("/api/analyze", {"W": 8, "n": BIG, "alpha": 84, "material": "dura-lar"}, "n"),
    ("/api/analyze", {"W": 8, "n": 8, "alpha": 84, "material": "dura-lar", "eta": [BIG]}, "eta[0]"),
]


@pytest.mark.parametrize(("route", "body", "field"), CASES)
def test_a_400_digit_integer_is_named_by_its_field(
    api: TestClient, caplog: pytest.LogCaptureFixture, route: str, body: dict[str, Any], field: str
) -> None:
    with caplog.at_level(logging.DEBUG):
        r = _post(api, route, body)
    assert r.status_code == 422, r.text[:300]
    answer = r.json()
    assert answer["field"] == field, answer
    assert "internal error" not in answer["detail"]
    assert answer["detail"].startswith(f"{field} = an integer of 401 digits is too long"), answer
    assert not [rec for rec in caplog.records if rec.exc_info], "a traceback was logged"


def test_bodies_without_long_integers_are_untouched(api: TestClient) -> None:
    """A 40-digit run inside a string is no integer: the route's own check answers."""
    r = _post(api, "/api/analyze", {"W": 8, "n": 8, "alpha": 84, "material": "9" * 40})
    assert r.status_code == 422
    assert r.json()["field"] == "material"
    r = _post(api, "/api/analyze", {"W": 8, "n": 8, "alpha": 84, "material": "dura-lar"})
    assert r.status_code == 200
