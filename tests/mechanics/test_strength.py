"""Peak facet stresses (corrugate.mechanics.strength) against limit cases, hand derivations and
second methods (numerical section integration, the spring model of corrugate.mechanics.springs)."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from corrugate.core.errors import InputError
from corrugate.mechanics.moduli import moduli
from corrugate.mechanics.springs import layer_springs
from corrugate.mechanics.strength import (
    LayerSection,
    bending_moment,
    chordwise_bending_stress,
    chordwise_compression_stress,
    chordwise_rigidity,
    chordwise_stiffness,
    peak_stress_bending,
    peak_stress_compression,
    spanwise_bending_stress,
    spanwise_compression_stress,
    spanwise_rigidity,
    spanwise_stiffness,
    stress_margin,
)

#: The paper's case study: Dura-Lar 0.125 mm, W 8 mm, n 8, alpha 84 deg (docs/theory.md 3.5).
CASE = LayerSection(E=2700.0, nu=0.43, t=0.125, W=8.0, n=8, alpha_deg=84.0)


def _springs(sec: LayerSection, length: float):  # type: ignore[no-untyped-def]
    """The spring model's springs of a layer whose n + 1 facets all have the length ``length``."""
    m = moduli(sec.E, sec.nu, sec.t, sec.W, sec.alpha_deg, "refined")
    s = math.sin(math.radians(sec.alpha_deg) / 2)
    q = (sec.n + 1) / length
    return layer_springs(m, sec.t, sec.W * s, q, sec.E, sec.nu, s)


def _numerical_I(sec: LayerSection, k: int = 400) -> tuple[float, float]:
    """Second moment (mm^4) and the largest fibre distance (mm) of the zig-zag section by brute
    force: every facet cut into k x k small squares of its (width x thickness) rectangle, placed
    on the folded profile, I = sum dA (z - z_bar)^2 about the centroid."""
    s, c = math.sin(math.radians(sec.alpha_deg) / 2), math.cos(math.radians(sec.alpha_deg) / 2)
    u = (np.arange(k) + 0.5) / k * sec.W  # along the facet
    v = ((np.arange(k) + 0.5) / k - 0.5) * sec.t  # through the thickness
    U, V = np.meshgrid(u, v)
    dA = (sec.W / k) * (sec.t / k)
    zs = []
    for j in range(sec.n + 1):
        up = j % 2 == 0  # facets rise and fall in turn
        # direction along the facet (s, +-c), normal (-+c, s)
        z0 = 0.0 if up else sec.W * c
        dz = c if up else -c
        nz = s
        zs.append(z0 + U * dz + V * nz)
    z = np.concatenate([a.ravel() for a in zs])
    zbar = z.mean()
    return float(np.sum((z - zbar) ** 2) * dA), float(np.max(np.abs(z - zbar)))


def test_spanwise_rigidity_is_the_second_moment_of_the_zigzag() -> None:
    """EI_S / E equals the brute-force second moment of the folded section (to the midpoint
    rule's error, 1e-5), for n odd and even and a deep and a shallow fold."""
    for sec in (
        CASE,
        LayerSection(2700.0, 0.43, 0.3, 10.0, 9, 40.0),
        LayerSection(2700.0, 0.3, 0.5, 12, 13, 150),
    ):
        I_num, _ = _numerical_I(sec)
        I = spanwise_rigidity(sec.E, sec.t, sec.W, sec.n, sec.alpha_deg) / sec.E
        assert pytest.approx(I_num, rel=1e-5) == I


def test_spanwise_rigidity_is_the_spring_models_D_S_times_L() -> None:
    """Second method: the refined D_S of corrugate.mechanics.springs (docs/theory.md 3.2) times
    the facet length."""
    L = 48.18
    D_S = float(_springs(CASE, L).D_S)
    assert spanwise_rigidity(CASE.E, CASE.t, CASE.W, CASE.n, CASE.alpha_deg) == pytest.approx(
        D_S * L, rel=1e-12
    )


def test_chordwise_rigidity_is_the_spring_models_D_C_times_the_chord() -> None:
    L = 48.18
    sp = _springs(CASE, L)
    chord = (CASE.n + 1) * CASE.W * math.sin(math.radians(CASE.alpha_deg) / 2)
    EI_C = chordwise_rigidity(CASE.E, CASE.nu, CASE.t, CASE.W, CASE.alpha_deg, L)
    assert pytest.approx(float(sp.D_C) * chord, rel=1e-12) == EI_C
    K_C = chordwise_stiffness(CASE.E, CASE.nu, CASE.t, CASE.W, CASE.n, CASE.alpha_deg, L)
    assert pytest.approx(float(sp.K_C), rel=1e-12) == K_C
    assert spanwise_stiffness(CASE.E, CASE.t, CASE.W, CASE.n, L) == pytest.approx(
        float(sp.K_S), rel=1e-12
    )


