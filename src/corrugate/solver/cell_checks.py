"""The binding checks of a problem solved by cells, searched together (docs/theory.md section 5).

A binding check of constraint c asks whether the problem P without c has a design lighter than
the goal, the certified optimum less twice its proven gap (g; :func:`~.solve._cell_binding`).
Each check used to be a whole cells search of P without c (:mod:`.cells`) and the branch and
bound from the boxes it left: about one solve each. :func:`shared_search` answers every check
in one cells search instead, its queue holding each cell pair once with the set of checks it
may still answer (a bit mask):

* a pair is dropped for check c when a constraint other than c alone shows it holds no design
  (each constraint judged by the cells' own rule, :func:`~.cells._own_ok` for a cell's own
  layer and the pair rule of :func:`~.cells._judge`, the same bounds with the same slack), or
  when its mass lower bound reaches the goal: so a pair kept for c is one that c's own search
  keeps, and every design of P without c lighter than the goal lies in a pair kept for c;
* when the optimum is certified, a pair is also dropped for c where every constraint called c
  holds at every design of the pair (:func:`_met`): a design of P without c lighter than the
  goal that meets c would be a design of P lighter than the optimum by more than its proven
  gap, which the certificate excludes, so every such design breaks c (the negation of
  :func:`~.solve._relaxed`) and none lies in that pair. The bounds are the cells' own: a layer's
  extent, blank, facet width, t / W, n and validated ranges monotone in W, alpha and n (their
  values at the cell's corners, a relative slack :data:`~.cells.SLACK` toward keeping), the
  folded thickness W1 cos(alpha1 / 2) + W2 cos(alpha2 / 2) at its corners; the others (the
  stiffness bounds, a mass bound, the part's sides) are never shown met, so they never drop;
* designs drawn in the lightest pairs are evaluated exactly (P's certified values, every
  constraint with no slack, the cells' rule): one that meets every constraint but c's with a
  mass below the goal answers c (binding), which then leaves every pair.

When no pair is left below the goal less :data:`~.cells.CELL_GAP` (relative), each unanswered
check's pairs are its start boxes per sheet pair (their union holds every design of P without c
lighter than the goal), from which the caller runs its branch and bound. So each answer is the
one its own search gives, at the cost of about one search for them all.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import NDArray

from corrugate.geometry.layouts import length_sum
from corrugate.mechanics.mass import connector_mass, layer_mass
from corrugate.solver import cells
from corrugate.solver.archive import bit_sets
from corrugate.solver.budget import budget_spent, current_budget
from corrugate.solver.points import DesignPoints, LayerPoints
from corrugate.solver.problem import Candidate, Constraint, Problem
from corrugate.solver.quantities import Tables, point_values
from corrugate.solver.quantity import (
    CREASES,
    FLAT,
    LX,
    LY,
    MASS,
    T_OVER_W,
    THICKNESS,
    W_MIN,
)
from corrugate.solver.separable import stiffness_along
from corrugate.solver.validity import LAYER_KINDS

__all__ = ["CellCheck", "Shared", "answered", "applies", "shared_search"]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]
Start = tuple[FloatArray, FloatArray, FloatArray]

#: At most this many constraints and checks (bits of an int64 mask).
MOST_BITS = 62


@dataclass(frozen=True)
class CellCheck:
    """One binding check: the constraints of the bit set ``bits`` (bit i: constraint i of the
    problem, all those of one name) dropped; ``negated``: its pairs where all of them hold
    everywhere are dropped too (the optimum is certified, module docstring)."""

    name: str
    bits: int
    negated: bool


@dataclass(frozen=True)
class Shared:
    """What :func:`shared_search` found: per check name, True when a design of its problem
    lighter than the goal was evaluated (binding), else the start boxes of each sheet pair
    (index of ``pairs``) that hold every such design, lo, hi (the branch and bound's
    coordinates) and a mass lower bound (g); ``settled`` False when the search stopped at its
    budget first (then nothing is proven)."""

    found: dict[str, bool]
    starts: dict[str, dict[int, Start]]
    settled: bool
    judged: int


def applies(problem: Problem, checks: Sequence[CellCheck]) -> bool:
    """Whether the shared search can take these checks: a problem of :func:`~.cells.applies`
    with at most :data:`MOST_BITS` constraints and checks."""
    return (
        cells.applies(problem)
        and len(problem.constraints) <= MOST_BITS
        and 0 < len(checks) <= MOST_BITS
    )


def _own(c: Constraint) -> bool:
    """Whether ``c`` bounds each layer on its own (the cells judge it per cell)."""
    return c.quantity not in (THICKNESS, MASS) and not stiffness_along(c.quantity)


def _bits(rows: NDArray[np.bool_]) -> IntArray:
    """Each row of a (cells x constraints) table as a bit set (bit k: column k;
    :func:`~.archive.bit_sets`)."""
    return bit_sets(np.ascontiguousarray(rows, dtype=bool))[0].astype(np.int64)


def _met(
    problem: Problem,
    cand: Candidate,
    which: int,
    n: FloatArray,
    W0: FloatArray,
    W1: FloatArray,
    a0: FloatArray,
    a1: FloatArray,
) -> NDArray[np.bool_]:
    """Per cell and constraint (cells x constraints), whether the constraint holds at every
    design of the cell as far as this layer decides it (True for a constraint that does not
    read this layer alone: the other layer's extent, the pair's; False where not shown):
    each quantity below is monotone in W, alpha and n, so bounded at the cell's corners
    (extents (n + 1) W sin(alpha / 2) in mm, the blank (n + 1) W, the facet width W, t / W,
    n, and the validated ranges of W, alpha, t / W, n + 1), judged with the relative slack
    :data:`~.cells.SLACK` against holding; n and n + 1 exactly (integers)."""
    other = LY if which == 1 else LX
    t = cand.t
    E0, E1 = cells._extent(n, W0, a0), cells._extent(n, W1, a1)
    up, down = 1 + cells.SLACK, 1 - cells.SLACK
    met = np.zeros((len(n), len(problem.constraints)), dtype=bool)
    for k, c in enumerate(problem.constraints):
        q, b, lo = c.quantity, c.bound, c.sense == "min"
        ok: object = False
        if q == other:  # the other layer's extent: its own cells decide
            ok = True
        elif not _own(c):  # the pair's (set by the pair's own bounds)
            ok = False
        elif q == W_MIN and lo:
            ok = W0 * down >= b
        elif q == T_OVER_W:
            ok = t / W1 * down >= b if lo else t / W0 * up <= b
        elif q == CREASES and not lo:
            ok = n <= b
        elif q in (LX, LY):
            ok = E0 * down >= b if lo else E1 * up <= b
        elif q == FLAT and not lo:
            ok = (n + 1.0) * W1 * up <= b
        elif q.kind in LAYER_KINDS and LAYER_KINDS[q.kind][0] == c.sense:
            var = LAYER_KINDS[q.kind][1]
            if var == "facets":
                ok = n + 1.0 >= b if lo else n + 1.0 <= b
            elif var == "W":
                ok = W0 * down >= b if lo else W1 * up <= b
            elif var == "alpha":
                ok = a0 * down >= b if lo else a1 * up <= b
            elif var == "t_over_W":
                ok = t / W1 * down >= b if lo else t / W0 * up <= b
        met[:, k] = np.asarray(ok, dtype=bool)
    return met


class _Layer:
    """One layer's cells (:class:`~.cells._Table` of the problem without the checks' own
    constraints, so that a cell only they break stays) with, per cell, the bit sets of P's
    constraints it breaks everywhere (:func:`~.cells._own_ok`) and holds everywhere
    (:func:`_met`)."""

    def __init__(self, st: cells.Setting, full: Problem, which: int) -> None:
        self.table = cells._Table(st, which)
        self.full, self.which, self.cand = full, which, st.sheets[which - 1]
        self.fail = np.empty(0, dtype=np.int64)
        self.met = np.empty(0, dtype=np.int64)
        self._grow()

    def _grow(self) -> None:
        L, done = self.table.cells, len(self.fail)
        if len(L) == done:
            return
        args = (L.n[done:], L.W0[done:], L.W1[done:], L.a0[done:], L.a1[done:])
        fail, met = layer_bits(self.full, self.cand, self.which, *args)
        self.fail = np.concatenate([self.fail, fail])
        self.met = np.concatenate([self.met, met])

    def children(self, ids: IntArray) -> IntArray:
        kids = self.table.children(ids)
        self._grow()
        return kids


def layer_bits(
    problem: Problem,
    cand: Candidate,
    which: int,
    n: FloatArray,
    W0: FloatArray,
    W1: FloatArray,
    a0: FloatArray,
    a1: FloatArray,
) -> tuple[IntArray, IntArray]:
    """Per cell, the bit sets of ``problem``'s constraints it breaks everywhere (its own
    layer's, :func:`~.cells._own_ok`) and holds everywhere as far as this layer decides
    (:func:`_met`; a constraint of the pair: not set)."""
    fails, _, _ = cells._own_ok(problem, cand, which, n, W0, W1, a0, a1)
    met = _met(problem, cand, which, n, W0, W1, a0, a1)
    pair = np.array([not _own(c) for c in problem.constraints], dtype=bool)
    met[:, pair] = False
    return _bits(fails), _bits(met)


@dataclass(frozen=True)
class _Cellset:
    """Cells with their bit sets (:func:`layer_bits`), for :func:`_judge`."""

    cells: cells._Cells
    fail: IntArray
    met: IntArray


def thickness_rule(
    c: Constraint, L1: cells._Cells, L2: cells._Cells, i: IntArray, j: IntArray
) -> tuple[NDArray[np.bool_], NDArray[np.bool_]]:
    """Per cell pair (i, j), whether the folded thickness bound ``c`` (mm) is broken at every
    design of the pair, and whether it holds at every one: t_d = W1 cos(alpha1 / 2) +
    W2 cos(alpha2 / 2) grows with W and falls with alpha, so it lies between the sum of the
    cells' depths at (W0, alpha1) and at (W1, alpha0) (:class:`~.cells._Cells` h0, h1), judged
    with the relative slack :data:`~.cells.SLACK` against breaking and against holding."""
    up, down = 1 + cells.SLACK, 1 - cells.SLACK
    h_lo, h_hi = L1.h0[i] + L2.h0[j], L1.h1[i] + L2.h1[j]
    if c.sense == "max":
        return h_lo * down > c.bound, h_hi * up <= c.bound
    return h_hi * up < c.bound, h_lo * down >= c.bound


def _judge(
    st: cells.Setting,
    A: _Cellset,
    B: _Cellset,
    I: IntArray,
    J: IntArray,
    worst: float,
    checks: Sequence[CellCheck],
    open_mask: int,
    parent: IntArray | None = None,
) -> tuple[IntArray, IntArray, FloatArray, IntArray]:
    """The cell pairs (I, J) that may hold a design lighter than ``worst`` (g) of some open
    check's problem (bit i of ``open_mask``: ``checks[i]``), their mass lower bounds (g) and
    the bit sets of the checks each may answer (module docstring): every bound as
    :func:`~.cells._judge` computes it. ``parent``: per pair, the bit set of the pair it was
    cut from (a child lies in its parent: what was shown of the parent holds of it)."""
    p = st.problem
    (c1, c2), (w1, w2) = st.sheets, st.low
    lay = p.layout
    m1, m2 = c1.material, c2.material
    L1, L2 = A.cells, B.cells
    up, down = 1 + cells.SLACK, 1 - cells.SLACK
    single = all(ch.bits & (ch.bits - 1) == 0 for ch in checks)
    outs: list[tuple[IntArray, IntArray, FloatArray, IntArray]] = []
    for s in range(0, len(I), cells.CHUNK):
        i, j = I[s : s + cells.CHUNK], J[s : s + cells.CHUNK]
        lb = layer_mass(m1.density, c1.t, L1.W0[i], length_sum(lay, L1.n[i], L2.E0[j]), lay)
        lb = lb + layer_mass(m2.density, c2.t, L2.W0[j], length_sum(lay, L2.n[j], L1.E0[i]), lay)
        lb = lb + connector_mass(m1.density, c1.t, lay, L1.E0[i], L2.E0[j], L1.h0[i] + L2.h0[j])
        lb = np.asarray(lb) * down
        light = np.flatnonzero(lb < worst)  # the others: dropped for every check
        i, j, lb = i[light], j[light], lb[light]
        alive = np.ones(len(i), dtype=bool)
        fail = A.fail[i] | B.fail[j]
        met = A.met[i] & B.met[j]
        for k, c in enumerate(p.constraints):
            q, bit = c.quantity, np.int64(1 << k)
            bad: NDArray[np.bool_] | None = None
            good: NDArray[np.bool_] | None = None
            if q == THICKNESS:
                bad, good = thickness_rule(c, L1, L2, i, j)
            elif q == MASS and c.sense == "max":
                bad = lb > c.bound
            elif stiffness_along(q) and c.sense == "min":
                bad = np.zeros(len(i), dtype=bool)
                for v1, v2 in zip(L1.views, L2.views, strict=True):
                    u, v, f, g = cells._terms(q, v1, v2, w1.t, w2.t)
                    bad |= (u[i] + v[j]) * f[i] * g[j] * up < c.bound
                if st.halves is not None:
                    few = (fail & (fail - 1)) == 0 if single else np.ones(len(i), dtype=bool)
                    sel = np.flatnonzero(~bad & alive & few)
                    inner = cells._inner_upper(q, L1, L2, i[sel], j[sel])
                    bad[sel] = inner * up < c.bound
            if bad is not None:
                fail = np.where(bad, fail | bit, fail)
            if good is not None:
                met = np.where(good, met | bit, met)
        mask = np.zeros(len(i), dtype=np.int64)
        for at, ch in enumerate(checks):
            if not (open_mask >> at) & 1:
                continue
            ok = alive & ((fail & ~np.int64(ch.bits)) == 0)
            if ch.negated:
                ok &= (met & np.int64(ch.bits)) != ch.bits
            mask = np.where(ok, mask | np.int64(1 << at), mask)
        if parent is not None:
            mask &= parent[s : s + cells.CHUNK][light]
        keep = mask != 0
        outs.append((i[keep], j[keep], lb[keep], mask[keep]))
    if not outs:
        return I[:0], J[:0], np.empty(0), np.empty(0, dtype=np.int64)
    return (
        np.concatenate([o[0] for o in outs]),
        np.concatenate([o[1] for o in outs]),
        np.concatenate([o[2] for o in outs]),
        np.concatenate([o[3] for o in outs]),
    )


def _draw(
    st: cells.Setting,
    full: Problem,
    A: _Cellset,
    B: _Cellset,
    I: IntArray,
    J: IntArray,
    lb: FloatArray,
    worst: float,
    checks: Sequence[CellCheck],
    open_mask: int,
    seed: int,
) -> DesignPoints | None:
    """Designs to evaluate exactly: :data:`~.cells.PROBE_POINTS` points drawn in each of the
    :data:`~.cells.PROBE_PAIRS` pairs of least mass bound, those that :func:`_judge` keeps for
    some open check at the points themselves, the :data:`~.cells.PROBES` lightest; None when
    none (any design will do: the draws are fixed by ``seed``)."""
    k = min(cells.PROBE_PAIRS, len(I))
    pick = np.argpartition(lb, k - 1)[:k] if len(I) > k else np.arange(len(I))
    i = np.repeat(I[pick], cells.PROBE_POINTS)
    j = np.repeat(J[pick], cells.PROBE_POINTS)
    L1, L2 = A.cells, B.cells
    u = np.random.default_rng(seed).random((4, len(i)))
    W1 = L1.W0[i] + u[0] * (L1.W1[i] - L1.W0[i])
    a1 = L1.a0[i] + u[1] * (L1.a1[i] - L1.a0[i])
    W2 = L2.W0[j] + u[2] * (L2.W1[j] - L2.W0[j])
    a2 = L2.a0[j] + u[3] * (L2.a1[j] - L2.a0[j])
    sets = []
    for which, n, W, a in ((1, L1.n[i], W1, a1), (2, L2.n[j], W2, a2)):
        P, kept = cells._cells(st, which, n, W, W, a, a)
        cand = st.sheets[which - 1]
        fail, met = layer_bits(full, cand, which, P.n, P.W0, P.W1, P.a0, P.a1)
        sets.append((_Cellset(P, fail, met), kept))
    (P1, k1), (P2, k2) = sets
    both = np.intersect1d(k1, k2)
    pi, pj = np.searchsorted(k1, both), np.searchsorted(k2, both)
    pi, pj, mass, _ = _judge(replace(st, problem=full), P1, P2, pi, pj, worst, checks, open_mask)
    if not len(pi):
        return None
    if len(pi) > cells.PROBES:
        sel = np.argpartition(mass, cells.PROBES - 1)[: cells.PROBES]
        pi, pj = pi[sel], pj[sel]
    C1, C2 = P1.cells, P2.cells
    return DesignPoints.of(
        LayerPoints(C1.n[pi], C1.W0[pi], C1.a0[pi]), LayerPoints(C2.n[pj], C2.W0[pj], C2.a0[pj])
    )


def _answers(
    problem: Problem,
    pair: tuple[Candidate, Candidate],
    tables: Tables,
    x: DesignPoints,
    goal: float,
    checks: Sequence[CellCheck],
    open_mask: int,
) -> int:
    """The bit set of the open checks answered by the designs ``x``: one of them meets every
    constraint of the check's problem (P's certified values, ``point_values``, no slack: the
    cells' and the branch and bound's rule) with a mass below ``goal`` (g)."""
    vals = point_values(problem, *pair, x, tables)
    light = np.asarray(vals[MASS], dtype=np.float64) < goal
    if not light.any():
        return 0
    held = np.stack(
        [np.asarray(c.satisfied(vals[c.quantity], rtol=0.0), bool) for c in problem.constraints],
        axis=1,
    )
    found = 0
    for at, ch in enumerate(checks):
        if not (open_mask >> at) & 1:
            continue
        others = np.array([not (ch.bits >> k) & 1 for k in range(held.shape[1])], dtype=bool)
        if bool(np.any(light & held[:, others].all(axis=1))):
            found |= 1 << at
    return found


def answered(
    problem: Problem,
    pair: tuple[Candidate, Candidate],
    tables: Tables,
    x: DesignPoints,
    goal: float,
    check: CellCheck,
) -> bool:
    """Whether one of the designs ``x`` on sheets ``pair`` answers ``check`` (binding): the
    rule of the shared search's evaluated designs (:func:`_answers`)."""
    return _answers(problem, pair, tables, x, goal, [check], 1) == 1


