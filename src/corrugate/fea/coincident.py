"""Coincident mesh points found by position: one integer key per place, the same for two points
computed by different arithmetic (a layer's node and the band's point on it, docs/fea.md 2.3).

A point's key is its coordinates rounded to multiples of ``tol`` (mm). Rounding alone is not
enough: where the mesh spacing is commensurate with ``tol`` a coordinate falls on a rounding tie
(c / tol = i + 1/2 exactly), and two copies of one point that differ by one unit in the last
place round to i and to i + 1. That split the connector band from its layers at 16 elements
per facet on a 48.3 mm panel of 8 facets (tol = 1e-7 x 48.3 mm, the stations at odd multiples
of pitch / 32: c / tol = (2 k + 1) x 39062.5), "46 layer edge nodes do not meet the band's
mesh". :class:`CoincidentKeys` gives a point the key of a point already seen within half a
``tol`` in every coordinate, whichever way it rounds.
"""

from __future__ import annotations

import itertools
import math

__all__ = ["CoincidentKeys", "Key"]

Key = tuple[int, int, int]

#: A coordinate this far (in units of tol) from its rounded value may have a copy that rounds
#: to the neighbouring integer; its neighbour's key is looked up too.
_NEAR_TIE = 0.25


class CoincidentKeys:
    """The keys of points in 3-space (mm): :meth:`key` returns the key of a point seen before
    whose coordinates each lie within ``tol`` / 2 of it (the first such point's), else the new
    point's own key, its coordinates rounded to multiples of ``tol``. Points whose coordinates
    differ by less than ``tol`` / 4 always share a key; points ``tol`` or more apart in a
    coordinate never do."""

    def __init__(self, tol: float) -> None:
        if not (math.isfinite(tol) and tol > 0):
            raise ValueError(f"tol must be a positive number, not {tol!r}")
        self.tol = tol
        self._seen: dict[Key, tuple[float, float, float]] = {}

    def key(self, x: float, y: float, z: float) -> Key:
        """The key of the point (x, y, z), registering it when it is new (class docstring)."""
        xyz = (x, y, z)
        scaled = [c / self.tol for c in xyz]
        own = tuple(round(s) for s in scaled)
        k: Key = (own[0], own[1], own[2])
        if k in self._seen:
            return k
        options = []
        for s, r in zip(scaled, own, strict=True):
            d = s - r
            options.append((r, r + (1 if d > 0 else -1)) if abs(d) > _NEAR_TIE else (r,))
        for cand in itertools.product(*options):
            c: Key = (cand[0], cand[1], cand[2])
            p = self._seen.get(c)
            if p is not None and all(
                abs(a - b) <= self.tol / 2 for a, b in zip(p, xyz, strict=True)
            ):
                return c
        self._seen[k] = xyz
        return k
