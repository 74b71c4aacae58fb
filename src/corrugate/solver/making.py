"""What making the part asks of a design, as solver quantities (docs/fabrication.md, "What the
solve asks of the making").

* ``part_short`` and ``part_long`` (mm): over every cut part (layer 1's and layer 2's flat blanks,
  (n + 1) W by their longest facet L_j, and the band's longest segment with its overlap tab by
  t_d plus its two glue flanges), the largest shorter side and the largest longer side. A part
  fits a machine's usable area A x B (A <= B), turned 90 deg or not, exactly when its shorter
  side is at most A and its longer side at most B; so every part fits exactly when
  ``part_short`` <= A and ``part_long`` <= B.
* ``W_min`` (mm): the narrowest facet of the two layers; ``t_over_W``: the largest t / W;
  ``creases``: the most creases n of a layer.

Each is monotone in the box's corners (the blanks grow with n and W, the extents with n, W and
alpha, t_d with W and falling alpha), so its bounds over a box are its values at the corners;
min and max of bounds bound the min and max. The band's segment along a smooth outline (a
circle) is its perimeter over ceil(perimeter / segment_max) arcs, which is not monotone: it is
bounded by the perimeter at the low corner over the arc count at the high one, and by
min(perimeter, segment_max).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from corrugate.geometry.fabrication_options import DEFAULT_FABRICATION
from corrugate.geometry.profile import ZIGZAG, ProfileKind
from corrugate.solver.evaluator import Evaluator, register
from corrugate.solver.points import blank_width
from corrugate.solver.quantity import CREASES, PART_LONG, PART_SHORT, T_OVER_W, W_MIN, Quantity

if TYPE_CHECKING:
    from corrugate.geometry.layouts import Layout
    from corrugate.solver.context import AtPoints, OverBoxes
    from corrugate.solver.points import DesignPoints
    from corrugate.solver.problem import Candidate, Problem

__all__ = ["MAKING", "MAKINGS", "band_run", "making_bounds", "making_values"]

FloatArray = NDArray[np.float64]
Pair = tuple[FloatArray, FloatArray]

#: The quantities of this module.
MAKING: frozenset[Quantity] = frozenset({PART_SHORT, PART_LONG, W_MIN, T_OVER_W, CREASES})


def _runs(layout: Layout, Lx: Any, Ly: Any) -> tuple[FloatArray | None, FloatArray | None]:
    """The longest cornered run (mm) and the longest smooth run's whole length of ``layout`` at
    extents Lx, Ly (None where it has no run of that kind)."""
    cornered: FloatArray | None = None
    smooth: FloatArray | None = None
    for length, at_corner in layout.perimeter_runs(Lx, Ly):
        L = np.asarray(length, dtype=np.float64)
        if at_corner:
            cornered = L if cornered is None else np.maximum(cornered, L)
        else:
            smooth = L if smooth is None else np.maximum(smooth, L)
    return cornered, smooth


def _arcs(L: FloatArray) -> FloatArray:
    """How many equal arcs a smooth run of length L (mm) is cut into (at most segment_max each)."""
    return np.maximum(1.0, np.ceil(L / DEFAULT_FABRICATION.segment_max - 1e-9))


def _longest(cornered: FloatArray | None, smooth_arc: FloatArray | None) -> FloatArray:
    parts = [v for v in (cornered, smooth_arc) if v is not None]
    assert parts
    return parts[0] if len(parts) == 1 else np.maximum(parts[0], parts[1])


def band_run(layout: Layout, Lx: Any, Ly: Any) -> FloatArray:
    """The band's longest segment (mm) on ``layout`` of folded extents Lx, Ly (arrays), as
    :func:`corrugate.fabrication.band.band_parts` cuts it: the longest edge, or along a smooth
    outline its arc."""
    cornered, smooth = _runs(layout, Lx, Ly)
    return _longest(cornered, None if smooth is None else smooth / _arcs(smooth))


def _parts(
    blanks: tuple[Any, Any, Any, Any], band: tuple[Any, Any]
) -> tuple[FloatArray, FloatArray]:
    """(largest shorter side, largest longer side) of the parts: layer 1 (flat, facet), layer 2
    (flat, facet) and the band segment (length, height)."""
    f1, l1, f2, l2 = (np.asarray(v, dtype=np.float64) for v in blanks)
    b_len, b_h = (np.asarray(v, dtype=np.float64) for v in band)
    short = np.maximum.reduce([np.minimum(f1, l1), np.minimum(f2, l2), np.minimum(b_len, b_h)])
    long = np.maximum.reduce([np.maximum(f1, l1), np.maximum(f2, l2), np.maximum(b_len, b_h)])
    return short, long


def making_values(
    layout: Layout,
    c1: Candidate,
    c2: Candidate,
    x: DesignPoints,
    facet1: Any,
    facet2: Any,
    Lx: Any,
    Ly: Any,
    td: Any,
    kind: ProfileKind = ZIGZAG,
) -> dict[Quantity, FloatArray]:
    """The quantities of this module at the points ``x``: ``facet1`` and
    ``facet2`` the layers' longest facets (mm), ``Lx``, ``Ly`` the folded extents and ``td`` the
    folded thickness (mm); the blanks are those of the profile ``kind``
    (:func:`~.points.blank_width`)."""
    opts = DEFAULT_FABRICATION
    x1, x2 = x.layer(0), x.layer(1)
    n1, W1 = np.asarray(x1.n, np.float64), np.asarray(x1.W, np.float64)
    n2, W2 = np.asarray(x2.n, np.float64), np.asarray(x2.W, np.float64)
    band = (band_run(layout, Lx, Ly) + opts.overlap, np.asarray(td) + 2.0 * opts.tab_depth)
    blanks = blank_width(x1, kind), blank_width(x2, kind)
    short, long = _parts((blanks[0], facet1, blanks[1], facet2), band)
    return {
        PART_SHORT: short,
        PART_LONG: long,
        W_MIN: np.minimum(W1, W2),
        T_OVER_W: np.maximum(c1.t / W1, c2.t / W2),
        CREASES: np.maximum(n1, n2),
    }


def making_bounds(
    layout: Layout,
    c1: Candidate,
    c2: Candidate,
    lo: DesignPoints,
    hi: DesignPoints,
    facets: tuple[Pair, Pair],
    extents: tuple[Pair, Pair],
    td: Pair,
    kind: ProfileKind = ZIGZAG,
) -> dict[Quantity, Pair]:
    """Bounds of the quantities of this module over the boxes [lo, hi]: ``facets`` the (low,
    high) bounds of each layer's longest facet, ``extents`` those of Lx and Ly, ``td`` of the
    folded thickness (mm); module docstring for why the corners bound them."""
    opts = DEFAULT_FABRICATION
    (Lx_lo, Lx_hi), (Ly_lo, Ly_hi) = extents
    corner_lo, smooth_lo = _runs(layout, Lx_lo, Ly_lo)
    corner_hi, smooth_hi = _runs(layout, Lx_hi, Ly_hi)
    # a smooth run's arc: at least its low length over its high count, at most its high length
    # and segment_max (module docstring)
    run_lo = _longest(
        corner_lo, None if smooth_lo is None or smooth_hi is None else smooth_lo / _arcs(smooth_hi)
    )
    run_hi = _longest(
        corner_hi, None if smooth_hi is None else np.minimum(smooth_hi, opts.segment_max)
    )
    out: dict[Quantity, Pair] = {}
    sides = []
    for b, run, t_d, k in ((lo, run_lo, td[0], 0), (hi, run_hi, td[1], 1)):
        b1, b2 = b.layer(0), b.layer(1)
        band = (run + opts.overlap, np.asarray(t_d) + 2.0 * opts.tab_depth)
        blanks = blank_width(b1, kind), blank_width(b2, kind)
        sides.append(_parts((blanks[0], facets[0][k], blanks[1], facets[1][k]), band))
    out[PART_SHORT] = (sides[0][0], sides[1][0])
    out[PART_LONG] = (sides[0][1], sides[1][1])
    W1lo, W1hi = np.asarray(lo.layer(0).W, np.float64), np.asarray(hi.layer(0).W, np.float64)
    W2lo, W2hi = np.asarray(lo.layer(1).W, np.float64), np.asarray(hi.layer(1).W, np.float64)
    out[W_MIN] = (np.minimum(W1lo, W2lo), np.minimum(W1hi, W2hi))
    out[T_OVER_W] = (
        np.maximum(c1.t / W1hi, c2.t / W2hi),
        np.maximum(c1.t / W1lo, c2.t / W2lo),
    )
    n1lo, n1hi = np.asarray(lo.layer(0).n, np.float64), np.asarray(hi.layer(0).n, np.float64)
    n2lo, n2hi = np.asarray(lo.layer(1).n, np.float64), np.asarray(hi.layer(1).n, np.float64)
    out[CREASES] = (np.maximum(n1lo, n2lo), np.maximum(n1hi, n2hi))
    return out


def _making_at(at: AtPoints, q: Quantity) -> FloatArray:
    """The value of ``q`` at the points (the five quantities computed together, once)."""
    values = at.shared(
        "making",
        lambda: making_values(
            at.problem.layout,
            at.c1,
            at.c2,
            at.x,
            *at.facets,
            at.Lx,
            at.Ly,
            at.ev.thickness[:, 0],
            at.problem.profile_kind,
        ),
    )
    return values[q]


def _making_over(over: OverBoxes, q: Quantity) -> Pair:
    """The bounds of ``q`` over the boxes (the five computed together, once)."""
    bounds = over.shared(
        "making",
        lambda: making_bounds(
            over.problem.layout,
            over.c1,
            over.c2,
            over.lo,
            over.hi,
            over.facets,
            (over.Lx, over.Ly),
            over.thickness,
            over.problem.profile_kind,
        ),
    )
    return bounds[q]


def _making_reported(problem: Problem) -> frozenset[Quantity]:
    """All five once one is asked for."""
    return MAKING if MAKING.intersection(problem.quantities) else frozenset()


#: The evaluator of this module's quantities.
MAKINGS = register(
    Evaluator(tuple(sorted(q.kind for q in MAKING)), _making_at, _making_over, _making_reported)
)
