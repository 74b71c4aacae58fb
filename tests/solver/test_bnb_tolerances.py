"""The branch and bound under worst-case tolerances and in bounded memory (docs/tolerances.md
section 5), each checked against a second method:

* every design of a small grid evaluated directly over its tolerance box (``point_values`` of
  the problem with its tolerances, no screening, at all 5525 grid points; the feasibility rule
  of docs/theory.md section 5 with FEAS_RTOL), then the least mass, or the largest EI(0) with
  the other constraints held, found by hand: what the screened search must certify;
* the same evaluation in one pass against the chunks and runs that bound the memory (equal to
  the last bit, archive included);
* the point model at parts of the tolerance box against the certified value (the certified
  value is the lower bound over the whole box, so it is at most the model anywhere in it).

The spec is tests/solver/test_bnb.py's small grid (an 80 x 80 mm rectangle, W 8-20 mm, n
6-30, alpha 40-120 deg) with the default tolerances and EI(0) >= 50 mN m^2.
"""

from __future__ import annotations

import math
import tracemalloc
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from numpy.typing import NDArray

from corrugate.solver import Problem, bnb, quantities, tolerance_box
from corrugate.solver.archive import Archive
from corrugate.solver.bnb import branch_and_bound
from corrugate.solver.points import DesignPoints, LayerPoints
from corrugate.solver.problem import FEAS_RTOL
from corrugate.solver.quantities import Tables, box_bounds, point_values
from corrugate.solver.worst_case import NOMINAL, WorstCase
from corrugate.spec.schema import load_spec

SPEC = """name = "small-grid-tolerances"
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
flexural_rigidity = [{ min = "50 mN*m^2", eta = "0 deg" }]

[objective]
minimize = "mass"

[tolerances]
"""


@pytest.fixture(scope="module")
def small(tmp_path_factory: pytest.TempPathFactory) -> tuple[Problem, DesignPoints]:
    path = Path(tmp_path_factory.mktemp("bnbtol")) / "small.toml"
    path.write_text(SPEC, "utf-8")
    problem = Problem.from_spec(load_spec(path))
    assert problem.tolerances == WorstCase(3.0, 0.1, 0.05, 0.10)
    ns = np.arange(problem.n_lo, problem.n_hi + 1, dtype=np.float64)
    n, W, a = (
        v.reshape(-1)
        for v in np.meshgrid(ns, problem.W.values(), problem.alpha.values(), indexing="ij")
    )
    return problem, DesignPoints.of(LayerPoints(n, W, a))


def _by_hand(problem: Problem, x: DesignPoints) -> NDArray[np.float64]:
    """Per grid design, its objective (inf where infeasible), from its certified values."""
    c = problem.candidates[0]
    vals = point_values(problem, c, c, x, Tables(problem))
    ok = np.all([k.satisfied(vals[k.quantity], rtol=FEAS_RTOL) for k in problem.constraints], 0)
    sign = -1.0 if problem.objective.sense == "max" else 1.0
    return np.where(ok, sign * vals[problem.objective.quantity], np.inf)


def test_the_screened_search_finds_the_grid_optimum_under_tolerances(small) -> None:
    """Least mass and, EI(0) dropped, the largest certified EI(0) with the other constraints:
    the screened search (points judged by the point model at corners first) certifies the
    optimum every grid design's own tolerance-box evaluation gives."""
    problem, x = small
    c = problem.candidates[0]
    ei = problem.constraints[-1]
    assert ei.quantity.key == "EI@0"
    for p in (problem, problem.without(ei.name).with_objective(ei.quantity, "max")):
        f = _by_hand(p, x)
        assert np.isfinite(f).any() and np.isinf(f).any()
        best = float(f.min())
        sign = -1.0 if p.objective.sense == "max" else 1.0
        for r in (branch_and_bound(p, c, c), branch_and_bound(p, c, c, record=True)):
            assert r.certified and r.gap == 0.0
            assert sign * r.value == pytest.approx(best, rel=1e-12)
            assert r.point is not None
            k = int(np.flatnonzero(f == f.min())[0])  # the point found is one of the best
            assert sign * r.value == f[k]


def test_the_tolerances_change_the_answer(small) -> None:
    """A check that the fixture tests something: the nominal least mass is lighter."""
    problem, x = small
    nominal = replace(problem, tolerances=NOMINAL)
    assert _by_hand(nominal, x).min() < _by_hand(problem, x).min()


def _archive_equal(a: Archive | None, b: Archive | None) -> None:
    assert a is not None and b is not None
    for field in ("lo", "hi", "bound", "mask"):
        assert np.array_equal(getattr(a, field), getattr(b, field)), field


@pytest.mark.parametrize("tolerant", [False, True])
def test_runs_and_chunks_give_the_one_pass_answer_and_archive(
    small, monkeypatch: pytest.MonkeyPatch, tolerant: bool
) -> None:
    """Enumerated grid points in runs of at most 8 (a box each) and evaluations in chunks of 64
    points give the same optimum, point and archive, row for row, as the defaults (runs of
    65536 points: one per iteration here)."""
    problem, _ = small
    if not tolerant:
        problem = replace(problem, tolerances=NOMINAL)
    c = problem.candidates[0]
    one = branch_and_bound(problem, c, c, record=True)
    runs: list[int] = []
    plain_runs = bnb.chunk_runs

    def counted(points, most):  # type: ignore[no-untyped-def]
        out = plain_runs(points, most)
        runs.append(len(out))
        return out

    monkeypatch.setattr(bnb, "chunk_runs", counted)
    monkeypatch.setattr(bnb, "ENUMERATE_CHUNK", 8)
    monkeypatch.setattr(
        quantities, "CHUNK_ROWS", 64 * (quantities.TOLERANCE_ROWS if tolerant else 1)
    )
    cut = branch_and_bound(problem, c, c, record=True)
    assert cut.value == one.value and cut.point == one.point
    _archive_equal(cut.archive, one.archive)
    assert max(runs) > 1  # some iteration went through in several runs


