"""The evaluators of the directional quantities: stiffness under a support condition, the
panel's length, the end facets' buckling load, and the quantities of a load case.

At points every value is read from ``evaluate`` (:class:`~.context.AtPoints`): EI, D and K at
every direction of the problem under free sides, and under each other support condition a
quantity asks for by its entry's ``model`` in :mod:`corrugate.mechanics.behaviours` (its own
``evaluate`` for one that reads the layout's coupon); a load case by the formulas of
:mod:`corrugate.mechanics.load_cases` (docs/load_cases.md) on its support's D or K.

Over boxes (:class:`~.context.OverBoxes`) the moduli variant's own function is evaluated in
:class:`~.interval.Interval` arithmetic over the box (W, alpha), then the spring sums of
docs/theory.md 3.2 (:mod:`~.interval_springs`), and the assembly by the ``bounds`` of the
quantity's support condition (or load case) in the registry of behaviours (the rule of 3.3 for a
frame, the free-panel lower bounds of :mod:`corrugate.mechanics.offaxis` for free sides, each
variable once per term so the intervals are tight), with q = sum_j 1/L_j = Q(n) / S (Q from
:func:`corrugate.geometry.layouts.inverse_length_sum`); for identical layers p q = Q(n) / (n + 1)
exactly, which removes the dependency on p. A hole only removes terms from the parallel sums and
lengthens the series ones, so the hole-free bounds remain upper bounds, and the lower bounds come
from :func:`~.interval_springs._hole_pq_bounds`. EI = D x span: for square, rectangle and circle
the span grows with Lx and Ly (its value at the upper corner bounds it); for a polygon the span
moves by at most 2 (|dLx sin eta| + |dLy cos eta|) when the box is shrunk to a corner (each
vertex moves by at most its share of dLx, dLy), which bounds it from both sides. The buckling
load is :func:`corrugate.mechanics.buckling.buckling_scale` in interval arithmetic (each variable
appears once, and K_C / K_S from the interval springs). Interval bounds converge to the exact
value as the box shrinks, which is what makes branch and bound terminate.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from typing import Any

import numpy as np
from numpy.typing import NDArray

from corrugate.geometry.layer import crease_layer
from corrugate.mechanics.behaviours import DEFAULT_SUPPORT, get_load_case, get_support, supports
from corrugate.mechanics.buckling import K_SIMPLE_FREE, buckling_scale
from corrugate.mechanics.load_cases import (
    apparent,
    load_stiffness,
    shear_and_depth,
    walls_stiffness,
)
from corrugate.mechanics.offaxis import _cs
from corrugate.solver.context import AtPoints, Columns, OverBoxes, column
from corrugate.solver.evaluator import Evaluator, Pair, register
from corrugate.solver.interval import Interval, number
from corrugate.solver.problem import Candidate, Problem
from corrugate.solver.quantity import STIFFNESS, Quantity

__all__ = ["BUCKLING", "LENGTH", "LOAD_CASES", "STIFFNESSES", "capacity_modes_at"]

FloatArray = NDArray[np.float64]


def _clamped(v: Interval) -> Pair:
    """Bounds of a quantity that cannot be negative."""
    return np.maximum(v.lo, 0.0), v.hi


def _etas(problem: Problem) -> tuple[float, ...]:
    """The directions (deg) point values cover: the problem's, else 0."""
    return tuple(float(e) for e in np.asarray(problem.etas or (0.0,), dtype=np.float64))


# --- stiffness under a support condition: EI (N mm^2), D (N mm), K (N/mm) ---


def _stiffness_reported(problem: Problem) -> Iterator[Quantity]:
    """EI, D and K at every direction under free sides and each support asked for."""
    asked = {q.support for q in problem.quantities}
    names = [DEFAULT_SUPPORT]
    names += [b.name for b in supports() if b.name != DEFAULT_SUPPORT and b.name in asked]
    for e in _etas(problem):
        for name in names:
            for kind in STIFFNESS:
                yield Quantity(kind, e, name)


