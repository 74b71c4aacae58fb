"""The certified search of a problem whose layers are independent, layer by layer.

When the two layers are independent (``layers = "independent"``) on a rectangle without holes and
without a bonded connector band, every quantity the solver bounds is a function of a few terms of
each layer (docs/theory.md sections 3-5; ``s``, ``c`` = sin, cos of alpha/2, p = W s, the extent
E = (n + 1) p, the depth h = W c and the blank B = (n + 1) W of each layer, its moduli Ecx, Ecy,
Ebx, Eby from the model's ``from_sc``):

* Lx = E1 and Ly = E2 (each one layer's own), the narrowest facet, t / W, the creases, the blank
  and the facet length L_j (each a max or min over the layers of one layer's term; a rectangle's
  facets of layer 1 are Ly long, those of layer 2 Lx);
* the folded thickness h1 + h2 (a sum of layer terms);
* the mass rho1 t1 B1 E2 + rho2 t2 B2 E1 + the band's (a function of E1, E2 and h1 + h2,
  increasing in each; :mod:`corrugate.mechanics.mass`);
* along the creases (eta 0 or 90, free sides or a frame: both give the paper's rule there,
  :mod:`corrugate.mechanics.offaxis`), with pq1 = E1 / E2 and pq2 = E2 / E1 (a rectangle's
  q = (n + 1) / S): K(0) = (t1 Ecy1 + t2 Ecx2) E1 / E2, D(0) = (t1^3 Eby1 + t2^3 Ebx2) / 12 x
  E1 / E2, EI(0) = D(0) Ly, and at 90 deg the same with the layers' roles exchanged (EI(90) =
  D(90) Lx). Each is (u_i + v_j) f_i g_j: a sum of a term of layer 1 and a term of layer 2,
  times positive factors of each.

So the search (:func:`search`) is:

1. per layer, the designs that meet the constraints of that layer alone: its extent range (the
   extent grows with n, so for each (W, alpha) of the grid only the n whose extent lies in the
   range are formed, computed directly rather than scanned), the narrowest facet, t / W, the
   creases, the blank and the facet length;
2. the pairs that may meet the coupled bounds: for each coupled bound (a stiffness bound
   (u_i + v_j) f_i g_j >= C, or the thickness h_i + h_j <= T) layer 2's designs sorted by
   their term (v, or h), so that the partners of a layer-1 design that can meet it are a prefix
   of that order (a necessary condition, with g at its largest); each layer-1 design is paired
   with the shortest of its prefixes;
3. on those pairs, every modelled bound by the formulas above (with a relative slack of
   :data:`SLACK` beyond the solver's own :data:`~.problem.FEAS_RTOL`, so rounding never drops a
   feasible pair), and a lower bound of the mass, low1_i + low2_j (each layer's blank over the
   least extent of the other layer's list, and the band at layer 1's own extent and depth with
   layer 2's least: the mass grows with each); of the pairs left, first only those whose lower bound is below the
   mass of the pair of least lower bound (the optimum is at most that if it proves feasible),
   and all of them if the answer is heavier than that; their mass by the formulas, below the
   incumbent (a layer-1 design whose lower bound with layer 2's least already reaches the
   incumbent forms no pair at all);
4. those pairs in order of their mass, in batches, evaluated exactly with
   :func:`~.quantities.point_values` (``evaluate``, the same values and the same feasibility rule,
   FEAS_RTOL, as the branch and bound), until the lightest exactly feasible pair is no heavier
   than the next pair's mass less the slack.

Certificate: every design of the grid is in a layer list that a constraint of its own layer
alone excludes, in a pair that a necessary condition excludes, in a pair whose modelled values
break a bound (or reach the incumbent) by more than the slack, or in a pair whose mass (or its
lower bound) is at least the answer's: the answer is the exact optimum over the grid (gap 0), as the branch and
bound's. The formulas are those of ``evaluate`` rearranged, equal to it to rounding (a few
units in the last place, far below the slack; the tests compare them with ``point_values``).
Problems of any other structure (identical layers, other layouts, holes, a connector band,
continuous variables, off-axis or other support conditions, load cases, buckling, an objective
other than the least mass), or whose layer lists or pairs to score are too many
(:data:`MAX_LAYER_DESIGNS`, :data:`MAX_PAIRS`), are left to the branch and bound (:func:`search`
returns None).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Hashable
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from corrugate.geometry.layouts import Rectangle, Square, length_sum
from corrugate.geometry.profile import ZigZag
from corrugate.mechanics.behaviours import get_support
from corrugate.mechanics.creases import creased_moduli, flexibility
from corrugate.mechanics.mass import connector_mass, layer_mass
from corrugate.mechanics.moduli import get_model
from corrugate.solver import tolerance_box
from corrugate.solver.points import DesignPoints, LayerPoints
from corrugate.solver.problem import FEAS_RTOL, Candidate, Constraint, Problem
from corrugate.solver.quantity import (
    CREASES,
    FACET,
    FLAT,
    LX,
    LY,
    MASS,
    PART_LONG,
    PART_SHORT,
    T_OVER_W,
    THICKNESS,
    W_MIN,
    Quantity,
)
from corrugate.solver.validity import LAYER_KINDS, layer_limits

__all__ = [
    "MAX_LAYER_DESIGNS",
    "MAX_PAIRS",
    "SLACK",
    "LayerDesigns",
    "SeparableResult",
    "applies",
    "layer_designs",
    "layer_key",
    "pair_floor",
    "pair_floors",
    "search",
    "stiffness_along",
]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]
#: Exact values of pairs: (mass in g, feasible) at the points (both layers' arrays).
Exact = Callable[[DesignPoints], tuple[FloatArray, NDArray[np.bool_]]]
#: Corners of the designs' tolerance boxes a search also bounds the stiffness at: (dW, dalpha)
#: each (:func:`~.tolerance_box.corner_shifts`).
Shifts = tuple[tuple[float, float], ...]

#: Relative slack beyond FEAS_RTOL with which the formulas judge a pair (rounding: far above the
#: few units in the last place by which they may differ from ``evaluate``).
SLACK = 1e-9
#: Past this many designs in a layer's list the branch and bound is used instead.
MAX_LAYER_DESIGNS = 200_000
#: Past this many pairs to score (step 2) the branch and bound is used instead.
MAX_PAIRS = 4_000_000
#: Pairs scored by the formulas at once (memory: a few arrays of this length).
CHUNK_PAIRS = 1_000_000
#: Pairs evaluated exactly in the first batch (then fourfold each batch).
FIRST_EXACT = 16
#: Quantities that are one layer's own, or that the pair stage leaves to the exact evaluation.
_LAYER_KINDS = {LX, LY, W_MIN, T_OVER_W, CREASES, FLAT, FACET}
_EXACT_ONLY = {PART_SHORT, PART_LONG}


@dataclass(frozen=True)
class SeparableResult:
    """The optimum over one sheet pair: its point (None: no design beats the incumbent, or none
    exists), mass (g), and how many pairs of layer designs were scored and evaluated exactly."""

    point: DesignPoints | None
    value: float
    layer_designs: tuple[int, int]
    scored: int
    evaluated: int


def _stiffness(q: Quantity) -> bool:
    """Whether ``q`` is a stiffness along the creases under the paper's rule (module docstring)."""
    return (
        q.kind in ("EI", "D", "K")
        and q.eta in (0.0, 90.0)
        and q.support is not None
        and get_support(q.support).crease_rule  # the paper's rule there (docs/theory.md 3.3)
        and q.test is None
        and q.span is None
    )


