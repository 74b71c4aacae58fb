"""The certified solver: a spec's problem, its branch and bound and the explained answer.

Pipeline (docs/architecture.md): :func:`corrugate.spec.schema.load_spec` -> :meth:`Problem.from_spec`
-> :func:`solve` -> :class:`Solution` (``to_dict()`` is the ``corrugate design --json`` object).
"""

from corrugate.solver.bnb import BnBResult, branch_and_bound
from corrugate.solver.budget import Budget, budget_scope
from corrugate.solver.problem import Candidate, Constraint, DesignVariable, Objective, Problem
from corrugate.solver.quantity import Quantity
from corrugate.solver.solve import ConstraintReport, Diagnosis, RunnerUp, Solution, optimize, solve

__all__ = [
    "BnBResult",
    "Budget",
    "Candidate",
    "Constraint",
    "ConstraintReport",
    "DesignVariable",
    "Diagnosis",
    "Objective",
    "Problem",
    "Quantity",
    "RunnerUp",
    "Solution",
    "branch_and_bound",
    "budget_scope",
    "optimize",
    "solve",
]
