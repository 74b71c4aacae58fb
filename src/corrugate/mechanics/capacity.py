"""The load a panel holds in a test: every failure mode's load, the least of them and its name.

A load case's capacity (docs/load_cases.md, section 10) is the load at its first failure divided
by the safety factor. The failure modes of a folded-sheet panel, each the load (N) at which it
occurs, without the safety factor:

* ``yield``, ``yield-across``, ``band-yield``: the peak facet stress of the layer along eta, of
  the other layer and of the connector band's walls at the yield strength
  (:func:`corrugate.mechanics.load_cases.stress_per_load`, section 6);
* ``facet-buckling``: the facets of the layer along eta as plates of width W under the in-plane
  bending stress across their width (sigma_1 = E kappa h / 2 at the crease lines, stress ratio
  psi = -1) at the section of the largest moment, together with the shear that acts there
  (tau = 1.5 V / ((n + 1) h t) at mid-facet); k = 23.9 for long plates hinged on both long edges
  (the lower bound; 39.6 clamped; Timoshenko and Gere 1961, chapter 9), k_s = 5.35 in shear
  (the long plate), combined by the circular interaction (sigma / sigma_cr)^2 + (tau / tau_cr)^2
  = 1 (the usual fit of the computed curves of combined bending and shear, chapter 9);
* ``shear-buckling``: the same facets in shear alone over the shear span a (between a load and a
  support): k_s = 5.35 + 4 (W / a)^2 (chapter 9), hinged edges;
* ``edge-facet-buckling`` (the layers not bonded at their edges, joint ``none``): the outermost
  facet, hinged on its crease and free on its other long edge, under in-plane bending with the
  free edge compressed (psi = -1): k = 0.57 - 0.21 psi + 0.07 psi^2 = 0.85 (EN 1993-1-5:2006,
  Table 4.2, outstand elements; the hinged crease is the lower bound);
* ``end-facet-buckling`` (platens): :func:`corrugate.mechanics.buckling.buckling_scale` times
  0.425 (the end facets, free on one edge, under uniform compression; Timoshenko and
  Gere, section 9.2).

Crippling or crushing under the load and support lines is not modelled (section 10.5 says why).

Every function is plain arithmetic on floats, NumPy arrays or
:class:`~corrugate.solver.interval.Interval` values (the solver bounds the very formulas a design
is reported with). Units: mm, N, MPa.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from corrugate.mechanics.behaviours import TestForm
from corrugate.mechanics.buckling import K_SIMPLE_FREE, buckling_scale
from corrugate.mechanics.load_cases import stress_per_load, wall_capacity

__all__ = [
    "K_BENDING_CLAMPED",
    "K_BENDING_HINGED",
    "K_EDGE_BENDING",
    "K_SHEAR_LONG",
    "MODES",
    "Capacity",
    "bending_buckling_modes",
    "capacity_modes",
    "describe",
    "first_failure",
    "holds_words",
    "plate_buckling_stress",
    "platen_buckling_modes",
    "shear_fraction",
    "shear_span",
]

#: k of a long plate under in-plane bending (psi = -1), both long edges hinged (Timoshenko and
#: Gere 1961, chapter 9: 23.9): the lower bound the model uses.
K_BENDING_HINGED = 23.9
#: The same plate with both long edges clamped (39.6): the upper end, not used by the model.
K_BENDING_CLAMPED = 39.6
#: k of a long plate hinged on one long edge and free on the other, under in-plane bending with
#: the free edge compressed (psi = -1): 0.57 - 0.21 psi + 0.07 psi^2 (EN 1993-1-5:2006 Table 4.2).
K_EDGE_BENDING = 0.57 + 0.21 + 0.07
#: k_s of an infinitely long plate in shear, long edges hinged (Timoshenko and Gere, chapter 9).
K_SHEAR_LONG = 5.35

#: Every mode's name, in the order a report lists them.
MODES: tuple[str, ...] = (
    "yield",
    "yield-across",
    "band-yield",
    "facet-buckling",
    "edge-facet-buckling",
    "shear-buckling",
    "end-facet-buckling",
)


def plate_buckling_stress(k: Any, E: Any, nu: Any, t: Any, W: Any) -> Any:
    """The critical stress (MPa) of a plate of width ``W`` and thickness ``t`` (mm), modulus
    ``E`` (MPa) and Poisson ratio ``nu``: k pi^2 E / (12 (1 - nu^2)) (t / W)^2 (Timoshenko and
    Gere 1961, chapter 9; docs/load_cases.md 10.2)."""
    return k * (math.pi**2 / 12.0) * E / (1.0 - nu * nu) * (t * t) / (W * W)


def shear_fraction(form: TestForm) -> float:
    """The largest shear force of a bending test per newton of load: 1 for a cantilever (the
    load at its tip), else the larger support reaction of equal loads at ``form.loads``
    (fractions of the span): 1/2 in three- and four-point bending."""
    if form.clamped:
        return 1.0
    if not form.loads:
        return 0.5
    k = len(form.loads)
    return max(sum(1.0 - x for x in form.loads) / k, sum(form.loads) / k)


def shear_span(form: TestForm) -> float:
    """The length, as a fraction of the span, over which that largest shear acts (a load to its
    support): the span of a cantilever, Ls / 2 in three-point, Ls / 4 in four-point bending."""
    if form.clamped or not form.loads:
        return 1.0 if form.clamped else 0.5
    return min(min(form.loads), 1.0 - max(form.loads))


def _sqrt(x: Any) -> Any:
    return x.sqrt() if hasattr(x, "sqrt") else np.sqrt(x)


def bending_buckling_modes(
    form: TestForm,
    E: Any,
    nu: Any,
    t: Any,
    W: Any,
    n: Any,
    h: Any,
    stiffness: Any,
    length: Any,
    span: Any | None,
    free_edges: bool,
) -> dict[str, Any]:
    """The buckling loads (N, no safety factor) of the facets of the layer along eta in the
    bending test ``form`` (module docstring): E (MPa), nu, t, W (mm), n creases and depth h (mm)
    of that layer; ``stiffness`` the layers' pure-bending D (N mm) over the panel's ``length``
    (mm) along eta (their curvature kappa = M / (D length) under the moment M = moment x P x Ls);
    ``span`` the test's Ls (None: the length); ``free_edges``: the outermost facets' outer edges
    are free (joint ``none``). Keys ``facet-buckling``, ``shear-buckling`` and, with free edges,
    ``edge-facet-buckling``."""
    Ls = length if span is None else span
    sigma = E * (form.moment * Ls) * h / (2.0 * stiffness * length)  # MPa per N at a crease
    tau = 1.5 * shear_fraction(form) / ((n + 1) * h * t)  # MPa per N at mid-facet
    P_bend = plate_buckling_stress(K_BENDING_HINGED, E, nu, t, W) / sigma
    P_shear = plate_buckling_stress(K_SHEAR_LONG, E, nu, t, W) / tau
    a = shear_span(form) * Ls
    k_s = K_SHEAR_LONG + 4.0 * (W / a) ** 2
    modes = {
        "facet-buckling": 1.0 / _sqrt((1.0 / P_bend) ** 2 + (1.0 / P_shear) ** 2),
        "shear-buckling": plate_buckling_stress(k_s, E, nu, t, W) / tau,
    }
    if free_edges:
        modes["edge-facet-buckling"] = plate_buckling_stress(K_EDGE_BENDING, E, nu, t, W) / sigma
    return modes


def platen_buckling_modes(
    E: Any, nu: Any, t: Any, W: Any, n: Any, K_S: Any, K_C: Any
) -> dict[str, Any]:
    """The buckling load (N, no safety factor) between platens: the end facets of the layer
    along eta, free on one edge (k = 0.425, :mod:`corrugate.mechanics.buckling`), with the
    other layer's share K_C / K_S. Key ``end-facet-buckling``."""
    return {"end-facet-buckling": K_SIMPLE_FREE * buckling_scale(E, nu, t, W, n, K_S, K_C)}