#: Whether a quantity is a stiffness along the creases under the paper's rule (module docstring).
stiffness_along = _stiffness


def applies(problem: Problem) -> bool:
    """Whether ``problem`` has the structure of the module docstring (else: branch and bound)."""
    lay = problem.layout
    if (
        problem.identical
        or not problem.profile_kind.is_default  # its formulas are the zig-zag's
        or not problem.gridded
        or type(lay) is not Rectangle
        or isinstance(lay, Square)
        or lay.holes
        or problem.joint != "none"
        or problem.objective.quantity != MASS
        or problem.objective.sense != "min"
        or not problem.tolerances.nominal  # its formulas are the nominal point model's
        or problem.calibrated  # the same: a calibrated sheet's intervals are bounded over
    ):
        return False
    for c in problem.constraints:
        q = c.quantity
        if q in _LAYER_KINDS or q in _EXACT_ONLY or q in (THICKNESS, MASS):
            continue
        if _stiffness(q) and c.sense == "min":
            continue
        if LAYER_KINDS.get(q.kind, ("",))[0] == c.sense:  # a validated range, layer by layer
            continue
        return False
    return True


@dataclass(frozen=True)
class _Layer:
    """One layer's designs that meet its own constraints: n, W (mm), alpha (deg), the extent E,
    depth h and blank B (mm), and the moduli (MPa); ``corners``: the same designs at each
    corner of their tolerance boxes asked for (:func:`layer_designs`' ``shifts``), n the same,
    W and alpha moved (the other fields at the moved geometry)."""

    n: FloatArray
    W: FloatArray
    a: FloatArray
    E: FloatArray
    h: FloatArray
    B: FloatArray
    Ecx: FloatArray
    Ecy: FloatArray
    Ebx: FloatArray
    Eby: FloatArray
    corners: tuple[_Layer, ...] = ()

    def __len__(self) -> int:
        return len(self.n)

    def take(self, idx: IntArray) -> _Layer:
        arrays = {f: getattr(self, f)[idx] for f in _ARRAYS}
        return _Layer(**arrays, corners=tuple(c.take(idx) for c in self.corners))

    def views(self) -> tuple[_Layer, ...]:
        """The designs as they are, then at each corner (:attr:`corners`)."""
        return (self, *self.corners)


