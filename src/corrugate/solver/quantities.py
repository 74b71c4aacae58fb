"""The quantities constraints bound: exact values at points, rigorous bounds over boxes.

Points and boxes are :class:`~.points.DesignPoints` (per layer: creases n, facet width W in mm,
fold angle alpha in deg); identical layers are one stored layer.

:func:`point_values` calls :func:`corrugate.analysis.evaluate.evaluate` (the one implementation of the
model), so a design the solver accepts is exactly the design ``analyze`` reports.

:func:`box_bounds` returns, for each quantity, a lower and an upper bound valid for every design in
a box ``lo <= x <= hi`` (elementwise over many boxes). The arguments, per quantity:

* extents, thickness, blank, mass: monotone. With s = sin(alpha/2), c = cos(alpha/2) and
  0 < alpha < 180 deg, Lx = (n1 + 1) W1 s1 increases with n1, W1 and alpha1; t_d = W1 c1 + W2 c2
  increases with W and decreases with alpha; the blank (n + 1) W increases with n and W; the mass
  rho t W (n + 1) S a_f of each layer (S the other layer's extent, a_f the outline's area fraction;
  :mod:`corrugate.mechanics.mass`) increases with every variable, and the connector band's mass increases
  with Lx, Ly and t_d (:mod:`corrugate.geometry.connectors`). So their bounds are their values at
  the box corners (the band's at the bounds of Lx, Ly and t_d), computed with the same building
  blocks as ``evaluate``.
* facet length: max_j L_j = F(n) S with F(n) = (n + 1) max_j dA_j (:mod:`corrugate.geometry.layouts`),
  bounded by the range of F over the box's n and the range of S.
* holes (:mod:`corrugate.geometry.holes`): each layer's mass drops by rho t A_h / s, largest at the box's
  lowest alpha, so the corner bounds stay bounds; a hole only removes terms from the parallel
  sums and lengthens the series ones, so the hole-free stiffness bounds remain upper bounds, and
  the lower bounds come from :func:`_hole_pq_bounds` (touched facets and blocked lengths over
  the box).
* stiffness: the moduli variant's own function evaluated in :class:`~.interval.Interval`
  arithmetic over the box (W, alpha), then the spring sums of docs/theory.md 3.2 and the assembly
  by the ``bounds`` of the quantity's support condition (or load case) in the registry of
  behaviours (:mod:`corrugate.mechanics.behaviours`: the rule of 3.3 for a frame, the free-panel
  lower bounds of :mod:`corrugate.mechanics.offaxis` for free sides, each variable once per term
  so the intervals are tight)
  in interval arithmetic, with q = sum_j 1/L_j = Q(n) / S (Q from
  :func:`corrugate.geometry.layouts.inverse_length_sum`). For identical layers p q = Q(n) / (n + 1) exactly,
  which removes the dependency on p. EI = D x span: for square, rectangle and circle the span grows
  with Lx and Ly (its value at the upper corner bounds it); for a polygon the span moves by at most
  2 (|dLx sin eta| + |dLy cos eta|) when the box is shrunk to a corner (each vertex moves by at most
  its share of dLx, dLy), which bounds it from both sides.

* buckling load: :func:`corrugate.mechanics.buckling.buckling_scale` in interval arithmetic (each variable
  appears once, and K_C / K_S from the interval springs).

Interval bounds converge to the exact value as the box shrinks, which is what makes branch and
bound terminate.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from corrugate.analysis.evaluate import LayerArrays, coupon_of, evaluate
from corrugate.geometry.layer import crease_layer
from corrugate.geometry.layouts import (
    Axis,
    Circle,
    Rectangle,
    facet_lengths,
    inverse_length_sum,
    length_sum,
)
from corrugate.mechanics.behaviours import DEFAULT_SUPPORT, get_load_case, get_support, supports
from corrugate.mechanics.buckling import K_SIMPLE_FREE, buckling_scale
from corrugate.mechanics.load_cases import (
    apparent,
    band_walls,
    load_capacity,
    load_stiffness,
    shear_and_depth,
    stress_per_load,
    wall_capacity,
    walls_stiffness,
)
from corrugate.mechanics.mass import connector_mass, layer_mass
from corrugate.mechanics.moduli import get_model
from corrugate.mechanics.offaxis import (
    Coupon,
    _cs,
    finite_panel_deficit,
    shear_spring,
    shear_springs,
)
from corrugate.solver.interval import Interval
from corrugate.solver.making import MAKING, making_bounds, making_values
from corrugate.solver.points import DesignPoints, LayerPoints
from corrugate.solver.problem import Candidate, Problem
from corrugate.solver.quantity import FACET, FLAT, LX, LY, MASS, THICKNESS, Quantity

__all__ = ["RangeTable", "box_bounds", "layer_corner", "point_values"]

FloatArray = NDArray[np.float64]
Bounds = dict[Quantity, tuple[FloatArray, FloatArray]]


class RangeTable:
    """Minimum and maximum of a table f(n), n = n0..n1, over index ranges (sparse table)."""

    def __init__(self, n0: int, values: FloatArray) -> None:
        self.n0 = n0
        v = np.asarray(values, dtype=np.float64)
        d = np.diff(v)
        #: +1 if f is non-decreasing in n, -1 if non-increasing, 0 otherwise (then the table)
        self.monotone = 1 if np.all(d >= 0) else (-1 if np.all(d <= 0) else 0)
        self._values = v
        self._min: list[FloatArray] = []
        self._max: list[FloatArray] = []
        if not self.monotone:  # a monotone f needs no table (its extremes are at the ends)
            self._min.append(v)
            self._max.append(v)
            k = 1
            while 2 * k <= len(v):
                a, b = self._min[-1], self._max[-1]
                self._min.append(np.minimum(a[:-k], a[k:]))
                self._max.append(np.maximum(b[:-k], b[k:]))
                k *= 2

    def bounds(self, lo: FloatArray, hi: FloatArray) -> tuple[FloatArray, FloatArray]:
        """min and max of f over n in [lo, hi] (arrays of integers)."""
        i = np.asarray(lo, dtype=np.int64) - self.n0
        j = np.asarray(hi, dtype=np.int64) - self.n0
        if self.monotone:  # the extremes sit at the ends of the range
            a, b = self._values[i], self._values[j]
            return (a, b) if self.monotone > 0 else (b, a)
        length = j - i + 1
        level = np.floor(np.log2(np.maximum(length, 1))).astype(np.int64)
        mins = np.empty(i.shape)
        maxs = np.empty(i.shape)
        # the levels present (not np.unique: it imports numpy.ma, 0.1 s, on its first call)
        for lv in np.flatnonzero(np.bincount(level)):
            sel = level == lv
            k = 1 << int(lv)
            a, b = i[sel], j[sel] - k + 1
            mins[sel] = np.minimum(self._min[lv][a], self._min[lv][b])
            maxs[sel] = np.maximum(self._max[lv][a], self._max[lv][b])
        return mins, maxs


@dataclass(frozen=True)
class Tables:
    """Per-n tables of the layout for a problem: Q(n) = (n + 1) G(n) and F(n), per axis."""

    problem: Problem

    def _table(self, what: str, axis: str) -> RangeTable:
        p = self.problem
        ns = np.arange(p.n_lo, p.n_hi + 1)
        if what == "Q":
            vals = inverse_length_sum(p.layout, ns, 1.0, axis)  # type: ignore[arg-type]
        elif isinstance(p.layout, Rectangle):
            vals = np.ones(len(ns))
        else:
            pick = np.max if what == "F" else np.min
            vals = np.array(
                [
                    pick(facet_lengths(p.layout, int(k), 1.0, axis))  # type: ignore[arg-type]
                    for k in ns
                ]
            )
        return RangeTable(p.n_lo, np.asarray(vals, dtype=np.float64))

    @cached_property
    def Qx(self) -> RangeTable:
        return self._table("Q", "x")

    @cached_property
    def Qy(self) -> RangeTable:
        return self._table("Q", "y")

    @cached_property
    def Fx(self) -> RangeTable:
        return self._table("F", "x")

    @cached_property
    def Fy(self) -> RangeTable:
        return self._table("F", "y")

    @cached_property
    def Fmin_x(self) -> RangeTable:
        """min_j L_j / S per n (layer 1), for the bounds with holes."""
        return self._table("Fmin", "x")

    @cached_property
    def Fmin_y(self) -> RangeTable:
        return self._table("Fmin", "y")

    def facet_factor(self, n: FloatArray, axis: str) -> FloatArray:
        """F(n) = max_j L_j / S at integer n (array)."""
        table = self.Fx if axis == "x" else self.Fy
        return table.bounds(n, n)[0]


def _layers(cand: Candidate, x: LayerPoints) -> LayerArrays:
    """The layer ``x`` at the points, as columns; ``x`` may override E (MPa) and t (mm) per
    point (used by the tolerance analysis)."""
    m = cand.material
    E = x.E[:, None] if x.E is not None else m.E
    t = x.t[:, None] if x.t is not None else cand.t
    n = np.asarray(x.n)[:, None]
    return LayerArrays(
        E,
        m.nu,
        t,
        np.asarray(x.W)[:, None],
        n.astype(np.int64),
        np.asarray(x.alpha)[:, None],
        m.density,
    )


def point_values(
    problem: Problem, c1: Candidate, c2: Candidate, x: DesignPoints, tables: Tables
) -> dict[Quantity, FloatArray]:
    """Exact values of every quantity at the points ``x`` (1-D arrays), via ``evaluate``: the
    sizes, the mass, EI, D and K at every eta of the problem under the default support (free
    sides) and under each other support condition a quantity asks for (its entry's ``model`` in
    :mod:`corrugate.mechanics.behaviours`), the load cases asked for, and the buckling loads when
    one is bounded."""
    etas = np.asarray(problem.etas or (0.0,), dtype=np.float64)
    keys = problem.quantities
    asked = {q.support for q in keys}
    others = [b for b in supports() if b.name != DEFAULT_SUPPORT and b.name in asked]
    tests = [q for q in keys if q.test is not None]
    x1, x2 = x.layer(0), x.layer(1)
    l1 = _layers(c1, x1)
    # identical layers: evaluate computes one layer (analysis.identical_layers)
    l2 = l1 if _same_layers(c1, c2, x) else _layers(c2, x2)
    # one direction: a scalar eta keeps evaluate on its fast path (no per-eta masks)
    eta_arg = etas[0] if len(etas) == 1 else etas
    ev = evaluate(l1, l2, problem.layout, problem.model, eta_arg, joint=problem.joint)
    Lx, Ly = ev.Lx[:, 0], ev.Ly[:, 0]
    facet1 = tables.facet_factor(x1.n, "x") * Ly  # each layer's longest facet (mm)
    facet2 = tables.facet_factor(x2.n, "y") * Lx
    out: dict[Quantity, FloatArray] = {
        LX: Lx,
        LY: Ly,
        THICKNESS: ev.thickness[:, 0],
        MASS: ev.mass[:, 0],
        FLAT: np.maximum((x1.n + 1) * x1.W, (x2.n + 1) * x2.W),
        FACET: np.maximum(facet1, facet2),
    }
    if MAKING.intersection(keys):
        out.update(
            making_values(problem.layout, c1, c2, x, facet1, facet2, Lx, Ly, ev.thickness[:, 0])
        )
    # a support that reads the layout's coupon gets evaluate's own treatment of it
    coupled = {
        b.name: evaluate(
            l1, l2, problem.layout, problem.model, eta_arg, support=b.name, joint=problem.joint
        )
        for b in others
        if b.uses_coupon
    }
    walls = None
    if problem.joint != "none":
        td = np.asarray(ev.thickness[:, 0])

        def walls(length: FloatArray) -> tuple[Any, Any, Any]:
            return band_walls(
                _column(np.asarray(l1.E)), c1.material.nu, _column(np.asarray(l1.t)), td, length
            )

    for k, eta in enumerate(etas):
        e = float(eta)
        out[Quantity("EI", e, DEFAULT_SUPPORT)] = np.asarray(ev.EI[:, k])
        out[Quantity("D", e, DEFAULT_SUPPORT)] = np.asarray(ev.D[:, k])
        out[Quantity("K", e, DEFAULT_SUPPORT)] = np.asarray(ev.K[:, k])
        for b in others:
            if b.name in coupled:
                evb = coupled[b.name]
                out[Quantity("EI", e, b.name)] = np.asarray(evb.EI[:, k])
                out[Quantity("D", e, b.name)] = np.asarray(evb.D[:, k])
                out[Quantity("K", e, b.name)] = np.asarray(evb.K[:, k])
                continue
            span = np.asarray(problem.layout.span(Lx, Ly, np.asarray(e)))
            D_b = np.asarray(b.model("D", ev.springs, e, None))[:, 0]
            K_b = np.asarray(b.model("K", ev.springs, e, None))[:, 0]
            if walls is not None and crease_layer(e) is not None:
                w = walls(span)
                D_b, K_b = D_b + w[0], K_b + w[2]
            out[Quantity("D", e, b.name)] = D_b
            out[Quantity("EI", e, b.name)] = D_b * span
            out[Quantity("K", e, b.name)] = K_b
        span = np.asarray(problem.layout.span(Lx, Ly, np.asarray(e)))
        out[Quantity("length", e)] = span
        band = None if walls is None or crease_layer(e) is None else walls(span)
        for q in tests:
            if q.eta != e:
                continue
            form = get_load_case(q.test).form  # type: ignore[arg-type]
            assert form is not None
            base = out[Quantity("K" if form.kind == "inplane" else "D", e, q.support)]
            layers = base if band is None else base - band[2 if form.kind == "inplane" else 0]
            if q.kind == "Pmax":
                along = 0 if crease_layer(e) == 0 else 1
                extents = (Lx, Ly) if along == 0 else (Ly, Lx)
                E = (np.asarray(l1.E, dtype=np.float64), np.asarray(l2.E, dtype=np.float64))
                t = (np.asarray(l1.t, dtype=np.float64), np.asarray(l2.t, dtype=np.float64))
                lay_E = (_column(E[along]), _column(E[1 - along]))
                lay_t = (_column(t[along]), _column(t[1 - along]))
                sp = ev.springs if along == 0 else ev.springs[::-1]
                per = stress_per_load(
                    form,
                    (_columns(sp[0]), _columns(sp[1])),
                    0,
                    layers,  # the layers' own D or K: their curvature or strain from above
                    lay_E,
                    lay_t,
                    extents[1],
                    extents[0],
                    q.span,
                )
                cap = load_capacity(per, _allowables(c1, c2, along), problem.safety_factor)
                if band is not None:  # the walls, at the whole panel's curvature or strain
                    cap = np.minimum(
                        cap,
                        wall_capacity(
                            form,
                            base,
                            _column(np.asarray(l1.E)),
                            _column(np.asarray(l1.t)),
                            ev.thickness[:, 0],
                            span,
                            q.span,
                            _allowables(c1, c1, 0)[0],
                            problem.safety_factor,
                        ),
                    )
                out[q] = np.asarray(cap)
                continue
            cos2, sin2 = _cs(e)
            V, h = shear_and_depth(ev.springs, cos2, sin2)
            k = load_stiffness(
                form, layers, np.asarray(V)[:, 0], np.asarray(h)[:, 0], span, q.span, e
            )
            if band is not None:  # the walls beside the layers (parallel beams)
                k = k + walls_stiffness(form, band, span, q.span)
            out[q] = np.asarray(apparent(form, q.kind, k, span))
    if any(q.kind == "Pb" for q in keys):
        s1, s2 = ev.springs
        for e_pb, (lay, sa, sc) in {0.0: (l1, s1, s2), 90.0: (l2, s2, s1)}.items():
            out[Quantity("Pb", e_pb)] = np.asarray(
                K_SIMPLE_FREE * buckling_scale(lay.E, lay.nu, lay.t, lay.W, lay.n, sa.K_S, sc.K_C)
            )[:, 0]
    return out


def _column(v: FloatArray) -> Any:
    """A (k, 1) column of per-point values as a 1-D array (a scalar as a float)."""
    a = np.asarray(v, dtype=np.float64)
    return float(a) if a.ndim == 0 else a.reshape(-1)


class _Col:
    """A layer's springs (arrays of shape (k, 1) or scalars) seen as 1-D arrays."""

    def __init__(self, springs: Any) -> None:
        self._s = springs

    def __getattr__(self, name: str) -> Any:
        return _column(getattr(self._s, name))


