"""Vectorised branch and bound that certifies the global optimum of a :class:`Problem`.

The search space of one candidate sheet pair is a box in (n1, W1, alpha1, n2, W2, alpha2); n is
integer and W, alpha are continuous or gridded (identical layers share layer 1's coordinates).
Every iteration treats up to :data:`BATCH` open boxes at once (those with the lowest bounds
inherited from their parent, so the search is best-first when there are many):

1. bound every constrained quantity and the objective over each box
   (:func:`~.quantities.box_bounds`, rigorous);
2. drop a box when some constraint cannot be met anywhere in it, or when its objective bound is
   no better than the incumbent (for mass, the bound is the mass at the box's lower corner);
3. evaluate points of each remaining box exactly with ``evaluate``: every grid point of a grid
   box with at most :data:`ENUMERATE` points (the box is then closed), else its lower corner,
   its upper corner and its centre, snapped to the grid; keep the best feasible one;
4. cut the boxes still open in two along their relatively widest coordinate (and, while there
   are few boxes, into :data:`MULTI_PARTS` along every coordinate when that makes at most
   :data:`MULTI_SPLIT_CHILDREN` boxes, else along every coordinate nearly as wide as the widest),
   cutting grid coordinates between two grid values. All boxes of an iteration go through numpy
   together: the cost of an iteration is mostly fixed, so few iterations of many boxes are
   cheapest.

Certificate. Every design of the original box lies in exactly one box that was either (a) dropped
because a rigorous bound shows it infeasible or no better than the incumbent, (b) a grid box
of at most :data:`ENUMERATE` points, every one of them evaluated exactly, or (c) still open when
the loop stops. The loop stops when no box is
open (gridded problems: the optimum is exact, gap 0) or when every open box's bound is within the
relative tolerance ``gap_rtol`` of the incumbent (continuous problems: no design is better than
the incumbent by more than ``gap_rtol``, proved). If the iteration limit is hit first, or the work
budget of the enclosing :func:`~.budget.budget_scope` is spent (checked before each iteration), the
result is not certified and reports the remaining gap. Interval bounds are rounded outward. On a grid,
points and boxes are judged with the relative slack :data:`~.problem.FEAS_RTOL` (a grid value may
sit exactly on a bound, up to floating-point noise); with continuous variables, with no slack, so
the design meets every bound exactly (margin >= 0). Points and boxes always use the same rule.
The corner bounds of the monotone quantities (extents, thickness, mass) are computed in ordinary
floating point, so they are exact to a few units in the last place, far below both tolerances.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from corrugate.solver.budget import current_budget
from corrugate.solver.problem import FEAS_RTOL, Candidate, DesignVariable, Problem
from corrugate.solver.progress import report
from corrugate.solver.quantities import Tables, box_bounds, point_values

__all__ = ["GAP_RTOL", "BnBResult", "branch_and_bound"]

FloatArray = NDArray[np.float64]

#: Relative optimality gap proved for continuous variables.
GAP_RTOL = 1e-12
#: Limits after which the search stops, uncertified: iterations, boxes bounded, boxes open.
MAX_ITERATIONS = 2_000
MAX_BOXES = 20_000_000
MAX_OPEN = 2_000_000
#: Boxes bounded per iteration; beyond it the lowest bounds go first (best-first).
BATCH = 20_000
#: Below this many open boxes, split along several coordinates at once (fewer iterations).
MULTI_SPLIT_BELOW = 2_000
#: Parts per coordinate in such a split.
MULTI_PARTS = 8
#: Such a split cuts every coordinate when that makes at most this many boxes (grid
#: coordinates may give fewer), else only the coordinates at least half as wide as the widest.
MULTI_SPLIT_CHILDREN = 4096
#: Grid boxes with at most this many points are enumerated (each point evaluated exactly) and
#: closed, instead of being bounded and split further: a point costs far less than a box.
ENUMERATE = 512


@dataclass(frozen=True)
class BnBResult:
    """Outcome for one candidate pair: the best point found (or None), its objective value, the
    proven bound on the optimum (``bound``), whether it is certified, and search statistics."""

    point: dict[str, float] | None
    value: float
    bound: float
    certified: bool
    boxes: int
    iterations: int

    @property
    def gap(self) -> float:
        """Relative gap |value - bound| / |value| (0 when exact; inf without a point)."""
        if self.point is None:
            return 0.0 if self.certified else math.inf
        return abs(self.value - self.bound) / max(abs(self.value), 1e-300)


@dataclass(frozen=True)
class _Dim:
    name: str
    var: DesignVariable  # n is a gridded variable with step 1


def _dims(problem: Problem, n_fixed: tuple[int, int] | None) -> list[_Dim]:
    n_lo, n_hi = (problem.n_lo, problem.n_hi) if n_fixed is None else n_fixed
    n_var = DesignVariable(float(n_lo), float(n_hi), 1.0)
    layer = [("n", n_var), ("W", problem.W), ("a", problem.alpha)]
    layers = (1,) if problem.identical else (1, 2)
    return [_Dim(f"{k}{i}", v) for i in layers for k, v in layer]


def _snap(v: FloatArray, var: DesignVariable, up: bool) -> FloatArray:
    """Grid value at or below (above if ``up``) v; v itself for a continuous variable."""
    if var.step is None:
        return v
    k = (v - var.lo) / var.step
    k = np.ceil(k - 1e-9) if up else np.floor(k + 1e-9)
    return np.asarray(var.lo + var.step * k)


def _split(
    lo: FloatArray,
    hi: FloatArray,
    width: FloatArray,
    dims: list[_Dim],
    multi: bool,
    tag: FloatArray,
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Cut each box along its relatively widest coordinate (``width``: (hi - lo) / lo, with n
    counted as n + 1, so every coordinate is judged by how much it changes across the box) into
    two, and (``multi``) into :data:`MULTI_PARTS` along every coordinate if that makes at most
    :data:`MULTI_SPLIT_CHILDREN` boxes, else along every coordinate at least half as wide as the
    widest (so few boxes become many in few iterations: the per-iteration cost is mostly fixed;
    the case study then takes 2 iterations instead of 3).
    Grid coordinates are cut between two grid values, into at most as many parts as values."""
    widest = width.max(axis=1, keepdims=True)
    if multi:
        split = width > 0  # every coordinate, while the children stay few
        if int((float(MULTI_PARTS) ** split.sum(axis=1)).sum()) > MULTI_SPLIT_CHILDREN:
            split &= width >= 0.5 * widest
    else:
        split = np.zeros(width.shape, dtype=bool)
        split[np.arange(len(width)), np.argmax(width, axis=1)] = True
    parts = MULTI_PARTS if multi else 2
    for i, d in enumerate(dims):
        sel = split[:, i]
        if not sel.any():
            continue
        a, b = lo[sel, i], hi[sel, i]
        j = np.arange(parts + 1, dtype=np.float64)[:, None]  # cut j of parts + 1 (0 and end)
        if d.var.step is None:
            edges = a + (b - a) * (j / parts)
            edges[-1] = b
            starts, ends = edges[:-1], edges[1:]
            valid = np.ones(starts.shape, dtype=bool)
        else:
            k_lo = np.round((a - d.var.lo) / d.var.step)
            k_hi = np.round((b - d.var.lo) / d.var.step)
            count = k_hi - k_lo + 1  # grid values in the box (>= 2 here)
            first = k_lo + np.ceil(j * count / parts)  # first grid index of each part
            starts = d.var.lo + d.var.step * first[:-1]
            ends = d.var.lo + d.var.step * (first[1:] - 1)
            valid = first[1:] > first[:-1]  # a part holds at least one grid value
        # rows: the boxes not cut here, then part by part each cut box's valid parts (no copies
        # of whole boxes per part: one gather, then this coordinate's new edges)
        keep = valid.reshape(-1)
        src = np.concatenate([np.flatnonzero(~sel), np.tile(np.flatnonzero(sel), parts)[keep]])
        first_child = len(lo) - len(a)
        lo, hi = lo[src], hi[src]
        lo[first_child:, i] = starts.reshape(-1)[keep]
        hi[first_child:, i] = ends.reshape(-1)[keep]
        split, tag = split[src], tag[src]
    return lo, hi, tag


