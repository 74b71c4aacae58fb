"""Solve a design problem and explain the answer (docs/theory.md section 5).

:func:`solve` runs the certified branch and bound (:mod:`.bnb`) over every candidate sheet pair
(the material and thickness are a discrete variable; a shared incumbent prunes the later pairs;
where the pairs have certified floors, :mod:`.choices`, best-first by them, whole pairs pruned),
then, unless ``explain=False``, builds the explanation:

* the design's performance, exactly as :func:`corrugate.analysis.evaluate.analyze` reports it;
* every constraint with its value, bound, margin (>= 0 when met, in the quantity's unit), whether
  it is *active* (margin within 1e-6 of the bound) and whether it is *binding*: dropping it alone
  lets the solver find a strictly better design (certified: re-searched from the boxes of the
  solve's own tree that this constraint alone closed below the optimum, :class:`~.archive.Archive`,
  stopping at the first better design; from the whole domain when there is no archive);
* runner-ups: the certified best design for each n near the optimum's n (one search per sheet
  pair, one incumbent per n, from the tree's boxes that may hold a feasible design);
* warnings: the model's (``analyze``) plus the solver's;
* when no design exists, a diagnosis (:mod:`corrugate.solver.diagnosis`): the structural causes
  (identical layers forcing a square, off-axis bounds on a free panel), and for each constraint
  the best value of its quantity that the *other* constraints allow (e.g. the most rigidity
  reachable inside the size limits), with the constraints it binds together with and a hint;
  if no single constraint is to blame, the pairs that must both be relaxed.
"""

from __future__ import annotations

import functools
import heapq
import math
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from corrugate.analysis.evaluate import Analysis, analyze
from corrugate.analysis.warnings import bench_notes
from corrugate.geometry.layer import Assembly, Layer
from corrugate.mechanics.behaviours import get_load_case, own_test
from corrugate.solver import tolerance_box
from corrugate.solver.archive import Archive, bit_sets
from corrugate.solver.bnb import (
    GAP_RTOL,
    BnBResult,
    PerNGrid,
    branch_and_bound,
    enumerated_per_n,
    per_n_answer,
    per_n_grid,
)
from corrugate.solver.budget import Budget, budget_scope, budget_spent
from corrugate.solver.choices import RELAX, CellFloors, Floors, floors, shared_lists
from corrugate.solver.joint_checks import (
    Check,
    answered_by,
    joint_search,
    narrowed,
    reopened,
    three_points,
)
from corrugate.solver.points import VARIABLES, DesignPoints, LayerPoints, coordinates
from corrugate.solver.problem import (
    FEAS_RTOL,
    HOLDS,
    Candidate,
    Constraint,
    DesignVariable,
    Problem,
)
from corrugate.solver.progress import BINDING, DIAGNOSIS, RUNNER_UPS, SEARCHING, stage
from corrugate.solver.quantities import Tables, point_values
from corrugate.solver.quantity import Quantity
from corrugate.solver.validity import outside_ranges

if TYPE_CHECKING:
    from corrugate.mechanics.capacity import Capacity
    from corrugate.solver import cell_checks

__all__ = [
    "ConstraintReport",
    "Diagnosis",
    "Optimum",
    "RunnerUp",
    "Solution",
    "assembly_of",
    "layer_dict",
    "optimize",
    "solve",
]

FloatArray = NDArray[np.float64]

#: Relative margin under which a constraint counts as active.
ACTIVE_RTOL = 1e-6
#: How many n on each side of the optimum's n the runner-ups cover.
RUNNER_UP_SPREAD = 3
#: Relative gap to which a runner-up is certified with continuous variables (on grids: exact):
#: no design with its n is better by more than this. The optimum's own n shows the optimum.
RUNNER_UP_GAP_RTOL = 1e-6
#: The probe of the binding checks (:func:`_witnesses`): moves of n and of gridded W and alpha
#: by these many grid steps, and of continuous W and alpha by these fractions of their range.
PROBE_STEPS = (1, 2, 3)
PROBE_FRACTIONS = (1e-6, 1e-4, 1e-3, 1e-2, 3e-2, 1e-1)
#: The start boxes the cells may leave to the branch and bound at most (:func:`_by_cells`): past
#: them, or when the cells gave up at once (:data:`~.cells.FIRST_MOST`), the solve takes the
#: plain per-pair search (a wide domain: tests/cli/test_interrupt.py's spec left 32 M boxes;
#: benchmarks/edges.py's films-13-cont leaves 4.4 M, from which its search certifies).
CELL_BOXES = 10_000_000
#: The cell pairs a runner-up's cells judge at most (:func:`_cell_runner_ups`); past them
#: (or past a hundredth as many boxes left) the runner-up is shown not certified.
RUNNER_UP_CELLS = 2_000_000
#: A search with a limit ``most`` (:func:`_by_cells`: the runner-ups') stops once its queue holds
#: more than this many times the ``most // 100`` boxes it may leave (not certified, as past the
#: limit). films-5-cont: n = 22's queue grew to 94 k pairs in 1.7 M judged without closing
#: (stopped at the limit); the queues of the n it certifies held at most 9 k (n = 18).
RUNNER_UP_CROWD = 2


@dataclass(frozen=True)
class Optimum:
    """The best design over all sheet pairs, with its certificate."""

    point: DesignPoints | None
    candidates: tuple[Candidate, Candidate] | None
    value: float
    certified: bool
    gap: float
    boxes: int
    iterations: int
    #: ``record``: each sheet pair's closed boxes (:func:`pairs` order; an entry is None when
    #: its archive outgrew :data:`~.archive.ARCHIVE_ROWS`, or the pair was pruned whole),
    #: None otherwise
    archives: tuple[Archive | None, ...] | None = None
    #: the sheet pairs (:func:`pairs` order) pruned whole by a floor (:mod:`.choices`): no
    #: design of theirs is lighter than the answer; not searched, no archive
    pruned: frozenset[int] = frozenset()
    #: the floors (:mod:`.choices`) the solve ordered and pruned the sheet pairs by (None:
    #: none), and the least mass each pruned pair's designs were shown to have at least (g;
    #: its coarse floor, or its fine one refined against the incumbent of the time), which
    #: the runner-ups read instead of computing them again
    floors: Floors | None = field(default=None, compare=False, repr=False)
    floor_of: dict[int, float] = field(default_factory=dict, compare=False, repr=False)
    #: a search by cells (:func:`_by_cells`): the boxes its cells left of each sheet pair
    #: (:func:`pairs` order) and the constraints that fired (by index,
    #: :func:`~.cells.search_pairs`); None otherwise
    starts: tuple[Start, ...] | None = None
    fired: frozenset[int] | None = None

    def tree(self) -> tuple[Archive, ...] | None:
        """Every pair's archive, or None when one is missing (then the explanation re-solves)."""
        if self.archives is None or any(a is None for a in self.archives):
            return None
        return tuple(a for a in self.archives if a is not None)

    def trees(self) -> tuple[Archive | None, ...] | None:
        """Every pair's archive, None for the pairs pruned whole (:attr:`pruned`); None when a
        searched pair's is missing (then the explanation re-solves)."""
        if self.archives is None or any(
            a is None and i not in self.pruned for i, a in enumerate(self.archives)
        ):
            return None
        return self.archives


#: Boxes (lo, hi, lower bound of sign * objective) to start one pair's search from.
Start = tuple[FloatArray, FloatArray, FloatArray]
#: The boxes a joint search starts from (:func:`~.joint_checks.reopened`): lo, hi, bound and
#: the checks each carries.
JointStart = tuple[FloatArray, FloatArray, FloatArray, NDArray[np.bool_]]


@dataclass(frozen=True, slots=True)
class ConstraintReport:
    """One constraint at the design: value and bound in ``unit``, margin >= 0 when met. A
    deflection bound is reported as a deflection (mm, sense ``max``) under its ``load`` (N), with
    the test's P / delta (N/mm) the solver bounded in ``stiffness``."""

    name: str
    quantity: Quantity
    sense: str
    value: float
    bound: float
    margin: float
    unit: str
    active: bool
    binding: bool | None
    load: float | None = None
    stiffness: float | None = None
    capacity: Capacity | None = None  # the load case's capacity at the safety factor

    def as_dict(self) -> dict[str, object]:
        held = None if self.capacity is None else self.capacity.load
        return {
            "name": self.name,
            "quantity": self.quantity.key,
            "sense": self.sense,
            "value": self.value,
            "bound": self.bound,
            "margin": self.margin,
            "unit": self.unit,
            "relative_margin": self.margin / abs(self.bound) if self.bound else None,
            "active": self.active,
            "binding": self.binding,
            **(
                {}
                if self.load is None
                else {
                    "test": self.quantity.test or own_test().name,
                    "load_N": self.load,
                    "stiffness_N_per_mm": self.stiffness,
                    "load_capacity_N": held,
                    "stress_margin": None if held is None else held / self.load - 1.0,
                }
            ),
            **({} if self.capacity is None else self.capacity.as_dict()),
        }


@dataclass(frozen=True, slots=True)
class RunnerUp:
    """The certified best design with layer 1 having ``n`` creases."""

    n: int
    objective: float
    layers: tuple[dict[str, object], ...]
    certified: bool

    def as_dict(self) -> dict[str, object]:
        return {
            "n": self.n,
            "objective": self.objective,
            "layers": list(self.layers),
            "certified": self.certified,
        }


@dataclass(frozen=True, slots=True)
class Diagnosis:
    """Why no design exists (:mod:`corrugate.solver.diagnosis`): constraint ``names`` cannot all
    hold. ``kind``: ``orientation`` (the directions are a quarter turn off:
    :mod:`corrugate.solver.orientation`), ``layers`` (identical layers force Lx = Ly),
    ``support`` (off-axis bounds on a
    free panel), ``single`` (relaxing the one named constraint restores feasibility), ``pair``
    (both named must be relaxed) or ``none`` (no hint exists). ``reachable`` is the best value of
    the first one's quantity that the other constraints allow (a pair: with the other dropped),
    ``alone`` its best with no other constraint (a pair: together, the other at its best), in
    ``unit``; ``hint`` the spec edit that restores feasibility (None: the message says why there
    is none), ``relative`` the edit's size relative to the bound. A ``reachable`` from a search
    the work budget cut short is a value a design was found to reach, and the message says "not
    certified"; ``alone`` is then None."""

    names: tuple[str, ...]
    bound: float | None
    reachable: float | None
    unit: str
    message: str
    kind: str = "single"
    hint: str | None = None
    alone: float | None = None
    relative: float | None = None

    def as_dict(self) -> dict[str, object]:
        return {
            "kind": self.kind,
            "constraints": list(self.names),
            "bound": self.bound,
            "reachable": self.reachable,
            "reachable_alone": self.alone,
            "unit": self.unit,
            "hint": self.hint,
            "message": self.message,
        }


