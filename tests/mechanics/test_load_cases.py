"""Load cases (corrugate.mechanics.load_cases, docs/load_cases.md): the formula against a hand
derivation and against the FE of the parameter sweep, the solver's bounds, the spec's errors,
and certified answers against exhaustive search."""

from __future__ import annotations

import csv
import math
import re
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from corrugate import Assembly, Layer, analyze, get_material
from corrugate.mechanics.load_cases import LOCAL
from corrugate.solver import Problem, solve
from corrugate.solver.points import DesignPoints, LayerPoints
from corrugate.solver.quantities import Tables, box_bounds, point_values
from corrugate.solver.quantity import MASS, Quantity
from corrugate.spec.schema import SpecError, parse_spec
from fe_rows import identical_square
from spec_units import with_units

ROOT = Path(__file__).resolve().parents[2]
DL = get_material("dura-lar")


def _hand_three_point(W: float, n: int, alpha: float, t: float = 0.125) -> tuple[float, float]:
    """(P / delta in N/mm, L in mm) of a square of identical Dura-Lar layers in three-point
    bending over its own side at eta = 0, written out from docs/load_cases.md: delta / P = L^3 /
    (48 EI) + (L / 4 + c h sqrt(0.01 W / t)) / S with EI = D L from analyze (the pure-bending
    model, checked elsewhere), S = (5/6) G t W c_a^2 (n + 1) (the parabolic shear flow of each
    facet), h = W c_a, c the three-point coefficient."""
    a = Assembly.identical(Layer(W=W, n=n, alpha_deg=alpha, material=DL, t=t))
    r = analyze(a, "refined", [0.0]).stiffness[0]
    c = math.cos(math.radians(alpha / 2))
    G = DL.E / (2 * (1 + DL.nu))
    S = 5 / 6 * G * t * W * c * c * (n + 1)
    L = r.span
    local = LOCAL * W * c * math.sqrt(0.01 * W / t)
    return 1.0 / (L**3 / (48 * r.D * L) + (L / 4 + local) / S), L


def _problem(
    extra: dict[str, Any] | None = None, size: str = "side", **constraints: Any
) -> Problem:
    d: dict[str, Any] = {
        "name": "lc",
        "tolerances": "none",  # nominal: the test checks the model, not the tolerances (docs/tolerances.md)
        "material": {"name": "dura-lar", "thickness": 0.125},
        "layout": {"shape": "square"},
        "variables": {
            "W": {"min": 6, "max": 14, "step": 1},
            "n": {"min": 7, "max": 13},
            "alpha": {"min": 40, "max": 115, "step": 5},
        },
        "constraints": {size: {"min": 40, "max": 80}, **constraints},
    }
    if extra:
        d.update(extra)
    return Problem.from_spec(parse_spec(with_units(d)))


def _grid() -> tuple[np.ndarray, DesignPoints]:
    """The whole grid of :func:`_problem` (n 7-13, W 6-14 step 1, alpha 40-115 step 5) as rows
    (n, W, alpha) and as the point arrays of identical layers."""
    grid = np.array(
        [(n, W, a) for n in range(7, 14) for W in range(6, 15) for a in range(40, 116, 5)],
        dtype=float,
    )
    return grid, DesignPoints.of(LayerPoints(grid[:, 0], grid[:, 1], grid[:, 2]))


def _point(n: float, W: float, a: float) -> DesignPoints:
    return DesignPoints.of(LayerPoints(np.array([n]), np.array([W]), np.array([a])))


def test_three_point_deflection_is_the_hand_formula() -> None:
    """The solver's P / delta of a deflection bound (default span: the panel's side) is the
    formula of docs/load_cases.md written out by hand, and the deflection reported is P over it."""
    p = _problem(deflection=[{"test": "three-point", "load": "10 N", "max": "1 mm"}])
    [c] = [c for c in p.constraints if c.load is not None]
    assert c.quantity.key == "k3pt@0" and c.bound == pytest.approx(10.0)
    cand = p.candidates[0]
    v = point_values(p, cand, cand, _point(8, 8, 84), Tables(p))[c.quantity][0]
    hand, _ = _hand_three_point(8, 8, 84)
    assert v == pytest.approx(hand, rel=1e-12)
    assert c.deflection(v) == pytest.approx(10.0 / hand)


