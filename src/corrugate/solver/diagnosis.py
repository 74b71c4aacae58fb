"""Why no design meets a spec: the numbers, the cause and what would change it.

:func:`diagnose` explains an infeasible :class:`~corrugate.solver.problem.Problem` with certified
re-solves of variants of it (each one the branch and bound of :mod:`.bnb`, so every number is the
best a design in the variable bounds reaches, not an estimate). A variant that only drops
constraints (one, a partner, a pair, the off-axis set of at most two) is searched warm, from the
boxes of the infeasible solve's tree that break nothing but the dropped constraints
(:class:`~.archive.Archive`): every design of the variant lies in them.

* **the orientation trap** (first, :mod:`.orientation`): a rectangle or polygon whose spec has a
  design once every eta is turned by 90 deg (or side_x and side_y are swapped), e.g. a 150 mm
  cantilever span at the default eta = 0 (along y) on a part whose 150 mm side is side_x; the
  hint is the edit of each eta (or the swap).
* **identical layers on a rectangle or polygon**: both layers fold to the same extent, Lx = Ly (a
  square bounding box). When ``layers = "independent"`` makes the spec feasible, that is the
  hint, with the lightest design it allows; when the side_x and side_y ranges do not overlap,
  the diagnosis says that identical layers cannot meet them whatever else is changed.
* **off-axis stiffness with free sides** (docs/offaxis.md): off the crease directions no facet of
  a free panel runs from one loaded edge to the other, so its EI, D and K there are those of the
  soft across-crease bending, twisting and shear. The diagnosis gives each off-axis bound's best
  value with the other constraints held, what a rigid frame (``support = "frame"``) would give
  (the spec re-solved with that support), the best along the creases, and names a face sheet
  (not modelled) as the other way.
* **one constraint**: for each constraint whose relaxation alone restores feasibility, the best
  value of its quantity with every other constraint held (the most rigidity the size limits
  allow, ...), the shortfall, the constraints it binds together with (each one dropped in turn:
  the value reached without it) and the value with no other constraint at all (variable bounds
  only); the hint is the edit, written with its unit, rounded towards feasible.
* **two constraints** when no single one is to blame: each one's best with the other dropped,
  and together (the other relaxed to its own best), and the pair of edits that restores
  feasibility.
* **a thicker or stiffer sheet** (:mod:`.sheet_hint`) when a behavioural bound is short by more
  than :data:`SMALL_EDIT`, or no edit of one or two bounds helps: the first library sheet with
  which the spec has a design.
* otherwise, why no hint exists.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from dataclasses import replace

import numpy as np

from corrugate.names import DEFAULT_MARGIN_MM
from corrugate.solver.archive import ARCHIVE_DEPTH, Archive
from corrugate.solver.budget import budget_spent, current_budget
from corrugate.solver.orientation import orientation
from corrugate.solver.problem import Constraint, Problem
from corrugate.solver.progress import DIAGNOSIS, stage
from corrugate.solver.quantities import Tables
from corrugate.solver.quantity import STIFFNESS, Quantity
from corrugate.solver.solve import Diagnosis, Optimum, Start, constraint_bits, optimize

__all__ = ["SMALL_EDIT", "best_hint", "diagnose", "shown"]

#: Relative improvement above which dropping a constraint counts as raising another's reach.
_BETTER_RTOL = 1e-9
#: A relative edit of one bound up to which it is the hint even when a structural change (independent
#: layers, a frame) would also restore feasibility: a few per cent is a tolerance, not a redesign.
SMALL_EDIT = 0.10
#: How many constraints a single diagnosis names as binding together with it.
_MAX_PARTNERS = 3


def shown(value: float, unit: str) -> str:
    """``value`` (internal ``unit``) as the spec writes it: a rigidity in mN*m^2, else the unit."""
    if unit == "N*mm^2":
        return f"{value / 1000:.4g} mN*m^2"
    return f"{value:.4g} {unit}".rstrip()


def _rounded(value: float, unit: str, down: bool) -> str:
    """``value`` rounded to 4 significant digits towards ``down`` (a lower bound rounded down
    still holds), as a quoted spec value with its unit, or a bare TOML number without one
    (``fabrication.max_t_over_W = 0.08334``)."""
    v = value / 1000 if unit == "N*mm^2" else value
    text_unit = "mN*m^2" if unit == "N*mm^2" else unit
    if v != 0 and math.isfinite(v):
        step = 10.0 ** (math.floor(math.log10(abs(v))) - 3)
        v = (math.floor(v / step) if down else math.ceil(v / step)) * step
    return f'"{v:.4g} {text_unit}"' if text_unit else f"{v:.4g}"  # a plain number unquoted


def _in_written(c: Constraint, value: float, unit: str) -> tuple[float, str] | None:
    """``value`` (internal ``unit``) in the unit the spec wrote ``c``'s bound in
    (:attr:`~.problem.Constraint.written`: ``1e8`` N*mm^2 -> ``(100, "N*m^2")`` when the spec
    wrote ``"100 N*m^2"``); None when it wrote a plain number or another dimension."""
    if not c.written or not unit or not math.isfinite(value):
        return None
    from corrugate.core.errors import CorrugateError
    from corrugate.core.units import parse_quantity

    try:
        factor = parse_quantity(f"1 {c.written}", unit, c.name)
    except CorrugateError:
        return None
    return (value / factor, c.written) if factor > 0 and math.isfinite(factor) else None


def _shown(c: Constraint, value: float, unit: str | None = None) -> str:
    """``value`` of ``c``'s quantity (or of ``unit``, e.g. a deflection in mm) as the spec wrote
    its bound: in its unit (:func:`_in_written`), else as :func:`shown` writes it."""
    u = c.unit if unit is None else unit
    w = _in_written(c, value, u)
    return shown(value, u) if w is None else f"{w[0]:.4g} {w[1]}"


def _rounded_for(c: Constraint, value: float, unit: str, down: bool) -> str:
    """:func:`_rounded` in the unit the spec wrote ``c``'s bound in, when it wrote one."""
    w = _in_written(c, value, unit)
    if w is None:
        return _rounded(value, unit, down)
    v, text_unit = w
    if v != 0 and math.isfinite(v):
        step = 10.0 ** (math.floor(math.log10(abs(v))) - 3)
        v = (math.floor(v / step) if down else math.ceil(v / step)) * step
    return f'"{v:.4g} {text_unit}"'


