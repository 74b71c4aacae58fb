"""FE first buckling of the capacity validation set, for docs/validation/capacity.md (issue 34).

    python benchmarks/fea_capacity.py run [--minutes M] [--max-along A] [--only-along A] [--design TEXT] [--step dead,held]
    python benchmarks/fea_capacity.py table                               # Markdown summary
    python benchmarks/fea_capacity.py judge                               # each series judged
    python benchmarks/fea_capacity.py corners                             # the worst corner

Writes ``docs/validation/capacity_fe.csv``, one row per (design, step, along): the design's load
case run as a linear buckling analysis (``*BUCKLE``, docs/fea.md 2) on the mesh of ``along``
elements per facet, ``load_N`` the lowest positive buckling factor times the load (N: the
fixture's load at which the part buckles), ``second_N`` the next one, ``where`` the first mode's
largest displacement (:func:`corrugate.fea.modes.mode_location`: the part, and its position as
fractions of the span and of the width from the panel's corner), ``nodes`` the model's nodes and
``seconds`` the wall-clock time. Two ways of loading, the ``step`` column:

* ``dead``: :class:`corrugate.fea.steps.LinearBuckling`, the load lines (or platen) tied to a
  reference node loaded by 1 N: a dead load, free to move in the mode (a weight, a finger);
* ``held``: the static deck with ``*STATIC`` replaced by ``*BUCKLE`` (issue 34's review): the
  load lines held at their prescribed travel in the mode (a testing machine's head); the factor
  times the static run's force at that travel is the load.

For one and the same discrete model the dead load's first buckling load would be at or below the
held one's (its eigenproblem has every mode of the held one and the load line's own motion:
tests/fea/test_buckling_step.py). The two decks are not the same discrete model at the load
line (equations on the line's shell nodes against prescribed displacements of them, which ccx
applies to its expanded shells in its own way), and they differ either way: the capacity table
shows both and takes the lower one, the conservative one, saying which.

Designs (:func:`designs`): the stubby panel of issue 34, the chassis example's design with and
without the bonded band, and six more spread over alpha 40-150 deg, t/W 0.006-0.05, L/h 4-30,
Dura-Lar, polycarbonate and polypropylene, in three-point, four-point, cantilever and platens;
and with the band bonded along the edges, over the panel's length, the chassis example as it
answered before the band's walls could buckle in the model, its answer since (0.3 mm) and the
blimp gripper's cantilever (docs/validation/capacity.md).
All at eta = 0 (layer 1's creases along the span), the span the panel's length except the
chassis's 120 mm without the band (its example's span; with the band the FE supports the panel at
its ends, 121.2 mm apart: the band is modelled on the structured mesh only, and a shorter span
needs gmsh's).

Resumable (``resumable_csv.py``): the keys already in the CSV are skipped, each new row is
appended as its case returns. The meshes run in the order 2, 4, 8 per facet over all designs, so
a stopped run leaves whole coarse series, then 16 per facet for the designs of :data:`FINER`;
``--max-along`` stops at that mesh, ``--only-along`` runs that mesh only. ``--minutes M``
starts no new case after M minutes. Needs ccx.
"""

from __future__ import annotations

import csv
import itertools
import math
import sys
import tempfile
import time
from collections.abc import Iterator
from dataclasses import dataclass, replace
from pathlib import Path

from corrugate import Assembly, Layer, get_material
from corrugate.geometry.layouts import Rectangle
from resumable_csv import appender, done_keys  # type: ignore[import-not-found]

OUT = Path(__file__).resolve().parents[1] / "docs" / "validation"
CSV = OUT / "capacity_fe.csv"
FIELDS = ("design", "test", "step", "along", "nodes", "load_N", "second_N", "where", "seconds")
KEY = ("design", "test", "step", "along")
ALONGS = (2, 4, 8)
STEPS = ("dead", "held")


@dataclass(frozen=True, slots=True)
class Case:
    """One row of the validation set: the assembly, its load case (a fixture name), the span
    (mm; None: the panel's length), whether the band joins the layers (joint band-edges) and
    the test's direction eta (deg: 0 along layer 1's creases, 90 along layer 2's)."""

    assembly: Assembly
    test: str
    span: float | None = None
    band: bool = False
    eta: float = 0.0