_ARRAYS = ("n", "W", "a", "E", "h", "B", "Ecx", "Ecy", "Ebx", "Eby")


#: One layer's designs that meet its own constraints (step 1 of the module docstring).
LayerDesigns = _Layer


def _ok(c: Constraint, v: FloatArray, rtol: float) -> NDArray[np.bool_]:
    return c.satisfied(v, rtol=rtol)


def _layer(problem: Problem, cand: Candidate, which: int, shifts: Shifts = ()) -> _Layer | None:
    """Step 1 of the module docstring for layer ``which`` (1: its extent is Lx, 2: Ly), with
    the designs at each (dW, dalpha) of ``shifts`` (:attr:`_Layer.corners`); None if the list
    is longer than :data:`MAX_LAYER_DESIGNS`."""
    own = LX if which == 1 else LY
    W_2d, a_2d = np.meshgrid(problem.W.values(), problem.alpha.values(), indexing="ij")
    W_g: FloatArray = W_2d.reshape(-1)
    a_g: FloatArray = a_2d.reshape(-1)
    t = cand.t
    keep = np.ones(len(W_g), dtype=bool)
    n_lo, n_hi = float(problem.n_lo), float(problem.n_hi)
    lo_n = np.full(len(W_g), n_lo)
    hi_n = np.full(len(W_g), n_hi)
    for c in problem.constraints:
        q = c.quantity
        if q == W_MIN and c.sense == "min":
            keep &= _ok(c, W_g, FEAS_RTOL)
        elif q == T_OVER_W and c.sense == "max":
            keep &= _ok(c, t / W_g, FEAS_RTOL)
        elif q == CREASES and c.sense == "max":
            hi_n = np.minimum(hi_n, math.floor(c.bound * (1 + FEAS_RTOL) + 1e-9))
    limits = layer_limits(problem.constraints)  # the validated ranges (.validity)
    for variable, value in (("W", W_g), ("alpha", a_g), ("t_over_W", t / W_g)):
        if variable in limits:
            keep &= (value >= limits[variable][0]) & (value <= limits[variable][1])
    if "facets" in limits:
        f_lo, f_hi = limits["facets"]
        if math.isfinite(f_lo):
            lo_n = np.maximum(lo_n, math.ceil(f_lo - 1e-9) - 1.0)
        if math.isfinite(f_hi):
            hi_n = np.minimum(hi_n, math.floor(f_hi + 1e-9) - 1.0)
    # the extent (n + 1) p grows with n: the n range of each (W, alpha) from its bounds, one
    # value wider on each side, then checked exactly below with evaluate's arithmetic
    zz = ZigZag.of(W_g, a_g)  # the zig-zag's profile, as analysis.evaluate._layer_part
    p = zz.pitch
    for c in problem.constraints:
        if c.quantity == own or (c.quantity == FACET and c.sense == "max"):
            # FACET: the other layer's facets are this layer's extent long (a rectangle)
            b = c.bound
            if c.sense == "min":
                lo_n = np.maximum(lo_n, np.floor(b * (1 - 2 * FEAS_RTOL) / p) - 2.0)
            else:
                hi_n = np.minimum(hi_n, np.ceil(b * (1 + 2 * FEAS_RTOL) / p))
        elif c.quantity == FLAT and c.sense == "max":
            hi_n = np.minimum(hi_n, np.ceil(c.bound * (1 + 2 * FEAS_RTOL) / W_g))
    lo_n = np.maximum(lo_n, n_lo)
    count = np.where(keep, np.maximum(hi_n - lo_n + 1.0, 0.0), 0.0).astype(np.int64)
    total = int(count.sum())
    if total > MAX_LAYER_DESIGNS:
        return None
    g = np.repeat(np.arange(len(W_g)), count)
    n = lo_n[g] + (np.arange(total) - np.repeat(np.cumsum(count) - count, count))
    E = (n + 1.0) * p[g]
    B = (n + 1.0) * W_g[g]
    ok = np.ones(total, dtype=bool)
    for c in problem.constraints:
        q = c.quantity
        if q == own or (q == FACET and c.sense == "max"):
            ok &= _ok(c, E, FEAS_RTOL)
        elif q == FLAT and c.sense == "max":
            ok &= _ok(c, B, FEAS_RTOL)
        elif q == CREASES and c.sense == "max":
            ok &= _ok(c, n, FEAS_RTOL)
    idx = np.flatnonzero(ok)
    g, n, E, B = g[idx], n[idx], E[idx], B[idx]
    model = problem.model
    corners = []
    for dW, da in shifts:  # the same designs, W and alpha moved as tolerance_box moves them
        W_m, a_m = tolerance_box.moved(W_g, a_g, dW, da)
        corners.append(_at(model, cand, W_m, a_m, g, n, ZigZag.of(W_m, a_m)))
    return replace(_at(model, cand, W_g, a_g, g, n, zz), corners=tuple(corners))


