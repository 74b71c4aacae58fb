"""Bounds of the directional quantities over the worst-case tolerance box (docs/tolerances.md).

With a problem's :class:`~.worst_case.WorstCase` tolerances (fold angle +-da deg, facet width
+-dW mm, thickness and Young's modulus +-dt, +-dE relative), the value the solver certifies of
a directional quantity q (a stiffness, a load case's P / delta or capacity, a buckling load, the
panel's length: every such constraint is a lower bound, ``Problem.from_spec``) at a design x is

    G(x) = the lower bound of q over the tolerance box T(x),

T(x) the designs with each layer's W in [W - dW, W + dW] and alpha in [alpha - da, alpha + da]
(each layer on its own: identical layers are bounded as two independent layers of one sheet),
n exact, and sheets whose E and t are the intervals [E (1 - dE), E (1 + dE)] and
[t (1 - dt), t (1 + dt)]. It is computed by the quantity's own bounds over boxes
(:class:`~.context.OverBoxes`, the interval arithmetic of :mod:`~.interval_springs` with E and t
as :class:`~.interval.Interval` values), so G(x) <= q(x') for every x' in T(x): a design with
G(x) >= bound meets the bound at every corner of its tolerance box (and everywhere inside).

Over a search box B the lower bound of G is that of q over B widened by the tolerances (the
enclosure over B + T contains every T(x) of x in B: inclusion isotonicity). Its upper bound is
the least of that enclosure's upper bound and, when B is at most 2 d wide in every W and alpha
and holds one n, the lower bound over the inner box [hi - d, lo + d], which every T(x) of x in B
contains, so it is at least every G(x) and closes on G as B shrinks (without it, boxes near a
bound would never close on a continuous variable). At a point box both are G(x) itself. The
thickness's interval is cut into :data:`T_PIECES` pieces at points and inner boxes. The sizes,
the mass and the making stay nominal (docs/tolerances.md says why).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from corrugate.materials.library import Material
from corrugate.solver.context import OverBoxes
from corrugate.solver.interval import Interval
from corrugate.solver.points import DesignPoints, LayerPoints
from corrugate.solver.problem import Candidate, Problem
from corrugate.solver.quantity import Quantity
from corrugate.solver.tables import Tables
from corrugate.solver.worst_case import WorstCase

__all__ = [
    "T_PIECES",
    "ToleranceBounds",
    "corners",
    "covered",
    "low_sheet",
    "sheet",
    "stacked",
    "widened",
]

FloatArray = NDArray[np.float64]

#: The fold angles a widened box stays within (deg): the zig-zag's 0 < alpha < 180.
_ALPHA_MIN, _ALPHA_MAX = 1e-3, 180.0 - 1e-3


def covered(problem: Problem, q: Quantity) -> bool:
    """Whether ``q`` is bounded over the tolerance box (a directional quantity under
    tolerances that are not nominal, or on a calibrated sheet)."""
    return q.eta is not None and (not problem.tolerances.nominal or problem.calibrated)


def _E_range(m: Material, tol: WorstCase) -> tuple[float, float]:
    """E's interval (MPa): a calibrated material's measured one (docs/calibration.md 9), else
    (a datasheet's E, or an inline material's stated crease and springback) the tolerance's
    E (1 -+ dE)."""
    cal = m.calibration
    if cal is not None and cal.E_measured:
        return cal.E_lo, cal.E_hi
    return m.E * (1 - tol.E), m.E * (1 + tol.E)


def _k_low(m: Material) -> float:
    """The softest crease stiffness (N mm/(rad mm)) of a material: its calibrated interval's
    low end, else its own."""
    cal = m.calibration
    return m.crease_stiffness if cal is None or math.isinf(cal.k_lo) else cal.k_lo


def alpha_offsets(problem: Problem, c: Candidate) -> tuple[float, float]:
    """How far below and above a design's fold angle (deg) its tolerance box reaches on the
    sheet ``c``: -da and +da, each moved by a calibrated springback's interval (the folds take
    alpha + springback; docs/calibration.md 9)."""
    da = half_widths(problem)[1]
    cal = c.material.calibration
    if cal is None:
        return -da, da
    return cal.springback_lo - da, cal.springback_hi + da


def sheet(c: Candidate, tol: WorstCase, pieces: int = 1, rows: int = 1) -> Candidate:
    """The sheet ``c`` with E (MPa) and t (mm) as intervals over the tolerances (floats when a
    half-width is 0); with ``pieces`` > 1, t's interval cut into that many equal pieces, each
    repeated for ``rows`` boxes (an array of ``pieces * rows`` intervals, piece by piece). A
    calibrated material takes its measured E interval instead of the tolerance's, and its
    crease stiffness's interval (:mod:`corrugate.materials.calibrated`)."""
    m = c.material
    E_lo, E_hi = _E_range(m, tol)
    E: object = Interval(E_lo, E_hi) if E_lo < E_hi else m.E
    cal = m.calibration
    k: object = m.crease_stiffness
    if cal is not None and not math.isinf(cal.k_lo):
        k = Interval(cal.k_lo, cal.k_hi)
    t: object = c.t
    if tol.t:
        edges = np.linspace(c.t * (1 - tol.t), c.t * (1 + tol.t), pieces + 1)
        t = Interval(np.repeat(edges[:-1], rows), np.repeat(edges[1:], rows))
        if pieces == 1 and rows == 1:
            t = Interval(float(edges[0]), float(edges[1]))
    return replace(c, material=replace(m, E=E, crease_stiffness=k), t=t)  # type: ignore[arg-type]


