"""Quantities at the boundary: plain numbers in the default unit, strings with units via pint."""

from __future__ import annotations

import pytest

from corrugate.errors import InputError
from corrugate.units import parse_quantity


@pytest.mark.parametrize(
    ("value", "unit", "expected"),
    [
        (8, "mm", 8.0),
        ("8", "mm", 8.0),
        ("0.3 in", "mm", 7.62),
        ("5 mil", "mm", 0.127),  # sheet gauges: a mil is a thousandth of an inch
        ("2.7GPa", "MPa", 2700.0),
        ("1.39 g/cm^3", "g/cm^3", 1.39),
        ("1390 kg/m^3", "g/cm^3", 1.39),
        ("80 mN*m^2", "N*mm^2", 80_000.0),  # the paper's EI bound in internal units
        ("0.5 turn", "deg", 180.0),
    ],
)
def test_conversions(value: object, unit: str, expected: float) -> None:
    assert parse_quantity(value, unit, "x") == pytest.approx(expected)


@pytest.mark.parametrize(
    ("value", "reason"),
    [
        ("3 GPa", "wrong dimension"),
        ("5 percent", "wrong dimension"),
        ("5 bogons", "unknown unit"),
        ("1.2.3 mm", "cannot be read"),
        ("abc", "cannot be read"),
        (None, "is not a number"),
        (True, "is not a number"),
    ],
)
def test_rejections_name_the_field(value: object, reason: str) -> None:
    with pytest.raises(InputError, match=rf"^W = .* {reason}.*: allowed .*mm"):
        parse_quantity(value, "mm", "W")
