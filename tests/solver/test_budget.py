"""The solver's work budget (issue 22, item 2): counted in boxes here, so the tests do not depend
on the machine's speed; the seconds are the same check (tests/system/test_hostile.py runs them)."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from corrugate.core.errors import InputError
from corrugate.solver import Budget, Problem, Solution, solve
from corrugate.solver.budget import budget_scope, current_budget
from corrugate.solver.pareto import pareto_front
from corrugate.spec.schema import load_spec

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


@pytest.fixture(scope="module")
def problem() -> Problem:
    return Problem.from_spec(load_spec(EXAMPLES / "blimp_gripper.toml"))


@pytest.fixture(scope="module")
def certified(problem: Problem) -> Solution:
    return solve(problem, explain=False)


def test_a_budget_of_one_box_stops_uncertified_and_never_beats_the_optimum(
    problem: Problem, certified: Solution
) -> None:
    """The first iteration bounds more than one box, so the search stops before the second:
    status not-certified, what ran out recorded; any design found is a real one, so it is no
    lighter than the certified optimum and its proven gap covers the difference."""
    assert certified.status == "optimal"
    sol = solve(problem, budget=Budget(boxes=1))
    assert sol.status == "not-certified" and not sol.certified
    spent = sol.stats["budget"]
    assert isinstance(spent, dict)
    assert spent["stopped_by"] == "boxes" and spent["exhausted"] is True
    assert spent["used_boxes"] >= 1
    best = certified.objective
    if sol.assembly is not None:
        assert sol.objective >= best * (1 - 1e-12)
        if math.isfinite(sol.gap):
            assert (sol.objective - best) / sol.objective <= sol.gap * (1 + 1e-9)
    else:
        assert sol.diagnosis == ()  # nothing was proven: nothing to diagnose
    warning = [w for w in sol.warnings if w["code"] == "not-certified"]
    assert warning and "budget of 1 boxes" in warning[0]["message"]


def test_a_budget_that_lasts_changes_nothing(problem: Problem, certified: Solution) -> None:
    sol = solve(problem, explain=False, budget=Budget(seconds=3600))
    assert sol.status == "optimal" and sol.certified
    assert sol.objective == certified.objective
    spent = sol.stats["budget"]
    assert isinstance(spent, dict)
    assert spent["exhausted"] is False and spent["stopped_by"] is None
    assert spent["used_boxes"] == sol.stats["boxes"]  # every box of the search was charged


def test_the_pareto_front_stops_at_its_budget(problem: Problem) -> None:
    front = pareto_front(problem, "flexural_rigidity", budget=Budget(boxes=1))
    assert front.stopped == "boxes"
    assert not front.certified
    assert front.budget is not None and front.budget["exhausted"] is True


def test_scopes_nest_and_end() -> None:
    """None inside a scope reuses it (a robust solve's inner solves share one budget); outside
    any scope there is none; a charge past the boxes exhausts it."""
    assert current_budget() is None
    with budget_scope(Budget(boxes=10)) as outer:
        with budget_scope(None) as inner:
            assert inner is outer
        outer.charge(9)
        assert not outer.exhausted
        outer.charge(1)
        assert outer.exhausted and outer.stopped == "boxes"
    assert current_budget() is None


@pytest.mark.parametrize("seconds", [0.0, -1.0, math.nan, math.inf, 86_401.0])
def test_a_budget_outside_its_limit_is_refused(seconds: float) -> None:
    with pytest.raises(InputError) as exc:
        Budget(seconds=seconds)
    assert exc.value.field == "budget"
