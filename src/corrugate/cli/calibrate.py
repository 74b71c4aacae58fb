"""``corrugate calibrate``: measure your own sheet (``kit``), fit its E and crease (``fit``)
(`corrugate docs calibration`)."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Annotated

import typer

from corrugate.cli import options as o
from corrugate.core.parameters import PARAMETERS

__all__ = ["COMMANDS", "calibrate_app", "fit_cmd", "kit_cmd"]

Opt = typer.Option

calibrate_app = typer.Typer(
    name="calibrate",
    help="Measure your own sheet with coins and a ruler: a cut kit, then the fit of E and the "
    "creases (`corrugate docs calibration`).",
    no_args_is_help=True,
    pretty_exceptions_enable=False,
)


@calibrate_app.command("kit")
@o.table_options("material", "thickness", "out", "cutter", "coin")
def kit_cmd(
    table: o.TableValues,
    out: Annotated[
        str, Opt("--out", metavar="DIR", help="Folder for the kit (created if missing).")
    ],
    coin: Annotated[
        str, Opt("--coin", metavar="MASS", help="The mass of one of your coins (g).")
    ] = "5 g",
    quiet: o.Quiet = False,
) -> None:
    """Write the cut files, protocol (Markdown and PDF) and measurements template of a
    calibration kit (--material, the library's sheet; --thickness, default the material's).

    Example: corrugate calibrate kit --material dura-lar --thickness 0.125mm --out kit
    """
    from corrugate.calibration.kit import write_kit
    from corrugate.core.errors import InputError
    from corrugate.core.units import parse_quantity
    from corrugate.materials.library import get_material

    if table["material"] is None:
        raise InputError(
            PARAMETERS["material"].flag,
            None,
            "a library material (corrugate materials)",
            reason="is missing",
        )
    mat = get_material(table["material"])
    given = table["thickness"]
    t = (
        mat.default_thickness
        if given is None
        else parse_quantity(given, "mm", PARAMETERS["thickness"].flag)
    )
    if t is None:
        raise InputError(
            PARAMETERS["thickness"].flag,
            None,
            "a sheet thickness such as 0.125mm",
            reason="is missing",
        )
    if not 0.0 < t <= 5.0:
        raise InputError(PARAMETERS["thickness"].flag, f"{t:g} mm", "0 < thickness <= 5 mm")
    kit, paths = write_kit(mat, t, table["cutter"], out, parse_quantity(coin, "g", "--coin"))
    if quiet:
        return
    for f in kit.flat:
        typer.echo(
            f"{f.name} ({f.direction}): free {f.overhang:g} mm, sag ~{f.sag_alone:.0f} mm; "
            f"free {f.coin_overhang:g} mm with {f.coins} coin(s), sag ~{f.sag_coins:.0f} mm"
        )
    c = kit.crease
    typer.echo(
        f"{c.name}: {c.creases} creases folded to {c.angle:g} deg, loads of {', '.join(map(str, c.coins))} "
        f"coins"
    )
    for p in paths:
        typer.echo(f"wrote {p}")


@calibrate_app.command("fit")
def fit_cmd(
    measurements: Annotated[
        Path, typer.Argument(metavar="MEASUREMENTS", help="The filled-in measurements.toml.")
    ],
    save: Annotated[
        bool, Opt("--save", help="Add the fitted material to your materials file.")
    ] = False,
    materials: Annotated[
        Path | None,
        Opt(
            "--materials",
            metavar="FILE",
            help="The materials file --save writes (default: materials.toml in your config "
            "folder; corrugate-materials.toml beside a spec serves that spec's folder).",
        ),
    ] = None,
    plot: Annotated[
        Path | None,
        Opt(
            "--plot",
            metavar="FILE",
            help="The figure of readings against the model (default: fit.png beside MEASUREMENTS).",
        ),
    ] = None,
    seed: Annotated[int, Opt("--seed", help="The bootstrap's random seed.")] = 0,
    as_json: Annotated[bool, Opt("--json", help="Print the fit as JSON.")] = False,
    quiet: o.Quiet = False,
) -> None:
    """Fit E (each direction), the crease stiffness and the springback to your readings, with
    90 % intervals; print them with the residuals and draw readings against the model.

    Example: corrugate calibrate fit kit/measurements.toml --save
    """
    from corrugate.calibration.entry import material_entry, summary
    from corrugate.calibration.fit import fit_measurements
    from corrugate.calibration.measurements import load_measurements
    from corrugate.calibration.plot import fit_figure
    from corrugate.core.fileio import atomic_write
    from corrugate.core.plotting import png_bytes
    from corrugate.materials.user import CONFIG_FILE, config_dir, existing_text, write_entry

    m = load_measurements(measurements)
    target = materials if materials is not None else config_dir() / CONFIG_FILE
    if save:  # a materials file that cannot be read is named before the fit and the figure
        existing_text(target, "--materials" if materials is not None else "materials file")
    fit = fit_measurements(m, seed=seed)
    figure_path = plot if plot is not None else measurements.parent / "fit.png"
    atomic_write(figure_path, png_bytes(fit_figure(fit)), "--plot")
    entry = material_entry(fit)
    saved = None
    if save:
        field = "--materials" if materials is not None else "materials file"
        saved = write_entry(target, m.name, entry, field)
    if as_json:

        def num(x: float) -> float | None:
            return None if math.isinf(x) else x

        typer.echo(
            json.dumps(
                {
                    "material": m.name,
                    "moduli": [
                        {
                            "direction": f.direction,
                            "E_MPa": f.E,
                            "E_90_MPa": [f.lo, f.hi],
                            "n": f.n,
                            "residuals_mm": list(f.residuals),
                        }
                        for f in fit.moduli
                    ],
                    "crease": None
                    if fit.crease is None
                    else {
                        "k_N_per_rad": num(fit.crease.k),
                        "k_90_N_per_rad": [num(fit.crease.k_lo), num(fit.crease.k_hi)],
                        "angle_deg": fit.crease.angle,
                        "springback_deg": fit.crease.springback,
                    },
                    "entry": entry,
                    "plot": str(figure_path),
                    "saved": None if saved is None else str(saved),
                },
                indent=2,
            )
        )
        return
    if quiet:
        return
    for line in summary(fit):
        typer.echo(line)
    typer.echo(f"wrote {figure_path}")
    if saved is not None:
        typer.echo(
            f'saved material {m.name!r} to {saved}; a spec names it as [material] name = "{m.name}"'
        )
    else:
        typer.echo("(--save adds it to your materials file)")


#: The commands of this module, by name (registered by :mod:`corrugate.cli`): a group.
COMMANDS = {"calibrate": calibrate_app}