def _at(
    model: str,
    cand: Candidate,
    W_g: FloatArray,
    a_g: FloatArray,
    g: IntArray,
    n: FloatArray,
    zz: ZigZag,
) -> _Layer:
    """The layer designs (grid value ``g`` of ``W_g``, ``a_g`` with ``n`` creases) on sheet
    ``cand`` under the moduli ``model``: extent, depth, blank and moduli as ``evaluate``
    computes them."""
    t = cand.t
    from_sc: Any = get_model(model).from_sc  # (scalar material, arrays of the grid)
    m = from_sc(float(cand.material.E), float(cand.material.nu), float(t), W_g, zz.s, zz.c)
    # compliant creases (rigid: m itself), as evaluate's profile_moduli puts them
    m = creased_moduli(m, flexibility(cand.material.crease_stiffness), float(t), W_g, zz.s, zz.c)

    def per(x: object) -> FloatArray:
        arr = np.asarray(x, dtype=np.float64)
        return np.asarray(np.broadcast_to(arr, W_g.shape)[g])

    E = (n + 1.0) * zz.pitch[g]
    B = (n + 1.0) * W_g[g]
    return _Layer(
        n, W_g[g], a_g[g], E, zz.height[g], B, per(m.Ecx), per(m.Ecy), per(m.Ebx), per(m.Eby)
    )


def layer_key(problem: Problem, cand: Candidate, which: int, shifts: Shifts = ()) -> Hashable:
    """Everything :func:`_layer` reads of its arguments (the grids, the n range, the model and
    profile, the sheet, the corners and the constraints of one layer alone): two calls with the
    same key return the same list."""
    own = LX if which == 1 else LY
    read = (W_MIN, T_OVER_W, CREASES, own, FACET, FLAT)
    cons = tuple(
        c for c in problem.constraints if c.quantity in read or c.quantity.kind in LAYER_KINDS
    )
    grid = (problem.W, problem.alpha, problem.n_lo, problem.n_hi)
    return (which, cand, shifts, problem.model, problem.profile_kind, grid, cons)


def layer_designs(
    problem: Problem, cand: Candidate, which: int, shifts: Shifts = ()
) -> LayerDesigns | None:
    """Step 1 of the module docstring for layer ``which`` (1 or 2) of sheet ``cand``, with the
    designs at each corner of ``shifts`` too; None if the list is longer than
    :data:`MAX_LAYER_DESIGNS`."""
    return _layer(problem, cand, which, shifts)


def pair_floor(
    problem: Problem, c1: Candidate, c2: Candidate, L1: LayerDesigns, L2: LayerDesigns
) -> float:
    """A lower bound (g) of the mass of every design of sheets (c1, c2) that meets the
    constraints (inf: none does), from the layer lists alone (:func:`layer_designs`), without
    pairing them: the least of each layer's mass bound of step 3 (its blank over the least
    extent of the other list, the band at the least of those) over the designs of that layer
    that may meet every coupled bound with the other list's terms at their largest (a
    stiffness (u_i + max v) f_i max g >= C for a layer-1 design i, (max u + v_j) max f g_j >= C
    for a layer-2 design j; the thickness h_i + min h2 <= T, h_i + max h2 >= T), inf when no
    design of a layer may. A necessary condition of :func:`search`'s pairs (its terms are
    positive), so never above its answer; problems of :func:`applies`."""
    if not len(L1) or not len(L2):
        return math.inf
    ok1, ok2 = _viable(problem, L1, L2, c1.t, c2.t)
    if not ok1.any() or not ok2.any():
        return math.inf
    lay, m1, m2 = problem.layout, c1.material, c2.material
    E1_min, E2_min, h2_min = float(L1.E.min()), float(L2.E.min()), float(L2.h.min())
    low1 = layer_mass(m1.density, c1.t, L1.W, length_sum(lay, L1.n, E2_min), lay)
    low1 = low1 + connector_mass(m1.density, c1.t, lay, L1.E, E2_min, L1.h + h2_min)
    low2 = layer_mass(m2.density, c2.t, L2.W, length_sum(lay, L2.n, E1_min), lay)
    return (float(np.min(low1[ok1])) + float(np.min(low2[ok2]))) * (1 - SLACK)


