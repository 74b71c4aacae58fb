"""The binding checks of a problem solved by cells, searched together
(:mod:`corrugate.solver.cell_checks`), checked against a second method:

* each answer of the shared search is that of the check's own search (the problem without the
  constraint searched by its own cells and branch and bound, :func:`~.solve._cell_binding`'s
  per-check path), nominal and with the default worst-case tolerances, binding and not;
* a constraint the cells show to hold over a cell (:func:`~.cell_checks.layer_bits`) holds at
  designs drawn in it (the problem's certified values, no slack);
* the binding check of a constraint that never fired in the cells, searched with its negation
  from the solve's boxes, gives the answer of the plain per-pair branch and bound of the
  problem without it over every sheet pair's whole domain;
* the runner-ups of a cells solve are those of the plain per-pair branch and bound, one
  incumbent per n, and the incumbents their searches start from are designs no lighter than
  its optimum per n; a runner-up whose cells stop at their crowd is shown not certified, a
  design no lighter than that optimum;
* the shared search draws designs where every open check has pairs;
* a check shown binding by a polish of the optimum binds by its own search too.
"""

from __future__ import annotations

import importlib
import math
import tomllib
from dataclasses import replace

import numpy as np
import pytest

from corrugate.solver import Problem, cell_checks, cells, solve
from corrugate.solver.bnb import GAP_RTOL, branch_and_bound
from corrugate.solver.choices import CellFloors, floors
from corrugate.solver.points import DesignPoints, LayerPoints
from corrugate.solver.quantities import Tables, point_values
from corrugate.solver.quantity import THICKNESS
from corrugate.solver.solve import (
    RUNNER_UP_GAP_RTOL,
    RUNNER_UP_SPREAD,
    Optimum,
    _cell_binding,
    _polished_witnesses,
    _runner_ups,
    _shared_cell_binding,
    _witnesses,
    optimize,
    pairs,
)
from corrugate.spec.schema import Spec
from sheet_specs import continuous_two_sheets, designs_in_cells

#: the module (its name is shadowed by the function :func:`~corrugate.solver.solve`)
solve_module = importlib.import_module("corrugate.solver.solve")


def _problem(wide: bool, tolerances: bool, extra: tuple[str, ...] = ()) -> Problem:
    """The two-sheet continuous problem of :func:`sheet_specs.continuous_two_sheets`."""
    spec = continuous_two_sheets(tolerances, wide, extra)
    return Problem.from_spec(Spec.model_validate(tomllib.loads(spec)))


@pytest.mark.parametrize("tolerances", [False, pytest.param(True, marks=pytest.mark.slow)])
def test_shared_answers_are_each_checks_own_search(tolerances: bool) -> None:
    p = _problem(True, tolerances)
    tables = Tables(p)
    opt = optimize(p, tables=tables, record=True, prune=True)
    assert opt.certified and opt.point is not None and opt.fired is not None
    tol = 2 * GAP_RTOL * opt.value
    # the checks the solve leaves to a search: those its probe near the optimum did not show
    witnessed = _witnesses(p, opt, tables, tol)
    names = [n for n in dict.fromkeys(c.name for c in p.constraints) if n not in witnessed]
    shared = _shared_cell_binding(p, opt, names, tables, tol)
    fired = {p.constraints[i].name for i in opt.fired}
    assert set(shared) == fired & set(names)  # each that fired, by the shared search
    assert True in shared.values() and False in shared.values()  # both answers exercised
    for name, answer in shared.items():
        assert answer == _cell_binding(p, opt, name, tables, tol), name


