"""The registry of behaviours (corrugate.mechanics.behaviours): a toy support condition registered
by a test is seen by the analysis, the solver, the spec (its parser and reference), the report's
polar figure and the FE validation's closed forms, and is gone once unregistered.

The toy ``half`` is a panel whose stiffness is half the rigid frame's (its interval bound half the
frame's interval). Independent sources: the frame's rule written out again from the layers'
springs (docs/theory.md 3.3), an exhaustive search over the design grid with that hand-written
value, and the same spec solved under the frame with a bound twice as high.
"""

from __future__ import annotations

import copy
from collections.abc import Iterator
from dataclasses import replace
from typing import Any

import numpy as np
import pytest

from corrugate import Assembly, Layer, LayerArrays, analyze, evaluate, get_material, make_layout
from corrugate.core.errors import InputError
from corrugate.mechanics.behaviours import (
    STIFFNESS_UNITS,
    Behaviour,
    get_support,
    register,
    support_names,
    unregister,
)
from corrugate.mechanics.offaxis import frame_rule
from corrugate.solver import Problem, solve
from corrugate.solver.points import DesignPoints, LayerPoints
from corrugate.solver.quantities import Tables, box_bounds, point_values
from corrugate.solver.quantity import Quantity
from corrugate.spec.reference import json_schema, reference_markdown
from corrugate.spec.schema import SpecError, parse_spec

DL = get_material("dura-lar")


def _half_model(kind: str, springs: tuple[Any, Any], eta_deg: float, coupon: Any) -> Any:
    return frame_rule(kind, springs, eta_deg) * 0.5


def _half_bounds(kind: str, springs: tuple[Any, Any], eta_deg: float, coupon: Any) -> Any:
    # the frame's interval (frame_rule on interval springs) halved: an Interval times 0.5
    return get_support("frame").bounds(kind, springs, eta_deg, coupon) * 0.5


HALF = Behaviour(
    name="half",
    model=_half_model,
    bounds=_half_bounds,
    fixture="frame",
    label=" at half the frame",
    suffix="half",
    units=STIFFNESS_UNITS,
    text="a toy: half the rigid frame",
    curve="half the frame (toy)",
    off_axis=lambda angles, layout: f"toy support at eta = {angles} deg on a {layout}",
)


@pytest.fixture
def half() -> Iterator[Behaviour]:
    """``half`` registered for one test, unregistered after it (no other test sees it)."""
    register(HALF)
    try:
        yield HALF
    finally:
        unregister("half")
    assert "half" not in support_names()


def _rule_by_hand(springs: tuple[Any, Any], eta: float) -> tuple[float, float]:
    """K (N/mm) and D (N mm) of the frame's rule, written out from the layers' springs."""
    s1, s2 = springs
    c2, s2_ = np.cos(np.radians(eta)) ** 2, np.sin(np.radians(eta)) ** 2
    K = (s1.K_S + s2.K_C) * c2 + (s2.K_S + s1.K_C) * s2_
    D = (s1.D_S + s2.D_C) * c2 + (s2.D_S + s1.D_C) * s2_
    return float(K), float(D)


def test_analysis_reports_the_registered_support(half: Behaviour) -> None:
    """analyze(support='half') is half the rule written out by hand at every eta (and EI = D x
    span); its JSON names the support and its off-axis warning is the entry's."""
    a = Assembly.identical(Layer(W=8, n=8, alpha_deg=84, material=DL))
    etas = [0.0, 30.0, 45.0, 90.0]
    r = analyze(a, "refined", etas, support="half")
    for s, eta in zip(r.stiffness, etas, strict=True):
        K, D = _rule_by_hand(r.springs, eta)
        assert pytest.approx(0.5 * K, rel=1e-12) == s.K
        assert pytest.approx(0.5 * D, rel=1e-12) == s.D
        assert pytest.approx(s.D * s.span, rel=1e-12) == s.EI
    frame = analyze(a, "refined", etas, support="frame").stiffness
    assert [s.K for s in r.stiffness] == [0.5 * f.K for f in frame]
    assert r.to_dict()["support"] == "half"
    [w] = [w for w in r.warnings if w.code == "off-axis"]
    assert w.message == "toy support at eta = 30, 45 deg on a square"