@dataclass(frozen=True)
class Solution:
    """The answer to a design problem (see the module docstring)."""

    problem: Problem
    status: str  # "optimal" | "infeasible" | "not-certified" (see :func:`solve`)
    certified: bool
    gap: float
    objective: float
    assembly: Assembly | None
    analysis: Analysis | None
    constraints: tuple[ConstraintReport, ...] = ()
    runner_ups: tuple[RunnerUp, ...] = ()
    warnings: tuple[dict[str, str], ...] = ()
    diagnosis: tuple[Diagnosis, ...] = ()
    stats: dict[str, object] = field(default_factory=dict)
    #: with ``trust = "extrapolate"``: the validated ranges the design lies outside
    #: (:func:`~.validity.outside_ranges`); then it is extrapolated, not certified
    extrapolated: tuple[str, ...] = ()
    #: information that is no warning (the paper's bench range: docs/validation/ranges.md)
    notes: tuple[dict[str, str], ...] = ()

    def __repr__(self) -> str:
        """Five lines at most (:func:`corrugate.solver.display.solution_repr`)."""
        from corrugate.solver.display import solution_repr

        return solution_repr(self)

    def _repr_html_(self) -> str:
        from corrugate.solver.display import solution_html

        return solution_html(self)

    @property
    def mass(self) -> float | None:
        return None if self.analysis is None else self.analysis.mass.total

    @property
    def certificate(self) -> str:
        """What the certificate is a statement about: the model variant, and for each
        behavioural bound the support condition and the test it is taken in
        (docs/load_cases.md), e.g. ``certified under the refined model: EI(0 deg) in pure
        bending, free sides; deflection 0.94 mm <= 1 mm under 10 N in three-point bending over
        120 mm, free sides``."""
        p = self.problem
        head = "certified" if self.certified else "not certified"
        if not p.tolerances.nominal:  # every directional bound over the tolerance box
            head += f" {p.tolerance_sentence}"
        if p.calibrated:  # and over the measured intervals (docs/calibration.md 9)
            head += f" ({p.calibration_words})"
        head += f" under the {p.model} model"
        if self.extrapolated:
            head = (
                f"extrapolated, not certified: optimal under the {p.model} model outside the "
                f"range it was validated over ({'; '.join(self.extrapolated)})"
            )
        if p.joint != "none":
            head += f", the layers joined by the connector band ({p.joint}: its walls counted)"
        parts = []
        for c in self.constraints:
            q = c.quantity
            if q.eta is None or q.kind == "length" or (q.kind == "Pb" and q.duration is None):
                continue
            sustained = self._sustained(q)
            if q.kind == "Pb":
                parts.append(f"buckling load Pb({q.eta:g} deg){sustained}")
                continue
            where = f"{q.support} sides" if q.support == "free" else f"support {q.support}"
            test = (
                get_load_case(q.test).label
                if q.test is not None
                else (own_test().label if q.kind == "K" else " in pure bending")
            )
            span = "" if q.span is None else f" over {q.span:g} mm"
            if c.name.endswith(HOLDS):  # said by its deflection bound
                continue
            if c.load is not None:
                held = ""
                if c.capacity is not None:
                    held = f": {c.capacity.sentence}"
                parts.append(
                    f"deflection {c.value:.4g} mm <= {c.bound:.4g} mm under {c.load:g} N"
                    f"{test}{span} at {q.eta:g} deg, {where}{sustained}{held}"
                )
            elif q.kind == "Pmax":
                first = "" if c.capacity is None else f"; first failure: {c.capacity.words}"
                parts.append(
                    f"holds {c.bound:g} N{test}{span} at {q.eta:g} deg (capacity {c.value:.4g} N "
                    f"at safety factor {p.safety_factor:g}{first}), {where}"
                )
            else:
                parts.append(f"{q.kind}({q.eta:g} deg){test}, {where}{sustained}")
        return head + (": " + "; ".join(parts) if parts else "")

    def _sustained(self, q: Quantity) -> str:
        """For a quantity under a sustained load, the words of the certificate: how long, the
        creep modulus it used of each sheet's E and its source (docs/load_cases.md section
        11); "" for a short-term one."""
        if q.duration is None:
            return ""
        from corrugate.materials.creep import duration_text

        mats = (
            [c.material for c in self.problem.candidates]
            if self.assembly is None
            else [layer.material for layer in self.assembly.layers]
        )
        said = []
        for m in dict.fromkeys(mats):
            assert m.creep is not None  # Problem.from_spec refuses a sustained load without
            said.append(
                f"{m.id} at its creep modulus E_c = {m.creep_modulus(q.duration):.4g} MPa "
                f"(short-term E = {m.E:.4g} MPa; {m.creep.source})"
            )
        return f", the load held {duration_text(q.duration)}: " + "; ".join(said)

    @property
    def hint(self) -> str | None:
        """The one edit to try first for an infeasible spec (``hint``,
        :func:`corrugate.solver.diagnosis.best_hint`), None without a diagnosis (the
        diagnosis module imported only with one)."""
        if not self.diagnosis:
            return None
        from corrugate.solver.diagnosis import best_hint

        return best_hint(self.diagnosis)

    def to_dict(self) -> dict[str, object]:
        """The JSON object of ``corrugate design --json`` (keys carry units)."""
        p = self.problem
        perf = self.analysis.to_dict() if self.analysis is not None else None
        design = None
        if self.assembly is not None and perf is not None:
            design = {
                "layout": perf["layout"],
                "layers": [
                    layer_dict(i + 1, layer) for i, layer in enumerate(self.assembly.layers)
                ],
                "L_mm": perf["L_mm"],
                "extent_x_mm": perf["extent_x_mm"],
                "extent_y_mm": perf["extent_y_mm"],
                "thickness_mm": perf["thickness_mm"],
            }
        return {
            "name": p.name,
            "status": self.status,
            "certified": self.certified,
            "certificate": self.certificate,
            "tolerances": p.tolerances.as_dict(p.E_measured),
            **({"calibration": p.calibration_words} if p.calibrated else {}),
            "gap": self.gap if math.isfinite(self.gap) else None,  # JSON: null, unbounded
            "model": p.model,
            "objective": {
                "quantity": p.objective.quantity.key,
                "sense": p.objective.sense,
                "value": None if math.isnan(self.objective) else self.objective,
            },
            "design": design,
            "mass_g": self.mass,
            "stiffness": perf["stiffness"] if perf is not None else None,
            "performance": perf,
            "constraints": [c.as_dict() for c in self.constraints],
            "runner_ups": [r.as_dict() for r in self.runner_ups],
            "warnings": list(self.warnings),
            "notes": list(self.notes),
            "trust": p.trust,
            "extrapolated": list(self.extrapolated),
            "diagnosis": [d.as_dict() for d in self.diagnosis],
            "hint": self.hint,
            "solver": {
                "method": "vectorised branch and bound with interval bounds (exhaustive on grids)",
                "gap_rtol": 0.0 if p.gridded else GAP_RTOL,
                **self.stats,
            },
        }


def layer_dict(index: int, layer: Layer) -> dict[str, object]:
    """A layer as the ``design.layers`` entries of the JSON output (units in the keys)."""
    return {
        "index": index,
        "W_mm": layer.W,
        "n": layer.n,
        "alpha_deg": layer.alpha_deg,
        "material": layer.material.id,
        "t_mm": layer.t,
    }


def pairs(problem: Problem) -> list[tuple[Candidate, Candidate]]:
    """The sheet pairs a problem searches, in the order of :attr:`Optimum.archives`."""
    if problem.identical:
        return [(c, c) for c in problem.candidates]
    return [(a, b) for a in problem.candidates for b in problem.candidates]


_pairs = pairs  # the former name


def optimize(
    problem: Problem,
    *,
    n_fixed: tuple[int, int] | None = None,
    tables: Tables | None = None,
    incumbent: float | None = None,
    gap_rtol: float = GAP_RTOL,
    record: bool = False,
    warm: Sequence[Start | None] | None = None,
    stop_below: float | None = None,
    prune: bool = False,
    most: int | None = None,
    seek: bool = False,
) -> Optimum:
    """The certified optimum of ``problem`` over every candidate sheet pair (continuous
    variables: to the relative gap ``gap_rtol``). Inside a
    :func:`~.budget.budget_scope` whose budget is spent, the sheet pairs not yet searched are
    skipped: the optimum is then not certified and its gap infinite.

    ``record``: keep each pair's closed boxes (:attr:`Optimum.archives`). ``warm``: per pair,
    the boxes to search instead of its whole domain (reopened from an archive of a search of a
    problem whose feasible designs include this one's: the answer is then the same).
    ``stop_below``: stop at the first design strictly better than this objective value (it
    proves that one exists; the answer is then not certified unless the search had ended).
    A ``warm`` entry None: that pair's whole domain.

    ``prune``: when the sheet pairs have floors (:func:`~.choices.floors`: least mass,
    independent layers that decompose), take them best-first by their floors and prune whole
    the pairs whose floor reaches the incumbent (:func:`_by_floors`; not with ``warm``,
    ``n_fixed`` or ``stop_below``): the same answer and certificate; with continuous W and
    alpha, by cells (:func:`_by_cells`; ``most``: its limit; ``seek``: a design sought and
    polished before its first cell pairs, :func:`~.cells.search_pairs`)."""
    tables = tables or Tables(problem)
    if prune and warm is None and n_fixed is None and stop_below is None:
        fl = floors(problem)
        if isinstance(fl, CellFloors):
            got = _by_cells(problem, fl, tables, incumbent, record, gap_rtol, most, seek)
            if got is not None:
                return got  # else the domain is too wide for the cells: the plain search
        if isinstance(fl, Floors):
            return _by_floors(problem, fl, tables, incumbent, record)
    sign = -1.0 if problem.objective.sense == "max" else 1.0
    best: BnBResult | None = None
    best_pair: tuple[Candidate, Candidate] | None = None
    certified = True
    bound = math.inf
    boxes = iterations = 0
    inc = incumbent
    archives: list[Archive | None] = []
    for i, pair in enumerate(pairs(problem)):
        if budget_spent():  # the pairs left: nothing proven
            certified = False
            bound = -math.inf
            break
        start = None if warm is None else warm[i]
        if start is not None and not len(start[0]):  # nothing of this pair to search
            if record:  # its archive: no box (the archives stay in the order of the pairs)
                empty = np.empty((0, np.shape(start[0])[1] if np.ndim(start[0]) == 2 else 0))
                archives.append(Archive(empty, empty, np.empty(0), np.empty(0, dtype=np.uint64)))
            continue
        r = branch_and_bound(
            problem,
            *pair,
            incumbent=inc,
            n_fixed=n_fixed,
            tables=tables,
            gap_rtol=gap_rtol,
            start=start,
            record=record,
            stop_below=stop_below,
        )
        archives.append(r.archive)
        boxes += r.boxes
        iterations += r.iterations
        certified &= r.certified
        if r.point is not None and (best is None or sign * r.value < sign * best.value):
            best, best_pair = r, pair
            inc = r.value
            if stop_below is not None and sign * r.value < sign * stop_below:
                break  # shown: a better design exists
        if not r.certified:
            bound = min(bound, sign * r.bound)
    kept = tuple(archives) if record and certified else None
    if best is None:
        return Optimum(
            None,
            None,
            math.nan,
            certified,
            0.0 if certified else math.inf,
            boxes,
            iterations,
            kept,
        )
    best_val = sign * best.value
    gap_abs = (
        max(best_val - bound, best.gap * abs(best_val))
        if not certified
        else (best.gap * abs(best_val))
    )
    gap = 0.0 if problem.gridded and certified else gap_abs / max(abs(best_val), 1e-300)
    return Optimum(best.point, best_pair, best.value, certified, gap, boxes, iterations, kept)


