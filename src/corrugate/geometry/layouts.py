"""Layouts: the plan outline both layers fill, and the facet lengths L_j it gives each layer.

Coordinates. Layer 1's creases run along y, so its facets are strips across x (its chordwise
direction); layer 2 lies on it rotated 90 deg, its facets strips across y. Both layers fill the same
bounding box Lx x Ly, set by the layers themselves: Lx = (n1 + 1) p1 and Ly = (n2 + 1) p2 with the
pitch p = W sin(alpha/2) (docs/theory.md section 2). A layout is a shape in the unit box, scaled to
Lx x Ly:

* ``square``: the box itself, with Lx = Ly = L (paper eq. rect_geo_constrain_1);
* ``rectangle``: the box, Lx and Ly free (layers may differ);
* ``circle``: the inscribed disc, Lx = Ly = diameter;
* ``polygon``: any simple polygon, convex or concave, given by its vertices; it is scaled so that
  its bounding box is Lx x Ly (so a triangle or a trapezoid is a polygon).

Facet length. Facet j of a layer with n creases is the strip of plan width p between its two creases.
Its length is defined as the area of the outline inside that strip divided by the pitch,

    L_j = area(outline intersected with strip j) / p.

This equals the facet's length for a rectangle, the chord at the strip's centre to second order for a
smooth outline, and it makes the flat area of the facet exactly W L_j (the flat facet is the plan
strip stretched by 1/sin(alpha/2)), so mass follows the cut file exactly. A strip that a concave
outline cuts into several pieces has as L_j their total length: the pieces act as parallel springs,
as the spring model assumes.

Holes. Every layout may carry ``holes`` (:mod:`corrugate.geometry.holes`): inner cut-outs in mm from the
box's centre, not scaled. L_j above is the outline's without holes; :func:`layer_inverse_sums`
applies the hole model to the spring sums (touched facets left out of the parallel sum, blocked
lengths out of the series sum) and :mod:`corrugate.mechanics.mass` removes the cut area.

Because the shape is scaled, L_j = S (n + 1) dA_j with S the other side of the box and dA_j the
fraction of the unit box's outline area in strip j; the springs need only the sum of 1/L_j, which is
(n + 1)/S times G(n) = sum_j 1/((n + 1)^2 dA_j), computed once per n and cached.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from functools import lru_cache
from typing import TYPE_CHECKING, Literal, Protocol

import numpy as np
from numpy.typing import ArrayLike, NDArray

from corrugate.core.errors import InputError, UnknownNameError
from corrugate.geometry.planar import crosses_itself
from corrugate.geometry.planar import signed_area as _signed_area
from corrugate.names import LAYOUT_SHAPES

if TYPE_CHECKING:
    from corrugate.geometry.holes import Hole

__all__ = [
    "LAYOUTS",
    "Axis",
    "Circle",
    "Layout",
    "Polygon",
    "Rectangle",
    "Square",
    "facet_lengths",
    "layer_inverse_sums",
    "make_layout",
]

Axis = Literal["x", "y"]
#: Sides of the regular polygon that stands for a circle in cut files (area error 1.3e-5).
CIRCLE_SEGMENTS = 720
FloatArray = NDArray[np.float64]


class Layout(Protocol):
    """A plan outline in the unit box [0, 1] x [0, 1], scaled to the layers' box Lx x Ly."""

    @property
    def name(self) -> str:
        """Layout name (square, rectangle, circle, polygon)."""
        ...

    @property
    def equal_sides(self) -> bool:
        """Whether Lx must equal Ly (square, circle)."""
        ...

    @property
    def holes(self) -> tuple[Hole, ...]:
        """Inner cut-outs, in mm relative to the box's centre (:mod:`corrugate.geometry.holes`)."""
        ...

    def __hash__(self) -> int: ...

    def area_fraction(self) -> float:
        """Outline area divided by the area of its bounding box."""
        ...

    def cumulative_area(self, u: FloatArray, axis: Axis) -> FloatArray:
        """Area of the unit-box outline on the side coordinate < u along ``axis``."""
        ...

    def span(self, Lx: FloatArray, Ly: FloatArray, eta_deg: FloatArray) -> FloatArray:
        """Width (mm) of the scaled outline projected on the direction eta (from the y axis)."""
        ...

    def describe(self) -> dict[str, object]:
        """JSON-ready description."""
        ...

    def plan_outline(self, Lx: float, Ly: float) -> FloatArray:
        """The outline scaled to Lx x Ly (mm) as a counter-clockwise polygon, shape (k, 2).

        Exact for polygonal layouts; a circle is a regular polygon of ``CIRCLE_SEGMENTS`` sides.
        """
        ...

    def perimeter_runs(self, Lx: ArrayLike, Ly: ArrayLike) -> list[tuple[FloatArray, bool]]:
        """The perimeter as straight or smooth runs: (length in mm, ends at a corner) per run.

        Vectorised over Lx, Ly. A polygon has one run per edge, each ending at a corner; a circle
        has one smooth run, its circumference.
        """
        ...


