"""What the evaluators of a problem's quantities share at points and over boxes.

:class:`AtPoints` holds the points (:class:`~.points.DesignPoints`) and what every value there
is read from: one :func:`corrugate.analysis.evaluate.evaluate` of the two layers (the one
implementation of the model, so a design the solver accepts is exactly the design ``analyze``
reports), the extents Lx, Ly (mm), the longest facets (mm), the band's walls of a bonded joint.
:class:`OverBoxes` holds the boxes ``lo <= x <= hi`` (``lo is hi``: points) and what every
bound is read from: each layer at the low and the high corner (W, cos(alpha/2), pitch and
extent, computed as ``evaluate`` does), the bounds of Lx, Ly, the folded thickness t_d and the
longest facets, the layers' interval springs (:mod:`~.interval_springs`) and the layout's
coupon. Each is computed on first use and kept; :meth:`AtPoints.value` and
:meth:`OverBoxes.bounds` compute a quantity once with its evaluator (:mod:`~.evaluator`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import cached_property
from typing import Any, TypeVar

import numpy as np
from numpy.typing import NDArray

from corrugate.analysis.evaluate import LayerArrays, LazyEvaluation, coupon_of
from corrugate.geometry.layer import crease_layer
from corrugate.geometry.layouts import Circle, Rectangle
from corrugate.geometry.profile import ZIGZAG, ProfileKind
from corrugate.mechanics.behaviours import Behaviour
from corrugate.mechanics.creases import flexibility
from corrugate.mechanics.load_cases import band_walls
from corrugate.mechanics.offaxis import Coupon
from corrugate.solver.evaluator import Pair, evaluator_of
from corrugate.solver.interval import Interval, number
from corrugate.solver.interval_springs import Springs, layer_springs, span_bounds
from corrugate.solver.points import DesignPoints, LayerPoints
from corrugate.solver.problem import Candidate, Problem
from corrugate.solver.quantity import Quantity
from corrugate.solver.tables import Tables

__all__ = ["AtPoints", "Corner", "OverBoxes", "layer_corner"]

FloatArray = NDArray[np.float64]
T = TypeVar("T")


def _layers(cand: Candidate, x: LayerPoints, kind: ProfileKind = ZIGZAG) -> LayerArrays:
    """The layer ``x`` at the points, as columns, folded to ``kind``; ``x`` may override E (MPa)
    and t (mm) per point (used by the tolerance analysis)."""
    m = cand.material
    E = x.E[:, None] if x.E is not None else m.E
    t = x.t[:, None] if x.t is not None else cand.t
    n = np.asarray(x.n)[:, None]
    W, alpha = np.asarray(x.W)[:, None], np.asarray(x.alpha)[:, None]
    flex = flexibility(m.crease_stiffness)
    return LayerArrays(E, m.nu, t, W, n.astype(np.int64), alpha, m.density, kind, flex)


def same_layers(c1: Candidate, c2: Candidate, x: DesignPoints) -> bool:
    """Whether layer 2 is layer 1 (identical layers of one sheet, no per-point overrides)."""
    return c1 == c2 and x.identical and not x.layer(0).overrides


def column(v: FloatArray) -> Any:
    """A (k, 1) column of per-point values as a 1-D array (a scalar as a float)."""
    a = np.asarray(v, dtype=np.float64)
    return float(a) if a.ndim == 0 else a.reshape(-1)


class Columns:
    """A layer's springs (arrays of shape (k, 1) or scalars) seen as 1-D arrays."""

    def __init__(self, springs: Any) -> None:
        self._s = springs

    def __getattr__(self, name: str) -> Any:
        return column(getattr(self._s, name))


class _Shared:
    """Values computed once on first use, under a name (:meth:`shared`)."""

    def __init__(self) -> None:
        self._shared: dict[str, Any] = {}

    def shared(self, name: str, make: Callable[[], T]) -> T:
        """The value kept as ``name``, made by ``make()`` on first use (e.g. quantities an
        evaluator computes together)."""
        if name not in self._shared:
            self._shared[name] = make()
        return self._shared[name]  # type: ignore[no-any-return]