def shared_search(
    problem: Problem,
    everything: Sequence[tuple[Candidate, Candidate]],
    tables: Tables,
    checks: Sequence[CellCheck],
    goal: float,
    budget: int = cells.BUDGET,
    gap: float = cells.CELL_GAP,
) -> Shared:
    """The checks' shared cells search of the module docstring over the sheet pairs
    ``everything`` of ``problem`` (a problem of :func:`applies`) below ``goal`` (g): one queue
    of cell pairs, each with the bit set of the checks it may answer, those of least mass bound
    split first (:data:`~.cells.BATCH` at a time, each pair's relatively wider cell halved),
    designs drawn in the lightest evaluated every :data:`~.cells.PROBE_EVERY` rounds, until no
    pair is left below ``goal`` less ``gap`` (relative), or ``budget`` pairs were judged (not
    settled). A search whose first cell pairs alone (counted before they are formed,
    :func:`_first_count`) reach ``budget`` is not run: not settled, nothing found, none judged
    (films-13-cont: 20.7 M first pairs against 2e7 judged and one probe round, 1.6 s of CPU
    that settled nothing; its three answers are found by the caller's polish instead). Only a
    stop: nothing is proven of its checks, each is left to its caller as unknown."""
    own = 0
    for ch in checks:
        own |= ch.bits
    kept = tuple(c for k, c in enumerate(problem.constraints) if not ((own >> k) & 1 and _own(c)))
    loose = replace(problem, constraints=kept)  # the tables keep the cells only checks drop
    worst = goal * (1 + cells.SLACK)
    open_mask = (1 << len(checks)) - 1
    found = 0
    layers: dict[tuple[int, Candidate, Candidate], _Layer] = {}
    settings, loose_settings = [], []
    tabs: list[tuple[_Layer, _Layer]] = []
    for c1, c2 in everything:
        st = cells.setting(loose, c1, c2, tables)
        settings.append(replace(st, problem=problem))
        loose_settings.append(st)
        two = []
        for which in (1, 2):
            key = (which, st.sheets[which - 1], st.low[which - 1])
            if key not in layers:
                layers[key] = _Layer(st, problem, which)
            two.append(layers[key])
        tabs.append((two[0], two[1]))

    unique = list(layers.values())  # the layers' tables, each shared by its sheet pairs
    at_layer = {id(lay): t for t, lay in enumerate(unique)}
    layer_of = np.array([[at_layer[id(a)], at_layer[id(b)]] for a, b in tabs], dtype=np.int64)

    def sets(k: int) -> tuple[_Cellset, _Cellset]:
        a, b = tabs[k]
        return (
            _Cellset(a.table.cells, a.fail, a.met),
            _Cellset(b.table.cells, b.fail, b.met),
        )

    formed = 0
    for k in range(len(settings)):
        A, B = sets(k)
        formed += _first_count(A.fail, B.fail, checks)
    if formed >= budget:  # its first pairs alone reach its limit: stopped before judging them
        return Shared({ch.name: False for ch in checks}, {}, False, 0)
    Ks, Is, Js, Bs, Ms = [], [], [], [], []
    judged = 0
    for k, st in enumerate(settings):
        A, B = sets(k)
        I, J = _first_pairs(A.fail, B.fail, checks)
        judged += len(I)
        I, J, lb, M = _judge(st, A, B, I, J, worst, checks, open_mask)
        Ks.append(np.full(len(I), k, dtype=np.int64))
        Is.append(I)
        Js.append(J)
        Bs.append(lb)
        Ms.append(M)
    K, I, J = np.concatenate(Ks), np.concatenate(Is), np.concatenate(Js)
    lb, M = np.concatenate(Bs), np.concatenate(Ms)
    rounds, settled = 0, True
    spend, charged = current_budget(), 0
    while len(I):
        if rounds % cells.PROBE_EVERY == 0:
            for k, sel in _draw_places(K, lb, M, open_mask, len(checks)):
                A, B = sets(k)
                x = _draw(
                    loose_settings[k], problem, A, B, I[sel], J[sel], lb[sel], worst, checks,
                    open_mask, rounds,
                )  # fmt: skip
                if x is None:
                    continue
                got = _answers(problem, everything[k], tables, x, goal, checks, open_mask)
                found |= got
                open_mask &= ~got
            M = M & np.int64(open_mask)
            keep = M != 0
            K, I, J, lb, M = K[keep], I[keep], J[keep], lb[keep], M[keep]
        rounds += 1
        if not len(I) or float(lb.min()) >= goal * (1 - gap):
            break
        if judged >= budget or budget_spent():
            settled = False
            break
        if spend is not None:
            spend.charge(judged - charged)
            charged = judged
        if len(I) > cells.BATCH:
            take = np.zeros(len(I), dtype=bool)
            take[np.argpartition(lb, cells.BATCH - 1)[: cells.BATCH]] = True
        else:
            take = np.ones(len(I), dtype=bool)
        pK, pI, pJ, pM = K[take], I[take], J[take], M[take]
        K, I, J, lb, M = K[~take], I[~take], J[~take], lb[~take], M[~take]
        kids = np.empty((len(pK), 2), dtype=np.int64)
        one = np.empty(len(pK), dtype=bool)
        for k in np.unique(pK):
            sel = pK == k
            a, b = tabs[k]
            w1 = cells._width(a.table.cells, pI[sel], a.table.spans)
            w2 = cells._width(b.table.cells, pJ[sel], b.table.spans)
            one[sel] = w1 >= w2
        for which in (1, 2):  # each layer's cells split once per round, whichever pairs ask
            side = one if which == 1 else ~one
            own = layer_of[pK, which - 1]
            for t in np.unique(own[side]):
                sel = side & (own == t)
                kids[sel] = unique[t].children((pI if which == 1 else pJ)[sel])
        nK, nM = np.repeat(pK, 2), np.repeat(pM, 2)
        nI = np.where(np.repeat(one, 2), kids.reshape(-1), np.repeat(pI, 2))
        nJ = np.where(np.repeat(one, 2), np.repeat(pJ, 2), kids.reshape(-1))
        ok = (nI >= 0) & (nJ >= 0)
        nK, nI, nJ, nM = nK[ok], nI[ok], nJ[ok], nM[ok]
        judged += len(nK)
        parts = [(K, I, J, lb, M)]
        for k in np.unique(nK):
            sel = nK == k
            A, B = sets(k)
            gI, gJ, gb, gM = _judge(
                settings[k], A, B, nI[sel], nJ[sel], worst, checks, open_mask, nM[sel]
            )
            parts.append((np.full(len(gI), k, dtype=np.int64), gI, gJ, gb, gM))
        K = np.concatenate([x[0] for x in parts])
        I = np.concatenate([x[1] for x in parts])
        J = np.concatenate([x[2] for x in parts])
        lb = np.concatenate([x[3] for x in parts])
        M = np.concatenate([x[4] for x in parts])
    answers = {ch.name: bool((found >> at) & 1) for at, ch in enumerate(checks)}
    starts: dict[str, dict[int, Start]] = {}
    for at, ch in enumerate(checks):
        if answers[ch.name] or not settled:
            continue
        mine = ((M >> at) & 1) == 1
        per: dict[int, Start] = {}
        for k in np.unique(K[mine]).tolist():
            sel = mine & (k == K)
            a, b = tabs[k]
            L1, L2 = a.table.cells, b.table.cells
            i, j = I[sel], J[sel]
            lo = np.stack([L1.n[i], L1.W0[i], L1.a0[i], L2.n[j], L2.W0[j], L2.a0[j]], axis=1)
            hi = np.stack([L1.n[i], L1.W1[i], L1.a1[i], L2.n[j], L2.W1[j], L2.a1[j]], axis=1)
            per[int(k)] = (lo, hi, lb[sel].copy())
        starts[ch.name] = per
    return Shared(answers, starts, settled, judged)


