"""Quantities at the boundary: plain numbers in the default unit, strings with units via pint."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from corrugate.core.errors import InputError
from corrugate.core.units import parse_quantity


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


def test_every_table_unit_is_pints() -> None:
    """The units read without pint: each entry's SI value and dimension are pint's own."""
    from corrugate.core.units import _TABLE, _table_key, ureg

    reg = ureg()
    base = {"[length]": 0, "[mass]": 1, "[time]": 2}
    for text, (factor, dims) in _TABLE.items():
        q = reg.Quantity(1.0, reg.Unit(text)).to_base_units()
        assert q.magnitude == pytest.approx(factor, rel=1e-12), text
        expected = [0, 0, 0]
        for name, power in q.dimensionality.items():
            expected[base[name]] = power
        assert tuple(expected) == dims[:3], text
        # the angle column: pint's radian is dimensionless, so an angle has dims (0, 0, 0, 1)
        assert dims[3] == (
            1
            if reg.Unit(text).is_compatible_with("radian")
            and text not in ("dimensionless", "percent")
            else 0
        ), text
        assert _table_key(text) == text


@pytest.mark.parametrize(
    ("value", "unit"),
    [
        ("80 mN * m ^ 2", "N*mm^2"),
        ("80 mN m**2", "N*mm^2"),
        ("3 ksi", "MPa"),
        ("12 lbf", "N"),
        ("1 turn", "deg"),
        ("2 oz", "g"),
        ("0.5 N*m", "N*mm"),
        ("250 N/m", "N/mm"),
        ("1 rad", "dimensionless"),  # an angle to a pure number: pint's rule (radian = 1)
        ("3 kg/m^3", "g/cm^3"),
    ],
)
def test_table_and_pint_agree(value: str, unit: str) -> None:
    """A quantity converts to the same number on the table's path and on pint's."""
    from corrugate.core.units import ureg

    reg = ureg()
    magnitude, text = value.split(" ", 1)
    expected = reg.Quantity(float(magnitude), reg.Unit(text)).to(reg.Unit(unit))
    assert parse_quantity(value, unit, "x") == pytest.approx(float(expected.magnitude), rel=1e-12)


@pytest.mark.slow
def test_a_spec_in_common_units_does_not_import_pint_or_dask(tmp_path: Path) -> None:
    """Start-up: a whole spec in the usual units is read without pint; a rarer unit brings pint in
    (from its disk cache) but not dask."""
    script = (
        "import sys\n"
        "from corrugate.spec.schema import load_spec\n"
        "load_spec(sys.argv[1])\n"
        "assert 'pint' not in sys.modules, 'pint'\n"
        "from corrugate.core.units import parse_quantity\n"
        "assert abs(parse_quantity('2 yard', 'mm', 'x') - 1828.8) < 1e-9\n"
        "assert 'pint' in sys.modules and 'dask' not in sys.modules, sorted(sys.modules)\n"
    )
    env = {**os.environ, "CORRUGATE_PINT_CACHE": str(tmp_path / "cache")}
    spec = Path(__file__).resolve().parents[2] / "examples" / "blimp_gripper.toml"
    for _ in range(2):  # the second run reads the cache the first wrote
        done = subprocess.run(
            [sys.executable, "-c", script, str(spec)], env=env, capture_output=True, text=True
        )
        assert done.returncode == 0, done.stderr
    assert any((tmp_path / "cache").iterdir())
