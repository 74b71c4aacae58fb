"""Sheet pairs pruned whole by certified floors (:mod:`corrugate.solver.choices`), checked against
a second method, the plain path (every pair searched by the branch and bound, in order):

* each pair's floors (coarse from the layer lists, fine from the relaxation's layer-by-layer
  optimum) are at most that pair's optimum found by the branch and bound of the problem itself,
  with its worst-case tolerances (the relaxation's claim, docs/theory.md section 5), and with n
  fixed as the runner-ups fix it;
* the answer with pruning is the plain path's: the same design, mass and certificate, and the
  whole explanation (binding checks, runner-ups) the same, with the default tolerances and
  nominal, on random stiffness bounds too (hypothesis), and an infeasible spec's archives (every
  pair searched) the same pair by pair.
"""

from __future__ import annotations

import importlib
import math
import tomllib
from dataclasses import replace
from unittest import mock

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from corrugate.materials.calibrated import Calibration
from corrugate.solver import Problem, solve
from corrugate.solver import separable as sep
from corrugate.solver.bnb import branch_and_bound
from corrugate.solver.choices import RELAX, Floors, floors, relaxation
from corrugate.solver.quantities import Tables
from corrugate.solver.solve import optimize, pairs
from corrugate.spec.schema import Spec

SOLVE = importlib.import_module("corrugate.solver.solve")
CHOICES = importlib.import_module("corrugate.solver.choices")


def _problem(tolerances: bool, ei0: float = 150.0, ei90: float = 40.0) -> Problem:
    """Four sheets (16 pairs) on a coarse grid, independent layers on a rectangle (the shipped
    examples/rectangle_independent.toml with fewer grid values); EI bounds in mN*m^2."""
    lines = [
        'name = "choices"',
        'model = "refined"',
        'layers = "independent"',
        *([] if tolerances else ['tolerances = "none"']),
        "[[materials]]",
        'name = "dura-lar"',
        'thickness = ["0.05 mm", "0.125 mm"]',
        "[[materials]]",
        'name = "mylar"',
        'thickness = ["0.023 mm", "0.075 mm"]',
        "[layout]",
        'shape = "rectangle"',
        "[variables]",
        'W = { min = "4 mm", max = "16 mm", step = "4 mm" }',
        "n = { min = 4, max = 14 }",
        'alpha = { min = "40 deg", max = "140 deg", step = "20 deg" }',
        "[constraints]",
        'sheet_max = "250 mm"',
        'side_x = { min = "80 mm", max = "100 mm" }',
        'side_y = { min = "40 mm", max = "60 mm" }',
        'thickness = { min = "8 mm", max = "16 mm" }',
        f'flexural_rigidity = [{{ min = "{ei0} mN*m^2", eta = "0 deg" }}, '
        f'{{ min = "{ei90} mN*m^2", eta = "90 deg" }}]',
    ]
    return Problem.from_spec(Spec.model_validate(tomllib.loads("\n".join(lines))))


def _plain() -> mock._patch:  # type: ignore[type-arg]
    """The plain path: no floors anywhere (every pair searched, in order)."""
    return mock.patch.object(SOLVE, "floors", return_value=None)


def _answer(problem: Problem) -> dict[str, object]:
    """The explained answer's JSON without the solver's counts."""
    d = solve(problem).to_dict()
    d.pop("solver")
    return d


def test_relaxation_applies_to_choices_only() -> None:
    """A relaxation exists for several sheets on the layer-by-layer structure, not for one."""
    p = _problem(True)
    r = relaxation(p)
    assert r is not None and r.tolerances.nominal
    # rho t kept, t and E at their low ends
    for a, b in zip(p.candidates, r.candidates, strict=True):
        assert math.isclose(b.t, a.t * (1 - p.tolerances.t), rel_tol=1e-15)
        assert math.isclose(b.material.E, a.material.E * (1 - p.tolerances.E), rel_tol=1e-15)
        rho_t = a.material.density * a.t
        assert math.isclose(b.material.density * b.t, rho_t, rel_tol=1e-15)
    one = replace(p, candidates=p.candidates[:1])
    assert relaxation(one) is None


def test_no_relaxation_for_a_calibrated_sheet() -> None:
    """A calibrated sheet's certificate takes its measured E interval (which may reach below
    E (1 - dE)) and the springback's angle, so R would not bound it from below: no floors."""
    p = _problem(True)
    m = p.candidates[0].material
    cal = Calibration(date="2026-12-06", measurements=10, coupons=("F1",), E_lo=0.8 * m.E, E_hi=m.E)
    first = replace(p.candidates[0], material=replace(m, calibration=cal))
    calibrated = replace(p, candidates=(first, *p.candidates[1:]))
    assert calibrated.calibrated
    assert relaxation(calibrated) is None


@pytest.mark.parametrize("tolerances", [True, False])
def test_all_pairs_floors_are_each_pairs(tolerances: bool) -> None:
    """The coarse floors of every pair at once (``pair_floors``, broadcast) are those of
    ``pair_floor`` pair by pair (a second method: the scalar arithmetic), some of them inf."""
    r = relaxation(_problem(tolerances, ei0=500.0))
    assert r is not None
    c = r.candidates
    one = [sep.layer_designs(r, x, 1) for x in c]
    two = [sep.layer_designs(r, x, 2) for x in c]
    got = sep.pair_floors(r, c, one, two)
    for i in range(len(c)):
        for j in range(len(c)):
            L1, L2 = one[i], two[j]
            assert L1 is not None and L2 is not None
            assert got[i, j] == sep.pair_floor(r, c[i], c[j], L1, L2)
    assert np.isinf(got).any() and np.isfinite(got).any()