def test_a_span_shorter_than_the_panel_is_stiffer_and_must_fit() -> None:
    """Over a shorter span the same panel deflects less (both terms fall with Ls), and the
    panel's length along eta must reach the supports: a constraint of its own."""
    p = _problem(deflection=[{"test": "three-point", "load": 5, "max": 1, "span": "40 mm"}])
    names = [c.name for c in p.constraints]
    assert "constraints.deflection[0].span" in names
    [c] = [c for c in p.constraints if c.load is not None]
    assert c.quantity == Quantity("k", 0.0, "free", "three-point", 40.0)
    assert Quantity.parse(c.quantity.key) == c.quantity
    cand = p.candidates[0]
    vals = point_values(p, cand, cand, _point(8, 8, 84), Tables(p))
    full, L = _hand_three_point(8, 8, 84)
    assert L > 40 and vals[c.quantity][0] > full
    assert vals[Quantity("length", 0.0)][0] == pytest.approx(L)


def test_the_tests_order_as_their_formulas_say() -> None:
    """For one panel over its own length: a cantilever (Ls^3 / 3) is the softest, three-point
    (Ls^3 / 48) next, four-point at its load points (Ls^3 / 96) the stiffest; without shear the
    ratios would be exactly 16 and 2, with it they are smaller (shear adds relatively more to
    the stiffer tests)."""
    kinds = {t: Quantity("k", 0.0, "free", t) for t in ("cantilever", "three-point", "four-point")}
    p = _problem(deflection=[{"test": t, "load": 1, "max": 1} for t in kinds])
    cand = p.candidates[0]
    v = point_values(p, cand, cand, _point(8, 8, 84), Tables(p))
    k = {t: v[q][0] for t, q in kinds.items()}
    assert k["cantilever"] < k["three-point"] < k["four-point"]
    assert 0.8 * 16 < k["three-point"] / k["cantilever"] < 16
    assert 0.8 * 2 < k["four-point"] / k["three-point"] < 2


def _sweep_fe() -> list[tuple[float, int, float, float, float]]:
    """(W, n, alpha, FE 3-point D, FE 4-point D) at eta = 0 of docs/validation/sweep_paper.csv
    (CalculiX, 8 or 16 elements per facet, converged by the sweep's refinement study)."""
    rows: dict[str, dict[str, float]] = {}
    with (ROOT / "docs" / "validation" / "sweep_paper.csv").open() as f:
        for r in csv.DictReader(f):
            if r["FE"] and r["converged"] == "True":
                rows.setdefault(r["case"], {})[r["quantity"]] = float(r["FE"])
    out = []
    for case, q in rows.items():
        m = re.match(r"W=(\S+) n=(\d+) alpha=(\S+)", case)
        assert m is not None
        if "D_Nmm@0" in q and "D4_Nmm@0" in q:
            out.append((float(m[1]), int(m[2]), float(m[3]), q["D_Nmm@0"], q["D4_Nmm@0"]))
    return out


def test_three_point_model_is_at_or_below_the_fe_of_the_sweep() -> None:
    """Second method: the FE three-point D (apparent, P L^2 / (48 delta)) of the ten sweep designs
    (W 8-14, n 7-13, alpha 40-115 deg). The model's apparent D is at or below it (the
    certificate holds) and at least 0.84 of it (docs/load_cases.md section 2: 0.843-0.990 since
    issue 35's refit; the target 0.85 along the creases is missed by the stubbiest design,
    alpha 40, L / h 4.4); without the shear term (the pure D) it would be up to 30 % above."""
    rows = _sweep_fe()
    assert len(rows) == 10
    worst_pure = 0.0
    for W, n, alpha, fe3, _fe4 in rows:
        k, L = _hand_three_point(W, n, alpha)
        model = k * L * L / 48.0
        assert 0.84 * fe3 <= model <= fe3, (W, n, alpha, model, fe3)
        pure = analyze(Assembly.identical(Layer(W=W, n=n, alpha_deg=alpha, material=DL)))
        worst_pure = max(worst_pure, pure.stiffness[0].D / fe3)
    assert worst_pure > 1.25


