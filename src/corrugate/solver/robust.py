"""Robust designs: meet every bound with a chosen probability under tolerances.

A spec's ``[robust]`` table asks that the design still meets its bounds with probability p when
W, alpha, t and E scatter with the given one-sigma tolerances (:mod:`.tolerance`). This module
finds such a design by *margin inflation*, a heuristic around the certified solver:

1. solve the spec with every bound tightened by a factor f_c (min bounds times f_c, max bounds
   divided by f_c; all f_c = 1 at first), certified;
2. Monte Carlo the design against the *original* bounds; stop when every bound holds jointly with
   probability >= p;
3. otherwise, for each constraint c whose own probability falls short of p_c = 1 - (1 - p) / m
   (m constraints that can fail: by the union bound, meeting every p_c gives p jointly), raise f_c
   by the ratio between its bound and the matching quantile of its value, and go to 1.

What is proven and what is not: each round's design is the certified optimum of the tightened
spec, and its probability of meeting the spec is a Monte Carlo estimate (reported with its
standard error, re-checked with an independent seed). That no lighter design meets the bounds with
probability p is **not** proven, so a robust answer is never reported as certified.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from corrugate.solver.problem import Constraint, Problem
from corrugate.solver.solve import Solution, solve
from corrugate.solver.tolerance import ToleranceReport, Tolerances, monte_carlo

__all__ = ["RobustResult", "robust_solve", "tighten"]

#: Rounds of margin inflation before giving up.
MAX_ROUNDS = 15


@dataclass(frozen=True)
class RobustResult:
    """The last round's certified solution of the tightened spec, the factors used, and the
    Monte Carlo check against the original spec (``check``: an independent seed)."""

    solution: Solution
    target: float
    factors: dict[str, float]
    rounds: int
    met: bool
    search: ToleranceReport | None
    check: ToleranceReport | None

    def as_dict(self, problem: Problem) -> dict[str, object]:
        p = self.check.p_all if self.check is not None else None
        n = self.check.samples if self.check is not None else 0
        se = math.sqrt(p * (1 - p) / n) if p is not None and n else None
        return {
            "target_probability": self.target,
            "probability_met": p,
            "probability_standard_error": se,
            "met": self.met,
            "rounds": self.rounds,
            "tolerances_1sigma": (self.check or self.search).tolerances.as_dict()  # type: ignore[union-attr]
            if (self.check or self.search) is not None
            else None,
            "tightened_bounds": [
                {
                    "name": c.name,
                    "bound": c.bound,
                    "factor": self.factors[c.name],
                    "tightened": tighten(c, self.factors[c.name]).bound,
                }
                for c in problem.constraints
            ],
            "constraints_probability": list(self.check.probabilities) if self.check else [],
            "certified_lightest_robust": False,
            "note": "the design is the certified optimum of the spec with the tightened bounds; "
            "its probability of meeting the original bounds is a Monte Carlo estimate, "
            "and that no lighter design reaches it is not proven",
        }


def tighten(c: Constraint, f: float) -> Constraint:
    """``c`` with its bound tightened by the factor ``f`` >= 1 (a minimum times f, a maximum
    over f): the bound a round of margin inflation solves for."""
    return replace(c, bound=c.bound * f if c.sense == "min" else c.bound / f)


def robust_solve(
    problem: Problem, tol: Tolerances, target: float, samples: int = 4000, seed: int = 0
) -> RobustResult:
    """Margin inflation (see the module docstring) until the design meets ``problem``'s bounds
    with probability >= ``target``; ``met`` is False if no round gets there."""
    factors = {c.name: 1.0 for c in problem.constraints}
    sol: Solution | None = None
    search: ToleranceReport | None = None
    for rounds in range(1, MAX_ROUNDS + 1):
        tightened = replace(
            problem, constraints=tuple(tighten(c, factors[c.name]) for c in problem.constraints)
        )
        sol = solve(tightened, explain=False)
        if sol.assembly is None:
            return RobustResult(sol, target, factors, rounds, False, search, None)
        search = monte_carlo(problem, sol.assembly, tol, samples, seed)
        if search.p_all >= target:
            check = monte_carlo(problem, sol.assembly, tol, samples, seed + 1)
            final = solve(tightened, explain=True)
            return RobustResult(
                final, target, factors, rounds, check.p_all >= target, search, check
            )
        probs = dict(search.probabilities)
        failing = [c for c in problem.constraints if probs[c.name] < 1.0]
        goal = 1 - (1 - target) / max(len(failing), 1)
        for c in failing:
            if probs[c.name] >= goal:
                continue
            v = search.values[c.quantity]
            if c.sense == "min":
                q = float(np.quantile(v, 1 - goal))
                ratio = c.bound / q if q > 0 else 2.0
            else:
                q = float(np.quantile(v, goal))
                ratio = q / c.bound if c.bound > 0 else 2.0
            factors[c.name] *= max(ratio, 1.0) * 1.002
    assert sol is not None
    return RobustResult(sol, target, factors, MAX_ROUNDS, False, search, None)
