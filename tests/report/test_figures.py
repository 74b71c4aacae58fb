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


@pytest.mark.parametrize(
    ("name", "binding"),
    [
        # the binding EI bound's label was drawn under the optimum's star
        ("blimp_gripper.toml", "flexural_rigidity[0].min"),
        # a mass contour's label ("3 g") was drawn under the star
        ("wheel_circle.toml", "3 g"),
    ],
)
def test_no_curve_label_is_drawn_under_the_optimums_star(name: str, binding: str) -> None:
    """The design-space figure as drawn: the box of every label on a curve (a constraint's name,
    a mass in g) overlaps not the star's, and the label of the curve that ran under the star is
    still on the figure, moved along its curve (the key under the figure names it too)."""
    from matplotlib.path import Path as MplPath
    from matplotlib.transforms import Affine2D

    run = design(EXAMPLES / name)
    problem, a = run.solution.problem, run.solution.analysis
    assert a is not None
    fig, _key = figures.design_space(problem, a)
    renderer = fig.canvas.get_renderer()
    fig.draw(renderer)
    ax = fig.axes[0]
    (star,) = [line for line in ax.lines if line.get_marker() == "*"]
    x, y = star.get_data()
    assert (x[0], y[0]) == (a.assembly.layer1.W, a.assembly.layer1.alpha_deg)
    star_box = star.get_window_extent(renderer)
    labels = [t for t in ax.texts if t.get_text()]
    assert labels
    for t in labels:  # the rectangle the text is drawn in: its box unturned, turned
        box = t.get_window_extent(renderer)
        turned = t.get_rotation()
        t.set_rotation(0.0)
        flat = t.get_window_extent(renderer)
        t.set_rotation(turned)
        cx, cy = (box.x0 + box.x1) / 2, (box.y0 + box.y1) / 2
        corners = (
            Affine2D()
            .rotate_deg_around(cx, cy, turned)
            .transform(
                [
                    (cx - flat.width / 2, cy - flat.height / 2),
                    (cx + flat.width / 2, cy - flat.height / 2),
                    (cx + flat.width / 2, cy + flat.height / 2),
                    (cx - flat.width / 2, cy + flat.height / 2),
                ]
            )
        )
        outline = MplPath([*corners, corners[0]], closed=True)
        assert not outline.intersects_bbox(star_box, filled=True), t.get_text()
    assert binding in {t.get_text() for t in labels}


@pytest.mark.parametrize("name", ["blimp_gripper.toml", "wheel_circle.toml"])
def test_mass_against_n_has_its_title_inside_and_whole_numbers_of_creases(name: str) -> None:
    """The figure as drawn: its title's box lies inside the figure's (the continuous grid's title,
    "... a 161 x 161 grid of W and alpha; gaps: no feasible design)", was cut at the right edge
    of the wheel's figure) and every tick of n shown is a whole number (the wheel's two n were
    ticked 6.0, 6.2, ... 7.0)."""
    run = design(EXAMPLES / name)
    problem, a = run.solution.problem, run.solution.analysis
    assert a is not None
    fig = figures.mass_by_n_figure(problem, a, n_max=24)
    renderer = fig.canvas.get_renderer()
    fig.draw(renderer)
    ax = fig.axes[0]
    title = ax.title.get_window_extent(renderer)
    assert title.x0 >= 0 and title.x1 <= fig.bbox.width and title.y1 <= fig.bbox.height
    assert ax.title.get_text().endswith("gaps: no feasible design)")
    lo, hi = ax.get_xlim()
    shown = [t for t in ax.get_xticks() if lo <= t <= hi]
    assert len(shown) >= 2
    assert all(float(t).is_integer() for t in shown), shown


def test_each_constraint_curve_is_told_apart_from_the_others_by_its_key() -> None:
    """The wheel's design space draws 13 constraint curves in matplotlib's 10 colours: two curves
    of one colour were told apart by nothing (the key named both in the same colour, e.g.
    constraints.diameter.min and validity.wheel.t_over_W.min in pink). Each constraint's key
    entry is now a (colour, line style) no other entry has, and a curve drawn in the figure has
    that colour and style."""
    from matplotlib.colors import to_hex

    run = design(EXAMPLES / "wheel_circle.toml")
    problem, a = run.solution.problem, run.solution.analysis
    assert a is not None
    fig, key = figures.design_space(problem, a)
    curves = [e for e in key if e.mark in ("line", "dashed", "dashdot")]
    assert len(curves) > 10  # more curves than colours
    assert len({(e.colour, e.mark) for e in curves}) == len(curves)
    drawn = set()
    for cs in fig.axes[0].collections:
        for colour, (_offset, dashes) in zip(cs.get_edgecolor(), cs.get_linestyle(), strict=False):
            style = "line" if dashes is None else ("dashdot" if len(dashes) == 4 else "dashed")
            drawn.add((to_hex(colour), style))
    for e in curves:
        assert (e.colour, e.mark) in drawn, e.label
