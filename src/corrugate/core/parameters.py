"""The parameters a user gives to describe one design and its output files, declared once.

:data:`PARAMETERS` holds one :class:`Parameter` per option: its name (the keyword of
:func:`corrugate.spec.inputs.assembly_from_options` and the field of the JSON API), its command-line
flags and metavar, its internal unit, default and kind, its one help text and the key of
:data:`corrugate.core.limits.LIMITS` that bounds it. Every surface is made from it:

* the command line's options of ``analyze``, ``pattern``, ``validate`` and ``design``
  (:mod:`corrugate.cli.options` builds each typer option from its entry), ``analyze``'s load
  case among them (:data:`LOAD_CASE_PARAMETERS`);
* the design fields of the web API's request bodies (:mod:`corrugate.web.schemas`: each field's
  default and description);
* the spec reference (:data:`corrugate.spec.reference.KEYS`), where a spec key is the same
  parameter (an inline material's ``E``, ``nu`` and ``density``, ``model``, ``layout.shape``).

This module imports only :mod:`corrugate.names` (no numpy, no typer, no pydantic), so that the
command line can declare its options at start-up.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

from corrugate.names import (
    DEFAULT_FOLD_STYLE,
    DEFAULT_LAYOUT,
    DEFAULT_MACHINE,
    DEFAULT_MARGIN_MM,
    DEFAULT_MODEL,
    DEFAULT_PAPER,
    DEFAULT_SPACING_MM,
    DEFAULT_SUPPORT,
    DEFAULT_TAB_DEPTH_MM,
    FOLD_OP_NAMES,
    FOLD_STYLES,
    JOINTS,
    LASER,
    LAYOUT_SHAPES,
    LOAD_CASES,
    MACHINE_NAMES,
    MODEL_NAMES,
    PAPER_NAMES,
    SUPPORTS,
)

__all__ = [
    "DESIGN_PARAMETERS",
    "LOAD_CASE_PARAMETERS",
    "OUTPUT_PARAMETERS",
    "PARAMETERS",
    "Kind",
    "Parameter",
    "choices_metavar",
]

#: How a value is written: a ``quantity`` is a number in ``unit`` or a string with units
#: (``'0.3 in'``), an ``integer`` a whole number, a ``name`` one of ``choices``, ``text`` free text
#: read by its own parser (a material id, vertices, JSON), a ``flag`` an on/off switch.
Kind = Literal["quantity", "integer", "name", "text", "flag"]


@dataclass(frozen=True, slots=True)
class Parameter:
    """One user option.

    ``name``: keyword and JSON field; ``flags``: the command line's spellings (``--W``;
    ``--labels/--no-labels`` for a flag); ``metavar``: what ``--help`` shows for the value (None for
    a flag); ``unit``: the internal unit a plain number is read in ("" for none); ``default``: the
    value taken when it is not given, as the command line shows it (None: not given; ignored when
    ``required``); ``kind``: see :data:`Kind`; ``help``: the one help text of every surface;
    ``limits``: the key of :data:`corrugate.core.limits.LIMITS` that bounds the value (None: none
    of them); ``choices``: the allowed names of a ``name`` (empty: any; a ``name`` without a
    default is one that may be left out)."""

    name: str
    flags: tuple[str, ...]
    metavar: str | None
    unit: str
    default: str | None
    kind: Kind
    help: str
    limits: str | None = None
    choices: tuple[str, ...] = ()
    required: bool = False

    @property
    def flag(self) -> str:
        """The first command-line spelling, without a flag's ``/--no-...`` half."""
        return self.flags[0].split("/")[0]


def choices_metavar(choices: tuple[str, ...]) -> str:
    """``[a|b|c]``: how ``--help`` shows an option that takes one of ``choices``."""
    return "[" + "|".join(choices) + "]"


def _layer2(p: Parameter, flag: str, help_text: str) -> Parameter:
    """Layer 2's variant of layer 1's ``p`` (``flag``: ``--W2`` for ``--W``), never required."""
    return Parameter(
        flag.removeprefix("--"),
        (flag,),
        p.metavar,
        p.unit,
        None,
        p.kind,
        help_text,
        p.limits,
        p.choices,
    )


_W = Parameter(
    "W",
    ("--W",),
    "LENGTH",
    "mm",
    None,
    "quantity",
    "Facet width (mm, or with units: '0.3 in').",
    "W",
    required=True,
)
_N = Parameter(
    "n",
    ("--n",),
    "INTEGER",
    "",
    None,
    "integer",
    "Number of creases (n + 1 facets).",
    "n",
    required=True,
)
_ALPHA = Parameter(
    "alpha",
    ("--alpha",),
    "ANGLE",
    "deg",
    None,
    "quantity",
    "Interior fold angle (deg, 180 = flat; or '1.4 rad').",
    "alpha",
    required=True,
)
_MATERIAL = Parameter(
    "material",
    ("--material",),
    "MATERIAL",
    "",
    None,
    "text",
    "Library material id (see `corrugate materials`, or GET /api/materials).",
)
_THICKNESS = Parameter(
    "thickness",
    ("--thickness",),
    "LENGTH",
    "mm",
    None,
    "quantity",
    "Sheet thickness (mm); default: the material's.",
    "thickness",
)

