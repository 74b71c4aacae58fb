"""The cross-section of a corrugation: one object that every model asks for its geometry.

A :class:`Profile` is what a layer's fold makes of its flat sheet, repeated once per facet
(docs/theory.md section 2): the plan length of one facet across the creases (``pitch``, mm), the
depth of the corrugation crease line to crease line (``height``, mm), the flat length one facet
takes of the sheet (``developed``, mm, so the blank is stretched by ``developed / pitch`` across the
creases), the folded extent of n creases, (n + 1) pitch (:meth:`Profile.extent`), the flat blank's
width (n + 1) developed (:meth:`Profile.flat_width`), and the integrals of Xia, Friswell and
Saavedra Flores (2012) that give any profile's equivalent plate (:class:`ProfileIntegrals`,
docs/theory.md section 3.1; :func:`corrugate.mechanics.profiles.equivalent_plate`).

:class:`ZigZag` is the profile of every design today: facets of flat width W folded to the interior
angle alpha, with s = sin(alpha/2), c = cos(alpha/2), pitch p = W s, height h = W c. Its formulas
are written once, here, with ``+ - * /`` and ``np.sin``/``np.cos`` only, so the same code runs on
Python floats, NumPy arrays and the solver's intervals (:mod:`corrugate.solver.interval`: it has
``sin``, ``cos`` and ``__array_ufunc__``; this module does not import it). The layer
(:class:`corrugate.geometry.layer.Layer`), the moduli, the strength formulas, the vectorised
evaluator and the warnings build their zig-zag here; a layer, ``analyze`` and the solver build
their profile through :class:`ProfileKind` (the zig-zag unless another designable profile is
named), and ask it for pitch, height, developed width, :attr:`Profile.plan_ratio` and
:attr:`Profile.web2` (the springs) and its integrals (the moduli of another profile).

The half angle: alpha (deg) x pi/360, radians(alpha) / 2 and 0.5 radians(alpha) are the same
double for every normal alpha (pi/360 and pi/180 round to doubles a factor 2 apart, and halving
is exact), so :meth:`ZigZag.of` and :meth:`ZigZag.of_float` differ only in who computes sin and
cos: NumPy (arrays, intervals) or :mod:`math` (Python floats out, for one layer's properties).

Profiles are registered by name (:func:`register_profile`, :func:`get_profile`); ``zig-zag`` is
the default and the only built-in one. The trapezoid of Xia's Table 5
(:class:`corrugate.mechanics.profiles.Trapezoid`) implements the same protocol; the tests register
it and get Table 5's plate through the registry (tests/geometry/test_profile.py,
tests/mechanics/test_profiles.py); the designable trapezoid
(:class:`corrugate.mechanics.profiles.FlatCrest`) is registered by tests/solver/test_profile_design.py,
which analyses and designs with it. A profile's moduli: :func:`corrugate.mechanics.profiles.profile_moduli`.
"""

from __future__ import annotations

import math
import threading
from dataclasses import dataclass
from typing import Any, Final, Protocol, runtime_checkable

import numpy as np

from corrugate.core.errors import InputError, UnknownNameError

__all__ = [
    "DEFAULT_PROFILE",
    "ZIGZAG",
    "Profile",
    "ProfileIntegrals",
    "ProfileKind",
    "ZigZag",
    "get_profile",
    "profile_names",
    "register_profile",
    "unregister_profile",
]

#: The profile of a layer unless another is named.
DEFAULT_PROFILE: Final[str] = "zig-zag"

#: pi / 360: degrees to the half angle in radians, alpha (deg) x pi/360 = radians(alpha) / 2.
HALF_ANGLE_PER_DEG: Final[float] = np.pi / 360.0


@dataclass(frozen=True, slots=True)
class ProfileIntegrals:
    """Geometry a profile contributes to Xia's equivalent plate (lengths in mm).

    ``c``: half period; ``l``: developed length of a half period; ``I1``: integral of
    cos^2(theta) over the developed length of one period (mm); ``I2``: integral of z^2 over the
    developed length of one period (mm^3), z measured from the mid-plane of the profile
    (Xia et al. 2012; docs/theory.md section 3.1).
    """

    c: float
    l: float
    I1: float
    I2: float