def _columns(springs: Any) -> Any:
    return _Col(springs)


def _allowables(c1: Candidate, c2: Candidate, along: int) -> tuple[float, float]:
    """The yield strengths (MPa) of (the layer along eta, the other) (Problem.from_spec refuses
    a strength bound on a material without one)."""
    y1, y2 = c1.material.yield_strength, c2.material.yield_strength
    assert y1 is not None and y2 is not None
    return (y1, y2) if along == 0 else (y2, y1)


def _same_layers(c1: Candidate, c2: Candidate, x: DesignPoints) -> bool:
    """Whether layer 2 is layer 1 (identical layers of one sheet, no per-point overrides)."""
    return c1 == c2 and x.identical and not x.layer(0).overrides


@dataclass(frozen=True, slots=True)
class _Corner:
    """One layer at one corner of the boxes, computed as :func:`corrugate.analysis.evaluate.evaluate`
    does (sin and cos of alpha/2 once): W (mm), cos(alpha/2), pitch W sin(alpha/2) and chord
    extent (n + 1) p (mm)."""

    W: FloatArray
    c: FloatArray
    p: FloatArray
    extent: FloatArray


def layer_corner(b: LayerPoints) -> _Corner:
    """The layer ``b`` at a corner of the boxes (:class:`_Corner`)."""
    half = np.asarray(b.alpha, dtype=np.float64) * (np.pi / 360.0)
    W = np.asarray(b.W, dtype=np.float64)
    p = W * np.sin(half)
    return _Corner(W, np.cos(half), p, (np.asarray(b.n, dtype=np.float64) + 1.0) * p)


