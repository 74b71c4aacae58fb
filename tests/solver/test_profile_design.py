"""A second designable profile through the seam (issue 33, item 1): the flat-crested trapezoid
(corrugate.mechanics.profiles.FlatCrest) registered by the test, carried by a layer, analysed
and designed by the certified solver.

Independent sources: the equivalent plate of Xia, Friswell and Saavedra Flores (2012) written
out here in full (A and D, then the moduli from the determinants, as the paper reduces them),
against the package's factored form and the zig-zag's springs (docs/theory.md 3.1-3.3); the
shape against Xia's own trapezoid parameters (c, f, theta: corrugate.mechanics.profiles.Trapezoid);
the solver's certified least mass against an exhaustive numpy search over the same grid.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import replace

import numpy as np
import pytest

from corrugate.analysis.evaluate import analyze
from corrugate.core.errors import InputError
from corrugate.geometry.connectors import connector_area
from corrugate.geometry.layer import Assembly, Layer
from corrugate.geometry.profile import ProfileKind, register_profile, unregister_profile
from corrugate.materials.library import get_material
from corrugate.mechanics.profiles import FlatCrest, Trapezoid, profile_moduli
from corrugate.solver import Constraint, Problem, solve
from corrugate.solver.interval import Interval
from corrugate.solver.problem import FEAS_RTOL, Objective
from corrugate.solver.quantity import MASS, Quantity
from corrugate.spec.schema import parse_spec

FLAT = 0.25  # flat part of each half period, as a fraction of the incline's width W
EI0 = Quantity.stiffness("EI", 0.0)  # under the default support, free sides


@pytest.fixture
def kind() -> Iterator[ProfileKind]:
    register_profile("flat-crest", FlatCrest)
    try:
        yield ProfileKind("flat-crest", (FLAT,))
    finally:
        unregister_profile("flat-crest")


def _xia_plate(W, s, c, E, nu, t, membrane):  # type: ignore[no-untyped-def]
    """Xia (2012) A and D of the flat-crested trapezoid, term by term from its segments: per
    period two inclines (length W, cos(theta) = s, z from -h/2 to h/2, h = W c) and two level
    parts (length FLAT W at |z| = h/2)."""
    h = W * c
    cc = W * s + FLAT * W  # half period
    ll = W + FLAT * W  # developed half period
    I1 = 2 * W * s**2 + 2 * FLAT * W * 1.0**2
    I2 = 2 * (W * h**2 / 12) + 2 * FLAT * W * (h / 2) ** 2
    A = E * t / (1 - nu**2)
    D = E * t**3 / (12 * (1 - nu**2))
    A11 = 2 * cc / (I1 / A + I2 / D)
    A12 = nu * A11
    A22 = nu**2 * A11 + ll / cc * E * t
    Am = A if membrane == "plane-strain" else E * t
    D11 = cc / ll * D
    D12 = nu * D11
    D22 = (I2 * Am + I1 * D) / (2 * cc)
    return A11, A12, A22, D11, D12, D22


def _xia_moduli(W, s, c, E, nu, t, membrane):  # type: ignore[no-untyped-def]
    A11, A12, A22, D11, D12, D22 = _xia_plate(W, s, c, E, nu, t, membrane)
    return (
        (A11 * A22 - A12**2) / (t * A22),
        (A11 * A22 - A12**2) / (t * A11),
        12 * (D11 * D22 - D12**2) / (t**3 * D22),
        12 * (D11 * D22 - D12**2) / (t**3 * D11),
    )


def test_flat_crest_is_xias_trapezoid() -> None:
    # the same shape given by Xia's (c, f, theta): c = W (s + flat), f = W c / 2, theta = 90 - alpha/2
    W, alpha = 7.0, 80.0
    z = FlatCrest.of_float(W, alpha, FLAT)
    trap = Trapezoid(c=z.pitch, f=z.height / 2, theta_deg=90.0 - alpha / 2)
    assert trap.flat == pytest.approx(FLAT * W, rel=1e-12)
    for key in ("c", "l", "I1", "I2"):
        assert getattr(z.integrals(), key) == pytest.approx(
            getattr(trap.integrals(), key), rel=1e-12
        )
    assert z.developed == pytest.approx(trap.developed, rel=1e-12)
    assert z.plan_ratio == pytest.approx(trap.plan_ratio, rel=1e-12)
    assert z.web2 == pytest.approx(trap.web2, rel=1e-12)
    # no flat part: the zig-zag's geometry
    zz = FlatCrest.of_float(W, alpha, 0.0)
    assert (zz.pitch, zz.height, zz.developed) == pytest.approx(
        (W * np.sin(np.radians(alpha / 2)), W * np.cos(np.radians(alpha / 2)), W), rel=1e-15
    )


def test_profile_moduli_over_intervals_enclose_the_points() -> None:
    # the solver bounds a general profile's moduli by interval arithmetic of the same code
    mat = get_material("dura-lar")
    E, nu, t = float(mat.E), float(mat.nu), 0.125
    box = FlatCrest.of(Interval(5.0, 6.0), Interval(70.0, 80.0), FLAT)
    m = profile_moduli(box, E, nu, t, "refined")
    W, a = np.meshgrid(np.linspace(5, 6, 11), np.linspace(70, 80, 11))
    pts = profile_moduli(FlatCrest.of(W, a, FLAT), E, nu, t, "refined")
    for key in ("Ecx", "Ecy", "Ebx", "Eby"):
        iv, v = getattr(m, key), getattr(pts, key)
        assert np.all(iv.lo <= v) and np.all(v <= iv.hi), key
        assert iv.lo > 0, key  # the factored form keeps the enclosure positive


@pytest.mark.parametrize(("model", "membrane"), [("xia", "plane-strain"), ("refined", "uniaxial")])
def test_analyze_a_flat_crest_layer(kind: ProfileKind, model: str, membrane: str) -> None:
    mat = get_material("dura-lar")
    t = 0.125
    W, n, alpha = 6.0, 9, 75.0
    layer = Layer(W, n, alpha, mat, t, kind)
    a = analyze(Assembly.identical(layer), model=model, eta_deg=[0.0, 90.0])
    s, c = np.sin(np.radians(alpha) / 2), np.cos(np.radians(alpha) / 2)
    p = W * (s + FLAT)
    L = (n + 1) * p  # a square: every facet spans the other layer's extent
    assert a.assembly.Lx == pytest.approx(L, rel=1e-14)
    assert a.assembly.thickness == pytest.approx(2 * W * c, rel=1e-14)
    Ecx, Ecy, Ebx, Eby = _xia_moduli(W, s, c, float(mat.E), float(mat.nu), t, membrane)
    got = a.moduli[0].as_dict()
    for key, want in zip(("Ecx", "Ecy", "Ebx", "Eby"), (Ecx, Ecy, Ebx, Eby), strict=True):
        assert got[key] == pytest.approx(want, rel=1e-12), key
    # identical layers on a square: p sum_j 1/L_j = 1, so along layer 1's creases the panel's
    # D is layer 1's spanwise plate bending plus layer 2's chordwise (docs/theory.md 3.2-3.3)
    D = (Eby + Ebx) * t**3 / 12
    assert pytest.approx(D * L, rel=1e-12) == a.stiffness[0].EI
    assert pytest.approx(D * L, rel=1e-12) == a.stiffness[1].EI
    # mass: rho t x developed width x facet length per repeat unit, both layers, and the band
    blank = float(mat.density) * t * (W * (1 + FLAT)) * L * (n + 1)
    assert a.mass.layer1 == pytest.approx(blank, rel=1e-12)
    # the zig-zag's answer differs (the seam is not a no-op)
    zz = analyze(Assembly.identical(Layer(W, n, alpha, mat, t)), model=model, eta_deg=[0.0])
    assert abs(zz.stiffness[0].EI / a.stiffness[0].EI - 1) > 0.05


def _problem(kind: ProfileKind, bound: float) -> Problem:
    """Identical flat-crest layers on a square: n 4-30, W 4-12 mm step 1, alpha 60-120 deg step
    10; least mass with EI at 0 deg >= bound."""
    spec = parse_spec(
        {
            "name": "flat-crest",
            "tolerances": "none",  # the nominal model (tolerances: tests/solver/test_tolerance_box.py)
            "material": {"name": "dura-lar", "thickness": "0.125 mm"},
            "layout": {"shape": "square"},
            "variables": {
                "W": {"min": 4, "max": 12, "step": 1},
                "n": {"min": 4, "max": 30},
                "alpha": {"min": 60, "max": 120, "step": 10},
            },
        }
    )
    return replace(
        Problem.from_spec(spec),
        constraints=(Constraint("EI", EI0, "min", bound),),
        objective=Objective(MASS, "min"),
        profile_kind=kind,
    )


def test_the_solver_certifies_a_least_mass_flat_crest_design(kind: ProfileKind) -> None:
    mat = get_material("dura-lar")
    E, nu, rho, t = float(mat.E), float(mat.nu), float(mat.density), 0.125
    n, W, a = (
        g.ravel()
        for g in np.meshgrid(
            np.arange(4, 31, dtype=float),
            np.arange(4, 13, dtype=float),
            np.arange(60, 121, 10, dtype=float),
            indexing="ij",
        )
    )
    s, c = np.sin(np.radians(a) / 2), np.cos(np.radians(a) / 2)
    _, _, Ebx, Eby = _xia_moduli(W, s, c, E, nu, t, "uniaxial")  # the default model, refined
    L = (n + 1) * W * (s + FLAT)
    EI = (Eby + Ebx) * t**3 / 12 * L
    td = 2 * W * c
    band = rho * t * connector_area(_problem(kind, 1.0).layout, L, L, td)
    mass = 2 * rho * t * W * (1 + FLAT) * L * (n + 1) + band
    bound = float(np.quantile(EI, 0.6))
    bound = 0.5 * (bound + float(np.min(EI[bound < EI])))  # halfway between two grid values
    feasible = bound * (1 - FEAS_RTOL) <= EI
    best = int(np.argmin(np.where(feasible, mass, np.inf)))
    assert mass[best] > 1.5 * np.min(mass)  # the bound binds: not the grid's lightest corner

    sol = solve(_problem(kind, bound), explain=False)
    assert sol.status == "optimal" and sol.certified and sol.gap == 0.0
    assert sol.objective == pytest.approx(float(mass[best]), rel=1e-12)
    layer = sol.assembly.layer1
    assert layer.profile_kind == kind
    assert (layer.n, layer.W, layer.alpha_deg) == (int(n[best]), W[best], a[best])
    assert bound * (1 - FEAS_RTOL) <= analyze(sol.assembly, eta_deg=[0.0]).stiffness[0].EI


def test_a_profile_without_constructors_from_W_and_alpha_is_refused() -> None:
    register_profile("xia-trapezoid", Trapezoid)
    try:
        with pytest.raises(InputError, match="designable"):
            ProfileKind("xia-trapezoid")
    finally:
        unregister_profile("xia-trapezoid")


def test_fabrication_and_fe_refuse_another_profile_in_one_line(kind: ProfileKind) -> None:
    from corrugate.fabrication.build import build_pattern
    from corrugate.fea.shells import layer_shell

    layer = Layer(6.0, 9, 75.0, get_material("dura-lar"), 0.125, kind)
    a = Assembly.identical(layer)
    with pytest.raises(InputError, match=r"^profile = flat-crest has no fold pattern yet"):
        build_pattern(a)
    with pytest.raises(InputError, match=r"^profile = flat-crest has no FE mesh yet"):
        layer_shell(layer, a.Ly, 2, 1, 0, 0.0)
    build_pattern(Assembly.identical(replace(layer, profile_kind=ProfileKind())))  # the zig-zag


def test_no_flat_part_is_the_zig_zag_through_the_general_theory() -> None:
    # limit case: flat = 0 is the zig-zag, whose Xia closed forms (model xia) the general theory
    # reproduces (Xia 2012; tests/mechanics/test_profiles.py), so the whole analysis agrees
    register_profile("flat-crest-0", FlatCrest)
    try:
        mat = get_material("dura-lar")
        flat0 = Layer(6.0, 9, 75.0, mat, 0.125, ProfileKind("flat-crest-0", (0.0,)))
        zig = replace(flat0, profile_kind=ProfileKind())
        etas = [0.0, 30.0, 90.0]
        a = analyze(Assembly.identical(flat0), model="xia", eta_deg=etas)
        b = analyze(Assembly.identical(zig), model="xia", eta_deg=etas)
        for sa, sb in zip(a.stiffness, b.stiffness, strict=True):
            assert pytest.approx(sb.EI, rel=1e-9) == sa.EI
            assert pytest.approx(sb.K, rel=1e-9) == sa.K
        assert a.mass.total == pytest.approx(b.mass.total, rel=1e-12)
    finally:
        unregister_profile("flat-crest-0")


def test_the_zig_zags_strength_closed_forms_refuse_another_profile(kind: ProfileKind) -> None:
    from corrugate.mechanics.strength import assembly_sections

    layer = Layer(6.0, 9, 75.0, get_material("dura-lar"), 0.125, kind)
    with pytest.raises(InputError, match=r"^profile = flat-crest has no strength closed forms"):
        assembly_sections(Assembly.identical(layer))
