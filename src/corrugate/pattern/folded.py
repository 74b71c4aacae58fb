"""Folded geometry: FOLD 1.2 documents of the layers and the 3D mesh of the assembly.

A layer's flat point (u, v) in facet j (j W <= u <= (j + 1) W, local w = u - j W) folds to

    x = j p + w s,    y = v,    z = w c  (j even)  or  h - w c  (j odd)

with s = sin(alpha/2), c = cos(alpha/2), p = W s, h = W c: each facet moves rigidly, so the map is
an isometry facet by facet and every face stays planar. Layer 1 sits at 0 <= z <= h1; layer 2,
whose creases run along x, rests on layer 1's ridges: (x, y, z) = (v, x2, h1 + z2). The band stands
along the perimeter from z = 0 to t_d.

FOLD (https://github.com/edemaine/fold, spec 1.2): faces are the facets (the outline clipped to each
facet's strip); edges on a crease carry its assignment (M, V) and ``edges_foldAngle`` in degrees
(+ valley, - mountain, magnitude 180 - alpha); the others are boundary (B). A second frame holds the
folded 3D coordinates (``frame_classes`` ["foldedForm"]).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from ..geometry import Assembly, Layer
from .layers import crease_role
from .model import Part, Role

__all__ = [
    "band_walls",
    "facet_polygons",
    "fold_document",
    "fold_points",
    "folded_mesh",
    "layer_faces",
]

FloatArray = NDArray[np.float64]
Point = tuple[float, float]


def fold_points(layer: Layer, uv: FloatArray) -> FloatArray:
    """Folded (x, y, z) (mm) of flat points ``uv`` (shape (k, 2)) of ``layer``'s blank."""
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


def fold_document(part: Part, layer: Layer) -> dict[str, object]:
    """A FOLD 1.2 document (a JSON-ready dict) of one layer blank with its folded frame."""
    faces = facet_polygons(part, layer)
    index: dict[tuple[int, int], int] = {}
    coords: list[Point] = []

    def vid(p: Point) -> int:
        key = (round(p[0] * 1e6), round(p[1] * 1e6))
        if key not in index:
            index[key] = len(coords)
            coords.append(p)
        return index[key]

    faces_vertices = [[vid(p) for p in face] for face in faces]
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
    for face in facet_polygons(part, layer):
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
    ``(vertices, faces)`` for trimesh.
    """
    polygons = [*layer_faces(a, parts, 1), *layer_faces(a, parts, 2), *band_walls(a)]
    tris: list[list[int]] = []
    count = 0
    for poly in polygons:
        tris.extend(_fan(len(poly), count))
        count += len(poly)
    return np.vstack(polygons), np.asarray(tris, dtype=np.int64)
