"""Matplotlib figures of the report, each with labelled axes and units.

* :func:`design_space_figure`: W against alpha at the optimum's n (layer 1; layer 2 held at the
  optimum when the layers are independent), the feasible region shaded, each constraint's boundary
  drawn and labelled with its spec path, mass contours, the optimum marked;
* :func:`mass_by_n_figure`: the lightest feasible mass for each n over a grid of W and alpha;
* :func:`polar_figure`: K(eta) and D(eta) of the design, eta from layer 1's creases.

All values come from :func:`corrugate.solver.quantities.point_values`, i.e. from
:func:`corrugate.analysis.evaluate.evaluate`, the one implementation of the model.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np
from numpy.typing import NDArray

from corrugate.analysis.evaluate import Analysis, analyze
from corrugate.core.plotting import new_figure
from corrugate.mechanics.behaviours import get_load_case, own_test, supports
from corrugate.solver.making import MAKING
from corrugate.solver.points import DesignPoints, LayerPoints
from corrugate.solver.problem import Candidate, Problem
from corrugate.solver.quantities import Tables, box_bounds, point_values
from corrugate.solver.quantities import chunk as evaluation_chunk
from corrugate.solver.quantity import MASS
from corrugate.solver.solve import ConstraintReport

__all__ = ["KeyEntry", "design_space", "design_space_figure", "mass_by_n_figure", "polar_figure"]

FloatArray = NDArray[np.float64]
#: Grid used across W and alpha when a variable is continuous (or its grid is finer).
GRID = 161
#: Design points evaluated per call of the model when the figures scan a range of n: about
#: 16000 keeps each working array (125 KiB) below glibc's mmap threshold (128 KiB), so the calls
#: reuse heap memory instead of faulting in fresh pages (the case study's scan: 72 ms against
#: 121 ms with 100000, medians of 5, see corrugate.analysis.sweep.DEFAULT_CHUNK).
BATCH_POINTS = 16_000
#: Points screened at once by :func:`mass_by_n_figure` with the constraints on quantities without
#: a direction (point values of :func:`corrugate.solver.quantities.box_bounds`, a few arrays
#: each), at most: no more than the solver evaluates at once (:func:`~corrugate.solver.quantities.chunk`,
#: 65 536 points nominally), so that a pass is one evaluation and not two joined (the case
#: study's figure: 0.035 s of CPU against 0.047-0.061 s with 100 000, the same values; issue 39).
SCREEN_POINTS = 100_000
#: The screen's relative tolerance: looser than the feasibility check's (FEAS_RTOL, 1e-9), so a
#: point the model's own values accept is never screened out by a rounding difference; the points
#: that pass are checked with the model's values, as before.
SCREEN_RTOL = 1e-6
#: Fixed margins of each figure (fractions of the figure), those ``tight_layout`` finds for the
#: case study with a little room to spare. Not ``tight_layout``: it measures every tick label
#: once more, and leaves a layout engine on the figure that makes every ``savefig`` draw the
#: figure twice.
_MARGINS: dict[str, dict[str, float]] = {
    "design_space": {"left": 0.10, "right": 0.97, "bottom": 0.10, "top": 0.935},
    "mass_by_n": {"left": 0.10, "right": 0.98, "bottom": 0.14, "top": 0.91},
    "polar": {"left": 0.065, "right": 0.945, "bottom": 0.13, "top": 0.82, "wspace": 0.24},
}


#: The title's height on axes whose ticks and labels are all below them (axes coordinates): given,
#: so that matplotlib does not measure every tick label of both axes at each draw to find that
#: nothing stands above the axes (where it would move the title up).
_TITLE_Y = 1.0
#: The polar plots' titles, just above their 0 deg label: matplotlib's automatic place is 1.088
#: for this layout (figure size, font sizes), found by measuring every tick label at each draw,
#: 40 % of the figure's drawing time.
_POLAR_TITLE_Y = 1.09


def _axis(lo: float, hi: float, step: float | None) -> FloatArray:
    if step is not None and (hi - lo) / step + 1 <= GRID:
        return np.asarray(lo + step * np.arange(int(np.floor((hi - lo) / step + 1e-9)) + 1))
    return np.linspace(lo, hi, GRID)


def _points(
    problem: Problem, a: Analysis, n1: FloatArray, W1: FloatArray, a1: FloatArray
) -> DesignPoints:
    """Layer 1 at the points (n1, W1, a1), layer 2 at the analysed design's own (or layer 1's
    for identical layers)."""
    one = LayerPoints(n1, W1, a1)
    if problem.identical:
        return DesignPoints.of(one)
    l2 = a.assembly.layer2
    two = LayerPoints(
        np.full_like(W1, float(l2.n)), np.full_like(W1, l2.W), np.full_like(W1, l2.alpha_deg)
    )
    return DesignPoints.of(one, two)


def _candidates(a: Analysis) -> tuple[Candidate, Candidate]:
    l1, l2 = a.assembly.layer1, a.assembly.layer2
    return Candidate(l1.material, l1.t), Candidate(l2.material, l2.t)


@dataclass(frozen=True)
class KeyEntry:
    """One entry of a figure's key: what a mark stands for (``label``), drawn as ``mark`` ("line":
    a solid line, "dashed" and "dashdot": a line so drawn, "star": the optimum's star, "area": a
    filled region) in ``colour`` (a hex colour)."""

    label: str
    mark: Literal["line", "dashed", "dashdot", "star", "area"]
    colour: str


#: A constraint curve's line style, by the round of the colour cycle its colour comes from: a
#: spec with more constraints than colours (the wheel's 13 against 10) draws the 11th solid curve
#: and the 1st alike no more. Matplotlib's name of each style and the key's mark of it.
_CURVE_STYLES: tuple[
    tuple[Literal["solid", "dashed", "dashdot"], Literal["line", "dashed", "dashdot"]], ...
] = (
    ("solid", "line"),
    ("dashed", "dashed"),
    ("dashdot", "dashdot"),
)


#: The shade of the feasible region in the design-space figure.
FEASIBLE_COLOUR = "#a1d99b"


def design_space(problem: Problem, a: Analysis) -> tuple[Any, list[KeyEntry]]:
    """The (W, alpha) plane of layer 1 at the optimum's n (see the module docstring), without a
    legend, and its key: each constraint whose boundary crosses the plane (its spec path and
    quantity, in the colour of its curve, also labelled on the curve), the optimum, the feasible
    region. The report prints the key under the figure as text (:mod:`.html`): drawn into the
    figure, a legend of a dozen long entries hid a third of the plot, and ``report_html`` of the
    blimp example takes 0.216 s of CPU without it against 0.251 s
    (``benchmarks/figures.py --base main --repeats 5``, 16:26 UTC; issue 39)."""
    import matplotlib
    from matplotlib.colors import to_hex

    l1 = a.assembly.layer1
    # the continuous relaxation on a fine grid, so boundaries and the region read clearly
    Ws = np.linspace(problem.W.lo, problem.W.top, GRID)
    As = np.linspace(problem.alpha.lo, problem.alpha.top, GRID)
    WW, AA = np.meshgrid(Ws, As)
    x = _points(problem, a, np.full(WW.size, float(l1.n)), WW.ravel(), AA.ravel())
    values = point_values(problem, *_candidates(a), x, Tables(problem))
    fig = new_figure((7.5, 5.5), dpi=100)
    ax = fig.subplots()
    feasible = np.ones(WW.size, dtype=bool)
    colours = matplotlib.rcParams["axes.prop_cycle"].by_key()["color"]
    key: list[KeyEntry] = []
    curves: list[_Curves] = []  # every labelled contour set, to keep its labels off the star
    for k, c in enumerate(problem.constraints):
        v = values[c.quantity]
        feasible &= c.satisfied(v)
        margin = (v - c.bound) if c.sense == "min" else (c.bound - v)
        scale = abs(c.bound) or 1.0
        field = (margin / scale).reshape(WW.shape)
        if np.nanmin(field) < 0 < np.nanmax(field):
            colour = colours[k % len(colours)]
            dashes, mark = _CURVE_STYLES[(k // len(colours)) % len(_CURVE_STYLES)]
            curve = _Curves(
                field,
                {"levels": [0.0], "colors": [colour], "linewidths": 1.4, "linestyles": dashes},
                {0.0: c.name.replace("constraints.", "")},
                7,
            )
            curves.append(curve.draw(ax, WW, AA))
            key.append(KeyEntry(f"{c.name} ({c.quantity.description})", mark, to_hex(colour)))
    ax.contourf(
        WW,
        AA,
        feasible.reshape(WW.shape).astype(float),
        levels=[0.5, 1.5],
        colors=[FEASIBLE_COLOUR],
        alpha=0.6,
    )
    mass = values[MASS].reshape(WW.shape)
    cm = ax.contour(WW, AA, mass, levels=8, colors="grey", linewidths=0.5, linestyles="dotted")
    mass_fmt = {float(v): f"{v:.3g} g" for v in cm.levels}  # "%.3g g", level by level
    ax.clabel(cm, fmt=mass_fmt, fontsize=6)
    style = {"levels": list(mass_fmt), "colors": "grey", "linewidths": 0.5, "linestyles": "dotted"}
    curves.append(_Curves(mass, style, mass_fmt, 6, drawn=cm))
    optimum = f"optimum: W {l1.W:g} mm, alpha {l1.alpha_deg:g} deg"
    (star,) = ax.plot(
        [l1.W],
        [l1.alpha_deg],
        marker="*",
        color="black",
        markersize=14,
        linestyle="none",
        zorder=4,  # over every curve, those drawn again below too
    )
    key.append(KeyEntry(optimum, "star", "#000000"))
    key.append(KeyEntry("feasible", "area", FEASIBLE_COLOUR))
    ax.set_xlabel("facet width W (mm)")
    ax.set_ylabel("fold angle alpha (deg)")
    ax.set_title(
        f"design space at n = {l1.n}: feasible region (continuous), grey: mass (g)", y=_TITLE_Y
    )
    fig.subplots_adjust(**_MARGINS["design_space"])
    _labels_off_the_star(ax, star, curves, WW, AA)
    return fig, key


@dataclass
class _Curves:
    """One labelled contour set of the design-space figure: the ``field`` on the (W, alpha) grid,
    the ``contour`` keywords (its levels and style), each level's label (``fmt``) and the labels'
    font size (pt); ``drawn``: the set drawn last."""

    field: FloatArray
    style: dict[str, Any]
    fmt: dict[float, str]
    fontsize: float
    drawn: Any = None

    def draw(
        self, ax: Any, WW: FloatArray, AA: FloatArray, manual: Sequence[Point2] | bool = False
    ) -> _Curves:
        """Draw the curves and label them (matplotlib's places, or at ``manual`` (W, alpha)
        points: each label on the curve nearest its point); returns itself."""
        if self.drawn is not None:
            self.drawn.remove()  # the curves and their labels
        self.drawn = ax.contour(WW, AA, self.field, **self.style)
        ax.clabel(self.drawn, fmt=self.fmt, fontsize=self.fontsize, manual=manual)
        return self


Point2 = tuple[float, float]


def _quads(cx: Any, cy: Any, w: Any, h: Any, angle: Any) -> FloatArray:
    """The corners (..., 4, 2) of rectangles of sides ``w`` along and ``h`` across the direction
    ``angle`` (radians) about the centres (``cx``, ``cy``), in display units."""
    c, s = np.cos(angle), np.sin(angle)
    u = np.stack([c * w / 2, s * w / 2], axis=-1)[..., None, :]
    v = np.stack([-s * h / 2, c * h / 2], axis=-1)[..., None, :]
    signs = np.array([[1.0, 1.0], [-1.0, 1.0], [-1.0, -1.0], [1.0, -1.0]])
    centre = np.stack([np.asarray(cx, float), np.asarray(cy, float)], axis=-1)[..., None, :]
    return np.asarray(centre + signs[:, :1] * u + signs[:, 1:] * v)


def _apart(a: FloatArray, b: FloatArray) -> NDArray[np.bool_]:
    """Whether each rectangle of ``a`` (N, 4, 2) is clear of the rectangle ``b`` (4, 2) (their
    interiors do not meet): a side of one separates them (the separating axis theorem)."""
    apart = np.zeros(a.shape[0], dtype=bool)
    edges = [a[:, 1] - a[:, 0], a[:, 3] - a[:, 0]]
    edges += [
        np.broadcast_to(b[1] - b[0], (a.shape[0], 2)),
        np.broadcast_to(b[3] - b[0], (a.shape[0], 2)),
    ]
    for axis in edges:
        pa = np.einsum("nkd,nd->nk", a, axis)
        pb = b @ axis.T  # (4, N)
        apart |= (pa.max(axis=1) <= pb.min(axis=0)) | (pb.max(axis=0) <= pa.min(axis=1))
    return apart


def _text_quad(t: Any, renderer: Any) -> FloatArray:
    """The rectangle (4, 2) a centred, turned label ``t`` is drawn in (display units): its box
    unturned, turned by its rotation about the centre of its drawn box."""
    box = t.get_window_extent(renderer)
    turned = t.get_rotation()
    t.set_rotation(0.0)
    flat = t.get_window_extent(renderer)
    t.set_rotation(turned)
    quad = _quads(
        (box.x0 + box.x1) / 2, (box.y0 + box.y1) / 2, flat.width, flat.height, np.radians(turned)
    )
    return np.asarray(quad[0] if quad.ndim == 3 else quad)


def _labels_off_the_star(
    ax: Any, star: Any, curves: Sequence[_Curves], WW: FloatArray, AA: FloatArray
) -> None:
    """Move every curve label drawn over the optimum's star to the nearest point of its own curve
    where it clears the star, the axes' edges and the other labels (the label of a binding
    constraint, whose curve runs through the optimum, was drawn under the star); a label with no
    such point is left out (the key under the figure names its curve). A contour set with a label
    moved is drawn again, its other labels where they were. Labels are the rectangles their text
    is drawn in, turned along the curve as matplotlib turns them, in display units on the figure
    as laid out (its margins set)."""
    renderer = ax.figure.canvas.get_renderer()
    pad = 2.0  # display units (px at the figure's dpi) kept around the star
    sb = star.get_window_extent(renderer)
    star_quad = _quads(
        (sb.x0 + sb.x1) / 2, (sb.y0 + sb.y1) / 2, sb.width + 2 * pad, sb.height + 2 * pad, 0.0
    )
    frame = ax.bbox
    if not any(
        t.get_window_extent(renderer).overlaps(sb) for c in curves for t in c.drawn.labelTexts
    ):
        return  # no label's drawn box meets the star's: nothing to measure closer
    quads = {id(t): _text_quad(t, renderer) for c in curves for t in c.drawn.labelTexts}
    for c in curves:
        texts = list(c.drawn.labelTexts)
        under = {id(t) for t in texts if not _apart(quads[id(t)][None], star_quad)[0]}
        if not under:
            continue
        own = {id(t) for t in texts}
        others = [q for key, q in quads.items() if key not in own] + [star_quad]
        kept: list[Point2] = []
        for t in texts:
            x, y = t.get_position()
            if id(t) not in under:
                kept.append((float(x), float(y)))
                others.append(quads[id(t)])
                continue
            turned = t.get_rotation()
            t.set_rotation(0.0)
            flat = t.get_window_extent(renderer)  # the text's length and height, unturned
            t.set_rotation(turned)
            k = list(c.fmt).index(next(v for v, text in c.fmt.items() if text == t.get_text()))
            best: tuple[float, Point2, FloatArray] | None = None
            ox, oy = ax.transData.transform((x, y))
            for seg in c.drawn.allsegs[k]:
                if len(seg) < 2:
                    continue
                px, py = ax.transData.transform(seg).T
                angle = np.arctan2(np.gradient(py), np.gradient(px))
                spots = _quads(px, py, flat.width, flat.height, angle)
                ok = (spots[..., 0].min(axis=1) >= frame.x0) & (
                    spots[..., 0].max(axis=1) <= frame.x1
                )
                ok &= (spots[..., 1].min(axis=1) >= frame.y0) & (
                    spots[..., 1].max(axis=1) <= frame.y1
                )
                for q in others:
                    ok &= _apart(spots, q)
                if not ok.any():
                    continue
                far = np.where(ok, np.hypot(px - ox, py - oy), np.inf)
                j = int(np.argmin(far))
                if best is None or far[j] < best[0]:
                    best = (float(far[j]), (float(seg[j, 0]), float(seg[j, 1])), spots[j])
            if best is not None:
                kept.append(best[1])
                others.append(best[2])
        c.draw(ax, WW, AA, manual=kept)


def design_space_figure(problem: Problem, a: Analysis) -> Any:
    """The (W, alpha) plane of layer 1 at the optimum's n (see the module docstring), its key
    drawn in as a legend (:func:`design_space`: the figure and its key apart)."""
    from matplotlib.lines import Line2D
    from matplotlib.patches import Rectangle

    fig, key = design_space(problem, a)
    handles: list[Any] = []
    for e in key:
        if e.mark == "area":
            handles.append(Rectangle((0, 0), 1, 1, color=e.colour, label=e.label))
        elif e.mark == "star":
            handles.append(
                Line2D([], [], marker="*", color=e.colour, linestyle="none", label=e.label)
            )
        else:
            dashes = {mark: name for name, mark in _CURVE_STYLES}[e.mark]
            handles.append(Line2D([], [], color=e.colour, linestyle=dashes, label=e.label))
    fig.axes[0].legend(handles=handles, fontsize=7, loc="best")
    return fig


def _may_pass(
    problem: Problem,
    a: Analysis,
    ns: NDArray[np.int64],
    grid: tuple[FloatArray, FloatArray],
    tables: Tables,
    quantities: set[Any],
) -> NDArray[np.bool_]:
    """Whether each n of ``ns`` and W of the grid (W, alpha) may have an alpha of the grid at
    which the constraints on ``quantities`` are met (an array, n by W): not when the bounds of
    one of them over the segment of every alpha of the grid at that n and W
    (:func:`~corrugate.solver.quantities.box_bounds`, the solver's bounds, which hold at every
    point of the box) miss its bound, to :data:`SCREEN_RTOL` (a bound that is not a number
    drops nothing)."""
    Ws, As = grid
    keep = np.ones(ns.size * Ws.size, dtype=bool)
    if quantities:
        n, W = np.repeat(ns.astype(float), Ws.size), np.tile(Ws, ns.size)
        lo = _points(problem, a, n, W, np.full(n.size, As.min()))
        hi = _points(problem, a, n, W, np.full(n.size, As.max()))
        bounds = box_bounds(problem, *_candidates(a), lo, hi, tables, quantities)
        for c in problem.constraints:
            if c.quantity in quantities:
                low, high = bounds[c.quantity]
                best = np.asarray(high if c.sense == "min" else low)
                keep &= c.satisfied(best, rtol=SCREEN_RTOL) | np.isnan(best)
    return keep.reshape(ns.size, Ws.size)


def mass_by_n_figure(problem: Problem, a: Analysis, n_max: int = 200) -> Any:
    """Lightest feasible mass (g) for each n, over the W x alpha grid of :func:`design_space_figure`."""

    Ws = _axis(problem.W.lo, problem.W.top, problem.W.step)
    As = _axis(problem.alpha.lo, problem.alpha.top, problem.alpha.step)
    WW, AA = np.meshgrid(Ws, As)
    W1, A1 = WW.ravel(), AA.ravel()
    tables = Tables(problem)
    ns = np.arange(problem.n_lo, min(problem.n_hi, problem.n_lo + n_max - 1) + 1)
    c1, c2 = _candidates(a)
    cheap = {c.quantity for c in problem.constraints if not c.quantity.directional}
    # the making quantities (parts, facets, t/W) after the others, at the points those pass
    screens = [q for q in (cheap - MAKING, cheap & MAKING) if q]
    mass = np.full((len(ns), W1.size), np.inf)
    # the constraints on quantities without a direction (extents, thickness, blank, ...) first:
    # over each n and W's segment of alpha (a box), then at the points of the segments they may
    # pass, in passes of about SCREEN_POINTS; the model (stiffness, mass) only at the points
    # that pass them, BATCH_POINTS per evaluation. The boxes leave 155 of the case study's 6000
    # segments (n 1-200, W 1-30 mm): the figure built in 0.0125 s of CPU against 0.0403 s
    # (benchmarks/figures.py --base main, medians of 7), the same values (issue 39)
    per_pass = max(1, min(SCREEN_POINTS, evaluation_chunk(problem)) // W1.size)
    may = _may_pass(problem, a, ns, (Ws, As), tables, cheap)
    rows = np.flatnonzero(may.any(axis=1))
    for first_row in range(0, rows.size, per_pass):
        group = rows[first_row : first_row + per_pass]
        chunk = ns[group]
        n1 = np.repeat(chunk.astype(float), W1.size)
        x = _points(problem, a, n1, np.tile(W1, len(chunk)), np.tile(A1, len(chunk)))
        keep = np.tile(may[group], (1, As.size)).ravel()
        for screen in screens:
            at = np.flatnonzero(keep)
            if not at.size:
                break
            sub = x if at.size == n1.size else x.take(at)
            screened = box_bounds(problem, c1, c2, sub, sub, tables, screen)
            ok = np.ones(at.size, dtype=bool)
            for c in problem.constraints:
                if c.quantity in screen:
                    ok &= c.satisfied(screened[c.quantity][0], rtol=SCREEN_RTOL)
            keep[at] = ok
        found = np.full(n1.size, np.inf)
        passed = np.flatnonzero(keep)
        for first in range(0, passed.size, BATCH_POINTS):
            at = passed[first : first + BATCH_POINTS]
            values = point_values(problem, c1, c2, x.take(at), tables)
            ok = np.ones(at.size, dtype=bool)
            for c in problem.constraints:
                ok &= c.satisfied(values[c.quantity])
            found[at] = np.where(ok, values[MASS], np.inf)
        mass[group] = found.reshape(len(chunk), W1.size)
    lightest = mass.min(axis=1)
    best = np.where(np.isfinite(lightest), lightest, np.nan)
    from matplotlib.ticker import MaxNLocator

    fig = new_figure((7.5, 4.0), dpi=100)
    ax = fig.subplots()
    ax.plot(ns, best, marker="o", markersize=3, linewidth=1)
    l1 = a.assembly.layer1
    ax.plot(
        [l1.n],
        [a.mass.total],
        marker="*",
        color="black",
        markersize=14,
        linestyle="none",
        label=f"certified optimum, {a.mass.total:.4g} g",
    )
    grid = "the spec's grid" if problem.gridded else f"a {GRID} x {GRID} grid of W and alpha"
    ax.set_xlabel("number of creases n")
    ax.xaxis.set_major_locator(MaxNLocator(integer=True))  # n is a whole number of creases
    ax.set_ylabel("lightest feasible mass (g)")
    title = ax.set_title(f"mass against n (best over {grid}; gaps: no feasible design)", y=_TITLE_Y)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.subplots_adjust(**_MARGINS["mass_by_n"])
    # a title wider than the figure (the continuous grid's) is set smaller until it fits: it was
    # cut at the figure's right edge ("no feasible desigr")
    centre = (ax.bbox.x0 + ax.bbox.x1) / 2  # the title is centred over the axes
    room = 2 * min(centre, fig.bbox.width - centre) - fig.dpi * 0.1
    width = title.get_window_extent().width
    if width > room:
        title.set_fontsize(title.get_fontsize() * room / width)
    return fig


def _plain_number(value: float, _pos: object = None) -> str:
    return f"{value:g}"


def polar_figure(a: Analysis) -> Any:
    """K(eta) (N/mm) and D(eta) (N mm) of the design on polar axes, eta from layer 1's creases:
    one curve per registered support condition (:mod:`corrugate.mechanics.behaviours`, labelled by
    its entry): the free panel's lower bounds (:mod:`corrugate.mechanics.offaxis`) and the rule of
    a panel held in a rigid frame, on a logarithmic radius (they differ by up to three orders of
    magnitude); the design's own support condition is the solid line."""

    from matplotlib.ticker import FuncFormatter

    etas = np.linspace(0.0, 360.0, 145)
    curves = {
        b: analyze(a.assembly, a.model, list(etas), support=b.name, joint=a.joint).stiffness
        for b in supports()
    }
    fig = new_figure((8, 4), dpi=100)
    axes = fig.subplots(1, 2, subplot_kw={"projection": "polar"})
    for ax, key, title in (
        (axes[0], "K", "in-plane K(eta) (N/mm)"),
        (axes[1], "D", "bending D(eta) (N mm)"),
    ):
        for sup, st in curves.items():
            values = np.array([getattr(s, key) for s in st])
            style = "-" if sup.name == a.support else "--"
            ax.plot(np.radians(etas), values, style, label=sup.curve, lw=1.2)
        ax.set_rscale("symlog", linthresh=1.0)
        # radii as plain numbers (1, 10, 100): symlog's default 10^k labels are mathtext, whose
        # parser costs about 0.1 s of CPU to build in each process
        ax.yaxis.set_major_formatter(FuncFormatter(_plain_number))
        ax.set_theta_zero_location("N")
        ax.set_theta_direction(-1)
        ax.set_title(title, fontsize=9, y=_POLAR_TITLE_Y)
        ax.tick_params(labelsize=7)
    axes[0].legend(fontsize=7, loc="lower left", bbox_to_anchor=(-0.15, -0.2))
    fig.suptitle("eta measured from layer 1's creases", fontsize=8)
    fig.subplots_adjust(**_MARGINS["polar"])
    return fig


