"""The layer-by-layer search of independent layers (:mod:`corrugate.solver.separable`), checked
against two independent methods on random small specs:

* the whole grid, every pair of layer designs evaluated with ``point_values`` (``evaluate``) and
  judged with each constraint's own ``satisfied`` (the solver's rule, FEAS_RTOL): the least
  feasible mass, or none;
* the branch and bound itself (``record=True`` keeps it on its own path), the optimum the
  solver gave before the layer-by-layer search existed.

The specs are drawn so that the side ranges are sometimes unreachable (infeasible specs) and the
stiffness bounds are quantiles of what the size-feasible pairs reach (so they often bind: the
lightest size-feasible pair breaks them). The formulas the search judges pairs by are compared
with ``point_values`` directly, and the problems it must leave to the branch and bound are
listed.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from corrugate.solver import Problem, solve, tolerance_box
from corrugate.solver import separable as sep
from corrugate.solver.bnb import branch_and_bound
from corrugate.solver.points import DesignPoints, LayerPoints
from corrugate.solver.problem import Constraint
from corrugate.solver.quantities import Tables, point_values
from corrugate.solver.quantity import (
    FLAT,
    MASS,
    PART_LONG,
    PART_SHORT,
    THICKNESS,
    W_MIN,
    Quantity,
)
from corrugate.solver.solve import optimize, pairs
from corrugate.solver.worst_case import NOMINAL, WorstCase
from corrugate.spec.schema import Spec, load_spec


def _problem(
    *,
    model: str = "refined",
    thickness: str = '"0.25 mm"',
    W: tuple[float, float, float] = (5.0, 8.0, 1.0),
    alpha: tuple[float, float, float] = (60.0, 110.0, 10.0),
    n: tuple[int, int] = (6, 17),
    side_x: tuple[float, float] = (40.0, 44.0),
    side_y: tuple[float, float] = (60.0, 66.0),
    depth: float | None = None,
    machine: str | None = None,
    stiffness: tuple[tuple[str, float, str], ...] = (),
) -> Problem:
    """A small independent-layer rectangle spec; ``stiffness``: (kind, eta, support) bounds,
    each with min 1 (set later from the grid's values)."""
    lines = [
        'tolerances = "none"  # the separable search of the nominal model',
        'name = "separable"',
        f'model = "{model}"',
        'layers = "independent"',
        "[material]",
        'name = "polypropylene"',
        f"thickness = {thickness}",
        "[layout]",
        'shape = "rectangle"',
        "[variables]",
        f'W = {{ min = "{W[0]} mm", max = "{W[1]} mm", step = "{W[2]} mm" }}',
        f"n = {{ min = {n[0]}, max = {n[1]} }}",
        f'alpha = {{ min = "{alpha[0]} deg", max = "{alpha[1]} deg", step = "{alpha[2]} deg" }}',
        "[constraints]",
        f'side_x = {{ min = "{side_x[0]} mm", max = "{side_x[1]} mm" }}',
        f'side_y = {{ min = "{side_y[0]} mm", max = "{side_y[1]} mm" }}',
    ]
    if depth is not None:
        lines.append(f'thickness = {{ max = "{depth} mm" }}')
    units = {
        "flexural_rigidity": "N*mm^2",
        "bending_stiffness": "N*mm",
        "inplane_stiffness": "N/mm",
    }
    for kind, eta, support in stiffness:
        lines.append(
            f'[[constraints.{kind}]]\nmin = "1 {units[kind]}"\neta = "{eta} deg"\n'
            f'support = "{support}"'
        )
    if machine is not None:
        lines += ["[fabrication]", f'machine = "{machine}"']
    import tomllib

    return Problem.from_spec(Spec.model_validate(tomllib.loads("\n".join(lines))))


def _grid(problem: Problem) -> list[tuple[DesignPoints, dict[Quantity, np.ndarray]]]:
    """Every pair of layer designs of each sheet pair with the values of every quantity."""
    ns = np.arange(problem.n_lo, problem.n_hi + 1, dtype=np.float64)
    n, W, a = (
        v.reshape(-1)
        for v in np.meshgrid(ns, problem.W.values(), problem.alpha.values(), indexing="ij")
    )
    i, j = (v.reshape(-1) for v in np.meshgrid(np.arange(len(n)), np.arange(len(n)), indexing="ij"))
    x = DesignPoints.of(LayerPoints(n[i], W[i], a[i]), LayerPoints(n[j], W[j], a[j]))
    tables = Tables(problem)
    return [(x, point_values(problem, c1, c2, x, tables)) for c1, c2 in pairs(problem)]


def _feasible(problem: Problem, vals: dict[Quantity, np.ndarray]) -> np.ndarray:
    ok = np.ones(len(vals[MASS]), dtype=bool)
    for c in problem.constraints:
        ok &= c.satisfied(vals[c.quantity])
    return ok


def _grid_optimum(problem: Problem, grid: list) -> float:
    """The least feasible mass over the whole grid (nan: none)."""
    best = math.inf
    for _, vals in grid:
        m = np.where(_feasible(problem, vals), vals[MASS], np.inf)
        best = min(best, float(m.min()))
    return best if math.isfinite(best) else math.nan


def _with_bounds(problem: Problem, grid: list, quantiles: list[float]) -> Problem:
    """The problem with each stiffness bound set to a quantile of its values over the pairs of
    the first sheet pair that meet the size constraints (the largest value if there are none)."""
    stiff = [c.quantity.eta is not None for c in problem.constraints]
    sizes = replace(
        problem,
        constraints=tuple(c for c, s in zip(problem.constraints, stiff, strict=True) if not s),
    )
    vals = grid[0][1]
    ok = _feasible(sizes, vals)
    cons = []
    k = 0
    for c, s in zip(problem.constraints, stiff, strict=True):
        if s:
            v = vals[c.quantity][ok] if ok.any() else vals[c.quantity]
            bound = float(np.quantile(v, quantiles[k % len(quantiles)]))
            k += 1
            c = replace(c, bound=bound)
        cons.append(c)
    return replace(problem, constraints=tuple(cons))


def _same(a: float, b: float) -> bool:
    return (math.isnan(a) and math.isnan(b)) or a == pytest.approx(b, rel=1e-12)


def _bnb(problem: Problem) -> float:
    """The branch and bound's optimum (``record=True`` keeps it on its own path)."""
    opt = optimize(problem, record=True)
    assert opt.certified
    return opt.value


@pytest.mark.slow
@settings(
    max_examples=30,
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow],
    derandomize=True,
)
@given(
    model=st.sampled_from(["refined", "paper", "xia"]),
    two_sheets=st.booleans(),
    W0=st.integers(4, 9),
    a0=st.integers(40, 80),
    n0=st.integers(4, 12),
    centre=st.tuples(st.integers(0, 3), st.integers(0, 5), st.integers(0, 7)),
    widths=st.tuples(st.floats(0.02, 0.15), st.floats(0.02, 0.15)),
    reach=st.tuples(st.floats(0.85, 1.15), st.floats(0.85, 1.15)),
    depth=st.one_of(st.none(), st.floats(3.0, 12.0)),
    kinds=st.lists(
        st.tuples(
            st.sampled_from(["flexural_rigidity", "bending_stiffness", "inplane_stiffness"]),
            st.sampled_from([0.0, 90.0]),
            st.sampled_from(["free", "frame"]),
        ),
        max_size=2,
        unique=True,
    ),
    quantiles=st.lists(st.floats(0.0, 1.0), min_size=2, max_size=2),
    machine=st.sampled_from([None, "none"]),
)
def test_random_specs_match_the_whole_grid_and_the_branch_and_bound(
    model: str,
    two_sheets: bool,
    W0: int,
    a0: int,
    n0: int,
    centre: tuple[int, int, int],
    widths: tuple[float, float],
    reach: tuple[float, float],
    depth: float | None,
    kinds: list[tuple[str, float, str]],
    quantiles: list[float],
    machine: str | None,
) -> None:
    # the side ranges around the extent of a grid design, scaled by ``reach`` (near 0.85 or 1.15
    # often out of the grid's reach: of the 30 examples 13 are infeasible, and in 11 of the 17
    # others a stiffness bound binds: the lightest size-feasible pair breaks it)
    Wc, ac, nc = W0 + centre[0], a0 + 10 * centre[1], n0 + centre[2]
    ext = (nc + 1) * Wc * math.sin(math.radians(ac) / 2)
    sx = (ext * reach[0] * (1 - widths[0]), ext * reach[0] * (1 + widths[0]))
    sy = (ext * reach[1] * (1 - widths[1]), ext * reach[1] * (1 + widths[1]))
    problem = _problem(
        model=model,
        thickness='["0.2 mm", "0.3 mm"]' if two_sheets else '"0.25 mm"',
        W=(float(W0), float(W0 + 3), 1.0),
        alpha=(float(a0), float(a0 + 50), 10.0),
        n=(n0, n0 + 7),
        side_x=(round(sx[0], 3), round(sx[1], 3)),
        side_y=(round(sy[0], 3), round(sy[1], 3)),
        depth=depth,
        machine=machine,
        stiffness=tuple(kinds),
    )
    assert sep.applies(problem)
    grid = _grid(problem)
    problem = _with_bounds(problem, grid, quantiles)
    expected = _grid_optimum(problem, grid)
    sol = solve(problem, explain=False)
    assert sol.certified
    assert sol.status == ("infeasible" if math.isnan(expected) else "optimal")
    assert _same(sol.objective, expected)
    assert _same(_bnb(problem), expected)


