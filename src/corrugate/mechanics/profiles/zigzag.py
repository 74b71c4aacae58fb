"""Zig-zag (triangular) corrugation, the profile of the paper, in Xia's general theory."""

from __future__ import annotations

import math
from dataclasses import dataclass

from corrugate.mechanics.profiles.xia import ProfileIntegrals

__all__ = ["ZigZag"]


@dataclass(frozen=True, slots=True)
class ZigZag:
    """Facets of flat width ``W`` (mm) meeting at interior angle ``alpha_deg``.

    Half period c = W sin(alpha/2), amplitude f = W cos(alpha/2)/2, developed half length l = W,
    I1 = 2 W sin^2(alpha/2), I2 = W^3 cos^2(alpha/2)/6 (two facets per period).
    """

    W: float
    alpha_deg: float

    def integrals(self) -> ProfileIntegrals:
        """Xia's integrals of the zig-zag (see class docstring)."""
        half = math.radians(self.alpha_deg) / 2
        s, c = math.sin(half), math.cos(half)
        return ProfileIntegrals(
            c=self.W * s, l=self.W, I1=2 * self.W * s**2, I2=self.W**3 * c**2 / 6
        )
