"""Certified search of a problem with continuous W and alpha on independent layers and material
choices, layer by layer over cells (docs/theory.md section 5).

:mod:`.separable` searches the grid points of each layer and pairs them; with continuous W and
alpha a layer has no points to list, but it has *cells*: one n, an interval of W (mm) and one of
alpha (deg). For a problem P of :func:`applies` (least mass, independent layers of the zig-zag on a
rectangle without holes or band, stiffness lower bounds along the creases under the paper's rule,
sizes and validated ranges per layer; any worst-case tolerances but a calibrated sheet), a pair of
cells (one per layer) is shown to hold no design of P (:func:`_judge`, :func:`_own_ok`) when

* a cell alone breaks a bound of its own layer (extent, facet length, blank, narrowest facet,
  t / W, creases, a validated range: each monotone in W, alpha and n, so bounded at the cell's
  corners) everywhere in it;
* the folded thickness h_i + h_j misses its range at the depths' bounds;
* a stiffness bound fails at an upper bound of its certified value G over the pair (G(x): the
  interval lower bound over the tolerance box T(x), :mod:`~.tolerance_box`): the point model at
  each corner of T(x) (W -+ dW, alpha -+ da, both layers alike, on the sheet at its low t and E;
  each corner lies in T(x), so G(x) is at most the model there), bounded above over the cells
  moved to that corner by the model's own interval arithmetic
  (:func:`corrugate.mechanics.profiles.profile_moduli` on :class:`~.interval.Interval` values,
  outward rounded) in :mod:`.separable`'s terms (u_i + v_j) f_i g_j; and, for cells at most
  2 dW x 2 da, the lower bound of G's own formula (:mod:`~.stiffness`: D(0) = D_S1 + D_C2,
  EI(0) = D(0) Ly, D(90) = D_C1 + D_S2, EI(90) = D(90) Lx, K likewise, the springs of
  :mod:`~.interval_springs` with pq = pitch Q(n) / S) over the cells' *inner boxes*
  [W_hi - dW, W_lo + dW] x [alpha_hi - da, alpha_lo + da] on the thinnest of t's pieces
  (:func:`_inner`, :func:`_inner_upper`): every T(x) of a design of the cell holds its inner box,
  and G(x) is the least over t's pieces, so by inclusion isotonicity G(x) is at most that bound;

and to hold none lighter than an incumbent when its mass lower bound reaches it: the mass (both
layers' blanks and the band, :func:`corrugate.mechanics.mass.layer_mass` and ``connector_mass``)
grows with each W, each extent and the depth, so its value at the cells' low corners bounds it.
Every quantity is judged with a relative slack :data:`SLACK` toward keeping (rounding).

:func:`search_pairs` puts the cell pairs of every sheet pair in one queue, starting from coarse
cells (:data:`FIRST_W` x :data:`FIRST_ALPHA` per n; of the pairs of the two layers' cells, those
the judge would not drop by a cell's bound or a mass floor alone, :func:`_first_pairs`), and
splits those of least mass bound first, :data:`BATCH` at a time (each pair's relatively wider cell
halved across its wider side, :func:`_split`; children judged as above, those of every sheet
pair in one pass, :func:`_judge_pairs`; a layer's cells shared by every sheet pair of its
sheet). Every few rounds it evaluates designs exactly with P's own certified values
(``point_values``, tolerances included, every constraint met with no slack: the branch and
bound's rule for continuous variables): designs drawn in the lightest pairs and anywhere
in the queue that the rule above does not exclude at the point itself, and designs around the best
one found; the best feasible one is the incumbent of every sheet pair. Past :data:`SEED_FROM`
first cell pairs with no incumbent, a design is sought before they are formed (:func:`_seed`) and
the best designs found are polished (:mod:`.polish`): both only lower the incumbent, with designs
P's own rule accepts, so nothing below depends on them. Each child pair lies in its
parent, so the pairs left always cover every design of P lighter than the incumbent. The search
stops when none is left below the incumbent less :data:`CELL_GAP` (relative) or at its budget;
then

* a sheet pair with no cell pair left holds no design lighter than the incumbent (pruned whole);
  its least mass bound left is a floor of its lightest design (:class:`~.choices.CellFloors`);
* the pairs left of a sheet pair, as boxes of the branch and bound's coordinates (n fixed per
  layer), are start boxes whose union holds every design of it lighter than the incumbent: its
  branch and bound from them with the incumbent has the answer and certificate of its search of
  the whole domain (:func:`~.solve._by_cells`);
* a constraint that never alone dropped a cell or a pair below the incumbent of the moment
  (*fired*) drops nothing the search of P without it would keep: that search's designs lighter than
  the incumbent lie in the same boxes (the binding check, :func:`~.solve._cell_binding`);
* a closed box of that branch and bound and the part of the domain the cells dropped make its
  archive (:class:`CellArchive`): boxes reopened from the search's rows, and from the cells of P
  without the constraints reopened (:func:`relaxed_without`) searched again below the bound asked,
  so the explanation reopens what it would reopen from an archive of the whole domain, never less.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from corrugate.geometry.layouts import Rectangle, Square, length_sum
from corrugate.geometry.profile import ZIGZAG
from corrugate.mechanics.creases import flexibility
from corrugate.mechanics.mass import connector_mass, layer_mass
from corrugate.mechanics.profiles import profile_moduli
from corrugate.solver import tolerance_box
from corrugate.solver.archive import Archive
from corrugate.solver.budget import current_budget
from corrugate.solver.interval import Interval, number
from corrugate.solver.points import DesignPoints, LayerPoints
from corrugate.solver.polish import CLIMB_MOST, climb
from corrugate.solver.problem import Candidate, Problem
from corrugate.solver.quantities import Tables, point_values
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
from corrugate.solver.separable import Shifts, stiffness_along
from corrugate.solver.validity import LAYER_KINDS, layer_limits

__all__ = ["BUDGET", "FIRST_ALPHA", "FIRST_W", "CellArchive", "CellResult", "search"]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]
#: The queue's cell indices (int32) and the sheet pairs (int16): 14 bytes a pair with its bound
Index = NDArray[np.signedinteger[Any]]

#: Relative slack toward keeping with which a cell pair is judged (rounding of the products).
#: What the judge computes in plain floating point (the interval model's values are rounded
#: outward) is products, quotients and sums of positive numbers and sines and cosines (the
#: extents, depths, blanks, band and mass; the terms (u_i + v_j) f_i g_j and the inner boxes'
#: sums; the band's flanges g (e - g) with g <= e / 2: no cancellation), some 40 operations of
#: at most one ulp (1.1e-16) each, so each value is within 1e-14 of its exact value, and P's own
#: rule computes the same quantities within as much: 1e-13 covers both with a factor 5. A
#: design infeasible by less than the slack keeps its cell pair, and such designs are lighter
#: than the optimum by up to about ten times the slack on films-13-cont (three constraints
#: active): at 1e-12 the search could not close below 1.0e-11 of the optimum.
SLACK = 1e-13
#: The first cells of each n: W's range cut in this many, alpha's in this many.
FIRST_W = 4
FIRST_ALPHA = 5
#: Cell pairs a search judges at most (about a microsecond each).
BUDGET = 20_000_000
#: The first cell pairs (every sheet pair's coarse cells, each layer's that meet its own bounds)
#: past which a search with no incumbent gives up at once, the domain too wide for the cells (the
#: caller takes the plain search): benchmarks/edges.py's films-5-cont has 0.81 M, films-13-cont
#: 5.5 M, tests/cli/test_interrupt.py's spec (8 sheets, n 1-200, W 1-30 mm, alpha 1-120 deg) 86 M,
#: whose cells judged them in 18.8 s of CPU without a design and left 32 M start boxes.
FIRST_MOST = 20_000_000
#: Cell pairs split at once (the least mass bounds first).
BATCH = 32768
#: ... and in a search with a polished incumbent (:data:`SEED_FROM`): every pair below it is
#: split anyway, so the order matters little and fewer rounds cost less (each round bounds the
#: new cells of every sheet's table in one call: films-13-cont's search 10.5 -> 6.6 s of CPU,
#: the same pairs judged, but films-5-cont, with no incumbent early, judged 3.5 -> 12.3 M).
WIDE_BATCH = 262144
#: The search stops when no cell pair left is below the incumbent less this (relative): the
#: branch and bound closes the rest from them.
CELL_GAP = 1e-10
#: ... and, asked a finer gap (``fine``), goes on toward it while at most this many pairs are
#: left (the cells stall about ten times :data:`SLACK` below the optimum, above: films-13-cont's
#: queue grew to 0.9 M pairs at 1.0e-11 with a slack of 1e-12), the branch and bound closing
#: fewer boxes after.
FINE_MOST = 100_000
#: The finer gap the solve asks (:func:`~.solve._by_cells`): films-13-cont's branch and bound
#: from the cells' boxes at 1e-10 closed 293 k boxes in 8.0 s, at 1e-11 76 k in 2.2 s, at 5e-12
#: 35 k in 0.8 s (40 k start boxes); at 3e-12 the cells stopped at this cap.
FINE_GAP = 5e-12
#: Rounds of splitting between two draws of designs to evaluate (:func:`_probe`).
PROBE_EVERY = 4
#: Pairs of one level judged at once (memory: a few arrays of this length).
CHUNK = 1_000_000
#: At each level: the cell pairs of least mass bound drawn in, the points drawn in each, and
#: the lightest of those the cells' rule keeps evaluated exactly (:func:`_probe`).
PROBE_PAIRS = 256
PROBE_POINTS = 4
PROBES = 64
#: Sheet pairs probed at once: those of the least mass bounds.
PROBE_SHEETS = 2
#: The first cell pairs past which a search with no incumbent seeks one before forming them
#: (:func:`_seed`), polishes the best designs it finds (:func:`~.polish.climb`) and probes
#: anywhere in the queue all along (else only until a first design): benchmarks/edges.py's
#: films-5-cont has 0.81 M first pairs, films-13-cont 5.5 M.
SEED_FROM = 2_000_000
#: Before the first cell pairs (:func:`_seed`): the points drawn in each layer's first cells,
#: the pairs of them judged per sheet pair, and the sheet pairs whose best design is polished
#: (films-13-cont: one climb from the lightest sheet pair's best design reaches the optimum's
#: incumbent, a second climb cost 0.8 s of CPU of its 5.2 s solve and lowered nothing; in one
#: process, the same optimum, its explained solve unchanged).
SEED_POINTS = 2048
SEED_PAIRS = 2048
SEED_CLIMBS = 1
#: The polishes of each of those climbs at most.
SEED_CLIMB = 30
#: The (sheet pair, n1, n2) polished at most in the search (:func:`~.polish.climb`).
POLISHES = 8
#: Sheet pairs probed at once anywhere in the queue.
PROBE_FAR = 2
#: Designs drawn around the best one at each probe, and their first reach (relative to the
#: variables' ranges; halved when none is lighter).
MOVES = 64
MOVE_SCALE = 0.02
_LAYER = {LX, LY, W_MIN, T_OVER_W, CREASES, FLAT, FACET}
_IGNORED = {PART_SHORT, PART_LONG}  # left to the branch and bound (a relaxation drops them)


def applies(problem: Problem) -> bool:
    """Whether ``problem`` has the structure of the module docstring: :mod:`.separable`'s
    (independent layers of the zig-zag on a rectangle without holes or band, least mass,
    nominal tolerances, no calibrated sheet, lower bounds of stiffness along the creases under
    the paper's rule, sizes and validated ranges per layer) with W and alpha both continuous."""
    lay = problem.layout
    if (
        problem.identical
        or not problem.profile_kind.is_default
        or problem.W.gridded
        or problem.alpha.gridded
        or type(lay) is not Rectangle
        or isinstance(lay, Square)
        or lay.holes
        or problem.joint != "none"
        or problem.objective.quantity != MASS
        or problem.objective.sense != "min"
        or problem.calibrated
    ):
        return False
    for c in problem.constraints:
        q = c.quantity
        if q in _LAYER or q in _IGNORED or q in (THICKNESS, MASS):
            continue
        if stiffness_along(q) and c.sense == "min":
            continue
        if LAYER_KINDS.get(q.kind, ("",))[0] == c.sense:
            continue
        return False
    return True


def _extent(n: FloatArray, W: FloatArray, a: FloatArray) -> FloatArray:
    """The zig-zag's extent (n + 1) W sin(alpha / 2) (mm), as ``evaluate`` computes it."""
    return np.asarray(ZIGZAG.of(W, a).extent(n), dtype=np.float64)


def _depth(W: FloatArray, a: FloatArray) -> FloatArray:
    """The zig-zag's depth W cos(alpha / 2) (mm)."""
    return np.asarray(ZIGZAG.of(W, a).height, dtype=np.float64)


def _own_ok(
    problem: Problem,
    cand: Candidate,
    which: int,
    n: FloatArray,
    W0: FloatArray,
    W1: FloatArray,
    a0: FloatArray,
    a1: FloatArray,
) -> tuple[NDArray[np.bool_], FloatArray, FloatArray]:
    """Per cell and constraint (cells x constraints), whether the constraint, one of the
    cell's own layer (extent, facet length, blank, narrowest facet, t / W, creases, validated
    ranges: each a monotone function of W, alpha and n, bounded at the cell's corners), is
    broken everywhere in the cell; and the extents' bounds (mm)."""
    own = LX if which == 1 else LY
    t = cand.t
    E0, E1 = _extent(n, W0, a0), _extent(n, W1, a1)
    up, down = 1 + SLACK, 1 - SLACK
    fails = np.zeros((len(n), len(problem.constraints)), dtype=bool)
    for k, c in enumerate(problem.constraints):
        q, b = c.quantity, c.bound
        ok: Any = True
        if q == W_MIN and c.sense == "min":
            ok = W1 * up >= b
        elif q == T_OVER_W and c.sense == "max":
            ok = t / W1 * down <= b
        elif q == T_OVER_W and c.sense == "min":
            ok = t / W0 * up >= b
        elif q == CREASES and c.sense == "max":
            ok = n <= b * up
        elif q == own:
            ok = E1 * up >= b if c.sense == "min" else E0 * down <= b
        elif q == FACET and c.sense == "max":
            ok = E0 * down <= b
        elif q == FLAT and c.sense == "max":
            ok = (n + 1.0) * W0 * down <= b
        elif LAYER_KINDS.get(q.kind, ("",))[0] == c.sense:  # a validated range
            lim = layer_limits((c,))
            for name, lo_v, hi_v in (
                ("W", W0, W1),
                ("alpha", a0, a1),
                ("t_over_W", t / W1, t / W0),
            ):
                if name in lim:
                    lo, hi = lim[name]
                    ok = ok & (hi_v * up >= lo) & (lo_v * down <= hi)
            if "facets" in lim:
                lo, hi = lim["facets"]
                ok = ok & (n + 1.0 >= lo * down) & (n + 1.0 <= hi * up)
        fails[:, k] = ~np.asarray(ok, dtype=bool)
    return fails, E0, E1


@dataclass(frozen=True)
class _Cells:
    """One layer's cells (n, W in [W0, W1] mm, alpha in [a0, a1] deg): the extent's and the
    depth's bounds (mm); per view (the cells as they are, then moved to each corner of the
    tolerance box, on the sheet at its low t and E) the upper bounds of the moduli (MPa) and
    the extent's bounds there; and over the cells' inner boxes (:func:`_inner`), per piece of
    the thickness, the lower bounds of the springs' layer factors (inf where a cell has no
    inner box) and the inner box's extent bounds."""

    n: FloatArray
    W0: FloatArray
    W1: FloatArray
    a0: FloatArray
    a1: FloatArray
    E0: FloatArray
    E1: FloatArray
    h0: FloatArray
    h1: FloatArray
    views: tuple[tuple[FloatArray, ...], ...]  # (Ecx, Ecy, Ebx, Eby, E0, E1) per view
    inner: tuple[FloatArray, ...]  # (S_D, C_D, S_K, C_K): 1 x cells; then iE0, iE1

    def __len__(self) -> int:
        return len(self.n)


_FIELDS = ("n", "W0", "W1", "a0", "a1", "E0", "E1", "h0", "h1")


@dataclass(frozen=True)
class Setting:
    """What the cells of a problem read: the problem P, its tables, each layer's sheet (the
    nominal one: sizes, mass, t / W) and the sheet of its views (low t and E under
    tolerances), the views' shifts (dW, dalpha; (0, 0) first), and under tolerances the half
    widths (dW, dalpha) and the sheets' E interval and t's pieces (:func:`~.tolerance_box.sheet`)."""

    problem: Problem
    tables: Tables
    sheets: tuple[Candidate, Candidate]
    low: tuple[Candidate, Candidate]
    shifts: Shifts
    halves: tuple[float, float] | None


def setting(problem: Problem, c1: Candidate, c2: Candidate, tables: Tables) -> Setting:
    """The :class:`Setting` of ``problem`` on sheets (c1, c2)."""
    tol = problem.tolerances
    if tol.nominal:
        return Setting(problem, tables, (c1, c2), (c1, c2), ((0.0, 0.0),), None)
    low = (tolerance_box.low_sheet(c1, tol), tolerance_box.low_sheet(c2, tol))
    shifts = ((0.0, 0.0), *tolerance_box.corner_shifts(tol))
    return Setting(problem, tables, (c1, c2), low, shifts, tolerance_box.half_widths(problem))


def _inner(
    st: Setting,
    which: int,
    n: FloatArray,
    W0: FloatArray,
    W1: FloatArray,
    a0: FloatArray,
    a1: FloatArray,
) -> tuple[FloatArray, ...]:
    """Over each cell's inner box [W1 - dW, W0 + dW] x [a1 - da, a0 + da] (a cell at most
    2 dW and 2 da wide; every tolerance box of a design of the cell holds it,
    :mod:`~.tolerance_box`), on t's thinnest piece (the sheet's E interval, t's first piece as
    :class:`~.tolerance_box.ToleranceBounds` cuts them), the lower bounds of the layer factors
    of its springs (:mod:`~.interval_springs`, no holes: pq = pitch Q(n) / S with S the other
    layer's extent): S_D = Eby t^3 / 12 pitch Q and C_D = Ebx t^3 / 12 / (pitch Q) (D_S =
    S_D / S, D_C = C_D S), S_K = Ecy t pitch Q and C_K = Ecx t / (pitch Q) (K_S, K_C
    likewise), inf where the cell has no inner box; and the inner box's extent bounds (mm)."""
    p = st.problem
    k = len(n)
    full = tolerance_box.T_PIECES if p.tolerances.t else 1
    pieces = 1  # t's thinnest piece only
    inf = np.full((pieces, k), math.inf)
    if st.halves is None or not k:
        return inf, inf, inf, inf, n * 0.0, n * 0.0 + math.inf
    dW, da = st.halves
    has = (2 * dW >= W1 - W0) & (a1 - a0 <= 2 * da)
    iW0, ia0 = tolerance_box.moved(W1, a1, -dW, -da)
    iW1, ia1 = tolerance_box.moved(W0, a0, dW, da)
    iW1, ia1 = np.maximum(iW1, iW0), np.maximum(ia1, ia0)
    iE0, iE1 = _extent(n, iW0, ia0), _extent(n, iW1, ia1)
    sel = np.flatnonzero(has)
    out = [inf.copy() for _ in range(4)]
    if len(sel):
        cand = st.sheets[which - 1]
        sh = tolerance_box.sheet(cand, p.tolerances, full, len(sel))
        if isinstance(sh.t, Interval) and np.ndim(sh.t.lo):  # the first piece's rows
            sh = replace(
                sh, t=Interval(np.asarray(sh.t.lo)[: len(sel)], np.asarray(sh.t.hi)[: len(sel)])
            )
        m = sh.material
        rep = sel
        zz = p.profile_kind.of_half(
            Interval(iW0[rep], iW1[rep]), Interval(np.radians(ia0[rep]), np.radians(ia1[rep])) * 0.5
        )
        flex = flexibility(cand.material.crease_stiffness)
        mod = profile_moduli(zz, number(m.E), float(m.nu), number(sh.t), p.model, flex)
        Q = st.tables.Qx if which == 1 else st.tables.Qy
        q_lo, q_hi = Q.bounds(n[rep], n[rep])
        pitch = Interval.of(zz.pitch)
        t = Interval.of(sh.t)
        t3 = t**3
        pq_lo = np.asarray(pitch.lo) * q_lo
        pq_hi = np.asarray(pitch.hi) * q_hi
        vals = (
            Interval.of(mod.Eby * (t3 / 12.0)).lo * pq_lo,
            Interval.of(mod.Ebx * (t3 / 12.0)).lo / pq_hi,
            Interval.of(mod.Ecy * t).lo * pq_lo,
            Interval.of(mod.Ecx * t).lo / pq_hi,
        )
        for o, v in zip(out, vals, strict=True):
            o[:, sel] = np.broadcast_to(np.asarray(v, np.float64), rep.shape).reshape(pieces, -1)
    return (*out, iE0, iE1)


def _cells(
    st: Setting,
    which: int,
    n: FloatArray,
    W0: FloatArray,
    W1: FloatArray,
    a0: FloatArray,
    a1: FloatArray,
    fired: tuple[set[int], float] | None = None,
) -> tuple[_Cells, IntArray]:
    """The cells (n, [W0, W1], [a0, a1]) of layer ``which`` that may meet their own layer's
    bounds, with their bounds (:class:`_Cells`), and their indices. ``fired`` = (a set, a
    mass in g): the constraints that alone drop a cell whose designs' mass is not shown to
    reach that mass (a lower bound with the other layer at its lightest) are added to the set
    (by index)."""
    problem = st.problem
    fails, E0, E1 = _own_ok(problem, st.sheets[which - 1], which, n, W0, W1, a0, a1)
    idx = np.flatnonzero(~fails.any(axis=1))
    alone = np.flatnonzero(fails.sum(axis=1) == 1)
    if len(alone) and fired is not None:  # a cell only its one bound drops, light enough
        other = st.problem.W.lo, st.problem.alpha.lo, float(st.problem.n_lo)
        c_own = st.sheets[which - 1]  # its blank alone bounds the mass below
        lay = problem.layout
        E_other = float(
            _extent(np.array([other[2]]), np.array([other[0]]), np.array([other[1]]))[0]
        )
        theirs = LY if which == 1 else LX  # the other layer's extent, at least its own least
        for c in problem.constraints:
            if c.quantity == theirs and c.sense == "min":
                E_other = max(E_other, c.bound * (1 - SLACK))
        lb = layer_mass(
            c_own.material.density, c_own.t, W0[alone], length_sum(lay, n[alone], E_other), lay
        )
        light = np.asarray(lb) * (1 - SLACK) < fired[1]
        for k in np.flatnonzero(fails[alone[light]].any(axis=0)):
            fired[0].add(int(k))
    n, W0, W1, a0, a1, E0, E1 = (x[idx] for x in (n, W0, W1, a0, a1, E0, E1))
    cand = st.low[which - 1]
    m = cand.material
    flex = flexibility(m.crease_stiffness)
    kind = problem.profile_kind
    # every view's cells moved at once (one call of the elementwise interval model for all
    # the shifts: the same values as one call per shift, at one call's fixed cost)
    moved = [
        (*tolerance_box.moved(W0, a0, dW, da), *tolerance_box.moved(W1, a1, dW, da))
        for dW, da in st.shifts
    ]
    mW0, ma0, mW1, ma1 = (np.concatenate([v[c] for v in moved]) for c in range(4))
    nn = np.tile(n, len(moved))
    Wi = Interval(mW0, mW1)
    half = Interval(np.radians(ma0), np.radians(ma1)) * 0.5
    mod = profile_moduli(
        kind.of_half(Wi, half), float(m.E), float(m.nu), float(cand.t), problem.model, flex
    )
    his = [
        np.broadcast_to(np.asarray(Interval.of(v).hi, np.float64), nn.shape)
        for v in (mod.Ecx, mod.Ecy, mod.Ebx, mod.Eby)
    ]
    lows, highs = _extent(nn, mW0, ma0), _extent(nn, mW1, ma1)
    size = len(n)
    views = [
        tuple(x[v * size : (v + 1) * size].copy() for x in (*his, lows, highs))
        for v in range(len(moved))
    ]
    h0, h1 = _depth(W0, a1), _depth(W1, a0)
    inner = _inner(st, which, n, W0, W1, a0, a1)
    return _Cells(n, W0, W1, a0, a1, E0, E1, h0, h1, tuple(views), inner), idx


def _terms(
    q: Quantity, v1: tuple[FloatArray, ...], v2: tuple[FloatArray, ...], t1: float, t2: float
) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """Upper bounds of (u, v, f, g) of a stiffness along the creases (:mod:`.separable`'s
    terms) over layer 1's cells (view ``v1``) and layer 2's (``v2``)."""
    s1, s2 = (t1, t1**3 / 12.0), (t2, t2**3 / 12.0)
    return _terms_of(q, v1, v2, s1, s2, len(v1[4]), len(v2[4]))


def _terms_of(
    q: Quantity,
    v1: Sequence[FloatArray],
    v2: Sequence[FloatArray],
    s1: tuple[Any, Any],
    s2: tuple[Any, Any],
    n1: int,
    n2: int,
) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """:func:`_terms` with each layer's sheet given as (t, t^3 / 12) (mm, mm^3; floats, or one
    per cell, each computed as a float) and its number of cells: the same products in the same
    order, reading of each view (Ecx, Ecy, Ebx, Eby, E0, E1) only what ``q`` uses."""
    (t1, d1), (t2, d2) = s1, s2
    if q.eta == 0.0:
        if q.kind == "K":
            return t1 * v1[1], t2 * v2[0], v1[5], 1.0 / v2[4]
        u, v = d1 * v1[3], d2 * v2[2]
        return (u, v, v1[5], 1.0 / v2[4]) if q.kind == "D" else (u, v, v1[5], np.ones(n2))
    if q.kind == "K":
        return t1 * v1[0], t2 * v2[1], 1.0 / v1[4], v2[5]
    u, v = d1 * v1[2], d2 * v2[3]
    return (u, v, 1.0 / v1[4], v2[5]) if q.kind == "D" else (u, v, np.ones(n1), v2[5])


def _inner_upper(q: Quantity, L1: _Cells, L2: _Cells, i: Index, j: Index) -> FloatArray:
    """An upper bound of the certified value of stiffness ``q`` (along the creases, free
    sides) over the cell pairs (i, j): its lower bound over the inner boxes on t's thinnest
    piece (the certified value is the least over the pieces), as :mod:`~.stiffness` computes it there (D(0) = D_S1 + D_C2, EI(0) = D(0)
    Ly, D(90) = D_C1 + D_S2, EI(90) = D(90) Lx, K likewise), which every design's certified
    value is at most (inclusion isotonicity); inf where a cell has no inner box."""
    k = 2 if q.kind == "K" else 0
    return _inner_upper_of(
        q,
        (L1.inner[k][:, i], L1.inner[k + 1][:, i], L1.inner[4][i], L1.inner[5][i]),
        (L2.inner[k][:, j], L2.inner[k + 1][:, j], L2.inner[4][j], L2.inner[5][j]),
    )


def _inner_upper_of(
    q: Quantity, one: tuple[FloatArray, ...], two: tuple[FloatArray, ...]
) -> FloatArray:
    """:func:`_inner_upper` from each layer's cells of the pairs, in the pairs' order: the
    factors (S, C) of ``q``'s kind (pieces x pairs) and the inner box's extent bounds."""
    S1, C1, Lx0, Lx1 = one
    S2, C2, Ly0, Ly1 = two
    with np.errstate(invalid="ignore"):
        if q.eta == 0.0:
            v = S1 / Ly1 + C2 * Lx0
            if q.kind == "EI":
                v = v * Ly0
        else:
            v = C1 * Ly0 + S2 / Lx1
            if q.kind == "EI":
                v = v * Lx0
    return np.asarray(np.where(np.isnan(v), math.inf, v).min(axis=0), dtype=np.float64)


@dataclass(frozen=True)
class CellResult:
    """The cells' search of one sheet pair: the floor (g; inf: no design lighter than the
    incumbent), the start boxes (lo, hi, mass lower bound; the branch and bound's coordinates),
    the best design of P found at the cells' centres (None: none better than the incumbent
    given) and its mass (g), the cell pairs judged."""

    floor: float
    start: tuple[FloatArray, FloatArray, FloatArray]
    point: DesignPoints | None
    value: float
    judged: int
    #: False when the search gave up at once (:data:`FIRST_MOST`): no start boxes, not searched
    settled: bool = True


class _Gather:
    """One layer's cells of cell pairs judged together, each pair's from its own table:
    ``of(f)`` is f(table's cells)[index] per pair, in the pairs' order (one fancy index per
    table the pairs use)."""

    def __init__(self, tables: Sequence[_Cells], tid: IntArray, ids: Index) -> None:
        self.tables, self.tid, self.ids = tables, tid, ids
        self.parts: list[tuple[_Cells, IntArray | None, Index]] = []
        if len(tid) and (len(tid) == 1 or bool(np.all(tid == tid[0]))):  # one table
            self.parts.append((tables[int(tid[0])], None, ids))
        elif len(tid):
            for t in np.unique(tid).tolist():
                pos = np.flatnonzero(tid == t)
                self.parts.append((tables[t], pos, ids[pos]))

    def of(self, f: Callable[[_Cells], FloatArray]) -> FloatArray:
        """f of each pair's cell (f: a 1-D array over a table's cells)."""
        if len(self.parts) == 1 and self.parts[0][1] is None:
            L, _, ids = self.parts[0]
            return f(L)[ids]
        out = np.empty(len(self.ids))  # none (no pair) or several tables
        for L, pos, ids in self.parts:
            out[pos] = f(L)[ids]
        return out

    def field(self, name: str) -> FloatArray:
        """The pairs' cells' field ``name`` of :class:`_Cells` (a 1-D one: n, W0, E0, h0, ...)."""
        return self.of(lambda L: getattr(L, name))

    def sub(self, sel: IntArray) -> _Gather:
        """The pairs ``sel`` (positions) only."""
        if len(self.parts) == 1 and self.parts[0][1] is None and len(sel):
            out = _Gather(self.tables, self.tid[:0], self.ids[:0])
            out.tid, out.ids = self.tid[sel], self.ids[sel]
            out.parts = [(self.parts[0][0], None, out.ids)]
            return out
        return _Gather(self.tables, self.tid[sel], self.ids[sel])


def _inner_of(g: _Gather, at: int) -> tuple[FloatArray, ...]:
    """The pairs' inner-box factors (S, C) of the kind at ``at`` of :class:`_Cells` inner (0:
    D and EI, 2: K; 1 x pairs) and the inner box's extent bounds, for :func:`_inner_upper_of`."""
    return (
        g.of(lambda L: L.inner[at][0])[None, :],
        g.of(lambda L: L.inner[at + 1][0])[None, :],
        g.of(lambda L: L.inner[4]),
        g.of(lambda L: L.inner[5]),
    )


class _View(Sequence[FloatArray]):
    """View ``v`` of the pairs' cells of one layer (:class:`_Cells` views: Ecx, Ecy, Ebx, Eby,
    E0, E1), each array gathered the first time it is read."""

    def __init__(self, g: _Gather, v: int) -> None:
        self.g, self.v = g, v
        self.got: dict[int, FloatArray] = {}

    def __getitem__(self, x: Any) -> Any:
        if x not in self.got:
            self.got[x] = self.g.of(lambda L: L.views[self.v][x])
        return self.got[x]

    def __len__(self) -> int:
        return 6


def _judge(
    st: Setting,
    L1: _Cells,
    L2: _Cells,
    I: Index,
    J: Index,
    worst: float,
    fired: set[int] | None = None,
) -> tuple[Index, Index, FloatArray]:
    """The cell pairs (I, J) that may hold a design of the problem lighter than ``worst`` (g)
    (module docstring), and their mass lower bounds (g), judged in chunks. ``fired``: the
    constraints (by index) that alone drop a pair lighter than ``worst`` are added to it."""
    tab = np.array([[0, 1]], dtype=np.int64)
    K = np.zeros(len(I), dtype=np.int16)
    _, i, j, lb = _judge_pairs([st], [L1, L2], tab, K, I, J, worst, fired)
    return i, j, lb


#: Cell pairs of one sheet pair past which :func:`_judge_pairs` judges them apart (each
#: table's arrays read directly), fewer with those of the sheet pairs next to them (one pass
#: instead of one per sheet pair: films-13-cont's explained solve judged one sheet pair at a
#: time in 7211 passes, 5095 of fewer than 100 pairs, which took 0.28 ms each).
ALONE = 4096


def _judge_pairs(
    settings: Sequence[Setting],
    tables: Sequence[_Cells],
    tab_of: IntArray,
    K: Index,
    I: Index,
    J: Index,
    worst: float,
    fired: set[int] | None = None,
) -> tuple[Index, Index, Index, FloatArray]:
    """:func:`_judge` of the cell pairs (I, J) of the sheet pairs K (``settings[k]``, one
    problem; its layer 1's cells ``tables[tab_of[k, 0]]``, its layer 2's
    ``tables[tab_of[k, 1]]``): each pair judged as :func:`_judge` judges it on its own sheet
    pair, the same operations on the same numbers (a sheet's t, t^3 / 12 and density computed
    as floats, taken per pair), the pairs of sheet pairs with few of them (:data:`ALONE`) in
    one pass. Returns the pairs kept (K, I, J) and their mass lower bounds (g), by sheet pair
    (increasing k), each sheet pair's in the order given: the order of :func:`_judge` called
    on each sheet pair in turn."""
    per: list[tuple[float, ...]] = []
    for st in settings:  # (density, t) of each nominal sheet, (t, t^3 / 12) of each low sheet
        (c1, c2), (w1, w2) = st.sheets, st.low
        d1, d2 = c1.material.density, c2.material.density
        per.append((d1, c1.t, d2, c2.t, w1.t, w1.t**3 / 12.0, w2.t, w2.t**3 / 12.0))
    if not len(K):
        return K[:0], I[:0], J[:0], np.empty(0)
    if np.any(K[1:] < K[:-1]):  # grouped by sheet pair, each in the order given
        order = np.argsort(K, kind="stable")
        K, I, J = K[order], I[order], J[order]
    cols = [np.asarray(col) for col in zip(*per, strict=True)]
    # runs of the pairs: a sheet pair with many alone, the others' together, in order
    starts = np.flatnonzero(np.r_[True, K[1:] != K[:-1]])
    ends = np.r_[starts[1:], len(K)].astype(np.int64)
    runs: list[tuple[int, int]] = []
    for a, b in zip(starts.tolist(), ends.tolist(), strict=True):
        if b - a >= ALONE or not runs or runs[-1][1] - runs[-1][0] >= ALONE:
            runs.append((a, b))
        else:
            runs[-1] = (runs[-1][0], b)
    outs: list[tuple[Index, Index, Index, FloatArray]] = []
    for a, b in runs:
        for s in range(a, b, CHUNK):
            e = min(s + CHUNK, b)
            k, i, j = K[s:e], I[s:e], J[s:e]
            one = int(k[0]) == int(k[-1])  # K is sorted: one sheet pair
            sh: Any = per[int(k[0])] if one else tuple(c[k] for c in cols)
            outs.append(_judge_run(settings[0], tables, tab_of, sh, one, k, i, j, worst, fired))
    return (
        np.concatenate([o[0] for o in outs]),
        np.concatenate([o[1] for o in outs]),
        np.concatenate([o[2] for o in outs]),
        np.concatenate([o[3] for o in outs]),
    )


def _judge_run(
    st: Setting,
    tables: Sequence[_Cells],
    tab_of: IntArray,
    sh: Any,
    one: bool,
    k: Index,
    i: Index,
    j: Index,
    worst: float,
    fired: set[int] | None,
) -> tuple[Index, Index, Index, FloatArray]:
    """One pass of :func:`_judge_pairs` over the pairs (k, i, j): ``sh`` the sheets' numbers
    (floats when ``one`` sheet pair, else one per pair), ``st`` the setting of any of them
    (the problem, its layout and tolerance widths, the same for all)."""
    problem, lay = st.problem, st.problem.layout
    r1, t1, r2, t2 = sh[0], sh[1], sh[2], sh[3]
    g1, g2 = _Gather(tables, tab_of[k, 0], i), _Gather(tables, tab_of[k, 1], j)
    W01, n1, E01, h01 = (g1.field(f) for f in ("W0", "n", "E0", "h0"))
    W02, n2, E02, h02 = (g2.field(f) for f in ("W0", "n", "E0", "h0"))
    lb = layer_mass(r1, t1, W01, length_sum(lay, n1, E02), lay)
    lb = lb + layer_mass(r2, t2, W02, length_sum(lay, n2, E01), lay)
    lb = lb + connector_mass(r1, t1, lay, E01, E02, h01 + h02)
    lb = np.asarray(lb) * (1 - SLACK)
    light = np.flatnonzero(lb < worst)  # the others: dropped by their mass alone
    if len(light) < len(i):
        k, i, j, lb = k[light], i[light], j[light], lb[light]
        h01, h02 = h01[light], h02[light]
        if not one:
            sh = tuple(x[light] for x in sh)
        g1, g2 = g1.sub(light), g2.sub(light)
    s1, s2 = (sh[4], sh[5]), (sh[6], sh[7])
    most = 0 if fired is None else 1  # failures counted per pair: past this it is dropped
    alive = np.ones(len(i), dtype=bool)
    count = np.zeros(len(i), dtype=np.int64)
    which = np.full(len(i), -1, dtype=np.int64)

    def fail(
        c: int, bad: NDArray[np.bool_], tally: tuple[Any, Any, Any] = (alive, count, which)
    ) -> None:
        live, n_bad, first = tally
        bad = bad & live & (n_bad <= most)
        first[bad & (n_bad == 0)] = c
        n_bad[bad] += 1

    views = [(_View(g1, v), _View(g2, v)) for v in range(len(st.shifts))]
    # one sheet pair with more pairs than cells: its terms computed over its tables' cells
    # (elementwise either way: the same numbers)
    whole: tuple[_Cells, _Cells] | None = None
    if one and len(i):
        L1, L2 = tables[int(tab_of[k[0], 0])], tables[int(tab_of[k[0], 1])]
        if len(i) >= len(L1) + len(L2):
            whole = (L1, L2)
    for c, con in enumerate(problem.constraints):
        q = con.quantity
        if q == THICKNESS:
            if con.sense == "max":
                fail(c, (h01 + h02) * (1 - SLACK) > con.bound)
            else:
                h11, h12 = g1.field("h1"), g2.field("h1")
                fail(c, (h11 + h12) * (1 + SLACK) < con.bound)
        elif q == MASS and con.sense == "max":
            fail(c, lb > con.bound)
        elif stiffness_along(q) and con.sense == "min":
            bad = np.zeros(len(i), dtype=bool)
            for at_v, (v1, v2) in enumerate(views):
                if whole is not None:  # the terms over the tables' cells, then the pairs'
                    L1, L2 = whole
                    u, v, f, g = _terms_of(
                        q, L1.views[at_v], L2.views[at_v], s1, s2, len(L1), len(L2)
                    )
                    u, v, f, g = u[i], v[j], f[i], g[j]
                else:  # the pairs' cells, then their terms
                    u, v, f, g = _terms_of(q, v1, v2, s1, s2, len(i), len(i))
                bad |= (u + v) * f * g * (1 + SLACK) < con.bound
            if st.halves is not None:
                sel = np.flatnonzero(~bad & alive & (count <= most))
                a1, a2 = g1.sub(sel), g2.sub(sel)
                at = 2 if q.kind == "K" else 0
                up = _inner_upper_of(q, _inner_of(a1, at), _inner_of(a2, at))
                bad[sel] = up * (1 + SLACK) < con.bound
            fail(c, bad)
    ok = alive & (count == 0)
    if fired is not None:
        fired.update(int(x) for x in np.unique(which[alive & (count == 1)]))
    return k[ok], i[ok], j[ok], lb[ok]


def _cell_floors(st: Setting, L1: _Cells, L2: _Cells) -> tuple[FloatArray, FloatArray]:
    """Per cell of each layer, a lower bound (g) of the mass of every design of the sheet pair
    with its layer in the cell: (A_i, B_j) with A_i + B_j at most the mass lower bound
    :func:`_judge` gives the pair (i, j). A_i: layer 1's blank at the cell's least W and
    extent with layer 2's least extent over its cells, and the band at the least extents and
    depths (layer 2's least over its cells); B_j: layer 2's blank at its cell's least W with
    layer 1's least extent. The mass grows with each W, each extent and the depth (module
    docstring), so each term is at most its term of the pair's bound."""
    (c1, c2), lay = st.sheets, st.problem.layout
    m1, m2 = c1.material, c2.material
    e1, e2 = float(L1.E0.min()), float(L2.E0.min())
    d2 = float(L2.h0.min())
    a = layer_mass(m1.density, c1.t, L1.W0, length_sum(lay, L1.n, e2), lay)
    a = np.asarray(a + connector_mass(m1.density, c1.t, lay, L1.E0, e2, L1.h0 + d2))
    b = np.asarray(layer_mass(m2.density, c2.t, L2.W0, length_sum(lay, L2.n, e1), lay))
    return np.asarray(a, np.float64), np.asarray(b, np.float64)


def _cells_failing(
    st: Setting, L1: _Cells, L2: _Cells
) -> tuple[NDArray[np.bool_], NDArray[np.bool_]]:
    """Per cell of each layer and constraint of P (cells x constraints), whether the
    constraint fails at every cell pair of the sheet pair holding it, by :func:`_judge`'s own
    rule at the other layer's most favourable values over its cells: the folded thickness at
    the other layer's least (a maximum) or greatest (a minimum) depth bound; a stiffness
    along the creases in some view at (u_i + max v) f_i max g (layer 1's cell i; (max u +
    v_j) max f g_j for layer 2's cell j). Every term is positive and rounding is monotone, so
    the value computed for any pair (i, j) is at most this one, and the judge drops every pair
    of the cell by this constraint."""
    (w1, w2), cons = st.low, st.problem.constraints
    bad1 = np.zeros((len(L1), len(cons)), dtype=bool)
    bad2 = np.zeros((len(L2), len(cons)), dtype=bool)
    for k, c in enumerate(cons):
        q = c.quantity
        if q == THICKNESS:
            if c.sense == "max":
                bad1[:, k] = (L1.h0 + L2.h0.min()) * (1 - SLACK) > c.bound
                bad2[:, k] = (L1.h0.min() + L2.h0) * (1 - SLACK) > c.bound
            else:
                bad1[:, k] = (L1.h1 + L2.h1.max()) * (1 + SLACK) < c.bound
                bad2[:, k] = (L1.h1.max() + L2.h1) * (1 + SLACK) < c.bound
        elif stiffness_along(q) and c.sense == "min":
            for v1, v2 in zip(L1.views, L2.views, strict=True):
                u, v, f, g = _terms(q, v1, v2, w1.t, w2.t)
                bad1[:, k] |= (u + v.max()) * f * g.max() * (1 + SLACK) < c.bound
                bad2[:, k] |= (u.max() + v) * f.max() * g * (1 + SLACK) < c.bound
    return bad1, bad2


def _first_pairs(
    st: Setting, L1: _Cells, L2: _Cells, worst: float, fired: set[int] | None = None
) -> tuple[Index, Index]:
    """The first cell pairs of a sheet pair worth judging (:func:`_judge` drops every other):
    of the cells no constraint drops whole (:func:`_cells_failing`), the pairs (i, j) with
    (A_i + B_j) (1 - SLACK) below ``worst`` (g) (:func:`_cell_floors`: A_i + B_j is at most the
    pair's mass lower bound, both within the judge's rounding, which SLACK covers); layer 1's
    index first, as the full grid lists them. With no design on the sheet pair lighter than
    ``worst`` none is left: the pair is pruned whole before any cell pair is formed. ``fired``:
    a constraint that alone drops a cell whose pairs may be lighter than ``worst`` is added."""
    empty = np.empty(0, dtype=np.int32)
    if not len(L1) or not len(L2):
        return empty, empty
    a, b = _cell_floors(st, L1, L2)
    bad1, bad2 = _cells_failing(st, L1, L2)
    if fired is not None:
        for bad, light in ((bad1, (a + b.min()) * (1 - SLACK) < worst), (bad2, None)):
            if light is None:
                light = (a.min() + b) * (1 - SLACK) < worst
            alone = light & (bad.sum(axis=1) == 1)
            fired.update(int(k) for k in np.flatnonzero(bad[alone].any(axis=0)))
    i = np.flatnonzero(~bad1.any(axis=1)).astype(np.int32)
    j = np.flatnonzero(~bad2.any(axis=1)).astype(np.int32)
    if not len(i) or not len(j):
        return empty, empty
    j = j[np.argsort(b[j], kind="stable")]
    bj = b[j]
    # pairs with (a_i + b_j) (1 - SLACK) < worst: a prefix of j's sorted floors per i
    room = worst / (1 - SLACK) - a[i] if math.isfinite(worst) else np.full(len(i), math.inf)
    take = np.searchsorted(bj, room, side="left")
    take = np.minimum(take + 1, len(j))  # one more: the division's rounding, judged anyway
    I = np.repeat(i, take)
    starts = np.cumsum(take) - take
    J = j[np.arange(len(I)) - np.repeat(starts, take)]
    order = np.lexsort((J, I))
    return I[order], J[order]


def _first(problem: Problem) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray, FloatArray]:
    """The first cells of a layer: every n of the range, W and alpha cut in
    :data:`FIRST_W` x :data:`FIRST_ALPHA`."""
    ns = np.arange(problem.n_lo, problem.n_hi + 1, dtype=np.float64)
    We = np.linspace(problem.W.lo, problem.W.top, FIRST_W + 1)
    ae = np.linspace(problem.alpha.lo, problem.alpha.top, FIRST_ALPHA + 1)
    grid = np.meshgrid(ns, np.arange(FIRST_W), np.arange(FIRST_ALPHA), indexing="ij")
    n, wi, ai = (g.reshape(-1) for g in grid)
    w, a = wi.astype(np.int64), ai.astype(np.int64)
    return np.asarray(n, np.float64), We[w], We[w + 1], ae[a], ae[a + 1]