def test_a_constraint_shown_held_holds_at_designs_of_the_cell() -> None:
    p = _problem(True, True, ('sheet_max = "70 mm"',))  # the blank's (n + 1) W too
    tables = Tables(p)
    rng = np.random.default_rng(11)
    k = 3000
    shown = set()
    for a, b in pairs(p)[:2]:
        n1, n2 = rng.integers(4, 10, k).astype(float), rng.integers(4, 10, k).astype(float)
        W1, W2 = rng.uniform(1.5, 11, k), rng.uniform(1.5, 11, k)
        a1, a2 = rng.uniform(50, 110, k), rng.uniform(50, 110, k)
        w, v = rng.uniform(0, 1, k), rng.uniform(0, 10, k)
        met1 = cell_checks.layer_bits(p, a, 1, n1, W1, W1 + w, a1, a1 + v)[1]
        met2 = cell_checks.layer_bits(p, b, 2, n2, W2, W2 + w, a2, a2 + v)[1]
        u = rng.uniform(size=(4, k))
        x = DesignPoints.of(
            LayerPoints(n1, W1 + u[0] * w, a1 + u[1] * v),
            LayerPoints(n2, W2 + u[2] * w, a2 + u[3] * v),
        )
        vals = point_values(p, a, b, x, tables)
        own = [m for m, c in enumerate(p.constraints) if cell_checks._own(c)]
        for m in own:
            held = ((met1 >> m) & 1 == 1) & ((met2 >> m) & 1 == 1)
            ok = p.constraints[m].satisfied(vals[p.constraints[m].quantity], rtol=0.0)
            assert np.all(ok[held]), p.constraints[m].name
            if held.sum() > 0 and not ok.all():  # shown held in some cells, broken elsewhere
                shown.add(p.constraints[m].quantity.kind)
    # the sides both ways, the blank, t / W, the facet width, the validated facets
    assert {"Lx", "Ly", "flat", "t_over_W", "W_min", "facets_least"} <= shown, shown


def test_the_thickness_rule_at_designs_of_the_pair() -> None:
    p = _problem(True, False)
    tables = Tables(p)
    a, b = pairs(p)[1]
    st = cells.setting(replace(p, constraints=()), a, b, tables)  # every cell kept
    rng = np.random.default_rng(5)
    k = 3000
    drawn = []
    for which in (1, 2):
        n = rng.integers(4, 10, k).astype(float)
        W, alpha = rng.uniform(2, 18, k), rng.uniform(40, 150, k)
        w, v = rng.uniform(0, 1.5, k), rng.uniform(0, 15, k)
        drawn.append(cells._cells(st, which, n, W, W + w, alpha, alpha + v)[0])
    L1, L2 = drawn
    i = j = np.arange(k)
    u = rng.uniform(size=(4, k))
    x = designs_in_cells(L1, L2, i, u)
    td = point_values(p, a, b, x, tables)[THICKNESS]
    counts = []
    for c in p.constraints:
        if c.quantity != THICKNESS:
            continue
        broken, held = cell_checks.thickness_rule(c, L1, L2, i, j)
        ok = c.satisfied(td, rtol=0.0)
        assert np.all(ok[held]) and not np.any(ok[broken]), c.name
        counts += [int(held.sum()), int(broken.sum())]
    assert len(counts) == 4 and min(counts) > 10  # both bounds, both rules exercised


@pytest.mark.slow
def test_a_check_that_never_fired_is_the_plain_search() -> None:
    p = _problem(False, True)
    tables = Tables(p)
    opt = optimize(p, tables=tables, record=True, prune=True)
    assert opt.certified and opt.fired is not None
    idle = [c.name for i, c in enumerate(p.constraints) if i not in opt.fired]
    name = "constraints.thickness.max"
    assert name in idle
    tol = 2 * GAP_RTOL * opt.value
    goal = opt.value - tol
    plain = False
    for a, b in pairs(p):  # the problem without it, every pair's whole domain
        r = branch_and_bound(p.without(name), a, b, incumbent=goal, tables=tables, stop_below=goal)
        assert r.certified or r.point is not None
        plain |= r.point is not None and r.value < goal
    assert _cell_binding(p, opt, name, tables, tol) is plain


