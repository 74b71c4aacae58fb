"""Hostile values through the web API (issue 22, items 2 and 4): the classes of
``tests/system/test_hostile.py`` through ``/api/analyze``, ``/api/pattern`` and ``/api/design`` give
422 with the field named (never ``field: null`` and "internal error"), and no NaN in any answer.

The app runs in-process (FastAPI's TestClient); its tests are ``slow`` (the app starts design
worker processes).
"""

from __future__ import annotations

import copy
import json
from collections.abc import Iterator
from typing import Any

import pytest
from fastapi.testclient import TestClient

from corrugate.core.limits import LIMITS, MAX_DASHES
from corrugate.web import WebSettings, create_app
from corrugate.web.schemas import BLIMP_GRIPPER

pytestmark = pytest.mark.slow

LAYER: dict[str, Any] = {"W": 8, "n": 8, "alpha": 84, "material": "dura-lar"}
INLINE: dict[str, Any] = {"E": 3000, "nu": 0.3, "density": 1.2, "thickness": 0.1}


@pytest.fixture(scope="module")
def api() -> Iterator[TestClient]:
    with TestClient(create_app(WebSettings()), raise_server_exceptions=False) as c:
        yield c


def _refused(api: TestClient, route: str, body: dict[str, Any], field: str) -> str:
    """POST ``body`` to ``route``: 422 naming ``field``; returns the message."""
    r = api.post(route, json=body)
    assert r.status_code == 422, (route, body, r.status_code, r.text[:400])
    answer = r.json()
    assert answer["field"] == field, (route, body, answer)
    assert "internal error" not in answer["detail"], answer
    return str(answer["detail"])


def _just_outside(key: str) -> list[float]:
    lim = LIMITS[key]
    below = lim.lo if lim.open_lo else lim.lo * (1 - 1e-3) if lim.lo else -1e-3
    above = lim.hi if lim.open_hi else lim.hi * (1 + 1e-3)
    return [below, above]


#: The fields of /api/analyze and /api/pattern that a LIMITS entry bounds.
ANALYZE_FIELDS = {
    "W": "W",
    "W2": "W",
    "alpha": "alpha",
    "alpha2": "alpha",
    "thickness": "thickness",
    "thickness2": "thickness",
    "E": "E",
    "nu": "nu",
    "density": "density",
}


@pytest.mark.parametrize("field", sorted(ANALYZE_FIELDS))
def test_analyze_refuses_each_limit_as_422_naming_the_field(api: TestClient, field: str) -> None:
    for value in _just_outside(ANALYZE_FIELDS[field]):
        body = dict(LAYER)
        if field in INLINE:
            body = {k: v for k, v in body.items() if k != "material"} | INLINE
        for given in (value, repr(value)):  # a JSON number and a string
            _refused(api, "/api/analyze", body | {field: given}, field)


@pytest.mark.parametrize(
    ("field", "value"),
    [
        ("alpha", "5e-324"),
        ("alpha", 5e-324),
        ("thickness", "nan"),
        ("thickness2", "NaN"),
        ("W", "inf"),
        ("W2", "-inf"),
        ("n", 10**30),
    ],
)
def test_analyze_refuses_non_finite_and_subnormal_values(
    api: TestClient, field: str, value: Any
) -> None:
    _refused(api, "/api/analyze", LAYER | {field: value}, field)


def test_an_overflowing_design_is_422_naming_the_body(api: TestClient) -> None:
    """alpha = 1e-200 deg lies inside 0 < alpha < 180 but overflows the formulas: 422 naming the
    body (was 422 "internal error (OverflowError ...)" with field null)."""
    message = _refused(api, "/api/analyze", LAYER | {"alpha": "1e-200"}, "body")
    assert "outside the range the models can evaluate" in message


