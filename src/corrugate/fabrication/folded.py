"""Folded geometry: FOLD 1.2 documents of the layers and the 3D mesh of the assembly.

A layer's flat point (u, v) in facet j (j W <= u <= (j + 1) W, local w = u - j W) folds to

    x = j p + w s,    y = v,    z = w c  (j even)  or  h - w c  (j odd)

with s = sin(alpha/2), c = cos(alpha/2), p = W s, h = W c: each facet moves rigidly, so the map is
an isometry facet by facet and every face stays planar. Layer 1 sits at 0 <= z <= h1; layer 2,
whose creases run along x, rests on layer 1's ridges: (x, y, z) = (v, x2, h1 + z2). The band stands
along the perimeter from z = 0 to t_d.

FOLD (https://github.com/edemaine/fold, spec 1.2): faces are the facets (the outline clipped to each
facet's strip); edges on a crease carry its assignment (M, V) and ``edges_foldAngle`` in degrees
(+ valley, - mountain, magnitude 180 - alpha); the others are boundary (B). A facet that a hole
meets is split into convex trapezoids around the hole (flat edges F between them), so the hole is
a ring of boundary edges and no face covers it, in FOLD and in the 3D mesh alike. A second frame holds the
folded 3D coordinates (``frame_classes`` ["foldedForm"]).
"""

from __future__ import annotations

import itertools
import math

import numpy as np
from numpy.typing import NDArray

from corrugate.fabrication.layers import crease_role
from corrugate.fabrication.model import Part, Role
from corrugate.geometry.layer import Assembly, Layer, require_zigzag

__all__ = [
    "MESH_GROUPS",
    "band_walls",
    "facet_pieces",
    "facet_polygons",
    "fold_document",
    "fold_points",
    "folded_mesh",
    "folded_mesh_groups",
    "layer_faces",
]

FloatArray = NDArray[np.float64]
Point = tuple[float, float]


def fold_points(layer: Layer, uv: FloatArray) -> FloatArray:
    """Folded (x, y, z) (mm) of flat points ``uv`` (shape (k, 2)) of ``layer``'s blank."""
    require_zigzag(layer, "folded geometry")
    u, v = uv[:, 0], uv[:, 1]
    j = np.clip(np.floor(u / layer.W + 1e-9), 0, layer.n).astype(int)
    w = u - j * layer.W
    x = j * layer.pitch + w * layer.s
    z = np.where(j % 2 == 0, w * layer.c, layer.height - w * layer.c)
    return np.column_stack([x, v, z])


def _clip(poly: list[Point], keep_lo: float, keep_hi: float) -> list[Point]:
    """Sutherland-Hodgman clip of a polygon to the strip keep_lo <= u <= keep_hi."""

    def clip_half(pts: list[Point], bound: float, upper: bool) -> list[Point]:
        def inside(p: Point) -> bool:
            return p[0] <= bound + 1e-12 if upper else p[0] >= bound - 1e-12

        out: list[Point] = []
        for i, p in enumerate(pts):
            q = pts[(i + 1) % len(pts)]
            if inside(p):
                out.append(p)
            if inside(p) != inside(q):
                t = (bound - p[0]) / (q[0] - p[0])
                out.append((bound, p[1] + t * (q[1] - p[1])))
        return out

    pts = clip_half(poly, keep_lo, upper=False)
    return clip_half(pts, keep_hi, upper=True) if pts else []


def facet_polygons(part: Part, layer: Layer) -> list[list[Point]]:
    """Each facet of a layer blank as a flat polygon (counter-clockwise), in order along u.

    A facet that a concave outline cuts into separate pieces comes out as one polygon joined along
    the strip's edge (Sutherland-Hodgman); such outlines get a correct cut file and mass but a FOLD
    face that is not simple.
    """
    poly = list(part.outline)
    out = []
    for j in range(layer.n + 1):
        face = _clip(poly, j * layer.W, (j + 1) * layer.W)
        cleaned: list[Point] = []
        for p in face:
            if not cleaned or math.dist(cleaned[-1], p) > 1e-9:
                cleaned.append(p)
        if len(cleaned) > 1 and math.dist(cleaned[0], cleaned[-1]) <= 1e-9:
            cleaned.pop()
        out.append(cleaned)
    return out


