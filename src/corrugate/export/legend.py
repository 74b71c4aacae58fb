"""The legend of a fold map and of a cut file: what each colour and line does, placed off the parts
(lengths in sheet mm, y up).

Each legend is a few rows of text, one per kind of line the file holds, in the palette's colour of
that kind (:mod:`corrugate.fabrication.palette`): :func:`fold_map_legend` for the fold map (its
first row says it is for people, not the cutter), :func:`cut_legend` for a cut file (the machine,
then each layer and what to set it to in the machine's software, :meth:`Machine.action`).

:func:`legend_spot` finds where it goes: a free box on the sheet, ``spacing`` mm clear of every
part's bounding box and of the PDF's check-square box, within the sheet's ``margin``, as low on the
sheet as there is room (the parts are packed from the top-left corner, so the free strip is at the
bottom). Text height is :data:`LEGEND_TEXT_MM` (2.5 mm), or smaller down to
:data:`MIN_LEGEND_TEXT_MM` (2 mm: a pen still draws it legibly) when the free box is smaller; a
row's box is 0.7 em per character long and 1.6 em tall. A cut file draws its legend as single-stroke glyphs
on the ``LEGEND`` layer (the pen: never a cutting layer); when no free box takes it, the cut file
has no legend (the fold map and docs/fabrication.md still give it) and the fold map puts its legend
in a strip below the sheet, which it is free to do as no machine reads it.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from corrugate.export.machines import Machine
from corrugate.fabrication.palette import LINES
from corrugate.fabrication.sheets import Sheet, free_spot

__all__ = [
    "LEGEND_TEXT_MM",
    "MIN_LEGEND_TEXT_MM",
    "LegendRow",
    "LegendSpot",
    "cut_legend",
    "fold_map_legend",
    "legend_size",
    "legend_spot",
    "row_length",
]

#: Text height (mm) of a legend, and the smallest it is drawn at.
LEGEND_TEXT_MM = 2.5
MIN_LEGEND_TEXT_MM = 2.0
_EM_LENGTH = 0.7  # box length per character, em (capitals are wider than 0.6 em)
_ROW = 1.6  # row pitch, em
_EPS = 1e-9


@dataclass(frozen=True, slots=True)
class LegendRow:
    """One row of a legend: its ``text`` and the ``colour`` (``#rrggbb``) of the kind it names."""

    text: str
    colour: str


@dataclass(frozen=True, slots=True)
class LegendSpot:
    """Where a legend goes: the lower-left corner (``x``, ``y``, sheet mm) of its box, the text
    height ``size`` (mm) and the box's ``width`` and ``height`` (mm)."""

    x: float
    y: float
    size: float
    width: float
    height: float

    def row_box(self, k: int, rows: int, length: float) -> tuple[float, float, float, float]:
        """The box (x0, y0, x1, y1) of row ``k`` (0: the top row) of ``rows``, ``length`` mm
        long."""
        pitch = _ROW * self.size
        top = self.y + self.height - (k + 1) * pitch + 0.2 * self.size
        return self.x, top, self.x + length, top + 1.2 * self.size


def row_length(text: str, size: float) -> float:
    """Length (mm) of the box of one row of ``text`` at text height ``size`` (mm)."""
    return _EM_LENGTH * size * len(text)


def legend_size(rows: list[LegendRow], size: float) -> tuple[float, float]:
    """Width and height (mm) of the box of ``rows`` at text height ``size`` (mm)."""
    longest = max(len(r.text) for r in rows)
    return _EM_LENGTH * size * longest, _ROW * size * len(rows)


def fold_map_legend(ops: object | None = None, *, steps: bool = True) -> list[LegendRow]:
    """The fold map's legend: for people, not the cutter; each colour's meaning and, with the fold
    operations ``ops`` (a :class:`~corrugate.export.operations.FoldOperations`), what the cut file
    does with each kind. ``steps``: the labels start with the part's step in the folding order
    (the fold map's do; the printed PDF's are the parts' names, and its legend says so)."""

    def made(kind: str) -> str:
        op = getattr(ops, kind, None)
        return "" if op is None else f" (cut file: {op.value})"

    return [
        LegendRow("FOLD MAP: for people, not the cutter (cut the cut-N file)", LINES["note"].hex),
        LegendRow(
            "red: mountain crease, fold towards you" + made("mountain"), LINES["mountain"].hex
        ),
        LegendRow("blue: valley crease, fold away" + made("valley"), LINES["valley"].hex),
        LegendRow("black: outline and holes, cut; green: slit, cut", LINES["cut"].hex),
        LegendRow("magenta: band mark, a crease end sits on it" + made("marks"), LINES["mark"].hex),
        LegendRow(
            "grey: labels, with the step in the folding order"
            if steps
            else "grey: labels, the parts' names (as ASSEMBLY.md's steps call them)",
            LINES["note"].hex,
        ),
    ]


def cut_legend(machine: Machine, layers: list[str]) -> list[LegendRow]:
    """The legend of a cut file for ``machine`` holding ``layers`` (in file order): the machine,
    then one row per layer with what it holds and what to set it to."""
    what = {
        "CUT": ("black", "outlines, holes, slits", "cut"),
        "MOUNTAIN": ("red", "mountain creases", "mountain"),
        "VALLEY": ("blue", "valley creases", "valley"),
        "MARK": ("magenta", "band angle marks", "mark"),
        "LABEL": ("grey", "part names", "note"),
        "LEGEND": ("grey", "this legend", "note"),
    }
    rows = [
        LegendRow(
            f"corrugate cut file, {machine.cutter.description}: set in {machine.software}",
            LINES["note"].hex,
        )
    ]
    for layer in [*layers, "LEGEND"] if "LEGEND" not in layers else layers:
        colour, content, kind = what[layer.split("-", 1)[0]]
        off = " or off" if layer in ("LABEL", "LEGEND") else ""
        rows.append(
            LegendRow(
                f"{colour} {layer}: {content} -> {machine.action(layer)}{off}", LINES[kind].hex
            )
        )
    return rows


def _free_box(
    sheet: Sheet,
    w: float,
    h: float,
    margin: float,
    spacing: float,
    blocked: Sequence[tuple[float, float, float, float]] = (),
) -> tuple[float, float] | None:
    """The lower-left corner of a ``w`` x ``h`` box inside the margins, ``spacing`` clear of every
    part, of the reserved box and of the boxes ``blocked``, lowest then leftmost; None if there
    is none."""
    boxes = [*(p.bounds for p in sheet.placements), *blocked]
    if sheet.reserved is not None:
        rx, ry, rw, rh = sheet.reserved
        boxes.append((rx, ry, rx + rw, ry + rh))
    return free_spot(boxes, sheet.width, sheet.height, w, h, margin, spacing, top_right=False)


def legend_spot(
    sheet: Sheet,
    rows: list[LegendRow],
    margin: float = 0.0,
    spacing: float = 0.0,
    blocked: Sequence[tuple[float, float, float, float]] = (),
) -> LegendSpot | None:
    """Where ``rows`` go on ``sheet`` (module docstring), off the boxes ``blocked`` too (the
    PDF's callouts), or None when no free box takes them at :data:`MIN_LEGEND_TEXT_MM`."""
    size = LEGEND_TEXT_MM
    while size >= MIN_LEGEND_TEXT_MM - _EPS:
        w, h = legend_size(rows, size)
        corner = _free_box(sheet, w, h, margin, spacing, blocked)
        if corner is not None:
            return LegendSpot(corner[0], corner[1], size, w, h)
        size -= 0.25
    return None