def _key(c: Constraint) -> str:
    """The spec key of ``c`` (``constraints.sheet_max (flat blank)`` -> ``constraints.sheet_max``)."""
    return c.name.split(" ")[0]


#: Relative gap to which the diagnosis proves a best reachable value with continuous variables:
#: the value reported is a design's own (reachable, so a hint built on it holds), and no design
#: is better by more than this; it is shown to 4 digits. (The design's own gap, 1e-12, took the
#: thin-ligament wheel's off-axis diagnosis over 60 s: 5000 iterations of a few boxes each.)
DIAGNOSIS_GAP_RTOL = 1e-6


class _Tree:
    """The closed boxes of the infeasible solve (:attr:`~.solve.Optimum.archives`, per sheet
    pair), reopened for a problem with some of its constraints dropped: only the boxes shown
    to break nothing but dropped constraints can hold a design of it (None: search all)."""

    def __init__(self, problem: Problem, archives: tuple[Archive, ...] | None) -> None:
        self.problem = problem
        self.archives = archives
        #: the searches of :meth:`best` kept for a second asker, by what they search (the
        #: off-axis bound's best with the other constraints held, asked again by its single)
        self.memo: dict[tuple[object, ...], Optimum] = {}

    def best(
        self,
        problem: Problem,
        c: Constraint,
        tables: Tables,
        dropped: tuple[Constraint, ...],
        keep: bool = False,
    ) -> Optimum:
        """:func:`_best` of ``c``'s quantity under ``problem`` (this tree's problem less the
        constraints ``dropped``), warm from the boxes that break nothing but ``dropped``,
        recorded on a grid (for :meth:`partner`); ``keep``: kept for the next asker of the
        same search, which takes it (its archives are not held longer: the memory of the
        diagnosis stays that of one search at a time, and this one)."""
        key = (
            tuple((d.name, d.quantity, d.sense, d.bound) for d in problem.constraints),
            c.quantity,
            c.sense,
            tuple(d.name for d in dropped),
        )
        found = self.memo.pop(key, None)
        if found is None:
            warm = self.warm(*dropped) if len(dropped) <= ARCHIVE_DEPTH else None
            found = _best(problem, c.quantity, c.sense, tables, warm, record=self.problem.gridded)
        if keep:
            self.memo[key] = found
        return found

    def partner(self, c: Constraint, d: Constraint, best: Optimum) -> list[Start] | None:
        """Per pair, the boxes that may hold a design meeting every constraint but ``c`` and
        ``d`` whose value of ``c``'s quantity is better than ``best``'s (the search of the
        problem without ``c``, from :meth:`warm` of ``c``, recorded): inside the boxes that
        search started from, its own closed boxes that may hold such a design breaking ``d``
        alone (a box closed by its bound holds nothing better than ``best``); outside them,
        this tree's boxes shown to break ``d`` and nothing outside {``c``, ``d``} (bounds
        forgotten). None when an archive is missing (then :meth:`warm` of both)."""
        closed = best.tree()
        if self.archives is None or closed is None or len(closed) != len(self.archives):
            return None
        rest = self.problem.without(c.name)
        bc = np.uint64(constraint_bits(self.problem, c.name))
        both = bc | np.uint64(constraint_bits(self.problem, d.name))
        bd = constraint_bits(rest, d.name)
        sign = 1.0 if c.sense == "max" else -1.0  # best's search minimises sign * q
        out = []
        for a, b in zip(self.archives, closed, strict=True):
            lo, hi, bound = b.reopen(bd, sign * best.value)
            outside = ((a.mask & ~both) == 0) & ((a.mask & ~bc) != 0)
            out.append(
                (
                    np.concatenate([lo, a.lo[outside]]),
                    np.concatenate([hi, a.hi[outside]]),
                    np.concatenate([bound, np.full(int(outside.sum()), -np.inf)]),
                )
            )
        return out

    def warm(self, *dropped: Constraint) -> list[Start] | None:
        """Per pair, the boxes that may hold a design meeting every constraint but ``dropped``
        (their bounds forgotten: the re-solve may optimise another quantity)."""
        if self.archives is None:
            return None
        bits = 0
        for c in dropped:
            bits |= constraint_bits(self.problem, c.name)
        out = []
        for a in self.archives:
            lo, hi, bound = a.reopen(bits)
            out.append((lo, hi, np.full(len(bound), -np.inf)))
        return out