def _clean(face: list[Point]) -> list[Point]:
    cleaned: list[Point] = []
    for p in face:
        if not cleaned or math.dist(cleaned[-1], p) > 1e-9:
            cleaned.append(p)
    if len(cleaned) > 1 and math.dist(cleaned[0], cleaned[-1]) <= 1e-9:
        cleaned.pop()
    return cleaned


def _trapezoids(rings: list[list[Point]]) -> list[list[Point]]:
    """Trapezoidal decomposition of the region the ``rings`` bound (even-odd rule: an outline and
    its holes): the region is cut at the v of every vertex; in each band the edges that cross it
    are sorted along u and taken in pairs. Each piece is convex and counter-clockwise."""
    edges: list[tuple[float, float, float, float]] = []
    levels: set[float] = set()
    for ring in rings:
        for i, p in enumerate(ring):
            q = ring[(i + 1) % len(ring)]
            levels.add(p[1])
            if abs(q[1] - p[1]) > 1e-12:
                s0, s1 = (p, q) if p[1] < q[1] else (q, p)
                edges.append((s0[0], s0[1], s1[0], s1[1]))

    def u_at(e: tuple[float, float, float, float], v: float) -> float:
        return e[0] + (v - e[1]) * (e[2] - e[0]) / (e[3] - e[1])

    out: list[list[Point]] = []
    vs = sorted(levels)
    for v0, v1 in itertools.pairwise(vs):
        if v1 - v0 < 1e-9:
            continue
        vm = (v0 + v1) / 2
        active = sorted((e for e in edges if e[1] <= vm <= e[3]), key=lambda e: u_at(e, vm))
        for a, b in zip(active[::2], active[1::2], strict=False):
            quad = _clean(
                [(u_at(a, v0), v0), (u_at(b, v0), v0), (u_at(b, v1), v1), (u_at(a, v1), v1)]
            )
            if len(quad) >= 3 and abs(u_at(b, vm) - u_at(a, vm)) > 1e-9:
                out.append(quad)
    return out


def facet_pieces(part: Part, layer: Layer) -> list[tuple[int, list[Point]]]:
    """The faces of a layer blank as (facet index j, flat polygon), in order along u.

    A facet no hole meets is one polygon (:func:`facet_polygons`); a facet a hole meets is the
    outline's strip less the hole, cut into convex trapezoids (:func:`_trapezoids`). When the
    part has holes, every face also carries the vertices of its neighbours that lie on its
    axis-parallel edges, so that faces meet edge to edge (no T-junctions) along creases and cuts.
    """
    whole = facet_polygons(part, layer)
    if not part.holes:
        return [(j, f) for j, f in enumerate(whole)]
    W = layer.W
    out: list[tuple[int, list[Point]]] = []
    for j, face in enumerate(whole):
        lo, hi = j * W, (j + 1) * W
        cut = [
            _clean(_clip(list(h), lo, hi))
            for h in part.holes
            if min(p[0] for p in h) < hi and max(p[0] for p in h) > lo
        ]
        cut = [c for c in cut if len(c) >= 3]
        if not cut:
            out.append((j, face))
        else:
            out.extend((j, piece) for piece in _trapezoids([face, *cut]))
    return _no_t_junctions(out)


def _distinct(values: list[float], tol: float = 1e-7) -> list[float]:
    """``values`` sorted, each run of values within ``tol`` (mm) of the run's first kept once:
    the same point computed twice (a hole's row on both sides of a crease) is one vertex."""
    out: list[float] = []
    for v in sorted(values):
        if not out or v - out[-1] > tol:
            out.append(v)
    return out


