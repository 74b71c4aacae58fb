"""The in-plane compressive load at which a panel's facets buckle: closed-form bounds.

The stiffness K of ``analyze`` is a small-load stiffness; thin facets buckle long before the
sheet yields. Under compression along the creases of one layer (eta = 0: layer 1, eta = 90:
layer 2) rigid platens give every facet of that layer the same strain, hence the same stress
sigma along its creases, and the layer carries sigma (n + 1) W t; the other layer, loaded across
its creases, carries the share K_C / K_S of that in parallel (docs/theory.md 3.3).

Each facet is a long plate of width W and thickness t. An interior facet is held along both
creases (its inclined neighbours keep each crease line straight): k >= 4. The two end facets have
one free edge (the layer's outer crease line) and one crease; they buckle first, with

    sigma_cr = k pi^2 E / (12 (1 - nu^2)) (t / W)^2,     0.425 <= k <= 1.277

where 0.425 is the long plate simply supported on the crease and free on the other edge, 1.277
the long plate clamped on the crease and free on the other (Timoshenko and Gere, *Theory of
Elastic Stability*, 2nd ed., 1961, section 9.2; Gerard and Becker, NACA TN 3781, 1957, fig. 4);
a real crease restrains the facet's rotation elastically, between the two. The upper value is
for long facets (length >= about 3 W) with simply supported loaded ends; shorter facets or held
ends raise it slightly.

The shell FE (``corrugate validate --buckling``, docs/fea.md section 2.6) checks this: its first
buckling mode is the end facets', inside these bounds. A connector band (a wall on every edge)
holds the free edges and raises the load (the FE measured about 2.7 times for the case study).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from corrugate.geometry.layer import Assembly, crease_layer
from corrugate.mechanics.springs import LayerSprings

__all__ = [
    "K_CLAMPED_FREE",
    "K_SIMPLE_FREE",
    "BucklingEstimate",
    "buckling_bounds",
    "buckling_scale",
]

#: Buckling coefficient of a long plate, simply supported on one edge, free on the other.
K_SIMPLE_FREE = 0.425
#: Buckling coefficient of a long plate, clamped on one edge, free on the other.
K_CLAMPED_FREE = 1.277


@dataclass(frozen=True, slots=True)
class BucklingEstimate:
    """Bounds (N) on the platen load at which the end facets buckle, compression along
    ``eta_deg``: ``low`` with the crease as a hinge, ``high`` with it clamped; ``K`` (N/mm) is
    the platen stiffness along eta of the springs used (K_S + K_C of the two layers)."""

    eta_deg: float
    low: float
    high: float
    K: float

    def travel(self) -> tuple[float, float]:
        """The platen travel (mm) at ``low`` and at ``high``: how far K holds."""
        return self.low / self.K, self.high / self.K

    def as_dict(self) -> dict[str, float]:
        return {"eta_deg": self.eta_deg, "low_N": self.low, "high_N": self.high}


def buckling_scale(E: Any, nu: Any, t: Any, W: Any, n: Any, K_S: Any, K_C: Any) -> Any:
    """The load (N) per unit buckling coefficient k of the assembly compressed along one
    layer's creases: pi^2 E / (12 (1 - nu^2)) (t / W)^2 (n + 1) W t (1 + K_C / K_S), written as
    pi^2 E t^3 (n + 1) / (12 (1 - nu^2) W) (1 + K_C / K_S) so that each variable appears once.

    E (MPa), nu, t, W (mm) and n of the layer loaded along its creases; K_S (N/mm) its spanwise
    spring, K_C (N/mm) the other layer's chordwise one. Plain arithmetic: takes arrays or
    :class:`~corrugate.solver.interval.Interval` (monotone in each argument, so interval bounds
    are exact up to rounding). Times :data:`K_SIMPLE_FREE` it is the lower bound the solver's
    ``buckling_load`` constraints use."""
    return (math.pi**2 / 12.0) * E / (1.0 - nu * nu) * (t * t * t) * (n + 1) / W * (1.0 + K_C / K_S)


def buckling_bounds(
    assembly: Assembly, springs: tuple[LayerSprings, LayerSprings], eta_deg: float
) -> BucklingEstimate | None:
    """Bounds (N) on the in-plane compressive load along ``eta_deg`` at which the end facets of
    the layer loaded along its creases buckle (module docstring), with the layers' ``springs``
    for the other layer's share. None where they do not apply: eta not along a layer's creases,
    or a layout other than a square or rectangle (its facets differ in length and its end facets
    are not long plates)."""
    along = crease_layer(eta_deg)
    if along is None or assembly.layout.name not in ("square", "rectangle"):
        return None
    across = 1 - along
    layer = assembly.layers[along]
    K_S, K_C = float(springs[along].K_S), float(springs[across].K_C)
    m = layer.material
    load = float(buckling_scale(m.E, m.nu, layer.t, layer.W, layer.n, K_S, K_C))  # N per unit k
    return BucklingEstimate(float(eta_deg), K_SIMPLE_FREE * load, K_CLAMPED_FREE * load, K_S + K_C)
