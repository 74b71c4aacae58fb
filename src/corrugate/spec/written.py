"""The units a spec's author wrote its quantities in, by spec path (issue 36 item 4).

The spec is read into internal units (mm, N, MPa, g; docs/theory.md section 8), so ``min = "100
N*m^2"`` becomes 1e8 N*mm^2. What the answer says back about a bound (the diagnosis of an
infeasible spec, :mod:`corrugate.solver.diagnosis`) is written in the unit the author used, so
:func:`written_units` keeps, for each quantity given as a string with a unit, its unit text:
``{"constraints.flexural_rigidity[0].min": "N*m^2", "constraints.side.max": "mm", ...}``.
A plain number (read in the key's own unit) has no entry.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from typing import Any

__all__ = ["written_units"]

#: A number, then a unit text (as :func:`corrugate.core.units.parse_quantity` reads it).
_QUANTITY = re.compile(r"^\s*[-+]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][-+]?\d+)?\s*([^\d.\s].*?)\s*$")
#: The tables whose quantities a diagnosis may name.
_TABLES = ("constraints", "fabrication")


def written_units(data: Mapping[str, Any]) -> dict[str, str]:
    """The unit text of every quantity written with one under ``data``'s ``[constraints]`` and
    ``[fabrication]`` tables (a spec as read from TOML), by its spec path."""
    out: dict[str, str] = {}

    def walk(value: Any, path: str, depth: int) -> None:
        if depth > 8:  # a spec is shallow; the parser refuses deeper nesting anyway
            return
        if isinstance(value, Mapping):
            for k, v in value.items():
                walk(v, f"{path}.{k}", depth + 1)
        elif isinstance(value, list):
            for i, v in enumerate(value):
                walk(v, f"{path}[{i}]", depth + 1)
        elif isinstance(value, str):
            m = _QUANTITY.match(value)
            if m is not None:
                out[path] = m.group(1)

    for table in _TABLES:
        if isinstance(data.get(table), Mapping):
            walk(data[table], table, 0)
    return out