def _split(
    L: _Cells, spans: tuple[float, float]
) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray, FloatArray]:
    """Every cell of ``L`` cut in two across its relatively wider side (W's or alpha's width
    over its range ``spans``, W on a tie), child k of cell c at 2 c + k."""
    by_W = (L.W1 - L.W0) / spans[0] >= (L.a1 - L.a0) / spans[1]
    Wm = np.where(by_W, 0.5 * (L.W0 + L.W1), L.W1)
    am = np.where(by_W, L.a1, 0.5 * (L.a0 + L.a1))
    n = np.repeat(L.n, 2)
    W0 = np.stack([L.W0, np.where(by_W, Wm, L.W0)], axis=1).reshape(-1)
    W1 = np.stack([Wm, L.W1], axis=1).reshape(-1)
    a0 = np.stack([L.a0, np.where(by_W, L.a0, am)], axis=1).reshape(-1)
    a1 = np.stack([am, L.a1], axis=1).reshape(-1)
    return n, W0, W1, a0, a1


def _spans(problem: Problem) -> tuple[float, float]:
    return problem.W.top - problem.W.lo, problem.alpha.top - problem.alpha.lo


def _width(L: _Cells, ids: Index, spans: tuple[float, float]) -> FloatArray:
    """The relative width of cells ``ids``: the larger of W's and alpha's over their ranges."""
    return np.maximum((L.W1[ids] - L.W0[ids]) / spans[0], (L.a1[ids] - L.a0[ids]) / spans[1])


