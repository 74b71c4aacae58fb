"""PDF writer (matplotlib), one page per sheet, at 1:1 scale, for printing and for cutters that
take PDF (docs/theory.md section 7).

Each page is exactly the sheet: the figure is ``width / 25.4`` by ``height / 25.4`` inches (a page of
``width / 25.4 * 72`` by ``height / 25.4 * 72`` pt), with one axes filling the whole figure and limits
0..width, 0..height mm, so 1 mm of the drawing is 1 mm on paper (print at 100 %, "actual size").
A 10 mm check square labelled "10 mm" sits in the box the sheet layout keeps free in the top-right
corner (:data:`corrugate.fabrication.sheets.CHECK_BOX`); on a sheet without that box it goes to the
first free spot found, and is left out only if no 10 mm spot is free. Lines use the SVG colours
(:data:`corrugate.export.svg.COLOURS`), solid; with the ``perforated`` style the creases are drawn
as their dashes. Part labels, the check square and a one-line note in the bottom margin are grey
(:data:`corrugate.export.svg.ANNOTATION`), so a cutter that imports the PDF can skip them by colour.

Tiles (:func:`write_tiled_pdf`, ``pattern-a4.pdf`` / ``pattern-letter.pdf``): the same drawing at
1:1 on portrait A4 (210 x 297 mm) or Letter (215.9 x 279.4 mm) pages, for printing on any printer
and taping together as a template for cutting by hand. Each sheet is cut into a grid of windows
from its top-left corner (:func:`sheet_tiles`); a window that holds no part is left out (its
place in the grid stays). A page shows one window in its drawing area (the
paper less :data:`PAGE_MARGIN_MM` at the left, right and top and :data:`FOOTER_MM` at the bottom),
framed by a thin grey line. Neighbouring windows overlap by :data:`OVERLAP_MM`; registration
crosses sit on the middle line of each overlap every :data:`MARK_PITCH_MM`
(:func:`registration_marks`), at the same sheet point on both pages. The footer holds a black
10 mm check square, the page's sheet, row, column and number, how to join the pages, and a map of
the grid with the page filled. The last page is the key (:func:`key_figure`): the fold map's
legend and every part's full label, as a tile shows a part by its name where the full label does
not fit. All lengths are mm.
"""

from __future__ import annotations

import math
import os
from collections.abc import Collection, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from corrugate.core.errors import InputError, UnknownNameError
from corrugate.core.fileio import staged
from corrugate.core.plotting import pdf_pages
from corrugate.export.labels import (
    READABLE_TEXT_MM,
    LabelSpot,
    callout_spot,
    label_gap,
    label_text,
    readable_label,
)
from corrugate.export.legend import LegendRow, fold_map_legend, legend_spot, row_length
from corrugate.export.svg import ANNOTATION, BOUNDARY, COLOURS
from corrugate.fabrication.linestyle import (
    SOLID,
    LineStyle,
    StyleKind,
    check_style,
    crease_name,
    dashes,
)
from corrugate.fabrication.model import Point, Role
from corrugate.fabrication.sheets import Sheet, SheetPlan, place
from corrugate.names import PAPER_NAMES

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = [
    "CHECK_SQUARE_MM",
    "FOOTER_MM",
    "KEY_TEXT_MM",
    "LINE_MM",
    "MARK_INSET_MM",
    "MARK_PITCH_MM",
    "MARK_SIZE_MM",
    "OVERLAP_MM",
    "PAGE_MARGIN_MM",
    "PAPERS",
    "PAPER_CHOICES",
    "REGISTRATION",
    "Paper",
    "PrintedLabel",
    "Tile",
    "check_paper",
    "check_square_spot",
    "drawing_area",
    "get_paper",
    "key_figure",
    "key_rows",
    "plan_tiles",
    "printed_labels",
    "registration_marks",
    "render_pdf",
    "render_tiled_pdf",
    "sheet_figure",
    "sheet_tiles",
    "tile_figure",
    "tile_used",
    "write_pdf",
    "write_tiled_pdf",
]