#: The least half-width of a continuous W or alpha, relative to its range: with a zero
#: tolerance on a continuous variable the search's boxes could never close (the upper bound
#: over a box is the inner box's, module docstring), so it covers that much more.
_TINY = 1e-9


def half_widths(problem: Problem) -> tuple[float, float]:
    """The half-widths of W (mm) and alpha (deg) the bounds use: the tolerances', at least
    :data:`_TINY` of a continuous variable's range."""
    tol = problem.tolerances
    dW, da = tol.W, tol.alpha
    if not dW and not problem.W.gridded:
        dW = _TINY * (problem.W.hi - problem.W.lo)
    if not da and not problem.alpha.gridded:
        da = _TINY * (problem.alpha.hi - problem.alpha.lo)
    return dW, da


def _clip(W: FloatArray, a: FloatArray) -> tuple[FloatArray, FloatArray]:
    # a facet width stays positive (W >= min_facet >> dW in practice), 0 < alpha < 180
    return np.maximum(W, 1e-6), np.clip(a, _ALPHA_MIN, _ALPHA_MAX)


def moved(W: FloatArray, a: FloatArray, dW: float, da: float) -> tuple[FloatArray, FloatArray]:
    """Facet widths ``W`` (mm) and fold angles ``a`` (deg) moved by ``dW`` and ``da`` and
    clipped: the arithmetic of every corner of a tolerance box (:func:`corners`,
    :func:`moved_points`)."""
    return _clip(np.asarray(W, np.float64) + dW, np.asarray(a, np.float64) + da)


def moved_points(x: DesignPoints, dW: float, das: Sequence[float]) -> DesignPoints:
    """Every stored layer i of ``x`` with W moved by ``dW`` (mm) and alpha by ``das[i]`` (deg;
    the last one for the layers past it), clipped (:func:`moved`)."""
    layers = []
    for i, lay in enumerate(x.layers):
        W, a = moved(lay.W, lay.alpha, dW, das[min(i, len(das) - 1)])
        layers.append(LayerPoints(np.asarray(lay.n, np.float64), W, a))
    return x.with_layers(*layers)


def corner_shifts(tol: WorstCase) -> tuple[tuple[float, float], ...]:
    """The (dW, da) of the four corners of :func:`corners` for sheets without a calibrated
    springback (W -+ dW, alpha -+ da); none when both half-widths are 0."""
    if not (tol.W or tol.alpha):
        return ()
    return tuple((sW * tol.W, sa * tol.alpha) for sW, sa in _SHIFTS)


