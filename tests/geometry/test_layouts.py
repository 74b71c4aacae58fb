"""Layouts and facet lengths, checked by hand derivations and by a second method."""

from __future__ import annotations

import math

import numpy as np
import pytest

from corrugate import Assembly, Layer, analyze, get_material, make_layout
from corrugate.core.errors import InputError
from corrugate.geometry.layouts import Circle, Polygon, Rectangle, facet_lengths, inverse_length_sum

DURALAR = get_material("dura-lar")


def _clip_area(vertices: list[tuple[float, float]], x0: float, x1: float) -> float:
    """Area of a polygon inside the strip x0 <= x <= x1, by Sutherland-Hodgman (second method)."""

    def clip(poly: list[tuple[float, float]], keep, cut) -> list[tuple[float, float]]:  # type: ignore[no-untyped-def]
        out: list[tuple[float, float]] = []
        for i, p in enumerate(poly):
            q = poly[(i + 1) % len(poly)]
            if keep(p):
                out.append(p)
            if keep(p) != keep(q):
                out.append(cut(p, q))
        return out

    def cut_at(x: float):  # type: ignore[no-untyped-def]
        return lambda p, q: (x, p[1] + (q[1] - p[1]) * (x - p[0]) / (q[0] - p[0]))

    poly = clip(vertices, lambda p: p[0] >= x0, cut_at(x0))
    poly = clip(poly, lambda p: p[0] <= x1, cut_at(x1)) if poly else []
    if len(poly) < 3:
        return 0.0
    xs, ys = np.array(poly).T
    return float(abs(0.5 * np.sum(xs * np.roll(ys, -1) - np.roll(xs, -1) * ys)))


def test_rectangle_facets_equal_other_side() -> None:
    L = facet_lengths(Rectangle(), 5, 37.0, "x")
    assert L.shape == (6,)
    np.testing.assert_allclose(L, 37.0)


def test_circle_facet_is_strip_area_over_pitch() -> None:
    """Hand derivation: disc of diameter d, strip [a, b]: area = F(b) - F(a) with
    F(x) = x sqrt(r^2 - x^2) + r^2 asin(x/r)."""
    d, n = 50.0, 8
    r = d / 2
    p = d / (n + 1)

    def F(x: float) -> float:
        return x * math.sqrt(r * r - x * x) + r * r * math.asin(x / r)

    expected = [(F(-r + (j + 1) * p) - F(-r + j * p)) / p for j in range(n + 1)]
    np.testing.assert_allclose(facet_lengths(Circle(), n, d, "x"), expected, rtol=1e-12)
    np.testing.assert_allclose(facet_lengths(Circle(), n, d, "y"), expected, rtol=1e-12)


@pytest.mark.parametrize("axis", ["x", "y"])
def test_polygon_strips_match_clipping(axis: str) -> None:
    """A concave polygon (an L shape with a notch): exact strip areas against clipping."""
    verts = [(0, 0), (4, 0), (4, 1), (2.5, 1), (2.5, 3), (1, 2), (0, 3)]
    poly = Polygon(tuple((float(x), float(y)) for x, y in verts))
    n, Lx, Ly = 11, 40.0, 30.0
    scaled = [(x / 4 * Lx, y / 3 * Ly) for x, y in verts]
    if axis == "y":
        scaled = [(y, x) for x, y in scaled]
    chord, other = (Lx, Ly) if axis == "x" else (Ly, Lx)
    p = chord / (n + 1)
    expected = [_clip_area(scaled, j * p, (j + 1) * p) / p for j in range(n + 1)]
    got = facet_lengths(poly, n, other, axis)  # type: ignore[arg-type]
    np.testing.assert_allclose(got, expected, rtol=1e-10)
    q = inverse_length_sum(poly, np.array([n]), np.array([other]), axis)  # type: ignore[arg-type]
    assert q[0] == pytest.approx(np.sum(1 / np.array(expected)), rel=1e-10)


