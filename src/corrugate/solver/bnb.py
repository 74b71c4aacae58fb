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
   are few boxes, into :data:`~.boxes.MULTI_PARTS` along every coordinate when that makes at
   most :data:`~.boxes.MULTI_SPLIT_CHILDREN` boxes, else along every coordinate nearly as wide
   as the widest), cutting grid coordinates between two grid values (:mod:`.boxes`). All boxes of an iteration go through numpy
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

Reading the code. :func:`branch_and_bound` builds a :class:`_Search` (the open boxes, the
incumbent, the counts) and calls its :meth:`~_Search.step` (one iteration: 1-4 above) until it
returns False, then reads :meth:`~_Search.result`. The options are parts given to the search,
not flags inside its loop: the incumbent (one, or one per n for ``per_n``: :class:`_PerN`), the
recorder of the closed boxes (``record``: :class:`~.archive.Recorder`, else
:class:`~.archive.NoRecorder`), the pace (``stop_below``: :class:`_StopBelow`, else
:class:`_Pace`), the first boxes (``start``: :meth:`~_Search.start`) and the coordinates
(``n_fixed``: :func:`_dims`). The boxes are rows of flat arrays (:mod:`.boxes`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from corrugate.solver import tolerance_box
from corrugate.solver.archive import Archive, NoRecorder, Recorder
from corrugate.solver.boxes import grid_points, snap, split, widths
from corrugate.solver.budget import current_budget
from corrugate.solver.making import MAKING
from corrugate.solver.points import VARIABLES, Coordinate, DesignPoints, LayerPoints, coordinates
from corrugate.solver.problem import FEAS_RTOL, Candidate, Constraint, Problem
from corrugate.solver.progress import report
from corrugate.solver.quantities import Tables, box_bounds, chunk, layer_corner, point_values
from corrugate.solver.quantity import LX, LY, Quantity
from corrugate.solver.worst_case import NOMINAL

__all__ = [
    "GAP_RTOL",
    "BnBResult",
    "PerNGrid",
    "branch_and_bound",
    "chunk_runs",
    "enumerated_per_n",
    "per_n_answer",
    "per_n_grid",
]

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
#: Grid points enumerated at once (:meth:`_Search._enumerated`): the boxes of an iteration
#: that are enumerated go through in runs of at most this many points (a box has at most
#: :data:`ENUMERATE`), about 250 bytes each before their evaluation (which itself takes at
#: most :func:`~.quantities.chunk` points at once).
ENUMERATE_CHUNK = 1 << 16
#: Grid boxes with at most this many points are enumerated (each point evaluated exactly) and
#: closed, instead of being bounded and split further: a point costs far less than a box.
ENUMERATE = 512
#: The same under worst-case tolerances, where a point costs more than a box (its tolerance box
#: in pieces, :meth:`_Search._evaluate`): boxes are split further and their bounds prune first
#: (the chassis plate's best capacity with no constraint, docs/tolerances.md section 5: 16.3 s
#: of CPU at 64, 16.6 s at 16, 25.4 s at 4, not done within 20 s at 512).
ENUMERATE_TOLERANCES = 64


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


def _enumerate(
    problem: Problem, lo: FloatArray, counts: FloatArray, dims: list[_Dim], rtol: float
) -> tuple[FloatArray, NDArray[np.int64], list[tuple[NDArray[np.int64], NDArray[np.bool_]]]]:
    """The grid points of each box (:func:`~.boxes.grid_points`, same order) with the box each lies
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
        every = grid_points(lo, counts, [d.var for d in dims])
        owner = np.repeat(np.arange(nbox), counts.prod(axis=1).astype(np.int64))
        return every, owner, []
    kept: list[NDArray[np.int64]] = []
    sizes: list[NDArray[np.int64]] = []
    pts: list[FloatArray] = []
    dropped: list[tuple[NDArray[np.int64], NDArray[np.bool_]]] = []
    per = len(VARIABLES)
    for layer, idx in enumerate(per_layer):
        cols = slice(per * layer, per * layer + per)
        g = grid_points(lo[:, cols], counts[:, cols], [d.var for d in dims[cols]])
        own = np.repeat(np.arange(nbox), counts[:, cols].prod(axis=1).astype(np.int64))
        ext = layer_corner(LayerPoints(*(g[:, j] for j in range(per))), problem.profile_kind).extent
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


def chunk_runs(
    points: NDArray[np.floating[Any]] | NDArray[np.integer[Any]], most: int
) -> list[slice]:
    """Consecutive runs of the rows whose ``points`` (per row) add up to at most ``most`` (a
    row of more is a run of its own): the chunks a search enumerates at once."""
    runs: list[slice] = []
    start, total = 0, 0.0
    for i, k in enumerate(points.tolist()):
        if total and total + k > most:
            runs.append(slice(start, i))
            start, total = i, 0.0
        total += k
    if start < len(points):
        runs.append(slice(start, len(points)))
    return runs


def _thresholds(best: FloatArray, tol: float) -> FloatArray:
    """Per incumbent (sign * objective ``best``, one per slot), the bound below which a box may
    still hold a better design: ``tol`` (relative) below it, itself when not finite."""
    with np.errstate(invalid="ignore"):
        return np.where(np.isfinite(best), best - tol * np.abs(best), best)


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
    from corrugate.solver import separable  # independent layers on a rectangle only

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


def _lower(bounds: tuple[FloatArray, FloatArray], sign: float) -> FloatArray:
    """A lower bound of sign * objective from the objective's (lower, upper) bounds."""
    return np.asarray(sign * (bounds[1] if sign < 0 else bounds[0]))


class _Incumbent:
    """The best design found so far and the threshold a box's bound must be below to stay open.

    ``value`` is sign * objective of the best point (inf: none yet, or the ``incumbent`` given
    to :func:`branch_and_bound`); the threshold lies ``tol`` (relative) below it. One slot:
    :class:`_PerN` keeps one per n."""

    def __init__(self, first: float | FloatArray, tol: float, slots: int = 1) -> None:
        self.value = np.full(slots, first)
        self.point: list[DesignPoints | None] = [None] * slots
        self.tol = tol

    def slot(self, rows: FloatArray) -> NDArray[np.int64]:
        """The incumbent each box (or point) of ``rows`` is judged against."""
        return np.zeros(len(rows), dtype=np.int64)

    def limit(self, rows: FloatArray) -> FloatArray:
        """Per row, the bound below which its box may still hold a better design."""
        return _thresholds(self.value, self.tol)[self.slot(rows)]

    def frozen(self) -> Callable[[FloatArray], FloatArray]:
        """:meth:`limit` as the incumbent stands now, whatever it becomes later."""
        value = self.value.copy()
        return lambda rows: _thresholds(value, self.tol)[self.slot(rows)]

    def cut(
        self, lo: FloatArray, hi: FloatArray, bound: FloatArray
    ) -> tuple[FloatArray, FloatArray, FloatArray]:
        """The first open boxes as this incumbent needs them (here: as they are)."""
        return lo, hi, bound

    def offer(self, pts: FloatArray, f: FloatArray, x: DesignPoints) -> None:
        """Points ``pts`` with sign * objective ``f`` (inf where infeasible) and their
        coordinates ``x``: the best replaces the incumbent if it is better."""
        k = int(np.argmin(f))
        if f[k] < self.value[0]:
            self.value[0] = float(f[k])
            self.point[0] = x.point(k)

    def results(
        self, open_: NDArray[np.bool_], q_lo: FloatArray, q_bound: FloatArray, sign: float
    ) -> list[tuple[DesignPoints | None, float, float, bool]]:
        """Per slot: (point, objective value, proven bound on the optimum, certified), the bound
        being the best open box's when some is left open (``open_``: of the queue q_lo)."""
        q_slot = self.slot(q_lo)
        out = []
        for s in range(len(self.value)):
            sel = open_ & (q_slot == s)
            best, point = float(self.value[s]), self.point[s]
            if sel.any():  # stopped early: the bound is the best open box's
                bound, cert = float(np.min(q_bound[sel])), False
            else:  # closed: the incumbent, less the gap proved (0 on grids)
                cert = True
                bound = best - self.tol * abs(best) if point is not None else math.inf
            value = sign * best if point is not None else math.nan
            out.append((point, value, sign * min(bound, best), cert))
        return out

    def result(self, common: BnBResult, slots: list[BnBResult]) -> BnBResult:
        """The search's result from its ``common`` fields (certified, archive, counts) and the
        results of the slots."""
        return replace(slots[0], certified=common.certified, archive=common.archive)


class _PerN(_Incumbent):
    """One incumbent per n in a..b (``per_n``): the best design with each n, n fixed as
    ``n_fixed=(n, n)`` fixes it (every layer's n); the result's ``by_n``."""

    def __init__(self, first: float | FloatArray, tol: float, per_n: tuple[int, int]) -> None:
        super().__init__(first, tol, per_n[1] - per_n[0] + 1)
        self.a, self.b = per_n

    def slot(self, rows: FloatArray) -> NDArray[np.int64]:
        return np.asarray(np.round(rows[:, 0]) - self.a, dtype=np.int64)

    def cut(
        self, lo: FloatArray, hi: FloatArray, bound: FloatArray
    ) -> tuple[FloatArray, FloatArray, FloatArray]:
        """Every box cut to single n values in a..b (n1 = n2 = n, as n_fixed)."""
        a0, b0 = np.maximum(lo[:, 0], self.a), np.minimum(hi[:, 0], self.b)
        count = np.maximum(b0 - a0 + 1, 0).astype(np.int64)
        src = np.repeat(np.arange(len(lo)), count)
        k = np.arange(int(count.sum())) - np.repeat(np.cumsum(count) - count, count)
        lo, hi, bound = lo[src], hi[src], bound[src]
        lo[:, 0] = hi[:, 0] = a0[src] + k
        if lo.shape[1] > 3:  # layer 2's n too
            both = (lo[:, 3] <= lo[:, 0]) & (lo[:, 0] <= hi[:, 3])
            lo, hi, bound = lo[both], hi[both], bound[both]
            lo[:, 3] = hi[:, 3] = lo[:, 0]
        return lo, hi, bound

    def offer(self, pts: FloatArray, f: FloatArray, x: DesignPoints) -> None:
        p_slot = self.slot(pts)
        for s in range(len(self.value)):
            fs = np.where(p_slot == s, f, np.inf)
            k = int(np.argmin(fs))
            if fs[k] < self.value[s]:
                self.value[s] = float(fs[k])
                self.point[s] = x.point(k)

    def result(self, common: BnBResult, slots: list[BnBResult]) -> BnBResult:
        """No point of its own and no archive; the slots' results by n (``by_n``)."""
        by_n = {self.a + i: r for i, r in enumerate(slots)}
        return replace(common, archive=None, by_n=by_n)


@dataclass(frozen=True)
class _Pace:
    """How a search takes its boxes: :data:`BATCH` per iteration, to the end."""

    def batch(self, iteration: int) -> int:
        """Boxes bounded in iteration ``iteration`` (from 1) at most."""
        return BATCH

    def reached(self, best: float) -> bool:
        """Whether the search may stop at its incumbent (sign * objective ``best``)."""
        return False


@dataclass(frozen=True)
class _StopBelow(_Pace):
    """A search that stops at its first design with sign * objective below ``goal``
    (``stop_below``): its boxes best-first in batches growing from :data:`FIRST_BATCH`
    fourfold (it often ends in the first few)."""

    goal: float

    def batch(self, iteration: int) -> int:
        return min(BATCH, FIRST_BATCH * int(4 ** (iteration - 1)))

    def reached(self, best: float) -> bool:
        return best < self.goal


class _Search:
    """The state of one branch and bound (module docstring): the open boxes (``q_lo``, ``q_hi``
    and ``q_bound``, a lower bound of sign * objective over each), the incumbent, the counts;
    :meth:`step` makes one iteration and :meth:`result` reads the answer. The modes are the
    parts it is given: the incumbent (one, or :class:`_PerN`), the recorder of the archive
    (:class:`~.archive.Recorder` or :class:`~.archive.NoRecorder`) and the pace (to the end, or
    :class:`_StopBelow`); the first boxes (warm starts) and the coordinates (``n_fixed``) come
    from :func:`branch_and_bound`."""

    def __init__(
        self,
        problem: Problem,
        pair: tuple[Candidate, Candidate],
        tables: Tables,
        dims: list[_Dim],
        parts: tuple[_Incumbent, NoRecorder, _Pace],
    ) -> None:
        self.problem, (self.c1, self.c2), self.tables, self.dims = problem, pair, tables, dims
        self.best, self.log, self.pace = parts
        self.sign = -1.0 if problem.objective.sense == "max" else 1.0  # minimise sign * objective
        self.obj = problem.objective.quantity
        self.cons = problem.constraints
        self.needed = {c.quantity for c in self.cons} | {self.obj}
        # what the points' evaluations compute (the rest of the reported quantities, an
        # off-axis D above all, no point of the search reads)
        self.asked = frozenset(self.needed)
        self.costly = {q for q in self.needed if q.directional}  # stiffness, buckling: intervals
        self.cheap = self.needed - self.costly
        # under worst-case tolerances: the nominal problem, whose values screen the points
        # (:meth:`_evaluate`), the quantities it covers and the constraints it cannot screen
        self.covered = frozenset(q for q in self.needed if tolerance_box.covered(problem, q))
        self.screen = replace(problem, tolerances=NOMINAL) if self.covered else None
        self.enumerate = ENUMERATE if self.screen is None else ENUMERATE_TOLERANCES
        self.first = chunk(problem)  # points evaluated over their tolerance box first
        self.unscreened = [
            i for i, c in enumerate(self.cons) if c.quantity in self.covered and c.sense != "min"
        ]
        self.vars = [d.var for d in dims]
        self.exact = all(v.gridded for v in self.vars)
        self.feas_rtol = FEAS_RTOL if self.exact else 0.0
        # relative widths: n counts as n + 1 (the number of facets), W and alpha as themselves
        self.offset = np.array([1.0 if d.variable == "n" else 0.0 for d in dims])
        self.steps = np.array([d.var.step if d.var.step is not None else math.nan for d in dims])
        self.q_lo = self.q_hi = self.q_bound = np.empty(0)
        self.boxes = self.it = 0
        self.budget = current_budget()

    def start(self, start: tuple[FloatArray, FloatArray, FloatArray] | None) -> None:
        """The first open boxes: ``start`` (a warm start), else the whole domain cut at once
        (bounding the root alone prunes nothing); as the incumbent needs them (:meth:`_PerN.cut`)."""
        if start is not None:
            lo, hi, bound = (np.array(a, dtype=np.float64) for a in start)
            self.q_lo, self.q_hi, self.q_bound = self.best.cut(lo, hi, bound)
            return
        root = (
            np.array([[d.var.lo for d in self.dims]]),
            np.array([[d.var.top for d in self.dims]]),
            np.array([-math.inf]),
        )
        lo, hi, bound = self.best.cut(*root)
        width = widths(lo, hi, self.offset)
        if np.any(width > 0):
            lo, hi, bound = split(lo, hi, width, self.vars, True, bound, BATCH)
        self.q_lo, self.q_hi, self.q_bound = lo, hi, bound

    def running(self) -> bool:
        """Whether another iteration is due: boxes open, within the limits and the budget, the
        goal (:class:`_StopBelow`) not reached."""
        return (
            bool(len(self.q_lo))
            and self.it < MAX_ITERATIONS
            and self.boxes < MAX_BOXES
            and len(self.q_lo) < MAX_OPEN
            and not (self.budget is not None and self.budget.exhausted)
            and not self.pace.reached(float(self.best.value[0]))
        )

    def step(self) -> bool:
        """One iteration (module docstring, 1-4) on the open boxes with the lowest bounds; False
        (nothing done) when the search is over."""
        if not self.running():
            return False
        self.it += 1
        self._close_overtaken()
        report(self.it, _gap(self.best.value, self.q_bound), _best_of(self.best.value, self.sign))
        if not len(self.q_lo):
            return False
        lo, hi, parent = self._take(self.pace.batch(self.it))
        counts, enum = self._grid_counts(lo, hi)
        bound, broken = self._bound(lo, hi, parent, enum)
        keep = self._prune(lo, hi, bound, broken)
        lo, hi, bound, counts, enum = lo[keep], hi[keep], bound[keep], counts[keep], enum[keep]
        if not len(lo):
            return True
        if enum.any():  # every grid point of these boxes evaluated; the boxes close
            self._enumerated(lo[enum], hi[enum], bound[enum], counts[enum])
            lo, hi, bound = lo[~enum], hi[~enum], bound[~enum]
        # candidate points of the others: lower corner, upper corner, centre (snapped to the grid)
        mid = np.stack(
            [snap(0.5 * (lo[:, i] + hi[:, i]), v, up=False) for i, v in enumerate(self.vars)],
            axis=1,
        )
        mid = np.clip(mid, lo, hi)
        self._evaluate(np.concatenate([lo, hi, mid]))
        self._queue(lo, hi, bound)
        return True

    def _close_overtaken(self) -> None:
        """Close the open boxes whose bound the incumbent has reached since they were queued."""
        waiting = self.q_bound < self.best.limit(self.q_lo)
        self.log.closed(self.q_lo, self.q_hi, self.q_bound, ~waiting)
        self.q_lo, self.q_hi = self.q_lo[waiting], self.q_hi[waiting]
        self.q_bound = self.q_bound[waiting]

    def _prune(
        self, lo: FloatArray, hi: FloatArray, bound: FloatArray, broken: NDArray[np.bool_]
    ) -> NDArray[np.bool_]:
        """Which boxes stay: those with no constraint shown broken (``broken``: boxes x
        constraints) whose ``bound`` is below the incumbent's threshold; the others close."""
        keep = np.asarray(~broken.any(axis=1))
        self.log.infeasible(lo, hi, bound, broken, ~keep)
        better = bound < self.best.limit(lo)
        self.log.closed(lo, hi, bound, keep & ~better)
        return keep & better

    def _take(self, batch: int) -> tuple[FloatArray, FloatArray, FloatArray]:
        """Up to ``batch`` open boxes, those with the lowest bounds (best-first), off the queue;
        counted and charged to the budget."""
        if len(self.q_lo) > batch:
            take = np.zeros(len(self.q_lo), dtype=bool)
            take[np.argpartition(self.q_bound, batch)[:batch]] = True
            lo, hi, parent = self.q_lo[take], self.q_hi[take], self.q_bound[take]
            self.q_lo, self.q_hi = self.q_lo[~take], self.q_hi[~take]
            self.q_bound = self.q_bound[~take]
        else:
            lo, hi, parent = self.q_lo, self.q_hi, self.q_bound
            self.q_lo, self.q_hi, self.q_bound = self.q_lo[:0], self.q_hi[:0], self.q_bound[:0]
        self.boxes += len(lo)
        if self.budget is not None:
            self.budget.charge(len(lo))
        return lo, hi, parent

    def _grid_counts(self, lo: FloatArray, hi: FloatArray) -> tuple[FloatArray, NDArray[np.bool_]]:
        """Grid values per coordinate of each box, and which boxes (at most :data:`ENUMERATE`
        grid points) have every point evaluated and close (none with continuous variables)."""
        if self.exact:
            counts = np.round((hi - lo) / self.steps) + 1
            return counts, counts.prod(axis=1) <= self.enumerate
        return lo[:, :0], np.zeros(len(lo), dtype=bool)

    def _bound(
        self, lo: FloatArray, hi: FloatArray, parent: FloatArray, enum: NDArray[np.bool_]
    ) -> tuple[FloatArray, NDArray[np.bool_]]:
        """A lower bound of sign * objective over each box (at least its parent's) and the
        constraints shown broken in it: the cheap bounds (extents, thickness, blank, facet,
        mass: corner values) for all, the interval (stiffness) bounds only for the boxes that
        will be split (an enumerated box has all its points evaluated exactly anyway), and
        under worst-case tolerances for the enumerated boxes too (bounding a box costs less
        than one of its points over its tolerance box)."""
        problem, c1, c2, tables = self.problem, self.c1, self.c2, self.tables
        xlo = DesignPoints.from_columns(lo)
        xhi = DesignPoints.from_columns(hi)
        bnd, broken = _cheap_bounds(
            problem, c1, c2, xlo, xhi, tables, self.cheap, self.feas_rtol, self.obj
        )
        if self.obj in self.cheap:
            bound = np.maximum(_lower(bnd[self.obj], self.sign), parent)
        else:  # bounded below with the stiffness, for the boxes that get it
            bound = parent.copy()
        sub = ~broken.any(axis=1)
        if self.screen is None:  # under tolerances a box's bounds cost less than its points'
            sub &= ~enum
        if self.costly and sub.any():
            slo, shi = xlo.take(sub), xhi.take(sub)
            sb = box_bounds(problem, c1, c2, slo, shi, tables, self.costly)
            broken[sub] |= _broken(self.cons, sb, self.costly, int(sub.sum()), self.feas_rtol)
            if self.obj in self.costly:
                bound[sub] = np.maximum(_lower(sb[self.obj], self.sign), parent[sub])
        return bound, broken

    def _enumerated(
        self, lo: FloatArray, hi: FloatArray, bound: FloatArray, counts: FloatArray
    ) -> None:
        """Evaluate every grid point of the boxes (lo, hi, bound) (:func:`_enumerate`), less
        those a cheap bound (at a point, its value) shows broken or no better than the
        incumbent as it stood when the iteration began, which need no full evaluation; the
        boxes go to the archive (the pairs one layer's bound dropped first, then the points).
        The boxes go through in runs of at most :data:`ENUMERATE_CHUNK` points, so the memory
        of an iteration does not grow with its batch; the answer, the archive and the order of
        the offers are those of one pass over all the points."""
        limit = self.best.frozen()
        later = self.log.child()  # the points' rows, after every dropped pair's
        per_layer: list[list[tuple[NDArray[np.int64], NDArray[np.bool_]]]] = []
        for run in chunk_runs(counts.prod(axis=1), ENUMERATE_CHUNK):
            r_lo, r_hi, r_bound = lo[run], hi[run], bound[run]
            every, owner, dropped = _enumerate(
                self.problem, r_lo, counts[run], self.dims, self.feas_rtol
            )
            per_layer.append([(own + run.start, why) for own, why in dropped])
            e = DesignPoints.from_columns(every)
            eb, e_broken = _cheap_bounds(
                self.problem,
                self.c1,
                self.c2,
                e,
                e,
                self.tables,
                self.cheap,
                self.feas_rtol,
                self.obj,
            )
            ok = np.asarray(~e_broken.any(axis=1))
            if self.obj in self.cheap:
                point_bound = _lower(eb[self.obj], self.sign)
                ok &= point_bound < limit(every)
            else:  # a lower bound of its objective: its box's (the exact one once evaluated)
                point_bound = r_bound[owner]
            evaluated = self._evaluate(every[ok])
            later.enumerated(r_lo, r_hi, r_bound, (owner, e_broken, point_bound, ok), evaluated)
        if per_layer and per_layer[0]:
            layers = range(len(per_layer[0]))
            merged = [
                (
                    np.concatenate([p[j][0] for p in per_layer]),
                    np.concatenate([p[j][1] for p in per_layer]),
                )
                for j in layers
            ]
            self.log.dropped(lo, hi, bound, merged)
        self.log.adopt(later)

    def _evaluate(self, pts: FloatArray) -> tuple[NDArray[np.bool_], FloatArray]:
        """Exact values at the points ``pts`` (rows): the constraints each breaks and its sign *
        objective; the best feasible one is offered to the incumbent. Continuous variables:
        exact feasibility (margins >= 0); grids: :data:`~.problem.FEAS_RTOL`.

        Under worst-case tolerances the points are first evaluated by the point model
        (``screen``: the problem without tolerances), at the point and at four corners of its
        tolerance box (:func:`~.tolerance_box.corners`): a point's certified value of a
        directional quantity is at most the least of these (it is the lower bound over the
        whole box), so a point whose least breaks a lower bound breaks it certified too, and
        one whose least cannot beat the incumbent (a maximised directional objective) cannot be
        better; only the others are evaluated over their tolerance boxes, which costs about 16
        times a point of the model (docs/tolerances.md): the most promising (least objective
        bound) first, then those whose objective bound still reaches the best of them, so the
        offers are those of every point evaluated. The row of a point screened out says
        what the point model shows (some of its broken constraints; a lower bound of its
        objective), which is all the archive asks of a row."""
        if not len(pts):
            return np.zeros((0, len(self.cons)), dtype=bool), np.empty(0)
        x = DesignPoints.from_columns(pts)
        if self.screen is None:
            vals = point_values(self.problem, self.c1, self.c2, x, self.tables, self.asked)
            p_broken = _broken(self.cons, vals, self.needed, len(pts), self.feas_rtol)
            value = self.sign * vals[self.obj]
            self.best.offer(pts, np.where(~p_broken.any(axis=1), value, np.inf), x)
            return p_broken, value
        nominal = point_values(self.screen, self.c1, self.c2, x, self.tables, self.asked)
        corners = tolerance_box.corners(self.problem, self.c1, self.c2, x)
        if corners:  # the four corners as one evaluation of 4 k points, corner by corner
            at = point_values(
                self.screen,
                self.c1,
                self.c2,
                tolerance_box.stacked(corners),
                self.tables,
                self.covered,
            )
            for q in self.covered:
                every = np.broadcast_to(np.asarray(at[q]), (len(corners) * len(pts),))
                least = every.reshape(len(corners), len(pts)).min(axis=0)
                nominal[q] = np.minimum(nominal[q], least)
        p_broken = _broken(self.cons, nominal, self.needed, len(pts), self.feas_rtol)
        p_broken[:, self.unscreened] = False  # not shown by a nominal value
        value = np.asarray(self.sign * nominal[self.obj], dtype=np.float64)
        if self.obj in self.covered and self.sign > 0:  # no lower bound from the point model
            value = np.full(len(pts), -np.inf)
        slots = self.best.slot(pts)
        # the points that may beat the incumbent: the most promising first (at most a chunk),
        # then those the best of them leaves in reach (a tie included: the first in order wins)
        maybe = np.flatnonzero(~p_broken.any(axis=1) & (value < self.best.value[slots]))
        full = np.zeros(len(pts), dtype=bool)
        first = maybe
        if len(maybe) > self.first:
            first = maybe[np.argpartition(value[maybe], self.first)[: self.first]]
        for sel in (first, None):
            if sel is None:  # in reach of the best so far, not yet evaluated
                star = self.best.value.copy()
                done = np.flatnonzero(full & ~p_broken.any(axis=1))
                np.minimum.at(star, slots[done], value[done])
                sel = maybe[~full[maybe] & (value[maybe] <= star[slots[maybe]])]
            if not len(sel):
                continue
            vals = point_values(
                self.problem, self.c1, self.c2, x.take(sel), self.tables, self.asked
            )
            p_broken[sel] = _broken(self.cons, vals, self.needed, len(sel), self.feas_rtol)
            value[sel] = self.sign * vals[self.obj]
            full[sel] = True
        f = np.where(full & ~p_broken.any(axis=1), value, np.inf)
        self.best.offer(pts, f, x)
        return p_broken, value

    def _queue(self, lo: FloatArray, hi: FloatArray, bound: FloatArray) -> None:
        """Close the boxes the incumbent leaves behind and the single grid points (evaluated);
        split the rest and queue the parts with their bound."""
        keep = bound < self.best.limit(lo)
        self.log.closed(lo, hi, bound, ~keep)  # their points meet the constraints or not
        lo, hi, bound = lo[keep], hi[keep], bound[keep]
        width = widths(lo, hi, self.offset)
        point = np.all(width <= 0, axis=1)
        self.log.closed(lo, hi, bound, point)  # evaluated, kept whatever it broke
        lo, hi, bound = lo[~point], hi[~point], bound[~point]
        if not len(lo):
            return
        multi = len(lo) + len(self.q_lo) < MULTI_SPLIT_BELOW
        lo, hi, bound = split(lo, hi, width[~point], self.vars, multi, bound, BATCH)
        self.q_lo = np.concatenate([self.q_lo, lo])
        self.q_hi = np.concatenate([self.q_hi, hi])
        self.q_bound = np.concatenate([self.q_bound, bound])

    def result(self) -> BnBResult:
        """The answer: certified when no box is left open (stopped or not); the boxes still
        open that the incumbent has caught up with are closed first."""
        open_ = self.q_bound < self.best.limit(self.q_lo)
        self.log.closed(self.q_lo, self.q_hi, self.q_bound, ~open_)
        certified = not open_.any()
        archive = self.log.archive(len(self.dims)) if certified else None
        common = BnBResult(None, math.nan, math.nan, certified, self.boxes, self.it, archive)
        slots = [
            BnBResult(point, value, bound, cert, self.boxes, self.it)
            for point, value, bound, cert in self.best.results(
                open_, self.q_lo, self.q_bound, self.sign
            )
        ]
        return self.best.result(common, slots)


def branch_and_bound(
    problem: Problem,
    c1: Candidate,
    c2: Candidate,
    *,
    incumbent: float | FloatArray | None = None,
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
    for pruning; the result then holds a point only if it beats it (with ``per_n``, an array:
    one per n, -inf: nothing with that n searched). ``n_fixed``: restrict n
    (n1 for independent layers) to a range. ``start``: the open boxes (lo, hi, lower bound of
    sign * objective) to search instead of the whole domain (boxes reopened from an
    :class:`~.archive.Archive`; their union must hold every design the answer is about). ``record``: keep
    the closed boxes in ``BnBResult.archive`` (None if the search was not certified or the
    archive outgrew :data:`~.archive.ARCHIVE_ROWS`). ``per_n`` = (a, b): the best design for
    each n in a..b with n fixed as ``n_fixed=(n, n)`` fixes it (every layer's n), one incumbent
    per n (``BnBResult.by_n``), the start boxes cut to single n values first.
    ``stop_below``: stop (uncertified unless nothing is left open) as soon as a design with
    objective strictly better than this value is found (enough to show that one exists).
    """
    tables = tables or Tables(problem)
    if start is None and not record and per_n is None and n_fixed is None and stop_below is None:
        assert incumbent is None or isinstance(incumbent, float | int)
        by_layer = _by_layer(problem, c1, c2, incumbent, tables)
        if by_layer is not None:
            return by_layer
    sign = -1.0 if problem.objective.sense == "max" else 1.0  # minimise sign * objective
    dims = _dims(problem, n_fixed)
    tol = 0.0 if all(d.var.gridded for d in dims) else gap_rtol
    first: float | FloatArray = math.inf if incumbent is None else sign * incumbent
    best = _Incumbent(first, tol) if per_n is None else _PerN(first, tol, per_n)
    log = Recorder(len(problem.constraints)) if record else NoRecorder()
    pace = _Pace() if stop_below is None else _StopBelow(sign * stop_below)
    search = _Search(problem, (c1, c2), tables, dims, (best, log, pace))
    search.start(start)
    while search.step():
        pass
    return search.result()


#: Grid points :func:`enumerated_per_n` evaluates at most (one evaluation of the model).
PER_N_POINTS = 4096


def enumerated_per_n(
    problem: Problem,
    c1: Candidate,
    c2: Candidate,
    *,
    start: tuple[FloatArray, FloatArray, FloatArray],
    per_n: tuple[int, int],
    tables: Tables,
    most: int = PER_N_POINTS,
) -> BnBResult | None:
    """:func:`branch_and_bound` with ``start`` and ``per_n`` (no incumbent, no ``n_fixed``, on a
    grid, nominal) when its first iteration would enumerate every box: the start boxes cut to
    single n values (:meth:`_PerN.cut`) each hold at most :data:`ENUMERATE` grid points, at most
    ``most`` in all. Then every grid point of them (:func:`_enumerate`: the same points in the
    same order, less the layer points whose own extent breaks a side bound) is evaluated
    exactly in one call and judged by the search's rule (:data:`~.problem.FEAS_RTOL`), and the
    best feasible one of each n, the first in that order among equals, is its answer
    (:meth:`_PerN.offer`): an exhaustive evaluation of the boxes, where the search would first
    drop the boxes and points whose cheap bounds show them infeasible (rigorous: their points
    are infeasible by their values too) and then evaluate the same points. Certified for every
    n (nothing is left open); the result's fields are the search's (``boxes``: the cut boxes,
    one iteration). None when it does not apply (the search is then needed), or inside a
    spent budget (the search reports the stop)."""
    grid = per_n_grid(problem, start=start, per_n=per_n, most=most)
    if grid is None:
        return None
    x = DesignPoints.from_columns(grid.points)
    vals = point_values(problem, c1, c2, x, tables) if len(x) else {}
    return per_n_answer(problem, grid, vals)


@dataclass(frozen=True)
class PerNGrid:
    """The grid points :func:`enumerated_per_n` evaluates: ``points`` (rows of the search's
    coordinates, in the search's order), from ``boxes`` start boxes cut per n, for the n of
    ``per_n``."""

    points: FloatArray
    boxes: int
    per_n: tuple[int, int]


def per_n_grid(
    problem: Problem,
    *,
    start: tuple[FloatArray, FloatArray, FloatArray],
    per_n: tuple[int, int],
    most: int = PER_N_POINTS,
) -> PerNGrid | None:
    """The points of :func:`enumerated_per_n` (its docstring), None when it does not apply."""
    dims = _dims(problem, None)
    needed = {c.quantity for c in problem.constraints} | {problem.objective.quantity}
    budget = current_budget()
    if (
        not all(d.var.gridded for d in dims)
        or any(tolerance_box.covered(problem, q) for q in needed)
        or (budget is not None and budget.exhausted)
    ):
        return None
    lo, hi, bound = _PerN(math.inf, 0.0, per_n).cut(*(np.array(a, dtype=np.float64) for a in start))
    if len(lo) > BATCH or not np.all(bound < math.inf):  # the search would not take them all
        return None
    steps = np.array([d.var.step for d in dims], dtype=np.float64)
    counts = np.round((hi - lo) / steps) + 1
    per = counts.prod(axis=1)
    if np.any(per > ENUMERATE) or per.sum() > most:
        return None
    every, _, _ = _enumerate(problem, lo, counts, dims, FEAS_RTOL)
    return PerNGrid(every, len(lo), per_n)


def per_n_answer(problem: Problem, grid: PerNGrid, vals: dict[Quantity, FloatArray]) -> BnBResult:
    """:func:`enumerated_per_n`'s answer from the exact values ``vals`` at ``grid.points``
    (charged to the budget as the search charges its boxes)."""
    budget = current_budget()
    if budget is not None:
        budget.charge(grid.boxes)
    obj = problem.objective.quantity
    sign = -1.0 if problem.objective.sense == "max" else 1.0
    best = _PerN(math.inf, 0.0, grid.per_n)
    every = grid.points
    if len(every):
        x = DesignPoints.from_columns(every)
        met = np.ones(len(every), dtype=bool)  # every constraint met, as _broken judges them
        for c in problem.constraints:
            met &= c.satisfied(vals[c.quantity], rtol=FEAS_RTOL)
        best.offer(every, np.where(met, sign * vals[obj], np.inf), x)
    common = BnBResult(None, math.nan, math.nan, True, grid.boxes, 1)
    slots = [
        BnBResult(point, value, bnd, cert, grid.boxes, 1)
        for point, value, bnd, cert in best.results(
            np.zeros(0, dtype=bool), every[:0], np.empty(0), sign
        )
    ]
    return best.result(common, slots)


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
