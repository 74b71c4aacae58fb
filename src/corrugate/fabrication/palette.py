"""The one palette of corrugate: one colour per part and one per kind of line, in every file.

The fold map (``sheet-N.svg``), the cut files (``cut-N.dxf`` / ``cut-N.svg``), ``pattern.pdf``,
the assembly figure (``assembly.png``), the report (which shows those figures) and the web page's
3D view (the GLB's materials, and the fallbacks in ``web/static/app.js``) all take their colours
from here; ``tests/fabrication/test_palette.py`` checks each of them against this module.

Lines (what a line is on the part; docs/fabrication.md, "One palette"):

==========  ===========  =====  =================================================================
kind        colour       ACI    meaning
==========  ===========  =====  =================================================================
``cut``     ``#000000``  7      outline and hole edges, cut through (Origami Simulator "boundary")
``slit``    ``#00ff00``  3      a cut inside a part (Origami Simulator "cut"); the cut files cut
                                it with the outlines, so it is drawn there in ``cut``'s colour
``mountain`` ``#ff0000``  1      mountain crease (Origami Simulator's mountain)
``valley``  ``#0000ff``  5      valley crease (Origami Simulator's valley)
``mark``    ``#ff00ff``  6      the band's angle marks (in the fold map inside ``<defs>``, which
                                Origami Simulator does not import: a magenta line it reads is an
                                "undriven" crease)
``note``    ``#808080``  8      labels and legends: for a pen, or for people
==========  ===========  =====  =================================================================

The crease colours are those Origami Simulator reads from an SVG (red mountain, blue valley, black
boundary, green cut), so the fold map stays an Origami Simulator input (its marks out of the app's
reach, :mod:`corrugate.export.svg`); every
other file uses the same colour for the same kind of line, so red always means mountain and blue
always valley. A cut file gives each kind exactly one machine operation (its DXF layer or SVG
group is named for both, e.g. ``MOUNTAIN-PERFORATE``), so a colour is also one setting in
Silhouette Studio's "cut by line colour" and one layer in Cricut Design Space.

Parts (faces of the 3D view and the assembly figure): ``L1`` blue, ``L2`` orange, the band grey.
"""

from __future__ import annotations

from dataclasses import dataclass
from types import MappingProxyType

__all__ = ["LINES", "PALETTE", "PARTS", "Palette", "Swatch", "part_colour", "rgb", "rgba"]


@dataclass(frozen=True, slots=True)
class Swatch:
    """One colour: ``hex`` (``#rrggbb``), its AutoCAD colour index ``aci`` (the DXF layer colour;
    0 for a colour no DXF holds) and the ``name`` legends and titles call it by."""

    hex: str
    aci: int
    name: str


@dataclass(frozen=True, slots=True)
class Palette:
    """Every colour of corrugate: ``lines`` by kind of line, ``parts`` by part group
    (``L1``, ``L2``, ``band``)."""

    lines: MappingProxyType[str, Swatch]
    parts: MappingProxyType[str, Swatch]


#: The kinds of line, in the order legends list them.
LINES: MappingProxyType[str, Swatch] = MappingProxyType(
    {
        "cut": Swatch("#000000", 7, "black"),
        "slit": Swatch("#00ff00", 3, "green"),
        "mountain": Swatch("#ff0000", 1, "red"),
        "valley": Swatch("#0000ff", 5, "blue"),
        "mark": Swatch("#ff00ff", 6, "magenta"),
        "note": Swatch("#808080", 8, "grey"),
    }
)

#: The part groups: the two layers and the connector band.
PARTS: MappingProxyType[str, Swatch] = MappingProxyType(
    {
        "L1": Swatch("#548cd9", 0, "blue"),
        "L2": Swatch("#f28c33", 0, "orange"),
        "band": Swatch("#9e9e9e", 0, "grey"),
    }
)

#: The palette every writer uses (the same object everywhere).
PALETTE = Palette(LINES, PARTS)


def rgb(hex_colour: str) -> tuple[int, int, int]:
    """``#rrggbb`` as 0-255 integers."""
    h = hex_colour.lstrip("#")
    return int(h[0:2], 16), int(h[2:4], 16), int(h[4:6], 16)


def rgba(hex_colour: str, alpha: float = 1.0) -> tuple[float, float, float, float]:
    """``#rrggbb`` as 0-1 floats with ``alpha`` (glTF's ``baseColorFactor``)."""
    r, g, b = rgb(hex_colour)
    return r / 255, g / 255, b / 255, alpha


def part_colour(part_name: str, kind: str = "layer") -> Swatch:
    """The colour of a part: ``L1`` / ``L2`` (or a layer whose name ends in 1 / 2), the band for a
    connector (``B1``, ``B2``, ...)."""
    if kind == "connector" or part_name.lower().startswith(("b", "band")):
        return PARTS["band"]
    return PARTS["L2"] if part_name.endswith("2") else PARTS["L1"]
