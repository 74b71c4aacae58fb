"""DXF writer (ezdxf), in millimetres, one layer per line role (docs/theory.md section 7).

``$INSUNITS`` = 4 (mm) and ``$MEASUREMENT`` = 1 (metric); coordinates are sheet mm, y up. Layers
(ACI colour):

=============  =====  ==========================================================================
layer          ACI    content
=============  =====  ==========================================================================
``CUT``        7      outlines and holes as closed LWPOLYLINEs, cut lines inside parts as LINEs
``MOUNTAIN``   1 red  mountain creases, one LINE each, XDATA ``CORRUGATE`` with the fold angle
``VALLEY``     5 blue valley creases, likewise
``MARK``       6      assembly marks (not cut)
``SCORE``      4      with the ``scored`` style: every crease again, for the scoring tool
``PERFORATE``  3      with the ``perforated`` style: the dashes of every crease, as LINEs
``LABEL``      8      part labels (TEXT)
=============  =====  ==========================================================================

This is the whole drawing of a sheet for CAD (the fold map with its tool paths), not a cut file:
MOUNTAIN and VALLEY always hold the fold map, whatever the style, and a cutter would cut every one
of its lines. :func:`corrugate.export.files.write_files` does not write it; the machines get the
operation-clean files of :mod:`.cutfile` (``cut-N.dxf``) instead.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import TYPE_CHECKING

from corrugate.core.fileio import staged
from corrugate.export.labels import label_spot
from corrugate.fabrication.linestyle import (
    SOLID,
    LineStyle,
    StyleKind,
    check_style,
    crease_name,
    dashes,
)
from corrugate.fabrication.model import Role
from corrugate.fabrication.sheets import Sheet, place

if TYPE_CHECKING:
    from ezdxf.document import Drawing

__all__ = ["LAYERS", "dxf_document", "write_dxf"]

#: Layer name -> ACI colour.
LAYERS: dict[str, int] = {
    "CUT": 7,
    "MOUNTAIN": 1,
    "VALLEY": 5,
    "MARK": 6,
    "SCORE": 4,
    "PERFORATE": 3,
    "LABEL": 8,
}
_ROLE_LAYER = {Role.CUT: "CUT", Role.MOUNTAIN: "MOUNTAIN", Role.VALLEY: "VALLEY", Role.MARK: "MARK"}
APPID = "CORRUGATE"


def dxf_document(sheet: Sheet, style: LineStyle = SOLID, *, labels: bool = True) -> Drawing:
    """The DXF drawing (an ezdxf ``Drawing``) of one sheet."""
    from ezdxf import units
    from ezdxf.enums import TextEntityAlignment
    from ezdxf.filemanagement import new

    check_style((p.part for p in sheet.placements), style)
    doc = new("R2010", units=units.MM)
    doc.header["$MEASUREMENT"] = 1
    doc.appids.add(APPID)
    wanted = ["CUT", "MOUNTAIN", "VALLEY", "MARK", "LABEL"]
    if style.kind is StyleKind.SCORED:
        wanted.append("SCORE")
    elif style.kind is StyleKind.PERFORATED:
        wanted.append("PERFORATE")
    for name in wanted:
        doc.layers.add(name, color=LAYERS[name])
    msp = doc.modelspace()
    for placement in sheet.placements:
        placed = place(placement)
        part = placement.part
        msp.add_lwpolyline(placed.outline, close=True, dxfattribs={"layer": "CUT"})
        for hole in placed.holes:
            msp.add_lwpolyline(hole, close=True, dxfattribs={"layer": "CUT"})
        for i, ln in enumerate(placed.lines):
            entity = msp.add_line(ln.a, ln.b, dxfattribs={"layer": _ROLE_LAYER[ln.role]})
            if ln.role not in (Role.MOUNTAIN, Role.VALLEY):
                continue
            where = crease_name(part, i)
            entity.set_xdata(
                APPID, [(1000, where), (1000, "fold_angle_deg"), (1040, ln.fold_angle_deg)]
            )
            if style.kind is StyleKind.SCORED:
                msp.add_line(ln.a, ln.b, dxfattribs={"layer": "SCORE"})
            elif style.kind is StyleKind.PERFORATED:
                for a, b in dashes(ln, style.cut, style.gap, where=where):
                    msp.add_line(a, b, dxfattribs={"layer": "PERFORATE"})
        if labels and part.label:
            spot = label_spot(placed)
            text = msp.add_text(
                part.label,
                height=spot.size,
                rotation=spot.rotation,
                dxfattribs={"layer": "LABEL"},
            )
            text.set_placement((spot.x, spot.y), align=TextEntityAlignment.MIDDLE_CENTER)
    return doc


def write_dxf(
    sheet: Sheet, path: str | os.PathLike[str], style: LineStyle = SOLID, *, labels: bool = True
) -> Path:
    """Write one sheet as DXF to ``path`` (all or nothing, see :mod:`corrugate.core.fileio`); returns the path."""
    doc = dxf_document(sheet, style, labels=labels)
    target = Path(path)
    with staged() as st:
        doc.saveas(st.path(target))
    return target
