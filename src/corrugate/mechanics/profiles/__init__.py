"""Xia's general equivalent-plate theory for corrugation profiles, and the profiles themselves.

A profile is anything that reports its :class:`~corrugate.mechanics.profiles.xia.ProfileIntegrals` (half
period, developed length and the two integrals of Xia et al. 2012); a new profile (sinusoidal,
curved) is a new small module implementing :class:`~corrugate.mechanics.profiles.xia.Profile`.
"""

from corrugate.mechanics.profiles.trapezoid import Trapezoid
from corrugate.mechanics.profiles.xia import (
    PlateStiffness,
    Profile,
    ProfileIntegrals,
    equivalent_plate,
    plate_moduli,
)
from corrugate.mechanics.profiles.zigzag import ZigZag

__all__ = [
    "PlateStiffness",
    "Profile",
    "ProfileIntegrals",
    "Trapezoid",
    "ZigZag",
    "equivalent_plate",
    "plate_moduli",
]
