"""The strip's anticlastic moment law (corrugate.calibration.elastica.Anticlastic; docs/calibration.md
section 3) against a second method and its limits, and the elastica with it against the linear
elastica in the beam's and the plate's limits."""

from __future__ import annotations

import math
from itertools import pairwise

import numpy as np
import pytest

from corrugate.calibration.elastica import (
    Anticlastic,
    anticlastic_factor,
    drop_ratio,
)


def _ritz_factor(theta: float, nu: float, degree: int = 60) -> float:
    """g by a second method: the strip's strain energy per unit length,
    U(kappa) = min_u int 1/2 D (kappa^2 + u''^2 + 2 nu kappa u'') + 1/2 E t kappa^2 u^2 dy,
    minimised over even Legendre polynomials u of the width (Rayleigh-Ritz, no boundary condition
    imposed: the free edges' conditions are natural), and M = dU/dkappa by a central difference
    of the minimum. Units D = 1, E t = 4 (lambda = 1 at kappa = 1), half width theta."""
    from numpy.polynomial import legendre as leg

    eta, w = leg.leggauss(200)
    y_w = w * theta  # dy = theta d eta
    cols = []
    for j in range(0, degree + 1, 2):
        c = np.zeros(j + 1)
        c[j] = 1.0
        cols.append((leg.legval(eta, c), leg.legval(eta, leg.legder(c, 2)) / theta**2))
    B0 = np.array([c[0] for c in cols]).T  # u
    B2 = np.array([c[1] for c in cols]).T  # u''

    def energy(kappa: float) -> float:
        # U = 1/2 x^T A x + kappa nu f^T x + const, A = B2^T W B2 + 4 kappa^2 B0^T W B0
        A = B2.T @ (y_w[:, None] * B2) + 4.0 * kappa**2 * (B0.T @ (y_w[:, None] * B0))
        f = nu * kappa * (B2.T @ y_w)
        x = np.linalg.lstsq(A, -f, rcond=None)[0]
        return float(0.5 * kappa**2 * 2 * theta + 0.5 * x @ A @ x + f @ x)

    h = 1e-4
    M = (energy(1.0 + h) - energy(1.0 - h)) / (2 * h)
    return M / (2 * theta)


@pytest.mark.parametrize("theta", [0.5, 1.0, 2.0, 4.0])
@pytest.mark.parametrize("nu", [0.3, 0.43])
def test_the_closed_form_factor_equals_the_ritz_energy_method(theta: float, nu: float) -> None:
    beta = (2 * theta) ** 2 / math.sqrt(3 * (1 - nu * nu))  # theta = sqrt(sqrt(3(1-nu^2)) beta)/2
    assert anticlastic_factor(beta, nu) == pytest.approx(_ritz_factor(theta, nu), rel=1e-5)


def test_the_factor_runs_from_the_beam_to_the_plate() -> None:
    nu = 0.43
    assert anticlastic_factor(0.0, nu) == 1.0 - nu * nu
    assert anticlastic_factor(1e-6, nu) == pytest.approx(1.0 - nu * nu, rel=1e-9)
    g = [anticlastic_factor(b, nu) for b in np.geomspace(1e-3, 1e6, 60)]
    assert all(b >= a for a, b in pairwise(g))
    # two edges' boundary layers apart: 1 - (3/4) nu^2 / theta, the semi-infinite strip's moment
    # (docs/calibration.md section 3, by hand); here from the finite strip's closed form at theta 10
    beta = 20.0**2 / math.sqrt(3 * (1 - nu * nu))
    assert anticlastic_factor(beta, nu) == pytest.approx(1 - 0.75 * nu * nu / 10.0, rel=1e-9)


def test_the_law_inverts_itself() -> None:
    law = Anticlastic.for_strip(20.0, 0.125, 80.0, 0.43)
    k = np.concatenate([-np.geomspace(1e-7, 50, 30), [0.0], np.geomspace(1e-7, 50, 30)])
    assert law.curvature(law.moment(k)) == pytest.approx(k, rel=2e-5, abs=1e-15)


@pytest.mark.parametrize(("a", "b"), [(2.0, 0.0), (0.5, 1.5), (4.0, 3.0)])
def test_the_elastica_tends_to_the_beam_and_the_plate(a: float, b: float) -> None:
    nu = 0.43
    beam = 1 - nu * nu
    narrow = Anticlastic(1e-8, nu)  # a strip as narrow as a beam: EI = E b t^3 / 12
    assert drop_ratio(a, b, narrow) == pytest.approx(drop_ratio(a / beam, b / beam), rel=1e-5)
    wide = Anticlastic(1e9, nu)  # so wide that it is a plate but at the tip: within 1e-3
    assert drop_ratio(a, b, wide) == pytest.approx(drop_ratio(a, b), rel=1e-3)
    # a kit's strip lies between them
    kit = Anticlastic.for_strip(20.0, 0.125, 80.0, nu)
    assert drop_ratio(a, b) < drop_ratio(a, b, kit) < drop_ratio(a / beam, b / beam)