def _no_t_junctions(faces: list[tuple[int, list[Point]]]) -> list[tuple[int, list[Point]]]:
    """Insert into every vertical or horizontal face edge the vertices lying inside it."""
    columns: dict[int, list[float]] = {}
    rows: dict[int, list[float]] = {}
    for _, face in faces:
        for u, v in face:
            columns.setdefault(round(u * 1e6), []).append(v)
            rows.setdefault(round(v * 1e6), []).append(u)
    for d in (columns, rows):
        for key in d:
            d[key] = _distinct(d[key])
    out = []
    for j, face in faces:
        ring: list[Point] = []
        for i, p in enumerate(face):
            q = face[(i + 1) % len(face)]
            ring.append(p)
            if abs(p[0] - q[0]) < 1e-9:
                vals = columns.get(round(p[0] * 1e6), [])
                lo, hi = sorted((p[1], q[1]))
                mid = [v for v in vals if lo + 1e-7 < v < hi - 1e-7]
                ring.extend((p[0], v) for v in (mid if q[1] > p[1] else mid[::-1]))
            elif abs(p[1] - q[1]) < 1e-9:
                vals = rows.get(round(p[1] * 1e6), [])
                lo, hi = sorted((p[0], q[0]))
                mid = [u for u in vals if lo + 1e-7 < u < hi - 1e-7]
                ring.extend((u, p[1]) for u in (mid if q[0] > p[0] else mid[::-1]))
        out.append((j, ring))
    return out


def fold_document(part: Part, layer: Layer) -> dict[str, object]:
    """A FOLD 1.2 document (a JSON-ready dict) of one layer blank with its folded frame.

    With holes, the faces are the pieces of :func:`facet_pieces`: edges between two pieces of
    one facet are flat (F), a hole's edges are boundary (B)."""
    faces = [face for _, face in facet_pieces(part, layer)]
    index: dict[tuple[int, int], int] = {}
    coords: list[Point] = []

    def vid(p: Point) -> int:
        key = (round(p[0] * 1e6), round(p[1] * 1e6))
        if key not in index:
            index[key] = len(coords)
            coords.append(p)
        return index[key]

    faces_vertices = []
    for face in faces:  # consecutive points that are one vertex (within 1 nm) are kept once
        ring = [vid(p) for p in face]
        ring = [v for i, v in enumerate(ring) if v != ring[i - 1]] if len(set(ring)) > 1 else []
        if len(ring) >= 3:
            faces_vertices.append(ring)
    edge_faces: dict[tuple[int, int], int] = {}
    edges: list[tuple[int, int]] = []
    for fv in faces_vertices:
        for a, b in zip(fv, fv[1:] + fv[:1], strict=True):
            key = (min(a, b), max(a, b))
            if key not in edge_faces:
                edge_faces[key] = 0
                edges.append(key)
            edge_faces[key] += 1
    assignment: list[str] = []
    angles: list[float] = []
    for a, b in edges:
        ua, ub = coords[a][0], coords[b][0]
        k = round(ua / layer.W)
        on_crease = edge_faces[(a, b)] == 2 and abs(ua - ub) < 1e-9 and abs(ua - k * layer.W) < 1e-6
        if on_crease and 1 <= k <= layer.n:
            role = crease_role(k)
            assignment.append("M" if role is Role.MOUNTAIN else "V")
            sign = -1.0 if role is Role.MOUNTAIN else 1.0
            angles.append(sign * layer.fold_angle_deg)
        elif edge_faces[(a, b)] == 2:  # between two pieces of one facet (holes)
            assignment.append("F")
            angles.append(0.0)
        else:
            assignment.append("B")
            angles.append(0.0)
    folded = fold_points(layer, np.asarray(coords, dtype=np.float64))
    return {
        "file_spec": 1.2,
        "file_creator": "corrugate",
        "file_title": part.label,
        "file_classes": ["singleModel"],
        "frame_title": f"{part.name} flat",
        "frame_classes": ["creasePattern"],
        "frame_attributes": ["2D"],
        "frame_unit": "mm",
        "vertices_coords": [[float(x), float(y)] for x, y in coords],
        "edges_vertices": [[a, b] for a, b in edges],
        "edges_assignment": assignment,
        "edges_foldAngle": angles,
        "faces_vertices": faces_vertices,
        "file_frames": [
            {
                "frame_title": f"{part.name} folded",
                "frame_classes": ["foldedForm"],
                "frame_attributes": ["3D"],
                "frame_parent": 0,
                "frame_inherit": True,
                "frame_unit": "mm",
                "vertices_coords": [[float(c) for c in row] for row in folded],
            }
        ],
    }