def capacity_modes(
    form: TestForm,
    springs: tuple[Any, Any],
    E: tuple[Any, Any],
    t: tuple[Any, Any],
    nu: Any,
    W: Any,
    n: Any,
    layers: Any,
    whole: Any,
    length: Any,
    width: Any,
    span: Any | None,
    allowable: tuple[float, float],
    band: tuple[Any, Any, Any, float] | None,
    free_edges: bool,
) -> dict[str, Any]:
    """Every failure mode's load (N, without the safety factor) of the load case ``form`` along
    a crease direction (module docstring; docs/load_cases.md 10), pairs ordered (the layer along
    eta, the other): the layers' ``springs``, moduli ``E`` (MPa) and thicknesses ``t`` (mm);
    ``nu``, ``W`` (mm) and ``n`` of the layer along eta; ``layers`` the layers' own D (N mm,
    bending) or K (N/mm, platens) and ``whole`` the panel's with the band's walls; the panel's
    ``length`` along eta and ``width`` across it (mm), the test's ``span`` (mm; None: the
    length); the yield strengths ``allowable`` (MPa; +inf: no yield mode); ``band``: (E, t,
    depth, yield strength) of the band's walls of a bonded joint (None: no band);
    ``free_edges``: the outermost facets' outer edges are free (joint ``none``)."""
    per = stress_per_load(form, springs, 0, layers, E, t, length, width, span)
    modes: dict[str, Any] = {
        "yield": allowable[0] / per[0],
        "yield-across": allowable[1] / per[1],
    }
    if band is not None:  # the walls, at the whole panel's curvature or strain
        Eb, tb, depth, yb = band
        modes["band-yield"] = wall_capacity(form, whole, Eb, tb, depth, length, span, yb, 1.0)
    a, c = springs
    if form.kind == "inplane":
        modes.update(platen_buckling_modes(E[0], nu, t[0], W, n, a.K_S, c.K_C))
    else:
        modes.update(
            bending_buckling_modes(
                form, E[0], nu, t[0], W, n, a.h, layers, length, span, free_edges
            )
        )
    return modes