def _binding_case(
    sides: tuple[tuple[float, float], tuple[float, float]] | None = None,
) -> tuple[Problem, list]:
    """EI(0) at the 70 % quantile of the size-feasible pairs, thickness at most 8 mm."""
    more = {} if sides is None else {"side_x": sides[0], "side_y": sides[1]}
    problem = _problem(stiffness=(("flexural_rigidity", 0.0, "free"),), depth=8.0, **more)
    grid = _grid(problem)
    return _with_bounds(problem, grid, [0.7]), grid


def test_a_binding_stiffness_bound_moves_the_optimum() -> None:
    """The EI(0) bound at the 70 % quantile of the size-feasible pairs binds: the lightest
    design without it is lighter, and both optima are the whole grid's."""
    problem, grid = _binding_case()
    free = problem.without("constraints.flexural_rigidity[0].min")
    with_bound, without = solve(problem, explain=False), solve(free, explain=False)
    assert with_bound.objective == pytest.approx(_grid_optimum(problem, grid), rel=1e-12)
    assert without.objective == pytest.approx(_grid_optimum(free, grid), rel=1e-12)
    assert without.objective < with_bound.objective * (1 - 1e-6)


@pytest.mark.parametrize(
    ("quantity", "sense", "wide"),
    [
        (PART_LONG, "max", True),
        (PART_SHORT, "max", False),
        (FLAT, "min", False),
        (W_MIN, "max", True),
    ],
)
def test_bounds_left_to_the_exact_evaluation_that_bind(
    quantity: Quantity, sense: str, wide: bool
) -> None:
    """Bounds the formulas do not model (the cut parts' sides, the blank's minimum, the
    narrowest facet's maximum) are judged only by the exact evaluation: set just past the
    optimum's value, one binds, the pairs the formulas rank lightest break it, and the search
    goes on (past its first threshold) to the whole grid's optimum, an EI bound binding too.
    (``wide``: side ranges 35-50 and 50-75 mm, where a design remains.)"""
    problem, grid = _binding_case(((35.0, 50.0), (50.0, 75.0)) if wide else None)
    first = optimize(problem)
    assert first.point is not None and first.candidates is not None
    x = first.point.arrays()
    at = float(point_values(problem, *first.candidates, x, Tables(problem))[quantity][0])
    bound = at * (1 - 1e-6) if sense == "max" else at * (1 + 1e-6)
    extra = Constraint("extra", quantity, sense, bound)  # type: ignore[arg-type]
    tight = replace(problem, constraints=(*problem.constraints, extra))
    expected = _grid_optimum(tight, grid)
    assert expected > first.value * (1 + 1e-9)  # it binds (and leaves a design)
    sol = solve(tight, explain=False)
    assert sol.certified and sol.objective == pytest.approx(expected, rel=1e-12)
    assert sol.objective == pytest.approx(_bnb(tight), rel=1e-12)