#: Side of the check square (mm).
CHECK_SQUARE_MM = 10.0
#: Line width on paper (mm).
LINE_MM = 0.2
#: Stroke colour of the tiles' registration crosses (black, as printers print it best).
REGISTRATION = "#000000"
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
    plan: SheetPlan,
    number: int,
    style: LineStyle = SOLID,
    *,
    labels: bool = True,
    operations: object | None = None,
) -> Figure:
    """The matplotlib figure of sheet ``number`` (1-based) of ``plan``, at 1:1 (see the module
    docstring); save it as PDF for print, or as PNG for a preview. ``operations`` (a
    :class:`~corrugate.export.operations.FoldOperations`): the cut files' fold operations, which
    the legend names."""
    from matplotlib.figure import Figure

    sheet = plan.sheets[number - 1]
    W, H = sheet.width, sheet.height
    fig = Figure(figsize=(W / 25.4, H / 25.4))
    ax = fig.add_axes((0.0, 0.0, 1.0, 1.0))
    ax.set_xlim(0.0, W)
    ax.set_ylim(0.0, H)
    ax.set_axis_off()
    printed = printed_labels(plan, number) if labels else []  # both draw them: found once
    _draw_sheet(ax, plan, number, style, printed)
    _draw_legend(ax, plan, number, operations, printed)
    return fig


@dataclass(frozen=True, slots=True)
class PrintedLabel:
    """One part's label on a printed sheet: the ``text`` written at ``spot``, the part's full
    label when ``text`` is its name only (``full``; the key gives it), and for a callout the
    point on the part its leader runs to (``leader``; None: written on the part)."""

    text: str
    spot: LabelSpot
    full: str | None = None
    leader: Point | None = None

    @property
    def box(self) -> tuple[float, float, float, float]:
        """The text's box grown by its gap (sheet mm)."""
        (x0, y0), _, (x1, y1), _ = self.spot.corners()
        g = label_gap(self.spot.size)
        return x0 - g, y0 - g, x1 + g, y1 + g


def printed_labels(plan: SheetPlan, number: int) -> list[PrintedLabel]:
    """The labels of sheet ``number`` as the PDF writes them (module docstring of
    :mod:`corrugate.export.labels`): the full label on the part at 2 mm or more, else the name on
    the part at 2 mm or more, else the name as a callout beside the part (off every part and the
    check square), else the name at the size that fits on the part."""
    sheet = plan.sheets[number - 1]
    blocked = [p.bounds for p in sheet.placements]
    corner = check_square_spot(sheet, plan.spacing)
    if corner is not None:
        x, y = corner
        blocked.append((x, y - _LABEL_MM - 1.0, x + CHECK_SQUARE_MM, y + CHECK_SQUARE_MM))
    out: list[PrintedLabel] = []
    for placement in sheet.placements:
        part = placement.part
        if not part.label:
            continue
        placed = place(placement)
        full = label_text(placed)
        text, spot, short = readable_label(placed, full, part.name)
        if spot.size >= READABLE_TEXT_MM - 1e-9:
            out.append(PrintedLabel(text, spot, full if short else None))
            continue
        beside = callout_spot(placed, text, blocked, sheet.width, sheet.height)
        if beside is None:
            out.append(PrintedLabel(text, spot, full if short else None))
            continue
        label = PrintedLabel(text, beside, full if short else None, (spot.x, spot.y))
        blocked.append(label.box)
        out.append(label)
    return out


def _draw_legend(
    ax: Axes,
    plan: SheetPlan,
    number: int,
    operations: object | None,
    printed: Sequence[PrintedLabel],
) -> None:
    """The fold map's legend (:func:`~corrugate.export.legend.fold_map_legend`: for people, not
    the cutter; each colour's meaning and what the cut file does with it) in the free box of sheet
    ``number`` that :func:`~corrugate.export.legend.legend_spot` finds (off the callouts too),
    each row in its kind's colour, then the full label of each part of ``printed`` (the sheet's
    :func:`printed_labels`, none without labels) that carries its name only; none when no box
    takes it (the page is the sheet: there is no strip to add)."""
    sheet = plan.sheets[number - 1]
    rows = fold_map_legend(operations, steps=False)  # the printed labels carry no step
    rows += [LegendRow(p.full, ANNOTATION) for p in printed if p.full is not None]
    callouts = [p.box for p in printed if p.leader is not None]
    key = legend_spot(sheet, rows, plan.margin, plan.spacing, callouts)
    if key is None:
        return
    for k, row in enumerate(rows):
        x0, y0, _x1, y1 = key.row_box(k, len(rows), row_length(row.text, key.size))
        ax.text(
            x0,
            (y0 + y1) / 2,
            row.text,
            fontsize=key.size * _PT,
            ha="left",
            va="center",
            color=row.colour,
            clip_on=True,
        )


