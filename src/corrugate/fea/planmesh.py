"""Shell mesh of a folded layer cut to any rectangle at any angle to its creases (gmsh).

The folded layer is a surface z = z0 + h tri(u / p) over its plan, where u is the chordwise
coordinate (across the creases), p the pitch, h the corrugation height and tri the unit triangle
wave (0 at even integers: valleys; 1 at odd integers: ridges). This module meshes the plan of a
rectangle [0, A] x [0, B] (the test specimen) with gmsh, the crease lines u = k p and the fixture
lines y = const given by the caller embedded as element edges, so that every element lies in one
flat facet; lifting its nodes onto the surface is then exact (mid-side nodes included). Elements
are 8-node quadrilaterals (S8R) where gmsh recombines, 6-node triangles (S6) elsewhere, all with
their normals on the +z side.

The element size in plan is ``pitch / along``, so a facet has about ``along`` elements across
its plan width (and W / p = 1 / sin(alpha / 2) times longer elements across it on the folded
surface).

gmsh keeps global state, so calls are serialised by a lock.
"""

from __future__ import annotations

import math
import threading
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from .ccx import SolverError

__all__ = ["Corrugation", "PlanMesh", "plan_mesh"]

FloatArray = NDArray[np.float64]
_LOCK = threading.Lock()

#: gmsh element type -> (CalculiX type, reorder applied when the element's normal points down)
_TYPES: dict[int, tuple[str, tuple[int, ...]]] = {
    16: ("S8R", (0, 3, 2, 1, 7, 6, 5, 4)),  # 8-node quadrilateral, same node order as CalculiX
    9: ("S6", (0, 2, 1, 5, 4, 3)),  # 6-node triangle
}


@dataclass(frozen=True, slots=True)
class Corrugation:
    """A zig-zag over the plan: chordwise unit vector ``chord`` (in the plan's x, y), chordwise
    coordinate u = chord . (x, y) + ``offset`` (valley at u = 0), ``pitch`` p and ``height`` h (mm),
    and the height ``z0`` (mm) of its valleys."""

    chord: tuple[float, float]
    offset: float
    pitch: float
    height: float
    z0: float = 0.0

    def u(self, xy: FloatArray) -> FloatArray:
        """Chordwise coordinate (mm) of plan points ``xy`` (N x 2)."""
        u: FloatArray = xy @ np.asarray(self.chord, dtype=np.float64) + self.offset
        return u

    def z(self, xy: FloatArray) -> FloatArray:
        """Height (mm) of the folded surface over plan points ``xy`` (N x 2)."""
        q = self.u(xy) / self.pitch
        frac = np.mod(q, 2.0)
        tri = np.where(frac <= 1.0, frac, 2.0 - frac)
        return self.z0 + self.height * tri


@dataclass(frozen=True, slots=True)
class PlanMesh:
    """Nodes (N x 3, mm) and elements of a lifted layer: ``elements[type]`` lists node index rows
    (0-based into ``xyz``) in CalculiX order, for type ``"S8R"`` and ``"S6"``."""

    xyz: FloatArray
    elements: dict[str, list[list[int]]]


def _line_in_rect(
    normal: tuple[float, float], c: float, A: float, B: float, tol: float
) -> tuple[tuple[float, float], tuple[float, float]] | None:
    """The chord of the rectangle [0, A] x [0, B] on the line normal . (x, y) = c, or None when the
    line misses the rectangle, touches it at one point or runs along one of its edges."""
    nx, ny = normal
    pts: list[tuple[float, float]] = []
    if abs(ny) > 1e-12:
        for x in (0.0, A):
            y = (c - nx * x) / ny
            if -tol <= y <= B + tol:
                pts.append((x, min(max(y, 0.0), B)))
    if abs(nx) > 1e-12:
        for y in (0.0, B):
            x = (c - ny * y) / nx
            if -tol <= x <= A + tol:
                pts.append((min(max(x, 0.0), A), y))
    uniq: list[tuple[float, float]] = []
    for p in pts:
        if all(math.dist(p, q) > tol for q in uniq):
            uniq.append(p)
    if len(uniq) != 2:
        return None
    (x0, y0), (x1, y1) = uniq
    on_same_edge = (abs(x0 - x1) < tol and (abs(x0) < tol or abs(x0 - A) < tol)) or (
        abs(y0 - y1) < tol and (abs(y0) < tol or abs(y0 - B) < tol)
    )
    return None if on_same_edge else (uniq[0], uniq[1])