def _richardson(series: dict[int, float]) -> float:
    """The converged value of a mesh series {elements per facet: value} by Richardson
    extrapolation from its three finest meshes at their observed order."""
    v1, v2, v3 = (series[k] for k in sorted(series)[-3:])
    d1, d2 = v1 - v2, v2 - v3
    p = math.log2(d1 / d2)
    return v3 - d2 / (2**p - 1)


def test_off_axis_k_is_at_or_below_the_fe_coupons() -> None:
    """Second method: CalculiX coupons of docs/validation/off_axis_fe.csv (compression, the
    case study's square, 2 / 4 / 8 elements per facet and 16 where run, converging from above).
    With the finite-panel factor the free-panel K is at or below the Richardson extrapolation of
    each series off the creases, and above half of it (docs/load_cases.md section 4)."""
    series: dict[float, dict[int, float]] = {}
    with (ROOT / "docs" / "validation" / "off_axis_fe.csv").open() as f:
        for r in csv.DictReader(f):
            if r["test"] == "compression" and r["design"].startswith("case study"):
                series.setdefault(float(r["eta_deg"]), {})[int(r["along"])] = float(r["value"])
    a = Assembly.identical(Layer(W=8, n=8, alpha_deg=84, material=DL))
    checked = 0
    for eta, s in series.items():
        if eta % 90 == 0 or len(s) < 3:
            continue
        fe = _richardson(s)
        K = analyze(a, "refined", [eta]).stiffness[0].K
        assert 0.5 * fe <= K <= fe, (eta, K, fe, s)
        checked += 1
    assert checked >= 3


def _fail(**constraints: Any) -> SpecError:
    with pytest.raises(SpecError) as info:
        _problem(**constraints)
    return info.value


@pytest.mark.parametrize(
    ("entry", "field"),
    [
        ({"test": "five-point", "load": 1, "max": 1}, "constraints.deflection[0].test"),
        ({"test": "three-point", "load": 1, "max": 1, "span": 0}, "constraints.deflection[0].span"),
        ({"test": "three-point", "load": 0, "max": 1}, "constraints.deflection[0].load"),
        ({"test": "three-point", "max": 1}, "constraints.deflection[0].load"),
        ({"test": "three-point", "load": 1, "max": -1}, "constraints.deflection[0].max"),
        ({"test": "platens", "load": 1, "max": 1, "span": 30}, "constraints.deflection[0].span"),
        ({"test": "cantilever", "load": "1 mm", "max": 1}, "constraints.deflection[0].load"),
    ],
)
def test_bad_load_cases_name_their_field(entry: dict[str, Any], field: str) -> None:
    assert _fail(deflection=[entry]).field == field


def test_a_bending_test_on_k_and_a_circle_are_refused() -> None:
    err = _fail(inplane_stiffness=[{"min": 1, "eta": 0, "test": "three-point"}])
    assert err.field == "constraints.inplane_stiffness[0].test" and "'platens'" in err.allowed
    err = _fail(flexural_rigidity=[{"min": 1, "eta": 0, "test": "platens"}])
    assert err.field == "constraints.flexural_rigidity[0].test"
    with pytest.raises(SpecError) as info:
        _problem(
            {"layout": {"shape": "circle"}},
            "diameter",
            deflection=[{"test": "three-point", "load": 1, "max": 1}],
        )
    assert info.value.field == "constraints.deflection[0].test"