def _strip_fractions(layout: Layout, n: int, axis: Axis) -> FloatArray:
    u = np.linspace(0.0, 1.0, n + 2)
    dA = np.diff(layout.cumulative_area(u, axis))
    if np.any(dA <= 1e-12):
        raise InputError(
            "layout",
            layout.name,
            "an outline that covers every facet strip",
            reason=f"leaves a facet strip empty with n = {n} creases",
        )
    return np.asarray(dA, dtype=np.float64)


@lru_cache(maxsize=4096)
def _inverse_strip_sum(layout: Layout, n: int, axis: Axis) -> float:
    dA = _strip_fractions(layout, n, axis)
    return float(np.sum(1.0 / ((n + 1) ** 2 * dA)))


def inverse_length_sum(
    layout: Layout, n: ArrayLike, other_side: ArrayLike, axis: Axis
) -> FloatArray:
    """sum_j 1/L_j (1/mm) for layers with ``n`` creases whose facets span ``other_side`` (mm).

    Vectorised over arrays; exact for every layout (see the module docstring).
    """
    n_arr = np.asarray(n, dtype=np.int64)
    S = np.asarray(other_side, dtype=np.float64)
    if isinstance(layout, Square | Rectangle):  # G(n) = 1 in closed form
        return np.asarray((np.asarray(n_arr, dtype=np.float64) + 1.0) / S)
    else:
        uniq, inverse = np.unique(n_arr, return_inverse=True)
        G = np.array([_inverse_strip_sum(layout, int(k), axis) for k in uniq])[inverse]
        G = G.reshape(n_arr.shape)
    return np.asarray(G * (n_arr + 1) / S, dtype=np.float64)


def length_sum(layout: Layout, n: ArrayLike, other_side: ArrayLike) -> FloatArray:
    """sum_j L_j (mm): (n + 1) S times the outline's area fraction."""
    n_arr = np.asarray(n, dtype=np.float64)
    total = (n_arr + 1) * np.asarray(other_side)
    af = layout.area_fraction()
    return np.asarray(total if af == 1.0 else total * af)


def layer_inverse_sums(
    layout: Layout, n: ArrayLike, pitch: ArrayLike, other_side: ArrayLike, axis: Axis
) -> tuple[FloatArray, FloatArray]:
    """(parallel, series) sums of 1/L_j (1/mm) of layers with ``n`` creases, pitch ``pitch`` (mm)
    and facets spanning ``other_side`` (mm), with the layout's holes (:mod:`corrugate.geometry.holes`):
    the parallel sum leaves out the facets a hole touches, the series sum shortens them by the
    length the hole blocks. Without holes both are :func:`inverse_length_sum`. Vectorised."""
    q = inverse_length_sum(layout, n, other_side, axis)
    if not layout.holes:
        return q, q
    from corrugate.geometry.holes import touched_sums  # a layout with holes only

    touched, extra = touched_sums(
        layout.holes,
        axis,
        n,
        pitch,
        other_side,
        lambda u: layout.cumulative_area(np.asarray(u, dtype=np.float64), axis),
    )
    return np.maximum(q - touched, 0.0), np.asarray(q + extra, dtype=np.float64)