def _viable(
    problem: Problem, L1: _Layer, L2: _Layer, t1: float, t2: float
) -> tuple[NDArray[np.bool_], NDArray[np.bool_]]:
    """Per design of each list, whether it may meet every coupled bound with the other list's
    terms at their largest (:func:`pair_floor`), judged as :func:`search` judges pairs (the
    relative slack FEAS_RTOL + SLACK, and SLACK more on the side of keeping)."""
    loose = FEAS_RTOL + SLACK
    ok1, ok2 = np.ones(len(L1), dtype=bool), np.ones(len(L2), dtype=bool)
    for c in problem.constraints:
        q = c.quantity
        if _stiffness(q) and c.sense == "min":
            need = c.bound * (1 - loose)
            for V1, V2 in zip(L1.views(), L2.views(), strict=True):
                u, v, f, g = _terms(q, V1, V2, t1, t2)
                ok1 &= (u + float(v.max())) * f * float(g.max()) * (1 + SLACK) >= need
                ok2 &= (float(u.max()) + v) * float(f.max()) * g * (1 + SLACK) >= need
        elif q == THICKNESS and c.sense == "max":
            top = c.bound * (1 + loose) * (1 + SLACK)
            ok1 &= L1.h + float(L2.h.min()) <= top
            ok2 &= float(L1.h.min()) + L2.h <= top
        elif q == THICKNESS and c.sense == "min":
            least = c.bound * (1 - loose) * (1 - SLACK)
            ok1 &= L1.h + float(L2.h.max()) >= least
            ok2 &= float(L1.h.max()) + L2.h >= least
    return ok1, ok2


def pair_floors(
    problem: Problem,
    cands: tuple[Candidate, ...],
    firsts: list[LayerDesigns | None],
    seconds: list[LayerDesigns | None],
) -> FloatArray:
    """:func:`pair_floor` of every sheet pair (i, j) at once, as an N x N array: sheet i's
    layer-1 list ``firsts[i]`` with sheet j's layer-2 list ``seconds[j]`` (None: a list too
    long, floor 0), the same arithmetic broadcast over the partners' extremes."""
    N = len(cands)
    out = np.zeros((N, N))
    ok1 = np.array([L is not None for L in firsts])
    ok2 = np.array([L is not None for L in seconds])
    empty1 = np.array([L is not None and not len(L) for L in firsts])
    empty2 = np.array([L is not None and not len(L) for L in seconds])
    full1 = [i for i in range(N) if ok1[i] and not empty1[i]]
    full2 = [j for j in range(N) if ok2[j] and not empty2[j]]
    if full1 and full2:
        A: list[_Layer] = [L for i in full1 if (L := firsts[i]) is not None]
        B: list[_Layer] = [L for j in full2 if (L := seconds[j]) is not None]
        ok_a = [np.ones((len(L), len(B)), dtype=bool) for L in A]  # (:func:`_viable`)
        ok_b = [np.ones((len(L), len(A)), dtype=bool) for L in B]
        loose = FEAS_RTOL + SLACK
        h1 = np.array([[float(L.h.min()), float(L.h.max())] for L in A])
        h2 = np.array([[float(L.h.min()), float(L.h.max())] for L in B])
        for c in problem.constraints:
            q = c.quantity
            if _stiffness(q) and c.sense == "min":
                need = c.bound * (1 - loose)
                for view in range(len(A[0].views())):  # as they are, then at each corner
                    ta = [
                        _terms(q, L.views()[view], L.views()[view], cands[i].t, cands[i].t)
                        for L, i in zip(A, full1, strict=True)
                    ]
                    tb = [
                        _terms(q, L.views()[view], L.views()[view], cands[j].t, cands[j].t)
                        for L, j in zip(B, full2, strict=True)
                    ]
                    uf = np.array([[float(x[0].max()), float(x[2].max())] for x in ta])
                    vg = np.array([[float(x[1].max()), float(x[3].max())] for x in tb])
                    for r, terms in enumerate(ta):
                        u, f = terms[0][:, None], terms[2][:, None]
                        ok_a[r] &= (u + vg[None, :, 0]) * f * vg[None, :, 1] * (1 + SLACK) >= need
                    for col, terms in enumerate(tb):
                        v, g = terms[1][:, None], terms[3][:, None]
                        ok_b[col] &= (uf[None, :, 0] + v) * uf[None, :, 1] * g * (1 + SLACK) >= need
            elif q == THICKNESS and c.sense == "max":
                top = c.bound * (1 + loose) * (1 + SLACK)
                for r, L in enumerate(A):
                    ok_a[r] &= L.h[:, None] + h2[None, :, 0] <= top
                for col, L in enumerate(B):
                    ok_b[col] &= h1[None, :, 0] + L.h[:, None] <= top
            elif q == THICKNESS and c.sense == "min":
                least = c.bound * (1 - loose) * (1 - SLACK)
                for r, L in enumerate(A):
                    ok_a[r] &= L.h[:, None] + h2[None, :, 1] >= least
                for col, L in enumerate(B):
                    ok_b[col] &= h1[None, :, 1] + L.h[:, None] >= least
        lay = problem.layout
        E1_min = np.array([float(L.E.min()) for L in A])
        E2_min = np.array([float(L.E.min()) for L in B])
        low1 = np.empty((len(A), len(B)))
        for r, (L, i) in enumerate(zip(A, full1, strict=True)):
            m, t = cands[i].material, cands[i].t
            W, n = L.W[:, None], L.n[:, None]
            x = layer_mass(m.density, t, W, length_sum(lay, n, E2_min[None, :]), lay)
            x = np.asarray(x) + connector_mass(
                m.density,
                t,
                lay,
                L.E[:, None],
                E2_min[None, :],
                L.h[:, None] + h2[None, :, 0],
            )
            low1[r] = np.where(ok_a[r], x, math.inf).min(axis=0)
        low2 = np.empty((len(A), len(B)))
        for col, (L, j) in enumerate(zip(B, full2, strict=True)):
            m, t = cands[j].material, cands[j].t
            W, n = L.W[:, None], L.n[:, None]
            y = layer_mass(m.density, t, W, length_sum(lay, n, E1_min[None, :]), lay)
            low2[:, col] = np.where(ok_b[col], y, math.inf).min(axis=0)
        out[np.ix_(full1, full2)] = (low1 + low2) * (1 - SLACK)
    out[empty1 & ok1, :] = math.inf
    out[:, empty2 & ok2] = math.inf
    out[~ok1, :] = 0.0
    out[:, ~ok2] = 0.0
    return out


