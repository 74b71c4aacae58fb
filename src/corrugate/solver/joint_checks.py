"""The binding checks of a gridded problem searched together over one sheet pair's archive
(docs/theory.md section 5).

A binding check of constraint c asks whether a design better than the certified optimum meets
every constraint but c (:func:`~.solve._binding`): on a grid, whether some grid point of the
check's problem (c dropped, its negation added: :func:`~.solve._relaxed`) has an objective
strictly better than the optimum. Every such point lies in the boxes of the solve's archive that
c alone closed below the optimum (:meth:`~.archive.Archive.reopen`), so each check used to be a
branch and bound of its own from those boxes: a few iterations each, each iteration's cost
mostly fixed (the case study: four checks of 1-2 iterations, about 1 ms each).

:func:`joint_search` answers every check of a sheet pair in one search instead: its boxes are the
union of the boxes the checks reopen, each box carrying the checks it may still answer. An
iteration bounds every quantity over its boxes once (:func:`~.quantities.box_bounds`: the cheap
ones, then the directional ones over the boxes left) and keeps, per box, the checks whose problem
no bound shows broken there (each check judges a box as its own branch and bound would: its
constraints to :data:`~.problem.FEAS_RTOL`) and whose objective bound is below the optimum; it
evaluates three points of each box (lower and upper corners, centre: in the first iteration of
every box before anything else, so that a design found there answers its checks early; later of
the boxes to split) and every grid point of the boxes of at most :data:`~.bnb.ENUMERATE` points
(:data:`~.bnb.ENUMERATE_TOLERANCES` under worst-case tolerances) as the branch and bound does
(cheap bounds at the points first, then the exact values, :func:`~.quantities.point_values`,
under tolerances after the point model's screen), and splits the others
(:func:`~.boxes.split`). A point that meets every constraint of a check's problem with an
objective better than the optimum answers that check (binding); a check answered leaves every
box. When no box is left, the checks unanswered have no such point in the
pair: each check's answer is that of its own search (a grid point is judged by the same values
and the same rule, every bound is rigorous, and every point a check's own search could find is
in a box it carries), found with the fixed cost of one search.

Only on grids: with continuous variables a check's own search ends at a gap, its incumbent
lowered by the designs it finds, so the checks keep their own searches there.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import NDArray

from corrugate.solver import tolerance_box
from corrugate.solver.archive import Archive
from corrugate.solver.bnb import (
    BATCH,
    ENUMERATE,
    ENUMERATE_CHUNK,
    ENUMERATE_TOLERANCES,
    MAX_BOXES,
    MAX_ITERATIONS,
    MAX_OPEN,
    MULTI_SPLIT_BELOW,
    chunk_runs,
)
from corrugate.solver.boxes import MULTI_PARTS, cut_widest, grid_points, snap, split, widths
from corrugate.solver.budget import current_budget
from corrugate.solver.making import MAKING
from corrugate.solver.points import DesignPoints, coordinates
from corrugate.solver.problem import FEAS_RTOL, Candidate, Constraint, DesignVariable, Problem
from corrugate.solver.quantities import Tables, box_bounds, point_values
from corrugate.solver.quantity import Quantity
from corrugate.solver.worst_case import NOMINAL

__all__ = ["Check", "answered_by", "joint_search", "narrowed", "reopened", "three_points"]

FloatArray = NDArray[np.float64]
BoolArray = NDArray[np.bool_]

#: How the joint search cuts its start boxes before their first bound (offered, :func:`joint_search`):
#: along the relatively widest coordinate into :data:`~.boxes.MULTI_PARTS` parts, then each
#: part in two along its own widest (:func:`~.boxes.cut_widest`).
START_CUTS = (MULTI_PARTS, 2)


@dataclass(frozen=True)
class Check:
    """One binding check: the constraints called ``name`` dropped, ``negation`` (None: none)
    added; ``bits`` are their :class:`~.archive.Archive` mask bits."""

    name: str
    bits: int
    negation: Constraint | None


def reopened(
    archive: Archive, checks: Sequence[Check], below: float
) -> tuple[FloatArray, FloatArray, FloatArray, BoolArray]:
    """The archive's rows that some check reopens (:meth:`~.archive.Archive.reopen`: its mask
    inside the check's bits, its bound below ``below``, sign * objective): (lo, hi, bound,
    carried), ``carried`` (rows x checks) saying which checks reopen each row. The rows below
    ``below`` are picked first (few of a finished search's are), then their masks judged."""
    rows = np.flatnonzero(archive.bound < below)
    mask = archive.mask[rows]
    carried = np.empty((len(rows), len(checks)), dtype=bool)
    for j, c in enumerate(checks):
        carried[:, j] = (mask & ~np.uint64(c.bits)) == 0
    some = _rows_any(carried)
    rows, carried = rows[some], carried[some]
    return archive.lo[rows], archive.hi[rows], archive.bound[rows], carried


def narrowed(
    start: tuple[FloatArray, FloatArray, FloatArray, BoolArray], keep: Sequence[int]
) -> tuple[FloatArray, FloatArray, FloatArray, BoolArray]:
    """:func:`reopened` for the checks ``keep`` (their columns, in order) of the checks that
    ``start`` was reopened for: the rows some of them carry, in the same order (the same
    arrays as :func:`reopened` of those checks alone)."""
    lo, hi, bound, carried = start
    carried = carried[:, list(keep)]
    rows = _rows_any(carried)
    return lo[rows], hi[rows], bound[rows], carried[rows]


#: A constraint as the judge reads it: its quantity, whether it is a lower bound ("min"), and
#: the threshold its values are compared with (:func:`_rule`).
_Rule = tuple[Quantity, bool, float]


def _rule(c: Constraint) -> _Rule:
    """``c`` as (quantity, lower bound, threshold): met to :data:`~.problem.FEAS_RTOL` where
    the value is at least (a lower bound) or at most (an upper bound) the threshold, the bound
    less (more) ``FEAS_RTOL * |bound|``: the same floating-point operations as
    :meth:`~.problem.Constraint.satisfied`, so the same verdicts, without its calls per
    array (the judge reads every constraint at every bound)."""
    tol = FEAS_RTOL * abs(c.bound)
    if c.sense == "min":
        return c.quantity, True, c.bound - tol
    return c.quantity, False, c.bound + tol


def _met_rule(
    rule: _Rule,
    values: dict[Quantity, tuple[FloatArray, FloatArray]] | dict[Quantity, FloatArray],
    screened: frozenset[Quantity],
) -> BoolArray | None:
    """Per row, whether the bounds (or the values) ``values`` leave the constraint of ``rule``
    (:func:`_rule`) possibly met, to :data:`~.problem.FEAS_RTOL`, as the branch and bound
    judges it (a lower bound needs the upper bound of its quantity at least the bound, an
    upper bound its lower bound at most the bound); None when they say nothing of it: its
    quantity is not in ``values``, or it is an upper bound of one of ``screened``."""
    q, lower, threshold = rule
    v = values.get(q)
    if v is None or (not lower and q in screened):
        return None
    if isinstance(v, tuple):
        v = v[1] if lower else v[0]
    return np.asarray(v >= threshold) if lower else np.asarray(v <= threshold)


def _rows_any(a: BoolArray) -> BoolArray:
    """``a.any(axis=1)`` of a (rows x checks) array, as a boolean matrix product (or of ands)
    with a column of ones: numpy's reduction along a short last axis costs several times as
    much (8135 x 9: about 290 against 55 us; 236 x 9: 6 against 2.6 us)."""
    return np.asarray(a @ np.ones(a.shape[1], dtype=bool))


def _cols_any(a: BoolArray) -> BoolArray:
    """``a.any(axis=0)`` of a (rows x checks) array, as :func:`_rows_any` (a row of ones times
    it; 8135 x 9: about 1.3 against 300 us)."""
    return np.asarray(np.ones(a.shape[0], dtype=bool) @ a)


def _both(a: BoolArray | None, b: BoolArray | None) -> BoolArray | None:
    """``a & b``, None standing for every row True."""
    if a is None:
        return b
    return a if b is None else a & b


def _all(arrays: Iterable[BoolArray]) -> BoolArray | None:
    """The rows where every array of ``arrays`` is True (None: no array)."""
    out: BoolArray | None = None
    for a in arrays:
        out = _both(out, a)
    return out


class _Judge:
    """Which checks a box (or point) may still answer, from the constraints shown broken on it:
    a check's problem is every constraint but its own (``bits``) and its negation."""

    def __init__(self, problem: Problem, checks: Sequence[Check]) -> None:
        self.cons = problem.constraints
        self.checks = checks
        # the check each constraint belongs to (-1: none; the first, were bits shared)
        self.owner = [-1] * len(self.cons)
        for j, c in reversed(list(enumerate(checks))):
            for i in range(len(self.cons)):
                if c.bits >> i & 1:
                    self.owner[i] = j
        self.answered = np.zeros(len(checks), dtype=bool)
        # each constraint as (quantity, sense, threshold): met where the quantity's value is
        # at least (min) or at most (max) the threshold, the bound less (more) its slack,
        # computed as :meth:`~.problem.Constraint.satisfied` computes it
        self.rules = [_rule(c) for c in self.cons]
        self.neg_rules = [None if c.negation is None else _rule(c.negation) for c in checks]

    def alive(
        self,
        values: dict[Quantity, tuple[FloatArray, FloatArray]] | dict[Quantity, FloatArray],
        rows: int,
        carried: BoolArray,
        screened: frozenset[Quantity] = frozenset(),
    ) -> BoolArray:
        """(rows x checks): ``carried`` less the checks answered and those whose problem the
        bounds (or values) ``values`` show broken on the row; ``screened``: quantities whose
        values are upper bounds of the exact ones (a point screened under tolerances), so only
        their lower bounds are judged. A row keeps check j when every constraint outside j's
        is possibly met there (:func:`_met_rule`) and so is j's negation: the constraints of no
        check still carried are judged together once, those of each carried check apart."""
        ok = carried & ~self.answered if self.answered.any() else carried.copy()
        cols = np.flatnonzero(_cols_any(ok)).tolist()
        if not cols:
            return np.asarray(ok)
        common: BoolArray | None = None  # the constraints of no check carried
        own: dict[int, BoolArray] = {}  # those of each carried check
        for i, rule in enumerate(self.rules):
            met = _met_rule(rule, values, screened)
            if met is None:
                continue
            j = self.owner[i]
            if j in cols:
                own[j] = met if j not in own else own[j] & met
            else:
                common = met if common is None else common & met
        # per carried check, the others' constraints together: prefix and suffix products
        # (linear in the checks carried)
        order = list(own)
        before: list[BoolArray | None] = [common]  # common & the checks before
        after: list[BoolArray | None] = [None]  # the checks after
        for k, m in zip(order[:-1], reversed(order[1:]), strict=True):
            before.append(_both(before[-1], own[k]))
            after.append(_both(after[-1], own[m]))
        others = {k: _both(b, a) for k, b, a in zip(order, before, after[::-1], strict=False)}
        for j in cols:
            keep = others[j] if j in others else _both(common, _all(own.values()))
            neg = self.neg_rules[j]
            met_neg = None if neg is None else _met_rule(neg, values, screened)
            if met_neg is not None:
                keep = met_neg if keep is None else keep & met_neg
            if keep is not None:
                ok[:, j] &= keep
        return np.asarray(ok)


def _points_of(boxes: list[tuple[FloatArray, FloatArray, BoolArray]]) -> int:
    """Grid points of the boxes ``boxes`` (lower corners, grid values per coordinate, ...)."""
    return int(sum(float(b[1].prod(axis=1).sum()) for b in boxes))


def _centres(lo: FloatArray, hi: FloatArray, variables: Sequence[DesignVariable]) -> FloatArray:
    """The centre of each box, snapped down to the grid and kept inside the box."""
    mid = np.stack(
        [snap(0.5 * (lo[:, i] + hi[:, i]), v, up=False) for i, v in enumerate(variables)],
        axis=1,
    ).reshape(len(lo), len(variables))
    return np.asarray(np.clip(mid, lo, hi))


def three_points(problem: Problem, lo: FloatArray, hi: FloatArray) -> FloatArray:
    """The three points of each box (lo, hi: rows of the search's coordinates) that
    :func:`joint_search` judges first: lower corners, upper corners, centres (rows)."""
    variables = [d.var for d in coordinates(problem)]
    return np.concatenate([lo, hi, _centres(lo, hi, variables)])


def answered_by(
    problem: Problem,
    checks: Sequence[Check],
    values: dict[Quantity, FloatArray],
    goal: float,
) -> BoolArray:
    """Per check, whether one of the points whose exact values are ``values`` meets every
    constraint of its problem with an objective strictly better than ``goal``, as
    :func:`joint_search` judges its points (nominal values, on a grid)."""
    judge = _Judge(problem, checks)
    sign = -1.0 if problem.objective.sense == "max" else 1.0
    rows = len(values[problem.objective.quantity])
    ok = judge.alive(values, rows, np.ones((rows, len(checks)), dtype=bool))
    ok &= (sign * values[problem.objective.quantity] < sign * goal)[:, None]
    return _cols_any(ok)


def _lower(bounds: tuple[FloatArray, FloatArray], sign: float) -> FloatArray:
    """A lower bound of sign * objective from the objective's (lower, upper) bounds."""
    return np.asarray(sign * (bounds[1] if sign < 0 else bounds[0]))


def joint_search(
    problem: Problem,
    pair: tuple[Candidate, Candidate],
    tables: Tables,
    checks: Sequence[Check],
    start: tuple[FloatArray, FloatArray, FloatArray, BoolArray],
    goal: float,
    offered: bool = False,
) -> list[bool | None]:
    """Per check of ``checks`` (on a grid), whether a grid point of the boxes ``start`` that
    carry it (:func:`reopened`) meets every constraint of its problem with an objective strictly
    better than ``goal`` (the optimum): True when one was found, False when none exists, None
    when the budget or the search's limits (those of :mod:`.bnb`) stopped it first (module
    docstring). ``offered``: the three points (:func:`three_points`) of every start box were
    judged already for every check (:func:`answered_by`; the checks they answer are not in
    ``checks``), so the first iteration does not judge them again; nor does it bound the
    start boxes (the search's own bounds showed each broken by at most the constraints of
    the checks it carries, and bounds only prune: a box split unbounded has its parts bounded
    in the next iteration), which on the case study saves a cheap and an interval bound of 56
    boxes (joint search 3.99 -> 3.29 ms, medians of 200). It cuts every start box instead,
    those of at most :data:`~.bnb.ENUMERATE` points too, two levels deep (:data:`START_CUTS`),
    so that their first bound, one call for all, closes most of them before any grid point is
    judged, and bounds with the interval bounds only the boxes it will split (nominally, as
    the branch and bound does): on the case study 572 boxes bounded leave 4336 grid points to
    screen and 755 to evaluate, no interval bound, where 236 boxes, 50 interval bounds and the
    small start boxes' own points left 8135 and 256 (joint search 30 % cheaper: 3.25 -> 2.27
    ms in one process, medians of 300, with the judge's cheaper reading of the bounds)."""
    c1, c2 = pair
    sign = -1.0 if problem.objective.sense == "max" else 1.0
    limit = sign * goal
    obj = problem.objective.quantity
    needed = {c.quantity for c in problem.constraints} | {obj}
    costly = {q for q in needed if q.directional}
    cheap = needed - costly
    # the grid points' screen: the cheap values but the making's parts (the costliest of them:
    # a screen only drops points early, and every point left is judged by all its values)
    screened_by = (cheap - MAKING) | ({obj} & cheap)
    judge = _Judge(problem, checks)
    dims = coordinates(problem)
    variables = [d.var for d in dims]
    steps = np.array([v.step for v in variables], dtype=np.float64)
    offset = np.array([1.0 if d.variable == "n" else 0.0 for d in dims])
    covered = frozenset(q for q in needed if tolerance_box.covered(problem, q))
    screen = replace(problem, tolerances=NOMINAL) if covered else None
    most = ENUMERATE_TOLERANCES if covered else ENUMERATE
    budget = current_budget()

    def offer(x: DesignPoints, carried: BoolArray) -> None:
        """Judge the points ``x`` (carrying ``carried``) by their exact values; under
        worst-case tolerances the points the point model screens out first, as the branch and
        bound does (:meth:`~.bnb._Search._evaluate`): a directional quantity's least over the
        point and four corners of its tolerance box is at least its certified value, so a lower
        bound it breaks is broken certified too (an upper bound is not judged by it)."""
        if not len(x):
            return
        if screen is not None:
            nominal = point_values(screen, c1, c2, x, tables)
            for corner in tolerance_box.corners(problem, c1, c2, x):
                at = point_values(screen, c1, c2, corner, tables, covered)
                for q in covered:
                    nominal[q] = np.minimum(nominal[q], at[q])
            ok = judge.alive(nominal, len(x), carried, covered)
            if obj not in covered:
                ok &= (sign * nominal[obj] < limit)[:, None]
            sel = _rows_any(ok)
            x, carried = x.take(sel), ok[sel]
            if not len(x):
                return
        vals = point_values(problem, c1, c2, x, tables)
        ok = judge.alive(vals, len(x), carried)
        ok &= (sign * vals[obj] < limit)[:, None]
        judge.answered |= _cols_any(ok)

    waiting: list[tuple[FloatArray, FloatArray, BoolArray]] = []

    def enumerate_waiting(points: list[FloatArray], carried: list[BoolArray]) -> None:
        """Judge ``points`` (carrying ``carried``) and every grid point of the boxes waiting
        (:data:`waiting`: lower corners, grid values per coordinate, checks carried): cheap
        bounds at the points, then the exact values of those left, in runs of at most
        ENUMERATE_CHUNK points (the memory of an iteration does not grow with its batch, as
        the branch and bound's)."""
        e_lo = np.concatenate([w[0] for w in waiting])
        e_counts = np.concatenate([w[1] for w in waiting])
        e_car = np.concatenate([w[2] for w in waiting]) & ~judge.answered
        waiting.clear()
        live = _rows_any(e_car)
        e_lo, e_counts, e_car = e_lo[live], e_counts[live], e_car[live]
        per = e_counts.prod(axis=1).astype(np.int64)
        for run in chunk_runs(per, ENUMERATE_CHUNK):
            every = grid_points(e_lo[run], e_counts[run], variables)
            owner_car = np.repeat(e_car[run] & ~judge.answered, per[run], axis=0)
            e = DesignPoints.from_columns(every)
            eb = box_bounds(problem, c1, c2, e, e, tables, screened_by)
            pc = judge.alive(eb, len(every), owner_car)
            if obj in cheap:
                pc &= (_lower(eb[obj], sign) < limit)[:, None]
            sel = _rows_any(pc)
            points.append(every[sel])
            carried.append(pc[sel])
            if sum(len(x) for x in points) >= ENUMERATE_CHUNK:
                offer(DesignPoints.from_columns(np.concatenate(points)), np.concatenate(carried))
                points, carried = [], []
        if points and sum(len(x) for x in points):
            offer(DesignPoints.from_columns(np.concatenate(points)), np.concatenate(carried))

    q_lo, q_hi, q_bound, q_car = start
    q_lo, q_hi = np.asarray(q_lo, dtype=np.float64), np.asarray(q_hi, dtype=np.float64)
    q_bound = np.asarray(q_bound, dtype=np.float64)
    iterations = boxes = 0
    while len(q_lo):
        if judge.answered.any():
            keep = _rows_any(q_car & ~judge.answered)
            q_lo, q_hi, q_bound, q_car = q_lo[keep], q_hi[keep], q_bound[keep], q_car[keep]
            if not len(q_lo):
                break
        if (
            (budget is not None and budget.exhausted)
            or iterations >= MAX_ITERATIONS
            or boxes >= MAX_BOXES
            or len(q_lo) >= MAX_OPEN
        ):
            return [True if a else None for a in judge.answered]
        iterations += 1
        if len(q_lo) > BATCH:  # the lowest bounds first
            take = np.zeros(len(q_lo), dtype=bool)
            take[np.argpartition(q_bound, BATCH)[:BATCH]] = True
            lo, hi, bound, car = q_lo[take], q_hi[take], q_bound[take], q_car[take]
            q_lo, q_hi, q_bound, q_car = q_lo[~take], q_hi[~take], q_bound[~take], q_car[~take]
        else:
            lo, hi, bound, car = q_lo, q_hi, q_bound, q_car
            q_lo, q_hi, q_bound, q_car = lo[:0], hi[:0], bound[:0], car[:0]
        boxes += len(lo)
        if budget is not None:
            budget.charge(len(lo))
        counts = np.round((hi - lo) / steps) + 1
        first = iterations == 1
        # offered: the start boxes go unbounded and unjudged, every one cut (docstring)
        enum = (counts.prod(axis=1) <= most) & (not (first and offered))
        if not (first and offered):
            xlo, xhi = DesignPoints.from_columns(lo), DesignPoints.from_columns(hi)
            bnd = box_bounds(problem, c1, c2, xlo, xhi, tables, cheap)
            if obj in cheap:
                bound = np.maximum(bound, _lower(bnd[obj], sign))
            car = judge.alive(bnd, len(lo), car) & (bound < limit)[:, None]
            sub = _rows_any(car)
            # the costly bounds of the boxes still open that will be split, as the branch and
            # bound bounds them (:meth:`~.bnb._Search._bound`: an enumerated box has its points
            # evaluated exactly anyway; under tolerances the boxes to enumerate too, a box's
            # bounds costing less than one of its points over its tolerance box)
            bounded = sub if screen is not None else sub & ~enum
            if costly and bounded.any():
                sb = box_bounds(
                    problem, c1, c2, xlo.take(bounded), xhi.take(bounded), tables, costly
                )
                if obj in costly:
                    bound[bounded] = np.maximum(bound[bounded], _lower(sb[obj], sign))
                car[bounded] = (
                    judge.alive(sb, int(bounded.sum()), car[bounded])
                    & (bound[bounded] < limit)[:, None]
                )
                sub = _rows_any(car)
            lo, hi, bound, car, counts, enum = (
                lo[sub],
                hi[sub],
                bound[sub],
                car[sub],
                counts[sub],
                enum[sub],
            )
        rest = ~enum
        points: list[FloatArray] = []
        carried: list[BoolArray] = []
        # three points of each box (lower and upper corners, centre): in the first iteration
        # of every box first, so that a design found there answers its checks before any box
        # is enumerated; later only of the boxes to be split, with the enumerated points
        # (offered: the first iteration judges none)
        if first and not offered:
            mid = _centres(lo, hi, variables)
            offer(DesignPoints.from_columns(np.concatenate([lo, hi, mid])), np.tile(car, (3, 1)))
            car = car & ~judge.answered
            live = _rows_any(car)
            lo, hi, bound, car, rest, enum = (
                lo[live],
                hi[live],
                bound[live],
                car[live],
                rest[live],
                enum[live],
            )
            counts = counts[live]
        elif not first and rest.any():
            mid = _centres(lo[rest], hi[rest], variables)
            points += [lo[rest], hi[rest], mid]
            carried += [car[rest]] * 3
        # nominally, the boxes to enumerate wait while others are split (within
        # ENUMERATE_CHUNK points), so that the points of several iterations are judged in one
        # evaluation (under tolerances a design found there answers its checks first: the
        # chassis plate's explanation bounded 34 204 boxes so, 44 024 with them waiting)
        if enum.any():
            waiting.append((lo[enum], counts[enum], car[enum]))
        splits = screen is None and bool((car[rest] & ~judge.answered).any())
        if waiting and (not splits or _points_of(waiting) > ENUMERATE_CHUNK):
            enumerate_waiting(points, carried)
        elif points:
            offer(DesignPoints.from_columns(np.concatenate(points)), np.concatenate(carried))
        lo, hi, bound, car = lo[rest], hi[rest], bound[rest], car[rest]
        if judge.answered.any():
            car &= ~judge.answered
            live = _rows_any(car)
            lo, hi, bound, car = lo[live], hi[live], bound[live], car[live]
        if not len(lo):
            continue
        multi = len(lo) + len(q_lo) < MULTI_SPLIT_BELOW
        tag = np.arange(len(lo), dtype=np.float64)
        if first and offered:  # the start boxes: two levels at once before their first bound
            c_lo, c_hi, c_tag = lo, hi, tag
            for parts in START_CUTS:
                width = widths(c_lo, c_hi, offset)
                c_lo, c_hi, c_tag = cut_widest(c_lo, c_hi, width, variables, c_tag, parts)
        else:
            c_lo, c_hi, c_tag = split(lo, hi, widths(lo, hi, offset), variables, multi, tag, BATCH)
        parent = c_tag.astype(np.int64)
        q_lo = np.concatenate([q_lo, c_lo])
        q_hi = np.concatenate([q_hi, c_hi])
        q_bound = np.concatenate([q_bound, bound[parent]])
        q_car = np.concatenate([q_car, car[parent]])
    if waiting:  # left by an iteration whose split boxes all closed in the next
        enumerate_waiting([], [])
    return [bool(a) for a in judge.answered]
