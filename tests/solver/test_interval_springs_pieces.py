"""A layer's interval springs over boxes repeated once per piece of the thickness (the
worst-case tolerances, :class:`corrugate.solver.tolerance_box._Pieces`), evaluated once per
block (:func:`corrugate.solver.interval_springs.layer_springs`) against the same boxes
evaluated row by row (:func:`~corrugate.solver.interval_springs._layer_springs`, the second
method): every spring the same floats, on a rectangle and on a disc with a hole (the holes'
bounds), with independent and identical layers."""

from __future__ import annotations

import re
from dataclasses import fields, replace
from pathlib import Path

import numpy as np
import pytest

from corrugate.solver import Problem
from corrugate.solver import interval_springs as isp
from corrugate.solver.quantities import Tables
from corrugate.solver.tolerance_box import T_PIECES, sheet
from corrugate.spec.schema import parse_spec_text

ROOT = Path(__file__).resolve().parents[2]


def _problem(name: str) -> Problem:
    text = (ROOT / "examples" / name).read_text()
    text = re.sub(r'(?m)^tolerances = "none".*\n', "", text)  # the default tolerances
    return Problem.from_spec(parse_spec_text(text))


def _boxes(problem: Problem, rng: np.random.Generator, k: int) -> dict[str, tuple]:
    """k random boxes of one layer: (low, high) of n, W (mm), alpha (deg) and the other
    extent S (mm)."""
    n_lo = rng.integers(problem.n_lo, problem.n_hi + 1, size=k).astype(np.float64)
    n_hi = np.minimum(n_lo + rng.integers(0, 3, size=k), problem.n_hi)
    W_lo = rng.uniform(problem.W.lo, problem.W.top, size=k)
    W_hi = np.minimum(W_lo + rng.uniform(0.0, 3.0, size=k), problem.W.top)
    a_lo = rng.uniform(problem.alpha.lo, problem.alpha.top, size=k)
    a_hi = np.minimum(a_lo + rng.uniform(0.0, 20.0, size=k), problem.alpha.top)
    S_lo = rng.uniform(40.0, 90.0, size=k)
    S_hi = S_lo + rng.uniform(0.0, 10.0, size=k)
    return {"n": (n_lo, n_hi), "W": (W_lo, W_hi), "a": (a_lo, a_hi), "S": (S_lo, S_hi)}


def _same(a: np.ndarray, b: np.ndarray) -> bool:
    a = np.broadcast_to(np.asarray(a, np.float64), np.shape(b))
    return bool(np.all((a.view(np.int64) == b.view(np.int64)) | (np.isnan(a) & np.isnan(b))))


@pytest.mark.parametrize(
    ("example", "identical"),
    [
        ("rectangle_independent.toml", False),
        ("rectangle_independent.toml", True),
        ("wheel_circle.toml", True),
    ],
)
def test_blocks_once_equal_rows_one_by_one(example: str, identical: bool) -> None:
    problem = replace(_problem(example), identical=identical)
    tables = Tables(problem)
    rng = np.random.default_rng(len(example) + identical)
    for k in (1, 7, 300):
        boxes = _boxes(problem, rng, k)
        tiled = {
            key: (np.tile(lo, T_PIECES), np.tile(hi, T_PIECES)) for key, (lo, hi) in boxes.items()
        }
        for c in problem.candidates:
            cand = sheet(c, problem.tolerances, T_PIECES, k)
            args = (tiled["n"], tiled["W"], tiled["a"], tiled["S"])
            assert isp._period(cand.t, args) == k  # the shared way is taken
            for axis, Q in (("x", tables.Qx), ("y", tables.Qy)):
                got = isp.layer_springs(problem, cand, *args, Q, tables, axis)
                want = isp._layer_springs(problem, cand, *args, Q, tables, axis)
                for f in fields(want):
                    g, w = getattr(got, f.name), getattr(want, f.name)
                    assert g.lo.shape == (T_PIECES * k,), f.name
                    assert _same(g.lo, w.lo) and _same(g.hi, w.hi), f.name


def test_rows_not_in_blocks_are_not_shared() -> None:
    """Boxes that do not repeat block after block (or a thickness of one piece) take the
    row-by-row way."""
    problem = _problem("rectangle_independent.toml")
    rng = np.random.default_rng(3)
    k = 50
    boxes = _boxes(problem, rng, T_PIECES * k)  # every row its own box
    c = problem.candidates[0]
    cand = sheet(c, problem.tolerances, T_PIECES, k)
    args = (boxes["n"], boxes["W"], boxes["a"], boxes["S"])
    assert isp._period(cand.t, args) == 0
    one = sheet(c, problem.tolerances, 1, T_PIECES * k)
    assert isp._period(one.t, args) == 0
    assert isp._period(c.t, args) == 0