def _identical(W: float, n: int, alpha: float, material: str, t: float) -> Assembly:
    return Assembly.identical(Layer(W, n, alpha, get_material(material), t))


def designs() -> dict[str, Case]:
    """The validation set (module docstring), by the name the CSV gives it."""
    pp = get_material("polypropylene")
    chassis = Assembly(Layer(16.0, 6, 90.0, pp, 0.25), Layer(5.0, 27, 120.0, pp, 0.25), Rectangle())
    # examples/chassis_plate.toml solved over the panel's length under the capacity model of
    # commit 801451e (docs/validation/capacity.md)
    resolved = Assembly(
        Layer(12.0, 9, 85.0, pp, 0.25), Layer(10.0, 13, 120.0, pp, 0.25), Rectangle()
    )
    # examples/chassis_plate.toml's answer in 0.3 mm sheet (issue 34's band-wall modes), over
    # the panel's length (its own 120 mm span cannot be meshed with the band)
    example = Assembly(Layer(11.0, 10, 85.0, pp, 0.3), Layer(7.0, 19, 120.0, pp, 0.3), Rectangle())
    # examples/chassis_plate.toml's answer in 0.5 mm sheet (the default tolerances, issue 35),
    # over its own 120 mm span (the band on the structured mesh, docs/fea.md 2.1)
    plate = Assembly(Layer(12.0, 7, 110.0, pp, 0.5), Layer(13.0, 10, 120.0, pp, 0.5), Rectangle())
    # its answers since the band's walls bend with layer 1 as one section (docs/load_cases.md
    # 10.5): the first under interval bounds of the composite formula as written (loose over the
    # tolerance box), the second under its monotone form (the example's answer)
    plate2 = Assembly(Layer(10.0, 18, 50.0, pp, 0.5), Layer(11.0, 12, 120.0, pp, 0.5), Rectangle())
    plate3 = Assembly(Layer(11.0, 11, 75.0, pp, 0.5), Layer(11.0, 12, 120.0, pp, 0.5), Rectangle())
    # examples/blimp_gripper_cantilever.toml's answer (Dura-Lar 0.175, W 8 n 7 alpha 98) at the
    # worst corner of its default tolerances for the capacity (docs/tolerances.md 1: the model's
    # least of the 64 corners, docs/validation/capacity.md "The worst tolerance corner")
    soft = get_material("dura-lar")
    soft = replace(soft, E=soft.E * 0.9)
    corner = Assembly(
        Layer(7.9, 7, 101.0, soft, 0.175 * 0.95),
        Layer(8.1, 7, 95.0, soft, 0.175 * 0.95),
        Rectangle(),
    )
    return {
        "stubby: dura-lar 0.075, W 12 n 10 a 40": Case(
            _identical(12.0, 10, 40.0, "dura-lar", 0.075), "three-point"
        ),
        "chassis, joint none: pp 0.25, W 16 n 6 a 90 / W 5 n 27 a 120": Case(
            chassis, "three-point", span=120.0
        ),
        "chassis, joint band-edges: pp 0.25, W 16 n 6 a 90 / W 5 n 27 a 120": Case(
            chassis, "three-point", band=True
        ),
        "case study: dura-lar 0.125, W 8 n 8 a 84": Case(
            _identical(8.0, 8, 84.0, "dura-lar", 0.125), "platens"
        ),
        "pc 0.25, W 10 n 13 a 120": Case(
            _identical(10.0, 13, 120.0, "polycarbonate", 0.25), "four-point"
        ),
        "pp 0.3, W 6 n 5 a 150": Case(
            _identical(6.0, 5, 150.0, "polypropylene", 0.3), "cantilever"
        ),
        "dura-lar 0.125, W 10 n 7 a 60": Case(
            _identical(10.0, 7, 60.0, "dura-lar", 0.125), "cantilever"
        ),
        "pp 0.5, W 10 n 5 a 100": Case(_identical(10.0, 5, 100.0, "polypropylene", 0.5), "platens"),
        "pc 0.175, W 7 n 12 a 130": Case(
            _identical(7.0, 12, 130.0, "polycarbonate", 0.175), "three-point"
        ),
        "chassis re-solved, joint band-edges: pp 0.25, W 12 n 9 a 85 / W 10 n 13 a 120": Case(
            resolved, "three-point", band=True
        ),
        "chassis example 0.3, joint band-edges: pp 0.3, W 11 n 10 a 85 / W 7 n 19 a 120": Case(
            example, "three-point", band=True
        ),
        "chassis plate 0.5, joint band-edges: pp 0.5, W 12 n 7 a 110 / W 13 n 10 a 120": Case(
            plate, "three-point", span=120.0, band=True
        ),
        "chassis plate composite, joint band-edges: pp 0.5, W 10 n 18 a 50 / W 11 n 12 a 120": Case(
            plate2, "three-point", span=120.0, band=True
        ),
        "chassis plate answer, joint band-edges: pp 0.5, W 11 n 11 a 75 / W 11 n 12 a 120": Case(
            plate3, "three-point", span=120.0, band=True
        ),
        "blimp cantilever, joint band-edges: dura-lar 0.125, W 8 n 7 a 98": Case(
            _identical(8.0, 7, 98.0, "dura-lar", 0.125), "cantilever", band=True
        ),
        "blimp cantilever worst corner, joint band-edges: dura-lar 0.16625 E x 0.9, "
        "W 7.9 n 7 a 101 / W 8.1 n 7 a 95": Case(corner, "cantilever", band=True),
        # the corner where the model's facet buckling (layer 1, the FE's mode) is least
        "blimp cantilever facet corner, joint band-edges: dura-lar 0.16625 E x 0.9, "
        "W 8.1 n 7 a 101": Case(
            Assembly.identical(Layer(8.1, 7, 101.0, soft, 0.175 * 0.95)), "cantilever", band=True
        ),
        # along layer 2's creases (eta 90 deg): layer 2's outstand (joint none) and the band's
        # walls composite with layer 2 (band-edges), docs/load_cases.md 10.4-10.5
        "eta 90, joint none: dura-lar 0.125, W 10 n 7 a 60 / W 8 n 8 a 90": Case(
            Assembly(
                Layer(10.0, 7, 60.0, get_material("dura-lar"), 0.125),
                Layer(8.0, 8, 90.0, get_material("dura-lar"), 0.125),
                Rectangle(),
            ),
            "three-point",
            eta=90.0,
        ),
        "eta 90, joint none: pp 0.3, W 12 n 5 a 120 / W 7 n 9 a 80": Case(
            Assembly(Layer(12.0, 5, 120.0, pp, 0.3), Layer(7.0, 9, 80.0, pp, 0.3), Rectangle()),
            "three-point",
            eta=90.0,
        ),
        "blimp cantilever eta 90, joint band-edges: dura-lar 0.125, W 8 n 7 a 98": Case(
            _identical(8.0, 7, 98.0, "dura-lar", 0.125), "cantilever", band=True, eta=90.0
        ),
    }


