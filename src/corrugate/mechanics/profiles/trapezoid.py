"""Trapezoidal corrugation profile (Xia et al. 2012, section 4 and Table 5).

A :class:`corrugate.geometry.profile.Profile` whose repeat unit is a half period: one incline and
one flat part, of plan length c and developed length l (docs/theory.md section 3.1). No built-in
design uses it; tests/geometry/test_profile.py registers it to show the seam."""

from __future__ import annotations

import math
from dataclasses import dataclass

from corrugate.core.errors import InputError
from corrugate.geometry.profile import ProfileIntegrals

__all__ = ["Trapezoid"]


@dataclass(frozen=True, slots=True)
class Trapezoid:
    """Trapezoid of half period ``c`` (mm), amplitude ``f`` (mid-plane to crest, mm) and incline
    ``theta_deg`` of its sloped segments; the flat part of each half period is c - 2 f / tan(theta).

    With no flat part (c = 2 f / tan(theta)) it is the zig-zag.
    """

    c: float
    f: float
    theta_deg: float

    def __post_init__(self) -> None:
        if not self.c > 0:
            raise InputError("c", self.c, "c > 0 mm")
        if not self.f > 0:
            raise InputError("f", self.f, "f > 0 mm")
        if not 0 < self.theta_deg <= 90:
            raise InputError("theta", f"{self.theta_deg} deg", "0 < theta <= 90 deg")
        if self.flat < -1e-9 * self.c:
            raise InputError(
                "f",
                self.f,
                f"f <= c tan(theta) / 2 = {self.c * self.tan / 2:g} mm",
                reason="leaves a negative flat part",
            )

    @property
    def pitch(self) -> float:
        """Plan length of the repeat unit, the half period c (mm)."""
        return self.c

    @property
    def height(self) -> float:
        """Depth of the corrugation, crest to trough, 2 f (mm)."""
        return 2 * self.f

    @property
    def developed(self) -> float:
        """Developed length of a half period, l = 2 f / sin(theta) + flat (mm)."""
        return self.integrals().l

    def extent(self, n: float) -> float:
        """(n + 1) c (mm): the folded extent of n + 1 half periods."""
        return (n + 1) * self.pitch

    def flat_width(self, n: float) -> float:
        """(n + 1) l (mm): the flat blank of n + 1 half periods."""
        return (n + 1) * self.developed

    @property
    def tan(self) -> float:
        return math.tan(math.radians(self.theta_deg))

    @property
    def flat(self) -> float:
        """Length of the flat part of a half period, c - 2 f / tan(theta) (mm)."""
        return self.c - 2 * self.f / self.tan

    def integrals(self) -> ProfileIntegrals:
        """Xia's integrals: l = 2f/sin + flat, I1 = 4 f cos^2/sin + 2 flat,
        I2 = 4 f^3/(3 sin) + 2 f^2 flat (the flat part is at |z| = f)."""
        th = math.radians(self.theta_deg)
        sin, cos = math.sin(th), math.cos(th)
        flat = max(self.flat, 0.0)
        return ProfileIntegrals(
            c=self.c,
            l=2 * self.f / sin + flat,
            I1=4 * self.f * cos**2 / sin + 2 * flat,
            I2=4 * self.f**3 / (3 * sin) + 2 * self.f**2 * flat,
        )
