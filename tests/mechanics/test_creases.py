"""Compliant creases in the moduli, the springs and the free panel (docs/offaxis.md, "Compliant
creases"; corrugate.mechanics.creases)."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from corrugate.analysis.evaluate import analyze
from corrugate.calibration.crease import compliance
from corrugate.geometry.layer import Assembly, Layer
from corrugate.geometry.profile import ZigZag
from corrugate.materials.library import get_material
from corrugate.mechanics.creases import creased_moduli, flexibility
from corrugate.mechanics.profiles import profile_moduli
from corrugate.solver.interval import Interval

E, NU, T = 2700.0, 0.43, 0.125


def test_rigid_creases_give_the_rigid_numbers_bit_for_bit() -> None:
    m = get_material("dura-lar")
    a = Assembly.identical(Layer(W=8, n=8, alpha_deg=84, material=m, t=0.125))
    b = Assembly.identical(
        Layer(W=8, n=8, alpha_deg=84, material=replace(m, crease_stiffness=math.inf), t=0.125)
    )
    ra = analyze(a, eta_deg=[0, 15, 45, 90])
    rb = analyze(b, eta_deg=[0, 15, 45, 90])
    for sa, sb in zip(ra.stiffness, rb.stiffness, strict=True):
        assert (sa.K, sa.D, sa.EI) == (sb.K, sb.D, sb.EI)
    z = ZigZag.of_float(8.0, 84.0)
    assert profile_moduli(z, E, NU, T, "refined", 0.0) is not None
    m0 = profile_moduli(z, E, NU, T, "refined")
    assert creased_moduli(m0, 0.0, T, 8.0, z.s, z.c) is m0
    assert flexibility(math.inf) == 0.0


@pytest.mark.parametrize("k", [1.0, 0.1, 0.02])
@pytest.mark.parametrize("alpha", [50.0, 84.0, 130.0])
def test_ecx_is_the_kit_strips_compliance_per_pitch(k: float, alpha: float) -> None:
    """Second method: the zig-zag strip of calibration/crease.py (docs/calibration.md 4, its own
    virtual-work derivation, facets stretching at E b t) over N creases and width b is the
    chordwise spring of a layer, C = N p / (Ecx t b) as N grows (its two half facets are one
    facet)."""
    W, b, N = 8.0, 20.0, 4000
    z = ZigZag.of_float(W, alpha)
    m = profile_moduli(z, E, NU, T, "refined", 1.0 / k)
    C = compliance(k, E, T, b, W, alpha, N, NU)
    assert float(m.Ecx) == pytest.approx(N * W * z.s / (C * T * b), rel=1e-12)


def test_ebx_adds_one_crease_rotation_per_pitch() -> None:
    """Hand derivation: a moment M per unit width turns every crease by M / k and bends every
    facet by M W / D_facet over the pitch p = W s; the rigid Ebx's D_C = Ebx t^3 / 12 is the
    facets' share, so 1 / D_C,k = 1 / D_C + 1 / (k p)."""
    W, alpha, k = 10.0, 70.0, 0.08
    z = ZigZag.of_float(W, alpha)
    rigid = profile_moduli(z, E, NU, T, "refined")
    soft = profile_moduli(z, E, NU, T, "refined", 1.0 / k)
    DC, DCk = (float(x.Ebx) * T**3 / 12 for x in (rigid, soft))
    assert 1 / DCk == pytest.approx(1 / DC + 1 / (k * W * z.s), rel=1e-12)
    assert (float(soft.Ecy), float(soft.Eby)) == (float(rigid.Ecy), float(rigid.Eby))


def test_limit_of_a_very_soft_crease_is_the_hinges_alone() -> None:
    """k -> 0: the creases carry everything, Ecx -> 4 k s / (t W c^2) (the hinge term)."""
    W, alpha, k = 8.0, 84.0, 1e-9
    z = ZigZag.of_float(W, alpha)
    m = profile_moduli(z, E, NU, T, "refined", 1.0 / k)
    assert float(m.Ecx) == pytest.approx(4 * k * z.s / (T * W * z.c**2), rel=1e-6)


def test_a_compliant_crease_softens_the_free_panel_off_axis_not_along_the_creases() -> None:
    m = get_material("dura-lar")
    rows = {}
    for k in (math.inf, 1.0, 0.05):
        lay = Layer(W=8, n=4, alpha_deg=84, material=replace(m, crease_stiffness=k), t=0.125)
        r = analyze(Assembly.identical(lay), eta_deg=[0, 45])
        rows[k] = (r.stiffness[0].K, r.stiffness[1].K, float(r.springs[0].K_C))
    # along the creases K = K_S + K_C, K_C falls, K_S stays: the change is K_C's
    assert rows[0.05][0] - rows[math.inf][0] == pytest.approx(
        rows[0.05][2] - rows[math.inf][2], rel=1e-9
    )
    # at 45 deg the chordwise term dominates: K falls with k
    assert rows[math.inf][1] > rows[1.0][1] > rows[0.05][1]


def test_interval_crease_encloses_the_point_values() -> None:
    z = ZigZag.of_float(8.0, 84.0)
    k_lo, k_hi = 0.05, 0.2
    box = profile_moduli(z, E, NU, T, "refined", Interval(k_lo, k_hi).reciprocal())
    for k in np.linspace(k_lo, k_hi, 7):
        v = float(profile_moduli(z, E, NU, T, "refined", 1.0 / k).Ecx)
        assert float(box.Ecx.lo) <= v <= float(box.Ecx.hi)
