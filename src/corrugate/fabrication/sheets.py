"""Sheet layout: the parts of a pattern arranged on the sheets (mats, beds) of a cutter.

All lengths are in mm. A sheet's coordinates start at (0, 0) in the lower-left corner of the
cutter's usable cut area, x to the right and y up (as in DXF and in the parts' own coordinates);
the SVG writer flips y so that nothing is mirrored. A part is placed as it is or turned 90 deg
counter-clockwise (a rotation, never a mirror, so mountain stays mountain), with ``spacing`` between
parts and ``margin`` to the edges of the usable area.

Cutters (``get_cutter``):

``cameo4-12x12``, ``cameo4-12x24``
    Silhouette Cameo 4 on its 12 x 12 in and 12 x 24 in mats. The mat's adhesive area is 12 x 12 in
    (12 x 24 in); the rollers grip a non-adhesive border outside it (about 1/4 in at the sides,
    1 in at the ends; smart-silhouette.com, "cut border"). Silhouette America quotes only the
    12 in maximum cutting width. **Assumption:** the cut border that Silhouette Studio draws keeps
    about 1/4 in inside the adhesive area on each side, so the usable area is taken as
    11.5 x 11.5 in = 292.1 x 292.1 mm (11.5 x 23.5 in = 292.1 x 596.9 mm), the same as Cricut's
    stated maximum cut size for mats of the same size. The paper (Liu, Yan and Mehta, case study)
    uses a more conservative 250 mm working space; ask for ``laser:250x250`` to reproduce it.
``maker-12x12``, ``maker-12x24``
    Cricut Maker on its 12 x 12 in and 12 x 24 in mats: maximum cut size 11.5 x 11.5 in and
    11.5 x 23.5 in, as Cricut's help centre states (292.1 x 292.1 mm, 292.1 x 596.9 mm).
``laser:WxH``
    A generic laser (or any flat-bed) cutter whose usable bed is W x H mm, e.g. ``laser:600x400``.

The packer is a deterministic shelf packer (first fit, decreasing height): parts sorted by height,
each one put on the first shelf of the first sheet where it fits, in the orientation that keeps
shelves low; new shelves and sheets are opened as needed. Shelves start at the top edge and go
down, parts start at the left edge: a cutting mat's origin is its top-left corner, so the parts sit
there and an unused part of the mat is a strip at its bottom (or right), easy to cut off and reuse.
Each sheet also gets a small free box for the PDF's 10 mm check square (see :data:`CHECK_BOX`):
the parts are packed first without it and a free spot is looked for on every sheet; if some sheet
has none, the parts are packed again with the bottom-right corner of every sheet kept free (a
sheet holding a part too large for that gets no box).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field

from corrugate.core.cutters import CUTTERS, Cutter, get_cutter
from corrugate.core.errors import InputError
from corrugate.core.limits import LIMITS, abnormal_reason, is_normal
from corrugate.fabrication.model import Line, Part, Pattern, Point
from corrugate.names import DEFAULT_MACHINE, DEFAULT_MARGIN_MM, DEFAULT_SPACING_MM

__all__ = [
    "CHECK_BOX",
    "CUTTERS",
    "Cutter",
    "PartTooLargeError",
    "PlacedPart",
    "Placement",
    "Sheet",
    "SheetPlan",
    "free_spot",
    "get_cutter",
    "place",
    "plan_sheets",
]

#: Width and height (mm) of the box kept free in the top-right corner of each sheet for the PDF's
#: 10 mm check square and its "10 mm" label.
CHECK_BOX: tuple[float, float] = (16.0, 20.0)
_EPS = 1e-9


class PartTooLargeError(InputError):
    """A part does not fit on the cutter's sheet in either orientation."""