def _best(
    problem: Problem,
    q: Quantity,
    sense: str,
    tables: Tables | None,
    warm: Sequence[Start] | None = None,
    record: bool = False,
    incumbent: float | None = None,
) -> Optimum:
    """The best value of ``q`` (largest for ``sense`` min, smallest for max) under ``problem``'s
    constraints, to the relative gap :data:`DIAGNOSIS_GAP_RTOL` (``warm``: per sheet pair, boxes
    that hold every design of ``problem``, :func:`~.solve.optimize`; ``record``: keep the closed
    boxes, :attr:`~.solve.Optimum.archives`; ``incumbent``: a value of ``q`` to beat, the
    answer then holding a design only if one beats it)."""
    return optimize(
        problem.with_objective(q, "max" if sense == "min" else "min"),
        tables=tables if tables is not None else Tables(problem),
        gap_rtol=DIAGNOSIS_GAP_RTOL,
        warm=warm,
        record=record,
        incumbent=incumbent,
    )


def _closes_alone(archives: tuple[Archive, ...], problem: Problem, kept: set[str], d: str) -> bool:
    """Whether some box of ``archives`` (closed boxes of a search of ``problem``) was shown to
    break the constraint ``d`` and no constraint outside the names ``kept`` (which include
    ``d``)."""
    bd = np.uint64(constraint_bits(problem, d))
    allowed = np.uint64(sum(constraint_bits(problem, name) for name in kept))
    return any(bool(np.any(((a.mask & ~allowed) == 0) & ((a.mask & bd) != 0))) for a in archives)


def _cannot_improve(
    problem: Problem, c: Constraint, d: Constraint, tree: _Tree, best: Optimum
) -> bool:
    """Whether dropping ``d`` as well certainly leaves ``c``'s best (``best``: the search of
    ``problem`` without ``c``, recorded) where it is, on a grid (exact values): a design better
    than ``best`` without ``c`` and ``d`` must break ``d`` (else ``best`` would not be the best),
    so it lies in a box of the infeasible solve's tree shown to break ``d`` and nothing outside
    {``c``, ``d``}, or, inside the boxes ``best`` searched, in one of its boxes shown to break
    ``d`` alone (a box closed by its objective bound holds nothing better than ``best``; one
    shown to break another constraint too still breaks it). With neither, no such design
    exists and the re-solve without ``d`` is skipped."""
    closed = best.tree()
    if not problem.gridded or tree.archives is None or closed is None:
        return False
    rest = problem.without(c.name)
    return not _closes_alone(tree.archives, problem, {c.name, d.name}, d.name) and not (
        _closes_alone(closed, rest, {d.name}, d.name)
    )


def _improves(c: Constraint, new: float, old: float) -> bool:
    sign = 1.0 if c.sense == "min" else -1.0
    return sign * (new - old) > _BETTER_RTOL * max(abs(old), abs(c.bound), 1e-300)


def _meets(c: Constraint, value: float) -> bool:
    return bool(c.satisfied(value))  # type: ignore[arg-type]


def _reach(c: Constraint) -> str:
    """How far a bound's value as the spec reads it (:func:`_value`) can be pushed: a ``min``
    bound (>=) at most its largest value, a ``max`` bound (<=) at least its smallest one; a
    deflection bound (P / delta >= load / max) at least its smallest deflection."""
    return "at most" if c.sense == "min" and c.load is None else "at least"