BASE: dict[str, Any] = {
    "material": {"name": "dura-lar", "thickness": "0.125 mm"},
    "variables": {
        "W": {"min": 6, "max": 14, "step": 1},
        "n": {"min": 2, "max": 20},
        "alpha": {"min": 50, "max": 110, "step": 2},
    },
    "constraints": {"side": {"min": 40, "max": 60}},
}
K_MIN = 300.0  # N/mm at 45 deg under 'half'; the frame needs 600 for the same panels


def _spec(support: str, k_min: float) -> dict[str, Any]:
    d = copy.deepcopy(BASE)
    d["tolerances"] = "none"  # nominal: the test checks the support, not the tolerances
    d["constraints"]["inplane_stiffness"] = [
        {"min": f"{k_min} N/mm", "eta": 45, "support": support}
    ]
    return d


def test_solver_certifies_a_bound_under_the_registered_support(half: Behaviour) -> None:
    """The certified optimum with K(45) >= 300 N/mm under 'half' is the lightest point of an
    exhaustive search of the grid with half the hand-written rule, the bound binds there, and it
    is the optimum of the same spec under the frame with K(45) >= 600 N/mm."""
    sol = solve(Problem.from_spec(parse_spec(_spec("half", K_MIN))))
    assert sol.status == "optimal" and sol.certified and sol.assembly is not None
    [rep] = [c for c in sol.constraints if c.name.startswith("constraints.inplane")]
    assert rep.quantity.key == "Khalf@45" and rep.unit == "N/mm"
    assert rep.binding
    d = sol.to_dict()
    spec_rows = [
        c for c in d["constraints"] if not c["name"].startswith(("fabrication.", "validity."))
    ]
    assert [c["quantity"] for c in spec_rows] == ["Lx", "Lx", "Khalf@45"]
    # a stiffness bound brings the springs' validated range (docs/validation/ranges.md)
    assert [c["quantity"] for c in d["constraints"] if c["name"].startswith("validity.")] == [
        "facets_least"
    ]

    Ws, ns, As = np.arange(6.0, 14.5, 1.0), np.arange(2, 21), np.arange(50.0, 110.5, 2.0)
    n, W, A = (g.ravel() for g in np.meshgrid(ns, Ws, As, indexing="ij"))
    layer = LayerArrays(DL.E, DL.nu, 0.125, W, n, A, DL.density)
    ev = evaluate(layer, layer, make_layout("square"), "refined", 45.0)
    s = ev.springs[0]  # identical layers on a square: at 45 deg the rule is (K_S + K_C) / 2
    k_half = 0.5 * ((s.K_S + s.K_C) * 0.5 + (s.K_S + s.K_C) * 0.5)
    rtol = 1e-9
    ok = (ev.Lx >= 40 * (1 - rtol)) & (ev.Lx <= 60 * (1 + rtol)) & (k_half >= K_MIN * (1 - rtol))
    best = float(np.min(np.where(ok, ev.mass, np.inf)))
    assert sol.mass == pytest.approx(best, rel=1e-12)
    unbounded = float(np.min(np.where(ok | (k_half < K_MIN), ev.mass, np.inf)))
    assert unbounded < best  # the bound is what decides the design

    got = analyze(sol.assembly, "refined", [45.0], support="half").stiffness[0].K
    assert got >= K_MIN * (1 - rtol)
    frame = solve(Problem.from_spec(parse_spec(_spec("frame", 2 * K_MIN))))
    assert frame.mass == sol.mass
    assert frame.assembly == sol.assembly


