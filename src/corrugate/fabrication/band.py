"""The connector band's segments as cut parts (see :mod:`corrugate.geometry.connectors`).

Each segment is drawn with its inner face up: x runs along the perimeter (counter-clockwise seen
from above), y from the base (0) to the top of the assembly (t_d). Its glue tabs hang below y = 0
and above y = t_d on valley folds of 90 deg; its overlap tab lies beyond x = e, on a fold by the
outline's turning angle at a corner (valley at a convex corner, mountain at a reflex one) or behind
a mark along a smooth outline. Marks show where each crease of layer 1 (0..h1) and of layer 2
(h1..t_d) meets the band.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from corrugate.fabrication.model import Line, Part, Role
from corrugate.geometry.connectors import band_segments, slit_count
from corrugate.geometry.fabrication_options import DEFAULT_FABRICATION, FabricationOptions
from corrugate.geometry.layer import Assembly

__all__ = ["band_parts", "crease_crossings"]

FloatArray = NDArray[np.float64]
Point = tuple[float, float]


def _flange(
    e: float, y0: float, sign: float, cornered: bool, opts: FabricationOptions
) -> tuple[list[Point], list[Line]]:
    """Outline points of one glue flange along y = y0 from x = 0 to e (sign -1: below, +1: above),
    in increasing x, with its 90 deg fold line and the slits that divide it into tabs."""
    g = opts.tab_depth
    ch = min(g, e / 2) if cornered else 0.0
    y1 = y0 + sign * g
    if cornered and ch < g:  # a short segment: the flange is a triangle of height e/2
        pts = [(0.0, y0), (e / 2, y0 + sign * ch), (e, y0)]
    else:
        pts = [(0.0, y0), (ch, y1), (e - ch, y1), (e, y0)]
    lines = [Line((0.0, y0), (e, y0), Role.VALLEY, 90.0)]
    k = slit_count(e, opts) + 1
    for i in range(1, k):
        x = i * e / k
        depth = min(g, x, e - x) if cornered else g  # stay inside the chamfers
        lines.append(Line((x, y0), (x, y0 + sign * depth), Role.CUT))
    return pts, lines


def crease_crossings(a: Assembly, outline: FloatArray) -> list[tuple[float, int]]:
    """Where creases meet the perimeter: (arc length from the outline's first vertex in mm, layer).

    ``outline`` is the plan outline (counter-clockwise, mm). Layer 1's creases are the lines
    x = k p1, layer 2's the lines y = k p2.
    """
    d = np.roll(outline, -1, axis=0) - outline
    seg = np.hypot(d[:, 0], d[:, 1])
    start = np.concatenate([[0.0], np.cumsum(seg)[:-1]])
    out: list[tuple[float, int]] = []
    for layer_index, axis, layer in ((1, 0, a.layer1), (2, 1, a.layer2)):
        for k in range(1, layer.n + 1):
            c = k * layer.pitch
            q0, q1 = outline[:, axis], outline[:, axis] + d[:, axis]
            hit = ((q0 <= c) & (c < q1)) | ((q1 <= c) & (c < q0))
            for i in np.flatnonzero(hit):
                t = (c - q0[i]) / d[i, axis]
                out.append((float(start[i] + t * seg[i]), layer_index))
    return sorted(out)


def _turning_angles(outline: FloatArray) -> FloatArray:
    """Turning angle (deg) at the end of each edge, positive at convex corners (counter-clockwise)."""
    d = np.roll(outline, -1, axis=0) - outline
    d_next = np.roll(d, -1, axis=0)
    cross = d[:, 0] * d_next[:, 1] - d[:, 1] * d_next[:, 0]
    dot = (d * d_next).sum(axis=1)
    return np.asarray(np.degrees(np.arctan2(cross, dot)), dtype=np.float64)


def band_parts(a: Assembly, opts: FabricationOptions = DEFAULT_FABRICATION) -> list[Part]:
    """The band segments of assembly ``a`` as cut parts, named B1, B2, ... around the perimeter."""
    outline = a.layout.plan_outline(a.Lx, a.Ly)
    td, h1 = a.thickness, a.layer1.height
    d = np.roll(outline, -1, axis=0) - outline
    poly_len = np.hypot(d[:, 0], d[:, 1])
    runs = a.layout.perimeter_runs(a.Lx, a.Ly)
    cornered = all(c for _, c in runs)
    crossings = crease_crossings(a, outline)
    if cornered:
        lengths = [float(e) for e in poly_len]
        starts = np.concatenate([[0.0], np.cumsum(poly_len)[:-1]])
        turn = _turning_angles(outline)
        scale = 1.0
    else:  # a smooth outline: equal arcs of the exact perimeter
        ((arc, count, _),) = band_segments(a.layout, a.Lx, a.Ly, opts)
        lengths = [float(arc)] * int(count)
        starts = np.arange(int(count)) * float(arc)
        turn = np.zeros(int(count))
        scale = float(arc) * int(count) / float(poly_len.sum())
    parts: list[Part] = []
    m = len(lengths)
    for i, e in enumerate(lengths):
        bottom, folds_b = _flange(e, 0.0, -1.0, cornered, opts)
        top, folds_t = _flange(e, td, 1.0, cornered, opts)
        o = opts.overlap
        outline_pts = [*bottom, (e + o, 0.0), (e + o, td), *reversed(top)]
        lines = [*folds_b, *folds_t]
        angle = float(turn[i])
        if abs(angle) > 1e-6:
            role = Role.VALLEY if angle > 0 else Role.MOUNTAIN
            lines.append(Line((e, 0.0), (e, td), role, abs(angle)))
        else:
            lines.append(Line((e, 0.0), (e, td), Role.MARK))
        for s, layer_index in crossings:
            x = s * scale - float(starts[i])
            if -1e-9 <= x < e - 1e-9:
                y0, y1 = (0.0, h1) if layer_index == 1 else (h1, td)
                lines.append(Line((max(x, 0.0), y0), (max(x, 0.0), y1), Role.MARK))
        nxt = (i + 1) % m + 1
        parts.append(
            Part(
                name=f"B{i + 1}",
                label=f"band {i + 1}/{m}: overlap tab under B{nxt}",
                outline=tuple(outline_pts),
                lines=tuple(lines),
                kind="connector",
                meta={"segment": float(i + 1), "length": e},
                material_id=a.layer1.material.id,
                t=a.layer1.t,
                density=a.layer1.material.density,
            )
        )
    return parts
