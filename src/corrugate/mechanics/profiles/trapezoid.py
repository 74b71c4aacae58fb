"""Trapezoidal corrugation profiles (Xia et al. 2012, section 4 and Table 5).

:class:`Trapezoid`: a :class:`corrugate.geometry.profile.Profile` whose repeat unit is a half
period: one incline and one flat part, of plan length c and developed length l (docs/theory.md
section 3.1), given as Xia gives it (c, f, theta). :class:`FlatCrest`: the same shape designed as
the zig-zag is, from the facet width W (mm) and the fold angle alpha (deg) of its inclines with a
fixed flat fraction, so a layer, ``analyze`` and the solver can carry it
(:class:`corrugate.geometry.profile.ProfileKind`). No built-in design uses either;
tests/geometry/test_profile.py registers the first to show the seam, tests/solver/test_profile_design.py
the second to design with it."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from corrugate.core.errors import InputError
from corrugate.geometry.profile import ProfileIntegrals

__all__ = ["FlatCrest", "Trapezoid"]


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

    @property
    def plan_ratio(self) -> float:
        """c / l: pitch over developed length."""
        return self.c / self.developed

    @property
    def web2(self) -> float:
        """Mean (dz/ds)^2 over the developed half period: the incline 2 f / sin(theta) at
        slope sin(theta), the flat part level: 2 f sin(theta) / l."""
        return 2 * self.f * math.sin(math.radians(self.theta_deg)) / self.developed

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


@dataclass(frozen=True, slots=True)
class FlatCrest:
    """A trapezoid designed as the zig-zag is: each repeat unit (a half period) is one incline of
    flat width ``W`` (mm) standing at the zig-zag's half angle, s = sin(alpha/2),
    c = cos(alpha/2) (plan W s, rise W c), and one level flat part of width ``flat`` x W at the
    crest or the trough (``flat`` >= 0, the flat fraction; 0 is the zig-zag). It is
    :class:`Trapezoid` (c = W (s + flat), f = W c / 2, theta = 90 deg - alpha/2) written with
    ``+ - *`` and ``np.sin``/``np.cos`` only, so floats, arrays and the solver's intervals alike
    (docs/theory.md section 3.1).

    Pitch W (s + flat) grows with W and alpha, height W c grows with W and falls with alpha,
    developed / pitch = (1 + flat) / (s + flat) falls with alpha: the corner bounds of the
    solver's sizes and mass hold (:class:`corrugate.geometry.profile.ProfileKind`).
    """

    W: Any
    s: Any
    c: Any
    flat: float = 0.0

    @classmethod
    def of(cls, W: Any, alpha_deg: Any, flat: float = 0.0) -> FlatCrest:
        """From ``alpha_deg`` (deg): the half angle alpha x pi/360, then sin and cos of it."""
        return cls.of_half(W, alpha_deg * (np.pi / 360.0), flat)

    @classmethod
    def of_half(cls, W: Any, half: Any, flat: float = 0.0) -> FlatCrest:
        """From the half angle ``half`` = alpha/2 (rad)."""
        return cls(W, np.sin(half), np.cos(half), flat)

    @classmethod
    def of_float(cls, W: float, alpha_deg: float, flat: float = 0.0) -> FlatCrest:
        """One layer in Python floats."""
        half = math.radians(alpha_deg) / 2
        return cls(W, math.sin(half), math.cos(half), flat)

    def __post_init__(self) -> None:
        if not (math.isfinite(self.flat) and self.flat >= 0):
            raise InputError("flat", self.flat, "a flat fraction >= 0")

    @property
    def pitch(self) -> Any:
        """W (s + flat) (mm): the incline's plan W s and the flat part."""
        return self.W * (self.s + self.flat)

    @property
    def height(self) -> Any:
        """W c (mm), the incline's rise, crest to trough."""
        return self.W * self.c

    @property
    def developed(self) -> Any:
        """W (1 + flat) (mm)."""
        return self.W * (1.0 + self.flat)

    @property
    def plan_ratio(self) -> Any:
        """(s + flat) / (1 + flat): pitch over developed."""
        return (self.s + self.flat) / (1.0 + self.flat)

    @property
    def web2(self) -> Any:
        """c^2 / (1 + flat): the incline (slope c) over the developed length, the flat level."""
        return self.c * self.c / (1.0 + self.flat)

    def extent(self, n: Any) -> Any:
        """(n + 1) pitch (mm)."""
        return (n + 1) * self.pitch

    def flat_width(self, n: Any) -> Any:
        """(n + 1) developed (mm)."""
        return (n + 1) * self.developed

    def integrals(self) -> ProfileIntegrals:
        """Xia's integrals over a period (two repeat units): half period c = W (s + flat),
        l = W (1 + flat), I1 = 2 W s^2 + 2 flat W (the level parts have cos = 1),
        I2 = W^3 c^2 / 6 + flat W^3 c^2 / 2 (the level parts at |z| = W c / 2)."""
        W, s, c, f = self.W, self.s, self.c, self.flat
        W3c2 = W * W * W * (c * c)
        return ProfileIntegrals(
            c=self.pitch,
            l=self.developed,
            I1=2.0 * W * (s * s) + 2.0 * f * W,
            I2=W3c2 / 6.0 + f * W3c2 / 2.0,
        )