@settings(max_examples=12, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    test=st.sampled_from(["three-point", "four-point", "cantilever", "platens"]),
    eta=st.sampled_from([0.0, 15.0, 45.0, 90.0]),
    stiff=st.floats(0.05, 1.0),
    k45=st.booleans(),
    joint=st.sampled_from(["none", "band-edges"]),
)
def test_certified_load_case_answers_match_exhaustive_search(
    test: str, eta: float, stiff: float, k45: bool, joint: str
) -> None:
    """Random specs with a deflection bound (any test, on or off the creases), optionally an
    off-axis K bound, the layers joined or not by the band: the certified answer meets every
    constraint under the model evaluated
    pointwise, and no point of the whole grid (W 6-14 step 1, n 7-13, alpha 40-115 step 5) is
    feasible and lighter (the exhaustive search reads the same point_values)."""
    p0 = _problem()
    cand = p0.candidates[0]
    # a bound that some grid points meet: a fraction of the grid's best P / delta
    grid, x = _grid()
    probe = _problem({"joint": joint}, deflection=[{"test": test, "load": 1, "max": 1, "eta": eta}])
    qd = next(c.quantity for c in probe.constraints if c.load is not None)
    k_all = point_values(probe, cand, cand, x, Tables(probe))[qd]
    load = 1.0
    most = load / (stiff * float(np.max(k_all)))
    cons: dict[str, Any] = {"deflection": [{"test": test, "load": load, "max": most, "eta": eta}]}
    if k45:
        cons["inplane_stiffness"] = [{"min": 0.2, "eta": 45}]
    p = _problem({"joint": joint}, **cons)
    sol = solve(p, explain=False)
    vals = point_values(p, cand, cand, x, Tables(p))
    ok = np.ones(len(grid), dtype=bool)
    for c in p.constraints:
        ok &= c.satisfied(vals[c.quantity])
    if sol.status != "optimal":
        assert not ok.any()
        return
    assert sol.certified
    best = float(np.min(vals[MASS][ok]))
    assert sol.mass == pytest.approx(best, rel=1e-9)
    layer = sol.assembly.layer1
    at = _point(layer.n, layer.W, layer.alpha_deg)
    here = point_values(p, cand, cand, at, Tables(p))
    for c in p.constraints:
        assert c.satisfied(here[c.quantity])[0], c.name


def test_box_bounds_contain_the_load_case_values() -> None:
    """Interval bounds of every load-case quantity over a box contain its values at points
    inside the box (the certificate rests on it)."""
    p = _problem(
        deflection=[
            {"test": t, "load": 1, "max": 1, "eta": e}
            for t in ("three-point", "cantilever", "four-point")
            for e in (0, 30, 90)
        ]
    )
    cand = p.candidates[0]
    qs = {c.quantity for c in p.constraints if c.load is not None}
    lo, hi = _point(8, 7, 60), _point(10, 9, 80)
    b = box_bounds(p, cand, cand, lo, hi, Tables(p), qs)
    rng = np.random.default_rng(0)
    for _ in range(20):
        n = float(rng.integers(8, 11))
        W, a = float(rng.uniform(7, 9)), float(rng.uniform(60, 80))
        v = point_values(p, cand, cand, _point(n, W, a), Tables(p))
        for q in qs:
            assert b[q][0][0] <= v[q][0] * (1 + 1e-12) and v[q][0] <= b[q][1][0] * (1 + 1e-12), q


def test_the_chassis_example_certifies_its_deflection() -> None:
    """examples/chassis_plate.toml: at most 1 mm under 10 N at mid-span over 120 mm; the answer
    is certified, its deflection (reported) at most 1 mm and equal to 10 N over the formula."""
    from corrugate.spec.schema import load_spec

    spec = load_spec(ROOT / "examples" / "chassis_plate.toml")
    p = Problem.from_spec(spec)
    sol = solve(p, explain=False)
    assert sol.status == "optimal" and sol.certified
    [c] = [c for c in p.constraints if c.load is not None]
    l1, l2 = sol.assembly.layer1, sol.assembly.layer2
    x = DesignPoints.of(
        *(
            LayerPoints(np.array([float(la.n)]), np.array([la.W]), np.array([la.alpha_deg]))
            for la in (l1, l2)
        )
    )
    cand1 = next(cd for cd in p.candidates if cd.t == l1.t)
    vals = point_values(p, cand1, cand1, x, Tables(p))
    k = vals[c.quantity][0]
    assert c.deflection(k) <= 1.0 + 1e-9
    # and it holds its 10 N at the safety factor (docs/load_cases.md 10.6)
    [held] = [h for h in p.constraints if h.quantity.kind == "Pmax"]
    assert held.bound == 10.0 and vals[held.quantity][0] >= 10.0 * (1 - 1e-9)


