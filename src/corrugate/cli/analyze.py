"""``corrugate analyze`` and ``corrugate materials``: one design's stiffness, and the library.

``analyze --test T --load P [--span Ls]`` also states a load case (docs/load_cases.md): at each
direction asked, the deflection delta (mm) of the test ``T`` under the load P (N) and the test's
P / delta (N/mm), from the support's D or K, the layers' shear springs and the panel's length
along eta (:func:`load_case_rows`).
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Annotated

import typer

from corrugate.cli import options as o
from corrugate.cli.console import fmt as _fmt
from corrugate.cli.console import make_console
from corrugate.core.errors import InputError, UnknownNameError
from corrugate.core.parameters import PARAMETERS
from corrugate.names import DEFAULT_LAYOUT, DEFAULT_MODEL, DEFAULT_SUPPORT, LOAD_CASES

if TYPE_CHECKING:
    from rich.console import Console

    from corrugate.analysis.evaluate import Analysis

__all__ = [
    "COMMANDS",
    "LoadCase",
    "analyze_cmd",
    "load_case_dict",
    "load_case_of",
    "load_case_rows",
    "materials_cmd",
]

Opt = typer.Option


@dataclass(frozen=True, slots=True)
class LoadCase:
    """A load case of ``analyze``: the test's name, the load (N) and the span (mm; None: the
    panel's length along each eta, and always None between platens)."""

    test: str
    load: float
    span: float | None = None


def _flag(name: str) -> str:
    return PARAMETERS[name].flag


def load_case_of(test: str | None, load: str | None, span: str | None) -> LoadCase | None:
    """The load case the options ``--test``, ``--load`` and ``--span`` state (None when none is
    given); :class:`InputError` naming the option at fault: a load or a span without a test, a
    test without a load, an unknown test, a load or span that is not > 0, a span between
    platens."""
    from corrugate.core.limits import LIMITS, abnormal_reason
    from corrugate.core.units import parse_quantity

    if test is None:
        for name, value in (("load", load), ("span", span)):
            if value is not None:
                raise InputError(
                    _flag(name),
                    value,
                    f"only with {_flag('test')} ({', '.join(LOAD_CASES)})",
                    reason=f"is given without {_flag('test')}",
                )
        return None
    if test not in LOAD_CASES:
        raise UnknownNameError(_flag("test"), test, LOAD_CASES)
    if load is None:
        raise InputError(
            _flag("load"),
            "not given",
            "a load in N (e.g. 10 or '2 lbf')",
            reason=f"is required with {_flag('test')}",
        )

    def positive(name: str, value: str, unit: str, limit: str) -> float:
        x = parse_quantity(value, unit, _flag(name))
        hi = LIMITS[limit].hi
        if not 0.0 < x <= hi:
            reason = abnormal_reason(x) or "is out of range"
            raise InputError(
                _flag(name), f"{x:g} {unit}", f"> 0 {unit} and <= {hi:g} {unit}", reason=reason
            )
        return x

    P = positive("load", load, "N", "load")
    if span is None:
        return LoadCase(test, P)
    if test == "platens":
        raise InputError(
            _flag("span"),
            span,
            "no span for platens (the panel's length along eta is compressed)",
            reason="does not apply",
        )
    return LoadCase(test, P, positive("span", span, "mm", "length"))


def load_case_rows(r: Analysis, case: LoadCase) -> list[dict[str, float]]:
    """For each direction of ``r``: the span Ls (mm; platens: the length compressed), the
    deflection (mm) of ``case`` under its load and the test's P / delta (N/mm), by
    :func:`corrugate.mechanics.load_cases.load_stiffness` (docs/load_cases.md, sections 1-3):
    the support's D (bending tests, EI = D L over the panel's length L along eta, the layers'
    shear spring V and depth h at eta) or K (platens). :class:`InputError` naming ``--span``
    where it is longer than the panel, and ``--test`` for a layout without straight edges."""
    from corrugate.mechanics.behaviours import get_load_case
    from corrugate.mechanics.load_cases import load_stiffness, shear_and_depth
    from corrugate.mechanics.offaxis import _cs

    layout = r.assembly.layout
    if layout.name not in ("square", "rectangle"):
        raise InputError(
            _flag("test"),
            f"{case.test} on layout {layout.name}",
            "a square or rectangle layout",
            reason="has no straight edges to support or load",
        )
    form = get_load_case(case.test).form
    assert form is not None
    rows = []
    for st in r.stiffness:
        if case.span is not None and case.span > st.span:
            raise InputError(
                _flag("span"),
                f"{case.span:g} mm",
                f"at most the panel's length along eta = {st.eta_deg:g} deg, {st.span:.6g} mm",
            )
        if form.kind == "inplane":
            k = float(load_stiffness(form, st.K, None, None, st.span))
            Ls = st.span
        else:
            V, h = shear_and_depth(r.springs, *_cs(st.eta_deg))
            k = float(load_stiffness(form, st.D, float(V), float(h), st.span, case.span))
            Ls = st.span if case.span is None else case.span
        if not (math.isfinite(k) and k > 0):
            raise InputError("body", f"P/delta = {k}", "a positive stiffness", reason="is not")
        rows.append(
            {
                "eta_deg": st.eta_deg,
                "span_mm": Ls,
                "deflection_mm": case.load / k,
                "stiffness_N_per_mm": k,
            }
        )
    return rows


