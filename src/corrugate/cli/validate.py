"""``corrugate validate``: finite-element (CalculiX) check of a design against every model variant.

Registered by :mod:`corrugate.cli` (see :data:`COMMANDS`). The FE subpackage
(:mod:`corrugate.fea`) is imported only when the command runs, so the core CLI works without it.
``--design`` reads a design.json through :func:`corrugate.export.record.read_record`.

Examples::

    corrugate validate --W 10 --n 7 --alpha 90 --material dura-lar
    corrugate validate --W 10 --n 7 --alpha 90 --refine 0.01
    corrugate validate --sweep paper --out docs/validation --jobs 2
    corrugate validate --design out/mydesign/design.json
    corrugate validate --design out/wheel/design.json --fixture wheel --series 2,4,8 --eta 45
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from dataclasses import replace
from pathlib import Path
from typing import TYPE_CHECKING, Annotated

import typer

from corrugate.cli import options as o
from corrugate.cli.console import make_console
from corrugate.core.errors import InputError
from corrugate.core.parameters import PARAMETERS, choices_metavar
from corrugate.names import MODEL_NAMES as MODELS
from corrugate.names import RECTANGULAR_LAYOUTS

if TYPE_CHECKING:
    from rich.console import Console

    from corrugate.fea.connector_band import Bond
    from corrugate.fea.validation import CaseResult, Progress, Refinement
    from corrugate.geometry.layer import Assembly

__all__ = ["COMMANDS", "progress_lines", "validate_cmd"]

Opt = typer.Option


def _print_result(r: CaseResult, console: Console) -> None:
    from rich.table import Table

    if r.error:
        console.print(f"[red]failed[/red] {r.case.label}: {r.error}")
        return
    t = Table(
        title=f"{r.case.label}: FE (CalculiX) versus the closed forms "
        f"({', '.join(f'{k} mesh {v}' for k, v in r.meshes.items())})",
        title_justify="left",
    )
    t.add_column("quantity")
    t.add_column("FE", justify="right")
    for m in MODELS:
        t.add_column(m, justify="right")
        t.add_column(f"{m}/FE", justify="right")
    from corrugate.fea.validation import fixture_key, fixture_supports

    units = {
        "K_N_per_mm": "N/mm",
        **{fixture_key(b): "N/mm" for b in fixture_supports()},
        "D_Nmm": "N mm",
        "EI_Nmm2": "N mm^2",
        "D4_Nmm": "N mm",
    }
    keys = _display_keys(r)
    for key in keys:
        t.add_row(_name(key, units), f"{r.fe[key]:.5g}", *_model_cells(r, key))
    console.print(t)
    if any(k.startswith("D4_") for k in keys):
        console.print(D4_LEGEND)
    for eta, (low, high) in _buckling_bounds(r).items():
        P, K = r.fe[f"Pcr_N@{eta}"], r.fe.get(f"K_N_per_mm@{eta}")
        at = f", at a platen displacement of {P / K:.3g} mm" if K else ""
        console.print(
            f"first buckling load in compression along eta = {eta} deg: FE {P:.4g} N{at} "
            f"(plate theory for the end facets, one free edge: {low:.4g}-{high:.4g} N"
            + (", without the band" if r.case.connectors else "")
            + ")"
        )
    if not r.refined:
        console.print(
            "one mesh, not refined: these FE numbers are not checked for mesh convergence "
            "(--refine TOL runs a refinement study)"
        )
    elif not r.converged:
        console.print(
            "[yellow]warning[/yellow]: mesh refinement stopped at the finest mesh allowed "
            "before every value was shown within the tolerance of its limit (not converged)"
        )
    if len(r.history) > 2:
        console.print("[bold]mesh refinement[/bold]")
        for label, vals in r.history:
            shown = [k for k in _display_keys(r) if k in vals]
            text = ", ".join(f"{_name(k, units)} = {vals[k]:.6g}" for k in shown)
            console.print(f"  {label}: {text}")


#: What the D4 row of the table is, printed under it.
D4_LEGEND = (
    "D4: the bending stiffness from a 4-point (pure) bending test, measured between the load "
    "lines where the moment is constant and there is no shear: the quantity the closed forms "
    "model; D is the 3-point value a bench test measures, shear included (`corrugate docs fea`, "
    "section 2.1)."
)


def _buckling_bounds(r: CaseResult) -> dict[str, tuple[float, float]]:
    """Plate-theory bounds (N) beside each FE buckling load of ``r``, by eta."""
    from corrugate.analysis.evaluate import facet_buckling_load

    out: dict[str, tuple[float, float]] = {}
    for key in r.fe:
        if key.startswith("Pcr_N@"):
            eta = key.split("@")[1]
            b = facet_buckling_load(r.case.assembly, float(eta))
            out[eta] = (b.low, b.high)
    return out


def _display_keys(r: CaseResult) -> list[str]:
    """Stiffness keys first (by eta, then K, K under each support condition with a fixture of its
    own such as the frame, D, EI, D4), then the moduli of layer 1 (and of layer 2 when it
    differs)."""
    from corrugate.fea.validation import fixture_key, fixture_supports

    fixed = tuple(fixture_key(b) for b in fixture_supports())
    order = ("K_N_per_mm", *fixed, "D_Nmm", "EI_Nmm2", "D4_Nmm")
    etas = list(dict.fromkeys(f"{e:g}" for e in r.case.eta_deg))
    keys = sorted(
        (k for k in r.fe if "@" in k and not k.startswith("Pcr")),
        key=lambda k: (etas.index(k.split("@")[1]), order.index(k.split("@")[0])),
    )
    a = r.case.assembly
    for i in (1,) if a.layer1 == a.layer2 else (1, 2):
        keys += [f"layer{i}.{m}" for m in ("Ecx", "Ecy", "Ebx", "Eby") if f"layer{i}.{m}" in r.fe]
    return keys


def _name(key: str, units: dict[str, str]) -> str:
    if "@" in key:
        q, eta = key.split("@")
        return f"{q.split('_')[0]}({eta}) {units[q]}"
    return f"{key} MPa"


def _model_cells(r: CaseResult, key: str) -> list[str]:
    cells: list[str] = []
    for m in MODELS:
        mv = r.models[m][key]
        cells += [f"{mv:.5g}", f"{mv / r.fe[key]:.3f}"]
    return cells


@o.table_options(
    *o.DESIGN[:14],  # W ... thickness2, layout: no vertices, holes, model
    "design",
    "eta",
    "fixture",
    "series",
    "support",
    optional=("W", "n", "alpha"),  # validate takes the design from --design instead
    overrides={
        "layout": {
            "metavar": choices_metavar(RECTANGULAR_LAYOUTS),
            "help": " | ".join(RECTANGULAR_LAYOUTS) + " (the FE tests need straight loaded edges).",
            "autocompletion": None,
        }
    },
)
def validate_cmd(
    table: o.TableValues,
    design: Annotated[
        Path | None,
        Opt(help="A design.json (or its folder) from `corrugate design/pattern --out`."),
    ] = None,
    eta: Annotated[
        list[str] | None,
        Opt(
            metavar=o.ANGLE,
            help="Direction of the load, deg from layer 1's creases; repeat for several "
            "(default 0). The platens compress the panel along eta and the bending span runs "
            "along it: at 0 or 90 the layout itself (square, rectangle, or a polygon cut from "
            "its box); at any other eta a coupon of the layout's proportions cut from the two "
            "layers with its edges along and across eta (square or rectangle). With --fixture "
            "wheel, the ground patch pushes the rim towards the hub along eta. `corrugate docs "
            "fea`, 2.4 and 2.8.",
        ),
    ] = None,
    fixture: Annotated[
        str | None,
        Opt(
            metavar="wheel|corners|clamped-corners",
            help="Instead of the paper's tests, a fixture for any outline (circle, polygon; "
            "with --design): wheel (radial K between a no-slip ground patch of +-15 deg at eta "
            "and a rigid axle in the hub), corners or clamped-corners (P / delta of the plate "
            "bolted or clamped at its corners, loaded at its centre). `corrugate docs fea`, 2.8.",
        ),
    ] = None,
    series: Annotated[
        str | None,
        Opt(
            metavar="N,N,...",
            help="With --fixture: run it on this mesh series (elements per facet, each twice "
            "the one before) and extrapolate, e.g. 2,4,8 (default: --mesh alone).",
        ),
    ] = None,
    mesh: Annotated[
        int | None,
        Opt(
            parser=o.ASCII_INT,
            help="Shell elements across each facet (even; default 4, with --refine 2).",
        ),
    ] = None,
    cell_mesh: Annotated[
        str | None,
        Opt(
            metavar="ALONGxTHROUGH",
            help="Unit-cell mesh: elements along a facet x through t, graded towards the creases "
            "(default 80x8: Ecx within 0.7 % of the converged value at alpha 40-115 deg, "
            "`corrugate docs fea`, section 1.3; with --refine 40x4).",
        ),
    ] = None,
    refine: Annotated[
        float | None,
        Opt(
            metavar="FRACTION",
            parser=o.ASCII_FLOAT,
            help="Refine the meshes (doubling) until every result's finest value is shown within "
            "this fraction (e.g. 0.01) of its FE limit: two successive Richardson extrapolations "
            "over four meshes agreeing (`corrugate docs fea`, section 3); else not converged at "
            "the finest mesh allowed.",
        ),
    ] = None,
    no_unit_cell: Annotated[bool, Opt("--no-unit-cell", help="Skip the unit-cell runs.")] = False,
    connectors: Annotated[
        bool,
        Opt(
            "--connectors",
            help="Add the connector band to the assembly model (`corrugate docs fea`, 2.3).",
        ),
    ] = False,
    bond: Annotated[
        str,
        Opt(
            metavar="[edges|flanges]",
            help="With --connectors: edges (layers bonded to the band along their whole edges) "
            "or flanges (the band as cut, glued only where the layers rest on its flanges).",
        ),
    ] = "edges",
    buckling: Annotated[
        bool,
        Opt(
            "--buckling",
            help="Also the first buckling load in compression (eta 0/90), with its plate bounds.",
        ),
    ] = False,
    no_pure_bending: Annotated[
        bool, Opt("--no-pure-bending", help="Skip the 4-point (pure) bending diagnostic.")
    ] = False,
    sweep: Annotated[
        str | None, Opt(metavar="NAME", help="Run a named sweep instead of one design: paper.")
    ] = None,
    out: Annotated[
        Path, Opt(metavar="DIR", help="Folder for the sweep's table, CSV and plot.")
    ] = Path("out/validation"),
    jobs: Annotated[
        int | None,
        Opt(parser=o.ASCII_INT, help="Worker processes for a sweep (default: all cores)."),
    ] = None,
    scheduler: Annotated[
        str | None,
        Opt(
            metavar="ADDRESS",
            help="dask.distributed scheduler address for a sweep (needs the `dist` extra).",
        ),
    ] = None,
    workdir: Annotated[
        Path | None, Opt(metavar="DIR", help="Parent folder of the ccx work folders.")
    ] = None,
    keep: Annotated[bool, Opt(help="Keep the ccx work folders.")] = False,
    timeout: Annotated[
        float, Opt(parser=o.ASCII_FLOAT, help="Time-out of one ccx run (s).")
    ] = 900.0,
    as_json: Annotated[bool, Opt("--json", help="Print one JSON object (single design).")] = False,
    quiet: o.Quiet = False,
) -> None:
    """Check a design (or a sweep) by finite elements: FE versus each model variant.

    The paper's tests (platens, 3- and 4-point bending, and a cantilever) load the panel along
    each --eta. Circles and polygons (--design) take --fixture instead: wheel (radial K between
    a ground patch and the hub) or corners / clamped-corners (a plate held at its corners).

    Example: corrugate validate --W 10 --n 7 --alpha 90 --material dura-lar --refine 0.02
    """
    import sys

    from corrugate.export.record import design_label
    from corrugate.fea.ccx import find_ccx
    from corrugate.fea.series import check_sweep_options
    from corrugate.fea.validation import Case, run_case
    from corrugate.mechanics.behaviours import check_support

    bond_ = _bond(bond, connectors)
    mesh, cell_mesh = _start_meshes(mesh, cell_mesh, refine)
    refinement = _refinement(mesh, cell_mesh, refine)
    check_sweep_options(jobs, timeout, workdir)
    if fixture is not None or series is not None:
        if connectors or sweep is not None:
            raise InputError(
                "connectors" if connectors else "sweep",
                "given",
                "no band and no sweep with --fixture (the outline fixtures: one design, no band)",
                reason="conflicts with --fixture",
            )
        _run_fixture(
            fixture, series, mesh, design, table, eta, workdir, keep, timeout, quiet, as_json
        )
        return
    find_ccx()  # fail early, with one clear line, when CalculiX is missing
    console = make_console()
    if sweep is not None:
        _run_sweep(
            sweep,
            refinement,
            not no_unit_cell,
            out,
            jobs,
            scheduler,
            workdir,
            keep,
            console,
            connectors,
            bond_,
            quiet,
        )
        return
    assembly = _assembly(design, table)
    etas = _etas(assembly, eta, connectors)
    band = (" +connectors" + (" (flanges)" if bond == "flanges" else "")) if connectors else ""
    case = Case(
        design_label(assembly) + band,
        assembly,
        eta_deg=etas,
        unit_cell=not no_unit_cell,
        pure_bending=not no_pure_bending,
        refinement=refinement,
        folder=workdir,
        keep=keep,
        timeout=timeout,
        connectors=connectors,
        buckling=buckling,
        bond=bond_,
        support=check_support(table["support"], PARAMETERS["support"].flag),
    )
    result = run_case(case, progress_lines(quiet or (as_json and not sys.stderr.isatty())))
    if as_json:
        typer.echo(json.dumps(_result_json(result), indent=2))
    elif quiet:
        if result.error:
            make_console(stderr=True).print(f"failed {result.case.label}: {result.error}")
    else:
        _print_result(result, console)
    if result.error:
        raise typer.Exit(1)


def _run_fixture(
    fixture: str | None,
    series: str | None,
    mesh: int,
    design: Path | None,
    options: Mapping[str, object],
    eta: list[str] | None,
    workdir: Path | None,
    keep: bool,
    timeout: float,
    quiet: bool,
    as_json: bool,
) -> None:
    """``validate --fixture``: an outline fixture (:mod:`corrugate.fea.outline`) on a mesh
    series, extrapolated, beside the model's K(eta) for the wheel (a different statement: the
    model's K sums the strips between platens)."""
    import sys

    from corrugate.analysis.evaluate import analyze
    from corrugate.export.record import design_label, read_record
    from corrugate.fea.assembly import AssemblyMesh
    from corrugate.fea.ccx import find_ccx
    from corrugate.fea.extrapolate import extrapolate
    from corrugate.fea.outline import OUTLINE_NAMES, OUTLINE_TESTS, solve_outline
    from corrugate.fea.verify import parse_meshes
    from corrugate.spec.inputs import parse_etas

    if fixture is None:
        raise InputError("series", series, "together with --fixture", reason="needs a fixture")
    if fixture not in OUTLINE_TESTS:
        raise InputError("fixture", repr(fixture), " or ".join(OUTLINE_TESTS))
    meshes = parse_meshes(series) if series is not None else (AssemblyMesh(mesh).along,)
    if design is not None:
        given = [PARAMETERS[k].flag for k in ("W", "n", "alpha") if options.get(k) is not None]
        if given:
            raise InputError(
                given[0],
                "given",
                "either --design or the layer options",
                reason="conflicts with --design",
            )
        assembly = read_record(design).assembly(any_layout=True)
    else:
        assembly = _assembly(None, options)
    etas = parse_etas(eta or ["0"])
    if fixture != "wheel" and len(etas) > 1:
        raise InputError("eta", "repeated", "one eta (the corner fixtures have no direction)")
    if fixture != "wheel" and assembly.layout.name == "circle":
        raise InputError("fixture", fixture, "wheel for a circle", reason="needs corners")
    find_ccx()
    progress = progress_lines(quiet or (as_json and not sys.stderr.isatty()))
    model = analyze(assembly, "refined", list(etas)).stiffness if fixture == "wheel" else None
    rows: list[dict[str, object]] = []
    for i, e in enumerate(etas if fixture == "wheel" else etas[:1]):
        values: dict[int, float] = {}
        for along in meshes:
            where = f" along eta = {e:g} deg" if fixture == "wheel" else ""
            progress(f"{OUTLINE_NAMES[fixture]}{where}, mesh {along}/facet")
            r = solve_outline(
                assembly,
                fixture,
                AssemblyMesh(along),
                e,
                folder=workdir,
                keep=keep,
                timeout=timeout,
            )
            values[along] = r.value
        x = extrapolate(values)
        rows.append(
            {
                "eta_deg": e,
                "fe_series": {str(k): v for k, v in values.items()},
                "fe": x.value,
                "order": x.order,
                "estimate": x.how,
                "model_K": None if model is None else model[i].K,
                "wheel_test_K": None if model is None else _wheel_test(model[i].K, e),
            }
        )
    data = {
        "design": design_label(assembly),
        "fixture": fixture,
        "quantity": "K_N_per_mm" if fixture == "wheel" else "P_per_delta_N_per_mm",
        "meshes": list(meshes),
        "rows": rows,
    }
    if as_json:
        typer.echo(json.dumps(data, indent=2, allow_nan=False))
        return
    if quiet:
        return
    from rich.table import Table

    console = make_console()
    t = Table(
        title=f"{design_label(assembly)}: {OUTLINE_NAMES[fixture]} (CalculiX), mesh "
        f"{' / '.join(map(str, meshes))} elements per facet",
        title_justify="left",
    )
    wheel = fixture == "wheel"
    name = "K(eta) N/mm" if wheel else "P / delta N/mm"
    cols = ["eta deg"] if wheel else []
    cols += [f"FE series {name}", "FE estimate"]
    cols += ["model K (spring sum)", "wheel test c(eta) K"] if wheel else []
    for col in cols:
        t.add_column(col, justify="right")
    for row in rows:
        ser = " / ".join(f"{v:.5g}" for v in row["fe_series"].values())  # type: ignore[attr-defined]
        fe = row["fe"]
        est = f"- ({row['estimate']})" if fe is None else f"{fe:.5g} ({row['estimate']})"
        mk, wk = row["model_K"], row["wheel_test_K"]
        cells = [ser, est]
        if wheel:
            cells = [
                f"{row['eta_deg']:g}",
                *cells,
                "-" if mk is None else f"{mk:.5g}",
                "-" if wk is None else f"{wk:.5g}",
            ]
        t.add_row(*cells)
    console.print(t)
    if fixture == "wheel":
        console.print(
            "the model's K is not this test: it sums the strips' springs between platens, a "
            "statement no bench test of a disc makes (`corrugate docs fea`, 2.8); the wheel "
            "test's bound c(eta) K is (`corrugate docs load_cases`, section 9; eta a multiple "
            "of 45 deg)"
        )


