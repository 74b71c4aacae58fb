"""Inner cut-outs (holes) of a layout: an axle hole in a wheel, a bolt hole, any polygonal window.

Coordinates. A hole is given in plan mm relative to the **centre of the layout's bounding box**:
x across layer 1's creases (its chordwise direction), y along them. Unlike the outline, a hole is
not scaled with the layers: a 6 mm axle hole stays 6 mm whatever the panel's size.

Shapes. A ``circle`` (``diameter``, ``center``) or a ``polygon`` (``vertices`` relative to
``center``, any orientation, simple). In cut files a circle is the inscribed regular polygon of
:data:`HOLE_SEGMENTS` sides; the **mass** uses that polygon's area (so it equals rho t times the
area cut), the **stiffness** uses the true circle (slightly larger, so conservative).

The model of a hole (used by :mod:`corrugate.analysis.evaluate`, docs/theory.md 3.2 with holes). Facet j of a
layer is the plan strip of width p between two creases; its length L_j (:mod:`corrugate.geometry.layouts`)
is that of the outline without holes. A hole *touches* facet j when it overlaps the strip with
positive area. Each facet is read as a bundle of independent columns (lateral load sharing is
neglected, which can only make the panel softer):

* parallel (spanwise) sums, K_S and D_S: a touched facet is cut through along its length, so it
  carries nothing: sum_j 1/L_j runs over the untouched facets only (conservative: the ligaments
  beside a hole that only nicks a facet are ignored);
* series (chordwise) sums, K_C and D_C: a column of facet j that meets the hole is broken, so the
  facet carries load over L_j - b_j only, b_j the y-extent (span-wise extent) of the hole inside
  the strip, summed over the holes that touch it: sum_j 1/(L_j - b_j). If b_j >= L_j the layer
  has no chordwise stiffness (1/0 = inf).

A hole only ever removes terms from parallel sums and shortens series lengths, so every stiffness
with holes is at most the one without; the certified solver's bounds rely on that
(:mod:`corrugate.solver.quantities`). The mass of each layer drops by rho t A_h / s with A_h the
plan area of the holes: the flat blank is the plan stretched by 1/sin(alpha/2) across the creases,
so a plan circle is cut as an ellipse of axes d/s and d.

Validity. Every hole must lie inside the outline with a ligament of at least
:data:`MIN_LIGAMENT` mm, and holes must be that far apart; :func:`check_holes` checks it for a
given size. For square, rectangle and circle layouts the ligaments grow with the size, so a hole
that fits the smallest panel a spec allows fits every larger one.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from corrugate.core.errors import InputError
from corrugate.geometry.planar import crosses_itself
from corrugate.geometry.planar import signed_area as _signed_area
from corrugate.names import DEFAULT_HOLE_SHAPE, HOLE_SHAPES, HoleShape

__all__ = [
    "HOLE_SEGMENTS",
    "MIN_LIGAMENT",
    "Hole",
    "check_holes",
    "hole_area",
    "hole_rings",
    "holes_from_data",
    "holes_text",
    "touched_sums",
]

FloatArray = NDArray[np.float64]
Point = tuple[float, float]
Axis = Literal["x", "y"]

#: Sides of the regular polygon cut for a circular hole (area 5.1e-5 below pi r^2).
HOLE_SEGMENTS = 360
#: Smallest material ligament (mm) allowed between a hole and the outline or another hole.
MIN_LIGAMENT = 0.5


@dataclass(frozen=True)
class Hole:
    """One inner cut-out, in plan mm relative to the layout's centre (x across layer 1's creases).

    ``shape`` "circle" uses ``diameter`` (mm, > 0); "polygon" uses ``vertices`` ((x, y) in mm,
    relative to ``center``, simple, at least 3). ``center`` (mm) places either.
    """

    shape: HoleShape
    center: tuple[float, float] = (0.0, 0.0)
    diameter: float = 0.0
    vertices: tuple[tuple[float, float], ...] = ()

    def __post_init__(self) -> None:
        if not all(math.isfinite(c) for c in self.center):
            raise InputError("center", self.center, "finite (x, y) in mm")
        if self.shape == "circle":
            if not (math.isfinite(self.diameter) and self.diameter > 0):
                raise InputError("diameter", f"{self.diameter} mm", "diameter > 0 mm")
            return
        if self.shape != "polygon":
            raise InputError(
                "shape", repr(self.shape), "'circle' or 'polygon'", reason="is unknown"
            )
        v = np.asarray(self.vertices, dtype=np.float64)
        if v.ndim != 2 or v.shape[1] != 2 or len(v) < 3 or not np.all(np.isfinite(v)):
            raise InputError(
                "vertices",
                self.vertices,
                "at least 3 finite (x, y) pairs",
                reason="is not a polygon",
            )
        if abs(_signed_area(v)) <= 1e-12:
            raise InputError(
                "vertices", self.vertices, "a polygon with area", reason="is degenerate"
            )
        if crosses_itself(v):
            raise InputError(
                "vertices",
                self.vertices,
                "a simple polygon (edges must not cross)",
                reason="crosses itself",
            )

    @property
    def radius(self) -> float:
        """Radius (mm) of a circular hole; 0 for a polygon."""
        return float(self.diameter) / 2

    def ring(self) -> FloatArray:
        """The cut polygon (counter-clockwise, mm, relative to the layout's centre), shape (k, 2).

        A circle is the inscribed regular polygon of :data:`HOLE_SEGMENTS` sides."""
        cx, cy = self.center
        if self.shape == "circle":
            k = np.arange(HOLE_SEGMENTS) * (2 * np.pi / HOLE_SEGMENTS)
            return np.column_stack([cx + self.radius * np.cos(k), cy + self.radius * np.sin(k)])
        v: FloatArray = np.asarray(self.vertices, dtype=np.float64) + np.array([cx, cy])
        return v if _signed_area(v) > 0 else np.ascontiguousarray(v[::-1])

    @property
    def area(self) -> float:
        """Area (mm^2) cut: that of :meth:`ring` (for a circle, the inscribed polygon's)."""
        return _signed_area(self.ring())

    def extent(self, axis: Axis) -> tuple[float, float]:
        """(min, max) of the hole along ``axis`` (mm, relative to the centre); a circle's exact."""
        i = 0 if axis == "x" else 1
        if self.shape == "circle":
            return self.center[i] - self.radius, self.center[i] + self.radius
        r = self.ring()[:, i]
        return float(r.min()), float(r.max())

    def blocked(self, axis: Axis, lo: ArrayLike, hi: ArrayLike) -> FloatArray:
        """Extent (mm) across ``axis`` of the hole inside the slab lo <= (coordinate along
        ``axis``) <= hi, vectorised: the length of the facet a hole blocks (module docstring).

        A circle uses the true circle (2 sqrt(r^2 - d^2), d the distance from the centre to the
        slab); a polygon the extent of its part inside the slab. 0 where they do not overlap.
        """
        a = np.asarray(lo, dtype=np.float64)
        b = np.asarray(hi, dtype=np.float64)
        i = 0 if axis == "x" else 1
        if self.shape == "circle":
            c = self.center[i]
            d = np.maximum(np.maximum(a - c, c - b), 0.0)
            r = self.radius
            return np.asarray(np.where(d < r, 2 * np.sqrt(np.maximum(r * r - d * d, 0.0)), 0.0))
        ring = self.ring()
        u0, w0 = ring[:, i], ring[:, 1 - i]
        u1, w1 = np.roll(u0, -1), np.roll(w0, -1)
        A, B = a[..., None], b[..., None]
        inside = (u0 >= A) & (u0 <= B)
        cand_hi = [np.where(inside, w0, -np.inf)]
        cand_lo = [np.where(inside, w0, np.inf)]
        du = u1 - u0
        safe = np.where(du == 0, 1.0, du)
        for X in (A, B):
            cross = ((u0 - X) * (u1 - X) < 0) & (du != 0)
            w = w0 + (X - u0) / safe * (w1 - w0)
            cand_hi.append(np.where(cross, w, -np.inf))
            cand_lo.append(np.where(cross, w, np.inf))
        top = np.max(np.concatenate(cand_hi, axis=-1), axis=-1)
        bot = np.min(np.concatenate(cand_lo, axis=-1), axis=-1)
        out = np.where(np.isfinite(top) & np.isfinite(bot), top - bot, 0.0)
        lo_e, hi_e = self.extent(axis)
        return np.asarray(np.where((lo_e < b) & (hi_e > a), out, 0.0))

    def describe(self) -> dict[str, object]:
        """JSON-ready description (mm)."""
        out: dict[str, object] = {"shape": self.shape, "center_mm": list(self.center)}
        if self.shape == "circle":
            out["diameter_mm"] = self.diameter
        else:
            out["vertices_mm"] = [list(p) for p in self.vertices]
        out["area_mm2"] = self.area
        return out


def holes_text(holes: Sequence[Hole]) -> str:
    """One line naming the holes (empty without holes), for reports."""
    if not holes:
        return ""
    return "holes: " + "; ".join(_shown(h) for h in holes) + " (from the layout's centre)"


def hole_area(holes: Sequence[Hole]) -> float:
    """Total plan area (mm^2) of the holes' cut polygons."""
    return float(sum(h.area for h in holes))


def hole_rings(holes: Sequence[Hole], Lx: float, Ly: float) -> list[FloatArray]:
    """The holes' cut polygons in the layout's plan coordinates [0, Lx] x [0, Ly] (mm)."""
    return [h.ring() + np.array([Lx / 2, Ly / 2]) for h in holes]


# -- validity ----------------------------------------------------------------------------------


def _inside(points: FloatArray, poly: FloatArray) -> NDArray[np.bool_]:
    """Even-odd point-in-polygon, vectorised over ``points`` (k, 2)."""
    x, y = points[:, 0][:, None], points[:, 1][:, None]
    x0, y0 = poly[:, 0], poly[:, 1]
    x1, y1 = np.roll(x0, -1), np.roll(y0, -1)
    cond = (y0 > y) != (y1 > y)
    dy = np.where(y1 == y0, 1.0, y1 - y0)
    xc = x0 + (y - y0) * (x1 - x0) / dy
    return np.asarray(np.count_nonzero(cond & (x < xc), axis=1) % 2 == 1)


def _point_segment_distance(points: FloatArray, poly: FloatArray) -> float:
    """Smallest distance (mm) from ``points`` to the edges of the closed polygon ``poly``."""
    a = poly
    b = np.roll(poly, -1, axis=0)
    ab = b - a
    ap = points[:, None, :] - a[None, :, :]
    denom = np.maximum(np.sum(ab * ab, axis=1), 1e-300)
    t = np.clip(np.sum(ap * ab[None], axis=2) / denom, 0.0, 1.0)
    d = ap - t[..., None] * ab[None]
    return float(np.sqrt(np.min(np.sum(d * d, axis=2))))


def _gap(p: FloatArray, q: FloatArray) -> float:
    """Distance (mm) between the boundaries of two polygons."""
    return min(_point_segment_distance(p, q), _point_segment_distance(q, p))


#: Slack (mm) of :func:`_clear`: within it of the ligament, the full check decides.
_CLEAR_SLACK = 1e-9


def _clear(centre: FloatArray, reach: float, outline: FloatArray) -> bool:
    """Whether the disc of radius ``reach`` (mm) about ``centre`` lies inside ``outline`` with a
    ligament of at least :data:`MIN_LIGAMENT` mm: its centre inside, and every edge of the
    outline at least ``reach + MIN_LIGAMENT`` from it. Then any polygon inside that disc passes
    :func:`check_holes`' outline test (every point of its boundary is within ``reach`` of the
    centre, every point of the outline's at least that plus the ligament away, and the disc,
    connected and clear of the outline, lies inside it). One point against the outline's edges
    instead of every vertex of the hole (a circular hole has :data:`HOLE_SEGMENTS`)."""
    c = np.asarray(centre, dtype=np.float64)[None, :]
    if not bool(_inside(c, outline)[0]):
        return False
    return _point_segment_distance(c, outline) >= reach + MIN_LIGAMENT + _CLEAR_SLACK


def check_holes(
    holes: Sequence[Hole], outline: FloatArray, Lx: float, Ly: float, field: str = "holes"
) -> None:
    """Raise :class:`InputError` (field ``{field}[i]``) unless every hole lies inside ``outline``
    (plan polygon in [0, Lx] x [0, Ly], mm) with a ligament >= :data:`MIN_LIGAMENT` mm and the
    holes are as far apart. A circle is checked as the true circle."""
    rings = hole_rings(holes, Lx, Ly)
    centres = [ring.mean(axis=0) for ring in rings]
    reach = [float(np.max(np.hypot(*(ring - c).T))) for ring, c in zip(rings, centres, strict=True)]
    for i, (h, ring) in enumerate(zip(holes, rings, strict=True)):
        where = f"{field}[{i}]"
        size = f"the {Lx:.4g} x {Ly:.4g} mm outline"
        pad = h.radius - h.radius * math.cos(math.pi / HOLE_SEGMENTS) if h.shape == "circle" else 0
        if _clear(centres[i], reach[i] + pad, outline):
            inside, gap = True, math.inf  # the ring's enclosing circle is a ligament inside
        else:
            inside = bool(np.all(_inside(ring, outline)))
            gap = _gap(ring, outline) - pad
        if not inside or gap < MIN_LIGAMENT:
            raise InputError(
                where,
                _shown(h),
                f"a hole inside {size} with a ligament >= {MIN_LIGAMENT:g} mm",
                reason="cuts the outline"
                if not inside or gap <= 0
                else f"leaves a ligament of {gap:.3g} mm",
            )
        for k in range(i):
            # two holes whose enclosing circles are a ligament apart need no closer look: the
            # boundaries are at least that far apart (and cannot overlap)
            apart = float(np.hypot(*(centres[i] - centres[k]))) - reach[i] - reach[k]
            if apart >= MIN_LIGAMENT:
                continue
            other = rings[k]
            pad_k = (
                holes[k].radius - holes[k].radius * math.cos(math.pi / HOLE_SEGMENTS)
                if holes[k].shape == "circle"
                else 0
            )
            overlap = bool(np.any(_inside(ring, other)) or np.any(_inside(other, ring)))
            gap = _gap(ring, other) - pad - pad_k
            if overlap or gap < MIN_LIGAMENT:
                raise InputError(
                    where,
                    _shown(h),
                    f"holes apart from {field}[{k}] by >= {MIN_LIGAMENT:g} mm",
                    reason=f"cuts {field}[{k}]" if overlap or gap <= 0 else "is too close",
                )


def _shown(h: Hole) -> str:
    cx, cy = h.center
    if h.shape == "circle":
        return f"circle d {h.diameter:g} mm at ({cx:g}, {cy:g}) mm"
    return f"polygon of {len(h.vertices)} vertices at ({cx:g}, {cy:g}) mm"


# -- facet sums --------------------------------------------------------------------------------

#: Most point-facet values :func:`touched_sums` holds at once (8 MB a temporary, a dozen of them):
#: its points are taken in slices of TOUCHED_SLICE / (facets a hole touches) (the thin-ligament
#: wheel's 225 885 points by 61 facets took 1.3 GB at once).
TOUCHED_SLICE = 1 << 20


def touched_sums(
    holes: Sequence[Hole],
    axis: Axis,
    n: ArrayLike,
    p: ArrayLike,
    S: ArrayLike,
    cumulative_area: Callable[[FloatArray], FloatArray],
) -> tuple[FloatArray, FloatArray]:
    """The hole corrections of a layer's facet sums, vectorised over points.

    Layer with ``n`` creases and pitch ``p`` (mm) across ``axis`` (its strips j = 0..n span
    [j p, (j + 1) p] - (n + 1) p / 2 relative to the centre) whose facets span ``S`` (mm);
    ``cumulative_area(u)`` is the unit outline's area below u along ``axis``, so that
    L_j = (n + 1) S dA_j (:mod:`corrugate.geometry.layouts`). Returns ``(touched, extra)``, each summed
    over the facets the holes touch: sum 1/L_j (to subtract from the parallel sum) and
    sum [1/(L_j - b_j) - 1/L_j] (to add to the series sum; inf when b_j >= L_j), in 1/mm.
    """
    n_arr = np.asarray(n, dtype=np.int64)
    p_arr = np.asarray(p, dtype=np.float64)
    S_arr = np.asarray(S, dtype=np.float64)
    shape = np.broadcast_shapes(n_arr.shape, p_arr.shape, S_arr.shape)
    n_b = np.broadcast_to(n_arr, shape).ravel()
    p_b = np.broadcast_to(p_arr, shape).ravel()
    S_b = np.broadcast_to(S_arr, shape).ravel()
    zero = np.zeros(shape)
    if not holes or n_b.size == 0:
        return zero, zero.copy()
    half = (n_b + 1) * p_b / 2
    j_lo = np.full(n_b.shape, np.iinfo(np.int64).max)
    j_hi = np.full(n_b.shape, -1)
    for h in holes:
        lo, hi = h.extent(axis)
        a = np.floor((lo + half) / p_b).astype(np.int64)
        b = np.ceil((hi + half) / p_b).astype(np.int64) - 1
        j_lo = np.minimum(j_lo, np.clip(a, 0, n_b))
        j_hi = np.maximum(j_hi, np.clip(b, 0, n_b))
    K = int(np.max(j_hi - j_lo + 1))
    rows = max(1, TOUCHED_SLICE // max(K, 1))
    if n_b.size > rows:  # points by facets touched, a dozen temporaries: in slices
        parts = [
            touched_sums(
                holes,
                axis,
                n_b[k : k + rows],
                p_b[k : k + rows],
                S_b[k : k + rows],
                cumulative_area,
            )
            for k in range(0, n_b.size, rows)
        ]
        return (
            np.concatenate([t for t, _ in parts]).reshape(shape),
            np.concatenate([e for _, e in parts]).reshape(shape),
        )
    j = j_lo[:, None] + np.arange(max(K, 1))[None, :]
    valid = j <= j_hi[:, None]
    j = np.minimum(j, n_b[:, None])
    slab_lo = j * p_b[:, None] - half[:, None]
    slab_hi = slab_lo + p_b[:, None]
    touched = np.zeros(j.shape, dtype=bool)
    b_sum = np.zeros(j.shape)
    for h in holes:
        lo, hi = h.extent(axis)
        t = (lo < slab_hi) & (hi > slab_lo)
        touched |= t
        b_sum += np.where(t, h.blocked(axis, slab_lo, slab_hi), 0.0)
    touched &= valid
    m = (n_b + 1)[:, None].astype(np.float64)
    dA = cumulative_area((j + 1) / m) - cumulative_area(j / m)
    L = m * S_b[:, None] * np.asarray(dA, dtype=np.float64)
    inv_L = np.where(touched, 1.0 / np.where(touched, L, 1.0), 0.0)
    net = L - b_sum
    with np.errstate(divide="ignore"):
        extra_j = np.where(
            touched, np.where(net > 0, 1.0 / np.where(net > 0, net, 1.0), np.inf), 0.0
        )
    extra_j = np.where(touched, extra_j - inv_L, 0.0)
    return inv_L.sum(axis=1).reshape(shape), extra_j.sum(axis=1).reshape(shape)


def holes_from_data(data: object, field: str = "holes") -> tuple[Hole, ...]:
    """Holes from plain data: a list of tables ``{shape, diameter, center, vertices}`` whose
    values are numbers in mm or strings with units (``"6 mm"``); errors name ``{field}[i].key``."""
    from corrugate.core.units import parse_quantity

    if data is None:
        return ()
    if not isinstance(data, Sequence) or isinstance(data, str | bytes):
        raise InputError(field, repr(data), "a list of hole tables", reason="is not a list")
    out = []
    for i, item in enumerate(data):
        where = f"{field}[{i}]"
        if not isinstance(item, dict):
            raise InputError(where, repr(item), "a table {shape, diameter | vertices, center}")
        item = {k: v for k, v in item.items() if v is not None}
        unknown = set(item) - {"shape", "diameter", "center", "vertices"}
        if unknown:
            key = sorted(unknown)[0]
            raise InputError(
                f"{where}.{key}",
                repr(item[key]),
                "one of center, diameter, shape, vertices",
                reason="is not a known key",
            )
        shape = item.get("shape", DEFAULT_HOLE_SHAPE)
        if shape not in HOLE_SHAPES:
            raise InputError(
                f"{where}.shape", repr(shape), "'circle' or 'polygon'", reason="is unknown"
            )

        def pair(v: object, key: str) -> tuple[float, float]:
            if not isinstance(v, Sequence) or isinstance(v, str | bytes) or len(v) != 2:
                raise InputError(key, repr(v), "[x, y] in mm", reason="cannot be read")
            return (parse_quantity(v[0], "mm", key), parse_quantity(v[1], "mm", key))

        center = pair(item.get("center", (0.0, 0.0)), f"{where}.center")
        try:
            if shape == "circle":
                if "vertices" in item:
                    raise InputError(
                        f"{where}.vertices",
                        "…",
                        "only for shape = 'polygon'",
                        reason="does not apply",
                    )
                if "diameter" not in item:
                    raise InputError(f"{where}.diameter", None, "a length > 0", reason="is missing")
                d = parse_quantity(item["diameter"], "mm", f"{where}.diameter")
                out.append(Hole("circle", center, diameter=d))
            else:
                if "diameter" in item:
                    raise InputError(
                        f"{where}.diameter",
                        repr(item["diameter"]),
                        "only for shape = 'circle'",
                        reason="does not apply",
                    )
                raw = item.get("vertices")
                if not isinstance(raw, Sequence) or isinstance(raw, str | bytes):
                    raise InputError(
                        f"{where}.vertices",
                        repr(raw),
                        "at least 3 [x, y] pairs",
                        reason="is missing",
                    )
                verts = tuple(pair(v, f"{where}.vertices[{k}]") for k, v in enumerate(raw))
                out.append(Hole("polygon", center, vertices=verts))
        except InputError as exc:
            if exc.field.startswith(where):
                raise
            raise exc.renamed(f"{where}.{exc.field}") from None
    return tuple(out)
