"""The report's figures (corrugate.report.figures): the mass against n is the model's own lightest
feasible mass at each n, whatever the figure screens out of its grid first."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from corrugate.report import figures
from corrugate.solver.quantities import Tables, point_values
from corrugate.solver.quantity import MASS
from corrugate.workflow.notebook import design

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


@pytest.mark.parametrize(
    ("name", "n_max"),
    [
        ("blimp_gripper.toml", 24),  # identical layers, n from 1: the answer (n 9) inside
        ("rectangle_independent.toml", 27),  # independent layers, every n of the spec (4-30)
    ],
)
def test_mass_against_n_is_the_least_feasible_mass_of_each_n(name: str, n_max: int) -> None:
    """Each point drawn is the least mass, by the model's values (``point_values``) at every
    point of its n's grid of W and alpha, of the points that meet every constraint; a gap where
    none does. The figure screens its grid first (boxes of a segment of alpha, then points);
    this evaluates every point, so a screen that dropped a feasible point would show here."""
    run = design(EXAMPLES / name)
    problem, a = run.solution.problem, run.solution.analysis
    assert a is not None
    ns, drawn = figures.mass_by_n_figure(problem, a, n_max=n_max).axes[0].lines[0].get_data()
    Ws = problem.W.lo + problem.W.step * np.arange(
        round((problem.W.top - problem.W.lo) / problem.W.step) + 1
    )
    As = problem.alpha.lo + problem.alpha.step * np.arange(
        round((problem.alpha.top - problem.alpha.lo) / problem.alpha.step) + 1
    )
    WW, AA = (m.ravel() for m in np.meshgrid(Ws, As))
    expected = []
    for n in ns:
        x = figures._points(problem, a, np.full(WW.size, float(n)), WW, AA)
        values = point_values(problem, *figures._candidates(a), x, Tables(problem))
        ok = np.ones(WW.size, dtype=bool)
        for c in problem.constraints:
            ok &= c.satisfied(values[c.quantity])
        expected.append(values[MASS][ok].min() if ok.any() else np.nan)
    assert list(ns) == list(range(problem.n_lo, problem.n_lo + n_max))
    np.testing.assert_array_equal(np.asarray(drawn), np.asarray(expected))
    assert np.isfinite(np.asarray(drawn)).any() and np.isnan(np.asarray(drawn)).any()
    # the design's own n is drawn at its mass (the certified optimum is the lightest of its n)
    k = list(ns).index(a.assembly.layer1.n)
    assert drawn[k] == pytest.approx(a.mass.total, rel=1e-9)