def _solved_and_plain_per_n(
    p: Problem,
) -> tuple[Tables, Optimum, int, tuple[int, int], dict[int, float]]:
    """``p`` solved by cells (recorded, pruned; asserted certified and by cells), the
    optimum's n, the runner-ups' span of n about it, and the second method: each n's least
    mass by the plain branch and bound of every sheet pair's whole domain with one incumbent
    per n (``per_n``, each asserted certified)."""
    tables = Tables(p)
    opt = optimize(p, tables=tables, record=True, prune=True)
    assert opt.certified and opt.point is not None and opt.starts is not None  # by cells
    n0 = round(opt.point.layer(0).n)
    span = (max(p.n_lo, n0 - RUNNER_UP_SPREAD), min(p.n_hi, n0 + RUNNER_UP_SPREAD))
    plain: dict[int, float] = {}
    for a, b in pairs(p):
        r = branch_and_bound(p, a, b, tables=tables, per_n=span, gap_rtol=RUNNER_UP_GAP_RTOL)
        assert r.by_n is not None
        for n, rn in r.by_n.items():
            assert rn.certified
            if rn.point is not None:
                plain[n] = min(plain.get(n, math.inf), rn.value)
    return tables, opt, n0, span, plain


@pytest.mark.slow
def test_runner_ups_of_a_cells_solve_are_the_plain_search_per_n() -> None:
    """The runner-ups of a cells solve (one cells search per n) against the plain branch and
    bound of every sheet pair's whole domain with one incumbent per n (``per_n``): the same n
    have a design, each mass within both searches' relative gap RUNNER_UP_GAP_RTOL."""
    p = _problem(True, False)
    tables, opt, _, _, plain = _solved_and_plain_per_n(p)
    rows = _runner_ups(p, opt, tables)
    assert {row.n for row in rows} == set(plain) and len(plain) >= 3
    for row in rows:
        assert row.certified
        assert abs(row.objective - plain[row.n]) <= 2 * RUNNER_UP_GAP_RTOL * plain[row.n]


