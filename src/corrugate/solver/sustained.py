"""The evaluator of a quantity under a sustained load: the same model on sheets at their creep
modulus.

A quantity with a ``duration`` t (hours; :class:`~.quantity.Quantity`) is its short-term
quantity (the same key without ``/t=``) evaluated, at points and over boxes, by that quantity's
own evaluator on candidate sheets whose Young's modulus E is replaced by the material's creep
modulus E_c(t) (:meth:`corrugate.materials.library.Material.creep_modulus`: its table read in
log time; a per-point E of the tolerance analysis scaled by E_c(t) / E). Every stiffness,
load-case and buckling model of the solver is linear in E at fixed nu (docs/load_cases.md
section 11), so on a sheet of one material the value is the short-term one times E_c(t) / E; the
substitution also covers two layers of different materials, and the bounds over boxes stay
rigorous because they are the short-term evaluator's own bounds of the substituted problem.
``Problem.from_spec`` refuses a duration on a material without creep data or beyond its table,
so every candidate here has a creep modulus at t.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from corrugate.solver.context import AtPoints, OverBoxes
from corrugate.solver.evaluator import Evaluator, Pair, register_sustained
from corrugate.solver.interval import Interval
from corrugate.solver.points import DesignPoints, LayerPoints
from corrugate.solver.problem import Candidate, Problem
from corrugate.solver.quantity import Quantity

__all__ = ["SUSTAINED", "held", "short_term"]

FloatArray = NDArray[np.float64]


def short_term(q: Quantity) -> Quantity:
    """``q`` without its duration: the quantity under a short-term load."""
    return replace(q, duration=None)


def held(c: Candidate, hours: float) -> Candidate:
    """The sheet ``c`` with its E (MPa) replaced by its creep modulus after ``hours`` (an
    interval of the same relative width when E is one: a sheet over worst-case tolerances)."""
    m = c.material
    Ec: Any = m.creep_modulus(hours)
    if isinstance(m.E, Interval):  # E over worst-case tolerances (tolerance_box): E_c likewise
        Ec = Interval(Ec * m.E.lo / m.E.mid, Ec * m.E.hi / m.E.mid)
    return replace(c, material=replace(m, E=Ec))


def _ratio(c: Candidate, hours: float) -> float:
    return c.material.creep_modulus(hours) / c.material.E


def _held_points(x: DesignPoints, c1: Candidate, c2: Candidate, hours: float) -> DesignPoints:
    """``x`` with each stored layer's per-point E (if any) scaled by its sheet's E_c / E."""
    if not any(lay.E is not None for lay in x.layers):
        return x
    ratios = (_ratio(c1, hours), _ratio(c2, hours))
    layers: list[LayerPoints] = [
        lay if lay.E is None else replace(lay, E=np.asarray(lay.E) * ratios[i])
        for i, lay in enumerate(x.layers)
    ]
    return x.with_layers(*layers)


def _point(at: AtPoints, q: Quantity) -> FloatArray:
    hours = q.duration
    assert hours is not None
    sub = at.shared(
        f"sustained:{hours!r}",
        lambda: AtPoints(
            at.problem,
            held(at.c1, hours),
            held(at.c2, hours),
            _held_points(at.x, at.c1, at.c2, hours),
            at.tables,
        ),
    )
    return sub.value(short_term(q))


def _bounds(over: OverBoxes, q: Quantity) -> Pair:
    hours = q.duration
    assert hours is not None

    def make() -> OverBoxes:
        lo = _held_points(over.lo, over.c1, over.c2, hours)
        hi = lo if over.point else _held_points(over.hi, over.c1, over.c2, hours)
        return OverBoxes(
            over.problem, held(over.c1, hours), held(over.c2, hours), lo, hi, over.tables
        )

    sub: Any = over.shared(f"sustained:{hours!r}", make)
    return sub.bounds(short_term(q))  # type: ignore[no-any-return]


def _reported(problem: Problem) -> Iterator[Quantity]:
    """The quantities under a sustained load the problem asks for."""
    return (q for q in problem.quantities if q.duration is not None)


#: The evaluator of every quantity with a duration.
SUSTAINED = register_sustained(Evaluator(("sustained",), _point, _bounds, _reported))
