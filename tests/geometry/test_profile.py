"""The profile seam: the zig-zag's cross-section, its limit cases, its evaluation over intervals,
and the registry of profiles (a second profile, the trapezoid, registered by a test)."""

from __future__ import annotations

import math
from collections.abc import Iterator
from typing import Any

import numpy as np
import pytest

from corrugate.core.errors import InputError, UnknownNameError
from corrugate.geometry.layer import Layer
from corrugate.geometry.profile import (
    DEFAULT_PROFILE,
    Profile,
    ZigZag,
    get_profile,
    profile_names,
    register_profile,
    unregister_profile,
)
from corrugate.materials.library import get_material
from corrugate.mechanics.profiles import Trapezoid
from corrugate.solver.interval import Interval


@pytest.fixture
def trapezoid() -> Iterator[type[Any]]:
    """The trapezoid registered as a second profile for one test."""
    register_profile("trapezoid", Trapezoid)
    yield get_profile("trapezoid")
    unregister_profile("trapezoid")


@pytest.mark.parametrize("build", [ZigZag.of, ZigZag.of_float])
def test_flat_limit(build: object) -> None:
    # alpha = 180 deg: the sheet is flat, so a facet's plan length is its width and the
    # corrugation has no depth (docs/theory.md section 2)
    W, n = 7.5, 9
    z = build(W, 180.0)  # type: ignore[operator]
    assert z.pitch == W
    assert z.height == pytest.approx(0.0, abs=1e-14 * W)
    assert z.extent(n) == z.flat_width(n) == (n + 1) * W
    assert z.developed / z.pitch == 1.0


def test_right_angle_by_hand() -> None:
    # alpha = 90 deg: each facet is the hypotenuse of an isosceles right triangle, p = h = W / sqrt(2)
    W = 10.0
    for z in (ZigZag.of(W, 90.0), ZigZag.of_float(W, 90.0)):
        assert z.pitch == pytest.approx(W / math.sqrt(2), rel=1e-15)
        assert z.height == pytest.approx(W / math.sqrt(2), rel=1e-15)
        # a facet's second moment about mid-depth, W t (h^2 + t^2 s^2) / 12 (the rotated
        # rectangle), equals the mean of a rectangle's two principal moments at 45 deg
        t = 0.5
        second_moment = W * t * z.section_depth2(t) / 12
        assert second_moment == pytest.approx((W**3 * t / 12 + W * t**3 / 12) / 2, rel=1e-14)


def test_the_layer_asks_the_profile() -> None:
    # Layer(W = 8, n = 8, alpha = 84 deg): the paper's case 1 spans 9 x 8 sin(42 deg) mm
    layer = Layer(8.0, 8, 84.0, get_material("dura-lar"))
    assert layer.chord_extent == pytest.approx(9 * 8 * math.sin(math.radians(42)), rel=1e-15)
    assert layer.height == pytest.approx(8 * math.cos(math.radians(42)), rel=1e-15)
    assert layer.flat_width == 72.0
    assert (layer.s, layer.c, layer.pitch) == (
        layer.profile.s,
        layer.profile.c,
        layer.profile.pitch,
    )
    assert isinstance(layer.profile, Profile)


def test_the_half_angle_is_one_double() -> None:
    # alpha x pi/360 and radians(alpha) / 2 are the same double (pi/360 and pi/180 round a factor
    # 2 apart; halving is exact), so of() and of_float() differ only in who computes sin and cos
    alpha = np.linspace(0.01, 179.99, 20001)
    assert np.array_equal(alpha * (np.pi / 360.0), np.radians(alpha) / 2)
    assert all(a * (np.pi / 360.0) == math.radians(a) / 2 for a in alpha[::97].tolist())


def test_the_same_code_bounds_a_box() -> None:
    # over a box of W and alpha the profile's formulas, run on intervals, enclose every point
    W_lo, W_hi, a_lo, a_hi = 6.0, 14.0, 40.0, 115.0
    box = ZigZag.of(Interval(W_lo, W_hi), Interval(a_lo, a_hi))
    n = Interval(7.0, 13.0)
    rng = np.random.default_rng(3)
    W = rng.uniform(W_lo, W_hi, 2000)
    a = rng.uniform(a_lo, a_hi, 2000)
    k = rng.integers(7, 14, 2000).astype(float)
    point = ZigZag.of(W, a)
    for name, lo_hi, values in (
        ("pitch", box.pitch, point.pitch),
        ("height", box.height, point.height),
        ("extent", box.extent(n), point.extent(k)),
    ):
        assert np.all(lo_hi.lo <= values) and np.all(values <= lo_hi.hi), name
    # and the bounds are attained at the corners (p grows with W and alpha; h falls with alpha)
    assert float(box.pitch.hi) == pytest.approx(W_hi * math.sin(math.radians(a_hi / 2)))
    assert float(box.height.lo) == pytest.approx(W_lo * math.cos(math.radians(a_hi / 2)))


def test_registry(trapezoid: type[Any]) -> None:
    assert DEFAULT_PROFILE == "zig-zag"
    assert get_profile() is ZigZag
    assert profile_names() == ("zig-zag", "trapezoid")
    assert trapezoid is Trapezoid
    assert isinstance(trapezoid(50.8, 12.7, 45.0), Profile)
    with pytest.raises(InputError, match="already registered"):
        register_profile("Trapezoid", Trapezoid)
    with pytest.raises(UnknownNameError, match="sinusoid"):
        get_profile("sinusoid")
    with pytest.raises(InputError):
        unregister_profile("zig-zag")


def test_trapezoid_by_hand(trapezoid: type[Any]) -> None:
    # Xia's Table 5 section: c = 50.8, f = 12.7 mm, theta = 45 deg: the flat part is
    # c - 2 f / tan(theta) = 25.4 mm and a half period develops 2 f / sin(theta) + 25.4 mm
    profile = trapezoid(50.8, 12.7, 45.0)
    assert profile.pitch == 50.8
    assert profile.height == 25.4
    assert profile.developed == pytest.approx(25.4 * math.sqrt(2) + 25.4, rel=1e-14)
    assert profile.extent(3) == pytest.approx(4 * 50.8)
    assert profile.flat_width(3) == pytest.approx(4 * (25.4 * math.sqrt(2) + 25.4))


@pytest.mark.parametrize("alpha", [30.0, 84.0, 120.0, 170.0])
def test_trapezoid_without_flat_has_the_zigzags_geometry(alpha: float) -> None:
    # a second method: the trapezoid of half period W s, amplitude W c / 2 and incline
    # 90 - alpha/2 deg has no flat part, so it is the zig-zag
    W = 9.0
    z = ZigZag.of_float(W, alpha)
    trap = Trapezoid(z.pitch, z.height / 2, 90.0 - alpha / 2)
    assert trap.pitch == z.pitch
    assert trap.height == pytest.approx(z.height, rel=1e-15)
    assert trap.developed == pytest.approx(z.developed, rel=1e-12)
    ti, zi = trap.integrals(), z.integrals()
    for key in ("c", "l", "I1", "I2"):
        assert getattr(ti, key) == pytest.approx(getattr(zi, key), rel=1e-12), key