def ranges(case: Case) -> tuple[float, float, float]:
    """(alpha deg, t / W, L / h) of the layer along the span (layer 1 at eta 0, layer 2 at
    eta 90), L the span."""
    a = case.assembly
    layer = a.layer1 if case.eta == 0.0 else a.layer2
    length = case.span if case.span is not None else (a.Ly if case.eta == 0.0 else a.Lx)
    return layer.alpha_deg, layer.t / layer.W, length / layer.height


#: The designs whose 8-per-facet runs come last, dead load only (the chassis plate, about
#: 120 000 nodes, both layers and the band in one ccx run, and the 4-point polycarbonate panel,
#: about 88 000: each several GB and tens of minutes on the shared 2 cores; their dead and held
#: loads agree within 2 % at 2 and 4 per facet).
LARGE = ("chassis", "pc 0.25, W 10 n 13")
#: The designs run on at 16 per facet, both loadings: those whose lower 2 / 4 / 8 series is not
#: asymptotic (the stubby panel's dead load: 0.745 / 1.074 / 1.058 N), and those whose 16 per
#: facet fits a 7 GB cap (at most about 25 000 nodes at 8 per facet: four times that at 16),
#: so that :func:`corrugate.fea.extrapolate.judge` can settle their series (issue 35).
FINER = (
    "stubby",
    "case study",
    "pp 0.3, W 6 n 5 a 150",
    "dura-lar 0.125, W 10 n 7 a 60",
    "pp 0.5, W 10 n 5 a 100",
    "eta 90, joint none",
)


