"""A spec written as TOML by :mod:`corrugate.spec.toml_text` reads back to the same spec.

The independent source is the shipped example files (``examples/*.toml``, written by hand) and
Python's own TOML parser (``tomllib``): every example, parsed, written and parsed again, gives the
same keys and the same validated :class:`~corrugate.spec.schema.Spec`.
"""

from __future__ import annotations

import math
import tomllib

import pytest

from corrugate.spec.examples import example_names, example_text
from corrugate.spec.schema import SpecError, parse_spec
from corrugate.spec.toml_text import read_spec_toml, spec_toml, toml_value


@pytest.mark.parametrize("name", example_names())
def test_every_example_round_trips(name: str) -> None:
    data = tomllib.loads(example_text(name))
    text = spec_toml(data, ["saved", ""])
    assert text.startswith("# saved\n#\n")
    assert tomllib.loads(text) == data
    spec, back = read_spec_toml(text, f"{name}.toml")
    assert back == data
    assert spec == parse_spec(data)


def test_awkward_strings_keys_and_values() -> None:
    data = {
        "name": 'a "quoted"\tname\\ with \x7f and \u00e9 \U0001f600',
        "material": {"name": "dura-lar", "thickness": "0.125 mm"},
        "layout": {"shape": "polygon", "vertices": [[0, 0], [60.5, 0], [30, 50]]},
        "constraints": {"flexural_rigidity": [{"min": "80 mN*m^2", "eta": "0 deg"}]},
        "robust": None,  # TOML has no null: left out, the default applies
    }
    back = tomllib.loads(spec_toml(data))
    assert back == {k: v for k, v in data.items() if v is not None}
    assert toml_value({"a b": 1, "c": None}) == '{ "a b" = 1 }'
    assert toml_value([True, 1.5, 2]) == "[true, 1.5, 2]"
    with pytest.raises(ValueError, match="no TOML form"):
        toml_value(math.inf)


def test_a_bad_spec_is_refused_naming_its_key() -> None:
    with pytest.raises(SpecError) as info:
        spec_toml({"constraints": {"side": {"min": "50 kg"}}})
    assert info.value.field == "constraints.side.min"
    with pytest.raises(SpecError) as info:
        read_spec_toml("name = ", "bad.toml")
    assert info.value.field == "spec" and "bad.toml" in str(info.value)
