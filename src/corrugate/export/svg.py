"""SVG writer, in millimetres, with the Origami Simulator colour convention (docs/theory.md section 7).

The root has ``width="<W>mm" height="<H>mm"`` and a viewBox of the same proportions in user
units of :data:`FOLD_MAP_UNIT_MM` (0.01 mm: ``viewBox="0 0 100W 100H"``), so the drawing prints at
its size in mm. The small unit is for Origami Simulator: its SVG import merges every two vertices
closer than 3 user units (its default "vertex merge tolerance", in px), which with 1 mm units
silently collapsed the creases of any design with W < 3 mm and moved the band's tab slits
(checked by hand with the app, ``benchmarks/origami_simulator.py``); at 0.01 mm it merges only
vertices closer than 0.03 mm. The sheet's y axis (up) is flipped to SVG's (down) by
``y_svg = H - y``: a rotation-free, mirror-free view of the sheet, so mountain and valley keep
their meaning. Colours (stroke, ``fill="none"``):

==========================  ===========  ===============================================
what                        colour       ``opacity`` attribute
==========================  ===========  ===============================================
outline and hole edges      ``#000000``  1 (Origami Simulator "boundary": free edges)
cut lines inside a part     ``#00ff00``  1 (Origami Simulator "cut": slits, e.g. slots)
mountain crease             ``#ff0000``  fold angle / 180 (dihedral, 0 flat .. 1 folded flat)
valley crease               ``#0000ff``  fold angle / 180
mark (assembly guide)       ``#ff00ff``  1 (in ``<defs>``: Origami Simulator skips it)
==========================  ===========  ===============================================

Holes are drawn as boundary, not cut: their edges are free edges of the sheet, exactly FOLD's
"B"; #00ff00 is kept for slits, which have material on both sides. The opacity is an attribute,
never an RGBA colour, as Origami Simulator reads it. Every crease is one ``<line>`` element with
``class="crease mountain|valley"``, ``data-crease="<part>:<k>"`` (k = 1-based crease number in
the part) and ``data-fold-angle`` in degrees. This SVG is the fold map, for people and for Origami
Simulator, not for a cutter: every crease is drawn solid whatever the fold-line style, which is
recorded in ``data-style`` (the cut-ready files, :mod:`.cutfile`, hold the perforations as separate
dashes; no file of corrugate uses ``stroke-dasharray``, which cutters ignore).
Part labels are ``<text>`` elements in a ``<g id="labels">`` group (grey fill, no stroke), placed
clear of every line (:mod:`.labels`) and squeezed into their box with ``textLength``; with
``fold_order`` each label starts with the part's step number in the folding order and the part's
group carries ``data-fold-order``; a label that would be smaller than ``READABLE_TEXT_MM`` (2 mm)
is the part's name only (:func:`~corrugate.export.labels.readable_label`), and the legend gives the
full label in a row of its own. ``labels=False`` leaves them out, ``marks=False`` leaves the
marks out.

The band's marks are drawn in a group Origami Simulator does not import: a ``<g id="band-marks">``
inside ``<defs>``, shown where it is by one ``<use>`` naming it by ``href`` and ``xlink:href``
(browsers read either; Inkscape 1.2.2 drew no marks for ``href`` alone, docs/calibration.md
"Opened in"). Origami Simulator's SVG import deletes every child of ``<defs>`` but styles and
reads no ``<use>`` (js/pattern.js of amandaghassaei/OrigamiSimulator). A magenta line it did read was an "undriven"
crease ending inside a face, which kept the folded sheet from reaching its fold angles (issue 36:
16-17 deg off, edges strained 3-5 %); ``benchmarks/origami_simulator.py`` folds the fold map in
the app and checks every crease's angle and the edges' strain.

The colours are the palette's (:mod:`corrugate.fabrication.palette`), the same in every file. The
legend (:func:`corrugate.export.legend.fold_map_legend`: "FOLD MAP: for people, not the cutter",
then each colour's meaning and what the cut file does with each kind) is a ``<g id="legend">`` of
``<text>`` rows, each filled in the colour it names, in a free box off every part
(:func:`~corrugate.export.legend.legend_spot`) or, when the sheet has none, in a strip added below
the sheet (the root's ``data-sheet-mm`` keeps the sheet's width and height); Origami Simulator
reads no text, so it adds no edge.
"""

from __future__ import annotations

import os
import xml.etree.ElementTree as ET
from collections.abc import Mapping
from pathlib import Path

from corrugate.core.fileio import staged
from corrugate.export.labels import LabelSpot, label_text, readable_label
from corrugate.export.legend import (
    LEGEND_TEXT_MM,
    LegendRow,
    fold_map_legend,
    legend_size,
    legend_spot,
    row_length,
)
from corrugate.fabrication.linestyle import SOLID, LineStyle, check_style
from corrugate.fabrication.model import Point, Role
from corrugate.fabrication.palette import LINES
from corrugate.fabrication.sheets import Sheet, place
from corrugate.names import DEFAULT_MARGIN_MM, DEFAULT_SPACING_MM

