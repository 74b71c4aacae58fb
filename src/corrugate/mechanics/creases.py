"""Compliant creases: a rotational spring at every crease, in series with the facets.

A crease of a folded sheet is not a rigid hinge: it turns by M / k under a moment M per unit
crease length, with k (N mm/(rad mm)) the crease's rotational stiffness per unit length
(docs/calibration.md section 4 measures it; docs/offaxis.md, "Compliant creases", derives what
follows). k = inf is the rigid crease every model assumed before; :func:`flexibility` is 1 / k
(rad/N), 0 for a rigid crease.

Chordwise the zig-zag carries its load through the creases, one per pitch p = W s (s =
sin(alpha/2), c = cos(alpha/2), W the facet's developed width, t the sheet's thickness, mm):

* **in-plane (Ecx)**: a chordwise force N per unit width acts on the mid-height line, so a
  crease carries the moment N h / 2, h = W c, and turns by N h / (2 k); its two facets then open
  the chord by (h / 2) times that: N W^2 c^2 / (4 k) per pitch, a strain N W c^2 / (4 k s) over
  p. In series with the facets' own compliance 1 / (Ecx t):

      1 / Ecx_k = 1 / Ecx + t W c^2 / (4 k s)                                     (MPa)

  the hinge term of the zig-zag strip of :func:`corrugate.calibration.crease.compliance`, per
  pitch and per unit width;
* **bending (Ebx)**: a chordwise moment M per unit width passes every crease whole, each
  turning by M / k, a curvature M / (k p) added to the facets' M / D_C, D_C = Ebx t^3 / 12:

      1 / Ebx_k = 1 / Ebx + t^3 / (12 k W s)                                      (MPa)

Along the creases (Ecy, Eby) no crease turns, and the in-plane shear and twisting springs of
the free-panel model (:func:`corrugate.mechanics.offaxis.shear_springs`) are left rigid: a
shear flow along the developed width and a twist of the developed sheet bend no crease to
first order. Everything downstream of Ecx and Ebx (the layers' K_C and D_C, the frame rule, the
free panel's K(eta) and D(eta), the wheel's factor times K(eta)) follows.

Floats, arrays and the solver's intervals alike; a flexibility of exactly 0.0 returns the
moduli unchanged (the same objects), so a rigid crease gives today's numbers bit for bit.
"""

from __future__ import annotations

import math
from typing import Any

from corrugate.mechanics.moduli import Moduli

__all__ = ["creased_moduli", "flexibility", "is_rigid"]


def flexibility(k: float) -> float:
    """1 / k (rad/N) of a crease stiffness ``k`` (N mm/(rad mm)); 0.0 for a rigid crease (k =
    inf)."""
    return 0.0 if math.isinf(k) else 1.0 / k


def is_rigid(flex: Any) -> bool:
    """Whether ``flex`` (rad/N) is the rigid crease's plain 0 (not an array or interval)."""
    return isinstance(flex, int | float) and flex == 0.0


def creased_moduli(m: Moduli, flex: Any, t: Any, W: Any, s: Any, c: Any) -> Moduli:
    """The moduli ``m`` (MPa) of a zig-zag (facet width ``W``, sheet ``t``, mm; s = sin(alpha/2),
    c = cos(alpha/2)) with a crease of flexibility ``flex`` = 1 / k (rad/N; :func:`flexibility`)
    in series at every crease (module docstring): Ecx and Ebx lowered, Ecy and Eby as they are.
    ``flex`` 0.0 returns ``m`` itself."""
    if is_rigid(flex):
        return m
    Ecx = 1.0 / (1.0 / m.Ecx + flex * (t * W * c * c / (4.0 * s)))
    Ebx = 1.0 / (1.0 / m.Ebx + flex * (t * t * t / (12.0 * W * s)))
    return Moduli(Ecx, m.Ecy, Ebx, m.Eby)