def load_case_dict(case: LoadCase, rows: list[dict[str, float]]) -> dict[str, object]:
    """The ``load_case`` object of ``analyze --json``."""
    return {
        "test": case.test,
        "load_N": case.load,
        "span_mm": case.span,
        "directions": rows,
    }


def _print_load_case(case: LoadCase, rows: list[dict[str, float]], console: Console) -> None:
    from rich.table import Table

    over = (
        ""
        if case.test == "platens"
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
    for b in r.buckling:
        lo, hi = b.travel()
        console.print(
            f"compression along {b.eta_deg:g} deg: K holds until the end facets buckle, at "
            f"{b.low:.3g}-{b.high:.3g} N (platen travel {lo:.2g}-{hi:.2g} mm)"
        )
    for w in r.warnings:
        console.print(f"[yellow]warning[/yellow] ({w.code}): {w.message}")


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
        per_model = [load_case_rows(r, case) for r in results]
        for i, d in enumerate(results[0].stiffness):
            e = _fmt(d.eta_deg)
            t.add_row(
                f"{case.test} delta({e}) mm at {case.load:g} N",
                *(_fmt(rows[i]["deflection_mm"], 5) for rows in per_model),
            )
    console.print(t)


def analyze_cmd(
    W: o.W,
    n: o.N,
    alpha: o.Alpha,
    material: o.Material = None,
    thickness: o.Thickness = None,
    E: o.YoungsModulus = None,
    nu: o.Nu = None,
    density: o.Density = None,
    W2: o.W2 = None,
    n2: o.N2 = None,
    alpha2: o.Alpha2 = None,
    material2: o.Material2 = None,
    thickness2: o.Thickness2 = None,
    layout: o.Layout = DEFAULT_LAYOUT,
    vertices: o.Vertices = None,
    holes: o.Holes = None,
    model: o.Model = DEFAULT_MODEL,
    eta: Annotated[
        list[str] | None,
        Opt(
            metavar=o.ANGLE,
            help="Direction (deg from layer 1's creases); repeat for several. Default 0 and 90.",
        ),
    ] = None,
    support: o.SupportOpt = DEFAULT_SUPPORT,
    test: o.TestOpt = None,
    load: o.LoadOpt = None,
    span: o.SpanOpt = None,
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
    from corrugate.mechanics.behaviours import check_support
    from corrugate.mechanics.moduli import MODELS, get_model
    from corrugate.spec.inputs import assembly_from_namespace, parse_etas

    assembly = assembly_from_namespace(locals())
    etas = parse_etas(eta)
    get_model(model)
    support = check_support(support, PARAMETERS["support"].flag)
    case = load_case_of(test, load, span)
    models = list(MODELS) if compare_models else [model]
    results = [analyze(assembly, m, etas, support=support) for m in models]
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
        for w in results[0].warnings:
            if w.code != "paper-model":
                console.print(f"[yellow]warning[/yellow] ({w.code}): {w.message}")
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
    for col in ("id", "E GPa", "nu", "rho g/cm^3", "yield MPa", "t mm (default)", "sold in mm"):
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
        )
    console = make_console()
    console.print(t)
    console.print("Names, every thickness and the sources: `corrugate materials --json`.")


#: The commands of this module, by name (registered by :mod:`corrugate.cli`).
COMMANDS = {"analyze": analyze_cmd, "materials": materials_cmd}