def _draw_sheet(
    ax: Axes, plan: SheetPlan, number: int, style: LineStyle, printed: Sequence[PrintedLabel]
) -> None:
    """Draw sheet ``number`` (1-based) of ``plan`` into ``ax``, whose data units are sheet mm and
    whose scale is 1:1 on paper (the caller sets the figure size and the axes' limits), with the
    labels ``printed`` (the sheet's :func:`printed_labels`, none without labels); every artist is
    clipped to ``ax``."""
    from matplotlib.collections import LineCollection
    from matplotlib.patches import Rectangle

    lw = LINE_MM * _PT
    sheet = plan.sheets[number - 1]
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
    for label in printed:
        spot = label.spot
        ax.text(
            spot.x,
            spot.y,
            label.text,
            fontsize=spot.size * _PT,
            rotation=spot.rotation,
            ha="center",
            va="center",
            color=ANNOTATION,
            clip_on=True,
        )
        if label.leader is not None:  # a callout: a leader from its box to its spot on the part
            x0, y0, x1, y1 = label.box
            lx, ly = label.leader
            ex, ey = min(max(lx, x0), x1), min(max(ly, y0), y1)
            segs.setdefault(ANNOTATION, []).append(((ex, ey), (lx, ly)))
            ax.plot([lx], [ly], marker="o", markersize=0.8 * _PT, color=ANNOTATION, clip_on=True)
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
            clip_on=True,
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
            clip_on=True,
        )


def render_pdf(
    plan: SheetPlan,
    path: Path,
    style: LineStyle = SOLID,
    *,
    labels: bool = True,
    title: str = "",
    figures: Sequence[Figure] | None = None,
    operations: object | None = None,
) -> None:
    """Draw ``plan`` into a PDF at ``path`` directly (no staging: use :func:`write_pdf`).

    ``figures``: the sheets' :func:`sheet_figure` (same plan, style and labels), built already
    (the report shows the same figures); ``None`` builds them here."""
    PdfPages = pdf_pages()

    check_style((p.part for p in plan.placements), style)
    if figures is not None and len(figures) != len(plan.sheets):
        raise ValueError(f"{len(figures)} figures for {len(plan.sheets)} sheets")
    metadata = {"Title": title, "Creator": "corrugate", "CreationDate": None}
    with PdfPages(path, metadata=metadata) as pdf:
        for number in range(1, len(plan.sheets) + 1):
            fig = (
                sheet_figure(plan, number, style, labels=labels, operations=operations)
                if figures is None
                else figures[number - 1]
            )
            pdf.savefig(fig)


# ----------------------------------------------------------------------------------------------
# 1:1 tiles on office paper (A4, Letter), to print on any printer and tape together


@dataclass(frozen=True, slots=True)
class Paper:
    """An office paper size, portrait: ``width`` x ``height`` (mm)."""

    name: str
    width: float
    height: float


#: The paper sizes of the tiled PDF (ISO 216 A4, 210 x 297 mm; US Letter, 8.5 x 11 in).
PAPERS: dict[str, Paper] = {
    "a4": Paper("a4", 210.0, 297.0),
    "letter": Paper("letter", 8.5 * 25.4, 11.0 * 25.4),
}
#: Values of the ``paper`` option: ``mat`` (the mat-size pages only) or a :data:`PAPERS` name.
PAPER_CHOICES: tuple[str, ...] = PAPER_NAMES
#: Blank margin (mm) at the left, right and top of a tile page, outside most printers' dead zone.
PAGE_MARGIN_MM = 10.0
#: Height (mm) of the strip at the bottom of a tile page: its 10 mm check square and its position.
FOOTER_MM = 24.0
#: Width (mm) of the strip of the sheet that two neighbouring tiles both show.
OVERLAP_MM = 10.0
#: Distance (mm, along an overlap) between neighbouring registration marks.
MARK_PITCH_MM = 40.0
#: Distance (mm) from the end of a tile's drawing area to the first registration mark of an overlap.
MARK_INSET_MM = 20.0
#: Length (mm) of each of the two strokes of a registration cross; its circle has half this radius.
MARK_SIZE_MM = 6.0


