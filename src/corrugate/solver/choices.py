"""Certified lower bounds on the lightest design of each sheet pair, to order the pairs and prune
whole ones (docs/theory.md section 5).

A problem with material choices searches every sheet pair (:func:`~.solve.pairs`). When its
independent layers decompose (least mass, a rectangle, gridded, bounds along the creases:
:func:`~.separable.applies`), a *relaxation* R of it does too: every design the problem P accepts
meets R's constraints, with the same mass. R is P with

* nominal tolerances, and each sheet (t, E, density rho) replaced by (t (1 - dt), E (1 - dE),
  rho / (1 - dt)): rho t, hence every mass, unchanged (to rounding); the certified value G(x)
  of a directional quantity is at most its value at every part of the tolerance box T(x), and
  (W, alpha, t (1 - dt), E (1 - dE)) is one of them (:mod:`~.tolerance_box`), so a design whose
  G meets a lower bound meets it in R (every directional constraint is a lower bound);
* each directional lower bound relaxed by :data:`RELAX` (relative; rounding) and every lower
  bound of t / W dropped (t (1 - dt) / W is smaller); the sizes, the making and the mass are
  nominal in both (docs/tolerances.md);
* each directional lower bound held at the four corners of the tolerance box too (every
  layer's W -+ dW and alpha -+ da, on the same low sheet: :func:`~.tolerance_box.corners`,
  :func:`~.tolerance_box.corner_shifts`): each corner is a part of T(x), so G(x) is at most
  the point model's value there as well (the branch and bound screens points by the same
  fact). Without this, R's optimum of a pair lay 8.3-10.6 % below P's on the feasible pairs of
  tests/solver/test_choices.py's four sheets (default tolerances); with it 0-2.2 %.

So the lightest design of R on a pair, less :data:`RELAX`, is at most P's on that pair. Two such
floors per pair (:class:`Floors`): :meth:`Floors.coarse`, from R's layer lists alone
(:func:`~.separable.pair_floor`: the lists are built once per sheet, not per pair; each
layer's lightest design that may meet the coupled bounds with the other list's terms at their
largest), and
:meth:`Floors.fine`, the layer-by-layer search (:func:`~.separable.search`) of R on the pair
whose designs, lightest first, are judged by R's exact values and then by P's own certified
values (``point_values`` of P, tolerances included, judged with FEAS_RTOL: the branch and bound's
evaluation of a point), for at most :data:`EXACT_POINTS` designs of the pair, R's alone past
them: every design lighter than its answer was shown infeasible in R or in P, and P's designs
are R's, so its answer is at most P's optimum on the pair, and equal to it (less RELAX) while
the designs judged stay within EXACT_POINTS (films-32 of benchmarks/edges.py: the main solve
searches 1 pair instead of 15; about 21 us of CPU per design judged by P).
:func:`~.solve.optimize` takes the pairs best-first by these floors, refining a coarse floor
before it searches the pair, and stops when the least floor left reaches the incumbent: those
pairs hold no design lighter than the answer (the branch and bound of each would return none), so
the answer is the same, its certificate too, whatever the number of sheets.
"""

from __future__ import annotations

import math
from collections.abc import Hashable, Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING

import numpy as np

from corrugate.solver import tolerance_box
from corrugate.solver.points import DesignPoints
from corrugate.solver.problem import FEAS_RTOL, Candidate, Constraint, Problem
from corrugate.solver.quantities import Tables, point_values
from corrugate.solver.quantity import MASS, T_OVER_W
from corrugate.solver.worst_case import NOMINAL, WorstCase

if TYPE_CHECKING:
    from corrugate.solver import cells
    from corrugate.solver.separable import LayerDesigns, Shifts

__all__ = ["EXACT_POINTS", "RELAX", "CellFloors", "Floors", "floors", "relaxation", "shared_lists"]

#: Relative relaxation of R's directional lower bounds and of its floors (rounding: far above
#: the few units in the last place by which R's values may differ from P's).
RELAX = 1e-9
#: Designs of one pair a fine floor judges by the problem's own certified values at most (about
#: 0.1 s of CPU); past them R's values alone judge (module docstring).
EXACT_POINTS = 4096


#: The layer lists built inside :func:`shared_lists`, by :func:`~.separable.layer_key`.
_LISTS: ContextVar[dict[Hashable, LayerDesigns | None] | None] = ContextVar(
    "corrugate_layer_lists", default=None
)


