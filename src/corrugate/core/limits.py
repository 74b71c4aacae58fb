"""The one table of input limits: every number a user can give, with its physical meaning.

The command line, the spec parser and the web API check their inputs against :data:`LIMITS` before
any arithmetic or allocation, so that no input can overflow a formula, ask numpy for gigabytes, run
for minutes or print NaN. The bounds are generous physical ones (a facet narrower than 0.01 mm
cannot be cut, a sheet thicker than 100 mm does not fold), not the limits of the models' validity
(those give warnings). NaN, infinity and subnormal values (:func:`is_normal`) lie outside every
range. Each failure is one :class:`~corrugate.core.errors.InputError` line naming the field, the
value and the allowed range.

:func:`require_finite` is the last check before anything is printed: NaN or infinity never reaches
stdout or JSON.
"""

from __future__ import annotations

import math
import numbers
import sys
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from corrugate.core.errors import InputError, ResultError

__all__ = [
    "LIMITS",
    "MAX_BUDGET_BOXES",
    "MAX_COUNTS",
    "MAX_DASHES",
    "MAX_DEPTH",
    "MAX_GRID_POINTS",
    "MAX_INT_DIGITS",
    "MAX_NAME_CHARS",
    "MAX_PATH_CHARS",
    "MAX_SPEC_BYTES",
    "MAX_TEXT_CHARS",
    "Limit",
    "abnormal_reason",
    "bracket_depth",
    "check",
    "check_count",
    "check_depth",
    "check_grid",
    "check_integer",
    "check_items",
    "check_text",
    "first_non_finite",
    "integer_shown",
    "is_normal",
    "require_finite",
]


@dataclass(frozen=True, slots=True)
class Limit:
    """Allowed range ``lo .. hi`` of one input, in ``unit``; ``open_lo`` / ``open_hi`` exclude the
    bound itself. ``meaning`` says why the bounds are where they are."""

    key: str
    lo: float
    hi: float
    unit: str
    meaning: str
    open_lo: bool = False
    open_hi: bool = False

    @property
    def allowed(self) -> str:
        u = f" {self.unit}" if self.unit else ""
        lo = "<" if self.open_lo else "<="
        hi = "<" if self.open_hi else "<="
        return f"{self.lo:g} {lo} {self.key} {hi} {self.hi:g}{u}"

    def contains(self, x: float) -> bool:
        if not is_normal(x):
            return False
        above = x > self.lo if self.open_lo else x >= self.lo
        below = x < self.hi if self.open_hi else x <= self.hi
        return above and below


#: The table. Lengths in mm, angles in deg, moduli in MPa, densities in g/cm^3, times in s.
LIMITS: dict[str, Limit] = {
    lim.key: lim
    for lim in (
        Limit("W", 0.01, 10_000.0, "mm", "facet width: 10 um (below any cutter) to 10 m"),
        Limit("thickness", 1e-5, 100.0, "mm", "sheet thickness: 10 nm film to a 100 mm board"),
        Limit(
            "n", 1, 5000, "", "number of creases: one fold to 5000 (a 10 m sheet of 2 mm pleats)"
        ),
        Limit("alpha", 0.0, 180.0, "deg", "interior fold angle: closed to flat", True, True),
        Limit(
            "eta",
            -360.0,
            360.0,
            "deg",
            "a direction in the panel: one turn either way (1e300 deg names no direction "
            "a reader can check; docs/spec.md)",
        ),
        Limit("E", 1e-3, 1e7, "MPa", "Young's modulus: a soft foam (1 kPa) to above diamond"),
        Limit("nu", -1.0, 0.5, "", "Poisson's ratio of a stable isotropic solid", True, True),
        Limit("density", 1e-3, 30.0, "g/cm^3", "aerogel to above osmium (22.6 g/cm^3)"),
        Limit("length", 0.0, 1e6, "mm", "any other length (sizes, holes, bounds): up to 1 km"),
        Limit("coordinate", -1e6, 1e6, "mm", "a position in the plan: within 1 km"),
        Limit("mass", 0.0, 1e9, "g", "a mass bound: up to 1000 t"),
        Limit("stiffness", 0.0, 1e15, "", "a stiffness bound in N/mm, N mm or N mm^2"),
        Limit("load", 0.0, 1e9, "N", "a load case's load: up to 1 GN (100 000 t)"),
        Limit("mesh", 2, 64, "", "shell elements across one facet (the refinement stops at 16)"),
        Limit("cell_mesh", 1, 2000, "", "unit-cell elements along a facet (refinement: <= 640)"),
        Limit("cell_mesh_through", 1, 64, "", "unit-cell elements through t or along y"),
        Limit("jobs", 1, 64, "", "parallel solver processes"),
        Limit("timeout", 1.0, 86_400.0, "s", "time allowed for one solver run: 1 s to a day"),
        Limit(
            "budget",
            0.01,
            86_400.0,
            "s",
            "CPU seconds one design or Pareto front may take (search and explanation): "
            "10 ms to a day",
        ),
        Limit("samples", 2, 1_000_000, "", "Monte Carlo samples"),
        Limit("points", 2, 10_000, "", "points on a Pareto front"),
        Limit("W_tol", 0.0, 1_000.0, "mm", "one-sigma error of W: up to 1 m"),
        Limit("alpha_tol", 0.0, 90.0, "deg", "one-sigma error of alpha: up to 90 deg"),
        Limit("W_worst", 0.0, 5.0, "mm", "worst-case error of W ([tolerances]): up to 5 mm"),
        Limit(
            "alpha_worst",
            0.0,
            30.0,
            "deg",
            "worst-case error of alpha ([tolerances]): up to 30 deg",
        ),
        Limit("seed", 0, 2**63 - 1, "", "random seed (numpy takes a non-negative integer)"),
        Limit(
            "perforation",
            0.1,
            1_000.0,
            "mm",
            "a perforation dash or gap: at least the 0.1 mm a blade or laser cutter resolves",
        ),
    )
}

