"""The cells' search of continuous W and alpha on independent layers with material choices
(:mod:`corrugate.solver.cells`), checked against a second method, the plain path: every sheet
pair searched from its whole domain by the branch and bound, the least of their optima:

* the answer by cells is the plain path's optimum (both certified to the relative gap
  GAP_RTOL), nominal and with the default worst-case tolerances;
* each pair's floors (the first cells alone, the cells' search) are at most that pair's optimum
  found by the branch and bound;
* the cells' upper bound of a certified stiffness over a cell pair (its inner boxes,
  docs/theory.md section 5) is at least the certified value (``point_values``, tolerances
  included) at designs drawn in the pair, within the cells' slack;
* a design on its active bounds (a pair's optimum, and it polished at a margin of 1e-13) keeps
  the cell pair that is exactly it: the slack covers the judge's rounding.
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import replace

import numpy as np
import pytest

from corrugate.solver import Problem, cells
from corrugate.solver.bnb import GAP_RTOL, branch_and_bound
from corrugate.solver.choices import CellFloors, floors
from corrugate.solver.polish import FINE, polish
from corrugate.solver.quantities import Tables, point_values
from corrugate.solver.solve import optimize, pairs
from corrugate.spec.schema import Spec
from sheet_specs import continuous_two_sheets, designs_in_cells


def _problem(tolerances: bool) -> Problem:
    """The two-sheet continuous problem of :func:`sheet_specs.continuous_two_sheets`."""
    return Problem.from_spec(Spec.model_validate(tomllib.loads(continuous_two_sheets(tolerances))))


_PLAIN: dict[bool, list[float]] = {}


def _plain(tolerances: bool) -> list[float]:
    """Each pair's optimum (g; inf: none) by the branch and bound of its whole domain."""
    if tolerances not in _PLAIN:
        p = _problem(tolerances)
        out = []
        for a, b in pairs(p):
            r = branch_and_bound(p, a, b)
            assert r.certified
            out.append(r.value if r.point is not None else math.inf)
        _PLAIN[tolerances] = out
    return _PLAIN[tolerances]


def _same_optimum(tolerances: bool) -> None:
    p = _problem(tolerances)
    assert isinstance(floors(p), CellFloors)  # the cells' path is taken
    got = optimize(p, prune=True)
    plain = _plain(tolerances)
    assert got.certified and got.point is not None
    best = min(plain)
    assert math.isfinite(best)
    # both certified to the relative gap GAP_RTOL: within twice of each other
    assert abs(got.value - best) <= 2 * GAP_RTOL * best
    k = pairs(p).index(got.candidates)
    assert abs(plain[k] - got.value) <= 2 * GAP_RTOL * best  # on the same sheet pair
    # the design meets every constraint exactly (continuous variables: no slack)
    vals = point_values(p, *got.candidates, got.point.arrays(), Tables(p))
    for c in p.constraints:
        assert bool(c.satisfied(vals[c.quantity], rtol=0.0)), c.name


def test_nominal_answer_is_the_plain_optimum() -> None:
    _same_optimum(False)


@pytest.mark.slow
def test_tolerance_answer_is_the_plain_optimum() -> None:
    _same_optimum(True)


@pytest.mark.slow
@pytest.mark.parametrize("tolerances", [False, True])
def test_floors_at_most_each_pairs_optimum(tolerances: bool) -> None:
    p = _problem(tolerances)
    fl = floors(p)
    assert isinstance(fl, CellFloors)
    plain = _plain(tolerances)
    for k, best in enumerate(plain):
        coarse, fine = fl.coarse(k), fl.fine(k, math.inf)
        assert coarse <= fine * (1 + 1e-12) or math.isinf(best)
        assert fine <= best * (1 + 1e-12)
        assert coarse <= best * (1 + 1e-12)
    assert any(math.isfinite(b) for b in plain)  # some pair holds a design


