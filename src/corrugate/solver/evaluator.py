"""The registry of quantity kinds the solver evaluates: one evaluator per kind.

An :class:`Evaluator` serves the quantities (:class:`~.quantity.Quantity`) of its ``kinds``: its
``point`` method gives their exact values at points (arrays over the points of an
:class:`~.context.AtPoints`) and its ``bounds`` method a lower and an upper bound over boxes
(arrays over the boxes of an :class:`~.context.OverBoxes`; its values when the boxes are points),
the two written next to each other. A quantity of a load case (``Quantity.test`` set) is served by
the evaluator registered with ``tests=True`` for its kind, every other quantity by the one of its
kind; the behaviour (support condition or load case) a quantity is taken under is its
:attr:`~.quantity.Quantity.behaviour` in :mod:`corrugate.mechanics.behaviours`, which the
evaluator reads. ``reported`` says which quantities of its kinds
:func:`~.quantities.point_values` gives for a problem (by default those the problem asks for).

:func:`~.quantities.point_values` and :func:`~.quantities.box_bounds` are loops over this
registry. A quantity under a sustained load (``Quantity.duration`` set) is served by the one
evaluator of :func:`register_sustained` (:mod:`~.sustained`: its quantity without the duration
on sheets whose E is their creep modulus), whatever its kind. A new kind is its evaluator and
one :func:`register` call (with its readable name and
unit, which :class:`~.quantity.Quantity` then reports); docs/architecture.md section 3.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from corrugate.solver.quantity import Quantity, declare_kind

if TYPE_CHECKING:
    from corrugate.solver.points import DesignPoints
    from corrugate.solver.problem import Candidate, Problem

__all__ = [
    "Evaluator",
    "Pair",
    "evaluator_of",
    "evaluators",
    "generation",
    "register",
    "register_sustained",
    "unregister",
]

FloatArray = NDArray[np.float64]
#: Lower and upper bounds over boxes (arrays over the boxes).
Pair = tuple[FloatArray, FloatArray]


def asked(problem: Problem, kinds: tuple[str, ...], tests: bool) -> Iterator[Quantity]:
    """The quantities of ``kinds`` the problem asks for (of load cases when ``tests``)."""
    for q in problem.quantities:
        if q.kind in kinds and (q.test is not None) == tests:
            yield q


@dataclass(frozen=True)
class Evaluator:
    """How the solver computes the quantities of ``kinds`` (module docstring): ``point(at, q)``
    their values at points, ``bounds(over, q)`` their bounds over boxes; ``reported(problem)``
    the quantities of these kinds that point values give (None: those asked); ``tests``: it
    serves the quantities of load cases of these kinds; ``label`` and ``unit``: the readable
    name and internal unit of a kind that :mod:`~.quantity` does not know yet."""

    kinds: tuple[str, ...]
    point: Callable[[Any, Quantity], FloatArray]
    bounds: Callable[[Any, Quantity], Pair]
    reported: Callable[[Problem], Iterable[Quantity]] | None = None
    tests: bool = False
    label: str | None = None
    unit: str | None = None

    @classmethod
    def monotone(
        cls,
        kind: str,
        value: Callable[[DesignPoints, Candidate, Candidate], FloatArray],
        *,
        falling: bool = False,
        reported: Callable[[Problem], Iterable[Quantity]] | None = None,
        label: str | None = None,
        unit: str | None = None,
    ) -> Evaluator:
        """The evaluator of a kind whose value ``value(x, c1, c2)`` at the points ``x`` on sheets
        (c1, c2) grows with every variable (falls, ``falling``): its bounds over a box are its
        values at the box's low and high corners, by the same function."""

        def point(at: Any, q: Quantity) -> FloatArray:
            return value(at.x, at.c1, at.c2)

        def bounds(over: Any, q: Quantity) -> Pair:
            low = value(over.lo, over.c1, over.c2)
            high = low if over.point else value(over.hi, over.c1, over.c2)
            return (high, low) if falling else (low, high)

        return cls((kind,), point, bounds, reported, label=label, unit=unit)

    def quantities(self, problem: Problem) -> Iterable[Quantity]:
        """The quantities of its kinds that point values give for ``problem``."""
        if self.reported is not None:
            return self.reported(problem)
        return asked(problem, self.kinds, self.tests)


_REGISTRY: dict[tuple[str, bool], Evaluator] = {}
#: The registry's key of the evaluator of every quantity under a sustained load.
_SUSTAINED = ("sustained", False)
#: How many times the registry changed (:func:`generation`).
_CHANGES = [0]


def generation() -> int:
    """A number that changes whenever an evaluator is registered or unregistered: what is
    derived from the registry (:func:`~.quantities.reported`) may be kept while it holds."""
    return _CHANGES[0]


def register(evaluator: Evaluator) -> Evaluator:
    """Add ``evaluator`` for its kinds (replacing an earlier one of the same kinds); a kind with
    a ``label`` and ``unit`` is declared to :class:`~.quantity.Quantity` too."""
    for kind in evaluator.kinds:
        _REGISTRY[(kind, evaluator.tests)] = evaluator
        if evaluator.label is not None and evaluator.unit is not None:
            declare_kind(kind, evaluator.label, evaluator.unit)
    _CHANGES[0] += 1
    return evaluator


def register_sustained(evaluator: Evaluator) -> Evaluator:
    """Make ``evaluator`` the one of every quantity with a ``duration`` (module docstring)."""
    _REGISTRY[_SUSTAINED] = evaluator
    _CHANGES[0] += 1
    return evaluator


def unregister(evaluator: Evaluator) -> None:
    """Remove ``evaluator`` (a test's toy kind)."""
    for kind in evaluator.kinds:
        if _REGISTRY.get((kind, evaluator.tests)) is evaluator:
            del _REGISTRY[(kind, evaluator.tests)]
    _CHANGES[0] += 1


def evaluator_of(q: Quantity) -> Evaluator:
    """The evaluator of ``q``: the sustained one (``q.duration`` set), else its load case's
    kind's (``q.test`` set), else its kind's."""
    if q.duration is not None:
        return _REGISTRY[_SUSTAINED]
    try:
        return _REGISTRY[(q.kind, q.test is not None)]
    except KeyError:
        raise KeyError(f"no evaluator of the quantity {q.key}") from None


def evaluators() -> tuple[Evaluator, ...]:
    """Every registered evaluator once, in the order of registration."""
    return tuple(dict.fromkeys(_REGISTRY.values()))
