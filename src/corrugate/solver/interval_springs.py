"""A layer's springs over boxes in interval arithmetic, and the panel's span over boxes.

The bounds of every stiffness over a box of designs (docs/theory.md 3.2-3.3) start from each
layer's springs K_C, K_S, D_C, D_S (N/mm, N mm) and its shear and twisting springs, computed by
the moduli variant's own function (:mod:`corrugate.mechanics.moduli`; another profile than the
zig-zag: Xia's general theory, :func:`corrugate.mechanics.profiles.profile_moduli`, of the
problem's :class:`~corrugate.geometry.profile.ProfileKind`) in
:class:`~.interval.Interval` arithmetic over the box's W (mm) and alpha (deg), with the layout's
facet-length sums bounded over its n (:class:`~.tables.Tables`; with holes by
:func:`_hole_pq_bounds`). :func:`span_bounds` bounds the panel's length along a direction (mm).
"""

from __future__ import annotations

from dataclasses import dataclass, fields, replace

import numpy as np
from numpy.typing import ArrayLike, NDArray

from corrugate.geometry.layouts import Axis, Circle, Rectangle
from corrugate.mechanics.creases import flexibility
from corrugate.mechanics.offaxis import (
    facet_share,
    finite_panel_deficit,
    local_depth,
    shear_spring,
    shear_springs,
)
from corrugate.mechanics.profiles import profile_moduli
from corrugate.solver.interval import Interval, number
from corrugate.solver.problem import Candidate, Problem
from corrugate.solver.tables import RangeTable, Tables

