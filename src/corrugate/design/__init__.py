"""Design from a behavioural spec: the problem, its certified solver and the explained answer.

Pipeline (DESIGN.md section 9): :func:`corrugate.spec.load_spec` -> :meth:`Problem.from_spec`
-> :func:`solve` -> :class:`Solution` (``to_dict()`` is the ``corrugate design --json`` object).
"""

from .bnb import BnBResult, branch_and_bound
from .problem import Candidate, Constraint, DesignVariable, Objective, Problem
from .solve import ConstraintReport, Diagnosis, RunnerUp, Solution, optimize, solve

__all__ = [
    "BnBResult",
    "Candidate",
    "Constraint",
    "ConstraintReport",
    "DesignVariable",
    "Diagnosis",
    "Objective",
    "Problem",
    "RunnerUp",
    "Solution",
    "branch_and_bound",
    "optimize",
    "solve",
]
