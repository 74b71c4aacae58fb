"""The command-line options that describe a design, declared once for every command that takes
them (``analyze``, ``pattern``, ``validate``): typer reads each ``Annotated`` alias below as the
option it declares. :func:`corrugate.spec.inputs.assembly_from_namespace` turns their values into an
:class:`~corrugate.geometry.layer.Assembly`.
"""

from __future__ import annotations

from typing import Annotated

import typer

__all__ = [
    "ANGLE",
    "FOLD_STYLES",
    "LAYOUTS",
    "LENGTH",
    "MODEL_CHOICES",
    "N2",
    "W2",
    "Alpha",
    "Alpha2",
    "Density",
    "Holes",
    "Labels",
    "Machine",
    "Material",
    "Material2",
    "N",
    "Nu",
    "Paper",
    "Quiet",
    "SupportOpt",
    "Thickness",
    "Thickness2",
    "Vertices",
    "W",
    "YoungsModulus",
]

Opt = typer.Option


def complete_materials(incomplete: str) -> list[str]:
    """Shell completion of a material option: the library's ids."""
    from corrugate.materials.library import library

    return [m for m in library() if m.startswith(incomplete)]


def complete_models(incomplete: str) -> list[str]:
    """Shell completion of ``--model``: the moduli variants."""
    from corrugate.names import MODEL_NAMES

    return [m for m in MODEL_NAMES if m.startswith(incomplete)]


def complete_layouts(incomplete: str) -> list[str]:
    """Shell completion of ``--layout``."""
    return [m for m in ("square", "rectangle", "circle", "polygon") if m.startswith(incomplete)]


def complete_machines(incomplete: str) -> list[str]:
    """Shell completion of ``--machine``/``--cutter`` (a laser takes its bed: ``laser:WxH``)."""
    names = ("cameo4-12x12", "cameo4-12x24", "maker-12x12", "maker-12x24", "laser:")
    return [m for m in names if m.startswith(incomplete)]


def complete_supports(incomplete: str) -> list[str]:
    """Shell completion of ``--support``."""
    return [m for m in ("free", "frame") if m.startswith(incomplete)]


W = Annotated[str, Opt("--W", metavar="LENGTH", help="Facet width (mm, or with units: '0.3 in').")]
N = Annotated[str, Opt("--n", metavar="INTEGER", help="Number of creases (n + 1 facets).")]
Alpha = Annotated[
    str, Opt("--alpha", metavar="ANGLE", help="Interior fold angle (deg, 180 = flat).")
]
Material = Annotated[
    str | None,
    Opt(
        metavar="MATERIAL",
        autocompletion=complete_materials,
        help="Library material id (see `corrugate materials`).",
    ),
]
Thickness = Annotated[
    str | None, Opt(metavar="LENGTH", help="Sheet thickness (mm); default: the material's.")
]
YoungsModulus = Annotated[
    str | None,
    Opt("--E", metavar="MODULUS", help="Inline material: Young's modulus (MPa or '2.7GPa')."),
]
Nu = Annotated[str | None, Opt("--nu", metavar="NUMBER", help="Inline material: Poisson's ratio.")]
Density = Annotated[str | None, Opt(metavar="DENSITY", help="Inline material: density (g/cm^3).")]
W2 = Annotated[
    str | None, Opt("--W2", metavar="LENGTH", help="Layer 2 facet width (default: layer 1's).")
]
N2 = Annotated[
    str | None, Opt("--n2", metavar="INTEGER", help="Layer 2 creases (default: layer 1's).")
]
Alpha2 = Annotated[
    str | None, Opt("--alpha2", metavar="ANGLE", help="Layer 2 fold angle (default: layer 1's).")
]
Material2 = Annotated[
    str | None,
    Opt(
        metavar="MATERIAL",
        autocompletion=complete_materials,
        help="Layer 2 library material (default: layer 1's).",
    ),
]
Thickness2 = Annotated[
    str | None, Opt(metavar="LENGTH", help="Layer 2 thickness (default: layer 1's).")
]
Vertices = Annotated[
    str | None,
    Opt(
        metavar="POINTS",
        help="Polygon outline, e.g. '0,0 1,0 0.5,1' (shape only; scaled to the layers).",
    ),
]
Machine = Annotated[
    str,
    Opt(
        "--machine",
        "--cutter",
        metavar="MACHINE",
        autocompletion=complete_machines,
        help="Machine and sheet: cameo4-12x12 | cameo4-12x24 (Silhouette Cameo 4: cut-N.dxf) | "
        "maker-12x12 | maker-12x24 (Cricut Maker: cut-N.svg) | laser:WxH (bed in mm: cut-N.svg "
        "and cut-N.dxf, hairlines).",
    ),
]
Labels = Annotated[
    bool | None,
    Opt(
        "--labels/--no-labels",
        help="Part names in the cut files too (drawn with a pen, engraved on a laser) / no labels "
        "anywhere. "
        "Default: on the fold map and the PDF only.",
        show_default=False,
    ),
]
SupportOpt = Annotated[
    str,
    Opt(
        "--support",
        metavar="[free|frame]",
        autocompletion=complete_supports,
        help="free (sides free: a bench test, most mounts; default) | frame (held in a rigid "
        "frame on all four edges: the paper's cos^2 rule). Matters off the crease directions.",
    ),
]

#: Output option of ``pattern`` and ``design``: the 1:1 tiles of the sheets for office paper.
Paper = Annotated[
    str,
    Opt(
        metavar="[mat|a4|letter]",
        help="mat: pattern.pdf, one mat-size page per sheet; a4 | letter: also pattern-a4.pdf / "
        "pattern-letter.pdf, the sheets at 1:1 on pages to tape together.",
    ),
]
Holes = Annotated[
    str | None,
    Opt(
        metavar="JSON",
        help="Inner cut-outs as JSON, mm from the layout's centre, e.g. "
        '\'[{"shape": "circle", "diameter": "6 mm", "center": [0, 0]}]\'.',
    ),
]

#: ``--quiet`` of the commands that print (design, analyze, pattern, validate, pareto, tolerance).
Quiet = Annotated[
    bool,
    Opt(
        "--quiet",
        "-q",
        help="Print nothing but errors (on stderr); files are still written, --json still "
        "printed, exit codes unchanged.",
    ),
]

#: Metavars shown in ``--help`` for options read as a quantity with an optional unit.
LENGTH = "LENGTH"  # '8', '8mm', '0.3 in'
ANGLE = "ANGLE"  # '84', '84deg', '1.47 rad'
LAYOUTS = "[square|rectangle|circle|polygon]"
MODEL_CHOICES = "[paper|xia|refined]"
FOLD_STYLES = "[solid|scored|perforated]"

Layout = Annotated[
    str,
    Opt(
        metavar=LAYOUTS,
        autocompletion=complete_layouts,
        help="Outline: square | rectangle | circle | polygon.",
    ),
]
Model = Annotated[
    str,
    Opt(
        metavar=MODEL_CHOICES,
        autocompletion=complete_models,
        help="Moduli variant: paper | xia | refined (the one design.json records).",
    ),
]