def facet_lengths(layout: Layout, n: int, other_side: float, axis: Axis) -> FloatArray:
    """The n + 1 facet lengths L_j (mm) of one layer, in order along its chord ``axis``."""
    return (n + 1) * other_side * _strip_fractions(layout, n, axis)


@dataclass(frozen=True)
class Rectangle:
    """The whole box: Lx = (n1 + 1) p1 and Ly = (n2 + 1) p2; every L_j equals the other side."""

    name: str = "rectangle"
    equal_sides: bool = False
    holes: tuple[Hole, ...] = ()

    def area_fraction(self) -> float:
        return 1.0

    def cumulative_area(self, u: FloatArray, axis: Axis) -> FloatArray:
        return np.clip(np.asarray(u, dtype=np.float64), 0.0, 1.0)

    def span(self, Lx: FloatArray, Ly: FloatArray, eta_deg: FloatArray) -> FloatArray:
        e = np.radians(eta_deg)
        a, b = np.abs(np.sin(e)), np.abs(np.cos(e))
        if np.ndim(e) == 0:  # one direction: |x y| = |x| |y| exactly, so skip the zero term
            a_, b_ = float(a), float(b)
            if a_ == 0.0:
                return np.asarray(np.abs(Ly) if b_ == 1.0 else np.abs(Ly) * b_)
            if b_ == 0.0:
                return np.asarray(np.abs(Lx) * a_)
        return np.asarray(np.abs(Lx) * a + np.abs(Ly) * b)

    def describe(self) -> dict[str, object]:
        return _with_holes({"shape": self.name}, self.holes)

    def plan_outline(self, Lx: float, Ly: float) -> FloatArray:
        return np.array([[0.0, 0.0], [Lx, 0.0], [Lx, Ly], [0.0, Ly]])

    def perimeter_runs(self, Lx: ArrayLike, Ly: ArrayLike) -> list[tuple[FloatArray, bool]]:
        x, y = np.asarray(Lx, dtype=np.float64), np.asarray(Ly, dtype=np.float64)
        return [(x, True), (y, True), (x, True), (y, True)]


@dataclass(frozen=True)
class Square(Rectangle):
    """The paper's square: Lx = Ly = L = (n + 1) W sin(alpha/2), L_j = L."""

    name: str = "square"
    equal_sides: bool = True


@dataclass(frozen=True)
class Circle:
    """The disc inscribed in the box; Lx = Ly = diameter. Strip areas are exact (circular segments)."""

    name: str = "circle"
    equal_sides: bool = True
    holes: tuple[Hole, ...] = ()

    def area_fraction(self) -> float:
        return math.pi / 4

    def cumulative_area(self, u: FloatArray, axis: Axis) -> FloatArray:
        r = 0.5
        x = np.clip(np.asarray(u, dtype=np.float64) - r, -r, r)

        def F(z: FloatArray) -> FloatArray:
            return np.asarray(
                z * np.sqrt(np.maximum(r * r - z * z, 0.0)) + r * r * np.arcsin(z / r)
            )

        return np.asarray(F(x) - F(np.asarray(-r)))

    def span(self, Lx: FloatArray, Ly: FloatArray, eta_deg: FloatArray) -> FloatArray:
        e = np.radians(eta_deg)
        return np.asarray(np.hypot(Lx * np.sin(e), Ly * np.cos(e)))

    def describe(self) -> dict[str, object]:
        return _with_holes({"shape": self.name}, self.holes)

    def plan_outline(self, Lx: float, Ly: float) -> FloatArray:
        k = np.arange(CIRCLE_SEGMENTS) * (2 * np.pi / CIRCLE_SEGMENTS)
        return np.column_stack([Lx / 2 * (1 + np.cos(k)), Ly / 2 * (1 + np.sin(k))])

    def perimeter_runs(self, Lx: ArrayLike, Ly: ArrayLike) -> list[tuple[FloatArray, bool]]:
        a = np.asarray(Lx, dtype=np.float64) / 2
        b = np.asarray(Ly, dtype=np.float64) / 2
        # Ramanujan's ellipse perimeter; exact (pi D) for the circle, where a = b
        h = ((a - b) / (a + b)) ** 2
        return [(np.asarray(np.pi * (a + b) * (1 + 3 * h / (10 + np.sqrt(4 - 3 * h)))), False)]