def test_strength_capacity_is_the_peak_stress_of_the_section_model() -> None:
    """Second method: corrugate.mechanics.strength.peak_stress_bending computes the peak stress
    from the zig-zag section's own rigidity (not the springs) with the moment shared by
    stiffness; the solver's yield mode of a three-point test (refined moduli, whose spanwise
    D_S x L is that section rigidity) is yield / peak stress per newton at M = P L / 4, and the
    load capacity Pmax is at most that over the safety factor (the least of the modes,
    docs/load_cases.md 10)."""
    from corrugate.mechanics.strength import LayerSection, peak_stress_bending
    from corrugate.solver.context import AtPoints
    from corrugate.solver.stiffness import capacity_modes_at

    p = _problem(
        {"safety_factor": 2.5},
        strength=[{"test": "three-point", "load": "5 N", "eta": "0 deg"}],
    )
    [c] = [c for c in p.constraints if c.name == "constraints.strength[0].load"]
    assert c.quantity.key == "Pmax3pt@0" and c.bound == 5.0 and p.safety_factor == 2.5
    cand = p.candidates[0]
    cap = point_values(p, cand, cand, _point(8, 8, 84), Tables(p))[c.quantity][0]
    at = AtPoints(p, cand, cand, _point(8, 8, 84), Tables(p))
    yield_load = capacity_modes_at(at, c.quantity)["yield"][0]
    layer = Layer(W=8, n=8, alpha_deg=84, material=DL, t=0.125)
    L = Assembly.identical(layer).Ly
    sec = LayerSection.from_layer(layer)
    peak = peak_stress_bending(sec, sec, 1.0 * L / 4).sigma  # per newton
    assert DL.yield_strength is not None
    assert yield_load == pytest.approx(DL.yield_strength / peak, rel=2e-3)
    assert cap <= yield_load / 2.5 * (1 + 1e-12)


def test_strength_bounds_refuse_what_is_not_modelled() -> None:
    assert (
        _fail(strength=[{"test": "three-point", "load": 1, "eta": 45}]).field
        == "constraints.strength[0].eta"
    )
    assert (
        _fail(strength=[{"test": "platens", "load": 1, "span": 30}]).field
        == "constraints.strength[0].span"
    )
    inline = {"material": {"E": 3000, "nu": 0.3, "density": 1.2, "thickness": 0.1}}
    with pytest.raises(SpecError) as info:
        _problem(inline, strength=[{"test": "cantilever", "load": 1}])
    assert info.value.field == "material.yield_strength"
    p = _problem(
        {"material": {**inline["material"], "yield_strength": "40 MPa"}},
        strength=[{"test": "cantilever", "load": 1}],
    )
    assert p.candidates[0].material.yield_strength == 40.0
    with pytest.raises(SpecError) as info:
        _problem({"safety_factor": 0.5})
    assert info.value.field == "safety_factor"


