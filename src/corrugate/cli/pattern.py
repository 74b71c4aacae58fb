"""``corrugate pattern``: the cut files, FOLD, 3D model and assembly steps of a given design."""

from __future__ import annotations

import json
from typing import Annotated

import typer

from corrugate.cli import options as o
from corrugate.cli.console import make_console
from corrugate.core.parameters import PARAMETERS
from corrugate.names import (
    DEFAULT_FOLD_STYLE,
    DEFAULT_LAYOUT,
    DEFAULT_MACHINE,
    DEFAULT_MODEL,
    DEFAULT_PAPER,
    DEFAULT_SUPPORT,
)

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
    layout: o.Layout = DEFAULT_LAYOUT,
    vertices: o.Vertices = None,
    holes: o.Holes = None,
    model: o.Model = DEFAULT_MODEL,
    support: o.SupportOpt = DEFAULT_SUPPORT,
    cutter: o.Machine = DEFAULT_MACHINE,
    labels: o.Labels = None,
    fold_style: o.FoldStyle = DEFAULT_FOLD_STYLE,
    mountain: o.Mountain = None,
    valley: o.Valley = None,
    marks: o.Marks = None,
    cut: o.Cut = None,
    gap: o.Gap = None,
    spacing: o.Spacing = o.DEFAULT_SPACING,
    margin: o.Margin = o.DEFAULT_MARGIN,
    tab_depth: o.TabDepth = o.DEFAULT_TAB_DEPTH,
    paper: o.Paper = DEFAULT_PAPER,
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
    opts = output_options(
        cutter,
        fold_style,
        cut,
        gap,
        spacing,
        margin,
        tab_depth,
        labels,
        paper,
        mountain=mountain,
        valley=valley,
        marks=marks,
    )
    result = analyze(
        assembly,
        model,
        (0.0, 90.0),
        opts.fabrication,
        check_support(support, PARAMETERS["support"].flag),
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