def _take(L: _Cells, idx: IntArray) -> _Cells:
    return replace(
        L,
        **{f: getattr(L, f)[idx] for f in _FIELDS},
        views=tuple(tuple(x[idx] for x in v) for v in L.views),
        inner=tuple(x[..., idx] for x in L.inner),
    )


def _probe(
    st: Setting,
    L1: _Cells,
    L2: _Cells,
    I: IntArray,
    J: IntArray,
    lb: FloatArray,
    worst: float,
    seed: int,
) -> DesignPoints | None:
    """Designs to evaluate exactly: :data:`PROBE_POINTS` points drawn in each of the
    :data:`PROBE_PAIRS` cell pairs of least mass bound, those the cells' rule does not exclude
    at the points themselves (:func:`_judge`) lighter than ``worst`` (g), the :data:`PROBES`
    lightest; None when there is none. Any design will do (an incumbent only prunes): the
    draws are fixed by ``seed``."""
    k = min(PROBE_PAIRS, len(I))
    pick = np.argpartition(lb, k - 1)[:k] if len(I) > k else np.arange(len(I))
    i, j = np.repeat(I[pick], PROBE_POINTS), np.repeat(J[pick], PROBE_POINTS)
    rng = np.random.default_rng(seed)
    u = rng.random((4, len(i)))
    W1 = L1.W0[i] + u[0] * (L1.W1[i] - L1.W0[i])
    a1 = L1.a0[i] + u[1] * (L1.a1[i] - L1.a0[i])
    W2 = L2.W0[j] + u[2] * (L2.W1[j] - L2.W0[j])
    a2 = L2.a0[j] + u[3] * (L2.a1[j] - L2.a0[j])
    P1, k1 = _cells(st, 1, L1.n[i], W1, W1, a1, a1)
    P2, k2 = _cells(st, 2, L2.n[j], W2, W2, a2, a2)
    both = np.intersect1d(k1, k2)
    pi, pj = np.searchsorted(k1, both), np.searchsorted(k2, both)
    pi, pj, mass = _judge(st, P1, P2, pi, pj, worst)
    if not len(pi):
        return None
    if len(pi) > PROBES:
        sel = np.argpartition(mass, PROBES - 1)[:PROBES]
        pi, pj = pi[sel], pj[sel]
    return DesignPoints.of(
        LayerPoints(P1.n[pi], P1.W0[pi], P1.a0[pi]), LayerPoints(P2.n[pj], P2.W0[pj], P2.a0[pj])
    )