def _wheel_test(K: float, eta: float) -> float | None:
    """The wheel test's bound c(eta) K (N/mm) from the model's K (N/mm) at ``eta`` (deg), or
    None where it has no factor (docs/load_cases.md 9)."""
    from corrugate.mechanics.wheel import wheel_direction, wheel_factor

    return None if wheel_direction(eta) is None else K * wheel_factor(eta)


def progress_lines(quiet: bool) -> Progress:
    """One line on stderr before each CalculiX run (nothing with --quiet, nor with --json unless
    stderr is a terminal): the run's number, the seconds since the first one and what it
    computes."""
    import time

    if quiet:
        return lambda line: None
    err = make_console(stderr=True)
    start = time.monotonic()
    count = 0

    def say(line: str) -> None:
        nonlocal count
        count += 1
        err.print(f"CalculiX run {count} ({time.monotonic() - start:.0f} s): {line}")

    return say


def _bond(bond: str, connectors: bool) -> Bond:
    """The ``--bond`` option, checked against ``--connectors``."""
    if bond not in ("edges", "flanges"):
        raise InputError("bond", repr(bond), "edges or flanges")
    if bond != "edges" and not connectors:
        raise InputError(
            "bond", bond, "flanges only together with --connectors", reason="needs the band"
        )
    return "flanges" if bond == "flanges" else "edges"


