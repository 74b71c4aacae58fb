"""``corrugate pattern``: the cut files, FOLD, 3D model and assembly steps of a given design."""

from __future__ import annotations

import json
from typing import Annotated

import typer

from corrugate.cli import options as o
from corrugate.cli.console import make_console
from corrugate.names import DEFAULT_MODEL

__all__ = ["COMMANDS", "pattern_cmd"]

Opt = typer.Option


def pattern_cmd(
    W: o.W,
    n: o.N,
    alpha: o.Alpha,
    out: Annotated[
        str, Opt("--out", metavar="DIR", help="Folder for the files (created if missing).")
    ],
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
    layout: o.Layout = "square",
    vertices: o.Vertices = None,
    holes: o.Holes = None,
    model: o.Model = DEFAULT_MODEL,
    support: o.SupportOpt = "free",
    cutter: o.Machine = "cameo4-12x12",
    labels: o.Labels = None,
    fold_style: Annotated[
        str, Opt(metavar=o.FOLD_STYLES, help="Fold lines: solid | scored | perforated.")
    ] = "solid",
    cut: Annotated[str | None, Opt(metavar=o.LENGTH, help="Perforation: cut length (mm).")] = None,
    gap: Annotated[str | None, Opt(metavar=o.LENGTH, help="Perforation: gap length (mm).")] = None,
    spacing: Annotated[
        str, Opt(metavar=o.LENGTH, help="Space between parts on the sheet (mm).")
    ] = "5",
    margin: Annotated[str, Opt(metavar=o.LENGTH, help="Margin to the sheet's edge (mm).")] = "5",
    tab_depth: Annotated[
        str, Opt(metavar=o.LENGTH, help="Depth of the connector's glue tabs (mm).")
    ] = "4",
    paper: o.Paper = "mat",
    as_json: Annotated[bool, Opt("--json", help="Print design.json's summary as JSON.")] = False,
    quiet: o.Quiet = False,
) -> None:
    """Write the machine's cut files, the fold map, the PDF, FOLD, GLB/STL and assembly steps of one
    design (`corrugate docs fabrication`)."""
    from corrugate.analysis.evaluate import analyze
    from corrugate.mechanics.behaviours import check_support
    from corrugate.mechanics.moduli import get_model
    from corrugate.spec.inputs import assembly_from_namespace
    from corrugate.workflow import output_options, write_design_files

    assembly = assembly_from_namespace(locals())
    get_model(model)
    opts = output_options(cutter, fold_style, cut, gap, spacing, margin, tab_depth, labels, paper)
    result = analyze(
        assembly, model, (0.0, 90.0), opts.fabrication, check_support(support, "--support")
    )
    paths = write_design_files(result, out, opts)
    if as_json:
        typer.echo(
            json.dumps(
                {
                    "out": str(out),
                    "files": [p.name for p in paths],
                    "mass_g": result.mass.as_dict(),
                },
                indent=2,
            )
        )
        return
    if quiet:
        return
    console = make_console()
    m = result.mass
    console.print(
        f"mass {m.total:.3f} g: layers {m.layer1:.3f} + {m.layer2:.3f} g, connectors "
        f"{m.connectors:.3f} g (rho t x cut area)"
    )
    for p in paths:
        console.print(f"wrote {p}")


#: The commands of this module, by name (registered by :mod:`corrugate.cli`).
COMMANDS = {"pattern": pattern_cmd}
