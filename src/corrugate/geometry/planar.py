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
    """Whether two non-adjacent edges of the closed polygon ``v`` (N x 2) cross."""
    m = len(v)
    for i in range(m):
        for j in range(i + 2, m):
            if i == 0 and j == m - 1:
                continue
            if segments_cross(v[i], v[(i + 1) % m], v[j], v[(j + 1) % m]):
                return True
    return False
