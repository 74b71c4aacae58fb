"""The part a calibrated certificate speaks of, as the FE twin meshes it (docs/calibration.md 9).

A design on a calibrated sheet (a material with a :class:`~corrugate.materials.calibrated.
Calibration`) is certified over the measured intervals: E over its 90 % interval, the crease
stiffness k (N mm/(rad mm)) over its interval, and the folds at the angle cut plus the
springback, over the springback's interval. ``verify`` checks that part, not the one cut, at
the worst end of those intervals (:func:`certified_part`):

- E at its interval's low end: every stiffness and buckling load of the models is E times a
  function of the geometry (and of E / k through the crease's compliance, which a lower E only
  makes a smaller share of), so the least E is the least stiff part;
- k at its interval's low end: a softer crease only adds compliance in series with the facets
  (docs/offaxis.md, "Compliant creases"), so the least k is the least stiff part; the FE meshes
  it as the crease strips of :func:`corrugate.fea.shells.crease_strip`;
- each calibrated layer's fold angle at alpha + springback_lo or alpha + springback_hi, the end
  whose model value of the quantity is the lower (:func:`corrugate.analysis.evaluate.analyze`
  at eta: K for a stiffness K or a buckling load between platens, D for every bending
  quantity), as no stiffness is monotone in alpha in every direction (EI along the creases
  falls as the folds open, K across them rises).

Every directional constraint is a lower bound on a stiffness or a load, or an upper bound on a
deflection (a load over a stiffness), so the least stiff end is the worst for each. A layer on a
sheet without a calibration keeps its own E, k and angle. Units: E in MPa, k in N mm/(rad mm),
angles in deg.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, replace
from typing import Any

from corrugate.core.errors import InputError
from corrugate.geometry.layer import Assembly, Layer
from corrugate.geometry.layouts import Rectangle

__all__ = ["CertifiedPart", "certified_part"]


@dataclass(frozen=True, slots=True)
class CertifiedPart:
    """The assembly the FE twin meshes (``assembly``) and, when it is not the design's own,
    what was changed (``changes``: one entry per calibrated layer, its E (MPa), crease
    stiffness k (N mm/(rad mm), None: rigid), the angle cut and the angle meshed (deg) and the
    springback end taken)."""

    assembly: Assembly
    changes: tuple[dict[str, Any], ...] = ()

    @property
    def calibrated(self) -> bool:
        return bool(self.changes)

    @property
    def key(self) -> str:
        """What tells two parts apart in the runs a verification shares ("" for the design)."""
        return "; ".join(
            f"L{c['layer']} E {c['E_MPa']:.10g} k {c['crease_stiffness']} a {c['alpha_deg']:.10g}"
            for c in self.changes
        )

    def words(self) -> str:
        """The row's note: ``meshed at the calibrated worst end: layer 1 E 2738 MPa, k 0.0949
        N*mm/(rad*mm), folds at 87.5 deg (cut 93 deg, springback -5.5 deg)``."""
        if not self.changes:
            return ""
        changes = list(self.changes)
        same = len(changes) == 2 and {**changes[0], "layer": 0} == {**changes[1], "layer": 0}
        parts = []
        for c in changes[:1] if same else changes:
            k = c["crease_stiffness"]
            kk = "rigid creases" if k is None else f"k {k:.3g} N*mm/(rad*mm)"
            by = f", the end of lower model {c['by']}" if c["by"] else ""
            who = "both layers" if same else f"layer {c['layer']}"
            parts.append(
                f"{who} E {c['E_MPa']:.4g} MPa, {kk}, folds at "
                f"{c['alpha_deg']:.4g} deg (cut {c['alpha_cut_deg']:.4g} deg, springback "
                f"{c['springback_deg']:+.2g} deg{by})"
            )
        return "meshed at the calibrated worst end: " + "; ".join(parts)

    def as_json(self) -> list[dict[str, Any]]:
        return [dict(c) for c in self.changes]


def _measure(kind: str) -> str:
    """The model stiffness whose lower value picks the angle end: K for K and the platens'
    buckling load, D for every bending quantity (D, EI, a test's P / delta, its capacity)."""
    return "K" if kind in ("K", "Pb") else "D"


def _at(layer: Layer, E: float, k: float, alpha: float) -> Layer:
    """``layer`` at E (MPa), k and the fold angle alpha (deg), kept within 1-179 deg as the
    certificate's box keeps it inside the zig-zag's 0-180 (:mod:`corrugate.solver.tolerance_box`)."""
    m = replace(layer.material, E=E, crease_stiffness=k)
    return replace(layer, material=m, alpha_deg=min(max(alpha, 1.0), 179.0))


def _assembled(a: Assembly, layers: tuple[Layer, Layer]) -> Assembly:
    """The assembly of ``layers`` on ``a``'s layout; a square whose layers' springbacks differ
    becomes the rectangle of their extents (the part the folds make)."""
    try:
        return replace(a, layer1=layers[0], layer2=layers[1])
    except InputError:
        if a.layout.name != "square":
            raise
        return Assembly(layers[0], layers[1], Rectangle(holes=a.layout.holes))


def certified_part(
    assembly: Assembly, kind: str, eta: float | None, support: str, model: str | None = None
) -> CertifiedPart:
    """The part of the module docstring for a quantity of ``kind`` (K, D, EI, k, Pb, Pmax) at
    ``eta`` (deg; None: 0) under ``support``, the angle end picked with the moduli variant
    ``model`` (None: the default): ``assembly`` itself when no layer's sheet is calibrated."""
    from corrugate.analysis.evaluate import analyze
    from corrugate.names import DEFAULT_MODEL

    layers = assembly.layers
    cals = [lay.material.calibration for lay in layers]
    if all(c is None for c in cals):
        return CertifiedPart(assembly)
    ends: list[list[tuple[Layer, float]]] = []
    for lay, cal in zip(layers, cals, strict=True):
        if cal is None:
            ends.append([(lay, 0.0)])
            continue
        k = cal.k_lo if not math.isinf(cal.k_lo) else lay.material.crease_stiffness
        sbs = sorted({cal.springback_lo, cal.springback_hi})
        E = cal.E_lo if cal.E_measured else lay.material.E  # a stated k and springback: E as is
        ends.append([(_at(lay, E, k, lay.alpha_deg + sb), sb) for sb in sbs])
    End = tuple[Layer, float]
    combos: list[tuple[End, End]]
    if assembly.layer1 == assembly.layer2:  # one sheet folded twice: the same folds
        combos = [(e, e) for e in ends[0]]
    else:
        combos = list(itertools.product(ends[0], ends[1]))
    measure = _measure(kind)
    e = 0.0 if eta is None else float(eta)
    best: tuple[float, Assembly, tuple[tuple[Layer, float], ...]] | None = None
    for combo in combos:
        a = _assembled(assembly, (combo[0][0], combo[1][0]))
        if len(combos) == 1:
            best = (0.0, a, tuple(combo))
            break
        r = analyze(a, model or DEFAULT_MODEL, [e], support=support).stiffness[0]
        value = r.K if measure == "K" else r.D
        if best is None or value < best[0]:
            best = (value, a, tuple(combo))
    assert best is not None
    _, part, chosen = best
    changes = []
    for i, ((lay, sb), orig, cal) in enumerate(zip(chosen, layers, cals, strict=True), 1):
        if cal is None:
            continue
        k = lay.material.crease_stiffness
        changes.append(
            {
                "layer": i,
                "E_MPa": lay.material.E,
                "crease_stiffness": None if math.isinf(k) else k,
                "alpha_cut_deg": orig.alpha_deg,
                "alpha_deg": lay.alpha_deg,
                "springback_deg": sb,
                "by": measure if len(combos) > 1 else "",
            }
        )
    return CertifiedPart(part, tuple(changes))
