"""The binding checks answered together (:mod:`corrugate.solver.joint_checks`) and from the
floors of the sheet pairs (:meth:`corrugate.solver.choices.Floors.accepted`,
:attr:`corrugate.solver.solve.Optimum.floor_of`), each against a second method: every check's
own certified branch and bound from the boxes it reopens, and cold certified re-solves."""

from __future__ import annotations

from pathlib import Path

import pytest

from corrugate.solver import Problem
from corrugate.solver.bnb import branch_and_bound
from corrugate.solver.choices import floors, shared_lists
from corrugate.solver.joint_checks import joint_search, reopened
from corrugate.solver.quantities import Tables
from corrugate.solver.solve import _checks, _relaxed, optimize, pairs, solve
from corrugate.spec.schema import load_spec
from sheet_specs import sheet_choices_spec

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"


def _problem(path: Path) -> Problem:
    return Problem.from_spec(load_spec(path))


@pytest.mark.parametrize(
    "path",
    [
        EXAMPLES / "blimp_gripper.toml",  # identical layers, nominal
        pytest.param(EXAMPLES / "chassis_plate.toml", marks=pytest.mark.slow),  # tolerances
    ],
    ids=lambda p: p.stem,
)
def test_one_search_answers_each_check_as_its_own_search_does(path: Path) -> None:
    """Every constraint's check, answered by one joint search of the optimum's sheet pair,
    equals the answer of its own branch and bound (the check's problem: the constraint
    negated; the optimum as incumbent, stopping at the first better design) from the boxes the
    archive reopens for it; both answers occur."""
    problem = _problem(path)
    assert problem.gridded
    tables = Tables(problem)
    opt = optimize(problem, tables=tables, record=True)
    assert opt.certified and opt.candidates is not None
    tree = opt.tree()
    assert tree is not None and len(tree) == 1
    names = list(dict.fromkeys(c.name for c in problem.constraints))
    checks = _checks(problem, opt, names)  # the optimum is certified: each with its negation
    start = reopened(tree[0], checks, opt.value)
    joint = joint_search(problem, opt.candidates, tables, checks, start, opt.value)
    alone = []
    for check in checks:
        lo, hi, bound = tree[0].reopen(check.bits, opt.value)
        if not len(lo):
            alone.append(False)
            continue
        r = branch_and_bound(
            _relaxed(problem, check.name),
            *opt.candidates,
            incumbent=opt.value,
            tables=tables,
            start=(lo, hi, bound),
            stop_below=opt.value,
        )
        found = r.point is not None and r.value < opt.value
        assert found or r.certified
        alone.append(found)
    assert joint == alone
    assert True in alone and False in alone


def _sheet_choices(tmp: Path) -> Problem:
    """The six-sheet spec of :func:`sheet_specs.sheet_choices_spec` as a problem."""
    return _problem(sheet_choices_spec(tmp))


@pytest.mark.slow
def test_the_solves_floors_and_a_floors_accepted_design_are_what_they_claim(
    tmp_path: Path,
) -> None:
    """(1) :attr:`Optimum.floor_of`, which the runner-ups read: each pruned pair's cold
    certified optimum (its own branch and bound, no incumbent) is no lighter. (2)
    :meth:`Floors.accepted` of a pair, which a binding check takes as a better design: the
    pair's cold certified optimum is no heavier. (3) The runner-ups, whose pruned pairs are
    skipped by those floors, equal cold certified solves with n fixed."""
    problem = _sheet_choices(tmp_path)
    tables = Tables(problem)
    everything = pairs(problem)
    with shared_lists():
        opt = optimize(problem, tables=tables, record=True, prune=True)
        assert opt.certified and len(opt.pruned) >= 20 and opt.floors is not None
        assert set(opt.floor_of) == set(opt.pruned)
        accepted = 0
        fl = floors(problem)
        assert fl is not None
        for k in sorted(opt.pruned):
            cold = branch_and_bound(problem, *everything[k], tables=tables)
            assert cold.certified
            if cold.point is not None:
                assert cold.value >= opt.floor_of[k]
            fl.fine(k, float("inf"))
            if fl.accepted(k) < float("inf"):
                assert cold.point is not None and cold.value <= fl.accepted(k)
                accepted += 1
        assert accepted >= 5
    sol = solve(problem)
    got = {r.n: r for r in sol.runner_ups}
    assert sol.assembly is not None
    n_star = round(sol.assembly.layer1.n)
    for n in range(max(problem.n_lo, n_star - 3), min(problem.n_hi, n_star + 3) + 1):
        cold_n = optimize(problem, n_fixed=(n, n), tables=tables)
        assert cold_n.certified
        if cold_n.point is None:
            assert n not in got
            continue
        assert got[n].objective == cold_n.value, n