def test_a_json_nan_is_refused(api: TestClient) -> None:
    """A bare NaN in the request body (Python's json reads it) is refused, not the default."""
    r = api.post(
        "/api/analyze",
        content='{"W": 8, "n": 8, "alpha": 84, "thickness": NaN}',
        headers={"content-type": "application/json"},
    )
    assert r.status_code == 422 and r.json()["field"] == "thickness", r.text[:300]


@pytest.mark.parametrize(
    ("cut", "gap", "field"),
    [(1e-9, 1e-9, "cut"), ("0.001", 0.001, "cut"), (1, 0.05, "gap"), (1, "nan", "gap")],
)
def test_pattern_refuses_a_perforation_finer_than_a_cutter(
    api: TestClient, cut: Any, gap: Any, field: str
) -> None:
    body = LAYER | {"fold_style": "perforated", "cut": cut, "gap": gap}
    message = _refused(api, "/api/pattern", body, field)
    assert f"0.1 mm <= {field} <= 1000 mm" in message


def test_pattern_refuses_too_many_dashes(api: TestClient) -> None:
    """W 8 mm, n 60: about 39 m of creases; dashes of 0.1 + 0.1 mm give about 196 000 dashes."""
    body = LAYER | {
        "n": 60,
        "cutter": "laser:5000x5000",
        "fold_style": "perforated",
        "cut": 0.1,
        "gap": 0.1,
    }
    message = _refused(api, "/api/pattern", body, "cut")
    assert f"at most {MAX_DASHES} dashes" in message


def _spec(**changes: Any) -> dict[str, Any]:
    body = copy.deepcopy(BLIMP_GRIPPER)
    for path, value in changes.items():
        *parents, last = path.split("__")
        d = body
        for p in parents:
            d = d.setdefault(p, {})
        d[last] = value
    return body


@pytest.mark.parametrize(
    ("body", "field"),
    [
        (_spec(robust__seed=-1), "robust.seed"),
        (_spec(robust__seed=2**63), "robust.seed"),
        (_spec(robust__samples=1), "robust.samples"),
        (_spec(robust__samples=10**6 + 1), "robust.samples"),
        (_spec(robust__W=1e308), "robust.W"),
        (_spec(robust__alpha="nan"), "robust.alpha"),
        (_spec(variables__alpha={"min": 5e-324, "max": 100}), "variables.alpha.min"),
        (_spec(variables__W={"min": "inf", "max": 30}), "variables.W.min"),
        (_spec(fold_style="perforated", cut=1e-9, gap=1e-9), "cut"),
        (_spec(fold_style="perforated", cut=1, gap="1e-9 mm"), "gap"),
    ],
)
def test_design_refuses_hostile_values_naming_the_field(
    api: TestClient, body: dict[str, Any], field: str
) -> None:
    _refused(api, "/api/design", body, field)


@pytest.mark.parametrize("route", ["/api/design", "/api/analyze", "/api/pattern"])
def test_a_4400_digit_integer_is_422_naming_its_key(api: TestClient, route: str) -> None:
    """Python's JSON reader refuses an integer of more than 4300 digits (a ValueError, not a
    JSONDecodeError), which FastAPI's reader answered 400 "There was an error parsing the body",
    naming no key: 422 naming the key, as an integer of 31 to 4300 digits is."""
    body = BLIMP_GRIPPER if route == "/api/design" else LAYER
    r = api.post(
        route,
        content=json.dumps(body)[:-1] + ', "robust": {"seed": ' + "9" * 4400 + "}}",
        headers={"content-type": "application/json"},
    )
    assert r.status_code == 422, r.text[:300]
    answer = r.json()
    assert answer["field"] == "seed", answer
    assert answer["detail"] == (
        "seed = an integer of 4400 digits is too long: allowed a number of at most 30 digits"
    )
    # the same body as plain digits within int()'s reach: the same key named by the route
    r = api.post(
        route,
        content=json.dumps(body)[:-1] + ', "robust": {"seed": ' + "9" * 4000 + "}}",
        headers={"content-type": "application/json"},
    )
    assert r.status_code == 422 and r.json()["field"].endswith("seed"), r.text[:300]
