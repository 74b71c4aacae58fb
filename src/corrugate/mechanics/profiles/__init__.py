"""Xia's general equivalent-plate theory for corrugation profiles, and the profiles themselves:
an independent **cross-check** of the closed-form moduli, not a seam the models use.

The stiffness models (:mod:`corrugate.mechanics.moduli`, the springs and the solver) use the
zig-zag's closed forms only; nothing in the package evaluates a profile. The tests use this
subpackage as a second method: the published trapezoidal benchmark (Xia et al. 2012, Table 5) and
the zig-zag special case, which reproduces the ``xia`` variant's four moduli and the ``refined``
variant's Ecx, Ecy and Eby (its Ebx keeps Xia's closed form)
(tests/mechanics/test_profiles.py). A profile is anything that reports its
:class:`~corrugate.mechanics.profiles.xia.ProfileIntegrals` (half period, developed length and the
two integrals of Xia et al. 2012). Making another profile (sinusoidal, trapezoidal) a model users
can design with would need its moduli in :mod:`corrugate.mechanics.moduli`'s table, interval bounds
for the solver and a pattern generator; none exists today.
"""

from corrugate.geometry.profile import Profile, ProfileIntegrals, ZigZag
from corrugate.mechanics.profiles.trapezoid import Trapezoid
from corrugate.mechanics.profiles.xia import (
    PlateStiffness,
    equivalent_plate,
    plate_moduli,
)

__all__ = [
    "PlateStiffness",
    "Profile",
    "ProfileIntegrals",
    "Trapezoid",
    "ZigZag",
    "equivalent_plate",
    "plate_moduli",
]
