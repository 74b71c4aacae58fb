"""The virtual experiment: readings a kit would give for a known sheet, with a ruler's error.

The sags of a kit's flat strips follow the elastica at a true E, the crease strip's length the
true angle and its extensions the zig-zag model at a true crease stiffness
(:mod:`corrugate.calibration.crease`); each reading gets an error uniform in +-``noise`` mm (a
ruler read by eye). Fitting them back (:func:`corrugate.calibration.fit.fit_measurements`) and
counting how often the 90 % interval holds the truth checks the fit and its intervals
(docs/calibration.md section 7; the suite runs a small study, ``benchmarks/calibration_coverage.py``
the full one). Lengths in mm, E in MPa, k in N mm/(rad mm).
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from corrugate.calibration.coupons import GRAVITY, Kit, expected_sag
from corrugate.calibration.crease import compliance
from corrugate.calibration.measurements import CreaseTest, FlatTest, Measurements
from corrugate.materials.library import Material

__all__ = ["measurements_toml", "virtual_measurements"]


@lru_cache(maxsize=64)
def _sag(E: float, mat: Material, t: float, b: float, L: float, tip_g: float) -> float:
    """:func:`~corrugate.calibration.coupons.expected_sag`, solved once per set-up (a study
    draws many trials of the same kit)."""
    return expected_sag(E, mat, t, b, L, tip_g)


def virtual_measurements(
    kit: Kit,
    E: float,
    k: float,
    angle: float,
    rng: np.random.Generator,
    *,
    repeats: int = 5,
    noise: float = 1.0,
    E_across: float | None = None,
) -> Measurements:
    """The readings of ``kit`` for a sheet of modulus ``E`` (``E_across`` across; None: the same)
    whose creases have stiffness ``k`` and take the angle ``angle`` (deg), each with an error
    uniform in +-``noise`` mm, ``repeats`` per set-up."""
    mat, t = kit.material, kit.t

    def read(true: float) -> tuple[float, ...]:
        return tuple(float(max(true + rng.uniform(-noise, noise), 0.0)) for _ in range(repeats))

    flat: list[FlatTest] = []
    for f in kit.flat:
        Ef = E if f.direction == "along" or E_across is None else E_across
        for L, n in ((f.overhang, 0), (f.coin_overhang, f.coins)):
            sag = _sag(Ef, mat, t, f.width, L, n * f.coin_g)
            flat.append(
                FlatTest(
                    f.name, f.direction, f.width, L, n * f.coin_g, read(sag), f"flat[{len(flat)}]"
                )
            )
    c = kit.crease
    length = c.creases * c.facet * math.sin(math.radians(angle) / 2)
    C = compliance(k, E, t, c.width, c.facet, angle, c.creases, mat.nu)
    crease = CreaseTest(
        c.name,
        c.width,
        c.facet,
        c.creases,
        c.angle,
        read(length),
        tuple(n * c.coin_g for n in c.coins),
        tuple(read(C * n * c.coin_g * GRAVITY) for n in c.coins),
    )
    return Measurements(mat, t, noise, f"virtual-{mat.id}", "", tuple(flat), crease)


def measurements_toml(m: Measurements) -> str:
    """The measurements file of ``m`` (readings to 0.1 mm), as ``calibrate fit`` reads it."""

    def nums(xs: tuple[float, ...]) -> str:
        return "[" + ", ".join(f"{x:.1f}" for x in xs) + "]"

    lines = [
        "[sheet]",
        f'material = "{m.material.id}"',
        f'thickness = "{m.t:g} mm"',
        f'ruler = "{m.ruler:g} mm"',
        f'name = "{m.name}"',
        f'date = "{m.date}"',
    ]
    for f in m.flat:
        lines += [
            "",
            "[[flat]]",
            f'coupon = "{f.coupon}"',
            f'direction = "{f.direction}"',
            f'width = "{f.width:g} mm"',
            f'overhang = "{f.overhang:g} mm"',
            f'tip_mass = "{f.tip_g:g} g"',
            f"sag = {nums(f.sags)}",
        ]
    c = m.crease
    if c is not None:
        lines += [
            "",
            "[crease]",
            f'coupon = "{c.coupon}"',
            f'width = "{c.width:g} mm"',
            f'facet = "{c.facet:g} mm"',
            f"creases = {c.creases}",
            f'folded_to = "{c.folded_to:g} deg"',
            f"length = {nums(c.lengths)}",
            "mass = [" + ", ".join(f'"{x:g} g"' for x in c.masses) + "]",
            "extension = [" + ", ".join(nums(e) for e in c.extensions) + "]",
        ]
    return "\n".join(lines) + "\n"
