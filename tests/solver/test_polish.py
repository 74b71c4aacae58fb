"""The incumbent of the cells' search (:mod:`corrugate.solver.polish`, ``cells._seed``): a design
it returns meets every constraint of the problem exactly (checked here by ``point_values``, no
slack) and is no lighter than the certified optimum of its sheet pair found by a second method,
the branch and bound of the pair's whole domain; the polish never returns a design heavier than
its start.
"""

from __future__ import annotations

import math
import tomllib

import numpy as np
import pytest

from corrugate.solver import Problem, cells
from corrugate.solver.bnb import GAP_RTOL, branch_and_bound
from corrugate.solver.points import DesignPoints, LayerPoints
from corrugate.solver.polish import climb, polish
from corrugate.solver.problem import Candidate
from corrugate.solver.quantities import Tables, point_values
from corrugate.solver.quantity import MASS
from corrugate.solver.solve import optimize, pairs
from corrugate.spec.schema import Spec
from sheet_specs import continuous_two_sheets


def _problem() -> Problem:
    """The nominal two-sheet continuous problem of :func:`sheet_specs.continuous_two_sheets`
    (tests/solver/test_cells.py's problem)."""
    return Problem.from_spec(Spec.model_validate(tomllib.loads(continuous_two_sheets(False))))


def _meets(p: Problem, c1: Candidate, c2: Candidate, x: DesignPoints, tables: Tables) -> float:
    """The mass (g) of the one design ``x``, asserting it meets every constraint exactly."""
    vals = point_values(p, c1, c2, x.arrays(), tables)
    for c in p.constraints:
        assert bool(np.all(c.satisfied(vals[c.quantity], rtol=0.0))), c.name
    return float(np.asarray(vals[MASS]).reshape(-1)[0])


def _feasible_start(
    p: Problem, c1: Candidate, c2: Candidate, tables: Tables
) -> tuple[DesignPoints, float]:
    """The lightest of designs drawn at random on a grid that meets every constraint."""
    rng = np.random.default_rng(1)
    k = 4000
    x = DesignPoints.of(
        LayerPoints(
            rng.integers(p.n_lo, p.n_hi + 1, k).astype(float),
            rng.uniform(p.W.lo, p.W.top, k),
            rng.uniform(p.alpha.lo, p.alpha.top, k),
        ),
        LayerPoints(
            rng.integers(p.n_lo, p.n_hi + 1, k).astype(float),
            rng.uniform(p.W.lo, p.W.top, k),
            rng.uniform(p.alpha.lo, p.alpha.top, k),
        ),
    )
    mass, ok = cells.judge_of(p, c1, c2, tables)(x)
    f = np.where(ok, mass, math.inf)
    b = int(np.argmin(f))
    assert math.isfinite(float(f[b]))  # some drawn design meets every constraint
    return x.point(b), float(f[b])


def test_polish_meets_the_constraints_and_is_no_lighter_than_the_optimum() -> None:
    p = _problem()
    tables = Tables(p)
    c1, c2 = pairs(p)[2]  # thick and thin: the pair of the optimum
    best = branch_and_bound(p, c1, c2)
    assert best.certified and best.point is not None
    x0, m0 = _feasible_start(p, c1, c2, tables)
    exact = cells.judge_of(p, c1, c2, tables)
    got = polish(p, c1, c2, x0, tables, exact)
    assert got is not None
    mass = _meets(p, c1, c2, got.point, tables)
    assert mass == got.mass
    assert mass <= m0  # never heavier than its start
    assert mass >= best.value * (1 - 2 * GAP_RTOL)  # nothing is lighter than the optimum
    climbed = climb(p, c1, c2, x0, tables, exact, set())
    assert climbed is not None and climbed.mass <= mass
    assert _meets(p, c1, c2, climbed.point, tables) == climbed.mass
    assert climbed.mass >= best.value * (1 - 2 * GAP_RTOL)


def test_the_seed_is_a_design_no_lighter_than_the_optimum() -> None:
    p = _problem()
    tables = Tables(p)
    everything = pairs(p)
    settings = [cells.setting(p, a, b, tables) for a, b in everything]
    exacts = [cells.judge_of(p, a, b, tables) for a, b in everything]
    tabs = [cells._Table(st, w) for st in settings for w in (1, 2)]
    tab_of = np.arange(2 * len(settings)).reshape(-1, 2)
    got = cells._seed(settings, tabs, tab_of, exacts)
    assert got is not None
    mass, x, k = got
    assert _meets(p, *everything[k], x, tables) == mass
    plain = [branch_and_bound(p, a, b) for a, b in everything]
    best = min(r.value for r in plain if r.point is not None)
    assert mass >= best * (1 - 2 * GAP_RTOL)


def test_a_seeded_search_has_the_plain_optimum(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(cells, "SEED_FROM", 0)  # seek and polish an incumbent on this small spec
    p = _problem()
    got = optimize(p, prune=True)
    assert got.certified and got.point is not None and got.candidates is not None
    plain = [branch_and_bound(p, a, b) for a, b in pairs(p)]
    best = min(r.value for r in plain if r.point is not None)
    assert abs(got.value - best) <= 2 * GAP_RTOL * best
    assert _meets(p, *got.candidates, got.point, Tables(p)) == pytest.approx(got.value, rel=1e-15)


def test_a_constraint_of_n_alone_met_exactly_does_not_stop_the_polish() -> None:
    """The pair's optimum has a layer at n = 6: 7 facets, the validity bound's least, so that
    constraint's margin is 0 at every W and alpha of that n. From starts that break other
    constraints (the optimum with layer 2's W moved by 0.3 mm or its alpha by 3 deg), the polish
    reaches the pair's optimum of the branch and bound (a second method) to 1e-6, with a design
    that meets every constraint exactly; asking that constraint a margin, it found none."""
    p = _problem()
    tables = Tables(p)
    c1, c2 = pairs(p)[2]
    best = branch_and_bound(p, c1, c2)
    assert best.certified and best.point is not None
    x = best.point.arrays()
    facets = [c for c in p.constraints if c.quantity.kind == "facets_least"]
    assert facets and float(x.layer(1).n[0]) + 1 == facets[0].bound  # met with no margin
    exact = cells.judge_of(p, c1, c2, tables)
    for dW, da in ((-0.3, 0.0), (-0.1, 0.0), (0.0, -3.0), (-0.3, -3.0)):
        one, two = x.layer(0), x.layer(1)
        start = DesignPoints.of(
            LayerPoints(float(one.n[0]), float(one.W[0]), float(one.alpha[0])),
            LayerPoints(float(two.n[0]), float(two.W[0]) + dW, float(two.alpha[0]) + da),
        )
        m0, ok0 = exact(start.arrays())
        assert float(m0[0]) < best.value and not bool(ok0[0])  # lighter: it breaks one
        got = polish(p, c1, c2, start, tables, exact)
        assert got is not None
        mass = _meets(p, c1, c2, got.point, tables)
        assert best.value * (1 - 2 * GAP_RTOL) <= mass <= best.value * (1 + 1e-6)
