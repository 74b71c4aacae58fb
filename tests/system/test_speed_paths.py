"""The fast paths against the reference paths they replace (issue 13).

* ``evaluate`` with identical layers (one layer computed) against the same call with the
  identical-layer shortcut switched off (both layers computed), and broadcast grid axes against
  the flattened grid;
* the chunked :func:`corrugate.analysis.sweep.sweep` against one block, against a plain ``evaluate`` of
  the whole grid with the constraints written out by hand, against the certified solver on the
  case study (docs/theory.md 3.5: W 8 mm, n 8, alpha 84 deg), and on a local dask cluster against
  the in-process run;
* the branch and bound's k-way splits and grid enumeration against plain halving without
  enumeration (and the exhaustive hypothesis tests of tests/solver/test_solve.py);
* the interval fast paths (known signs, one rounding per quotient) contain every sampled value.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import corrugate.analysis.evaluate as analysis
from corrugate import LayerArrays, evaluate, get_material
from corrugate.analysis.sweep import FIELDS, sweep
from corrugate.geometry.layouts import Circle, Rectangle, Square
from corrugate.solver import Problem, solve
from corrugate.solver import bnb as bnb_module
from corrugate.solver import boxes as boxes_module
from corrugate.solver.interval import Interval
from corrugate.spec.schema import load_spec
from data_files import PAPER_CASE_STUDY

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
DURALAR = get_material("dura-lar")
CASE_BOUNDS = {"Lx": (48.0, 60.0), "thickness": (10.0, 12.5), "flat": (None, 250.0)}
CASE_BOUNDS["EI"] = (80e3, None)


def _random_layer(seed: int, size: int = 2_000) -> LayerArrays:
    rng = np.random.default_rng(seed)
    return LayerArrays(
        DURALAR.E,
        DURALAR.nu,
        0.125,
        rng.uniform(1, 30, size),
        rng.integers(1, 200, size),
        rng.uniform(1, 179, size),
        DURALAR.density,
    )


@pytest.mark.parametrize("layout", [Square(), Rectangle(), Circle()], ids=lambda x: x.name)
@pytest.mark.parametrize("model", ["paper", "xia", "refined"])
@pytest.mark.parametrize(("eta", "support"), [(0.0, "free"), (30.0, "free"), (60.0, "frame")])
def test_identical_layer_path_equals_two_layer_path(
    monkeypatch: pytest.MonkeyPatch, layout: object, model: str, eta: float, support: str
) -> None:
    layer = _random_layer(1)
    assert analysis.identical_layers(layer, layer, layout)  # type: ignore[arg-type]
    fast = evaluate(layer, layer, layout, model, eta, support=support)  # type: ignore[arg-type]
    monkeypatch.setattr(analysis, "identical_layers", lambda *args: False)
    ref = evaluate(layer, layer, layout, model, eta, support=support)  # type: ignore[arg-type]
    for name in ("Lx", "Ly", "thickness", "mass", "mass_connectors", "K", "D", "EI"):
        # the band sums its four equal sides as 4 x side instead of side + side + side + side
        np.testing.assert_allclose(getattr(fast, name), getattr(ref, name), rtol=1e-15)
    for f in ("K_C", "K_S", "D_C", "D_S", "K_T", "D_T"):
        np.testing.assert_array_equal(getattr(fast.springs[1], f), getattr(ref.springs[1], f))


def test_different_layers_are_not_shortcut() -> None:
    a, b = _random_layer(1), _random_layer(2)
    assert not analysis.identical_layers(a, b, Square())
    # equal values in new arrays are the same layer; holes or a polygon never are
    copy = LayerArrays(
        a.E, a.nu, a.t, np.array(a.W), np.array(a.n), np.array(a.alpha_deg), a.density
    )
    assert analysis.identical_layers(a, copy, Square())
    assert not analysis.identical_layers(a, a, Square(holes=(object(),)))  # type: ignore[arg-type]


def test_broadcast_axes_equal_the_flattened_grid() -> None:
    W = np.arange(1.0, 31.0)
    n = np.arange(1, 41)
    A = np.arange(5.0, 180.0, 7.0)
    grid = LayerArrays(
        DURALAR.E, DURALAR.nu, 0.125, W[:, None, None], n[None, :, None], A[None, None, :], 1e-3
    )
    Wf, nf, Af = (x.reshape(-1) for x in np.meshgrid(W, n, A, indexing="ij"))
    flat = LayerArrays(DURALAR.E, DURALAR.nu, 0.125, Wf, nf, Af, 1e-3)
    g = evaluate(grid, grid, Square(), "refined", 45.0)
    f = evaluate(flat, flat, Square(), "refined", 45.0)
    shape = (len(W), len(n), len(A))
    for name in ("Lx", "thickness", "mass", "K", "D", "EI"):
        full = np.broadcast_to(getattr(g, name), shape).reshape(-1)
        np.testing.assert_allclose(full, getattr(f, name), rtol=1e-14)


def _hand_search(W: np.ndarray, n: np.ndarray, A: np.ndarray, model: str) -> tuple[int, float, int]:
    """Flat index of the lightest design within CASE_BOUNDS, its mass and the feasible count, by
    one evaluate call over the whole (flattened) grid."""
    Wf, nf, Af = (x.reshape(-1) for x in np.meshgrid(W, n, A, indexing="ij"))
    layer = LayerArrays(DURALAR.E, DURALAR.nu, 0.125, Wf, nf, Af, DURALAR.density)
    ev = evaluate(layer, layer, Square(), model, 0.0)
    ok = (ev.Lx >= 48) & (ev.Lx <= 60) & (ev.thickness >= 10) & (ev.thickness <= 12.5)
    ok &= ((nf + 1) * Wf <= 250) & (ev.EI >= 80e3)
    mass = np.where(ok, ev.mass, np.inf)
    k = int(np.argmin(mass))
    return k, float(mass[k]), int(ok.sum())


def test_sweep_finds_the_case_study_optimum_like_the_solver_and_a_hand_search() -> None:
    W, n, A = np.arange(1.0, 31.0), np.arange(1, 201), np.arange(1.0, 121.0)
    r = sweep(W, n, A, DURALAR, 0.125, model="paper", bounds=CASE_BOUNDS)
    assert r.best is not None
    assert (r.best["W"], r.best["n"], r.best["alpha"]) == (8.0, 8.0, 84.0)  # docs/theory.md 3.5
    sol = solve(Problem.from_spec(load_spec(PAPER_CASE_STUDY)), explain=False)
    assert sol.certified
    assert r.best["mass"] == pytest.approx(sol.mass, rel=1e-12)
    k, mass, count = _hand_search(W, n, A, "paper")
    assert np.ravel_multi_index(r.best_index, r.shape) == k  # type: ignore[arg-type]
    assert r.best["mass"] == pytest.approx(mass, rel=1e-14)
    assert r.feasible == count
    assert r.count == W.size * n.size * A.size


@settings(max_examples=15, deadline=None)
@given(
    chunk=st.integers(1, 5_000),
    model=st.sampled_from(["paper", "xia", "refined"]),
    eta=st.sampled_from([0.0, 30.0, 90.0]),
)
@pytest.mark.slow
def test_chunked_sweep_equals_one_block(chunk: int, model: str, eta: float) -> None:
    W, n, A = np.arange(2.0, 20.0, 1.5), np.arange(3, 40, 2), np.arange(30.0, 150.0, 4.0)
    bounds = {"Lx": (20.0, None), "EI": (1e3, None)}
    kw = {"model": model, "eta_deg": eta, "bounds": bounds, "keep": True}
    one = sweep(W, n, A, DURALAR, 0.2, chunk=10**9, **kw)  # type: ignore[arg-type]
    many = sweep(W, n, A, DURALAR, 0.2, chunk=chunk, **kw)  # type: ignore[arg-type]
    assert many.best_index == one.best_index
    assert (many.count, many.feasible) == (one.count, one.feasible)
    assert one.values is not None and many.values is not None
    for f in FIELDS:
        np.testing.assert_allclose(many.values[f], one.values[f], rtol=1e-14)
        assert many.minimum[f] == pytest.approx(one.minimum[f], rel=1e-14)
        assert many.maximum[f] == pytest.approx(one.maximum[f], rel=1e-14)


def test_sweep_values_are_evaluate_values() -> None:
    W, n, A = np.array([8.0, 12.0]), np.array([8, 13]), np.array([84.0, 100.0])
    r = sweep(W, n, A, DURALAR, 0.125, model="xia", eta_deg=30.0, keep=True, layout=Circle())
    assert r.values is not None
    for i, w in enumerate(W):
        for j, k in enumerate(n):
            for m, a in enumerate(A):
                layer = LayerArrays(DURALAR.E, DURALAR.nu, 0.125, w, k, a, DURALAR.density)
                ev = evaluate(layer, layer, Circle(), "xia", 30.0)
                assert r.values["EI"][i, j, m] == pytest.approx(float(ev.EI), rel=1e-14)
                assert r.values["mass"][i, j, m] == pytest.approx(float(ev.mass), rel=1e-14)
                assert r.values["flat"][i, j, m] == (k + 1) * w


def test_sweep_without_feasible_designs() -> None:
    r = sweep([1.0, 2.0], [1, 2], [10.0], DURALAR, 0.125, bounds={"Lx": (1e6, None)})
    assert r.best is None and r.best_index is None and r.feasible == 0 and r.count == 4
    assert all(np.isnan(v) for v in r.minimum.values())


@pytest.mark.slow
def test_sweep_on_a_local_dask_cluster_equals_in_process(dask_cluster: str) -> None:
    """The grid cut into tasks on a cluster of two worker processes (issue 39, item 5): the same
    best design, counts and ranges as the in-process sweep (the partial results combine exactly,
    ties to the lowest index), both by the client and by the scheduler's address."""
    from distributed import Client

    W, n, A = np.arange(1.0, 31.0), np.arange(1, 121), np.arange(1.0, 121.0)
    local = sweep(W, n, A, DURALAR, 0.125, model="paper", bounds=CASE_BOUNDS, chunk=4096)
    with Client(dask_cluster) as client:
        remote = sweep(
            W, n, A, DURALAR, 0.125, model="paper", bounds=CASE_BOUNDS, chunk=4096, scheduler=client
        )
    by_address = sweep(
        W,
        n,
        A,
        DURALAR,
        0.125,
        model="paper",
        bounds=CASE_BOUNDS,
        chunk=4096,
        scheduler=dask_cluster,
        tasks=7,
    )
    assert local.feasible > 0 and local.best is not None  # something to compare
    for r in (remote, by_address):
        assert r.best_index == local.best_index
        assert r.best == local.best
        assert (r.count, r.feasible) == (local.count, local.feasible)
        assert r.minimum == local.minimum and r.maximum == local.maximum


