"""``corrugate analyze`` and ``corrugate materials``: one design's stiffness, and the library.

``analyze --test T --load P [--span Ls]`` also states a load case (docs/load_cases.md): at each
direction asked, the deflection delta (mm) of the test ``T`` under the load P (N) and the test's
P / delta (N/mm), from the support's D or K, the layers' shear springs and the panel's length
along eta (:func:`corrugate.analysis.load_case.load_case_rows`).
"""

from __future__ import annotations

import json
from typing import TYPE_CHECKING, Annotated, Any

import typer

from corrugate.cli import options as o
from corrugate.cli.console import fmt as _fmt
from corrugate.cli.console import make_console
from corrugate.core.parameters import PARAMETERS

if TYPE_CHECKING:
    from rich.console import Console

    from corrugate.analysis.evaluate import Analysis
    from corrugate.analysis.load_case import LoadCase
    from corrugate.materials.library import Material

__all__ = ["COMMANDS", "analyze_cmd", "materials_cmd"]


Opt = typer.Option


def _print_load_case(case: LoadCase, rows: list[dict[str, Any]], console: Console) -> None:
    from rich.table import Table

    from corrugate.mechanics.behaviours import get_load_case

    form = get_load_case(case.test).form
    over = (
        ""  # an in-plane test has no span: the panel's length along eta is compressed
        if form is not None and form.kind == "inplane"
        else (f" over {case.span:g} mm" if case.span is not None else " over the panel's length")
    )
    t = Table(
        title=f"load case: {case.test}, {case.load:g} N{over} (`corrugate docs load_cases`)",
        title_justify="left",
    )
    for col in ("eta deg", "span mm", "deflection mm", "P/delta N/mm"):
        t.add_column(col, justify="right")
    for row in rows:
        t.add_row(
            _fmt(row["eta_deg"]),
            _fmt(row["span_mm"]),
            _fmt(row["deflection_mm"], 5),
            _fmt(row["stiffness_N_per_mm"], 5),
        )
    console.print(t)
    for row in rows:  # the capacity along the creases (docs/load_cases.md 10)
        if "holds" in row:
            console.print(f"at {row['eta_deg']:g} deg: {row['holds']}", highlight=False)


def _print_analysis(r: Analysis, console: Console) -> None:
    from rich.table import Table

    from corrugate.geometry.holes import holes_text
    from corrugate.mechanics.moduli import get_model

    a = r.assembly
    console.print(f"[bold]model[/bold] {r.model}: {get_model(r.model).source}")
    t = Table(title="layers (t, W in mm; alpha in deg; moduli in MPa)", title_justify="left")
    for col in ("layer", "material", "t", "W", "n", "alpha", "Ecx", "Ecy", "Ebx", "Eby"):
        t.add_column(col, justify="right")
    for i, (layer, m) in enumerate(zip(a.layers, r.moduli, strict=True)):
        md = m.as_dict()
        t.add_row(
            str(i + 1),
            layer.material.id,
            _fmt(layer.t),
            _fmt(layer.W),
            str(layer.n),
            _fmt(layer.alpha_deg),
            *(_fmt(md[k]) for k in ("Ecx", "Ecy", "Ebx", "Eby")),
        )
    console.print(t)
    size = (
        f"L = {a.Lx:.2f} mm" if a.layout.equal_sides else f"Lx = {a.Lx:.2f} mm, Ly = {a.Ly:.2f} mm"
    )
    console.print(
        f"layout {a.layout.name}: {size}, folded thickness t_d = {a.thickness:.2f} mm, "
        f"mass = {r.mass.total:.3f} g (layers {r.mass.layer1:.3f} + "
        f"{r.mass.layer2:.3f} g, connectors {r.mass.connectors:.3f} g)"
    )
    if a.layout.holes:
        console.print(holes_text(a.layout.holes))
    s = Table(title="stiffness", title_justify="left")
    for col in ("eta deg", "K N/mm", "D N mm", "EI N mm^2", "EI mN m^2"):
        s.add_column(col, justify="right")
    for d in r.stiffness:
        s.add_row(_fmt(d.eta_deg), _fmt(d.K, 5), _fmt(d.D, 5), _fmt(d.EI, 5), f"{d.EI / 1000:.2f}")
    console.print(s)
    asked = {d.eta_deg for d in r.stiffness}
    for b in (b for b in r.buckling if b.eta_deg in asked):  # the directions the user asked for
        lo, hi = b.travel()
        console.print(
            f"compression along {b.eta_deg:g} deg: K holds until the end facets buckle, at "
            f"{b.low:.3g}-{b.high:.3g} N (platen travel {lo:.2g}-{hi:.2g} mm)"
        )
    from rich.markup import escape  # a message's [[table]] is text, not markup

    for w in r.warnings:
        console.print(f"[yellow]warning[/yellow] ({w.code}): {escape(w.message)}")


