"""The cantilever elastica (corrugate.calibration.elastica) against the small-deflection limit,
Bisshopp and Drucker's tip-load values and a second method (quadrature of the first integral)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq

from corrugate.calibration.elastica import drop_ratio, drop_ratios
from corrugate.core.errors import InputError


@pytest.mark.parametrize(("a", "b"), [(1e-3, 0.0), (0.0, 1e-3), (2e-3, 5e-4)])
def test_small_loads_give_the_linear_cantilever(a: float, b: float) -> None:
    # w = q L^4 / (8 EI) + P L^3 / (3 EI), i.e. w / L = a / 8 + b / 3 (beam theory)
    assert drop_ratio(a, b) == pytest.approx(a / 8 + b / 3, rel=2e-3)


def _tip_load_by_quadrature(b: float) -> float:
    """w / L under a tip load b = P L^2 / EI from the first integral
    theta'^2 / 2 = b (sin theta_L - sin theta) (s in units of L): the tip angle theta_L solves
    sqrt(2 b) = int_0^theta_L dtheta / sqrt(sin theta_L - sin theta), and
    w / L = int_0^theta_L sin theta dtheta / sqrt(2 b (sin theta_L - sin theta)); theta =
    theta_L - u^2 removes the square-root singularity at the tip."""

    def integral(tl: float, f: object) -> float:
        def g(u: float) -> float:
            th = tl - u * u  # sin tl - sin th = 2 cos(tl - u^2 / 2) sin(u^2 / 2), no cancellation
            gap = 2 * math.cos(tl - u * u / 2) * math.sin(u * u / 2)
            return (
                2 * f(th) / math.sqrt(gap / (u * u))
                if u > 0
                else 2 * f(th) / math.sqrt(math.cos(tl))
            )  # type: ignore[operator]

        return quad(g, 0.0, math.sqrt(tl), limit=200, epsabs=1e-11, epsrel=1e-10)[0]

    tl = brentq(
        lambda x: integral(x, lambda th: 1.0) - math.sqrt(2 * b),
        1e-6,
        math.pi / 2 - 1e-9,
        xtol=1e-14,
    )
    return integral(tl, math.sin) / math.sqrt(2 * b)


@pytest.mark.parametrize(
    ("b", "table"),
    # Bisshopp and Drucker (1945), vertical tip deflection over length for P L^2 / EI
    [(1.0, 0.30172), (2.0, 0.49346), (3.0, 0.60325), (10.0, 0.81061)],
)
def test_tip_load_matches_bisshopp_drucker_and_the_quadrature(b: float, table: float) -> None:
    w = drop_ratio(0.0, b)
    assert w == pytest.approx(table, abs=1e-5)
    assert w == pytest.approx(_tip_load_by_quadrature(b), rel=1e-4)


def test_large_self_weight_sags_less_than_the_linear_formula() -> None:
    # at a = 2 the linear formula says w / L = 0.25; the strip rotates and its arm shortens
    w = drop_ratio(2.0, 0.0)
    assert 0.18 < w < 0.25


def test_a_load_path_matches_single_solves() -> None:
    scale = np.array([0.1, 0.5, 1.0, 4.0])
    path = drop_ratios(scale, 1.2, 0.4)
    single = [drop_ratio(1.2 * s, 0.4 * s) for s in scale]
    assert path == pytest.approx(single, rel=1e-6)


def test_negative_loads_are_refused() -> None:
    with pytest.raises(InputError, match="a, b >= 0"):
        drop_ratio(-1.0, 0.0)