@pytest.mark.slow
def test_polygon_many_sided_approaches_circle() -> None:
    k = 4000
    verts = tuple(
        (0.5 + 0.5 * math.cos(2 * math.pi * i / k), 0.5 + 0.5 * math.sin(2 * math.pi * i / k))
        for i in range(k)
    )
    np.testing.assert_allclose(
        facet_lengths(Polygon(verts), 9, 60.0, "x"),
        facet_lengths(Circle(), 9, 60.0, "x"),
        rtol=1e-5,
    )


def test_rectangle_polygon_equals_rectangle_layout() -> None:
    layer1 = Layer(8, 8, 84, DURALAR)
    layer2 = Layer(10, 12, 90, DURALAR)
    rect = analyze(Assembly(layer1, layer2, Rectangle()), "refined", [0, 45, 90])
    poly = analyze(
        Assembly(layer1, layer2, make_layout("polygon", [(0, 0), (3, 0), (3, 2), (0, 2)])),
        "refined",
        [0, 45, 90],
    )
    for a, b in zip(rect.stiffness, poly.stiffness, strict=True):
        assert pytest.approx(b.K, rel=1e-12) == a.K
        assert pytest.approx(b.EI, rel=1e-12) == a.EI
    assert rect.mass.total == pytest.approx(poly.mass.total, rel=1e-12)


def test_mass_of_square_by_hand() -> None:
    """Two blanks of (n + 1) W by L, rho t each: m = 2 rho t (n + 1) W L."""
    layer = Layer(8, 8, 84, DURALAR)
    a = Assembly.identical(layer)
    L = 9 * 8 * math.sin(math.radians(42))
    expected = 2 * DURALAR.density * 0.125 * 9 * 8 * L
    m = analyze(a).mass
    assert m.layer1 + m.layer2 == pytest.approx(expected, rel=1e-12)
    # the band: four segments of length L, height t_d, each with an 8 mm overlap and two glue
    # flanges 4 mm deep with 45 deg chamfers at the corners (area 4 L - 16 each; slits cut no area)
    td = 2 * 8 * math.cos(math.radians(42))
    band = 4 * ((L + 8) * td + 2 * (4 * L - 16))
    assert m.connectors == pytest.approx(DURALAR.density * 0.125 * band, rel=1e-12)
    assert m.total == pytest.approx(expected + DURALAR.density * 0.125 * band, rel=1e-12)


def test_mass_is_area_of_cut_facets_for_a_triangle() -> None:
    """Flat facet area is plan area / sin(alpha/2): the triangle's layers weigh rho t area/s."""
    layer = Layer(6, 10, 100, DURALAR)
    tri = make_layout("polygon", [(0, 0), (1, 0), (0.5, 1)])
    a = Assembly(layer, layer, tri)
    plan_area = 0.5 * a.Lx * a.Ly
    expected = 2 * DURALAR.density * layer.t * plan_area / layer.s
    m = analyze(a).mass
    assert m.layer1 + m.layer2 == pytest.approx(expected, rel=1e-12)


def test_square_needs_equal_sides() -> None:
    with pytest.raises(InputError, match="layout"):
        Assembly(Layer(8, 8, 84, DURALAR), Layer(8, 9, 84, DURALAR))


def test_self_crossing_polygon_rejected() -> None:
    with pytest.raises(InputError, match="crosses itself"):
        make_layout("polygon", [(0, 0), (1, 1), (1, 0), (0, 1)])


def test_unknown_layout() -> None:
    with pytest.raises(InputError, match="layout = 'hexagon' is unknown"):
        make_layout("hexagon")


def test_span_of_square_is_its_projection() -> None:
    r = analyze(Assembly.identical(Layer(8, 8, 84, DURALAR)), "refined", [0, 45])
    L = r.assembly.Lx
    assert r.stiffness[0].span == pytest.approx(L)
    assert r.stiffness[1].span == pytest.approx(L * math.sqrt(2))
    assert pytest.approx(r.stiffness[0].D * L) == r.stiffness[0].EI
