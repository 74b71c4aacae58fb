"""Spec dicts built from numbers in internal units, written with their units before parsing.

A spec refuses a plain number for a quantity whose unit is not mm or deg
(:class:`corrugate.spec.schema.MissingUnitError`). Tests that compute with the numbers of a spec
dict (brute-force searches read ``b["min"]``) keep them as numbers and pass
:func:`with_units` of the dict to the parser: every such number written as a string with its
internal unit (``80000`` -> ``"80000 N*mm^2"``), so the parser reads exactly the same value.
"""

from __future__ import annotations

import copy
from typing import Any

#: The internal unit of each quantity-valued spec key that needs one, by (table, key).
_STIFFNESS = {
    "flexural_rigidity": "N*mm^2",
    "bending_stiffness": "N*mm",
    "inplane_stiffness": "N/mm",
    "buckling_load": "N",
}
_MATERIAL = {"E": "MPa", "density": "g/cm^3", "yield_strength": "MPa"}


def _q(value: Any, unit: str) -> Any:
    """``value`` with ``unit`` when it is a plain number (repr keeps every digit), else as is."""
    if isinstance(value, bool) or not isinstance(value, int | float):
        return value
    return f"{float(value)!r} {unit}"


def with_units(spec: dict[str, Any]) -> dict[str, Any]:
    """A copy of ``spec`` with every plain number of a key that needs a unit given its
    internal unit."""
    d = copy.deepcopy(spec)
    c = d.get("constraints") or {}
    for key, unit in _STIFFNESS.items():
        for bound in c.get(key) or []:
            bound["min"] = _q(bound.get("min"), unit)
    for key in ("deflection", "strength"):
        for case in c.get(key) or []:
            if "load" in case:
                case["load"] = _q(case["load"], "N")
    if isinstance(c.get("mass"), dict) and "max" in c["mass"]:
        c["mass"]["max"] = _q(c["mass"]["max"], "g")
    mats = [d["material"]] if isinstance(d.get("material"), dict) else []
    mats += [m for m in d.get("materials") or [] if isinstance(m, dict)]
    for m in mats:
        for key, unit in _MATERIAL.items():
            if key in m:
                m[key] = _q(m[key], unit)
    return d