def _start_meshes(mesh: int | None, cell_mesh: str | None, refine: float | None) -> tuple[int, str]:
    """``--mesh`` and ``--cell-mesh``, or their defaults: 4 and 80x8, or one doubling coarser
    with ``--refine`` (2 and 40x4), so that its series reach the four meshes its rule needs
    within the finest allowed (:func:`corrugate.fea.validation.settled`: 2 / 4 / 8 / 16 per facet,
    40 / 80 / 160 / 320 along the unit cell)."""
    from corrugate.fea.validation import REFINE_START, Refinement

    start = REFINE_START if refine is not None else Refinement()
    if mesh is None:
        mesh = start.assembly_mesh.along
    return mesh, cell_mesh if cell_mesh is not None else start.cell_mesh.label()


def _refinement(mesh: int, cell_mesh: str, refine: float | None) -> Refinement:
    """The meshes to start from (``--mesh``, ``--cell-mesh``) and the refinement tolerance."""
    from corrugate.fea.assembly import AssemblyMesh
    from corrugate.fea.unitcell import UnitCellMesh
    from corrugate.fea.validation import Refinement

    if refine is not None and not 0 < refine < 1:
        raise InputError("refine", refine, "0 < TOL < 1 (a relative change, e.g. 0.01)")
    try:
        along, through = (int(v) for v in cell_mesh.lower().split("x"))
    except ValueError:
        raise InputError(
            "cell-mesh", repr(cell_mesh), "ALONGxTHROUGH, e.g. 40x2", reason="cannot be read"
        ) from None
    return Refinement(AssemblyMesh(mesh), UnitCellMesh(along, through), refine)