@pytest.mark.parametrize("mass_factor", [0.999, 1.0, 1.2])
def test_a_thickness_minimum_and_a_mass_budget(mass_factor: float) -> None:
    """A folded thickness of at least 7 mm (of the 8 mm allowed) and a mass budget of 0.999,
    1 and 1.2 times the optimum so found: infeasible just below it, the same design at it and
    above it; the whole grid and the branch and bound agree each time."""
    problem, grid = _binding_case()
    deep = replace(
        problem, constraints=(*problem.constraints, Constraint("tmin", THICKNESS, "min", 7.0))
    )
    best = _grid_optimum(deep, grid)
    assert best > _grid_optimum(problem, grid) * (1 + 1e-6)  # the minimum binds
    budget = Constraint("budget", MASS, "max", best * mass_factor)
    capped = replace(deep, constraints=(*deep.constraints, budget))
    expected = _grid_optimum(capped, grid)
    assert math.isnan(expected) == (mass_factor < 1)
    sol = solve(capped, explain=False)
    assert sol.certified and _same(sol.objective, expected)
    assert _same(_bnb(capped), expected)


def test_unreachable_sides_are_certified_infeasible() -> None:
    """side_x above the largest extent of the grid: no design, certified (and the grid agrees)."""
    problem = _problem(side_x=(500.0, 510.0))
    sol = solve(problem, explain=False)
    assert sol.status == "infeasible" and sol.certified
    assert math.isnan(_grid_optimum(problem, _grid(problem)))