@dataclass(frozen=True)
class _Coupled:
    """A bound (u_i + v_j) f_i g_j >= bound (sense min) or h_i + h_j <= bound (thickness max):
    the per-layer terms of layer 1 (u, f) and layer 2 (v, g)."""

    constraint: Constraint
    u: FloatArray
    v: FloatArray
    f: FloatArray
    g: FloatArray


def _terms(q: Quantity, L1: _Layer, L2: _Layer, t1: float, t2: float) -> tuple[FloatArray, ...]:
    """(u, v, f, g) of a stiffness along the creases (module docstring)."""
    one1, one2 = np.ones(len(L1)), np.ones(len(L2))
    if q.eta == 0.0:
        if q.kind == "K":
            return t1 * L1.Ecy, t2 * L2.Ecx, L1.E, 1.0 / L2.E
        u, v = t1**3 / 12.0 * L1.Eby, t2**3 / 12.0 * L2.Ebx
        return (u, v, L1.E, 1.0 / L2.E) if q.kind == "D" else (u, v, L1.E, one2)
    if q.kind == "K":
        return t1 * L1.Ecx, t2 * L2.Ecy, 1.0 / L1.E, L2.E
    u, v = t1**3 / 12.0 * L1.Ebx, t2**3 / 12.0 * L2.Eby
    return (u, v, 1.0 / L1.E, L2.E) if q.kind == "D" else (u, v, one1, L2.E)


def _prefix_pairs(order: IntArray, counts: IntArray) -> tuple[IntArray, IntArray]:
    """Pairs (i, order[k]) for k < counts[i], as two index arrays."""
    total = int(counts.sum())
    i = np.repeat(np.arange(len(counts)), counts)
    k = np.arange(total) - np.repeat(np.cumsum(counts) - counts, counts)
    return i, order[k]


def _mass(
    problem: Problem, c1: Candidate, c2: Candidate, L1: _Layer, L2: _Layer, i: IntArray, j: IntArray
) -> FloatArray:
    """Mass (g) of the pairs: both layers' blanks and the band (``evaluate``'s terms)."""
    lay = problem.layout
    E1, E2 = L1.E[i], L2.E[j]
    m1, m2 = c1.material, c2.material
    mass = layer_mass(m1.density, c1.t, L1.W[i], length_sum(lay, L1.n[i], E2), lay)
    mass = mass + layer_mass(m2.density, c2.t, L2.W[j], length_sum(lay, L2.n[j], E1), lay)
    return np.asarray(mass + connector_mass(m1.density, c1.t, lay, E1, E2, L1.h[i] + L2.h[j]))


