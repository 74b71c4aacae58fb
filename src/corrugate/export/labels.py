"""Where a part's label goes: a point on the part clear of every line, and a text size that fits
there (all lengths in mm).

The anchor is the sampled point of the part (outline minus holes) farthest from every line drawn on
it: the cut edges, the creases, the marks and the slits (a coarse "pole of inaccessibility", so
concave parts, parts with holes and the strips between creases get their label on bare material).
The text runs along x or along y, whichever allows the larger letters, sized so that its box, 0.6
em per character long by 1.2 em tall (:attr:`LabelSpot.length`, :attr:`LabelSpot.height`), fits
the free runs from the anchor (the anchor first moved to the middle of its free runs along x and
along y); the box, grown on every side by a gap of :data:`GAP_MM` plus a quarter of the text height
(:func:`label_gap`: a pen's or a scoring wheel's line and the glyphs' overshoot), is then checked
against every line and shrunk until it touches none, so no line runs through or along a label
(issue 36: a crease drawn on the "L" of "L1"). Writers fit the text into that box: the SVG fold map with ``textLength``, the cut
files with single-stroke glyphs scaled into it (:func:`label_strokes`).

On a printed sheet (the PDF and its tiles) a label is written at :data:`READABLE_TEXT_MM` (2 mm)
or more, turned a quarter only where the turned text is the larger; the full label falls back to
the part's name (the page's key gives the full label), and a name that does not fit on its part
at 2 mm either, a narrow strip's, is a callout (:func:`callout_spot`): written level at 2 mm
beside the part, off every part, with a leader to its spot on the part.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from typing import Any

import numpy as np
from numpy.typing import NDArray

from corrugate.fabrication.model import Line, Point
from corrugate.fabrication.sheets import PlacedPart

__all__ = [
    "GAP_MM",
    "MAX_TEXT_MM",
    "MIN_TEXT_MM",
    "READABLE_TEXT_MM",
    "LabelSpot",
    "callout_spot",
    "label_gap",
    "label_spot",
    "label_strokes",
    "label_text",
    "plain_text",
    "readable_label",
]

#: Largest label text height (mm).
MAX_TEXT_MM = 4.0
#: Smallest text height (mm) worth printing: a label that would be smaller is replaced by the
#: part's name where writers offer that (the fold map).
MIN_TEXT_MM = 1.2
#: Smallest text height (mm) a printed label is written at in full (the PDF's and the fold map's
#: "name: label"); below it the part carries its name only and the sheet's key the full label.
READABLE_TEXT_MM = 2.0
#: The least gap (mm) between a label's box and any line (plus a quarter of the text height).
GAP_MM = 0.5
_GRID = 25


def label_gap(size: float) -> float:
    """The clear gap (mm) kept between a label of text height ``size`` (mm) and every line."""
    return GAP_MM + 0.25 * size


@dataclass(frozen=True, slots=True)
class LabelSpot:
    """A label's centre (``x``, ``y`` in sheet mm), text height ``size`` (mm), ``rotation``
    (degrees counter-clockwise, 0 or 90) and the length of its box along the text (mm)."""

    x: float
    y: float
    size: float
    rotation: float
    length: float = 0.0

    @property
    def height(self) -> float:
        """Height of the label's box across the text (mm): 1.2 em."""
        return 1.2 * self.size

    def corners(self) -> tuple[Point, Point, Point, Point]:
        """The box's corners in sheet mm (counter-clockwise)."""
        hl, hh = self.length / 2, self.height / 2
        if self.rotation:
            hl, hh = hh, hl
        x, y = self.x, self.y
        return ((x - hl, y - hh), (x + hl, y - hh), (x + hl, y + hh), (x - hl, y + hh))


def label_text(placed: PlacedPart) -> str:
    """The text written on a part: its name (L1, L2, B1, ..., as ASSEMBLY.md's steps call it)
    and its label, or its name alone if it has no label."""
    name, label = placed.part.name, placed.part.label
    if not label or label.startswith(name):
        return label or name
    return f"{name}: {label}"


def _segments(rings: list[tuple[Point, ...]]) -> NDArray[np.float64]:
    segs = []
    for ring in rings:
        p = np.asarray(ring, dtype=np.float64)
        segs.append(np.hstack([p, np.roll(p, -1, axis=0)]))
    return np.vstack(segs)


