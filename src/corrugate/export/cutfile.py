"""Cut-ready files: one sheet as the paths a machine should cut, score or draw, nothing else.

Coordinates are sheet mm (y up, as in DXF; the SVG flips y with ``y_svg = H - y``, no mirror).
Each path belongs to one layer of :data:`corrugate.export.machines.OPERATIONS`, named for the kind
of line and its operation (:class:`corrugate.export.operations.FoldOperations`): outlines, holes
and slits on ``CUT``; each crease on ``MOUNTAIN-<OP>`` or ``VALLEY-<OP>`` and each band mark on
``MARK-<OP>`` by its kind's operation; a perforated crease is its dashes, each a separate two-point
path of the set cut length (:func:`corrugate.fabrication.linestyle.dashes`: evenly spread, half a
gap or more at each end, so no dash reaches the outline); a kind whose operation is ``none`` is
left out (it is in the fold map). Without operations given, a cut file holds the machine's default
for the sheet's material (:func:`corrugate.export.operations.default_operations`). No
``stroke-dasharray``, no ``<text>`` and no DXF TEXT: labels (on by default) are single-stroke glyphs of the
part's name (e.g. ``L1``, ``B3``) on ``LABEL``, placed clear of every line (:mod:`.labels`), and
the legend (:mod:`.legend`: the machine, then each layer and what to set it to) is single-stroke glyphs
on ``LEGEND``, a pen layer, in a free box off every part.

SVG: ``width``/``height`` in mm with a matching ``viewBox``; one ``<g>`` per layer, with ``id``
and ``inkscape:label`` the layer's name, its stroke colour and the machine's stroke width,
``fill="none"``; every path a ``<path>`` of straight segments (``M``/``L``, ``Z`` when closed); the
``LEGEND`` group's ``<desc>`` holds the legend's text. DXF: R2010, ``$INSUNITS`` = 4 (mm); one
layer per operation (ACI and true colour); closed rings as closed LWPOLYLINEs, two-point paths as LINEs, pen strokes as open LWPOLYLINEs;
the paper-space page is the sheet (``$PLIMMAX`` = width x height mm) at scale 1:1
(``$PSVPSCALE`` = 1), so a CAD program prints the file at actual size; for a laser every layer's
lineweight is 0 (0.00 mm, a hairline).
"""

from __future__ import annotations

import os
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from corrugate.core.fileio import staged
from corrugate.export.labels import LabelSpot, label_spot, label_strokes
from corrugate.export.legend import LegendRow, cut_legend, legend_spot, row_length
from corrugate.export.machines import OPERATIONS, Family, Machine, get_machine, layer_name
from corrugate.export.operations import (
    CREASE_KINDS,
    FoldOp,
    FoldOperations,
    check_operations,
    default_operations,
    style_operations,
)
from corrugate.export.svg import svg_number, svg_root, svg_text
from corrugate.fabrication.linestyle import LineStyle, crease_name, dashes
from corrugate.fabrication.model import Point, Role
from corrugate.fabrication.palette import rgb
from corrugate.fabrication.sheets import Sheet, place
from corrugate.names import DEFAULT_MARGIN_MM, DEFAULT_SPACING_MM

if TYPE_CHECKING:
    from ezdxf.document import Drawing

__all__ = [
    "CutPath",
    "cut_dxf_document",
    "cut_paths",
    "cut_svg_document",
    "resolve_operations",
    "write_cut_files",
]

#: What a cut file is told to do with its creases: fold operations, a ``--fold-style`` line style
#: (:func:`~corrugate.export.operations.style_operations`), or None (the machine's default).
Operations = FoldOperations | LineStyle | None

INKSCAPE_NS = "http://www.inkscape.org/namespaces/inkscape"


@dataclass(frozen=True, slots=True)
class CutPath:
    """One path of a cut file: its ``operation`` name, its ``points`` (sheet mm), whether it is
    ``closed``, and the ``part`` it belongs to."""

    operation: str
    points: tuple[Point, ...]
    closed: bool
    part: str


