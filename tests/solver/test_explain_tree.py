"""The explanation from the search's own tree (issue 24, item 1): the archive of closed boxes
(:class:`corrugate.solver.archive.Archive`) and what is built from it, checked against independent
second methods.

* The archive's promise, on the whole grid of a spec (every design evaluated, no search): every
  design that meets all constraints but a set R (|R| <= 2) lies in a row that ``reopen(R)``
  returns, with a bound no higher than its objective.
* The explained answer (binding constraints, runner-ups) equals what independent certified
  re-solves from the whole domain give (the path every earlier version took): each constraint
  dropped in turn with the optimum as incumbent, and each n1 fixed in turn.
* The diagnosis of infeasible specs equals the one made with the archive switched off (every
  relaxed problem re-solved from its whole domain).
"""

from __future__ import annotations

import itertools
import math
from pathlib import Path

import numpy as np
import pytest

import corrugate.solver.archive as archive
from corrugate.solver import Problem, solve
from corrugate.solver.points import DesignPoints, LayerPoints
from corrugate.solver.progress import reporting
from corrugate.solver.quantities import Tables, point_values
from corrugate.solver.solve import GAP_RTOL, RUNNER_UP_GAP_RTOL, optimize, pairs
from corrugate.spec.schema import load_spec
from sheet_specs import sheet_choices_spec

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
DIAGNOSIS = ROOT / "tests" / "data" / "diagnosis"


def _problem(path: Path) -> Problem:
    return Problem.from_spec(load_spec(path))


SMALL_GRID = """[variables]
W = { min = "5 mm", max = "20 mm", step = "1 mm" }
n = { min = 6, max = 30 }
alpha = { min = "40 deg", max = "120 deg", step = "5 deg" }
"""


def _small(tmp: Path, feasible: bool) -> Problem:
    """tests/data/diagnosis/rectangle_identical.toml on a small grid (n 6-30, W 5-20 mm, alpha
    40-120 deg step 5: 6800 designs): infeasible (identical layers fold to Lx = Ly, but side_x
    and side_y do not overlap), or (``feasible``) with side_y 78-82 mm like side_x."""
    text = (DIAGNOSIS / "rectangle_identical.toml").read_text("utf-8")
    head, rest = text.split("[variables]", 1)
    text = head + SMALL_GRID + rest.split("\n\n", 1)[1]
    if feasible:
        text = text.replace(
            'side_y = { min = "118 mm", max = "122 mm" }',
            'side_y = { min = "78 mm", max = "82 mm" }',
        )
    path = tmp / "small.toml"
    path.write_text(text, "utf-8")
    return _problem(path)


def _small_independent(tmp: Path) -> Problem:
    """examples/rectangle_independent.toml on a small grid (per layer n 4-10, W 4-9 mm, alpha
    60-140 deg step 10: 378 designs, 142 884 pairs)."""
    text = (EXAMPLES / "rectangle_independent.toml").read_text("utf-8")
    head, rest = text.split("[variables]", 1)
    grid = (
        '[variables]\nW = { min = "4 mm", max = "9 mm", step = "1 mm" }\nn = { min = 4, max = 10 }\n'
        'alpha = { min = "60 deg", max = "140 deg", step = "10 deg" }\n'
    )
    path = tmp / "small_independent.toml"
    path.write_text(head + grid + rest.split("\n\n", 1)[1], "utf-8")
    return _problem(path)