def _asked(c: Constraint) -> str:
    """What ``c`` asks, e.g. ``flexural rigidity EI(45 deg) >= 80 mN*m^2``."""
    if c.load is not None:
        return (
            f"a deflection <= {_shown(c, c.load / c.bound, 'mm')} under {c.load:g} N "
            f"({c.quantity.description})"
        )
    need = ">=" if c.sense == "min" else "<="
    return f"{c.quantity.description} {need} {_shown(c, c.bound)}"


def _value(c: Constraint, v: float) -> str:
    """A value of ``c``'s quantity as the spec reads it (a deflection bound: the deflection)."""
    return _shown(c, c.load / v, "mm") if c.load is not None else _shown(c, v)


def _edit(c: Constraint, v: float) -> str:
    """The spec edit that lets ``c`` accept the value ``v`` of its quantity."""
    if c.name.startswith("validity."):  # a validated range: no spec key moves it
        return (
            'trust = "extrapolate" (an answer outside the validated range, marked '
            "extrapolated, not certified; FE that widens the range would certify it)"
        )
    if c.quantity.kind in ("part_short", "part_long"):  # a machine's side, not a number
        side = "shorter" if c.quantity.kind == "part_short" else "longer"
        bed = math.ceil(v + 2 * DEFAULT_MARGIN_MM)
        return (
            f'fabrication.machine = "laser:{bed}x{bed}" (or any cutter whose {side} side is at '
            f"least {bed} mm: the parts need {v:.4g} mm, plus 5 mm margins)"
        )
    if c.load is not None:  # P/delta >= v: a deflection of load / v, rounded up
        return f"{_key(c)} = {_rounded_for(c, c.load / v, 'mm', down=False)}"
    return f"{_key(c)} = {_rounded_for(c, v, c.unit, down=c.sense == 'min')}"


def _machine_pair(a: Constraint, va: float, b: Constraint, vb: float) -> str:
    """The one edit of ``fabrication.machine`` that gives the parts both sides they need (the
    shorter and the longer side of a pair of machine bounds reaching ``va`` and ``vb``)."""
    short, long_ = (va, vb) if a.quantity.kind == "part_short" else (vb, va)
    need = (math.ceil(short + 2 * DEFAULT_MARGIN_MM), math.ceil(long_ + 2 * DEFAULT_MARGIN_MM))
    bed = max(need)
    return (
        f'fabrication.machine = "laser:{bed}x{bed}" (or any cutter whose shorter side is at '
        f"least {need[0]} mm and longer side at least {need[1]} mm: the parts need "
        f"{short:.4g} x {long_:.4g} mm, plus 5 mm margins)"
    )


#: What a value from a search cut short by the work budget says: a design reaching it was found,
#: not that none goes further (the search's own certificate, :attr:`~.solve.Optimum.certified`).
NOT_CERTIFIED = " (not certified: the work budget ran out before the search ended)"


def _cut(opt: Optimum) -> str:
    """Nothing for a certified search's value, else :data:`NOT_CERTIFIED`."""
    return "" if opt.certified else NOT_CERTIFIED


def _pct(c: Constraint, v: float) -> float:
    return 100 * abs(c.bound - v) / abs(c.bound) if c.bound else math.inf


def _off_axis_free(c: Constraint) -> bool:
    """A bound on EI, D or K of the panel itself off the crease directions, without a frame."""
    q = c.quantity
    return (
        q.kind in STIFFNESS
        and q.test is None
        and q.eta is not None
        and q.eta % 90 != 0
        and q.support != "frame"
    )


# -- the diagnosis --------------------------------------------------------------------------------


def diagnose(
    problem: Problem, tables: Tables, archives: tuple[Archive, ...] | None = None
) -> list[Diagnosis]:
    """Why ``problem`` (infeasible) has no design: the structural causes first (identical layers
    forcing a square, off-axis bounds on a free panel), then each constraint whose relaxation
    alone restores feasibility, else the pairs that must both be relaxed; every entry with its
    numbers and a hint, or why there is none (module docstring). ``archives``: the closed boxes
    of the certified infeasible solve (:attr:`~.solve.Optimum.archives`), from which each
    relaxed problem is searched (warm) instead of from its whole domain.

    Its searches keep their memory bounded (docs/tolerances.md section 5); should one still
    run out of memory, the entries found so far are kept and the last says the diagnosis is
    partial (memory cap), instead of the proven infeasibility being lost to the error."""
    out: list[Diagnosis] = []
    try:
        return _diagnose(problem, tables, archives, out)
    except MemoryError:
        return [*out, _partial(problem, memory=True)]