def jobs(ds: dict[str, Case], max_along: int) -> Iterator[tuple[str, str, int]]:
    """(design, step, along): every design at 2, then at 4, then at 8 per facet; at 8 the
    large designs last and under the dead load only."""
    for along in ALONGS:
        if along > max_along:
            return
        large = [n for n in ds if n.startswith(LARGE)] if along == 8 else []
        for name in ds:
            if name not in large:
                for step in STEPS:
                    yield name, step, along
        for name in large:
            yield name, "dead", along
    if max_along >= 16:
        for name in ds:
            if name.startswith(FINER):
                for step in STEPS:
                    yield name, step, 16


def solve(case: Case, step: str, along: int) -> tuple[int, float, float, str]:
    """One buckling run: (nodes, first load N, second load N, where the first mode is)."""
    from corrugate.fea.assembly import AssemblyMesh, assembly_deck, solve_assembly
    from corrugate.fea.ccx import run_ccx
    from corrugate.fea.modes import mode_location, parse_frd_mode, with_mode_output
    from corrugate.fea.steps import LinearBuckling

    a, mesh = case.assembly, AssemblyMesh(along)
    kw = {"connectors": case.band, "span": case.span}
    scale = 1.0
    if step == "dead":
        deck, info = assembly_deck(a, case.test, mesh, case.eta, step=LinearBuckling(), **kw)
    else:
        static = solve_assembly(a, case.test, mesh, case.eta, split=False, **kw)
        deck, info = assembly_deck(a, case.test, mesh, case.eta, **kw)
        deck = deck.replace("*STATIC", "*BUCKLE\n3,1.e-6")
        scale = static.force
    with tempfile.TemporaryDirectory(prefix="capfe-") as d:
        run = run_ccx(with_mode_output(deck), Path(d), job="b", timeout=1800.0)
        shape = parse_frd_mode((Path(d) / "b.frd").read_text())
    f = [x * scale for x in run.buckling_factors if x > 0]
    if case.eta == 0.0:
        where = mode_location(shape, 1, a.Lx, a.Ly)
    else:  # along layer 2's creases: the span along x
        where = mode_location(shape, 0, a.Ly, a.Lx)
    second = f[1] if len(f) > 1 else math.nan
    return info.nodes, f[0], second, where


def run(
    minutes: float = math.inf,
    max_along: int = 16,
    only: int | None = None,
    design: str = "",
    steps: tuple[str, ...] = STEPS,
) -> None:
    """Run the cases not yet in the CSV, one ccx at a time; no new case after ``minutes``;
    ``only``: the cases of that mesh only; ``design``: of the designs whose name holds it;
    ``steps``: of those loadings only."""
    from corrugate.core.errors import CorrugateError

    ds = designs()
    done = done_keys(CSV, KEY)
    start = time.perf_counter()
    pre = ["python benchmarks/fea_capacity.py run (docstring: what each column is)"]
    with appender(CSV, FIELDS, pre) as write:
        for name, step, along in jobs(ds, max_along):
            if (only is not None and along != only) or design not in name or step not in steps:
                continue
            case = ds[name]
            key = (name, case.test, step, str(along))
            if key in done:
                continue
            if time.perf_counter() - start > 60 * minutes:
                print(f"stopped: {minutes:g} minutes", flush=True)
                return
            t0 = time.perf_counter()
            try:
                nodes, first, second, where = solve(case, step, along)
            except CorrugateError as exc:
                print("failed", *key, exc, flush=True)
                continue
            s = time.perf_counter() - t0
            write((*key, nodes, f"{first:.7g}", f"{second:.7g}", where, f"{s:.1f}"))
            print(*key, nodes, f"{first:.5g}", where, f"{s:.0f} s", flush=True)


