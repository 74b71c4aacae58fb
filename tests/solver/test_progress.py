"""The branch and bound's progress hook (:mod:`corrugate.solver.progress`): one report per
iteration, numbered from 1 in each run, with a gap that is never negative and a best value that is
a feasible design's (so never better than the certified optimum)."""

from __future__ import annotations

import math
from pathlib import Path

from corrugate.solver import Problem
from corrugate.solver.progress import report, reporting
from corrugate.solver.solve import optimize
from corrugate.spec.schema import load_spec

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def test_every_iteration_reports_and_the_reports_are_consistent() -> None:
    problem = Problem.from_spec(load_spec(EXAMPLES / "blimp_gripper_continuous.toml"))
    calls: list[tuple[int, float, float | None]] = []
    with reporting(lambda it, gap, best: calls.append((it, gap, best))):
        opt = optimize(problem)
    assert opt.certified and calls
    runs: list[list[int]] = []
    for it, _, _ in calls:
        if it == 1:
            runs.append([])
        runs[-1].append(it)
    for r in runs:  # each run numbers its iterations 1, 2, 3, ...
        assert r == list(range(1, len(r) + 1))
    # every iteration but, at most, the last of each run (which finds nothing left) reports
    assert opt.iterations - len(runs) <= len(calls) <= opt.iterations
    for _, gap, best in calls:
        assert gap >= 0
        if best is None:
            assert math.isinf(gap)
        else:  # a feasible design's mass (minimised): never below the certified optimum
            assert best >= opt.value * (1 - 1e-12)
    # the continuous search finds designs before it ends, and closes in on the optimum
    bests = [b for _, _, b in calls if b is not None]
    assert len(bests) >= 2 and bests[-1] < bests[0]
    assert bests[-1] >= opt.value * (1 - 1e-12)


def test_without_a_reporter_nothing_happens_and_blocks_nest() -> None:
    report(1, 0.5, 2.0)  # the default: no reporter, no error
    outer: list[int] = []
    inner: list[int] = []
    with reporting(lambda it, gap, best: outer.append(it)):
        report(1, math.inf, None)
        with reporting(lambda it, gap, best: inner.append(it)):
            report(2, 0.1, 3.0)
        report(3, 0.0, 3.0)
    report(4, 0.0, 3.0)
    assert outer == [1, 3] and inner == [2]
