"""The elastica against the FE twin of a kit's flat strip (CalculiX, NLGEOM; docs/calibration.md
section 7): Dura-Lar 0.125 mm, 20 mm wide, E 3100 MPa. The strip bends as a plate (its rigidity
E b t^3 / (12 (1 - nu^2)), what the fit uses), not as a beam (E b t^3 / 12, 22 % softer at
nu = 0.43): the FE's sag lies near the plate elastica's and well below the beam's."""

from __future__ import annotations

import pytest

from corrugate.calibration.elastica import drop_ratio
from corrugate.calibration.fe_strip import strip_sag
from corrugate.materials.library import get_material

MAT = get_material("dura-lar")
E, T, B = 3100.0, 0.125, 20.0


def _elastica(L: float, tip_g: float, rigidity: float) -> float:
    q = MAT.density * B * T * 9.80665e-3
    return L * drop_ratio(q * L**3 / rigidity, tip_g * 9.80665e-3 * L**2 / rigidity)


@pytest.mark.fea
@pytest.mark.slow
def test_the_strip_sags_as_the_plate_elastica_says(ccx: str) -> None:
    plate = E * B * T**3 / (12 * (1 - MAT.nu**2))
    beam = E * B * T**3 / 12
    # own weight, 75 mm free: 16 x 2 elements (the mesh series converges up to about +4 %:
    # benchmarks/calibration_fe_strip.py)
    fe = strip_sag(MAT, E, T, B, 75.0, 0.0, 16).sag
    assert _elastica(75.0, 0.0, plate) * 0.98 < fe < _elastica(75.0, 0.0, plate) * 1.1
    assert fe < 0.9 * _elastica(75.0, 0.0, beam)
    # a 5 g coin at 40 mm, the steep large-deflection range: 8 x 2 elements
    fe = strip_sag(MAT, E, T, B, 40.0, 5.0, 8).sag
    assert fe == pytest.approx(_elastica(40.0, 5.0, plate), rel=0.04)
