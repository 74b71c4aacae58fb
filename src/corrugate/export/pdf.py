"""PDF writer (matplotlib), one page per sheet, at 1:1 scale, for printing and for cutters that
take PDF (DESIGN.md section 7).

Each page is exactly the sheet: the figure is ``width / 25.4`` by ``height / 25.4`` inches (a page of
``width / 25.4 * 72`` by ``height / 25.4 * 72`` pt), with one axes filling the whole figure and limits
0..width, 0..height mm, so 1 mm of the drawing is 1 mm on paper (print at 100 %, "actual size").
A 10 mm check square labelled "10 mm" sits in the box the sheet layout keeps free in the top-right
corner (:data:`corrugate.pattern.sheets.CHECK_BOX`); on a sheet without that box it goes to the
first free spot found, and is left out only if no 10 mm spot is free. Lines use the SVG colours
(:data:`corrugate.export.svg.COLOURS`), solid; with the ``perforated`` style the creases are drawn
as their dashes. Part labels, the check square and a one-line note in the bottom margin are grey
(:data:`corrugate.export.svg.ANNOTATION`), so a cutter that imports the PDF can skip them by colour.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import TYPE_CHECKING

from ..fileio import staged
from ..pattern.linestyle import SOLID, LineStyle, StyleKind, check_style, crease_name, dashes
from ..pattern.model import Point, Role
from ..pattern.sheets import Sheet, SheetPlan, place
from .labels import label_spot
from .svg import ANNOTATION, BOUNDARY, COLOURS

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = [
    "CHECK_SQUARE_MM",
    "LINE_MM",
    "check_square_spot",
    "render_pdf",
    "sheet_figure",
    "write_pdf",
]

#: Side of the check square (mm).
CHECK_SQUARE_MM = 10.0
#: Line width on paper (mm).
LINE_MM = 0.2
_PT = 72.0 / 25.4  # points per mm
_LABEL_MM = 3.0


def check_square_spot(sheet: Sheet, spacing: float = 2.0) -> tuple[float, float] | None:
    """Lower-left corner (mm) of the check square on ``sheet``: in its reserved box if it has one,
    else the free spot nearest the top-right corner (``None`` if there is none)."""
    side = CHECK_SQUARE_MM
    need_w, need_h = side, side + _LABEL_MM + 1.0
    if sheet.reserved is not None:
        rx, ry, rw, rh = sheet.reserved
        if rw >= need_w and rh >= need_h:
            return rx + (rw - side) / 2, ry + rh - side - (rh - need_h) / 2
    boxes = [p.bounds for p in sheet.placements]
    xs = {1.0, sheet.width - need_w - 1.0} | {b[2] + spacing for b in boxes}
    ys = {1.0, sheet.height - need_h - 1.0} | {b[3] + spacing for b in boxes}
    for y in sorted(ys, reverse=True):
        for x in sorted(xs, reverse=True):
            if x < 0 or y < 0 or x + need_w > sheet.width or y + need_h > sheet.height:
                continue
            if all(
                x + need_w + spacing <= b[0]
                or b[2] + spacing <= x
                or y + need_h + spacing <= b[1]
                or b[3] + spacing <= y
                for b in boxes
            ):
                return x, y + _LABEL_MM + 1.0
    return None


def write_pdf(
    plan: SheetPlan,
    path: str | os.PathLike[str],
    style: LineStyle = SOLID,
    *,
    labels: bool = True,
    title: str = "corrugate pattern",
) -> Path:
    """Write every sheet of ``plan`` as one page of a PDF at ``path`` (all or nothing)."""
    check_style((p.part for p in plan.placements), style)
    target = Path(path)
    with staged() as st:
        render_pdf(plan, st.path(target), style, labels=labels, title=title)
    return target


def sheet_figure(
    plan: SheetPlan, number: int, style: LineStyle = SOLID, *, labels: bool = True
) -> Figure:
    """The matplotlib figure of sheet ``number`` (1-based) of ``plan``, at 1:1 (see the module
    docstring); save it as PDF for print, or as PNG for a preview."""
    from matplotlib.collections import LineCollection
    from matplotlib.figure import Figure
    from matplotlib.patches import Rectangle

    lw = LINE_MM * _PT
    sheet = plan.sheets[number - 1]
    W, H = sheet.width, sheet.height
    fig = Figure(figsize=(W / 25.4, H / 25.4))
    ax = fig.add_axes((0.0, 0.0, 1.0, 1.0))
    ax.set_xlim(0.0, W)
    ax.set_ylim(0.0, H)
    ax.set_axis_off()
    segs: dict[str, list[tuple[Point, Point]]] = {}
    for placement in sheet.placements:
        placed = place(placement)
        part = placement.part
        for ring in (placed.outline, *placed.holes):
            for k in range(len(ring)):
                segs.setdefault(BOUNDARY, []).append((ring[k], ring[(k + 1) % len(ring)]))
        for i, ln in enumerate(placed.lines):
            colour = COLOURS[ln.role]
            if style.kind is StyleKind.PERFORATED and ln.role in (
                Role.MOUNTAIN,
                Role.VALLEY,
            ):
                where = crease_name(part, i)
                segs.setdefault(colour, []).extend(dashes(ln, style.cut, style.gap, where=where))
            else:
                segs.setdefault(colour, []).append((ln.a, ln.b))
        if labels and part.label:
            spot = label_spot(placed)
            ax.text(
                spot.x,
                spot.y,
                part.label,
                fontsize=spot.size * _PT,
                rotation=spot.rotation,
                ha="center",
                va="center",
                color=ANNOTATION,
            )
    for colour, lines in segs.items():
        ax.add_collection(LineCollection(lines, colors=colour, linewidths=lw, capstyle="butt"))
    corner = check_square_spot(sheet, plan.spacing)
    if corner is not None:
        x, y = corner
        side = CHECK_SQUARE_MM
        ax.add_patch(Rectangle((x, y), side, side, fill=False, edgecolor=ANNOTATION, linewidth=lw))
        ax.text(
            x + side / 2,
            y - 0.5,
            "10 mm",
            fontsize=_LABEL_MM * _PT * 0.8,
            ha="center",
            va="top",
            color=ANNOTATION,
        )
    if plan.margin >= 3.0:  # a one-line note in the bottom margin
        ax.text(
            1.0,
            1.0,
            f"{plan.cutter.name}  sheet {number}/{len(plan.sheets)}  print at 100 %",
            fontsize=1.8 * _PT,
            ha="left",
            va="bottom",
            color=ANNOTATION,
        )
    return fig


def render_pdf(
    plan: SheetPlan, path: Path, style: LineStyle = SOLID, *, labels: bool = True, title: str = ""
) -> None:
    """Draw ``plan`` into a PDF at ``path`` directly (no staging: use :func:`write_pdf`)."""
    from matplotlib.backends.backend_pdf import PdfPages

    check_style((p.part for p in plan.placements), style)
    metadata = {"Title": title, "Creator": "corrugate", "CreationDate": None}
    with PdfPages(path, metadata=metadata) as pdf:
        for number in range(1, len(plan.sheets) + 1):
            pdf.savefig(sheet_figure(plan, number, style, labels=labels))
