"""The range of designs each model and fitted term was validated over (issue 35 item 1).

One source, ``data/validity.toml``: for each model (the homogenised springs, the local terms of
the three-point, four-point and cantilever tests, the off-axis finite-panel factors, the wheel
test's factor, the capacity model's facet modes and the band's walls' modes) the rows of
docs/validation/*.csv it comes from and, per design variable, the least and greatest value of
its sample: ``facets`` (n + 1 of a layer), ``W`` (mm), ``alpha`` (deg), ``t_over_W``, ``hub``
(the axle hole's diameter over the disc's), ``t`` (the sheet's thickness, mm), ``td_over_h1``
(the folded thickness t_d = h1 + h2 over layer 1's depth h1: how high the band's walls stand
above layer 1) and ``L_over_h`` (the span over the corrugation depth, information only).
``enforce`` names the ends that the solver makes constraints by default
(:mod:`corrugate.solver.validity`; docs/spec.md, ``trust``).
tests/mechanics/test_validity.py recomputes every range from the CSVs.
"""

from __future__ import annotations

import tomllib
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path
from types import MappingProxyType
from typing import Literal

__all__ = ["VARIABLES", "End", "ModelRange", "model_range", "model_ranges"]

#: The design variables a range is stated over, with their words and units.
VARIABLES: dict[str, tuple[str, str]] = {
    "facets": ("facets per layer", ""),
    "W": ("facet width W", " mm"),
    "alpha": ("fold angle alpha", " deg"),
    "t_over_W": ("t/W", ""),
    "hub": ("axle hole over disc diameter", ""),
    "t": ("sheet thickness t", " mm"),
    "td_over_h1": ("folded thickness over layer 1's depth t_d/h1", ""),
    "L_over_h": ("span over corrugation depth L/h", ""),
}

End = Literal["min", "max"]


@dataclass(frozen=True, slots=True)
class ModelRange:
    """One model's validated range (module docstring): its ``name`` (the TOML table), ``label``
    and ``covers`` (what it is and which bounds use it), ``source`` (the validation rows),
    ``ranges`` (variable -> (lo, hi)) and ``enforce`` ((variable, end) pairs)."""

    name: str
    label: str
    covers: str
    source: str
    ranges: MappingProxyType[str, tuple[float, float]]
    enforce: tuple[tuple[str, End], ...]

    def sentence(self, variable: str, end: End) -> str:
        """E.g. ``the cantilever model (local term c = 2.5) is validated for >= 7 facets per
        layer (docs/validation/load_cases_fe.csv ...)``."""
        words, unit = VARIABLES[variable]
        lo, hi = self.ranges[variable]
        value = f">= {lo:.4g}{unit}" if end == "min" else f"<= {hi:.4g}{unit}"
        if variable == "facets":
            return f"{self.label} is validated for {value} facets per layer"
        return f"{self.label} is validated for {words} {value}"


def _read() -> dict[str, object]:
    path = Path(__file__).parents[1] / "data" / "validity.toml"
    if path.is_file():
        return tomllib.loads(path.read_text("utf-8"))
    from importlib import resources

    text = resources.files("corrugate").joinpath("data/validity.toml").read_text("utf-8")
    return tomllib.loads(text)


@lru_cache(maxsize=1)
def model_ranges() -> MappingProxyType[str, ModelRange]:
    """Every model's range, by name, in the file's order."""
    out: dict[str, ModelRange] = {}
    for name, entry in _read().items():
        assert isinstance(entry, dict)
        ranges = {v: (float(entry[v][0]), float(entry[v][1])) for v in VARIABLES if v in entry}
        enforce: list[tuple[str, End]] = []
        for item in entry.get("enforce", []):
            variable, _, end = str(item).partition(".")
            assert variable in ranges and end in ("min", "max"), item
            enforce.append((variable, "min" if end == "min" else "max"))
        out[name] = ModelRange(
            name,
            str(entry["label"]),
            str(entry["covers"]),
            str(entry["source"]),
            MappingProxyType(ranges),
            tuple(enforce),
        )
    return MappingProxyType(out)


def model_range(name: str) -> ModelRange:
    """The range of the model ``name`` (``springs``, ``three-point``, ``cantilever``, ...)."""
    return model_ranges()[name]
