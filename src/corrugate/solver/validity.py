"""The validated range of every model a spec's constraints use, as constraints of the solve
(issue 35 item 1; the ranges: :mod:`corrugate.mechanics.validity`, ``data/validity.toml``).

By default (``trust = "certified"``, docs/spec.md) :func:`validity_constraints` adds, for each
enforced end of the range of each model a constraint uses (the homogenised springs for every
stiffness, deflection, load and buckling bound; the local term of its test for a three-point,
four-point or cantilever bound; the off-axis factors off the crease directions; the wheel
test's factor), one constraint ``validity.MODEL.VARIABLE.END (the sentence)`` on a quantity of
this module, bounded over the branch-and-bound boxes like the fabrication limits
(:mod:`.making`): each is monotone in the box's corners. Where several models bound the same
end, the tightest is kept, named by the first model that states it (a test's before the off-axis
factors' before the springs'); an end that no design within the variable bounds (and the
fabrication's t/W limit) can cross is left out. With ``trust = "extrapolate"`` the constraints
are kept aside (:attr:`~.problem.Problem.ranges`) and :func:`outside_ranges` names those the
answer lies outside: it is extrapolated, not certified.

The quantities (over the two layers of a design):

* ``facets_least``, ``facets_most``: the fewest and most facets n + 1 of a layer;
* ``alpha_least``, ``alpha_most`` (deg), ``W_least``, ``W_most`` (mm): the least and greatest
  fold angle and facet width of a layer;
* ``tw_least``, ``tw_most``: the least and greatest t / W of a layer;
* ``hub``: the central axle hole's diameter over the disc's diameter Lx (0 without one);
* ``t_least``, ``t_most`` (mm): the thinnest and thickest sheet of the two layers;
* ``td_h1``: the folded thickness t_d = h1 + h2 over layer 1's depth h1 (h = W cos(alpha/2),
  the zig-zag's), how high the band's walls stand above layer 1.

A load capacity (``Pmax``: "holds X N", and the load a deflection bound holds) uses the capacity
model's ranges too: its facet modes' (``capacity``) and, with a bonded band in a bending test,
its walls' (``band-walls``; docs/load_cases.md 10).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from corrugate.mechanics.validity import End, model_ranges
from corrugate.solver.evaluator import Evaluator, register
from corrugate.solver.quantity import Quantity

if TYPE_CHECKING:
    from corrugate.geometry.layer import Assembly
    from corrugate.geometry.layouts import Layout
    from corrugate.solver.context import AtPoints, OverBoxes
    from corrugate.solver.problem import Candidate, Constraint, DesignVariable

__all__ = [
    "LAYER_KINDS",
    "VALIDITY",
    "layer_limits",
    "models_of",
    "outside_ranges",
    "validity_constraints",
]

FloatArray = NDArray[np.float64]
Pair = tuple[FloatArray, FloatArray]

#: Quantity kind of each (variable, end) of a range: (kind, readable name, unit).
_KINDS: dict[tuple[str, End], tuple[str, str, str]] = {
    ("facets", "min"): ("facets_least", "fewest facets n + 1 of a layer", ""),
    ("facets", "max"): ("facets_most", "most facets n + 1 of a layer", ""),
    ("alpha", "min"): ("alpha_least", "least fold angle alpha of a layer", "deg"),
    ("alpha", "max"): ("alpha_most", "greatest fold angle alpha of a layer", "deg"),
    ("W", "min"): ("W_least", "narrowest facet W of a layer", "mm"),
    ("W", "max"): ("W_most", "widest facet W of a layer", "mm"),
    ("t_over_W", "min"): ("tw_least", "least t/W of a layer", ""),
    ("t_over_W", "max"): ("tw_most", "greatest t/W of a layer", ""),
    ("hub", "min"): ("hub", "axle hole over disc diameter", ""),
    ("hub", "max"): ("hub", "axle hole over disc diameter", ""),
    ("t", "min"): ("t_least", "thinnest sheet t of a layer", "mm"),
    ("t", "max"): ("t_most", "thickest sheet t of a layer", "mm"),
    ("td_over_h1", "min"): ("td_h1", "folded thickness over layer 1's depth t_d/h1", ""),
    ("td_over_h1", "max"): ("td_h1", "folded thickness over layer 1's depth t_d/h1", ""),
}
#: The quantities of this module.
VALIDITY: frozenset[Quantity] = frozenset(Quantity(k) for k, _, _ in _KINDS.values())


#: The kinds that bound every layer on its own (the least of the layers >= a bound: each layer
#: >= it; the most <= a bound: each <= it), with the sense that makes them so, and the layer's
#: variable: what the layer-by-layer search (:mod:`.separable`) filters each layer's list by.
LAYER_KINDS: dict[str, tuple[str, str]] = {
    "facets_least": ("min", "facets"),
    "facets_most": ("max", "facets"),
    "alpha_least": ("min", "alpha"),
    "alpha_most": ("max", "alpha"),
    "W_least": ("min", "W"),
    "W_most": ("max", "W"),
    "tw_least": ("min", "t_over_W"),
    "tw_most": ("max", "t_over_W"),
}


def layer_limits(constraints: Sequence[Constraint]) -> dict[str, tuple[float, float]]:
    """Each layer's own limits (variable -> (lo, hi); ``facets`` is n + 1) of the range
    constraints among ``constraints`` of :data:`LAYER_KINDS` (module docstring), to the solver's
    feasibility tolerance (:data:`~.problem.FEAS_RTOL`)."""
    from corrugate.solver.problem import FEAS_RTOL

    out: dict[str, tuple[float, float]] = {}
    for c in constraints:
        entry = LAYER_KINDS.get(c.quantity.kind)
        if entry is None or entry[0] != c.sense:
            continue
        lo, hi = out.get(entry[1], (-math.inf, math.inf))
        tol = FEAS_RTOL * abs(c.bound)
        if c.sense == "min":
            lo = max(lo, c.bound - tol)
        else:
            hi = min(hi, c.bound + tol)
        out[entry[1]] = (lo, hi)
    return out


def _hub_diameter(layout: Layout, diameter: Any) -> float:
    """The diameter (mm) of the layout's central circular hole (0.0 without one), as the wheel
    fixture reads it (docs/load_cases.md 9: a hole around the centre)."""
    for h in layout.holes:
        if h.shape == "circle" and math.hypot(*h.center) <= h.radius:
            return 2.0 * float(h.radius)
    return 0.0


def _values(kind: str, layers: Sequence[Any], t: tuple[float, float], Lx: Any, hub: float) -> Any:
    """The value of ``kind`` at design points: ``layers`` the two layers' (n, W, alpha) arrays,
    ``t`` their sheets' thickness (mm), ``Lx`` the disc diameter (mm), ``hub`` the hole's."""
    (n1, W1, a1), (n2, W2, a2) = layers
    if kind == "facets_least":
        return np.minimum(n1, n2) + 1.0
    if kind == "facets_most":
        return np.maximum(n1, n2) + 1.0
    if kind == "alpha_least":
        return np.minimum(a1, a2)
    if kind == "alpha_most":
        return np.maximum(a1, a2)
    if kind == "W_least":
        return np.minimum(W1, W2)
    if kind == "W_most":
        return np.maximum(W1, W2)
    if kind == "tw_least":
        return np.minimum(t[0] / W1, t[1] / W2)
    if kind == "tw_most":
        return np.maximum(t[0] / W1, t[1] / W2)
    if kind in ("t_least", "t_most"):
        pick = min if kind == "t_least" else max
        return np.full(np.shape(n1), pick(t), dtype=np.float64)
    if kind == "td_h1":
        return 1.0 + _depth(W2, a2) / _depth(W1, a1)
    assert kind == "hub", kind
    return hub / np.asarray(Lx, dtype=np.float64)


def _depth(W: Any, alpha: Any) -> Any:
    """The zig-zag's depth h = W cos(alpha/2) (mm; alpha in deg)."""
    return W * np.cos(np.radians(alpha) / 2.0)


