"""Stiffness along any direction eta for the built-in support conditions (docs/offaxis.md).

The models here are the point models (and, evaluated on intervals, the solver's bounds) of the
entries ``free`` and ``frame`` of the registry of behaviours (:mod:`corrugate.mechanics.behaviours`,
the entries in :mod:`corrugate.mechanics.supports`); :func:`assembly_directional` looks a support
up there by name.

The paper's rule, ``support = "frame"``: K(eta) = K_y cos^2 + K_x sin^2 (and D likewise,
:mod:`corrugate.mechanics.springs`). It is the stiffness of a panel whose both crease directions are
driven at once, i.e. held in a rigid frame (the project's frame FE agrees within 0.2 %).

A panel with free sides (``support = "free"``, the default: a bench test, a part held at two
edges) is far softer off-axis, because its facets no longer run from one loaded edge to the
other. Its model here is a **lower bound** (for the homogenised plate) built from each layer's
own springs, the layers acting in parallel (as the unconnected layers of the FE coupons do).
Against FE coupons (docs/validation/off_axis.md; three squares and a 1:2 rectangle, eta 0-90
deg, FE extrapolated from 2/4/8 or 4/8/16 elements per facet) K is 0.83-1.19 of the FE (not
conservative near 15 and 75 deg; at 15 deg the converged coupon is 22, 15 and 9 % below the model
at 4, 8 and 16 cells: docs/offaxis.md, coupon-size series; 19 % for the rectangle); D is
0.62-1.12 of the 3-point FE at 15-30 deg for the squares (before the strips were counted one
fewer; since, at most 0.84 of the FE at 15-75 deg on the five designs of docs/validation/
load_cases.md, docs/load_cases.md 5) but 0.008-0.02 at 45 deg, and 0.017 at 30 deg for the
rectangle (very conservative where no facet runs from support to support). For a layer whose creases
make the angle theta with the load direction, c = cos theta, s = sin theta:

* In-plane (plate of the layer under uniaxial stress along the load, free sides; the complementary
  energy of that statically admissible stress field bounds the stiffness from below, whatever
  the platens do):

      K_i(theta) = 1 / (c^4 / K_S + s^4 / K_C + s^2 c^2 / K_T)

  with K_T = A66 p q, A66 = G t sin(alpha/2) the in-plane shear stiffness of the zig-zag
  (Xia et al. 2012) and p q = p sum_j 1/L_j the layer's spanwise geometry factor (1 for a square).
  The Poisson coupling a12 = -nu a22 is left out: it can only lower the compliance, so leaving it
  out keeps the bound (at most 0.65 % of the compliance for W 8-14 mm, alpha 40-115 deg, Dura-Lar
  0.125 mm; docs/offaxis.md). That bound is for the homogenised (large) plate; a finite panel
  with free edges is softer off the creases, so each layer's share is multiplied there by the
  finite-panel factor 1 - w(eta) 0.6 / sqrt(n) (:func:`finite_panel_factor`, w = 1 up to 15 deg
  from the creases, 0.25 at 45; docs/load_cases.md section 4), which keeps the certified K at or
  below the converged FE coupons.
* Bending, the larger of two lower bounds: the same uniaxial-moment plate bound with D_S, D_C
  and the twisting rigidity D_T = D66 p q, D66 = G t^3 / (12 sin(alpha/2)) (Xia 2012), and a
  strip bound: the facets that run from one support to the other in a square coupon
  (a fraction 1 - |tan theta| of them) as independent beams of span L / cos theta loaded at
  mid-span, every other facet discarded, which gives D_S c^4 (1 - |tan theta|). Discarding
  material and the connections between strips can only soften a linear structure; the strips
  are Euler-Bernoulli beams, as the paper's D is, so shear deformation of a stubby panel (about
  10 % in the FE 3-point test at eta = 0) is not in it. A finite coupon holds a whole number of
  such strips, one fewer than (n + 1)(1 - |tan theta|) on average over where it is cut, so the
  strip bound counts one facet fewer: D_S c^4 max(0, 1 - |tan theta| - 1 / (n + 1))
  (:func:`facet_share`); and each layer's share of D takes a finite-panel factor
  1 - w(eta) 0.3 / sqrt(n) off the creases, of the same form as K's, which keeps the margin
  that the FE series of thick, few-facet coupons need to be judged converged (docs/load_cases.md
  section 5: the model at or below every settled FE coupon).

At eta = 0 and 90 deg both conditions give the paper's springs exactly. Every function here is
plain arithmetic, so it takes NumPy arrays or :class:`~corrugate.solver.interval.Interval`
arguments alike: the certified solver bounds the very formula ``analyze`` evaluates.

Units: K in N/mm, D in N mm, angles in degrees at the API.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Literal

import numpy as np
from numpy.typing import NDArray

from corrugate.mechanics.behaviours import check_support, get_support
from corrugate.names import DEFAULT_SUPPORT, Support

__all__ = [
    "ANGLE_DECIMALS",
    "FINITE_PANEL_BENDING",
    "FINITE_PANEL_DEFICIT",
    "LOCAL_T_OVER_W",
    "SHEAR_CORRECTION",
    "Coupon",
    "Support",
    "assembly_directional",
    "check_support",
    "facet_share",
    "finite_panel_deficit",
    "finite_panel_factor",
    "finite_panel_weight",
    "frame_rule",
    "free_bending",
    "free_inplane",
    "free_panel",
    "local_depth",
    "on_grid",
    "shear_spring",
    "shear_springs",
    "strip_fraction",
]

FloatArray = NDArray[np.float64]


def shear_springs(E: Any, nu: Any, t: Any, s: Any, pq: Any) -> tuple[Any, Any]:
    """In-plane shear spring K_T (N/mm) and twisting spring D_T (N mm) of a layer.

    ``E`` MPa, ``nu``, ``t`` mm, ``s`` = sin(alpha/2) (any profile's pitch / developed,
    :attr:`corrugate.geometry.profile.Profile.plan_ratio`), ``pq`` = p sum_j 1/L_j (the factor that
    turns a plate stiffness per unit width into the layer's spanwise spring, K_S = Ecy t pq).
    A66 = G t s and D66 = G t^3 / (12 s) are Xia et al. (2012) for a zig-zag of developed
    width W = p / s (c/l and l/c of any profile); G = E / (2 (1 + nu))."""
    G = E / (2.0 * (1.0 + nu))
    return (G * t) * s * pq, (G * (t * t * t / 12.0)) / s * pq


#: c of the finite-panel factor 1 - c / sqrt(n) (docs/load_cases.md, section 4).
FINITE_PANEL_DEFICIT = 0.6


def finite_panel_deficit(n: Any) -> Any:
    """d(n) = min(1, c / sqrt(n)), c = :data:`FINITE_PANEL_DEFICIT`: the largest share of the
    homogenised (large-panel) in-plane K that a free panel whose layer has ``n`` creases loses
    off the crease directions, near 15 deg from them (docs/load_cases.md, section 4: converged
    FE coupons of 4, 8 and 16 cells are 18, 13 and 8 % below the homogenised coupon at 15 deg,
    a 1:2 rectangle 16 %; c = 0.6 bounds each, 0.36 would fit the squares). Falls with n;
    arrays (n >= 0)."""
    n_ = np.maximum(np.asarray(n, dtype=np.float64), 1.0)
    return np.minimum(FINITE_PANEL_DEFICIT / np.sqrt(n_), 1.0)


def finite_panel_weight(eta_deg: float) -> float:
    """w(eta): how much of the deficit applies at eta (deg): 0 on the crease directions (K is
    exact there), 1 up to 15 deg from them, falling linearly to 0.25 at 45 deg (the FE coupons'
    deficit at 30 and 45 deg is at most a third and an eighth of that at 15; docs/load_cases.md
    section 4)."""
    e = on_grid(eta_deg, 90.0)
    off = min(e, 90.0 - e)
    if off == 0.0:
        return 0.0
    return 1.0 if off <= 15.0 else 1.0 - 0.75 * (off - 15.0) / 30.0


def finite_panel_factor(n: Any, eta_deg: float = 15.0) -> Any:
    """The share of a layer's homogenised in-plane K that a free panel keeps at ``eta_deg``:
    1 - w(eta) d(n) (:func:`finite_panel_weight`, :func:`finite_panel_deficit`)."""
    return 1.0 - finite_panel_weight(eta_deg) * finite_panel_deficit(n)


#: The shear correction of a facet acting as a web (docs/load_cases.md, section 2): the shear flow
#: of the zig-zag vanishes at every crease, so across each facet it is parabolic, and the
#: strain energy of a parabolic flow is 6/5 that of the uniform one carrying the same force.
SHEAR_CORRECTION = 5.0 / 6.0


def shear_spring(E: Any, nu: Any, t: Any, ratio: Any, web2: Any, pq: Any) -> Any:
    """Transverse shear spring V_S (N/mm) of a layer bent along its creases: S / L, with S =
    (5/6) G t W c^2 (n + 1) the shear stiffness (N) of its n + 1 facets acting as webs, each
    carrying a parabolic shear flow that vanishes at its creases (:data:`SHEAR_CORRECTION`,
    docs/load_cases.md section 2), and L their length; in terms of the layer's geometry factor
    pq = p sum_j 1/L_j, V_S = (5/6) G t c^2 pq / s. ``E`` MPa, ``nu``, ``t`` mm; the profile's
    ``ratio`` = pitch / developed (s = sin(alpha/2) for the zig-zag) and ``web2``, the mean
    (dz/ds)^2 over its developed length (c^2 = cos^2(alpha/2);
    :class:`corrugate.geometry.profile.Profile`). The factor 5/6 is derived for the zig-zag;
    another profile takes the same factor."""
    G = E / (2.0 * (1.0 + nu))
    return SHEAR_CORRECTION * (G * t) * web2 * pq / ratio


#: The sheet thickness over facet width at which the local term's coefficients are stated
#: (docs/load_cases.md, section 2): the local term is c h sqrt(LOCAL_T_OVER_W / (t / W)).
LOCAL_T_OVER_W = 0.01


def local_depth(h: Any, W: Any, t: Any) -> Any:
    """The length (mm) that a load case's local coefficient c multiplies: h sqrt(0.01 W / t),
    the depth ``h`` (mm) scaled by the square root of :data:`LOCAL_T_OVER_W` over the sheet's
    ``t`` / ``W`` (mm / mm): the thinner the sheet beside its facets, the more it deforms under
    the load and support lines (docs/load_cases.md, section 2; docs/validation/load_cases.md,
    "The local term"). Floats, arrays and intervals."""
    r = (LOCAL_T_OVER_W * W) / t
    return h * (r.sqrt() if hasattr(r, "sqrt") else np.sqrt(r))


#: Angles are rounded to this many decimals of a degree before the crease directions are
#: recognised, so that eta and its mirror image 90 - eta (or eta - 90, as layer 2 sees it) fall on
#: the same side of a crease direction whatever the rounding of the subtraction (1e-9 deg: far
#: below any test's angle, far above the 1.4e-14 deg rounding of 90 - eta).
ANGLE_DECIMALS = 9


def on_grid(theta_deg: float, period: float = 180.0) -> float:
    """``theta_deg`` modulo ``period`` (deg), rounded to :data:`ANGLE_DECIMALS` decimals: in
    ``[0, period)``, exactly 0 or 90 on a crease direction."""
    t = round(float(theta_deg) % period, ANGLE_DECIMALS)
    return 0.0 if t >= period else t


def _cs(theta_deg: float) -> tuple[float, float]:
    """cos^2 and sin^2 of theta (deg), exactly 1 and 0 on the crease directions (theta on the
    rounding of :func:`on_grid`)."""
    t = on_grid(theta_deg)
    if t == 0.0:
        return 1.0, 0.0
    if t == 90.0:
        return 0.0, 1.0
    th = np.radians(t)
    return float(np.cos(th) ** 2), float(np.sin(th) ** 2)


def _plate(along: Any, across: Any, shear: Any, theta_deg: float) -> Any:
    c2, s2 = _cs(theta_deg)
    if s2 == 0.0:
        return along
    if c2 == 0.0:
        return across
    # a spring of 0 (every facet cut by a hole) makes its term infinite and the layer's share 0
    with np.errstate(divide="ignore", over="ignore"):
        return 1.0 / (c2 * c2 / along + s2 * s2 / across + s2 * c2 / shear)


def free_inplane(K_S: Any, K_C: Any, K_T: Any, theta_deg: float) -> Any:
    """K (N/mm) of one free layer loaded at theta (deg) from its creases: plate lower bound."""
    return _plate(K_S, K_C, K_T, theta_deg)


def strip_fraction(theta_deg: float, span_over_width: Any = 1.0) -> Any:
    """Share of a coupon's facets that run from one support to the other at theta (deg): 1 -
    (span / width) |tan theta|, at least 0 (1 - |tan theta| for a square)."""
    c2, s2 = _cs(theta_deg)
    if s2 == 0.0:
        return 1.0
    if c2 == 0.0:
        return 0.0
    tan = float(np.sqrt(s2 / c2))
    if isinstance(span_over_width, float | int) and span_over_width == 1:
        return max(0.0, 1.0 - tan)
    return np.maximum(1.0 - span_over_width * tan, 0.0)  # arrays and intervals


def facet_share(n: Any) -> Any:
    """1 / (n + 1): the share of one facet in a layer of ``n`` creases (n + 1 facets), the strip
    bound's loss to where a finite coupon is cut (:func:`free_bending`; docs/load_cases.md 5).
    Falls with n; arrays (n >= 0)."""
    return 1.0 / (np.maximum(np.asarray(n, dtype=np.float64), 0.0) + 1.0)


def free_bending(
    D_S: Any,
    D_C: Any,
    D_T: Any,
    theta_deg: float,
    span_over_width: Any = 1.0,
    facet: Any = 0.0,
) -> Any:
    """D (N mm) of one free layer bent about theta (deg) from its creases: the larger of the
    plate and the strip lower bounds (module docstring), on a coupon whose span is
    ``span_over_width`` times its width (1: a square). The strip bound counts the share f of the
    facets that run from support to support less ``facet``, one facet's share of the layer
    (:func:`facet_share`: a finite coupon holds a whole number of such strips, one fewer than
    (n + 1) f on average over where it is cut; docs/load_cases.md 5): D_S c^4 max(0, f -
    facet). ``facet`` 0 is the homogenised count."""
    c2, s2 = _cs(theta_deg)
    if s2 == 0.0:  # along the creases plate and strip bounds are both D_S
        return D_S
    plate = _plate(D_S, D_C, D_T, theta_deg)
    f = strip_fraction(theta_deg, span_over_width)
    if isinstance(f, float) and f == 0.0:
        return plate
    counted = np.maximum(f - facet, 0.0)  # intervals too (Interval.__array_ufunc__)
    if isinstance(counted, float) and counted == 0.0:
        return plate
    strip = D_S * (c2 * c2) * counted
    return np.maximum(plate, strip)  # intervals too (Interval.maximum)


def _free_pair(
    kind: Literal["K", "D"],
    s1: Any,
    s2: Any,
    eta_deg: float,
    scale: tuple[tuple[Any, Any], tuple[Any, Any]] | None = None,
    r: Any = 1.0,
) -> Any:
    """The free panel's K or D from the two layers' springs: with ``scale`` = ((g1, h1), (g2,
    h2)) each layer's parallel and shear springs times g and its series spring times h, and the
    strip bound on a coupon of span over width ``r`` (None, 1: the layout's own springs; a
    coupon: :func:`assembly_directional`)."""
    if scale is None:
        if kind == "K":
            return free_inplane(s1.K_S, s1.K_C, s1.K_T, eta_deg) * _finite(
                s1, eta_deg
            ) + free_inplane(s2.K_S, s2.K_C, s2.K_T, eta_deg - 90.0) * _finite(s2, eta_deg)
        d1 = free_bending(s1.D_S, s1.D_C, s1.D_T, eta_deg, 1.0, s1.facet)
        d2 = free_bending(s2.D_S, s2.D_C, s2.D_T, eta_deg - 90.0, 1.0, s2.facet)
        return d1 * _finite(s1, eta_deg, _B) + d2 * _finite(s2, eta_deg, _B)
    (g1, h1), (g2, h2) = scale
    if kind == "K":
        return free_inplane(s1.K_S * g1, s1.K_C * h1, s1.K_T * g1, eta_deg) * _finite(
            s1, eta_deg
        ) + free_inplane(s2.K_S * g2, s2.K_C * h2, s2.K_T * g2, eta_deg - 90.0) * _finite(
            s2, eta_deg
        )
    d1 = free_bending(s1.D_S * g1, s1.D_C * h1, s1.D_T * g1, eta_deg, r, s1.facet)
    d2 = free_bending(s2.D_S * g2, s2.D_C * h2, s2.D_T * g2, eta_deg - 90.0, r, s2.facet)
    return d1 * _finite(s1, eta_deg, _B) + d2 * _finite(s2, eta_deg, _B)


#: c of the finite-panel deficit of off-axis bending, c / sqrt(n) (docs/load_cases.md,
#: section 5): smaller than K's (:data:`FINITE_PANEL_DEFICIT`), since it covers only where the
#: coupon is cut (a whole number of facets runs from support to support).
FINITE_PANEL_BENDING = 0.3
_B = FINITE_PANEL_BENDING / FINITE_PANEL_DEFICIT


def _finite(springs: Any, eta_deg: float, share: float = 1.0) -> Any:
    """The finite-panel factor of a layer's share of K (``share`` 1) or D (``share`` = :data:`
    FINITE_PANEL_BENDING` / :data:`FINITE_PANEL_DEFICIT`) at eta: 1 on the crease directions
    (exact there), 1 - w(eta) share d(n) off them with d(n) the springs' ``deficit``
    (:func:`finite_panel_factor`; n >= 1, where 0.6 / sqrt(n) <= 1, so the share scales the
    deficit itself)."""
    w = finite_panel_weight(eta_deg)
    return 1.0 if w == 0.0 else 1.0 - springs.deficit * (w * share)


@dataclass(frozen=True)
class Coupon:
    """How a layout that is not a square is read off the crease directions (arrays or
    intervals): ``aspect`` = Lx / Ly of its box, ``pq1`` and ``pq2`` the two layers' geometry
    factors p sum_j 1/L_j without holes (the springs over the plate stiffnesses: Lx / Ly and
    Ly / Lx for a rectangle), and ``capped``: whether the value is also kept at most the
    square's formula on the layout's own springs (circles and polygons, whose coupon is a
    convention: see :func:`assembly_directional`)."""

    aspect: Any
    pq1: Any
    pq2: Any
    capped: bool = False


def assembly_directional(
    kind: Literal["K", "D"],
    springs: tuple[Any, Any],
    eta_deg: float,
    support: str = DEFAULT_SUPPORT,
    coupon: Coupon | None = None,
) -> Any:
    """K(eta) (N/mm) or D(eta) (N mm) of the two-layer assembly at one direction eta (deg from
    layer 1's creases) under ``support``, any registered support condition
    (:func:`corrugate.mechanics.behaviours.get_support`: :func:`frame_rule` for ``frame``,
    :func:`free_panel` for ``free``); ``springs`` are the layers'
    :class:`~corrugate.mechanics.springs.LayerSprings` (or anything with the same fields,
    intervals too) and ``coupon`` the layout's (:class:`Coupon`; None: a square)."""
    return get_support(support).model(kind, springs, eta_deg, coupon)


def frame_rule(kind: str, springs: tuple[Any, Any], eta_deg: float, coupon: Any = None) -> Any:
    """The paper's rule (docs/theory.md 3.3), ``support = "frame"``: K(eta) = (K_S1 + K_C2)
    cos^2 + (K_S2 + K_C1) sin^2 (N/mm), D likewise (N mm); ``coupon`` is not read (the frame
    drives both crease directions whatever the outline)."""
    s1, s2 = springs
    c2, s2_ = _cs(eta_deg)
    if kind == "K":
        return (s1.K_S + s2.K_C) * c2 + (s2.K_S + s1.K_C) * s2_
    return (s1.D_S + s2.D_C) * c2 + (s2.D_S + s1.D_C) * s2_


def free_panel(
    kind: str, springs: tuple[Any, Any], eta_deg: float, coupon: Coupon | None = None
) -> Any:
    """K(eta) (N/mm) or D(eta) (N mm) of the assembly with free sides, ``support = "free"``:
    the layers in parallel, layer 1 at theta = eta and layer 2 (turned by 90 deg) at theta =
    eta - 90, each by the lower bounds of the module docstring, for a square.

    A layout that is not a square (``coupon``, :class:`Coupon`; None: a square) is taken off the
    crease directions as the coupon of its box's proportions cut along eta, turned to the crease
    direction nearer to eta: width across eta / length along eta f = Lx / Ly below 45 deg,
    Ly / Lx above, the smaller of the two values at 45. A layer's springs are its plate
    stiffnesses times its geometry factor pq (parallel and shear springs) or over it (series),
    and a coupon's stiffness is its plate stiffness times f; so the coupon is the square's
    formula on each layer's springs times f / pq (parallel, shear) and f pq (series), with the
    strip bound's span over width 1 / f. For a rectangle (pq1 = Lx / Ly, pq2 = Ly / Lx) this is
    derived and checked against FE coupons of the rectangle's proportions (docs/offaxis.md,
    "Rectangles"): the layout's own springs mix Lx / Ly (spanwise) and Ly / Lx (chordwise) in
    one compliance, which no coupon has, and gave 42.9 N/mm for 48 x 96 mm at 15 deg where the
    FE coupon gives 13.4 at 4 elements per facet. A circle or polygon has no straight edges to
    load; its value is the smaller of its box's coupon and the square's formula on its own
    springs (``capped``), so it is never more than either."""
    k: Literal["K", "D"] = "K" if kind == "K" else "D"
    s1, s2 = springs
    c2, s2_ = _cs(eta_deg)
    if coupon is None or c2 == 0.0 or s2_ == 0.0:  # a square, or along the creases
        return _free_pair(k, s1, s2, eta_deg)
    c = coupon
    e = float(eta_deg) % 180.0
    e = min(e, 180.0 - e)

    def oriented(f: Any) -> Any:  # the coupon of width / length f
        scale = ((f / c.pq1, f * c.pq1), (f / c.pq2, f * c.pq2))
        return _free_pair(k, s1, s2, eta_deg, scale, 1.0 / f)

    if e < 45.0:
        value = oriented(c.aspect)
    elif e > 45.0:
        value = oriented(1.0 / c.aspect)
    else:
        value = np.minimum(oriented(c.aspect), oriented(1.0 / c.aspect))
    return np.minimum(value, _free_pair(k, s1, s2, eta_deg)) if c.capped else value