def _diagnose(
    problem: Problem, tables: Tables, archives: tuple[Archive, ...] | None, out: list[Diagnosis]
) -> list[Diagnosis]:
    """:func:`diagnose`, its entries added to ``out`` as they are found."""
    tree = _Tree(problem, archives)
    stage(DIAGNOSIS, "orientation")
    out += orientation(problem)  # first: a quarter turn off is the fix, whatever else is short
    out += _layers(problem)
    out += _free_off_axis(problem, tables, tree)
    singles: list[Diagnosis] = []
    for c in problem.constraints:
        if budget_spent():
            return [*out, _partial(problem)]
        stage(DIAGNOSIS, c.name)
        d = _single(problem, c, tables, tree)
        if d is not None:
            singles.append(d)
            out.append(d)
    out += _sheets(problem, singles)
    if singles:
        # the budget spent inside the last single (its partners, its search alone) or the
        # sheets: what is above may lack parts, and says so
        return [*out, _partial(problem)] if budget_spent() else out
    stage(DIAGNOSIS, "pairs of constraints")
    pairs = _pairs(problem, tables, tree)
    out += pairs
    if budget_spent():
        return [*out, _partial(problem)]
    if not pairs and not any(d.hint for d in out):
        out += _sheets(problem, [], everything=True)
    if not pairs and not any(d.hint for d in out):
        names = tuple(c.name for c in problem.constraints)
        out.append(
            Diagnosis(
                names,
                None,
                None,
                "",
                "no design meets the variable bounds and constraints even with any two "
                "constraints dropped, so no single edit of a bound is a hint: widen the variable "
                "bounds ([variables] W, n, alpha) or choose a stiffer or thicker material",
                kind="none",
            )
        )
    return [*out, _partial(problem)] if budget_spent() else out


def _sheets(
    problem: Problem, singles: list[Diagnosis], everything: bool = False
) -> list[Diagnosis]:
    """A thicker or stiffer sheet (:mod:`.sheet_hint`) when a behavioural bound is short by more
    than :data:`SMALL_EDIT` (``everything``: when no edit of one or two bounds helps, for every
    behavioural bound)."""
    from corrugate.solver.sheet_hint import stiffer_sheet

    far = {
        n for d in singles if d.relative is not None and d.relative > SMALL_EDIT for n in d.names
    }
    short = [
        c
        for c in problem.constraints
        if (everything or c.name in far)
        and c.quantity.eta is not None
        and c.quantity.kind != "length"
    ]
    if not short or budget_spent():
        return []
    # how far the shortest falls short (a min bound over its reach; 1 when unknown)
    need = max(
        (
            d.bound / d.reachable
            for d in singles
            if d.names[0] in far and d.bound and d.reachable and d.bound > d.reachable > 0
        ),
        default=1.0,
    )
    stage(DIAGNOSIS, "a thicker or stiffer sheet")
    return stiffer_sheet(problem, short, need)


def _partial(problem: Problem, memory: bool = False) -> Diagnosis:
    """The last entry of a diagnosis cut short by the work budget (``memory``: by the memory
    available)."""
    if memory:
        text = (
            "partial diagnosis (memory cap): the spec is proven infeasible, but the machine's "
            "memory ran out during the diagnosis: the entries above are the ones found before "
            "it did"
        )
    else:
        budget = current_budget()
        what = "the work budget" if budget is None else f"the budget of {budget.label}"
        text = (
            f"the spec is proven infeasible, but {what} ran out during the diagnosis: the "
            "entries above are the ones found before it did (run again with a larger --budget "
            "for the rest)"
        )
    return Diagnosis(tuple(c.name for c in problem.constraints), None, None, "", text, kind="none")


def best_hint(diagnosis: tuple[Diagnosis, ...] | list[Diagnosis]) -> str:
    """The one hint to act on: the smallest relative edit of one bound when it is at most
    :data:`SMALL_EDIT` of the bound, else a structural change that restores feasibility
    (directions turned by 90 deg or the sides swapped, independent layers, a frame, a thicker
    or stiffer sheet), else the smallest single edit, else the pair of edits, else
    why no hint exists."""
    singles = [d for d in diagnosis if d.kind == "single" and d.hint]
    best = min(
        singles, key=lambda d: d.relative if d.relative is not None else math.inf, default=None
    )
    single = (
        None
        if best is None
        else f"the smallest single change is {best.hint}; edit that key of the spec and run again"
    )
    if best is not None and single and best.relative is not None and best.relative <= SMALL_EDIT:
        return single
    for d in diagnosis:
        if d.kind in ("orientation", "layers", "support", "sheet") and d.hint:
            return d.hint
    if single:
        return single
    for d in diagnosis:
        if d.hint:
            return d.hint
    return "none: " + (diagnosis[-1].message if diagnosis else "no design meets the spec")


