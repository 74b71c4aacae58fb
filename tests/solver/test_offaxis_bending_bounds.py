"""The solver's off-axis D (docs/load_cases.md 5: the strip bound counting one facet fewer,
D_S c^4 max(0, 1 - |tan theta| - 1 / (n + 1)), times 1 - w 0.3 / sqrt(n)) is analyze's at a
point, and its box bounds, in interval arithmetic over n, W and alpha, contain the point values
of designs drawn inside each box (second method: the float evaluation)."""

from __future__ import annotations

import numpy as np
import pytest

from corrugate import Assembly, Layer, analyze, get_material
from corrugate.solver import Problem
from corrugate.solver.points import DesignPoints, LayerPoints
from corrugate.solver.quantities import Tables, box_bounds, point_values
from corrugate.spec.schema import parse_spec
from spec_units import with_units

ETAS = (15.0, 30.0, 35.0, 60.0)


def _problem() -> Problem:
    spec = {
        "name": "off-axis bending",
        "tolerances": "none",
        "material": {"name": "dura-lar", "thickness": 0.175},
        "layout": {"shape": "square"},
        "variables": {
            "W": {"min": 6, "max": 12},
            "n": {"min": 6, "max": 12},
            "alpha": {"min": 40, "max": 120},
        },
        "constraints": {"bending_stiffness": [{"min": 1, "eta": e} for e in ETAS]},
    }
    return Problem.from_spec(parse_spec(with_units(spec)))


def _point(n: float, W: float, alpha: float) -> DesignPoints:
    return DesignPoints.of(LayerPoints(np.array([n]), np.array([W]), np.array([alpha])))


def test_the_solvers_off_axis_d_is_analyzes_and_its_bounds_hold_it() -> None:
    p = _problem()
    cand = p.candidates[0]
    tables = Tables(p)
    qs = {c.quantity for c in p.constraints if c.quantity.kind == "D"}
    assert {q.eta for q in qs} == set(ETAS)
    values = point_values(p, cand, cand, _point(6.0, 10.0, 40.0), tables)
    layer = Layer(W=10.0, n=6, alpha_deg=40.0, material=get_material("dura-lar"), t=0.175)
    for st in analyze(Assembly.identical(layer), "refined", list(ETAS)).stiffness:
        (q,) = (q for q in qs if q.eta == st.eta_deg)
        assert values[q][0] == pytest.approx(st.D, rel=1e-9), st.eta_deg
    rng = np.random.default_rng(35)
    for _ in range(30):
        n0 = int(rng.integers(6, 12))
        n1 = int(rng.integers(n0, 13))
        W0, a0 = rng.uniform(6, 11), rng.uniform(40, 110)
        # narrow in W and alpha (the n term decides the bound) or wide
        W1, a1 = (W0 + 1e-3, a0 + 1e-3) if _ % 2 else (rng.uniform(W0, 12), rng.uniform(a0, 120))
        b = box_bounds(p, cand, cand, _point(n0, W0, a0), _point(n1, W1, a1), tables, qs)
        for _ in range(4):
            n = float(rng.integers(n0, n1 + 1))
            v = point_values(
                p, cand, cand, _point(n, rng.uniform(W0, W1), rng.uniform(a0, a1)), tables
            )
            for q in qs:
                assert b[q][0][0] <= v[q][0] <= b[q][1][0], (q.eta, n0, n1, W0, W1, a0, a1)