def _under_support(at: AtPoints, support: str, e: float) -> tuple[FloatArray, FloatArray]:
    """D and K at direction ``e`` (deg) under a support that does not read the coupon, with
    the band's walls along the creases."""

    def make() -> tuple[FloatArray, FloatArray]:
        b = get_support(support)
        springs = at.ev.springs
        D_b = np.asarray(b.model("D", springs, e, None))[:, 0]
        K_b = np.asarray(b.model("K", springs, e, None))[:, 0]
        if at.walls is not None and crease_layer(e) is not None:
            w = at.walls(at.span(e))
            D_b, K_b = D_b + w[0], K_b + w[2]
        return D_b, K_b

    return at.shared(f"support:{support}@{e!r}", make)


def _stiffness_at(at: AtPoints, q: Quantity) -> FloatArray:
    assert q.eta is not None and q.support is not None
    e = q.eta
    b = get_support(q.support)
    if b.name == DEFAULT_SUPPORT or b.uses_coupon:  # evaluate's own treatment of the coupon
        ev = at.ev if b.name == DEFAULT_SUPPORT else at.under(b.name)
        return ev.column(q.kind, at.column(e))
    D_b, K_b = _under_support(at, b.name, e)
    if q.kind == "D":
        return D_b
    if q.kind == "K":
        return K_b
    return np.asarray(D_b * at.span(e))


def _stiffness_over(over: OverBoxes, q: Quantity) -> Pair:
    assert q.eta is not None
    entry = get_support(q.support or DEFAULT_SUPPORT)
    coupon = over.coupon(entry, q.eta)
    band, _ = over.walls(q.eta)
    v = entry.bounds("D" if q.kind == "EI" else q.kind, over.springs, q.eta, coupon)
    if band is not None:  # the band's walls along the creases (mechanics.load_cases)
        v = v + (band[2] if q.kind == "K" else band[0])
    if q.kind == "EI":
        v = v * over.span(q.eta)
    return _clamped(v)


STIFFNESSES = register(Evaluator(STIFFNESS, _stiffness_at, _stiffness_over, _stiffness_reported))


# --- the panel's length along eta (mm) ---


def _length_at(at: AtPoints, q: Quantity) -> FloatArray:
    assert q.eta is not None
    return at.span(q.eta)


def _length_over(over: OverBoxes, q: Quantity) -> Pair:
    assert q.eta is not None
    return _clamped(over.span(q.eta))


LENGTH = register(
    Evaluator(
        ("length",),
        _length_at,
        _length_over,
        lambda problem: (Quantity("length", e) for e in _etas(problem)),
    )
)


# --- the end facets' buckling load along layer 1's (0) or layer 2's (90) creases (N) ---


def _buckling_at(at: AtPoints, q: Quantity) -> FloatArray:
    l1, l2 = at.layers
    s1, s2 = at.ev.springs
    lay, sa, sc = (l1, s1, s2) if q.eta == 0.0 else (l2, s2, s1)
    return np.asarray(
        K_SIMPLE_FREE * buckling_scale(lay.E, lay.nu, lay.t, lay.W, lay.n, sa.K_S, sc.K_C)
    )[:, 0]


def _f64(x: Any) -> Any:
    """A sheet's E or t as a float64, or its :class:`~.interval.Interval` over the tolerances."""
    return x if isinstance(x, Interval) else np.float64(x)


def _buckling_over(over: OverBoxes, q: Quantity) -> Pair:
    sp1, sp2 = over.springs
    along, across, b, m = (sp1, sp2, 0, over.c1) if q.eta == 0.0 else (sp2, sp1, 1, over.c2)
    Wb = Interval(over.lo.layer(b).W, over.hi.layer(b).W)
    nb = Interval(over.lo.layer(b).n, over.hi.layer(b).n)
    mat = m.material
    v = (
        buckling_scale(_f64(mat.E), np.float64(mat.nu), _f64(m.t), Wb, nb, along.K_S, across.K_C)
        * K_SIMPLE_FREE
    )
    return _clamped(v)


