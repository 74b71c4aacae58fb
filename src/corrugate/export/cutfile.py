"""Cut-ready files: one sheet as the paths a machine should cut, score or draw, nothing else.

Coordinates are sheet mm (y up, as in DXF; the SVG flips y with ``y_svg = H - y``, no mirror).
Each path belongs to one operation of :data:`corrugate.export.machines.OPERATIONS` and is real
geometry: a perforated fold is its dashes, each a separate two-point path of the set cut length
(:func:`corrugate.fabrication.linestyle.dashes`: evenly spread, half a gap or more at each end, so no
dash reaches the outline); a scored fold is one line on SCORE; a ``solid`` fold is left out (it is in
the fold map). No ``stroke-dasharray``, no ``<text>`` and no DXF TEXT: labels, when asked, are
glyph outlines of the part's name (e.g. ``L1``, ``B3``) on the LABEL operation, placed clear of
every line (:mod:`.labels`).

SVG: ``width``/``height`` in mm with a matching ``viewBox``; one ``<g>`` per operation, with
``id`` and ``inkscape:label`` the operation's name, its stroke colour and the machine's stroke width,
``fill="none"``; every path a ``<path>`` of straight segments (``M``/``L``, ``Z`` when closed).
DXF: R2010, ``$INSUNITS`` = 4 (mm); one layer per operation (ACI and true colour); closed rings as
closed LWPOLYLINEs, open paths as LINEs; the paper-space page is the sheet (``$PLIMMAX`` = width x
height mm) at scale 1:1 (``$PSVPSCALE`` = 1), so a CAD program prints the file at actual size; for a
laser every layer's lineweight is 0 (0.00 mm, a hairline).
"""

from __future__ import annotations

import os
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from corrugate.core.fileio import staged
from corrugate.export.labels import label_outlines, label_spot
from corrugate.export.machines import OPERATIONS, Family, Machine, get_machine
from corrugate.export.svg import svg_number, svg_root, svg_text
from corrugate.fabrication.linestyle import (
    SOLID,
    LineStyle,
    StyleKind,
    check_style,
    crease_name,
    dashes,
)
from corrugate.fabrication.model import Point, Role
from corrugate.fabrication.sheets import Sheet, place

if TYPE_CHECKING:
    from ezdxf.document import Drawing

__all__ = ["CutPath", "cut_dxf_document", "cut_paths", "cut_svg_document", "write_cut_files"]

INKSCAPE_NS = "http://www.inkscape.org/namespaces/inkscape"


@dataclass(frozen=True, slots=True)
class CutPath:
    """One path of a cut file: its ``operation`` name, its ``points`` (sheet mm), whether it is
    ``closed``, and the ``part`` it belongs to."""

    operation: str
    points: tuple[Point, ...]
    closed: bool
    part: str


def cut_paths(sheet: Sheet, style: LineStyle = SOLID, *, labels: bool = False) -> list[CutPath]:
    """Every path of ``sheet``'s cut file, operation by operation (see the module docstring).

    Raises :class:`~corrugate.fabrication.linestyle.PerforationError` if a perforation does not fit a
    crease.
    """
    check_style((p.part for p in sheet.placements), style)
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
            elif ln.role in (Role.MOUNTAIN, Role.VALLEY):
                if style.kind is StyleKind.SCORED:
                    paths.append(CutPath("SCORE", (ln.a, ln.b), False, name))
                elif style.kind is StyleKind.PERFORATED:
                    where = crease_name(part, i)
                    paths.extend(
                        CutPath("PERFORATE", (a, b), False, name)
                        for a, b in dashes(ln, style.cut, style.gap, where=where)
                    )
        if labels:  # the part's name, e.g. "L1", large enough for a pen (the fold map says more)
            text = part.name
            spot = label_spot(placed, text)
            paths.extend(
                CutPath("LABEL", tuple(ring), True, name) for ring in label_outlines(spot, text)
            )
    order = list(OPERATIONS)
    return sorted(paths, key=lambda p: order.index(p.operation))


def cut_svg_document(
    sheet: Sheet,
    machine: str | Machine,
    style: LineStyle = SOLID,
    *,
    labels: bool = False,
) -> str:
    """The SVG text of ``sheet``'s cut file for ``machine`` (see the module docstring)."""
    m = get_machine(machine)
    paths = cut_paths(sheet, style, labels=labels)
    W, H = sheet.width, sheet.height
    ET.register_namespace("inkscape", INKSCAPE_NS)
    root = svg_root(W, H)
    ET.SubElement(root, "title").text = f"corrugate cut file, {m.cutter.description}"
    for op in OPERATIONS.values():
        mine = [p for p in paths if p.operation == op.name]
        if not mine:
            continue
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
        for p in mine:
            d = " ".join(
                f"{'M' if k == 0 else 'L'}{svg_number(x)} {svg_number(H - y)}"
                for k, (x, y) in enumerate(p.points)
            )
            ET.SubElement(g, "path", {"d": d + (" Z" if p.closed else ""), "data-part": p.part})
    return svg_text(root)


def cut_dxf_document(
    sheet: Sheet,
    machine: str | Machine,
    style: LineStyle = SOLID,
    *,
    labels: bool = False,
) -> Drawing:
    """The DXF drawing (an ezdxf ``Drawing``) of ``sheet``'s cut file for ``machine``."""
    from ezdxf import units
    from ezdxf.filemanagement import new

    m = get_machine(machine)
    paths = cut_paths(sheet, style, labels=labels)
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
        layer.rgb = (int(op.colour[1:3], 16), int(op.colour[3:5], 16), int(op.colour[5:7], 16))
        if m.family is Family.LASER:
            layer.dxf.lineweight = 0  # 0.00 mm: a hairline
    for p in paths:
        attribs = {"layer": p.operation}
        if p.closed:
            msp.add_lwpolyline(p.points, close=True, dxfattribs=attribs)
        else:
            for a, b in zip(p.points, p.points[1:], strict=False):
                msp.add_line(a, b, dxfattribs=attribs)
    return doc


def write_cut_files(
    sheet: Sheet,
    out_stem: str | os.PathLike[str],
    machine: str | Machine,
    style: LineStyle = SOLID,
    *,
    labels: bool = False,
) -> list[Path]:
    """Write ``sheet``'s cut files for ``machine`` as ``out_stem`` + ``.svg`` / ``.dxf`` (the
    formats the machine reads), all or nothing; returns the paths written."""
    m = get_machine(machine)
    stem = Path(out_stem)
    svg = cut_svg_document(sheet, m, style, labels=labels) if "svg" in m.formats else None
    dxf = cut_dxf_document(sheet, m, style, labels=labels) if "dxf" in m.formats else None
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
