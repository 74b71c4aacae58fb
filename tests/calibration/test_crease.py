"""The zig-zag strip with compliant creases (corrugate.calibration.crease): limit cases, the
facets' share by numerical integration, and the angle read from the strip's length against the
zig-zag's pitch (corrugate.geometry.profile)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from corrugate.calibration.crease import angle_from_length, compliance, crease_stiffness
from corrugate.geometry.profile import ZigZag

E, t, b, W, NU = 2700.0, 0.125, 20.0, 12.0, 0.43


def test_a_flat_strip_is_a_bar_in_tension() -> None:
    # alpha = 180 deg: no lever arm, the compliance is L / (E A) whatever the creases
    C = compliance(0.01, E, t, b, W, 180.0, 9, NU)
    assert pytest.approx(9 * W / (E * b * t), rel=1e-9) == C


def test_the_terms_add_up_to_a_virtual_work_integral() -> None:
    alpha, n, k = 84.0, 7, 0.1
    e = W * math.cos(math.radians(alpha) / 2) / 2
    EI = E * b * t**3 / (12 * (1 - NU**2))  # a plate strip's rigidity
    # a facet's moment falls linearly from F e to -F e; integrate M^2 / EI numerically (F = 1)
    x = np.linspace(0.0, W, 20001)
    bending = float(np.trapezoid((e * (1 - 2 * x / W)) ** 2, x)) / EI
    hinge = e**2 / (k * b)  # rotation M / (k b) times the arm e
    stretch = W * math.sin(math.radians(alpha) / 2) ** 2 / (E * b * t)
    expected = n * (hinge + bending + stretch)  # n - 1 facets and two halves: n facets' worth
    assert compliance(k, E, t, b, W, alpha, n, NU) == pytest.approx(expected, rel=1e-6)


def test_rigid_creases_are_the_limit_and_the_inverse_recovers_k() -> None:
    rigid = compliance(math.inf, E, t, b, W, 90.0, 9, NU)
    assert compliance(1e9, E, t, b, W, 90.0, 9, NU) == pytest.approx(rigid, rel=1e-9)
    for k in (0.01, 0.1, 2.0):
        C = compliance(k, E, t, b, W, 90.0, 9, NU)
        assert crease_stiffness(C, E, t, b, W, 90.0, 9, NU) == pytest.approx(k, rel=1e-9)
    assert crease_stiffness(rigid * 0.99, E, t, b, W, 90.0, 9, NU) == math.inf


@pytest.mark.parametrize("alpha", [40.0, 84.0, 120.0])
def test_the_angle_from_the_length_inverts_the_zigzag_pitch(alpha: float) -> None:
    p = float(ZigZag.of_float(W, alpha).pitch)  # one facet's projection, the project's formula
    assert angle_from_length(9 * p, W, 9) == pytest.approx(alpha, abs=1e-9)
    assert math.isnan(angle_from_length(9 * W, W, 9))