def test_two_sheets_search_every_pair_with_the_incumbent() -> None:
    """Two thicknesses (four sheet pairs): the answer is the lightest over all four, the same
    design as the branch and bound's."""
    problem = _problem(
        thickness='["0.2 mm", "0.3 mm"]', stiffness=(("bending_stiffness", 90.0, "frame"),)
    )
    grid = _grid(problem)
    problem = _with_bounds(problem, grid, [0.8])
    opt = optimize(problem)
    ref = optimize(problem, record=True)
    assert opt.value == pytest.approx(_grid_optimum(problem, grid), rel=1e-12)
    assert opt.value == pytest.approx(ref.value, rel=1e-12)
    assert opt.point == ref.point and opt.candidates == ref.candidates


@pytest.mark.parametrize(
    ("kind", "eta", "support"),
    [
        (k, e, s)
        for k in ("flexural_rigidity", "bending_stiffness", "inplane_stiffness")
        for e in (0.0, 90.0)
        for s in ("free", "frame")
    ],
)
def test_the_formulas_are_point_values(kind: str, eta: float, support: str) -> None:
    """(u_i + v_j) f_i g_j and the mass of :mod:`~corrugate.solver.separable` equal
    ``point_values`` (``evaluate``) at every pair of two small layer lists, to rounding."""
    problem = _problem(stiffness=((kind, eta, support),), side_x=(30.0, 60.0), side_y=(30.0, 80.0))
    c = problem.candidates[0]
    L1, L2 = sep._layer(problem, c, 1), sep._layer(problem, c, 2)
    assert L1 is not None and L2 is not None and len(L1) > 10 and len(L2) > 10
    i, j = (v.reshape(-1) for v in np.meshgrid(np.arange(len(L1)), np.arange(len(L2))))
    x = DesignPoints.of(
        LayerPoints(L1.n[i], L1.W[i], L1.a[i]), LayerPoints(L2.n[j], L2.W[j], L2.a[j])
    )
    vals = point_values(problem, c, c, x, Tables(problem))
    q = problem.constraints[-1].quantity
    u, v, f, g = sep._terms(q, L1, L2, c.t, c.t)
    np.testing.assert_allclose((u[i] + v[j]) * f[i] * g[j], vals[q], rtol=1e-13)
    np.testing.assert_allclose(sep._mass(problem, c, c, L1, L2, i, j), vals[MASS], rtol=1e-13)


@pytest.mark.parametrize("kind", ["flexural_rigidity", "inplane_stiffness"])
def test_the_corner_terms_are_point_values_at_the_tolerance_box_corners(kind: str) -> None:
    """The layer lists' designs at the corners of their tolerance boxes (``shifts``, the floors
    of :mod:`~corrugate.solver.choices`) give, by the same formulas, ``point_values`` at the
    four parts :func:`~corrugate.solver.tolerance_box.corners` makes (a second method: the
    branch and bound's point screen), to rounding; the nominal list is unchanged by them."""
    problem = _problem(stiffness=((kind, 0.0, "free"),), side_x=(30.0, 60.0), side_y=(30.0, 80.0))
    c = problem.candidates[0]
    tol = WorstCase(alpha=3.0, W=0.1)
    shifts = tolerance_box.corner_shifts(tol)
    assert len(shifts) == 4
    L1, L2 = sep._layer(problem, c, 1, shifts), sep._layer(problem, c, 2, shifts)
    plain = sep._layer(problem, c, 1)
    assert L1 is not None and L2 is not None and plain is not None
    np.testing.assert_array_equal(L1.Eby, plain.Eby)
    i, j = (v.reshape(-1) for v in np.meshgrid(np.arange(len(L1)), np.arange(len(L2))))
    x = DesignPoints.of(
        LayerPoints(L1.n[i], L1.W[i], L1.a[i]), LayerPoints(L2.n[j], L2.W[j], L2.a[j])
    )
    q = problem.constraints[-1].quantity
    parts = tolerance_box.corners(replace(problem, tolerances=tol), c, c, x)
    for k, part in enumerate(parts):
        vals = point_values(problem, c, c, part, Tables(problem))
        u, v, f, g = sep._terms(q, L1.corners[k], L2.corners[k], c.t, c.t)
        np.testing.assert_allclose((u[i] + v[j]) * f[i] * g[j], vals[q], rtol=1e-13)
        assert not np.allclose(L1.corners[k].Eby, plain.Eby)  # the corner moved the moduli


