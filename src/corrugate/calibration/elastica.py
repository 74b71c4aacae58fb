"""The large-deflection cantilever (the elastica) under its own weight and a tip load.

A strip clamped at s = 0 and free at s = L (mm), loaded by its own weight q (N/mm, uniform along
its length) and a weight P (N) at its tip. With theta(s) the slope below the horizontal and M(s)
the moment of everything beyond s, the moment balance differentiated once is

    M'(s) = -(P + q (L - s)) cos theta(s),   theta' = kappa(M),   theta(0) = 0,   M(L) = 0,

and the tip's drop below the clamp is w = int_0^L sin theta ds (docs/calibration.md section 3).
For a linear moment law M = EI kappa, in the arc length s/L and the loads a = q L^3 / EI,
b = P L^2 / EI it reads theta'' = -(b + a (1 - s)) cos theta, and w / L depends on (a, b) only;
for small loads it tends to w = q L^4 / (8 EI) + P L^3 / (3 EI) (w / L = a / 8 + b / 3).

**A strip is neither a beam nor a plate** (:class:`Anticlastic`). Bent to the curvature kappa, a
strip of width b and thickness t curls the other way near its free edges (its anticlastic
curvature) over a boundary layer about 1 / lambda wide, lambda^4 = 3 (1 - nu^2) kappa^2 / t^2, and
the moment it takes is M = D b kappa g(beta), D = E t^3 / (12 (1 - nu^2)), with g a function of
the Searle parameter beta = b^2 kappa / t alone: g = 1 - nu^2 (the beam, E b t^3 / 12) at
beta -> 0, and g -> 1 - (3/4) nu^2 / theta -> 1 (the plate) as beta grows, theta = lambda b / 2
(the linear theory of Ashwell, "The anticlastic curvature of rectangular beams and plates",
J. R. Aeronaut. Soc. 54, 1950; derived in docs/calibration.md section 3). Along a cantilever the
curvature falls to zero at the tip: the strip bends as a plate near the clamp and as a beam near
its tip. With this law a and b are taken with the plate's rigidity D b (:func:`rigidity`).

The boundary value problem (states theta, M L / EI and w / L) is solved with
:func:`scipy.integrate.solve_bvp`, the load raised in steps from the linear solution
(continuation), so that every step starts from a converged shape.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from numpy.typing import NDArray

from corrugate.core.errors import InputError

__all__ = ["Anticlastic", "anticlastic_factor", "drop_ratio", "drop_ratios", "rigidity"]


def rigidity(E: float, nu: float, b: float, t: float) -> float:
    """The bending rigidity (N mm^2) of a strip of width b and thickness t (mm) as a plate,
    D b = E b t^3 / (12 (1 - nu^2)) (E in MPa): the rigidity the strip reaches where it is
    curved enough (:class:`Anticlastic`), and the one the models take for a facet
    (docs/theory.md)."""
    return E * b * t**3 / (12 * (1 - nu * nu))


#: Gauss-Legendre points over the half width for the membrane term of g (theta < _WIDE).
_GAUSS = np.polynomial.legendre.leggauss(160)
#: theta = lambda b / 2 from which the two edges' boundary layers no longer meet (their overlap
#: is of order e^(-2 theta), below 1e-12): g = 1 - (3/4) nu^2 / theta there.
_WIDE = 14.0


def _factor_theta(theta: float, nu: float) -> float:
    """g (-) at theta = lambda b / 2 (> 0) and Poisson's ratio nu. The strip's transverse
    deflection u(y) solves D u'''' + E t kappa^2 u = 0 with the free edges' u'' = -nu kappa and
    u''' = 0, so u = Re[C cosh((1 + i) lambda y)]; the moment is the derivative of the strain
    energy in kappa, M = int D (kappa + nu u'') + E t kappa u^2 dy (docs/calibration.md section
    3). Units lambda = 1, kappa = 1, D = 1 (so E t kappa = 4), half width c = theta."""
    if theta >= _WIDE:
        return 1.0 - 0.75 * nu * nu / theta
    mu = 1.0 + 1.0j
    a1 = mu**2 * np.cosh(mu * theta)
    a2 = mu**3 * np.sinh(mu * theta)
    x, y = np.linalg.solve(np.array([[a1.real, -a1.imag], [a2.real, -a2.imag]]), [-nu, 0.0])
    C = x + 1j * y
    nodes, weights = _GAUSS
    half = 0.5 * theta
    u = (C * np.cosh(mu * half * (nodes + 1.0))).real  # over 0 <= y <= c; u is even
    membrane = 2.0 * half * float(np.sum(weights * u * u))
    slope = float((C * mu * np.sinh(mu * theta)).real)  # u'(c); int u'' dy = 2 u'(c)
    return (2.0 * theta + 2.0 * nu * slope + 4.0 * membrane) / (2.0 * theta)


def anticlastic_factor(beta: float, nu: float) -> float:
    """g = M / (D b kappa) (-) of a strip at the Searle parameter beta = b^2 kappa / t (>= 0) and
    Poisson's ratio nu (module docstring): 1 - nu^2 at beta = 0, rising towards 1."""
    if beta <= 0.0:
        return 1.0 - nu * nu
    theta = 0.5 * math.sqrt(math.sqrt(3.0 * (1.0 - nu * nu)) * beta)
    return _factor_theta(theta, nu)


