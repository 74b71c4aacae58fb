"""Units at the boundaries: parse user quantities into corrugate's internal system.

Internal units (docs/theory.md section 8): mm, N, MPa (= N/mm^2), g, degrees at the boundary and radians
inside the formulas. Users may give a plain number (read in the field's default unit) or a string
with units such as ``"0.3 in"`` or ``"2.7 GPa"``. The common units are converted from a small
table (:data:`_TABLE`, checked against pint by the tests), so a spec in them never imports pint;
pint converts everything else, its registry loaded from its disk cache.

A quantity string is a number, then a unit read by the grammar of
:mod:`corrugate.core.unit_grammar` (never by an expression evaluator): unit names joined by
``*``, ``/``, ``·`` or a space, each with an optional whole exponent ``^n`` or ``**n``
(|n| <= 4, no exponent of an exponent, no parenthesised exponent), parentheses at most 4 deep,
at most 64 characters; ``1/mm`` is allowed, any other number inside the unit is refused
(``mm/0`` as a division by zero) and ``mm^0`` is the pure number 1. pint is given only single
unit names; the unit is their product with the small integer powers the grammar found, so no
text makes it compute. Every refusal is an :class:`InputError` naming the field.
"""

from __future__ import annotations

import math
import os
import re
import sys
from functools import lru_cache
from typing import Any

from corrugate.core.errors import InputError
from corrugate.core.text import foreign_digits
from corrugate.core.unit_grammar import parse_unit

__all__ = ["parse_quantity", "ureg"]

_MIL = re.compile(r"\bmils?\b")
_QUANTITY = re.compile(r"^([-+]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][-+]?\d+)?)\s*([^\d.].*)$")


#: Unit texts read without pint: text -> (value of one unit in SI base units, its dimension as
#: exponents of (m, kg, s, angle)). pint counts angles as dimensionless; here they are a dimension
#: of their own, so an angle meets only an angle on this path and everything else (and every text
#: not listed) goes to pint. tests/core/test_units.py checks every entry against pint.
_L, _M, _F, _A, _ONE = (1, 0, 0, 0), (0, 1, 0, 0), (1, 1, -2, 0), (0, 0, 0, 1), (0, 0, 0, 0)
_P = (-1, 1, -2, 0)  # pressure, modulus: N/m^2
_RHO = (-3, 1, 0, 0)  # density
_EI = (3, 1, -2, 0)  # force * length^2 (flexural rigidity)
_D = (2, 1, -2, 0)  # force * length (bending stiffness)
_K = (0, 1, -2, 0)  # force / length (in-plane stiffness)
_T = (0, 0, 1, 0)  # time (a sustained load's duration)
_INCH = 0.0254
_LBF = 4.4482216152605
_TABLE: dict[str, tuple[float, tuple[int, int, int, int]]] = {
    "m": (1.0, _L),
    "cm": (1e-2, _L),
    "mm": (1e-3, _L),
    "um": (1e-6, _L),
    "in": (_INCH, _L),
    "inch": (_INCH, _L),
    "thou": (_INCH / 1000, _L),
    "ft": (12 * _INCH, _L),
    "deg": (math.pi / 180, _A),
    "degree": (math.pi / 180, _A),
    "rad": (1.0, _A),
    "radian": (1.0, _A),
    "turn": (2 * math.pi, _A),
    "Pa": (1.0, _P),
    "kPa": (1e3, _P),
    "MPa": (1e6, _P),
    "GPa": (1e9, _P),
    "psi": (_LBF / _INCH**2, _P),
    "ksi": (1e3 * _LBF / _INCH**2, _P),
    "N/mm^2": (1e6, _P),
    "N/m^2": (1.0, _P),
    "N": (1.0, _F),
    "mN": (1e-3, _F),
    "kN": (1e3, _F),
    "lbf": (_LBF, _F),
    "g": (1e-3, _M),
    "mg": (1e-6, _M),
    "kg": (1.0, _M),
    "lb": (0.45359237, _M),
    "oz": (0.45359237 / 16, _M),
    "g/cm^3": (1e3, _RHO),
    "g/mm^3": (1e6, _RHO),
    "kg/m^3": (1.0, _RHO),
    "N*mm^2": (1e-6, _EI),
    "N*cm^2": (1e-4, _EI),
    "N*m^2": (1.0, _EI),
    "mN*m^2": (1e-3, _EI),
    "N*mm": (1e-3, _D),
    "N*m": (1.0, _D),
    "mN*m": (1e-3, _D),
    "N/mm": (1e3, _K),
    "N/m": (1.0, _K),
    "kN/m": (1e3, _K),
    "mN/mm": (1.0, _K),
    "s": (1.0, _T),
    "min": (60.0, _T),
    "minute": (60.0, _T),
    "h": (3600.0, _T),
    "hr": (3600.0, _T),
    "hour": (3600.0, _T),
    "day": (86400.0, _T),
    "week": (7 * 86400.0, _T),
    "year": (365.25 * 86400.0, _T),
    "dimensionless": (1.0, _ONE),
    "percent": (1e-2, _ONE),
}
_OPERATOR = re.compile(r"\s*(\*\*|[*/^])\s*")
_SPACES = re.compile(r"\s+")