@pytest.mark.slow
def test_floors_are_below_each_pairs_optimum() -> None:
    """Coarse <= fine <= the pair's certified optimum under the default tolerances (branch and
    bound of the problem itself, no incumbent), for every pair: the fine floor, its designs
    judged by the problem's own certified values, is that optimum less RELAX (inf for a pair
    with no design); judged by R alone (no ``original``), or by the problem for one batch of
    designs only (:data:`EXACT_POINTS` 1), still at most the optimum; and with n fixed (both
    layers, as the runner-ups fix it) below the per-n optimum."""
    p = _problem(True)
    fl = floors(p)
    assert fl is not None
    alone = Floors(fl.relaxed, fl.shifts)  # R's judgement only
    tables = Tables(p)
    feasible = 0
    for k, pair in enumerate(pairs(p)):
        coarse, fine, r_fine = fl.coarse(k), fl.fine(k, math.inf), alone.fine(k, math.inf)
        with mock.patch.object(CHOICES, "EXACT_POINTS", 1):
            once = fl.fine(k, math.inf)
        assert coarse <= r_fine <= once <= fine
        r = branch_and_bound(p, *pair, tables=tables, record=True)  # record: its own path
        assert r.certified
        if r.point is None:
            assert fine == math.inf
            continue
        feasible += 1
        assert fine <= r.value <= fine * (1 + 2 * RELAX)
        # R's floor alone is worth having: its stiffness held at the tolerance box's corners
        # too (0.978-1.000 of the optimum here; at the nominal part alone 0.894-0.917)
        assert r_fine >= 0.97 * r.value
        # the coarse one too: only the layer designs that may meet the coupled bounds
        # count (0.836-0.866 of the optimum here; the extremes alone gave about half)
        assert coarse >= 0.7 * r.value
    assert feasible >= 3
    n = 8
    pn = replace(p, n_lo=n, n_hi=n)
    fn = floors(pn)
    assert fn is not None
    for k, pair in enumerate(pairs(p)):
        r = branch_and_bound(p, *pair, tables=tables, per_n=(n, n))
        assert r.by_n is not None
        got = r.by_n[n]
        if got.point is not None:
            assert fn.coarse(k) <= fn.fine(k, math.inf) <= got.value


@pytest.mark.slow
@pytest.mark.parametrize("tolerances", [True, False])
def test_pruned_answer_is_the_plain_one(tolerances: bool) -> None:
    """The explained answer with pairs pruned whole is the plain path's, key by key (binding
    checks and runner-ups included), and some pairs were pruned."""
    p = _problem(tolerances)
    opt = optimize(p, record=True, prune=True)
    assert opt.certified and opt.point is not None
    assert 0 < len(opt.pruned) < len(pairs(p))
    with _plain():
        plain = optimize(p, record=True, prune=True)
    assert not plain.pruned
    assert opt.value == plain.value and opt.candidates == plain.candidates
    assert opt.point == plain.point
    got = _answer(p)
    with _plain():
        want = _answer(p)
    assert got == want
    assert any(c["binding"] for c in got["constraints"])  # type: ignore[index, union-attr]
    assert got["runner_ups"]


def test_coarse_floors_see_an_out_of_reach_stiffness() -> None:
    """EI(0) >= 900 mN*m^2 is out of reach of every pair (the branch and bound of each, with the
    default tolerances, finds no design, certified): the coarse floors say so from the layer
    lists alone, every one inf (no layer design may meet the bound with the other list's terms
    at their largest; the lists' extremes alone, the floors before, left the eight pairs of two
    layer-1 sheets finite, 0.79-1.74 g)."""
    p = _problem(True, ei0=900.0)
    fl = floors(p)
    assert fl is not None
    tables = Tables(p)
    for k, pair in enumerate(pairs(p)):
        r = branch_and_bound(p, *pair, tables=tables)
        assert r.certified and r.point is None
        assert fl.coarse(k) == math.inf


def test_infeasible_searches_every_pair() -> None:
    """An infeasible spec (EI(0) out of reach): with ``record`` every pair is searched, so the
    archives the diagnosis reopens are the plain path's, pair by pair."""
    p = _problem(False, ei0=1e6)
    got = optimize(p, record=True, prune=True)
    with _plain():
        want = optimize(p, record=True, prune=True)
    assert got.point is None and want.point is None and got.certified
    assert not got.pruned
    a, b = got.tree(), want.tree()
    assert a is not None and b is not None
    for x, y in zip(a, b, strict=True):
        for f in ("lo", "hi", "bound", "mask"):
            assert np.array_equal(getattr(x, f), getattr(y, f))


@settings(max_examples=12, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    ei0=st.floats(min_value=20.0, max_value=400.0),
    ei90=st.floats(min_value=5.0, max_value=120.0),
)
def test_pruned_optimum_on_random_bounds(ei0: float, ei90: float) -> None:
    """The certified solve (nominal: the plain path takes the layer-by-layer search per pair)
    with pruning finds the plain path's optimum on random stiffness bounds, feasible or not."""
    p = _problem(False, ei0=ei0, ei90=ei90)
    got = optimize(p, prune=True)
    want = optimize(p)
    assert got.certified and want.certified
    assert (got.point is None) == (want.point is None)
    if want.point is not None:
        assert got.value == want.value and got.candidates == want.candidates
        assert got.point == want.point
        fl = floors(p)
        assert fl is not None
        k = pairs(p).index(want.candidates)  # type: ignore[arg-type]
        assert fl.fine(k, math.inf) <= want.value * (1 + RELAX)
