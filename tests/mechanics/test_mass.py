"""Mass (corrugate.mechanics.mass) against rho t times the area of the parts that are cut
(docs/theory.md section 4), the areas computed here independently: by hand for a square, and by
the shoelace formula over the polygons of the flat pattern for every layout."""

from __future__ import annotations

import math

import pytest

from corrugate import Assembly, Layer, get_material, make_layout
from corrugate.fabrication.build import build_pattern
from corrugate.geometry.holes import Hole
from corrugate.geometry.layouts import Layout
from corrugate.mechanics.mass import MassBreakdown, assembly_mass, layer_mass

DURALAR = get_material("dura-lar")
KAPTON = get_material("kapton")
AXLE = Hole("circle", (0.0, 0.0), diameter=6.0)
TRIANGLE = Hole("polygon", (10.0, 5.0), vertices=((0.0, 0.0), (4.0, 0.0), (0.0, 3.0)))


def shoelace(points: tuple[tuple[float, float], ...]) -> float:
    """Area (mm^2) of a simple polygon, either orientation."""
    total = 0.0
    for (x0, y0), (x1, y1) in zip(points, (*points[1:], points[0]), strict=True):
        total += x0 * y1 - x1 * y0
    return abs(total) / 2


def test_a_square_layer_weighs_its_flat_blank() -> None:
    """W 8, n 8, alpha 84 deg, Dura-Lar 0.125 mm: the blank is (n + 1) W = 72 mm across the
    creases by L = 72 sin(42 deg) = 48.18 mm along them, so a layer weighs rho t 72 L; flat
    (alpha -> 180 deg) the blank is the 72 x 72 mm plan itself."""
    rho, t = DURALAR.density, 0.125
    L = 72 * math.sin(math.radians(42))
    m = assembly_mass(Assembly.identical(Layer(8.0, 8, 84.0, DURALAR, t)))
    assert m.layer1 == pytest.approx(rho * t * 72 * L, rel=1e-12)
    assert m.layer2 == pytest.approx(m.layer1, rel=1e-15)
    flat = assembly_mass(Assembly.identical(Layer(8.0, 8, 180 - 1e-9, DURALAR, t)))
    assert flat.layer1 == pytest.approx(rho * t * 72 * 72, rel=1e-12)
    # layer_mass itself: density x t x W x sum_j L_j
    assert float(layer_mass(rho, t, 8.0, 9 * L)) == pytest.approx(rho * t * 72 * L, rel=1e-12)


def test_a_hole_removes_its_area_stretched_across_the_creases() -> None:
    """A hole of plan area A is cut from the blank stretched by 1 / sin(alpha/2) across the
    creases: it removes rho t A / sin(42 deg) from each layer. The 6 mm hole is cut as the
    inscribed regular 360-gon (corrugate.geometry.holes), A = 180 x 3^2 sin(1 deg), the
    triangle's A = 4 x 3 / 2 = 6 mm^2."""
    rho, t = DURALAR.density, 0.125
    layer = Layer(8.0, 8, 84.0, DURALAR, t)
    plain = assembly_mass(Assembly.identical(layer))
    holes = (AXLE, TRIANGLE)
    holed = assembly_mass(Assembly.identical(layer, make_layout("square", holes=holes)))
    area = 180 * 9 * math.sin(math.radians(1)) + 6
    assert area == pytest.approx(math.pi * 9 + 6, rel=1e-4)  # nearly the disc
    cut = rho * t * area / math.sin(math.radians(42))
    assert plain.layer1 - holed.layer1 == pytest.approx(cut, rel=1e-12)
    assert plain.layer2 - holed.layer2 == pytest.approx(cut, rel=1e-12)
    assert holed.connectors == plain.connectors  # the band goes round the outline only


CASES: list[tuple[str, Layout, Layer, Layer, float]] = [
    ("square", make_layout("square"), Layer(8, 8, 84, DURALAR), Layer(8, 8, 84, DURALAR), 1e-12),
    (
        "rectangle, two sheets",
        make_layout("rectangle"),
        Layer(8, 8, 84, DURALAR),
        Layer(6, 13, 100, KAPTON, 0.05),
        1e-12,
    ),
    # the outline is a 720-gon (area 1.3e-5 below the disc), the hole a polygon as fine
    ("circle", make_layout("circle"), Layer(10, 11, 90, DURALAR), Layer(10, 11, 90, DURALAR), 2e-5),
    (
        "square with holes",
        make_layout("square", holes=(AXLE, TRIANGLE)),
        Layer(8, 8, 84, DURALAR),
        Layer(8, 8, 84, DURALAR),
        2e-5,
    ),
    (
        "concave polygon",
        make_layout("polygon", [(0, 0), (3, 0), (3, 1), (1, 1), (1, 3), (0, 3)]),
        Layer(6, 12, 100, DURALAR),
        Layer(6, 12, 100, DURALAR),
        1e-9,
    ),
]


@pytest.mark.parametrize(("name", "layout", "l1", "l2", "rel"), CASES, ids=[c[0] for c in CASES])
def test_mass_is_rho_t_times_the_shoelace_area_of_the_cut_parts(
    name: str, layout: Layout, l1: Layer, l2: Layer, rel: float
) -> None:
    a = Assembly(l1, l2, layout)
    pattern = build_pattern(a)
    found = {"L1": 0.0, "L2": 0.0, "connector": 0.0}
    for part in pattern.parts:
        t = part.t if part.t > 0 else pattern.t
        rho = part.density if part.density > 0 else pattern.density
        area = shoelace(part.outline) - sum(shoelace(h) for h in part.holes)
        found[part.name if part.kind == "layer" else part.kind] += rho * t * area
    m = assembly_mass(a)
    assert m.layer1 == pytest.approx(found["L1"], rel=rel)
    assert m.layer2 == pytest.approx(found["L2"], rel=rel)
    assert m.connectors == pytest.approx(found["connector"], rel=1e-9)
    assert m.total == pytest.approx(sum(found.values()), rel=rel)
    # the band is cut from layer 1's sheet
    if l2.material is not l1.material:
        band = [p for p in pattern.parts if p.kind == "connector"]
        assert band and all(
            (p.t or pattern.t, p.density or pattern.density) == (l1.t, l1.material.density)
            for p in band
        )


def test_breakdown_adds_its_parts() -> None:
    m = MassBreakdown(1.5, 2.25, 0.125)
    assert m.total == 3.875
    assert m.as_dict() == {
        "layer1_g": 1.5,
        "layer2_g": 2.25,
        "connectors_g": 0.125,
        "total_g": 3.875,
    }
