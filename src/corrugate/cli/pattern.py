"""``corrugate pattern``: the cut files, FOLD, 3D model and assembly steps of a given design."""

from __future__ import annotations

import json
from typing import Annotated

import typer

from corrugate.cli import options as o
from corrugate.cli.console import make_console
from corrugate.core.parameters import PARAMETERS

__all__ = ["COMMANDS", "pattern_cmd"]

Opt = typer.Option


@o.table_options("W", "n", "alpha", "out", *o.DESIGN[3:], *o.OUTPUT)
def pattern_cmd(
    table: o.TableValues,
    out: Annotated[
        str, Opt("--out", metavar="DIR", help="Folder for the files (created if missing).")
    ],
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

    assembly = assembly_from_namespace(table)
    model = table["model"]
    get_model(model)
    opts = output_options(**{k: table[k] for k in o.OUTPUT})  # the table's names are its keywords
    result = analyze(
        assembly,
        model,
        (0.0, 90.0),
        opts.fabrication,
        check_support(table["support"], PARAMETERS["support"].flag),
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
        console.print(f"wrote {p}", markup=False)


#: The commands of this module, by name (registered by :mod:`corrugate.cli`).
COMMANDS = {"pattern": pattern_cmd}
