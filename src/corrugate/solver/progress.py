"""Progress of the branch and bound, for whoever wants to show it (the web app's jobs).

:func:`corrugate.solver.bnb.branch_and_bound` calls :func:`report` once per iteration with the
iteration count of its run, the relative gap proved so far and the best objective value found
(None before the first feasible point). Outside a :func:`reporting` block :func:`report` does
nothing (one context-variable lookup); inside one it calls the block's reporter, which decides
itself how often to pass the news on (the web's reporter throttles to a few messages a second:
:mod:`corrugate.web.jobs`). A reporter must be cheap and must not raise.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from contextlib import contextmanager
from contextvars import ContextVar

__all__ = ["Reporter", "report", "reporting"]

#: ``reporter(iterations, gap, best)``: iterations of the current branch-and-bound run (from 1),
#: its relative gap (inf without a feasible point) and the best objective value found (or None).
Reporter = Callable[[int, float, "float | None"], None]

_REPORTER: ContextVar[Reporter | None] = ContextVar("corrugate_progress", default=None)


def report(iterations: int, gap: float, best: float | None) -> None:
    """Tell the reporter of the innermost :func:`reporting` block (none: do nothing) that the
    branch and bound has run ``iterations`` iterations, proved the relative ``gap`` and found
    ``best`` (the objective value in its own unit, e.g. g for mass; None before a feasible point)."""
    reporter = _REPORTER.get()
    if reporter is not None:
        reporter(iterations, gap, best)


@contextmanager
def reporting(reporter: Reporter) -> Iterator[None]:
    """Send every :func:`report` made inside the block (same thread or task) to ``reporter``."""
    token = _REPORTER.set(reporter)
    try:
        yield
    finally:
        _REPORTER.reset(token)