def _moves(
    problem: Problem, x: DesignPoints, scale: float, rng: np.random.Generator
) -> DesignPoints:
    """:data:`MOVES` designs near the design ``x``: its W and alpha moved at random by up to
    ``scale`` of their ranges, n kept, inside the bounds."""
    one, two = x.layer(0), x.layer(1)
    cols = []
    for lay in (one, two):
        for name, var in (("W", problem.W), ("alpha", problem.alpha)):
            at = float(np.asarray(getattr(lay, name)).reshape(-1)[0])
            span = var.top - var.lo
            cols.append(np.clip(at + scale * span * rng.uniform(-1, 1, MOVES), var.lo, var.top))
    n1 = np.full(MOVES, float(np.asarray(one.n).reshape(-1)[0]))
    n2 = np.full(MOVES, float(np.asarray(two.n).reshape(-1)[0]))
    return DesignPoints.of(LayerPoints(n1, cols[0], cols[1]), LayerPoints(n2, cols[2], cols[3]))


def _ns(x: DesignPoints) -> tuple[float, float]:
    """The n of each layer of the one design ``x``."""
    return (
        float(np.asarray(x.layer(0).n).reshape(-1)[0]),
        float(np.asarray(x.layer(1).n).reshape(-1)[0]),
    )


Judge = Callable[[DesignPoints], tuple[FloatArray, NDArray[np.bool_]]]