@pytest.mark.parametrize("case", ["identical-infeasible", "identical-feasible", "independent"])
def test_archive_holds_every_design_of_every_relaxation(case: str, tmp_path: Path) -> None:
    if case == "independent":  # the per-layer enumeration (bnb._enumerate) drops pairs too
        problem = _small_independent(tmp_path)
        assert not problem.identical
    else:
        problem = _small(tmp_path, case == "identical-feasible")
        assert problem.identical
    tables = Tables(problem)
    opt = optimize(problem, tables=tables, record=True)
    assert opt.certified
    if problem.identical:
        assert (opt.point is not None) is (case == "identical-feasible")
    tree = opt.tree()
    assert tree is not None and len(tree) == 1
    archive = tree[0]
    # every grid design, evaluated directly
    ns = np.arange(problem.n_lo, problem.n_hi + 1, dtype=np.float64)
    n, W, a = (
        v.reshape(-1)
        for v in np.meshgrid(ns, problem.W.values(), problem.alpha.values(), indexing="ij")
    )
    if problem.identical:
        x = DesignPoints.of(LayerPoints(n, W, a))
    else:  # every pair of layer designs
        i, j = (
            v.reshape(-1) for v in np.meshgrid(np.arange(len(n)), np.arange(len(n)), indexing="ij")
        )
        x = DesignPoints.of(LayerPoints(n[i], W[i], a[i]), LayerPoints(n[j], W[j], a[j]))
    pts = x.columns()  # the search's coordinates
    c1 = problem.candidates[0]
    vals = point_values(problem, c1, c1, x, tables)
    broken = np.stack([~c.satisfied(vals[c.quantity]) for c in problem.constraints], axis=1)
    mass = vals[problem.objective.quantity]
    if opt.point is not None:  # the search's optimum is the grid's
        feasible = ~broken.any(axis=1)
        assert opt.value == pytest.approx(float(mass[feasible].min()), rel=1e-12)
    else:
        assert broken.any(axis=1).all()
    cons = range(len(problem.constraints))
    sets = [()] + [(i,) for i in cons] + list(itertools.combinations(cons, 2))
    checked = 0
    for relaxed in sets:
        bits = sum(1 << i for i in relaxed)
        others = [i for i in cons if i not in relaxed]
        meets = ~broken[:, others].any(axis=1) if others else np.ones(len(pts), dtype=bool)
        if not meets.any():
            continue
        lo, hi, bound = archive.reopen(bits)
        p = pts[meets]
        inside = np.all((lo[None] <= p[:, None]) & (p[:, None] <= hi[None]), axis=2)
        low_enough = inside & (bound[None] <= mass[meets][:, None] * (1 + 1e-12))
        assert low_enough.any(axis=1).all(), (relaxed, p[~low_enough.any(axis=1)][:5])
        checked += int(meets.sum())
    assert checked > 0


EXPLAINED = [
    EXAMPLES / "blimp_gripper.toml",
    EXAMPLES / "blimp_gripper_continuous.toml",
    EXAMPLES / "chassis_plate.toml",
    EXAMPLES / "rectangle_independent.toml",
    EXAMPLES / "wheel_circle.toml",
    ROOT / "benchmarks" / "specs" / "chassis_independent.toml",
]


@pytest.mark.parametrize("path", EXPLAINED, ids=lambda p: p.stem)
def test_binding_and_runner_ups_equal_independent_re_solves(path: Path) -> None:
    problem = _problem(path)
    sol = solve(problem)
    # a spec with trust = "extrapolate" is searched as exhaustively, its answer marked
    # extrapolated (the wheel example no longer asks for it: issue 35, docs/load_cases.md 9)
    assert sol.status == "optimal" and (sol.certified or problem.trust == "extrapolate")
    tables = Tables(problem)
    sign = -1.0 if problem.objective.sense == "max" else 1.0
    tol = (0.0 if problem.gridded else 2 * GAP_RTOL) * abs(sol.objective)
    for report in sol.constraints:  # each constraint dropped: a cold certified re-solve
        relaxed = optimize(problem.without(report.name), tables=tables, incumbent=sol.objective)
        assert relaxed.certified
        expected = relaxed.point is not None and sign * relaxed.value < sign * sol.objective - tol
        assert report.binding is expected, report.name
    assert any(r.binding for r in sol.constraints) or not sol.constraints
    n_star = round(sol.assembly.layer1.n)
    got = {r.n: r for r in sol.runner_ups}
    assert n_star in got or not problem.identical
    for n in range(max(problem.n_lo, n_star - 3), min(problem.n_hi, n_star + 3) + 1):
        cold = optimize(problem, n_fixed=(n, n), tables=tables)
        assert cold.certified
        if cold.point is None:
            assert n not in got
            continue
        assert got[n].certified
        if problem.gridded:
            assert got[n].objective == cold.value
        else:  # certified to RUNNER_UP_GAP_RTOL: a real design, no better one by more than that
            assert problem.objective.sense == "min"
            assert cold.value * (1 - 2 * GAP_RTOL) <= got[n].objective
            assert got[n].objective <= cold.value * (1 + RUNNER_UP_GAP_RTOL)
        assert [layer["n"] for layer in got[n].layers] == [n, n]  # as n_fixed: both layers
    if problem.identical or sol.assembly.layer2.n == n_star:
        assert got[n_star].objective == pytest.approx(sol.objective, rel=1e-12)


