"""Shell mesh of a folded layer over a disc with a central circular hole that conforms to the
rim and the hole (gmsh; docs/fea.md 2.8). Lengths in mm, in plan (x, y).

The structured mesh cut to a staircase (:mod:`corrugate.fea.cuts`) changes its rim, its hole
and the wheel's ground patch with every mesh, so a wheel's mesh series turns instead of
settling (docs/load_cases.md 9). Here the plan of the disc is cut into bands across the creases
by the lines u = const (u the chordwise coordinate) of every crease (and of the crease strips'
edges), of the disc's centre, of the hole's two sides and of each given rim point (the wheel's
patch ends); each band is split by the diameter along u into two cells, each with four sides
(three at the rim's two tangent points): two of its band's lines, the rim's arc, and the
diameter or the hole's arc. Each cell is meshed by transfinite interpolation (a mapped,
structured mesh): every mesh has the same rim, the same hole and the same rim points, every
element lies in one flat facet, so lifting its nodes onto the folded surface
(:class:`corrugate.fea.planmesh.Corrugation`) is exact, and a mesh with twice as many elements
per facet splits every element of the one before in four (even ``along``): the series are
nested. A band w wide gets (along / 2) max(1, round(2 w / p)) elements across (p the pitch;
``along`` across a whole facet), every cell (along / 2) max(1, round(2 R / p)) from its
diameter or hole to the rim (R the disc's radius). 8-node quadrilaterals (S8R), 6-node
triangles (S6) at the tangent points, normals on the +z side.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from corrugate.fea.ccx import SolverError
from corrugate.fea.coincident import CoincidentKeys, Key
from corrugate.fea.planmesh import Corrugation, PlanMesh, gmsh_mesh, gmsh_plan

__all__ = ["Disc", "disc_mesh", "divisions"]

FloatArray = NDArray[np.float64]
Point = tuple[float, float]


@dataclass(frozen=True, slots=True)
class Disc:
    """A disc of radius ``R`` centred at ``centre`` (plan, mm) less a concentric hole of radius
    ``r`` (0: none), 0 <= r < R."""

    centre: tuple[float, float]
    R: float
    r: float = 0.0


def divisions(width: float, pitch: float, along: int) -> int:
    """The number of elements across a length ``width`` (mm) at ``along`` elements per
    ``pitch`` (mm): (along / 2) max(1, round(2 width / pitch)) for an even ``along`` (so that
    doubling ``along`` doubles every count: nested meshes), max(1, round(along width / pitch))
    for an odd one."""
    if along % 2 == 0:
        return (along // 2) * max(1, round(2 * width / pitch))
    return max(1, round(along * width / pitch))


def _cuts(disc: Disc, creases: Sequence[float], rim_u: Sequence[float], tol: float) -> list[float]:
    """The band lines u = const inside the disc (band frame): the creases', the centre's, the
    hole's sides and ``rim_u``, with the disc's two tangent lines, sorted, none within ``tol``
    of another."""
    (cu, _), R, r = disc.centre, disc.R, disc.r
    extra = [cu, cu - r, cu + r] if r > 0 else [cu]
    us = sorted(u for u in (*creases, *extra, *rim_u) if cu - R + tol < u < cu + R - tol)
    out = [cu - R]
    for u in us:
        if u - out[-1] > tol:
            out.append(u)
    if cu + R - out[-1] <= tol:
        out.pop()
    out.append(cu + R)
    return out


def disc_mesh(
    corrugation: Corrugation,
    disc: Disc,
    along: int,
    rim_angles: Sequence[float] = (),
    *,
    strip: float = 0.0,
) -> PlanMesh:
    """Mesh the folded layer ``corrugation`` (its chord along x or y) over ``disc`` (module
    docstring), about ``along`` elements across each facet, a node of the rim at each plan angle
    of ``rim_angles`` (deg from +x towards +y); nodes lifted onto the folded surface. ``strip``
    > 0 (mm, in plan) adds the lines that far on either side of each crease as band lines and
    marks the elements between them (``in_strip``), as
    :func:`corrugate.fea.planmesh.plan_mesh` does."""
    chord = corrugation.chord
    axis = {(1.0, 0.0): 0, (0.0, 1.0): 1}.get((float(chord[0]), float(chord[1])))
    if axis is None:
        raise SolverError("a disc mesh needs a layer whose chord runs along x or y")
    if not 0.0 <= disc.r < disc.R:
        raise SolverError("the disc's hole must be smaller than the disc")
    p, off = corrugation.pitch, corrugation.offset
    tol = 1e-7 * disc.R

    def to_band(x: float, y: float) -> Point:
        return (x, y) if axis == 0 else (y, x)

    band = Disc(to_band(*disc.centre), disc.R, disc.r)
    (cu, cv), R, r = band.centre, disc.R, disc.r
    creases: list[float] = []
    offsets = (0.0,) if strip <= 0.0 else (-strip, 0.0, strip)
    for k in range(math.floor((cu - R + off) / p) - 1, math.ceil((cu + R + off) / p) + 2):
        creases += [k * p + d - off for d in offsets]
    rim_u = [to_band(*disc.centre)[0] + R * _band_cos(a, axis) for a in rim_angles]
    cuts = _cuts(band, creases, rim_u, tol)
    nv = divisions(R, p, along)

    def outer(u: float) -> float:
        return math.sqrt(max(0.0, R * R - (u - cu) ** 2))

    def inner(u: float) -> float:
        return math.sqrt(max(0.0, r * r - (u - cu) ** 2)) if r > 0 else 0.0

    def build(gmsh: Any) -> None:
        """The cells as transfinite (mapped) surfaces of gmsh's built-in kernel."""
        geo = gmsh.model.geo
        points: dict[Key, int] = {}
        coincident = CoincidentKeys(tol)

        def point(q: Point) -> int:
            x, y = to_band(*q)  # the swap is its own inverse
            key = coincident.key(x, y, 0.0)
            if key not in points:
                points[key] = geo.addPoint(x, y, 0.0)
            return points[key]

        centre = point(band.centre)
        curves: dict[tuple[int, int], int] = {}

        def curve(a_: int, b_: int, arc: bool, nodes: int) -> int:
            if (b_, a_) in curves:
                return -curves[(b_, a_)]
            if (a_, b_) not in curves:
                tag = geo.addCircleArc(a_, centre, b_) if arc else geo.addLine(a_, b_)
                geo.mesh.setTransfiniteCurve(tag, nodes + 1)
                curves[(a_, b_)] = tag
            return curves[(a_, b_)]

        for u0, u1 in itertools.pairwise(cuts):
            nu = divisions(u1 - u0, p, along)
            over_hole = r > 0 and cu - r - tol <= u0 and u1 <= cu + r + tol
            for s in (1.0, -1.0):
                bl = point((u0, cv + s * inner(u0) if over_hole else cv))
                br = point((u1, cv + s * inner(u1) if over_hole else cv))
                tr = point((u1, cv + s * outer(u1)))
                tl = point((u0, cv + s * outer(u0)))
                loop = [curve(bl, br, over_hole, nu)]
                corners = [bl, br]
                if tr != br:
                    loop.append(curve(br, tr, False, nv))
                    corners.append(tr)
                loop.append(curve(tr, tl, True, nu))
                if tl != bl:
                    loop.append(curve(tl, bl, False, nv))
                    corners.append(tl)
                if len(corners) == 3:  # a tangent point: the apex first
                    apex = bl if tl == bl else br
                    i = corners.index(apex)
                    corners = corners[i:] + corners[:i]
                surf = geo.addPlaneSurface([geo.addCurveLoop(loop)])
                geo.mesh.setTransfiniteSurface(surf, "Left", corners)
                geo.mesh.setRecombine(2, surf)
        geo.synchronize()

    index, xy, types, conns = gmsh_mesh("disc", "disc", build)
    return gmsh_plan(xy, types, conns, index, corrugation, strip)


def _band_cos(angle_deg: float, axis: int) -> float:
    """The band-frame u component of the plan unit vector at ``angle_deg`` (deg from +x towards
    +y): its x for a chord along x (``axis`` 0), its y for one along y."""
    a = math.radians(angle_deg)
    return math.cos(a) if axis == 0 else math.sin(a)