def _table_key(unit_text: str) -> str:
    """``unit_text`` written as the keys of :data:`_TABLE`: ``**`` as ``^``, no space around an
    operator, a space between two units as ``*``."""
    text = _OPERATOR.sub(lambda m: "^" if m.group(1) == "**" else m.group(1), unit_text.strip())
    return _SPACES.sub("*", text)


def _table_factor(unit_text: str, unit: str) -> float | None:
    """How many ``unit`` one ``unit_text`` is, from :data:`_TABLE`; None when either is not listed
    or their dimensions differ (pint then converts, or names the error)."""
    have, want = _TABLE.get(_table_key(unit_text)), _TABLE.get(_table_key(unit))
    if have is None or want is None or have[1] != want[1]:
        return None
    return have[0] / want[0]


def _cache_folder() -> str | None:
    """Where pint keeps its parsed definitions (``$CORRUGATE_PINT_CACHE``; default pint's own
    user cache folder, ``:auto:``); ``CORRUGATE_PINT_CACHE=off`` builds the registry from text."""
    folder = os.environ.get("CORRUGATE_PINT_CACHE", ":auto:")
    return None if folder.lower() in ("", "off", "none") else folder


def _import_pint() -> Any:
    """Import pint without letting it import dask (pint.compat probes for dask arrays, ~0.3 s of
    CPU; corrugate never gives pint a dask array). A dask already imported is left as it is."""
    if "pint" in sys.modules or "dask" in sys.modules:
        import pint

        return pint
    sys.modules["dask"] = None  # type: ignore[assignment]  # import machinery: "not installed"
    try:
        import pint
    finally:
        if sys.modules.get("dask", 0) is None:
            del sys.modules["dask"]
    return pint


@lru_cache(maxsize=1)
def _registry() -> Any:
    pint = _import_pint()
    folder = _cache_folder()
    if folder is not None:
        try:
            # the definitions parsed once and kept on disk: 0.05 s instead of 0.45 s per process
            return pint.UnitRegistry(cache_folder=folder)
        except Exception:  # an unwritable or half-written cache: build from the text instead
            pass
    return pint.UnitRegistry()


def ureg() -> Any:
    """The package's single pint unit registry (created on first use, from pint's disk cache)."""
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
    if isinstance(value, int):  # a 400-digit integer would overflow float(): named by its field
        from corrugate.core.limits import check_integer

        return float(check_integer(field, value))
    if isinstance(value, float):
        return float(value)
    if not isinstance(value, str):
        raise InputError(
            field, value, f"a number or a quantity in {unit}", reason="is not a number"
        )
    text = value.strip()
    if foreign_digits(text):  # float() reads full-width and other scripts' digits
        raise InputError(
            field,
            repr(value),
            f"a number in ASCII digits 0-9, or a quantity in {unit} such as '1 {unit}'",
            reason="has digits other than 0-9",
        )
    try:
        return float(text)
    except ValueError:
        pass
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
    powers = parse_unit(unit_text, field, value)  # refuses every text outside the grammar
    factor = _table_factor(unit_text, unit)
    if factor is not None:  # the common units, without importing pint (~0.3 s of CPU)
        return magnitude * factor
    pint = _import_pint()
    reg = ureg()
    unknown = InputError(
        field,
        repr(value),
        f"a number or a quantity in {unit} such as '1 {unit}'",
        reason=f"has an unknown unit {unit_text!r}",
    )
    try:
        q = reg.Quantity(magnitude, _product(reg, powers))
    except _UnknownNameError:
        raise unknown from None
    except (pint.errors.PintError, ArithmeticError, TypeError, ValueError) as exc:
        # an offset unit (degC) in a product, a size beyond a float: not a unit to convert
        raise unknown from exc
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
    except (pint.errors.PintError, ArithmeticError) as exc:
        raise InputError(
            field,
            repr(value),
            f"a quantity convertible to {unit}",
            reason=f"cannot be converted to {unit} ({type(exc).__name__})",
        ) from exc


class _UnknownNameError(LookupError):
    """A unit name pint does not read as one unit (internal to :func:`_product`)."""


def _product(reg: Any, powers: tuple[tuple[str, int], ...]) -> Any:
    """The pint unit ``prod(name ** power)``: each name looked up alone, the powers small integers
    (:func:`corrugate.core.unit_grammar.parse_unit`), so nothing here evaluates an expression."""
    unit = reg.Unit("dimensionless")
    for name, power in powers:
        try:
            one = reg.Unit(name)  # one identifier (or ``°``, ``%``): pint reads it as one name
        except Exception as exc:  # pint's name reader fails in many ways on odd names
            raise _UnknownNameError(name) from exc
        unit = unit * one**power
    return unit