def test_chunked_values_and_bounds_are_the_one_pass_values(
    small, monkeypatch: pytest.MonkeyPatch
) -> None:
    """point_values and box_bounds over 3000 points and boxes in chunks of 100: equal to the
    last bit to one pass, and the chunks' peak memory a fraction of one pass's."""
    problem, x = small
    c = problem.candidates[0]
    tables = Tables(problem)
    rng = np.random.default_rng(7)
    pick = rng.choice(len(x), 3000, replace=False)
    pts = x.take(pick)
    lo = pts
    hi = DesignPoints.of(
        LayerPoints(lo.layers[0].n, lo.layers[0].W + 1.0, lo.layers[0].alpha + 5.0)
    )
    qs = set(problem.quantities)

    def measured(fn):  # type: ignore[no-untyped-def]
        tracemalloc.start()
        out = fn()
        peak = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
        return out, peak

    whole, whole_peak = measured(lambda: point_values(problem, c, c, pts, tables))
    bounds = box_bounds(problem, c, c, lo, hi, tables, qs)
    monkeypatch.setattr(quantities, "CHUNK_ROWS", 100 * quantities.TOLERANCE_ROWS)
    parts, parts_peak = measured(lambda: point_values(problem, c, c, pts, tables))
    cut_bounds = box_bounds(problem, c, c, lo, hi, tables, qs)
    for q, v in whole.items():
        assert np.array_equal(np.broadcast_to(v, (3000,)), parts[q]), q.key
    for q, (b_lo, b_hi) in bounds.items():
        assert np.array_equal(np.broadcast_to(b_lo, (3000,)), cut_bounds[q][0]), q.key
        assert np.array_equal(np.broadcast_to(b_hi, (3000,)), cut_bounds[q][1]), q.key
    assert parts_peak < whole_peak / 4


def test_corners_lie_in_the_tolerance_box_and_bound_the_certified_value(small) -> None:
    """The four corners the screen evaluates are parts of T(x) (W and alpha moved by exactly
    dW and da, E and t at their low limits), and the point model there is at or above the
    certified value (the lower bound over all of T(x))."""
    problem, x = small
    c = problem.candidates[0]
    tables = Tables(problem)
    tol = problem.tolerances
    pts = x.take(np.arange(0, len(x), 7))
    certified = point_values(problem, c, c, pts, tables)
    nominal = replace(problem, tolerances=NOMINAL)
    covered = [q for q in problem.quantities if tolerance_box.covered(problem, q)]
    assert covered
    for corner in tolerance_box.corners(problem, c, c, pts):
        lay = corner.layers[0]
        assert np.allclose(np.abs(lay.W - pts.layers[0].W), tol.W)
        assert np.allclose(np.abs(lay.alpha - pts.layers[0].alpha), tol.alpha)
        assert np.allclose(lay.E, c.material.E * (1 - tol.E))
        assert np.allclose(lay.t, c.t * (1 - tol.t))
        at = point_values(nominal, c, c, corner, tables)
        for q in covered:
            assert np.all(certified[q] <= at[q] * (1 + 1e-12)), q.key


def test_the_upper_bound_over_a_box_holds_at_its_points(small) -> None:
    """Over boxes of 2 x 2 grid steps (wider than 2 dW and 2 da: no inner box), the upper bound
    of the certified value (from the shifted corner boxes) is at or above the certified value
    at each of the box's grid points, and below the widened box's own upper bound somewhere
    (it is tighter)."""
    problem, x = small
    c = problem.candidates[0]
    tables = Tables(problem)
    sel = np.flatnonzero(
        (x.layers[0].W <= 19) & (x.layers[0].alpha <= 115) & (x.layers[0].n % 5 == 0)
    )
    lo = x.take(sel)
    l0 = lo.layers[0]
    hi = DesignPoints.of(LayerPoints(l0.n, l0.W + 1.0, l0.alpha + 5.0))
    q = problem.constraints[-1].quantity
    up = box_bounds(problem, c, c, lo, hi, tables, {q})[q][1]
    wlo, whi = tolerance_box.widened(problem, lo, hi)
    plain = replace(problem, tolerances=NOMINAL, identical=False)
    loose = box_bounds(plain, c, c, wlo, whi, tables, {q})[q][1]  # at most the widened box's
    assert np.any(up < 0.95 * loose)
    for dW in (0.0, 1.0):
        for da in (0.0, 5.0):
            p = DesignPoints.of(LayerPoints(l0.n, l0.W + dW, l0.alpha + da))
            g = point_values(problem, c, c, p, tables)[q]
            assert np.all(g <= up * (1 + 1e-12))
    assert math.isfinite(float(up.max()))