__all__ = ["Springs", "layer_springs", "span_bounds"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class Springs:
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
    local: Interval  # the local term's length h sqrt(0.01 W / t) (mm; offaxis.local_depth)
    deficit: Interval  # finite-panel deficit (corrugate.mechanics.offaxis.finite_panel_deficit)
    facet: Interval  # one facet's share 1 / (n + 1) (corrugate.mechanics.offaxis.facet_share)


def layer_springs(
    problem: Problem,
    cand: Candidate,
    n: tuple[FloatArray, FloatArray],
    W: tuple[FloatArray, FloatArray],
    a: tuple[FloatArray, FloatArray],
    S: tuple[FloatArray, FloatArray],
    Q: RangeTable,
    tables: Tables,
    axis: str,
) -> Springs:
    """K_C, K_S, D_C, D_S (docs/theory.md 3.2) and the shear and twisting springs K_T, D_T
    (:func:`corrugate.mechanics.offaxis.shear_springs`, on the parallel sum) of a layer over a box, in
    interval arithmetic.

    Boxes repeated once per piece of the sheet's thickness (the worst-case tolerances' t cut in
    pieces, :class:`~.tolerance_box._Pieces`: ``pieces`` blocks of the same ``k`` boxes, t one
    interval per block) are evaluated once, their t as a (pieces x k) array against the k boxes
    (:func:`_period`): the geometry (the profile, the facet-length sums) then costs one block
    instead of all, and every spring, each operation elementwise, is the same floats."""
    k = _period(cand.t, (n, W, a, S))
    if k:
        t = cand.t
        assert isinstance(t, Interval)
        rows = t.lo.size
        block = replace(cand, t=Interval(t.lo.reshape(-1, k), t.hi.reshape(-1, k)))
        got = _layer_springs(problem, block, *(_first(p, k) for p in (n, W, a, S)), Q, tables, axis)
        return _rows(got, rows // k, k)
    return _layer_springs(problem, cand, n, W, a, S, Q, tables, axis)


def _period(t: object, pairs: tuple[tuple[FloatArray, FloatArray], ...]) -> int:
    """The k of boxes repeated in blocks (module docstring of :func:`layer_springs`): t an
    interval of one value per row that changes first at row k (its pieces of k rows each),
    and every array of ``pairs`` (each box's low and high n, W, alpha and extent) of those rows
    the same k values block after block; 0 when not (then nothing is shared)."""
    if not isinstance(t, Interval) or t.lo.ndim != 1 or t.lo.shape != t.hi.shape:
        return 0
    rows = t.lo.size
    k = int(np.argmax(t.lo != t.lo[0])) if rows else 0
    if k == 0 or rows % k:
        return 0
    for pair in pairs:
        for x in pair:
            if not (isinstance(x, np.ndarray) and x.shape == (rows,)):
                return 0
            if not np.array_equal(x.reshape(-1, k), np.broadcast_to(x[:k], (rows // k, k))):
                return 0
    return k


def _first(pair: tuple[FloatArray, FloatArray], k: int) -> tuple[FloatArray, FloatArray]:
    """The first k rows of a (low, high) pair of arrays."""
    return pair[0][:k], pair[1][:k]


def _rows(sp: Springs, pieces: int, k: int) -> Springs:
    """``sp`` of k boxes against t of (pieces x k) made one row per box and piece again,
    piece by piece (the rows' order in :class:`~.tolerance_box._Pieces`): each field broadcast
    to (pieces x k) and flattened."""

    def flat(v: Interval) -> Interval:
        lo = np.broadcast_to(v.lo, (pieces, k)).reshape(-1)
        hi = np.broadcast_to(v.hi, (pieces, k)).reshape(-1)
        return Interval._raw(lo, hi, v._nn)

    return Springs(*(flat(getattr(sp, f.name)) for f in fields(sp)))


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
) -> Springs:
    """:func:`layer_springs` of the boxes as given."""
    m = cand.material
    t = cand.t
    Wi = Interval(W[0], W[1])
    alpha = Interval(np.radians(a[0]), np.radians(a[1]))
    # the model functions are plain arithmetic, so they accept intervals (duck typing); sin and
    # cos of alpha/2 once, as evaluate does: the layer's profile over the box (the zig-zag's
    # closed forms, another profile's Xia general theory, corrugate.mechanics.profiles)
    kind = problem.profile_kind
    zz = kind.of_half(Wi, alpha * 0.5)
    # the creases' flexibility 1 / k (rad/N): 0.0 for rigid creases, an interval over a
    # calibrated k's (solver.tolerance_box.sheet)
    k = m.crease_stiffness
    flex = k.reciprocal() if isinstance(k, Interval) else flexibility(k)
    mod = profile_moduli(zz, number(m.E), float(m.nu), number(t), problem.model, flex)
    q_lo, q_hi = Q.bounds(n[0], n[1])  # Q(n) = S sum_j 1/L_j
    if problem.identical:  # p q = Q(n) / (n + 1) exactly (S = (n + 1) p)
        pq = Interval(q_lo / (n[1] + 1), q_hi / (n[0] + 1))
    else:
        pq = zz.pitch * Interval(q_lo, q_hi) / Interval(S[0], S[1])
    Ecx, Ecy, Ebx, Eby = (Interval.of(v) for v in (mod.Ecx, mod.Ecy, mod.Ebx, mod.Eby))
    t3 = t**3
    pq_par, pq_ser = pq, pq
    if problem.layout.holes:
        p_lo = np.asarray(kind.of_half(W[0], np.radians(a[0]) / 2).pitch)
        p_hi = np.asarray(kind.of_half(W[1], np.radians(a[1]) / 2).pitch)
        Fmin = tables.Fmin_x if axis == "x" else tables.Fmin_y  # built only with holes
        pq_par, pq_ser = _hole_pq_bounds(problem, n, (p_lo, p_hi), S, (q_lo, q_hi), Fmin, pq, axis)
    ratio = zz.plan_ratio  # pitch / developed: s = sin(alpha/2) for the zig-zag
    K_T, D_T = shear_springs(number(m.E), float(m.nu), number(t), ratio, pq_par)
    # c^2 / s falls as alpha grows: one interval each (c and s are monotone on the box)
    V_S = shear_spring(number(m.E), float(m.nu), number(t), ratio, zz.web2, pq_par)
    d_lo, d_hi = finite_panel_deficit(n[1]), finite_panel_deficit(n[0])  # falls with n
    f_lo, f_hi = facet_share(n[1]), facet_share(n[0])  # falls with n
    return Springs(
        Ecx * t / pq_ser,
        Ecy * t * pq_par,
        Ebx * (t3 / 12.0) / pq_ser,
        Eby * (t3 / 12.0) * pq_par,
        Interval.of(K_T),
        Interval.of(D_T),
        pq,
        Interval.of(V_S),
        zz.height,
        Interval.of(local_depth(zz.height, Wi, number(t))),
        Interval(d_lo, d_hi),
        Interval(np.nextafter(f_lo, 0.0), np.nextafter(f_hi, np.inf)),  # outward
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


def span_bounds(
    problem: Problem,
    Lx: tuple[FloatArray, FloatArray],
    Ly: tuple[FloatArray, FloatArray],
    eta_deg: float,
) -> Interval:
    """Bounds of the panel's length (mm) along ``eta_deg`` (deg) over boxes of extents Lx, Ly
    (mm; (low, high) arrays) (:mod:`~.quantities`, the span's argument)."""
    lay = problem.layout
    eta = np.asarray(eta_deg, dtype=np.float64)
    hi = np.asarray(lay.span(Lx[1], Ly[1], eta), dtype=np.float64)
    if isinstance(lay, Rectangle | Circle):  # monotone in Lx and Ly
        lo = np.asarray(lay.span(Lx[0], Ly[0], eta), dtype=np.float64)
        return Interval(np.nextafter(lo, 0.0), np.nextafter(hi, np.inf))
    e = np.radians(eta_deg)
    slack = 2.0 * (np.abs(np.sin(e)) * (Lx[1] - Lx[0]) + np.abs(np.cos(e)) * (Ly[1] - Ly[0]))
    return Interval(np.maximum(hi - slack, 0.0), hi + slack)