def _grid_points(lo: FloatArray, counts: FloatArray, dims: list[_Dim]) -> FloatArray:
    """Every grid point of each box (lower corners ``lo``, ``counts`` grid values per
    coordinate), as rows; values lo + step k exactly as :func:`_split` and :func:`_snap` make."""
    per_box = counts.prod(axis=1).astype(np.int64)
    r = np.arange(int(per_box.sum())) - np.repeat(np.cumsum(per_box) - per_box, per_box)
    out = np.empty((len(r), len(dims)))
    for i in range(len(dims) - 1, -1, -1):  # mixed radix, last coordinate fastest
        var = dims[i].var
        assert var.step is not None
        # per box, then repeated for its points (cheaper than indexing by each point's box)
        c = np.repeat(counts[:, i].astype(np.int64), per_box)
        k0 = np.repeat(np.round((lo[:, i] - var.lo) / var.step), per_box)
        out[:, i] = var.lo + var.step * (k0 + r % c)
        r = r // c
    return out


def _threshold(best: float, tol: float) -> float:
    """Boxes whose bound is below this may still hold a better design."""
    return best if not math.isfinite(best) else best - tol * abs(best)


def _full(x: dict[str, FloatArray], identical: bool) -> dict[str, FloatArray]:
    if identical:
        return {**x, "n2": x["n1"], "W2": x["W1"], "a2": x["a1"]}
    return x