def box_bounds(
    problem: Problem,
    c1: Candidate,
    c2: Candidate,
    lo: DesignPoints,
    hi: DesignPoints,
    tables: Tables,
    quantities: set[Quantity],
) -> Bounds:
    """Lower and upper bounds of the requested ``quantities`` over boxes [lo, hi] (``lo is hi``:
    the values at points, each computed once)."""
    lay = problem.layout
    point = lo is hi
    same = _same_layers(c1, c2, lo) and (point or _same_layers(c1, c2, hi))
    # each layer at the lower and the upper corner (the same objects for points or the same layer)
    g1_lo = layer_corner(lo.layer(0))
    g1_hi = g1_lo if point else layer_corner(hi.layer(0))
    g2_lo = g1_lo if same else layer_corner(lo.layer(1))
    g2_hi = g1_hi if same else (g2_lo if point else layer_corner(hi.layer(1)))
    Lx_lo, Lx_hi = g1_lo.extent, g1_hi.extent
    Ly_lo, Ly_hi = g2_lo.extent, g2_hi.extent
    out: Bounds = {LX: (Lx_lo, Lx_hi), LY: (Ly_lo, Ly_hi)}
    making = bool(MAKING.intersection(quantities))
    if THICKNESS in quantities or MASS in quantities or problem.joint != "none" or making:
        # (the band's walls of a bonded joint stand t_d high: their stiffness needs it too)
        # t_d = W1 c1 + W2 c2 grows with W and falls with alpha: W low with alpha high, and back
        if same:
            td_lo = 2.0 * (g1_lo.W * g1_hi.c)
            td_hi = td_lo if point else 2.0 * (g1_hi.W * g1_lo.c)
        else:
            td_lo = g1_lo.W * g1_hi.c + g2_lo.W * g2_hi.c
            td_hi = td_lo if point else g1_hi.W * g1_lo.c + g2_hi.W * g2_lo.c
        out[THICKNESS] = (td_lo, td_hi)
    if FLAT in quantities:
        lo1, lo2, hi1, hi2 = lo.layer(0), lo.layer(1), hi.layer(0), hi.layer(1)
        flat_lo = np.maximum((lo1.n + 1) * lo1.W, (lo2.n + 1) * lo2.W)
        flat_hi = flat_lo if point else np.maximum((hi1.n + 1) * hi1.W, (hi2.n + 1) * hi2.W)
        out[FLAT] = (flat_lo, flat_hi)
    if FACET in quantities or making:
        # each layer's longest facet: the facet factor's range over n times the other extent
        f1 = tables.Fx.bounds(lo.layer(0).n, hi.layer(0).n)
        f2 = tables.Fy.bounds(lo.layer(1).n, hi.layer(1).n)
        facets = ((f1[0] * Ly_lo, f1[1] * Ly_hi), (f2[0] * Lx_lo, f2[1] * Lx_hi))
        facet_lo = np.maximum(facets[0][0], facets[1][0])
        facet_hi = facet_lo if point else np.maximum(facets[0][1], facets[1][1])
        out[FACET] = (facet_lo, facet_hi)
    if making:
        out.update(
            making_bounds(
                lay, c1, c2, lo, hi, facets, ((Lx_lo, Lx_hi), (Ly_lo, Ly_hi)), out[THICKNESS]
            )
        )
    if MASS in quantities:

        def mass(b: DesignPoints, g1: _Corner, g2: _Corner, td: FloatArray) -> FloatArray:
            # holes remove rho t A_h / s(alpha) per layer, most at the box's lowest alpha: the
            # corner's own pitch gives the bound on the same side as its blank.
            # The band (cut from layer 1's sheet) grows with Lx, Ly and t_d (corrugate.fabrication.
            # connectors), so its bounds are its values at those quantities' own bounds.
            band = connector_mass(c1.material.density, c1.t, lay, g1.extent, g2.extent, td)
            m1 = layer_mass(
                c1.material.density, c1.t, g1.W, length_sum(lay, b.layer(0).n, g2.extent), lay, g1.p
            )
            if same:  # the same layer twice (x + x = 2 x exactly, as evaluate does)
                return np.asarray(2.0 * m1 + band)
            m2 = layer_mass(
                c2.material.density, c2.t, g2.W, length_sum(lay, b.layer(1).n, g1.extent), lay, g2.p
            )
            return np.asarray(m1 + m2 + band)

        mass_lo = mass(lo, g1_lo, g2_lo, td_lo)
        out[MASS] = (mass_lo, mass_lo if point else mass(hi, g1_hi, g2_hi, td_hi))
    stiff = sorted((q for q in quantities if q.directional), key=_order)
    if stiff:
        out.update(_stiffness_bounds(problem, c1, c2, lo, hi, tables, out, stiff))
    return out


