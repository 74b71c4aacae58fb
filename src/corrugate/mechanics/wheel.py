"""The wheel test: a disc's radial stiffness between a ground patch and its axle (docs/load_cases.md 9).

A wheel (a circle layout) carries its load from a ground patch under the rim to an axle through a
central hole: the wheel fixture of docs/fea.md 2.8 (:func:`corrugate.fea.outline.solve_outline`,
``wheel``: the axle pinned through the hole, a rigid no-slip patch of +-15 deg under the rim
pushed towards the axle along eta). The model's K(eta) of a disc sums its strips' springs between
platens (:mod:`corrugate.mechanics.offaxis`), which no bench test of a disc makes. The wheel
test's model is a conservative statement about that FE test, in the style of the finite-panel
factors of docs/load_cases.md 4:

    K_wheel(eta) >= c(eta) x K(eta)

with c(eta) the least ratio FE / model over the sweep of wheel designs of
``docs/validation/wheel_fe.csv`` (``python benchmarks/fea_wheel.py``: ten discs, 2 / 4 / 8
elements per facet), each design's FE taken at 8 per facet less the last step of its series as
the margin for the mesh (:data:`WHEEL_LOWER_RATIO`). The sweep ran at eta = 0 and 45 deg; a
disc's two layers are identical (a circle layout has no independent layers) and the disc is
mirror-symmetric, so eta = 90 reads as 0 and 135 as 45 (the sweep's check at 4 elements per
facet, docs/load_cases.md 9). Other directions have no factor and are refused by the spec.
Outside the validated range (:data:`VALIDATED_WHEEL`: the discs whose mesh series settle, on
the mesh conforming to the rim and the hole since issue 35) the answer warns
(:func:`corrugate.analysis.warnings.wheel_warnings`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from types import MappingProxyType

from corrugate.core.errors import InputError
from corrugate.mechanics.validity import model_range

__all__ = [
    "VALIDATED_WHEEL",
    "WHEEL_DIRECTIONS",
    "WHEEL_FACTOR",
    "WHEEL_LOWER_RATIO",
    "wheel_direction",
    "wheel_factor",
]

#: The least lower ratio over the designs of docs/validation/wheel_fe.csv, by direction (deg):
#: for each design, its FE K at 8 elements per facet less the last step of its series |K8 - K4|
#: (the margin for the mesh: docs/fea.md 6 takes a converging series' next step to be smaller
#: than its last), and its 16-per-facet K where that was run if lower, over the model's K
#: (``python benchmarks/fea_wheel.py --table`` prints it; tests/mechanics/test_wheel.py
#: recomputes it from the file).
WHEEL_LOWER_RATIO: Mapping[float, float] = MappingProxyType({0.0: 0.237011, 45.0: 1.16623})
#: c(eta): :data:`WHEEL_LOWER_RATIO` rounded down to 3 decimals.
WHEEL_FACTOR: Mapping[float, float] = MappingProxyType(
    {e: math.floor(1000.0 * r) / 1000.0 for e, r in WHEEL_LOWER_RATIO.items()}
)
#: The directions the factor holds at (deg): the sweep's and their mirror images.
WHEEL_DIRECTIONS = "a multiple of 45 deg"
#: The validated range (both layers alike; ``data/validity.toml``'s ``[wheel]``,
#: :mod:`corrugate.mechanics.validity`): since issue 35 the span of the sweep's discs whose mesh
#: series judge settles (docs/load_cases.md 9): creases n, interior angle alpha (deg), facet
#: width W (mm), sheet thickness over facet width t / W, and the axle hole's diameter over the
#: disc's.
_WHEEL = model_range("wheel").ranges
VALIDATED_WHEEL: Mapping[str, tuple[float, float]] = MappingProxyType(
    {
        "n": (_WHEEL["facets"][0] - 1, _WHEEL["facets"][1] - 1),
        "alpha": _WHEEL["alpha"],
        "W": _WHEEL["W"],
        "t/W": _WHEEL["t_over_W"],
        "hole/diameter": _WHEEL["hub"],
    }
)


def wheel_direction(eta_deg: float) -> float | None:
    """The sweep's direction (0 or 45 deg) that ``eta_deg`` (deg) reads as by the disc's symmetry
    (module docstring), or None when it is not a multiple of 45 deg."""
    k = eta_deg / 45.0
    if not math.isfinite(k) or abs(k - round(k)) > 1e-9:
        return None
    return 0.0 if round(k) % 2 == 0 else 45.0


def wheel_factor(eta_deg: float) -> float:
    """c(eta): the factor the model's K(eta) (N/mm) is multiplied by to give the wheel test's
    lower bound (module docstring; :data:`WHEEL_FACTOR`)."""
    e = wheel_direction(eta_deg)
    if e is None:
        raise InputError(
            "eta",
            f"{eta_deg:g} deg",
            f"{WHEEL_DIRECTIONS} for the wheel test (the directions its FE sweep covers)",
        )
    return WHEEL_FACTOR[e]