class _Table:
    """One layer's cells, grown as they are split: cell k's two children (:func:`_split`) are
    ``kids[k]`` (-1: a child that breaks its own layer's bounds; -2: not split yet), made once
    whichever pairs ask for them."""

    def __init__(
        self, st: Setting, which: int, fired: tuple[set[int], float] | None = None
    ) -> None:
        self.st, self.which = st, which
        self.spans = _spans(st.problem)
        first, _ = _cells(st, which, *_first(st.problem), fired=fired)
        self.size = len(first)
        self.buf = _grown(first, max(2 * self.size, 1024))
        self.kids = np.full((len(self.buf), 2), -2, dtype=np.int64)
        self.cells = _head(self.buf, self.size)

    def children(self, ids: Index, fired: tuple[set[int], float] | None = None) -> IntArray:
        """The children of cells ``ids`` (len(ids) x 2), split now where not yet (``fired``:
        :func:`_cells`')."""
        new = np.unique(ids[self.kids[ids, 0] == -2])
        if len(new):
            parts = _split(_take(self.cells, new), self.spans)
            made, kept = _cells(self.st, self.which, *parts, fired=fired)
            pos = np.full(2 * len(new), -1, dtype=np.int64)
            pos[kept] = self.size + np.arange(len(kept))
            self.kids[new] = pos.reshape(-1, 2)
            end = self.size + len(made)
            if end > len(self.buf):  # room for twice as many
                self.buf = _grown(_head(self.buf, self.size), 2 * end)
                kids = np.full((len(self.buf), 2), -2, dtype=np.int64)
                kids[: self.size] = self.kids[: self.size]
                self.kids = kids
            _put(self.buf, made, self.size)
            self.size = end
            self.cells = _head(self.buf, self.size)
        return self.kids[ids]


