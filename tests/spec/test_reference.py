"""The spec reference and JSON Schema are generated from the parser's own models, so they list
every key it accepts; the examples validate against the schema, and the schema rejects what the
parser rejects for the same reason (an unknown key)."""

from __future__ import annotations

import tomllib
from pathlib import Path

import jsonschema
import pytest

from corrugate.spec.reference import KEYS, json_schema, reference_markdown, spec_keys
from corrugate.spec.schema import parse_spec

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = sorted((ROOT / "examples").glob("*.toml"))


def test_docs_spec_md_is_the_generated_reference() -> None:
    assert (ROOT / "docs" / "spec.md").read_text() == reference_markdown()


def test_every_key_the_parser_accepts_is_in_docs_spec_md() -> None:
    text = (ROOT / "docs" / "spec.md").read_text()
    keys = spec_keys()
    assert len(keys) > 60
    for key in keys:
        assert f"| `{key}` |" in text, key
    # and the reference describes no key the parser does not accept
    assert set(KEYS) == set(keys)


def test_keys_found_by_walking_the_models_are_accepted_by_the_parser() -> None:
    # A second source: keys written by hand from the examples and docs/design.md must all be listed.
    for key in (
        "constraints.mass.max",
        "objective.maximize",
        "materials[].thickness",
        "layers",
        "layout.holes[].center",
        "constraints.buckling_load[].eta",
        "constraints.inplane_stiffness[].support",
        "robust.probability",
    ):
        assert key in spec_keys(), key


@pytest.mark.parametrize("path", EXAMPLES, ids=[p.name for p in EXAMPLES])
def test_examples_validate_against_the_schema(path: Path) -> None:
    data = tomllib.loads(path.read_text())
    jsonschema.Draft202012Validator(json_schema()).validate(data)
    parse_spec(data)  # and the parser agrees


def test_schema_rejects_an_unknown_key_and_a_wrong_choice() -> None:
    v = jsonschema.Draft202012Validator(json_schema())
    data = tomllib.loads((ROOT / "examples" / "blimp_gripper.toml").read_text())
    assert v.is_valid(data)
    assert not v.is_valid(data | {"colour": "red"})
    assert not v.is_valid(data | {"support": "glued"})
    bad = dict(data)
    bad["constraints"] = dict(data["constraints"]) | {"side": {"min": "48 mm", "mux": 3}}
    assert not v.is_valid(bad)


def test_quantities_take_numbers_and_strings_with_units_in_the_schema() -> None:
    v = jsonschema.Draft202012Validator(json_schema())
    for W in ({"min": 1, "max": 30}, {"min": "1 mm", "max": "3 cm", "step": "0.5 mm"}):
        assert v.is_valid({"variables": {"W": W, "alpha": {"min": 10, "max": 120}}})
    schema = json_schema()
    assert schema["properties"]["support"]["description"].startswith("Support condition")
    length = schema["$defs"]["LengthVariable"]["properties"]["min"]
    assert length["description"].endswith("[mm]")