@runtime_checkable
class Profile(Protocol):
    """A corrugation's cross-section, one repeat unit at a time: the part of the section that a
    layer of n creases repeats n + 1 times (a facet of the zig-zag, a half period of the
    trapezoid).

    Values may be floats, arrays or intervals, whatever the profile was built from; lengths in mm.
    """

    @property
    def pitch(self) -> Any:
        """Plan length of one repeat unit across the creases (mm)."""
        ...

    @property
    def height(self) -> Any:
        """Depth of the corrugation, crease line to crease line (mm)."""
        ...

    @property
    def developed(self) -> Any:
        """Flat length of sheet one repeat unit takes across the creases (mm)."""
        ...

    @property
    def plan_ratio(self) -> Any:
        """pitch / developed: the in-plane shear A66 = G t pitch/developed and the twisting
        D66 = G t^3 / 12 x developed/pitch per unit width (Xia et al. 2012, c/l and l/c;
        sin(alpha/2) for the zig-zag)."""
        ...

    @property
    def web2(self) -> Any:
        """The mean of (dz/ds)^2 over the developed length of a repeat unit: the share of the
        sheet's shear stiffness G t that carries a shear load across the depth, per developed
        length (cos^2(alpha/2) for the zig-zag; docs/load_cases.md section 2)."""
        ...

    def extent(self, n: Any) -> Any:
        """Folded extent of n + 1 repeat units, (n + 1) pitch (mm)."""
        ...

    def flat_width(self, n: Any) -> Any:
        """Flat blank width of n + 1 repeat units, (n + 1) developed (mm)."""
        ...

    def integrals(self) -> ProfileIntegrals:
        """Half period, developed half length and Xia's two integrals over one period."""
        ...


@dataclass(frozen=True, slots=True)
class ZigZag:
    """The zig-zag (triangular) profile: facets of flat width ``W`` (mm) meeting at the interior
    angle alpha, given by ``s`` = sin(alpha/2) and ``c`` = cos(alpha/2) (docs/theory.md section 2).

    Build it with :meth:`of` (alpha in degrees; arrays, intervals), :meth:`of_float` (one layer:
    Python floats) or :meth:`of_half` (alpha/2 in radians already). Every property is one
    expression in W, s and c, in the order the models have always computed it.
    """

    W: Any
    s: Any
    c: Any

    @classmethod
    def of(cls, W: Any, alpha_deg: Any) -> ZigZag:
        """From ``alpha_deg`` (deg; float, array or interval): the half angle alpha x pi/360,
        then ``np.sin`` and ``np.cos`` of it."""
        return cls.of_half(W, alpha_deg * HALF_ANGLE_PER_DEG)

    @classmethod
    def of_half(cls, W: Any, half: Any) -> ZigZag:
        """From the half angle ``half`` = alpha/2 (rad; float, array or interval)."""
        return cls(W, np.sin(half), np.cos(half))

    @classmethod
    def of_float(cls, W: float, alpha_deg: float) -> ZigZag:
        """One layer's zig-zag in Python floats: ``math.sin`` and ``math.cos`` of
        radians(alpha) / 2."""
        half = math.radians(alpha_deg) / 2
        return cls(W, math.sin(half), math.cos(half))

    @property
    def pitch(self) -> Any:
        """p = W sin(alpha/2) (mm)."""
        return self.W * self.s

    @property
    def height(self) -> Any:
        """h = W cos(alpha/2) (mm), crease line to crease line."""
        return self.W * self.c

    @property
    def developed(self) -> Any:
        """W (mm): a facet is flat."""
        return self.W

    @property
    def plan_ratio(self) -> Any:
        """p / W = s = sin(alpha/2)."""
        return self.s

    @property
    def web2(self) -> Any:
        """c^2 = cos^2(alpha/2): every facet is a web of slope cos(alpha/2)."""
        return self.c * self.c

    def extent(self, n: Any) -> Any:
        """(n + 1) p (mm), the folded extent of n creases."""
        return (n + 1) * self.pitch

    def flat_width(self, n: Any) -> Any:
        """(n + 1) W (mm), the flat blank across n creases."""
        return (n + 1) * self.W

    def section_depth2(self, t: Any) -> Any:
        """h^2 + t^2 s^2 (mm^2): a facet's second moment about mid-depth is W t / 12 times this
        (the rotated rectangle, W^3 t c^2 / 12 + W t^3 s^2 / 12; docs/theory.md section 9.2)."""
        h = self.height
        return h * h + t * t * self.s * self.s

    def integrals(self) -> ProfileIntegrals:
        """Xia's integrals of the zig-zag (two facets per period): half period c = W s, developed
        half length l = W, I1 = 2 W s^2, I2 = W^3 c^2 / 6 (amplitude W c / 2)."""
        W, s, c = self.W, self.s, self.c
        return ProfileIntegrals(c=W * s, l=W, I1=2 * W * s**2, I2=W**3 * c**2 / 6)


