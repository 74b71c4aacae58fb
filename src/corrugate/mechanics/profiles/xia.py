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
from typing import Any, Literal

from corrugate.core.errors import InputError
from corrugate.geometry.profile import Profile, ProfileIntegrals, ZigZag
from corrugate.mechanics.creases import creased_moduli, is_rigid
from corrugate.mechanics.moduli import Moduli, get_model

__all__ = [
    "MEMBRANES",
    "PlateStiffness",
    "Profile",
    "ProfileIntegrals",
    "equivalent_plate",
    "general_moduli",
    "plate_moduli",
    "profile_moduli",
]

Membrane = Literal["plane-strain", "uniaxial"]
#: The membrane stiffness along the corrugation of each moduli variant that has one in Xia's theory
#: (:mod:`corrugate.mechanics.moduli`); ``paper`` is the zig-zag's printed formulas only.
MEMBRANES: dict[str, Membrane] = {"xia": "plane-strain", "refined": "uniaxial"}


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


def general_moduli(
    profile: Profile, E: Any, nu: Any, t: Any, membrane: Membrane = "plane-strain"
) -> Moduli:
    """:func:`plate_moduli` of :func:`equivalent_plate`, reduced by hand so that floats, arrays
    and the solver's intervals (:mod:`corrugate.solver.interval`) alike give it without the
    cancellations of the determinants: with r = l / c, A12 = nu A11, A22 = nu^2 A11 + r E t and
    D12 = nu D11, A11 A22 - A12^2 = A11 r E t and D11 D22 - D12^2 = D11 (D22 - nu^2 D11), so

        Ecx = A11 r E / A22,  Ecy = r E,  Ebx = 12 D11 (D22 - nu^2 D11) / (t^3 D22),
        Eby = 12 (D22 - nu^2 D11) / t^3   (MPa, for E in MPa and t in mm).

    In interval arithmetic each is a sound enclosure (the repeated A11, D11, D22 make it wider
    than the exact range over a box, never narrower), and it closes on the value as the box
    shrinks."""
    g = profile.integrals()
    k = 1 - nu * nu
    A = E * t / k
    D = E * (t * t * t) / (12 * k)
    Am = A if membrane == "plane-strain" else E * t
    r = g.l / g.c
    A11 = 2 * g.c / (g.I1 / A + g.I2 / D)
    A22 = nu * nu * A11 + r * (E * t)
    D11 = D / r
    D22 = (g.I2 * Am + g.I1 * D) / (2 * g.c)
    rest = D22 - nu * nu * D11
    t3 = t * t * t
    return Moduli(A11 * r * E / A22, r * E, 12 * D11 * rest / (t3 * D22), 12 * rest / t3)


def profile_moduli(
    profile: Profile, E: Any, nu: Any, t: Any, model: str, flex: Any = 0.0
) -> Moduli:
    """The four moduli (MPa) of a sheet (E MPa, nu, t mm) folded to ``profile``, in the variant
    ``model``: the zig-zag's closed forms (:meth:`corrugate.mechanics.moduli.ModuliModel.of_profile`,
    the numbers ``analyze`` prints), any other profile's from Xia's general theory with the
    variant's membrane (:data:`MEMBRANES`; :func:`general_moduli`, docs/theory.md section 3.1);
    floats, arrays or intervals (the solver bounds a layer's moduli over boxes with it,
    :mod:`corrugate.solver.interval_springs`). The refined closed form
    keeps Xia's Ebx, so for the zig-zag the general theory's uniaxial Ebx is a little lower.

    ``flex`` = 1 / k (rad/N) puts a compliant crease of stiffness k (N mm/(rad mm)) at every
    crease of the zig-zag (:func:`corrugate.mechanics.creases.creased_moduli`; 0.0, rigid: the
    moduli above unchanged); another profile takes rigid creases only."""
    variant = get_model(model)
    if isinstance(profile, ZigZag):
        return creased_moduli(
            variant.of_profile(E, nu, t, profile), flex, t, profile.W, profile.s, profile.c
        )
    if not is_rigid(flex):
        raise InputError(
            "material.crease_stiffness",
            "finite",
            f"rigid creases (inf) for a {type(profile).__name__} profile",
            reason="is modelled for the zig-zag only",
        )
    if variant.name not in MEMBRANES:
        raise InputError(
            "model",
            repr(model),
            f"one of {', '.join(MEMBRANES)} for a {type(profile).__name__} profile",
            reason="has closed forms for the zig-zag only",
        )
    return general_moduli(profile, E, nu, t, MEMBRANES[variant.name])