def _layers(problem: Problem) -> list[Diagnosis]:
    """Identical layers on a rectangle or polygon: Lx = Ly. Says so when the size constraints
    need Lx != Ly, and re-solves with independent layers."""
    if not problem.identical or problem.layout.name not in ("rectangle", "polygon"):
        return []
    lo = {"Lx": -math.inf, "Ly": -math.inf}
    hi = {"Lx": math.inf, "Ly": math.inf}
    names: dict[str, list[str]] = {"Lx": [], "Ly": []}
    for c in problem.constraints:
        k = c.quantity.kind
        if k in lo:
            names[k].append(c.name)
            if c.sense == "min":
                lo[k] = max(lo[k], c.bound)
            else:
                hi[k] = min(hi[k], c.bound)
    apart = max(lo["Lx"], lo["Ly"]) > min(hi["Lx"], hi["Ly"])
    independent = replace(problem, identical=False)
    found = optimize(independent, tables=Tables(independent))
    if found.point is None and not apart:
        return []

    def span(k: str) -> str:
        a = f"{lo[k]:g}" if math.isfinite(lo[k]) else "0"
        b = f"{hi[k]:g}" if math.isfinite(hi[k]) else "any"
        return f"{a}-{b} mm"

    why = (
        'with layers = "identical" both layers are the same, so they fold to the same extent: '
        "Lx = Ly, a square outline"
    )
    if apart:
        why += f", but side_x allows Lx {span('Lx')} and side_y allows Ly {span('Ly')}"
    if found.point is not None:
        o = problem.objective
        unit = o.quantity.unit
        hint = 'layers = "independent" (each layer its own W, n, alpha)'
        message = (
            f"{why}; with {hint} the spec is feasible: the "
            f"{'lightest' if o.quantity.key == 'mass' and o.sense == 'min' else 'best'} design "
            f"is {shown(found.value, unit)}" + ("" if found.certified else " (not certified)")
        )
        return [
            Diagnosis(
                tuple(names["Lx"] + names["Ly"]),
                None,
                found.value,
                unit,
                message + f"; hint: {hint}",
                kind="layers",
                hint=hint,
            )
        ]
    return [
        Diagnosis(
            tuple(names["Lx"] + names["Ly"]),
            None,
            None,
            "mm",
            f"{why}; independent layers alone do not make the spec feasible either (see below)"
            if found.certified
            else f"{why}; whether independent layers alone make the spec feasible is not known"
            + NOT_CERTIFIED,
            kind="layers",
        )
    ]