def _grown(L: _Cells, capacity: int) -> _Cells:
    """``L`` in arrays of ``capacity`` cells (the first ``len(L)`` filled)."""

    def room(x: FloatArray) -> FloatArray:
        out = np.empty((*x.shape[:-1], capacity))
        out[..., : x.shape[-1]] = x
        return out

    return replace(
        L,
        **{f: room(getattr(L, f)) for f in _FIELDS},
        views=tuple(tuple(room(x) for x in v) for v in L.views),
        inner=tuple(room(x) for x in L.inner),
    )


def _head(L: _Cells, size: int) -> _Cells:
    """The first ``size`` cells of ``L`` (views of its arrays)."""
    return replace(
        L,
        **{f: getattr(L, f)[:size] for f in _FIELDS},
        views=tuple(tuple(x[:size] for x in v) for v in L.views),
        inner=tuple(x[..., :size] for x in L.inner),
    )


def _put(buf: _Cells, L: _Cells, at: int) -> None:
    """Write the cells ``L`` into ``buf`` from cell ``at`` on."""
    end = at + len(L)
    for f in _FIELDS:
        getattr(buf, f)[at:end] = getattr(L, f)
    for vb, vl in zip(buf.views, L.views, strict=True):
        for x, y in zip(vb, vl, strict=True):
            x[at:end] = y
    for x, y in zip(buf.inner, L.inner, strict=True):
        x[..., at:end] = y