__all__ = [
    "ANNOTATION",
    "BOUNDARY",
    "COLOURS",
    "FOLD_MAP_UNIT_MM",
    "STROKE_MM",
    "fold_opacity",
    "svg_document",
    "svg_number",
    "svg_root",
    "svg_text",
    "write_svg",
]

SVG_NS = "http://www.w3.org/2000/svg"
#: The XLink namespace of SVG 1.1's ``xlink:href`` (a ``<use>``'s reference as Inkscape 1.2 reads it).
XLINK_NS = "http://www.w3.org/1999/xlink"
#: Stroke colour of outlines and holes (Origami Simulator "boundary"; the palette's ``cut``).
BOUNDARY = LINES["cut"].hex
#: Stroke colour of each line role (Origami Simulator: cut, mountain, valley; marks in <defs>), from the
#: palette (:mod:`corrugate.fabrication.palette`).
COLOURS: dict[Role, str] = {
    Role.CUT: LINES["slit"].hex,
    Role.MOUNTAIN: LINES["mountain"].hex,
    Role.VALLEY: LINES["valley"].hex,
    Role.MARK: LINES["mark"].hex,
}
#: Colour of part labels (text fill) and other annotations that are neither cut nor folded.
ANNOTATION = LINES["note"].hex
#: Stroke width (mm).
STROKE_MM = 0.25
#: The fold map's user unit (mm): small enough that Origami Simulator's vertex merging (3 units)
#: never joins two distinct points of a pattern (module docstring).
FOLD_MAP_UNIT_MM = 0.01


def svg_number(x: float) -> str:
    """A length (mm) as SVG text: at most 4 decimals, no trailing zeros, never '-0'."""
    s = f"{x:.4f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def svg_root(width: float, height: float, unit_mm: float = 1.0) -> ET.Element:
    """An ``<svg>`` element of ``width`` x ``height`` mm whose user unit is ``unit_mm`` mm."""
    return ET.Element(
        "svg",
        {
            "xmlns": SVG_NS,
            "version": "1.1",
            "width": f"{svg_number(width)}mm",
            "height": f"{svg_number(height)}mm",
            "viewBox": f"0 0 {svg_number(width / unit_mm)} {svg_number(height / unit_mm)}",
        },
    )


def svg_text(root: ET.Element) -> str:
    """The document text of ``root``: XML declaration, indented, ending in a newline."""
    ET.indent(root)
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(root, encoding="unicode") + "\n"


def fold_opacity(fold_angle_deg: float) -> float:
    """Origami Simulator's opacity for a crease: |fold angle| / 180, clipped to [0, 1]."""
    return min(max(abs(fold_angle_deg) / 180.0, 0.0), 1.0)


def _points(ring: tuple[Point, ...], height: float, unit: float) -> str:
    """SVG points of ``ring`` (sheet mm, y up) in user units of ``unit`` mm, y down."""
    return " ".join(f"{svg_number(x / unit)},{svg_number((height - y) / unit)}" for x, y in ring)


