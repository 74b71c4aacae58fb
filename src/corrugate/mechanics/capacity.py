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
  Gere, section 9.2);
* ``crippling`` (bending tests): the facets of the layer along eta as webs under a load or
  support line of ``bearing`` width s_s across them: each line's load shared by the n + 1
  facets, a facet's in-plane force its share over cos(alpha/2), held at the least of the web's
  elastic patch-loading load F_cr = k_F pi^2 E t^3 / (12 (1 - nu^2) W) (k_F = 6 away from an
  end, 2 + 6 s_s / W <= 6 at one: EN 1993-1-5:2006 section 6.4), its bearing yield F_y = f_y t
  s_s and EN 1993-1-5's patch resistance 0.5 sqrt(F_y F_cr) (chi_F = 0.5 / lambda_F, 6.2-6.4);
* ``band-wall-buckling`` (a bonded band, bending tests): the band's walls along the span as
  plates of height t_d under the in-plane bending of the panel's curvature, bending fully
  composite with the layer along the span (k(psi) of EN 1993-1-5 Table 4.1, edges held by the
  layers; or the free strip above layer 1's zig-zag as an outstand, k of EN 1993-1-5 Table 4.2,
  when the span runs along layer 2's creases) and the whole shear of the test (k_s = 5.35),
  combined linearly (a lower bound of the interaction: the stable region of a linear
  eigenproblem in its load parameters is convex);
* ``band-wall-crippling`` (a bonded band, bending tests): each wall under half of a load line
  on its edge, the patch-loading load of ``crippling`` with h_w = t_d, with EN 1993-1-5 7.2's
  interaction with bending (F / F_R + 0.8 M / M_R <= 1.4).

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
    "DEFAULT_BEARING",
    "K_BENDING_CLAMPED",
    "K_BENDING_HINGED",
    "K_EDGE_BENDING",
    "K_PATCH",
    "K_SHEAR_LONG",
    "MODES",
    "Band",
    "Capacity",
    "bending_buckling_modes",
    "capacity_modes",
    "composite_factor",
    "composite_share",
    "crippling_load",
    "crippling_modes",
    "describe",
    "first_failure",
    "holds_words",
    "k_bending",
    "patch_critical_load",
    "plate_buckling_stress",
    "platen_buckling_modes",
    "shear_fraction",
    "shear_span",
    "wall_buckling_modes",
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
#: k_F of a web under a patch load on one long edge away from its ends (EN 1993-1-5:2006 6.4,
#: Figure 6.1 type (a): 6 + 2 (h_w / a)^2, a -> infinity, its least value).
K_PATCH = 6.0
#: k_F = 2 + 6 (s_s + c) / h_w <= 6 of the same web loaded at its end (type (c)), c = 0.
K_PATCH_END = 2.0
#: The width (mm) of a load or support line unless the load case gives its ``bearing``: a
#: fingertip's or a small pad's contact, and about the 10 mm of the bearing lengths of
#: EN 1993-1-3's web-crippling tests (docs/load_cases.md 10.5).
DEFAULT_BEARING = 10.0

#: Every mode's name, in the order a report lists them.
MODES: tuple[str, ...] = (
    "yield",
    "yield-across",
    "band-yield",
    "facet-buckling",
    "edge-facet-buckling",
    "shear-buckling",
    "end-facet-buckling",
    "crippling",
    "band-wall-buckling",
    "band-wall-crippling",
)


@dataclass(frozen=True)
class Band:
    """The connector band's walls of a bonded joint (docs/load_cases.md 7, 10.5): layer 1's sheet
    (modulus ``E`` MPa, Poisson ratio ``nu``, thickness ``t`` mm, ``yield_strength`` MPa, +inf:
    none) standing ``depth`` t_d (mm) high. Floats, arrays or intervals."""

    E: Any
    nu: Any
    t: Any
    depth: Any
    yield_strength: float


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


def _min(x: Any, y: Any) -> Any:
    if hasattr(x, "minimum"):
        return x.minimum(y)
    if hasattr(y, "minimum"):
        return y.minimum(x)
    return np.minimum(x, y)


def patch_critical_load(k_F: Any, E: Any, nu: Any, t: Any, h_w: Any) -> Any:
    """The elastic critical load (N) of a web of depth ``h_w`` and thickness ``t`` (mm), modulus
    ``E`` (MPa), Poisson ratio ``nu``, under a patch load on one long edge: k_F pi^2 E t^3 /
    (12 (1 - nu^2) h_w) (EN 1993-1-5:2006 6.4, 0.9 k_F E t^3 / h_w written for any nu;
    docs/load_cases.md 10.5)."""
    return k_F * (math.pi**2 / 12.0) * E / (1.0 - nu * nu) * (t * t * t) / h_w


def crippling_load(F_cr: Any, yield_strength: float, t: Any, bearing: Any) -> Any:
    """A web's first failure (N) under a patch load of ``bearing`` length s_s (mm) on its edge:
    the least of its elastic critical load ``F_cr`` (N), the yield load of the bearing length
    F_y = f_y t s_s (``yield_strength`` f_y MPa, ``t`` mm; no flange: l_y = s_s) and EN
    1993-1-5:2006's patch resistance chi_F F_y = 0.5 sqrt(F_y F_cr) (6.2-6.4: chi_F = 0.5 /
    lambda_F, lambda_F = sqrt(F_y / F_cr)). Without a yield strength (+inf): F_cr.
    docs/load_cases.md 10.5."""
    if math.isinf(yield_strength):
        return F_cr
    F_y = yield_strength * t * bearing
    return _min(_min(F_cr, F_y), 0.5 * _sqrt(F_y * F_cr))


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


def crippling_modes(
    form: TestForm,
    E: Any,
    nu: Any,
    t: Any,
    W: Any,
    n: Any,
    h: Any,
    yield_strength: float,
    bearing: Any,
) -> dict[str, Any]:
    """The crippling load (N, no safety factor) of the facets of the layer along eta under the
    load and support lines of the bending test ``form`` (docs/load_cases.md 10.5): E (MPa), nu,
    t, W (mm), n creases and depth h (mm) of that layer, its ``yield_strength`` (MPa, +inf:
    none), the lines' ``bearing`` width s_s (mm). A line carrying the share s of the load puts
    s P / (n + 1) on each facet, s P / ((n + 1) c) in the facet's plane (c = h / W =
    cos(alpha/2): the facets are webs inclined at asin(c) to the panel's plane); each facet holds
    :func:`crippling_load` with k_F = 6 under a load line inside the span and 2 + 6 s_s / W <= 6
    at the panel's end (the supports of three- and four-point bending, conservatively at the
    end; a cantilever's tip). The clamped root of a cantilever does not cripple. Key
    ``crippling``."""
    c = h / W
    per = (n + 1.0) * c  # P per newton of facet force, for a line carrying the whole load

    def held(k_F: Any) -> Any:
        return crippling_load(patch_critical_load(k_F, E, nu, t, W), yield_strength, t, bearing)

    end = held(_min(K_PATCH_END + 6.0 * bearing / W, K_PATCH))
    if form.clamped:
        return {"crippling": per * end}
    inside = per * held(K_PATCH) * len(form.loads or (0.5,))
    return {"crippling": _min(inside, per * end / shear_fraction(form))}


def k_bending(psi: Any) -> Any:
    """k of a plate hinged on both long edges under a linear stress whose far edge is at ``psi``
    (0 >= psi >= -1) times the compressed edge's: 7.81 - 6.29 psi + 9.78 psi^2 (EN 1993-1-5:2006
    Table 4.1; 7.81 at psi = 0, 23.9 at psi = -1)."""
    return 7.81 - 6.29 * psi + 9.78 * (psi * psi)


def composite_share(facets_width: Any, depth: Any, h_along: Any, h_other: Any) -> Any:
    """How far the band's walls bending as one section with the layer along the span move their
    neutral axis (fully composite, docs/load_cases.md 10.5): u = r h_o / t_d, between 0 (no
    layer: the walls' own mid-height) and 1. The layer along the span, (n + 1) facets of width W
    (``facets_width`` (n + 1) W, mm) and thickness t, has its axial area (n + 1) W t at the
    middle of its depth ``h_along`` (mm): at h_a / 2 above the walls' foot for layer 1, t_d -
    h_a / 2 for layer 2; the walls' area 2 t t_d at t_d / 2 (``depth`` t_d = h_a + h_o, mm;
    ``h_other`` h_o the other layer's depth). The common neutral axis lies r h_o / 2 from the
    walls' mid-height towards the layer, r = (n + 1) W / ((n + 1) W + 2 t_d) the layer's share
    of the area (t cancels), so the walls' edge away from the layer is at e = t_d (1 + u) / 2
    from it and the other at psi = -(1 - u) / (1 + u) times its stress. Each variable enters
    once (h_a / h_o as one ratio), so over intervals the bounds are those of the formula."""
    r = 1.0 / (1.0 + 2.0 * depth / facets_width)
    return r / (1.0 + h_along / h_other)


def _composite_factor(u: float | np.ndarray) -> Any:
    psi = -(1.0 - u) / (1.0 + u)
    return k_bending(psi) / (1.0 + u)


def composite_factor(u: Any) -> Any:
    """k(psi) / (1 + u) (:func:`k_bending`, psi = -(1 - u) / (1 + u)) of the share ``u`` of
    :func:`composite_share`: the walls' bending buckling load with the composite action over
    the load about their own mid-height times 23.9 (P_sigma = k sigma_cr / sigma_1, sigma_1 = E
    kappa t_d (1 + u) / 2). It falls as u grows (psi rises from -1 towards 0, where k falls,
    and the edge moves away), so over an interval it is its values at the ends: the greatest u
    gives the least."""
    if hasattr(u, "lo") and hasattr(u, "hi"):  # an Interval (corrugate.solver.interval)
        return type(u)(_composite_factor(u.hi), _composite_factor(u.lo))
    return _composite_factor(u)


def wall_buckling_modes(
    form: TestForm,
    band: Band,
    whole: Any,
    length: Any,
    span: Any | None,
    top_free: Any | None,
    bearing: Any,
    composite: Any | None = None,
) -> dict[str, Any]:
    """The buckling and crippling loads (N, no safety factor) of the connector band's two walls
    along the span in the bending test ``form`` (docs/load_cases.md 10.5): ``band`` the walls,
    ``whole`` the panel's D with them (N mm) over its ``length`` (mm) along eta, ``span`` the
    test's Ls (None: the length), ``top_free`` the height (mm) of the strip of wall above the
    other layer's edge crease when the span runs along layer 2's creases (None: along layer 1's,
    the walls held along both long edges), ``bearing`` the load lines' width s_s (mm).

    ``band-wall-buckling``: the walls share the panel's curvature kappa = M / (D L), bending
    fully composite with the layer along the span (``composite``: the share u of
    :func:`composite_share`; docs/load_cases.md 10.5): the edge away from that layer at
    E kappa t_d (1 + u) / 2, the other at psi = -(1 - u) / (1 + u) times it, for the test's
    load where that edge is the compressed one (the caller passes None where the compressed edge
    is beside the layer, which the composite action only relieves),
    critical at k(psi) of :func:`k_bending` (both long edges held: layer 1's edge crease and
    the other layer's zig-zag edge; hinged, the least restraint) over t_d (without
    ``composite``, or u = 0: about the walls' own mid-height, psi = -1, k = 23.9), or,
    sagging with a free strip of height b on top, about the walls' mid-height, k = 0.57 - 0.21
    psi + 0.07 psi^2 over b, psi = 1 - 2 b / t_d (EN 1993-1-5 Table 4.2); with the whole largest shear V in the two
    walls, tau = 1.5 (V / 2) / (t_d t), critical at k_s = 5.35 over t_d; the two combined
    linearly, 1 / P = 1 / P_sigma + 1 / P_tau. ``band-wall-crippling``: each wall carries at
    most half of a load line on its edge (the layers take the rest), holding
    :func:`crippling_load` with k_F = 6 and h_w = t_d, reduced by EN 1993-1-5 7.2's interaction
    F / F_R + 0.8 P / P_sigma <= 1.4 under the largest moment (three- and four-point); a
    cantilever's tip load is at the walls' ends (k_F of an end, type (c); no moment there)."""
    E, nu, t, td = band.E, band.nu, band.t, band.depth
    Ls = length if span is None else span
    # MPa per N at the wall's edge about its mid-height, E kappa t_d / 2, kappa = M / (D L)
    sigma = E * (form.moment * Ls) * td / (2.0 * whole * length)
    if top_free is None or form.clamped:
        # k(psi) / (1 + u): 23.9 about the walls' own mid-height (u = 0, psi = -1)
        k_w = K_BENDING_HINGED if composite is None else composite_factor(composite)
        P_sigma = plate_buckling_stress(k_w, E, nu, t, td) / sigma
    else:
        psi = 1.0 - 2.0 * top_free / td
        k = 0.57 - 0.21 * psi + 0.07 * psi * psi
        P_sigma = plate_buckling_stress(k, E, nu, t, top_free) / sigma
    tau = 1.5 * (shear_fraction(form) / 2.0) / (td * t)  # MPa per N in each wall
    P_tau = plate_buckling_stress(K_SHEAR_LONG, E, nu, t, td) / tau
    if form.clamped:
        k_F: Any = _min(K_PATCH_END + 6.0 * bearing / td, K_PATCH)
    else:
        k_F = K_PATCH
    F = crippling_load(patch_critical_load(k_F, E, nu, t, td), band.yield_strength, t, bearing)
    P_F = 2.0 * F * len(form.loads or (0.5,))  # P at which one wall's share reaches F
    if not form.clamped:
        P_F = _min(P_F, 1.4 / (1.0 / P_F + 0.8 / P_sigma))
    return {
        "band-wall-buckling": 1.0 / (1.0 / P_sigma + 1.0 / P_tau),
        "band-wall-crippling": P_F,
    }


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
    band: Band | None,
    free_edges: bool,
    along: int = 0,
    bearing: Any = None,
) -> dict[str, Any]:
    """Every failure mode's load (N, without the safety factor) of the load case ``form`` along
    a crease direction (module docstring; docs/load_cases.md 10), pairs ordered (the layer along
    eta, the other): the layers' ``springs``, moduli ``E`` (MPa) and thicknesses ``t`` (mm);
    ``nu``, ``W`` (mm) and ``n`` of the layer along eta; ``layers`` the layers' own D (N mm,
    bending) or K (N/mm, platens) and ``whole`` the panel's with the band's walls; the panel's
    ``length`` along eta and ``width`` across it (mm), the test's ``span`` (mm; None: the
    length); the yield strengths ``allowable`` (MPa; +inf: no yield mode); ``band``: the band's
    walls of a bonded joint (None: no band); ``free_edges``: the outermost facets' outer edges
    are free (joint ``none``); ``along``: the layer along eta (0: layer 1, 1: layer 2);
    ``bearing``: the load and support lines' width s_s (mm; None: :data:`DEFAULT_BEARING`)."""
    s_s = DEFAULT_BEARING if bearing is None else bearing
    per = stress_per_load(form, springs, 0, layers, E, t, length, width, span)
    modes: dict[str, Any] = {
        "yield": allowable[0] / per[0],
        "yield-across": allowable[1] / per[1],
    }
    a, c = springs
    if band is not None:  # the walls, at the whole panel's curvature or strain
        modes["band-yield"] = wall_capacity(
            form, whole, band.E, band.t, band.depth, length, span, band.yield_strength, 1.0
        )
        if form.kind != "inplane":
            top = a.h if along == 1 else None  # layer 2 along eta: the strip above layer 1
            # the layer along eta bending as one section with the walls, where the compressed
            # edge is the one away from it: layer 1's sagging (three-, four-point), layer 2's
            # hogging (a cantilever); the edge beside the layer gains from it (10.5)
            away = (along == 0) != bool(form.clamped)
            u = composite_share((n + 1.0) * W, band.depth, a.h, c.h) if away else None
            modes.update(wall_buckling_modes(form, band, whole, length, span, top, s_s, u))
    if form.kind == "inplane":
        modes.update(platen_buckling_modes(E[0], nu, t[0], W, n, a.K_S, c.K_C))
    else:
        modes.update(
            bending_buckling_modes(
                form, E[0], nu, t[0], W, n, a.h, layers, length, span, free_edges
            )
        )
        modes.update(crippling_modes(form, E[0], nu, t[0], W, n, a.h, allowable[0], s_s))
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
    bearing: float | None = None

    @classmethod
    def of(
        cls,
        modes: Mapping[str, float],
        safety_factor: float,
        form: TestForm,
        along: int,
        bearing: float | None = None,
    ) -> Capacity:
        """From every mode's failure load (N); ``along``: the layer (1 or 2) along eta;
        ``bearing``: the load lines' width (mm; None: :data:`DEFAULT_BEARING`), for a bending
        test (the crippling modes use it)."""
        mode, load = first_failure(modes)
        if form.kind != "inplane":
            bearing = DEFAULT_BEARING if bearing is None else float(bearing)
        return cls(
            load / safety_factor,
            safety_factor,
            mode,
            describe(mode, form, along, bearing),
            {k: float(v) for k, v in modes.items()},
            bearing,
        )

    @property
    def sentence(self) -> str:
        """``holds 10.2 N at safety factor 2 (first failure: ...)`` (:func:`holds_words`)."""
        return holds_words(self.load, self.safety_factor, self.words)

    def as_dict(self) -> dict[str, object]:
        """The keys ``design.json`` and ``--json`` carry."""
        out: dict[str, object] = {
            "first_failure": self.words,
            "first_failure_mode": self.mode,
            "failure_loads_N": dict(self.modes),
            "safety_factor": self.safety_factor,
        }
        if self.bearing is not None:
            out["bearing_mm"] = self.bearing
        return out


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


def describe(mode: str, form: TestForm, along: int, bearing: float | None = None) -> str:
    """A mode in words, e.g. ``facet buckling in layer 1 at mid-span``: ``along`` (1 or 2) is
    the layer whose creases run along the load case's direction; ``bearing`` (mm) the load
    lines' width a crippling mode names (None: not named)."""
    other = 3 - along
    place = _place(form)
    wide = "" if bearing is None else f" ({bearing:g} mm wide)"
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
        "crippling": f"crippling of layer {along}'s facets under a load or support line{wide}",
        "band-wall-buckling": f"buckling of the connector band's walls {place}",
        "band-wall-crippling": f"crippling of the connector band's walls under the load line{wide}",
    }
    return words.get(mode, mode)