@contextmanager
def shared_lists() -> Iterator[None]:
    """Inside the block, the :class:`Floors` of every problem share the layer lists they build
    (one solve and its explanation: the floors of the check problems, the runner-ups' n fixed,
    mostly the same lists); freed at its end."""
    token = _LISTS.set({} if _LISTS.get() is None else _LISTS.get())
    try:
        yield
    finally:
        _LISTS.reset(token)


def _sheet(c: Candidate, tol: WorstCase) -> Candidate:
    """The sheet of R (module docstring): t and E at their low ends, rho t unchanged."""
    m = c.material
    if not (tol.t or tol.E):
        return c
    low = replace(m, E=m.E * (1 - tol.E), density=m.density / (1 - tol.t))
    return replace(c, material=low, t=c.t * (1 - tol.t))


def _relaxed(c: Constraint) -> Constraint | None:
    """A constraint of R: a directional lower bound relaxed by :data:`RELAX`, a lower bound of
    t / W dropped (None), the others as they are."""
    q = c.quantity
    if c.sense == "min" and (q == T_OVER_W or q.kind == "tw_least"):
        return None
    if c.sense == "min" and q.eta is not None:
        return replace(c, bound=c.bound - RELAX * abs(c.bound))
    return c


def relaxation(problem: Problem) -> Problem | None:
    """R of the module docstring, None when ``problem`` is not a least-mass problem whose R the
    layer-by-layer search takes (:func:`~.separable.applies`, which also declines a calibrated
    sheet: its measured E interval and springback angle are not bounded by R's sheet)."""
    if problem.objective.quantity != MASS or problem.objective.sense != "min":
        return None
    if problem.identical or len(problem.candidates) < 2:
        return None
    if any(c.quantity.eta is not None and c.sense != "min" for c in problem.constraints):
        return None
    kept = tuple(r for r in (_relaxed(c) for c in problem.constraints) if r is not None)
    sheets = tuple(_sheet(c, problem.tolerances) for c in problem.candidates)
    relaxed = replace(problem, tolerances=NOMINAL, constraints=kept, candidates=sheets)
    from corrugate.solver import separable  # imported when a problem may take it

    return relaxed if separable.applies(relaxed) else None