#: The options that describe one design (``corrugate analyze``, ``pattern``, ``validate``; the
#: web API's ``/api/analyze``, ``/api/mesh`` and ``/api/pattern``), in the order ``--help`` lists
#: them.
DESIGN_PARAMETERS: tuple[Parameter, ...] = (
    _W,
    _N,
    _ALPHA,
    _MATERIAL,
    _THICKNESS,
    Parameter(
        "E",
        ("--E",),
        "MODULUS",
        "MPa",
        None,
        "quantity",
        "Inline material: Young's modulus (MPa or '2.7GPa').",
        "E",
    ),
    Parameter(
        "nu",
        ("--nu",),
        "NUMBER",
        "",
        None,
        "quantity",
        "Inline material: Poisson's ratio (-1 < nu < 0.5).",
        "nu",
    ),
    Parameter(
        "density",
        ("--density",),
        "DENSITY",
        "g/cm^3",
        None,
        "quantity",
        "Inline material: density (g/cm^3).",
        "density",
    ),
    _layer2(_W, "--W2", "Layer 2 facet width (default: layer 1's)."),
    _layer2(_N, "--n2", "Layer 2 creases (default: layer 1's)."),
    _layer2(_ALPHA, "--alpha2", "Layer 2 fold angle (default: layer 1's)."),
    _layer2(_MATERIAL, "--material2", "Layer 2 library material (default: layer 1's)."),
    _layer2(_THICKNESS, "--thickness2", "Layer 2 thickness (default: layer 1's)."),
    Parameter(
        "layout",
        ("--layout",),
        choices_metavar(LAYOUT_SHAPES),
        "",
        DEFAULT_LAYOUT,
        "name",
        # no "|" in it: it is also a cell of the spec reference's Markdown table
        "Outline: " + ", ".join(LAYOUT_SHAPES[:-1]) + " or " + LAYOUT_SHAPES[-1] + ".",
        choices=LAYOUT_SHAPES,
    ),
    Parameter(
        "vertices",
        ("--vertices",),
        "POINTS",
        "",
        None,
        "text",
        "Polygon outline, e.g. '0,0 1,0 0.5,1' (shape only; scaled to the layers).",
    ),
    Parameter(
        "holes",
        ("--holes",),
        "JSON",
        "mm",
        None,
        "text",
        "Inner cut-outs as JSON, mm from the layout's centre, e.g. "
        '\'[{"shape": "circle", "diameter": "6 mm", "center": [0, 0]}]\'.',
    ),
    Parameter(
        "model",
        ("--model",),
        choices_metavar(MODEL_NAMES),
        "",
        DEFAULT_MODEL,
        "name",
        "Moduli variant: 'refined' (default, this project's), 'xia' (Xia et al. 2012) or "
        "'paper' (Liu, Yan and Mehta, with its known errors; for reproducing Table 1).",
        choices=MODEL_NAMES,
    ),
    Parameter(
        "support",
        ("--support",),
        choices_metavar(SUPPORTS),
        "",
        DEFAULT_SUPPORT,
        "name",
        "free (sides free: a bench test, most mounts; default) | frame (held in a rigid "
        "frame on all four edges: the paper's cos^2 rule). Matters off the crease directions.",
        choices=SUPPORTS,
    ),
)

