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

Memory. Both functions work on at most :func:`chunk` points or boxes at once and concatenate
the results (every value is elementwise in the points, so the answer is the same): an
evaluation's temporaries take about 0.5 kB per point nominally and 8.5 kB per point or box
under the worst-case tolerances (the thickness in :data:`~.tolerance_box.T_PIECES` pieces;
measured with ``tracemalloc`` on the chassis plate's quantities, 10^4 and 10^5 random points),
so a search's millions of grid points stay within a few tens of MB (docs/tolerances.md).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from corrugate.mechanics.behaviours import support_names
from corrugate.solver import (  # noqa: F401  (they register the kinds)
    making,
    sizes,
    stiffness,
    sustained,
    tolerance_box,
    validity,
)
from corrugate.solver.context import AtPoints, OverBoxes, layer_corner
from corrugate.solver.evaluator import evaluators, generation
from corrugate.solver.points import DesignPoints
from corrugate.solver.problem import Candidate, Problem
from corrugate.solver.quantity import Quantity
from corrugate.solver.tables import RangeTable, Tables

__all__ = [
    "CHUNK_ROWS",
    "TOLERANCE_ROWS",
    "RangeTable",
    "Tables",
    "box_bounds",
    "chunk",
    "layer_corner",
    "point_values",
    "reported",
]

FloatArray = NDArray[np.float64]
Bounds = dict[Quantity, tuple[FloatArray, FloatArray]]


def reported(problem: Problem) -> list[Quantity]:
    """The quantities :func:`point_values` gives for ``problem``: each evaluator's (the sizes
    and mass always, EI, D and K at every direction of the problem under free sides and each
    support asked for, the length along each, both buckling loads once one is asked for, the
    rest as asked). Kept on the (frozen) problem while the registries it is read from, the
    evaluators' and the support conditions', are unchanged (:func:`_registries`)."""
    key = _registries()
    kept = problem.__dict__.get(_REPORTED)
    if kept is not None and kept[0] == key:
        return list(kept[1])
    got = tuple(dict.fromkeys(q for e in evaluators() for q in e.quantities(problem)))
    object.__setattr__(problem, _REPORTED, (key, got))  # a cache, not a field (as cached_property)
    return list(got)


#: The attribute of a problem that keeps its :func:`reported` quantities.
_REPORTED = "_reported_quantities"


def _registries() -> tuple[int, tuple[str, ...]]:
    """What :func:`reported` reads besides the problem: the evaluator registry's generation
    (:func:`~.evaluator.generation`) and the support conditions' names (the stiffness
    evaluator reports each support a problem asks for that is registered)."""
    return generation(), support_names()


def _covered_any(problem: Problem) -> bool:
    """Whether some quantity of ``problem`` is bounded over the tolerance box (kept on the
    problem: it reads only its fields)."""
    kept = problem.__dict__.get(_COVERED)
    if kept is None:
        kept = any(tolerance_box.covered(problem, q) for q in problem.quantities)
        object.__setattr__(problem, _COVERED, kept)
    return bool(kept)


#: The attribute of a problem that keeps :func:`_covered_any`.
_COVERED = "_covered_any"


#: Rows of arithmetic evaluated at once: a nominal point or box is one row (about 0.5 kB of
#: temporaries, module docstring), so 2^16 rows are some 35-60 MB.
CHUNK_ROWS = 1 << 16
#: Rows a point or box takes under worst-case tolerances: 8.5 kB against 0.5 kB nominally
#: (the thickness in :data:`~.tolerance_box.T_PIECES` pieces, module docstring).
TOLERANCE_ROWS = 16


def chunk(problem: Problem) -> int:
    """Points or boxes :func:`point_values` and :func:`box_bounds` take at once for
    ``problem``: :data:`CHUNK_ROWS` over the rows each takes."""
    if _covered_any(problem):
        return CHUNK_ROWS // TOLERANCE_ROWS
    return CHUNK_ROWS


def _sliceable(x: DesignPoints) -> bool:
    """Whether every field of every stored layer of ``x`` is an array of one value per point
    (so slices of the points are slices of each array)."""
    n = len(x)
    return all(
        v is None or (np.ndim(v) == 1 and np.size(v) == n)
        for lay in x.layers
        for v in (lay.n, lay.W, lay.alpha, lay.E, lay.t)
    )


def _pieces(size: int, step: int) -> list[slice]:
    return [slice(a, min(a + step, size)) for a in range(0, size, step)]


def _joined(parts: list[dict[Quantity, Any]], counts: list[int]) -> dict[Quantity, Any]:
    """The per-chunk dicts of arrays (or pairs of arrays) joined along the points."""

    def flat(values: list[Any]) -> FloatArray:
        return np.concatenate(
            [
                np.broadcast_to(np.asarray(v, np.float64), (k,))
                for v, k in zip(values, counts, strict=True)
            ]
        )

    out: dict[Quantity, Any] = {}
    for q, first in parts[0].items():
        if isinstance(first, tuple):
            out[q] = (flat([p[q][0] for p in parts]), flat([p[q][1] for p in parts]))
        else:
            out[q] = flat([p[q] for p in parts])
    return out


def point_values(
    problem: Problem,
    c1: Candidate,
    c2: Candidate,
    x: DesignPoints,
    tables: Tables,
    only: frozenset[Quantity] | None = None,
) -> dict[Quantity, FloatArray]:
    """Exact values of the quantities :func:`reported` for ``problem`` (``only``: those of
    them in it) at the points ``x`` (arrays over the points) on sheets (c1, c2), each by its
    evaluator; at most :func:`chunk` points at once (module docstring)."""
    step = chunk(problem)
    if len(x) <= step or not _sliceable(x):
        return _point_values(problem, c1, c2, x, tables, only)
    cuts = _pieces(len(x), step)
    parts = [_point_values(problem, c1, c2, x.take(s), tables, only) for s in cuts]
    return _joined(parts, [s.stop - s.start for s in cuts])


def _point_values(
    problem: Problem,
    c1: Candidate,
    c2: Candidate,
    x: DesignPoints,
    tables: Tables,
    only: frozenset[Quantity] | None = None,
) -> dict[Quantity, FloatArray]:
    at = AtPoints(problem, c1, c2, x, tables)
    covered = [
        q
        for q in (problem.quantities if _covered_any(problem) else ())
        if tolerance_box.covered(problem, q) and (only is None or q in only)
    ]
    worst: dict[Quantity, FloatArray] = {}
    if covered:  # their worst case over the tolerance box (docs/tolerances.md)
        tol = tolerance_box.ToleranceBounds(problem, c1, c2, x, x, tables)
        worst = {q: np.asarray(tol.bounds(q)[0]) for q in covered}
    # a covered quantity's nominal value is not computed: its worst case replaces it
    out = {
        q: worst[q] if q in worst else at.value(q)
        for q in reported(problem)
        if only is None or q in only
    }
    out.update(worst)
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
    the values at points, each computed once), each by its evaluator, in a fixed order; at
    most :func:`chunk` boxes at once (module docstring)."""
    step = chunk(problem)
    if len(lo) <= step or not (_sliceable(lo) and (hi is lo or _sliceable(hi))):
        return _box_bounds(problem, c1, c2, lo, hi, tables, quantities)
    cuts = _pieces(len(lo), step)
    parts = []
    for s in cuts:
        slo = lo.take(s)
        parts.append(
            _box_bounds(problem, c1, c2, slo, slo if hi is lo else hi.take(s), tables, quantities)
        )
    return _joined(parts, [s.stop - s.start for s in cuts])


def _box_bounds(
    problem: Problem,
    c1: Candidate,
    c2: Candidate,
    lo: DesignPoints,
    hi: DesignPoints,
    tables: Tables,
    quantities: set[Quantity],
) -> Bounds:
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