def load_case_figure(
    reports: Sequence[ConstraintReport], extents: tuple[float, float] = (1.0, 1.0)
) -> Any:
    """One panel per deflection bound (:class:`~corrugate.solver.solve.ConstraintReport` with a
    ``load``): the test's supports (rollers for three- and four-point bending, a clamp for a
    cantilever, platens for compression), the load, and the deflected shape of an Euler-Bernoulli
    beam (shape only, exaggerated), titled with the certified deflection (mm) under the load (N)
    and its bound (docs/load_cases.md). Each test's sketch is its registry entry's
    (:class:`~corrugate.mechanics.behaviours.TestForm`: ``clamped``, ``loads``, ``shape``). ``extents`` (Lx, Ly in mm) give the span of a report
    without one of its own (Ly along eta = 0, Lx otherwise). None when no report is a
    deflection bound."""
    cases = [r for r in reports if r.load is not None]
    if not cases:
        return None
    fig = new_figure((4.2 * len(cases), 2.4), dpi=100)
    axes = fig.subplots(1, len(cases), squeeze=False)[0]
    for ax, r in zip(axes, cases, strict=True):
        q = r.quantity
        case = get_load_case(q.test) if q.test else own_test()  # a K bound: the own test's
        form = case.form
        assert form is not None
        span = q.span or (extents[1] if (q.eta or 0.0) % 180 == 0 else extents[0])
        x = np.linspace(0.0, 1.0, 101)
        amp = 0.12
        ax.plot([0, 1], [0, 0], color="0.75", lw=6, solid_capstyle="butt")  # the panel
        if form.kind == "inplane":  # pressed between platens
            for xp in (-0.03, 1.03):
                ax.plot([xp, xp], [-0.2, 0.2], color="k", lw=4)
            ax.annotate("", xy=(0.97, 0), xytext=(1.25, 0), arrowprops={"arrowstyle": "-|>"})
            ax.annotate("", xy=(0.03, 0), xytext=(-0.25, 0), arrowprops={"arrowstyle": "-|>"})
        else:
            if form.clamped:  # the root clamped at x = 0
                ax.fill_between([-0.06, 0], -0.25, 0.25, color="0.3", hatch="///")
            else:  # rollers at both ends
                for xs in (0.0, 1.0):
                    ax.plot([xs], [-0.05], marker="^", color="k", ms=10)
            if form.shape is not None:
                w = form.shape(x)
                ax.plot(
                    x,
                    -amp * w / np.max(w),
                    color="tab:red",
                    lw=1.5,
                    label="deflected (not to scale)",
                )
            for xl in form.loads:
                ax.annotate("", xy=(xl, 0.04), xytext=(xl, 0.3), arrowprops={"arrowstyle": "-|>"})
        test = case.name
        span_text = f", span {span:.4g} mm" if form.kind == "bending" else ""
        ax.set_title(
            f"{test}{span_text}\n{r.value:.3g} mm under {r.load:g} N (at most {r.bound:.3g} mm)",
            fontsize=9,
        )
        ax.set_xlim(-0.3, 1.3)
        ax.set_ylim(-0.35, 0.35)
        ax.axis("off")
    fig.tight_layout()
    return fig