def _offsets(
    problem: Problem, cands: tuple[Candidate, Candidate] | None, i: int
) -> tuple[float, float]:
    """:func:`alpha_offsets` of layer ``i``'s sheet (-da, +da without ``cands``)."""
    if cands is None:
        da = half_widths(problem)[1]
        return -da, da
    return alpha_offsets(problem, cands[min(i, 1)])


def widened(
    problem: Problem,
    lo: DesignPoints,
    hi: DesignPoints,
    inner: bool = False,
    cands: tuple[Candidate, Candidate] | None = None,
) -> tuple[DesignPoints, DesignPoints]:
    """The boxes [lo, hi] widened by the tolerances of ``problem``, every layer stored (so
    identical layers vary independently); ``inner``: the boxes every tolerance box of a point
    of [lo, hi] contains, [hi - d, lo + d] (n one value, widths at most 2 d). ``cands``: the
    layers' sheets, whose calibrated springback moves alpha's (:func:`alpha_offsets`)."""
    dW = half_widths(problem)[0]
    count = lo.count
    lows, highs = [], []
    for i in range(count):
        a, b = lo.layer(i), hi.layer(i)
        off_lo, off_hi = _offsets(problem, cands, i)
        aW, bW = np.asarray(a.W, np.float64), np.asarray(b.W, np.float64)
        aa, ba = np.asarray(a.alpha, np.float64), np.asarray(b.alpha, np.float64)
        n = np.asarray(a.n, np.float64)
        low = _clip(bW - dW, ba + off_lo) if inner else _clip(aW - dW, aa + off_lo)
        high = _clip(aW + dW, aa + off_hi) if inner else _clip(bW + dW, ba + off_hi)
        lows.append(LayerPoints(n, *low))
        highs.append(LayerPoints(n if inner else np.asarray(b.n, np.float64), *high))
    return DesignPoints(tuple(lows), count), DesignPoints(tuple(highs), count)


def _inner_rows(
    problem: Problem,
    lo: DesignPoints,
    hi: DesignPoints,
    cands: tuple[Candidate, Candidate] | None = None,
) -> NDArray[np.intp]:
    """The boxes whose inner box exists: n one value and W, alpha at most as wide as their
    tolerance boxes (2 d, alpha's with a springback's interval)."""
    dW = half_widths(problem)[0]
    ok = np.ones(len(lo), dtype=bool)
    for i in range(lo.count):
        a, b = lo.layer(i), hi.layer(i)
        off_lo, off_hi = _offsets(problem, cands, i)
        ok &= np.asarray(a.n) == np.asarray(b.n)
        ok &= np.asarray(b.W, np.float64) - np.asarray(a.W, np.float64) <= 2 * dW
        ok &= np.asarray(b.alpha, np.float64) - np.asarray(a.alpha, np.float64) <= off_hi - off_lo
    return np.flatnonzero(ok)


#: The pieces the thickness interval is cut into at points (their worst case is the least of
#: the pieces'): t appears in many terms of the springs (t and t^3), so one interval
#: over-reaches (docs/tolerances.md gives the measured effect); boxes take it whole.
T_PIECES = 8