#: The options of a design's files (``corrugate pattern``, ``design --out``; the web API's
#: ``/api/pattern`` and ``/api/design`` take those it has fields for), lengths in mm.
OUTPUT_PARAMETERS: tuple[Parameter, ...] = (
    Parameter(
        "cutter",
        ("--machine", "--cutter"),
        "MACHINE",
        "",
        DEFAULT_MACHINE,
        "name",
        "Machine and sheet: cameo4-12x12 | cameo4-12x24 (Silhouette Cameo 4: cut-N.dxf) | "
        "maker-12x12 | maker-12x24 (Cricut Maker: cut-N.svg) | laser:WxH (bed in mm: cut-N.svg "
        "and cut-N.dxf, hairlines). For design: overrides the spec's [fabrication] machine, and "
        "every cut part must fit it in the solve.",
        choices=(*MACHINE_NAMES, LASER),
    ),
    Parameter(
        "labels",
        ("--labels/--no-labels",),
        None,
        "",
        None,
        "flag",
        "Part names (L1, L2, B1, ...: the names the assembly steps use) on every cut part "
        "(drawn by the pen, engraved on a laser), the fold map and the PDF / no labels "
        "anywhere. Default: on.",
    ),
    Parameter(
        "fold_style",
        ("--fold-style",),
        choices_metavar(FOLD_STYLES),
        "",
        DEFAULT_FOLD_STYLE,
        "name",
        "Fold lines in the cut files: machine (the machine's default for the sheet: mountains "
        "perforated, valleys cut-scored or scored, band marks drawn) | solid (creases left out) | "
        "scored | perforated (needs --cut and --gap).",
        choices=FOLD_STYLES,
    ),
    Parameter(
        "mountain",
        ("--mountain",),
        choices_metavar(FOLD_OP_NAMES),
        "",
        None,
        "name",
        "What the machine does with the mountain creases: "
        + " | ".join(FOLD_OP_NAMES)
        + " (default: the --fold-style's).",
        choices=FOLD_OP_NAMES,
    ),
    Parameter(
        "valley",
        ("--valley",),
        choices_metavar(FOLD_OP_NAMES),
        "",
        None,
        "name",
        "What the machine does with the valley creases: "
        + " | ".join(FOLD_OP_NAMES)
        + " (default: the --fold-style's).",
        choices=FOLD_OP_NAMES,
    ),
    Parameter(
        "marks",
        ("--marks",),
        choices_metavar(FOLD_OP_NAMES),
        "",
        None,
        "name",
        "What the machine does with the band's angle marks: "
        + " | ".join(FOLD_OP_NAMES)
        + " (default: the --fold-style's).",
        choices=FOLD_OP_NAMES,
    ),
    Parameter("cut", ("--cut",), "LENGTH", "mm", None, "quantity", "Perforation: cut length (mm)."),
    Parameter("gap", ("--gap",), "LENGTH", "mm", None, "quantity", "Perforation: gap length (mm)."),
    Parameter(
        "spacing",
        ("--spacing",),
        "LENGTH",
        "mm",
        f"{DEFAULT_SPACING_MM:g}",
        "quantity",
        "Space between parts on the sheet (mm).",
    ),
    Parameter(
        "margin",
        ("--margin",),
        "LENGTH",
        "mm",
        f"{DEFAULT_MARGIN_MM:g}",
        "quantity",
        "Margin to the sheet's edge (mm).",
    ),
    Parameter(
        "tab_depth",
        ("--tab-depth",),
        "LENGTH",
        "mm",
        f"{DEFAULT_TAB_DEPTH_MM:g}",
        "quantity",
        "Depth of the connector's glue tabs (mm).",
    ),
    Parameter(
        "paper",
        ("--paper",),
        choices_metavar(PAPER_NAMES),
        "",
        DEFAULT_PAPER,
        "name",
        "mat: pattern.pdf, one mat-size page per sheet; a4 | letter: also "
        "pattern-a4.pdf / pattern-letter.pdf, the sheets at 1:1 on pages to tape together.",
        choices=PAPER_NAMES,
    ),
)

#: The load case of ``corrugate analyze`` (docs/load_cases.md): the test, its load (N) and its
#: span (mm); none given: no load case.
LOAD_CASE_PARAMETERS: tuple[Parameter, ...] = (
    Parameter(
        "test",
        ("--test",),
        choices_metavar(LOAD_CASES),
        "",
        None,
        "name",
        "Load case (`corrugate docs load_cases`): "
        + ", ".join(LOAD_CASES[:-1])
        + " or "
        + LOAD_CASES[-1]
        + "; prints the deflection under --load and P/delta at each --eta.",
        choices=LOAD_CASES,
    ),
    Parameter(
        "load",
        ("--load",),
        "FORCE",
        "N",
        None,
        "quantity",
        "The load case's load (N, or '2 lbf'); needs --test.",
        "load",
    ),
    Parameter(
        "span",
        ("--span",),
        "LENGTH",
        "mm",
        None,
        "quantity",
        "The test's support spacing (cantilever: its free length; mm); default and at most the "
        "panel's length along eta; none between platens.",
        "length",
    ),
    Parameter(
        "joint",
        ("--joint",),
        choices_metavar(JOINTS),
        "",
        "none",
        "name",
        "How the layers are joined: none (default: the band left out, the outermost facets' "
        "edges free) | band-edges | band-flanges (the band bonded: its walls counted, the edges "
        "held); docs/load_cases.md 7 and 10.",
        choices=JOINTS,
    ),
)

#: Every parameter by name.
PARAMETERS: dict[str, Parameter] = {
    p.name: p for p in (*DESIGN_PARAMETERS, *OUTPUT_PARAMETERS, *LOAD_CASE_PARAMETERS)
}
