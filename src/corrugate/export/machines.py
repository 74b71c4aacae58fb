"""Machine profiles: which cut-ready files each machine gets, and how each operation is drawn.

A cut-ready file holds only what the machine should do, because Silhouette Studio, Cricut Design
Space and LightBurn cut every imported line unless the user changes its action, and cut a path
whole whatever its dash style (docs/theory.md section 7). Every path is real geometry on a layer
(DXF) or group (SVG) named for what it is and what the machine does with it, in the colour of what
it is (:mod:`corrugate.fabrication.palette`): a colour is one setting in the machine's software.

======================  ===========  ===  =========================================================
layer / group           colour       ACI  content
======================  ===========  ===  =========================================================
``CUT``                 ``#000000``  7    outlines, holes and slits: cut through
``MOUNTAIN-<OP>``       ``#ff0000``  1    mountain creases, by their operation (``PERFORATE``:
                                          each dash a separate segment; ``CUT-SCORE``, ``SCORE``,
                                          ``PEN``: one line each)
``VALLEY-<OP>``         ``#0000ff``  5    valley creases, likewise
``MARK-<OP>``           ``#ff00ff``  6    the band's angle marks, one line each (default ``PEN``)
``LABEL``               ``#808080``  8    part names, single-stroke glyphs (off with ``--no-labels``): pen
``LEGEND``              ``#808080``  8    the file's legend, single-stroke glyphs, off every part: pen
======================  ===========  ===  =========================================================

``<OP>`` is the kind's :class:`~corrugate.export.operations.FoldOp` (``CUT-SCORE``, ``PERFORATE``,
``SCORE``, ``PEN``); a kind whose operation is ``none`` is not in the file (it is in the fold map).
:meth:`Machine.action` says what to set each operation to in the machine's software; the legend
drawn in the file says the same (:mod:`corrugate.export.legend`).

Profiles (``get_machine``; the names are those of :data:`corrugate.fabrication.sheets.CUTTERS`):

``cameo4-12x12``, ``cameo4-12x24`` (Silhouette Cameo 4)
    ``cut-N.dxf``: the basic edition of Silhouette Studio opens DXF, not SVG. Two tool holders: the
    blade in the first, a pen (or an embossing tool) in the second.
``maker-12x12``, ``maker-12x24`` (Cricut Maker)
    ``cut-N.svg``: Cricut Design Space imports SVG (not DXF); strokes 0.25 mm, which Design Space
    ignores (it cuts the path itself). Clamp A holds a pen or the scoring stylus, clamp B the blade
    or the scoring wheel. One pressure for the whole mat: no cut-score.
``laser:WxH`` (a laser with a W x H mm bed)
    ``cut-N.svg`` and ``cut-N.dxf`` (LightBurn and most laser drivers read either), strokes a
    hairline, 0.001 in = 0.0254 mm, which laser drivers take as a vector cut; LightBurn makes a
    layer of each colour. A laser cannot press a score.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import StrEnum

from corrugate.core.cutters import Cutter, get_cutter
from corrugate.fabrication.palette import LINES
from corrugate.names import DEFAULT_MACHINE, LASER_PREFIX, CutFormat

__all__ = [
    "DEFAULT_MACHINE",
    "HAIRLINE_MM",
    "OPERATIONS",
    "Family",
    "Machine",
    "Operation",
    "get_machine",
    "layer_name",
]

#: A laser driver's hairline: 0.001 in (mm).
HAIRLINE_MM = 0.0254


class Family(StrEnum):
    """The kind of machine, which decides the file formats and line widths."""

    SILHOUETTE = "silhouette"
    CRICUT = "cricut"
    LASER = "laser"


@dataclass(frozen=True, slots=True)
class Operation:
    """One thing the machine does: its layer ``name``, stroke ``colour`` (SVG, #rrggbb), ``aci``
    colour (DXF) and ``action`` (what to set it to in the machine's software)."""

    name: str
    colour: str
    aci: int
    action: str


#: The kinds of line of a cut file and their palette colour.
_KINDS = {"MOUNTAIN": "mountain", "VALLEY": "valley", "MARK": "mark"}
_OPS = ("PERFORATE", "CUT-SCORE", "SCORE", "PEN")
_ACTIONS = {
    "CUT": "cut through",
    "PERFORATE": "cut through (each dash is its own line)",
    "CUT-SCORE": "cut part-way, not through (a kiss cut)",
    "SCORE": "score: press a line, do not cut",
    "PEN": "draw with a pen, or engrave",
}


def layer_name(kind: str, op: str) -> str:
    """The layer (DXF) or group (SVG) of the lines of ``kind`` (``mountain``, ``valley``,
    ``marks``) made by operation ``op`` (a fold operation's value: ``cut-score``, ...)."""
    k = "MARK" if kind in ("mark", "marks") else kind.upper()
    return f"{k}-{op.upper()}"


def _operation(name: str, colour: str, op: str) -> Operation:
    swatch = LINES[colour]
    return Operation(name, swatch.hex, swatch.aci, _ACTIONS[op])


#: Every layer a cut file may hold, by name, in the order files list them.
OPERATIONS: dict[str, Operation] = {
    "CUT": _operation("CUT", "cut", "CUT"),
    **{
        f"{k}-{op}": _operation(f"{k}-{op}", colour, op)
        for k, colour in _KINDS.items()
        for op in _OPS
    },
    "LABEL": _operation("LABEL", "note", "PEN"),
    "LEGEND": _operation("LEGEND", "note", "PEN"),
}

#: What to set each operation to, per machine family (in the machine's own software).
ACTIONS: dict[Family, dict[str, str]] = {
    Family.SILHOUETTE: {
        "CUT": "Cut (blade in tool 1, the material's through-cut setting)",
        "PERFORATE": "Cut, as CUT",
        "CUT-SCORE": "Cut at about half the force: scored, not through",
        "SCORE": "Emboss (embossing tool in tool 2)",
        "PEN": "Sketch (a pen in tool 2)",
    },
    Family.CRICUT: {
        "CUT": "Basic Cut",
        "PERFORATE": "Basic Cut",
        "CUT-SCORE": "(not possible: one pressure per mat)",
        "SCORE": "Score (scoring wheel or stylus)",
        "PEN": "Pen (Draw)",
    },
    Family.LASER: {
        "CUT": "Line at cutting power",
        "PERFORATE": "Line at cutting power",
        "CUT-SCORE": "Line at a low power that does not cut through",
        "SCORE": "(not possible: a laser cannot press)",
        "PEN": "Line at the lowest power that marks (engrave)",
    },
}


@dataclass(frozen=True, slots=True)
class Machine:
    """A machine profile: its ``cutter`` (sheet size, mm), ``family``, the cut-file ``formats`` it
    reads (``"svg"``, ``"dxf"``) and the SVG stroke width ``stroke_mm`` (mm)."""

    cutter: Cutter
    family: Family
    formats: tuple[CutFormat, ...]
    stroke_mm: float

    @property
    def name(self) -> str:
        return self.cutter.name

    @property
    def label_action(self) -> str:
        """What the machine does with the LABEL operation."""
        return "engrave" if self.family is Family.LASER else "draw (pen)"

    @property
    def software(self) -> str:
        """The program that sends the cut file to the machine."""
        return {
            Family.SILHOUETTE: "Silhouette Studio",
            Family.CRICUT: "Cricut Design Space",
            Family.LASER: "LightBurn or the laser's driver",
        }[self.family]

    def action(self, layer: str) -> str:
        """What to set the layer (or group) ``layer`` of a cut file to in the machine's software,
        e.g. ``Sketch (a pen in tool 2)`` for ``MARK-PEN`` on a Silhouette."""
        op = "PEN" if layer in ("LABEL", "LEGEND") else layer.split("-", 1)[-1]
        return ACTIONS[self.family]["CUT" if layer == "CUT" else op]


def get_machine(name: str | Cutter | Machine = DEFAULT_MACHINE) -> Machine:
    """The profile of machine ``name`` (a cutter name or ``laser:WxH`` in mm).

    Raises :class:`~corrugate.core.errors.UnknownNameError` for an unknown name and
    :class:`~corrugate.core.errors.InputError` for a bad laser bed (see
    :func:`corrugate.core.cutters.get_cutter`).
    """
    if isinstance(name, Machine):
        return name
    cutter = get_cutter(name)
    if cutter.name.startswith(LASER_PREFIX):
        return Machine(cutter, Family.LASER, ("svg", "dxf"), HAIRLINE_MM)
    if cutter.name.startswith("maker"):
        return Machine(cutter, Family.CRICUT, ("svg",), 0.25)
    return Machine(cutter, Family.SILHOUETTE, ("dxf",), 0.25)