#: Most perforation dashes in one design (about 150 bytes of DXF a dash: at most about 15 MB; see
#: :func:`corrugate.fabrication.linestyle.check_style`).
MAX_DASHES = 100_000


def is_normal(x: float) -> bool:
    """Whether ``x`` is zero or a finite normal float: not NaN, not infinite, not subnormal
    (below 2.2e-308 in magnitude, where a quotient or a cube overflows or loses all precision)."""
    return math.isfinite(x) and (x == 0 or abs(x) >= sys.float_info.min)


def abnormal_reason(x: float) -> str | None:
    """Why ``x`` is not a value to compute with (the ``reason`` of its :class:`InputError`):
    NaN, infinite or subnormal; None for zero and finite normal floats."""
    if math.isnan(x):
        return "is not a number (NaN)"
    if math.isinf(x):
        return "is infinite"
    if not is_normal(x):
        return f"is subnormal (closer to zero than {sys.float_info.min:.3g})"
    return None


#: Most boxes one design or Pareto front may bound (the work budget's box count,
#: :mod:`corrugate.solver.budget`).
MAX_BUDGET_BOXES = 10**12

#: Most items of the lists of a spec that set how much work a solve is, by what they count
#: (checked where the spec is parsed: command line, TOML and web alike; each refusal one
#: :class:`InputError` line). Costs at the cap, one design on a 2-core machine
#: (``corrugate design``, CPU time and peak memory; the benchmark specs of issue 22):
#: 16 two-mm holes in a 70-90 mm square 1.9 s, 150 MB; a 256-vertex outline 8.5 s, 340 MB;
#: 32 stiffness bounds 1.1 s, 110 MB (32 off-axis ones under ``maximize`` 9.7 s); 32 thickness
#: candidates 2.3 s, 80 MB. Beyond, the work grows with the count (the pairs of sheets, every
#: bound in every box, every vertex in every point) and the work budget stops it.
MAX_COUNTS: dict[str, int] = {
    "holes": 16,  # layout.holes
    "vertices": 256,  # layout.vertices, and each polygon hole's vertices
    "bounds": 32,  # behavioural bounds: stiffness, buckling, deflection and strength, together
    "thicknesses": 32,  # candidate sheets: thicknesses over every material
}

#: Most points a gridded design variable may have ((max - min) / step + 1).
MAX_GRID_POINTS = 100_000
#: Longest name (spec name, material name) in characters; longest other text value.
MAX_NAME_CHARS = 200
MAX_TEXT_CHARS = 10_000
#: Largest spec file, deepest nesting of arrays and tables in a spec or request body.
MAX_SPEC_BYTES = 1 << 20
MAX_DEPTH = 16
#: Longest output path (Linux PATH_MAX is 4096, NAME_MAX 255).
MAX_PATH_CHARS = 4000


#: Most digits of an integer in any input (a spec, a web body, a design.json, an option): 10**30
#: is beyond every range of :data:`LIMITS` and within a float's; a longer one is refused by its
#: key (:func:`check_integer`) before it reaches a float conversion.
MAX_INT_DIGITS = 30


def integer_shown(value: int) -> str:
    """How an error shows a long integer: its digit count, never its (maybe 4000) digits."""
    v = abs(int(value))
    if v < 10**MAX_INT_DIGITS:
        return str(value)
    digits = len(str(v)) if v.bit_length() < 13_000 else int(v.bit_length() * 0.30103) + 1
    return f"an integer of {digits} digits"


def check_integer(field: str, value: int) -> int:
    """``value`` (an integer of an input) when it has at most :data:`MAX_INT_DIGITS` digits, else
    one :class:`InputError` line naming ``field`` and the digit count."""
    if abs(int(value)) >= 10**MAX_INT_DIGITS:
        raise InputError(
            field,
            integer_shown(value),
            f"a number of at most {MAX_INT_DIGITS} digits",
            reason="is too long",
        )
    return int(value)