def search(
    st: Setting,
    incumbent: float,
    exact: Judge | None = None,
    budget: int = BUDGET,
    gap: float = CELL_GAP,
) -> CellResult:
    """The cells' search of one sheet pair (:func:`search_pairs` of ``st`` alone)."""
    results, _, _ = search_pairs([st], incumbent, None if exact is None else [exact], budget, gap)
    return results[0]


def search_pairs(
    settings: Sequence[Setting],
    incumbent: float,
    exacts: Sequence[Judge] | None = None,
    budget: int = BUDGET,
    gap: float = CELL_GAP,
    fine: float | None = None,
    seek: bool = False,
    crowd: int | None = None,
) -> tuple[list[CellResult], int, frozenset[int]]:
    """The cells' search of the module docstring over the sheet pairs of ``settings``
    (:func:`setting`; a problem of :func:`applies`) at once, below ``incumbent`` (g; inf:
    none): the cell pairs of every sheet pair in one queue, those of least mass bound split
    first, :data:`BATCH` at a time, one incumbent for all (a design of any sheet pair prunes
    every other), until none is left below the incumbent less ``gap`` (relative), then on
    until none is below it less ``fine`` (relative, when given and finer) or more than
    :data:`FINE_MOST` are left, or ``budget`` cell pairs have been judged. ``exacts``: per sheet pair the problem's (mass,
    feasible) at points (:func:`judge_of`), whose feasible best lowers the incumbent (None: no
    point evaluated). Returns each sheet pair's result (its design: the best over all pairs,
    on the pair that holds it, None on the others), the index of the pair of the best
    design (-1: none), and the constraints (by index) that *fired*: that alone dropped a cell
    or a cell pair below the incumbent of the moment. A search of the problem without a
    constraint that did not fire drops what this one dropped: every design of it lighter than
    the incumbent lies in the boxes left (:func:`~.solve._cell_binding`). ``seek``: a design
    sought before the first pairs and polished (:func:`_seed`) whatever their number, not only
    past :data:`SEED_FROM` (an incumbent only prunes: the answer's certificate is the same).
    ``crowd``: the search also stops when more cell pairs than this are left in its queue
    (its start boxes are then all of them: the caller's rule for too many boxes decides; the
    runner-ups', :func:`~.solve._by_cells`)."""
    inc = incumbent
    best_x: DesignPoints | None = None
    best_at = -1
    worst = inc * (1 + SLACK) if math.isfinite(inc) else math.inf
    shared: dict[tuple[int, Candidate, Candidate], int] = {}
    tabs: list[_Table] = []
    fired: set[int] = set()

    def table(st: Setting, which: int) -> int:
        key = (which, st.sheets[which - 1], st.low[which - 1])
        if key not in shared:
            shared[key] = len(tabs)
            tabs.append(_Table(st, which, (fired, worst)))
        return shared[key]

    tab_of = np.array([[table(st, 1), table(st, 2)] for st in settings], dtype=np.int64)
    first = sum(len(tabs[t1].cells) * len(tabs[t2].cells) for t1, t2 in tab_of.tolist())
    if not math.isfinite(inc) and first > FIRST_MOST:  # too wide a domain for the cells
        none = np.empty((0, 6))
        gave_up = CellResult(0.0, (none, none, np.empty(0)), None, math.nan, 0, False)
        return [gave_up] * len(settings), -1, frozenset()
    wide = seek or first > SEED_FROM  # a design sought before the first pairs, and polished
    if exacts is not None and not math.isfinite(inc) and wide:
        seeded = _seed(settings, tabs, tab_of, exacts)
        if seeded is not None and seeded[0] < inc:
            inc, best_x, best_at = seeded
            worst = inc * (1 + SLACK)
    kind = np.int16 if len(settings) < 2**15 else np.int32  # the sheet pairs' index
    judged = 0
    # the first pairs of the sheet pairs judged together, in order, once :data:`CHUNK` of them
    # wait (so no more than that are held unjudged)
    cellsets = [T.cells for T in tabs]
    waiting: list[tuple[Index, Index, Index]] = []
    kept: list[tuple[Index, Index, Index, FloatArray]] = []

    def flush() -> None:
        if waiting:
            K, I, J = (np.concatenate([w[x] for w in waiting]) for x in range(3))
            kept.append(_judge_pairs(settings, cellsets, tab_of, K, I, J, worst, fired))
            waiting.clear()

    for k, st in enumerate(settings):
        T1, T2 = tabs[tab_of[k, 0]], tabs[tab_of[k, 1]]
        I, J = _first_pairs(st, T1.cells, T2.cells, worst, fired)
        judged += len(I)
        waiting.append((np.full(len(I), k, dtype=kind), I, J))
        if sum(len(w[0]) for w in waiting) >= CHUNK:
            flush()
    flush()
    K, I, J, lb = (np.concatenate([x[c] for x in kept]) for c in range(4))
    rounds = 0
    climbed: set[tuple[int, float, float]] = set()  # (sheet pair, n1, n2) polished
    climbed_n: dict[int, set[tuple[float, float]]] = {}
    spend, charged = current_budget(), 0
    scale = MOVE_SCALE
    while len(I):
        if exacts is not None and rounds % PROBE_EVERY == 0 and len(I):
            rng = np.random.default_rng(rounds)
            low = np.argpartition(lb, min(PROBE_PAIRS, len(lb)) - 1)[:PROBE_PAIRS]
            order = low[np.argsort(lb[low])]
            ks = list(dict.fromkeys(K[order].tolist()))[:PROBE_SHEETS]
            tries = [(k, order[K[order] == k]) for k in ks]
            if not math.isfinite(incumbent) and (best_x is None or wide):  # and anywhere
                anywhere = rng.integers(0, len(I), PROBE_PAIRS)
                far = list(dict.fromkeys(K[anywhere].tolist()))[:PROBE_FAR]
                tries += [(k, anywhere[K[anywhere] == k]) for k in far]
            for k, sel in tries:
                T1, T2 = tabs[tab_of[k, 0]], tabs[tab_of[k, 1]]
                x = _probe(settings[k], T1.cells, T2.cells, I[sel], J[sel], lb[sel], worst, rounds)
                if x is None:
                    continue
                mass, feasible = exacts[k](x)
                f = np.where(feasible, mass, math.inf)
                b = int(np.argmin(f))
                if f[b] < inc:
                    inc, best_x, best_at = float(f[b]), x.point(b), int(k)
                    worst = inc * (1 + SLACK)
            polished = sum(len(d) for d in climbed_n.values())
            if (
                wide
                and best_x is not None
                and (best_at, *_ns(best_x)) not in climbed
                and polished < POLISHES
            ):  # polish it
                st = settings[best_at]
                done = climbed_n.setdefault(best_at, set())
                most = min(CLIMB_MOST, POLISHES - polished)
                got = climb(st.problem, *st.sheets, best_x, st.tables, exacts[best_at], done, most)
                climbed.add((best_at, *_ns(best_x)))
                if got is not None and got.mass < inc:
                    inc, best_x = got.mass, got.point
                    worst = inc * (1 + SLACK)
                    climbed.add((best_at, *_ns(best_x)))
            if best_x is not None:  # moves around the best design
                x = _moves(settings[best_at].problem, best_x, scale, rng)
                mass, feasible = exacts[best_at](x)
                f = np.where(feasible, mass, math.inf)
                b = int(np.argmin(f))
                if f[b] < inc:
                    inc, best_x = float(f[b]), x.point(b)
                    worst = inc * (1 + SLACK)
                else:
                    scale = max(scale / 2, 1e-6)
            keep = lb < worst
            K, I, J, lb = K[keep], I[keep], J[keep], lb[keep]
        rounds += 1
        if not len(I) or judged >= budget or _settled(float(lb.min()), inc, len(I), gap, fine):
            break
        if crowd is not None and len(I) > crowd:  # the caller gives up on so many boxes
            break
        if spend is not None:
            spend.charge(judged - charged)
            charged = judged
            if spend.exhausted:
                break
        batch = WIDE_BATCH if wide else BATCH
        if len(I) > batch:  # the lightest bounds first
            take = np.zeros(len(I), dtype=bool)
            take[np.argpartition(lb, batch - 1)[:batch]] = True
            pK, pI, pJ = K[take], I[take], J[take]
            K, I, J, lb = K[~take], I[~take], J[~take], lb[~take]
        else:
            pK, pI, pJ = K, I, J
            K, I, J, lb = K[:0], I[:0], J[:0], lb[:0]
        # each pair's relatively wider cell cut in two (layer 1's on a tie), every table's
        # cells split at once
        t1, t2 = tab_of[pK, 0], tab_of[pK, 1]
        w1 = np.empty(len(pK))
        w2 = np.empty(len(pK))
        for t in np.unique(t1):
            sel = t1 == t
            w1[sel] = _width(tabs[t].cells, pI[sel], tabs[t].spans)
        for t in np.unique(t2):
            sel = t2 == t
            w2[sel] = _width(tabs[t].cells, pJ[sel], tabs[t].spans)
        one = w1 >= w2
        kids = np.empty((len(pK), 2), dtype=np.int64)
        for which, tt, ids in ((1, t1, pI), (2, t2, pJ)):
            side = one if which == 1 else ~one
            for t in np.unique(tt[side]):
                sel = side & (tt == t)
                kids[sel] = tabs[t].children(ids[sel], (fired, worst))
        nK = np.repeat(pK, 2)
        nI = np.where(np.repeat(one, 2), kids.reshape(-1), np.repeat(pI, 2)).astype(np.int32)
        nJ = np.where(np.repeat(one, 2), np.repeat(pJ, 2), kids.reshape(-1)).astype(np.int32)
        ok = (nI >= 0) & (nJ >= 0)
        nK, nI, nJ = nK[ok], nI[ok], nJ[ok]
        judged += len(nK)
        parts = [(K, I, J, lb)]
        # every sheet pair's children judged in one pass (ordered by sheet pair, as judged
        # one sheet pair at a time)
        parts.append(
            _judge_pairs(settings, [T.cells for T in tabs], tab_of, nK, nI, nJ, worst, fired)
        )
        K = np.concatenate([x[0] for x in parts])
        I = np.concatenate([x[1] for x in parts])
        J = np.concatenate([x[2] for x in parts])
        lb = np.concatenate([x[3] for x in parts])
    T = [(tabs[tab_of[k, 0]], tabs[tab_of[k, 1]]) for k in range(len(settings))]
    out = []
    for k, (T1, T2) in enumerate(T):
        mine = k == K
        i, j, b = I[mine], J[mine], lb[mine]
        L1, L2 = T1.cells, T2.cells
        lo = np.stack([L1.n[i], L1.W0[i], L1.a0[i], L2.n[j], L2.W0[j], L2.a0[j]], axis=1)
        hi = np.stack([L1.n[i], L1.W1[i], L1.a1[i], L2.n[j], L2.W1[j], L2.a1[j]], axis=1)
        floor = float(b.min()) if len(b) else math.inf
        own = best_x if k == best_at else None
        value = inc if own is not None else math.nan
        out.append(CellResult(floor, (lo, hi, b.copy()), own, value, judged))
    return out, best_at, frozenset(fired)