@dataclass
class Floors:
    """Lower bounds (g) of each sheet pair's lightest design (pair k: (candidates[k // N],
    candidates[k % N]), :func:`~.solve.pairs`' order), from the relaxation ``relaxed``."""

    relaxed: Problem
    #: the corners of the tolerance boxes (W -+ dW, alpha -+ da) where R's stiffness bounds
    #: hold too (module docstring): none under nominal tolerances
    shifts: Shifts = ()
    #: P itself, whose certified values judge R's designs too (:meth:`fine`); None: R's alone
    original: Problem | None = None
    _lists: dict[tuple[int, int], LayerDesigns | None] = field(default_factory=dict)
    _tables: Tables | None = None
    _own_tables: Tables | None = None
    _coarse: np.ndarray | None = None
    _accepted: dict[int, float] = field(default_factory=dict)

    @property
    def size(self) -> int:
        return len(self.relaxed.candidates) ** 2

    def _list(self, i: int, which: int) -> LayerDesigns | None:
        from corrugate.solver import separable

        key = (i, which)
        if key not in self._lists:
            cand = self.relaxed.candidates[i]
            shared = _LISTS.get()
            whole = separable.layer_key(self.relaxed, cand, which, self.shifts)
            if shared is not None and whole in shared:
                self._lists[key] = shared[whole]
            else:
                self._lists[key] = separable.layer_designs(self.relaxed, cand, which, self.shifts)
                if shared is not None:
                    shared[whole] = self._lists[key]
        return self._lists[key]

    def with_n(self, n: int) -> Floors:
        """The floors of the same problem with every layer's n fixed at ``n`` (those of
        :func:`floors` of ``replace(problem, n_lo=n, n_hi=n)``), its layer lists this one's
        designs with that n where this one has built them (a list holds the grid's designs that
        meet the layer's own constraints, so those with n are the list of n alone; their order
        may differ, not the floors' validity)."""
        relaxed = replace(self.relaxed, n_lo=n, n_hi=n)
        original = None if self.original is None else replace(self.original, n_lo=n, n_hi=n)
        out = Floors(relaxed, self.shifts, original)
        for key, designs in self._lists.items():
            if designs is not None:
                out._lists[key] = designs.take(np.flatnonzero(designs.n == n))
        return out

    def _pair(self, k: int) -> tuple[int, int]:
        return divmod(k, len(self.relaxed.candidates))

    def coarse(self, k: int) -> float:
        """A floor of pair ``k`` from the layer lists alone (0 when a list is too long), all
        pairs' at the first call (:func:`~.separable.pair_floors`)."""
        from corrugate.solver import separable

        if self._coarse is None:
            n = len(self.relaxed.candidates)
            firsts = [self._list(i, 1) for i in range(n)]
            seconds = [self._list(i, 2) for i in range(n)]
            got = separable.pair_floors(self.relaxed, self.relaxed.candidates, firsts, seconds)
            self._coarse = (got * (1 - RELAX)).reshape(-1)
        return float(self._coarse[k])

    def fine(self, k: int, below: float) -> float:
        """A floor of pair ``k`` at least :meth:`coarse`'s: its lightest design that R's and
        P's values (:attr:`original`; at most :data:`EXACT_POINTS` designs judged by P) do not
        show infeasible, less :data:`RELAX` (P's certified optimum on the pair, less RELAX,
        when P judged every design it took); inf when there is none lighter than ``below``
        (g), 0 when the search declines (lists or pairs too many)."""
        from corrugate.solver import separable

        i, j = self._pair(k)
        c1, c2 = self.relaxed.candidates[i], self.relaxed.candidates[j]
        if self._tables is None:
            self._tables = Tables(self.relaxed)
        tables, relaxed, shifts = self._tables, self.relaxed, self.shifts
        cons = relaxed.constraints
        stiff = [c for c in cons if c.quantity.eta is not None]  # R's are lower bounds
        asked = frozenset(c.quantity for c in stiff)
        own = self.original
        if own is not None and self._own_tables is None:
            self._own_tables = Tables(own)
        own_tables = self._own_tables
        o1, o2 = (c1, c2) if own is None else (own.candidates[i], own.candidates[j])
        judged = 0  # designs judged by P's certified values
        accepted = math.inf  # the least mass of a design P accepted

        def exact(x: DesignPoints) -> tuple[np.ndarray, np.ndarray]:
            vals = point_values(relaxed, c1, c2, x, tables)
            ok = np.ones(len(x), dtype=bool)
            for c in cons:
                ok &= np.asarray(c.satisfied(vals[c.quantity], rtol=FEAS_RTOL), dtype=bool)
            for dW, da in shifts if stiff else ():  # and at each corner
                at = point_values(
                    relaxed, c1, c2, tolerance_box.moved_points(x, dW, (da,)), tables, asked
                )
                for c in stiff:
                    ok &= np.asarray(c.satisfied(at[c.quantity], rtol=FEAS_RTOL), dtype=bool)
            nonlocal judged, accepted  # then by P itself, up to EXACT_POINTS designs
            if own is not None and own_tables is not None and judged < EXACT_POINTS and ok.any():
                sel = np.flatnonzero(ok)
                judged += len(sel)
                got = point_values(own, o1, o2, x.take(sel), own_tables)
                good = np.ones(len(sel), dtype=bool)
                for c in own.constraints:
                    good &= np.asarray(c.satisfied(got[c.quantity], rtol=FEAS_RTOL), dtype=bool)
                ok[sel] = good
                if good.any():
                    accepted = min(accepted, float(np.min(got[MASS][good])))
            return vals[MASS], ok

        inc = None if not math.isfinite(below) else below * (1 + RELAX)
        lists = (self._list(i, 1), self._list(j, 2))
        r = separable.search(relaxed, c1, c2, inc, exact, shifts, lists)
        self._accepted[k] = accepted
        if r is None:
            return 0.0
        return math.inf if r.point is None else r.value * (1 - RELAX)

    def accepted(self, k: int) -> float:
        """The least mass (g) of a design of pair ``k`` that P (:attr:`original`) accepted in
        the last :meth:`fine` of the pair (its certified values, to FEAS_RTOL, as the branch
        and bound judges a point): a real design of P with that mass; inf when none was."""
        return self._accepted.get(k, math.inf)