def _order(q: Quantity) -> tuple[str, float, str, str]:
    """A fixed order of the directional quantities (the bounds do not depend on it)."""
    return (q.kind, q.eta or 0.0, q.support or "", q.test or "")


@dataclass(frozen=True)
class _Springs:
    """A layer's springs over boxes, as intervals (the fields of
    :class:`~corrugate.mechanics.springs.LayerSprings`)."""

    K_C: Interval
    K_S: Interval
    D_C: Interval
    D_S: Interval
    K_T: Interval
    D_T: Interval
    pq: Interval  # p sum_j 1/L_j without holes (corrugate.mechanics.offaxis.Coupon)
    V_S: Interval  # transverse shear spring (N/mm; corrugate.mechanics.load_cases)
    h: Interval  # depth W cos(alpha/2) (mm)
    deficit: Interval  # finite-panel deficit (corrugate.mechanics.offaxis.finite_panel_deficit)


def _layer_springs(
    problem: Problem,
    cand: Candidate,
    n: tuple[FloatArray, FloatArray],
    W: tuple[FloatArray, FloatArray],
    a: tuple[FloatArray, FloatArray],
    S: tuple[FloatArray, FloatArray],
    Q: RangeTable,
    tables: Tables,
    axis: str,
) -> _Springs:
    """K_C, K_S, D_C, D_S (docs/theory.md 3.2) and the shear and twisting springs K_T, D_T
    (:func:`corrugate.mechanics.offaxis.shear_springs`, on the parallel sum) of a layer over a box, in
    interval arithmetic."""
    m = cand.material
    t = cand.t
    Wi = Interval(W[0], W[1])
    alpha = Interval(np.radians(a[0]), np.radians(a[1]))
    # the model functions are plain arithmetic, so they accept intervals (duck typing); sin and
    # cos of alpha/2 once, as evaluate does
    from_sc: Any = get_model(problem.model).from_sc
    half = alpha * 0.5
    sh, ch = half.sin(), half.cos()
    mod = from_sc(float(m.E), float(m.nu), float(t), Wi, sh, ch)
    q_lo, q_hi = Q.bounds(n[0], n[1])  # Q(n) = S sum_j 1/L_j
    if problem.identical:  # p q = Q(n) / (n + 1) exactly (S = (n + 1) p)
        pq = Interval(q_lo / (n[1] + 1), q_hi / (n[0] + 1))
    else:
        pq = Wi * sh * Interval(q_lo, q_hi) / Interval(S[0], S[1])
    Ecx, Ecy, Ebx, Eby = (Interval.of(v) for v in (mod.Ecx, mod.Ecy, mod.Ebx, mod.Eby))
    t3 = t**3
    pq_par, pq_ser = pq, pq
    if problem.layout.holes:
        p_lo = np.asarray(W[0] * np.sin(np.radians(a[0]) / 2))
        p_hi = np.asarray(W[1] * np.sin(np.radians(a[1]) / 2))
        Fmin = tables.Fmin_x if axis == "x" else tables.Fmin_y  # built only with holes
        pq_par, pq_ser = _hole_pq_bounds(problem, n, (p_lo, p_hi), S, (q_lo, q_hi), Fmin, pq, axis)
    K_T, D_T = shear_springs(float(m.E), float(m.nu), float(t), sh, pq_par)
    # c^2 / s falls as alpha grows: one interval each (c and s are monotone on the box)
    V_S = shear_spring(float(m.E), float(m.nu), float(t), sh, ch, pq_par)
    d_lo, d_hi = finite_panel_deficit(n[1]), finite_panel_deficit(n[0])  # falls with n
    return _Springs(
        Ecx * t / pq_ser,
        Ecy * t * pq_par,
        Ebx * (t3 / 12.0) / pq_ser,
        Eby * (t3 / 12.0) * pq_par,
        Interval.of(K_T),
        Interval.of(D_T),
        pq,
        Interval.of(V_S),
        Wi * ch,
        Interval(d_lo, d_hi),
    )