def _by_floors(
    problem: Problem,
    fl: Floors,
    tables: Tables,
    incumbent: float | None,
    record: bool,
) -> Optimum:
    """:func:`optimize` of a least-mass problem over its sheet pairs best-first by their floors
    (:mod:`.choices`): a pair's coarse floor is refined before the pair is searched, and the
    search stops when the least floor left reaches the incumbent (the pairs left are pruned
    whole). The answer is :func:`optimize`'s: a pruned pair's branch and bound would return no
    design (none lighter than the incumbent; :func:`optimize` keeps the first strictly lighter
    one), the same one unless two pairs tie exactly. With ``record`` and no design found, the
    pruned pairs are searched too (the diagnosis reopens every pair's archive)."""
    everything = pairs(problem)
    heap = [(fl.coarse(k), 0, k) for k in range(len(everything))]
    heapq.heapify(heap)
    inc = math.inf if incumbent is None else incumbent
    best: BnBResult | None = None
    best_pair: tuple[Candidate, Candidate] | None = None
    certified = True
    boxes = iterations = 0
    archives: list[Archive | None] = [None] * len(everything)
    uncertified: list[float] = []  # the proven bounds of the pairs not certified

    def run(k: int) -> None:
        nonlocal best, best_pair, certified, boxes, iterations, inc
        pair = everything[k]
        r = branch_and_bound(
            problem,
            *pair,
            incumbent=None if not math.isfinite(inc) else inc,
            tables=tables,
            record=record,
        )
        archives[k] = r.archive
        if not r.certified:
            uncertified.append(r.bound)
        boxes += r.boxes
        iterations += r.iterations
        certified &= r.certified
        if r.point is not None and (best is None or r.value < best.value):
            best, best_pair, inc = r, pair, r.value

    bound = math.inf  # the least proven bound of the pairs not certified
    shown: dict[int, float] = {}  # a fine floor's lower bound of the pair's designs (g)
    while heap:
        if budget_spent():  # the pairs left: nothing proven
            certified, bound = False, -math.inf
            break
        floor, level, k = heapq.heappop(heap)
        if floor >= inc:  # this pair and every pair left: no design lighter than the answer
            heapq.heappush(heap, (floor, level, k))
            break
        if level == 0:
            fine = fl.fine(k, inc)
            # inf: no design lighter than the incumbent (RELAX below it, as a floor)
            shown[k] = max(floor, fine if math.isfinite(fine) else inc * (1 - RELAX))
            heapq.heappush(heap, (max(floor, fine), 1, k))
            continue
        run(k)
    pruned = frozenset(k for _, _, k in heap) if certified else frozenset()
    if record and certified and best is None and pruned:
        for k in sorted(pruned):  # for the diagnosis' archives: every pair searched
            run(k)
        pruned = frozenset()
    floor_of = {k: shown.get(k, fl.coarse(k)) for k in pruned}
    kept = tuple(archives) if record and certified else None
    ends = (certified, min([bound, *uncertified]), boxes, iterations, kept, pruned)
    return _ended(problem, best, best_pair, *ends, floors=fl, floor_of=floor_of)


def _ended(
    problem: Problem,
    best: BnBResult | None,
    best_pair: tuple[Candidate, Candidate] | None,
    certified: bool,
    bound: float,
    boxes: int,
    iterations: int,
    kept: tuple[Archive | None, ...] | None,
    pruned: frozenset[int],
    **extra: Any,
) -> Optimum:
    """The :class:`Optimum` of a least-mass search that took the sheet pairs in its own order
    (:func:`_by_floors`, :func:`_by_cells`): ``best`` the lightest design found on
    ``best_pair``; certified, its gap 0 on grids, else the gap its pair's search proved; not
    certified, the distance to ``bound``, the least proven bound of the pairs not certified.
    ``extra``: the search's own fields of the Optimum."""
    if best is None or best_pair is None:
        gap = 0.0 if certified else math.inf
        return Optimum(
            None, None, math.nan, certified, gap, boxes, iterations, kept, pruned, **extra
        )
    gap = 0.0 if problem.gridded else best.gap  # continuous: the gap proved
    if not certified:
        gap = max(best.value - bound, best.gap * abs(best.value)) / max(abs(best.value), 1e-300)
    return Optimum(
        best.point, best_pair, best.value, certified, gap, boxes, iterations, kept, pruned, **extra
    )