def _free_off_axis(problem: Problem, tables: Tables, tree: _Tree) -> list[Diagnosis]:
    """Off-axis bounds on a panel with free sides: each one's best with the other constraints
    held, the spec re-solved with a frame, and the best along the creases."""
    off = [c for c in problem.constraints if _off_axis_free(c)]
    if not off:
        return []
    # each off-axis bound alone among them, every other constraint held
    base = replace(problem, constraints=tuple(c for c in problem.constraints if c not in off))
    reach: list[tuple[Constraint, float | None, str]] = []
    warm = tree.warm(*off) if len(off) <= ARCHIVE_DEPTH else None
    for c in off:
        best = tree.best(base, c, tables, tuple(off), keep=len(off) == 1)
        reach.append((c, None if best.point is None else best.value, _cut(best)))
    short = [c for c, r, _ in reach if r is None or not _meets(c, r)]
    framed = replace(
        problem,
        constraints=tuple(
            replace(c, quantity=Quantity(c.quantity.kind, c.quantity.eta, "frame"))
            if _off_axis_free(c)
            else c
            for c in problem.constraints
        ),
    )
    # its designs meet every constraint but the off-axis ones: on a grid (an exact optimum,
    # of which only the value is said) searched from the tree's boxes that may hold them
    fixed = optimize(framed, tables=Tables(framed), warm=warm if problem.gridded else None)
    if not short and fixed.point is None:
        return []
    parts = []
    for c, r, cut in reach:
        if r is None:
            got = "no design meets the rest" if not cut else "no design found" + cut
        else:
            got = f"at most {_value(c, r)}" if not cut else f"{_value(c, r)} found" + cut
        parts.append(f"{_key(c)} asks {_asked(c)}: {got}")
    etas = sorted({f"{c.quantity.eta:g}" for c in off})
    why = (
        f"with free sides no facet runs from edge to edge at {' and '.join(etas)} deg off the "
        "creases (docs/offaxis.md), so a free panel carries an off-axis load only through its "
        "soft across-crease bending, twisting and shear; with every constraint but the "
        "off-axis ones held, " + "; ".join(parts)
    )
    c0 = off[0]
    along: list[tuple[float, float, str]] = []
    for eta in (0.0, 90.0):
        q = Quantity(c0.quantity.kind, eta, c0.quantity.support)
        # only the better of the two is said: on a grid (exact optima) the second searched
        # for a design that beats the first (none: the first stays, as on a tie)
        beat = along[0][1] if along and problem.gridded else None
        best = _best(base, q, c0.sense, tables, warm, incumbent=beat)
        if best.point is not None:
            along.append((eta, best.value, _cut(best)))
    keys = ", ".join(_key(c) for c in off)
    if fixed.point is not None:
        o = problem.objective
        # one edit per bound, each at its own table's key (pasted into the spec as it reads)
        hint = " and ".join(f'{_key(c).rpartition(".")[0]}.support = "frame"' for c in off)
        frame_text = (
            f'what would carry it: a rigid frame (support = "frame" on {keys}: then the spec '
            f"is feasible, best {shown(fixed.value, o.quantity.unit)}{_cut(fixed)})"
        )
    elif fixed.certified:
        hint = None
        frame_text = 'even a rigid frame (support = "frame") does not make the spec feasible'
    else:
        hint = None
        frame_text = (
            'whether a rigid frame (support = "frame") makes the spec feasible is not known'
        )
        frame_text += NOT_CERTIFIED
    if along:
        eta, v, cut = max(along, key=lambda item: item[1] if c0.sense == "min" else -item[1])
        frame_text += (
            f"; a load case along the creases (eta = {eta:g} deg, where the same constraints "
            f"allow {c0.quantity.kind} up to {_shown(c0, v)}{cut})"
        )
    frame_text += "; or a face sheet bonded to one side (not modelled by corrugate)"
    message = f"{why}; {frame_text}" + (f"; hint: {hint}" if hint else "")
    first = reach[0][1]
    return [
        Diagnosis(
            tuple(c.name for c in off),
            c0.bound,
            first,
            c0.unit,
            message,
            kind="support",
            hint=hint,
        )
    ]


def _single(problem: Problem, c: Constraint, tables: Tables, tree: _Tree) -> Diagnosis | None:
    """``c`` alone: its best with every other constraint held (None when those conflict among
    themselves), the constraints it binds together with, and its best with none held."""
    rest = problem.without(c.name)
    best = tree.best(rest, c, tables, (c,))
    if best.point is None or _meets(c, best.value):
        return None
    r = best.value
    word = "largest" if c.sense == "min" else "smallest"
    if c.load is not None:
        word = "smallest"
    pct = _pct(c, r)
    if best.certified:
        text = (
            f"{c.name} asks {_asked(c)}; the {word} reachable with every other constraint held "
            f"is {_value(c, r)} (short by {pct:.3g} %)"
        )
    else:  # a design reaching r exists (the hint holds), not that none goes further
        text = (
            f"{c.name} asks {_asked(c)}; with every other constraint held a design reaching "
            f"{_value(c, r)} was found (short by {pct:.3g} %){NOT_CERTIFIED}"
        )
    partners = []
    for d in problem.constraints:
        if d.name == c.name or budget_spent() or _cannot_improve(problem, c, d, tree, best):
            continue
        # on a grid (exact optima) from the boxes that may hold a design better than r, r
        # the incumbent: a design only if one beats r, then the same optimum
        warm = tree.partner(c, d, best) if problem.gridded else None
        if warm is None:
            without = _best(rest.without(d.name), c.quantity, c.sense, tables, tree.warm(c, d))
        else:
            without = _best(rest.without(d.name), c.quantity, c.sense, tables, warm, incumbent=r)
        if without.point is not None and _improves(c, without.value, r):
            partners.append((d, without.value, _cut(without)))
    partners.sort(key=lambda item: -abs(item[1] - r))
    alone = _best(replace(problem, constraints=()), c.quantity, c.sense, tables)
    # alone, the best says how far the variable bounds reach: only a finished search says it
    a = None if alone.point is None or not alone.certified else alone.value
    if partners:
        named = [
            f"{_key(d)} (without it: {_value(c, v)}{cut})" for d, v, cut in partners[:_MAX_PARTNERS]
        ]
        more = len(partners) - _MAX_PARTNERS
        text += (
            "; it binds together with "
            + ", ".join(named)
            + (f" and {more} more" if more > 0 else "")
        )
    if a is not None and _off_axis_free(c) and not _meets(c, a):
        text += (
            f"; even alone (variable bounds only) a free panel reaches {_value(c, a)} "
            "(off-axis, free sides: see above)"
        )
    elif a is not None and not _meets(c, a):
        text += (
            f"; no design in the variable bounds reaches it even alone (best {_value(c, a)}): "
            + _limits(problem, alone)
        )
    if c.name.startswith("validity."):
        hint = f"{_edit(c, r)}, to reach {_value(c, r)} instead of {_shown(c, c.bound)}"
    elif c.load is not None:
        hint = f"{_edit(c, r)} instead of {_shown(c, c.load / c.bound, 'mm')}"
    else:
        hint = f"{_edit(c, r)} instead of {_shown(c, c.bound)}"
    hint += f" ({pct:.3g} %)"
    text += f"; relaxing it alone makes the spec feasible: hint: {hint}"
    return Diagnosis(
        (c.name,), c.bound, r, c.unit, text, kind="single", hint=hint, alone=a, relative=pct / 100
    )