@dataclass(frozen=True, slots=True)
class Placement:
    """Where one part goes: on sheet number ``sheet`` (0-based; files are numbered from 1), with
    the lower-left corner of its (possibly rotated) bounding box at (``x``, ``y``) mm; ``rotated``
    means turned 90 deg counter-clockwise."""

    part: Part
    sheet: int
    x: float
    y: float
    rotated: bool = False

    @property
    def size(self) -> tuple[float, float]:
        """Width and height (mm) of the part's bounding box as placed."""
        w, h = self.part.size
        return (h, w) if self.rotated else (w, h)

    @property
    def bounds(self) -> tuple[float, float, float, float]:
        """(xmin, ymin, xmax, ymax) of the placed part on its sheet (mm)."""
        w, h = self.size
        return self.x, self.y, self.x + w, self.y + h

    def transform(self, point: Point) -> Point:
        """A point of the part (its own coordinates, mm) in sheet coordinates (mm)."""
        return self.mapping()(point)

    def mapping(self) -> Callable[[Point], Point]:
        """The rigid motion part -> sheet as a function (computes the part's origin once)."""
        pts = self.part.outline
        x0 = min(p[0] for p in pts)
        y0 = min(p[1] for p in pts)
        h = max(p[1] for p in pts) - y0
        X, Y = self.x, self.y
        if self.rotated:  # 90 deg counter-clockwise, then back into the box
            return lambda p: (X + h - (p[1] - y0), Y + (p[0] - x0))
        return lambda p: (X + (p[0] - x0), Y + (p[1] - y0))


@dataclass(frozen=True, slots=True)
class Sheet:
    """One sheet (mat or bed) of ``width`` x ``height`` mm, the usable cut area, with its parts.

    ``reserved`` is the box (x, y, w, h in mm) kept free for the PDF's check square, or ``None``.
    """

    width: float
    height: float
    placements: tuple[Placement, ...]
    reserved: tuple[float, float, float, float] | None = None


@dataclass(frozen=True, slots=True)
class SheetPlan:
    """Every sheet needed to cut a pattern on ``cutter``, with the ``spacing`` between parts and the
    ``margin`` to the sheet edges used (mm)."""

    cutter: Cutter
    sheets: tuple[Sheet, ...]
    spacing: float = DEFAULT_SPACING_MM
    margin: float = DEFAULT_MARGIN_MM

    @property
    def placements(self) -> tuple[Placement, ...]:
        """Every placement, sheet by sheet."""
        return tuple(p for s in self.sheets for p in s.placements)


@dataclass(frozen=True, slots=True)
class PlacedPart:
    """A part's geometry in sheet coordinates (mm): the same outline, holes and lines, moved."""

    placement: Placement
    outline: tuple[Point, ...]
    holes: tuple[tuple[Point, ...], ...]
    lines: tuple[Line, ...]

    @property
    def part(self) -> Part:
        return self.placement.part


def place(placement: Placement) -> PlacedPart:
    """The outline, holes and lines of a placed part in sheet coordinates (mm).

    Lines keep their role and fold angle; a crease's index in ``lines`` is its index in the part.
    """
    t = placement.mapping()
    return PlacedPart(
        placement=placement,
        outline=tuple(t(p) for p in placement.part.outline),
        holes=tuple(tuple(t(p) for p in hole) for hole in placement.part.holes),
        lines=tuple(
            Line(t(ln.a), t(ln.b), ln.role, ln.fold_angle_deg) for ln in placement.part.lines
        ),
    )


# ----------------------------------------------------------------------------------------------
# the packer


@dataclass(slots=True)
class _Shelf:
    y: float
    height: float
    x: float  # next free x
    limit: float  # largest x a part may reach on this shelf


@dataclass(slots=True)
class _SheetState:
    width: float
    height: float
    margin: float
    spacing: float
    reserved: tuple[float, float, float, float] | None
    shelves: list[_Shelf] = field(default_factory=list)
    placements: list[Placement] = field(default_factory=list)

    def next_y(self) -> float:
        if not self.shelves:
            return self.margin
        last = self.shelves[-1]
        return last.y + last.height + self.spacing

    def shelf_limit(self, y: float, h: float) -> float:
        right = self.width - self.margin
        if self.reserved is None:
            return right
        rx, ry, _, _ = self.reserved
        return rx - self.spacing if y + h > ry - self.spacing + _EPS else right


