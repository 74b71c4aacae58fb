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

A plain search (no start boxes, no archive, no n fixed, no runner-ups, no early stop) of a problem
whose independent layers decompose (:mod:`.separable`: a rectangle, gridded, least mass, bounds
along the creases) is made layer by layer instead, with the same certificate (gap 0 on the grid,
the same feasibility rule); the explanation, which reopens this search's archive, still runs the
branch and bound.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import NDArray

from corrugate.solver import separable
from corrugate.solver.budget import current_budget
from corrugate.solver.making import MAKING
from corrugate.solver.points import VARIABLES, Coordinate, DesignPoints, LayerPoints, coordinates
from corrugate.solver.problem import FEAS_RTOL, Candidate, Constraint, DesignVariable, Problem
from corrugate.solver.progress import report
from corrugate.solver.quantities import Tables, box_bounds, layer_corner, point_values
from corrugate.solver.quantity import LX, LY, Quantity

__all__ = ["GAP_RTOL", "Archive", "BnBResult", "branch_and_bound"]

FloatArray = NDArray[np.float64]

#: Relative optimality gap proved for continuous variables.
GAP_RTOL = 1e-12
#: Limits after which the search stops, uncertified: iterations, boxes bounded, boxes open.
MAX_ITERATIONS = 2_000
MAX_BOXES = 20_000_000
MAX_OPEN = 2_000_000
#: Boxes bounded per iteration; beyond it the lowest bounds go first (best-first).
BATCH = 20_000
#: The first batch of a search that stops at its first better design (``stop_below``).
FIRST_BATCH = 64
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

    point: DesignPoints | None
    value: float
    bound: float
    certified: bool
    boxes: int
    iterations: int
    #: the closed boxes (``record``), None otherwise
    archive: Archive | None = None
    #: ``per_n``: the best design for each n1, as a result of its own
    by_n: dict[int, BnBResult] | None = None

    @property
    def gap(self) -> float:
        """Relative gap |value - bound| / |value| (0 when exact; inf without a point)."""
        if self.point is None:
            return 0.0 if self.certified else math.inf
        return abs(self.value - self.bound) / max(abs(self.value), 1e-300)


_Dim = Coordinate  # one coordinate of the search (n is a gridded variable with step 1)


def _dims(problem: Problem, n_fixed: tuple[int, int] | None) -> list[_Dim]:
    return coordinates(problem, n_fixed)


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
        if int((float(MULTI_PARTS) ** split.sum(axis=1)).sum()) > BATCH:
            multi = False  # still too many children for one batch: halve along the widest
    if not multi:
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


