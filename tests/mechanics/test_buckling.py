"""Facet buckling bounds (corrugate.mechanics.buckling) against a hand calculation and a second
method: the plate buckling coefficients the bounds use, recomputed here by Rayleigh-Ritz."""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.polynomial import polynomial as poly
from scipy.linalg import eigh
from scipy.optimize import minimize_scalar

from corrugate import Assembly, Layer, analyze, get_material, make_layout
from corrugate.analysis.evaluate import facet_buckling_load
from corrugate.core.errors import InputError
from corrugate.mechanics.buckling import (
    K_CLAMPED_FREE,
    K_SIMPLE_FREE,
    buckling_bounds,
    buckling_scale,
)
from corrugate.solver.interval import Interval

DURALAR = get_material("dura-lar")


def _monomial(k: int) -> np.ndarray:
    """Coefficients of y^k."""
    return np.eye(k + 1)[k]


def _ritz_k(basis: list[np.ndarray], nu: float, aspect: float) -> float:
    """Buckling coefficient k = N_cr b^2 / (pi^2 D) of a plate of width b = 1 compressed along x,
    one half-wave of length ``aspect`` (a / b) along x: w = f(y) sin(pi x / a), f a combination
    of the polynomials ``basis`` (which set the edge conditions: the natural ones, free, hold
    wherever the basis does not fix w or w'). Averaged over the half-wave the strain energy per
    unit length is (D/4) int [(f'' - m^2 f)^2 + 2 (1 - nu) m^2 (f f'' + f'^2)] dy and the load's
    work (N/4) m^2 int f^2 dy, m = pi / a; the smallest generalised eigenvalue is N_cr (an upper
    bound that falls as the basis grows)."""
    m = math.pi / aspect

    def integral(c: np.ndarray) -> float:
        return float(poly.polyval(1.0, poly.polyint(c)))

    size = len(basis)
    A, B = np.zeros((size, size)), np.zeros((size, size))
    for i, a in enumerate(basis):
        for j, b in enumerate(basis):
            ua = poly.polysub(poly.polyder(a, 2), m * m * a)
            ub = poly.polysub(poly.polyder(b, 2), m * m * b)
            twist = poly.polyadd(
                poly.polyadd(
                    poly.polymul(a, poly.polyder(b, 2)), poly.polymul(b, poly.polyder(a, 2))
                ),
                2 * poly.polymul(poly.polyder(a), poly.polyder(b)),
            )
            A[i, j] = integral(poly.polymul(ua, ub)) + (1 - nu) * m * m * integral(twist)
            B[i, j] = m * m * integral(poly.polymul(a, b))
    return float(eigh(A, B, eigvals_only=True)[0]) / math.pi**2


def _long_plate_k(basis: list[np.ndarray], nu: float) -> float:
    """k of a long plate: the smallest over the half-wave length a / b in [0.3, 100]."""
    found = minimize_scalar(
        lambda r: _ritz_k(basis, nu, math.exp(r)),
        bounds=(math.log(0.3), math.log(100.0)),
        method="bounded",
        options={"xatol": 1e-4},
    )
    return float(found.fun)


def test_the_plate_coefficients_are_the_rayleigh_ritz_values() -> None:
    """The module's k are those of a long plate with one free edge, at nu = 0.3 (Timoshenko and
    Gere 9.2): simply supported on the other edge (basis y, y^2, ...) 0.425, which is
    6 (1 - nu) / pi^2 = 0.4255 as a / b grows (the plate turns about its supported edge); clamped
    (y^2, y^3, ...) 1.277, at a / b near 1.64. An interior facet, held on both creases
    (y^k - y^(k + 1)), has k = 4 at a / b = 1: the end facets buckle first, the premise of the
    bounds."""
    simple = _long_plate_k([_monomial(k) for k in range(1, 6)], 0.3)
    assert simple == pytest.approx(6 * 0.7 / math.pi**2, rel=2e-3)
    assert simple == pytest.approx(K_SIMPLE_FREE, rel=3e-3)
    clamped = _long_plate_k([_monomial(k) for k in range(2, 8)], 0.3)
    assert clamped == pytest.approx(K_CLAMPED_FREE, rel=5e-3)
    held = [poly.polysub(_monomial(k), _monomial(k + 1)) for k in range(1, 6)]
    interior = _ritz_k(held, 0.3, 1.0)
    assert interior == pytest.approx(4.0, rel=1e-3)
    assert K_SIMPLE_FREE < K_CLAMPED_FREE < interior


