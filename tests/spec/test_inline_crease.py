"""An inline [material]'s optional crease_stiffness (N mm/(rad mm), "inf" rigid) and springback
(deg, within +-30) (docs/calibration.md 9): read in their units, bad values refused in one line
naming the field, the value and the range; a library material's are refused (its materials file
holds them)."""

from __future__ import annotations

import math

import pytest

from corrugate.spec.examples import example_text
from corrugate.spec.schema import SpecError, parse_spec_text

INLINE = 'E = "2700 MPa"\nnu = 0.43\ndensity = "1.39 g/cm^3"\nthickness = "0.125 mm"\n'


def _spec(extra: str, inline: str = INLINE) -> str:
    text = example_text("blimp_gripper")
    head, _, rest = text.partition("[material]\n")
    _, _, tail = rest.partition("\n\n")
    return f"{head}[material]\n{inline}{extra}\n{tail}"


def test_the_fields_are_read_in_their_units() -> None:
    m = parse_spec_text(_spec('crease_stiffness = "100 N*mm/(rad*m)"\nspringback = "-0.1 rad"'))
    assert m.material.crease_stiffness == pytest.approx(0.1)  # 100 per metre of crease
    assert m.material.springback == pytest.approx(-0.1 * 180 / math.pi)
    assert parse_spec_text(_spec('crease_stiffness = "inf"')).material.crease_stiffness == math.inf


@pytest.mark.parametrize(
    ("extra", "field", "words"),
    [
        ('crease_stiffness = "-1 N*mm/(rad*mm)"', "crease_stiffness", "is out of range"),
        ('crease_stiffness = "0 N*mm/(rad*mm)"', "crease_stiffness", "> 0 and <= 1e+06"),
        ("crease_stiffness = 0.1", "crease_stiffness", "has no unit"),
        ('crease_stiffness = "2 mm"', "crease_stiffness", "wrong dimension"),
        ('springback = "31 deg"', "springback", ">= -30 deg and <= 30 deg"),
        ('springback = "4 mm"', "springback", "wrong dimension"),
    ],
)
def test_bad_values_are_one_line_naming_the_field(extra: str, field: str, words: str) -> None:
    with pytest.raises(SpecError) as info:
        parse_spec_text(_spec(extra))
    text = str(info.value)
    assert f"material.{field}" in text and words in text and "\n" not in text


def test_a_library_material_refuses_them() -> None:
    with pytest.raises(SpecError) as info:
        parse_spec_text(_spec('springback = "-4 deg"', 'name = "dura-lar"\n'))
    assert "material.springback" in str(info.value) and "inline material" in str(info.value)