def get_paper(name: str) -> Paper:
    """The paper called ``name`` (``a4`` or ``letter``, any case); raises
    :class:`~corrugate.core.errors.UnknownNameError` naming the field ``paper`` otherwise."""
    key = name.strip().lower()
    if key not in PAPERS:
        raise UnknownNameError("paper", name, list(PAPERS))
    return PAPERS[key]


def check_paper(name: str) -> str:
    """``name`` normalised if it is one of :data:`PAPER_CHOICES`; else
    :class:`~corrugate.core.errors.UnknownNameError` naming the field ``paper``."""
    key = name.strip().lower()
    if key not in PAPER_CHOICES:
        raise UnknownNameError("paper", name, list(PAPER_CHOICES))
    return key


@dataclass(frozen=True, slots=True)
class Tile:
    """One tile page: the part of sheet ``sheet`` (1-based) that the page shows at 1:1.

    ``row`` and ``column`` are 1-based, row 1 at the top of the sheet, column 1 at its left;
    ``rows`` x ``columns`` is the grid of the sheet. The page's drawing area shows the sheet
    window ``x0 <= x <= x0 + width``, ``y0 <= y <= y0 + height`` (sheet mm, y up), with its
    lower-left corner at (``PAGE_MARGIN_MM``, ``FOOTER_MM``) on the page.
    """

    sheet: int
    row: int
    column: int
    rows: int
    columns: int
    x0: float
    y0: float
    width: float
    height: float

    @property
    def window(self) -> tuple[float, float, float, float]:
        """(xmin, ymin, xmax, ymax) of the sheet window the page shows (mm)."""
        return self.x0, self.y0, self.x0 + self.width, self.y0 + self.height

    def to_page(self, point: Point) -> Point:
        """A sheet point (mm) as a page point (mm from the page's lower-left corner)."""
        return point[0] - self.x0 + PAGE_MARGIN_MM, point[1] - self.y0 + FOOTER_MM


def drawing_area(paper: Paper) -> tuple[float, float]:
    """Width and height (mm) of the drawing area of a tile page of ``paper``."""
    return paper.width - 2 * PAGE_MARGIN_MM, paper.height - PAGE_MARGIN_MM - FOOTER_MM


def _count(extent: float, window: float, overlap: float) -> int:
    if extent <= window + 1e-9:
        return 1
    return math.ceil((extent - window) / (window - overlap) - 1e-9) + 1


def sheet_tiles(
    sheet: Sheet, paper: Paper, number: int = 1, overlap: float = OVERLAP_MM
) -> tuple[Tile, ...]:
    """The tiles of ``sheet`` (number ``number``, 1-based) on ``paper``, row by row from the top
    left: a grid of windows, each ``overlap`` mm into its right and lower neighbours, anchored at
    the sheet's top-left corner (the mat's origin) and together covering the whole sheet."""
    cw, ch = drawing_area(paper)
    if not 0 <= overlap <= min(cw, ch) / 2:
        raise InputError("overlap", f"{overlap} mm", f"0 <= overlap <= {min(cw, ch) / 2:g} mm")
    cols = _count(sheet.width, cw, overlap)
    rows = _count(sheet.height, ch, overlap)
    return tuple(
        Tile(
            sheet=number,
            row=r + 1,
            column=c + 1,
            rows=rows,
            columns=cols,
            x0=c * (cw - overlap),
            y0=sheet.height - r * (ch - overlap) - ch,
            width=cw,
            height=ch,
        )
        for r in range(rows)
        for c in range(cols)
    )


def tile_used(tile: Tile, sheet: Sheet) -> bool:
    """Whether ``tile``'s window overlaps the bounding box of some part on ``sheet`` (a page with
    something to cut)."""
    x0, y0, x1, y1 = tile.window
    return any(
        b[0] < x1 and b[2] > x0 and b[1] < y1 and b[3] > y0
        for b in (p.bounds for p in sheet.placements)
    )