def branch_and_bound(
    problem: Problem,
    c1: Candidate,
    c2: Candidate,
    *,
    incumbent: float | None = None,
    n_fixed: tuple[int, int] | None = None,
    tables: Tables | None = None,
    gap_rtol: float = GAP_RTOL,
) -> BnBResult:
    """Optimise ``problem.objective`` over sheets (c1, c2), certifying the result (see module).

    ``incumbent``: an objective value already reached elsewhere (another sheet pair), used only
    for pruning; the result then holds a point only if it beats it. ``n_fixed``: restrict n
    (n1 for independent layers) to a range.
    """
    tables = tables or Tables(problem)
    maximize = problem.objective.sense == "max"
    sign = -1.0 if maximize else 1.0  # minimise sign * objective
    obj_key = problem.objective.quantity
    dims = _dims(problem, n_fixed)
    cons = problem.constraints
    needed = {c.quantity for c in cons} | {obj_key}
    costly = {q for q in needed if q.directional}  # stiffness and buckling: interval arithmetic
    cheap = needed - costly
    exact = all(d.var.gridded for d in dims)
    tol = 0.0 if exact else gap_rtol
    feas_rtol = FEAS_RTOL if exact else 0.0

    # the queue of open boxes, each with a lower bound on sign * objective (its parent's)
    q_lo = np.array([[d.var.lo for d in dims]])
    q_hi = np.array([[d.var.top for d in dims]])
    q_bound = np.array([-math.inf])
    # relative widths: n counts as n + 1 (the number of facets), W and alpha as themselves
    offset = np.array([1.0 if d.name.startswith("n") else 0.0 for d in dims])
    steps = np.array([d.var.step if d.var.step is not None else math.nan for d in dims])
    best_val = math.inf if incumbent is None else sign * incumbent
    best_pt: dict[str, float] | None = None
    boxes = 0
    it = 0
    width = (q_hi - q_lo) / np.maximum(q_lo + offset, 1e-300)
    if np.any(width > 0):  # bounding the root alone prunes nothing: cut it first
        q_lo, q_hi, q_bound = _split(q_lo, q_hi, width, dims, True, q_bound)
    budget = current_budget()
    while len(q_lo) and it < MAX_ITERATIONS and boxes < MAX_BOXES and len(q_lo) < MAX_OPEN:
        if budget is not None and budget.exhausted:
            break
        it += 1
        waiting = q_bound < _threshold(best_val, tol)
        q_lo, q_hi, q_bound = q_lo[waiting], q_hi[waiting], q_bound[waiting]
        if not len(q_lo):
            break
        report(  # the gap proved so far: best value against the lowest open bound
            it,
            (best_val - float(q_bound.min())) / max(abs(best_val), 1e-300) if best_pt else math.inf,
            sign * best_val if best_pt else None,
        )
        if len(q_lo) > BATCH:  # best-first: the boxes with the lowest bounds go first
            take = np.zeros(len(q_lo), dtype=bool)
            take[np.argpartition(q_bound, BATCH)[:BATCH]] = True
            lo, hi = q_lo[take], q_hi[take]
            q_lo, q_hi, q_bound = q_lo[~take], q_hi[~take], q_bound[~take]
        else:
            lo, hi = q_lo, q_hi
            q_lo, q_hi, q_bound = q_lo[:0], q_hi[:0], q_bound[:0]
        boxes += len(lo)
        if budget is not None:
            budget.charge(len(lo))
        # on grids, a box of at most ENUMERATE grid points has every point evaluated and closes
        if exact:
            counts = np.round((hi - lo) / steps) + 1
            enum = counts.prod(axis=1) <= ENUMERATE
        else:
            counts = lo[:, :0]
            enum = np.zeros(len(lo), dtype=bool)
        # cheap bounds first (extents, thickness, blank, facet, mass: corner values), for all
        xlo = _full({d.name: lo[:, i] for i, d in enumerate(dims)}, problem.identical)
        xhi = _full({d.name: hi[:, i] for i, d in enumerate(dims)}, problem.identical)
        bnd = box_bounds(problem, c1, c2, xlo, xhi, tables, cheap)
        keep = np.ones(len(lo), dtype=bool)
        for c in cons:
            if c.quantity in cheap:
                b_lo, b_hi = bnd[c.quantity]
                keep &= c.satisfied(b_hi if c.sense == "min" else b_lo, rtol=feas_rtol)
        if obj_key in cheap:
            o_lo, o_hi = bnd[obj_key]
            obj_bound = sign * (o_hi if maximize else o_lo)  # lower bound of sign * objective
        else:  # bounded below with the stiffness, for the boxes that get it
            obj_bound = np.full(len(lo), -math.inf)
        # interval (stiffness) bounds only for the boxes that will be split: an enumerated box
        # has all its points evaluated exactly anyway
        sub = keep & ~enum
        if costly and sub.any():
            slo = {k: v[sub] for k, v in xlo.items()}
            shi = {k: v[sub] for k, v in xhi.items()}
            if problem.identical:
                slo, shi = _full(slo, True), _full(shi, True)
            sb = box_bounds(problem, c1, c2, slo, shi, tables, costly)
            ok = np.ones(int(sub.sum()), dtype=bool)
            for c in cons:
                if c.quantity in costly:
                    b_lo, b_hi = sb[c.quantity]
                    ok &= c.satisfied(b_hi if c.sense == "min" else b_lo, rtol=feas_rtol)
            if obj_key in costly:
                o_lo, o_hi = sb[obj_key]
                obj_bound[sub] = sign * (o_hi if maximize else o_lo)
            keep[sub] &= ok
        keep &= obj_bound < _threshold(best_val, tol)
        lo, hi, obj_bound = lo[keep], hi[keep], obj_bound[keep]
        counts, enum = counts[keep], enum[keep]
        if not len(lo):
            continue
        if enum.any():
            every = _grid_points(lo[enum], counts[enum], dims)
            lo, hi, obj_bound = lo[~enum], hi[~enum], obj_bound[~enum]
            # each point is a box of its own: the same cheap bounds (values, there) drop the
            # points that break a cheap constraint or cannot beat the incumbent, before the
            # full evaluation
            e = _full({d.name: every[:, i] for i, d in enumerate(dims)}, problem.identical)
            eb = box_bounds(problem, c1, c2, e, e, tables, cheap)
            ok = np.ones(len(every), dtype=bool)
            for c in cons:
                if c.quantity in cheap:
                    b_lo, b_hi = eb[c.quantity]
                    ok &= c.satisfied(b_hi if c.sense == "min" else b_lo, rtol=feas_rtol)
            if obj_key in cheap:
                o_lo, o_hi = eb[obj_key]
                ok &= sign * (o_hi if maximize else o_lo) < _threshold(best_val, tol)
            every = every[ok]
        else:
            every = lo[:0]
        # candidate points of the others: lower corner, upper corner, centre (snapped to the grid)
        mid = np.stack(
            [_snap(0.5 * (lo[:, i] + hi[:, i]), d.var, up=False) for i, d in enumerate(dims)],
            axis=1,
        )
        mid = np.clip(mid, lo, hi)
        pts = np.concatenate([every, lo, hi, mid])
        if len(pts):
            x = _full({d.name: pts[:, i] for i, d in enumerate(dims)}, problem.identical)
            vals = point_values(problem, c1, c2, x, tables)
            ok = np.ones(len(pts), dtype=bool)
            for c in cons:  # continuous: exact feasibility (margins >= 0); grids: FEAS_RTOL
                ok &= c.satisfied(vals[c.quantity], rtol=feas_rtol)
            f = np.where(ok, sign * vals[obj_key], np.inf)
            k = int(np.argmin(f))
            if f[k] < best_val:
                best_val = float(f[k])
                best_pt = {name: float(v[k]) for name, v in x.items()}
        keep = obj_bound < _threshold(best_val, tol)
        lo, hi, obj_bound = lo[keep], hi[keep], obj_bound[keep]
        # close single grid points; split the rest and queue the halves with their bound
        width = (hi - lo) / np.maximum(lo + offset, 1e-300)
        point = np.all(width <= 0, axis=1)
        lo, hi, obj_bound = lo[~point], hi[~point], obj_bound[~point]
        if not len(lo):
            continue
        multi = len(lo) + len(q_lo) < MULTI_SPLIT_BELOW
        lo, hi, obj_bound = _split(lo, hi, width[~point], dims, multi, obj_bound)
        q_lo = np.concatenate([q_lo, lo])
        q_hi = np.concatenate([q_hi, hi])
        q_bound = np.concatenate([q_bound, obj_bound])
    q_open = q_bound < _threshold(best_val, tol)
    if q_open.any():  # stopped early: the bound is the best open box's
        global_bound = float(np.min(q_bound[q_open]))
        certified = False
    else:
        certified = True
        global_bound = best_val if best_pt is not None else math.inf
        if best_pt is not None and not exact:
            global_bound = best_val - gap_rtol * abs(best_val)
    value = sign * best_val if best_pt is not None else math.nan
    return BnBResult(best_pt, value, sign * min(global_bound, best_val), certified, boxes, it)
