"""Grid sweeps (corrugate.analysis.sweep) against a second method: a plain loop that builds each
design as a Layer and an Assembly and calls ``analyze`` on it, then reduces by hand (count,
feasible designs, the lightest one, the range of each quantity). The chunked and distributed
paths are checked against one block in tests/system/test_speed_paths.py."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from corrugate import Assembly, Layer, analyze, get_material, make_layout
from corrugate.analysis.sweep import FIELDS, sweep
from corrugate.core.errors import InputError

DURALAR = get_material("dura-lar")
W = np.array([6.0, 8.0, 10.0, 12.0])
N = np.array([5, 8, 11])
ALPHA = np.array([60.0, 84.0, 100.0])


def _by_analyze(
    W: float, n: int, alpha: float, model: str, eta: float, support: str, layout: str = "square"
) -> dict[str, float]:
    layer = Layer(float(W), int(n), float(alpha), DURALAR, 0.125)
    a = Assembly.identical(layer, make_layout(layout))
    r = analyze(a, model, [eta], support=support)  # type: ignore[arg-type]
    s = r.stiffness[0]
    return {
        "Lx": a.Lx,
        "thickness": a.thickness,
        "flat": layer.flat_width,
        "mass": r.mass.total,
        "K": s.K,
        "D": s.D,
        "EI": s.EI,
    }


@pytest.mark.parametrize(
    ("model", "eta", "support", "layout"),
    [
        ("paper", 0.0, "free", "square"),
        ("refined", 90.0, "free", "square"),
        ("refined", 30.0, "free", "square"),
        ("xia", 45.0, "frame", "square"),
        ("refined", 0.0, "free", "circle"),
    ],
)
def test_reductions_equal_a_loop_over_analyze(
    model: str, eta: float, support: str, layout: str
) -> None:
    bounds = {"Lx": (30.0, 80.0), "EI": (2e3, None), "thickness": (None, 15.0)}
    r = sweep(
        W,
        N,
        ALPHA,
        DURALAR,
        0.125,
        model=model,
        eta_deg=eta,
        support=support,  # type: ignore[arg-type]
        layout=make_layout(layout),
        bounds=bounds,
        keep=True,
        chunk=5,  # several blocks, so the reductions are merged
    )
    rows = []
    for (i, w), (j, n), (k, a) in itertools.product(enumerate(W), enumerate(N), enumerate(ALPHA)):
        v = _by_analyze(w, n, a, model, eta, support, layout)
        ok = all(
            (lo is None or v[f] >= lo) and (hi is None or v[f] <= hi)
            for f, (lo, hi) in bounds.items()
        )
        rows.append(((i, j, k), v, ok))
        assert r.values is not None
        for f in FIELDS:
            assert r.values[f][i, j, k] == pytest.approx(v[f], rel=1e-12), (f, w, n, a)
    feasible = [(index, v) for index, v, ok in rows if ok]
    assert 0 < len(feasible) < len(rows)  # the bounds bind
    assert r.count == len(rows) and r.feasible == len(feasible)
    best_index, best = min(feasible, key=lambda x: x[1]["mass"])  # first of equal masses
    assert r.best_index == best_index
    assert r.best is not None
    assert (r.best["W"], r.best["n"], r.best["alpha"]) == (
        W[best_index[0]],
        N[best_index[1]],
        ALPHA[best_index[2]],
    )
    for f in FIELDS:
        assert r.best[f] == pytest.approx(best[f], rel=1e-12)
        assert r.minimum[f] == pytest.approx(min(v[f] for _, v in feasible), rel=1e-12)
        assert r.maximum[f] == pytest.approx(max(v[f] for _, v in feasible), rel=1e-12)


def test_another_objective_and_no_bounds() -> None:
    """Without bounds every design is feasible; the objective may be any field (here the
    thinnest panel, which is the one with the smallest W cos(alpha/2))."""
    r = sweep(W, N, ALPHA, DURALAR, 0.125, objective="thickness", fields=("thickness", "K"))
    assert r.feasible == r.count == W.size * N.size * ALPHA.size
    assert r.values is None  # not kept
    assert set(r.minimum) == {"thickness", "K"}
    heights = {
        (i, k): 2 * w * math.cos(math.radians(a) / 2)
        for (i, w), (k, a) in itertools.product(enumerate(W), enumerate(ALPHA))
    }
    (i, k), t_d = min(heights.items(), key=lambda x: x[1])
    assert r.best_index == (i, 0, k)  # n does not change the thickness: the lowest index wins
    assert r.best is not None and r.best["thickness"] == pytest.approx(t_d, rel=1e-12)
    assert r.minimum["thickness"] == pytest.approx(t_d, rel=1e-12)


def test_ties_go_to_the_lowest_index() -> None:
    """The same W twice: two identical designs, the first one is the answer."""
    r = sweep([8.0, 8.0], [8], [84.0], DURALAR, 0.125)
    assert r.best_index == (0, 0, 0)


@pytest.mark.parametrize(
    ("kwargs", "field"),
    [
        ({"fields": ("weight",)}, "fields"),
        ({"bounds": {"stiffness": (1.0, None)}}, "fields"),
        ({"objective": "price"}, "fields"),
        ({"chunk": 0}, "chunk"),
        ({"layout": make_layout("polygon", [(0, 0), (1, 0), (0, 1)])}, "layout"),
        ({"support": "clamped"}, "support"),
        ({"model": "nonsense"}, "model"),
    ],
)
def test_bad_arguments_name_their_field(kwargs: dict[str, object], field: str) -> None:
    with pytest.raises(InputError) as info:
        sweep(W, N, ALPHA, DURALAR, 0.125, **kwargs)  # type: ignore[arg-type]
    assert info.value.field == field