def model(case: Case) -> tuple[float, str] | None:
    """The model's first-failure load (N, the least mode at safety factor 1: no factor) and its
    words (:func:`corrugate.analysis.load_case.load_case_capacity`, the formulas the solver
    bounds, docs/load_cases.md), for the design's joint; None where the model states none."""
    from corrugate.analysis.evaluate import analyze
    from corrugate.analysis.load_case import LoadCase, load_case_capacity

    joint = "band-edges" if case.band else "none"
    r = analyze(case.assembly, "refined", eta_deg=[case.eta], joint=joint)
    cap = load_case_capacity(
        r, LoadCase(case.test, 1.0, span=case.span), case.eta, safety_factor=1.0
    )
    if cap is None:
        return None
    return float(cap.load), str(cap.words)


def corners(
    layer: Layer,
    test: str,
    band: bool,
    tol: tuple[float, float, float, float] = (3.0, 0.1, 0.05, 0.1),
) -> None:
    """The model's first failure (:func:`model`, N, no safety factor) at the 64 corners of the
    tolerance box around identical layers ``layer`` (docs/tolerances.md 1: each layer's W +-
    dW and alpha +- dalpha on its own, the sheet's t and E +- their relative half-widths; ``tol``
    (dalpha deg, dW mm, dt, dE), the defaults), least first: the corner an FE of the worst part
    is meshed at (docs/validation/capacity.md, "The worst tolerance corner")."""
    da, dW, dt, dE = tol
    out = []
    for w1, a1, w2, a2, st, se in itertools.product(*[(-1, 1)] * 6):
        m = replace(layer.material, E=layer.material.E * (1 + se * dE))
        t = layer.t * (1 + st * dt)
        a = Assembly(
            Layer(layer.W + w1 * dW, layer.n, layer.alpha_deg + a1 * da, m, t),
            Layer(layer.W + w2 * dW, layer.n, layer.alpha_deg + a2 * da, m, t),
            Rectangle(),
        )
        got = model(Case(a, test, band=band))
        if got is not None:
            out.append((got[0], (w1, a1, w2, a2, st, se), got[1], a.Lx, a.Ly))
    nominal = model(Case(Assembly.identical(layer), test, band=band))
    print(f"nominal: {nominal}")
    out.sort()
    print("(dW1, da1, dW2, da2, dt, dE): load N, first failure, Lx, Ly (mm)")
    for load, c, words, lx, ly in out[:4] + out[-1:]:
        print(f"{c}: {load:.4g} N, {words}, {lx:.2f} x {ly:.2f}")


def _text(series: dict[int, float], digits: int) -> str:
    """A series' values, coarsest first, with its meshes named unless they are 2, 4, 8, ..."""
    ks = sorted(series)
    text = " / ".join(f"{series[k]:.{digits}g}" for k in ks)
    if ks != [2 * 2**i for i in range(len(ks))]:
        text += " (at " + " / ".join(map(str, ks)) + " per facet)"
    return text


def _series(rows: list[dict[str, str]], name: str, step: str) -> dict[int, dict[str, str]]:
    return {int(r["along"]): r for r in rows if r["design"] == name and r["step"] == step}