def _buckling_reported(problem: Problem) -> tuple[Quantity, ...]:
    """Both directions once one is asked for."""
    if any(q.kind == "Pb" for q in problem.quantities):
        return (Quantity("Pb", 0.0), Quantity("Pb", 90.0))
    return ()


BUCKLING = register(Evaluator(("Pb",), _buckling_at, _buckling_over, _buckling_reported))


# --- the quantities of a load case (docs/load_cases.md) ---


def _allowables(c1: Candidate, c2: Candidate, along: int) -> tuple[float, float]:
    """The yield strengths (MPa) of (the layer along eta, the other); +inf for a material
    without one (its yield is then not a mode; Problem.from_spec refuses a strength bound on
    it)."""
    y1, y2 = (
        math.inf if c.material.yield_strength is None else float(c.material.yield_strength)
        for c in (c1, c2)
    )
    return (y1, y2) if along == 0 else (y2, y1)


def capacity_modes_at(at: AtPoints, q: Quantity) -> dict[str, FloatArray]:
    """Every failure mode's load (N, no safety factor) of the load case of the ``Pmax``
    quantity ``q`` at the points (:func:`corrugate.mechanics.capacity.capacity_modes`;
    docs/load_cases.md 10): the capacity is their least divided by the safety factor."""
    from corrugate.mechanics.capacity import Band, capacity_modes  # a load case's bound only

    assert q.eta is not None and q.test is not None
    e = q.eta
    form = get_load_case(q.test).form
    assert form is not None
    base = at.value(Quantity("K" if form.kind == "inplane" else "D", e, q.support))
    span = at.value(Quantity("length", e))
    band = None if at.walls is None or crease_layer(e) is None else at.walls(span)
    layers = base if band is None else base - band[2 if form.kind == "inplane" else 0]
    l1, l2 = at.layers
    along = 0 if crease_layer(e) == 0 else 1
    extents = (at.Lx, at.Ly) if along == 0 else (at.Ly, at.Lx)
    lay = (l1, l2) if along == 0 else (l2, l1)
    sp = at.ev.springs if along == 0 else at.ev.springs[::-1]
    y1 = _allowables(at.c1, at.c1, 0)[0]
    modes = capacity_modes(
        form,
        (Columns(sp[0]), Columns(sp[1])),
        (column(np.asarray(lay[0].E)), column(np.asarray(lay[1].E))),
        (column(np.asarray(lay[0].t)), column(np.asarray(lay[1].t))),
        float(np.asarray(lay[0].nu)),
        column(np.asarray(lay[0].W, np.float64)),
        column(np.asarray(lay[0].n, np.float64)),
        layers,  # the layers' own D or K: their curvature or strain from above
        base,
        extents[1],
        extents[0],
        q.span,
        _allowables(at.c1, at.c2, along),
        None
        if band is None
        else Band(
            column(np.asarray(l1.E)),
            float(at.c1.material.nu),
            column(np.asarray(l1.t)),
            at.ev.thickness[:, 0],
            y1,
        ),
        at.problem.joint == "none",
        along,
        q.bearing,
    )
    return {k: np.broadcast_to(np.asarray(v, np.float64), span.shape) for k, v in modes.items()}


