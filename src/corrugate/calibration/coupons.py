"""The coupons of a calibration kit, sized for the sheet's datasheet modulus, and their parts.

Two flat strips (one along the sheet's x, the roll direction when the sheet is laid with its roll
along the cutter's x, one across it) are held at a table edge under a book and sag under their
own weight, then with coins taped at the tip (:mod:`corrugate.calibration.elastica`). One
zig-zag strip hangs from a clip and is pulled along its chords by coins in a bag
(:mod:`corrugate.calibration.crease`). The free length of the flat strips and the number of coins
are chosen so that the sag or extension the datasheet E predicts lies in 5-50 mm, what a ruler
reads to a few per cent (docs/calibration.md section 2). Lengths in mm, masses in g, E in MPa.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from corrugate.calibration.crease import compliance
from corrugate.calibration.elastica import Anticlastic, drop_ratio, rigidity
from corrugate.core.errors import InputError
from corrugate.core.parameters import PARAMETERS
from corrugate.fabrication.model import Line, Part, Role
from corrugate.materials.library import Material

#: The option a kit's sheet thickness is given by (the parameter table's spelling).
THICKNESS = PARAMETERS["thickness"].flag

__all__ = [
    "GRAVITY",
    "CreaseCoupon",
    "FlatCoupon",
    "Kit",
    "design_kit",
    "expected_sag",
    "strip_weight",
]

#: Standard gravity in N per g (the weight of 1 g, N).
GRAVITY = 9.80665e-3
#: The sag or extension a ruler reads well (mm): the kit aims inside this range.
TARGET = (5.0, 50.0)
#: The strip length held under the book (mm).
CLAMP = 40.0
#: Width of the flat strips and of the crease strip (mm).
STRIP_WIDTH = 20.0
#: The crease strip: developed facet width (mm), creases, the angle it is folded to (deg), tab (mm).
FACET = 12.0
CREASES = 9
FOLD_ANGLE = 90.0
TAB = 18.0
#: Diameter of the hanging holes in the crease strip's tabs (mm) and their distance from its ends.
HOLE = 4.0
HOLE_INSET = 7.0
#: The crease stiffness the coin counts are sized for: the sheet's bending stiffness per unit
#: width D = E t^3 / (12 (1 - nu^2)) (N mm) over this length (mm), a crease as compliant as a facet of this
#: width bent by end moments (docs/calibration.md section 4).
SIZING_LENGTH = 12.0
#: The most coins the crease strip's bag is loaded with.
MAX_COINS = 30


def strip_weight(material: Material, t: float, b: float) -> float:
    """The weight per unit length q (N/mm) of a strip of width ``b`` (mm) and thickness ``t``."""
    return material.density * b * t * GRAVITY


def expected_sag(E: float, material: Material, t: float, b: float, L: float, tip_g: float) -> float:
    """The tip's drop (mm) of a strip of free length ``L`` (mm) under its weight and ``tip_g``
    grams at its tip, for modulus ``E`` (MPa): the elastica with the strip's anticlastic moment
    law (:class:`~corrugate.calibration.elastica.Anticlastic`)."""
    EI = rigidity(E, material.nu, b, t)
    q = strip_weight(material, t, b)
    law = Anticlastic.for_strip(b, t, L, material.nu)
    return L * drop_ratio(q * L**3 / EI, tip_g * GRAVITY * L**2 / EI, law)


@dataclass(frozen=True, slots=True)
class FlatCoupon:
    """A flat strip: its ``name``, ``direction`` (``along`` the sheet's x or ``across``),
    ``width`` and ``length`` (mm), its free length beyond the table edge alone (``overhang``, mm)
    and with the coins on its tip (``coin_overhang``; ``coins`` of ``coin_g`` grams each) and
    the sags the datasheet E predicts there (mm)."""

    name: str
    direction: str
    width: float
    length: float
    overhang: float
    coin_overhang: float
    coins: int
    coin_g: float
    sag_alone: float
    sag_coins: float


@dataclass(frozen=True, slots=True)
class CreaseCoupon:
    """The zig-zag strip: its ``name``, ``width`` (mm, the creases' length), ``facet`` (mm,
    developed), ``creases``, the ``angle`` to fold it to (deg), ``tab`` (mm), the coin counts it
    is loaded with and the extensions (mm) the datasheet E predicts for each with rigid creases
    (``rigid``) and with creases of stiffness D / :data:`SIZING_LENGTH` (``soft``)."""

    name: str
    width: float
    facet: float
    creases: int
    angle: float
    tab: float
    coins: tuple[int, ...]
    coin_g: float
    rigid: tuple[float, ...]
    soft: tuple[float, ...]

    @property
    def length(self) -> float:
        """The flat length (mm): two tabs and ``creases`` facets."""
        return 2 * self.tab + self.creases * self.facet


@dataclass(frozen=True, slots=True)
class Kit:
    """A kit: the sheet (``material``, ``t`` in mm), the cutter's usable length (mm) and the
    coupons."""

    material: Material
    t: float
    coin_g: float
    flat: tuple[FlatCoupon, ...]
    crease: CreaseCoupon

    def parts(self) -> tuple[Part, ...]:
        """The coupons as parts to cut (flat strips along their direction, creases drawn)."""
        return (*(_flat_part(c) for c in self.flat), _crease_part(self.crease))


def _closest(sags: list[float], target: float) -> int:
    return int(np.argmin([abs(math.log(max(x, 1e-9) / target)) for x in sags]))


def _flat_size(
    material: Material, t: float, b: float, longest: float, coin_g: float
) -> tuple[float, float, int]:
    """The free length (mm) whose self-weight sag is closest to 15 mm within (30 mm,
    ``longest``); the fewest coins (1-10) that sag at least 10 mm at that length, and the free
    length at most that one (from 40 mm: a coin is about 20 mm across) whose sag with them is nearest 0.4 times it (where the
    sag still follows 1/E; at least 8 mm when it can be)."""
    E = material.E
    try:
        grid = [float(x) for x in np.arange(30.0, longest + 1e-9, 5.0)]
        L1 = grid[_closest([expected_sag(E, material, t, b, L, 0.0) for L in grid], 15.0)]
        n = next(
            (k for k in range(1, 11) if expected_sag(E, material, t, b, L1, k * coin_g) >= 10.0),
            10,
        )
        short = [float(x) for x in np.arange(min(40.0, L1), L1 + 1e-9, 5.0)]
        sags = [expected_sag(E, material, t, b, L, n * coin_g) for L in short]
        # the most informative: w / L near 0.4 (the sag still ~ 1/E), w >= 8 mm if it can be
        score = [
            abs(math.log(w / (0.4 * L))) + (5.0 if w < 8.0 else 0.0)
            for w, L in zip(sags, short, strict=True)
        ]
        L2 = short[int(np.argmin(score))]
    except InputError:
        raise InputError(
            THICKNESS,
            f"{t:g} mm",
            f"a sheet stiff enough for a 30 mm strip not to hang down (E t^2 of {material.id})",
            reason="is too flexible to calibrate with this kit",
        ) from None
    return L1, L2, n


def design_kit(material: Material, t: float, usable: float, coin_g: float = 5.0) -> Kit:
    """The kit for ``material`` at thickness ``t`` (mm) whose strips are at most ``usable`` (mm)
    long, loaded with coins of ``coin_g`` grams; :class:`InputError` naming
    ``--thickness`` or ``--coin`` when no coupon can be sized."""
    if not 0.0 < coin_g <= 50.0:
        raise InputError("--coin", f"{coin_g:g} g", "0 < coin <= 50 g")
    longest = usable - CLAMP
    if longest < 60.0:
        raise InputError(
            PARAMETERS["cutter"].flag,
            f"{usable:.0f} mm",
            "a cutter whose strips may be >= 100 mm long",
        )
    b = STRIP_WIDTH
    L1, L2, n = _flat_size(material, t, b, longest, coin_g)
    alone = expected_sag(material.E, material, t, b, L1, 0.0)
    withc = expected_sag(material.E, material, t, b, L2, n * coin_g)
    if max(alone, withc) < TARGET[0]:
        raise InputError(
            THICKNESS,
            f"{t:g} mm",
            f"a sheet whose {L1:.0f} mm strip sags >= {TARGET[0]:g} mm under 10 coins of "
            f"{coin_g:g} g (it sags {withc:.1f} mm): a thinner sheet or heavier coins",
            reason="is too stiff to calibrate with this kit",
        )
    flats = tuple(
        FlatCoupon(name, d, b, L1 + CLAMP, L1, L2, n, coin_g, alone, withc)
        for name, d in (("F1", "along"), ("F2", "across"))
    )
    k_guess = rigidity(material.E, material.nu, 1.0, t) / SIZING_LENGTH
    coins = _crease_coins(material, t, coin_g, k_guess)
    rigid, soft = (
        tuple(
            n
            * coin_g
            * GRAVITY
            * compliance(k, material.E, t, b, FACET, FOLD_ANGLE, CREASES, material.nu)
            for n in coins
        )
        for k in (math.inf, k_guess)
    )
    crease = CreaseCoupon("C1", b, FACET, CREASES, FOLD_ANGLE, TAB, coins, coin_g, rigid, soft)
    return Kit(material, t, coin_g, flats, crease)


def _crease_coins(material: Material, t: float, coin_g: float, k: float) -> tuple[int, ...]:
    """Three coin counts n, 2n, 3n: 3n the most (up to 30) whose extension with creases of
    stiffness ``k`` stays below 50 mm and a third of the strip's chord (n at least 1)."""
    C = compliance(k, material.E, t, STRIP_WIDTH, FACET, FOLD_ANGLE, CREASES, material.nu)
    chord = CREASES * FACET * math.sin(math.radians(FOLD_ANGLE) / 2)
    limit = min(TARGET[1], chord / 3)
    top = max((m for m in range(1, MAX_COINS + 1) if m * coin_g * GRAVITY * C <= limit), default=1)
    n = max(1, top // 3)
    return (n, 2 * n, 3 * n)


def _rectangle(w: float, h: float) -> tuple[tuple[float, float], ...]:
    return ((0.0, 0.0), (w, 0.0), (w, h), (0.0, h))


def _circle(x: float, y: float, r: float, n: int = 24) -> tuple[tuple[float, float], ...]:
    return tuple(
        (x + r * math.cos(2 * math.pi * i / n), y + r * math.sin(2 * math.pi * i / n))
        for i in range(n)
    )


def _flat_part(c: FlatCoupon) -> Part:
    """The strip, long along x (``along``) or y (``across``), with a mark across it at each
    table-edge position (``overhang`` and ``coin_overhang`` from its tip at x or y = 0)."""
    at = sorted({c.overhang, c.coin_overhang})
    if c.direction == "along":
        outline = _rectangle(c.length, c.width)
        marks = tuple(Line((x, 0.0), (x, c.width), Role.MARK) for x in at)
    else:
        outline = _rectangle(c.width, c.length)
        marks = tuple(Line((0.0, y), (c.width, y), Role.MARK) for y in at)
    return Part(c.name, f"{c.name} {c.direction}", outline, marks, kind="coupon")


def _crease_part(c: CreaseCoupon) -> Part:
    """The zig-zag strip along x: tab, half facet, ``creases`` creases a facet apart (mountain
    and valley in turn, folded to ``angle``), half facet, tab; a tab crease at each end (folded
    half as far) keeps the tab on the chord line; a hole in each tab."""
    fold = 180.0 - c.angle
    lines = [Line((c.tab, 0.0), (c.tab, c.width), Role.MOUNTAIN, fold / 2)]
    for i in range(c.creases):
        x = c.tab + (i + 0.5) * c.facet
        role = Role.VALLEY if i % 2 == 0 else Role.MOUNTAIN
        lines.append(Line((x, 0.0), (x, c.width), role, fold))
    end = c.tab + c.creases * c.facet
    last = Role.MOUNTAIN if c.creases % 2 == 0 else Role.VALLEY
    lines.append(Line((end, 0.0), (end, c.width), last, fold / 2))
    holes = (
        _circle(HOLE_INSET, c.width / 2, HOLE / 2),
        _circle(c.length - HOLE_INSET, c.width / 2, HOLE / 2),
    )
    return Part(
        c.name,
        c.name,
        _rectangle(c.length, c.width),
        tuple(lines),
        holes,
        kind="coupon",
    )