def _draw_places(
    K: IntArray, lb: FloatArray, M: IntArray, open_mask: int, count: int
) -> list[tuple[int, IntArray]]:
    """Where the shared search draws designs on a probe round: per sheet pair (index of
    ``K``), the indices of queued pairs to draw in, lightest first. The
    :data:`~.cells.PROBE_PAIRS` lightest pairs of the queue in its :data:`~.cells.PROBE_SHEETS`
    lightest sheet pairs (as :func:`~.cells.search_pairs`), and, for each open check (bit of
    ``open_mask`` among ``count``) whose lightest pair is not among those, the lightest
    pairs that carry it (bit set ``M``) in its lightest sheet pair: a check whose pairs are
    not the queue's lightest is drawn in too (where a design that answers it may lie). Only
    where designs are drawn: every answer is judged by :func:`_answers`."""
    out: list[tuple[int, IntArray]] = []
    low = np.argpartition(lb, min(cells.PROBE_PAIRS, len(lb)) - 1)[: cells.PROBE_PAIRS]
    order = low[np.argsort(lb[low])]
    for k in list(dict.fromkeys(K[order].tolist()))[: cells.PROBE_SHEETS]:
        out.append((int(k), order[K[order] == k]))
    covered = 0
    for at in order.tolist():
        covered |= int(M[at])
    for at in range(count):
        bit = 1 << at
        if not (open_mask & bit) or covered & bit:
            continue
        mine = np.flatnonzero((M & np.int64(bit)) != 0)
        if not len(mine):
            continue
        k = int(K[mine[np.argmin(lb[mine])]])
        mine = mine[K[mine] == k]
        few = min(cells.PROBE_PAIRS, len(mine))
        pick = mine[np.argpartition(lb[mine], few - 1)[:few]]
        out.append((k, pick[np.argsort(lb[pick])]))
        for i in pick.tolist():
            covered |= int(M[i])
    return out