def test_facet_buckling_bounds_by_hand() -> None:
    """Hand calculation (corrugate.mechanics.buckling): Dura-Lar (E and nu from the library), W 8,
    n 8, t 0.125: sigma_0 = pi^2 E / (12 (1 - nu^2)) (t / W)^2, times the 9 facets' section
    9 x 8 x 0.125 = 9 mm^2, times 1 + K_C2 / K_S1, times k = 0.425 and 1.277. Only eta along
    a layer's creases is defined."""
    from corrugate.geometry.layouts import Circle

    m = get_material("dura-lar")
    a = Assembly.identical(Layer(8.0, 8, 84.0, m, 0.125))
    sp = analyze(a).springs
    sigma0 = math.pi**2 * m.E / (12 * (1 - m.nu**2)) * (0.125 / 8) ** 2
    unit = sigma0 * 9.0 * (1 + float(sp[1].K_C) / float(sp[0].K_S))
    b = facet_buckling_load(a, 0.0)
    assert b.low == pytest.approx(0.425 * unit) and b.high == pytest.approx(1.277 * unit)
    assert facet_buckling_load(a, 90.0).low == pytest.approx(b.low)
    with pytest.raises(InputError, match="eta = 45 deg"):
        facet_buckling_load(a, 45.0)
    # analyze reports the same bounds along both crease directions, in its JSON too
    r = analyze(a)
    assert [x.eta_deg for x in r.buckling] == [0.0, 90.0] and r.buckling[0] == b
    assert r.to_dict()["buckling"][0] == {"eta_deg": 0.0, "low_N": b.low, "high_N": b.high}
    # a circle's facets differ in length and its end facets are no long plates: no bounds
    assert analyze(Assembly.identical(Layer(8.0, 8, 84.0, m, 0.125), Circle())).buckling == ()
    with pytest.raises(InputError, match="layout = circle"):
        facet_buckling_load(Assembly.identical(Layer(8.0, 8, 84.0, m, 0.125), Circle()))


def test_a_rectangle_along_90_deg_buckles_layer_2s_facets() -> None:
    """Two different layers on a rectangle, compressed along 90 deg (along layer 2's creases):
    the facets that buckle are layer 2's (its E, nu, t, W and n + 1 = 16 facets), and layer 1,
    loaded across its creases, carries K_C1 / K_S2 of the load on top. K is the platen stiffness
    K_S2 + K_C1, which is the assembly's K(90) (docs/theory.md 3.3); the travel is load / K."""
    l1 = Layer(8.0, 8, 84.0, DURALAR, 0.125)
    kapton = get_material("kapton")
    l2 = Layer(6.0, 15, 100.0, kapton, 0.05)
    a = Assembly(l1, l2, make_layout("rectangle"))
    r = analyze(a, eta_deg=[0.0, 90.0])
    sp = r.springs
    b = buckling_bounds(a, sp, 90.0)
    assert b is not None
    sigma0 = math.pi**2 * kapton.E / (12 * (1 - kapton.nu**2)) * (0.05 / 6.0) ** 2
    unit = sigma0 * 16 * 6.0 * 0.05 * (1 + float(sp[0].K_C) / float(sp[1].K_S))
    assert (b.low, b.high) == pytest.approx((0.425 * unit, 1.277 * unit), rel=1e-12)
    assert pytest.approx(r.stiffness[1].K, rel=1e-12) == b.K
    assert b.travel() == pytest.approx((b.low / b.K, b.high / b.K), rel=1e-15)
    # along 0 deg it is layer 1's facets, with layer 2's K_C
    b0 = buckling_bounds(a, sp, 0.0)
    assert b0 is not None
    sigma1 = math.pi**2 * DURALAR.E / (12 * (1 - DURALAR.nu**2)) * (0.125 / 8.0) ** 2
    unit0 = sigma1 * 9 * 8.0 * 0.125 * (1 + float(sp[1].K_C) / float(sp[0].K_S))
    assert b0.low == pytest.approx(0.425 * unit0, rel=1e-12)
    assert pytest.approx(r.stiffness[0].K, rel=1e-12) == b0.K
    # 180 deg is 0 deg again, 270 deg is 90; anything between has no bounds
    b180, b270 = buckling_bounds(a, sp, 180.0), buckling_bounds(a, sp, 270.0)
    assert b180 is not None and (b180.low, b180.high, b180.K) == (b0.low, b0.high, b0.K)
    assert b270 is not None and (b270.low, b270.high, b270.K) == (b.low, b.high, b.K)
    assert buckling_bounds(a, sp, 30.0) is None


def test_the_scale_of_intervals_contains_the_scale_of_every_point() -> None:
    """buckling_scale is plain arithmetic, monotone in each argument: on intervals (the solver's
    use) its bounds contain the value at every sampled point of the box, and on degenerate
    intervals they are the point value."""
    E, nu = DURALAR.E, DURALAR.nu
    box = {"t": (0.1, 0.2), "W": (6.0, 12.0), "n": (5.0, 15.0), "K_S": (300.0, 500.0)}
    box["K_C"] = (1.0, 20.0)
    iv = {k: Interval(np.array([lo]), np.array([hi])) for k, (lo, hi) in box.items()}
    s = buckling_scale(E, nu, iv["t"], iv["W"], iv["n"], iv["K_S"], iv["K_C"])
    rng = np.random.default_rng(5)
    for _ in range(200):
        x = {k: rng.uniform(lo, hi) for k, (lo, hi) in box.items()}
        v = buckling_scale(E, nu, x["t"], x["W"], x["n"], x["K_S"], x["K_C"])
        assert s.lo[0] <= v <= s.hi[0]
    corner_lo = buckling_scale(E, nu, 0.1, 12.0, 5.0, 500.0, 1.0)
    corner_hi = buckling_scale(E, nu, 0.2, 6.0, 15.0, 300.0, 20.0)
    assert s.lo[0] == pytest.approx(corner_lo, rel=1e-12)
    assert s.hi[0] == pytest.approx(corner_hi, rel=1e-12)
