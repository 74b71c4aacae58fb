"""Machine profiles: which cut-ready files each machine gets, and how each operation is drawn.

A cut-ready file holds only what the machine should do, because Silhouette Studio, Cricut Design
Space and LightBurn cut every imported line unless the user changes its action, and cut a path
whole whatever its dash style (docs/theory.md section 7). Every operation is real geometry on its own
layer (DXF) or stroke colour (SVG), named for it:

=============  ===========  =====  =================================================================
operation      colour       ACI    what the machine does with it
=============  ===========  =====  =================================================================
``CUT``        ``#ff0000``  1      cut through: outlines, holes and slits
``PERFORATE``  ``#00ff00``  3      cut through: the dashes of perforated folds (``--fold-style
                                   perforated``), each dash a separate segment
``SCORE``      ``#0000ff``  5      score, not cut: scored folds (``--fold-style scored``)
``LABEL``      ``#000000``  7      draw with a pen (cutters) or engrave (laser): part names as
                                   glyph outlines, only with ``--labels``
=============  ===========  =====  =================================================================

Folds of the ``solid`` style are not in the cut files (the machine does nothing with them): they are
in the fold map (``sheet-N.svg``), for folding by hand. Assembly marks are in the fold map only.

Profiles (``get_machine``; the names are those of :data:`corrugate.fabrication.sheets.CUTTERS`):

``cameo4-12x12``, ``cameo4-12x24`` (Silhouette Cameo 4)
    ``cut-N.dxf``: the basic edition of Silhouette Studio opens DXF, not SVG.
``maker-12x12``, ``maker-12x24`` (Cricut Maker)
    ``cut-N.svg``: Cricut Design Space imports SVG (not DXF); strokes 0.25 mm, which Design Space
    ignores (it cuts the path itself).
``laser:WxH`` (a laser with a W x H mm bed)
    ``cut-N.svg`` and ``cut-N.dxf`` (LightBurn and most laser drivers read either), strokes a
    hairline, 0.001 in = 0.0254 mm, which laser drivers take as a vector cut; LightBurn makes a
    layer of each colour.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import StrEnum

from corrugate.fabrication.sheets import Cutter, get_cutter
from corrugate.names import DEFAULT_MACHINE, LASER_PREFIX, CutFormat

__all__ = [
    "DEFAULT_MACHINE",
    "HAIRLINE_MM",
    "OPERATIONS",
    "Family",
    "Machine",
    "Operation",
    "get_machine",
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


#: The operations, by name, in the order files list them.
OPERATIONS: dict[str, Operation] = {
    "CUT": Operation("CUT", "#ff0000", 1, "cut through"),
    "PERFORATE": Operation("PERFORATE", "#00ff00", 3, "cut through (the dashes of a fold)"),
    "SCORE": Operation("SCORE", "#0000ff", 5, "score (scoring tool, or a light pass)"),
    "LABEL": Operation("LABEL", "#000000", 7, "draw with a pen, or engrave"),
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


def get_machine(name: str | Cutter | Machine = DEFAULT_MACHINE) -> Machine:
    """The profile of machine ``name`` (a cutter name or ``laser:WxH`` in mm).

    Raises :class:`~corrugate.core.errors.UnknownNameError` for an unknown name and
    :class:`~corrugate.core.errors.InputError` for a bad laser bed (see
    :func:`corrugate.fabrication.sheets.get_cutter`).
    """
    if isinstance(name, Machine):
        return name
    cutter = get_cutter(name)
    if cutter.name.startswith(LASER_PREFIX):
        return Machine(cutter, Family.LASER, ("svg", "dxf"), HAIRLINE_MM)
    if cutter.name.startswith("maker"):
        return Machine(cutter, Family.CRICUT, ("svg",), 0.25)
    return Machine(cutter, Family.SILHOUETTE, ("dxf",), 0.25)