def resolve_operations(sheet: Sheet, machine: Machine, ops: Operations) -> FoldOperations:
    """The fold operations of ``sheet``'s cut file: ``ops`` itself, the operations a line style
    stands for, or (None) the machine's default for the material of the sheet's first part."""
    if isinstance(ops, FoldOperations):
        return ops
    material = next((p.part.material_id for p in sheet.placements), "")
    if ops is None:
        return default_operations(machine, material)
    return style_operations(ops, machine, material)


def _legend_paths(
    sheet: Sheet, machine: Machine, layers: list[str], margin: float, spacing: float
) -> tuple[list[CutPath], list[LegendRow]]:
    """The legend's pen strokes (layer ``LEGEND``) in a free box off the parts, and its rows
    (no paths when no box takes it, :func:`~corrugate.export.legend.legend_spot`)."""
    rows = cut_legend(machine, layers)
    spot = legend_spot(sheet, rows, margin, spacing)
    if spot is None:
        return [], rows
    out: list[CutPath] = []
    for k, row in enumerate(rows):
        length = row_length(row.text, spot.size)
        x0, y0, x1, y1 = spot.row_box(k, len(rows), length)
        box = LabelSpot((x0 + x1) / 2, (y0 + y1) / 2, spot.size, 0.0, length)
        strokes = label_strokes(box, row.text)
        if not strokes:
            continue
        shift = x0 - min(x for s in strokes for x, _ in s)  # left-aligned rows
        out.extend(
            CutPath("LEGEND", tuple((x + shift, y) for x, y in s), False, "legend") for s in strokes
        )
    return out, rows


def cut_paths(
    sheet: Sheet,
    operations: Operations = None,
    *,
    labels: bool = False,
    machine: Machine | None = None,
    legend: bool = True,
    margin: float = DEFAULT_MARGIN_MM,
    spacing: float = DEFAULT_SPACING_MM,
) -> list[CutPath]:
    """Every path of ``sheet``'s cut file for ``machine`` (default: the sheet plan's default
    machine), layer by layer (see the module docstring); ``legend`` adds the legend, placed
    ``spacing`` mm off the parts within ``margin`` mm of the sheet's edge.

    Raises :class:`~corrugate.fabrication.linestyle.PerforationError` if a perforation does not fit a
    crease.
    """
    m = get_machine() if machine is None else machine
    ops = resolve_operations(sheet, m, operations)
    check_operations((p.part for p in sheet.placements), ops)
    paths: list[CutPath] = []
    for placement in sheet.placements:
        placed = place(placement)
        part = placement.part
        name = part.name
        paths.append(CutPath("CUT", placed.outline, True, name))
        paths.extend(CutPath("CUT", hole, True, name) for hole in placed.holes)
        for i, ln in enumerate(placed.lines):
            if ln.role is Role.CUT:
                paths.append(CutPath("CUT", (ln.a, ln.b), False, name))
                continue
            op = ops.of(ln.role)
            if op is FoldOp.NONE:
                continue
            layer = layer_name(CREASE_KINDS[ln.role], op.value)
            if op is FoldOp.PERFORATE:
                where = crease_name(part, i)
                paths.extend(
                    CutPath(layer, (a, b), False, name)
                    for a, b in dashes(ln, ops.cut, ops.gap, where=where)
                )
            else:
                paths.append(CutPath(layer, (ln.a, ln.b), False, name))
        if labels:  # the part's name, e.g. "L1", large enough for a pen (the fold map says more)
            text = part.name
            spot = label_spot(placed, text)
            paths.extend(CutPath("LABEL", tuple(s), False, name) for s in label_strokes(spot, text))
    order = list(OPERATIONS)
    if legend:
        present = [op for op in order if any(p.operation == op for p in paths)]
        paths.extend(_legend_paths(sheet, m, present, margin, spacing)[0])
    return sorted(paths, key=lambda p: order.index(p.operation))


