"""The branch and bound's options (:func:`corrugate.solver.bnb.branch_and_bound`), each checked
against an independent second method: every design of a small grid evaluated directly
(``point_values`` at all 5525 grid points, the feasibility rule of docs/theory.md section 5 with
the solver's slack FEAS_RTOL), then the least mass found by hand for what each option asks.

The spec: an 80 x 80 mm rectangle, identical layers (the default), W 8-20 mm step 1, n 6-30,
alpha 40-120 deg step 5; sides 78-82 mm (so n >= 29 folds too long: 30 x 8 mm x sin 20 deg
= 82.1 mm), thickness <= 15 mm, D(0) >= 20 mN m^2; least mass.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from numpy.typing import NDArray

from corrugate.solver import Problem
from corrugate.solver.bnb import branch_and_bound
from corrugate.solver.points import DesignPoints, LayerPoints
from corrugate.solver.problem import FEAS_RTOL
from corrugate.solver.quantities import Tables, point_values
from corrugate.spec.schema import load_spec

SPEC = """name = "small-grid"
model = "refined"

[material]
name = "polypropylene"
thickness = "0.25 mm"

[layout]
shape = "rectangle"

[variables]
W = { min = "8 mm", max = "20 mm", step = "1 mm" }
n = { min = 6, max = 30 }
alpha = { min = "40 deg", max = "120 deg", step = "5 deg" }

[constraints]
sheet_max = "280 mm"
side_x = { min = "78 mm", max = "82 mm" }
side_y = { min = "78 mm", max = "82 mm" }
thickness = { max = "15 mm" }
flexural_rigidity = [{ min = "20 mN*m^2", eta = "0 deg" }]

[objective]
minimize = "mass"
"""


@pytest.fixture(scope="module")
def small(tmp_path_factory: pytest.TempPathFactory) -> tuple[Problem, NDArray[np.float64]]:
    """The problem, and per grid design (rows) its n and its mass (inf where infeasible)."""
    path = Path(tmp_path_factory.mktemp("bnb")) / "small.toml"
    path.write_text(SPEC, "utf-8")
    problem = Problem.from_spec(load_spec(path))
    assert problem.identical and problem.gridded
    ns = np.arange(problem.n_lo, problem.n_hi + 1, dtype=np.float64)
    n, W, a = (
        v.reshape(-1)
        for v in np.meshgrid(ns, problem.W.values(), problem.alpha.values(), indexing="ij")
    )
    x = DesignPoints.of(LayerPoints(n, W, a))  # identical layers: one stored layer
    c = problem.candidates[0]
    vals = point_values(problem, c, c, x, Tables(problem))
    ok = np.all([c_.satisfied(vals[c_.quantity], rtol=FEAS_RTOL) for c_ in problem.constraints], 0)
    return problem, np.stack([n, np.where(ok, vals[problem.objective.quantity], np.inf)], 1)


def _least(grid: NDArray[np.float64], n_lo: float, n_hi: float) -> float:
    """The least feasible mass of the grid designs with n in [n_lo, n_hi] (inf: none)."""
    sel = (grid[:, 0] >= n_lo) & (grid[:, 0] <= n_hi)
    return float(grid[sel, 1].min()) if sel.any() else math.inf


def test_the_plain_search_and_its_archive_find_the_grid_optimum(small) -> None:
    problem, grid = small
    c = problem.candidates[0]
    best = _least(grid, -math.inf, math.inf)
    assert math.isfinite(best)  # the grid has feasible designs, and infeasible ones
    assert np.isinf(grid[:, 1]).any()
    plain = branch_and_bound(problem, c, c)
    recorded = branch_and_bound(problem, c, c, record=True)
    for r in (plain, recorded):
        assert r.certified and r.gap == 0.0
        assert r.value == pytest.approx(best, rel=1e-12)
    assert plain.archive is None and recorded.archive is not None
    # warm from the archive's boxes (every box that may hold a feasible design): the same answer
    warm = branch_and_bound(problem, c, c, start=recorded.archive.reopen())
    assert warm.certified and warm.value == pytest.approx(best, rel=1e-12)


def test_n_fixed_and_per_n_find_each_n_s_own_optimum(small) -> None:
    problem, grid = small
    c = problem.candidates[0]
    a, b = 24, 30
    per = branch_and_bound(problem, c, c, per_n=(a, b))
    assert per.certified and per.by_n is not None and sorted(per.by_n) == list(range(a, b + 1))
    found = 0
    for n in range(a, b + 1):
        expected = _least(grid, n, n)
        fixed = branch_and_bound(problem, c, c, n_fixed=(n, n))
        for r in (per.by_n[n], fixed):
            assert r.certified
            if math.isinf(expected):
                assert r.point is None
            else:
                assert r.point is not None and r.point.layer(0).n == n
                assert r.value == pytest.approx(expected, rel=1e-12)
        found += math.isfinite(expected)
    assert 0 < found < b - a + 1  # some n have feasible designs, some none
    wide = branch_and_bound(problem, c, c, n_fixed=(a, b))
    assert wide.value == pytest.approx(_least(grid, a, b), rel=1e-12)


def test_an_incumbent_and_a_goal_prune_as_promised(small) -> None:
    problem, grid = small
    c = problem.candidates[0]
    best = _least(grid, -math.inf, math.inf)
    second = float(np.unique(grid[np.isfinite(grid[:, 1]), 1])[1])  # the next lighter mass
    # an incumbent no heavier than the optimum: nothing strictly better, certified
    none = branch_and_bound(problem, c, c, incumbent=best)
    assert none.certified and none.point is None
    above = branch_and_bound(problem, c, c, incumbent=second)
    assert above.certified and above.value == pytest.approx(best, rel=1e-12)
    # stop below the second lightest: the design found is strictly lighter, i.e. the optimum
    early = branch_and_bound(problem, c, c, stop_below=second)
    assert early.point is not None and early.value == pytest.approx(best, rel=1e-12)
    # stop below the optimum itself: nothing lighter exists, shown by a finished search
    never = branch_and_bound(problem, c, c, stop_below=best, incumbent=best)
    assert never.point is None and never.certified