class AtPoints(_Shared):
    """The points ``x`` of ``problem`` on sheets (c1, c2) and what their values share (module
    docstring)."""

    def __init__(
        self, problem: Problem, c1: Candidate, c2: Candidate, x: DesignPoints, tables: Tables
    ) -> None:
        super().__init__()
        self.problem, self.c1, self.c2, self.x, self.tables = problem, c1, c2, x, tables
        self._values: dict[Quantity, FloatArray] = {}

    def value(self, q: Quantity) -> FloatArray:
        """The values of ``q`` at the points (its evaluator's, computed once)."""
        v = self._values.get(q)
        if v is None:
            v = self._values[q] = evaluator_of(q).point(self, q)
        return v

    @cached_property
    def etas(self) -> FloatArray:
        """The directions (deg) the evaluation covers: the problem's, else 0."""
        return np.asarray(self.problem.etas or (0.0,), dtype=np.float64)

    def column(self, eta: float) -> int:
        """The index of direction ``eta`` (deg) among :attr:`etas`."""
        return int(np.flatnonzero(self.etas == eta)[0])

    @cached_property
    def layers(self) -> tuple[LayerArrays, LayerArrays]:
        """The two layers at the points (the same object for identical layers:
        :func:`corrugate.analysis.evaluate.identical_layers` then computes one)."""
        kind = self.problem.profile_kind
        l1 = _layers(self.c1, self.x.layer(0), kind)
        l2 = (
            l1 if same_layers(self.c1, self.c2, self.x) else _layers(self.c2, self.x.layer(1), kind)
        )
        return l1, l2

    @property
    def _eta_arg(self) -> Any:
        # one direction: a scalar eta keeps evaluate on its fast path (no per-eta masks)
        return self.etas[0] if len(self.etas) == 1 else self.etas

    @cached_property
    def ev(self) -> LazyEvaluation:
        """``evaluate`` of the points under the default support (free sides), each stiffness
        computed when a quantity reads it (:class:`~corrugate.analysis.evaluate.LazyEvaluation`:
        the same values bit for bit)."""
        p = self.problem
        return LazyEvaluation(*self.layers, p.layout, p.model, self._eta_arg, joint=p.joint)

    def under(self, support: str) -> LazyEvaluation:
        """``evaluate`` of the points under ``support`` (one that reads the layout's coupon),
        lazily as :attr:`ev`."""
        p = self.problem
        return self.shared(
            "evaluate:" + support,
            lambda: LazyEvaluation(
                *self.layers, p.layout, p.model, self._eta_arg, support=support, joint=p.joint
            ),
        )

    @cached_property
    def Lx(self) -> FloatArray:
        """Folded extent along x (mm)."""
        return np.asarray(self.ev.Lx[:, 0])

    @cached_property
    def Ly(self) -> FloatArray:
        """Folded extent along y (mm)."""
        return np.asarray(self.ev.Ly[:, 0])

    @cached_property
    def facets(self) -> tuple[FloatArray, FloatArray]:
        """Each layer's longest facet (mm)."""
        f = self.tables.facet_factor
        return f(self.x.layer(0).n, "x") * self.Ly, f(self.x.layer(1).n, "y") * self.Lx

    def span(self, eta: float) -> FloatArray:
        """The panel's length (mm) along ``eta`` (deg)."""
        return np.asarray(self.problem.layout.span(self.Lx, self.Ly, np.asarray(eta)))

    @cached_property
    def walls(self) -> Callable[[FloatArray], tuple[Any, Any, Any]] | None:
        """The band's walls of a bonded joint over a length (mm)
        (:func:`corrugate.mechanics.load_cases.band_walls`), None without a band."""
        if self.problem.joint == "none":
            return None
        td = np.asarray(self.ev.thickness[:, 0])
        l1 = self.layers[0]
        nu = self.c1.material.nu

        def walls(length: FloatArray) -> tuple[Any, Any, Any]:
            return band_walls(column(np.asarray(l1.E)), nu, column(np.asarray(l1.t)), td, length)

        return walls