def _box_clear(spot: LabelSpot, segs: NDArray[np.float64], gap: float = 0.0) -> bool:
    """Whether the (axis-aligned) box of ``spot``, grown by ``gap`` on every side, meets none of
    ``segs`` (Liang-Barsky clip)."""
    (x0, y0), _, (x1, y1), _ = spot.corners()
    x0, y0, x1, y1 = x0 - gap, y0 - gap, x1 + gap, y1 + gap
    ax, ay, bx, by = segs.T
    dx, dy = bx - ax, by - ay
    t0 = np.zeros(len(segs))
    t1 = np.ones(len(segs))
    hit = np.ones(len(segs), dtype=bool)
    for p, q in ((-dx, ax - x0), (dx, x1 - ax), (-dy, ay - y0), (dy, y1 - ay)):
        parallel = np.abs(p) < 1e-15
        hit &= ~(parallel & (q < 0))
        with np.errstate(divide="ignore", invalid="ignore"):
            r = np.where(parallel, 0.0, q / np.where(parallel, 1.0, p))
        t0 = np.where(~parallel & (p < 0), np.maximum(t0, r), t0)
        t1 = np.where(~parallel & (p > 0), np.minimum(t1, r), t1)
    return not bool(np.any(hit & (t0 <= t1)))


def _inside(points: NDArray[np.float64], ring: tuple[Point, ...]) -> NDArray[np.bool_]:
    """Even-odd point-in-polygon test for many points."""
    p = np.asarray(ring, dtype=np.float64)
    x0, y0 = p[:, 0], p[:, 1]
    x1, y1 = np.roll(x0, -1), np.roll(y0, -1)
    px, py = points[:, :1], points[:, 1:]
    crosses = (y0 > py) != (y1 > py)
    with np.errstate(divide="ignore", invalid="ignore"):
        xs = x0 + (py - y0) * (x1 - x0) / (y1 - y0)
    hits = crosses & (px < xs)
    return np.asarray(np.count_nonzero(hits, axis=1) % 2 == 1)


def _distance(points: NDArray[np.float64], segs: NDArray[np.float64]) -> NDArray[np.float64]:
    a, b = segs[None, :, :2], segs[None, :, 2:]
    d = b - a
    q = points[:, None, :]
    dd = np.maximum(np.sum(d * d, axis=2), 1e-300)
    t = np.clip(np.sum((q - a) * d, axis=2) / dd, 0.0, 1.0)
    closest = a + t[..., None] * d
    return np.asarray(np.min(np.hypot(*(q - closest).transpose(2, 0, 1)), axis=1))


def _run(
    origin: NDArray[np.float64], direction: tuple[float, float], segs: NDArray[np.float64]
) -> float:
    """Distance from ``origin`` along ``direction`` to the first segment it meets."""
    ox, oy = origin
    dx, dy = direction
    ax, ay, bx, by = segs.T
    ex, ey = bx - ax, by - ay
    den = dx * ey - dy * ex
    with np.errstate(divide="ignore", invalid="ignore"):
        t = ((ax - ox) * ey - (ay - oy) * ex) / den
        u = ((ax - ox) * dy - (ay - oy) * dx) / den
    ok = (np.abs(den) > 1e-12) & (t > 0) & (u >= 0) & (u <= 1)
    return float(np.min(t[ok])) if np.any(ok) else 0.0


@dataclass(frozen=True, slots=True)
class _Anchor:
    """What :func:`label_spot` finds on a part whatever its text: the bounding box ``lo``-``hi``,
    the anchor ``best`` (None on a degenerate sliver with no sample inside), the free runs ``rx``
    along x and ``ry`` along y from it, and the part's lines ``segs`` (mm)."""

    lo: tuple[float, float]
    hi: tuple[float, float]
    best: tuple[float, float] | None
    rx: float
    ry: float
    segs: NDArray[np.float64]