@pytest.mark.parametrize("name", ["blimp_gripper", "blimp_gripper_continuous"])
def test_kway_splits_and_enumeration_equal_plain_halving(
    monkeypatch: pytest.MonkeyPatch, name: str
) -> None:
    problem = Problem.from_spec(load_spec(EXAMPLES / f"{name}.toml"))
    fast = solve(problem, explain=False)
    monkeypatch.setattr(boxes_module, "MULTI_PARTS", 2)
    monkeypatch.setattr(bnb_module, "ENUMERATE", 0)
    ref = solve(problem, explain=False)
    assert fast.certified and ref.certified
    assert fast.mass == pytest.approx(ref.mass, rel=2e-12)
    if problem.gridded:
        assert fast.assembly == ref.assembly


finite = st.floats(-50, 50, allow_nan=False)
positive = st.floats(1e-3, 50, allow_nan=False)


@settings(max_examples=200, deadline=None)
@given(a=finite, b=finite, c=positive, d=positive, u=st.floats(0, 1), v=st.floats(0, 1))
def test_interval_fast_paths_contain_sampled_values(
    a: float, b: float, c: float, d: float, u: float, v: float
) -> None:
    x = Interval(np.array([min(a, b)]), np.array([max(a, b)]))
    y = Interval(np.array([min(c, d)]), np.array([max(c, d)]))  # positive
    # a point of each box: lo + u (hi - lo) rounds outside it (a = -1, b = -1.4e-45, u = 1 gives
    # 0.0 > hi), so it is clipped back in
    xs = np.clip(x.lo + u * (x.hi - x.lo), x.lo, x.hi)
    ys = np.clip(y.lo + v * (y.hi - y.lo), y.lo, y.hi)
    xp = Interval(np.abs(x.lo), np.abs(x.lo) + (x.hi - x.lo))  # non-negative
    xps = np.clip(xp.lo + u * (xp.hi - xp.lo), xp.lo, xp.hi)
    for box, val in (
        (x * y, xs * ys),
        (x / y, xs / ys),
        (xp * y, xps * ys),
        (xp / y, xps / ys),
        (xp + y, xps + ys),
        (xp * 3.0, xps * 3.0),
        (xp + 2.0, xps + 2.0),
        (xp**3, xps**3),
        (np.sqrt(xp), np.sqrt(xps)),
        (2.0 / y, 2.0 / ys),
    ):
        assert box.lo[0] <= val[0] <= box.hi[0]
    assert (xp * y).nonneg and (xp / y).nonneg and (xp + y).nonneg
    zero = Interval(np.array([0.0]), np.array([1.0]))
    assert (zero * zero).lo[0] == 0.0  # rounded towards 0, never below it