def test_solver_bounds_hold_under_the_registered_support(half: Behaviour) -> None:
    """Box bounds of K, D and EI at 30 deg under 'half' contain the exact values at points
    sampled in each box, and are half the frame's bounds."""
    d = copy.deepcopy(BASE)
    d["constraints"]["flexural_rigidity"] = [{"min": "1 N*mm^2", "eta": 30, "support": "half"}]
    d["constraints"]["inplane_stiffness"] = [{"min": "1 N/mm", "eta": 30, "support": "half"}]
    d["constraints"]["bending_stiffness"] = [{"min": "1 N*mm", "eta": 30, "support": "frame"}]
    prob = Problem.from_spec(parse_spec(d))
    tables = Tables(prob)
    c = prob.candidates[0]
    keys = {q.quantity for q in prob.constraints if q.quantity.directional}
    keys |= {Quantity("D", 30.0, "half")}
    rng = np.random.default_rng(3)
    for _ in range(20):
        nl = int(rng.integers(2, 18))
        Wl, al = rng.uniform(6, 12), rng.uniform(50, 100)
        blo = DesignPoints.of(LayerPoints(*(np.array([float(v)]) for v in (nl, Wl, al))))
        bhi = DesignPoints.of(
            LayerPoints(*(np.array([float(v)]) for v in (nl + 2, Wl + 1.0, al + 5.0)))
        )
        bounds = box_bounds(prob, c, c, blo, bhi, tables, keys)
        N = 50
        x = DesignPoints.of(
            LayerPoints(
                rng.integers(nl, nl + 3, N).astype(float),
                rng.uniform(Wl, Wl + 1.0, N),
                rng.uniform(al, al + 5.0, N),
            )
        )
        vals = point_values(prob, c, c, x, tables)
        for q in keys:
            assert np.all(vals[q] >= bounds[q][0][0] * (1 - 1e-12)), q.key
            assert np.all(vals[q] <= bounds[q][1][0] * (1 + 1e-12)), q.key
        half_D, frame_D = bounds[Quantity("D", 30.0, "half")], bounds[Quantity("D", 30.0, "frame")]
        assert half_D[0][0] == pytest.approx(0.5 * frame_D[0][0], rel=1e-12)
        assert half_D[1][0] == pytest.approx(0.5 * frame_D[1][0], rel=1e-12)


def test_spec_and_its_reference_list_the_registered_support(half: Behaviour) -> None:
    """The parser takes support = 'half' and names it among the allowed values; the reference
    (Markdown) and the JSON Schema list it for every support key."""
    spec = parse_spec(_spec("half", K_MIN) | {"support": "half"})
    assert spec.support == "half"
    with pytest.raises(SpecError) as info:
        parse_spec(_spec("glued", K_MIN))
    assert info.value.field == "constraints.inplane_stiffness[0].support"
    assert info.value.allowed == "'free', 'frame' or 'half'"

    md = reference_markdown()
    [row] = [line for line in md.splitlines() if line.startswith("| `support` |")]
    assert "'half' (a toy: half the rigid frame)" in row
    rows = [line for line in md.splitlines() if "].support` |" in line]
    assert len(rows) == 5 and all("'free', 'frame' or 'half'" in r for r in rows)
    schema = json_schema()
    assert schema["properties"]["support"]["enum"] == ["free", "frame", "half"]
    for name in ("RigiditySpec", "BendingSpec", "InPlaneSpec", "ObjectiveSpec"):
        sub = schema["$defs"][name]["properties"]["support"]["anyOf"][0]
        assert sub["enum"] == ["free", "frame", "half"], name


def test_unregistering_restores_the_reference_and_the_parser() -> None:
    """Registering and unregistering leaves the reference and the schema as they were, and the
    parser refuses 'half' again with the built-in choice."""
    md, schema = reference_markdown(), json_schema()
    register(HALF)
    try:
        assert reference_markdown() != md
    finally:
        unregister("half")
    assert reference_markdown() == md and json_schema() == schema
    with pytest.raises(SpecError) as info:
        parse_spec(_spec("half", K_MIN))
    assert info.value.allowed == "'free' or 'frame'"