@lru_cache(maxsize=256)
def _anchor(
    outline: tuple[Point, ...], holes: tuple[tuple[Point, ...], ...], lines: tuple[Line, ...]
) -> _Anchor:
    """The text-free part of :func:`label_spot` for a placed part's outline, holes and lines
    (sheet mm), kept for the next writer: the fold map, the PDF and the cut files label the same
    placed parts (with their own texts)."""
    p = np.asarray(outline, dtype=np.float64)
    lo, hi = p.min(axis=0), p.max(axis=0)
    gx = np.linspace(lo[0], hi[0], _GRID + 2)[1:-1]
    gy = np.linspace(lo[1], hi[1], _GRID + 2)[1:-1]
    pts = np.array([(x, y) for y in gy for x in gx] + [tuple((lo + hi) / 2)], dtype=np.float64)
    keep = _inside(pts, outline)
    for hole in holes:
        keep &= ~_inside(pts, hole)
    pts = pts[keep]
    segs = _segments([outline, *holes])
    if lines:
        segs = np.vstack([segs, np.array([(*ln.a, *ln.b) for ln in lines], dtype=np.float64)])
    box = (float(lo[0]), float(lo[1])), (float(hi[0]), float(hi[1]))
    if len(pts) == 0:
        return _Anchor(*box, None, 0.0, 0.0, segs)
    dist = _distance(pts, segs)
    near = pts[dist >= 0.95 * dist.max()]  # of the nearly best, the one nearest the middle
    centre = (lo + hi) / 2
    best = near[int(np.argmin(np.hypot(*(near - centre).T)))]
    # to the middle of its free runs (the grid's point may sit off the middle of a strip)
    # (kept only where it is at least as far from every line as the grid's point)
    for axis in ((1.0, 0.0), (0.0, 1.0)):
        ahead, back = _run(best, axis, segs), _run(best, (-axis[0], -axis[1]), segs)
        moved = best + (ahead - back) / 2 * np.asarray(axis)
        if (
            ahead > 0
            and back > 0
            and _distance(moved[None], segs)[0] >= _distance(best[None], segs)[0]
        ):
            best = moved
    rx = min(_run(best, (1.0, 0.0), segs), _run(best, (-1.0, 0.0), segs))
    ry = min(_run(best, (0.0, 1.0), segs), _run(best, (0.0, -1.0), segs))
    return _Anchor(*box, (float(best[0]), float(best[1])), rx, ry, segs)


def label_spot(placed: PlacedPart, text: str | None = None) -> LabelSpot:
    """Where and how large to write ``text`` (default :func:`label_text`) on ``placed``, clear of
    every line on it (see the module docstring)."""
    text = label_text(placed) if text is None else text
    found = _anchor(placed.outline, placed.holes, placed.lines)
    segs = found.segs
    chars = max(len(text), 1)
    if found.best is None:  # degenerate sliver: write at the bounding-box centre
        c = (np.asarray(found.lo) + np.asarray(found.hi)) / 2
        return LabelSpot(float(c[0]), float(c[1]), 1.0, 0.0, 0.6 * chars)
    rx, ry = found.rx, found.ry

    def fit(along: float, across: float) -> float:  # the runs less the gap of a MAX_TEXT_MM text
        along, across = (max(r - label_gap(MAX_TEXT_MM), 0.5 * r) for r in (along, across))
        return min(MAX_TEXT_MM, 0.9 * 2 * along / (0.6 * chars), 0.9 * 2 * across / 1.2)

    horizontal, vertical = fit(rx, ry), fit(ry, rx)
    rotation, size = (90.0, vertical) if vertical > horizontal * 1.05 else (0.0, horizontal)
    x, y = found.best
    spot = LabelSpot(x, y, size, rotation, 0.6 * chars * size)
    for _ in range(40):  # a slanted edge or the gap may still cut the box: shrink until clear
        if _box_clear(spot, segs, label_gap(size)):
            break
        size *= 0.85
        spot = LabelSpot(x, y, size, rotation, 0.6 * chars * size)
    return spot


def readable_label(placed: PlacedPart, text: str, short: str) -> tuple[str, LabelSpot, bool]:
    """The label a printed sheet writes on ``placed`` (the fold map, the PDF): ``text`` where it
    fits clear of every line at :data:`READABLE_TEXT_MM` or more, else ``short`` (the part's name)
    at the size that fits; returns the text written, its spot and whether it was shortened (the
    sheet's key then gives ``text``)."""
    spot = label_spot(placed, text)
    if spot.size >= READABLE_TEXT_MM or text == short:
        return text, spot, False
    return short, label_spot(placed, short), True


Box = tuple[float, float, float, float]


