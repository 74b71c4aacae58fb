"""A local polish of a feasible design of a problem with continuous W and alpha on independent
layers (:mod:`.cells`): an incumbent for the cells' search, never a certificate.

From a design x0 that meets every constraint of P under P's own rule (``point_values``, no slack:
:func:`~.cells.judge_of`), the sheets and each layer's n kept, :func:`polish` minimises the mass
over (W1, alpha1, W2, alpha2) inside their ranges subject to every constraint's relative margin
(value - bound) / |bound| (min; bound - value for max) at least :data:`MARGIN` (at least 0 for a
constraint of n alone, whose margin is the same at every W and alpha: the facets' count at its
bound cannot be given a margin, and asking one left SLSQP no feasible point; one such broken at
x0 ends the polish with no design, as no W and alpha meets it), by SLSQP
(:func:`scipy.optimize.minimize`) with forward differences evaluated in one vectorised call; the
designs on the segment from x0 to its result (x0 + s (x - x0), s = 1 - 10^-k) are then judged by
P's own rule and the lightest that meets it is returned. Whatever SLSQP does, the design returned
is one P's own rule accepts and no heavier than x0: an incumbent only prunes designs heavier than
a design of P, so the search's certificate does not depend on this module.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from corrugate.solver.points import DesignPoints, LayerPoints
from corrugate.solver.problem import Candidate, Problem
from corrugate.solver.quantities import Tables, point_values
from corrugate.solver.quantity import MASS, Quantity

FloatArray = NDArray[np.float64]

#: Relative margin every constraint is asked to keep in the polish (the result is judged by
#: P's own rule anyway).
MARGIN = 1e-10
#: The margin of the last polish of a :func:`climb`'s best design: its mass then lies within
#: about 1e-13 of the local optimum's (films-13-cont: 5e-13 above the certified optimum at
#: 1e-13, 8e-10 at :data:`MARGIN`), so that the cells' search can close to the solver's gap.
FINE = 1e-13
#: SLSQP's iterations at most, its tolerance and the forward-difference step (relative to each
#: variable's range).
ITERATIONS = 10
FTOL = 1e-13
STEP = 1e-7
#: Polishes one :func:`climb` runs at most.
CLIMB_MOST = 12
#: The segment from x0 to SLSQP's result is judged at s = 1 - 10^-k, k = 0 .. BACK.
BACK = 12


@dataclass(frozen=True)
class Polished:
    """A design of P (one point) and its mass (g)."""

    point: DesignPoints
    mass: float


def _points(n1: float, n2: float, v: FloatArray) -> DesignPoints:
    """Designs at rows v = (W1 mm, alpha1 deg, W2 mm, alpha2 deg), n1 and n2 creases."""
    k = len(v)
    return DesignPoints.of(
        LayerPoints(np.full(k, n1), v[:, 0].copy(), v[:, 1].copy()),
        LayerPoints(np.full(k, n2), v[:, 2].copy(), v[:, 3].copy()),
    )


def _margins(problem: Problem, vals: dict[Quantity, FloatArray], k: int) -> FloatArray:
    """Per point and constraint (k x constraints), the relative margin: >= 0 when met."""
    out = np.empty((k, len(problem.constraints)))
    for m, c in enumerate(problem.constraints):
        v = np.asarray(vals[c.quantity], dtype=np.float64).reshape(-1)
        scale = max(abs(c.bound), 1e-300)
        out[:, m] = (v - c.bound) / scale if c.sense == "min" else (c.bound - v) / scale
    return np.where(np.isnan(out), -1.0, out)


def polish(
    problem: Problem,
    c1: Candidate,
    c2: Candidate,
    x0: DesignPoints,
    tables: Tables,
    exact: Callable[[DesignPoints], tuple[FloatArray, NDArray[np.bool_]]],
    margin: float = MARGIN,
) -> Polished | None:
    """A design of ``problem`` on sheets (c1, c2) with x0's n, no heavier than x0 (one point
    that meets every constraint by ``exact``, :func:`~.cells.judge_of`), found as the module
    docstring says (each constraint asked the relative ``margin``); None when no design of
    the segment, x0 included, is accepted by ``exact``."""
    one, two = x0.layer(0), x0.layer(1)
    first = [
        float(np.asarray(getattr(lay, v)).reshape(-1)[0])
        for lay in (one, two)
        for v in ("W", "alpha")
    ]
    n1 = float(np.asarray(one.n).reshape(-1)[0])
    n2 = float(np.asarray(two.n).reshape(-1)[0])
    lo = np.array([problem.W.lo, problem.alpha.lo] * 2, dtype=np.float64)
    hi = np.array([problem.W.top, problem.alpha.top] * 2, dtype=np.float64)
    span = np.maximum(hi - lo, 1e-300)
    z0 = (np.asarray(first) - lo) / span
    only = frozenset({MASS, *(c.quantity for c in problem.constraints)})
    cache: dict[bytes, tuple[float, FloatArray, FloatArray, FloatArray]] = {}

    def at(z: FloatArray) -> tuple[float, FloatArray, FloatArray, FloatArray]:
        """Mass (g), margins and their gradients in z at z and z + STEP e_i (one call)."""
        key = np.asarray(z, dtype=np.float64).tobytes()
        if key not in cache:
            zs = np.vstack([z, z + STEP * np.eye(4)])
            v = lo + np.clip(zs, 0.0, 1.0) * span
            x = _points(n1, n2, v)
            vals = point_values(problem, c1, c2, x, tables, only)
            mass = np.asarray(vals[MASS], dtype=np.float64).reshape(-1)
            marg = _margins(problem, vals, len(v))
            gm = (mass[1:] - mass[0]) / STEP
            gc = (marg[1:] - marg[0]) / STEP
            cache.clear()
            cache[key] = (float(mass[0]), gm, marg[0], gc.T)
        return cache[key]

    from scipy.optimize import minimize  # here: its import is not paid by every solve

    # a constraint of n alone (its margin the same at every W and alpha, e.g. the facets' count)
    # asks no margin: met at n with none, it cannot be given one
    free = np.all(at(z0)[3] == 0.0, axis=1)
    if np.any(free & (at(z0)[2] < 0.0)):  # broken at every W and alpha of this n: no design
        return None
    need = np.where(free, 0.0, margin)
    m0, ok0 = exact(_points(n1, n2, np.asarray([first])))
    start = float(m0[0]) if bool(ok0[0]) else math.inf
    try:
        with np.errstate(all="ignore"):
            res = minimize(
                lambda z: at(z)[0],
                z0,
                jac=lambda z: at(z)[1],
                method="SLSQP",
                bounds=[(0.0, 1.0)] * 4,
                constraints=[
                    {
                        "type": "ineq",
                        "fun": lambda z: at(z)[2] - need,
                        "jac": lambda z: at(z)[3],
                    }
                ],
                options={"maxiter": ITERATIONS, "ftol": FTOL},
            )
        z1 = np.clip(np.asarray(res.x, dtype=np.float64), 0.0, 1.0)
    except (ValueError, ArithmeticError):
        return Polished(x0, start) if math.isfinite(start) else None
    s = 1.0 - 10.0 ** -np.arange(BACK + 1, dtype=np.float64)
    s[0] = 1.0
    v = lo + (z0 + s[:, None] * (z1 - z0)[None, :]) * span
    v = np.vstack([v, np.asarray([first])])
    mass, ok = exact(_points(n1, n2, v))
    f = np.where(ok, mass, math.inf)
    b = int(np.argmin(f))
    if not math.isfinite(float(f[b])):
        return None
    return Polished(_points(n1, n2, v[b : b + 1]).point(0), float(f[b]))


def climb(
    problem: Problem,
    c1: Candidate,
    c2: Candidate,
    x0: DesignPoints,
    tables: Tables,
    exact: Callable[[DesignPoints], tuple[FloatArray, NDArray[np.bool_]]],
    done: set[tuple[float, float]],
    most: int = 0,
) -> Polished | None:
    """The best of :func:`polish` from x0 and, while it improves, from the best design with
    each layer's n moved by -1, 0 or +1 (inside n's range), :data:`CLIMB_MOST` (or ``most``) polishes at
    most; ``done``: the (n1, n2) already
    polished (skipped; grown). None when nothing met P's rule."""
    best: Polished | None = None
    frontier = [(x0, (0.0, 0.0))]
    runs = 0
    most = most or CLIMB_MOST
    while frontier and runs < most:
        x, came = frontier.pop()
        n1 = float(np.asarray(x.layer(0).n).reshape(-1)[0])
        n2 = float(np.asarray(x.layer(1).n).reshape(-1)[0])
        if (n1, n2) in done:
            continue
        done.add((n1, n2))
        got = None
        for y in _starts(problem, x, best):
            runs += 1
            got = polish(problem, c1, c2, y, tables, exact)
            if got is not None:
                break
        if got is None or (best is not None and got.mass >= best.mass):
            continue
        best = got
        one, two = got.point.layer(0), got.point.layer(1)
        steps = [(d1, d2) for d1 in (-1.0, 0.0, 1.0) for d2 in (-1.0, 0.0, 1.0)]
        steps.sort(key=lambda d: d == came)  # the step that improved, tried first (popped last)
        for d1, d2 in steps:
            if True:
                m1, m2 = n1 + d1, n2 + d2
                if problem.n_lo <= m1 <= problem.n_hi and problem.n_lo <= m2 <= problem.n_hi:
                    frontier.append(
                        (
                            DesignPoints.of(
                                LayerPoints(m1, one.W, one.alpha),
                                LayerPoints(m2, two.W, two.alpha),
                            ),
                            (d1, d2),
                        )
                    )
    if best is not None:  # the best one polished closer to its constraints
        fine = polish(problem, c1, c2, best.point, tables, exact, FINE)
        if fine is not None and fine.mass < best.mass:
            best = fine
    return best


