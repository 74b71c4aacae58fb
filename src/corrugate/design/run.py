"""Spec -> answer: the steps ``corrugate design`` and ``POST /api/design`` share.

A plain spec is solved (:func:`corrugate.design.solve`); a spec with a ``[robust]`` table is solved
by :func:`corrugate.design.robust.robust_solve`, whose answer is labelled ``certified: false``
(its probability is a Monte Carlo estimate and its optimality is not proven).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from ..spec import Spec
from .problem import Problem
from .robust import RobustResult, robust_solve
from .solve import Solution, solve
from .tolerance import Tolerances

__all__ = ["DesignRun", "run_spec"]

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


def run_spec(spec: Spec, problem: Problem | None = None) -> DesignRun:
    """Solve ``spec`` (its ``problem`` may be given when already built)."""
    problem = problem if problem is not None else Problem.from_spec(spec)
    if spec.robust is None:
        sol = solve(problem)
        return DesignRun(sol, sol.to_dict(), None)
    r = spec.robust
    tol = Tolerances(W=r.W, alpha=r.alpha, t_rel=r.t, E_rel=r.E)
    robust = robust_solve(problem, tol, r.probability, r.samples, r.seed)
    sol = robust.solution
    payload = sol.to_dict()
    payload["certified"] = False  # the robust optimum itself is not proven (see robust.py)
    payload["robust"] = robust.as_dict(problem)
    payload["warnings"] = [*sol.warnings, dict(_ROBUST_WARNING)]
    return DesignRun(sol, payload, robust)
