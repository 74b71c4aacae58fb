"""Progress of a running search, for whoever listens (the web app's job page).

:func:`corrugate.solver.bnb.branch_and_bound` calls :func:`report` once per iteration with the
iterations done, the relative gap between the incumbent and the lowest open bound, and the
incumbent's objective value (None before one is found). Nothing listens by default (a no-op); a
caller sets a reporter for a block with :func:`reporting`, a context variable, so concurrent
searches in threads or tasks keep their own.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from contextlib import contextmanager
from contextvars import ContextVar

__all__ = ["Reporter", "report", "reporting"]

#: A listener: (iterations, gap, best objective value or None).
Reporter = Callable[[int, float, "float | None"], None]

_REPORTER: ContextVar[Reporter | None] = ContextVar("corrugate_progress", default=None)


def report(iterations: int, gap: float, best: float | None) -> None:
    """Tell the current reporter (if any) how far the search is."""
    fn = _REPORTER.get()
    if fn is not None:
        fn(iterations, gap, best)


@contextmanager
def reporting(fn: Reporter) -> Iterator[None]:
    """Send the :func:`report` calls made inside the block to ``fn``."""
    token = _REPORTER.set(fn)
    try:
        yield
    finally:
        _REPORTER.reset(token)
