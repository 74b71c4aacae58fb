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

import itertools
import math
import threading
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from corrugate.core.sigpipe import reapply_sigpipe
from corrugate.fea.ccx import SolverError
from corrugate.fea.coincident import CoincidentKeys, Key

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
    (0-based into ``xyz``) in CalculiX order, for type ``"S8R"`` and ``"S6"``; ``in_strip[type]``
    whether each lies in a crease's strip (:func:`plan_mesh`'s ``strip``; empty without)."""

    xyz: FloatArray
    elements: dict[str, list[list[int]]]
    in_strip: dict[str, list[bool]] = field(default_factory=dict)


Point = tuple[float, float]


def _clip(poly: list[Point], normal: Point, c: float, sign: float) -> list[Point]:
    """The part of the convex polygon ``poly`` where sign (normal . p - c) >= 0
    (Sutherland-Hodgman against one line)."""
    out: list[Point] = []
    n = len(poly)
    for i in range(n):
        p, q = poly[i], poly[(i + 1) % n]
        dp = sign * (normal[0] * p[0] + normal[1] * p[1] - c)
        dq = sign * (normal[0] * q[0] + normal[1] * q[1] - c)
        if dp >= 0:
            out.append(p)
        if (dp >= 0) != (dq >= 0):
            t = dp / (dp - dq)
            out.append((p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])))
    return out


def _cells(
    corrugation: Corrugation,
    A: float,
    B: float,
    fixture_y: Sequence[float],
    strip: float = 0.0,
) -> list[list[Point]]:
    """The plan of [0, A] x [0, B] cut by the crease lines and the lines y = each of
    ``fixture_y`` into convex cells (corners counter-clockwise), each inside one facet; with
    ``strip`` > 0 (mm, in plan) also by the lines ``strip`` on either side of each crease."""
    p, (cx, cy) = corrugation.pitch, corrugation.chord
    corners = np.array([[0.0, 0.0], [A, 0.0], [A, B], [0.0, B]])
    u_c = corrugation.u(corners)
    k_lo = math.floor(u_c.min() / p)
    k_hi = math.ceil(u_c.max() / p)
    ys = [0.0, *sorted(y for y in fixture_y), B]
    for y in fixture_y:
        if not 0.0 < y < B:
            raise SolverError(f"fixture line y = {y:g} mm does not cross the specimen")
    rect: list[Point] = [(0.0, 0.0), (A, 0.0), (A, B), (0.0, B)]
    cells: list[list[Point]] = []
    cuts = (0.0, p) if strip <= 0.0 else (0.0, strip, p - strip, p)
    for k in range(k_lo, k_hi):
        for u0, u1 in itertools.pairwise(cuts):
            band = _clip(rect, (cx, cy), k * p + u0 - corrugation.offset, 1.0)
            band = _clip(band, (cx, cy), k * p + u1 - corrugation.offset, -1.0)
            for y0, y1 in itertools.pairwise(ys):
                cell = _clip(_clip(band, (0.0, 1.0), y0, 1.0), (0.0, 1.0), y1, -1.0)
                if len(cell) >= 3:
                    cells.append(cell)
    return cells


def plan_mesh(
    corrugation: Corrugation,
    A: float,
    B: float,
    along: int,
    fixture_y: Sequence[float] = (),
    aspect: float = 1.0,
    *,
    strip: float = 0.0,
) -> PlanMesh:
    """Mesh the folded layer ``corrugation`` over the plan rectangle [0, A] x [0, B] (mm) with
    about ``along`` elements across each facet's plan width, creases and the lines y = each of
    ``fixture_y`` as element edges; nodes lifted onto the folded surface.

    ``aspect`` (>= 1, default 1) makes the elements that many times longer along the creases
    than across them: the plan is meshed isotropically after the affine map that shortens it
    by 1 / ``aspect`` along the crease direction, and the nodes are mapped back (straight lines,
    the creases and fixture lines among them, and mid-side nodes at midpoints are kept by an
    affine map). About 1 / ``aspect`` as many nodes (docs/fea.md 2.9).

    A corrugation and its mirror image in x = A / 2 get mirror-image meshes: one whose chord
    points to -x is meshed as its mirror image (chord to +x) and mirrored back. So the two
    layers of a coupon along eta and of one along 90 - eta, mirror images of each other for
    identical layers, are meshed alike.

    ``strip`` > 0 (mm, in plan) adds the lines that far on either side of each crease as
    element edges and marks the elements between them (``in_strip``): the compliant strips of
    :func:`corrugate.fea.shells.crease_strip`."""
    tol = 1e-7 * max(A, B)
    cx, cy = corrugation.chord
    mirrored = cx < 0  # u = cx x + cy y + o = (-cx) (A - x) + cy y + (o + cx A)
    # the cells of the (mirrored) corrugation, its chord and offset rounded to 1e-12 and 1e-9
    # mm: gmsh's mesh changes with perturbations of the geometry as small as 1e-14 mm, so
    # mirror images must reach it as the same numbers
    chord = (round(abs(cx), 12), round(cy, 12))
    offset = round(corrugation.offset + cx * A if mirrored else corrugation.offset, 9)
    cells = _cells(replace(corrugation, chord=chord, offset=offset), A, B, fixture_y, strip)
    size = corrugation.pitch / along
    # the affine map P -> P + (1 / aspect - 1) (t . P) t, t the crease direction (unit, normal to
    # the chord), and its inverse P -> P + (aspect - 1) (t . P) t
    tx, ty = -chord[1], chord[0]
    shrink = 1.0 / aspect - 1.0
    if aspect != 1.0:
        cells = [
            [
                (x + shrink * (tx * x + ty * y) * tx, y + shrink * (tx * x + ty * y) * ty)
                for x, y in c
            ]
            for c in cells
        ]

    def build(gmsh: Any) -> None:
        """The cells as plane surfaces of gmsh's built-in kernel."""
        # the built-in kernel, fed cells that share their points and edges: deterministic
        # (OpenCASCADE's fragment gave a different mesh for a second layer in one process)
        geo = gmsh.model.geo
        points: dict[Key, int] = {}
        coincident = CoincidentKeys(tol)  # a cell corner shared by two cells, one key
        lines: dict[tuple[int, int], int] = {}
        for cell in cells:
            tags: list[int] = []
            for x, y in cell:
                key = coincident.key(x, y, 0.0)
                if key not in points:
                    points[key] = geo.addPoint(x, y, 0.0)
                if not tags or tags[-1] != points[key]:
                    tags.append(points[key])
            if tags[0] == tags[-1]:
                tags.pop()
            if len(tags) < 3:
                continue  # a sliver thinner than the tolerance
            loop: list[int] = []
            for a_, b_ in zip(tags, tags[1:] + tags[:1], strict=True):
                if (b_, a_) in lines:
                    loop.append(-lines[(b_, a_)])
                else:
                    lines[(a_, b_)] = lines.get((a_, b_)) or geo.addLine(a_, b_)
                    loop.append(lines[(a_, b_)])
            geo.addPlaneSurface([geo.addCurveLoop(loop)])
        geo.synchronize()

    index, xy, types, conns = gmsh_mesh(
        "layer",
        "specimen",
        build,
        (
            ("Mesh.MeshSizeMin", size),
            ("Mesh.MeshSizeMax", size),
            ("Mesh.MeshSizeFromPoints", 0),
            ("Mesh.MeshSizeExtendFromBoundary", 0),
            ("Mesh.Algorithm", 8),  # frontal-Delaunay for quadrilaterals
            ("Mesh.RecombineAll", 1),
            ("Mesh.RecombinationAlgorithm", 1),  # blossom
        ),
    )
    if aspect != 1.0:
        along_t = xy @ np.array([tx, ty])
        xy = xy + (aspect - 1.0) * np.outer(along_t, [tx, ty])
    if mirrored:
        xy[:, 0] = A - xy[:, 0]  # the element orientation is restored below
    return gmsh_plan(xy, types, conns, index, corrugation, strip)


