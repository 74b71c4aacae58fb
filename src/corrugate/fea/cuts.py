"""Meshes cut to a plan outline and its holes: a staircase that converges to the true outline
as the mesh is refined (docs/fea.md 2.8), the crease strips cut as the rest. Lengths in mm, in
plan (x, y)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace

import numpy as np
from numpy.typing import NDArray

from corrugate.fea.ccx import SolverError
from corrugate.fea.shells import Shell
from corrugate.geometry.layer import Assembly

__all__ = ["cut_holes", "cut_outline", "inside_ring"]

FloatArray = NDArray[np.float64]


def inside_ring(xy: FloatArray, ring: FloatArray) -> NDArray[np.bool_]:
    """Whether each point of ``xy`` (k x 2) lies inside the closed polygon ``ring`` (m x 2):
    the even-odd rule, counting the ring's edges crossed by a ray along +x."""
    x, y = xy[:, 0][:, None], xy[:, 1][:, None]
    x0, y0 = ring[:, 0], ring[:, 1]
    x1, y1 = np.roll(x0, -1), np.roll(y0, -1)
    cond = (y0 > y) != (y1 > y)
    xc = x0 + (y - y0) * (x1 - x0) / np.where(y1 == y0, 1.0, y1 - y0)
    return np.asarray(np.count_nonzero(cond & (x < xc), axis=1) % 2 == 1)


def _centroids(sh: Shell, elems: list[list[int]], corners: int) -> FloatArray:
    index = {int(n): i for i, n in enumerate(sh.ids)}
    return np.array([sh.xyz[[index[n] for n in e[:corners]], :2].mean(axis=0) for e in elems])


def _kept(sh: Shell, keep: Callable[[list[list[int]], int], list[list[int]]]) -> Shell:
    """``sh`` with the elements ``keep`` keeps of each kind (S8R with 4 corners, S6 with 3; the
    crease strips' too, :func:`corrugate.fea.shells.crease_strip`), less the nodes none uses."""
    quads, tris = keep(sh.elements, 4), keep(sh.triangles, 3)
    s_quads, s_tris = keep(sh.strip_elements, 4), keep(sh.strip_triangles, 3)
    kinds = (quads, tris, s_quads, s_tris)
    if not any(kinds):
        raise SolverError("the outline leaves no element of the mesh")
    nodes = [n for elems in kinds for e in elems for n in e]
    used = np.isin(sh.ids, np.array(nodes, dtype=np.int64))
    return replace(
        sh,
        ids=sh.ids[used],
        xyz=sh.xyz[used],
        elements=quads,
        triangles=tris,
        strip_elements=s_quads,
        strip_triangles=s_tris,
    )


def cut_holes(sh: Shell, a: Assembly) -> Shell:
    """The shell less every element whose centroid (in plan) lies inside one of the layout's
    holes, and less the nodes no element uses: a staircase hole that converges to the true one as
    the mesh is refined."""
    from corrugate.geometry.holes import hole_rings

    rings = hole_rings(a.layout.holes, a.Lx, a.Ly)

    def keep(elems: list[list[int]], corners: int) -> list[list[int]]:
        if not elems:
            return elems
        xy = _centroids(sh, elems, corners)
        inside = np.zeros(len(elems), dtype=bool)
        for ring in rings:
            inside |= inside_ring(xy, ring)
        return [e for e, cut in zip(elems, inside, strict=True) if not cut]

    return _kept(sh, keep)


def cut_outline(sh: Shell, outline: FloatArray) -> Shell:
    """The shell less every element whose centroid (in plan) lies outside the closed polygon
    ``outline`` (k x 2, mm), and less the nodes no element uses (a staircase outline)."""

    def keep(elems: list[list[int]], corners: int) -> list[list[int]]:
        if not elems:
            return elems
        xy = _centroids(sh, elems, corners)
        inside = inside_ring(xy, np.asarray(outline, dtype=np.float64))
        return [e for e, ok in zip(elems, inside, strict=True) if ok]

    return _kept(sh, keep)