def _first_count(F1: IntArray, F2: IntArray, checks: Sequence[CellCheck]) -> int:
    """How many pairs :func:`_first_pairs` forms of the first cells (bit sets ``F1``, ``F2``
    of the constraints each breaks), counted by groups of equal bit sets without forming them."""
    allowed = [0, *(ch.bits for ch in checks)]
    u1, n1 = np.unique(F1, return_counts=True)
    u2, n2 = np.unique(F2, return_counts=True)
    total = 0
    for f1, c1 in zip(u1.tolist(), n1.tolist(), strict=True):
        for f2, c2 in zip(u2.tolist(), n2.tolist(), strict=True):
            if any((f1 | f2) & ~bits == 0 for bits in allowed):
                total += c1 * c2
    return total


def _first_pairs(
    F1: IntArray, F2: IntArray, checks: Sequence[CellCheck]
) -> tuple[IntArray, IntArray]:
    """The pairs of the first cells that some check may keep by their own layers' bounds alone:
    a cell i of layer 1 and j of layer 2 whose broken constraints (bit sets ``F1[i] | F2[j]``)
    are all of one check's (``_judge`` drops the others for every check), every such pair."""
    allowed = [0, *(ch.bits for ch in checks)]
    Is, Js = [], []
    for f1 in np.unique(F1).tolist():
        rows = np.flatnonzero(f1 == F1)
        for f2 in np.unique(F2).tolist():
            if not any((f1 | f2) & ~bits == 0 for bits in allowed):
                continue
            cols = np.flatnonzero(f2 == F2)
            grid = np.meshgrid(rows, cols, indexing="ij")
            Is.append(grid[0].reshape(-1))
            Js.append(grid[1].reshape(-1))
    if not Is:
        return np.empty(0, dtype=np.int64), np.empty(0, dtype=np.int64)
    I, J = np.concatenate(Is).astype(np.int64), np.concatenate(Js).astype(np.int64)
    order = np.lexsort((J, I))  # the order of the whole grid (i first)
    return I[order], J[order]


def checks_of(problem: Problem, names: Sequence[str], certified: bool) -> list[CellCheck]:
    """The :class:`CellCheck` of each constraint name (negated when ``certified``)."""
    out = []
    for name in names:
        bits = sum(1 << k for k, c in enumerate(problem.constraints) if c.name == name)
        out.append(CellCheck(name, bits, certified))
    return out
