"""The large-deflection cantilever (the elastica) under its own weight and a tip load.

A strip of bending rigidity EI (N mm^2) clamped at s = 0 and free at s = L (mm), loaded by its own
weight q (N/mm, uniform along its length) and a weight P (N) at its tip. With theta(s) the slope
below the horizontal, the moment balance of the part beyond s, differentiated once, is

    EI theta''(s) = -(P + q (L - s)) cos theta(s),   theta(0) = 0,   theta'(L) = 0,

and the tip's drop below the clamp is w = int_0^L sin theta ds (docs/calibration.md section 3).
In the arc length s/L and the loads a = q L^3 / EI, b = P L^2 / EI it reads
theta'' = -(b + a (1 - s)) cos theta, and w / L depends on (a, b) only. For small loads it tends to
w = q L^4 / (8 EI) + P L^3 / (3 EI) (w / L = a / 8 + b / 3). The boundary value problem is solved
with :func:`scipy.integrate.solve_bvp`, the load raised in steps from the linear solution
(continuation), so that every step starts from a converged shape.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

from corrugate.core.errors import InputError

__all__ = ["drop_ratio", "drop_ratios", "rigidity"]


def rigidity(E: float, nu: float, b: float, t: float) -> float:
    """The bending rigidity (N mm^2) of a strip of width b and thickness t (mm) as a plate,
    E b t^3 / (12 (1 - nu^2)) (E in MPa): a strip far wider than thick bends without its
    anticlastic curvature, as the finite elements of a kit's strip show (docs/calibration.md
    section 7), and the models take a facet's bending so (docs/theory.md)."""
    return E * b * t**3 / (12 * (1 - nu * nu))


#: The nodes of the arc length the shape is solved on (refined by solve_bvp where needed).
_NODES = 41
#: Loads a, b above which the strip hangs nearly vertical and a sag no longer tells EI apart.
_MAX_LOAD = 1.0e4


_Shape = tuple[NDArray[np.float64], NDArray[np.float64]]


def _solve(a: float, b: float, guess: _Shape | None) -> _Shape | None:
    """The shape (s, [theta, theta', w]) under the loads (a, b), from ``guess`` (None: the
    linear solution); None when solve_bvp does not converge."""
    from scipy.integrate import solve_bvp

    def rhs(s: NDArray[np.float64], y: NDArray[np.float64]) -> NDArray[np.float64]:
        theta, kappa, _ = y
        return np.vstack((kappa, -(b + a * (1.0 - s)) * np.cos(theta), np.sin(theta)))

    def bc(y0: NDArray[np.float64], y1: NDArray[np.float64]) -> NDArray[np.float64]:
        return np.array([y0[0], y1[1], y0[2]])

    if guess is None:
        s = np.linspace(0.0, 1.0, _NODES)
        # the linear solution: theta = int_0^s M/EI, with M/EI = b (1 - s) + a (1 - s)^2 / 2
        theta = b * (s - s**2 / 2) + a * (1 - (1 - s) ** 3) / 6
        kappa = b * (1 - s) + a * (1 - s) ** 2 / 2
        w = b * (s**2 / 2 - s**3 / 6) + a * (s**2 / 4 - s**3 / 6 + s**4 / 24)
        y = np.vstack((np.minimum(theta, 1.5), kappa, w))
    else:
        s, y = guess
    sol = solve_bvp(rhs, bc, s, y, tol=1e-8, max_nodes=20000)
    if sol.status != 0:
        return None
    return sol.x, sol.y


def drop_ratio(a: float, b: float) -> float:
    """The tip's drop over the length, w / L (-), of a cantilever under the self-weight load
    a = q L^3 / EI and the tip load b = P L^2 / EI (both >= 0, dimensionless)."""
    return float(drop_ratios(np.array([1.0]), a, b)[0])


def drop_ratios(
    scale: Sequence[float] | NDArray[np.float64], a: float, b: float
) -> NDArray[np.float64]:
    """w / L for the loads (a, b) multiplied by each of ``scale`` (ascending, > 0): one load path
    solved by continuation, e.g. one strip and coin for a range of trial moduli (a and b both scale
    as 1 / EI). Raises :class:`InputError` for negative loads or loads beyond 1e4."""
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
    for i, f in enumerate(factors):
        if f * max(a, b) < 1e-6:  # the linear limit, to 1e-12 relative
            out[i] = f * (a / 8 + b / 3)
            continue
        # continuation: raise the load from the last converged shape at most twofold a step
        steps = [] if guess is None or f <= 2 * done else list(np.geomspace(done, f, 8)[1:-1])
        for g in [*steps, f]:
            sol = _solve(g * a, g * b, guess) or _solve(g * a, g * b, None)
            if sol is None:
                raise InputError(
                    "load", f"a = {g * a:.4g}, b = {g * b:.4g}", "a converged elastica"
                )
            guess, done = sol, g
        assert guess is not None
        out[i] = guess[1][2, -1]
    return out