def _assembly(design: Path | None, options: Mapping[str, object]) -> Assembly:
    """The design to check: the record of ``--design`` or the layer ``options`` (``--W``, ...),
    never both."""
    from corrugate.export.record import read_record
    from corrugate.spec.inputs import assembly_from_namespace

    layer = {PARAMETERS[k].flag: options.get(k) for k in ("W", "n", "alpha")}
    if design is not None:
        given = [name for name, value in layer.items() if value is not None]
        if given:
            raise InputError(
                given[0],
                "given",
                "either --design or the layer options",
                reason="conflicts with --design",
            )
        # a polygon runs the paper's tests cut from its box; a circle is refused by the
        # fixtures with a line that names --fixture wheel (`corrugate docs fea`, 2.8)
        return read_record(design).assembly(any_layout=True)
    if any(value is None for value in layer.values()):
        raise InputError(
            "design",
            None,
            "--W, --n and --alpha, --design FILE, or --sweep NAME",
            reason="is missing",
        )
    return assembly_from_namespace(options)


def _etas(assembly: Assembly, eta: list[str] | None, connectors: bool) -> tuple[float, ...]:
    """The directions of ``--eta`` (default 0), checked against the FE model before any run:
    layout, eta and connectors must fit it."""
    from corrugate.fea.assembly import principal_axis, specimen
    from corrugate.spec.inputs import parse_etas

    etas = parse_etas(eta or ["0"])
    for e in etas:
        specimen(assembly, e)
        if connectors and principal_axis(e) is None:
            raise InputError(
                "eta",
                f"{e:g} deg",
                "0 or 90 deg with --connectors (`corrugate docs fea`, section 2.3)",
            )
    return etas