def _starts(problem: Problem, x: DesignPoints, best: Polished | None) -> list[DesignPoints]:
    """Starts of a polish at ``x``'s n from the design ``best`` (another n): ``x`` itself, and
    each layer's extent (n + 1) W sin(alpha / 2) kept as it was in ``best`` by its alpha, then
    by its W (inside their ranges)."""
    if best is None:
        return [x]
    out = [x]
    for by in ("alpha", "W"):
        lays = []
        for k in (0, 1):
            new, old = x.layer(k), best.point.layer(k)
            f = (float(np.asarray(old.n).reshape(-1)[0]) + 1.0) / (
                float(np.asarray(new.n).reshape(-1)[0]) + 1.0
            )
            W, a = (
                float(np.asarray(old.W).reshape(-1)[0]),
                float(np.asarray(old.alpha).reshape(-1)[0]),
            )
            if by == "W":
                W = min(max(W * f, problem.W.lo), problem.W.top)
            else:
                s = min(math.sin(math.radians(a) / 2.0) * f, 1.0)
                a = min(max(math.degrees(2.0 * math.asin(s)), problem.alpha.lo), problem.alpha.top)
            lays.append(LayerPoints(float(np.asarray(new.n).reshape(-1)[0]), W, a))
        out.append(DesignPoints.of(*lays))
    return out
