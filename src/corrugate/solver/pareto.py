"""The mass-versus-stiffness Pareto front of a spec, each point a certified optimum.

The front is traced by the epsilon-constraint method: the stiffness in question (``EI``, ``D`` or
``K`` at one eta) loses its bounds from the spec and becomes a lower bound s; each point is the
certified lightest design with stiffness >= s (every other constraint of the spec kept).

* Every variable gridded: the front is a finite staircase and is enumerated exactly. Start with
  no bound; after each point of stiffness S, ask for stiffness >= S (1 + 3e-9) (beyond the solver's
  feasibility slack :data:`~.problem.FEAS_RTOL`), so the next point is the lightest design strictly
  stiffer than the last one. This yields every Pareto-optimal (mass, stiffness) pair in order of
  increasing stiffness (up to that 3e-9 resolution), until no stiffer design exists or
  ``max_points`` is reached (then the front is reported as truncated). A point whose mass ties
  with the next (stiffer) one is dominated and dropped.
* Continuous W or alpha: the front is a curve; it is sampled at ``points`` stiffness levels evenly
  spaced from the stiffness of the lightest design to the largest reachable stiffness (itself a
  certified maximum).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, replace

from corrugate.solver.budget import Budget, budget_scope, budget_spent
from corrugate.solver.problem import Constraint, Problem
from corrugate.solver.quantities import Tables, point_values
from corrugate.solver.quantity import MASS, Quantity
from corrugate.solver.solve import Optimum, assembly_of, layer_dict, optimize

__all__ = ["ParetoFront", "ParetoPoint", "pareto_front"]

#: Relative step beyond the last stiffness when enumerating a gridded front.
STEP_RTOL = 3e-9


@dataclass(frozen=True, slots=True)
class ParetoPoint:
    """A certified optimum: the lightest design (``mass`` g) with stiffness >= ``level``;
    ``stiffness`` is the design's own value (unit of the quantity)."""

    level: float
    stiffness: float
    mass: float
    layers: tuple[dict[str, object], ...]
    certified: bool


@dataclass(frozen=True)
class ParetoFront:
    """Points in order of increasing stiffness; ``exact`` for gridded problems."""

    quantity: Quantity
    unit: str
    points: tuple[ParetoPoint, ...]
    exact: bool
    truncated: bool
    #: What ran out when the work budget stopped the front (``"seconds"`` or ``"boxes"``: the
    #: front then ends early, not certified), None when it did not.
    stopped: str | None = None
    budget: dict[str, object] | None = None

    @property
    def certified(self) -> bool:
        return self.stopped is None and all(p.certified for p in self.points)

    def csv(self) -> str:
        """CSV text: one row per point, units in the header."""
        unit = self.unit.replace("*", " ")
        head = [f"level_{unit}", f"stiffness_{unit}", "mass_g", "certified"]
        head += [
            f"layer{i}_{k}" for i in (1, 2) for k in ("W_mm", "n", "alpha_deg", "material", "t_mm")
        ]
        rows = [",".join(head)]
        for p in self.points:
            row = [f"{p.level:.10g}", f"{p.stiffness:.10g}", f"{p.mass:.10g}", str(p.certified)]
            for layer in p.layers:
                row += [str(layer[k]) for k in ("W_mm", "n", "alpha_deg", "material", "t_mm")]
            rows.append(",".join(row))
        return "\n".join(rows) + "\n"


def _at(problem: Problem, level: float, key: Quantity, name: str) -> Problem:
    cons = [c for c in problem.constraints if c.quantity != key]
    if level > 0:
        cons.append(Constraint(name, key, "min", level))
    return replace(
        problem,
        constraints=tuple(cons),
        objective=replace(problem.objective, quantity=MASS, sense="min"),
    )


def _point(
    problem: Problem, opt: Optimum, key: Quantity, level: float, tables: Tables
) -> ParetoPoint:
    assert opt.point is not None
    assert opt.candidates is not None
    vals = point_values(
        replace(problem, constraints=(Constraint("pareto", key, "min", 0.0),)),
        *opt.candidates,
        opt.point.arrays(),
        tables,
    )
    a = assembly_of(problem, opt)
    layers = tuple(layer_dict(i + 1, layer) for i, layer in enumerate(a.layers))
    return ParetoPoint(level, float(vals[key][0]), opt.value, layers, opt.certified)


def pareto_front(
    problem: Problem,
    kind: str,
    eta_deg: float = 0.0,
    *,
    points: int = 25,
    max_points: int = 500,
    progress: Callable[[int, int | None], None] | None = None,
    budget: Budget | float | None = None,
) -> ParetoFront:
    """Trace the mass-versus-``kind`` front (see the module docstring); ``kind`` is
    ``flexural_rigidity``, ``bending_stiffness`` or ``inplane_stiffness`` (or EI, D, K).

    ``progress(done, total)`` is called after each certified solve (``total`` is None on a gridded
    front, whose length is not known in advance). ``budget``: the work budget of the whole front
    (:class:`~.budget.Budget` or CPU seconds; None: the default 60 s): when it runs out the front
    ends at the points found so far, ``stopped`` says so and ``certified`` is False."""
    with budget_scope(budget) as spent:
        front = _front(problem, kind, eta_deg, points, max_points, progress)
    stopped = spent.stopped
    return replace(front, stopped=stopped, budget=spent.as_dict())


def _front(
    problem: Problem,
    kind: str,
    eta_deg: float,
    points: int,
    max_points: int,
    progress: Callable[[int, int | None], None] | None,
) -> ParetoFront:
    key = Quantity.stiffness(kind, eta_deg)
    name = f"pareto.{kind}"
    tables = Tables(problem)
    unit = Constraint(name, key, "min", 0.0).unit
    out: list[ParetoPoint] = []
    truncated = False
    if problem.gridded:
        level = 0.0
        while True:
            p = _at(problem, level, key, name)
            opt = optimize(p, tables=tables)
            if opt.point is None:
                break
            pt = _point(p, opt, key, level, tables)
            out.append(pt)
            if progress is not None:
                progress(len(out), None)
            if budget_spent():
                break
            if len(out) >= max_points:
                truncated = True
                break
            level = pt.stiffness * (1 + STEP_RTOL)
        # a lightest design may tie in mass with a stiffer one, which dominates it
        kept = [
            p
            for p, q in zip(out, [*out[1:], None][: len(out)], strict=True)
            if q is None or q.mass > p.mass * (1 + 1e-12)
        ]
        return ParetoFront(key, unit, tuple(kept), exact=True, truncated=truncated)
    lightest = optimize(_at(problem, 0.0, key, name), tables=tables)
    if lightest.point is None:
        return ParetoFront(key, unit, (), exact=False, truncated=False)
    s0 = _point(_at(problem, 0.0, key, name), lightest, key, 0.0, tables).stiffness
    stiffest = optimize(
        replace(
            _at(problem, 0.0, key, name),
            objective=replace(problem.objective, quantity=key, sense="max"),
        ),
        tables=tables,
    )
    s1 = stiffest.value if stiffest.point is not None else s0
    n = max(points, 2)
    for k in range(n):
        if budget_spent():
            break
        level = s0 + (s1 - s0) * k / (n - 1)
        if k == n - 1:
            level = s1 * (1 - 1e-9)  # the maximum itself, inside the solver's gap
        p = _at(problem, level, key, name)
        opt = optimize(p, tables=tables)
        if opt.point is not None and math.isfinite(opt.value):
            out.append(_point(p, opt, key, level, tables))
        if progress is not None:
            progress(k + 1, n)
    return ParetoFront(key, unit, tuple(out), exact=False, truncated=False)