def callout_spot(
    placed: PlacedPart, text: str, blocked: list[Box], width: float, height: float
) -> LabelSpot | None:
    """Where ``text`` goes as a callout of ``placed`` on a ``width`` x ``height`` sheet: level, at
    :data:`READABLE_TEXT_MM`, its box grown by :func:`label_gap` inside the sheet and off every box
    (x0, y0, x1, y1) of ``blocked`` (the parts' bounds, the check square's and the callouts
    placed before); tried above, below, right of and left of the part's bounds, the text centred
    on its label spot, then slid along the side. None when no such place is free (the caller
    writes the name small on the part; the key still gives it)."""
    size = READABLE_TEXT_MM
    length, tall = 0.6 * max(len(text), 1) * size, 1.2 * size
    gap = label_gap(size)
    pts = np.asarray(placed.outline, dtype=np.float64)
    x0, y0 = pts.min(axis=0)
    x1, y1 = pts.max(axis=0)
    anchor = label_spot(placed, text)
    hl, hh = length / 2 + gap, tall / 2 + gap
    along_x = [anchor.x, (x0 + x1) / 2, x0 + hl, x1 - hl]
    along_y = [anchor.y, (y0 + y1) / 2, y0 + hh, y1 - hh]
    sides = [(cx, y1 + hh) for cx in along_x] + [(cx, y0 - hh) for cx in along_x]
    sides += [(x1 + hl, cy) for cy in along_y] + [(x0 - hl, cy) for cy in along_y]
    for cx, cy in sides:
        box = (cx - hl, cy - hh, cx + hl, cy + hh)
        if box[0] < 0 or box[1] < 0 or box[2] > width or box[3] > height:
            continue
        if all(
            box[2] <= b[0] or b[2] <= box[0] or box[3] <= b[1] or b[3] <= box[1] for b in blocked
        ):
            return LabelSpot(float(cx), float(cy), size, 0.0, length)
    return None


#: Characters outside the stroke font's printable ASCII, written as the font can draw them.
_PLAIN = {"°": " deg", "×": "x", "µ": "u", "–": "-", "—": "-", "≤": "<=", "≥": ">=", "·": "."}


@lru_cache(maxsize=1)
def _font() -> Any:
    """The Hershey Simplex Roman font (``futural``, single-stroke) of the Hershey-Fonts package."""
    from HersheyFonts import HersheyFonts

    font = HersheyFonts()
    # load_default_font first lists the package's fonts to check the name, which decompresses
    # its whole archive once more (bz2); naming the list here leaves one decompression: 0.008 s
    # of CPU less per process that writes a cut file (issue 39; the same glyphs,
    # tests/export/test_labels.py). That one reads the whole archive too, though futural is its
    # first member: tarfile lists every member to find one by name, and the archive is a single
    # bz2 block (245 760 bytes, 4.3 ms of CPU to decompress, 16:10 UTC). A version of the package
    # without that attribute ignores it and checks the name as before.
    font._HersheyFonts__default_font_names_list = ["futural"]
    font.load_default_font("futural")
    font.normalize_rendering(1.0)
    return font


def plain_text(text: str) -> str:
    """``text`` in the characters the stroke font draws: printable ASCII, with ``°``, ``×``,
    ``µ``, dashes and ``≤``/``≥`` spelt out (:data:`_PLAIN`) and any other character as ``?``."""
    out = []
    for ch in text:
        ch = _PLAIN.get(ch, ch)
        out.append(ch if all(32 <= ord(c) < 127 for c in ch) else "?")
    return "".join(out)


def label_strokes(spot: LabelSpot, text: str) -> list[list[Point]]:
    """The pen strokes of ``text`` as open polylines (sheet mm), scaled to fit the box of ``spot``
    and centred in it, for files that take no text (cut files: a pen draws each stroke once, a
    laser engraves it as a line). Single-stroke glyphs of the Hershey Simplex Roman font (the
    Hershey-Fonts package): a pen's tip traces each letter once, where an outline font's glyphs
    drawn by a pen are the letters' contours, which run together at a few mm.

    In floats, point by point (a legend is hundreds of strokes of a few points each, where numpy's
    cost per array was most of the time; issue 39): the same arithmetic, so the same numbers."""
    strokes = [
        [(float(x), float(y)) for x, y in s]
        for s in _font().strokes_for_text(plain_text(text))
        if len(s) >= 2
    ]
    if not strokes:
        return []
    xs = [x for s in strokes for x, _ in s]
    ys = [y for s in strokes for _, y in s]
    x0, x1, y0, y1 = min(xs), max(xs), min(ys), max(ys)
    scale = min(spot.length / max(x1 - x0, 1e-9), spot.height / max(y1 - y0, 1e-9))
    mx, my = (x0 + x1) / 2, (y0 + y1) / 2
    out: list[list[Point]] = []
    for s in strokes:
        local = [((x - mx) * scale, (y - my) * scale) for x, y in s]
        if spot.rotation:  # a quarter turn counter-clockwise
            local = [(-v, u) for u, v in local]
        out.append([(u + spot.x, v + spot.y) for u, v in local])
    return out