def _sheet_choices(tmp: Path) -> Problem:
    """The six-sheet spec of :func:`sheet_specs.sheet_choices_spec` as a problem."""
    return _problem(sheet_choices_spec(tmp))


@pytest.mark.slow
def test_binding_with_sheet_choices_equals_plain_re_solves(tmp_path: Path) -> None:
    """Material choices, most sheet pairs pruned whole by their floors (:mod:`.choices`): each
    constraint's binding flag (its check searched from the archive, the optimum's pair first,
    the pruned pairs ruled out by the floors of its own check or, for the checks with nothing
    to reopen, of one shared relaxation) equals a second method's: the plain certified solve
    of the spec without the constraint, the optimum as incumbent (layer by layer, no archive,
    no negation). The spec has binding constraints, constraints that do not bind, and
    constraints whose checks share the floors."""
    from corrugate.solver.solve import _untouched

    problem = _sheet_choices(tmp_path)
    tables = Tables(problem)
    opt = optimize(problem, tables=tables, record=True, prune=True)
    assert opt.certified and len(opt.pruned) >= 20  # most of the 36 pairs never searched
    tree = opt.trees()
    assert tree is not None
    shared = _untouched(problem, opt, tree, {c.name for c in problem.constraints})
    assert shared is not None and len(shared[1]) >= 2  # checks answered by shared floors
    sol = solve(problem)
    assert sol.objective == opt.value
    flags = []
    for report in sol.constraints:
        plain = optimize(
            problem.without(report.name), tables=tables, incumbent=sol.objective, prune=True
        )
        assert plain.certified
        expected = plain.point is not None and plain.value < sol.objective
        assert report.binding is expected, report.name
        flags.append(expected)
    assert any(flags) and not all(flags)


def test_a_witnessed_binding_constraint_binds_and_its_negation_holds_every_breaking_design() -> (
    None
):
    """The two shortcuts of the binding checks, each against a second method. (1) The probe
    (``_witnesses``): every constraint it names binds by a cold certified re-solve without it,
    and it names some on the shipped examples that have binding constraints (so the shortcut is
    used). (2) The negation a check adds (``_negation``): on a grid, a value just past the
    bound's slack (broken) meets it, and so does one on the slack's edge; continuous: the
    bound itself."""
    from corrugate.solver.problem import FEAS_RTOL, Constraint
    from corrugate.solver.quantity import LX
    from corrugate.solver.solve import _negation, _witnesses

    named = 0
    for path in (EXAMPLES / "wheel_circle.toml", EXAMPLES / "chassis_plate.toml"):
        problem = _problem(path)
        tables = Tables(problem)
        opt = optimize(problem, tables=tables)
        tol = (0.0 if problem.gridded else 2 * GAP_RTOL) * abs(opt.value)
        for name in _witnesses(problem, opt, tables, tol):
            relaxed = optimize(problem.without(name), tables=tables, incumbent=opt.value)
            assert relaxed.point is not None and relaxed.value < opt.value - tol, name
            named += 1
    assert named >= 2
    grid = _problem(EXAMPLES / "chassis_plate.toml")
    cont = _problem(EXAMPLES / "blimp_gripper_continuous.toml")
    for problem, r in ((grid, FEAS_RTOL), (cont, 0.0)):
        for sense in ("min", "max"):
            c = Constraint("side", LX, sense, 80.0)  # type: ignore[arg-type]
            neg = _negation(c, problem)
            assert neg.sense != c.sense
            edge = 80.0 * (1 - r) if sense == "min" else 80.0 * (1 + r)  # c holds here
            past = (
                np.array([edge * (1 - 1e-13)]) if sense == "min" else np.array([edge * (1 + 1e-13)])
            )
            assert not c.satisfied(past, rtol=r)[0]  # broken ...
            assert neg.satisfied(past, rtol=r)[0]  # ... so the negation holds
            assert neg.satisfied(np.array([edge]), rtol=r)[0]
            assert not neg.satisfied(np.array([80.0 * (1.1 if sense == "min" else 0.9)]), rtol=r)[0]


