"""Bounds of the directional quantities over the worst-case tolerance box (docs/tolerances.md).

With a problem's :class:`~.worst_case.WorstCase` tolerances (fold angle +-da deg, facet width
+-dW mm, thickness and Young's modulus +-dt, +-dE relative), the value the solver certifies of
a directional quantity q (a stiffness, a load case's P / delta or capacity, a buckling load, the
panel's length: every such constraint is a lower bound, ``Problem.from_spec``) at a design x is

    G(x) = the lower bound of q over the tolerance box T(x),

T(x) the designs with each layer's W in [W - dW, W + dW] and alpha in [alpha - da, alpha + da]
(each layer on its own: identical layers are bounded as two independent layers of one sheet),
n exact, and sheets whose E and t are the intervals [E (1 - dE), E (1 + dE)] and
[t (1 - dt), t (1 + dt)]. It is computed by the quantity's own bounds over boxes
(:class:`~.context.OverBoxes`, the interval arithmetic of :mod:`~.interval_springs` with E and t
as :class:`~.interval.Interval` values), so G(x) <= q(x') for every x' in T(x): a design with
G(x) >= bound meets the bound at every corner of its tolerance box (and everywhere inside).

Over a search box B the bounds of G are those of q over B widened by the tolerances: the interval
enclosure over B + T contains every T(x) of x in B (inclusion isotonicity), so its lower bound is
at most every G(x) and its upper bound at least every q(x) >= G(x). At a point box they are G(x)
itself. The sizes, the mass and the making stay nominal (docs/tolerances.md says why).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
from numpy.typing import NDArray

from corrugate.solver.context import OverBoxes
from corrugate.solver.interval import Interval
from corrugate.solver.points import DesignPoints, LayerPoints
from corrugate.solver.problem import Candidate, Problem
from corrugate.solver.quantity import Quantity
from corrugate.solver.tables import Tables
from corrugate.solver.worst_case import WorstCase

__all__ = ["T_PIECES", "ToleranceBounds", "covered", "sheet", "tolerance_boxes", "widened"]

FloatArray = NDArray[np.float64]

#: The fold angles a widened box stays within (deg): the zig-zag's 0 < alpha < 180.
_ALPHA_MIN, _ALPHA_MAX = 1e-3, 180.0 - 1e-3


def covered(problem: Problem, q: Quantity) -> bool:
    """Whether ``q`` is bounded over the tolerance box (a directional quantity under
    tolerances that are not nominal)."""
    return q.eta is not None and not problem.tolerances.nominal


def sheet(c: Candidate, tol: WorstCase, pieces: int = 1, rows: int = 1) -> Candidate:
    """The sheet ``c`` with E (MPa) and t (mm) as intervals over the tolerances (floats when a
    half-width is 0); with ``pieces`` > 1, t's interval cut into that many equal pieces, each
    repeated for ``rows`` boxes (an array of ``pieces * rows`` intervals, piece by piece)."""
    m = c.material
    E = Interval(m.E * (1 - tol.E), m.E * (1 + tol.E)) if tol.E else m.E
    t: object = c.t
    if tol.t:
        edges = np.linspace(c.t * (1 - tol.t), c.t * (1 + tol.t), pieces + 1)
        t = Interval(np.repeat(edges[:-1], rows), np.repeat(edges[1:], rows))
        if pieces == 1 and rows == 1:
            t = Interval(float(edges[0]), float(edges[1]))
    return replace(c, material=replace(m, E=E), t=t)  # type: ignore[arg-type]


def _widen(lay: LayerPoints, tol: WorstCase, up: bool) -> LayerPoints:
    s = 1.0 if up else -1.0
    W = np.asarray(lay.W, np.float64) + s * tol.W
    a = np.asarray(lay.alpha, np.float64) + s * tol.alpha
    W = np.maximum(W, 1e-6)  # a facet width stays positive (W >= min_facet >> dW in practice)
    a = np.clip(a, _ALPHA_MIN, _ALPHA_MAX)
    return LayerPoints(np.asarray(lay.n, np.float64), W, a)


def widened(
    problem: Problem, lo: DesignPoints, hi: DesignPoints
) -> tuple[DesignPoints, DesignPoints]:
    """The boxes [lo, hi] widened by the tolerances of ``problem``, every layer stored (so
    identical layers vary independently)."""
    tol = problem.tolerances
    count = lo.count
    lows = [_widen(lo.layer(i), tol, False) for i in range(count)]
    highs = [_widen(hi.layer(i), tol, True) for i in range(count)]
    return DesignPoints(tuple(lows), count), DesignPoints(tuple(highs), count)


#: The pieces the thickness interval is cut into at points (their worst case is the least of
#: the pieces'): t appears in many terms of the springs (t and t^3), so one interval
#: over-reaches (docs/tolerances.md gives the measured effect); boxes take it whole.
T_PIECES = 8


class ToleranceBounds:
    """The bounds over the boxes [lo, hi] (``lo is hi``: points) widened by the tolerances
    (module docstring): :meth:`bounds` of a quantity, the least and the greatest over the
    thickness's pieces."""

    def __init__(
        self,
        problem: Problem,
        c1: Candidate,
        c2: Candidate,
        lo: DesignPoints,
        hi: DesignPoints,
        tables: Tables,
    ) -> None:
        tol = problem.tolerances
        k = len(lo)
        # the pieces at points only: a box's bounds need not be tight, only enclose (the one
        # interval of t contains every piece, so its lower bound is at most theirs)
        self.pieces = T_PIECES if tol.t and lo is hi else 1
        self.rows = k
        wlo, whi = widened(problem, lo, hi)
        if self.pieces > 1:  # every box once per piece of t, piece by piece
            rep = np.tile(np.arange(k), self.pieces)
            wlo, whi = wlo.take(rep), whi.take(rep)
        s1 = sheet(c1, tol, self.pieces, k)
        s2 = s1 if c2 == c1 else sheet(c2, tol, self.pieces, k)
        free = replace(problem, identical=False) if problem.identical else problem
        self.over = OverBoxes(free, s1, s2, wlo, whi, tables)

    def bounds(self, q: Quantity) -> tuple[FloatArray, FloatArray]:
        """Lower and upper bounds of ``q`` over the widened boxes (arrays over the boxes)."""
        low, high = self.over.bounds(q)
        shape = (self.pieces, self.rows)
        low = np.broadcast_to(np.asarray(low, np.float64), (self.pieces * self.rows,))
        high = np.broadcast_to(np.asarray(high, np.float64), (self.pieces * self.rows,))
        return low.reshape(shape).min(axis=0), high.reshape(shape).max(axis=0)


def tolerance_boxes(
    problem: Problem,
    c1: Candidate,
    c2: Candidate,
    lo: DesignPoints,
    hi: DesignPoints,
    tables: Tables,
) -> ToleranceBounds:
    """The boxes [lo, hi] (``lo is hi``: points) widened by the tolerances, on sheets whose E
    and t are intervals (one object per distinct sheet), with identical layers bounded as
    independent ones (module docstring)."""
    return ToleranceBounds(problem, c1, c2, lo, hi, tables)