def test_spanwise_stress_is_beam_theory_at_the_extreme_fibre() -> None:
    """sigma = M z_max / I with z_max = h/2 + t/2 (the brute-force section's largest distance is
    h/2 + (t/2) s, at most t/2 below it)."""
    M = 1000.0
    I_num, zmax = _numerical_I(CASE)
    h = CASE.W * math.cos(math.radians(CASE.alpha_deg) / 2)
    sig = spanwise_bending_stress(CASE.E, CASE.t, CASE.W, CASE.n, CASE.alpha_deg, M)
    assert sig == pytest.approx(M * (h + CASE.t) / 2 / I_num, rel=1e-5)
    assert sig >= M * zmax / I_num  # the model's fibre is never nearer than the shell's surface
    assert sig == pytest.approx(M * zmax / I_num, rel=0.01)


def test_near_flat_sheet_gives_the_plate_formula() -> None:
    """alpha -> 180 deg: the zig-zag is a flat plate of width b = (n + 1) W, and sigma tends to
    6 M / (b t^2)."""
    t, W, n, M = 0.2, 10.0, 5, 50.0
    b = (n + 1) * W
    plate = 6 * M / (b * t**2)
    errors = [
        abs(spanwise_bending_stress(2000.0, t, W, n, 180.0 - d, M) / plate - 1)
        for d in (1e-1, 1e-3, 1e-5, 1e-7)
    ]
    assert errors[-1] < 1e-6  # the depth h = W cos(alpha/2) enters as h / t
    assert all(b_ < a_ for a_, b_ in itertools.pairwise(errors))
    # across the creases the flat sheet is the same plate, of width along the creases
    assert chordwise_bending_stress(t, b, M) == pytest.approx(6 * M / (b * t**2), rel=1e-15)


def test_stresses_are_linear_in_the_load_and_broadcast() -> None:
    M = np.array([1.0, 2.0, 10.0])
    sig = spanwise_bending_stress(CASE.E, CASE.t, CASE.W, CASE.n, CASE.alpha_deg, M)
    assert np.allclose(sig / sig[0], M / M[0], rtol=1e-14)
    P = np.array([3.0, -6.0])
    cc = chordwise_compression_stress(CASE.t, CASE.W, CASE.alpha_deg, 48.0, P)
    assert cc[1] == pytest.approx(-2 * cc[0], rel=1e-14)


def test_chordwise_compression_by_hand() -> None:
    """W 10, alpha 90, t 0.1, width 50, P 1 N: q = 0.02 N/mm, h = 7.0711, s = 0.70711; crease
    moment q h / 2 = 0.070711 N mm/mm, bending 6 x that / 0.01 = 42.426 MPa, membrane q s / t =
    0.14142 MPa: 42.568 MPa."""
    sig = chordwise_compression_stress(0.1, 10.0, 90.0, 50.0, 1.0)
    assert sig == pytest.approx(42.426 + 0.14142, rel=1e-4)
    assert spanwise_compression_stress(0.1, 10.0, 4, 1.0) == pytest.approx(1 / (5 * 10 * 0.1))


def test_chordwise_compression_stress_is_consistent_with_Ecx() -> None:
    """The crease-moment model's strain energy gives the thin-sheet Ecx: per facet U = q^2 c^2
    W^3 / (24 D), so the chordwise platen stiffness per unit width is 1 / ((n + 1) c^2 W^3 /
    (12 D)); the spring model's K_C agrees as t / W -> 0."""
    sec = LayerSection(2700.0, 0.43, 0.01, 10.0, 6, 84.0)
    c = math.cos(math.radians(sec.alpha_deg) / 2)
    D = sec.E * sec.t**3 / (12 * (1 - sec.nu**2))
    width = 50.0
    K_energy = width / ((sec.n + 1) * c**2 * sec.W**3 / (12 * D))
    K_C = chordwise_stiffness(sec.E, sec.nu, sec.t, sec.W, sec.n, sec.alpha_deg, width)
    assert pytest.approx(K_energy, rel=1e-5) == K_C