def plan_mesh(
    corrugation: Corrugation,
    A: float,
    B: float,
    along: int,
    fixture_y: Sequence[float] = (),
) -> PlanMesh:
    """Mesh the folded layer ``corrugation`` over the plan rectangle [0, A] x [0, B] (mm) with
    about ``along`` elements across each facet's plan width, creases and the lines y = each of
    ``fixture_y`` as element edges; nodes lifted onto the folded surface."""
    import gmsh

    tol = 1e-7 * max(A, B)
    cx, cy = corrugation.chord
    # crease lines u = k p, i.e. chord . (x, y) = k p - offset, for every k crossing the rectangle
    corners = np.array([[0.0, 0.0], [A, 0.0], [A, B], [0.0, B]])
    u_c = corrugation.u(corners)
    k_lo = math.floor(u_c.min() / corrugation.pitch) - 1
    k_hi = math.ceil(u_c.max() / corrugation.pitch) + 1
    segments = []
    for k in range(k_lo, k_hi + 1):
        seg = _line_in_rect((cx, cy), k * corrugation.pitch - corrugation.offset, A, B, tol)
        if seg is not None:
            segments.append(seg)
    for y in fixture_y:
        seg = _line_in_rect((0.0, 1.0), y, A, B, tol)
        if seg is None:
            raise SolverError(f"fixture line y = {y:g} mm does not cross the specimen")
        segments.append(seg)
    size = corrugation.pitch / along
    with _LOCK:
        gmsh.initialize(interruptible=False)
        try:
            gmsh.option.setNumber("General.Terminal", 0)
            gmsh.model.add("layer")
            occ = gmsh.model.occ
            rect = occ.addRectangle(0.0, 0.0, 0.0, A, B)
            lines = []
            for (x0, y0), (x1, y1) in segments:
                p0 = occ.addPoint(x0, y0, 0.0)
                p1 = occ.addPoint(x1, y1, 0.0)
                lines.append((1, occ.addLine(p0, p1)))
            if lines:
                occ.fragment([(2, rect)], lines)
            occ.synchronize()
            for name, value in (
                ("Mesh.MeshSizeMin", size),
                ("Mesh.MeshSizeMax", size),
                ("Mesh.MeshSizeFromPoints", 0),
                ("Mesh.MeshSizeExtendFromBoundary", 0),
                ("Mesh.Algorithm", 8),  # frontal-Delaunay for quadrilaterals
                ("Mesh.RecombineAll", 1),
                ("Mesh.RecombinationAlgorithm", 1),  # blossom
                ("Mesh.ElementOrder", 2),
                ("Mesh.SecondOrderIncomplete", 1),  # 8-node (serendipity) quadrilaterals
            ):
                gmsh.option.setNumber(name, value)
            gmsh.model.mesh.generate(2)
            tags, coords, _ = gmsh.model.mesh.getNodes()
            types, _, conns = gmsh.model.mesh.getElements(2)
        except Exception as exc:  # gmsh raises plain Exceptions with its log message
            raise SolverError(f"gmsh could not mesh the specimen: {exc}") from None
        finally:
            gmsh.finalize()
    index = {int(t): i for i, t in enumerate(tags)}
    xy = np.asarray(coords, dtype=np.float64).reshape(-1, 3)[:, :2]
    elements: dict[str, list[list[int]]] = {"S8R": [], "S6": []}
    for etype, conn in zip(types, conns, strict=True):
        if int(etype) not in _TYPES:
            raise SolverError(f"gmsh produced elements of type {int(etype)}, not S8R or S6")
        name, flip = _TYPES[int(etype)]
        k = 8 if name == "S8R" else 6
        rows = np.asarray([index[int(t)] for t in conn], dtype=np.int64).reshape(-1, k)
        nc = 4 if name == "S8R" else 3
        for row in rows:
            p = xy[row[:nc]]
            area2 = float(np.sum(p[:, 0] * np.roll(p[:, 1], -1) - np.roll(p[:, 0], -1) * p[:, 1]))
            ids = [int(v) for v in row]
            elements[name].append([ids[j] for j in flip] if area2 < 0 else ids)
    used = sorted({i for rows in elements.values() for r in rows for i in r})
    remap = {old: new for new, old in enumerate(used)}
    xy = xy[used]
    xyz = np.column_stack([xy, corrugation.z(xy)])
    out = {name: [[remap[i] for i in r] for r in rows] for name, rows in elements.items()}
    return PlanMesh(xyz, out)