_lock = threading.Lock()
_PROFILES: dict[str, type[Any]] = {DEFAULT_PROFILE: ZigZag}


def register_profile(name: str, kind: type[Any]) -> type[Any]:
    """Add the profile class ``kind`` (instances satisfy :class:`Profile`) under ``name`` and
    return it; the name (case-insensitive) must be new."""
    key = name.strip().lower()
    with _lock:
        if key in _PROFILES:
            raise InputError(
                "profile",
                repr(name),
                f"a name not yet registered (taken by {_PROFILES[key].__name__})",
                reason="is already registered",
            )
        _PROFILES[key] = kind
    return kind


def unregister_profile(name: str) -> None:
    """Remove the profile ``name`` (e.g. one a test registered); the default stays."""
    key = name.strip().lower()
    if key == DEFAULT_PROFILE:
        raise InputError("profile", repr(name), "a profile other than the default")
    with _lock:
        _PROFILES.pop(key, None)


def get_profile(name: str = DEFAULT_PROFILE) -> type[Any]:
    """The profile class registered as ``name``; :class:`UnknownNameError` if there is none."""
    key = name.strip().lower()
    if key not in _PROFILES:
        raise UnknownNameError("profile", name, tuple(_PROFILES))
    return _PROFILES[key]


def profile_names() -> tuple[str, ...]:
    """The registered profiles' names, the default first."""
    return tuple(_PROFILES)


@dataclass(frozen=True, slots=True)
class ProfileKind:
    """Which profile a layer is folded to: a registered profile's ``name`` and its fixed
    ``params`` (e.g. a flat fraction), beside the layer's design variables W (mm) and alpha (deg).

    A *designable* profile class (one a layer, ``analyze`` and the solver can carry) has the
    zig-zag's three constructors with the extra parameters last: ``of(W, alpha_deg, *params)``
    (floats, arrays, intervals), ``of_half(W, alpha/2 in rad, *params)`` and
    ``of_float(W, alpha_deg, *params)`` (Python floats). The solver bounds its sizes and mass by
    their values at a box's corners, so its pitch must grow with W and alpha, its height grow
    with W and fall with alpha, and developed / pitch fall with alpha, as the zig-zag's do
    (docs/theory.md section 5); its moduli and springs are bounded by interval arithmetic of
    the same code (:func:`corrugate.mechanics.profiles.profile_moduli`).
    """

    name: str = DEFAULT_PROFILE
    params: tuple[float, ...] = ()

    def __post_init__(self) -> None:
        kind = get_profile(self.name)
        missing = [m for m in ("of", "of_half", "of_float") if not hasattr(kind, m)]
        if missing:
            raise InputError(
                "profile",
                repr(self.name),
                "a designable profile (with of, of_half and of_float)",
                reason=f"has no {', '.join(missing)}",
            )
        object.__setattr__(self, "name", self.name.strip().lower())
        object.__setattr__(self, "params", tuple(float(v) for v in self.params))

    @property
    def is_default(self) -> bool:
        """Whether this is the default profile (the zig-zag) with no parameters."""
        return self.name == DEFAULT_PROFILE and not self.params

    def of(self, W: Any, alpha_deg: Any) -> Any:
        """The profile at facet width ``W`` (mm) and fold angle ``alpha_deg`` (deg); floats,
        arrays or intervals."""
        return get_profile(self.name).of(W, alpha_deg, *self.params)

    def of_half(self, W: Any, half: Any) -> Any:
        """The profile from the half angle ``half`` = alpha/2 (rad)."""
        return get_profile(self.name).of_half(W, half, *self.params)

    def of_float(self, W: float, alpha_deg: float) -> Any:
        """The profile of one layer in Python floats."""
        return get_profile(self.name).of_float(W, alpha_deg, *self.params)


#: The zig-zag, every layer's profile unless another is named.
ZIGZAG: Final[ProfileKind] = ProfileKind()
