"""The orientation trap: an infeasible spec whose directions are a quarter turn off.

A direction eta runs from layer 1's creases, which run along y (docs/spec.md; docs/models.md, "Layouts
and facet lengths"): eta = 0 is along y, the panel's length there is its extent Ly
(``side_y``), and eta = 90 deg is along x (Lx, ``side_x``). A user who puts the long side of a
part on ``side_x`` and leaves a load case at the default eta = 0 asks for a span along the short
side. :func:`orientation` recognises it: for a rectangle or a polygon with a load case whose span
the side along its eta cannot hold but the other side can (a bound without such a span, e.g.
an EI along the long side, is what the user asked for, and turning its eta would change the
requirement, not fix a mistake), it re-solves (a feasibility search within the running budget, stopped at
the first design found) the spec with every eta turned by 90 deg and, when that has no design,
with side_x and side_y swapped. When one of them has a design, its entry comes first in the
diagnosis (:func:`corrugate.solver.diagnosis.diagnose`) and its hint is the edit of each eta
(``constraints.deflection[0].eta = "90 deg"``) or the swap of the two size ranges.
"""

from __future__ import annotations

import math
from dataclasses import replace

from corrugate.solver.problem import Constraint, Objective, Problem
from corrugate.solver.quantities import Tables
from corrugate.solver.quantity import LX, LY
from corrugate.solver.solve import Diagnosis, optimize

__all__ = ["orientation"]

#: Layouts whose two sides may differ (a square and a circle have Lx = Ly: a quarter turn changes
#: nothing a spec can ask for).
_TWO_SIDES = ("rectangle", "polygon")


def _turned_eta(eta: float) -> float:
    """``eta`` + 90 deg, kept in [0, 180) deg (a bound along eta holds along eta + 180)."""
    return (eta + 90.0) % 180.0


def _entry(c: Constraint) -> str | None:
    """The spec table a directional constraint comes from (``constraints.deflection[0]`` of
    ``constraints.deflection[0].span``), None when it is not an array entry."""
    name = c.name.split(" ")[0]
    head, _, _ = name.rpartition(".")
    return head if head.endswith("]") else None


def _feasible(problem: Problem) -> bool:
    """Whether some design meets ``problem`` (a search stopped at its first design)."""
    plain = replace(problem, objective=Objective())
    found = optimize(plain, tables=Tables(plain), stop_below=math.inf)
    return found.point is not None


def _turned(problem: Problem) -> Problem:
    """``problem`` with every directional quantity (constraints and objective) turned by 90 deg."""

    def turn(c: Constraint) -> Constraint:
        q = c.quantity
        if q.eta is None:
            return c
        return replace(c, quantity=replace(q, eta=_turned_eta(q.eta)))

    o = problem.objective
    objective = o
    if o.quantity.eta is not None:
        objective = replace(o, quantity=replace(o.quantity, eta=_turned_eta(o.quantity.eta)))
    return replace(
        problem,
        constraints=tuple(turn(c) for c in problem.constraints),
        objective=objective,
    )


def _swapped(problem: Problem) -> Problem:
    """``problem`` with the bounds of Lx (side_x) and Ly (side_y) exchanged."""
    other = {LX: LY, LY: LX}

    def swap(c: Constraint) -> Constraint:
        q = other.get(c.quantity)
        return c if q is None else replace(c, quantity=q)

    return replace(problem, constraints=tuple(swap(c) for c in problem.constraints))


def _range(problem: Problem, q: object) -> tuple[float | None, float | None]:
    """The (min, max) a spec's size constraints put on the extent ``q`` (LX or LY), mm."""
    lo: float | None = None
    hi: float | None = None
    for c in problem.constraints:
        if c.quantity != q:
            continue
        if c.sense == "min":
            lo = c.bound if lo is None else max(lo, c.bound)
        else:
            hi = c.bound if hi is None else min(hi, c.bound)
    return lo, hi


def _range_toml(lo: float | None, hi: float | None) -> str:
    """A size range as the spec writes it: ``{ min = "35 mm", max = "40 mm" }``."""
    parts = [f'{k} = "{v:g} mm"' for k, v in (("min", lo), ("max", hi)) if v is not None]
    return "{ " + ", ".join(parts) + " }"


def _side(eta: float) -> str:
    """The side a length along ``eta`` (0 or 90 deg) runs along."""
    return "side_y" if eta % 180 == 0 else "side_x"


def _spans(problem: Problem) -> list[str]:
    """For each load case's span (a ``length`` bound along the creases) that the side along its
    eta cannot hold but the other side can: ``constraints.deflection[0]: eta = 0 deg runs along
    y (side_y: at most 40 mm); the span of 150 mm fits side_x (at most 160 mm)``."""
    out = []
    x_hi = _range(problem, LX)[1]
    y_hi = _range(problem, LY)[1]
    for c in problem.constraints:
        q = c.quantity
        if q.kind != "length" or q.eta is None or q.eta % 90 != 0 or c.sense != "min":
            continue
        along, across = (y_hi, x_hi) if q.eta % 180 == 0 else (x_hi, y_hi)
        if along is None or c.bound <= along or (across is not None and c.bound > across):
            continue
        axis = "y" if q.eta % 180 == 0 else "x"
        other = _side(_turned_eta(q.eta))
        fits = other if across is None else f"{other} (at most {across:g} mm)"
        out.append(
            f"{_entry(c) or c.name}: eta = {q.eta:g} deg runs along {axis} ({_side(q.eta)}: "
            f"at most {along:g} mm); the span of {c.bound:g} mm fits {fits}"
        )
    return out


def orientation(problem: Problem) -> list[Diagnosis]:
    """The orientation trap of ``problem`` (infeasible; module docstring): one entry (kind
    ``orientation``) when the spec with its directions turned by 90 deg, or its sides swapped,
    has a design; none otherwise."""
    if problem.layout.name not in _TWO_SIDES:
        return []
    spans = _spans(problem)  # the evidence of a mistake (module docstring)
    if not spans:
        return []
    directed = [c for c in problem.constraints if c.quantity.eta is not None]
    entries: dict[str, float] = {}
    for c in directed:
        entry = _entry(c)
        if entry is not None and c.quantity.eta is not None:
            entries.setdefault(entry, c.quantity.eta)
    names = tuple(c.name for c in directed)
    if _feasible(_turned(problem)):
        edits = [f'{e}.eta = "{_turned_eta(eta):g} deg"' for e, eta in entries.items()]
        hint = " and ".join(edits) if edits else None
        fix = f"set {hint}" if hint else "turn every eta by 90 deg"
        message = (
            f"{'; '.join(spans)}: {fix} (or swap side_x and side_y); then the spec is feasible"
        )
    else:
        x, y = _range(problem, LX), _range(problem, LY)
        if x == y or not _feasible(_swapped(problem)):
            return []
        hint = f"constraints.side_x = {_range_toml(*y)} and constraints.side_y = {_range_toml(*x)}"
        message = f"{'; '.join(spans)}: swap side_x and side_y ({hint})"
    return [
        Diagnosis(names, None, None, "", message + f"; hint: {hint}", kind="orientation", hint=hint)
    ]
