"""The FE twin of a design's first failure under each of its load cases: the rows ``corrugate
verify`` adds below the constraints' (issue 34; docs/fea.md sections 2 and 6).

Every load-case fixture a behavioural constraint of the design runs in (its twin,
:func:`corrugate.fea.verify.twin_of`: three-point, four-point, cantilever, platens along a crease
direction, the wheel) gives two statements, each on the mesh series and judged as the
constraint rows are (:func:`corrugate.fea.extrapolate.judge`, docs/fea.md 6: a load is at or
below the FE's only on a series shown asymptotic against it, refined up to ``max_mesh``, else
"not converged"):

* **buckling**: the fixture run as a linear buckling analysis
  (:class:`corrugate.fea.steps.LinearBuckling`): the lowest positive buckling factor is the load
  (N) at which the part first buckles. The load is a dead load (a weight, a finger: the load
  line free to move in the mode). The static deck with ``*STATIC`` replaced by ``*BUCKLE`` (a
  testing machine's held head) gives the same load where the two decks agree and differs
  elsewhere, either way (docs/validation/capacity.md: 1.07 against 4.76 N for issue 34's stubby
  panel, 0.80 against 0.66 N for a cantilever); verify runs the dead load only.
* **yield**: the static run with nodal stresses (coupon fixtures; the wheel's deck writes none):
  the load (N) at which the largest |principal stress| over the shells' nodes (both surfaces, the
  load and support lines included) reaches the yield strength of its part's material
  (:attr:`corrugate.materials.library.Material.yield_strength`), P_y = sigma_y x P / sigma_max
  of the linear run at force P. At the load and support lines the shell stresses concentrate and
  grow as the mesh refines, so this series may not converge: the finest value is then what there
  is, as its estimate says.

A row also names the load its constraints are certified under (the largest ``load_N`` among
them, None for a stiffness bound) and whether that load is at or below the FE estimate, and,
where the design carries a load capacity (a ``Pmax`` constraint: a strength bound, or the one a
deflection bound under a load brings; docs/load_cases.md), the model's first-failure load (its
least ``failure_loads_N``: the capacity times the safety factor) and whether it is at or below the
FE's (issue 34: "a certified capacity holds when X times the safety factor is at or below the
FE's first failure"). Each of the two comparisons has its verdict (``holds``, ``fails``, ``not
converged``), the first decided by the certified load, else by the model's first failure; a row
with neither shows the series' estimate on the safe side (:func:`corrugate.fea.extrapolate.
extrapolate` with ``sense`` ``min``: a lower bound, or none). The rows are evidence beside the
constraint rows, not part of their verdict (``holds``).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Generator, Mapping, Sequence
from concurrent.futures import Executor
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from corrugate.core.errors import CorrugateError
from corrugate.fea.assembly import AssemblyMesh, solve_assembly
from corrugate.fea.extrapolate import Judgement, extrapolate, judge
from corrugate.fea.outline import solve_outline
from corrugate.fea.steps import LinearBuckling
from corrugate.fea.tasks import Request, Tasks, worker_failure
from corrugate.fea.verify import Row, Twin, behavioural, joint_options, safety_factor, twin_of
from corrugate.geometry.layer import Assembly
from corrugate.mechanics.behaviours import own_test
from corrugate.solver.quantity import Quantity

__all__ = ["FailureRow", "first_failures", "yield_load"]

#: The failure modes of a row, in the order they are listed.
MODES = ("buckling", "yield")


@dataclass(frozen=True, slots=True)
class FailureRow:
    """One failure mode of one load-case fixture: ``test`` (the fixture run and where),
    ``mode`` (``buckling`` or ``yield``), the ``constraints`` run in it, the ``load`` (N) they
    are certified under (None: no load stated), the FE series (elements per facet -> load N at
    the first failure, None where the run failed), the estimate ``fe`` (N), its ``order`` and
    ``how``, a ``note`` (failed runs, why there is no value), the ``model``'s first-failure
    load (N, no safety factor; None without a load capacity among the constraints) and the
    ``verdict`` of the load against the FE and the ``model_verdict`` of the model's first failure
    against it (:data:`VERDICT_WORDS`, :func:`corrugate.fea.extrapolate.judge`; None where there
    is no load or no model value). Built without verdicts (a table made by hand), they are
    read from ``fe`` as a plain comparison."""

    test: str
    mode: str
    constraints: tuple[str, ...]
    load: float | None
    fe_series: dict[int, float | None] = field(default_factory=dict)
    fe: float | None = None
    order: float | None = None
    how: str = ""
    note: str = ""
    model: float | None = None
    verdict: str | None = None
    model_verdict: str | None = None

    @property
    def model_holds(self) -> bool | None:
        """Whether the model's first-failure load is at or below the FE's: True on a series
        shown asymptotic against it (``model_verdict`` ``holds``), False when it fails, None
        when not converged or without a model value."""
        return _holds(self.model_verdict, self.model, self.fe)

    @property
    def holds(self) -> bool | None:
        """Whether the certified load is at or below the FE's first failure: True on a series
        shown asymptotic against it (``verdict`` ``holds``), False when it fails, None when not
        converged or without a load."""
        return _holds(self.verdict, self.load, self.fe)

    @property
    def sentence(self) -> str:
        """The row in words: "first buckling at X N (series a / b / c, estimate e)"."""
        series = " / ".join("-" if v is None else f"{v:.4g}" for v in self.fe_series.values())
        first = "first buckling" if self.mode == "buckling" else "first yield"
        at = "-" if self.fe is None else f"{self.fe:.4g}"
        how = f", {self.how}" if self.how else ""
        return f"{first} at {at} N (series {series}{how})"

    def as_json(self) -> dict[str, Any]:
        """The row as verify.json writes it (no NaN: null where unknown)."""
        return {
            "test": self.test,
            "mode": self.mode,
            "constraints": list(self.constraints),
            "load_N": self.load,
            "fe_series": {str(k): _finite(v) for k, v in self.fe_series.items()},
            "fe": _finite(self.fe),
            "order": _finite(self.order),
            "estimate": self.how or None,
            "holds": self.holds,
            "verdict": self.verdict,
            "statement": self.sentence,
            "note": self.note or None,
            "model_first_failure_N": _finite(self.model),
            "model_holds": self.model_holds,
            "model_verdict": self.model_verdict,
        }


#: A comparison's verdict (:func:`corrugate.fea.extrapolate.judge`'s ``open`` is "not
#: converged", as in verify's constraint rows).
VERDICT_WORDS = {"holds": "holds", "fails": "fails", "open": "not converged"}


def _holds(verdict: str | None, bound: float | None, fe: float | None) -> bool | None:
    """True for ``holds``, False for ``fails``, None otherwise; without a verdict (a row made by
    hand) the plain comparison ``bound <= fe``."""
    if verdict is not None:
        return {"holds": True, "fails": False}.get(verdict)
    if bound is None or fe is None:
        return None
    return bound <= fe


def _finite(v: float | None) -> float | None:
    return v if v is not None and math.isfinite(v) else None


def yield_load(
    force: float, peak: Sequence[float], strengths: Sequence[float | None]
) -> float | None:
    """The load (N) at which a linear static run at ``force`` (N) first reaches yield: the least
    over the parts of sigma_y,k x force / sigma_max,k (``peak``: each part's largest |principal
    stress|, MPa; ``strengths``: its material's yield strength, MPa, None when unknown); None
    when no part has both."""
    loads = [
        s * abs(force) / p
        for p, s in zip(peak, strengths, strict=True)
        if s is not None and p > 0 and math.isfinite(p)
    ]
    return min(loads) if loads else None


def _peak_by_part(r: Any, parts: int) -> list[float]:
    """The largest |principal stress| (MPa) of each part (material 1, 2, 3) of a static run."""
    f = r.stresses
    amax = np.max(np.abs(f.principal()), axis=1)
    return [
        float(np.max(amax[f.material == k])) if np.any(f.material == k) else math.nan
        for k in range(1, parts + 1)
    ]


def first_failures(
    assembly: Assembly,
    constraints: Sequence[Mapping[str, Any]],
    joint: str = "none",
    meshes: Sequence[int] = (2, 4, 8),
    *,
    progress: Callable[[str], None] = lambda line: None,
    folder: Path | None = None,
    timeout: float = 900.0,
    done: Sequence[Row] = (),
    max_mesh: int | None = None,
    executor: Executor | None = None,
    jobs: int | None = None,
) -> tuple[FailureRow, ...]:
    """The failure rows (module docstring) of every load-case fixture the behavioural
    ``constraints`` of a design.json run in, on the mesh series ``meshes``: buckling first, then
    yield, per fixture in the order its first constraint comes. Constraints off the crease
    directions (a coupon cut along eta, whose value depends on where it is cut), in a frame,
    without an FE twin, or already a buckling bound, add no row. ``done``: the constraint rows
    of :func:`corrugate.fea.verify.verify_design` on the same meshes; a load capacity's row there
    already holds its fixture's buckling series over the safety factor, which is read back
    (times the factor) instead of running it again. A row whose load (else model first failure)
    is not yet shown at or below the FE's, nor shown above it
    (:func:`corrugate.fea.extrapolate.judge`), has its series extended by doubling its finest
    mesh up to ``max_mesh`` elements per facet (None: the finest of ``meshes``, no extension),
    as verify's constraint rows are; still open there, it is "not converged". ``executor`` and
    ``jobs``: the runs as tasks, in rounds, as :func:`corrugate.fea.verify.verify_design` runs
    them (the same rows)."""
    cap_mesh = max(meshes) if max_mesh is None else max_mesh
    connectors, bond = joint_options(joint)
    groups: dict[
        tuple[str, float, float | None], tuple[Twin, list[str], list[float], list[float]]
    ] = {}
    ran: dict[tuple[str, float, float | None], dict[int, float | None]] = {}
    rows_by_name = {r.name: r for r in done}
    for c, q in behavioural(constraints):
        load = _number(c.get("load_N"))
        model: float | None = None
        if q.kind == "Pmax":  # a load capacity: its load case's fixture (as a P / delta's)
            failure = c.get("failure_loads_N")
            found = [_number(v) for v in failure.values()] if isinstance(failure, dict) else []
            model = min((v for v in found if v is not None), default=None)
            sf = safety_factor(c)
            row = rows_by_name.get(str(c.get("name", q.key)))
            q = Quantity.load_case("k", q.eta or 0.0, q.test or own_test().name, **_support(q))
            cap = twin_of(q, assembly, joint, load)
            theirs = {} if row is None else row.fe_series
            # its requested meshes all ran (a failed extension past them is left out: the row
            # tries it again, where it fails as fast)
            complete = all(theirs.get(k) is not None for k in meshes)
            if sf and complete and isinstance(cap, Twin) and not cap.shifted:
                ran[(cap.test, cap.eta, cap.span)] = {
                    k: v * sf for k, v in theirs.items() if v is not None
                }
        twin = twin_of(q, assembly, joint, load)
        if isinstance(twin, str) or twin.read == "Pb" or twin.shifted:
            continue
        if twin.fixture.kind not in ("coupon", "outline"):
            continue
        key = (twin.test, twin.eta, twin.span)
        _, names, loads, models = groups.setdefault(key, (twin, [], [], []))
        names.append(str(c.get("name", q.key)))
        if load is not None:
            loads.append(load)
        if model is not None:
            models.append(model)
    parts = 3 if connectors else 2
    strengths = [assembly.layer1.material.yield_strength, assembly.layer2.material.yield_strength]
    strengths += [assembly.layer1.material.yield_strength] if connectors else []  # the band's
    setup = _Setup(assembly, connectors, bond, parts, strengths, folder, timeout)
    tasks: Tasks[_Task, tuple[float | None, str]] = Tasks(
        _task, _Task.line, _lost, progress, executor=executor, jobs=jobs
    )

    def runs(
        twin: Twin, mode: str, which: Sequence[int], name: str, why: str = ""
    ) -> list[Request[_Task]]:
        """The runs of ``twin`` in ``mode`` on the meshes ``which``, as a plan asks."""
        return [
            (
                (twin.test, twin.eta, twin.span, mode, along),
                _Task(setup, twin, mode, along, name, why),
            )
            for along in which
        ]

    def read(
        series: dict[int, float | None], failures: list[str], requests: list[Request[_Task]]
    ) -> None:
        """The loads of ``requests`` (run) into ``series``, their failures into ``failures``."""
        for key, item in requests:
            series[item.along], failure = tasks.results[key]
            if failure:
                failures.append(failure)

    def plan(
        twin: Twin, names: list[str], loads: list[float], models: list[float], mode: str
    ) -> Generator[list[Request[_Task]], None, FailureRow]:
        """The row of ``twin`` in ``mode``: its runs asked for in rounds
        (:class:`~corrugate.fea.tasks.Tasks`), each round's judged before the next."""
        where = f" along eta = {twin.eta:g} deg" + (
            f", span {twin.span:g} mm" if twin.span is not None else ""
        )
        buckle = LinearBuckling()
        label = buckle.describe(twin.fixture.label, twin.fixture.loading) + where
        static_label = twin.fixture.label + where
        load = max(loads) if loads else None
        series: dict[int, float | None] = {}
        failures: list[str] = []
        reused = ran.get((twin.test, twin.eta, twin.span)) if mode == "buckling" else None

        name = label if mode == "buckling" else f"{static_label}, stresses"
        if reused is not None:
            series = dict(reused)
        else:
            asked = runs(twin, mode, meshes, name)
            yield asked
            read(series, failures, asked)
        model = min(models) if models else None
        bound = load if load is not None else model
        extended: list[str] = []
        while bound is not None:  # refine an open series, as verify's constraint rows
            j = _judged(series, bound)
            finer = 2 * max(series)
            failed = any(v is None for v in series.values())
            if j.verdict != "open" or finer > cap_mesh or failed:
                break
            asked = runs(twin, mode, (finer,), name, f"extending the series: {j.why}")
            yield asked
            read(series, failures, asked)
            extended.append(f"extended to {finer} per facet ({j.why})")
        known = {k: v for k, v in series.items() if v is not None}
        verdict = _verdict(series, load)
        model_verdict = _verdict(series, model)
        decisive = _judged(series, bound) if bound is not None else None
        if decisive is not None:
            fe, order, how = decisive.value, decisive.order, decisive.how
        else:
            e = extrapolate(known, "min")
            fe, order, how = e.value, e.order, e.how
        note = list(failures)
        if mode == "yield" and not known and not failures:
            note.append("no yield strength for the sheet's material")
        if mode == "buckling":
            note.insert(0, "a dead load (the load line free to move in the mode)")
        else:
            note.insert(0, "largest |principal stress| anywhere, the load lines included")
        note += extended
        if decisive is not None and decisive.verdict == "open" and known:
            note.append(
                f"not converged at {max(series)} per facet (the finest allowed is "
                f"{cap_mesh}): {decisive.why}"
            )
        return FailureRow(
            label if mode == "buckling" else static_label,
            mode,
            tuple(names),
            load,
            series,
            fe,
            order,
            how,
            "; ".join(note),
            model,
            verdict,
            model_verdict,
        )

    plans = [
        plan(twin, names, loads, models, mode)
        for twin, names, loads, models in groups.values()
        for mode in MODES
        if not (mode == "yield" and twin.fixture.kind == "outline")
    ]
    return tuple(tasks.drive(plans))


@dataclass(frozen=True, slots=True)
class _Setup:
    """What every run of :func:`first_failures` shares: the design, its band, its parts' yield
    strengths and where and how long ccx runs."""

    assembly: Assembly
    connectors: bool
    bond: Any
    parts: int
    strengths: list[float | None]
    folder: Path | None
    timeout: float


def _run(setup: _Setup, twin: Twin, mode: str, along: int) -> tuple[float | None, str]:
    """One run of a first-failure row on ``along`` elements per facet: its load (N; None when
    the run failed or gave none) and the failure's words ("" when it ran)."""
    mesh = AssemblyMesh(along)
    buckle = LinearBuckling()
    try:
        if mode == "buckling" and twin.fixture.kind == "outline":
            o = solve_outline(
                setup.assembly,
                twin.test,
                mesh,
                twin.eta,
                step=buckle,
                folder=setup.folder,
                timeout=setup.timeout,
            )
            return o.value, ""
        how: dict[str, Any] = {"step": buckle} if mode == "buckling" else {"stresses": True}
        r = solve_assembly(
            setup.assembly,
            twin.test,
            mesh,
            twin.eta,
            connectors=setup.connectors,
            bond=setup.bond,
            span=twin.span,
            folder=setup.folder,
            timeout=setup.timeout,
            **how,
        )
        if mode == "buckling":
            return r.value(), ""
        return yield_load(r.force, _peak_by_part(r, setup.parts), setup.strengths), ""
    except CorrugateError as exc:
        return None, f"{along}/facet not run: {exc}"


@dataclass(frozen=True, slots=True)
class _Task:
    """One run of a first-failure row (a task shipped to a worker whole, pickled): ``twin``'s
    fixture in ``mode`` on ``along`` elements per facet; ``name`` and ``why`` are said on its
    progress line."""

    setup: _Setup
    twin: Twin
    mode: str
    along: int
    name: str
    why: str = ""

    def line(self) -> str:
        """The run in words, as its progress line says it."""
        because = f", {self.why}" if self.why else ""
        mesh = AssemblyMesh(self.along).label()
        return f"assembly, {self.name}, mesh {mesh} (first failure{because})"


def _task(t: _Task) -> tuple[float | None, str]:
    """:func:`_run` of ``t`` (a task of :class:`~corrugate.fea.tasks.Tasks`)."""
    return _run(t.setup, t.twin, t.mode, t.along)


def _lost(t: _Task, exc: Exception) -> tuple[float | None, str]:
    """The result of a run lost with its worker (killed, out of memory): no load, and why."""
    return None, f"{t.along}/facet not run: {worker_failure(exc)}"


def _judged(series: Mapping[int, float | None], bound: float) -> Judgement:
    """:func:`corrugate.fea.extrapolate.judge` of the runs that gave a value: is the first
    failure (N) at or above ``bound`` (N)?"""
    return judge({k: v for k, v in series.items() if v is not None}, bound, "min")


def _verdict(series: Mapping[int, float | None], bound: float | None) -> str | None:
    """The words of :func:`_judged` (:data:`VERDICT_WORDS`): "not converged" also when a run of
    the series failed; None without a bound or without any value."""
    if bound is None or not any(v is not None for v in series.values()):
        return None
    j = _judged(series, bound)
    if j.verdict != "fails" and any(v is None for v in series.values()):
        return "not converged"
    return VERDICT_WORDS[j.verdict]


def _number(v: object) -> float | None:
    """``v`` as a float when it is a number (not a bool), else None."""
    return float(v) if isinstance(v, int | float) and not isinstance(v, bool) else None


def _support(q: Quantity) -> dict[str, Any]:
    """The support and span of a load capacity's quantity, as :meth:`Quantity.load_case` takes
    them."""
    out: dict[str, Any] = {"span": q.span}
    if q.support is not None:
        out["support"] = q.support
    return out