def test_quantity_keys_read_back(half: Behaviour) -> None:
    """Each quantity's key reads back to the same quantity; the keys of the built-ins are the
    text the answers show (docs/spec.md: EI under free sides has no suffix)."""
    qs = [
        Quantity.stiffness("flexural_rigidity", 0.0),
        Quantity.stiffness("inplane_stiffness", 45.0, "frame"),
        Quantity.stiffness("D", 30.0, "half"),
        Quantity("Pb", 90.0),
        Quantity("mass"),
    ]
    assert [q.key for q in qs] == ["EI@0", "Kframe@45", "Dhalf@30", "Pb@90", "mass"]
    assert [Quantity.parse(q.key) for q in qs] == qs
    assert qs[1].description == "in-plane stiffness K(45 deg) in a frame"
    assert qs[2].description == "bending stiffness D(30 deg) at half the frame"
    assert [q.unit for q in qs] == ["N*mm^2", "N/mm", "N*mm", "N", "g"]
    with pytest.raises(InputError):
        register(replace(HALF, name="other"))  # the suffix 'half' is taken


def test_report_and_validation_see_the_registered_support(half: Behaviour) -> None:
    """The polar figure draws one curve per support (the toy's labelled by its entry), and the
    FE validation's closed forms give K under 'half' beside its fixture's (the frame's) key."""
    from corrugate.fea.validation import closed_forms, fixture_supports
    from corrugate.report.figures import polar_figure

    a = Assembly.identical(Layer(W=8, n=8, alpha_deg=84, material=DL))
    fig = polar_figure(analyze(a, "refined", [0.0, 90.0]))
    labels = fig.axes[0].get_legend_handles_labels()[1]
    assert labels == [
        "free sides (lower bound)",
        "rigid frame (cos^2 rule)",
        "half the frame (toy)",
    ]
    assert [b.name for b in fixture_supports()] == ["frame", "half"]
    forms = closed_forms(a, [0.0, 45.0])["refined"]
    assert forms["Khalf_N_per_mm@45"] == 0.5 * forms["Kframe_N_per_mm@45"]


def test_a_test_entry_without_a_form_is_refused() -> None:
    """A load case is a TestForm (what the test measures from the support's D or K): an entry
    of role 'test' without one cannot be registered."""
    toy = Behaviour(
        name="quarter",
        model=lambda kind, springs, eta, coupon: frame_rule(kind, springs, eta) * 0.25,
        bounds=lambda kind, springs, eta, coupon: frame_rule(kind, springs, eta) * 0.25,
        fixture="frame",
        label=", quarter test",
        suffix="q",
        units={"D": "N*mm"},
        text="a toy load case",
        curve="",
        off_axis=lambda angles, layout: "",
        role="test",
    )
    with pytest.raises(InputError):
        register(toy)


@pytest.mark.parametrize("layout", ["square", "rectangle"])
def test_a_support_flagged_crease_rule_is_the_rule_along_the_creases(layout: str) -> None:
    """``crease_rule`` (what the layer-by-layer search of independent layers relies on) holds
    for each support that says so: its K and D at eta 0 and 90 deg are the frame's rule written
    out by hand from the layers' springs (docs/theory.md 3.3), on a square and on a rectangle
    (which free sides read as a coupon); a toy support without the flag is not searched that
    way."""
    from corrugate.solver.separable import _stiffness

    flagged = [b for b in (get_support(n) for n in support_names()) if b.crease_rule]
    assert {b.name for b in flagged} == {"free", "frame"}
    one = Layer(W=8, n=8, alpha_deg=84, material=DL)
    two = Layer(W=6, n=11, alpha_deg=70, material=DL)
    a = Assembly.identical(one) if layout == "square" else Assembly(one, two, make_layout(layout))
    for b in flagged:
        r = analyze(a, "refined", [0.0, 90.0], support=b.name)
        for s in r.stiffness:
            K, D = _rule_by_hand(r.springs, s.eta_deg)
            assert pytest.approx(K, rel=1e-12) == s.K and pytest.approx(D, rel=1e-12) == s.D
        assert _stiffness(Quantity("K", 0.0, b.name))
    register(HALF)  # half the rule: not the rule, and not flagged
    try:
        assert not HALF.crease_rule and not _stiffness(Quantity("K", 0.0, "half"))
    finally:
        unregister("half")