def _orientations(part: Part, uw: float, uh: float) -> list[tuple[float, float, bool]]:
    """The orientations (w, h, rotated) that fit a usable area uw x uh, lowest first."""
    w, h = part.size
    options = [(w, h, False), (h, w, True)]
    if math.isclose(w, h, rel_tol=0.0, abs_tol=_EPS):
        options = options[:1]
    fits = [o for o in options if o[0] <= uw + _EPS and o[1] <= uh + _EPS]
    return sorted(fits, key=lambda o: (o[1], o[2]))


def _try_place(
    state: _SheetState, index: int, part: Part, options: list[tuple[float, float, bool]]
) -> bool:
    for shelf in state.shelves:
        for w, h, rot in options:
            if h <= shelf.height + _EPS and shelf.x + w <= shelf.limit + _EPS:
                state.placements.append(Placement(part, index, shelf.x, shelf.y, rot))
                shelf.x += w + state.spacing
                return True
    y = state.next_y()
    for w, h, rot in options:
        if y + h > state.height - state.margin + _EPS:
            continue
        limit = state.shelf_limit(y, h)
        if state.margin + w <= limit + _EPS:
            state.shelves.append(_Shelf(y, h, state.margin + w + state.spacing, limit))
            state.placements.append(Placement(part, index, state.margin, y, rot))
            return True
    return False


def plan_sheets(
    parts: Pattern | Iterable[Part],
    cutter: str | Cutter = DEFAULT_MACHINE,
    *,
    spacing: float = DEFAULT_SPACING_MM,
    margin: float = DEFAULT_MARGIN_MM,
    reserve: tuple[float, float] | None = CHECK_BOX,
) -> SheetPlan:
    """Arrange ``parts`` on as many sheets of ``cutter`` as needed (deterministic).

    ``spacing`` (mm) is the least distance between the bounding boxes of two parts, ``margin`` (mm)
    the least distance from a part to the edge of the usable area. ``reserve`` (w, h in mm) is a box
    kept free for the PDF check square, in the bottom-right corner when no other spot is left
    (``None``: none). Parts are packed from the top-left corner (see the module docstring).

    Raises :class:`PartTooLargeError` (an :class:`~corrugate.core.errors.InputError`) naming the part and
    its size when it fits the sheet in neither orientation, an ``InputError`` when two parts have
    the same name, and
    :class:`~corrugate.core.errors.UnknownNameError` for an unknown cutter.
    """
    cut = get_cutter(cutter)
    longest = LIMITS["length"].hi
    for name, value in (("spacing", spacing), ("margin", margin)):
        if not (is_normal(value) and 0 <= value <= longest):
            allowed = f"0 <= {name} <= {longest:g} mm"
            raise InputError(
                name, f"{value} mm", allowed, reason=abnormal_reason(value) or "is out of range"
            )
    seq: Sequence[Part] = parts.parts if isinstance(parts, Pattern) else tuple(parts)
    uw, uh = cut.width - 2 * margin, cut.height - 2 * margin
    if uw <= 0 or uh <= 0:
        raise InputError(
            "margin",
            f"{margin} mm",
            f"less than half the sheet ({cut.width:.1f} x {cut.height:.1f} mm of {cut.name})",
        )

    seen: set[str] = set()
    for part in seq:  # writers name parts and creases by part name
        if part.name in seen:
            raise InputError(
                "part name",
                repr(part.name),
                "a different name for every part",
                reason="is used twice",
            )
        seen.add(part.name)
    items: list[tuple[Part, list[tuple[float, float, bool]]]] = []
    for part in seq:
        options = _orientations(part, uw, uh)
        if not options:
            w, h = part.size
            raise PartTooLargeError(
                f"part {part.name!r}",
                f"{w:.1f} x {h:.1f} mm",
                f"a part that fits the usable area of {cut.name}, {uw:.1f} x {uh:.1f} mm "
                f"({cut.width:.1f} x {cut.height:.1f} mm less {margin:g} mm margins), "
                "turned 90 deg or not",
                reason="does not fit on the sheet",
            )
        items.append((part, options))
    order = sorted(range(len(items)), key=lambda i: (-items[i][1][0][1], -items[i][1][0][0], i))

    def pack(reserved: tuple[float, float, float, float] | None) -> list[_SheetState]:
        states: list[_SheetState] = []
        for i in order:
            part, options = items[i]
            if any(_try_place(s, k, part, options) for k, s in enumerate(states)):
                continue
            for res in (reserved, None) if reserved is not None else (None,):
                state = _SheetState(cut.width, cut.height, margin, spacing, res)
                if _try_place(state, len(states), part, options):
                    states.append(state)
                    break
            else:  # pragma: no cover - options fit an empty sheet without reservation
                raise AssertionError(f"part {part.name!r} fits no empty sheet")
        return states

    def sheet(state: _SheetState, box: tuple[float, float, float, float] | None) -> Sheet:
        # The packer fills shelves from y = margin upwards; the mat's origin is its top-left
        # corner, so the plan is mirrored top to bottom (the positions only: parts keep their
        # orientation) and the first shelf lies along the top edge.
        H = state.height
        placements = tuple(
            Placement(p.part, p.sheet, p.x, H - p.y - p.size[1], p.rotated)
            for p in state.placements
        )
        flipped = None if box is None else (box[0], H - box[1] - box[3], box[2], box[3])
        return Sheet(state.width, H, placements, flipped)

    # First without a reserved box; keep that if every sheet has a free spot for the box anyway.
    states = pack(None)
    if reserve is None:
        return SheetPlan(cut, tuple(sheet(s, None) for s in states), spacing, margin)
    rw, rh = reserve
    spots = [_free_box(s, rw, rh) for s in states]
    # else keep a corner free from the start (the packer's top right, the sheet's bottom right)
    if any(spot is None for spot in spots):
        states = pack((cut.width - margin - rw, cut.height - margin - rh, rw, rh))
        spots = [s.reserved or _free_box(s, rw, rh) for s in states]
    return SheetPlan(cut, tuple(map(sheet, states, spots)), spacing, margin)


