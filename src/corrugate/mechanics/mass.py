"""Mass of a design: rho t times the area of every cut part (docs/theory.md section 4).

The cut parts are the two layers' flat blanks and the connector band (cut from layer 1's sheet).
Facet j of a layer is a flat strip of width W and area W L_j (see :mod:`corrugate.geometry.layouts`), so a
layer weighs rho t W sum_j L_j; the band's area is :func:`corrugate.geometry.connectors.connector_area`.
Every mass the package reports, the optimiser's included, comes from this module, and equals
rho t times the area of the polygons in the cut files. A layout's holes (:mod:`corrugate.geometry.holes`)
are cut from both layers' blanks: each removes rho t A_h / sin(alpha/2) from a layer. Another
profile's layer (:class:`corrugate.geometry.profile.Profile`) is the same with W its developed
width per repeat unit and sin(alpha/2) its pitch / developed.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from corrugate.geometry.connectors import connector_area
from corrugate.geometry.fabrication_options import DEFAULT_FABRICATION, FabricationOptions
from corrugate.geometry.layer import Assembly
from corrugate.geometry.layouts import Layout, length_sum

__all__ = ["MassBreakdown", "assembly_mass", "connector_mass", "layer_mass"]


def layer_mass(
    density: ArrayLike,
    t: ArrayLike,
    W: ArrayLike,
    sum_L: ArrayLike,
    layout: Layout | None = None,
    pitch: ArrayLike | None = None,
) -> NDArray[np.float64]:
    """Mass (g) of a layer's flat blank: density (g/mm^3) x t (mm) x W (mm) x sum_j L_j (mm),
    with ``W`` the profile's developed width of one repeat unit (the facet width W for the
    zig-zag; :attr:`corrugate.geometry.profile.Profile.developed`),
    less the layout's holes when ``layout`` and the layer's ``pitch`` (mm) are given: each hole of
    plan area A_h is cut from the blank stretched by W / p = 1 / sin(alpha/2) across the creases,
    so it removes density x t x A_h W / p (:mod:`corrugate.geometry.holes`)."""
    m = np.asarray(density) * np.asarray(t) * np.asarray(W) * np.asarray(sum_L)
    if layout is not None and layout.holes and pitch is not None:
        from corrugate.geometry.holes import hole_area  # a layout with holes only

        cut = hole_area(layout.holes) * np.asarray(W) / np.asarray(pitch)
        m = m - np.asarray(density) * np.asarray(t) * cut
    return np.asarray(m, dtype=np.float64)


def connector_mass(
    density: ArrayLike,
    t: ArrayLike,
    layout: Layout,
    Lx: ArrayLike,
    Ly: ArrayLike,
    thickness: ArrayLike,
    opts: FabricationOptions = DEFAULT_FABRICATION,
) -> NDArray[np.float64]:
    """Mass (g) of the connector band: density (g/mm^3) x t (mm) x its flat area (mm^2)."""
    area = connector_area(layout, Lx, Ly, thickness, opts)
    return np.asarray(np.asarray(density) * np.asarray(t) * area, dtype=np.float64)


@dataclass(frozen=True, slots=True)
class MassBreakdown:
    """Mass of a design by part (g)."""

    layer1: float
    layer2: float
    connectors: float

    @property
    def total(self) -> float:
        return self.layer1 + self.layer2 + self.connectors

    def as_dict(self) -> dict[str, float]:
        return {
            "layer1_g": self.layer1,
            "layer2_g": self.layer2,
            "connectors_g": self.connectors,
            "total_g": self.total,
        }


def assembly_mass(a: Assembly, opts: FabricationOptions = DEFAULT_FABRICATION) -> MassBreakdown:
    """Mass (g) of the assembly's cut parts: both layers and the connector band."""
    l1, l2 = a.layer1, a.layer2
    z1, z2 = l1.profile, l2.profile  # developed = W for the zig-zag
    m1 = layer_mass(
        l1.material.density,
        l1.t,
        z1.developed,
        length_sum(a.layout, l1.n, a.Ly),
        a.layout,
        z1.pitch,
    )
    m2 = layer_mass(
        l2.material.density,
        l2.t,
        z2.developed,
        length_sum(a.layout, l2.n, a.Lx),
        a.layout,
        z2.pitch,
    )
    mc = connector_mass(l1.material.density, l1.t, a.layout, a.Lx, a.Ly, a.thickness, opts)
    return MassBreakdown(float(m1), float(m2), float(mc))