INFEASIBLE = [
    EXAMPLES / "infeasible.toml",
    DIAGNOSIS / "every_direction.toml",
    DIAGNOSIS / "offaxis_45.toml",
    DIAGNOSIS / "rectangle_identical.toml",
]


@pytest.mark.parametrize("path", INFEASIBLE, ids=lambda p: p.stem)
def test_diagnosis_from_the_tree_equals_the_cold_re_solves(
    path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    problem = _problem(path)
    warm = solve(problem)
    monkeypatch.setattr(archive, "ARCHIVE_ROWS", 0)  # no archive: every relaxation from scratch
    cold = solve(problem)
    assert warm.status == cold.status == "infeasible"
    assert warm.diagnosis  # something to compare
    assert [d.as_dict() for d in warm.diagnosis] == [d.as_dict() for d in cold.diagnosis]
    assert warm.stats["budget"]["used_boxes"] < cold.stats["budget"]["used_boxes"]  # type: ignore[index]


def test_an_archive_past_its_row_limit_is_dropped(monkeypatch: pytest.MonkeyPatch) -> None:
    problem = _problem(EXAMPLES / "blimp_gripper.toml")
    monkeypatch.setattr(archive, "ARCHIVE_ROWS", 10)
    opt = optimize(problem, record=True)
    assert opt.certified and opt.archives == (None,) and opt.tree() is None
    monkeypatch.undo()
    opt = optimize(problem, record=True)
    tree = opt.tree()
    assert tree is not None and len(tree) == len(pairs(problem)) and len(tree[0].lo) > 10


def test_progress_is_reported_once_per_iteration() -> None:
    problem = _problem(EXAMPLES / "rectangle_independent.toml")
    seen: list[tuple[int, float, float | None]] = []
    with reporting(lambda it, gap, best: seen.append((it, gap, best))):
        opt = optimize(problem)
    assert [s[0] for s in seen] == list(range(1, opt.iterations + 1))
    assert seen[0][2] is None or seen[0][2] >= opt.value
    finite = [s for s in seen if s[2] is not None]
    assert finite and all(b >= opt.value * (1 - 1e-12) for _, _, b in finite)
    assert all(g >= 0 and (math.isinf(g) or g < 10) for _, g, _ in seen)


@pytest.mark.parametrize("ncons", [1, 5, 12, 16, 17, 40, 52, 53, 63])
def test_bit_sets_and_distinct_equal_numpys_reductions(ncons: int) -> None:
    """The archive's bit sets of broken constraints (:func:`archive.bit_sets`: a product with
    powers of two, or bit by bit past 52 constraints) and their distinct values
    (:func:`archive.distinct`: a table up to 16 constraints) equal numpy's bitwise-or reduction,
    row sums and ``np.unique`` on random rows."""
    rng = np.random.default_rng(ncons)
    bits = np.uint64(1) << np.arange(ncons, dtype=np.uint64)
    for rows in (0, 1, 7, 3000):
        broken = rng.random((rows, ncons)) < 0.2
        mask, count = archive.bit_sets(broken)
        ref = np.zeros(rows, dtype=np.uint64)
        for i in range(ncons):
            ref |= np.where(broken[:, i], bits[i], np.uint64(0))
        assert mask.dtype == np.uint64
        np.testing.assert_array_equal(mask, ref)
        np.testing.assert_array_equal(count, broken.sum(axis=1))
        values, index = archive.distinct(mask, ncons)
        want, inverse = np.unique(ref, return_inverse=True)
        np.testing.assert_array_equal(values, want)
        np.testing.assert_array_equal(index, inverse.reshape(-1))


def _around(problem: Problem, point: DesignPoints, steps: int) -> tuple[np.ndarray, ...]:
    """Start boxes of the search's coordinates: a box of +-``steps`` grid steps around
    ``point`` (n by 1), cut in two along each coordinate's middle, clipped to the domain."""
    from corrugate.solver.points import coordinates

    dims = coordinates(problem)
    lo, hi = [], []
    for d in dims:
        v = float(getattr(point.layer(d.layer), d.variable))
        step = 1.0 if d.variable == "n" else float(d.var.step)
        lo.append(max(d.var.lo, v - steps * step))
        hi.append(min(d.var.top, v + steps * step))
    boxes = [(np.array(lo), np.array(hi))]
    for i, d in enumerate(dims):  # each box cut between two grid values of coordinate i
        step = 1.0 if d.variable == "n" else float(d.var.step)
        cut = []
        for a, b in boxes:
            k = math.floor((b[i] - a[i]) / step / 2)
            if k <= 0:
                cut.append((a, b))
                continue
            left_hi, right_lo = b.copy(), a.copy()
            left_hi[i] = a[i] + k * step
            right_lo[i] = a[i] + (k + 1) * step
            cut += [(a, left_hi), (right_lo, b)]
        boxes = cut
    lo_a = np.array([a for a, _ in boxes])
    hi_a = np.array([b for _, b in boxes])
    return lo_a, hi_a, np.full(len(boxes), -math.inf)


@pytest.mark.parametrize("name", ["blimp_gripper", "rectangle_independent"])
def test_runner_ups_by_enumeration_equal_the_branch_and_bound(name: str) -> None:
    """:func:`~.bnb.enumerated_per_n` (every grid point of small start boxes evaluated at
    once) gives the branch and bound's best design of each n (``per_n``) from the same boxes:
    the same point, value and certificate; on the case study's archive (identical layers) and
    on boxes around the optimum of the independent rectangle without tolerances (its layers'
    points paired as the search pairs them); None when a box holds too many points."""
    from dataclasses import replace

    from corrugate.solver.bnb import branch_and_bound, enumerated_per_n
    from corrugate.solver.worst_case import NOMINAL

    problem = replace(_problem(EXAMPLES / f"{name}.toml"), tolerances=NOMINAL)
    tables = Tables(problem)
    opt = optimize(problem, tables=tables, record=True)
    assert opt.point is not None and opt.candidates is not None
    n_star = round(opt.point.layer(0).n)
    span = (max(problem.n_lo, n_star - 3), min(problem.n_hi, n_star + 3))
    if problem.identical:
        tree = opt.tree()
        assert tree is not None
        start = tree[0].reopen()
    else:
        start = _around(problem, opt.point, 2)
    fast = enumerated_per_n(problem, *opt.candidates, start=start, per_n=span, tables=tables)
    assert fast is not None and fast.by_n is not None
    slow = branch_and_bound(problem, *opt.candidates, tables=tables, start=start, per_n=span)
    assert slow.by_n is not None and set(fast.by_n) == set(slow.by_n)
    found = 0
    for n, want in slow.by_n.items():
        got = fast.by_n[n]
        assert got.certified and want.certified
        assert got.point == want.point, n
        if want.point is not None:
            assert got.value == want.value
            found += 1
    assert found >= 2
    assert (
        enumerated_per_n(problem, *opt.candidates, start=start, per_n=span, tables=tables, most=1)
        is None
    )