def test_a_shared_search_stopped_at_its_limit_leaves_its_checks_unknown(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """Stopped at its limit of cell pairs before it settles, the shared search answers only the
    checks it found a design for (binding, as each one's own search would: such a design is the
    check's design) and leaves the others unknown, not searched one by one; the explained
    solution then says its explanation is partial."""
    p = _problem(True, False)
    tables = Tables(p)
    opt = optimize(p, tables=tables, record=True, prune=True)
    assert opt.certified and opt.fired is not None
    tol = 2 * GAP_RTOL * opt.value
    witnessed = _witnesses(p, opt, tables, tol)
    names = [n for n in dict.fromkeys(c.name for c in p.constraints) if n not in witnessed]
    full = _shared_cell_binding(p, opt, names, tables, tol)
    search = cell_checks.shared_search

    def stopped(*args: object, **kwargs: object) -> cell_checks.Shared:
        got = search(*args, **{**kwargs, "budget": 1})  # type: ignore[arg-type]
        assert not got.settled
        return got

    monkeypatch.setattr(cell_checks, "shared_search", stopped)
    cut = _shared_cell_binding(p, opt, names, tables, tol)
    assert set(cut) == set(full)
    for name, answer in cut.items():
        assert answer is None or (answer is True and full[name] is True), name
    assert None in cut.values()
    sol = solve(p, explain=True)
    unknown = {r.name for r in sol.constraints if r.binding is None}
    assert unknown and unknown <= {n for n, a in cut.items() if a is None}
    assert "explanation-partial" in {w["code"] for w in sol.warnings}
    assert sol.certified


def test_a_polished_witness_is_a_binding_answer_of_the_checks_own_search() -> None:
    """A check shown binding by a polish of the optimum (:func:`~.solve._polished_witnesses`)
    binds by the check's own search too (the problem without it searched by its own cells and
    branch and bound), and some check is shown so (the path is exercised)."""
    p = _problem(True, False)
    tables = Tables(p)
    opt = optimize(p, tables=tables, record=True, prune=True)
    assert opt.certified and opt.point is not None
    tol = 2 * GAP_RTOL * opt.value
    names = list(dict.fromkeys(c.name for c in p.constraints))
    checks = cell_checks.checks_of(p, names, True)
    shown = _polished_witnesses(p, opt, checks, tables, opt.value - tol)
    assert shown
    for ch in shown:
        assert _cell_binding(p, opt, ch.name, tables, tol) is True, ch.name


@pytest.mark.slow
def test_seeded_runner_ups_are_designs_no_lighter_than_the_plain_search_per_n(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """The incumbent a runner-up's search starts from (:func:`~.solve._runner_seed`: designs
    found at the neighbouring n, moved and polished) is a design of the problem with n fixed by
    its own rule, no lighter than that problem's optimum by the plain branch and bound of every
    sheet pair's whole domain (less its gap), and the runner-ups then found (some of them the
    seed itself, when the search finds nothing lighter) are that optimum to the gap."""
    p = _problem(True, False)
    tables, opt, _, span, plain = _solved_and_plain_per_n(p)
    seeds: list[tuple[int, float]] = []
    seed = solve_module._runner_seed

    def seen(fixed: Problem, n: int, *args: object) -> object:
        got = seed(fixed, n, *args)  # type: ignore[arg-type]
        if got is not None:
            mass, x, pair = got
            m, ok = cells.judge_of(fixed, *pair, tables)(solve_module._as_arrays(x))
            assert bool(ok[0]) and math.isclose(float(m[0]), mass, rel_tol=1e-12)
            assert round(float(x.layer(0).n)) == round(float(x.layer(1).n)) == n
            seeds.append((n, mass))
        return got

    monkeypatch.setattr(solve_module, "_runner_seed", seen)
    got = solve_module._cell_runner_ups(p, opt, tables, span)
    assert seeds  # the path is exercised
    for n, mass in seeds:
        assert mass >= plain[n] * (1 - RUNNER_UP_GAP_RTOL)
    assert set(got) == set(plain)
    for n, row in got.items():
        assert row.certified
        assert abs(row.value - plain[n]) <= 2 * RUNNER_UP_GAP_RTOL * plain[n]


def test_runner_ups_stopped_by_their_crowd_are_designs_shown_not_certified(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """A runner-up whose cells stop at their crowd (:func:`~.cells.search_pairs`' ``crowd``,
    :data:`~.solve.RUNNER_UP_CROWD` times the boxes they may leave; here every crowd given
    is made 0 and the limit 1000 cell pairs: they stop at their first pairs, more than the 10
    boxes the limit allows) is shown not certified, and its design is one of the
    problem with n fixed by the problem's own rule, no lighter than that problem's optimum by
    the plain branch and bound of every sheet pair's whole domain (less its gap): a stopped
    search proves nothing, it only shows what it found; the others are that optimum to the
    gap."""
    p = _problem(True, False)
    tables, opt, n0, span, plain = _solved_and_plain_per_n(p)
    # the crowd itself: a search given crowd 0 stops after its first pairs, before its end
    fixed = replace(p, n_lo=n0, n_hi=n0)
    fl = floors(fixed)
    assert isinstance(fl, CellFloors)
    below = plain[n0] * 1.1
    whole, _, _ = fl.search_all(below, RUNNER_UP_GAP_RTOL, 10**6, None, False, None)
    cut, _, _ = fl.search_all(below, RUNNER_UP_GAP_RTOL, 10**6, None, False, 0)
    assert cut[0].judged < whole[0].judged

    def ended(found: list[cells.CellResult]) -> bool:
        """No pair left below the incumbent (the best found, else ``below``) less the gap."""
        inc = min([below, *(r.value for r in found if r.point is not None)])
        return min(r.floor for r in found) >= inc * (1 - RUNNER_UP_GAP_RTOL)

    assert ended(whole) and not ended(cut)
    # the runner-ups: every crowd given made 0, with a limit of 1000 cell pairs (10 boxes)
    monkeypatch.setattr(solve_module, "RUNNER_UP_CELLS", 1000)
    stops: list[int] = []
    search = cells.search_pairs

    def crowded(*args: object) -> object:
        given = list(args)
        assert len(given) == 8 and given[7] == solve_module.RUNNER_UP_CROWD * 10  # the crowd
        given[7] = 0
        got = search(*given)  # type: ignore[arg-type]
        left = sum(len(r.start[0]) for r in got[0])
        if left > 10:
            stops.append(left)  # more boxes than the limit allows: not certified
        return got

    monkeypatch.setattr(cells, "search_pairs", crowded)
    got = solve_module._cell_runner_ups(p, opt, tables, span)
    assert stops and set(got) == set(plain)
    assert not all(row.certified for row in got.values())
    for n, row in got.items():
        assert row.point is not None and row.candidates is not None
        if row.certified:
            assert abs(row.value - plain[n]) <= 2 * RUNNER_UP_GAP_RTOL * plain[n]
            continue
        fixed = replace(p, n_lo=n, n_hi=n)
        m, ok = cells.judge_of(fixed, *row.candidates, tables)(solve_module._as_arrays(row.point))
        assert bool(ok[0]) and math.isclose(float(m[0]), row.value, rel_tol=1e-12)
        assert row.value >= plain[n] * (1 - RUNNER_UP_GAP_RTOL)


def test_the_shared_search_draws_where_every_open_check_has_pairs() -> None:
    """The places the shared search draws designs in (:func:`~.cell_checks._draw_places`):
    each open check that some queued pair carries is carried by a pair of some place (the
    lightest pairs that carry it, listed here one by one), each place's pairs lie in its sheet
    pair and carry an open check, and a closed check gets no place of its own."""
    rng = np.random.default_rng(3)
    count = 5
    K = rng.integers(0, 4, 5000)
    lb = rng.random(5000)
    M = rng.integers(1, 1 << count, 5000).astype(np.int64)
    M[lb < 0.5] &= ~np.int64(0b10100)  # checks 2 and 4 only in heavier pairs
    open_mask = 0b01111  # check 4 closed
    places = cell_checks._draw_places(K, lb, M, open_mask, count)
    carried = 0
    for k, sel in places:
        assert len(sel) and (K[sel] == k).all()
        for at in sel.tolist():
            carried |= int(M[at])
    for at in range(count):
        mine = [i for i in range(len(K)) if (int(M[i]) >> at) & 1]
        if (open_mask >> at) & 1 and mine:
            assert (carried >> at) & 1, at
    lightest_2 = min((i for i in range(len(K)) if (int(M[i]) >> 2) & 1), key=lambda i: lb[i])
    assert any(lightest_2 in sel.tolist() for _, sel in places)


def test_a_shared_search_whose_first_pairs_reach_its_limit_judges_none() -> None:
    """The first cell pairs are counted without forming them (:func:`~.cell_checks._first_count`
    against the pairs :func:`~.cell_checks._first_pairs` forms, per sheet pair), and a shared
    search whose first pairs alone reach its limit stops before judging any (not settled,
    nothing found), while one limit more judges them all."""
    p = _problem(True, False)
    tables = Tables(p)
    opt = optimize(p, tables=tables, record=True, prune=True)
    assert opt.certified and opt.fired is not None
    names = list(dict.fromkeys(p.constraints[i].name for i in opt.fired))
    checks = cell_checks.checks_of(p, names, True)
    assert checks and cell_checks.applies(p, checks)
    own = 0
    for ch in checks:
        own |= ch.bits
    loose = replace(
        p,
        constraints=tuple(
            c for k, c in enumerate(p.constraints) if not ((own >> k) & 1 and cell_checks._own(c))
        ),
    )
    everything = pairs(p)
    formed = 0
    for c1, c2 in everything:
        st = cells.setting(loose, c1, c2, tables)
        a, b = (cell_checks._Layer(st, p, which) for which in (1, 2))
        I, _ = cell_checks._first_pairs(a.fail, b.fail, checks)
        assert cell_checks._first_count(a.fail, b.fail, checks) == len(I)
        formed += len(I)
    assert formed > 0
    goal = opt.value * (1 - 2 * GAP_RTOL)
    cut = cell_checks.shared_search(p, everything, tables, checks, goal, budget=formed)
    assert not cut.settled and cut.judged == 0 and not any(cut.found.values())
    run = cell_checks.shared_search(p, everything, tables, checks, goal, budget=formed + 1)
    assert run.judged >= formed
