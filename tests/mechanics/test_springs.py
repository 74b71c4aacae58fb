"""The springs of a layer (corrugate.mechanics.springs) against hand derivations of docs/theory.md
section 3.2: facets in series across the creases, in parallel along them.

* A square layout: every L_j = L = (n + 1) p, so K_S = (n + 1) Ecy p t / L = Ecy t, K_C = Ecx t,
  D_S = Eby t^3 / 12, D_C = Ebx t^3 / 12, whatever W, n and alpha (the layer is a plate as long as
  it is wide).
* A rectangle: the same plate, width over length: K_S1 = Ecy t Lx / Ly, K_C1 = Ecx t Ly / Lx.
* Two facets (n = 1) of unequal lengths written out as two springs in parallel and in series.
* A circle with one crease: each facet is half the disc, L_j = (pi (2p)^2 / 8) / p = pi p / 2.
* The limit of a flat sheet (alpha -> 180 deg): every modulus tends to E, so a square layer is a
  flat plate: K = E t (compression E A / L with A = L t), D = E t^3 / 12 (per unit width, times
  width over length), in-plane shear G t and twisting G t^3 / 12.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from corrugate import Assembly, Layer, analyze, get_material, make_layout, moduli
from corrugate.mechanics.moduli import Moduli
from corrugate.mechanics.springs import layer_springs

DURALAR = get_material("dura-lar")


def _scalar(m: Moduli) -> tuple[float, float, float, float]:
    return float(m.Ecx), float(m.Ecy), float(m.Ebx), float(m.Eby)


@pytest.mark.parametrize(("W", "n", "alpha"), [(8.0, 8, 84.0), (5.0, 3, 120.0), (12.0, 20, 45.0)])
@pytest.mark.parametrize("model", ["paper", "xia", "refined"])
def test_a_square_layer_is_a_plate_as_long_as_it_is_wide(
    W: float, n: int, alpha: float, model: str
) -> None:
    layer = Layer(W, n, alpha, DURALAR, 0.125)
    r = analyze(Assembly.identical(layer), model)
    Ecx, Ecy, Ebx, Eby = _scalar(r.moduli[0])
    t = layer.t
    for sp in r.springs:  # identical layers: the same springs
        assert float(sp.K_S) == pytest.approx(Ecy * t, rel=1e-12)
        assert float(sp.K_C) == pytest.approx(Ecx * t, rel=1e-12)
        assert float(sp.D_S) == pytest.approx(Eby * t**3 / 12, rel=1e-12)
        assert float(sp.D_C) == pytest.approx(Ebx * t**3 / 12, rel=1e-12)
    # K(0) = K_S1 + K_C2 (docs/theory.md 3.3)
    assert pytest.approx((Ecy + Ecx) * t, rel=1e-12) == r.stiffness[0].K


def test_a_rectangle_layer_is_the_plate_of_its_proportions() -> None:
    """Layer 1 (creases along y) spans Lx across its creases and Ly along them: loaded along y
    it is a plate of width Lx and length Ly (K = E A / L = Ecy t Lx / Ly), loaded across its
    creases one of width Ly and length Lx."""
    l1 = Layer(8.0, 8, 84.0, DURALAR, 0.125)
    l2 = Layer(6.0, 15, 100.0, get_material("kapton"), 0.05)
    a = Assembly(l1, l2, make_layout("rectangle"))
    Lx, Ly = a.Lx, a.Ly
    assert Lx == pytest.approx(9 * 8 * math.sin(math.radians(42)))
    assert Ly == pytest.approx(16 * 6 * math.sin(math.radians(50)))
    r = analyze(a)
    for sp, m, layer, width, length in (
        (r.springs[0], r.moduli[0], l1, Lx, Ly),
        (r.springs[1], r.moduli[1], l2, Ly, Lx),
    ):
        Ecx, Ecy, Ebx, Eby = _scalar(m)
        t = layer.t
        assert float(sp.K_S) == pytest.approx(Ecy * t * width / length, rel=1e-12)
        assert float(sp.K_C) == pytest.approx(Ecx * t * length / width, rel=1e-12)
        assert float(sp.D_S) == pytest.approx(Eby * t**3 / 12 * width / length, rel=1e-12)
        assert float(sp.D_C) == pytest.approx(Ebx * t**3 / 12 * length / width, rel=1e-12)


def test_two_facets_in_parallel_and_in_series_by_hand() -> None:
    """n = 1: facets of lengths 10 and 30 mm, pitch 4 mm, t 0.1 mm, moduli 100, 200, 300, 400 MPa.
    Along the creases the facets act side by side: K_S = Ecy p t (1/10 + 1/30) = 200 x 4 x 0.1 x
    (4/30) = 32/3 N/mm. Across them one after the other: each facet a spring Ecx L_j t / p
    (100 x 10 x 0.1 / 4 = 25 and 100 x 30 x 0.1 / 4 = 75 N/mm), in series
    1 / (1/25 + 1/75) = 18.75 N/mm."""
    m = Moduli(np.float64(100.0), np.float64(200.0), np.float64(300.0), np.float64(400.0))
    q = 1 / 10 + 1 / 30
    sp = layer_springs(m, 0.1, 4.0, q, E=1000.0, nu=0.3, sin_half=0.5)
    assert float(sp.K_S) == pytest.approx(32 / 3, rel=1e-12)
    assert float(sp.K_C) == pytest.approx(18.75, rel=1e-12)
    # bending: the same sums with E t -> E t^3 / 12
    k3 = 0.1**3 / 12
    assert float(sp.D_S) == pytest.approx(400 * k3 * 4 * q, rel=1e-12)
    d1, d2 = 300 * k3 * 10 / 4, 300 * k3 * 30 / 4
    assert float(sp.D_C) == pytest.approx(1 / (1 / d1 + 1 / d2), rel=1e-12)
    # shear and twisting (docs/theory.md 3.3: A66_eq = s G t per unit width), G = 1000 / 2.6
    G = 1000 / 2.6
    assert float(sp.K_T) == pytest.approx(G * 0.1 * 0.5 * 4 * q, rel=1e-12)
    assert float(sp.D_T) == pytest.approx(G * 0.1**3 / 12 / 0.5 * 4 * q, rel=1e-12)


def test_series_sum_of_a_holed_layer_is_used_only_across_the_creases() -> None:
    """With holes the parallel springs take the sum over the untouched facets and the series
    ones the sum with the blocked lengths (corrugate.geometry.holes): two facets of 10 and 30 mm
    where a hole takes the first out of the parallel sum and blocks 5 mm of it in series."""
    m = Moduli(np.float64(100.0), np.float64(200.0), np.float64(300.0), np.float64(400.0))
    parallel, series = 1 / 30, 1 / 5 + 1 / 30
    sp = layer_springs(m, 0.1, 4.0, parallel, 1000.0, 0.3, 0.5, inv_length_sum_series=series)
    assert float(sp.K_S) == pytest.approx(200 * 0.1 * 4 / 30, rel=1e-12)
    assert float(sp.K_C) == pytest.approx(1 / (4 / (100 * 5 * 0.1) + 4 / (100 * 30 * 0.1)))
    assert float(sp.D_C) == pytest.approx(300 * 0.1**3 / 12 / (4 * series), rel=1e-12)


def test_a_circle_with_one_crease_has_two_half_discs() -> None:
    """Two facets, each a half of the disc of diameter 2p: L_j = (pi p^2 / 2) / p = pi p / 2, so
    K_S = 2 Ecy p t / (pi p / 2) = 4 Ecy t / pi and K_C = Ecx t pi / 4."""
    layer = Layer(10.0, 1, 90.0, DURALAR, 0.125)
    a = Assembly.identical(layer, make_layout("circle"))
    p = layer.pitch
    assert a.facet_lengths(1) == pytest.approx([math.pi * p / 2] * 2, rel=1e-12)
    r = analyze(a)
    Ecx, Ecy, _, _ = _scalar(r.moduli[0])
    assert float(r.springs[0].K_S) == pytest.approx(4 * Ecy * 0.125 / math.pi, rel=1e-12)
    assert float(r.springs[0].K_C) == pytest.approx(Ecx * 0.125 * math.pi / 4, rel=1e-12)


@pytest.mark.parametrize("model", ["xia", "refined"])
def test_a_flat_sheet_is_a_flat_plate(model: str) -> None:
    """alpha -> 180 deg: the corrected moduli all tend to E (docs/theory.md 3.1), so a square
    layer is a flat square plate: compression E t either way, bending E t^3 / 12, in-plane
    shear G t and twisting G t^3 / 12, G = E / (2 (1 + nu))."""
    E, nu, t = DURALAR.E, DURALAR.nu, 0.125
    G = E / (2 * (1 + nu))
    layer = Layer(8.0, 8, 180.0 - 1e-7, DURALAR, t)
    m = moduli(E, nu, t, layer.W, layer.alpha_deg, model)
    sp = layer_springs(m, t, layer.pitch, (layer.n + 1) / layer.chord_extent, E, nu, layer.s)
    assert float(sp.K_S) == pytest.approx(E * t, rel=1e-9)
    assert float(sp.K_C) == pytest.approx(E * t, rel=1e-9)
    assert float(sp.D_S) == pytest.approx(E * t**3 / 12, rel=1e-6)
    assert float(sp.D_C) == pytest.approx(E * t**3 / 12, rel=1e-6)
    assert float(sp.K_T) == pytest.approx(G * t, rel=1e-9)
    assert float(sp.D_T) == pytest.approx(G * t**3 / 12, rel=1e-9)


def test_springs_broadcast_over_arrays_like_scalars() -> None:
    """One call on arrays equals one call per element (the sweeps' fast path)."""
    W = np.array([5.0, 8.0, 12.0])
    alpha = np.array([60.0, 84.0, 150.0])
    t = 0.125
    s = np.sin(np.radians(alpha) / 2)
    p, q = W * s, np.array([0.1, 0.2, 0.05])
    E, nu = DURALAR.E, DURALAR.nu
    m = moduli(E, nu, t, W, alpha, "refined")
    many = layer_springs(m, t, p, q, E, nu, s)
    for i in range(3):
        mi = moduli(E, nu, t, W[i], alpha[i], "refined")
        one = layer_springs(mi, t, p[i], q[i], E, nu, s[i])
        for f in ("K_C", "K_S", "D_C", "D_S", "K_T", "D_T"):
            assert float(getattr(many, f)[i]) == pytest.approx(float(getattr(one, f)), rel=1e-14)