def _result_json(result: CaseResult) -> dict[str, object]:
    """The object ``validate --json`` prints for one design."""
    return {
        "case": result.case.label,
        "fe": result.fe,
        "models": result.models,
        "meshes": result.meshes,
        "refined": result.refined,
        "converged": result.converged,
        "error": result.error,
        "buckling_bounds_N": _buckling_bounds(result),
    }


def _run_sweep(
    name: str,
    refinement: Refinement,
    unit_cell: bool,
    out: Path,
    jobs: int | None,
    scheduler: str | None,
    workdir: Path | None,
    keep: bool,
    console: Console,
    connectors: bool = False,
    bond: Bond = "edges",
    quiet: bool = False,
) -> None:
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

    from corrugate.fea.series import SWEEPS, dask_executor, run_sweep, write_sweep_files

    if name not in SWEEPS:
        raise InputError("sweep", repr(name), "one of " + ", ".join(SWEEPS), reason="is unknown")
    cases = SWEEPS[name](refinement, unit_cell)
    if connectors:
        cases = [replace(c, connectors=True, bond=bond) for c in cases]
    executor = dask_executor(scheduler) if scheduler else None
    results: list[CaseResult] = []
    columns = (
        TextColumn("{task.description}"),
        BarColumn(),
        MofNCompleteColumn(),
        TimeElapsedColumn(),
    )
    try:
        with Progress(*columns, console=console, disable=quiet) as progress:
            task = progress.add_task(f"sweep {name}", total=len(cases))
            for r in run_sweep(cases, executor, jobs=jobs, folder=workdir, keep=keep):
                results.append(r)
                if not quiet:
                    status = f"[red]failed: {r.error}[/red]" if r.error else "done"
                    progress.console.print(f"{r.case.label}: {status}")
                elif r.error:
                    make_console(stderr=True).print(f"failed {r.case.label}: {r.error}")
                progress.advance(task)
    finally:
        if executor is not None:
            executor.shutdown()
    write_sweep_files(results, out, name)
    failed = [r for r in results if r.error]
    if quiet:
        if failed:
            raise typer.Exit(1)
        return
    console.print(
        f"wrote {out}/sweep_{name}.md, .csv and .png ({len(results) - len(failed)} "
        f"cases, {len(failed)} failed)"
    )
    console.print((out / f"sweep_{name}.md").read_text())
    if any(k.startswith("D4_") for r in results for k in r.fe):
        console.print(D4_LEGEND)
    if failed:
        raise typer.Exit(1)


#: The commands of this module, by name (registered by :mod:`corrugate.cli`).
COMMANDS = {"validate": validate_cmd}