def _fan(n_vertices: int, offset: int) -> list[list[int]]:
    return [[offset, offset + i, offset + i + 1] for i in range(1, n_vertices - 1)]


def layer_faces(a: Assembly, parts: tuple[Part, ...], index: int) -> list[FloatArray]:
    """The folded facets (each a (k, 3) array in mm, assembly coordinates) of layer ``index``."""
    part = next(p for p in parts if p.name == f"L{index}")
    layer = a.layer1 if index == 1 else a.layer2
    faces = []
    for _, face in facet_pieces(part, layer):
        if len(face) < 3:
            continue
        p3 = fold_points(layer, np.asarray(face, dtype=np.float64))
        if index == 2:
            p3 = np.column_stack([p3[:, 1], p3[:, 0], a.layer1.height + p3[:, 2]])
        faces.append(p3)
    return faces


def band_walls(a: Assembly) -> list[FloatArray]:
    """The band as flat walls (4 x 3 arrays, mm) standing on the outline from 0 to t_d."""
    outline = a.layout.plan_outline(a.Lx, a.Ly)
    nxt = np.roll(outline, -1, axis=0)
    td = a.thickness
    return [
        np.array([[p[0], p[1], 0.0], [q[0], q[1], 0.0], [q[0], q[1], td], [p[0], p[1], td]])
        for p, q in zip(outline, nxt, strict=True)
    ]


def folded_mesh(a: Assembly, parts: tuple[Part, ...]) -> tuple[FloatArray, NDArray[np.int64]]:
    """Vertices (mm) and triangles of the folded assembly: both layers and the band's walls.

    Facets are triangulated as fans (they are convex for convex outlines). Returns
    ``(vertices, faces)`` for the GLB and STL writers (:mod:`corrugate.export.files3d`).
    """
    vertices, faces, _ = folded_mesh_groups(a, parts)
    return vertices, faces


#: The parts of the folded mesh, in the order :func:`folded_mesh` stacks them.
MESH_GROUPS = ("layer 1", "layer 2", "band")


def folded_mesh_groups(
    a: Assembly, parts: tuple[Part, ...]
) -> tuple[FloatArray, NDArray[np.int64], list[tuple[str, int, int]]]:
    """:func:`folded_mesh` and its parts: ``(vertices, faces, groups)`` where ``groups`` lists
    each part of :data:`MESH_GROUPS` with its vertex and triangle counts; the parts' vertices and
    triangles follow one another in that order (a group's triangles use only its vertices)."""
    pieces = [layer_faces(a, parts, 1), layer_faces(a, parts, 2), band_walls(a)]
    polygons = [poly for piece in pieces for poly in piece]
    tris: list[list[int]] = []
    groups: list[tuple[str, int, int]] = []
    count = 0
    for name, piece in zip(MESH_GROUPS, pieces, strict=True):
        first_vertex, first_tri = count, len(tris)
        for poly in piece:
            tris.extend(_fan(len(poly), count))
            count += len(poly)
        groups.append((name, count - first_vertex, len(tris) - first_tri))
    return np.vstack(polygons), np.asarray(tris, dtype=np.int64), groups