@settings(max_examples=8, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    test=st.sampled_from(["three-point", "cantilever", "platens"]),
    eta=st.sampled_from([0.0, 90.0]),
    frac=st.floats(0.05, 0.9),
)
def test_certified_strength_answers_match_exhaustive_search(
    test: str, eta: float, frac: float
) -> None:
    """A strength bound (a fraction of the grid's largest capacity) with an off-axis K bound:
    the certified answer is the lightest grid point that meets both (exhaustive search over the
    same point values) and meets them pointwise."""
    grid, x = _grid()
    probe = _problem(strength=[{"test": test, "load": 1, "eta": eta}])
    cand = probe.candidates[0]
    q = next(c.quantity for c in probe.constraints if c.quantity.kind == "Pmax")
    load = frac * float(np.max(point_values(probe, cand, cand, x, Tables(probe))[q]))
    p = _problem(
        strength=[{"test": test, "load": load, "eta": eta}],
        inplane_stiffness=[{"min": 0.2, "eta": 30}],
    )
    sol = solve(p, explain=False)
    vals = point_values(p, cand, cand, x, Tables(p))
    ok = np.ones(len(grid), dtype=bool)
    for c in p.constraints:
        ok &= c.satisfied(vals[c.quantity])
    if sol.status != "optimal":
        assert not ok.any()
        return
    assert sol.certified and sol.mass == pytest.approx(float(np.min(vals[MASS][ok])), rel=1e-9)


def _band_fe(kind: str) -> dict[tuple[float, int, float], dict[str, float]]:
    """FE with the connector band (CalculiX, 8 elements per facet, one mesh) of the parameter
    sweep: {(W, n, alpha): {'edges': value, 'flanges': value}} for ``kind`` K_N_per_mm@0 or
    D_Nmm@0 (docs/validation/connectors/ and flanges/)."""
    out: dict[tuple[float, int, float], dict[str, float]] = {}
    for bond, folder in (("edges", "connectors"), ("flanges", "flanges")):
        with (ROOT / "docs" / "validation" / folder / "sweep_paper.csv").open() as f:
            for r in csv.DictReader(f):
                if r["quantity"] == kind and r["FE"]:
                    m = re.match(r"W=(\S+) n=(\d+) alpha=(\S+)", r["case"])
                    assert m is not None
                    key = (float(m[1]), int(m[2]), float(m[3]))
                    out.setdefault(key, {})[bond] = float(r["FE"])
    return out


def test_a_bonded_band_adds_its_walls_and_stays_below_the_band_fe() -> None:
    """Second method: the FE of the sweep's ten designs with the band bonded along its edges or
    on its glue flanges (3-point bending and platens at eta = 0). With joint = 'band-edges' the
    three-point model (layers plus the two walls as Timoshenko beams) is 0.8-1.0 of the
    edge-bonded FE and 0.65-1.0 of the flange FE, the platen K 0.95-1.0 of the edge FE; without
    the band (joint 'none') the three-point model is below half of the band FE."""
    d3 = _band_fe("D_Nmm@0")
    kf = _band_fe("K_N_per_mm@0")
    assert len(d3) == 10
    defl = [{"test": "three-point", "load": 1, "max": 1}]
    for (W, n, alpha), fe in d3.items():
        values = {}
        for joint in ("none", "band-edges"):
            p = _problem({"joint": joint}, deflection=defl, inplane_stiffness=[{"min": 1}])
            cand = p.candidates[0]
            v = point_values(p, cand, cand, _point(n, W, alpha), Tables(p))
            L = v[Quantity("length", 0.0)][0]
            values[joint] = (v[Quantity("k", 0.0, "free", "three-point")][0] * L * L / 48, v)
        model, v = values["band-edges"]
        assert 0.8 * fe["edges"] <= model <= fe["edges"], (W, n, alpha, model, fe)
        assert 0.65 * fe["flanges"] <= model <= fe["flanges"], (W, n, alpha, model, fe)
        assert values["none"][0] < 0.5 * fe["edges"]
        K = v[Quantity("K", 0.0, "free")][0]
        assert 0.95 * kf[(W, n, alpha)]["edges"] <= K <= kf[(W, n, alpha)]["edges"]


