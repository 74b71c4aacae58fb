"""The quantities constraints bound: exact values at points, rigorous bounds over boxes.

Points and boxes are :class:`~.points.DesignPoints` (per layer: creases n, facet width W in mm,
fold angle alpha in deg); identical layers are one stored layer.

Both functions here are loops over the registry of evaluators (:mod:`~.evaluator`: one per
quantity kind, its point values and its box bounds side by side), on what the quantities of a
problem share (:mod:`~.context`):

* :func:`point_values`: the exact values of a problem's quantities at points, read from
  :func:`corrugate.analysis.evaluate.evaluate` (the one implementation of the model), so a design
  the solver accepts is exactly the design ``analyze`` reports;
* :func:`box_bounds`: for each quantity asked, a lower and an upper bound valid for every design
  in a box ``lo <= x <= hi`` (elementwise over many boxes; ``lo is hi``: the values at points).
  Why each bound holds is said by its evaluator's module: the sizes and the mass
  (:mod:`~.sizes`: monotone, their values at the corners), the making (:mod:`~.making`), the
  stiffness, length, buckling load and load cases (:mod:`~.stiffness`: interval arithmetic on
  the layers' springs, :mod:`~.interval_springs`).

Interval bounds converge to the exact value as the box shrinks, which is what makes branch and
bound terminate.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from corrugate.solver import (  # noqa: F401  (they register the kinds)
    making,
    sizes,
    stiffness,
    sustained,
    tolerance_box,
    validity,
)
from corrugate.solver.context import AtPoints, OverBoxes, layer_corner
from corrugate.solver.evaluator import evaluators
from corrugate.solver.points import DesignPoints
from corrugate.solver.problem import Candidate, Problem
from corrugate.solver.quantity import Quantity
from corrugate.solver.tables import RangeTable, Tables

__all__ = ["RangeTable", "Tables", "box_bounds", "layer_corner", "point_values", "reported"]

FloatArray = NDArray[np.float64]
Bounds = dict[Quantity, tuple[FloatArray, FloatArray]]


def reported(problem: Problem) -> list[Quantity]:
    """The quantities :func:`point_values` gives for ``problem``: each evaluator's (the sizes
    and mass always, EI, D and K at every direction of the problem under free sides and each
    support asked for, the length along each, both buckling loads once one is asked for, the
    rest as asked)."""
    return list(dict.fromkeys(q for e in evaluators() for q in e.quantities(problem)))


def point_values(
    problem: Problem, c1: Candidate, c2: Candidate, x: DesignPoints, tables: Tables
) -> dict[Quantity, FloatArray]:
    """Exact values of the quantities :func:`reported` for ``problem`` at the points ``x``
    (arrays over the points) on sheets (c1, c2), each by its evaluator."""
    at = AtPoints(problem, c1, c2, x, tables)
    out = {q: at.value(q) for q in reported(problem)}
    covered = [q for q in problem.quantities if tolerance_box.covered(problem, q)]
    if covered:  # their worst case over the tolerance box (docs/tolerances.md)
        tol = tolerance_box.ToleranceBounds(problem, c1, c2, x, x, tables)
        for q in covered:
            out[q] = np.asarray(tol.bounds(q)[0])
    return out


def box_bounds(
    problem: Problem,
    c1: Candidate,
    c2: Candidate,
    lo: DesignPoints,
    hi: DesignPoints,
    tables: Tables,
    quantities: set[Quantity],
) -> Bounds:
    """Lower and upper bounds of the requested ``quantities`` over boxes [lo, hi] (``lo is hi``:
    the values at points, each computed once), each by its evaluator, in a fixed order."""
    over = OverBoxes(problem, c1, c2, lo, hi, tables)
    tol: tolerance_box.ToleranceBounds | None = None
    out: Bounds = {}
    for q in sorted(quantities, key=_order):
        if not tolerance_box.covered(problem, q):
            out[q] = over.bounds(q)
            continue
        if tol is None:  # the boxes widened by the tolerances (docs/tolerances.md)
            tol = tolerance_box.ToleranceBounds(problem, c1, c2, lo, hi, tables)
        low, high = tol.bounds(q)
        out[q] = (low, low) if over.point else (low, high)
    return out


def _order(q: Quantity) -> tuple[bool, str, float, str, str, float]:
    """A fixed order: the quantities without a direction, then the others (the layout's coupon
    is made at the first stiffness that reads it, :meth:`~.context.OverBoxes.coupon`)."""
    return (q.directional, q.kind, q.eta or 0.0, q.support or "", q.test or "", q.duration or 0.0)