def test_inner_bound_at_least_the_certified_value() -> None:
    p = _problem(True)
    tables = Tables(p)
    rng = np.random.default_rng(7)
    stiff = [c.quantity for c in p.constraints if c.quantity.eta is not None]
    dW, da = p.tolerances.W, p.tolerances.alpha
    for a, b in pairs(p):
        st = cells.setting(p, a, b, tables)
        k = 2000  # drawn cells, those that may meet their own layer's bounds kept
        n1, n2 = rng.integers(5, 8, k).astype(float), rng.integers(5, 8, k).astype(float)
        W1, W2 = rng.uniform(7, 10.8, k), rng.uniform(7, 10.8, k)
        a1, a2 = rng.uniform(70, 95, k), rng.uniform(70, 95, k)
        w, v = 2 * dW * rng.uniform(0.05, 1, k), 2 * da * rng.uniform(0.05, 1, k)
        L1 = cells._cells(st, 1, n1, W1, W1 + w, a1, a1 + v)[0]
        L2 = cells._cells(st, 2, n2, W2, W2 + w, a2, a2 + v)[0]
        i = j = np.arange(min(len(L1), len(L2)))
        assert len(i) > 20
        u = rng.uniform(size=(4, len(i)))
        x = designs_in_cells(L1, L2, i, u)
        vals = point_values(p, a, b, x, tables)
        for q in stiff:
            upper = cells._inner_upper(q, L1, L2, i, j)
            assert np.all(np.isfinite(upper))
            assert np.all(upper * (1 + cells.SLACK) >= vals[q]), q.key
            # and it is tight: within a few per cent of the certified value at these widths
            assert np.all(upper <= vals[q] * 1.5)