def _limits(problem: Problem, opt: Optimum) -> str:
    """Which design variables sit on their bounds at ``opt`` (what to widen)."""
    assert opt.point is not None
    x = opt.point
    layers = [x.layer(i) for i in range(x.count)]
    at = []
    for var, name, unit in ((problem.W, "W", "mm"), (problem.alpha, "alpha", "deg")):
        for layer in layers:
            v = getattr(layer, name)
            if math.isclose(v, var.lo, rel_tol=1e-9):
                at.append(f"{name} at its min {var.lo:g} {unit}")
            elif math.isclose(v, var.top, rel_tol=1e-9):
                at.append(f"{name} at its max {var.top:g} {unit}")
    for layer in layers:
        n = round(layer.n)
        if n == problem.n_lo:
            at.append(f"n at its min {n}")
        elif n == problem.n_hi:
            at.append(f"n at its max {n}")
    at = list(dict.fromkeys(at))
    if not at:
        return "choose a stiffer or thicker material"
    return "widen [variables] (" + ", ".join(at) + ") or choose a stiffer or thicker material"


def _pairs(problem: Problem, tables: Tables, tree: _Tree) -> list[Diagnosis]:
    """Pairs of constraints that must both be relaxed: each one's best with the other dropped and
    together (the other relaxed to its own best)."""
    out = []
    for a, b in itertools.combinations(problem.constraints, 2):
        if budget_spent():
            break
        rest = problem.without(a.name).without(b.name)
        warm = tree.warm(a, b)
        if optimize(rest, tables=tables, warm=warm).point is None:
            continue
        ra = _best(rest, a.quantity, a.sense, tables, warm)
        rb = _best(rest, b.quantity, b.sense, tables, warm)
        if ra.point is None or rb.point is None:  # only when the budget ran out meanwhile
            continue
        with_b = replace(rest, constraints=(*rest.constraints, replace(b, bound=rb.value)))
        with_a = replace(rest, constraints=(*rest.constraints, replace(a, bound=ra.value)))
        ta = _best(with_b, a.quantity, a.sense, tables, warm)
        tb = _best(with_a, b.quantity, b.sense, tables, warm)
        together = []
        if ta.point is not None:
            together.append(
                f"{_key(a)} {_reach(a)} {_value(a, ta.value)}{_cut(ta)} with {_key(b)} at "
                f"{_value(b, rb.value)}"
            )
        if tb.point is not None:
            together.append(
                f"{_key(b)} {_reach(b)} {_value(b, tb.value)}{_cut(tb)} with {_key(a)} at "
                f"{_value(a, ra.value)}"
            )
        hint = None
        if ta.point is not None:
            hint = f"{_edit(a, ta.value)} and {_edit(b, rb.value)}"
            if {a.quantity.kind, b.quantity.kind} == {"part_short", "part_long"}:
                hint = _machine_pair(a, ta.value, b, rb.value)  # one key: one edit
        text = (
            f"{a.name} and {b.name} bind only together: neither alone can be met with the other "
            f"constraints held, both dropped a design exists; {_key(a)} asks {_asked(a)} and reaches "
            f"{_reach(a)} {_value(a, ra.value)}{_cut(ra)} with {_key(b)} dropped; {_key(b)} asks "
            f"{_asked(b)} and reaches {_reach(b)} {_value(b, rb.value)}{_cut(rb)} with {_key(a)} "
            "dropped"
            + (f"; together {' or '.join(together)}" if together else "")
            + (f"; hint: {hint}" if hint else "")
        )
        out.append(
            Diagnosis(
                (a.name, b.name),
                a.bound,
                ra.value,
                a.unit,
                text,
                kind="pair",
                hint=hint,
                alone=ta.value if ta.point is not None else None,
            )
        )
    return out
