"""General equivalent plate of a corrugated sheet: Xia, Friswell and Saavedra Flores (2012).

Xia, Y., Friswell, M. I., Saavedra Flores, E. I. (2012), "Equivalent models of corrugated panels",
Int. J. Solids Struct. 49:1453-1462, eqs. for A and D of an arbitrary periodic profile. With the
sheet's A = E t/(1 - nu^2), D = E t^3/(12 (1 - nu^2)), A66 = E t/(2 (1 + nu)),
D66 = E t^3/(24 (1 + nu)), a profile of half period c, developed half length l and integrals
I1 = int cos^2(theta) ds, I2 = int z^2 ds over one period gives (x across the corrugation):

    A11 = 2c / (I1/A + I2/D),  A12 = nu A11,  A22 = nu^2 A11 + (l/c) E t,  A66 = (c/l) A66_sheet
    D11 = (c/l) D,  D12 = nu D11,  D22 = (I2 A_m + I1 D)/(2c),  D66 = (l/c) D66_sheet

``A_m`` is the membrane stiffness of the sheet stretched along the corrugation: Xia uses
A = E t/(1 - nu^2) (``membrane="plane-strain"``); the refined model (Ye et al. 2014; periodic
unit-cell FE) lets the strip contract freely, A_m = E t (``membrane="uniaxial"``).

Units: any consistent set; with E in MPa and lengths in mm, A is in N/mm and D in N mm.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

from corrugate.geometry.profile import Profile, ProfileIntegrals
from corrugate.mechanics.moduli import Moduli

__all__ = ["PlateStiffness", "Profile", "ProfileIntegrals", "equivalent_plate", "plate_moduli"]

Membrane = Literal["plane-strain", "uniaxial"]


@dataclass(frozen=True, slots=True)
class PlateStiffness:
    """Equivalent orthotropic plate: A (N/mm) and D (N mm) with x across the corrugation."""

    A11: float
    A12: float
    A22: float
    A66: float
    D11: float
    D12: float
    D22: float
    D66: float


def equivalent_plate(
    profile: Profile, E: float, nu: float, t: float, membrane: Membrane = "plane-strain"
) -> PlateStiffness:
    """A and D of the equivalent plate of ``profile`` in a sheet (E MPa, nu, t mm); Xia (2012)."""
    g = profile.integrals()
    A = E * t / (1 - nu**2)
    D = E * t**3 / (12 * (1 - nu**2))
    A66s = E * t / (2 * (1 + nu))
    D66s = E * t**3 / (24 * (1 + nu))
    A11 = 2 * g.c / (g.I1 / A + g.I2 / D)
    Am = A if membrane == "plane-strain" else E * t
    D11 = g.c / g.l * D
    return PlateStiffness(
        A11=A11,
        A12=nu * A11,
        A22=nu**2 * A11 + g.l / g.c * E * t,
        A66=g.c / g.l * A66s,
        D11=D11,
        D12=nu * D11,
        D22=(g.I2 * Am + g.I1 * D) / (2 * g.c),
        D66=g.l / g.c * D66s,
    )


def plate_moduli(plate: PlateStiffness, t: float) -> Moduli:
    """The four equivalent moduli (MPa) of a plate of thickness t (mm); paper eqs. E_c and E_b.

    Ecx = (A11 A22 - A12^2)/(t A22), Ecy = (A11 A22 - A12^2)/(t A11),
    Ebx = 12 (D11 D22 - D12^2)/(t^3 D22), Eby = 12 (D11 D22 - D12^2)/(t^3 D11).
    """
    import numpy as np

    detA = plate.A11 * plate.A22 - plate.A12**2
    detD = plate.D11 * plate.D22 - plate.D12**2
    return Moduli(
        np.asarray(detA / (t * plate.A22)),
        np.asarray(detA / (t * plate.A11)),
        np.asarray(12 * detD / (t**3 * plate.D22)),
        np.asarray(12 * detD / (t**3 * plate.D11)),
    )
