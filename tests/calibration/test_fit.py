"""The fit (corrugate.calibration.fit): E recovered from readings made by the elastica at a known
E (a second solve, not the fit's table), the crease stiffness and angle from the zig-zag model, and
bad readings refused in one line naming the field."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from corrugate.calibration.coupons import GRAVITY, expected_sag
from corrugate.calibration.crease import compliance
from corrugate.calibration.fit import FACET_SOFTENING, fit_crease, fit_modulus, sag_model
from corrugate.calibration.measurements import CreaseTest, FlatTest
from corrugate.core.errors import InputError
from corrugate.materials.library import get_material

MAT = get_material("dura-lar")
T = 0.125


def _flat(L: float, tip: float, sags: tuple[float, ...], field: str = "flat[0]") -> FlatTest:
    return FlatTest("F1", "along", 20.0, L, tip, sags, field)


def test_the_tabulated_model_is_the_elastica() -> None:
    test = _flat(75.0, 5.0, (1.0, 1.0, 1.0))
    for E in (900.0, 2700.0, 9000.0):
        direct = expected_sag(E, MAT, T, 20.0, 75.0, 5.0)
        assert float(sag_model(test, E, MAT.density, T, MAT.nu)) == pytest.approx(direct, rel=1e-6)


def test_exact_readings_give_back_e_inside_a_narrow_interval() -> None:
    E = 3300.0
    tests = [
        _flat(L, tip, (expected_sag(E, MAT, T, 20.0, L, tip),) * 3, f"flat[{i}]")
        for i, (L, tip) in enumerate(((75.0, 0.0), (45.0, 2.5)))
    ]
    fit = fit_modulus(tests, MAT, T, 1.0, np.random.default_rng(1), 300)
    assert pytest.approx(E, rel=2e-3) == fit.E
    assert fit.lo < E < fit.hi
    assert max(abs(r) for r in fit.residuals) < 0.02  # mm
    # a reading error of +-1 mm on 15 mm sags: the interval is a few per cent wide, not 0
    assert 0.01 < (fit.hi - fit.lo) / E < 0.2


def test_sags_no_modulus_explains_are_refused() -> None:
    # a strip that sags 70 mm at 75 mm free without a coin and 1 mm with one: no E does both
    tests = [_flat(75.0, 0.0, (70.0, 70.0, 70.0)), _flat(40.0, 5.0, (1.0, 1.0, 1.0), "flat[1]")]
    with pytest.raises(InputError, match=r"^flat \(along\) = .* fit no modulus"):
        fit_modulus(tests, MAT, T, 1.0, np.random.default_rng(0), 100)


def test_the_crease_fit_recovers_k_and_the_angle() -> None:
    E, k, alpha, W, n = 3000.0, 0.1, 84.0, 12.0, 9
    # the fit's model: the rigid strip's compliance taken times 1 + FACET_SOFTENING / 2
    rigid = compliance(math.inf, E, T, 20.0, W, alpha, n, MAT.nu)
    C = compliance(k, E, T, 20.0, W, alpha, n, MAT.nu) + rigid * FACET_SOFTENING / 2
    length = n * W * math.sin(math.radians(alpha) / 2)
    masses = (5.0, 10.0, 15.0)
    test = CreaseTest(
        "C1",
        20.0,
        W,
        n,
        90.0,
        (length,) * 3,
        masses,
        tuple((C * m * GRAVITY,) * 3 for m in masses),
    )
    fit = fit_crease(test, MAT, [E] * 200, E, T, 1.0, np.random.default_rng(2))
    assert fit.k == pytest.approx(k, rel=1e-6)
    assert fit.angle == pytest.approx(alpha, abs=1e-9)
    assert fit.springback == pytest.approx(alpha - 90.0, abs=1e-9)
    assert fit.k_lo < k < fit.k_hi
    # readings below the rigid strip's extension: stiffer than the readings tell
    stiff = replace(test, extensions=tuple((0.0, 0.0, 0.0) for _ in masses))
    assert math.isinf(fit_crease(stiff, MAT, [E] * 50, E, T, 1.0, np.random.default_rng(2)).k)
