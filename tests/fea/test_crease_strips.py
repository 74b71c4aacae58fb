"""The crease strips of the assembly FE (corrugate.fea.shells.crease_strip): rigid creases leave
the deck as it was; a finite k adds an orthotropic strip along every crease, on squares,
rectangles, polygons and around holes (the connector band refuses it in one line)."""

from __future__ import annotations

import math
from dataclasses import replace

import pytest

from corrugate.core.errors import InputError
from corrugate.fea.assembly import AssemblyMesh, assembly_deck, solve_assembly
from corrugate.fea.shells import STRIP_FRACTION, crease_strip
from corrugate.geometry.holes import Hole
from corrugate.geometry.layer import Assembly, Layer
from corrugate.geometry.layouts import Polygon, Square
from corrugate.materials.library import get_material


def _assembly(k: float = math.inf) -> Assembly:
    m = replace(get_material("dura-lar"), crease_stiffness=k)
    return Assembly.identical(Layer(W=8, n=4, alpha_deg=84, material=m, t=0.125))


@pytest.mark.parametrize("eta", [0.0, 90.0, 45.0])
def test_rigid_creases_leave_the_deck_byte_for_byte(eta: float) -> None:
    a = _assembly()
    mesh = AssemblyMesh(along=2)
    plain, _ = assembly_deck(a, "platens", mesh, eta)
    assert assembly_deck(a, "platens", mesh, eta, crease_stiffness=math.inf)[0] == plain
    assert "ELSET=C" not in plain


@pytest.mark.parametrize("eta", [90.0, 45.0])
def test_a_finite_crease_adds_one_strip_set_per_layer(eta: float) -> None:
    deck, info = assembly_deck(
        _assembly(), "platens", AssemblyMesh(along=2), eta, crease_stiffness=0.1
    )
    for k in (1, 2):
        assert f"*SHELL SECTION,ELSET=C{k},MATERIAL=MC{k},ORIENTATION=OC{k}" in deck
    rigid = assembly_deck(_assembly(), "platens", AssemblyMesh(along=2), eta)[1]
    assert info.elements > rigid.elements


def test_the_strip_is_the_sheet_at_an_infinite_stiffness_and_softens_as_the_crease() -> None:
    """k -> inf: E across -> E (the sheet); k -> 0: D_s -> k width f, E_a -> 12 k width f / t^3."""
    E, nu, t, W = 2700.0, 0.43, 0.125, 8.0
    w = STRIP_FRACTION * W
    assert crease_strip(t, E, nu, 1e12, w, (0.0, 1.0), W).E_across == pytest.approx(E, rel=1e-9)
    f = 1 - w / W + (w / W) ** 2 / 3
    soft = crease_strip(t, E, nu, 1e-6, w, (0.0, 1.0), W).E_across
    assert soft == pytest.approx(12 * 1e-6 * w * f / t**3, rel=1e-5)


def test_crease_strips_with_the_band_are_refused_in_one_line() -> None:
    with pytest.raises(InputError, match="crease_stiffness"):
        assembly_deck(_assembly(0.1), "platens", AssemblyMesh(along=2), 0.0, connectors=True)


def test_a_polygon_on_its_box_meshes_the_squares_strips() -> None:
    """A polygon of 4 vertices on its box is the square: with crease strips too, the same
    decks line for line (the outline cut keeps every strip element)."""
    sq = _assembly(0.1)
    poly = replace(sq, layout=Polygon(((0, 0), (2, 0), (2, 2), (0, 2))))
    for eta in (0.0, 90.0):
        d_sq = assembly_deck(sq, "three-point", AssemblyMesh(along=4), eta)[0]
        assert "ELSET=C1" in d_sq
        assert assembly_deck(poly, "three-point", AssemblyMesh(along=4), eta)[0] == d_sq


def _elset(deck: str, name: str) -> list[int]:
    body = deck.split(f"*ELEMENT,TYPE=S8R,ELSET={name}\n", 1)[1].split("*", 1)[0]
    return [int(r.split(",")[0]) for r in body.strip().splitlines()]


def test_a_hole_cuts_the_strips_as_the_rest() -> None:
    """A 10 mm hole at the centre of the 26 mm square: the strips lose their elements inside it
    as the facets do, and keep the rest (fewer strip elements than the square's, more than none)."""
    a = _assembly(0.1)
    holed = replace(a, layout=Square(holes=(Hole("circle", (0.0, 0.0), diameter=10.0),)))
    full = assembly_deck(a, "platens", AssemblyMesh(along=2), 0.0)[0]
    cut = assembly_deck(holed, "platens", AssemblyMesh(along=2), 0.0)[0]
    for k in (1, 2):
        assert 0 < len(_elset(cut, f"C{k}")) < len(_elset(full, f"C{k}"))
        assert len(_elset(cut, f"L{k}")) < len(_elset(full, f"L{k}"))


@pytest.mark.fea
def test_strips_around_a_hole_soften_and_at_a_stiff_crease_are_rigid(ccx: str) -> None:
    """Platens along layer 1's creases (eta 0) on the holed square, 2 per facet: a nearly rigid
    crease (k = 1e6) gives the rigid mesh's K within 1 % (the limit case: the strip is the
    sheet, only the mesh differs), and a soft one (k = 0.01) a smaller K (layer 2 is pulled
    across its creases)."""
    holed = replace(_assembly(), layout=Square(holes=(Hole("circle", (0.0, 0.0), diameter=10.0),)))
    mesh = AssemblyMesh(along=2)
    rigid = solve_assembly(holed, "platens", mesh, 0.0).value()
    stiff = solve_assembly(holed, "platens", mesh, 0.0, crease_stiffness=1e6).value()
    soft = solve_assembly(holed, "platens", mesh, 0.0, crease_stiffness=0.01).value()
    assert stiff == pytest.approx(rigid, rel=0.01)
    assert 0 < soft < stiff


@pytest.mark.parametrize("n", [2, 4, 5, 6])
def test_strips_keep_every_node_line_a_fixture_needs(n: int) -> None:
    """Four-point bending needs node lines at 1/4 and 3/8 of the span: on the rigid mesh at 4
    per facet they exist for every n (corners and mid-side nodes every W / 8), and with the
    strips too (strip_stations keeps those lines); before, n = 2, 4, 5, 6 were refused."""
    m = replace(get_material("dura-lar"), crease_stiffness=0.1)
    a = Assembly.identical(Layer(W=8, n=n, alpha_deg=84, material=m, t=0.125))
    for eta in (0.0, 90.0):
        assert "ELSET=C1" in assembly_deck(a, "four-point", AssemblyMesh(along=4), eta)[0]
