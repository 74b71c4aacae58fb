"""Flat blanks of the two corrugated layers, with their mountain and valley creases.

A layer's flat blank is its plan outline stretched across the creases by 1/sin(alpha/2): a plan
point (chord x, span y) lies at flat (u, v) = (x / s, y). Crease k (k = 1..n) is the line u = k W
inside the outline. With the layer's first facet rising from the base (z = 0 at u = 0), odd creases
are ridges, i.e. mountains seen from the face that is up when cut, and even creases valleys; every
crease has the dihedral fold angle 180 deg - alpha (docs/theory.md section 2). A layout's holes are
stretched the same way and cut as inner rings; creases stop at them.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

from corrugate.fabrication.model import Line, Part, Role
from corrugate.geometry.layer import Layer, require_zigzag

__all__ = ["crease_role", "layer_part", "line_intervals"]

FloatArray = NDArray[np.float64]


def crease_role(k: int) -> Role:
    """Role of crease k (1-based): odd creases are mountains, even ones valleys."""
    return Role.MOUNTAIN if k % 2 == 1 else Role.VALLEY


def line_intervals(
    poly: FloatArray, u: float, holes: Sequence[FloatArray] = ()
) -> list[tuple[float, float]]:
    """The v-intervals where the line u = const lies inside the polygon and outside its
    ``holes`` (even-odd rule over every ring)."""
    found = []
    for ring in (poly, *holes):
        u0, v0 = ring[:, 0], ring[:, 1]
        u1, v1 = np.roll(u0, -1), np.roll(v0, -1)
        crosses = ((u0 <= u) & (u < u1)) | ((u1 <= u) & (u < u0))
        t = (u - u0[crosses]) / (u1[crosses] - u0[crosses])
        found.append(v0[crosses] + t * (v1[crosses] - v0[crosses]))
    vs = np.sort(np.concatenate(found))
    return [(float(vs[i]), float(vs[i + 1])) for i in range(0, len(vs) - 1, 2)]


def layer_part(
    layer: Layer, plan: FloatArray, index: int, holes: Sequence[FloatArray] = ()
) -> Part:
    """The cut blank of ``layer`` (1 or 2) whose plan outline is ``plan`` (counter-clockwise, in its
    own (chord, span) coordinates, mm), with the plan ``holes`` (same coordinates) cut out:
    stretched like the outline, each becomes an inner cut ring of the part, and no crease is
    drawn across it."""
    require_zigzag(layer, "fold pattern")
    flat = np.column_stack([plan[:, 0] / layer.s, plan[:, 1]])
    origin = flat.min(axis=0)
    flat = flat - origin
    flat_holes = [np.column_stack([h[:, 0] / layer.s, h[:, 1]]) - origin for h in holes]
    angle = layer.fold_angle_deg
    lines: list[Line] = []
    for k in range(1, layer.n + 1):
        u = k * layer.W
        for v_lo, v_hi in line_intervals(flat, u, flat_holes):
            lines.append(Line((u, v_lo), (u, v_hi), crease_role(k), angle))
    name = f"L{index}"
    label = (
        f"layer {index}: W {layer.W:g} mm, n {layer.n}, alpha {layer.alpha_deg:g} deg, "
        f"{layer.material.id} {layer.t:g} mm"
    )
    return Part(
        name=name,
        label=label,
        outline=tuple((float(x), float(y)) for x, y in flat),
        lines=tuple(lines),
        holes=tuple(tuple((float(x), float(y)) for x, y in h) for h in flat_holes),
        kind="layer",
        meta={"layer": float(index), "W": layer.W, "n": float(layer.n), "alpha": layer.alpha_deg},
        material_id=layer.material.id,
        t=layer.t,
        density=layer.material.density,
    )
