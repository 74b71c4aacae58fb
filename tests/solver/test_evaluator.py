"""The registry of quantity kinds (corrugate.solver.evaluator): a kind registered from outside
reaches the point values, the box bounds and the certified search.

The toy kind is a made-up "blank run", the summed lengths of the two layers' flat blanks,
(n1 + 1) W1 + (n2 + 1) W2 (mm): it grows with n and W and does not depend on alpha, so its
bounds over a box are its values at the box's corners (Evaluator.monotone). The solver's
certified optimum with a bound on it is checked against an exhaustive search of the same grid
written here in numpy (the run and the extent (n + 1) W sin(alpha/2), docs/theory.md section 2,
from their formulas, not from the solver's code).
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import replace

import numpy as np
import pytest

from corrugate.solver import Constraint, Problem, solve
from corrugate.solver.evaluator import Evaluator, evaluator_of, register, unregister
from corrugate.solver.points import DesignPoints, LayerPoints
from corrugate.solver.problem import FEAS_RTOL, Candidate, Objective
from corrugate.solver.quantities import Tables, box_bounds, point_values
from corrugate.solver.quantity import LX, LY, Quantity
from corrugate.spec.schema import parse_spec

RUN = Quantity("blank_run")


def _run(x: DesignPoints, c1: Candidate, c2: Candidate) -> np.ndarray:
    one, two = x.layer(0), x.layer(1)
    return np.asarray((one.n + 1) * one.W + (two.n + 1) * two.W)


@pytest.fixture
def toy() -> Iterator[Evaluator]:
    ev = register(
        Evaluator.monotone("blank_run", _run, label="summed blank length (toy)", unit="mm")
    )
    try:
        yield ev
    finally:
        unregister(ev)


def _problem(constraints: tuple[Constraint, ...], objective: Objective) -> Problem:
    """Identical layers on a square, n 4-30, W 4-12 mm step 1, alpha 60-120 deg step 10."""
    spec = parse_spec(
        {
            "name": "toy",
            "material": {"name": "dura-lar"},
            "layout": {"shape": "square"},
            "variables": {
                "W": {"min": 4, "max": 12, "step": 1},
                "n": {"min": 4, "max": 30},
                "alpha": {"min": 60, "max": 120, "step": 10},
            },
        }
    )
    return replace(Problem.from_spec(spec), constraints=constraints, objective=objective)


def _grid() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    n, W, a = np.meshgrid(
        np.arange(4, 31, dtype=float),
        np.arange(4, 13, dtype=float),
        np.arange(60, 121, 10, dtype=float),
        indexing="ij",
    )
    return n.ravel(), W.ravel(), a.ravel()


def test_a_registered_kind_reaches_point_values_and_box_bounds(toy: Evaluator) -> None:
    p = _problem((Constraint("toy", RUN, "max", 150.0),), Objective(LX, "max"))
    assert evaluator_of(RUN) is toy and RUN.unit == "mm"
    c = p.candidates[0]
    n, W, a = _grid()
    at = point_values(p, c, c, DesignPoints.of(LayerPoints(n, W, a)), Tables(p))
    np.testing.assert_array_equal(at[RUN], 2 * (n + 1) * W)  # identical layers: twice one
    lo = DesignPoints.of(LayerPoints(np.array([5.0]), np.array([4.0]), np.array([60.0])))
    hi = DesignPoints.of(LayerPoints(np.array([9.0]), np.array([7.0]), np.array([90.0])))
    b = box_bounds(p, c, c, lo, hi, Tables(p), {RUN})
    assert (b[RUN][0][0], b[RUN][1][0]) == (2 * 6 * 4.0, 2 * 10 * 7.0)


def test_the_solver_certifies_a_bound_on_a_registered_kind(toy: Evaluator) -> None:
    """The widest square panel whose blanks run at most 201 mm in all (a bound on the toy
    kind), and the shortest run of a panel at least 83.3 mm wide: the certified answers are the
    exhaustive search's over the same grid."""
    n, W, a = _grid()
    run = 2.0 * (n + 1.0) * W  # identical layers
    extent = (n + 1.0) * W * np.sin(np.radians(a) / 2.0)
    # no grid value sits within the solver's slack of a bound (the searches agree on each)
    assert np.min(np.abs(run - 201.0)) > 0.5
    assert np.min(np.abs(extent - 83.3)) / 83.3 > 1e-6

    widest = _problem((Constraint("toy", RUN, "max", 201.0),), Objective(LX, "max"))
    sol = solve(widest)
    assert sol.status == "optimal" and sol.certified and sol.gap == 0.0
    assert sol.objective == pytest.approx(float(np.max(extent[run <= 201.0])), rel=1e-12)
    [report] = sol.constraints
    assert report.value <= 201.0 and report.binding is True

    wide = (Constraint("x", LX, "min", 83.3), Constraint("y", LY, "min", 83.3))
    shortest = _problem(wide, Objective(RUN, "min"))
    sol = solve(shortest, explain=False)
    assert sol.status == "optimal" and sol.certified
    best = float(np.min(run[extent >= 83.3 * (1 - FEAS_RTOL)]))
    assert sol.objective == pytest.approx(best, rel=1e-12)
    layer = sol.assembly.layer1
    assert 2.0 * (layer.n + 1) * layer.W == pytest.approx(best, rel=1e-12)


def test_reported_quantities_follow_the_registry_after_a_first_evaluation() -> None:
    """:func:`~.quantities.reported` is kept on a problem (quantities.py): an evaluator
    registered, then unregistered, after the problem's first point values still changes what
    they report (a toy kind that reports itself for every problem)."""
    p = _problem((Constraint("x", LX, "min", 10.0),), Objective(LX, "max"))
    c = p.candidates[0]
    x = DesignPoints.of(LayerPoints(np.array([5.0]), np.array([4.0]), np.array([60.0])))
    assert RUN not in point_values(p, c, c, x, Tables(p))
    always = Evaluator.monotone(
        "blank_run", _run, label="summed blank length (toy)", unit="mm", reported=lambda _: [RUN]
    )
    register(always)
    try:
        got = point_values(p, c, c, x, Tables(p))
        assert got[RUN][0] == 2 * 6 * 4.0  # identical layers: twice (n + 1) W
    finally:
        unregister(always)
    assert RUN not in point_values(p, c, c, x, Tables(p))