class _Pieces:
    """The bounds over the boxes [lo, hi] on the sheets' E and t intervals, t cut in
    ``pieces``: the least lower and the greatest upper bound of the pieces."""

    def __init__(
        self,
        problem: Problem,
        c1: Candidate,
        c2: Candidate,
        lo: DesignPoints,
        hi: DesignPoints,
        tables: Tables,
        pieces: int,
    ) -> None:
        tol = problem.tolerances
        k = len(lo)
        self.pieces, self.rows = pieces, k
        if pieces > 1:  # every box once per piece of t, piece by piece
            rep = np.tile(np.arange(k), pieces)
            lo, hi = lo.take(rep), hi.take(rep)
        s1 = sheet(c1, tol, pieces, k)
        s2 = s1 if c2 == c1 else sheet(c2, tol, pieces, k)
        free = replace(problem, identical=False) if problem.identical else problem
        self.over = OverBoxes(free, s1, s2, lo, hi, tables)

    def bounds(self, q: Quantity) -> tuple[FloatArray, FloatArray]:
        low, high = self.over.bounds(q)
        size = self.pieces * self.rows
        shape = (self.pieces, self.rows)
        low = np.broadcast_to(np.asarray(low, np.float64), (size,)).reshape(shape)
        high = np.broadcast_to(np.asarray(high, np.float64), (size,)).reshape(shape)
        return low.min(axis=0), high.max(axis=0)


#: The shifts (of W by dW, of alpha by da) of the corners of a tolerance box that bound the
#: certified value from above (:func:`corners`, :class:`ToleranceBounds`).
_SHIFTS = ((-1.0, -1.0), (-1.0, 1.0), (1.0, -1.0), (1.0, 1.0))


def _low(c: Candidate, tol: WorstCase) -> Candidate:
    """The sheet ``c`` at its lowest E (E (1 - dE), or a calibrated E's low end), t (1 - dt) and
    its softest crease: a corner of its tolerances."""
    m = c.material
    low = replace(m, E=_E_range(m, tol)[0], crease_stiffness=_k_low(m))
    return replace(c, material=low, t=c.t * (1 - tol.t))


#: The sheet at its lowest E, t and crease stiffness (a corner of its tolerances).
low_sheet = _low


def _shift(
    problem: Problem,
    x: DesignPoints,
    sW: float,
    sa: float,
    cands: tuple[Candidate, Candidate] | None = None,
) -> DesignPoints:
    """Every stored layer of ``x`` with W moved by ``sW`` dW and alpha to the low (``sa`` < 0)
    or high end of its tolerance box (:func:`alpha_offsets`; +-da without ``cands``), clipped
    as :func:`widened` clips."""
    tol = problem.tolerances
    das = []
    for i in range(len(x.layers)):
        cal = None if cands is None else cands[min(i, 1)].material.calibration
        if cal is None:
            das.append(sa * tol.alpha)
        else:  # inside the box's alpha + springback -+ da (alpha_offsets)
            das.append(cal.springback_lo - tol.alpha if sa < 0 else cal.springback_hi + tol.alpha)
    return moved_points(x, sW * tol.W, das)


def stacked(parts: Sequence[DesignPoints]) -> DesignPoints:
    """The points of ``parts`` one after the other (each field of each stored layer
    concatenated, a scalar repeated for its part's points); every part stores the same layers
    and sets the same per-point overrides. Every bound over boxes is elementwise in the boxes
    (:mod:`~.quantities`), so the bounds over the stacked boxes are those of each part."""
    first = parts[0]
    sizes = [len(p) for p in parts]

    def joined(values: list[Any]) -> Any:
        if values[0] is None:
            return None
        return np.concatenate(
            [np.broadcast_to(np.asarray(v), (k,)) for v, k in zip(values, sizes, strict=True)]
        )

    layers = []
    for i in range(len(first.layers)):
        lays = [p.layers[i] for p in parts]
        layers.append(
            LayerPoints(
                *(joined([getattr(lay, f) for lay in lays]) for f in ("n", "W", "alpha", "E", "t"))
            )
        )
    return first.with_layers(*layers)


