"""The cantilever fixture and the coupon shift of corrugate.fea.assembly (docs/fea.md 2.1, 2.4)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from corrugate import Assembly, Layer, get_material
from corrugate.core.errors import InputError
from corrugate.fea.assembly import AssemblyMesh, assembly_deck, solve_assembly
from corrugate.fea.shells import oblique_shells


def _layer(alpha_deg: float) -> Layer:
    return Layer(W=5.0, n=7, alpha_deg=alpha_deg, material=get_material("dura-lar"), t=0.1)


@pytest.mark.fea
def test_cantilever_of_a_near_flat_sheet_lies_between_beam_and_plane_strain_bounds(
    ccx: str,
) -> None:
    """A sheet folded to alpha = 179 deg (height 0.044 mm, under half its thickness 0.1 mm),
    clamped at y = 0 and pushed down at y = L. Layer 1's creases run along the span, so it is a
    prismatic beam whose section is the zig-zag: per facet of width W inclined at theta,
    I = W t (W^2 sin^2 theta + t^2 cos^2 theta) / 12 (hand derivation). Bounds on its tip
    stiffness (the layers are not connected, so layer 1's share is its own cantilever):

    * below: the beam stress field sigma_yy = M z / I, whose complementary energy gives
      EI_cant >= E I (Euler-Bernoulli; the shear energy is of order (t / L)^2 = 1e-5);
    * above: the plane-strain field w = w(y), u_x = 0, sections rigid in their plane, which meets
      the clamp and the tip's u_z = -delta and gives EI_cant <= E I / (1 - nu^2) (+23 % for nu =
      0.43).

    The clamp holds the lateral contraction at the root and the rigid tip line at the tip, so the
    FE lies in between; 1 % margins for the coarse mesh. A wrong span exponent or coefficient
    (the 3-point 48 for the cantilever's 3) or a root that is not clamped (a mechanism, P = 0)
    lands far outside."""
    layer = _layer(179.0)
    a = Assembly.identical(layer)
    r = solve_assembly(a, "cantilever", AssemblyMesh(2), 0.0)
    assert r.EI is not None and r.D is not None
    assert pytest.approx(r.D * r.span) == r.EI
    assert r.span == pytest.approx(a.Ly)
    m = layer.material
    theta = math.radians((180.0 - layer.alpha_deg) / 2)
    per_facet = (
        layer.W * layer.t * (layer.W**2 * math.sin(theta) ** 2 + (layer.t * math.cos(theta)) ** 2)
    )
    EI_beam = m.E * (layer.n + 1) * per_facet / 12
    EI_1 = r.layer_values[0] * r.span
    assert 0.99 * EI_beam <= EI_1 <= 1.01 * EI_beam / (1 - m.nu**2)
    assert sum(r.layer_values) == pytest.approx(r.value())


@pytest.mark.fea
def test_cantilever_is_stiffer_than_3_point_and_agrees_across_meshers_and_mirror(ccx: str) -> None:
    """For a Timoshenko beam over one span, the apparent EI of a cantilever, EI / (1 + 3 s), lies
    between the 3-point value EI / (1 + 12 s) and EI (s the shear-to-bending ratio); the compliance
    ratio delta_cant / delta_3pt = 16 (1 + 3 s) / (1 + 12 s) is therefore between 4 and 16. The
    gmsh mesh of the same layout (a second discretisation) agrees within 2 %, and for identical
    layers eta = 90 mirrors eta = 0 (other node sets and clamp axes): the totals to 1e-6, the share
    of the layer bent across its creases (about 1e-3 of the total) to 1e-4."""
    a = Assembly.identical(_layer(120.0))
    mesh = AssemblyMesh(2)
    cant = solve_assembly(a, "cantilever", mesh, 0.0)
    three = solve_assembly(a, "three-point", mesh, 0.0)
    assert cant.EI is not None and three.EI is not None
    assert cant.EI > three.EI
    # the same force per deflection on the same span: delta ratio = (k_3pt / k_cant)
    ratio = (three.force / three.displacement) / (cant.force / cant.displacement)
    assert 4.0 < ratio < 16.0
    g = solve_assembly(a, "cantilever", mesh, 0.0, mesher="gmsh")
    assert g.value() == pytest.approx(cant.value(), rel=0.02)
    r90 = solve_assembly(a, "cantilever", mesh, 90.0)
    assert r90.value() == pytest.approx(cant.value(), rel=1e-6)
    assert r90.layer_values[0] == pytest.approx(cant.layer_values[1], rel=1e-4)


def test_coupon_shift_moves_the_creases_and_bad_shifts_are_refused() -> None:
    """shift = 0 is the default deck; shift = 0.5 moves layer 1's valleys by half a pitch along its
    chord (found from the two meshes' valley nodes, not from the offset formula); values outside
    [0, 1), non-numbers and a shift on the structured mesh are InputErrors."""
    pytest.importorskip("gmsh")
    a = Assembly.identical(_layer(120.0))
    mesh = AssemblyMesh(2)
    assert assembly_deck(a, "three-point", mesh, 30.0, shift=0.0) == assembly_deck(
        a, "three-point", mesh, 30.0
    )
    assert (
        assembly_deck(a, "three-point", mesh, 30.0, shift=0.5)[0]
        != assembly_deck(a, "three-point", mesh, 30.0)[0]
    )
    eta = 30.0
    e = math.radians(eta)
    chord = np.array([math.cos(e), math.sin(e)])  # layer 1's chord in the test frame
    p = a.layer1.pitch

    def valley_phase(shift: float) -> float:
        sh = oblique_shells(a, eta, 2, (), shift=shift)[0]
        valleys = sh.xyz[np.abs(sh.xyz[:, 2]) < 1e-9]
        u = valleys[:, :2] @ chord
        # valleys repeat every 2 p: their phase in [0, 2 p), the same for all of them
        phase = np.mod(u, 2 * p)
        spread = np.abs(((phase - phase[0]) + p) % (2 * p) - p)
        assert float(spread.max()) < 1e-6
        return float(phase[0])

    moved = (valley_phase(0.5) - valley_phase(0.0)) % (2 * p)
    assert moved == pytest.approx(0.5 * p, abs=1e-6)
    for bad in (1.0, -0.1, math.nan, math.inf, True, "0.5"):
        with pytest.raises(InputError, match="shift"):
            assembly_deck(a, "three-point", mesh, 30.0, shift=bad)  # type: ignore[arg-type]
        with pytest.raises(InputError, match="shift"):
            oblique_shells(a, 30.0, 2, (), shift=bad)  # type: ignore[arg-type]
    with pytest.raises(InputError, match="structured mesh"):
        assembly_deck(a, "three-point", mesh, 0.0, shift=0.25)