def _layers(x: Any) -> list[tuple[FloatArray, FloatArray, FloatArray]]:
    return [
        tuple(np.asarray(getattr(x.layer(i), v), np.float64) for v in ("n", "W", "alpha"))  # type: ignore[misc]
        for i in (0, 1)
    ]


def _at(at: AtPoints, q: Quantity) -> FloatArray:
    hub = _hub_diameter(at.problem.layout, None)
    return np.asarray(
        _values(q.kind, _layers(at.x), (at.c1.t, at.c2.t), at.Lx, hub), dtype=np.float64
    )


def _over(over: OverBoxes, q: Quantity) -> Pair:
    """Bounds over the boxes: every quantity grows or falls with each variable (t / W falls
    with W, the hub ratio with Lx), so the corners bound it."""
    hub = _hub_diameter(over.problem.layout, None)
    t = (over.c1.t, over.c2.t)
    Lx_lo, Lx_hi = over.Lx
    lo_x, hi_x = _layers(over.lo), _layers(over.hi)
    if q.kind == "td_h1":  # grows with layer 2's depth, falls with layer 1's
        h1 = (_depth(lo_x[0][1], hi_x[0][2]), _depth(hi_x[0][1], lo_x[0][2]))
        h2 = (_depth(lo_x[1][1], hi_x[1][2]), _depth(hi_x[1][1], lo_x[1][2]))
        lo_td, hi_td = 1.0 + h2[0] / h1[1], 1.0 + h2[1] / h1[0]
        return np.asarray(lo_td, dtype=np.float64), np.asarray(hi_td, dtype=np.float64)
    lo = _values(q.kind, lo_x, t, Lx_hi, hub)
    hi = lo if over.point else _values(q.kind, hi_x, t, Lx_lo, hub)
    if q.kind.startswith("tw_"):  # falls with W
        lo, hi = hi, lo
    return np.asarray(lo, dtype=np.float64), np.asarray(hi, dtype=np.float64)


for _kind, _label, _unit in dict.fromkeys(_KINDS.values()):
    register(Evaluator((_kind,), _at, _over, label=_label, unit=_unit))