def test_a_domain_too_wide_for_the_cells_takes_the_plain_search(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """With more first cell pairs than cells.FIRST_MOST (here 0: every domain) the cells give up
    at once and the solve is the plain search (no cells' boxes kept), whose answer is the same
    optimum; with the default the cells' path is taken (its start boxes kept)."""
    p = _problem(False)
    assert optimize(p, prune=True).starts is not None
    monkeypatch.setattr(cells, "FIRST_MOST", 0)
    got = optimize(p, prune=True)
    assert got.starts is None and got.certified and got.point is not None
    best = min(_plain(False))
    assert abs(got.value - best) <= 2 * GAP_RTOL * best


def test_each_view_is_the_model_at_the_cells_moved_by_its_shift() -> None:
    """The views of a layer's cells (all the tolerance box's shifts computed in one call) are,
    value for value, the interval model's upper bounds at the cells moved by each shift alone
    and the extents there, as one call per shift gives them."""
    from corrugate.mechanics.creases import flexibility
    from corrugate.mechanics.profiles import profile_moduli
    from corrugate.solver import tolerance_box
    from corrugate.solver.interval import Interval

    p = _problem(True)
    p = replace(p, constraints=())  # every cell kept
    a, b = pairs(p)[1]
    st = cells.setting(p, a, b, Tables(p))
    assert len(st.shifts) == 5  # nominal and the four corners
    rng = np.random.default_rng(3)
    k = 500
    n = rng.integers(5, 8, k).astype(float)
    W0, a0 = rng.uniform(7, 10, k), rng.uniform(70, 95, k)
    W1, a1 = W0 + rng.uniform(0, 1, k), a0 + rng.uniform(0, 5, k)
    for which in (1, 2):
        L, idx = cells._cells(st, which, n, W0, W1, a0, a1)
        assert len(idx) == k
        cand = st.low[which - 1]
        m = cand.material
        for view, (dW, da) in zip(L.views, st.shifts, strict=True):
            mW0, ma0 = tolerance_box.moved(W0[idx], a0[idx], dW, da)
            mW1, ma1 = tolerance_box.moved(W1[idx], a1[idx], dW, da)
            half = Interval(np.radians(ma0), np.radians(ma1)) * 0.5
            mod = profile_moduli(
                p.profile_kind.of_half(Interval(mW0, mW1), half),
                float(m.E),
                float(m.nu),
                float(cand.t),
                p.model,
                flexibility(m.crease_stiffness),
            )
            for got, v in zip(view[:4], (mod.Ecx, mod.Ecy, mod.Ebx, mod.Eby), strict=True):
                want = np.broadcast_to(np.asarray(Interval.of(v).hi, np.float64), got.shape)
                assert np.array_equal(got, want)
            assert np.array_equal(view[4], cells._extent(n[idx], mW0, ma0))
            assert np.array_equal(view[5], cells._extent(n[idx], mW1, ma1))


@pytest.mark.parametrize("tolerances", [False, True])
def test_a_design_on_its_bounds_keeps_its_cell_pair(tolerances: bool) -> None:
    """The cells' slack (:data:`~corrugate.solver.cells.SLACK`, 1e-13) covers the rounding of
    what the judge computes in plain floating point: each pair's optimum by the branch and bound
    (a second method; its active constraints met to about 1e-12) and that optimum polished at a
    margin of 1e-13, both designs of the problem by its own rule (``point_values``), keep the
    cell pair that is exactly them (zero widths), with a mass bound at most their mass."""
    p = _problem(tolerances)
    tables = Tables(p)
    kept = 0
    for a, b in pairs(p):
        r = branch_and_bound(p, a, b)
        if r.point is None:
            continue
        exact = cells.judge_of(p, a, b, tables)
        fine = polish(p, a, b, r.point, tables, exact, FINE)
        assert fine is not None
        st = cells.setting(p, a, b, tables)
        for x in (r.point.arrays(), fine.point.arrays()):
            mass, ok = exact(x)
            assert bool(ok[0])  # a design of the problem by its own rule
            one, two = x.layer(0), x.layer(1)
            L1 = cells._cells(st, 1, one.n, one.W, one.W, one.alpha, one.alpha)[0]
            L2 = cells._cells(st, 2, two.n, two.W, two.W, two.alpha, two.alpha)[0]
            assert len(L1) == len(L2) == 1  # each cell meets its own layer's bounds
            zero = np.zeros(1, dtype=np.int32)
            i, _, lb = cells._judge(st, L1, L2, zero, zero, math.inf)
            assert len(i) == 1 and lb[0] <= mass[0]
            kept += 1
    assert kept >= 4


@pytest.mark.parametrize("tolerances", [False, True])
def test_first_pairs_keep_every_pair_the_judge_keeps(tolerances: bool) -> None:
    """The first cell pairs formed (cells._first_pairs: cells no constraint drops whole, pairs
    whose separable mass floor is below the incumbent) hold every first pair the judge keeps of
    the full grid, with the same fired constraints, at an incumbent a little above the
    plain per-pair optimum (so the mass floor prunes) and with none; a sheet pair left with no
    first pair has no design lighter than that incumbent by its plain branch and bound."""
    if tolerances:  # the narrow spec (the module's cached plain optima: a quick test)
        p, plain = _problem(True), _plain(True)
    else:  # the wide one: the sides and the thickness drop cells
        text = continuous_two_sheets(False, wide=True)
        p = Problem.from_spec(Spec.model_validate(tomllib.loads(text)))
        plain = []
        for a, b in pairs(p):
            r = branch_and_bound(p, a, b)
            assert r.certified
            plain.append(r.value if r.point is not None else math.inf)
    tables = Tables(p)
    best = min(plain)
    assert math.isfinite(best)
    pruned = 0
    for worst in (best * 1.02, math.inf):
        for k, (a, b) in enumerate(pairs(p)):
            st = cells.setting(p, a, b, tables)
            L1, L2 = cells._Table(st, 1).cells, cells._Table(st, 2).cells
            grid = np.meshgrid(np.arange(len(L1)), np.arange(len(L2)), indexing="ij")
            I, J = (g.reshape(-1).astype(np.int32) for g in grid)
            f_all: set[int] = set()
            gI, gJ, _ = cells._judge(st, L1, L2, I, J, worst, f_all)
            fI, fJ = cells._first_pairs(st, L1, L2, worst, set())
            f_few: set[int] = set()
            cells._first_pairs(st, L1, L2, worst, f_few)
            kept = set(zip(gI.tolist(), gJ.tolist(), strict=True))
            formed = set(zip(fI.tolist(), fJ.tolist(), strict=True))
            assert kept <= formed
            assert len(formed) <= len(I)
            hI, hJ, _ = cells._judge(st, L1, L2, fI, fJ, worst, f_few)
            assert set(zip(hI.tolist(), hJ.tolist(), strict=True)) == kept
            assert f_all <= f_few  # every constraint the full grid fires, fired
            if not len(fI):
                assert plain[k] >= worst  # pruned whole: the plain search agrees
            pruned += len(I) - len(fI)
    assert pruned > 0  # the floors and the cells' checks drop pairs on this spec


@pytest.mark.parametrize("tolerances", [False, True])
def test_seeded_answer_is_the_plain_optimum(
    tolerances: bool, monkeypatch: pytest.MonkeyPatch
) -> None:
    """With a design sought before the first pairs (cells.SEED_FROM 0: the first pairs formed
    below a finite incumbent, so whole sheet pairs may be dropped by their mass floors), the
    answer is the plain per-pair branch and bound's optimum."""
    monkeypatch.setattr(cells, "SEED_FROM", 0)
    _same_optimum(tolerances)


@pytest.mark.parametrize("tolerances", [False, True])
@pytest.mark.parametrize("alone", [1, 10**9])
def test_sheet_pairs_judged_in_one_pass_as_each_alone(
    tolerances: bool, alone: int, monkeypatch: pytest.MonkeyPatch
) -> None:
    """cells._judge_pairs judges the cell pairs of several sheet pairs, handed mixed, in one
    pass (each pair's cells gathered from its own sheets' tables, then its terms) and each
    sheet pair apart (its terms over its tables' cells, then the pairs'): the pairs it keeps, their mass bounds and
    the constraints fired are those of cells._judge of each sheet pair alone, bit for bit, with
    every sheet pair in one pass (``alone`` = 1e9) and with each apart (``alone`` = 1); and a
    kept pair's mass bound is the mass (corrugate.mechanics.mass, by hand: both blanks and the
    band at the cells' least W, extents and depths, on its own sheet pair's sheets) less the
    slack, so no pair took another sheet pair's density or thickness."""
    from corrugate.geometry.layouts import length_sum
    from corrugate.mechanics.mass import connector_mass, layer_mass

    monkeypatch.setattr(cells, "ALONE", alone)
    p = _problem(tolerances)
    tables = Tables(p)
    settings = [cells.setting(p, a, b, tables) for a, b in pairs(p)]
    # one table per layer and sheet, as cells.search_pairs shares them
    made: dict[tuple[int, object], int] = {}
    cellsets: list[cells._Cells] = []
    tab_of = np.zeros((len(settings), 2), dtype=np.int64)
    for k, st in enumerate(settings):
        for which in (1, 2):
            key = (which, st.sheets[which - 1])
            if key not in made:
                made[key] = len(cellsets)
                cellsets.append(cells._Table(st, which).cells)
            tab_of[k, which - 1] = made[key]
    assert len(cellsets) < 2 * len(settings)  # tables shared by sheet pairs
    rng = np.random.default_rng(7)
    Ks, Is, Js = [], [], []
    for k in range(len(settings)):
        n1, n2 = len(cellsets[tab_of[k, 0]]), len(cellsets[tab_of[k, 1]])
        m = 300 + 200 * k  # some sheet pairs with fewer pairs than cells, some with more
        Ks.append(np.full(m, k, dtype=np.int16))
        Is.append(rng.integers(0, n1, m).astype(np.int32))
        Js.append(rng.integers(0, n2, m).astype(np.int32))
    K, I, J = np.concatenate(Ks), np.concatenate(Is), np.concatenate(Js)
    # as a round of cells.search_pairs hands them: the sheet pairs mixed (the least mass
    # bounds first), here shuffled
    mix = rng.permutation(len(K))
    K, I, J = K[mix], I[mix], J[mix]
    for worst in (math.inf, 1.05 * min(_plain(tolerances))):
        fired: set[int] = set()
        gK, gI, gJ, gb = cells._judge_pairs(settings, cellsets, tab_of, K, I, J, worst, fired)
        assert np.all(np.diff(gK) >= 0)  # by sheet pair, each in the order given
        apart: set[int] = set()
        kept = 0
        for k, st in enumerate(settings):
            L1, L2 = cellsets[tab_of[k, 0]], cellsets[tab_of[k, 1]]
            sel = k == K
            i, j, b = cells._judge(st, L1, L2, I[sel], J[sel], worst, apart)
            mine = gK == k
            assert np.array_equal(gI[mine], i) and np.array_equal(gJ[mine], j)
            assert np.array_equal(gb[mine], b)  # bit for bit
            (c1, c2), lay = st.sheets, p.layout
            r1, r2 = c1.material.density, c2.material.density
            hand = (
                layer_mass(r1, c1.t, L1.W0[i], length_sum(lay, L1.n[i], L2.E0[j]))
                + layer_mass(r2, c2.t, L2.W0[j], length_sum(lay, L2.n[j], L1.E0[i]))
                + connector_mass(r1, c1.t, lay, L1.E0[i], L2.E0[j], L1.h0[i] + L2.h0[j])
            )
            assert np.allclose(gb[mine], hand * (1 - cells.SLACK), rtol=1e-15, atol=0.0)
            assert np.all(gb[mine] < worst)
            kept += len(i)
        assert fired == apart
        assert 0 < kept < len(K)  # the judge keeps some pairs and drops others