def _by_cells(
    problem: Problem,
    fl: CellFloors,
    tables: Tables,
    incumbent: float | None,
    record: bool,
    gap_rtol: float = GAP_RTOL,
    most: int | None = None,
    seek: bool = False,
) -> Optimum | None:
    """:func:`optimize` of a least-mass problem with continuous W and alpha on independent
    layers (:mod:`.cells`): every sheet pair's cells searched at once (one queue, one
    incumbent: the designs they find), then the branch and bound of each sheet pair the cells
    leave below the incumbent, best floor first, from the boxes they leave (every design of
    the pair lighter than the incumbent lies in them), the incumbent carried from pair to
    pair; the pairs they leave nothing of are pruned whole. The answer and its certificate
    are :func:`optimize`'s, to the gap: no design of any pair is lighter than the answer by more
    than the gap. With ``record``, a searched pair's archive reopens the part its cells dropped
    by its cells again (:class:`~.cells.CellArchive`); with no design found, every pair is
    searched so (the diagnosis reopens every pair's archive). ``most``: the cell pairs the
    cells judge at most (:data:`~.cells.BUDGET` by default) and a hundredth as many boxes
    they may leave to the branch and bound; past those it is not run and the design found is
    not certified; its cells also stop once their queue holds more than
    :data:`RUNNER_UP_CROWD` times those boxes (``crowd``, :func:`~.cells.search_pairs`: then
    not certified either, the same design shown as the best found). ``seek``: :func:`~.cells.search_pairs`'."""
    from corrugate.solver import cells  # continuous W and alpha on independent layers only

    everything = pairs(problem)
    inc = math.inf if incumbent is None else incumbent
    budget = cells.BUDGET if most is None else most
    fine = max(gap_rtol, cells.FINE_GAP)
    crowd = None if most is None else RUNNER_UP_CROWD * (most // 100)
    found, at, fired = fl.search_all(inc, max(gap_rtol, cells.CELL_GAP), budget, fine, seek, crowd)
    if not found or not found[0].settled or sum(len(r.start[0]) for r in found) > CELL_BOXES:
        return None
    best: BnBResult | None = None
    best_pair: tuple[Candidate, Candidate] | None = None
    if at >= 0:
        g = found[at]
        best = BnBResult(g.point, g.value, g.value - gap_rtol * abs(g.value), True, 0, 0)
        best_pair, inc = everything[at], g.value
    certified = True
    boxes = found[0].judged if found else 0
    iterations = 0
    archives: list[Archive | None] = [None] * len(everything)
    uncertified: list[float] = []
    searched: set[int] = set()
    bound = math.inf

    def run(k: int) -> None:
        nonlocal best, best_pair, certified, boxes, iterations, inc
        lo, hi, low = found[k].start
        keep = low < inc - gap_rtol * abs(inc) if math.isfinite(inc) else low < inc
        r = branch_and_bound(
            problem,
            *everything[k],
            incumbent=None if not math.isfinite(inc) else inc,
            tables=tables,
            start=(lo[keep], hi[keep], low[keep]),
            record=record,
            gap_rtol=gap_rtol,
        )
        searched.add(k)
        if record:
            archives[k] = cells.with_cells(r.archive, _cells_reopen(problem, everything[k], tables))
        if not r.certified:
            uncertified.append(r.bound)
        boxes += r.boxes
        iterations += r.iterations
        certified &= r.certified
        if r.point is not None and (best is None or r.value < best.value):
            best, best_pair, inc = r, everything[k], r.value

    order = sorted(range(len(everything)), key=lambda k: (found[k].floor, k))
    if most is not None and sum(len(r.start[0]) for r in found) > most // 100:
        order, certified, bound = [], False, min(r.floor for r in found)
    for k in order:
        if budget_spent():  # the pairs left: nothing proven
            certified, bound = False, -math.inf
            break
        if found[k].floor >= inc and k != at:
            continue
        run(k)
    pruned = frozenset(k for k in range(len(everything)) if k not in searched)
    if not certified:
        pruned = frozenset()
    if record and certified and best is None and pruned:
        for k in sorted(pruned):  # for the diagnosis' archives: every pair searched
            run(k)
        pruned = frozenset()
    kept = tuple(archives) if record and certified else None
    starts = tuple(r.start for r in found)
    ends = (certified, min([bound, *uncertified]), boxes, iterations, kept, pruned)
    return _ended(problem, best, best_pair, *ends, starts=starts, fired=fired)


def _cells_reopen(
    problem: Problem, pair: tuple[Candidate, Candidate], tables: Tables
) -> Callable[[int, float], Start]:
    """The boxes of sheet pair ``pair`` that may hold a design meeting every constraint of
    ``problem`` outside a bit set, lighter than a mass: the cells' search of the problem
    without those constraints (:func:`~.cells.search`, no design evaluated, so nothing
    lighter is dropped); with no mass given (the diagnosis), the whole domain."""
    from corrugate.solver import cells

    def reopen(relaxed: int, below: float) -> Start:
        sub = cells.relaxed_without(problem, relaxed)
        if not cells.applies(sub) or not math.isfinite(below):  # the whole domain
            dims = coordinates(problem)
            lo = np.array([[d.var.lo for d in dims]])
            hi = np.array([[d.var.top for d in dims]])
            return lo, hi, np.array([-math.inf])
        got = cells.search(cells.setting(sub, *pair, tables), below)
        return got.start

    return reopen


def assembly_of(problem: Problem, opt: Optimum) -> Assembly:
    """The :class:`~corrugate.geometry.layer.Assembly` of an optimum's point and sheets."""
    assert opt.point is not None
    assert opt.candidates is not None
    x1, x2 = opt.point.layer(0), opt.point.layer(1)
    c1, c2 = opt.candidates
    l1 = Layer(x1.W, round(x1.n), x1.alpha, c1.material, c1.t, problem.profile_kind)
    l2 = Layer(x2.W, round(x2.n), x2.alpha, c2.material, c2.t, problem.profile_kind)
    return Assembly(l1, l2, problem.layout)


def stop_reason(budget: Budget | None) -> str:
    """Why an uncertified search stopped: its budget (what ran out, :class:`~.budget.Budget`),
    else the branch and bound's own iteration and box limits."""
    if budget is not None and budget.stopped is not None:
        return f"the budget of {budget.label}"
    return "the search's iteration or box limit"


def solve(
    problem: Problem, *, explain: bool = True, budget: Budget | float | None = None
) -> Solution:
    """Certified optimum of ``problem`` and (if ``explain``) its explanation, within a work
    ``budget`` (:class:`~.budget.Budget`, or CPU seconds; None: the enclosing
    :func:`~.budget.budget_scope`'s, else the default 60 s) that covers the explanation too.

    ``status``: ``optimal`` (certified), ``infeasible`` (certified: no design exists) or
    ``not-certified`` (the search stopped at the budget or its own limits first: ``assembly`` is
    the best design found so far, or None, and ``gap`` the proven relative gap, inf when nothing
    bounds it). The budget used is in ``stats["budget"]``."""
    with budget_scope(budget) as spent, shared_lists():
        sol = _solve(problem, explain, spent)
    return replace(sol, stats={**sol.stats, "budget": spent.as_dict()})


def _solve(problem: Problem, explain: bool, budget: Budget) -> Solution:
    t0 = time.perf_counter()
    tables = Tables(problem)
    stage(SEARCHING)
    opt = optimize(problem, tables=tables, record=explain, prune=True)
    t_opt = time.perf_counter() - t0
    stats: dict[str, object] = {
        "boxes": float(opt.boxes),
        "iterations": float(opt.iterations),
        "solve_seconds": t_opt,
    }
    if opt.point is None:
        status = "infeasible" if opt.certified else "not-certified"
        # not certified: no design found, none proven impossible: nothing to diagnose
        diag = tuple(_diagnose(problem, tables, opt.tree())) if explain and opt.certified else ()
        warnings = (
            []
            if opt.certified
            else [
                {
                    "code": "not-certified",
                    "message": f"the search stopped at {stop_reason(budget)} before finding a "
                    "design or proving that none exists",
                }
            ]
        )
        stats["total_seconds"] = time.perf_counter() - t0
        return Solution(
            problem,
            status,
            opt.certified,
            opt.gap,
            math.nan,
            None,
            None,
            diagnosis=diag,
            warnings=tuple(warnings),
            stats=stats,
        )
    assembly = assembly_of(problem, opt)
    etas = sorted(set(problem.etas) | {0.0, 90.0})
    analysis = analyze(assembly, problem.model, etas, support=problem.support, joint=problem.joint)
    warnings = [w.as_dict() for w in analysis.warnings]
    notes = tuple(w.as_dict() for w in bench_notes(assembly))
    # the validated ranges are constraints (or, extrapolated, named in the certificate)
    outside = outside_ranges(problem.ranges, assembly) if problem.trust == "extrapolate" else ()
    if not opt.certified:
        warnings.append(
            {
                "code": "not-certified",
                "message": (
                    f"the search stopped at {stop_reason(budget)}: the best design found so far; "
                    + (
                        f"it may be up to {100 * opt.gap:.3g} % from the optimum"
                        if math.isfinite(opt.gap)
                        else "no bound on how far it is from the optimum was proven"
                    )
                ),
            }
        )
    elif not problem.gridded:
        warnings.append(
            {
                "code": "continuous-gap",
                "message": (
                    f"continuous variables: proved optimal to a relative gap of {opt.gap:.1e} "
                    "(no feasible design is better by more than that)"
                ),
            }
        )
    check = _under_refined(problem, opt)
    if check is not None:
        warnings.append(check)
    reports: tuple[ConstraintReport, ...] = ()
    runner_ups: tuple[RunnerUp, ...] = ()
    if explain:
        stage(BINDING)
        # the runner-ups' grid points of the optimum's pair, when few, evaluated with the
        # binding probe (:func:`_probed`): one evaluation for both
        grid = _runner_grid(problem, opt)
        got, at_grid = _constraint_reports(problem, opt, tables, grid)
        reports = tuple(got)
        stage(RUNNER_UPS)
        given = None if grid is None or at_grid is None else (grid, at_grid)
        runner_ups = tuple(_runner_ups(problem, opt, tables, given))
        if opt.certified and budget.stopped is not None:
            warnings.append(
                {
                    "code": "explanation-partial",
                    "message": (
                        f"the design is certified, but {stop_reason(budget)} ran out while it "
                        "was explained: whether a constraint binds is left unknown where it was "
                        "not proven, and runner-ups not certified are shown as such"
                    ),
                }
            )
        elif opt.certified and _cellular(opt) and any(r.binding is None for r in reports):
            from corrugate.solver import cells

            warnings.append(
                {
                    "code": "explanation-partial",
                    "message": (
                        "the design is certified, but the binding checks' search of the "
                        f"continuous domain stopped at its limit of {cells.BUDGET:.0e} cell "
                        "pairs: whether a constraint binds is left unknown where it was not "
                        "proven"
                    ),
                }
            )
    stats["total_seconds"] = time.perf_counter() - t0
    return Solution(
        problem,
        "optimal" if opt.certified else "not-certified",
        opt.certified and not outside,
        opt.gap,
        opt.value,
        assembly,
        analysis,
        reports,
        runner_ups,
        tuple(warnings),
        stats=stats,
        extrapolated=outside,
        notes=notes,
    )


#: The model the tool designs with, and checks an answer of another model against.
_CHECK_MODEL = "refined"


def _under_refined(problem: Problem, opt: Optimum) -> dict[str, str] | None:
    """For an answer solved under a model other than the refined one (e.g. the paper's formulas
    as printed), whether it meets its behavioural bounds under the refined model, the one that
    agrees with unit-cell FE (docs/theory.md): a warning naming each bound it fails there with
    both values (``fails-under-refined``), or saying that it holds (``holds-under-refined``);
    None under the refined model."""
    if problem.model == _CHECK_MODEL:
        return None
    twin = replace(problem, model=_CHECK_MODEL)
    values = _values_at(twin, opt, Tables(twin))
    failed: list[str] = []
    for c in problem.constraints:
        q = c.quantity
        if not (q.directional or q.test is not None):
            continue  # sizes and mass do not depend on the model
        v = values[q]
        if not bool(c.satisfied(np.asarray(v))):
            shown = c.deflection(v)
            if shown is not None:  # a deflection bound: the deflection under its load
                limit = c.deflection(c.bound)
                text = f"deflection {shown:.4g} mm > {limit:.4g} mm"
            else:
                sign = "<" if c.sense == "min" else ">"
                text = f"{q.description} = {v:.5g} {c.unit} {sign} {c.bound:.5g}"
            failed.append(f"{c.name}: {text}")
    if failed:
        return {
            "code": "fails-under-refined",
            "message": (
                f"solved under the {problem.model} model; under the {_CHECK_MODEL} model (the one "
                "that agrees with finite elements, `corrugate docs theory`) this design does NOT "
                "meet " + "; ".join(failed) + f': solve the spec with model = "{_CHECK_MODEL}" '
                "to design with it"
            ),
        }
    return {
        "code": "holds-under-refined",
        "message": (
            f"solved under the {problem.model} model; it also meets every behavioural bound "
            f"under the {_CHECK_MODEL} model (the one that agrees with finite elements)"
        ),
    }


def _diagnose(
    problem: Problem, tables: Tables, tree: tuple[Archive, ...] | None
) -> list[Diagnosis]:
    """:func:`corrugate.solver.diagnosis.diagnose` (imported here: it re-solves with
    :func:`optimize`)."""
    from corrugate.solver.diagnosis import diagnose

    stage(DIAGNOSIS)
    return diagnose(problem, tables, tree)


def _values_at(problem: Problem, opt: Optimum, tables: Tables) -> dict[Quantity, float]:
    assert opt.point is not None
    assert opt.candidates is not None
    vals = point_values(problem, *opt.candidates, opt.point.arrays(), tables)
    return {k: float(v[0]) for k, v in vals.items()}


def _capacity_quantity(problem: Problem, c: Constraint) -> Quantity | None:
    """The ``Pmax`` quantity of a constraint: its own (a strength bound or a deflection's
    ``holds`` bound) or its deflection's load case along the creases (None otherwise)."""
    q = c.quantity
    if q.kind == "Pmax":
        return q
    if c.load is None or q.eta is None or q.eta % 90 != 0:
        return None
    held = c.name.removesuffix(".max") + HOLDS  # its own held bound (with its bearing)
    for other in problem.constraints:
        if other.name == held:
            return other.quantity
    return Quantity.load_case(
        "Pmax", q.eta, q.test or own_test().name, q.support or problem.support, q.span
    )


def _capacities(
    problem: Problem, opt: Optimum, tables: Tables, vals: dict[Quantity, float]
) -> dict[str, Capacity]:
    """The capacity (:class:`Capacity`) of each deflection and strength bound's load case where
    it is modelled (along the creases): what every answer reports (docs/load_cases.md 10). Its
    modes are the nominal design's; under tolerances the load it holds is the certified one,
    the capacity quantity's value in ``vals`` (over the tolerance box, docs/tolerances.md)."""
    from corrugate.solver.context import AtPoints
    from corrugate.solver.stiffness import capacity_modes_at

    assert opt.candidates is not None and opt.point is not None
    at = AtPoints(problem, *opt.candidates, opt.point.arrays(), tables)
    out = {}
    for c in problem.constraints:
        q = _capacity_quantity(problem, c)
        if q is None or q.test is None or q.eta is None:
            continue
        from corrugate.mechanics.capacity import Capacity  # a load case's bound only

        form = get_load_case(q.test).form
        assert form is not None
        modes = {k: float(v[0]) for k, v in capacity_modes_at(at, q).items()}
        along = 1 if q.eta % 180 == 0 else 2
        cap = Capacity.of(modes, problem.safety_factor, form, along, q.bearing)
        if not problem.tolerances.nominal and q in vals:
            cap = replace(
                cap,
                load=min(cap.load, float(vals[q])),
                words=f"{cap.words}, the nominal design's first mode",
            )
        out[c.name] = cap
    return out


@functools.lru_cache(maxsize=64)
def _probe_moves(variables: tuple[DesignVariable, ...]) -> FloatArray:
    """The probe's moves (rows; columns: the coordinates of ``variables``): every move of one
    coordinate, and of two together, by :data:`PROBE_STEPS` grid steps (in steps: a gridded
    variable) or :data:`PROBE_FRACTIONS` of the range (in its unit: a continuous one), either
    way; made once per coordinates (read-only)."""
    moves: list[FloatArray] = []  # per coordinate: the offsets of its index (grid) or value
    for var in variables:
        if var.step is None:
            span = var.hi - var.lo
            m = np.array([f * span for f in PROBE_FRACTIONS])
        else:
            m = np.array(PROBE_STEPS, dtype=np.float64)
        moves.append(np.concatenate([m, -m]))
    n = len(variables)
    rows = [np.zeros(n) + np.eye(n)[i] * m[:, None] for i, m in enumerate(moves)]
    for i in range(n):
        for j in range(i + 1, n):
            a, b = np.meshgrid(moves[i], moves[j], indexing="ij")
            r = np.zeros((a.size, n))
            r[:, i], r[:, j] = a.ravel(), b.ravel()
            rows.append(r)
    out = np.concatenate(rows)
    out.flags.writeable = False
    return out


def _probe_points(problem: Problem, point: DesignPoints) -> DesignPoints:
    """Designs near ``point`` (the search's coordinates): every move of one coordinate, and of
    two together, by :data:`PROBE_STEPS` grid steps (n; W and alpha on a grid) or
    :data:`PROBE_FRACTIONS` of the range (continuous W, alpha), either way, inside the bounds;
    grid values computed as the search computes them (lo + step k)."""
    dims = [(d, d.var) for d in coordinates(problem)]
    d = _probe_moves(tuple(var for _, var in dims))
    x: list[FloatArray] = []
    ok = np.ones(len(d), dtype=bool)
    for i, (coord, var) in enumerate(dims):
        at = getattr(point.layer(coord.layer), coord.variable)
        if var.step is None:
            v = at + d[:, i]
        else:
            k = np.round((at - var.lo) / var.step) + d[:, i]
            v = var.lo + var.step * k
        ok &= (v >= var.lo) & (v <= var.top)
        x.append(v)
    return DesignPoints.from_columns(np.stack(x, axis=1)[ok])


def _witnesses(problem: Problem, opt: Optimum, tables: Tables, tol: float) -> set[str]:
    """Names of constraints shown binding by a design near the optimum (same sheets,
    :func:`_probe_points`) that breaks only constraints of that name and whose objective is
    better than the optimum's by more than ``tol``: such a design meets every other constraint
    (judged as the search judges points: exactly for continuous variables, to
    :data:`~.problem.FEAS_RTOL` on grids), so the search of the binding check would find a
    better design too. One evaluation for every constraint, before any search."""
    return _probed(problem, opt, tables, tol)[1]


def _probed(
    problem: Problem,
    opt: Optimum,
    tables: Tables,
    tol: float,
    *extras: FloatArray | None,
    with_probe: bool = True,
) -> tuple[dict[Quantity, float], set[str], list[dict[Quantity, FloatArray] | None]]:
    """The optimum's values (:func:`_values_at`), the constraints its probe shows binding
    (:func:`_witnesses`) and the values at the points of each of ``extras`` (in order; rows of the
    search's coordinates on the optimum's sheets; None or empty: none), from one evaluation of
    the optimum, the probe's points and ``extras`` together (every value is elementwise in the
    points: the same values as separate evaluations). ``with_probe`` False: no probe (none shown
    binding; the caller judges the probe's points among its ``extras``)."""
    assert opt.point is not None
    assert opt.candidates is not None
    here = opt.point.arrays()
    x = _probe_points(problem, opt.point) if problem.constraints and with_probe else None
    probe = x if x is not None and len(x) else None
    more = [DesignPoints.from_columns(e) if e is not None and len(e) else None for e in extras]
    parts = [d for d in (here, probe, *more) if d is not None]
    if any(len(d.layers) != len(here.layers) or d.count != here.count for d in parts):
        return _probed_apart(problem, opt, tables, tol, probe, more)  # not stored alike
    every = point_values(problem, *opt.candidates, _joined(parts), tables)
    at = {k: float(v[0]) for k, v in every.items()}
    end = 1 + (0 if probe is None else len(probe))
    witnessed = set()
    if probe is not None:
        witnessed = _witnessed(problem, opt, {k: v[1:end] for k, v in every.items()}, tol)
    values: list[dict[Quantity, FloatArray] | None] = []
    for d in more:
        if d is None:
            values.append(None)
            continue
        values.append({k: v[end : end + len(d)] for k, v in every.items()})
        end += len(d)
    return at, witnessed, values


def _joined(parts: Sequence[DesignPoints]) -> DesignPoints:
    """The points of ``parts`` (stored alike) one after the other."""
    return DesignPoints(
        tuple(
            LayerPoints(
                *(np.concatenate([getattr(p.layers[i], v) for p in parts]) for v in VARIABLES)
            )
            for i in range(len(parts[0].layers))
        ),
        parts[0].count,
    )


def _probed_apart(
    problem: Problem,
    opt: Optimum,
    tables: Tables,
    tol: float,
    probe: DesignPoints | None,
    extras: list[DesignPoints | None],
) -> tuple[dict[Quantity, float], set[str], list[dict[Quantity, FloatArray] | None]]:
    """:func:`_probed` by one evaluation of each part (points not stored alike)."""
    assert opt.candidates is not None
    witnessed: set[str] = set()
    if probe is not None:
        witnessed = _witnessed(
            problem, opt, point_values(problem, *opt.candidates, probe, tables), tol
        )
    more = [
        None if e is None else point_values(problem, *opt.candidates, e, tables) for e in extras
    ]
    return _values_at(problem, opt, tables), witnessed, more


def _witnessed(
    problem: Problem, opt: Optimum, vals: dict[Quantity, FloatArray], tol: float
) -> set[str]:
    """The constraints :func:`_witnesses` names, from the values ``vals`` of the probe's
    points."""
    rtol = FEAS_RTOL if problem.gridded else 0.0
    sign = -1.0 if problem.objective.sense == "max" else 1.0
    better = np.flatnonzero(sign * vals[problem.objective.quantity] < sign * opt.value - tol)
    if not len(better) or not problem.constraints:
        return set()
    # the bit set of the constraints each better point breaks (bit i: constraint i)
    rows = np.stack(
        [~c.satisfied(vals[c.quantity][better], rtol=rtol) for c in problem.constraints], axis=1
    )
    if rows.shape[1] <= 63:
        sets = [int(m) for m in np.unique(bit_sets(rows)[0])]
    else:  # past a uint64: as Python integers
        sets = [sum(1 << i for i in np.flatnonzero(r).tolist()) for r in rows]
    return {
        name
        for name, bits in _bits_by_name(problem).items()
        if any(m and not m & ~bits for m in sets)  # breaks some, only of that name
    }


def _relaxed(problem: Problem, name: str, certified: bool = True) -> Problem:
    """The problem a binding check searches: ``problem`` without the constraint ``name`` and,
    when that name is one constraint and the optimum is ``certified``, with its negation
    (:func:`_negation`) instead. A design better than the certified optimum (by more than twice
    its proven gap) that meets every other constraint must break this one, else it would be a
    better design of ``problem`` itself; so both problems have such a design or neither has,
    and the negation lets the search drop every box (and, on grids, every layer's point) that
    meets the constraint."""
    own = [c for c in problem.constraints if c.name == name]
    rest = problem.without(name)
    if len(own) != 1 or not certified:
        return rest
    return replace(rest, constraints=(*rest.constraints, _negation(own[0], problem)))


def _negation(c: Constraint, problem: Problem) -> Constraint:
    """A constraint met by every design that breaks ``c`` as the search judges it (on grids to
    the relative slack :data:`~.problem.FEAS_RTOL`, else exactly): ``q >= b`` (met when
    ``q >= b - r |b|``) is broken only where ``q < b - r |b|``, inside ``q <= b - r |b|``;
    ``q <= b`` only where ``q > b + r |b|``, inside ``q >= b + r |b|`` (the negation's own
    slack only widens it)."""
    r = FEAS_RTOL if problem.gridded else 0.0
    if c.sense == "min":
        return Constraint(f"{c.name} (broken)", c.quantity, "max", c.bound - r * abs(c.bound))
    return Constraint(f"{c.name} (broken)", c.quantity, "min", c.bound + r * abs(c.bound))


def _constraint_reports(
    problem: Problem, opt: Optimum, tables: Tables, grid: PerNGrid | None = None
) -> tuple[list[ConstraintReport], dict[Quantity, FloatArray] | None]:
    """Every constraint's report (value, margin, whether it binds), and the values at the
    runner-ups' points ``grid`` (:func:`_runner_grid`; None: none), evaluated with the probe."""
    tol = (0.0 if problem.gridded else 2 * GAP_RTOL) * abs(opt.value)
    tree = opt.trees()
    cellular = _cellular(opt)
    names = list(dict.fromkeys(c.name for c in problem.constraints))
    # on grids, nominally, the joint search's first points (three of each box the optimum's
    # pair reopens, :func:`~.joint_checks.three_points`) judged with the probe, in one
    # evaluation (under tolerances the joint search screens its points by the point model
    # first: a point's values over its tolerance box cost far more)
    nominal = not any(tolerance_box.covered(problem, q) for q in problem.quantities)
    every_check = _checks(problem, opt, names)
    first = (
        _first_boxes(problem, opt, tree, every_check)
        if problem.gridded and nominal and not cellular
        else None
    )
    more = None if grid is None or not len(grid.points) else grid.points
    if first is None:
        vals, witnessed, (at_grid,) = _probed(problem, opt, tables, tol, more)
    else:
        # the probe's points judged with the three points, by the checks' own rule
        # (:func:`~.joint_checks.answered_by`): with a certified optimum on a grid a point
        # better than it that meets every constraint but those of one name breaks one of them
        # (else it would be a better design), so the rule names what :func:`_witnessed` names
        assert opt.point is not None and opt.certified
        probe = _probe_points(problem, opt.point).columns() if problem.constraints else None
        extra = three_points(problem, first[0], first[1])
        if probe is not None:
            extra = np.concatenate([probe, extra])
        vals, _, (at_extra, at_grid) = _probed(
            problem, opt, tables, tol, extra, more, with_probe=False
        )
        assert at_extra is not None
        hit = answered_by(problem, every_check, at_extra, opt.value)
        witnessed = {c.name for c, h in zip(every_check, hit, strict=True) if h}
    capacity = _capacities(problem, opt, tables, vals)
    shared, idle = None, frozenset[str]()
    if tree is not None and not cellular:
        got = _untouched(problem, opt, tree, {c.name for c in problem.constraints} - witnessed)
        if got is not None:
            shared, idle = got
    # on grids, every check's searched pairs in one search per pair (:mod:`.joint_checks`)
    pending = [n for n in names if n not in witnessed]
    joint: dict[str, bool | None] = {}
    if tree is not None and problem.gridded and pending:
        todo = [c for c in every_check if c.name not in witnessed]
        joint = _joint_binding(
            problem,
            opt,
            tree,
            todo,
            tables,
            offered=first is not None,
            first_start=None if first is None else (every_check, first),
        )
    together: dict[str, bool | None] = {}
    if cellular and not budget_spent():  # the checks that fired in the cells: one search
        together = _shared_cell_binding(problem, opt, pending, tables, tol)
    out = []
    for c in problem.constraints:
        v = vals[c.quantity]
        margin = c.margin(v)
        binding: bool | None = None
        if c.name in witnessed:  # a better design breaking it alone was evaluated: binding
            binding = True
        elif c.name in joint and (joint[c.name] is not False or not opt.pruned):
            binding = joint[c.name]  # found, stopped (None), or no pair left to search
        elif c.name in together:
            binding = together[c.name]
        elif cellular and not budget_spent():  # the cells' search of each check
            binding = _cell_binding(problem, opt, c.name, tables, tol)
        elif not budget_spent():
            # binding once a design strictly better than the optimum (beyond the proven
            # gap) meets every other constraint; not binding once none is proven to exist
            binding = _binding(
                problem,
                opt,
                tree,
                c.name,
                tables,
                tol,
                shared if c.name in idle else None,
                searched=c.name in joint,
            )
        active = abs(margin) <= ACTIVE_RTOL * abs(c.bound)
        if c.load is not None:  # a deflection bound: delta = P / (P / delta) <= P / bound
            delta, most = c.load / v, c.load / c.bound
            out.append(
                ConstraintReport(
                    c.name,
                    c.quantity,
                    "max",
                    delta,
                    most,
                    most - delta,
                    "mm",
                    active,
                    binding,
                    load=c.load,
                    stiffness=v,
                    capacity=capacity.get(c.name),
                )
            )
            continue
        out.append(
            ConstraintReport(
                c.name,
                c.quantity,
                c.sense,
                v,
                c.bound,
                margin,
                c.unit,
                active,
                binding,
                capacity=capacity.get(c.name),
            )
        )
    return out, at_grid


class _PairFloors:
    """Whether each sheet pair's floor (:mod:`.choices`) reaches ``goal`` (no design of the pair
    lighter than it), from the floors of the first of ``problems`` that has them (each a
    relaxation of the problem a check searches); built at the first question, each pair's
    answer computed once (a coarse floor, refined when below the goal). No floors: never."""

    def __init__(self, problems: Sequence[Problem], goal: float) -> None:
        self.problems, self.goal = problems, goal
        self.floors: Floors | CellFloors | None = None
        self.built = False

        self.known: dict[int, float] = {}

    def _build(self) -> Floors | CellFloors | None:
        if not self.built:
            for p in self.problems:
                got = floors(p)
                if isinstance(got, CellFloors):  # a cells search per pair: not a cheap floor
                    continue
                self.floors = got
                if self.floors is not None:
                    break
            self.built = True
        return self.floors

    def floor(self, k: int) -> float:
        """Pair ``k``'s floor (g): coarse, refined when below the goal; 0 without floors."""
        if k not in self.known:
            fl, floor = self._build(), 0.0
            if fl is not None:
                floor = fl.coarse(k)
                if floor < self.goal:
                    floor = max(floor, fl.fine(k, self.goal))
            self.known[k] = floor
        return self.known[k]

    def reaches(self, k: int) -> bool:
        """Whether pair ``k`` holds no design lighter than the goal by its floor."""
        return self.floor(k) >= self.goal

    def found(self, k: int) -> bool:
        """Whether the fine floor of pair ``k`` met a design lighter than the goal that its
        problem accepts (:meth:`~.choices.Floors.accepted`): one exists."""
        return isinstance(self.floors, Floors) and self.floors.accepted(k) < self.goal


def _binding(
    problem: Problem,
    opt: Optimum,
    tree: tuple[Archive | None, ...] | None,
    name: str,
    tables: Tables,
    tol: float,
    shared: _PairFloors | None = None,
    searched: bool = False,
) -> bool | None:
    """Whether constraint ``name`` binds (None: not proven either way, the budget spent): the
    certified search of its check's problem (the constraint negated, :func:`_relaxed`) for a
    design better than the optimum by more than ``tol``, the optimum as incumbent, stopping at
    the first one; from the boxes of the solve's tree (``tree``) that this constraint alone
    closed below the optimum, a pair pruned whole (:attr:`Optimum.pruned`, archive None) from
    its whole domain (no tree: every pair from its whole domain). Every design of the check's
    problem better than the optimum lies in those boxes (:class:`~.archive.Archive`), so the
    answer is that of a search of the whole domain.

    A pair holds a better design or not whatever order the pairs are searched in, so the
    searched pairs go first: the optimum's own pair (where a better design, when there is
    one, lies most often), then the others by their floors (:class:`_PairFloors`, least first)
    of the check's problem (else of the problem without the constraint, a relaxation of it),
    those whose floor reaches the optimum skipped (no better design); then the pairs pruned
    whole, least floor of the solve first (:attr:`Optimum.floor_of`), skipped likewise, and
    answered without a search when the fine floor that did not reach the optimum met a better
    design that the check's problem accepts (:meth:`_PairFloors.found`: a design the search
    would find). The floors, which cost more than a search of a few boxes, are computed only
    once the optimum's pair has been searched to its end without a better design. ``shared``:
    floors of a relaxation of the check's problem too (the problem without several
    constraints, this one among them: :func:`_untouched`), asked first. ``searched``: the
    searched pairs are known to hold no better design (on grids, :func:`_joint_binding`), only
    the pairs pruned whole are left."""
    sign = -1.0 if problem.objective.sense == "max" else 1.0
    check = _relaxed(problem, name, opt.certified)
    goal = opt.value - sign * tol
    everything = pairs(problem)
    inc, certified = opt.value, True

    def search(i: int, start: Start | None) -> bool:
        """Search pair ``i`` from ``start``; whether a better design was found."""
        nonlocal inc, certified
        r = branch_and_bound(
            check, *everything[i], incumbent=inc, tables=tables, start=start, stop_below=goal
        )
        certified &= r.certified
        if r.point is not None and sign * r.value < sign * inc:
            inc = r.value
            return sign * r.value < sign * goal
        return False

    if tree is None:  # no archive: every pair from its whole domain, no floors
        for i in range(len(everything)):
            if budget_spent():
                return None
            if search(i, None):
                return True
        return False if certified else None
    bits = constraint_bits(problem, name)
    starts: dict[int, Start] = {}
    for i, a in enumerate(tree):
        if a is not None and not searched:
            start = a.reopen(bits, sign * opt.value)
            if len(start[0]):  # nothing reopened: no better design in the pair
                starts[i] = start
    first = everything.index(opt.candidates) if opt.candidates in everything else -1
    if first in starts:
        if budget_spent():
            return None
        if search(first, starts.pop(first)):
            return True
    own = _PairFloors((check, problem.without(name)), opt.value)

    def ruled_out(i: int) -> bool:
        return (shared is not None and shared.reaches(i)) or own.reaches(i)

    rest = sorted((i for i in starts if not ruled_out(i)), key=lambda i: (own.floor(i), i))
    todo: list[tuple[int, Start | None]] = [(i, starts[i]) for i in rest]
    # the pairs pruned whole, least floor of the solve first (a better design lies most often
    # in a pair that was nearly as light)
    whole = sorted(
        (i for i, a in enumerate(tree) if a is None), key=lambda i: (opt.floor_of.get(i, 0.0), i)
    )
    todo += [(i, None) for i in whole]
    for i, box in todo:
        if budget_spent():
            return None
        if box is None and ruled_out(i):
            continue
        if box is None and own.found(i):
            return True  # its floor met a better design that the check's problem accepts
        if search(i, box):
            return True  # shown: a better design exists
    return False if certified else None


def _checks(problem: Problem, opt: Optimum, names: Sequence[str]) -> list[Check]:
    """The binding checks of ``names`` (:class:`~.joint_checks.Check`): each name's bits, and
    its negation (:func:`_negation`) when it is one constraint and the optimum certified."""
    by_name: dict[str, list[Constraint]] = {}
    for c in problem.constraints:
        by_name.setdefault(c.name, []).append(c)
    checks = []
    for name in names:
        own = by_name.get(name, [])
        negation = _negation(own[0], problem) if len(own) == 1 and opt.certified else None
        checks.append(Check(name, constraint_bits(problem, name), negation))
    return checks


def _first_boxes(
    problem: Problem, opt: Optimum, tree: tuple[Archive | None, ...] | None, checks: list[Check]
) -> JointStart | None:
    """The boxes of the optimum's sheet pair's archive that some check of ``checks`` reopens
    (:func:`~.joint_checks.reopened`: lo, hi, bound, the checks each carries), the first that
    :func:`_joint_binding` searches; None without an archive of that pair or with none."""
    everything = pairs(problem)
    if tree is None or not checks or opt.candidates not in everything:
        return None
    a = tree[everything.index(opt.candidates)]
    if a is None:
        return None
    sign = -1.0 if problem.objective.sense == "max" else 1.0
    start = reopened(a, checks, sign * opt.value)
    return start if len(start[0]) else None


def _joint_binding(
    problem: Problem,
    opt: Optimum,
    tree: tuple[Archive | None, ...],
    names: Sequence[str] | Sequence[Check],
    tables: Tables,
    offered: bool = False,
    first_start: tuple[Sequence[Check], JointStart] | None = None,
) -> dict[str, bool | None]:
    """The binding checks of ``names`` (names, or their checks: :func:`_checks`) on a grid
    over the sheet pairs the solve searched (their archives), the optimum's own pair first,
    each pair's checks in one search (:func:`~.joint_checks.joint_search`, its answers those
    of each check's own search, the first part of :func:`_binding`): True, a better design was
    found (binding); None, the budget ran out first; False, no searched pair holds one (the
    pairs pruned whole are left to :func:`_binding`). ``offered``: the three points of every
    box the optimum's pair reopens for any constraint were judged for every check already
    (:func:`_first_boxes`), and the checks they answer are not in ``names``. ``first_start``:
    checks (named as those of ``names``, and more) and the boxes of the optimum's pair they
    reopen (:func:`_first_boxes`), narrowed to those of ``names`` instead of reopened again."""
    sign = -1.0 if problem.objective.sense == "max" else 1.0
    checks = [n for n in names if isinstance(n, Check)]
    checks += _checks(problem, opt, [n for n in names if isinstance(n, str)])
    answers: dict[str, bool | None] = {c.name: False for c in checks}
    everything = pairs(problem)
    first = everything.index(opt.candidates) if opt.candidates in everything else -1
    order = sorted(range(len(tree)), key=lambda i: (i != first, i))
    for i in order:
        a = tree[i]
        todo = [c for c in checks if answers[c.name] is False]
        if a is None or not todo:
            continue
        if i == first and first_start is not None:
            column = {c.name: j for j, c in enumerate(first_start[0])}
            start = narrowed(first_start[1], [column[c.name] for c in todo])
        else:
            start = reopened(a, todo, sign * opt.value)
        if not len(start[0]):
            continue
        got = joint_search(
            problem, everything[i], tables, todo, start, opt.value, offered and i == first
        )
        for c, answer in zip(todo, got, strict=True):
            if answer is not False:
                answers[c.name] = answer
    return answers


def _untouched(
    problem: Problem, opt: Optimum, tree: tuple[Archive | None, ...], names: set[str]
) -> tuple[_PairFloors, frozenset[str]] | None:
    """The constraints of ``names`` whose binding check has nothing to search in the searched
    pairs (their archives reopen no box below the optimum), only the pairs pruned whole, and
    the floors (:class:`_PairFloors`) of ``problem`` without all of them: one floor per pair
    answers each of these checks (each one's problem is a subset of this relaxation's), not
    the others'. None when fewer than two such constraints or no pair is pruned whole."""
    if not opt.pruned:
        return None
    sign = -1.0 if problem.objective.sense == "max" else 1.0
    idle = []
    for name in names:
        bits = constraint_bits(problem, name)
        if all(a is None or not len(a.reopen(bits, sign * opt.value)[0]) for a in tree):
            idle.append(name)
    if len(idle) < 2:
        return None
    rest = problem
    for name in idle:
        rest = rest.without(name)
    return _PairFloors((rest,), opt.value), frozenset(idle)


def _cellular(opt: Optimum) -> bool:
    """Whether the solve of ``opt`` was by cells (:mod:`.cells`: continuous W and alpha on
    independent layers, material choices; :func:`_by_cells`), not the plain search it falls
    back to on a wide domain."""
    return opt.starts is not None


def _cell_binding(
    problem: Problem, opt: Optimum, name: str, tables: Tables, tol: float
) -> bool | None:
    """Whether constraint ``name`` binds, for a problem solved by its cells: whether the
    problem without it has a design lighter than the optimum by more than ``tol`` (g), by
    :func:`optimize` of that problem with the goal as incumbent (its cells and branch and
    bound, :func:`_by_cells`). Such a design breaks the constraint (else it would be a design
    of the problem lighter than its certified optimum), so it is the binding check's design
    (:func:`_relaxed`). None when the optimum or the check is not certified."""
    if not opt.certified or problem.objective.sense != "min":
        return None
    goal = opt.value - tol
    own = {i for i, c in enumerate(problem.constraints) if c.name == name}
    if opt.starts is not None and opt.fired is not None and not own & opt.fired:
        # it dropped nothing the solve's cells dropped: its designs lighter than the
        # optimum lie in the boxes they left, searched for one by the branch and bound of
        # the check's problem with the constraint's negation (:func:`_relaxed`: the optimum
        # is certified, so each of them breaks it; the boxes where it holds are dropped)
        check, everything, certified = _relaxed(problem, name), pairs(problem), True
        for k, (lo, hi, low) in enumerate(opt.starts):
            keep = low < goal
            if not keep.any():
                continue
            r = branch_and_bound(
                check,
                *everything[k],
                incumbent=opt.value,
                tables=tables,
                start=(lo[keep], hi[keep], low[keep]),
                stop_below=goal,
            )
            if r.point is not None and r.value < goal:
                return True
            certified &= r.certified
        return False if certified else None
    got = optimize(problem.without(name), tables=tables, incumbent=goal, prune=True)
    if got.point is not None and got.value < goal:
        return True
    return False if got.certified else None


def _shared_cell_binding(
    problem: Problem, opt: Optimum, names: Sequence[str], tables: Tables, tol: float
) -> dict[str, bool | None]:
    """Whether each constraint of ``names`` that fired in the solve's cells
    (:attr:`Optimum.fired`) binds, for a problem solved by its cells: the answers of
    :func:`_cell_binding`, all found by one shared cells search
    (:func:`~.cell_checks.shared_search`, below the goal, the optimum less ``tol`` in g) and,
    for each check it leaves open, the branch and bound of the check's problem
    (:func:`_relaxed`: the optimum is certified) from the boxes it left of each sheet pair,
    the optimum's pair first, stopped at the first design below the goal. Empty (each check
    then searched on its own) when the optimum is not certified, nothing fired, or the shared
    search does not apply; None for a check whose search was not certified. When the shared
    search stops at its limit of cell pairs (:data:`~.cells.BUDGET`) first, a check it found a
    design for binds (True) and the others are left unknown (None): each one's own search of the
    whole domain (:func:`_cell_binding`) would judge the cell pairs of every sheet pair again
    and leave its branch and bound the boxes the shared one could not settle (films-13-cont of
    benchmarks/edges.py: the first such check ran 37 s to the 60 s budget and 1.47 GB without
    an answer, and left the runner-ups no time; unknown, the explanation ends in 31 s at 230 MB
    with every runner-up). Those it leaves unknown are then asked of a polish of the optimum
    (:func:`_polished_witnesses`): a design it finds answers True, as the check's own search
    would. A shared search whose first cell pairs alone reach its limit is not run (it could
    settle nothing), so every check is asked of the polish (films-13-cont: the same answers,
    1.6 s of CPU less)."""
    if not opt.certified or opt.fired is None or problem.objective.sense != "min":
        return {}
    from corrugate.solver import cell_checks  # a problem solved by its cells only

    fired = {problem.constraints[i].name for i in opt.fired}
    checks = cell_checks.checks_of(problem, [n for n in names if n in fired], True)
    if not checks or not cell_checks.applies(problem, checks):
        return {}
    goal = opt.value - tol
    everything = pairs(problem)
    got = cell_checks.shared_search(problem, everything, tables, checks, goal)
    out: dict[str, bool | None] = {}
    if not got.settled:
        out = {ch.name: True if got.found[ch.name] else None for ch in checks}
        unknown = [ch for ch in checks if out[ch.name] is None]
        for ch in _polished_witnesses(problem, opt, unknown, tables, goal):
            out[ch.name] = True
        return out
    first = everything.index(opt.candidates) if opt.candidates in everything else -1
    for ch in checks:
        if got.found[ch.name]:
            out[ch.name] = True
            continue
        check = _relaxed(problem, ch.name, True)
        answer: bool | None = False
        starts = got.starts.get(ch.name, {})
        for k in sorted(starts, key=lambda k: (k != first, float(starts[k][2].min()), k)):
            lo, hi, low = starts[k]
            keep = low < goal - GAP_RTOL * abs(goal)
            if not keep.any():
                continue
            if budget_spent():
                answer = None
                break
            r = branch_and_bound(
                check,
                *everything[k],
                incumbent=goal,
                tables=tables,
                start=(lo[keep], hi[keep], low[keep]),
                stop_below=goal,
            )
            if r.point is not None and r.value < goal:
                answer = True
                break
            if not r.certified:
                answer = None
        out[ch.name] = answer
    return out


#: The polishes a binding check's witness is sought by at most (:func:`_polished_witnesses`).
WITNESS_CLIMB = 3


def _polished_witnesses(
    problem: Problem,
    opt: Optimum,
    checks: Sequence[cell_checks.CellCheck],
    tables: Tables,
    goal: float,
) -> list[cell_checks.CellCheck]:
    """The checks shown binding by a polish of the optimum: for each check,
    :func:`~.polish.climb` of the optimum on the problem without the check's constraints
    (:data:`WITNESS_CLIMB` polishes at most: SLSQP on the optimum's sheets, then each layer's
    n moved by -1, 0 or +1 while it improves); binding when its design is lighter than
    ``goal`` (g) and meets every other constraint, judged as the shared search judges its
    evaluated designs (:func:`~.cell_checks.answered`: the problem's certified values, no
    slack). Such a design exists, so the check's own search (certified) answers True too; the
    polish only looks for it (the optimum is a design of each of those problems), and a check
    it does not show binding is left as it was (as are those left when the budget is spent). Asked for the checks a shared search stopped
    at its limit left unknown (:func:`_shared_cell_binding`): films-13-cont's side_x.min and
    side_y.min (the latter through an n moved by one) within 0.2 s."""
    if opt.point is None or opt.candidates is None:
        return []
    from corrugate.solver import cell_checks, cells
    from corrugate.solver.polish import climb

    out = []
    for ch in checks:
        if budget_spent():
            break
        relaxed = cells.relaxed_without(problem, ch.bits)
        exact = cells.judge_of(relaxed, *opt.candidates, tables)
        got = climb(relaxed, *opt.candidates, opt.point, tables, exact, set(), WITNESS_CLIMB)
        if got is None or not got.mass < goal:
            continue
        if cell_checks.answered(problem, opt.candidates, tables, _as_arrays(got.point), goal, ch):
            out.append(ch)
    return out


def _as_arrays(x: DesignPoints) -> DesignPoints:
    """Design ``x`` (one point, its coordinates floats or arrays) with arrays of one entry."""
    return DesignPoints.of(
        *(
            LayerPoints(
                *(
                    np.atleast_1d(np.asarray(getattr(x.layer(k), v), dtype=np.float64))
                    for v in ("n", "W", "alpha")
                )
            )
            for k in range(x.count)
        ),
        count=x.count,
    )


def _cell_runner_ups(
    problem: Problem, opt: Optimum, tables: Tables, span: tuple[int, int], skip: int | None = None
) -> dict[int, Optimum]:
    """The runner-ups of a problem solved by its cells: for each n of ``span`` but ``skip``
    (the optimum's own n when both its layers have it: the optimum is its runner-up),
    :func:`optimize` of the problem with both layers' n fixed to n (its cells and branch and
    bound, to :data:`RUNNER_UP_GAP_RTOL`); by n, those that have a design.

    The n are taken nearest the optimum's first, and each search starts from an incumbent: a
    design of the problem with n fixed (:func:`_runner_seed`, polished from the designs already
    found at the neighbouring n, each on its own sheet pair). Every design lighter than that
    incumbent lies in what its search keeps (it only prunes, as any incumbent), so a search that
    finds none lighter proves the incumbent the best with n to the same gap
    (:func:`_seeded_answer`); a lighter one found is the answer as before. With no such
    incumbent (none of the moved designs polished into the problem's set), the search seeks
    and polishes its own before its first cell pairs (``seek``, :func:`~.cells.search_pairs`).
    films-5-cont: n = 18 certified (2.19 g in 1.1 M cell pairs; without an incumbent its
    search stopped at :data:`RUNNER_UP_CELLS` with 4.30 g)."""
    out: dict[int, Optimum] = {}
    assert opt.point is not None and opt.candidates is not None
    known: dict[int, tuple[DesignPoints, tuple[Candidate, Candidate]]] = {}
    n_star = round(opt.point.layer(0).n)
    known[n_star] = (opt.point, opt.candidates)
    order = sorted(range(span[0], span[1] + 1), key=lambda n: (abs(n - n_star), n))
    for n in order:
        if n == skip:
            continue
        if budget_spent():
            break
        fixed = replace(problem, n_lo=n, n_hi=n)
        seed = _runner_seed(fixed, n, known, tables)
        got = optimize(
            fixed,
            tables=tables,
            incumbent=None if seed is None else seed[0],
            gap_rtol=RUNNER_UP_GAP_RTOL,
            prune=True,
            most=RUNNER_UP_CELLS,
            seek=seed is None,
        )
        if got.point is None and seed is not None:
            got = _seeded_answer(got, seed)
        if got.point is not None and got.candidates is not None:
            out[n] = got
            known[n] = (got.point, got.candidates)
    return out


#: The designs already found a runner-up's incumbent is polished from (:func:`_runner_seed`):
#: those of the n nearest its own, at most this many (films-5-cont's runner-ups: the same
#: answers with 1 as with 2, 5.27 against 5.68 s of CPU, medians of three alternated runs).
RUNNER_SEEDS = 1
#: The starts polished when none of a moved design's is accepted (:func:`_runner_seed`).
RESTORES = 1


def _seeded_answer(
    got: Optimum, seed: tuple[float, DesignPoints, tuple[Candidate, Candidate]]
) -> Optimum:
    """The runner-up of a search (``got``) that found no design lighter than its incumbent
    ``seed`` (mass g, design, sheet pair): the incumbent itself, certified when the search is
    (no design with its n lighter than its mass by more than :data:`RUNNER_UP_GAP_RTOL` of it:
    the search dropped only what the incumbent less that gap bounds)."""
    mass, point, pair = seed
    gap = RUNNER_UP_GAP_RTOL if got.certified else math.inf
    return Optimum(point, pair, mass, got.certified, gap, got.boxes, got.iterations)


def _runner_seed(
    fixed: Problem,
    n: int,
    known: dict[int, tuple[DesignPoints, tuple[Candidate, Candidate]]],
    tables: Tables,
) -> tuple[float, DesignPoints, tuple[Candidate, Candidate]] | None:
    """An incumbent for the runner-up search of ``fixed`` (both layers' n fixed to ``n``): the
    designs of ``known`` (by n: the optimum and the runner-ups found) at the
    :data:`RUNNER_SEEDS` n nearest ``n``, each moved to n on its own sheet pair
    (:func:`_moved_to`), judged by the problem's own rule (:func:`~.cells.judge_of`: its certified
    values, no slack), the lightest accepted one polished (:func:`~.polish.polish`, no heavier, a
    design of ``fixed`` by that rule), else the first :data:`RESTORES` of them polished anyway
    (SLSQP may reach the problem's set from outside it; the polish keeps only a design the
    rule accepts); its (mass g, design, sheet pair), or None when no polish found one. Only an
    incumbent: nothing of the certificate rests on it."""
    from corrugate.solver import cells
    from corrugate.solver.polish import polish

    best: tuple[float, DesignPoints, tuple[Candidate, Candidate]] | None = None
    near = sorted(known, key=lambda m: (abs(m - n), m))[:RUNNER_SEEDS]
    for m in near:
        x, pair = known[m]
        starts = _moved_to(fixed, x, n)
        if not len(starts):
            continue
        exact = cells.judge_of(fixed, *pair, tables)
        mass, ok = exact(starts)
        f = np.where(ok, mass, math.inf)
        b = int(np.argmin(f))
        # the lightest accepted start, else the nearest ones (SLSQP may reach P's set from them)
        tries = [b] if math.isfinite(float(f[b])) else range(min(RESTORES, len(starts)))
        for k in tries:
            got = polish(fixed, *pair, starts.point(k), tables, exact)
            if got is not None and (best is None or got.mass < best[0]):
                best = (got.mass, got.point, pair)
    return best


#: The fold angles a moved design's layer takes (:func:`_moved_to`): its own times these.
MOVED_ALPHA = np.geomspace(0.7, 1.0 / 0.7, 11)  # 1 among them (the 6th)
#: The extents a moved design's layer keeps (:func:`_moved_to`): its own times these.
MOVED_EXTENT = (1.0 + 1e-9, 1.0 + 1e-6, 1.01, 1.05)


def _moved_to(problem: Problem, x: DesignPoints, n: int) -> DesignPoints:
    """Designs with both layers' n set to ``n`` made from design ``x`` (one point): each layer's
    fold angle its own times :data:`MOVED_ALPHA`, its W then keeping its extent
    (n + 1) W sin(alpha / 2) times :data:`MOVED_EXTENT` (a rectangle's sides, often a bound that
    holds with equality), those inside W's and alpha's ranges; every pair of the two layers'
    such (n, W, alpha) (mm, deg). Only starts of a polish: judged by the problem's own rule."""
    per: list[tuple[FloatArray, FloatArray]] = []
    for k in (0, 1):
        lay = x.layer(k)
        m = float(np.asarray(lay.n).reshape(-1)[0])
        W = float(np.asarray(lay.W).reshape(-1)[0])
        a = float(np.asarray(lay.alpha).reshape(-1)[0])
        extent = (m + 1.0) * W * math.sin(math.radians(a) / 2.0)
        # nearest the design first: its own alpha, then by how far the factor is from 1
        order = np.argsort(np.abs(np.log(MOVED_ALPHA)), kind="stable")
        alphas = np.repeat(a * MOVED_ALPHA[order], len(MOVED_EXTENT))
        extents = np.tile(extent * np.asarray(MOVED_EXTENT), len(MOVED_ALPHA))
        Ws = extents / ((n + 1.0) * np.sin(np.radians(alphas) / 2.0))
        ok = (
            (Ws >= problem.W.lo)
            & (Ws <= problem.W.top)
            & (alphas >= problem.alpha.lo)
            & (alphas <= problem.alpha.top)
        )
        per.append((Ws[ok], alphas[ok]))
    (W1, a1), (W2, a2) = per
    grid = np.meshgrid(np.arange(len(W1)), np.arange(len(W2)), indexing="ij")
    i, j = (g.reshape(-1) for g in grid)
    nn = np.full(len(i), float(n))
    return DesignPoints.of(LayerPoints(nn, W1[i], a1[i]), LayerPoints(nn, W2[j], a2[j]))


def _runner_span(problem: Problem, opt: Optimum) -> tuple[int, int]:
    """The n of the runner-ups: within :data:`RUNNER_UP_SPREAD` of the optimum's layer-1 n."""
    assert opt.point is not None
    n_star = round(opt.point.layer(0).n)
    return (
        max(problem.n_lo, n_star - RUNNER_UP_SPREAD),
        min(problem.n_hi, n_star + RUNNER_UP_SPREAD),
    )


def _runner_grid(problem: Problem, opt: Optimum) -> PerNGrid | None:
    """The grid points of the runner-ups' search of the optimum's sheet pair when few
    (:func:`~.bnb.per_n_grid` of the boxes its archive may hold a feasible design in), so that
    they are evaluated with the binding probe; None when that search is needed."""
    tree = opt.trees()
    everything = pairs(problem)
    if tree is None or _cellular(opt) or opt.candidates not in everything:
        return None
    a = tree[everything.index(opt.candidates)]
    if a is None:
        return None
    return per_n_grid(problem, start=a.reopen(), per_n=_runner_span(problem, opt))


def _runner_ups(
    problem: Problem,
    opt: Optimum,
    tables: Tables,
    given: tuple[PerNGrid, dict[Quantity, FloatArray]] | None = None,
) -> list[RunnerUp]:
    """The certified best design for each n within :data:`RUNNER_UP_SPREAD` of the optimum's
    layer-1 n, n fixed as ``optimize(n_fixed=(n, n))`` fixes it (both layers' n; see
    :func:`~.bnb._dims`): one search per sheet pair with one incumbent per n, from the boxes of
    the solve that may hold a feasible design (:attr:`Optimum.archives`), else from the whole
    domain; with continuous variables to the relative gap :data:`RUNNER_UP_GAP_RTOL`. The entry
    of the optimum's n, when both its layers have it, is the certified optimum itself (the best
    design of the whole problem is the best with that n). ``given``: the optimum's pair's
    grid points (:func:`_runner_grid`) and their values, its answer without a search."""
    assert opt.point is not None
    n_star = round(opt.point.layer(0).n)
    a, b = _runner_span(problem, opt)
    tree = opt.trees()
    sign = -1.0 if problem.objective.sense == "max" else 1.0
    best: dict[int, tuple[BnBResult, tuple[Candidate, Candidate]]] = {}
    certified = {n: True for n in range(a, b + 1)}
    everything = pairs(problem)
    if _cellular(opt):
        own_n = opt.certified and round(opt.point.layer(1).n) == n_star
        got = _cell_runner_ups(problem, opt, tables, (a, b), n_star if own_n else None)
        rows = []
        for n in range(a, b + 1):
            found = opt if n == n_star and own_n else got.get(n)
            if found is None:
                continue
            rows.append(_runner_up(problem, n, found))
        return rows
    for i, pair in enumerate(everything):
        if budget_spent():
            for n in certified:
                certified[n] = False
            break
        if tree is not None and tree[i] is None:
            continue  # pruned whole: below, against the runner-ups of the others
        r: BnBResult | None
        if given is not None and pair == opt.candidates:  # its grid points' values given
            r = per_n_answer(problem, *given)
        else:
            start = None if tree is None else tree[i].reopen()  # type: ignore[union-attr]
            # few grid points left: all evaluated at once, the search's answer
            r = (
                None
                if start is None
                else enumerated_per_n(problem, *pair, start=start, per_n=(a, b), tables=tables)
            )
            if r is None:
                r = branch_and_bound(
                    problem,
                    *pair,
                    tables=tables,
                    start=start,
                    per_n=(a, b),
                    gap_rtol=RUNNER_UP_GAP_RTOL,
                )
        assert r.by_n is not None
        for n, rn in r.by_n.items():
            certified[n] &= rn.certified
            if rn.point is not None and (
                n not in best or sign * rn.value < sign * best[n][0].value
            ):
                best[n] = (rn, pair)
    if tree is not None and opt.pruned:
        _pruned_runner_ups(problem, opt, tables, (a, b), best, certified)
    out = []
    own = opt.certified and round(opt.point.layer(1).n) == n_star
    for n in range(a, b + 1):
        if n == n_star and own:
            found = opt
        elif n not in best:
            continue
        else:
            rn, pair = best[n]
            found = Optimum(rn.point, pair, rn.value, certified[n], 0.0, rn.boxes, rn.iterations)
        out.append(_runner_up(problem, n, found))
    return out


def _runner_up(problem: Problem, n: int, found: Optimum) -> RunnerUp:
    """The runner-up row of the best design ``found`` with n creases: its mass, layers and
    whether it is certified."""
    layers = assembly_of(problem, found).layers
    dicts = tuple(layer_dict(i + 1, layer) for i, layer in enumerate(layers))
    return RunnerUp(n, found.value, dicts, found.certified)


def _pruned_runner_ups(
    problem: Problem,
    opt: Optimum,
    tables: Tables,
    span: tuple[int, int],
    best: dict[int, tuple[BnBResult, tuple[Candidate, Candidate]]],
    certified: dict[int, bool],
) -> None:
    """The runner-ups of the sheet pairs pruned whole (:attr:`Optimum.pruned`, least mass),
    into ``best`` and ``certified``: a pair is searched only for the n whose floor with n fixed
    (:mod:`.choices`, both layers' n, as ``per_n`` fixes it) is below the best design with that
    n of the pairs before it, one incumbent per n (the others' best), the others' incumbent
    -inf (nothing searched); pairs by rising floor. A pair that holds no lighter design with
    some n would return none for it: the runner-ups are the same. The solve's own floor of a
    pair (:attr:`Optimum.floor_of`: every design of the pair, whatever its n, is at least that
    heavy) is asked before any floor with n fixed."""
    a, b = span
    everything = pairs(problem)
    whole = opt.floors if opt.floors is not None else floors(problem)
    per_n: dict[int, Floors | CellFloors | None] = {}
    order = sorted(opt.pruned, key=lambda k: (0.0 if whole is None else whole.coarse(k), k))
    for k in order:
        if budget_spent():
            for n in certified:
                certified[n] = False
            return
        target = {n: best[n][0].value if n in best else math.inf for n in range(a, b + 1)}
        floor = 0.0 if whole is None else whole.coarse(k)
        floor = max(floor, opt.floor_of.get(k, 0.0))
        need = {}
        for n, goal in target.items():
            if floor >= goal:
                continue
            if n not in per_n:  # the solve's lists with that n, else built
                per_n[n] = (
                    opt.floors.with_n(n)
                    if opt.floors is not None
                    else floors(replace(problem, n_lo=n, n_hi=n))
                )
            fn = per_n[n]
            f = 0.0 if fn is None else fn.coarse(k)
            if f < goal and fn is not None:
                f = max(f, fn.fine(k, goal))
            if f < goal:
                need[n] = goal
        if not need:
            continue
        incumbents = np.array([need.get(n, -math.inf) for n in range(a, b + 1)])
        r = branch_and_bound(
            problem,
            *everything[k],
            incumbent=incumbents,
            tables=tables,
            per_n=(a, b),
            gap_rtol=RUNNER_UP_GAP_RTOL,
        )
        assert r.by_n is not None
        for n, rn in r.by_n.items():
            certified[n] &= rn.certified
            if rn.point is not None and (n not in best or rn.value < best[n][0].value):
                best[n] = (rn, everything[k])


def constraint_bits(problem: Problem, name: str) -> int:
    """The bit set of :class:`~.archive.Archive` masks of the constraints called ``name`` (0:
    none)."""
    return _bits_by_name(problem).get(name, 0)


#: The attribute of a problem that keeps its constraints' bit sets by name.
_BITS = "_constraint_bits"


def _bits_by_name(problem: Problem) -> dict[str, int]:
    """Each constraint name's bit set (bit i: ``problem.constraints[i]``), built once per
    problem and kept on it (a cache of its own fields, as :func:`~.quantities.reported`)."""
    kept: dict[str, int] | None = problem.__dict__.get(_BITS)
    if kept is None:
        kept = {}
        for i, c in enumerate(problem.constraints):
            kept[c.name] = kept.get(c.name, 0) | 1 << i
        object.__setattr__(problem, _BITS, kept)
    return kept