def models_of(q: Quantity, joint: str = "none") -> list[str]:
    """The models (names in ``data/validity.toml``) whose range a bound on ``q`` relies on:
    for a load capacity (``Pmax``) the capacity model's facet modes' (``capacity``) and, with
    the layers joined by a band (``joint`` not ``none``) in a bending test, its walls'
    (``band-walls``); its test's, the off-axis factors' off the crease directions (not the
    wheel's, whose factor was measured at 45 deg), and the springs' for every behavioural
    quantity."""
    if q.eta is None or q.kind == "length":
        return []
    known = model_ranges()
    out = []
    if q.kind == "Pmax":
        out.append("capacity")
        if joint != "none" and q.test is not None and _bending(q.test):
            out.append("band-walls")
    if q.test is not None and q.test in known:
        out.append(q.test)
    if q.eta % 90 != 0 and q.test != "wheel":
        out.append("off-axis")
    out.append("springs")
    return out


def _bending(test: str) -> bool:
    """Whether the load case ``test`` bends the panel (its walls' buckling modes apply)."""
    from corrugate.mechanics.behaviours import get_load_case

    form = get_load_case(test).form
    return form is not None and form.kind != "inplane"


def _can_cross(
    variable: str,
    end: End,
    bound: float,
    W: DesignVariable,
    alpha: DesignVariable,
    n: tuple[int, int],
    cands: Sequence[Candidate],
    max_t_over_W: float,
    identical: bool = False,
) -> bool:
    """Whether some design within the variable bounds may lie beyond ``bound`` (``identical``
    layers: t_d / h1 is 2)."""
    if variable == "facets":
        return n[0] + 1 < bound if end == "min" else n[1] + 1 > bound
    if variable == "alpha":
        return alpha.lo < bound if end == "min" else alpha.top > bound
    if variable == "W":
        return W.lo < bound if end == "min" else W.top > bound
    if variable == "t_over_W":
        ts = [c.t for c in cands]
        if end == "min":
            return min(ts) / W.top < bound
        return min(max(ts) / W.lo, max_t_over_W) > bound
    if variable == "t":
        ts = [c.t for c in cands]
        return min(ts) < bound if end == "min" else max(ts) > bound
    if variable == "td_over_h1":
        if identical:
            return bound > 2.0 if end == "min" else bound < 2.0
        h_lo = W.lo * math.cos(math.radians(alpha.top) / 2.0)
        h_hi = W.top * math.cos(math.radians(alpha.lo) / 2.0)
        return 1.0 + h_lo / h_hi < bound if end == "min" else 1.0 + h_hi / h_lo > bound
    return True  # hub: depends on the folded diameter


def validity_constraints(
    constraints: Sequence[Constraint],
    W: DesignVariable,
    alpha: DesignVariable,
    n: tuple[int, int],
    cands: Sequence[Candidate],
    max_t_over_W: float,
    joint: str = "none",
    identical: bool = False,
) -> list[Constraint]:
    """The validated-range constraints of the models ``constraints`` use (module docstring),
    given the variable bounds ``W``, ``alpha``, ``n`` (lo, hi), the candidate sheets, the
    fabrication's largest t / W, how the layers are ``joint``-ed and whether they are
    ``identical``."""
    from corrugate.solver.problem import Constraint

    ranges = model_ranges()
    used: list[str] = []
    for c in constraints:
        for m in models_of(c.quantity, joint):
            if m not in used:
                used.append(m)
    tests = [m for m in used if m not in ("off-axis", "springs")]
    order = tests + [m for m in ("off-axis", "springs") if m in used]
    out: list[Constraint] = []
    seen: set[tuple[str, End]] = set()
    for m in order:
        for variable, end in ranges[m].enforce:
            if (variable, end) in seen:
                continue
            seen.add((variable, end))
            stating = [r for r in order if (variable, end) in ranges[r].enforce]
            values = [ranges[r].ranges[variable][0 if end == "min" else 1] for r in stating]
            bound = max(values) if end == "min" else min(values)
            model = ranges[stating[values.index(bound)]]
            if not _can_cross(variable, end, bound, W, alpha, n, cands, max_t_over_W, identical):
                continue
            kind = _KINDS[(variable, end)][0]
            name = f"validity.{model.name}.{variable}.{end} ({model.sentence(variable, end)})"
            out.append(Constraint(name, Quantity(kind), end, bound))
    return out


def outside_ranges(ranges: Sequence[Constraint], a: Assembly) -> tuple[str, ...]:
    """The names of the validated-range constraints ``ranges`` that the design ``a`` breaks."""
    layers = [
        (np.float64(layer.n), np.float64(layer.W), np.float64(layer.alpha_deg))
        for layer in a.layers
    ]
    t = (a.layers[0].t, a.layers[1].t)
    hub = _hub_diameter(a.layout, None)
    out = []
    for c in ranges:
        value = float(_values(c.quantity.kind, layers, t, a.Lx, hub))
        if not bool(c.satisfied(np.float64(value))):  # type: ignore[arg-type]
            out.append(c.name)
    return tuple(out)
