"""Spec files: the issue's example is accepted as written; malformed specs name their TOML path."""

from __future__ import annotations

import copy
import tomllib
from pathlib import Path
from typing import Any

import pytest

from corrugate.core.errors import InputError
from corrugate.spec.schema import SpecError, load_spec, parse_spec

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
BLIMP = EXAMPLES / "blimp_gripper.toml"

# The spec exactly as issue 3 prints it (the shipped example must be this text).
ISSUE_TEXT = """\
name = "blimp-gripper"
model = "paper"                 # paper | xia | refined (default refined)

[material]
name = "dura-lar"               # a library id, or inline E / nu / density / thickness
thickness = "0.125 mm"

[layout]
shape = "square"                # square | rectangle | circle | polygon

[variables]                     # bounds, and an optional grid step, for each design variable
W = { min = "1 mm", max = "30 mm", step = "1 mm" }
n = { min = 1, max = 200 }
alpha = { min = "1 deg", max = "120 deg", step = "1 deg" }

[constraints]
sheet_max = "250 mm"                                  # longest flat dimension the cutter takes
side = { min = "48 mm", max = "60 mm" }               # folded side L of a square layout
thickness = { min = "10 mm", max = "12.5 mm" }        # folded thickness t_d
flexural_rigidity = [{ min = "80 mN*m^2", eta = "0 deg" }]

[objective]
minimize = "mass"
"""


def _blimp() -> dict[str, Any]:
    return tomllib.loads(ISSUE_TEXT)


def test_example_file_is_the_issue_text() -> None:
    assert BLIMP.read_text("utf-8") == ISSUE_TEXT


def test_blimp_spec_values_in_internal_units() -> None:
    s = load_spec(BLIMP)
    assert s.model == "paper"
    assert s.material is not None
    assert s.material.name == "dura-lar"
    assert s.material.thickness == pytest.approx(0.125)
    v = s.variables
    assert (v.W.min, v.W.max, v.W.step) == (1.0, 30.0, 1.0)
    assert (v.n.min, v.n.max) == (1, 200)
    assert (v.alpha.min, v.alpha.max, v.alpha.step) == (1.0, 120.0, 1.0)
    c = s.constraints
    assert c.sheet_max == 250.0
    assert c.side is not None
    assert (c.side.min, c.side.max) == (48.0, 60.0)
    assert c.thickness is not None
    assert (c.thickness.min, c.thickness.max) == (10.0, 12.5)
    # 80 mN m^2 = 80e-3 N * 1e6 mm^2 = 80 000 N mm^2 (docs/theory.md 3.4)
    assert c.flexural_rigidity[0].min == pytest.approx(80_000.0)
    assert c.flexural_rigidity[0].eta == 0.0
    assert s.objective.minimize == "mass"


def test_units_are_converted() -> None:
    d = _blimp()
    d["constraints"]["side"] = {"min": "1.9 in", "max": "6 cm"}
    d["variables"]["alpha"] = {"min": "0.1 rad", "max": "2 rad"}
    d["constraints"]["flexural_rigidity"] = [{"min": "0.08 N*m^2", "eta": "0.5 rad"}]
    s = parse_spec(d)
    assert s.constraints.side is not None
    assert s.constraints.side.min == pytest.approx(48.26)
    assert s.constraints.side.max == pytest.approx(60.0)
    assert s.variables.alpha.max == pytest.approx(114.591559, rel=1e-6)
    assert s.constraints.flexural_rigidity[0].min == pytest.approx(80_000.0)
    assert s.constraints.flexural_rigidity[0].eta == pytest.approx(28.6478898, rel=1e-6)


def _set(d: dict[str, Any], path: tuple[Any, ...], value: Any) -> None:
    for p in path[:-1]:
        d = d[p]
    d[path[-1]] = value


