"""The four tolerance corners and the four shifted boxes evaluated as one stacked set
(:func:`corrugate.solver.tolerance_box.stacked`) against the second method: each corner and
each shifted box evaluated on its own (as before the stacking), over random boxes and points of
a spec with every directional kind the tolerance bound covers, bit for bit."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from corrugate.solver import Problem
from corrugate.solver.context import OverBoxes
from corrugate.solver.points import DesignPoints, LayerPoints
from corrugate.solver.quantities import Tables, point_values
from corrugate.solver.tolerance_box import (
    _SHIFTS,
    ToleranceBounds,
    _low,
    _shift,
    corners,
    covered,
    stacked,
)
from corrugate.solver.worst_case import NOMINAL
from corrugate.spec.schema import parse_spec

_SPEC = {
    "name": "stacked",
    "tolerances": {},
    "layers": "independent",
    "material": {"name": "dura-lar", "thickness": "0.125 mm", "yield_strength": "50 MPa"},
    "layout": {"shape": "rectangle"},
    "variables": {
        "W": {"min": "4 mm", "max": "14 mm"},
        "n": {"min": 6, "max": 14},
        "alpha": {"min": "50 deg", "max": "150 deg"},
    },
    "constraints": {
        "flexural_rigidity": [{"min": "1 mN*m^2", "eta": "0 deg"}],
        "bending_stiffness": [{"min": "1 N*mm", "eta": "90 deg", "support": "frame"}],
        "inplane_stiffness": [{"min": "1 N/mm", "eta": "45 deg"}],
        "buckling_load": [{"min": "0.1 N", "eta": "90 deg"}],
    },
}


def _problem() -> Problem:
    return Problem.from_spec(parse_spec(_SPEC))


def _boxes(k: int, seed: int) -> tuple[DesignPoints, DesignPoints]:
    rng = np.random.default_rng(seed)
    layers_lo, layers_hi = [], []
    for _ in range(2):
        n = rng.integers(6, 15, k).astype(float)
        W = rng.uniform(4.0, 13.0, k)
        a = rng.uniform(50.0, 140.0, k)
        dW, da = rng.uniform(0.0, 1.0, k), rng.uniform(0.0, 10.0, k)
        layers_lo.append(LayerPoints(n, W, a))
        layers_hi.append(LayerPoints(n, W + dW, a + da))
    return DesignPoints.of(*layers_lo), DesignPoints.of(*layers_hi)


def test_stacked_shifted_boxes_are_the_four_boxes_one_by_one() -> None:
    p = _problem()
    c = p.candidates[0]
    tables = Tables(p)
    lo, hi = _boxes(37, 1)
    tol = ToleranceBounds(p, c, c, lo, hi, tables)
    free = replace(p, identical=False)
    low = _low(c, p.tolerances)
    qs = [q for q in p.quantities if covered(p, q)]
    assert qs
    for q in qs:
        want = np.array(tol.outer.bounds(q)[1], dtype=np.float64)
        if tol.inner is not None:
            want[tol.sel] = np.minimum(want[tol.sel], tol.inner.bounds(q)[0])
        for shift in _SHIFTS:  # each shifted box on its own
            over = OverBoxes(
                free, low, low, _shift(p, lo, *shift, (c, c)), _shift(p, hi, *shift, (c, c)), tables
            )
            want = np.minimum(want, over.bounds(q)[1])
        np.testing.assert_array_equal(tol.bounds(q)[1], want, err_msg=str(q))


def test_stacked_corners_are_the_corners_one_by_one() -> None:
    p = _problem()
    c = p.candidates[0]
    tables = Tables(p)
    screen = replace(p, tolerances=NOMINAL)
    x, _ = _boxes(29, 2)
    qs = frozenset(q for q in p.quantities if covered(p, q))
    parts = corners(p, c, c, x)
    together = point_values(screen, c, c, stacked(parts), tables, qs)
    for i, corner in enumerate(parts):
        alone = point_values(screen, c, c, corner, tables, qs)
        for q in qs:
            np.testing.assert_array_equal(
                np.asarray(together[q])[i * len(x) : (i + 1) * len(x)], alone[q], err_msg=str(q)
            )


def test_only_asked_values_are_the_full_values() -> None:
    """point_values restricted to some quantities (the search's) gives their values as the
    full call does, tolerance-covered ones included."""
    p = _problem()
    c = p.candidates[0]
    tables = Tables(p)
    x, _ = _boxes(23, 3)
    full = point_values(p, c, c, x, tables)
    asked = frozenset([p.objective.quantity, *(k.quantity for k in p.constraints)])
    some = point_values(p, c, c, x, tables, asked)
    assert set(some) == asked & set(full)
    for q in some:
        np.testing.assert_array_equal(some[q], full[q], err_msg=str(q))