def search(
    problem: Problem,
    c1: Candidate,
    c2: Candidate,
    incumbent: float | None,
    exact: Exact,
    shifts: Shifts = (),
    lists: tuple[LayerDesigns | None, LayerDesigns | None] | None = None,
) -> SeparableResult | None:
    """The least-mass design over sheets (c1, c2), certified (module docstring), lighter than
    ``incumbent`` (g) if given; None when the problem lacks the structure (:func:`applies`) or
    its layer lists or pairs are too many. ``exact(x)`` returns the exact values and
    feasibility of the pairs ``x`` (:class:`~.points.DesignPoints`): ``(mass, feasible)``.
    ``shifts``: the corners (dW, dalpha) at which every stiffness bound must hold too (the
    layer designs moved there, :attr:`_Layer.corners`; ``exact`` judges the pairs there too):
    the search of a relaxation that bounds a certified stiffness by its value at those parts
    of the tolerance box (:mod:`.choices`). ``lists``: the two layer lists, already built by
    :func:`layer_designs` with these arguments."""
    if not applies(problem):
        return None
    if lists is not None:
        L1, L2 = lists
    else:
        L1 = _layer(problem, c1, 1, shifts)
        L2 = _layer(problem, c2, 2, shifts) if L1 is not None else None
    if L1 is None or L2 is None:
        return None
    sizes = (len(L1), len(L2))
    worst = math.inf if incumbent is None else incumbent * (1 + SLACK)
    loose = FEAS_RTOL + SLACK
    coupled: list[_Coupled] = []
    t_max = math.inf
    mass_max = math.inf
    for c in problem.constraints:
        q = c.quantity
        if _stiffness(q):  # as they are, then at each corner (``shifts``)
            for V1, V2 in zip(L1.views(), L2.views(), strict=True):
                coupled.append(_Coupled(c, *_terms(q, V1, V2, c1.t, c2.t)))
        elif q == THICKNESS and c.sense == "max":
            t_max = min(t_max, c.bound * (1 + loose))
        elif q == MASS and c.sense == "max":
            mass_max = min(mass_max, c.bound * (1 + loose))
    worst = min(worst, mass_max)
    empty = SeparableResult(None, math.nan, sizes, 0, 0)
    if not len(L1) or not len(L2):
        return empty
    # step 2: each layer-1 design's partners: a prefix of layer 2 sorted by one coupled term
    # (a necessary condition), the shortest of those the coupled bounds give
    orders: list[IntArray] = [np.arange(len(L2))]
    counts: list[IntArray] = [np.full(len(L1), len(L2), dtype=np.int64)]
    if math.isfinite(t_max):  # h1 + h2 <= t_max: layer 2 by rising h
        order = np.argsort(L2.h, kind="stable")
        orders.append(order)
        counts.append(np.searchsorted(L2.h[order], t_max - L1.h, side="right"))
    for k in coupled:
        # (u + v) f g >= C(1 - loose) needs v >= C(1 - loose) / (f g_max) - u: layer 2 by
        # falling v (a small relative widening against rounding)
        need = k.constraint.bound * (1 - loose) / (k.f * float(k.g.max()) * (1 + SLACK)) - k.u
        order = np.argsort(-k.v, kind="stable")
        orders.append(order)
        counts.append(np.searchsorted(-k.v[order], -need, side="right"))
    table = np.stack(counts)
    pick = np.argmin(table, axis=0)
    rows = table[pick, np.arange(len(L1))].astype(np.int64)
    if int(rows.sum()) > MAX_PAIRS:
        return None
    # a lower bound of each pair's mass, low1[i] + low2[j]: the mass grows with the partner's
    # extent and the thickness, so each layer's blank over the least extent of the other
    # layer's list, and the band at the least of those (module docstring)
    lay, m1, m2 = problem.layout, c1.material, c2.material
    E1_min, E2_min, h2_min = float(L1.E.min()), float(L2.E.min()), float(L2.h.min())
    low1 = layer_mass(m1.density, c1.t, L1.W, length_sum(lay, L1.n, E2_min), lay)
    low1 = low1 + connector_mass(m1.density, c1.t, lay, L1.E, E2_min, L1.h + h2_min)
    low2 = layer_mass(m2.density, c2.t, L2.W, length_sum(lay, L2.n, E1_min), lay)
    # step 3: the modelled values of the pairs, in chunks of layer-1 designs; a layer-1 design
    # whose lower bound with the least of layer 2's already reaches the incumbent forms no
    # pair (each of its pairs' lower bounds, below, would reach it: the same pairs are left;
    # they count as scored all the same)
    heavy = (low1 + float(low2.min())) * (1 - SLACK) >= worst
    evaluated = 0
    cand_i: list[IntArray] = []
    cand_j: list[IntArray] = []
    cand_m: list[FloatArray] = []
    scored = 0
    start = 0
    csum = np.cumsum(rows)
    while start < len(L1):
        base = 0 if start == 0 else int(csum[start - 1])
        stop = int(np.searchsorted(csum, base + CHUNK_PAIRS, side="right"))
        stop = max(stop, start + 1)
        scored += int(rows[start:stop].sum())
        parts_i, parts_j = [], []
        for o, order in enumerate(orders):
            mine = start + np.flatnonzero((pick[start:stop] == o) & ~heavy[start:stop])
            if len(mine):
                a, b = _prefix_pairs(order, rows[mine])
                parts_i.append(mine[a])
                parts_j.append(b)
        if not parts_i:
            start = stop
            continue
        i, j = np.concatenate(parts_i), np.concatenate(parts_j)
        if math.isfinite(t_max):
            sel = L1.h[i] + L2.h[j] <= t_max
            i, j = i[sel], j[sel]
        for k in coupled:
            val = (k.u[i] + k.v[j]) * k.f[i] * k.g[j]
            sel = val >= k.constraint.bound * (1 - loose)
            i, j = i[sel], j[sel]
        for c in problem.constraints:  # the thickness's minimum, if any
            if c.quantity == THICKNESS and c.sense == "min":
                sel = L1.h[i] + L2.h[j] >= c.bound * (1 - loose)
                i, j = i[sel], j[sel]
        lb = (low1[i] + low2[j]) * (1 - SLACK)
        sel = lb < worst
        cand_i.append(i[sel])
        cand_j.append(j[sel])
        cand_m.append(lb[sel])
        start = stop
    if not cand_i:
        return SeparableResult(None, math.nan, sizes, scored, 0)
    si, sj, slb = np.concatenate(cand_i), np.concatenate(cand_j), np.concatenate(cand_m)
    if not len(si):
        return SeparableResult(None, math.nan, sizes, scored, 0)
    # a first threshold: the mass of the pair of least lower bound (the optimum is at most that
    # if the pair proves feasible; else the search below is repeated without the threshold)
    first = int(np.argmin(slb))
    cap = float(_mass(problem, c1, c2, L1, L2, si[first : first + 1], sj[first : first + 1])[0])
    best, best_at = math.inf, -1
    ci, cj = si[:0], sj[:0]
    for threshold in (min(cap * (1 + SLACK), worst), worst):
        keep = slb < threshold
        ci, cj = si[keep], sj[keep]
        cm = _mass(problem, c1, c2, L1, L2, ci, cj)
        sel = cm < worst
        ci, cj, cm = ci[sel], cj[sel], cm[sel]
        best, best_at, n_exact = _lightest(L1, L2, ci, cj, cm, incumbent, exact)
        evaluated += n_exact
        if best <= threshold:  # every pair left out is at least as heavy
            break
    if best_at < 0:
        return SeparableResult(None, math.nan, sizes, scored, evaluated)
    one, two = int(ci[best_at]), int(cj[best_at])
    point = DesignPoints.of(
        LayerPoints(float(L1.n[one]), float(L1.W[one]), float(L1.a[one])),
        LayerPoints(float(L2.n[two]), float(L2.W[two]), float(L2.a[two])),
    )
    return SeparableResult(point, best, sizes, scored, evaluated)


