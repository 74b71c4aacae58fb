"""Nodal stresses from ccx (.frd) and the peak facet stress of corrugate.mechanics.strength
against the 3-point shell FE (docs/validation/strength.md)."""

from __future__ import annotations

import numpy as np
import pytest

from corrugate import Assembly, Layer, get_material
from corrugate.core.errors import CorrugateError
from corrugate.fea.assembly import AssemblyMesh, assembly_deck, solve_assembly
from corrugate.fea.ccx import parse_frd_stresses
from corrugate.mechanics.strength import LayerSection, peak_stress_bending

#: A hand-made .frd: two nodes, one element of material 2, a stress block whose numbers touch.
FRD = """\
    1C
    2C                             2                                     1
 -1         7 1.00000E+00 2.00000E+00-3.00000E+00
 -1         9 0.00000E+00 0.00000E+00 5.00000E-01
 -3
    3C                             1                                     1
 -1         1    4    0    2
 -2         7         9
 -3
  100CL  101 1.000000000             2                     0    1           1
 -4  STRESS      6    1
 -5  SXX         1    4    1    1
 -1         7 1.00000E+01-2.00000E+00 0.00000E+00 0.00000E+00 0.00000E+00 0.00000E+00
 -1         9 0.00000E+00 0.00000E+00 0.00000E+00 3.00000E+00 0.00000E+00 0.00000E+00
 -3
 9999
"""


def test_parse_frd_reads_fixed_width_fields() -> None:
    f = parse_frd_stresses(FRD)
    assert list(f.ids) == [7, 9]
    assert np.allclose(f.xyz[0], [1.0, 2.0, -3.0])
    assert np.allclose(f.stress[0], [10.0, -2.0, 0, 0, 0, 0])
    assert list(f.material) == [2, 2]
    # uniaxial-plus-transverse: principal 10, 0, -2; von Mises sqrt(100 + 4 + 20) = sqrt(124)
    assert np.allclose(f.principal()[0], [-2.0, 0.0, 10.0])
    assert f.von_mises()[0] == pytest.approx(np.sqrt(124.0))
    # pure shear 3: principal +-3, von Mises 3 sqrt(3)
    assert np.allclose(f.principal()[1], [-3.0, 0.0, 3.0])
    assert f.von_mises()[1] == pytest.approx(3 * np.sqrt(3.0))


def test_parse_frd_without_stresses_is_an_error() -> None:
    with pytest.raises(CorrugateError, match="STRESS"):
        parse_frd_stresses(FRD.split("  100CL")[0])


def test_stress_output_only_adds_lines_to_the_deck() -> None:
    a = Assembly.identical(Layer(W=8.0, n=8, alpha_deg=84.0, material=get_material("dura-lar")))
    plain, _ = assembly_deck(a, "three-point", AssemblyMesh(2))
    with_s, _ = assembly_deck(a, "three-point", AssemblyMesh(2), stresses=True)
    assert with_s.replace("*EL FILE\nS\n", "") == plain


@pytest.mark.fea
def test_three_point_window_stress_matches_the_beam_model(ccx: str) -> None:
    """Case study, 2 elements per facet: the reaction is the same with and without the stress
    output, and the peak |principal stress| of layer 1 between 1/8 and 3/8 of the span is the
    zig-zag beam stress at M(3L/8) = 3 P L / 16 within 10 % (docs/validation/strength.md: 0.97-1.0
    at 2-8 elements per facet)."""
    layer = Layer(W=8.0, n=8, alpha_deg=84.0, material=get_material("dura-lar"))
    a = Assembly.identical(layer)
    r0 = solve_assembly(a, "three-point", AssemblyMesh(2))
    r = solve_assembly(a, "three-point", AssemblyMesh(2), stresses=True)
    assert r.force == pytest.approx(r0.force, rel=1e-9) and r0.stresses is None
    f = r.stresses
    assert f is not None
    y = f.xyz[:, 1]
    L, P = r.span, r.force
    window = (f.material == 1) & (y >= L / 8) & (y <= 3 * L / 8)
    fe = float(np.max(np.abs(f.principal()[window])))
    sec = LayerSection.from_layer(layer)
    model = peak_stress_bending(sec, sec, 3 * P * L / 16).layer_sigma[0]
    assert model == pytest.approx(fe, rel=0.10)