def _print_comparison(
    results: list[Analysis], console: Console, case: LoadCase | None = None
) -> None:
    from rich.table import Table

    t = Table(
        title="model variants side by side (layer 1 moduli, assembly stiffness)",
        title_justify="left",
    )
    t.add_column("quantity")
    for r in results:
        t.add_column(r.model, justify="right")
    for k in ("Ecx", "Ecy", "Ebx", "Eby"):
        t.add_row(f"{k} MPa", *(_fmt(r.moduli[0].as_dict()[k]) for r in results))
    for i, d in enumerate(results[0].stiffness):
        e = _fmt(d.eta_deg)
        t.add_row(f"K({e}) N/mm", *(_fmt(r.stiffness[i].K, 5) for r in results))
        t.add_row(f"D({e}) N mm", *(_fmt(r.stiffness[i].D, 5) for r in results))
        t.add_row(f"EI({e}) N mm^2", *(_fmt(r.stiffness[i].EI, 5) for r in results))
    if case is not None:
        from corrugate.analysis.load_case import load_case_rows

        per_model = [load_case_rows(r, case) for r in results]
        for i, d in enumerate(results[0].stiffness):
            e = _fmt(d.eta_deg)
            t.add_row(
                f"{case.test} delta({e}) mm at {case.load:g} N",
                *(_fmt(rows[i]["deflection_mm"], 5) for rows in per_model),
            )
    console.print(t)


@o.table_options(*o.DESIGN[:-1], "eta", "support", *o.LOAD_CASE)
def analyze_cmd(
    table: o.TableValues,
    eta: Annotated[
        list[str] | None,
        Opt(
            metavar=o.ANGLE,
            help="Direction (deg from layer 1's creases); repeat for several. Default 0 and 90.",
        ),
    ] = None,
    as_json: Annotated[bool, Opt("--json", help="Print one JSON object.")] = False,
    compare_models: Annotated[
        bool, Opt(help="Show the three model variants side by side.")
    ] = False,
    quiet: o.Quiet = False,
) -> None:
    """Stiffness, size, mass and warnings of one OADLC design.

    Example: corrugate analyze --W 8 --n 8 --alpha 84 --material dura-lar --model paper --eta 0

    With a load case: ... --test three-point --load 10N --span 40mm (docs/load_cases.md).
    """
    from corrugate.analysis.evaluate import analyze
    from corrugate.analysis.load_case import load_case_dict, load_case_of, load_case_rows
    from corrugate.mechanics.behaviours import check_support
    from corrugate.mechanics.moduli import MODELS, get_model
    from corrugate.spec.inputs import assembly_from_namespace, parse_etas

    assembly = assembly_from_namespace(table)
    etas = parse_etas(eta)
    model = table["model"]
    get_model(model)
    support = check_support(table["support"], PARAMETERS["support"].flag)
    case = load_case_of(table["test"], table["load"], table["span"])
    models = list(MODELS) if compare_models else [model]
    joint = table["joint"]
    results = [analyze(assembly, m, etas, support=support, joint=joint) for m in models]
    cases = [None if case is None else load_case_rows(r, case) for r in results]
    if as_json:
        dicts = []
        for r, rows in zip(results, cases, strict=True):
            d = r.to_dict()
            if case is not None and rows is not None:
                d["load_case"] = load_case_dict(case, rows)
            dicts.append(d)
        payload: object = (
            {"models": {r.model: d for r, d in zip(results, dicts, strict=True)}}
            if compare_models
            else dicts[0]
        )
        typer.echo(json.dumps(payload, indent=2))
        return
    if quiet:
        return
    console = make_console()
    if compare_models:
        _print_comparison(results, console, case)
        from rich.markup import escape  # a message's [[table]] is text, not markup

        for w in results[0].warnings:
            if w.code != "paper-model":
                console.print(f"[yellow]warning[/yellow] ({w.code}): {escape(w.message)}")
    else:
        _print_analysis(results[0], console)
        if case is not None and cases[0] is not None:
            _print_load_case(case, cases[0], console)


def materials_cmd(
    as_json: Annotated[bool, Opt("--json", help="Print the library as JSON.")] = False,
) -> None:
    """List the bundled material library."""
    from rich.table import Table

    from corrugate.materials.library import library

    lib = library()
    if as_json:
        typer.echo(json.dumps([m.as_dict() for m in lib.values()], indent=2))
        return
    t = Table(title="material library (src/corrugate/data/materials.toml)", title_justify="left")
    for col in (
        "id",
        "E GPa",
        "nu",
        "rho g/cm^3",
        "yield MPa",
        "t mm (default)",
        "sold in mm",
        "creep E_c GPa @ h",
    ):
        t.add_column(col)
    for m in lib.values():
        sold = f"{min(m.thicknesses):g}-{max(m.thicknesses):g}" if m.thicknesses else "-"
        t.add_row(
            m.id,
            f"{m.E / 1000:g}",
            f"{m.nu:g}",
            f"{m.density_g_cm3:g}",
            _fmt(m.yield_strength),
            _fmt(m.default_thickness),
            sold,
            _creep(m),
        )
    console = make_console()
    console.print(t)
    console.print("Names, every thickness and the sources: `corrugate materials --json`.")


def _creep(m: Material) -> str:
    """A material's creep moduli (GPa) at their durations (h), ``est.`` for an estimate
    (docs/load_cases.md section 11), ``-`` without creep data."""
    if m.creep is None:
        return "-"
    text = " ".join(
        f"{e / 1000:g}@{h:g}" for h, e in zip(m.creep.hours, m.creep.moduli, strict=True)
    )
    return text + (" est." if m.creep.estimate else "")


#: The commands of this module, by name (registered by :mod:`corrugate.cli`).
COMMANDS = {"analyze": analyze_cmd, "materials": materials_cmd}
