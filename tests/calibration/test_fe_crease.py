"""The zig-zag strip pulled along its chord line, with compliant creases: CalculiX against the
hand derivation of corrugate.calibration.fe_crease (docs/offaxis.md, "Compliant creases")."""

from __future__ import annotations

import math

import pytest

from corrugate.calibration.crease import compliance as kit_compliance
from corrugate.calibration.fe_crease import (
    compliance,
    crease_strip_compliance,
    crease_strip_deck,
    rigid_ends,
)
from corrugate.materials.library import get_material

T, B, W, ALPHA, N = 0.125, 20.0, 12.0, 90.0, 9


def test_the_hand_derivation_is_the_kits_strip_with_its_ends_rigid() -> None:
    """The FE strip has n + 1 full facets and rigid end edges at the moment F h / 2: the kit's
    strip (n creases, n - 1 full facets and two half facets) plus one facet's bending and
    stretching (a second derivation, calibration/crease.py)."""
    m = get_material("dura-lar")
    for k in (math.inf, 0.1):
        ours = compliance(k, m.E, m.nu, T, B, W, ALPHA, N)
        kit = kit_compliance(k, m.E, T, B, W, ALPHA, N, m.nu)
        one = kit_compliance(math.inf, m.E, T, B, W, ALPHA, 1, m.nu)  # one facet's share
        assert ours == pytest.approx(kit + one, rel=1e-12)


def test_the_deck_has_strips_only_at_a_finite_stiffness() -> None:
    from dataclasses import replace

    m = get_material("dura-lar")
    rigid = crease_strip_deck(m, T, B, W, ALPHA, N, 2)
    soft = crease_strip_deck(replace(m, crease_stiffness=0.1), T, B, W, ALPHA, N, 2)
    assert "ELSET=C1" not in rigid
    assert soft.count("*ELEMENT,TYPE=S8R,ELSET=C1") == 1
    assert "*ELASTIC,TYPE=ENGINEERING CONSTANTS" in soft


@pytest.mark.fea
@pytest.mark.parametrize("k", [0.1, 0.05])
def test_the_fe_strip_with_crease_strips_matches_the_hand_derivation(ccx: str, k: float) -> None:
    """At 4 elements per facet (2-4 s of ccx) the FE compliance is within 1 % of the closed
    form (0.995 and 0.998; 2 / 4 / 8 / 16 per facet in docs/offaxis.md) and above the closed
    form less the FE's rigid end zones (its structure exactly), and the crease adds what
    n e^2 / (k b) says to within 3 % (against the same mesh at k = 1e6, nearly rigid)."""
    m = get_material("dura-lar")
    fe = crease_strip_compliance(m, k, T, B, W, ALPHA, N, 4).C
    closed = compliance(k, m.E, m.nu, T, B, W, ALPHA, N)
    assert fe == pytest.approx(closed, rel=0.01)
    assert fe > closed - rigid_ends(m.E, m.nu, T, B, W, ALPHA)
    stiff = crease_strip_compliance(m, 1e6, T, B, W, ALPHA, N, 4).C
    e = W * math.cos(math.radians(ALPHA) / 2) / 2
    assert fe - stiff == pytest.approx(N * e * e / (k * B), rel=0.03)