def free_spot(
    boxes: Sequence[tuple[float, float, float, float]],
    width: float,
    height: float,
    w: float,
    h: float,
    margin: float,
    spacing: float,
    *,
    top_right: bool,
) -> tuple[float, float] | None:
    """The lower-left corner (mm) of a ``w`` x ``h`` box inside the ``margin`` of a ``width`` x
    ``height`` sheet, ``spacing`` clear of every box (x0, y0, x1, y1) of ``boxes``: among the
    candidate positions (the margins and the edges of the boxes), the one nearest the top-right
    corner (``top_right``) or the bottom-left one; None if there is none."""
    m, sp = margin, spacing
    xs = {m, width - m - w} | {b[2] + sp for b in boxes} | {b[0] - sp - w for b in boxes}
    ys = {m, height - m - h} | {b[3] + sp for b in boxes} | {b[1] - sp - h for b in boxes}
    for y in sorted(ys, reverse=top_right):
        for x in sorted(xs, reverse=top_right):
            if x < m - _EPS or y < m - _EPS:
                continue
            if x + w > width - m + _EPS or y + h > height - m + _EPS:
                continue
            if all(
                x + w + sp <= b[0] + _EPS
                or b[2] + sp <= x + _EPS
                or y + h + sp <= b[1] + _EPS
                or b[3] + sp <= y + _EPS
                for b in boxes
            ):
                return x, y
    return None


def _free_box(state: _SheetState, w: float, h: float) -> tuple[float, float, float, float] | None:
    """A w x h box (x, y, w, h) inside the margins of a packed sheet, ``spacing`` away from every
    part, as near the top-right corner as candidate positions allow; ``None`` if there is none."""
    boxes = [p.bounds for p in state.placements]
    spot = free_spot(
        boxes, state.width, state.height, w, h, state.margin, state.spacing, top_right=True
    )
    return None if spot is None else (spot[0], spot[1], w, h)
