"""Units at the boundaries: parse user quantities into corrugate's internal system.

Internal units (DESIGN.md section 8): mm, N, MPa (= N/mm^2), g, degrees at the boundary and radians
inside the formulas. Users may give a plain number (read in the field's default unit) or a string
with units such as ``"0.3 in"`` or ``"2.7 GPa"``; pint does the conversion.
"""

from __future__ import annotations

import re
from functools import lru_cache
from typing import Any

from .errors import InputError

__all__ = ["parse_quantity", "ureg"]

_MIL = re.compile(r"\bmils?\b")
_QUANTITY = re.compile(r"^([-+]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][-+]?\d+)?)\s*([^\d.].*)$")


@lru_cache(maxsize=1)
def _registry() -> Any:
    import pint

    return pint.UnitRegistry()


def ureg() -> Any:
    """The package's single pint unit registry (created on first use)."""
    return _registry()


def parse_quantity(value: object, unit: str, field: str) -> float:
    """Return ``value`` as a float in ``unit``.

    ``value`` is a number (taken to be in ``unit`` already), a string holding a number (same), or a
    string with units (``"0.3 in"``, ``"2.7GPa"``, ``"84 deg"``). A quantity of the wrong
    dimension (a length given for a modulus) raises :class:`InputError` naming ``field``.
    """
    if isinstance(value, bool):
        raise InputError(
            field, value, f"a number or a quantity in {unit}", reason="is not a number"
        )
    if isinstance(value, int | float):
        return float(value)
    if not isinstance(value, str):
        raise InputError(
            field, value, f"a number or a quantity in {unit}", reason="is not a number"
        )
    text = value.strip()
    try:
        return float(text)
    except ValueError:
        pass
    import pint

    match = _QUANTITY.match(text)
    if match is None:
        raise InputError(
            field,
            repr(value),
            f"a number or a quantity in {unit} such as '1 {unit}'",
            reason="cannot be read as a quantity",
        )
    magnitude, unit_text = float(match.group(1)), match.group(2).strip()
    # Sheet thickness is sold in "mil" (a thousandth of an inch); pint reads "mil" as 1/1000.
    unit_text = _MIL.sub("thou", unit_text)
    reg = ureg()
    try:
        q = reg.Quantity(magnitude, reg.Unit(unit_text))
    except (
        pint.errors.UndefinedUnitError,
        pint.errors.DefinitionSyntaxError,
        ValueError,
        AttributeError,
        TypeError,
        SyntaxError,
        AssertionError,
    ) as exc:
        raise InputError(
            field,
            repr(value),
            f"a number or a quantity in {unit} such as '1 {unit}'",
            reason=f"has an unknown unit {unit_text!r}",
        ) from exc
    target = reg.Unit(unit)
    try:
        return float(q.to(target).magnitude)
    except pint.errors.DimensionalityError as exc:
        raise InputError(
            field,
            repr(value),
            f"a quantity convertible to {unit}",
            reason=f"has the wrong dimension ({q.dimensionality})",
        ) from exc