def test_the_layer_lists_are_the_designs_that_meet_their_own_bounds() -> None:
    """Each layer's list (extents computed directly from the n range) is exactly the grid's
    designs whose extent meets its side range, the other per-layer bounds holding."""
    problem = _problem(side_x=(40.0, 44.0), side_y=(60.0, 66.0))
    c = problem.candidates[0]
    ns = np.arange(problem.n_lo, problem.n_hi + 1, dtype=np.float64)
    n, W, a = (
        v.reshape(-1)
        for v in np.meshgrid(ns, problem.W.values(), problem.alpha.values(), indexing="ij")
    )
    ext = (n + 1) * W * np.sin(np.radians(a) / 2)
    for which, (lo, hi) in ((1, (40.0, 44.0)), (2, (60.0, 66.0))):
        L = sep._layer(problem, c, which)
        assert L is not None
        got = sorted(zip(L.n.tolist(), L.W.tolist(), L.a.tolist(), strict=True))
        ok = (ext >= lo * (1 - 1e-9)) & (ext <= hi * (1 + 1e-9))
        want = sorted(zip(n[ok].tolist(), W[ok].tolist(), a[ok].tolist(), strict=True))
        assert got == want and len(got) > 0


def test_problems_without_the_structure_are_left_to_the_branch_and_bound(tmp_path) -> None:
    """Identical layers, a square, holes, off-axis bounds, buckling and a stiffness objective
    are not decomposed (the branch and bound solves them)."""
    base = _problem()
    assert sep.applies(base)
    assert not sep.applies(replace(base, identical=True))
    assert not sep.applies(replace(base, joint="band-edges"))
    # its formulas are the nominal model's: a certificate over tolerances is the search's
    assert not sep.applies(replace(base, tolerances=WorstCase(3.0, 0.1, 0.05, 0.1)))
    off = _problem(stiffness=(("inplane_stiffness", 45.0, "free"),))
    assert not sep.applies(off)
    pb = replace(
        base, constraints=(*base.constraints, Constraint("b", Quantity("Pb", 0.0), "min", 1.0))
    )
    assert not sep.applies(pb)
    stiff = base.with_objective(Quantity.stiffness("EI", 0.0), "max")
    assert not sep.applies(stiff)
    assert not sep.applies(replace(base, W=replace(base.W, step=None)))
    from corrugate.geometry.layouts import make_layout

    assert not sep.applies(replace(base, layout=make_layout("square")))
    assert (
        sep.search(off, *base.candidates * 2, None, lambda x: (x.layer(0).n, x.layer(0).n > 0))
        is None
    )


def test_the_chassis_spec_is_the_branch_and_bounds_optimum() -> None:
    """Issue 24's chassis spec (benchmarks/specs/chassis_independent.toml): the layer-by-layer
    answer is the branch and bound's (the same mass and design), certified with gap 0."""
    from pathlib import Path

    spec = Path(__file__).resolve().parents[2] / "benchmarks" / "specs" / "chassis_independent.toml"
    # the nominal model: the layer-by-layer search is not taken under tolerances
    problem = replace(Problem.from_spec(load_spec(spec)), tolerances=NOMINAL)
    assert sep.applies(problem)
    fast = optimize(problem)
    ref = optimize(problem, record=True)
    assert fast.certified and fast.gap == 0.0
    assert fast.value == ref.value
    assert fast.point == ref.point
    c = problem.candidates[0]
    r = branch_and_bound(problem, c, c)
    assert r.iterations == 1 and r.point == ref.point  # the layer-by-layer path was taken
