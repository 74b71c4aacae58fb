"""Typed design points and boxes (corrugate.solver.points): the search's flat coordinates and
the typed value convert both ways, identical layers are one stored layer, and the coordinates
follow the problem (layer count, identical layers, n fixed)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from corrugate.solver.points import VARIABLES, DesignPoints, LayerPoints, coordinates
from corrugate.solver.problem import Problem
from corrugate.spec.schema import parse_spec


def _problem(layers: str) -> Problem:
    shape = "square" if layers == "identical" else "rectangle"
    d = {
        "name": "p",
        "material": {"name": "dura-lar"},
        "layers": layers,
        "layout": {"shape": shape},
    }
    spec = parse_spec(d)
    return Problem.from_spec(spec)


def test_columns_round_trip_and_identical_layers() -> None:
    rows = np.arange(12.0).reshape(2, 6)  # two points, two layers of (n, W, alpha)
    x = DesignPoints.from_columns(rows)
    assert not x.identical and len(x) == 2
    assert x.layer(1).W.tolist() == [4.0, 10.0]  # column 4: layer 2's W
    np.testing.assert_array_equal(x.columns(), rows)
    one = DesignPoints.from_columns(rows[:, :3])  # identical layers: layer 2 is layer 1
    assert one.identical and one.layer(1) is one.layer(0)
    with pytest.raises(IndexError):
        one.layer(2)
    p = one.take(np.array([1])).point(0)
    assert (p.layer(1).n, p.layer(1).W, p.layer(1).alpha) == (6.0, 7.0, 8.0)
    assert p.arrays().layer(0).alpha.tolist() == [8.0]


def test_coordinates_follow_the_problem() -> None:
    same, apart = _problem("identical"), _problem("independent")
    assert (same.searched_layers, apart.searched_layers) == (1, 2)
    c = coordinates(apart, n_fixed=(7, 9))
    assert [(d.layer, d.variable) for d in c] == [(i, v) for i in (0, 1) for v in VARIABLES]
    assert (c[0].var.lo, c[0].var.hi, c[0].var.step) == (7.0, 9.0, 1.0)
    assert c[1].var == apart.W and c[5].var == apart.alpha
    assert len(coordinates(same)) == len(VARIABLES)
    assert len(coordinates(replace(apart, identical=True))) == len(VARIABLES)


def test_sheet_overrides_make_layers_distinct() -> None:
    """Per-point E and t (the tolerance analysis) are carried by the layer they belong to."""
    a = LayerPoints(np.array([8.0]), np.array([8.0]), np.array([84.0]), E=np.array([3e3]))
    assert a.overrides and not LayerPoints(1.0, 2.0, 3.0).overrides
    assert a.take(np.array([0])).E.tolist() == [3e3]