def gmsh_plan(
    xy: NDArray[np.float64],
    types: Sequence[int],
    conns: Sequence[Sequence[int]],
    index: dict[int, int],
    corrugation: Corrugation,
    strip: float,
) -> PlanMesh:
    """The plan mesh of gmsh's 2-D elements (``types``, ``conns``: its node tags, ``index``: a
    tag's row of ``xy``, the nodes' plan coordinates in mm): S8R and S6 elements turned
    counter-clockwise, the nodes no element uses dropped, each node lifted to the corrugation's
    height, and, for ``strip`` > 0, each element marked when its centre lies within ``strip`` mm
    of a crease (along the chord, u) (the crease strips, docs/offaxis.md)."""
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
    if strip <= 0.0:
        return PlanMesh(xyz, out)
    marks: dict[str, list[bool]] = {}
    for name, rows_ in out.items():
        nc = 4 if name == "S8R" else 3
        u = np.array([corrugation.u(xy[r[:nc]]).mean() for r in rows_]) if rows_ else np.zeros(0)
        off = np.abs(u - corrugation.pitch * np.round(u / corrugation.pitch))
        marks[name] = [bool(d < strip) for d in off]
    return PlanMesh(xyz, out, marks)


def gmsh_mesh(
    model: str,
    what: str,
    build: Callable[[Any], None],
    options: Sequence[tuple[str, float]] = (),
) -> tuple[dict[int, int], FloatArray, Sequence[int], Sequence[Sequence[int]]]:
    """One gmsh session, under the lock (gmsh is a process-wide library): the model ``model``,
    its geometry added by ``build(gmsh)`` (which synchronises it), the mesh ``options`` and
    second order, 8-node (serendipity) quadrilaterals, the 2-D mesh generated. Returns each node
    tag's row (``index``), the nodes' plan coordinates (mm) and gmsh's 2-D element types and
    connectivities, for :func:`gmsh_plan`. SIGPIPE is ignored again after gmsh's initialisation
    (:mod:`corrugate.core.sigpipe`); any failure is a :class:`SolverError` naming ``what``."""
    import gmsh

    with _LOCK:
        gmsh.initialize(interruptible=False)
        reapply_sigpipe()  # gmsh sets SIGPIPE to its default in C (core.sigpipe)
        try:
            gmsh.option.setNumber("General.Terminal", 0)
            gmsh.model.add(model)
            build(gmsh)
            for name, value in (
                *options,
                ("Mesh.ElementOrder", 2),
                ("Mesh.SecondOrderIncomplete", 1),  # 8-node (serendipity) quadrilaterals
            ):
                gmsh.option.setNumber(name, value)
            gmsh.model.mesh.generate(2)
            tags, coords, _ = gmsh.model.mesh.getNodes()
            types, _, conns = gmsh.model.mesh.getElements(2)
        except Exception as exc:  # gmsh raises plain Exceptions with its log message
            raise SolverError(f"gmsh could not mesh the {what}: {exc}") from None
        finally:
            gmsh.finalize()
    index = {int(t): i for i, t in enumerate(tags)}
    xy = np.asarray(coords, dtype=np.float64).reshape(-1, 3)[:, :2]
    return index, xy, types, conns