#: Relative widening of the hole bounds against floating-point rounding.
_ROUND = 1e-12


def _hole_pq_bounds(
    problem: Problem,
    n: tuple[FloatArray, FloatArray],
    p: tuple[FloatArray, FloatArray],
    S: tuple[FloatArray, FloatArray],
    Q: tuple[FloatArray, FloatArray],
    Fmin: RangeTable,
    pq: Interval,
    axis: str,
) -> tuple[Interval, Interval]:
    """Bounds of p x (parallel sum) and p x (series sum) of a layer with the layout's holes
    (:mod:`corrugate.geometry.holes`) over boxes; ``pq`` bounds p x sum_j 1/L_j without holes.

    A hole only removes terms from the parallel sum and lengthens series terms, so ``pq.hi``
    bounds the parallel sum from above and ``pq.lo`` the series sum from below for every box.
    Loose, for any box: at most sum_h (w_h / p_lo + 2) facets are touched (w_h the hole's width
    across the creases), each of length >= L_min = S_lo min_j(L_j / S) and blocked by at most
    B = sum_h (the holes' extents along the creases). Tight, for boxes of one n, with
    L_j in S (n + 1) dA_j: every facet that a hole touches for some p of the box (it meets the
    union of strip j over p_lo..p_hi) is left out of the parallel sum's lower bound and blocked by
    at most the holes' extent inside that union; every facet a hole touches for all p (it meets
    the intersection of strip j over the box) is left out of the upper bound and blocked by at
    least the extent inside the intersection. Both sides converge to the exact value as
    p_hi - p_lo -> 0 for one n (except where a strip edge meets a hole's edge).
    """
    lay = problem.layout
    holes = lay.holes
    ax: Axis = "x" if axis == "x" else "y"
    other: Axis = "y" if axis == "x" else "x"
    p_lo, p_hi = p
    shape = np.shape(pq.lo)
    S_lo, S_hi = np.asarray(S[0], dtype=np.float64), np.asarray(S[1], dtype=np.float64)
    n_lo, n_hi = np.asarray(n[0]), np.asarray(n[1])
    # loose
    count = sum((h.extent(ax)[1] - h.extent(ax)[0]) / p_lo + 2.0 for h in holes)
    B = float(sum(h.extent(other)[1] - h.extent(other)[0] for h in holes))
    L_min = S_lo * Fmin.bounds(n_lo, n_hi)[0]
    with np.errstate(divide="ignore", invalid="ignore"):
        f = np.where(L_min > B, B / (L_min * (L_min - B)), np.inf)
        par_lo = np.array(np.broadcast_to(pq.lo - p_hi * count / L_min, shape), dtype=np.float64)
        ser_hi = np.array(np.broadcast_to(pq.hi + p_hi * count * f, shape), dtype=np.float64)
    par_hi = np.array(pq.hi, dtype=np.float64)
    ser_lo = np.array(pq.lo, dtype=np.float64)
    # tight, one n per box
    idx = np.flatnonzero(np.broadcast_to(n_lo == n_hi, shape))
    if idx.size:

        def pick(x: ArrayLike) -> FloatArray:
            return np.asarray(np.broadcast_to(np.asarray(x, dtype=np.float64), shape)[idx])

        nn = pick(n_lo).astype(np.int64)
        pl, ph, sl, sh = pick(p_lo), pick(p_hi), pick(S_lo), pick(S_hi)
        c = (nn + 1) / 2.0
        j_lo = np.full(nn.shape, np.iinfo(np.int64).max)
        j_hi = np.full(nn.shape, -1)
        for h in holes:
            lo, hi = h.extent(ax)
            a = np.floor(c + np.minimum(lo / pl, lo / ph)).astype(np.int64)
            b = np.ceil(c + np.maximum(hi / pl, hi / ph)).astype(np.int64) - 1
            j_lo = np.minimum(j_lo, np.clip(a, 0, nn))
            j_hi = np.maximum(j_hi, np.clip(b, 0, nn))
        K = max(int(np.max(j_hi - j_lo + 1)), 1)
        j = j_lo[:, None] + np.arange(K)[None, :]
        valid = j <= j_hi[:, None]
        j = np.minimum(j, nn[:, None])
        m = (nn + 1)[:, None].astype(np.float64)
        cum = lay.cumulative_area
        dA = np.asarray(cum((j + 1) / m, ax)) - np.asarray(cum(j / m, ax))
        dA = np.where(valid, dA, 1.0)
        jc = j - c[:, None]
        union = (
            np.minimum(jc * pl[:, None], jc * ph[:, None]),
            np.maximum((jc + 1) * pl[:, None], (jc + 1) * ph[:, None]),
        )
        common = (
            np.maximum(jc * pl[:, None], jc * ph[:, None]),
            np.minimum((jc + 1) * pl[:, None], (jc + 1) * ph[:, None]),
        )
        some = np.zeros(j.shape, dtype=bool)
        always = np.zeros(j.shape, dtype=bool)
        b_max = np.zeros(j.shape)
        b_min = np.zeros(j.shape)
        for h in holes:
            lo, hi = h.extent(ax)
            some |= (lo < union[1]) & (hi > union[0])
            hit = (lo < common[1]) & (hi > common[0]) & (common[0] < common[1])
            always |= hit
            b_max += h.blocked(ax, union[0], union[1])
            b_min += np.where(hit, h.blocked(ax, common[0], common[1]), 0.0)
        some &= valid
        always &= valid
        inv = 1.0 / (m * dA)  # (n + 1) dA_j = L_j / S
        Qlo, Qhi = pick(Q[0]), pick(Q[1])
        if problem.identical:  # p / S = 1 / (n + 1)
            r_lo = r_hi = 1.0 / (nn + 1.0)
        else:
            r_lo, r_hi = pl / sh, ph / sl
        t_par_lo = r_lo * np.maximum(Qlo - np.where(some, inv, 0.0).sum(axis=1), 0.0)
        t_par_hi = r_hi * np.maximum(Qhi - np.where(always, inv, 0.0).sum(axis=1), 0.0)
        L_lo = m * sl[:, None] * dA
        L_hi = m * sh[:, None] * dA
        with np.errstate(divide="ignore", invalid="ignore"):
            f_hi = np.where(L_lo > b_max, b_max / (L_lo * (L_lo - b_max)), np.inf)
            f_lo = np.where(L_hi > b_min, b_min / (L_hi * (L_hi - b_min)), np.inf)
        f_hi = np.where(some & (b_max > 0), f_hi, 0.0).sum(axis=1)
        f_lo = np.where(always & (b_min > 0), f_lo, 0.0).sum(axis=1)
        pq_lo, pq_hi = pick(pq.lo), pick(pq.hi)
        par_lo[idx] = np.maximum(par_lo[idx], t_par_lo * (1 - _ROUND))
        par_hi[idx] = np.minimum(par_hi[idx], t_par_hi * (1 + _ROUND))
        ser_hi[idx] = np.minimum(ser_hi[idx], (pq_hi + ph * f_hi) * (1 + _ROUND))
        ser_lo[idx] = np.maximum(ser_lo[idx], (pq_lo + pl * f_lo) * (1 - _ROUND))
    par_lo = np.maximum(par_lo, 0.0)
    return Interval(par_lo, np.maximum(par_hi, par_lo)), Interval(
        ser_lo, np.maximum(ser_hi, ser_lo)
    )