def _shown(value: object, unit: str) -> str:
    integral = isinstance(value, numbers.Integral) and not isinstance(value, bool)
    if integral and abs(int(value)) >= 10**MAX_INT_DIGITS:  # type: ignore[call-overload]
        return integer_shown(int(value))  # type: ignore[call-overload]
    if isinstance(value, numbers.Real) and not isinstance(value, bool):
        return f"{float(value):g} {unit}".strip()
    return repr(value)[:60]


def check(key: str, value: float, field: str | None = None) -> float:
    """``value`` if it lies within ``LIMITS[key]``, else :class:`InputError` naming ``field``
    (default: the key)."""
    lim = LIMITS[key]
    if isinstance(value, numbers.Integral) and not isinstance(value, bool):
        check_integer(field or key, int(value))
    x = float(value)
    if not lim.contains(x):
        reason = abnormal_reason(x)
        if reason is not None:
            raise InputError(field or key, _shown(x, lim.unit), lim.allowed, reason=reason)
        raise InputError(field or key, _shown(x, lim.unit), lim.allowed)
    return x


def check_count(key: str, value: int, field: str | None = None) -> int:
    """An integer ``value`` within ``LIMITS[key]`` (compared as an int: no float overflow)."""
    lim = LIMITS[key]
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise InputError(field or key, repr(value)[:60], lim.allowed, reason="is not an integer")
    if not lim.lo <= int(value) <= lim.hi:
        raise InputError(field or key, integer_shown(int(value)), lim.allowed)
    return int(value)


def check_items(kind: str, field: str, count: int, what: str) -> None:
    """At most ``MAX_COUNTS[kind]`` items (``what``, e.g. ``holes``) in ``field``, else one
    :class:`InputError` line naming the field, the count and the cap."""
    cap = MAX_COUNTS[kind]
    if count > cap:
        raise InputError(
            field, f"{count} {what}", f"at most {cap} {what}", reason="has too many items"
        )


def check_grid(field: str, lo: float, hi: float, step: float | None, unit: str) -> None:
    """A gridded variable ``lo, lo + step, ... hi`` has at most :data:`MAX_GRID_POINTS` points."""
    if step is None:
        return
    if not (math.isfinite(step) and step > 0):
        raise InputError(f"{field}.step", f"{step:g} {unit}", f"step > 0 {unit}")
    points = (hi - lo) / step + 1
    if not math.isfinite(points) or points > MAX_GRID_POINTS:
        raise InputError(
            f"{field}.step",
            f"{step:g} {unit}",
            f"a step giving at most {MAX_GRID_POINTS} grid points on {lo:g}..{hi:g} {unit} "
            f"(step >= {(hi - lo) / (MAX_GRID_POINTS - 1):.3g} {unit})",
            reason="is too fine",
        )


def check_text(field: str, value: str, limit: int = MAX_NAME_CHARS) -> str:
    """A text value of at most ``limit`` characters."""
    if len(value) > limit:
        raise InputError(
            field,
            f"{value[:20]!r}... ({len(value)} characters)",
            f"at most {limit} characters",
            reason="is too long",
        )
    return value


def check_depth(data: Any, field: str, limit: int = MAX_DEPTH) -> None:
    """Arrays and tables nested at most ``limit`` deep (checked without recursion)."""
    stack: list[tuple[Any, int]] = [(data, 0)]
    while stack:
        obj, depth = stack.pop()
        if depth > limit:
            raise InputError(
                field,
                f"nesting {depth} deep",
                f"at most {limit} levels of arrays and tables",
                reason="is nested too deeply",
            )
        if isinstance(obj, Mapping):
            stack.extend((v, depth + 1) for v in obj.values())
        elif isinstance(obj, list | tuple):
            stack.extend((v, depth + 1) for v in obj)


def bracket_depth(text: str) -> int:
    """An upper bound of the nesting of inline arrays and tables in TOML or JSON ``text``
    (brackets and braces in a row, counted without parsing; quoted text may only make it larger
    than the truth): deep nesting is refused before a parser recurses into it."""
    depth = best = 0
    for ch in text:
        if ch in "[{":
            depth += 1
            best = max(best, depth)
        elif ch in "]}":
            depth = max(0, depth - 1)
    return best


def first_non_finite(obj: object, where: str = "") -> str | None:
    """The path of the first NaN or infinite float in nested dicts and lists, or None."""
    stack: list[tuple[object, str]] = [(obj, where)]
    while stack:
        item, path = stack.pop()
        if isinstance(item, float):
            if not math.isfinite(item):
                return path or "result"
            continue
        if isinstance(item, str | int) or item is None:  # the common leaves: no ABC check
            continue
        if isinstance(item, Mapping):
            stack.extend((v, f"{path}.{k}" if path else str(k)) for k, v in item.items())
        elif isinstance(item, list | tuple):
            stack.extend((v, f"{path}[{i}]") for i, v in enumerate(item))
    return None


def require_finite(obj: object, what: str = "result") -> None:
    """Raise :class:`ResultError` if ``obj`` holds a NaN or an infinity (before printing it)."""
    bad = first_non_finite(obj)
    if bad is not None:
        raise ResultError(
            f"{what} {bad} is not a finite number: the inputs are outside the "
            "range the models can evaluate"
        )
