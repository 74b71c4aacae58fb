"""A geometrically nonlinear ramp of a load-case fixture, its first buckling mode as the
imperfection: the load-deflection curve and where the stiffness falls (issue 34 item 4,
``corrugate verify --nonlinear``; docs/fea.md section 6, docs/validation/capacity.md).

What :func:`ramp` runs, on one shell mesh of the assembly (:mod:`corrugate.fea.assembly`):

1. **the buckling step** of the fixture (:class:`corrugate.fea.steps.LinearBuckling`, a dead
   load), with every shell node's displacement printed to the ``.dat`` file: its first factor is
   the linear buckling load P_cr (N), its base state (the static solution under the 1 N reference
   load, printed before the factors) the load point's compliance, so the initial stiffness k0
   (N/mm) of the linear static run of the same deck, and its first mode the shape of the
   imperfection, read at the shell's own nodes;
2. **the imperfection**: the mode scaled so that its largest nodal displacement is
   ``amplitude`` (mm), added to the node coordinates of the same deck (CalculiX's own imperfection
   input is not used). The default amplitude is W / 200, W the flat width of a facet of the layer
   where the mode is largest (the band counts as layer 1): the equivalent geometric imperfection
   of a plate panel that buckles locally, b / 200 of its width b, of EN 1993-1-5:2006 Annex C
   (Table C.2); a facet is such a plate between its creases;
3. **the ramp** (:class:`corrugate.fea.steps.Nonlinear`, ``NLGEOM``): the load line tied to the
   reference node and that node loaded by a dead load ramped from 0 to ``target`` (N), by
   default 1.5 x the larger of P_cr and the model's first-failure load (issue 34: "to about 1.5
   times the predicted failure load"), in increments of 1/20 of it. Where ccx cannot converge an
   increment even cut to its minimum (1e-3 of the ramp), the curve ends at the last converged
   load (``ended`` = ``"not converged"``): a limit point of the dead load, or a numerical end, not
   a crash; a ramp that runs out of its time-out ends there too (``"timed out"``).

The curve is the load P (N) against the load point's travel delta (mm, along the load), and the
mode's amplitude w (mm): the displacement of the mode's largest node projected on the mode's
direction there, less that of the linear response (P times the base state's): how much the
imperfection grew beyond what the linear run predicts. :func:`knee` finds the first increment whose
tangent stiffness dP / d delta falls below ``fraction`` (0.5) of the initial one (the first
increment's); its load (the load at the start of that increment) is the FE's first failure this
curve shows. :func:`peak` is the largest load when the curve comes down after it, or the last load
of a ramp that stopped converging after its stiffness fell (a limit load). A local facet mode can
leave the panel's stiffness almost whole (the other facets carry the load): then the ramp reaches
its target without a knee, and w shows the facet's deflection instead (docs/validation/capacity.md,
"nonlinear ramp").
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from corrugate.core.errors import CorrugateError, InputError
from corrugate.fea.assembly import AssemblyMesh, assembly_deck
from corrugate.fea.ccx import SolverError, parse_dat, run_ccx, work_dir
from corrugate.fea.connector_band import Bond
from corrugate.fea.deck import node_set
from corrugate.fea.fixtures import get_fixture
from corrugate.fea.steps import LinearBuckling, Nonlinear
from corrugate.geometry.layer import Assembly

__all__ = [
    "AMPLITUDE_RULE",
    "KNEE_FRACTION",
    "TARGET_FACTOR",
    "NonlinearCase",
    "NonlinearResult",
    "knee",
    "nonlinear_case",
    "peak",
    "perturb",
    "ramp",
    "run_for_design",
]

#: The tangent stiffness, as a fraction of the initial one, below which the stiffness has fallen.
KNEE_FRACTION = 0.5
#: The ramp's end over the predicted failure load.
TARGET_FACTOR = 1.5
#: How the default imperfection amplitude is chosen (module docstring).
AMPLITUDE_RULE = "W / 200 of the facet where the mode is largest (EN 1993-1-5 Annex C, b / 200)"
#: Words of ccx's log when it gives up an increment (the curve then ends, module docstring).
_STALLED = ("increment size smaller", "too many cutbacks")
#: The increment of the ramp (a fraction of it; ccx cuts it where one does not converge).
INCREMENT = 0.05


def knee(
    loads: Sequence[float], travels: Sequence[float], fraction: float = KNEE_FRACTION
) -> int | None:
    """The index of the point where the stiffness falls: the start of the first segment of the
    curve (the origin, then ``loads`` N against ``travels`` mm) whose tangent dP / d delta is
    below ``fraction`` x the first segment's (a segment whose travel does not grow counts as
    fallen); None when none is. Index 0 is the origin, k the k-th point."""
    P = [0.0, *map(float, loads)]
    d = [0.0, *map(float, travels)]
    if len(P) < 3 or d[1] <= 0:
        return None
    k0 = P[1] / d[1]
    for i in range(2, len(P)):
        dd = d[i] - d[i - 1]
        if dd <= 0 or (P[i] - P[i - 1]) / dd < fraction * k0:
            return i - 1
    return None


def peak(loads: Sequence[float], limit: bool = False) -> int | None:
    """The index (0-based, in ``loads``) of the peak load: the largest load when a later point is
    lower, or with ``limit`` (the ramp stopped converging after its stiffness fell) the last
    point; None otherwise."""
    if not loads:
        return None
    i = int(np.argmax(loads))
    if i < len(loads) - 1 and min(loads[i + 1 :]) < loads[i]:
        return i
    return len(loads) - 1 if limit else None


@dataclass(frozen=True, slots=True)
class NonlinearCase:
    """The fixture a nonlinear ramp runs in: ``test`` (a coupon fixture), ``eta`` (deg),
    ``span`` (mm; None: the panel's length), the ``constraints`` of the design run in it and the
    model's first-failure load ``model`` (N, no safety factor; None without a load capacity) with
    its ``safety_factor``."""

    test: str
    eta: float
    span: float | None
    constraints: tuple[str, ...]
    model: float | None = None
    safety_factor: float | None = None


@dataclass(frozen=True, slots=True)
class NonlinearResult:
    """One ramp (module docstring): the fixture ``case``, the ``mesh``, the linear buckling load
    ``buckling_load`` (N, dead), the initial stiffness ``k0`` (N/mm, the linear static run's),
    the imperfection ``amplitude`` (mm) and where the mode is largest (``mode_at``), the ramp's
    ``target`` (N), the curve (``loads`` N, ``travels`` mm, ``mode_amplitudes`` mm), how it
    ``ended`` (``"target"``, ``"not converged"`` or ``"timed out"``), the knee's tangent
    ``fraction`` and the ccx wall time ``seconds`` of the two runs."""

    case: NonlinearCase
    mesh: AssemblyMesh
    buckling_load: float
    k0: float
    amplitude: float
    mode_at: str
    target: float
    loads: tuple[float, ...]
    travels: tuple[float, ...]
    mode_amplitudes: tuple[float, ...]
    ended: str
    fraction: float = KNEE_FRACTION
    seconds: float = math.nan
    note: str = ""

    @property
    def knee_load(self) -> float | None:
        """The load (N) where the stiffness falls (:func:`knee`), None if it does not."""
        i = knee(self.loads, self.travels, self.fraction)
        return None if i is None else ([0.0, *self.loads])[i]

    @property
    def peak_load(self) -> float | None:
        """The peak load (N, :func:`peak`), None if the curve shows none."""
        limit = self.ended == "not converged" and self.knee_load is not None
        i = peak(self.loads, limit)
        return None if i is None else self.loads[i]

    @property
    def end_load(self) -> float:
        """The last load the ramp converged at (N)."""
        return self.loads[-1] if self.loads else 0.0

    @property
    def compared_with(self) -> str:
        """What the model's first failure is compared with: the knee, or the end of the ramp
        when the stiffness did not fall."""
        return "knee" if self.knee_load is not None else "end of the ramp (no knee)"

    @property
    def model_holds(self) -> bool | None:
        """Whether the model's first-failure load is at or below the FE's: the knee, or, without
        one, the end of the ramp (the FE held at least that); None without a model value, or
        when it lies above a ramp that showed no knee."""
        m = self.case.model
        if m is None:
            return None
        k = self.knee_load
        if k is not None:
            return m <= k
        return True if m <= self.end_load else None

    def as_json(self) -> dict[str, Any]:
        """The ``nonlinear`` block of verify.json (N, mm)."""
        c = self.case
        return {
            "test": c.test,
            "eta_deg": c.eta,
            "span_mm": c.span,
            "constraints": list(c.constraints),
            "mesh": self.mesh.label(),
            "imperfection_mm": self.amplitude,
            "imperfection_rule": AMPLITUDE_RULE,
            "mode_at": self.mode_at,
            "buckling_load_N": self.buckling_load,
            "initial_stiffness_N_per_mm": self.k0,
            "target_N": self.target,
            "curve": [
                {"load_N": p, "displacement_mm": d, "mode_mm": w}
                for p, d, w in zip(self.loads, self.travels, self.mode_amplitudes, strict=True)
            ],
            "ended": self.ended,
            "end_load_N": self.end_load,
            "knee_fraction": self.fraction,
            "knee_N": self.knee_load,
            "peak_N": self.peak_load,
            "model_first_failure_N": c.model,
            "safety_factor": c.safety_factor,
            "compared_with": self.compared_with,
            "model_holds": self.model_holds,
            "wall_s": round(self.seconds, 1) if math.isfinite(self.seconds) else None,
            "note": self.note or None,
        }

    @property
    def sentence(self) -> str:
        """The ramp in words."""
        k = self.knee_load
        p = self.peak_load
        fell = (
            f"stiffness below {self.fraction:.0%} of the initial at {k:.4g} N"
            if k is not None
            else f"no knee up to {self.end_load:.4g} N"
        )
        pk = f", peak {p:.4g} N" if p is not None else ""
        end = {"target": "reached", "timed out": "timed out"}.get(self.ended, "stopped converging")
        return (
            f"{get_fixture(self.case.test).loading}, {self.mesh.label()}: {fell}{pk}; "
            f"linear buckling {self.buckling_load:.4g} N; ramp to {self.target:.4g} N {end}; "
            f"imperfection {self.amplitude:.3g} mm"
        )


def nonlinear_case(
    assembly: Assembly, constraints: Sequence[Mapping[str, Any]], joint: str = "none"
) -> NonlinearCase | None:
    """The fixture a design.json's nonlinear ramp runs in: that of its first load capacity (a
    ``Pmax`` constraint: what the certified capacity rests on), else of its first behavioural
    constraint, among those with a coupon twin along a crease direction (as
    :func:`corrugate.fea.first_failure.first_failures` groups them); the constraints run in it
    and the model's least first-failure load among its load capacities; None when no constraint
    has such a twin."""
    from corrugate.fea.verify import behavioural, safety_factor, twin_of
    from corrugate.mechanics.behaviours import own_test
    from corrugate.solver.quantity import Quantity

    twins: list[tuple[tuple[str, float, float | None], str, float | None, float | None]] = []
    capacities: list[tuple[str, float, float | None]] = []
    for c, q in behavioural(constraints):
        load = _number(c.get("load_N"))
        model: float | None = None
        if q.kind == "Pmax":  # a load capacity: its load case's fixture
            failure = c.get("failure_loads_N")
            found = [_number(v) for v in failure.values()] if isinstance(failure, dict) else []
            model = min((v for v in found if v is not None), default=None)
            extra: dict[str, Any] = {"span": q.span}
            if q.support is not None:
                extra["support"] = q.support
            q = Quantity.load_case("k", q.eta or 0.0, q.test or own_test().name, **extra)
        twin = twin_of(q, assembly, joint, load)
        if isinstance(twin, str) or twin.read == "Pb" or twin.shifted:
            continue
        if twin.fixture.kind != "coupon":
            continue
        key = (twin.test, twin.eta, twin.span)
        twins.append((key, str(c.get("name", q.key)), model, safety_factor(c)))
        if model is not None:
            capacities.append(key)
    # the first load capacity's fixture (what the certificate rests on), else the first one's
    chosen = capacities[0] if capacities else (twins[0][0] if twins else None)
    names = [name for key, name, _, _ in twins if key == chosen]
    models = [(m, sf) for key, _, m, sf in twins if key == chosen and m is not None]
    if chosen is None:
        return None
    least = min(models, default=None)
    return NonlinearCase(
        chosen[0],
        chosen[1],
        chosen[2],
        tuple(names),
        None if least is None else least[0],
        None if least is None else least[1],
    )


def _number(v: object) -> float | None:
    return float(v) if isinstance(v, int | float) and not isinstance(v, bool) else None


def _node_block(deck: str) -> tuple[int, int]:
    """The line range [start, end) of the mesh's node lines (the first ``*NODE`` card's)."""
    lines = deck.split("\n")
    start = lines.index("*NODE") + 1
    end = start
    while end < len(lines) and not lines[end].startswith("*"):
        end += 1
    return start, end


def _parts_of(deck: str) -> dict[int, int]:
    """Each shell node's part (1, 2, 3: the ``ELSET=Lk`` of the first element that uses it)."""
    part: dict[int, int] = {}
    k = 0
    for ln in deck.split("\n"):
        if ln.startswith("*"):
            k = 0
            if ln.startswith("*ELEMENT") and "ELSET=L" in ln:
                k = int(ln.rsplit("ELSET=L", 1)[1].split(",")[0])
            continue
        if k:
            for n in ln.split(",")[1:]:
                part.setdefault(int(n), k)
    return part