@dataclass(frozen=True)
class Polygon:
    """A simple polygon (convex or concave), scaled so its bounding box is Lx x Ly.

    ``vertices`` are (x, y) pairs in any unit and either orientation; only the shape matters.
    """

    vertices: tuple[tuple[float, float], ...]
    name: str = "polygon"
    equal_sides: bool = False
    holes: tuple[Hole, ...] = ()
    _unit: FloatArray = field(init=False, repr=False, compare=False, hash=False)

    def __post_init__(self) -> None:
        v = np.asarray(self.vertices, dtype=np.float64)
        if v.ndim != 2 or v.shape[1] != 2 or len(v) < 3 or not np.all(np.isfinite(v)):
            raise InputError(
                "vertices",
                self.vertices,
                "at least 3 finite (x, y) pairs",
                reason="is not a polygon",
            )
        lo, hi = v.min(axis=0), v.max(axis=0)
        if np.any(hi - lo <= 0):
            raise InputError(
                "vertices", self.vertices, "a polygon with area", reason="is degenerate"
            )
        unit = (v - lo) / (hi - lo)
        if _signed_area(unit) < 0:
            unit = unit[::-1].copy()
        if crosses_itself(unit):
            raise InputError(
                "vertices",
                self.vertices,
                "a simple polygon (edges must not cross)",
                reason="crosses itself",
            )
        object.__setattr__(self, "_unit", unit)

    def area_fraction(self) -> float:
        return _signed_area(self._unit)

    def cumulative_area(self, u: FloatArray, axis: Axis) -> FloatArray:
        """Exact area left of u: -sum over edges of the integral of y dx over their part with x < u
        (counter-clockwise orientation); axis ``y`` swaps the coordinates (which flips orientation).
        Evaluated in slices of u (:func:`_in_slices`): memory does not grow with u times edges."""
        uu = np.asarray(u, dtype=np.float64)
        return _in_slices(lambda part: self._cumulative_area(part, axis), len(self._unit), uu)

    def _cumulative_area(self, u: FloatArray, axis: Axis) -> FloatArray:
        v = self._unit if axis == "x" else self._unit[:, ::-1]
        sign_orient = 1.0 if axis == "x" else -1.0
        x0, y0 = v[:, 0], v[:, 1]
        x1, y1 = np.roll(x0, -1), np.roll(y0, -1)
        uu = np.asarray(u, dtype=np.float64)[..., None]
        a, b = np.minimum(x0, x1), np.maximum(x0, x1)
        dx = x1 - x0
        slope = np.divide(y1 - y0, dx, out=np.zeros_like(dx), where=dx != 0)
        bu = np.clip(uu, a, b)

        def y_at(x: FloatArray) -> FloatArray:
            return np.asarray(y0 + slope * (x - x0))

        integral = (bu - a) * (y_at(a) + y_at(bu)) / 2 * np.sign(dx)
        return np.asarray(-sign_orient * integral.sum(axis=-1))

    def span(self, Lx: FloatArray, Ly: FloatArray, eta_deg: FloatArray) -> FloatArray:
        """Width (mm) of the outline, scaled to Lx by Ly, across direction eta (deg), in slices
        of the points (:func:`_in_slices`)."""
        x, y, e = np.broadcast_arrays(
            np.asarray(Lx, dtype=np.float64),
            np.asarray(Ly, dtype=np.float64),
            np.asarray(eta_deg, dtype=np.float64),
        )
        xye = np.stack([x, y, e], axis=-1)
        return _in_slices(
            lambda part: self._span(part[..., 0], part[..., 1], part[..., 2]),
            len(self._unit),
            xye,
            trailing=1,
        )

    def _span(self, Lx: FloatArray, Ly: FloatArray, eta_deg: FloatArray) -> FloatArray:
        e = np.radians(np.asarray(eta_deg, dtype=np.float64))[..., None]
        px = self._unit[:, 0] * np.asarray(Lx, dtype=np.float64)[..., None]
        py = self._unit[:, 1] * np.asarray(Ly, dtype=np.float64)[..., None]
        proj = px * np.sin(e) + py * np.cos(e)
        return np.asarray(proj.max(axis=-1) - proj.min(axis=-1))

    def describe(self) -> dict[str, object]:
        out: dict[str, object] = {"shape": self.name, "vertices": [list(p) for p in self.vertices]}
        return _with_holes(out, self.holes)

    def plan_outline(self, Lx: float, Ly: float) -> FloatArray:
        return np.asarray(self._unit * np.array([Lx, Ly]), dtype=np.float64)

    def perimeter_runs(self, Lx: ArrayLike, Ly: ArrayLike) -> list[tuple[FloatArray, bool]]:
        x, y = np.asarray(Lx, dtype=np.float64), np.asarray(Ly, dtype=np.float64)
        d = np.roll(self._unit, -1, axis=0) - self._unit
        return [(np.asarray(np.hypot(dx * x, dy * y)), True) for dx, dy in d]