@dataclass(frozen=True, slots=True)
class Corner:
    """One layer at one corner of the boxes, computed as :func:`corrugate.analysis.evaluate.evaluate`
    does (sin and cos of alpha/2 once): W (mm), cos(alpha/2), pitch (W sin(alpha/2) for the
    zig-zag), chord extent (n + 1) p and the developed width of a repeat unit (W for the
    zig-zag) (mm)."""

    W: FloatArray
    c: FloatArray
    p: FloatArray
    extent: FloatArray
    developed: FloatArray


def layer_corner(b: LayerPoints, kind: ProfileKind = ZIGZAG) -> Corner:
    """The layer ``b`` at a corner of the boxes (:class:`Corner`), by its profile ``kind``
    (:class:`corrugate.geometry.profile.ProfileKind`; the zig-zag,
    :class:`corrugate.geometry.profile.ZigZag`, by default)."""
    W = np.asarray(b.W, dtype=np.float64)
    zz = kind.of(W, np.asarray(b.alpha, dtype=np.float64))
    return Corner(W, zz.c, zz.pitch, zz.extent(np.asarray(b.n, dtype=np.float64)), zz.developed)


class OverBoxes(_Shared):
    """The boxes [lo, hi] of ``problem`` on sheets (c1, c2) and what their bounds share
    (module docstring); ``lo is hi``: the values at points, each computed once."""

    def __init__(
        self,
        problem: Problem,
        c1: Candidate,
        c2: Candidate,
        lo: DesignPoints,
        hi: DesignPoints,
        tables: Tables,
    ) -> None:
        super().__init__()
        self.problem, self.c1, self.c2, self.lo, self.hi, self.tables = (
            problem,
            c1,
            c2,
            lo,
            hi,
            tables,
        )
        self.point = lo is hi
        self.same = same_layers(c1, c2, lo) and (self.point or same_layers(c1, c2, hi))
        self._bounds: dict[Quantity, Pair] = {}
        self._coupon: Coupon | None = None

    def bounds(self, q: Quantity) -> Pair:
        """The bounds of ``q`` over the boxes (its evaluator's, computed once)."""
        b = self._bounds.get(q)
        if b is None:
            b = self._bounds[q] = evaluator_of(q).bounds(self, q)
        return b

    @cached_property
    def corners(self) -> tuple[Corner, Corner, Corner, Corner]:
        """Layer 1 at the low and the high corner, then layer 2 (the same objects for points
        or the same layer)."""
        lo, hi, point, same = self.lo, self.hi, self.point, self.same
        k = self.problem.profile_kind
        g1_lo = layer_corner(lo.layer(0), k)
        g1_hi = g1_lo if point else layer_corner(hi.layer(0), k)
        g2_lo = g1_lo if same else layer_corner(lo.layer(1), k)
        g2_hi = g1_hi if same else (g2_lo if point else layer_corner(hi.layer(1), k))
        return g1_lo, g1_hi, g2_lo, g2_hi

    @property
    def Lx(self) -> Pair:
        """Bounds of Lx (mm): layer 1's extent at the corners."""
        return self.corners[0].extent, self.corners[1].extent

    @property
    def Ly(self) -> Pair:
        """Bounds of Ly (mm): layer 2's extent at the corners."""
        return self.corners[2].extent, self.corners[3].extent

    @cached_property
    def thickness(self) -> Pair:
        """Bounds of t_d = W1 c1 + W2 c2 (mm): it grows with W and falls with alpha, so W low
        with alpha high, and back (another profile's heights at those mixed corners:
        :class:`~corrugate.geometry.profile.ProfileKind` asks the same of them)."""
        g1_lo, g1_hi, g2_lo, g2_hi = self.corners
        if not self.problem.profile_kind.is_default:
            return self._mixed_heights()
        if self.same:
            td_lo = 2.0 * (g1_lo.W * g1_hi.c)
            td_hi = td_lo if self.point else 2.0 * (g1_hi.W * g1_lo.c)
        else:
            td_lo = g1_lo.W * g1_hi.c + g2_lo.W * g2_hi.c
            td_hi = td_lo if self.point else g1_hi.W * g1_lo.c + g2_hi.W * g2_lo.c
        return td_lo, td_hi

    def _mixed_heights(self) -> Pair:
        """Bounds of t_d (mm) from the heights of the profile at (W low, alpha high) and
        (W high, alpha low) of each layer."""
        kind, lo, hi = self.problem.profile_kind, self.lo, self.hi

        def height(W: Any, alpha: Any) -> FloatArray:
            return np.asarray(
                kind.of(np.asarray(W, np.float64), np.asarray(alpha, np.float64)).height
            )

        sides = []
        for a, b in ((lo, hi), (hi, lo)):
            h1 = height(a.layer(0).W, b.layer(0).alpha)
            h2 = h1 if self.same else height(a.layer(1).W, b.layer(1).alpha)
            sides.append(h1 + h2)
        return sides[0], sides[1]

    @cached_property
    def facets(self) -> tuple[Pair, Pair]:
        """Bounds of each layer's longest facet (mm): the facet factor's range over n times
        the other extent's."""
        (Lx_lo, Lx_hi), (Ly_lo, Ly_hi) = self.Lx, self.Ly
        f1 = self.tables.Fx.bounds(self.lo.layer(0).n, self.hi.layer(0).n)
        f2 = self.tables.Fy.bounds(self.lo.layer(1).n, self.hi.layer(1).n)
        return (f1[0] * Ly_lo, f1[1] * Ly_hi), (f2[0] * Lx_lo, f2[1] * Lx_hi)

    @cached_property
    def springs(self) -> tuple[Springs, Springs]:
        """Each layer's springs over the boxes (:func:`~.interval_springs.layer_springs`)."""
        p, lo, hi, tables = self.problem, self.lo, self.hi, self.tables
        a, b = lo.layer(0), hi.layer(0)
        sp1 = layer_springs(
            p, self.c1, (a.n, b.n), (a.W, b.W), (a.alpha, b.alpha), self.Ly, tables.Qx, tables, "x"
        )
        if (
            p.identical
            and isinstance(p.layout, Rectangle | Circle)
            and not p.layout.holes  # holes need not be symmetric under x <-> y
        ):
            # outline symmetric under x <-> y: identical layers have identical springs
            return sp1, sp1
        # a polygon's facet lengths differ across x and across y (regression: issue found by
        # brute force on a pentagon; layer 2 must use Q_y even when the layers are identical)
        a, b = lo.layer(1), hi.layer(1)
        sp2 = layer_springs(
            p, self.c2, (a.n, b.n), (a.W, b.W), (a.alpha, b.alpha), self.Lx, tables.Qy, tables, "y"
        )
        return sp1, sp2

    def span(self, eta: float) -> Interval:
        """Bounds of the panel's length (mm) along ``eta`` (deg)."""
        return span_bounds(self.problem, self.Lx, self.Ly, eta)

    def coupon(self, entry: Behaviour, eta: float) -> Coupon | None:
        """How the layout is read off the crease directions
        (:class:`corrugate.mechanics.offaxis.Coupon`): made at the first stiffness asked for
        off them under a behaviour that reads it (None for a square, and before)."""
        if self._coupon is None and entry.uses_coupon and crease_layer(eta) is None:
            (Lx_lo, Lx_hi), (Ly_lo, Ly_hi) = self.Lx, self.Ly
            sp1, sp2 = self.springs
            self._coupon = coupon_of(
                self.problem.layout,
                Interval(Lx_lo, Lx_hi),
                Interval(Ly_lo, Ly_hi),
                lambda: (sp1.pq, sp2.pq),
            )
        return self._coupon

    def walls(self, eta: float) -> tuple[tuple[Any, Any, Any] | None, Interval | None]:
        """The band's walls of a bonded joint along the creases at ``eta`` (deg) over the
        boxes, and the depth t_d they stand (None, None: no band there)."""
        p = self.problem
        if p.joint == "none" or crease_layer(eta) is None:
            return None, None
        depth = Interval(*self.thickness)
        m = self.c1.material
        return (
            band_walls(number(m.E), float(m.nu), number(self.c1.t), depth, self.span(eta)),
            depth,
        )