def plan_tiles(
    plan: SheetPlan, paper: str | Paper, overlap: float = OVERLAP_MM, *, empty: bool = False
) -> tuple[Tile, ...]:
    """The tiles of every sheet of ``plan`` in page order (sheet by sheet, row by row): those
    whose window overlaps a part (:func:`tile_used`), or every tile of the grid with
    ``empty=True``. Rows and columns keep their place in the grid either way."""
    pp = paper if isinstance(paper, Paper) else get_paper(paper)
    return tuple(
        t
        for k, sheet in enumerate(plan.sheets, start=1)
        for t in sheet_tiles(sheet, pp, k, overlap)
        if empty or tile_used(t, sheet)
    )


def registration_marks(
    tile: Tile, sheet_width: float, sheet_height: float, overlap: float = OVERLAP_MM
) -> tuple[Point, ...]:
    """Centres (sheet mm) of the registration crosses on ``tile`` of a ``sheet_width`` x
    ``sheet_height`` mm sheet: on the middle line of each overlap it shares with a neighbour, over
    the part of it that lies on the sheet, every :data:`MARK_PITCH_MM` from :data:`MARK_INSET_MM`
    after its start (from the top, from the left); one cross in its middle if it is shorter than
    two insets. A neighbour has the same crosses at the same sheet points, so the two pages line
    up when their crosses coincide."""
    x0, y0, x1, y1 = tile.window
    along_y = [-y for y in _ticks(-min(y1, sheet_height), -max(y0, 0.0))]
    along_x = _ticks(max(x0, 0.0), min(x1, sheet_width))
    marks: list[Point] = []
    if tile.column > 1:
        marks += [(x0 + overlap / 2, y) for y in along_y]
    if tile.column < tile.columns:
        marks += [(x1 - overlap / 2, y) for y in along_y]
    if tile.row > 1:
        marks += [(x, y1 - overlap / 2) for x in along_x]
    if tile.row < tile.rows:
        marks += [(x, y0 + overlap / 2) for x in along_x]
    return tuple(marks)


def _ticks(start: float, stop: float) -> list[float]:
    """Mark positions on [start, stop]: every MARK_PITCH_MM from start + MARK_INSET_MM up to
    stop - MARK_INSET_MM, or the middle alone when that range is empty."""
    first, last = start + MARK_INSET_MM, stop - MARK_INSET_MM
    if last < first - 1e-9:
        return [(start + stop) / 2]
    count = math.floor((last - first) / MARK_PITCH_MM + 1e-9) + 1
    return [first + k * MARK_PITCH_MM for k in range(count)]


