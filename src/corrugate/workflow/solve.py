"""The certified answer to a spec and the JSON object ``corrugate design --json`` prints for it
(:func:`solve_spec`, :class:`DesignRun`): a plain spec solved by :func:`corrugate.solver.solve`, a
spec with a ``[robust]`` table by :func:`corrugate.solver.robust.robust_solve` (docs/spec.md,
section robust). The solver is imported when a spec is solved, so the command line starts
without it.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from corrugate.solver.problem import Problem
    from corrugate.solver.robust import RobustResult
    from corrugate.solver.solve import Solution
    from corrugate.spec.schema import Spec

__all__ = ["DesignRun", "solve_spec"]


_ROBUST_WARNING = {
    "code": "robust-not-certified",
    "message": (
        "robust design: certified optimum of the spec with tightened bounds; its probability of "
        "meeting the spec is a Monte Carlo estimate and its optimality is not proven"
    ),
}


@dataclass(frozen=True)
class DesignRun:
    """The solution, the JSON object ``corrugate design --json`` prints, and the robust search
    (None for a plain spec)."""

    solution: Solution
    payload: dict[str, Any]
    robust: RobustResult | None


def solve_spec(
    spec: Spec, problem: Problem | None = None, *, budget: float | None = None
) -> DesignRun:
    """The solution of ``spec`` (its ``problem`` may be given when already built) and the JSON
    object ``corrugate design --json`` prints for it. A plain spec is solved
    (:func:`corrugate.solver.solve`); a spec with a ``[robust]`` table by
    :func:`corrugate.solver.robust.robust_solve`, whose answer is labelled ``certified: false``
    (its probability is a Monte Carlo estimate and its optimality is not proven).

    ``budget``: CPU seconds for the whole solve, explanation included (checked against
    ``LIMITS["budget"]``; None: the default 60 s, :mod:`corrugate.solver.budget`); when it runs
    out the solution's status is ``not-certified`` (``corrugate design``: exit code 4)."""
    from corrugate.solver.budget import Budget, budget_scope
    from corrugate.solver.problem import Problem
    from corrugate.solver.solve import solve

    chosen = Budget() if budget is None else Budget(seconds=budget)
    problem = problem if problem is not None else Problem.from_spec(spec)
    if spec.robust is None:
        sol = solve(problem, budget=chosen)
        return DesignRun(sol, sol.to_dict(), None)
    from corrugate.solver.robust import robust_solve  # a robust spec only: Monte Carlo's modules
    from corrugate.solver.tolerance import Tolerances

    r = spec.robust
    tol = Tolerances(W=r.W, alpha=r.alpha, t_rel=r.t, E_rel=r.E)
    with budget_scope(chosen):
        robust = robust_solve(problem, tol, r.probability, r.samples, r.seed)
    sol = robust.solution
    payload = {
        **sol.to_dict(),
        "certified": False,  # the robust optimum itself is not proven (see robust.py)
        "robust": robust.as_dict(problem),
        "warnings": [*sol.warnings, dict(_ROBUST_WARNING)],
    }
    return DesignRun(sol, payload, robust)