@dataclass
class CellFloors:
    """Floors (g) of each sheet pair's lightest design of a problem with continuous W and
    alpha on independent layers (:mod:`.cells`: the problem's own certified bounds over
    cells, no relaxation), pair k as :class:`Floors` numbers them; each pair's cells' search
    (:meth:`fine`) kept, whose start boxes and design its branch and bound then takes
    (:meth:`result`)."""

    problem: Problem
    _tables: Tables | None = None
    _coarse: dict[int, float] = field(default_factory=dict)
    _fine: dict[int, tuple[float, cells.CellResult]] = field(default_factory=dict)

    @property
    def size(self) -> int:
        return len(self.problem.candidates) ** 2

    @property
    def tables(self) -> Tables:
        if self._tables is None:
            self._tables = Tables(self.problem)
        return self._tables

    def _setting(self, k: int) -> cells.Setting:
        from corrugate.solver import cells

        i, j = divmod(k, len(self.problem.candidates))
        c1, c2 = self.problem.candidates[i], self.problem.candidates[j]
        return cells.setting(self.problem, c1, c2, self.tables)

    def coarse(self, k: int) -> float:
        """A floor of pair ``k`` from the first cells alone (:data:`~.cells.FIRST_W` x
        :data:`~.cells.FIRST_ALPHA` per n), no design evaluated."""
        from corrugate.solver import cells

        if k not in self._coarse:
            self._coarse[k] = cells.search(self._setting(k), math.inf, budget=0).floor
        return self._coarse[k]

    def fine(self, k: int, below: float) -> float:
        """A floor of pair ``k`` from its cells' search below ``below`` (g; the problem's
        designs evaluated at the cells too): inf when the pair holds no design lighter than
        ``below``, at most the lightest design found."""
        r = self.result(k, below)
        return min(r.floor, r.value) if r.point is not None else r.floor

    def search_all(
        self,
        below: float,
        gap: float | None = None,
        budget: int | None = None,
        fine: float | None = None,
        seek: bool = False,
        crowd: int | None = None,
    ) -> tuple[list[cells.CellResult], int, frozenset[int]]:
        """Every pair's cells searched at once below ``below`` (g) (:func:`~.cells.search_pairs`:
        one queue, one incumbent; to the relative ``gap``, on toward ``fine``), and the index of
        the pair of the best design found (-1: none), and the constraints that fired
        (:func:`~.cells.search_pairs`; ``seek``, ``crowd``: its). ``gap`` and ``budget``: by
        default :data:`~.cells.CELL_GAP` and :data:`~.cells.BUDGET`."""
        from corrugate.solver import cells

        gap = cells.CELL_GAP if gap is None else gap
        budget = cells.BUDGET if budget is None else budget
        everything = [(a, b) for a in self.problem.candidates for b in self.problem.candidates]
        settings = [cells.setting(self.problem, a, b, self.tables) for a, b in everything]
        exacts = [cells.judge_of(self.problem, a, b, self.tables) for a, b in everything]
        return cells.search_pairs(settings, below, exacts, budget, gap, fine, seek, crowd)

    def result(self, k: int, below: float) -> cells.CellResult:
        """Pair ``k``'s cells' search (:func:`~.cells.search`) below ``below`` (g), made once
        (a search below a higher incumbent serves: its boxes hold those below this one)."""
        from corrugate.solver import cells

        got = self._fine.get(k)
        if got is None or got[0] < below:
            i, j = divmod(k, len(self.problem.candidates))
            c1, c2 = self.problem.candidates[i], self.problem.candidates[j]
            st = cells.setting(self.problem, c1, c2, self.tables)
            exact = cells.judge_of(self.problem, c1, c2, self.tables)
            got = (below, cells.search(st, below, exact))
            self._fine[k] = got
        return got[1]


def floors(problem: Problem) -> Floors | CellFloors | None:
    """The :class:`Floors` of ``problem``'s sheet pairs, None without a relaxation
    (:func:`relaxation`); its stiffness bounds held at the four corners of the tolerance box
    too (:func:`~.tolerance_box.corner_shifts`), its designs judged by ``problem`` too."""
    if len(problem.candidates) > 1:
        from corrugate.solver import cells  # imported for a choice of sheets only

        if cells.applies(problem):
            return CellFloors(problem)
    relaxed = relaxation(problem)
    if relaxed is None:
        return None
    return Floors(relaxed, tolerance_box.corner_shifts(problem.tolerances), problem)