def tile_figure(
    plan: SheetPlan,
    tile: Tile,
    paper: Paper,
    style: LineStyle = SOLID,
    *,
    labels: bool = True,
    page: tuple[int, int] = (1, 1),
    overlap: float = OVERLAP_MM,
    printed: Collection[tuple[int, int]] | None = None,
) -> Figure:
    """The matplotlib figure of one tile page at 1:1: ``paper`` size, the sheet window of ``tile``
    in the drawing area (framed), the registration crosses, and in the bottom strip a 10 mm check
    square, the tile's place in the grid and ``page`` (number, count). ``printed`` is the (row,
    column) of every page of this sheet in the file (None: all); the grid map dots the others."""
    from matplotlib.figure import Figure
    from matplotlib.lines import Line2D
    from matplotlib.patches import Circle, Rectangle

    pw, ph = paper.width, paper.height
    cw, ch = tile.width, tile.height
    lw = LINE_MM * _PT
    fig = Figure(figsize=(pw / 25.4, ph / 25.4))
    ax = fig.add_axes((PAGE_MARGIN_MM / pw, FOOTER_MM / ph, cw / pw, ch / ph))
    x0, y0, x1, y1 = tile.window
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_axis_off()
    sheet = plan.sheets[tile.sheet - 1]
    ax.add_patch(  # the sheet's edge (the mat's usable area), dotted
        Rectangle(
            (0.0, 0.0),
            sheet.width,
            sheet.height,
            fill=False,
            edgecolor=ANNOTATION,
            linewidth=lw,
            linestyle=(0, (1, 4)),
        )
    )
    _draw_sheet(ax, plan, tile.sheet, style, printed_labels(plan, tile.sheet) if labels else [])

    page_ax = fig.add_axes((0.0, 0.0, 1.0, 1.0))  # page mm, over the drawing
    page_ax.set_xlim(0.0, pw)
    page_ax.set_ylim(0.0, ph)
    page_ax.set_axis_off()
    page_ax.add_patch(
        Rectangle(
            (PAGE_MARGIN_MM, FOOTER_MM), cw, ch, fill=False, edgecolor=ANNOTATION, linewidth=lw
        )
    )
    half = MARK_SIZE_MM / 2
    for point in registration_marks(tile, sheet.width, sheet.height, overlap):
        px, py = tile.to_page(point)
        for xs, ys in (([px - half, px + half], [py, py]), ([px, px], [py - half, py + half])):
            page_ax.add_line(Line2D(xs, ys, color=REGISTRATION, linewidth=lw))
        page_ax.add_patch(
            Circle((px, py), half / 2, fill=False, edgecolor=REGISTRATION, linewidth=lw)
        )
    # the bottom strip: check square, where this page goes, how to join the pages
    side = CHECK_SQUARE_MM
    sx, sy = PAGE_MARGIN_MM, FOOTER_MM - 4.0 - side
    page_ax.add_patch(Rectangle((sx, sy), side, side, fill=False, edgecolor="black", linewidth=lw))
    page_ax.text(sx + side / 2, sy - 0.8, "10 mm", fontsize=2.4 * _PT, ha="center", va="top")
    number, count = page
    lines = [
        f"sheet {tile.sheet}/{len(plan.sheets)} ({plan.cutter.name}), row {tile.row} of "
        f"{tile.rows}, column {tile.column} of {tile.columns}: page {number} of {count}",
        f"Print at 100 % (actual size) on {paper.name.upper() if paper.name == 'a4' else 'Letter'};"
        f" the square must measure 10 mm. Neighbouring pages overlap by {overlap:g} mm:",
        "trim one page along its frame, lay it over the next so the + marks coincide, tape.",
    ]
    if printed is not None and len(printed) < tile.rows * tile.columns:
        lines.append("Pages with nothing to cut are left out: dotted in the map at the right.")
    tx = sx + side + 4.0
    for k, text in enumerate(lines):
        page_ax.text(tx, sy + side - k * 4.0, text, fontsize=2.5 * _PT, ha="left", va="top")
    cell = 3.0  # a small map of the grid, this page filled
    gx = pw - PAGE_MARGIN_MM - tile.columns * cell
    gy = sy + side - tile.rows * cell
    for r in range(tile.rows):
        for c in range(tile.columns):
            here = (r + 1, c + 1) == (tile.row, tile.column)
            left_out = printed is not None and (r + 1, c + 1) not in printed
            page_ax.add_patch(
                Rectangle(
                    (gx + c * cell, gy + (tile.rows - 1 - r) * cell),
                    cell,
                    cell,
                    facecolor=ANNOTATION if here else "none",
                    edgecolor=ANNOTATION if left_out else "black",
                    linewidth=lw,
                    linestyle=(0, (1, 1.5)) if left_out else "solid",
                )
            )
    return fig


#: Text height (mm) of the tiled PDF's key page.
KEY_TEXT_MM = 3.0


def key_rows(
    plan: SheetPlan, operations: object | None = None, *, labels: bool = True
) -> list[LegendRow]:
    """The rows of the tiled PDF's key page: the fold map's legend
    (:func:`~corrugate.export.legend.fold_map_legend`), then for each sheet every labelled part's
    full label ("L1: layer 1: W 8 mm, ..."): a tile shows a part by its name where the full label
    does not fit (:func:`printed_labels`), and a page shows only its window of the sheet."""
    rows = fold_map_legend(operations, steps=False)  # the tiles' labels carry no step
    for number, sheet in enumerate(plan.sheets, start=1):
        parts = [label_text(place(p)) for p in sheet.placements if p.part.label] if labels else []
        if parts:
            rows.append(
                LegendRow(f"sheet {number}/{len(plan.sheets)}: the parts' labels", "#000000")
            )
            rows += [LegendRow(f"  {text}", ANNOTATION) for text in parts]
    return rows


