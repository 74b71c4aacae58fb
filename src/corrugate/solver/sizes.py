"""The evaluators of the sizes and the mass: exact values at points, bounds over boxes.

At points the extents Lx, Ly, the folded thickness t_d and the mass are ``evaluate``'s
(:class:`~.context.AtPoints`). Over boxes they are monotone (docs/theory.md sections 2 and 4):
with s = sin(alpha/2), c = cos(alpha/2) and 0 < alpha < 180 deg, Lx = (n1 + 1) W1 s1 increases
with n1, W1 and alpha1; t_d = W1 c1 + W2 c2 increases with W and decreases with alpha; the blank
(n + 1) W increases with n and W; the mass rho t W (n + 1) S a_f of each layer (S the other
layer's extent, a_f the outline's area fraction; :mod:`corrugate.mechanics.mass`) increases with
every variable, and the connector band's mass increases with Lx, Ly and t_d
(:mod:`corrugate.geometry.connectors`). So their bounds are their values at the box corners (the
band's at the bounds of Lx, Ly and t_d), computed with the same building blocks as ``evaluate``
(:class:`~.context.OverBoxes`). Holes (:mod:`corrugate.geometry.holes`) take rho t A_h / s off
each layer's mass, most at the box's lowest alpha, so the corner bounds stay bounds.

The longest facet max_j L_j = F(n) S with F(n) = (n + 1) max_j dA_j
(:mod:`corrugate.geometry.layouts`) is bounded by the range of F over the box's n
(:class:`~.tables.Tables`) and the range of S.

Each kind here is given by point values whether a problem asks for it or not (the answer and the
tolerance analysis read them).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from corrugate.geometry.layouts import length_sum
from corrugate.geometry.profile import ProfileKind
from corrugate.mechanics.mass import connector_mass, layer_mass
from corrugate.solver.context import AtPoints, Corner, OverBoxes
from corrugate.solver.evaluator import Evaluator, Pair, register
from corrugate.solver.points import DesignPoints, blank_width
from corrugate.solver.quantity import FACET, FLAT, LX, LY, MASS, THICKNESS, Quantity

__all__ = ["EXTENT_X", "EXTENT_Y", "FACETS", "FLATS", "MASSES", "THICKNESSES"]

FloatArray = NDArray[np.float64]


def _always(q: Quantity) -> tuple[Quantity]:
    return (q,)


EXTENT_X = register(
    Evaluator(
        ("Lx",),
        lambda at, q: at.Lx,
        lambda over, q: over.Lx,
        lambda problem: _always(LX),
    )
)
EXTENT_Y = register(
    Evaluator(
        ("Ly",),
        lambda at, q: at.Ly,
        lambda over, q: over.Ly,
        lambda problem: _always(LY),
    )
)


def _thickness_at(at: AtPoints, q: Quantity) -> FloatArray:
    return np.asarray(at.ev.thickness[:, 0])


THICKNESSES = register(
    Evaluator(
        ("thickness",),
        _thickness_at,
        lambda over, q: over.thickness,
        lambda problem: _always(THICKNESS),
    )
)


def _flat(x: DesignPoints, kind: ProfileKind) -> FloatArray:
    """The longest flat blank of the layers (mm): (n + 1) W for the zig-zag
    (:func:`~.points.blank_width`); it grows with every variable, so a box's corners bound it."""
    one, two = x.layer(0), x.layer(1)
    if kind.is_default:
        return np.asarray(np.maximum((one.n + 1) * one.W, (two.n + 1) * two.W))
    return np.asarray(np.maximum(blank_width(one, kind), blank_width(two, kind)))


def _flat_over(over: OverBoxes, q: Quantity) -> Pair:
    low = _flat(over.lo, over.problem.profile_kind)
    return low, low if over.point else _flat(over.hi, over.problem.profile_kind)


FLATS = register(
    Evaluator(
        ("flat",),
        lambda at, q: _flat(at.x, at.problem.profile_kind),
        _flat_over,
        lambda problem: _always(FLAT),
    )
)


def _facet_at(at: AtPoints, q: Quantity) -> FloatArray:
    facet1, facet2 = at.facets
    return np.asarray(np.maximum(facet1, facet2))


def _facet_over(over: OverBoxes, q: Quantity) -> Pair:
    facets = over.facets
    facet_lo = np.maximum(facets[0][0], facets[1][0])
    facet_hi = facet_lo if over.point else np.maximum(facets[0][1], facets[1][1])
    return facet_lo, facet_hi


FACETS = register(Evaluator(("facet",), _facet_at, _facet_over, lambda problem: _always(FACET)))


def _mass_at(at: AtPoints, q: Quantity) -> FloatArray:
    return np.asarray(at.ev.mass[:, 0])


def _mass_over(over: OverBoxes, q: Quantity) -> Pair:
    c1, c2, lay = over.c1, over.c2, over.problem.layout
    g1_lo, g1_hi, g2_lo, g2_hi = over.corners
    td_lo, td_hi = over.thickness

    def mass(b: DesignPoints, g1: Corner, g2: Corner, td: FloatArray) -> FloatArray:
        # holes remove rho t A_h / s(alpha) per layer, most at the box's lowest alpha: the
        # corner's own pitch gives the bound on the same side as its blank.
        # The band (cut from layer 1's sheet) grows with Lx, Ly and t_d (corrugate.fabrication.
        # connectors), so its bounds are its values at those quantities' own bounds.
        band = connector_mass(c1.material.density, c1.t, lay, g1.extent, g2.extent, td)
        m1 = layer_mass(
            c1.material.density,
            c1.t,
            g1.developed,
            length_sum(lay, b.layer(0).n, g2.extent),
            lay,
            g1.p,
        )
        if over.same:  # the same layer twice (x + x = 2 x exactly, as evaluate does)
            return np.asarray(2.0 * m1 + band)
        m2 = layer_mass(
            c2.material.density,
            c2.t,
            g2.developed,
            length_sum(lay, b.layer(1).n, g1.extent),
            lay,
            g2.p,
        )
        return np.asarray(m1 + m2 + band)

    mass_lo = mass(over.lo, g1_lo, g2_lo, td_lo)
    return mass_lo, mass_lo if over.point else mass(over.hi, g1_hi, g2_hi, td_hi)


MASSES = register(Evaluator(("mass",), _mass_at, _mass_over, lambda problem: _always(MASS)))