def table() -> None:
    """The Markdown table of docs/validation/capacity.md: per design its ranges, the dead and
    held FE series (N) at 2 / 4 / 8 (/ 16) per facet, each extrapolated
    (:func:`corrugate.fea.extrapolate.extrapolate`: Richardson where its three finest meshes are
    asymptotic, else "not converged" and its finest value), the FE first buckling (the lower of
    the two loadings' values, saying which and whether it is a finest value), where the dead
    load's first mode is on the finest mesh, the model's first-failure load and mode
    (:func:`model`) and model / FE. Not :func:`corrugate.fea.extrapolate.judge`'s verdict: that
    is :func:`judged`'s."""
    from corrugate.fea.extrapolate import extrapolate

    ds = designs()
    with CSV.open() as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    head = (
        "design",
        "test",
        "alpha, t/W, L/h",
        "FE dead 2 / 4 / 8 (/ 16) (N), estimate",
        "FE held 2 / 4 / 8 (/ 16) (N), estimate",
        "FE first buckling (N)",
        "FE first mode (dead, finest)",
        "model (N), first failure",
        "model / FE",
    )
    print("| " + " | ".join(head) + " |")
    print("|---" * len(head) + "|")
    for name, case in ds.items():
        alpha, tw, lh = ranges(case)
        cells: list[str] = []
        values: dict[str, tuple[float, bool]] = {}  # loading -> (value, an estimate)
        for step in STEPS:
            mine = _series(rows, name, step)
            if not mine:
                cells.append("-")
                continue
            series = {k: float(r["load_N"]) for k, r in mine.items()}
            e = extrapolate(series, "min")  # a failure load: only a value safe below the limit
            text = _text(series, 4)
            if e.value is not None and e.asymptotic and e.order is not None:
                values[step] = (e.value, True)
                cells.append(f"{text}; **{e.value:.4g}** (p = {e.order:.2f})")
            else:  # not converged: its finest value, which bounds a falling series from above
                values[step] = (series[max(series)], False)
                cells.append(f"{text}; not converged")
        if not values:  # not run yet
            continue
        lower = min(values, key=lambda k: values[k][0])
        fe, estimate = values[lower]
        fe_text = (
            f"{fe:.4g} ({lower})" if estimate else f"{fe:.4g} ({lower}, finest: not converged)"
        )
        dead = _series(rows, name, "dead")
        where = dead[max(dead)]["where"] if dead else "-"
        m = model(case)
        mod = "-" if m is None else f"{m[0]:.3g}: {m[1]}"
        ratio = "-" if m is None else f"{m[0] / fe:.2f}" + ("" if estimate else " (of the finest)")
        print(
            f"| {name} | {case.test} | {alpha:g}, {tw:.4f}, {lh:.1f} | {cells[0]} | {cells[1]} | "
            f"{fe_text} | {where} | {mod} | {ratio} |"
        )


def judged() -> None:
    """Each design's series against its model (docs/validation/capacity.md, "Which series are
    converged"): per design and loading the series (N) at 2 / 4 / 8 (/ 16) per facet and
    :func:`corrugate.fea.extrapolate.judge`'s verdict of it against the model's first failure
    (:func:`model`, sense min): "holds" or "fails" only where the series is shown asymptotic
    (four meshes, two extrapolations that agree) or its last two steps vanish, else "open" with
    the reason (not converged)."""
    from corrugate.fea.extrapolate import judge

    with CSV.open() as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    print("| design | step | FE series (N) | model (N) | judge | how |")
    print("|---|---|---|---|---|---|")
    for name, case in designs().items():
        m = model(case)
        for step in STEPS:
            mine = _series(rows, name, step)
            if not mine or m is None:
                continue
            series = {k: float(r["load_N"]) for k, r in mine.items()}
            text = _text(series, 5)
            j = judge(series, m[0], "min")
            verdict = j.verdict if j.verdict != "open" else "not converged"
            how = j.how + (f" ({j.why})" if j.why else "")
            print(f"| {name} | {step} | {text} | {m[0]:.4g} | {verdict} | {how} |")


if __name__ == "__main__":
    args = sys.argv[1:]
    if args[:1] == ["run"]:
        minutes, max_along, only = math.inf, 16, None
        if "--minutes" in args:
            minutes = float(args[args.index("--minutes") + 1])
        if "--max-along" in args:
            max_along = int(args[args.index("--max-along") + 1])
        if "--only-along" in args:
            only = int(args[args.index("--only-along") + 1])
        design = args[args.index("--design") + 1] if "--design" in args else ""
        steps = tuple(args[args.index("--step") + 1].split(",")) if "--step" in args else STEPS
        run(minutes, max_along, only, design, steps)
    elif args[:1] == ["table"]:
        table()
    elif args[:1] == ["judge"]:
        judged()
    elif args[:1] == ["corners"]:  # the blimp cantilever's answer (Dura-Lar 0.175 mm)
        corners(Layer(8.0, 7, 98.0, get_material("dura-lar"), 0.175), "cantilever", True)
    else:
        sys.exit(__doc__)
