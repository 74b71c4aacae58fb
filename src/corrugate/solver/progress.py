"""Progress of the branch and bound and of the stages of a solve, for whoever wants to show it
(the web app's jobs, the command line's progress display).

:func:`corrugate.solver.bnb.branch_and_bound` calls :func:`report` once per iteration with the
iteration count of its run, the relative gap proved so far and the best objective value found
(None before the first feasible point). :func:`corrugate.solver.solve.solve` and the diagnosis
(:mod:`corrugate.solver.diagnosis`) call :func:`stage` when they enter a stage of the answer:
:data:`SEARCHING` (the certified search), then, explaining it, :data:`BINDING`,
:data:`RUNNER_UPS` or :data:`DIAGNOSIS` (optionally with what it looks at, e.g.
``explaining: diagnosis (constraints.side.max)``). Outside a :func:`reporting` block both do
nothing (one context-variable lookup); inside one they call the block's reporter and stage
listener, which decide themselves how often to pass the news on (the web's reporter throttles
to a few messages a second: :mod:`corrugate.web.jobs`; the command line's to a line every few
seconds off a terminal: :mod:`corrugate.cli.progress`). Both must be cheap and must not raise.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from contextlib import contextmanager
from contextvars import ContextVar

__all__ = [
    "BINDING",
    "DIAGNOSIS",
    "RUNNER_UPS",
    "SEARCHING",
    "Reporter",
    "StageListener",
    "report",
    "reporting",
    "stage",
]

#: ``reporter(iterations, gap, best)``: iterations of the current branch-and-bound run (from 1),
#: its relative gap (inf without a feasible point) and the best objective value found (or None).
Reporter = Callable[[int, float, "float | None"], None]
#: ``listener(text)``: the stage a solve has entered (one of the names below, maybe with a detail).
StageListener = Callable[[str], None]

#: The certified search for the optimum (or the proof that no design exists).
SEARCHING = "searching"
#: The explanation of an answer: which constraints bind (a re-solve per constraint).
BINDING = "explaining: binding checks"
#: The explanation of an answer: the best design for each n near the optimum's.
RUNNER_UPS = "explaining: runner-ups"
#: The explanation of an infeasible spec: what it misses (:mod:`corrugate.solver.diagnosis`).
DIAGNOSIS = "explaining: diagnosis"

_REPORTER: ContextVar[Reporter | None] = ContextVar("corrugate_progress", default=None)
_STAGE: ContextVar[StageListener | None] = ContextVar("corrugate_stage", default=None)


def report(iterations: int, gap: float, best: float | None) -> None:
    """Tell the reporter of the innermost :func:`reporting` block (none: do nothing) that the
    branch and bound has run ``iterations`` iterations, proved the relative ``gap`` and found
    ``best`` (the objective value in its own unit, e.g. g for mass; None before a feasible point)."""
    reporter = _REPORTER.get()
    if reporter is not None:
        reporter(iterations, gap, best)


def stage(name: str, detail: str | None = None) -> None:
    """Tell the stage listener of the innermost :func:`reporting` block (none: do nothing) that
    the solve has entered the stage ``name`` (:data:`SEARCHING`, ...), looking at ``detail``
    (shown in parentheses: ``explaining: diagnosis (constraints.side.max)``)."""
    listener = _STAGE.get()
    if listener is not None:
        listener(name if detail is None else f"{name} ({detail})")


@contextmanager
def reporting(reporter: Reporter, stages: StageListener | None = None) -> Iterator[None]:
    """Send every :func:`report` made inside the block (same thread or task) to ``reporter``
    and every :func:`stage` to ``stages`` (None: stages are not heard)."""
    token = _REPORTER.set(reporter)
    stage_token = _STAGE.set(stages)
    try:
        yield
    finally:
        _STAGE.reset(stage_token)
        _REPORTER.reset(token)
