"""A custom (inline) material through the design API (issue 36, "a custom material on the web
form"): the body the page posts for one, ``material = {E, nu, density, thickness,
yield_strength}``, gets the answer the command line gives for a spec file with the same
``[material]`` table (the CLI run in-process on a file this test writes), is checked as the spec
is (422 naming ``material.E``, ``material.nu``, ...), and survives the page's save
(``POST /api/spec/toml``) and load (``POST /api/spec/parse``).
"""

from __future__ import annotations

import copy
import json
import tomllib
from collections.abc import Iterator
from pathlib import Path
from typing import TYPE_CHECKING, Any

import pytest
from fastapi.testclient import TestClient

from corrugate.web import WebSettings, create_app
from corrugate.web.schemas import BLIMP_GRIPPER

from .test_design_api import without_timings

if TYPE_CHECKING:
    from conftest import CliRun

pytestmark = pytest.mark.slow

#: A PETG-like sheet, in the units a maker reads off a datasheet.
INLINE = {
    "E": "2.1 GPa",
    "nu": 0.4,
    "density": "1.27 g/cm^3",
    "thickness": "0.25 mm",
    "yield_strength": "50 MPa",
}


@pytest.fixture(scope="module")
def api() -> Iterator[TestClient]:
    with TestClient(create_app(WebSettings()), raise_server_exceptions=False) as c:
        yield c


def body_with(material: dict[str, Any]) -> dict[str, Any]:
    body = copy.deepcopy(BLIMP_GRIPPER)
    body["tolerances"] = "none"  # as the case study's file (the paper's reproduction, nominal)
    body["material"] = material
    return body


def toml_value(v: Any) -> str:
    return json.dumps(v)  # a TOML basic string or number


def test_an_inline_material_gets_the_clis_answer(
    api: TestClient, tmp_path: Path, cli: CliRun
) -> None:
    r = api.post("/api/design", json=body_with(INLINE))
    assert r.status_code == 200, r.text[:400]
    web = r.json()["design"]
    # the CLI on a spec file written here: the case study's file with this [material] table
    text = (Path(__file__).resolve().parents[2] / "examples" / "blimp_gripper.toml").read_text()
    head, _, rest = text.partition("[material]\n")
    _, _, tail = rest.partition("\n\n")
    table = "".join(f"{k} = {toml_value(v)}\n" for k, v in INLINE.items())
    spec = tmp_path / "inline.toml"
    spec.write_text(f"{head}[material]\n{table}\n{tail}")
    assert tomllib.loads(spec.read_text())["material"] == INLINE
    code, out, err = cli(["design", str(spec), "--json"])
    assert code == 0, err
    cli_answer = json.loads(out)
    assert without_timings(web) == without_timings(cli_answer)
    # the sheet is the one given: 0.25 mm, E 2100 MPa (a datasheet's 2.1 GPa)
    layer = web["design"]["layers"][0]
    assert layer["t_mm"] == 0.25 and layer["material"] == "custom"


@pytest.mark.parametrize(
    ("change", "field"),
    [
        ({"E": "-2 GPa"}, "material.E"),
        ({"E": "2.1 mm"}, "material.E"),
        ({"nu": 0.6}, "material.nu"),
        ({"density": "1.27 g"}, "material.density"),
        ({"yield_strength": "0 MPa"}, "material.yield_strength"),
        ({"thickness": None}, "material.thickness"),
        ({"nu": None}, "material.nu"),
        ({"crease_stiffness": "-0.1 N*mm/(rad*mm)"}, "material.crease_stiffness"),
        ({"crease_stiffness": "0.1"}, "material.crease_stiffness"),
        ({"springback": "45 deg"}, "material.springback"),
    ],
)
def test_a_bad_inline_material_is_422_naming_the_field(
    api: TestClient, change: dict[str, Any], field: str
) -> None:
    material = {k: v for k, v in (INLINE | change).items() if v is not None}
    r = api.post("/api/design", json=body_with(material))
    assert r.status_code == 422, r.text[:400]
    assert r.json()["field"] == field, r.json()


def test_a_material_with_neither_a_name_nor_moduli_names_E(api: TestClient) -> None:
    """What the page posts for "custom" with its fields empty: the spec's own default name."""
    r = api.post("/api/design", json=body_with({"thickness": "0.25 mm"}))
    assert r.status_code == 422 and r.json()["field"] == "material.E", r.text[:300]


def test_an_inline_material_survives_save_and_load(api: TestClient) -> None:
    body = body_with(INLINE)
    r = api.post("/api/spec/toml", json=body)
    assert r.status_code == 200, r.text[:300]
    assert tomllib.loads(r.text)["material"] == INLINE
    back = api.post("/api/spec/parse", json={"toml": r.text, "name": "inline.toml"})
    assert back.status_code == 200, back.text[:300]
    assert back.json()["material"] == INLINE


def test_a_custom_crease_and_springback_reach_design_json(api: TestClient) -> None:
    """The form's two optional fields (docs/calibration.md 9): the answer certifies with them and
    the design's material carries them, as a spec file's [material] does."""
    material = {**INLINE, "crease_stiffness": "0.1 N*mm/(rad*mm)", "springback": "-4 deg"}
    r = api.post("/api/design", json=body_with(material))
    assert r.status_code == 200, r.text[:400]
    answer = r.json()["design"]
    assert "crease stiffness 0.1 N*mm/(rad*mm), springback -4.0 deg" in answer["certificate"]
