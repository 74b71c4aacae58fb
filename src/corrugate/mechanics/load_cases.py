"""The built-in load cases: what a stiffness or a deflection is in a stated test (docs/load_cases.md).

A support condition (:mod:`corrugate.mechanics.supports`) gives the panel's pure-bending
rigidity D(eta) (N mm) and its in-plane K(eta) (N/mm); a load case turns them into what a test
measures, in the user's terms: the deflection delta (mm) of the loading head under a load P (N),

* ``three-point``: simply supported over the span Ls, P at mid-span;
* ``four-point``: simply supported over Ls, P / 2 at a quarter and three quarters of the span,
  delta at the load points (the loading head's travel);
* ``cantilever``: clamped at the root, P at the free end Ls from it;
* ``platens``: compressed between rigid platens along eta (delta = P / K; no span: the panel's
  length along eta);
* ``wheel`` (circles, K only): a disc's radial stiffness between a ground patch and its axle,
  c(eta) K with the FE-validated factor of :mod:`corrugate.mechanics.wheel` (docs/load_cases.md 9).

For the bending tests (docs/load_cases.md, sections 2-3)

    delta / P = a Ls^3 / EI + (b Ls + c h_l) / S

with EI = D(eta) L the rigidity of the panel of length L along eta, S = V_S L the shear stiffness
of the facets acting as webs (:func:`corrugate.mechanics.offaxis.shear_spring`: (5/6) G t W c^2
per facet, the parabolic shear flow of each facet) and h_l = h sqrt(0.01 W / t) the local term's
length, h the depth W cos(alpha/2) of the corrugation
(:func:`corrugate.mechanics.offaxis.local_depth`): (a, b) are the Timoshenko beam's, and the
local term c h_l (c = 2 on line supports, 1.5 with a clamped root) bounds the extra compliance
FE shows at the load and support lines (docs/load_cases.md section 2). Off the crease directions
S and h_l are taken as V_S1 cos^2 + V_S2 sin^2 and the larger length (docs/load_cases.md,
section 2).

Every function is plain arithmetic, so it takes arrays and
:class:`~corrugate.solver.interval.Interval` values alike: the solver bounds the very formula a
design is reported with.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from corrugate.mechanics.behaviours import Behaviour, TestForm
from corrugate.mechanics.offaxis import SHEAR_CORRECTION
from corrugate.names import JOINTS as NAMED_JOINTS
from corrugate.names import RECTANGULAR_LAYOUTS

__all__ = [
    "BUILT_IN",
    "CANTILEVER",
    "DEFAULT_SAFETY_FACTOR",
    "FOUR_POINT",
    "JOINTS",
    "LOCAL",
    "LOCAL_CLAMPED",
    "PLATENS",
    "THREE_POINT",
    "WHEEL",
    "apparent",
    "band_walls",
    "load_capacity",
    "load_stiffness",
    "shear_and_depth",
    "stress_per_load",
    "wall_capacity",
    "walls_stiffness",
]

#: c of the local term c h sqrt(0.01 W / t) / S on line supports and loading lines (three- and
#: four-point; docs/load_cases.md, section 2): the FE rows need at most 1.38 (three-point) and
#: 1.35 (four-point), and the thinnest sheet's slow series leaves room for about 1.6
#: (docs/validation/load_cases.md, "The local term").
LOCAL = 2.0
#: c of the local term with a clamped root (cantilever): the FE rows need at most 0.93.
LOCAL_CLAMPED = 1.5

_BENDING_UNITS = {"EI": "N*mm^2", "D": "N*mm", "k": "N/mm", "Pmax": "N"}


def _no_model(kind: str, springs: tuple[Any, Any], eta_deg: float, coupon: Any) -> Any:
    """A load case is not a directional model of the springs alone: its value needs the panel's
    length and the span (:func:`load_stiffness`)."""
    raise TypeError("a load case's value is corrugate.mechanics.load_cases.load_stiffness")


def _warning(angles: str, layout: str) -> str:
    return (
        f"the test values at eta = {angles} deg use the free-panel D and K off the creases "
        "(`corrugate docs load_cases`): off-axis bending of a free panel depends on where the "
        "coupon is cut; check a part loaded there with corrugate validate --eta"
    )


def _entry(
    name: str,
    form: TestForm,
    fixture: str,
    label: str,
    suffix: str,
    text: str,
    **offered: Any,
) -> Behaviour:
    """A load case's entry; ``offered`` are its ``choice``, ``note``, ``layouts`` (default: the
    rectangular outlines, whose straight edges the test supports, clamps or loads) and
    ``stiffness_only`` (:class:`~corrugate.mechanics.behaviours.Behaviour`)."""
    units = _BENDING_UNITS if form.kind == "bending" else {"K": "N/mm", "k": "N/mm", "Pmax": "N"}
    return Behaviour(
        name=name,
        model=_no_model,
        bounds=_no_model,
        fixture=fixture,
        label=label,
        suffix=suffix,
        units=units,
        text=text,
        curve=name,
        off_axis=_warning,
        role="test",
        form=form,
        **{"layouts": RECTANGULAR_LAYOUTS, **offered},
    )


# The deflected shapes of the report's sketches (Euler-Bernoulli, x the fraction of the span,
# any scale; u the distance from the nearer support of a symmetric test).


def _mid_span_shape(x: Any) -> Any:
    """A simply supported beam under a mid-span load: w ~ u (3 - 4 u^2)."""
    u = np.minimum(x, 1 - x)
    return u * (3 - 4 * u**2)


def _quarter_points_shape(x: Any) -> Any:
    """A simply supported beam under equal loads at the quarter points (a = 1/4):
    w ~ u (3a - 3a^2 - u^2) outside the loads, a (3u - 3u^2 - a^2) between them."""
    u, a = np.minimum(x, 1 - x), 0.25
    return np.where(u <= a, u * (3 * a - 3 * a**2 - u**2), a * (3 * u - 3 * u**2 - a**2))


def _tip_load_shape(x: Any) -> Any:
    """A cantilever clamped at x = 0 under a tip load: w ~ x^2 (3 - x) / 2 (1 at the tip)."""
    return x**2 * (3 - x) / 2


THREE_POINT = _entry(
    "three-point",
    TestForm("bending", 1.0 / 48.0, 0.25, LOCAL, 0.25, loads=(0.5,), shape=_mid_span_shape),
    "three-point",
    " in three-point bending",
    "3pt",
    "simply supported over the span, the load at mid-span (the deflection under the load)",
)
FOUR_POINT = _entry(
    "four-point",
    TestForm(
        "bending", 1.0 / 96.0, 0.125, LOCAL, 0.125, loads=(0.25, 0.75), shape=_quarter_points_shape
    ),
    "four-point",
    " in four-point bending",
    "4pt",
    "simply supported over the span, half the load at each quarter point (the deflection there)",
)
CANTILEVER = _entry(
    "cantilever",
    TestForm(
        "bending",
        1.0 / 3.0,
        1.0,
        LOCAL_CLAMPED,
        1.0,
        loads=(1.0,),
        clamped=True,
        shape=_tip_load_shape,
    ),
    "cantilever",
    " as a cantilever",
    "cant",
    "clamped at the root, the load at the free end a span away (the deflection there)",
)
PLATENS = _entry(
    "platens",
    TestForm("inplane"),
    "platens",
    " between platens",
    "plat",
    "compressed between rigid platens along eta (the shortening)",
    choice="between platens",
    note="in-plane compression",
)


def _wheel_factor(eta_deg: float) -> float:
    """:func:`corrugate.mechanics.wheel.wheel_factor`, its module (the wheel test's FE factors)
    imported when a wheel test is first evaluated, not with this table (issue 39)."""
    from corrugate.mechanics.wheel import wheel_factor

    return wheel_factor(eta_deg)


WHEEL = _entry(
    "wheel",
    TestForm("inplane", factor=_wheel_factor),
    "wheel",
    " in the wheel test",
    "whl",
    "a disc's radial stiffness between a rigid ground patch under its rim (+-15 deg, no slip) "
    "and an axle pinned through its central hole, the load along eta (docs/load_cases.md 9)",
    note="its radial stiffness between a ground patch and an axle through its central hole: "
    "c(eta) K, eta a multiple of 45 deg; section 9",
    layouts=("circle",),
    stiffness_only=True,
)

#: The built-in load cases, in the order every list shows them (registered in this order by
#: :mod:`corrugate.mechanics.supports`): a new built-in test is its entry here and its place in
#: this tuple.
BUILT_IN: tuple[Behaviour, ...] = (THREE_POINT, FOUR_POINT, CANTILEVER, PLATENS, WHEEL)


def shear_and_depth(springs: tuple[Any, Any], c2: float, s2: float) -> tuple[Any, Any]:
    """V (N/mm) and the local term's length (mm, :func:`corrugate.mechanics.offaxis.
    local_depth`: the depth h times sqrt(0.01 W / t)) of the two layers' springs at a direction
    with cos^2 ``c2`` and sin^2 ``s2``: layer 1's on its creases (eta = 0), layer 2's on its own
    (90), V_S1 c^2 + V_S2 s^2 and the larger length in between (module docstring)."""
    a, b = springs
    if s2 == 0.0:
        return a.V_S, a.local
    if c2 == 0.0:
        return b.V_S, b.local
    return a.V_S * c2 + b.V_S * s2, _larger(a.local, b.local)


def _larger(x: Any, y: Any) -> Any:
    if hasattr(x, "maximum"):
        return x.maximum(y)
    return np.maximum(x, y)


def load_stiffness(
    form: TestForm,
    stiffness: Any,
    V: Any,
    local: Any,
    length: Any,
    span: Any | None = None,
    eta_deg: float = 0.0,
) -> Any:
    """P / delta (N/mm) of a load case: ``stiffness`` is the support's pure-bending D (N mm) for
    a bending test (EI = D x ``length``, the panel's length along eta in mm; S = ``V`` x length,
    ``local`` the local term's length h sqrt(0.01 W / t) in mm (:func:`shear_and_depth`),
    ``span`` the test's Ls in mm, the panel's length when None) or the
    in-plane K (N/mm) for an in-plane test (V, h and span not used), times the test's own
    factor at ``eta_deg`` (deg) when it has one (the wheel: docs/load_cases.md 9). Module
    docstring, docs/load_cases.md section 3."""
    if form.kind == "inplane":
        return stiffness if form.factor is None else stiffness * form.factor(eta_deg)
    Ls = length if span is None else span
    compliance = form.a * Ls**3 / (stiffness * length) + (form.b * Ls + form.c * local) / (
        V * length
    )
    return 1.0 / compliance


def apparent(form: TestForm, kind: str, k: Any, length: Any) -> Any:
    """The stiffness of ``kind`` that the test's own formula reads from P / delta = ``k`` over
    the panel's ``length`` (mm) as span: EI = a L^3 k (N mm^2), D = EI / L (N mm), K = k (N/mm),
    k itself."""
    if kind == "EI":
        return form.a * length**3 * k
    if kind == "D":
        return form.a * length**2 * k
    return k


#: Safety factor of a strength check unless the spec gives one (docs/load_cases.md, section 6).
DEFAULT_SAFETY_FACTOR = 2.0


def stress_per_load(
    form: TestForm,
    springs: tuple[Any, Any],
    along: int,
    stiffness: Any,
    E: tuple[float, float],
    t: tuple[float, float],
    length: Any,
    width: Any,
    span: Any | None = None,
) -> Any:
    """Peak facet stress per unit load (MPa/N) of a load case along a crease direction, of the
    layer along eta and of the other (a pair)
    (docs/load_cases.md, section 6; the formulas of :mod:`corrugate.mechanics.strength` written
    on the layers' springs, so that intervals bound them): ``along`` is the layer whose creases
    run along eta (0 or 1), ``stiffness`` the support's pure D (N mm, bending) or K (N/mm,
    platens), ``E``, ``t`` the layers' moduli (MPa) and thicknesses (mm), ``length`` (mm) the
    panel's length along eta, ``width`` (mm) across it and ``span`` the test's Ls (None: the
    length).

    Bending (the layers share the curvature kappa = M / (D L), M = moment x P x Ls): the layer
    along eta peaks at its crease lines, E kappa (h + t) / 2; the other carries its share
    M D_C / D as a plate moment over the width, 6 M D_C / (D width t^2). Platens (same strain
    delta / L): the layer along eta carries the membrane stress E / (K L) per newton; the other
    the crease moment of its share P K_C / K, (K_C / K) (3 h / t^2 + 1 / t) / width (the s / t
    membrane term of :func:`corrugate.mechanics.strength.chordwise_compression_stress` taken at
    its largest, s = 1)."""
    a, c = springs[along], springs[1 - along]
    Ea, ta = E[along], t[along]
    tc = t[1 - along]
    if form.kind == "inplane":
        own = Ea / (stiffness * length)
        other = (c.K_C / stiffness) * (3.0 * c.h / (tc * tc) + 1.0 / tc) / width
    else:
        Ls = length if span is None else span
        M = form.moment * Ls  # per newton
        own = Ea * M * (a.h + ta) / (2.0 * stiffness * length)
        other = 6.0 * M * c.D_C / (stiffness * width * tc * tc)
    return own, other


def load_capacity(
    per_load: tuple[Any, Any], allowable: tuple[float, float], safety_factor: float
) -> Any:
    """The largest load (N) at which each layer's peak stress times ``safety_factor`` stays at
    or below its ``allowable`` stress (MPa): the smaller of allowable / (safety_factor x sigma
    per newton) over (the layer along eta, the other), as :func:`stress_per_load` orders them."""
    own = allowable[0] / (safety_factor * per_load[0])
    other = allowable[1] / (safety_factor * per_load[1])
    if hasattr(own, "minimum"):
        return own.minimum(other)
    return np.minimum(own, other)


#: How the layers are joined (docs/load_cases.md, section 7): ``none`` ignores the connector
#: band (the paper's assumption; a lower bound); ``band-edges`` and ``band-flanges`` add the
#: band's two walls along the span as beams beside the layers (the same model for both: their
#: glue flanges are left out, which only lowers it).
JOINTS: tuple[str, ...] = NAMED_JOINTS


def band_walls(E: Any, nu: Any, t: Any, depth: Any, length: Any) -> tuple[Any, Any, Any]:
    """The band's two walls along a crease direction as beams (docs/load_cases.md, section 7):
    flat strips of height ``depth`` (the folded thickness t_d, mm), thickness ``t`` (mm, layer
    1's sheet, E MPa, nu) and ``length`` (mm, the panel's length along eta), bent in their own
    plane. Returns (D_w, S_w, K_w): their pure-bending D = 2 E t t_d^3 / (12 L) (N mm, as the
    panel's D: EI / L), their shear stiffness 2 (5/6) G t t_d (N) and their axial spring
    2 E t t_d / L (N/mm)."""
    G = E / (2.0 * (1.0 + nu))
    area = t * depth
    return (
        2.0 * E * area * depth * depth / (12.0 * length),
        2.0 * SHEAR_CORRECTION * G * area,
        2.0 * E * area / length,
    )


def walls_stiffness(
    form: TestForm, walls: tuple[Any, Any, Any], length: Any, span: Any | None = None
) -> Any:
    """P / delta (N/mm) of the band's walls alone in the load case ``form`` (Timoshenko beams,
    no local term: flat walls carry the load lines on their edges): a Ls^3 / (D_w L) + b Ls /
    S_w for bending, K_w for platens."""
    D_w, S_w, K_w = walls
    if form.kind == "inplane":
        return K_w
    Ls = length if span is None else span
    return 1.0 / (form.a * Ls**3 / (D_w * length) + form.b * Ls / S_w)


def wall_capacity(
    form: TestForm,
    stiffness: Any,
    E: Any,
    t: Any,
    depth: Any,
    length: Any,
    span: Any | None,
    allowable: float,
    safety_factor: float,
) -> Any:
    """The load (N) at which the band's walls reach ``allowable`` / ``safety_factor`` (MPa): at
    the panel's curvature M / (D L) (``stiffness`` the whole panel's D with its walls, N mm) the
    walls' edges, (t_d + t) / 2 from their middle, carry E kappa (t_d + t) / 2; between platens
    the walls' strain is the panel's, E P / (K L) (``stiffness`` its K, N/mm)."""
    if form.kind == "inplane":
        per = E / (stiffness * length)
    else:
        Ls = length if span is None else span
        per = E * form.moment * Ls * (depth + t) / (2.0 * stiffness * length)
    return allowable / (safety_factor * per)