def _stiffness_bounds(
    problem: Problem,
    c1: Candidate,
    c2: Candidate,
    lo: DesignPoints,
    hi: DesignPoints,
    tables: Tables,
    geo: Bounds,
    keys: list[Quantity],
) -> Bounds:
    Lx, Ly = geo[LX], geo[LY]
    sp1 = _layer_springs(
        problem,
        c1,
        (lo.layer(0).n, hi.layer(0).n),
        (lo.layer(0).W, hi.layer(0).W),
        (lo.layer(0).alpha, hi.layer(0).alpha),
        Ly,
        tables.Qx,
        tables,
        "x",
    )
    if (
        problem.identical
        and isinstance(problem.layout, Rectangle | Circle)
        and not problem.layout.holes  # holes need not be symmetric under x <-> y
    ):
        # outline symmetric under x <-> y: identical layers have identical springs
        sp2 = sp1
    else:  # a polygon's facet lengths differ across x and across y (regression: issue found
        # by brute force on a pentagon; layer 2 must use Q_y even when the layers are identical)
        sp2 = _layer_springs(
            problem,
            c2,
            (lo.layer(1).n, hi.layer(1).n),
            (lo.layer(1).W, hi.layer(1).W),
            (lo.layer(1).alpha, hi.layer(1).alpha),
            Lx,
            tables.Qy,
            tables,
            "y",
        )
    out: Bounds = {}
    # how the layout is read off the crease directions (corrugate.mechanics.offaxis.Coupon): made at the
    # first stiffness asked for off them under a behaviour that reads it (None for a square)
    coupon: Coupon | None = None
    for q in keys:
        assert q.eta is not None
        eta = q.eta
        v: Interval
        if q.kind == "Pb":  # buckling along layer 1's (0) or layer 2's (90) creases
            along, across, b, m = (sp1, sp2, 0, c1) if eta == 0.0 else (sp2, sp1, 1, c2)
            Wb = Interval(lo.layer(b).W, hi.layer(b).W)
            nb = Interval(lo.layer(b).n, hi.layer(b).n)
            mat = m.material
            v = (
                buckling_scale(
                    np.float64(mat.E),
                    np.float64(mat.nu),
                    np.float64(m.t),
                    Wb,
                    nb,
                    along.K_S,
                    across.K_C,
                )
                * K_SIMPLE_FREE
            )
            out[q] = (np.maximum(v.lo, 0.0), v.hi)
            continue
        if q.kind == "length":
            v = _span_bounds(problem, Lx, Ly, eta)
            out[q] = (np.maximum(v.lo, 0.0), v.hi)
            continue
        entry = get_support(q.support or DEFAULT_SUPPORT)  # the support condition
        if coupon is None and entry.uses_coupon and crease_layer(eta) is None:
            coupon = coupon_of(
                problem.layout,
                Interval(Lx[0], Lx[1]),
                Interval(Ly[0], Ly[1]),
                lambda: (sp1.pq, sp2.pq),
            )
        band, depth = None, None
        if problem.joint != "none" and crease_layer(eta) is not None:
            depth = Interval(*geo[THICKNESS])
            band = band_walls(
                float(c1.material.E),
                float(c1.material.nu),
                float(c1.t),
                depth,
                _span_bounds(problem, Lx, Ly, eta),
            )
        if q.test is not None:  # a load case on its support's D or K
            v = _load_case_bounds(problem, q, (sp1, sp2), Lx, Ly, coupon, (c1, c2), band, depth)
            out[q] = (np.maximum(v.lo, 0.0), v.hi)
            continue
        v = entry.bounds("D" if q.kind == "EI" else q.kind, (sp1, sp2), eta, coupon)
        if band is not None:  # the band's walls along the creases (mechanics.load_cases)
            v = v + (band[2] if q.kind == "K" else band[0])
        if q.kind == "EI":
            v = v * _span_bounds(problem, Lx, Ly, eta)
        out[q] = (np.maximum(v.lo, 0.0), v.hi)
    return out


