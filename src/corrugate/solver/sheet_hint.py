"""A thicker or stiffer sheet for a spec that asks more than its sheets can give (issue 36 item 4).

When the diagnosis (:mod:`corrugate.solver.diagnosis`) finds that a behavioural bound (a
stiffness, a load case's P/delta or capacity, a buckling load) is short by more than a tolerance
(:data:`~corrugate.solver.diagnosis.SMALL_EDIT`) with the spec's own sheets, the fix a maker
wants is usually another sheet, not a weaker requirement. :func:`stiffer_sheet` re-solves the
spec (a feasibility search within the running budget, stopped at its first design) with one
library sheet at a time: first the thicker sheets of the spec's own material (its library
``thicknesses``, ascending), then up to :data:`MAX_OTHERS` sheets of other library materials
whose E t (the membrane stiffness the facets' bending of a corrugated panel is made of,
docs/theory.md section 3) is at least what the shortfall asks (the bound over its reach, times
the spec's largest E t, less a fifth), in ascending order of E t. The first that has a design is the hint, written
as the spec's material table (``material = { name = "dura-lar", thickness = "0.25 mm" }``, or
``materials = [...]`` for a spec with several candidate sheets).
"""

from __future__ import annotations

import math
from dataclasses import replace

from corrugate.materials.library import Material, library
from corrugate.solver.budget import budget_spent
from corrugate.solver.problem import Candidate, Constraint, Objective, Problem
from corrugate.solver.quantities import Tables
from corrugate.solver.solve import Diagnosis, optimize

__all__ = ["MAX_OTHERS", "stiffer_sheet"]

#: How many sheets of other materials the search tries (each a feasibility search).
MAX_OTHERS = 4


def _feasible(problem: Problem) -> bool:
    plain = replace(problem, objective=Objective())
    return optimize(plain, tables=Tables(plain), stop_below=math.inf).point is not None


def _order(problem: Problem, need: float) -> list[tuple[Material, float, str]]:
    """The sheets to try, in order, each with why: thicker sheets of the spec's own materials,
    then up to :data:`MAX_OTHERS` other materials' sheets, ascending in E t, among those whose
    E t is at least ``need`` times (less a fifth: the scaling is the membrane's, approximate)
    the spec's largest."""
    lib = library()
    own = {c.material.id for c in problem.candidates}
    t_max = {m: max(c.t for c in problem.candidates if c.material.id == m) for m in own}
    least = 0.8 * need * max(c.material.E * c.t for c in problem.candidates)
    out: list[tuple[Material, float, str]] = []
    for m in sorted(own):
        if m in lib:
            out += [
                (lib[m], t, "a thicker sheet")
                for t in lib[m].thicknesses
                if t > t_max[m] and lib[m].E * t >= least
            ]
    others = sorted(
        (mat.E * t, mat.id, t)
        for mat in lib.values()
        if mat.id not in own
        for t in mat.thicknesses
        if mat.E * t >= least
    )
    out += [(lib[m], t, "a stiffer sheet") for _, m, t in others[:MAX_OTHERS]]
    return out


def _table(problem: Problem, m: Material, t: float) -> str:
    entry = f'{{ name = "{m.id}", thickness = "{t:g} mm" }}'
    return f"materials = [{entry}]" if len(problem.candidates) > 1 else f"material = {entry}"


def stiffer_sheet(problem: Problem, short: list[Constraint], need: float = 1.0) -> list[Diagnosis]:
    """One entry (kind ``sheet``) naming the first library sheet with which ``problem``
    (infeasible; ``short``: its behavioural bounds that no design of its sheets reaches, by a
    factor ``need`` at most) has a design (module docstring); none when no sheet tried has one or
    the budget runs out."""
    if not short:
        return []
    names = tuple(c.name for c in short)
    sheets = ", ".join(c.label for c in problem.candidates)
    for m, t, why in _order(problem, need):
        if budget_spent():
            return []
        if not _feasible(replace(problem, candidates=(Candidate(m, t),))):
            continue
        hint = _table(problem, m, t)
        message = (
            f"{', '.join(names)}: the spec's sheets ({sheets}) do not reach it with the other "
            f"constraints held; {why}, {m.id} {t:g} mm (E = {m.E / 1000:g} GPa), makes the spec "
            f"feasible; hint: {hint}"
        )
        return [Diagnosis(names, None, None, "", message, kind="sheet", hint=hint)]
    return []