def test_box_bounds_contain_the_banded_values() -> None:
    """With a bonded band the interval bounds of D, K, a load case's P / delta and its load
    capacity still contain their values at points inside the box."""
    p = _problem(
        {"joint": "band-flanges"},
        deflection=[{"test": "three-point", "load": 1, "max": 1}],
        strength=[{"test": "cantilever", "load": 1}, {"test": "platens", "load": 1}],
        bending_stiffness=[{"min": 1}],
        inplane_stiffness=[{"min": 1, "eta": 90}],
    )
    cand = p.candidates[0]
    qs = {c.quantity for c in p.constraints if c.quantity.eta is not None}
    lo, hi = _point(8, 7, 60), _point(10, 9, 80)
    b = box_bounds(p, cand, cand, lo, hi, Tables(p), qs)
    rng = np.random.default_rng(1)
    for _ in range(20):
        n = float(rng.integers(8, 11))
        W, a = float(rng.uniform(7, 9)), float(rng.uniform(60, 80))
        v = point_values(p, cand, cand, _point(n, W, a), Tables(p))
        for q in qs:
            assert b[q][0][0] <= v[q][0] * (1 + 1e-12) and v[q][0] <= b[q][1][0] * (1 + 1e-12), q


def test_a_joint_needs_straight_walls() -> None:
    with pytest.raises(SpecError) as info:
        _problem({"layout": {"shape": "circle"}, "joint": "band-edges"}, "diameter")
    assert info.value.field == "joint"
    with pytest.raises(SpecError) as info:
        _problem({"joint": "glue"})
    assert info.value.field == "joint"


def _fe_estimate(series: dict[int, float]) -> float:
    """A mesh series' limit, written out independently of corrugate.fea.extrapolate: Richardson's
    from the three finest meshes at their observed order p when the steps have one sign and
    0.5 <= p <= 4 (the shells' asymptotic range, docs/fea.md 2.2); otherwise the finest value."""
    v1, v2, v3 = (series[k] for k in sorted(series)[-3:])
    d1, d2 = v1 - v2, v2 - v3
    if d1 * d2 <= 0 or not 0.5 <= math.log2(d1 / d2) <= 4:
        return v3
    p = math.log2(d1 / d2)
    return v3 - d2 / (2**p - 1)


def test_the_local_term_bounds_every_row_of_the_fe_sample() -> None:
    """Second method: every FE row along the creases of the squares of identical layers in
    docs/validation/load_cases_fe.csv (the earlier sample and issue 35's thin, thick and
    polypropylene designs; three-point, four-point at its load points and cantilever; CalculiX
    mesh series of 3-5 meshes). With the exact shear stiffness and the fitted local term the
    model's apparent D is at or below the extrapolated FE (the certificate is conservative) on
    every row, at t / W 0.005 and 0.05 among them; with the local term left out (c = 0) it is
    above the FE on some row: the term is needed."""
    from dataclasses import replace

    from corrugate.mechanics.load_cases import (
        CANTILEVER,
        FOUR_POINT,
        THREE_POINT,
        apparent,
        load_stiffness,
        shear_and_depth,
    )

    forms = {"bending": THREE_POINT, "bending4-load": FOUR_POINT, "cantilever": CANTILEVER}
    series: dict[tuple[str, str], dict[int, float]] = {}
    with (ROOT / "docs" / "validation" / "load_cases_fe.csv").open() as f:
        for r in csv.DictReader(f):
            if r["test"] in forms and r["eta_deg"] == "0" and float(r["shift"]) == 0.0:
                series.setdefault((r["design"], r["test"]), {})[int(r["along"])] = float(r["value"])
    checked, thin_thick, without = 0, set(), 0.0
    for (design, test), s in series.items():
        a = identical_square(design)
        if a is None or len(s) < 3:
            continue
        form = forms[test].form
        assert form is not None
        r = analyze(a, "refined", [0.0])
        st = r.stiffness[0]
        V, local = shear_and_depth(r.springs, 1.0, 0.0)

        def model(f: Any, st: Any = st, V: Any = V, local: Any = local) -> float:
            k = load_stiffness(f, st.D, float(V), float(local), st.span)
            return float(apparent(f, "D", k, st.span))

        fe = _fe_estimate(s)
        assert model(form) <= fe, (design, test, model(form), fe, s)
        without = max(without, model(replace(form, c=0.0)) / fe)
        thin_thick.add(round(a.layer1.t / a.layer1.W, 4))
        checked += 1
    assert checked >= 24
    assert {0.005, 0.05} <= thin_thick
    assert without > 1.0
