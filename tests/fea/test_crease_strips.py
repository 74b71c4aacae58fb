"""The crease strips of the assembly FE (corrugate.fea.shells.crease_strip): rigid creases leave
the deck as it was; a finite k adds an orthotropic strip along every crease."""

from __future__ import annotations

import math
from dataclasses import replace

import pytest

from corrugate.core.errors import InputError
from corrugate.fea.assembly import AssemblyMesh, assembly_deck
from corrugate.fea.shells import STRIP_FRACTION, crease_strip
from corrugate.geometry.layer import Assembly, Layer
from corrugate.materials.library import get_material


def _assembly(k: float = math.inf) -> Assembly:
    m = replace(get_material("dura-lar"), crease_stiffness=k)
    return Assembly.identical(Layer(W=8, n=4, alpha_deg=84, material=m, t=0.125))


@pytest.mark.parametrize("eta", [0.0, 90.0, 45.0])
def test_rigid_creases_leave_the_deck_byte_for_byte(eta: float) -> None:
    a = _assembly()
    mesh = AssemblyMesh(along=2)
    plain, _ = assembly_deck(a, "platens", mesh, eta)
    assert assembly_deck(a, "platens", mesh, eta, crease_stiffness=math.inf)[0] == plain
    assert "ELSET=C" not in plain


@pytest.mark.parametrize("eta", [90.0, 45.0])
def test_a_finite_crease_adds_one_strip_set_per_layer(eta: float) -> None:
    deck, info = assembly_deck(
        _assembly(), "platens", AssemblyMesh(along=2), eta, crease_stiffness=0.1
    )
    for k in (1, 2):
        assert f"*SHELL SECTION,ELSET=C{k},MATERIAL=MC{k},ORIENTATION=OC{k}" in deck
    rigid = assembly_deck(_assembly(), "platens", AssemblyMesh(along=2), eta)[1]
    assert info.elements > rigid.elements


def test_the_strip_is_the_sheet_at_an_infinite_stiffness_and_softens_as_the_crease() -> None:
    """k -> inf: E across -> E (the sheet); k -> 0: D_s -> k width f, E_a -> 12 k width f / t^3."""
    E, nu, t, W = 2700.0, 0.43, 0.125, 8.0
    w = STRIP_FRACTION * W
    assert crease_strip(t, E, nu, 1e12, w, (0.0, 1.0), W).E_across == pytest.approx(E, rel=1e-9)
    f = 1 - w / W + (w / W) ** 2 / 3
    soft = crease_strip(t, E, nu, 1e-6, w, (0.0, 1.0), W).E_across
    assert soft == pytest.approx(12 * 1e-6 * w * f / t**3, rel=1e-5)


def test_crease_strips_with_the_band_are_refused_in_one_line() -> None:
    with pytest.raises(InputError, match="crease_stiffness"):
        assembly_deck(_assembly(0.1), "platens", AssemblyMesh(along=2), 0.0, connectors=True)