def _lightest(
    L1: _Layer,
    L2: _Layer,
    ci: IntArray,
    cj: IntArray,
    cm: FloatArray,
    incumbent: float | None,
    exact: Exact,
) -> tuple[float, int, int]:
    """Step 4 of the module docstring over the pairs (ci, cj) of modelled masses cm (g): the
    lightest exactly feasible mass (inf: none), its index (-1: none) and the pairs evaluated."""
    best, best_at = math.inf, -1
    evaluated = 0
    batch = FIRST_EXACT
    remaining = np.arange(len(cm))
    while len(remaining):
        if len(remaining) > batch:
            part = np.argpartition(cm[remaining], batch)
            take, remaining = remaining[part[:batch]], remaining[part[batch:]]
        else:
            take, remaining = remaining, remaining[:0]
        x = DesignPoints.of(
            LayerPoints(L1.n[ci[take]], L1.W[ci[take]], L1.a[ci[take]]),
            LayerPoints(L2.n[cj[take]], L2.W[cj[take]], L2.a[cj[take]]),
        )
        mass, feasible = exact(x)
        evaluated += len(take)
        if incumbent is not None:
            feasible = feasible & (mass < incumbent)
        f = np.where(feasible, mass, np.inf)
        k = int(np.argmin(f))
        if f[k] < best:
            best = float(f[k])
            best_at = int(take[k])
        if len(remaining) and float(cm[remaining].min()) * (1 - SLACK) >= best:
            break  # every pair left is at least as heavy as the best
        batch *= 4
    return best, best_at, evaluated