#: Most elements of a points-by-vertices temporary of a polygon outline (8 MB of float64 each).
SLICE_ELEMENTS = 1 << 20


def _in_slices(
    fn: Callable[[FloatArray], FloatArray], vertices: int, a: FloatArray, trailing: int = 0
) -> FloatArray:
    """``fn(a)`` for a function of points (the leading axes of ``a``; ``trailing`` axes belong
    to each point) whose temporaries hold ``vertices`` values a point, evaluated over slices of at
    most :data:`SLICE_ELEMENTS` / ``vertices`` points: the same values, bounded memory."""
    shape = a.shape[: a.ndim - trailing]
    count = int(np.prod(shape, dtype=np.int64))
    rows = max(1, SLICE_ELEMENTS // max(vertices, 1))
    if count <= rows:
        return np.asarray(fn(a))
    flat = a.reshape(count, *a.shape[a.ndim - trailing :])
    out = np.concatenate([np.asarray(fn(flat[k : k + rows])) for k in range(0, count, rows)])
    return out.reshape(shape)


def _with_holes(out: dict[str, object], holes: tuple[Hole, ...]) -> dict[str, object]:
    if holes:
        out["holes"] = [h.describe() for h in holes]
    return out


#: The outlines :func:`make_layout` builds, by name.
LAYOUTS = LAYOUT_SHAPES


def make_layout(shape: str, vertices: object = None, holes: tuple[Hole, ...] = ()) -> Layout:
    """Build a layout by name; ``polygon`` needs ``vertices`` (a sequence of (x, y) pairs);
    ``holes`` are inner cut-outs (:mod:`corrugate.geometry.holes`), in mm from the box's centre."""
    key = shape.strip().lower()
    holes = tuple(holes)
    if key == "square":
        return Square(holes=holes)
    if key == "rectangle":
        return Rectangle(holes=holes)
    if key == "circle":
        return Circle(holes=holes)
    if key == "polygon":
        if vertices is None:
            raise InputError("vertices", None, "at least 3 (x, y) pairs", reason="is missing")
        try:
            pts = tuple((float(p[0]), float(p[1])) for p in vertices)  # type: ignore[attr-defined]
        except (TypeError, ValueError, IndexError) as exc:
            raise InputError(
                "vertices", vertices, "a list of (x, y) pairs", reason="is not a polygon"
            ) from exc
        return Polygon(pts, holes=holes)
    raise UnknownNameError("layout", shape, list(LAYOUTS))