def _load_case_bounds(
    problem: Problem,
    q: Quantity,
    springs: tuple[_Springs, _Springs],
    Lx: tuple[FloatArray, FloatArray],
    Ly: tuple[FloatArray, FloatArray],
    coupon: Coupon | None,
    cands: tuple[Candidate, Candidate],
    band: tuple[Any, Any, Any] | None = None,
    depth: Interval | None = None,
) -> Interval:
    """Bounds of a load case's quantity over the boxes: the formula of
    :mod:`corrugate.mechanics.load_cases` on the interval springs, the support's D or K bounds
    (with the layout's ``coupon`` off the creases) and the panel length's bounds."""
    assert q.eta is not None and q.test is not None
    form = get_load_case(q.test).form
    assert form is not None
    support = get_support(q.support or DEFAULT_SUPPORT)
    base = support.bounds("K" if form.kind == "inplane" else "D", springs, q.eta, coupon)
    length = _span_bounds(problem, Lx, Ly, q.eta)
    whole = base if band is None else base + band[2 if form.kind == "inplane" else 0]
    if q.kind == "Pmax":
        along = 0 if crease_layer(q.eta) == 0 else 1
        width = Interval(*(Lx if along == 0 else Ly))
        sp = springs if along == 0 else springs[::-1]
        E = (float(cands[0].material.E), float(cands[1].material.E))
        t = (float(cands[0].t), float(cands[1].t))
        per = stress_per_load(
            form,
            (sp[0], sp[1]),
            0,
            base,
            (E[along], E[1 - along]),
            (t[along], t[1 - along]),
            length,
            width,
            q.span,
        )
        cap = load_capacity(
            (Interval.of(per[0]), Interval.of(per[1])),
            _allowables(cands[0], cands[1], along),
            problem.safety_factor,
        )
        if band is not None:
            wall = wall_capacity(
                form,
                whole,
                float(cands[0].material.E),
                float(cands[0].t),
                depth,
                length,
                q.span,
                _allowables(cands[0], cands[0], 0)[0],
                problem.safety_factor,
            )
            cap = Interval.of(cap).minimum(Interval.of(wall))
        return Interval.of(cap)
    cos2, sin2 = _cs(q.eta)
    V, h = shear_and_depth(springs, cos2, sin2)
    k = load_stiffness(form, base, V, h, length, q.span, q.eta)
    if band is not None:  # the walls beside the layers (parallel beams)
        k = k + walls_stiffness(form, band, length, q.span)
    return Interval.of(apparent(form, q.kind, k, length))


def _span_bounds(
    problem: Problem,
    Lx: tuple[FloatArray, FloatArray],
    Ly: tuple[FloatArray, FloatArray],
    eta_deg: float,
) -> Interval:
    lay = problem.layout
    eta = np.asarray(eta_deg, dtype=np.float64)
    hi = np.asarray(lay.span(Lx[1], Ly[1], eta), dtype=np.float64)
    if isinstance(lay, Rectangle | Circle):  # monotone in Lx and Ly
        lo = np.asarray(lay.span(Lx[0], Ly[0], eta), dtype=np.float64)
        return Interval(np.nextafter(lo, 0.0), np.nextafter(hi, np.inf))
    e = np.radians(eta_deg)
    slack = 2.0 * (np.abs(np.sin(e)) * (Lx[1] - Lx[0]) + np.abs(np.cos(e)) * (Ly[1] - Ly[0]))
    return Interval(np.maximum(hi - slack, 0.0), hi + slack)