@lru_cache(maxsize=16)
def _inverse_table(nu: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(log H, log beta) on a dense grid, H(beta) = beta g(beta): increasing, as g is."""
    beta = np.geomspace(1e-6, 1e9, 1501)
    H = beta * np.array([anticlastic_factor(float(x), nu) for x in beta])
    return np.log(H), np.log(beta)


@dataclass(frozen=True, slots=True)
class Anticlastic:
    """The moment law of a strip in the elastica's units, moment m = M L / (D b) and curvature
    k = kappa L: m = k g(sigma |k|), ``sigma`` = b^2 / (t L) (so that sigma |k| is the Searle
    parameter), ``nu`` Poisson's ratio (module docstring)."""

    sigma: float
    nu: float

    @staticmethod
    def for_strip(b: float, t: float, L: float, nu: float) -> Anticlastic:
        """The law of a strip ``b`` wide and ``t`` thick over the free length ``L`` (mm)."""
        return Anticlastic(b * b / (t * L), nu)

    def moment(self, k: NDArray[np.float64]) -> NDArray[np.float64]:
        """m (-) at the curvatures k (-)."""
        g = [anticlastic_factor(self.sigma * abs(float(x)), self.nu) for x in np.ravel(k)]
        out: NDArray[np.float64] = np.asarray(k, dtype=np.float64) * np.reshape(g, np.shape(k))
        return out

    def curvature(self, m: NDArray[np.float64]) -> NDArray[np.float64]:
        """k (-) with :meth:`moment` (k) = m: H = beta g(beta) tabulated (100 points a decade of
        beta, 1e-6 to 1e9) and inverted by interpolating log beta in log H; below the table, the
        beam's k = m / (1 - nu^2); above it, beta = H / (1 - (3/4) nu^2 / theta(H))."""
        logH, logb = _inverse_table(self.nu)
        h = self.sigma * np.abs(m)
        low, high = math.exp(logH[0]), math.exp(logH[-1])
        inside = np.clip(h, low, high)
        # above the table g is 1 - (3/4) nu^2 / theta within 1e-5 of 1: one fixed-point step
        theta = 0.5 * np.sqrt(math.sqrt(3.0 * (1.0 - self.nu**2)) * np.maximum(h, high))
        beta = np.where(
            h < low,
            h / (1.0 - self.nu**2),
            np.where(
                h > high,
                h / (1.0 - 0.75 * self.nu**2 / theta),
                np.exp(np.interp(np.log(inside), logH, logb)),
            ),
        )
        out: NDArray[np.float64] = np.sign(m) * beta / self.sigma
        return out


#: The nodes of the arc length the shape is solved on (refined by solve_bvp where needed).
_NODES = 41
#: solve_bvp's tolerance on the collocation residuals: the sags agree with 1e-8's to 8 digits,
#: and the tabulated moment law's kinks keep 1e-8 from being reached without many more nodes.
_TOL = 1e-7
#: Loads a, b above which the strip hangs nearly vertical and a sag no longer tells EI apart.
_MAX_LOAD = 1.0e4


_Shape = tuple[NDArray[np.float64], NDArray[np.float64]]


def _solve(a: float, b: float, guess: _Shape | None, law: Anticlastic | None) -> _Shape | None:
    """The shape (s, [theta, m, w]) under the loads (a, b) with the moment law ``law`` (None:
    linear, m = k), from ``guess`` (None: the linear solution); None when solve_bvp does not
    converge."""
    from scipy.integrate import solve_bvp

    def rhs(s: NDArray[np.float64], y: NDArray[np.float64]) -> NDArray[np.float64]:
        theta, m, _ = y
        k = m if law is None else law.curvature(m)
        return np.vstack((k, -(b + a * (1.0 - s)) * np.cos(theta), np.sin(theta)))

    def bc(y0: NDArray[np.float64], y1: NDArray[np.float64]) -> NDArray[np.float64]:
        return np.array([y0[0], y1[1], y0[2]])

    if guess is None:
        s = np.linspace(0.0, 1.0, _NODES)
        # the linear solution: theta = int_0^s m, with m = b (1 - s) + a (1 - s)^2 / 2
        theta = b * (s - s**2 / 2) + a * (1 - (1 - s) ** 3) / 6
        m = b * (1 - s) + a * (1 - s) ** 2 / 2
        w = b * (s**2 / 2 - s**3 / 6) + a * (s**2 / 4 - s**3 / 6 + s**4 / 24)
        y = np.vstack((np.minimum(theta, 1.5), m, w))
    else:
        s, y = guess
    sol = solve_bvp(rhs, bc, s, y, tol=_TOL, max_nodes=20000)
    if sol.status != 0:
        return None
    return sol.x, sol.y


def drop_ratio(a: float, b: float, law: Anticlastic | None = None) -> float:
    """The tip's drop over the length, w / L (-), of a cantilever under the self-weight load
    a = q L^3 / EI and the tip load b = P L^2 / EI (both >= 0, dimensionless), EI the rigidity
    of the linear law or, with ``law``, the plate's D b."""
    return float(drop_ratios(np.array([1.0]), a, b, law)[0])


def drop_ratios(
    scale: Sequence[float] | NDArray[np.float64],
    a: float,
    b: float,
    law: Anticlastic | None = None,
) -> NDArray[np.float64]:
    """w / L for the loads (a, b) multiplied by each of ``scale`` (ascending, > 0): one load path
    solved by continuation, e.g. one strip and coin for a range of trial moduli (a and b both scale
    as 1 / EI; the law's sigma does not depend on E). Raises :class:`InputError` for negative
    loads or loads beyond 1e4."""
    factors = np.asarray(scale, dtype=np.float64)
    if a < 0 or b < 0 or not (math.isfinite(a) and math.isfinite(b)):
        raise InputError("load", f"a = {a}, b = {b}", "a, b >= 0")
    if np.any(np.diff(factors) < 0) or np.any(factors <= 0):
        raise InputError("scale", "unsorted", "ascending factors > 0")
    if factors.size and factors[-1] * max(a, b) > _MAX_LOAD:
        raise InputError("load", f"{factors[-1] * max(a, b):.3g}", f"at most {_MAX_LOAD:g}")
    out = np.empty(factors.size)
    guess: _Shape | None = None
    done = 0.0  # the load factor of ``guess``
    sigma = 0.0 if law is None else law.sigma
    beam = 1.0 if law is None else 1.0 - law.nu**2
    for i, f in enumerate(factors):
        if f * max(a, b) * max(1.0, sigma) < 1e-6:  # the linear limit, to 1e-12 relative
            out[i] = f * (a / 8 + b / 3) / beam
            continue
        # continuation: raise the load from the last converged shape at most twofold a step
        steps = [] if guess is None or f <= 2 * done else list(np.geomspace(done, f, 8)[1:-1])
        for g in [*steps, f]:
            sol = _solve(g * a, g * b, guess, law) or _solve(g * a, g * b, None, law)
            if sol is None:
                raise InputError(
                    "load", f"a = {g * a:.4g}, b = {g * b:.4g}", "a converged elastica"
                )
            guess, done = sol, g
        assert guess is not None
        out[i] = guess[1][2, -1]
    return out