@dataclass(frozen=True)
class Capacity:
    """A load case's capacity at one design (docs/load_cases.md 10): the ``load`` (N) it holds
    at the ``safety_factor``, its first failure ``mode`` (a name of :data:`MODES`) and that mode
    in ``words`` (``facet buckling in layer 1 at mid-span``), every mode's failure load
    ``modes`` (N, without the safety factor)."""

    load: float
    safety_factor: float
    mode: str
    words: str
    modes: dict[str, float] = field(default_factory=dict)

    @classmethod
    def of(
        cls, modes: Mapping[str, float], safety_factor: float, form: TestForm, along: int
    ) -> Capacity:
        """From every mode's failure load (N); ``along``: the layer (1 or 2) along eta."""
        mode, load = first_failure(modes)
        return cls(
            load / safety_factor,
            safety_factor,
            mode,
            describe(mode, form, along),
            {k: float(v) for k, v in modes.items()},
        )

    @property
    def sentence(self) -> str:
        """``holds 10.2 N at safety factor 2 (first failure: ...)`` (:func:`holds_words`)."""
        return holds_words(self.load, self.safety_factor, self.words)

    def as_dict(self) -> dict[str, object]:
        """The keys ``design.json`` and ``--json`` carry."""
        return {
            "first_failure": self.words,
            "first_failure_mode": self.mode,
            "failure_loads_N": dict(self.modes),
        }


def first_failure(modes: Mapping[str, float]) -> tuple[str, float]:
    """The mode with the least load (N) and that load (ties: the first in :data:`MODES`)."""
    order = sorted(modes, key=lambda m: (modes[m], MODES.index(m) if m in MODES else len(MODES)))
    return order[0], float(modes[order[0]])


def holds_words(load: float, safety_factor: float, words: str) -> str:
    """The answer's sentence of a capacity: ``holds 10.2 N at safety factor 2 (first failure:
    facet buckling in layer 1 at mid-span)``; ``load`` (N) at the safety factor."""
    return f"holds {load:.3g} N at safety factor {safety_factor:g} (first failure: {words})"


def _place(form: TestForm) -> str:
    """Where the largest moment of a test acts."""
    if form.kind == "inplane":
        return "between the platens"
    if form.clamped:
        return "at the root"
    return "at mid-span" if len(form.loads) <= 1 else "between the load points"


def describe(mode: str, form: TestForm, along: int) -> str:
    """A mode in words, e.g. ``facet buckling in layer 1 at mid-span``: ``along`` (1 or 2) is
    the layer whose creases run along the load case's direction."""
    other = 3 - along
    place = _place(form)
    near = "along the span" if form.clamped else "near the supports"
    words = {
        "yield": f"yield in layer {along} {place}",
        "yield-across": f"yield in layer {other} {place}",
        "band-yield": f"yield of the connector band's walls {place}",
        "facet-buckling": f"facet buckling in layer {along} {place}",
        "edge-facet-buckling": f"buckling of the outermost facet (free edge) of layer {along} "
        f"{place}",
        "shear-buckling": f"shear buckling of the facets in layer {along} {near}",
        "end-facet-buckling": f"buckling of the end facets of layer {along}",
    }
    return words.get(mode, mode)