@pytest.mark.parametrize(
    ("path", "value", "field", "fragment"),
    [
        (("constraints", "sidee"), {"min": "1 mm"}, "constraints.sidee", "side"),
        (("constraints", "side", "mni"), "1 mm", "constraints.side.mni", "min"),
        (("constraints", "side", "min"), "48 kg", "constraints.side.min", "mm"),
        (("constraints", "side", "min"), "70 mm", "constraints.side.min", "constraints.side.max"),
        (("constraints", "side", "min"), "-3 mm", "constraints.side.min", "> 0 mm"),
        (("constraints", "thickness", "max"), "banana", "constraints.thickness.max", "mm"),
        (("variables", "W", "step"), "-1 mm", "variables.W.step", "> 0 mm"),
        (("variables", "W", "min"), "40 mm", "variables.W.min", "variables.W.max"),
        (("variables", "alpha", "max"), "200 deg", "variables.alpha.max", "180"),
        (("variables", "n", "min"), 0, "variables.n.min", "1 <= n"),
        (("variables", "n", "max"), 2.5, "variables.n.max", "integer"),
        (
            ("constraints", "flexural_rigidity", 0, "min"),
            "80 mN*m",
            "constraints.flexural_rigidity[0].min",
            "N*mm^2",
        ),
        (
            ("constraints", "flexural_rigidity", 0, "eta"),
            "3 mm",
            "constraints.flexural_rigidity[0].eta",
            "deg",
        ),
        (("material", "name"), "unobtainium", "material.name", "dura-lar"),
        (
            ("material", "thickness"),
            ["0.1 mm", "-2 mm"],
            "material.thickness",
            ">= 1e-05 mm and <= 100 mm",
        ),
        (("model",), "fancy", "model", "refined"),
        (("layout", "shape"), "hexagon", "layout.shape", "polygon"),
        (("objective", "minimize"), "cost", "objective.minimize", "mass"),
        (("constraints", "sheet_max"), "0 mm", "constraints.sheet_max", "> 0 mm"),
    ],
)
def test_malformed_spec_names_its_toml_path(
    path: tuple[Any, ...], value: Any, field: str, fragment: str
) -> None:
    d = copy.deepcopy(_blimp())
    _set(d, path, value)
    with pytest.raises(SpecError) as info:
        parse_spec(d)
    err = info.value
    assert isinstance(err, InputError)
    assert err.field == field
    msg = str(err)
    assert msg.startswith(f"{field} = ")
    assert fragment in msg
    assert "\n" not in msg


def test_size_constraint_must_match_layout() -> None:
    d = _blimp()
    d["layout"]["shape"] = "circle"
    with pytest.raises(SpecError) as info:
        parse_spec(d)
    assert info.value.field == "constraints.side"
    assert "diameter" in str(info.value)


def test_inline_material_and_candidate_lists() -> None:
    d = _blimp()
    d["material"] = {
        "name": "my-pet",
        "E": "4 GPa",
        "nu": 0.38,
        "density": "1.39 g/cm^3",
        "thickness": "0.1 mm",
    }
    s = parse_spec(d)
    assert s.material is not None
    assert pytest.approx(4000.0) == s.material.E
    d = _blimp()
    del d["material"]
    d["materials"] = [{"name": "dura-lar", "thickness": "all"}, {"name": "mylar"}]
    s = parse_spec(d)
    assert s.materials is not None
    assert len(s.materials) == 2


def test_inline_material_needs_everything() -> None:
    d = _blimp()
    d["material"] = {"name": "x", "E": "4 GPa", "nu": 0.38, "thickness": "0.1 mm"}
    with pytest.raises(SpecError) as info:
        parse_spec(d)
    assert info.value.field == "material.density"


def test_unreadable_file(tmp_path: Path) -> None:
    bad = tmp_path / "bad.toml"
    bad.write_text("name = \n", "utf-8")
    with pytest.raises(SpecError) as info:
        load_spec(bad)
    assert "TOML" in str(info.value)