def test_floors_with_n_fixed_from_the_solves_lists_equal_those_built_for_it(
    tmp_path: Path,
) -> None:
    """:meth:`Floors.with_n` (the runner-ups' floors with n fixed, their layer lists taken from
    the solve's): every list holds the same designs as the list built for the problem with n
    fixed (:func:`floors` of it, a second method), and every pair's coarse floor is the same."""
    from dataclasses import replace

    import numpy as np

    problem = _sheet_choices(tmp_path)
    whole = floors(problem)
    assert whole is not None
    whole.coarse(0)  # every list built
    compared = 0
    for n in (problem.n_lo, (problem.n_lo + problem.n_hi) // 2, problem.n_hi):
        taken = whole.with_n(n)
        built = floors(replace(problem, n_lo=n, n_hi=n))
        assert built is not None
        size = len(problem.candidates) ** 2
        for k in range(size):
            assert taken.coarse(k) == built.coarse(k), (n, k)
        for key, designs in built._lists.items():
            got = taken._lists[key]
            assert (designs is None) is (got is None)
            if designs is None or got is None:
                continue
            rows = {tuple(r) for r in np.stack([designs.n, designs.W, designs.a], axis=1).tolist()}
            mine = {tuple(r) for r in np.stack([got.n, got.W, got.a], axis=1).tolist()}
            assert rows == mine and len(got) == len(designs)
            assert np.all(got.n == n)
            compared += len(designs)
    assert compared > 100


@pytest.mark.parametrize(
    "path",
    [
        EXAMPLES / "blimp_gripper.toml",  # identical layers, nominal
        EXAMPLES / "rectangle_independent.toml",  # independent layers (made nominal below)
    ],
    ids=lambda p: p.stem,
)
def test_first_points_judged_apart_then_the_joint_search_answer_as_each_check_alone(
    path: Path,
) -> None:
    """The path of the explanation on a nominal grid: the three points of every box the
    archive reopens for some check judged first for every check
    (:func:`~.joint_checks.answered_by` on :func:`~.joint_checks.three_points`), then one
    joint search of the checks left that does not judge them again (``offered``, its boxes
    to enumerate waiting while others are split): each check's answer equals its own branch
    and bound from the boxes the archive reopens for it (the check's problem: the constraint
    negated, the optimum as incumbent)."""
    from dataclasses import replace

    from corrugate.solver.joint_checks import answered_by, three_points
    from corrugate.solver.points import DesignPoints
    from corrugate.solver.quantities import point_values
    from corrugate.solver.worst_case import NOMINAL

    problem = replace(_problem(path), tolerances=NOMINAL)
    tables = Tables(problem)
    opt = optimize(problem, tables=tables, record=True)
    assert opt.certified and opt.candidates is not None
    tree = opt.tree()
    assert tree is not None and len(tree) == 1
    names = list(dict.fromkeys(c.name for c in problem.constraints))
    checks = _checks(problem, opt, names)  # the optimum is certified: each with its negation
    lo, hi, _, _ = reopened(tree[0], checks, opt.value)
    pts = three_points(problem, lo, hi)
    vals = point_values(problem, *opt.candidates, DesignPoints.from_columns(pts), tables)
    first = answered_by(problem, checks, vals, opt.value)
    left = [c for c, hit in zip(checks, first, strict=True) if not hit]
    start = reopened(tree[0], left, opt.value)
    rest = joint_search(problem, opt.candidates, tables, left, start, opt.value, offered=True)
    assert None not in rest
    got = dict(zip([c.name for c in left], rest, strict=True))
    got |= {c.name: True for c, hit in zip(checks, first, strict=True) if hit}
    alone = {}
    for check in checks:
        lo, hi, bound = tree[0].reopen(check.bits, opt.value)
        if not len(lo):
            alone[check.name] = False
            continue
        r = branch_and_bound(
            _relaxed(problem, check.name),
            *opt.candidates,
            incumbent=opt.value,
            tables=tables,
            start=(lo, hi, bound),
            stop_below=opt.value,
        )
        found = r.point is not None and r.value < opt.value
        assert found or r.certified
        alone[check.name] = found
    assert got == alone
    assert True in alone.values() and False in alone.values()


def test_the_judges_rules_give_the_verdicts_of_the_constraints_own_test() -> None:
    """:func:`~.joint_checks._met_rule` of :func:`~.joint_checks._rule` (the judge's reading
    of a constraint, thresholds computed once) against :meth:`Constraint.satisfied` to
    FEAS_RTOL (the search's own test), at values on, just inside and just outside each
    threshold, for lower and upper bounds of either sign and zero; bounds (lo, hi) judged by
    hi for a lower bound and lo for an upper one; an upper bound of a screened quantity not
    judged."""
    import numpy as np

    from corrugate.solver.joint_checks import _met_rule, _rule
    from corrugate.solver.problem import FEAS_RTOL, Constraint
    from corrugate.solver.quantity import Quantity

    q = Quantity("mass")
    for bound in (2.5, -3.0, 0.0, 1e-12, 80.0):
        tol = FEAS_RTOL * abs(bound)
        near = [bound - tol, bound + tol, bound]
        v = np.array([x + d for x in near for d in (-1e-15, 0.0, 1e-15)] + [bound * 2, -1.0])
        for sense in ("min", "max"):
            c = Constraint("c", q, sense, bound)
            rule = _rule(c)
            assert np.array_equal(_met_rule(rule, {q: v}, frozenset()), c.satisfied(v))
            both = (v - 1.0, v)
            want = c.satisfied(v if sense == "min" else v - 1.0)
            assert np.array_equal(_met_rule(rule, {q: both}, frozenset()), want)
            screened = _met_rule(rule, {q: v}, frozenset({q}))
            assert (screened is None) == (sense == "max")
            assert _met_rule(rule, {}, frozenset()) is None


def test_rows_and_columns_any_as_numpy_reduces_them() -> None:
    """The judge's ``any`` along rows and along columns (boolean matrix products) against
    numpy's reductions, empty shapes included."""
    import numpy as np

    from corrugate.solver.joint_checks import _cols_any, _rows_any

    rng = np.random.default_rng(5)
    for shape in ((0, 4), (7, 0), (1, 1), (50, 9), (3000, 3)):
        for p in (0.0, 0.01, 0.5):
            a = rng.random(shape) < p
            assert np.array_equal(_rows_any(a), a.any(axis=1))
            assert np.array_equal(_cols_any(a), a.any(axis=0))


def test_reopened_holds_each_checks_own_reopened_rows_and_narrowed_fewer_checks() -> None:
    """:func:`~.joint_checks.reopened` of every check at once: the rows carrying check j are
    the rows :meth:`Archive.reopen` gives for j alone (its bits, below the optimum), in the
    archive's order; :func:`~.joint_checks.narrowed` to some of the checks equals
    :func:`~.joint_checks.reopened` of those checks alone (how the explanation reuses the
    first boxes' rows)."""
    import numpy as np

    from corrugate.solver.joint_checks import narrowed

    problem = _problem(EXAMPLES / "blimp_gripper.toml")
    opt = optimize(problem, record=True)
    tree = opt.tree()
    assert tree is not None and opt.certified
    names = list(dict.fromkeys(c.name for c in problem.constraints))
    checks = _checks(problem, opt, names)
    lo, hi, bound, carried = start = reopened(tree[0], checks, opt.value)
    assert len(lo) > 10 and carried.any(axis=1).all()
    for j, check in enumerate(checks):
        own = tree[0].reopen(check.bits, opt.value)
        rows = carried[:, j]
        assert np.array_equal(lo[rows], own[0]) and np.array_equal(hi[rows], own[1])
        assert np.array_equal(bound[rows], own[2])
    for keep in ([0], [len(checks) - 1, 1], list(range(0, len(checks), 2))):
        got = narrowed(start, keep)
        want = reopened(tree[0], [checks[k] for k in keep], opt.value)
        assert all(np.array_equal(g, w) for g, w in zip(got, want, strict=True))


@pytest.mark.parametrize(
    "path",
    [EXAMPLES / "blimp_gripper.toml", EXAMPLES / "rectangle_independent.toml"],
    ids=lambda p: p.stem,
)
def test_the_checks_rule_names_at_the_probe_what_the_probe_names(path: Path) -> None:
    """The explanation judges the binding probe's points by the checks' own rule
    (:func:`~.joint_checks.answered_by`, with a certified optimum on a grid): the names it
    gives equal those of :func:`~.solve._witnessed` (a better point breaking only constraints
    of that name), the probe's own judgement, on the same values; some are named."""
    from dataclasses import replace

    from corrugate.solver.joint_checks import answered_by
    from corrugate.solver.quantities import point_values
    from corrugate.solver.solve import _probe_points, _witnessed
    from corrugate.solver.worst_case import NOMINAL

    problem = replace(_problem(path), tolerances=NOMINAL)
    tables = Tables(problem)
    opt = optimize(problem, tables=tables, record=True)
    assert opt.certified and problem.gridded
    assert opt.point is not None and opt.candidates is not None
    x = _probe_points(problem, opt.point)
    vals = point_values(problem, *opt.candidates, x, tables)
    names = list(dict.fromkeys(c.name for c in problem.constraints))
    checks = _checks(problem, opt, names)
    hit = answered_by(problem, checks, vals, opt.value)
    by_rule = {c.name for c, h in zip(checks, hit, strict=True) if h}
    assert by_rule == _witnessed(problem, opt, vals, 0.0)
    assert by_rule