def perturb(deck: str, shape: Mapping[int, NDArray[np.float64]], scale: float) -> str:
    """``deck`` with every node of its mesh (the first ``*NODE`` card) moved by ``scale`` x its
    ``shape`` vector (mm; nodes without one stay)."""
    lines = deck.split("\n")
    start, end = _node_block(deck)
    for i in range(start, end):
        cells = lines[i].split(",")
        u = shape.get(int(cells[0]))
        if u is None:
            continue
        x = [float(c) + scale * float(v) for c, v in zip(cells[1:4], u, strict=True)]
        lines[i] = f"{cells[0]},{x[0]:.10g},{x[1]:.10g},{x[2]:.10g}"
    return "\n".join(lines)


def _reference(deck: str) -> tuple[int, int, float]:
    """The reference node of a deck with a tied load (its number), the driven degree of freedom
    and the load's sign (-1: along -axis)."""
    lines = deck.split("\n")
    i = lines.index("*CLOAD")
    node, dof, value = lines[i + 1].split(",")
    return int(node), int(dof), math.copysign(1.0, float(value))


def ramp(
    assembly: Assembly,
    case: NonlinearCase,
    mesh: AssemblyMesh,
    *,
    connectors: bool = False,
    bond: Bond = "edges",
    amplitude: float | None = None,
    target: float | None = None,
    increment: float = INCREMENT,
    fraction: float = KNEE_FRACTION,
    folder: Path | None = None,
    timeout: float = 900.0,
    progress: Callable[[str], None] = lambda line: None,
) -> NonlinearResult:
    """The nonlinear ramp of ``case``'s fixture on ``mesh`` (module docstring): ``amplitude``
    (mm; None: W / 200), ``target`` (N; None: 1.5 x the larger of the linear buckling load and
    the model's first failure), ``increment`` (a fraction of the ramp), ``fraction`` (the knee's
    tangent over the initial). Raises :class:`~corrugate.fea.ccx.SolverError` when the buckling
    run fails or the ramp converges at no increment."""
    if amplitude is not None and not (math.isfinite(amplitude) and amplitude > 0):
        raise InputError("amplitude", amplitude, "a positive length (mm)")
    if not 0 < increment <= 1:
        raise InputError("increment", increment, "0 < increment <= 1 (a fraction of the ramp)")
    args: dict[str, Any] = {"connectors": connectors, "bond": bond, "span": case.span}
    buckle, _ = assembly_deck(assembly, case.test, mesh, case.eta, step=LinearBuckling(), **args)
    lines = buckle.split("\n")
    start, end = _node_block(buckle)
    shell_nodes = [int(ln.split(",", 1)[0]) for ln in lines[start:end]]
    ref, dof, sign = _reference(buckle)
    printed = node_set("NLMODE", [*shell_nodes, ref])
    head, sep, tail = buckle.rpartition("*STEP")
    buckle = head + "\n".join(printed) + "\n" + sep + tail
    buckle = buckle.replace("*END STEP", "*NODE PRINT,NSET=NLMODE\nU\n*END STEP")
    label = f"{get_fixture(case.test).loading} along eta = {case.eta:g} deg"
    progress(f"assembly, buckling in {label}, mesh {mesh.label()} (nonlinear ramp's mode)")
    t0 = time.perf_counter()
    with work_dir(folder) as wd:
        run = run_ccx(buckle, wd, job="nl-buckle", timeout=timeout)
    if not run.buckling_factors:
        raise SolverError("ccx printed no buckling factor")
    blocks = [b for b in run.blocks if b.quantity.startswith("displacement")]
    if len(blocks) < 2:
        raise SolverError("ccx printed no mode shape of the buckling step")
    base, mode = blocks[0], blocks[1]
    k0 = 1.0 / abs(base.rows[ref][dof - 1])
    p_cr = run.buckling_factors[0]
    shape = {n: np.asarray(mode.rows[n][:3], dtype=np.float64) for n in shell_nodes}
    norms = {n: float(np.linalg.norm(u)) for n, u in shape.items()}
    top = max(norms, key=lambda n: norms[n])
    parts = _parts_of(buckle)
    where = parts.get(top, 1)
    layer = assembly.layer2 if where == 2 else assembly.layer1
    amp = layer.W / 200.0 if amplitude is None else amplitude
    scale = amp / norms[top]
    direction = shape[top] / norms[top]
    # the mode's node under 1 N in the linear base state, along the mode: subtracted, so that the
    # amplitude is the growth of the mode beyond the linear response
    linear = float(np.dot(np.asarray(base.rows[top][:3]), direction))
    mode_at = ("layer 1", "layer 2", "the band")[where - 1] if 1 <= where <= 3 else f"part {where}"
    predicted = max(p_cr, case.model or 0.0)
    goal = TARGET_FACTOR * predicted if target is None else target
    step = Nonlinear(goal, increment, watch=(top,))
    deck, _ = assembly_deck(assembly, case.test, mesh, case.eta, step=step, **args)
    deck = perturb(deck, shape, scale)
    progress(
        f"assembly, nonlinear ramp in {label} to {goal:.4g} N, mesh {mesh.label()} "
        f"(about {round(1 / increment)} increments)"
    )
    note = ""
    with work_dir(folder) as wd:
        try:
            found = run_ccx(deck, wd, job="nl-ramp", timeout=timeout).blocks
            ended = "target"
        except SolverError as exc:
            dat = wd / "nl-ramp.dat"
            log = (wd / "nl-ramp.log").read_text() if (wd / "nl-ramp.log").exists() else ""
            timed_out = "timed out" in str(exc)
            stalled = any(w in log.lower() for w in _STALLED)
            if not dat.exists() or not (stalled or timed_out):
                raise
            found = tuple(parse_dat(dat.read_text()))
            ended = "timed out" if timed_out and not stalled else "not converged"
            note = str(exc).split(": ", 1)[-1][:200]
    seconds = time.perf_counter() - t0
    loads, travels, amps = [], [], []
    for b in found:
        if not b.quantity.startswith("displacement") or b.nset != Nonlinear.PRINTED:
            continue
        loads.append(b.time * goal)
        travels.append(sign * b.rows[ref][dof - 1])
        moved = float(np.dot(np.asarray(b.rows[top][:3]), direction))
        amps.append(moved - b.time * goal * linear)
    if not loads:
        raise SolverError("the nonlinear ramp converged at no increment")
    if ended == "target" and loads[-1] < goal * (1 - 1e-6):
        ended = "not converged"
    return NonlinearResult(
        case,
        mesh,
        p_cr,
        k0,
        amp,
        mode_at,
        goal,
        tuple(loads),
        tuple(travels),
        tuple(amps),
        ended,
        fraction,
        seconds,
        note,
    )


def run_for_design(
    assembly: Assembly,
    constraints: Sequence[Mapping[str, Any]],
    joint: str,
    mesh: AssemblyMesh,
    **kwargs: Any,
) -> NonlinearResult | str:
    """:func:`ramp` of the design's first load-case fixture (:func:`nonlinear_case`), or why
    there is none (one phrase)."""
    from corrugate.fea.verify import joint_options

    case = nonlinear_case(assembly, constraints, joint)
    if case is None:
        return "no behavioural constraint with a coupon fixture along a crease direction"
    connectors, bond = joint_options(joint)
    try:
        return ramp(assembly, case, mesh, connectors=connectors, bond=bond, **kwargs)
    except CorrugateError as exc:
        return f"not run: {exc}"