def _load_case_at(at: AtPoints, q: Quantity) -> FloatArray:
    assert q.eta is not None and q.test is not None
    e = q.eta
    form = get_load_case(q.test).form
    assert form is not None
    if q.kind == "Pmax":
        modes = capacity_modes_at(at, q)
        return np.asarray(np.minimum.reduce(list(modes.values())) / at.problem.safety_factor)
    base = at.value(Quantity("K" if form.kind == "inplane" else "D", e, q.support))
    span = at.value(Quantity("length", e))
    band = None if at.walls is None or crease_layer(e) is None else at.walls(span)
    layers = base if band is None else base - band[2 if form.kind == "inplane" else 0]
    cos2, sin2 = _cs(e)
    V, h = shear_and_depth(at.ev.springs, cos2, sin2)
    k = load_stiffness(form, layers, np.asarray(V)[:, 0], np.asarray(h)[:, 0], span, q.span, e)
    if band is not None:  # the walls beside the layers (parallel beams)
        k = k + walls_stiffness(form, band, span, q.span)
    return np.asarray(apparent(form, q.kind, k, span))


def _modes_over(over: OverBoxes, q: Quantity, base: Any, whole: Any, band: Any) -> list[Any]:
    """Bounds of every failure mode's load (N, no safety factor) over the boxes: the formulas
    of :func:`capacity_modes_at` on the interval springs and the boxes' W and n."""
    from corrugate.mechanics.capacity import Band, capacity_modes

    assert q.eta is not None and q.test is not None
    form = get_load_case(q.test).form
    assert form is not None
    c1, c2 = over.c1, over.c2
    along = 0 if crease_layer(q.eta) == 0 else 1
    sp = over.springs if along == 0 else over.springs[::-1]
    cand = (c1, c2) if along == 0 else (c2, c1)
    walls = None
    if band is not None:
        _, depth = over.walls(q.eta)
        m1 = c1.material
        walls = Band(number(m1.E), float(m1.nu), number(c1.t), depth, _allowables(c1, c1, 0)[0])
    modes = capacity_modes(
        form,
        (sp[0], sp[1]),
        (number(cand[0].material.E), number(cand[1].material.E)),
        (number(cand[0].t), number(cand[1].t)),
        float(cand[0].material.nu),
        Interval(over.lo.layer(along).W, over.hi.layer(along).W),
        Interval(over.lo.layer(along).n, over.hi.layer(along).n),
        base,
        whole,
        over.span(q.eta),
        Interval(*(over.Lx if along == 0 else over.Ly)),
        q.span,
        _allowables(c1, c2, along),
        walls,
        over.problem.joint == "none",
        along,
        q.bearing,
    )
    return list(modes.values())


def _load_case_over(over: OverBoxes, q: Quantity) -> Pair:
    """The formula of :mod:`corrugate.mechanics.load_cases` on the interval springs, the
    support's D or K bounds (with the layout's coupon off the creases) and the panel length's
    bounds; a capacity: the least of the modes' bounds (:func:`_modes_over`) over the safety
    factor."""
    assert q.eta is not None and q.test is not None
    support = get_support(q.support or DEFAULT_SUPPORT)
    coupon = over.coupon(support, q.eta)
    band, _ = over.walls(q.eta)
    springs = over.springs
    form = get_load_case(q.test).form
    assert form is not None
    base = support.bounds("K" if form.kind == "inplane" else "D", springs, q.eta, coupon)
    length = over.span(q.eta)
    whole = base if band is None else base + band[2 if form.kind == "inplane" else 0]
    if q.kind == "Pmax":
        modes = _modes_over(over, q, base, whole, band)
        cap = Interval.of(modes[0])
        for m in modes[1:]:
            cap = cap.minimum(Interval.of(m))
        return _clamped(cap / over.problem.safety_factor)
    cos2, sin2 = _cs(q.eta)
    V, h = shear_and_depth(springs, cos2, sin2)
    k = load_stiffness(form, base, V, h, length, q.span, q.eta)
    if band is not None:  # the walls beside the layers (parallel beams)
        k = k + walls_stiffness(form, band, length, q.span)
    return _clamped(Interval.of(apparent(form, q.kind, k, length)))


LOAD_CASES = register(
    Evaluator(("EI", "D", "K", "k", "Pmax"), _load_case_at, _load_case_over, tests=True)
)