def _settled(least: float, inc: float, left: int, gap: float, fine: float | None) -> bool:
    """Whether the search stops with ``left`` pairs, the least bound ``least`` (g), below the
    incumbent ``inc`` (g): at ``gap`` (relative), or on toward ``fine`` while at most
    :data:`FINE_MOST` are left. The pairs left hold every design lighter than the incumbent
    whenever it stops: this only says how far the cells go before the branch and bound."""
    if least < inc * (1 - gap):
        return False
    return fine is None or fine >= gap or left > FINE_MOST or least >= inc * (1 - fine)


def _seed(
    settings: Sequence[Setting],
    tabs: list[_Table],
    tab_of: IntArray,
    exacts: Sequence[Judge],
) -> tuple[float, DesignPoints, int] | None:
    """A design of P before the first cell pairs are formed, or None: :data:`SEED_POINTS`
    points drawn in each layer's first cells that meet their own layer's bounds
    (:func:`_cells` at the points), :data:`SEED_PAIRS` of their pairs drawn per sheet pair and
    judged by the cells' rule at the points, the :data:`PROBES` lightest kept evaluated exactly
    (P's own rule), and the best feasible one polished (:func:`~.polish.climb`) with those of
    the next :data:`SEED_CLIMBS` - 1 sheet pairs. Any design will do (it only prunes): the
    draws are fixed (seed 0)."""
    rng = np.random.default_rng(0)
    pts: list[tuple[_Cells, IntArray] | None] = []
    for T in tabs:
        L = T.cells
        if not len(L):
            pts.append(None)
            continue
        c = rng.integers(0, len(L), SEED_POINTS)
        u = rng.random((2, SEED_POINTS))
        W = L.W0[c] + u[0] * (L.W1[c] - L.W0[c])
        a = L.a0[c] + u[1] * (L.a1[c] - L.a0[c])
        pts.append(_cells(T.st, T.which, L.n[c], W, W, a, a))
    found: list[tuple[float, int, int, int]] = []  # (mass, sheet pair, i, j)
    for k, st in enumerate(settings):
        one, two = pts[tab_of[k, 0]], pts[tab_of[k, 1]]
        if one is None or two is None or not len(one[0]) or not len(two[0]):
            continue
        P1, P2 = one[0], two[0]
        i = rng.integers(0, len(P1), SEED_PAIRS)
        j = rng.integers(0, len(P2), SEED_PAIRS)
        i, j, mass = _judge(st, P1, P2, i, j, math.inf)
        if len(i) > PROBES:
            sel = np.argpartition(mass, PROBES - 1)[:PROBES]
            i, j, mass = i[sel], j[sel], mass[sel]
        found.extend(zip(mass.tolist(), [k] * len(i), i.tolist(), j.tolist(), strict=True))
    found.sort()
    best: tuple[float, DesignPoints, int] | None = None
    tried: list[int] = []
    for _, k, _, _ in found:
        if k in tried:
            continue
        tried.append(k)
        if len(tried) > SEED_CLIMBS * 4:
            break
        mine = [(i, j) for _, kk, i, j in found if kk == k][:PROBES]
        one, two = pts[tab_of[k, 0]], pts[tab_of[k, 1]]
        assert one is not None and two is not None  # the pair had points
        P1, P2 = one[0], two[0]
        ii = np.array([x[0] for x in mine])
        jj = np.array([x[1] for x in mine])
        x = DesignPoints.of(
            LayerPoints(P1.n[ii], P1.W0[ii], P1.a0[ii]),
            LayerPoints(P2.n[jj], P2.W0[jj], P2.a0[jj]),
        )
        mass, feasible = exacts[k](x)
        f = np.where(feasible, mass, math.inf)
        b = int(np.argmin(f))
        if not math.isfinite(float(f[b])):
            continue
        st = settings[k]
        got = climb(st.problem, *st.sheets, x.point(b), st.tables, exacts[k], set(), SEED_CLIMB)
        if got is not None and (best is None or got.mass < best[0]):
            best = (got.mass, got.point, k)
        if len(tried) >= SEED_CLIMBS and best is not None:
            break
    return best


def judge_of(problem: Problem, c1: Candidate, c2: Candidate, tables: Tables) -> Judge:
    """P's exact (mass, feasible) at points on sheets (c1, c2): its certified values
    (``point_values``, tolerances included), every constraint met with no slack (the branch and
    bound's rule for continuous variables)."""

    def exact(x: DesignPoints) -> tuple[FloatArray, NDArray[np.bool_]]:
        vals = point_values(problem, c1, c2, x, tables)
        ok = np.ones(len(x), dtype=bool)
        for c in problem.constraints:
            ok &= np.asarray(c.satisfied(vals[c.quantity], rtol=0.0), dtype=bool)
        return np.asarray(vals[MASS], dtype=np.float64), ok

    return exact


@dataclass(frozen=True)
class CellArchive(Archive):
    """The archive of a search started from cells (module docstring): its own closed boxes,
    and the part of the domain the cells dropped, reopened by ``cells(relaxed, below)`` (the
    cells' start boxes of the problem without the constraints of the bit set ``relaxed``,
    below ``below``), each reopening made once."""

    cells: Callable[[int, float], tuple[FloatArray, FloatArray, FloatArray]] | None = None
    _made: dict[tuple[int, float], Any] = field(default_factory=dict, compare=False)

    def reopen(
        self, relaxed: int = 0, below: float = math.inf
    ) -> tuple[FloatArray, FloatArray, FloatArray]:
        key = (relaxed, below)
        if key not in self._made:
            own = super().reopen(relaxed, below)
            if self.cells is None:
                self._made[key] = own
            else:
                more = self.cells(relaxed, below)
                self._made[key] = tuple(
                    np.concatenate([a, b]) for a, b in zip(own, more, strict=True)
                )
        return self._made[key]  # type: ignore[no-any-return]


def with_cells(
    archive: Archive | None,
    cells: Callable[[int, float], tuple[FloatArray, FloatArray, FloatArray]],
) -> CellArchive | None:
    """``archive`` (a search's from start boxes) with the reopening of the cells' part."""
    if archive is None:
        return None
    return CellArchive(archive.lo, archive.hi, archive.bound, archive.mask, cells)


def relaxed_without(problem: Problem, bits: int) -> Problem:
    """``problem`` without the constraints of the bit set ``bits`` (bit i: constraint i)."""
    kept = tuple(c for i, c in enumerate(problem.constraints) if not (bits >> i) & 1)
    return replace(problem, constraints=kept)
