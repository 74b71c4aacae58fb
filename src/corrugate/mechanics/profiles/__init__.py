"""Any corrugation profile's equivalent plate: Xia's general theory (:mod:`.xia`), the seam through
which a profile other than the zig-zag gets its moduli, and the trapezoid of Xia's worked example
(:mod:`.trapezoid`).

A profile is a :class:`corrugate.geometry.profile.Profile` (registered by name there, ``zig-zag``
the default): it reports its pitch, height, developed length and its
:class:`~corrugate.geometry.profile.ProfileIntegrals` (half period, developed length and the two
integrals of Xia et al. 2012). :func:`equivalent_plate` turns those into the plate's A and D,
:func:`plate_moduli` into the four moduli, and :func:`profile_moduli` gives any profile's moduli
in a named variant: the zig-zag's closed forms of :mod:`corrugate.mechanics.moduli` (what every
design uses), another profile's from the general theory. The tests check the published trapezoidal
benchmark (Xia et al. 2012, Table 5) through the registry, and that the zig-zag in the general
theory reproduces the ``xia`` variant's four moduli and the ``refined`` variant's Ecx, Ecy and Eby
(its Ebx keeps Xia's closed form) (tests/mechanics/test_profiles.py,
tests/geometry/test_profile.py).

A designable profile (one with the zig-zag's constructors from W and alpha, such as
:class:`FlatCrest`) is carried by a layer (:class:`corrugate.geometry.layer.Layer`'s
``profile_kind``), analysed and designed by the solver through this seam; its pattern generator
and FE mesh are not (fabrication and the FE refuse it; docs/architecture.md section 3).
"""

from typing import TYPE_CHECKING as _TYPE_CHECKING

from corrugate.core.lazy import lazy_names as _lazy_names
from corrugate.geometry.profile import Profile, ProfileIntegrals, ZigZag
from corrugate.mechanics.profiles.xia import (
    MEMBRANES,
    PlateStiffness,
    equivalent_plate,
    general_moduli,
    plate_moduli,
    profile_moduli,
)

if _TYPE_CHECKING:
    from corrugate.mechanics.profiles.trapezoid import FlatCrest, Trapezoid

__all__ = [
    "MEMBRANES",
    "FlatCrest",
    "PlateStiffness",
    "Profile",
    "ProfileIntegrals",
    "Trapezoid",
    "ZigZag",
    "equivalent_plate",
    "general_moduli",
    "plate_moduli",
    "profile_moduli",
]

#: The profiles other than the zig-zag (:mod:`.trapezoid`), imported when one is first used (PEP
#: 562): every design imports this package for :func:`profile_moduli`, and none of the shipped
#: examples designs another profile (issue 39).
_LAZY = {"FlatCrest": "trapezoid", "Trapezoid": "trapezoid"}


__getattr__ = _lazy_names(__name__, {k: f".{v}" for k, v in _LAZY.items()}, globals())


def __dir__() -> list[str]:
    """The module's names, the public API (:data:`__all__`) included before its first use."""
    return sorted({*globals(), *__all__})