def key_figure(
    plan: SheetPlan,
    paper: Paper,
    operations: object | None = None,
    *,
    labels: bool = True,
    page: tuple[int, int] = (1, 1),
) -> Figure:
    """The tiled PDF's key page on ``paper``: :func:`key_rows` from the top left at
    :data:`KEY_TEXT_MM`, shrunk to fit the page's height but never below 2 mm, each row in its
    kind's colour, and ``page`` (number, count) at the foot."""
    from matplotlib.figure import Figure

    pw, ph = paper.width, paper.height
    fig = Figure(figsize=(pw / 25.4, ph / 25.4))
    ax = fig.add_axes((0.0, 0.0, 1.0, 1.0))
    ax.set_xlim(0.0, pw)
    ax.set_ylim(0.0, ph)
    ax.set_axis_off()
    rows = key_rows(plan, operations, labels=labels)
    top, bottom = ph - PAGE_MARGIN_MM, FOOTER_MM
    size = max(min(KEY_TEXT_MM, (top - bottom - 8.0) / (1.6 * max(len(rows), 1))), 2.0)
    ax.text(PAGE_MARGIN_MM, top, "Key", fontsize=1.4 * KEY_TEXT_MM * _PT, ha="left", va="top")
    y = top - 2.4 * KEY_TEXT_MM
    for row in rows:
        ax.text(
            PAGE_MARGIN_MM, y, row.text, fontsize=size * _PT, ha="left", va="top", color=row.colour
        )
        y -= 1.6 * size
    number, count = page
    ax.text(
        PAGE_MARGIN_MM,
        FOOTER_MM / 2,
        f"page {number} of {count}: the key of the tiles (print any scale)",
        fontsize=2.5 * _PT,
        ha="left",
        va="center",
    )
    return fig


def render_tiled_pdf(
    plan: SheetPlan,
    path: Path,
    paper: str | Paper,
    style: LineStyle = SOLID,
    *,
    labels: bool = True,
    title: str = "",
    overlap: float = OVERLAP_MM,
    empty: bool = False,
    operations: object | None = None,
) -> None:
    """Draw ``plan`` as 1:1 tile pages of ``paper`` into a PDF at ``path`` directly (no staging:
    use :func:`write_tiled_pdf`); pages with nothing to cut are left out unless ``empty``; the
    last page is the key (:func:`key_figure`; ``operations``: the cut files' fold operations,
    which it names)."""
    PdfPages = pdf_pages()

    pp = paper if isinstance(paper, Paper) else get_paper(paper)
    check_style((p.part for p in plan.placements), style)
    tiles = plan_tiles(plan, pp, overlap, empty=empty)
    printed: dict[int, set[tuple[int, int]]] = {}
    for t in tiles:
        printed.setdefault(t.sheet, set()).add((t.row, t.column))
    metadata = {"Title": title, "Creator": "corrugate", "CreationDate": None}
    count = len(tiles) + 1
    with PdfPages(path, metadata=metadata) as pdf:
        for k, tile in enumerate(tiles, start=1):
            fig = tile_figure(
                plan,
                tile,
                pp,
                style,
                labels=labels,
                page=(k, count),
                overlap=overlap,
                printed=printed[tile.sheet],
            )
            pdf.savefig(fig)
        pdf.savefig(key_figure(plan, pp, operations, labels=labels, page=(count, count)))


def write_tiled_pdf(
    plan: SheetPlan,
    path: str | os.PathLike[str],
    paper: str | Paper,
    style: LineStyle = SOLID,
    *,
    labels: bool = True,
    title: str = "corrugate pattern, tiled",
    overlap: float = OVERLAP_MM,
    empty: bool = False,
    operations: object | None = None,
) -> Path:
    """Write ``plan`` as 1:1 tile pages of ``paper`` (``a4`` or ``letter``) to a PDF at ``path``
    (all or nothing); see :func:`sheet_tiles` and :func:`tile_figure`. Pages whose window holds
    no part are left out unless ``empty``; the last page is the key (:func:`key_figure`)."""
    pp = paper if isinstance(paper, Paper) else get_paper(paper)
    check_style((p.part for p in plan.placements), style)
    target = Path(path)
    with staged() as st:
        render_tiled_pdf(
            plan,
            st.path(target),
            pp,
            style,
            labels=labels,
            title=title,
            overlap=overlap,
            empty=empty,
            operations=operations,
        )
    return target
