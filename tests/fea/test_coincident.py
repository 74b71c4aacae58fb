"""Coincident mesh points (corrugate.fea.coincident) and the connector band that needs them
(docs/fea.md 2.3): two copies of one point that fall on either side of a rounding tie share a
key, and the band meets every layer edge node at 16 elements per facet on the panel where it did
not (issue 35: blimp_gripper_cantilever's design, W 8, n 7, alpha 98, 48.30 mm: "46 layer edge
nodes do not meet the band's mesh"). Pure meshing, no CalculiX."""

from __future__ import annotations

import math

import numpy as np
import pytest

from corrugate import Assembly, Layer, get_material
from corrugate.fea.coincident import CoincidentKeys
from corrugate.fea.connector_band import band_shell
from corrugate.fea.shells import layer_shell
from corrugate.geometry.layouts import Rectangle


def test_copies_either_side_of_a_rounding_tie_share_a_key() -> None:
    """x / tol = 39062.5 exactly: round() sends x to 39062 and its next float up to 39063 (the
    tie of the defect: odd multiples of pitch / 32 on an 8-facet panel, tol = 1e-7 L)."""
    tol = 1e-7 * 48.0
    x = 39062.5 * tol
    up = math.nextafter(x, math.inf)
    down = math.nextafter(x, -math.inf)
    assert round(down / tol) != round(up / tol)  # plain rounding splits them
    keys = CoincidentKeys(tol)
    first = keys.key(down, 0.0, 1.0)
    assert keys.key(up, 0.0, 1.0) == first
    assert keys.key(x, 0.0, 1.0) == first


def test_points_a_tolerance_apart_stay_apart() -> None:
    """Points tol or more apart in one coordinate keep their own keys, as rounding gave them."""
    tol = 1e-3
    keys = CoincidentKeys(tol)
    a = keys.key(0.0, 0.0, 0.0)
    b = keys.key(0.0, tol, 0.0)
    c = keys.key(0.49 * tol, 0.0, 0.0)  # within tol / 2 of a
    assert a != b
    assert c == a
    assert keys.key(2.0, 3.0, 4.0) == (2000, 3000, 4000)


@pytest.mark.parametrize("tol", [0.0, -1.0, math.nan])
def test_a_tolerance_must_be_positive(tol: float) -> None:
    with pytest.raises(ValueError, match="tol"):
        CoincidentKeys(tol)


@pytest.mark.slow  # about 0.9 s of CPU: a 16-per-facet band
def test_the_band_meets_every_layer_edge_node_at_16_per_facet() -> None:
    """Layer 1 of the defect's design (Dura-Lar 0.175, W 8, n 7, alpha 98: 8 facets, Lx 48.30 mm,
    its 2 x 16 x 8 = 256 node stations at x / tol = k x 39062.5, half of them on ties) with a
    short layer 2 (n 1) to keep the mesh small: the band (bond along the edges) is built without
    the "do not meet" refusal, and every node of a layer on the outline is a node of the band."""
    dl = get_material("dura-lar")
    a = Assembly(
        Layer(W=8.0, n=7, alpha_deg=98.0, material=dl, t=0.175),
        Layer(W=4.0, n=1, alpha_deg=98.0, material=dl, t=0.175),
        Rectangle(),
    )
    along = 16
    tol = 1e-7 * max(a.Lx, a.Ly)  # the tolerance the assembly deck uses
    x_station = a.layer1.pitch / (2 * along)
    assert (x_station / tol) % 1 == pytest.approx(0.5, abs=1e-6)  # the tie, by construction
    s1 = layer_shell(a.layer1, a.Ly, along, 1, 0, 0.0, 2, along * (a.layer2.n + 1))
    s2 = layer_shell(a.layer2, a.Lx, along, int(s1.ids.max()) + 1, 1, a.layer1.height, 2, along * 8)
    shells = [s1, s2]
    band = band_shell(a, along, shells, tol, "edges")
    used = {n for e in band.elements for n in e}
    for sh in shells:
        x, y = sh.xyz[:, 0], sh.xyz[:, 1]
        on = (np.abs(x) < tol) | (np.abs(x - a.Lx) < tol) | (np.abs(y) < tol)
        on |= np.abs(y - a.Ly) < tol
        assert on.sum() > 0
        assert {int(n) for n in sh.ids[on]} <= used