def svg_document(
    sheet: Sheet,
    style: LineStyle = SOLID,
    *,
    labels: bool = True,
    marks: bool = True,
    title: str | None = None,
    fold_order: Mapping[str, int] | None = None,
    legend: bool = True,
    operations: object | None = None,
    margin: float = DEFAULT_MARGIN_MM,
    spacing: float = DEFAULT_SPACING_MM,
) -> str:
    """The SVG text of one sheet (see the module docstring for the conventions); ``legend`` adds
    the legend, naming what the cut file does with each kind when ``operations`` (a
    :class:`~corrugate.export.operations.FoldOperations`) is given."""
    check_style((p.part for p in sheet.placements), style)
    W, H = sheet.width, sheet.height
    u = FOLD_MAP_UNIT_MM

    def num(mm: float) -> str:  # a length in mm, in user units
        return svg_number(mm / u)

    written: dict[int, tuple[str, LabelSpot]] = {}  # each part's label: its text and spot
    key_rows: list[LegendRow] = []  # the full labels of the parts that carry their name only
    if labels:
        for j, placement in enumerate(sheet.placements):
            placed = place(placement)
            step = None if fold_order is None else fold_order.get(placement.part.name)
            prefix = "" if step is None else f"{step}. "
            full = label_text(placed)
            text, spot, short = readable_label(placed, prefix + full, prefix + placement.part.name)
            written[j] = (text, spot)
            if short:
                key_rows.append(LegendRow(full, ANNOTATION))
    rows = [*fold_map_legend(operations), *key_rows] if legend else []
    key = legend_spot(sheet, rows, margin, spacing) if rows else None
    extra = 0.0
    if rows and key is None:  # no room on the sheet: a strip below it (no machine reads this)
        from corrugate.export.legend import LegendSpot

        w, h = legend_size(rows, LEGEND_TEXT_MM)
        extra = h + 2 * margin
        key = LegendSpot(margin, -h - margin, LEGEND_TEXT_MM, w, h)
    root = svg_root(W, H + extra, u)
    root.set("data-sheet-mm", f"{svg_number(W)} {svg_number(H)}")  # the sheet, without a strip
    if title:
        ET.SubElement(root, "title").text = title
    common = {"fill": "none", "stroke-width": num(STROKE_MM), "stroke-linecap": "butt"}
    text_group = ET.Element("g", {"id": "labels"})
    mark_group: ET.Element | None = None
    for j, placement in enumerate(sheet.placements):
        placed = place(placement)
        part = placement.part
        g = ET.SubElement(
            root, "g", {"id": f"part-{j + 1}", "data-part": part.name, "data-label": part.label}
        )
        step = None if fold_order is None else fold_order.get(part.name)
        if step is not None:
            g.set("data-fold-order", str(step))
        ET.SubElement(
            g,
            "polygon",
            {
                "class": "boundary outline",
                "points": _points(placed.outline, H, u),
                "stroke": BOUNDARY,
                "opacity": "1",
                **common,
            },
        )
        for hole in placed.holes:
            ET.SubElement(
                g,
                "polygon",
                {
                    "class": "boundary hole",
                    "points": _points(hole, H, u),
                    "stroke": BOUNDARY,
                    "opacity": "1",
                    **common,
                },
            )
        number = 0
        for ln in placed.lines:
            if ln.role is Role.MARK and not marks:
                continue
            parent = g
            if ln.role is Role.MARK:  # in <defs>, out of Origami Simulator's reach (docstring)
                if mark_group is None:
                    mark_group = ET.SubElement(
                        ET.SubElement(root, "defs"), "g", {"id": "band-marks"}
                    )
                parent = mark_group
            attrs = {
                "x1": num(ln.a[0]),
                "y1": num(H - ln.a[1]),
                "x2": num(ln.b[0]),
                "y2": num(H - ln.b[1]),
                "stroke": COLOURS[ln.role],
                **common,
            }
            if ln.role in (Role.MOUNTAIN, Role.VALLEY):
                number += 1
                attrs["class"] = f"crease {ln.role.value}"
                attrs["data-crease"] = f"{part.name}:{number}"
                attrs["data-fold-angle"] = svg_number(ln.fold_angle_deg)
                attrs["opacity"] = f"{fold_opacity(ln.fold_angle_deg):.6g}"
                attrs["data-style"] = style.kind.value
            else:
                attrs["class"] = ln.role.value
                attrs["opacity"] = "1"
            if ln.role is Role.MARK:
                attrs["data-part"] = part.name
            ET.SubElement(parent, "line", attrs)
        if labels:
            text, spot = written[j]
            x, y = num(spot.x), num(H - spot.y)
            t_attrs = {
                "x": x,
                "y": y,
                "font-size": num(spot.size),
                "textLength": num(spot.length),
                "lengthAdjust": "spacingAndGlyphs",
                "font-family": "sans-serif",
                "text-anchor": "middle",
                "dominant-baseline": "central",
                "fill": ANNOTATION,
                "stroke": "none",
                "data-part": part.name,
            }
            if spot.rotation:
                t_attrs["transform"] = f"rotate({svg_number(-spot.rotation)} {x} {y})"
            ET.SubElement(text_group, "text", t_attrs).text = text
    if mark_group is not None:  # drawn where it is defined; SVG 2's href and SVG 1.1's xlink:href
        root.set("xmlns:xlink", XLINK_NS)  # (Inkscape 1.2 draws a <use> by xlink:href only)
        ET.SubElement(
            root, "use", {"href": "#band-marks", "xlink:href": "#band-marks", "class": "mark"}
        )
    if labels:
        root.append(text_group)
    if key is not None:
        g = ET.SubElement(root, "g", {"id": "legend", "data-for": "people, not the cutter"})
        for k, row in enumerate(rows):
            x0, y0, _x1, y1 = key.row_box(k, len(rows), row_length(row.text, key.size))
            ET.SubElement(
                g,
                "text",
                {
                    "x": num(x0),
                    "y": num(H - (y0 + y1) / 2),
                    "font-size": num(key.size),
                    "font-family": "sans-serif",
                    "dominant-baseline": "central",
                    "fill": row.colour,
                    "stroke": "none",
                },
            ).text = row.text
    return svg_text(root)


def write_svg(
    sheet: Sheet,
    path: str | os.PathLike[str],
    style: LineStyle = SOLID,
    *,
    labels: bool = True,
    marks: bool = True,
) -> Path:
    """Write one sheet as SVG to ``path`` (all or nothing, see :mod:`corrugate.core.fileio`); returns the path."""
    text = svg_document(sheet, style, labels=labels, marks=marks)
    target = Path(path)
    with staged() as st:
        st.path(target).write_text(text, encoding="utf-8")
    return target
