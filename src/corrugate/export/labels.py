"""Where a part's label goes: a point well inside the part, and a text size that fits there (mm).

The anchor is the sampled point of the part (outline minus holes) farthest from every cut edge (a
coarse "pole of inaccessibility", so concave parts and parts with holes get their label on
material). The text runs along x or along y, whichever allows the larger letters, sized so that a
box of 0.6 em per character by 1.2 em fits the free runs from the anchor to the nearest cut edge.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..pattern.model import Point
from ..pattern.sheets import PlacedPart

__all__ = ["MAX_TEXT_MM", "LabelSpot", "label_spot"]

#: Largest label text height (mm).
MAX_TEXT_MM = 4.0
_GRID = 25


@dataclass(frozen=True, slots=True)
class LabelSpot:
    """A label's centre (``x``, ``y`` in sheet mm), text height ``size`` (mm) and ``rotation``
    (degrees counter-clockwise, 0 or 90)."""

    x: float
    y: float
    size: float
    rotation: float


def _segments(rings: list[tuple[Point, ...]]) -> NDArray[np.float64]:
    segs = []
    for ring in rings:
        p = np.asarray(ring, dtype=np.float64)
        segs.append(np.hstack([p, np.roll(p, -1, axis=0)]))
    return np.vstack(segs)


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


def label_spot(placed: PlacedPart) -> LabelSpot:
    """Where and how large to write ``placed``'s label (see the module docstring)."""
    outline = placed.outline
    p = np.asarray(outline, dtype=np.float64)
    lo, hi = p.min(axis=0), p.max(axis=0)
    gx = np.linspace(lo[0], hi[0], _GRID + 2)[1:-1]
    gy = np.linspace(lo[1], hi[1], _GRID + 2)[1:-1]
    pts = np.array([(x, y) for y in gy for x in gx] + [tuple((lo + hi) / 2)], dtype=np.float64)
    keep = _inside(pts, outline)
    for hole in placed.holes:
        keep &= ~_inside(pts, hole)
    pts = pts[keep]
    segs = _segments([outline, *placed.holes])
    if len(pts) == 0:  # degenerate sliver: write at the bounding-box centre
        c = (lo + hi) / 2
        return LabelSpot(float(c[0]), float(c[1]), 1.0, 0.0)
    dist = _distance(pts, segs)
    near = pts[dist >= 0.95 * dist.max()]  # of the nearly best, the one nearest the middle
    centre = (lo + hi) / 2
    best = near[int(np.argmin(np.hypot(*(near - centre).T)))]
    rx = min(_run(best, (1.0, 0.0), segs), _run(best, (-1.0, 0.0), segs))
    ry = min(_run(best, (0.0, 1.0), segs), _run(best, (0.0, -1.0), segs))
    chars = max(len(placed.part.label), 1)

    def fit(along: float, across: float) -> float:
        return min(MAX_TEXT_MM, 0.9 * 2 * along / (0.6 * chars), 0.9 * 2 * across / 1.2)

    horizontal, vertical = fit(rx, ry), fit(ry, rx)
    if vertical > horizontal * 1.05:
        return LabelSpot(float(best[0]), float(best[1]), vertical, 90.0)
    return LabelSpot(float(best[0]), float(best[1]), horizontal, 0.0)
