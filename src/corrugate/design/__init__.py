"""Design from a behavioural spec: the problem, its certified solver and the explained answer.

Pipeline (DESIGN.md section 9): :func:`corrugate.spec.load_spec` -> :meth:`Problem.from_spec`
-> :func:`solve` -> :class:`Solution` (``to_dict()`` is the ``corrugate design --json`` object).
"""

import sys
from types import ModuleType
from typing import TYPE_CHECKING, Any

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

if TYPE_CHECKING:
    from ..api import DesignResult


class _CallableModule(ModuleType):
    """``corrugate.design(spec)`` is :func:`corrugate.api.design`: this subpackage, the solver,
    is also the one call a notebook needs (its submodules import as before)."""

    def __call__(self, spec: Any) -> "DesignResult":
        from ..api import design

        return design(spec)


sys.modules[__name__].__class__ = _CallableModule
