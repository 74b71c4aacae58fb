"""FE versus closed forms for one design: the cases ``corrugate validate`` runs.

A :class:`Case` is one design (two layers, identical or not, on a square or a rectangle) with
the FE settings; :func:`run_case` runs the periodic unit cell of each distinct layer
(:mod:`~corrugate.fea.unitcell`) and the assembly in the fixtures of :mod:`corrugate.fea.fixtures`
(``platens``, ``three-point``; ``four-point`` and a linear buckling run of ``platens`` on request;
the fixture of every support condition that has its own, e.g. ``frame``) at each eta, optionally refining the meshes until every result is shown within a tolerance of
its FE limit (:func:`settled`, the rule of :func:`corrugate.fea.extrapolate.judge`), and puts the closed forms of every model variant beside them
(:func:`corrugate.analysis.evaluate.analyze`, never reimplemented here).

Failures (solver errors, time-outs) are caught and reported in :attr:`CaseResult.error`, so a
sweep goes on with the other cases.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Protocol, TypeVar

from corrugate.analysis.evaluate import analyze
from corrugate.core.errors import CorrugateError
from corrugate.fea.assembly import (
    AssemblyMesh,
    AssemblyResult,
    Bond,
    principal_axis,
    solve_assembly,
)
from corrugate.fea.extrapolate import Judgement, judge
from corrugate.fea.fixtures import get_fixture
from corrugate.fea.frame import solve_frame
from corrugate.fea.steps import STATIC, LinearBuckling, Step
from corrugate.fea.unitcell import UnitCell, UnitCellMesh, solve_unit_cell
from corrugate.geometry.layer import Assembly
from corrugate.mechanics.behaviours import DEFAULT_SUPPORT, Behaviour, get_support, supports
from corrugate.mechanics.moduli import MODELS


class _Mesh(Protocol):
    @property
    def along(self) -> int: ...

    def label(self) -> str: ...


M = TypeVar("M", bound=_Mesh)

__all__ = [
    "REFINE_START",
    "Case",
    "CaseResult",
    "Refinement",
    "closed_forms",
    "fixture_key",
    "fixture_supports",
    "run_case",
    "settled",
]

#: Quantities of a case, with their units: assembly stiffness and layer-1 moduli.
STIFFNESS_KEYS = ("K_N_per_mm", "D_Nmm", "EI_Nmm2")
MODULI_KEYS = ("Ecx", "Ecy", "Ebx", "Eby")


@dataclass(frozen=True, slots=True)
class Refinement:
    """Mesh refinement: start meshes, the tolerance ``tol`` (relative: how close to its FE limit
    each finest value must be shown, :func:`settled`) and the finest meshes allowed.

    ``tol`` None means one run at the start meshes. Each step doubles the elements along a facet
    (and through the thickness of the unit cell, up to ``cell_max_through``).
    """

    assembly_mesh: AssemblyMesh = field(default_factory=AssemblyMesh)
    cell_mesh: UnitCellMesh = field(default_factory=UnitCellMesh)
    tol: float | None = None
    assembly_max_along: int = 16
    cell_max_along: int = 320
    cell_max_through: int = 16


#: Where ``validate --refine`` starts unless told (one doubling below the defaults): its rule
#: (:func:`settled`) needs four meshes each twice the one before, and the finest allowed are 16 per
#: facet and 320 along the unit cell.
REFINE_START = Refinement(AssemblyMesh(2), UnitCellMesh(40, 4))


@dataclass(frozen=True, slots=True)
class Case:
    """One design to validate: ``label``, the ``assembly``, the directions ``eta_deg`` (0 and 90:
    the layout itself; any other angle: a square coupon cut along eta, see
    :func:`corrugate.fea.assembly.specimen`), whether to run the unit cells and the 4-point (pure) bending diagnostic, whether the
    assembly model includes the connector band (``connectors``), whether to compute the first
    buckling load in compression (``buckling``), how the band holds the layers (``bond``: along
    their whole edges, or only where they rest on its glue flanges), and where ccx works
    (``folder``, kept if ``keep``)."""

    label: str
    assembly: Assembly
    eta_deg: tuple[float, ...] = (0.0,)
    unit_cell: bool = True
    pure_bending: bool = True
    refinement: Refinement = field(default_factory=Refinement)
    folder: Path | None = None
    keep: bool = False
    timeout: float = 900.0
    group: str = ""
    parameter: str = ""
    value: float = 0.0
    connectors: bool = False
    buckling: bool = False
    bond: Bond = "edges"
    support: str = DEFAULT_SUPPORT


@dataclass(frozen=True, slots=True)
class CaseResult:
    """FE and closed-form values of a case.

    ``fe`` and ``models[name]`` map ``"K_N_per_mm@eta"``, ``"D_Nmm@eta"``, ``"EI_Nmm2@eta"`` (from
    3-point bending, as the paper tested; EI along the layout's axes only), ``"Kframe_N_per_mm@eta"``
    (the panel in a rigid frame, :mod:`~corrugate.fea.frame`; in ``fe`` only when an off-axis eta
    is asked for), ``"Pcr_N@eta"`` (first buckling load in compression, N; ``fe`` only, with
    ``buckling`` and eta 0 or 90; the bounds are :func:`corrugate.analysis.evaluate.facet_buckling_load`), ``"D4_Nmm@eta"`` (pure bending between the load lines
    of a 4-point test; the closed forms' D for the models) and the layer moduli
    ``"layer1.Ecx"`` ... (MPa) to numbers. ``meshes`` says which meshes produced ``fe``;
    ``history`` lists (mesh label, values) of every refinement step. ``converged`` is True only
    after a refinement study (``refinement.tol`` set) that showed every value's finest within
    the tolerance of its FE limit (:func:`settled`): False for a single mesh (then ``refined``
    is False too: nothing was checked) and when refinement stopped at the finest mesh allowed
    before showing it. ``error`` holds
    the one-line message of a failed case (then ``fe`` is empty).
    """

    case: Case
    fe: dict[str, float]
    models: dict[str, dict[str, float]]
    meshes: dict[str, str]
    history: tuple[tuple[str, dict[str, float]], ...] = ()
    converged: bool = False
    error: str | None = None

    @property
    def refined(self) -> bool:
        """Whether a mesh refinement study ran (``--refine``); without one ``converged`` is
        False, since a single mesh says nothing about convergence."""
        return self.case.refinement.tol is not None

    def ratio(self, key: str, model: str) -> float:
        """Closed form of ``model`` divided by FE for ``key``."""
        return self.models[model][key] / self.fe[key]


def fixture_supports() -> tuple[Behaviour, ...]:
    """The registered support conditions that have an FE fixture of their own (their entry's
    ``fixture`` is not the default support's, the free coupon between platens that every case
    runs), e.g. ``frame`` (:mod:`corrugate.mechanics.behaviours`)."""
    free = get_support(DEFAULT_SUPPORT).fixture
    return tuple(b for b in supports() if b.fixture != free)


def fixture_key(support: Behaviour) -> str:
    """The key of K (N/mm) under ``support`` in :class:`CaseResult`, e.g. ``Kframe_N_per_mm``."""
    return f"K{support.suffix}_N_per_mm"


def closed_forms(
    assembly: Assembly, eta_deg: Sequence[float], support: str = DEFAULT_SUPPORT
) -> dict[str, dict[str, float]]:
    """The closed forms of every model variant in the keys of :class:`CaseResult`: K and D under
    ``support`` (the FE coupon has free sides), and K under each support condition with a
    fixture of its own (:func:`fixture_supports`: ``Kframe`` is always the rule, beside the
    frame FE)."""
    out: dict[str, dict[str, float]] = {}
    for name in MODELS:
        r = analyze(assembly, name, list(eta_deg), support=support)
        fixed = [
            (fixture_key(b), analyze(assembly, name, list(eta_deg), support=b.name).stiffness)
            for b in fixture_supports()
        ]
        values: dict[str, float] = {}
        for i, d in enumerate(r.stiffness):
            e = f"{d.eta_deg:g}"
            values[f"K_N_per_mm@{e}"] = d.K
            for key, st in fixed:  # e.g. the rule is the frame's stiffness
                values[f"{key}@{e}"] = st[i].K
            values[f"D_Nmm@{e}"] = d.D
            if principal_axis(d.eta_deg) is not None:  # off-axis the FE coupon has its own span
                values[f"EI_Nmm2@{e}"] = d.EI
            values[f"D4_Nmm@{e}"] = d.D  # the closed forms' D is a pure bending stiffness
        for i, m in enumerate(r.moduli, start=1):
            for k, v in m.as_dict().items():
                values[f"layer{i}.{k}"] = v
        out[name] = values
    return out


def _support_run(case: Case, mesh: AssemblyMesh, name: str) -> Callable[[float], float]:
    """K(eta) (N/mm) in the fixture ``name`` of a support condition: the frame's two runs
    combined (:func:`corrugate.fea.frame.solve_frame`), or one run of a coupon fixture at each
    eta."""
    fixture = get_fixture(name, ("coupon", "frame"))
    a, folder, keep, timeout = case.assembly, case.folder, case.keep, case.timeout
    if fixture.kind == "frame":
        return solve_frame(a, mesh, fixture=fixture, folder=folder, keep=keep, timeout=timeout).K

    def K(eta: float) -> float:
        r = solve_assembly(a, fixture, mesh, eta, folder=folder, keep=keep, timeout=timeout)
        assert r.K is not None
        return r.K

    return K


def _layers_to_run(a: Assembly) -> list[int]:
    return [1] if a.layer1 == a.layer2 else [1, 2]


#: Called with one line before each CalculiX run of :func:`run_case` (progress of a long case).
Progress = Callable[[str], None]


def _quiet(_: str) -> None:
    """The default :data:`Progress`: says nothing."""


def _cell_values(case: Case, mesh: UnitCellMesh, progress: Progress = _quiet) -> dict[str, float]:
    out: dict[str, float] = {}
    a = case.assembly
    for i in _layers_to_run(a):
        progress(f"unit cell of layer {i}, mesh {mesh.label()}")
        layer = a.layers[i - 1]
        m = layer.material
        cell = UnitCell(m.E, m.nu, layer.t, layer.W, layer.alpha_deg)
        r = solve_unit_cell(cell, mesh, folder=case.folder, keep=case.keep, timeout=case.timeout)
        for k, v in r.as_dict().items():
            out[f"layer{i}.{k}"] = v
            if a.layer1 == a.layer2:
                out[f"layer2.{k}"] = v
    return out


def _assembly_values(
    case: Case, mesh: AssemblyMesh, progress: Progress = _quiet
) -> dict[str, float]:
    out: dict[str, float] = {}
    if any(principal_axis(e) is None for e in case.eta_deg):  # e.g. the cos^2 rule's own fixture
        runs: dict[str, Callable[[float], float]] = {}
        for sup in fixture_supports():
            if sup.fixture not in runs:
                progress(f"{get_fixture(sup.fixture).label}, mesh {mesh.label()}")
                runs[sup.fixture] = _support_run(case, mesh, sup.fixture)
            for eta in case.eta_deg:
                out[f"{fixture_key(sup)}@{eta:g}"] = runs[sup.fixture](eta)

    def run(name: str, eta: float, step: Step = STATIC) -> AssemblyResult:
        fixture = get_fixture(name)
        what = step.describe(fixture.label, fixture.loading)
        progress(f"assembly, {what} along eta = {eta:g} deg, mesh {mesh.label()}")
        return solve_assembly(
            case.assembly,
            fixture,
            mesh,
            eta,
            step=step,
            connectors=case.connectors,
            bond=case.bond,
            folder=case.folder,
            keep=case.keep,
            timeout=case.timeout,
        )

    for eta in case.eta_deg:
        e = f"{eta:g}"
        principal = principal_axis(eta) is not None
        out[f"K_N_per_mm@{e}"] = run("platens", eta).value()
        b = run("three-point", eta)
        out[f"D_Nmm@{e}"] = b.value()
        if principal:
            out[f"EI_Nmm2@{e}"] = b.value() * b.span
        if case.buckling and principal:
            out[f"Pcr_N@{e}"] = run("platens", eta, LinearBuckling()).value()
        if case.pure_bending:
            out[f"D4_Nmm@{e}"] = run("four-point", eta).value()
    return out


def settled(series: Mapping[int, float], tol: float) -> Judgement:
    """Whether the finest value of a mesh series (elements per facet -> value, each mesh twice
    the one before) is within ``tol`` (relative) of the series' FE limit, by
    :func:`corrugate.fea.extrapolate.judge`'s rule (docs/fea.md 6): the limit shown at or above
    finest x (1 - tol) and at or below finest x (1 + tol), each on a series shown asymptotic (two
    successive Richardson extrapolations, four meshes, at the observed order: no order p >= 1 is
    assumed) or whose last two steps vanish. The judgement of the side that is not ``holds`` (the
    first's when both hold): ``holds`` settled, ``fails`` the limit lies outside (refine
    further), ``open`` not shown yet."""
    finest = series[max(series)]
    lo, hi = sorted((finest * (1 - tol), finest * (1 + tol)))
    below, above = judge(series, lo, "min"), judge(series, hi, "max")
    return below if below.verdict != "holds" or above.verdict == "holds" else above


def _settled(runs: Sequence[tuple[int, dict[str, float]]], tol: float) -> bool:
    """Whether every value of the last run is :func:`settled` on the runs' mesh series."""
    last = runs[-1][1]
    return all(
        settled({along: v[k] for along, v in runs if k in v}, tol).verdict == "holds" for k in last
    )


def _refine(
    name: str,
    mesh: M,
    finer: Callable[[M], M],
    too_fine: Callable[[M], bool],
    values: Callable[[M], dict[str, float]],
    tol: float | None,
    history: list[tuple[str, dict[str, float]]],
) -> tuple[dict[str, float], M, bool]:
    """Solve on ``mesh`` and, when ``tol`` is set, on ever finer meshes until every value's
    finest is shown within ``tol`` (relative) of its FE limit (:func:`settled`: the rule of
    :func:`corrugate.fea.extrapolate.judge`, four meshes each twice the one before, at the
    series' observed order); every mesh's values go to ``history``.

    Returns the last values, their mesh, and whether they were shown settled: False when the
    next mesh would have been too fine, and False without ``tol`` (one mesh: nothing checked).
    """
    prev = values(mesh)
    history.append((f"{name} {mesh.label()}", prev))
    runs = [(mesh.along, prev)]
    while tol is not None:
        if _settled(runs, tol):
            break
        nxt_mesh = finer(mesh)
        if too_fine(nxt_mesh):
            return prev, mesh, False
        prev = values(nxt_mesh)
        mesh = nxt_mesh
        history.append((f"{name} {mesh.label()}", prev))
        runs.append((mesh.along, prev))
    return prev, mesh, tol is not None


def run_case(case: Case, progress: Progress = _quiet) -> CaseResult:
    """Run the FE of ``case`` (refining if asked) beside the closed forms; never raises on a
    solver failure of the case: the message goes to :attr:`CaseResult.error`. ``progress`` is
    called with one line before each CalculiX run."""
    ref = case.refinement
    models = closed_forms(case.assembly, case.eta_deg, case.support)
    history: list[tuple[str, dict[str, float]]] = []
    meshes: dict[str, str] = {}
    fe: dict[str, float] = {}
    converged = ref.tol is not None  # a single mesh is never "converged"
    try:
        values, am, ok = _refine(
            "assembly",
            ref.assembly_mesh,
            lambda m: m.refined(),
            lambda m: m.along > ref.assembly_max_along,
            lambda m: _assembly_values(case, m, progress),
            ref.tol,
            history,
        )
        fe.update(values)
        meshes["assembly"] = am.label()
        converged = converged and ok
        if case.unit_cell:
            values, cm, ok = _refine(
                "unit cell",
                ref.cell_mesh,
                lambda m: replace(
                    m,
                    along=m.along * 2,
                    through=min(m.through * 2, max(m.through, ref.cell_max_through)),
                ),
                lambda m: m.along > ref.cell_max_along,
                lambda m: _cell_values(case, m, progress),
                ref.tol,
                history,
            )
            fe.update(values)
            meshes["unit cell"] = cm.label()
            converged = converged and ok
    except CorrugateError as exc:
        return CaseResult(case, {}, models, meshes, tuple(history), False, str(exc))
    return CaseResult(case, fe, models, meshes, tuple(history), converged)