class ToleranceBounds:
    """The certified value's bounds over the boxes [lo, hi] (``lo is hi``: its value at
    points) on sheets whose E and t are intervals, identical layers bounded as independent
    ones, module docstring: below, the bound over the boxes widened by the tolerances (t
    whole); above, the least of that box's upper bound, where the inner box exists the inner
    box's lower bound (t in pieces), which every point's certified value is at most and which
    closes on it as the box shrinks, and the upper bounds of the quantity over the box shifted
    to each of four corners of the tolerances (W -+ dW, alpha -+ da, the sheet at E (1 - dE)
    and t (1 - dt)): for each x of the box that corner of T(x) lies in the shifted box, so the
    certified value G(x), at most the quantity there, is at most the shifted box's upper bound.
    These need no inner box, so boxes of a grid coarser than the tolerances close too. The
    four shifted boxes are bounded in one evaluation of 4 k rows (:func:`stacked`)."""

    def __init__(
        self,
        problem: Problem,
        c1: Candidate,
        c2: Candidate,
        lo: DesignPoints,
        hi: DesignPoints,
        tables: Tables,
    ) -> None:
        self.point = lo is hi
        pieces = T_PIECES if problem.tolerances.t else 1
        cands = (c1, c2)
        wlo, whi = widened(problem, lo, hi, cands=cands)
        self.outer = _Pieces(problem, c1, c2, wlo, whi, tables, pieces if self.point else 1)
        self.inner: _Pieces | None = None
        self.sel = np.zeros(0, dtype=np.intp)
        self.shifted: OverBoxes | None = None
        if not self.point:
            self.sel = _inner_rows(problem, lo, hi, cands)
            if self.sel.size:
                ilo, ihi = widened(
                    problem, lo.take(self.sel), hi.take(self.sel), inner=True, cands=cands
                )
                self.inner = _Pieces(problem, c1, c2, ilo, ihi, tables, pieces)
            free = replace(problem, identical=False) if problem.identical else problem
            low1, low2 = _low(c1, problem.tolerances), _low(c2, problem.tolerances)
            # the four shifted boxes as one evaluation of 4 k rows, shift by shift
            slo = stacked([_shift(problem, lo, *shift, cands) for shift in _SHIFTS])
            shi = stacked([_shift(problem, hi, *shift, cands) for shift in _SHIFTS])
            self.shifted = OverBoxes(free, low1, low2, slo, shi, tables)
        self.rows = len(lo)

    def bounds(self, q: Quantity) -> tuple[FloatArray, FloatArray]:
        """Lower and upper bounds of ``q``'s certified value over the boxes (arrays over the
        boxes; at points both its value)."""
        low, high = self.outer.bounds(q)
        if self.point:
            return low, low
        high = np.array(high, dtype=np.float64)
        if self.inner is not None:
            high[self.sel] = np.minimum(high[self.sel], self.inner.bounds(q)[0])
        if self.shifted is not None:  # the least of the four shifted boxes' upper bounds
            k = self.rows
            up = np.broadcast_to(np.asarray(self.shifted.bounds(q)[1], np.float64), (4 * k,))
            high = np.minimum(high, up.reshape(len(_SHIFTS), k).min(axis=0))
        return low, high


def corners(problem: Problem, c1: Candidate, c2: Candidate, x: DesignPoints) -> list[DesignPoints]:
    """Four parts of the tolerance box T(x) of each point of ``x``: every layer's W at W -+ dW
    and alpha at alpha -+ da (both layers alike), on its sheet at E (1 - dE) and t (1 - dt)
    (per-point overrides, :class:`~.points.LayerPoints`), clipped as :func:`widened` clips.

    Each lies in T(x), so the point model's value of a quantity there is at least the
    certified value G(x), the lower bound over all of T(x) (module docstring): the least of
    them is an upper bound of G(x) at the cost of four nominal evaluations, which the branch
    and bound uses to skip the interval evaluation of points that cannot meet a bound or beat
    its incumbent (:meth:`corrugate.solver.bnb._Search._evaluate`)."""
    tol = problem.tolerances
    k = len(x)
    lows = (_low(c1, tol), _low(c2, tol))
    out = []
    for shift in _SHIFTS:
        moved = _shift(problem, x, *shift, (c1, c2))
        layers = [
            replace(lay, E=np.full(k, lows[i].material.E), t=np.full(k, float(lows[i].t)))
            for i, lay in enumerate(moved.layers)
        ]
        out.append(moved.with_layers(*layers))
    return out
