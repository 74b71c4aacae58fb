"""The solver's work budget: CPU seconds and boxes for one design or one Pareto front.

Every branch and bound run (:func:`corrugate.solver.bnb.branch_and_bound`) inside a
:func:`budget_scope` charges its boxes to the scope's :class:`Budget` and stops, uncertified, at the
start of the first iteration after the budget is spent; :func:`corrugate.solver.solve.solve` and
:func:`corrugate.solver.pareto.pareto_front` open a scope, so the explanation (binding checks,
runner-ups, the diagnosis of an infeasible spec) spends the same budget as the search: once it is
spent, each later re-solve stops after its first iteration and the explanation is left partial.

Seconds are CPU seconds of the process (``time.process_time``: user + system, all threads; on an
idle machine about wall seconds, on a busy one fewer than wall seconds), so that the same spec stops
at the same point whatever else the machine does. A stopped answer is "not certified within the
budget" (``corrugate design`` and ``pareto``: exit code 4): the best design found so far and the
proven gap.
"""

from __future__ import annotations

import time
from collections.abc import Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass, field

from corrugate.core.errors import InputError
from corrugate.core.limits import MAX_BUDGET_BOXES, check

__all__ = [
    "DEFAULT_BUDGET_BOXES",
    "DEFAULT_BUDGET_SECONDS",
    "Budget",
    "budget_scope",
    "budget_spent",
    "current_budget",
]

#: CPU seconds one design (search and explanation) or one Pareto front may take by default.
DEFAULT_BUDGET_SECONDS = 60.0
#: Boxes bounded by every branch and bound run of one design or front, by default (the case
#: study takes about 10^4; 10^8 boxes take several minutes, so the seconds stop first).
DEFAULT_BUDGET_BOXES = 100_000_000


@dataclass
class Budget:
    """``seconds`` of CPU time (s) and ``boxes`` bounded, counted from the first use: mutable
    (it counts what was spent). ``stopped`` is what ran out first (``"seconds"`` or ``"boxes"``),
    None while the budget lasts."""

    seconds: float = DEFAULT_BUDGET_SECONDS
    boxes: int = DEFAULT_BUDGET_BOXES
    used_boxes: int = 0
    stopped: str | None = None
    _start: float | None = field(default=None, repr=False)

    def __post_init__(self) -> None:
        self.seconds = check("budget", self.seconds)
        if isinstance(self.boxes, bool) or not 1 <= int(self.boxes) <= MAX_BUDGET_BOXES:
            raise InputError("budget.boxes", self.boxes, f"1 <= boxes <= {MAX_BUDGET_BOXES:g}")
        self.boxes = int(self.boxes)

    def start(self) -> None:
        """Start the clock (a second call does nothing)."""
        if self._start is None:
            self._start = time.process_time()

    @property
    def used_seconds(self) -> float:
        """CPU seconds spent since :meth:`start` (0 before)."""
        return 0.0 if self._start is None else time.process_time() - self._start

    def charge(self, boxes: int) -> None:
        """Count ``boxes`` more boxes bounded."""
        self.used_boxes += boxes

    @property
    def exhausted(self) -> bool:
        """Whether the seconds or the boxes are spent (then ``stopped`` says which)."""
        if self.stopped is None:
            if self.used_boxes >= self.boxes:
                self.stopped = "boxes"
            elif self.used_seconds >= self.seconds:
                self.stopped = "seconds"
        return self.stopped is not None

    @property
    def label(self) -> str:
        """E.g. ``60 s of CPU time`` or ``1000 boxes``: what was spent first (the seconds while
        nothing was)."""
        if self.stopped == "boxes":
            return f"{self.boxes} boxes"
        return f"{self.seconds:g} s of CPU time"

    def as_dict(self) -> dict[str, object]:
        """The ``solver.budget`` object of ``design --json`` (keys carry units)."""
        return {
            "cpu_seconds": self.seconds,
            "boxes": self.boxes,
            "used_cpu_seconds": self.used_seconds,
            "used_boxes": self.used_boxes,
            "exhausted": self.stopped is not None,
            "stopped_by": self.stopped,
        }


_CURRENT: ContextVar[Budget | None] = ContextVar("corrugate_budget", default=None)


def current_budget() -> Budget | None:
    """The budget of the innermost :func:`budget_scope`, None outside any."""
    return _CURRENT.get()


def budget_spent() -> bool:
    """Whether the budget of the innermost :func:`budget_scope` is spent (False outside any):
    the check the search and each step of the explanation make before more work."""
    budget = _CURRENT.get()
    return budget is not None and budget.exhausted


@contextmanager
def budget_scope(budget: Budget | float | None = None) -> Iterator[Budget]:
    """Run the block under ``budget`` (a :class:`Budget`, a number of CPU seconds, or None: the
    enclosing scope's budget if there is one, else a default one), started now."""
    outer = _CURRENT.get()
    if budget is None:
        chosen = outer if outer is not None else Budget()
    elif isinstance(budget, Budget):
        chosen = budget
    else:
        chosen = Budget(seconds=float(budget))
    chosen.start()
    token = _CURRENT.set(chosen)
    try:
        yield chosen
    finally:
        _CURRENT.reset(token)