def cut_svg_document(
    sheet: Sheet,
    machine: Machine,
    operations: Operations = None,
    *,
    labels: bool = False,
    margin: float = DEFAULT_MARGIN_MM,
    spacing: float = DEFAULT_SPACING_MM,
) -> str:
    """The SVG text of ``sheet``'s cut file for ``machine`` (see the module docstring)."""
    m = machine
    paths = cut_paths(sheet, operations, labels=labels, machine=m, margin=margin, spacing=spacing)
    W, H = sheet.width, sheet.height
    ET.register_namespace("inkscape", INKSCAPE_NS)
    root = svg_root(W, H)
    ET.SubElement(root, "title").text = f"corrugate cut file, {m.cutter.description}"
    present = [op for op in OPERATIONS if any(p.operation == op for p in paths)]
    for op in (OPERATIONS[name] for name in present):
        mine = [p for p in paths if p.operation == op.name]
        g = ET.SubElement(
            root,
            "g",
            {
                "id": op.name,
                f"{{{INKSCAPE_NS}}}label": op.name,
                f"{{{INKSCAPE_NS}}}groupmode": "layer",
                "fill": "none",
                "stroke": op.colour,
                "stroke-width": svg_number(m.stroke_mm),
                "stroke-linecap": "butt",
                "stroke-linejoin": "miter",
            },
        )
        if op.name == "LEGEND":
            rows = cut_legend(m, [n for n in present if n != "LEGEND"])
            ET.SubElement(g, "desc").text = "\n".join(r.text for r in rows)
        for p in mine:
            d = " ".join(
                f"{'M' if k == 0 else 'L'}{svg_number(x)} {svg_number(H - y)}"
                for k, (x, y) in enumerate(p.points)
            )
            ET.SubElement(g, "path", {"d": d + (" Z" if p.closed else ""), "data-part": p.part})
    return svg_text(root)


def cut_dxf_document(
    sheet: Sheet,
    machine: Machine,
    operations: Operations = None,
    *,
    labels: bool = False,
    margin: float = DEFAULT_MARGIN_MM,
    spacing: float = DEFAULT_SPACING_MM,
) -> Drawing:
    """The DXF drawing (an ezdxf ``Drawing``) of ``sheet``'s cut file for ``machine``."""
    from ezdxf import units
    from ezdxf.filemanagement import new

    m = machine
    paths = cut_paths(sheet, operations, labels=labels, machine=m, margin=margin, spacing=spacing)
    doc = new("R2010", units=units.MM)
    doc.header["$MEASUREMENT"] = 1
    # the paper is the sheet, printed 1:1 (CAD programs such as LibreCAD print it so)
    doc.layouts.active_layout().page_setup(
        size=(sheet.width, sheet.height), margins=(0, 0, 0, 0), units="mm", scale=(1, 1)
    )
    doc.header["$PSVPSCALE"] = 1.0
    msp = doc.modelspace()
    for op in OPERATIONS.values():
        if not any(p.operation == op.name for p in paths):
            continue
        layer = doc.layers.add(op.name, color=op.aci)
        layer.rgb = rgb(op.colour)
        layer.description = m.action(op.name)
        if m.family is Family.LASER:
            layer.dxf.lineweight = 0  # 0.00 mm: a hairline
    for p in paths:
        attribs = {"layer": p.operation}
        if p.closed:
            msp.add_lwpolyline(p.points, close=True, dxfattribs=attribs)
        elif len(p.points) > 2:  # a pen stroke: one polyline, one pen-down
            msp.add_lwpolyline(p.points, close=False, dxfattribs=attribs)
        else:
            msp.add_line(p.points[0], p.points[1], dxfattribs=attribs)
    return doc


def write_cut_files(
    sheet: Sheet,
    out_stem: str | os.PathLike[str],
    machine: Machine,
    operations: Operations = None,
    *,
    labels: bool = False,
) -> list[Path]:
    """Write ``sheet``'s cut files for ``machine`` as ``out_stem`` + ``.svg`` / ``.dxf`` (the
    formats the machine reads), all or nothing; returns the paths written."""
    m = machine
    stem = Path(out_stem)
    svg = cut_svg_document(sheet, m, operations, labels=labels) if "svg" in m.formats else None
    dxf = cut_dxf_document(sheet, m, operations, labels=labels) if "dxf" in m.formats else None
    written: list[Path] = []
    with staged() as st:
        if svg is not None:
            target = stem.with_suffix(".svg")
            st.path(target).write_text(svg, encoding="utf-8")
            written.append(target)
        if dxf is not None:
            target = stem.with_suffix(".dxf")
            dxf.saveas(st.path(target))
            written.append(target)
    return written