def _enumerate(
    problem: Problem, lo: FloatArray, counts: FloatArray, dims: list[_Dim], rtol: float
) -> tuple[FloatArray, NDArray[np.int64], list[tuple[NDArray[np.int64], NDArray[np.bool_]]]]:
    """The grid points of each box (:func:`_grid_points`, same order) with the box each lies
    in, less those that break a bound of one layer alone, which are found per layer.

    With independent layers the extents decompose: Lx is layer 1's own (n1 + 1) W1 sin(a1/2)
    and Ly layer 2's (:func:`~.quantities.box_bounds`, the same arithmetic), so a box of
    k1 x k2 points needs k1 + k2 extents to drop every pair with a layer outside its side
    range, before the pairs are formed. Returns the points, their boxes, and per layer the
    dropped layer points' boxes and broken constraints (points x constraints; a dropped pair
    breaks at least its layer's)."""
    cons = problem.constraints
    per_layer = [[i for i, c in enumerate(cons) if c.quantity == q] for q in (LX, LY)]
    nbox = len(lo)
    if len({d.layer for d in dims}) != 2 or not any(per_layer):
        every = _grid_points(lo, counts, dims)
        owner = np.repeat(np.arange(nbox), counts.prod(axis=1).astype(np.int64))
        return every, owner, []
    kept: list[NDArray[np.int64]] = []
    sizes: list[NDArray[np.int64]] = []
    pts: list[FloatArray] = []
    dropped: list[tuple[NDArray[np.int64], NDArray[np.bool_]]] = []
    per = len(VARIABLES)
    for layer, idx in enumerate(per_layer):
        cols = slice(per * layer, per * layer + per)
        g = _grid_points(lo[:, cols], counts[:, cols], dims[cols])
        own = np.repeat(np.arange(nbox), counts[:, cols].prod(axis=1).astype(np.int64))
        ext = layer_corner(LayerPoints(*(g[:, j] for j in range(per)))).extent
        broken = np.zeros((len(g), len(cons)), dtype=bool)
        for k in idx:
            broken[:, k] = ~cons[k].satisfied(ext, rtol=rtol)
        ok = ~broken.any(axis=1)
        dropped.append((own[~ok], broken[~ok]))
        s = np.flatnonzero(ok)
        kept.append(s)
        sizes.append(np.bincount(own[s], minlength=nbox))
        pts.append(g)
    k1, k2 = sizes
    per_box = k1 * k2
    box = np.repeat(np.arange(nbox), per_box)
    r = np.arange(int(per_box.sum())) - np.repeat(np.cumsum(per_box) - per_box, per_box)
    i1 = kept[0][(np.cumsum(k1) - k1)[box] + r // k2[box]]
    i2 = kept[1][(np.cumsum(k2) - k2)[box] + r % k2[box]]
    return np.concatenate([pts[0][i1], pts[1][i2]], axis=1), box, dropped


def _threshold(best: float, tol: float) -> float:
    """Boxes whose bound is below this may still hold a better design."""
    return best if not math.isfinite(best) else best - tol * abs(best)


def _thresholds(best: FloatArray, tol: float) -> FloatArray:
    """:func:`_threshold` of each incumbent (one per slot)."""
    with np.errstate(invalid="ignore"):
        return np.where(np.isfinite(best), best - tol * np.abs(best), best)


#: Rows the archive of a search keeps at most (about 110 bytes each for 6 coordinates): past
#: it the archive is dropped and the explanation re-solves instead.
ARCHIVE_ROWS = 1_000_000
#: The archive keeps boxes shown to break at most this many constraints (what the explanation
#: relaxes at once: one for the binding checks, two for the diagnosis' partners and pairs).
ARCHIVE_DEPTH = 2


@dataclass(frozen=True)
class Archive:
    """The closed boxes of a finished search, in flat arrays, for the explanation to reopen.

    Row k is a box ``lo[k] <= x <= hi[k]`` (the search's coordinates, :func:`_dims`) with
    ``bound[k]`` a lower bound of sign * objective over it (-inf when none was computed) and
    ``mask[k]`` a bit set of constraints (bit i: ``problem.constraints[i]``) each shown to be
    broken by every design of the box, or, for a box whose points were each evaluated, by some
    of its points. The boxes of a search cover its whole domain; the archive holds all of them
    except those shown to break more than :data:`ARCHIVE_DEPTH` constraints. So the designs
    that meet every constraint but those of a set R lie in the rows with ``mask`` inside R
    (:meth:`reopen`), and those better than the incumbent in the rows whose bound is below it.
    The mask of a box may miss constraints that were not bounded on it (a smaller mask reopens
    more, never less).
    """

    lo: FloatArray
    hi: FloatArray
    bound: FloatArray
    mask: NDArray[np.uint64]

    def reopen(
        self, relaxed: int = 0, below: float = math.inf
    ) -> tuple[FloatArray, FloatArray, FloatArray]:
        """The boxes (lo, hi, bound) that may hold a design meeting every constraint outside the
        bit set ``relaxed`` with sign * objective below ``below``."""
        sel = (self.mask & ~np.uint64(relaxed)) == 0
        if math.isfinite(below):
            sel &= self.bound < below
        return self.lo[sel], self.hi[sel], self.bound[sel]


class _Recorder:
    """Collects the closed boxes of a search into an :class:`Archive` (chunks of flat arrays)."""

    def __init__(self, ncons: int) -> None:
        self.ok = ncons <= 63
        self.bits = np.uint64(1) << np.arange(max(ncons, 1), dtype=np.uint64)
        self.parts: list[tuple[FloatArray, FloatArray, FloatArray, NDArray[np.uint64]]] = []
        self.rows = 0

    def masks(self, broken: NDArray[np.bool_]) -> tuple[NDArray[np.uint64], NDArray[np.bool_]]:
        """Bit sets of the rows of ``broken`` (boxes x constraints), and which rows to keep."""
        if not broken.shape[1]:
            return np.zeros(len(broken), dtype=np.uint64), np.ones(len(broken), dtype=bool)
        mask = np.bitwise_or.reduce(np.where(broken, self.bits, np.uint64(0)), axis=1)
        return mask, broken.sum(axis=1) <= ARCHIVE_DEPTH

    def add(
        self,
        lo: FloatArray,
        hi: FloatArray,
        bound: FloatArray,
        mask: NDArray[np.uint64] | None = None,
    ) -> None:
        if not self.ok or not len(lo):
            return
        if mask is None:
            mask = np.zeros(len(lo), dtype=np.uint64)
        self.rows += len(lo)
        if self.rows > ARCHIVE_ROWS:  # memory bounded: no archive (the explanation re-solves)
            self.ok = False
            self.parts = []
            return
        self.parts.append((lo, hi, np.broadcast_to(bound, (len(lo),)).copy(), mask))

    def add_points(
        self,
        lo: FloatArray,
        hi: FloatArray,
        bound: FloatArray,
        owner: NDArray[np.int64],
        mask: NDArray[np.uint64],
        value: FloatArray,
    ) -> None:
        """Enumerated boxes (lo, hi, bound) from their points: point k lies in box ``owner[k]``,
        breaks the constraints of ``mask[k]`` and has sign * objective >= ``value[k]``. One row
        per box and bit set, bounded by the least value of its points."""
        if not self.ok or not len(owner):
            return
        masks, m_id = np.unique(mask, return_inverse=True)  # few distinct bit sets
        key = owner.astype(np.int64) * len(masks) + m_id.reshape(-1)
        # a dense (box, bit set) table instead of sorting the keys: the same rows, in key order
        table = np.full(len(lo) * len(masks), np.inf)
        np.minimum.at(table, key, value)
        seen = np.zeros(len(table), dtype=bool)
        seen[key] = True
        groups = np.flatnonzero(seen)
        least = table[groups]
        b = groups // len(masks)
        self.add(lo[b], hi[b], np.maximum(bound[b], least), masks[groups % len(masks)])

    def archive(self, ndim: int) -> Archive | None:
        if not self.ok:
            return None
        if not self.parts:
            e = np.empty((0, ndim))
            return Archive(e, e, np.empty(0), np.empty(0, dtype=np.uint64))
        return Archive(*(np.concatenate(c) for c in zip(*self.parts, strict=True)))


def _broken(
    cons: tuple[Constraint, ...],
    values: dict[Quantity, tuple[FloatArray, FloatArray]] | dict[Quantity, FloatArray],
    which: set[Quantity],
    rows: int,
    rtol: float,
) -> NDArray[np.bool_]:
    """(rows x constraints): constraint i is shown broken on the row by the bounds (or values)
    ``values`` (only the constraints on ``which`` quantities; the others are left False)."""
    out = np.zeros((rows, len(cons)), dtype=bool)
    for i, c in enumerate(cons):
        if c.quantity in which:
            v = values[c.quantity]
            if isinstance(v, tuple):
                v = v[1] if c.sense == "min" else v[0]
            out[:, i] = ~c.satisfied(v, rtol=rtol)
    return out


def _cheap_bounds(
    problem: Problem,
    c1: Candidate,
    c2: Candidate,
    lo: DesignPoints,
    hi: DesignPoints,
    tables: Tables,
    cheap: set[Quantity],
    rtol: float,
    objective: Quantity,
) -> tuple[dict[Quantity, tuple[FloatArray, FloatArray]], NDArray[np.bool_]]:
    """Bounds of the ``cheap`` quantities over the boxes (``lo is hi``: at points) and which
    constraints they show broken (:func:`_broken`): the sizes and the mass for every box first,
    then the making's part sizes (:mod:`.making`, the costliest of them) only for the boxes
    those leave (the others get no bounds of them: their constraints count as not shown
    broken). The ``objective``'s bounds are always there (it goes first)."""
    cons = problem.constraints
    then = (cheap & MAKING) - {objective}
    first = cheap - then
    if not then or not first:
        bnd = box_bounds(problem, c1, c2, lo, hi, tables, cheap)
        return bnd, _broken(cons, bnd, cheap, len(lo), rtol)
    bnd = box_bounds(problem, c1, c2, lo, hi, tables, first)
    broken = _broken(cons, bnd, first, len(lo), rtol)
    alive = ~broken.any(axis=1)
    if alive.any():
        slo = lo.take(alive)
        shi = slo if hi is lo else hi.take(alive)
        more = box_bounds(problem, c1, c2, slo, shi, tables, then)
        broken[alive] |= _broken(cons, more, then, int(alive.sum()), rtol)
    return bnd, broken


def _by_layer(
    problem: Problem,
    c1: Candidate,
    c2: Candidate,
    incumbent: float | None,
    tables: Tables,
) -> BnBResult | None:
    """The search of independent layers layer by layer (:mod:`.separable`), certified as the
    branch and bound's on a grid (gap 0, the same feasibility rule, FEAS_RTOL), as a
    :class:`BnBResult` (``boxes``: the pairs of layer designs scored; ``iterations``: 1); None
    when the problem lacks that structure. Not inside a spent budget (then the branch and bound
    reports the stop)."""
    budget = current_budget()
    if (budget is not None and budget.exhausted) or not separable.applies(problem):
        return None
    cons = problem.constraints
    needed = {c.quantity for c in cons} | {problem.objective.quantity}

    def exact(x: DesignPoints) -> tuple[FloatArray, NDArray[np.bool_]]:
        vals = point_values(problem, c1, c2, x, tables)
        ok = ~_broken(cons, vals, needed, len(x), FEAS_RTOL).any(axis=1)
        return vals[problem.objective.quantity], np.asarray(ok, dtype=bool)

    r = separable.search(problem, c1, c2, incumbent, exact)
    if r is None:
        return None
    if budget is not None:
        budget.charge(r.scored)
    report(1, 0.0, None if r.point is None else r.value)
    if r.point is None:
        return BnBResult(None, math.nan, math.inf, True, r.scored, 1)
    return BnBResult(r.point, r.value, r.value, True, r.scored, 1)


def branch_and_bound(
    problem: Problem,
    c1: Candidate,
    c2: Candidate,
    *,
    incumbent: float | None = None,
    n_fixed: tuple[int, int] | None = None,
    tables: Tables | None = None,
    gap_rtol: float = GAP_RTOL,
    start: tuple[FloatArray, FloatArray, FloatArray] | None = None,
    record: bool = False,
    per_n: tuple[int, int] | None = None,
    stop_below: float | None = None,
) -> BnBResult:
    """Optimise ``problem.objective`` over sheets (c1, c2), certifying the result (see module).

    ``incumbent``: an objective value already reached elsewhere (another sheet pair), used only
    for pruning; the result then holds a point only if it beats it. ``n_fixed``: restrict n
    (n1 for independent layers) to a range. ``start``: the open boxes (lo, hi, lower bound of
    sign * objective) to search instead of the whole domain (boxes reopened from an
    :class:`Archive`; their union must hold every design the answer is about). ``record``: keep
    the closed boxes in ``BnBResult.archive`` (None if the search was not certified or the
    archive outgrew :data:`ARCHIVE_ROWS`). ``per_n`` = (a, b): the best design for each n in
    a..b with n fixed as ``n_fixed=(n, n)`` fixes it (every layer's n), one incumbent per n
    (``BnBResult.by_n``), the start boxes cut to single n values first.
    ``stop_below``: stop (uncertified unless nothing is left open) as soon as a design with
    objective strictly better than this value is found (enough to show that one exists).
    """
    tables = tables or Tables(problem)
    if start is None and not record and per_n is None and n_fixed is None and stop_below is None:
        by_layer = _by_layer(problem, c1, c2, incumbent, tables)
        if by_layer is not None:
            return by_layer
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
    rec = _Recorder(len(cons)) if record else None

    # relative widths: n counts as n + 1 (the number of facets), W and alpha as themselves
    offset = np.array([1.0 if d.variable == "n" else 0.0 for d in dims])
    steps = np.array([d.var.step if d.var.step is not None else math.nan for d in dims])
    # one incumbent per slot: per n1 value (per_n), else one
    n_base = per_n[0] if per_n is not None else 0
    slots = per_n[1] - per_n[0] + 1 if per_n is not None else 1
    best_val = np.full(slots, math.inf if incumbent is None else sign * incumbent)
    best_pt: list[DesignPoints | None] = [None] * slots

    def slot(lo: FloatArray) -> NDArray[np.int64]:
        if per_n is None:
            return np.zeros(len(lo), dtype=np.int64)
        return np.asarray(np.round(lo[:, 0]) - n_base, dtype=np.int64)

    if start is None:
        q_lo = np.array([[d.var.lo for d in dims]])
        q_hi = np.array([[d.var.top for d in dims]])
        q_bound = np.array([-math.inf])
    else:
        q_lo, q_hi, q_bound = (np.array(a, dtype=np.float64) for a in start)
    if per_n is not None:  # every box cut to single n values in a..b (n1 = n2 = n, as n_fixed)
        a0, b0 = np.maximum(q_lo[:, 0], per_n[0]), np.minimum(q_hi[:, 0], per_n[1])
        count = np.maximum(b0 - a0 + 1, 0).astype(np.int64)
        src = np.repeat(np.arange(len(q_lo)), count)
        k = np.arange(int(count.sum())) - np.repeat(np.cumsum(count) - count, count)
        q_lo, q_hi, q_bound = q_lo[src], q_hi[src], q_bound[src]
        q_lo[:, 0] = q_hi[:, 0] = a0[src] + k
        if len(dims) > 3:  # layer 2's n too
            both = (q_lo[:, 3] <= q_lo[:, 0]) & (q_lo[:, 0] <= q_hi[:, 3])
            q_lo, q_hi, q_bound = q_lo[both], q_hi[both], q_bound[both]
            q_lo[:, 3] = q_hi[:, 3] = q_lo[:, 0]
    boxes = 0
    it = 0
    width = (q_hi - q_lo) / np.maximum(q_lo + offset, 1e-300)
    if start is None and np.any(width > 0):  # bounding the root alone prunes nothing: cut it
        q_lo, q_hi, q_bound = _split(q_lo, q_hi, width, dims, True, q_bound)
    budget = current_budget()
    goal = -math.inf if stop_below is None else sign * stop_below
    while len(q_lo) and it < MAX_ITERATIONS and boxes < MAX_BOXES and len(q_lo) < MAX_OPEN:
        if budget is not None and budget.exhausted:
            break
        if best_val[0] < goal:
            break
        it += 1
        thr = _thresholds(best_val, tol)
        waiting = q_bound < thr[slot(q_lo)]
        if rec is not None:
            rec.add(q_lo[~waiting], q_hi[~waiting], q_bound[~waiting])
        q_lo, q_hi, q_bound = q_lo[waiting], q_hi[waiting], q_bound[waiting]
        report(it, _gap(best_val, q_bound), _best_of(best_val, sign))
        if not len(q_lo):
            break
        # a search that stops at its first better design takes its boxes best-first in batches
        # growing from FIRST_BATCH fourfold (it often ends in the first few)
        batch = BATCH if stop_below is None else min(BATCH, FIRST_BATCH * 4 ** (it - 1))
        if len(q_lo) > batch:  # best-first: the boxes with the lowest bounds go first
            take = np.zeros(len(q_lo), dtype=bool)
            take[np.argpartition(q_bound, batch)[:batch]] = True
            lo, hi, parent = q_lo[take], q_hi[take], q_bound[take]
            q_lo, q_hi, q_bound = q_lo[~take], q_hi[~take], q_bound[~take]
        else:
            lo, hi, parent = q_lo, q_hi, q_bound
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
        xlo = DesignPoints.from_columns(lo)
        xhi = DesignPoints.from_columns(hi)
        bnd, broken = _cheap_bounds(problem, c1, c2, xlo, xhi, tables, cheap, feas_rtol, obj_key)
        if obj_key in cheap:
            o_lo, o_hi = bnd[obj_key]
            obj_bound = sign * (o_hi if maximize else o_lo)  # lower bound of sign * objective
            obj_bound = np.maximum(obj_bound, parent)  # a box's bound is at least its parent's
        else:  # bounded below with the stiffness, for the boxes that get it
            obj_bound = parent.copy()
        # interval (stiffness) bounds only for the boxes that will be split: an enumerated box
        # has all its points evaluated exactly anyway
        sub = ~broken.any(axis=1) & ~enum
        if costly and sub.any():
            slo, shi = xlo.take(sub), xhi.take(sub)
            sb = box_bounds(problem, c1, c2, slo, shi, tables, costly)
            broken[sub] |= _broken(cons, sb, costly, int(sub.sum()), feas_rtol)
            if obj_key in costly:
                o_lo, o_hi = sb[obj_key]
                obj_bound[sub] = np.maximum(sign * (o_hi if maximize else o_lo), parent[sub])
        keep = ~broken.any(axis=1)
        if rec is not None and not keep.all():
            mask, kept = rec.masks(broken[~keep])
            rec.add(lo[~keep][kept], hi[~keep][kept], obj_bound[~keep][kept], mask[kept])
        better = obj_bound < _thresholds(best_val, tol)[slot(lo)]
        if rec is not None:
            gone = keep & ~better
            rec.add(lo[gone], hi[gone], obj_bound[gone])
        keep &= better
        lo, hi, obj_bound = lo[keep], hi[keep], obj_bound[keep]
        counts, enum = counts[keep], enum[keep]
        if not len(lo):
            continue
        e_lo = lo[:0]
        if enum.any():
            every, owner, dropped = _enumerate(problem, lo[enum], counts[enum], dims, feas_rtol)
            e_lo, e_hi, e_bound = lo[enum], hi[enum], obj_bound[enum]
            if rec is not None:  # the pairs dropped by one layer's bound: rows of its bits
                for own, why in dropped:
                    mask, kept = rec.masks(why)
                    rec.add_points(e_lo, e_hi, e_bound, own[kept], mask[kept], e_bound[own[kept]])
            lo, hi, obj_bound = lo[~enum], hi[~enum], obj_bound[~enum]
            # each point is a box of its own: the same cheap bounds (values, there) drop the
            # points that break a cheap constraint or cannot beat the incumbent, before the
            # full evaluation
            e = DesignPoints.from_columns(every)
            eb, e_broken = _cheap_bounds(problem, c1, c2, e, e, tables, cheap, feas_rtol, obj_key)
            ok = ~e_broken.any(axis=1)
            if obj_key in cheap:
                o_lo, o_hi = eb[obj_key]
                ok &= sign * (o_hi if maximize else o_lo) < _thresholds(best_val, tol)[slot(every)]
            # what each point's bound says, for the archive: its broken cheap bounds and a lower
            # bound of its objective (replaced by the exact ones for the points evaluated)
            e_all_broken = e_broken
            e_pb = sign * (o_hi if maximize else o_lo) if obj_key in cheap else e_bound[owner]
            e_ok = ok
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
            x = DesignPoints.from_columns(pts)
            vals = point_values(problem, c1, c2, x, tables)
            p_broken = _broken(cons, vals, needed, len(pts), feas_rtol)
            # continuous: exact feasibility (margins >= 0); grids: FEAS_RTOL
            ok = ~p_broken.any(axis=1)
            f = np.where(ok, sign * vals[obj_key], np.inf)
            p_slot = slot(pts)
            for s_ in range(slots) if slots > 1 else (0,):
                fs = np.where(p_slot == s_, f, np.inf) if slots > 1 else f
                k = int(np.argmin(fs))
                if fs[k] < best_val[s_]:
                    best_val[s_] = float(fs[k])
                    best_pt[s_] = x.point(k)
        if rec is not None and len(e_lo):  # the enumerated boxes, once per bit set
            n_ok = len(every)
            mask, kept = rec.masks(e_all_broken)
            e_pb = np.array(e_pb, dtype=np.float64)
            if n_ok:  # the points evaluated: every constraint, and their objective
                full, full_kept = rec.masks(p_broken[:n_ok])
                mask[e_ok], kept[e_ok] = full, full_kept
                e_pb[e_ok] = sign * vals[obj_key][:n_ok]
            rec.add_points(e_lo, e_hi, e_bound, owner[kept], mask[kept], e_pb[kept])
        keep = obj_bound < _thresholds(best_val, tol)[slot(lo)]
        if rec is not None:  # closed by the incumbent (their points meet the constraints or not)
            rec.add(lo[~keep], hi[~keep], obj_bound[~keep])
        lo, hi, obj_bound = lo[keep], hi[keep], obj_bound[keep]
        # close single grid points; split the rest and queue the halves with their bound
        width = (hi - lo) / np.maximum(lo + offset, 1e-300)
        point = np.all(width <= 0, axis=1)
        if rec is not None:  # a single point, evaluated above (kept whatever it broke)
            rec.add(lo[point], hi[point], obj_bound[point])
        lo, hi, obj_bound = lo[~point], hi[~point], obj_bound[~point]
        if not len(lo):
            continue
        multi = len(lo) + len(q_lo) < MULTI_SPLIT_BELOW
        lo, hi, obj_bound = _split(lo, hi, width[~point], dims, multi, obj_bound)
        q_lo = np.concatenate([q_lo, lo])
        q_hi = np.concatenate([q_hi, hi])
        q_bound = np.concatenate([q_bound, obj_bound])
    thr = _thresholds(best_val, tol)
    q_slot = slot(q_lo)
    q_open = q_bound < thr[q_slot]
    if rec is not None:
        rec.add(q_lo[~q_open], q_hi[~q_open], q_bound[~q_open])
    certified = not q_open.any()  # stopped or not, nothing is left open
    archive = rec.archive(len(dims)) if rec is not None and certified else None
    results = []
    for s_ in range(slots):
        sel = q_open & (q_slot == s_)
        bv = float(best_val[s_])
        if sel.any():  # stopped early: the bound is the best open box's
            global_bound = float(np.min(q_bound[sel]))
            cert = False
        else:
            cert = True
            global_bound = bv if best_pt[s_] is not None else math.inf
            if best_pt[s_] is not None and not exact:
                global_bound = bv - gap_rtol * abs(bv)
        value = sign * bv if best_pt[s_] is not None else math.nan
        results.append(BnBResult(best_pt[s_], value, sign * min(global_bound, bv), cert, boxes, it))
    if per_n is None:
        return replace(results[0], certified=certified, archive=archive)
    r0 = BnBResult(None, math.nan, math.nan, certified, boxes, it)
    return replace(r0, by_n={n_base + i: r for i, r in enumerate(results)})


def _gap(best: FloatArray, bounds: FloatArray) -> float:
    """Relative gap between the (first) incumbent and the lowest open bound (inf: none)."""
    b = float(best[0])
    if not math.isfinite(b):
        return math.inf
    low = float(bounds.min()) if len(bounds) else b
    return max(b - low, 0.0) / max(abs(b), 1e-300)


def _best_of(best: FloatArray, sign: float) -> float | None:
    b = float(best[0])
    return sign * b if math.isfinite(b) else None
