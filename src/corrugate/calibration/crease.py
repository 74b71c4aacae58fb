"""The single-layer zig-zag strip pulled along its chords: compliant creases and bending facets.

A strip of width b (mm, the creases' length) folded to a zig-zag of facets of developed width W
(mm) at the crease angle alpha (the layer's alpha, docs/theory.md section 2: pitch p = W sin(alpha/2),
height h = W cos(alpha/2)), with N creases, half a facet at each end and a flat tab beyond it on
the chord line through the mid-height of the zig-zag. A force F (N) along that line bends every
facet (moment F e at each crease, e = h / 2, falling linearly to zero at each facet's middle),
turns each crease, a rotational spring of stiffness k (N mm/(rad mm), per unit crease length,
k b for one crease), and stretches each facet. By virtual work (docs/calibration.md section 4) the
chord's extension is delta = C F with

    C = N e^2 / (k b) + N e^2 W / (3 E I) + N W sin^2(alpha/2) / (E b t),

where E (MPa) is the sheet's modulus, t (mm) its thickness and E I its rigidity as a plate,
E b t^3 / (12 (1 - nu^2)) (:func:`~corrugate.calibration.elastica.rigidity`): rigid creases are
k = inf. The
pitch the strip takes when folded and released fixes alpha (:func:`angle_from_length`).
"""

from __future__ import annotations

import math

from corrugate.calibration.elastica import rigidity

__all__ = ["angle_from_length", "compliance", "crease_stiffness"]


def compliance(
    k: float, E: float, t: float, b: float, W: float, alpha_deg: float, creases: int, nu: float
) -> float:
    """C = delta / F (mm/N) of the strip (module docstring); ``k`` in N mm/(rad mm) (inf: rigid
    creases), E in MPa, t, b, W in mm, alpha in deg, nu Poisson's ratio."""
    half = math.radians(alpha_deg) / 2
    e = W * math.cos(half) / 2
    EI = rigidity(E, nu, b, t)
    hinge = 0.0 if math.isinf(k) else creases * e**2 / (k * b)
    return hinge + creases * e**2 * W / (3 * EI) + creases * W * math.sin(half) ** 2 / (E * b * t)


def crease_stiffness(
    C: float, E: float, t: float, b: float, W: float, alpha_deg: float, creases: int, nu: float
) -> float:
    """The crease stiffness k (N mm/(rad mm)) that gives the compliance ``C`` (mm/N), the inverse
    of :func:`compliance`; inf when C is at or below the compliance of rigid creases."""
    rigid = compliance(math.inf, E, t, b, W, alpha_deg, creases, nu)
    e = W * math.cos(math.radians(alpha_deg) / 2) / 2
    if rigid >= C:
        return math.inf
    return creases * e**2 / (b * (C - rigid))


def angle_from_length(length: float, W: float, creases: int) -> float:
    """The crease angle alpha (deg) of a strip of ``creases`` creases and facets of developed
    width W (mm) whose length from the first half facet's end to the last's is ``length`` (mm):
    length = creases W sin(alpha/2); nan when the length is not in (0, creases W)."""
    ratio = length / (creases * W)
    if not 0.0 < ratio < 1.0:
        return math.nan
    return math.degrees(2 * math.asin(ratio))