def test_assembly_shares_add_up_and_follow_the_stiffnesses() -> None:
    M = 1234.0
    r = peak_stress_bending(CASE, CASE, M, 0.0)
    assert sum(r.shares) == pytest.approx(M, rel=1e-15)
    L = CASE.chord_extent
    EI_S = spanwise_rigidity(CASE.E, CASE.t, CASE.W, CASE.n, CASE.alpha_deg)
    EI_C = chordwise_rigidity(CASE.E, CASE.nu, CASE.t, CASE.W, CASE.alpha_deg, L)
    assert r.shares[0] / r.shares[1] == pytest.approx(EI_S / EI_C, rel=1e-12)
    assert r.layer == 1 and "crease" in r.where
    assert r.sigma == pytest.approx(
        spanwise_bending_stress(CASE.E, CASE.t, CASE.W, CASE.n, CASE.alpha_deg, r.shares[0])
    )
    # turned by 90 deg the roles swap
    r90 = peak_stress_bending(CASE, CASE, M, 90.0)
    assert r90.layer == 2 and r90.shares == pytest.approx(r.shares[::-1])
    P = 10.0
    c = peak_stress_compression(CASE, CASE, P, 0.0)
    assert sum(c.shares) == pytest.approx(P, rel=1e-15)
    assert c.layer_sigma[0] == pytest.approx(c.shares[0] / ((CASE.n + 1) * CASE.W * CASE.t))


def test_a_stiffer_second_layer_takes_more() -> None:
    """Doubling layer 2's thickness raises its chordwise rigidity (~t^3) and its share of M."""
    thick = LayerSection(CASE.E, CASE.nu, 2 * CASE.t, CASE.W, CASE.n, CASE.alpha_deg)
    a = peak_stress_bending(CASE, CASE, 100.0)
    b = peak_stress_bending(CASE, thick, 100.0)
    assert b.shares[1] > a.shares[1] and b.shares[0] < a.shares[0]


def test_bending_moments_of_the_bench_tests() -> None:
    """Statics: three-point, reactions P/2 at the ends, M(Ls/2) = P Ls / 4; four-point, P/2 at the
    quarter points, M = (P/2)(Ls/4); cantilever, M = P Ls at the clamp."""
    P, Ls = 3.0, 40.0
    assert bending_moment("three-point", P, Ls) == pytest.approx((P / 2) * (Ls / 2))
    assert bending_moment("four-point", P, Ls) == pytest.approx((P / 2) * (Ls / 4))
    assert bending_moment("cantilever", P, Ls) == pytest.approx(P * Ls)
    # the spec's names only (the moment is the load case's): the FE's old names and in-plane
    # tests are refused, naming the bending tests
    for other in ("bending", "bending4", "platens", "torsion"):
        with pytest.raises(InputError, match="three-point, four-point, cantilever"):
            bending_moment(other, P, Ls)


def test_stress_margin() -> None:
    assert stress_margin(50.0, 100.0) == pytest.approx(1.0)
    assert stress_margin(50.0, 100.0, 2.0) == pytest.approx(0.0)
    assert stress_margin(-50.0, 100.0, 4.0) == pytest.approx(-0.5)  # compression by magnitude
    assert stress_margin(0.0, 100.0) == math.inf
    assert np.allclose(stress_margin(np.array([25.0, 200.0]), 100.0), [3.0, -0.5])
    for bad in (0.0, -1.0, math.nan):
        with pytest.raises(InputError, match="safety_factor"):
            stress_margin(1.0, 100.0, bad)
    with pytest.raises(InputError, match="allowable"):
        stress_margin(1.0, 0.0)


def test_off_axis_and_bad_layers_are_refused() -> None:
    with pytest.raises(InputError, match="eta"):
        peak_stress_bending(CASE, CASE, 1.0, 45.0)
    with pytest.raises(InputError, match=r"layer2\.t"):
        peak_stress_bending(CASE, LayerSection(2700.0, 0.43, -0.1, 8.0, 8, 84.0), 1.0)
    with pytest.raises(InputError, match="M"):
        peak_stress_bending(CASE, CASE, math.inf)


def test_from_a_library_layer() -> None:
    from corrugate.geometry.layer import Layer
    from corrugate.materials.library import get_material

    layer = Layer(8.0, 8, 84.0, get_material("dura-lar"))
    sec = LayerSection.from_layer(layer)
    assert sec == CASE
    from corrugate.geometry.layer import Assembly
    from corrugate.mechanics.strength import assembly_sections

    s1, s2, lengths = assembly_sections(Assembly.identical(layer))
    assert s1 == s2 == CASE
    assert lengths == pytest.approx((CASE.chord_extent, CASE.chord_extent))  # L = 48.18 mm
    a = peak_stress_bending(s1, s2, 100.0, 0.0, lengths)
    assert a == peak_stress_bending(CASE, CASE, 100.0, 0.0)
