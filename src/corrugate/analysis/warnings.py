"""Warnings attached to every result: where the model is being used outside its evidence.

* fewer facets than the homogenised spring model was validated for against FE
  (``data/validity.toml``, docs/validation/ranges.md; the solver makes that range a
  constraint, :mod:`corrugate.solver.validity`, so only ``analyze`` and an extrapolated answer
  show it);
* thick sheets: the closed forms assume zero-thickness creases; periodic unit-cell FE
  (``docs/data/unitcell_fe.csv``) puts the resulting error in Ecx and Ebx at about t/W at
  alpha = 90 deg, growing as (90 deg / alpha)^2 for sharper folds (9 % at t/W = 0.02, 45 deg);
* a thickness the material is not sold in (the library lists what is sold);
* short panels: D is a pure-bending stiffness; a panel loaded as a short beam also shears. The
  shell FE of docs/fea.md (section 3) measured the 3-point shear compliance at 1.1-2.0 times
  the Timoshenko estimate e = 2 (1 + nu) (W / L)^2 of the bending compliance,
  L = (n + 1) W sin(alpha/2), so the test reads D / (1 + k e), k e / (1 + k e) less
  (:func:`shear_share`: between 0 and 100 %);
* directions other than along the creases (eta not a multiple of 90 deg): each support
  condition's own text (:mod:`corrugate.mechanics.supports`): with ``support = "free"`` K(eta) and
  D(eta) are the free-panel model of :mod:`corrugate.mechanics.offaxis` (lower bounds of the
  homogenised plate; docs/validation/off_axis.md compares them with FE coupons); with
  ``"frame"`` the paper's cos^2 rule, which holds only for a panel held in a rigid frame
  (docs/fea.md 2.5);
* the ``paper`` model, which has known errors (docs/theory.md 3.1);
* a wheel-test design outside the FE sweep that gives the test's factor (:func:`wheel_warnings`;
  the solver makes that range a constraint).

A repeated code is one warning (:func:`group_warnings`), and each says what to do. The range
the paper tested on the bench (n 7-13, W 8-14 mm, alpha 40-115 deg; Liu, Yan and Mehta, section
'Model Validation') is information, not a warning (:func:`bench_notes`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

from corrugate.geometry.layer import Assembly, Layer, crease_layer
from corrugate.geometry.profile import ZigZag
from corrugate.mechanics.behaviours import get_support, support_names
from corrugate.mechanics.validity import model_range
from corrugate.names import DEFAULT_LAYOUT, DEFAULT_SUPPORT

__all__ = [
    "CREASE_ERROR_LIMIT",
    "SHEAR_LIMIT",
    "VALIDATED",
    "ModelWarning",
    "bench_notes",
    "crease_error_estimate",
    "design_warnings",
    "group_warnings",
    "shear_estimate",
    "shear_share",
    "wheel_warnings",
]

#: Ranges validated experimentally in the paper.
VALIDATED = {"n": (7, 13), "W": (8.0, 14.0), "alpha": (40.0, 115.0)}
#: Estimated crease-thickness error above which a sheet counts as thick.
CREASE_ERROR_LIMIT = 0.05
#: Timoshenko shear estimate above which a short-panel warning is given.
SHEAR_LIMIT = 0.05
#: The shell FE's 3-point shear compliance over the Timoshenko estimate (docs/fea.md 3).
SHEAR_FACTORS = (1.1, 2.0)


def shear_estimate(nu: float, n: int, alpha_deg: float) -> float:
    """Timoshenko estimate of the shear share of a 3-point deflection, 2 (1 + nu) (W/L)^2 with
    W / L = 1 / ((n + 1) sin(alpha/2)) (docs/fea.md, section 3)."""
    # W / L = W / ((n + 1) W s): the extent of the zig-zag of unit facet width
    ratio: float = 1.0 / ZigZag.of_float(1.0, alpha_deg).extent(n)
    return 2 * (1 + nu) * ratio**2


@dataclass(frozen=True, slots=True)
class ModelWarning:
    """A warning: a stable ``code`` for programs and a ``message`` for people."""

    code: str
    message: str

    def as_dict(self) -> dict[str, str]:
        return {"code": self.code, "message": self.message}


def crease_error_estimate(t: float, W: float, alpha_deg: float) -> float:
    """Estimated relative error of Ecx and Ebx from finite crease thickness: (t/W)(90/alpha)^2."""
    return (t / W) * (90.0 / alpha_deg) ** 2


def bench_notes(a: Assembly) -> list[ModelWarning]:
    """Information, not a warning: the parameters of ``a``'s layers outside the range the paper
    tested on the bench (:data:`VALIDATED`), one note per layer (both layers once when they are
    identical). The models are validated against FE over wider ranges, which the solver
    enforces (docs/validation/ranges.md)."""
    out: list[ModelWarning] = []
    layers = (
        [("both layers", a.layer1)]
        if a.layer2 == a.layer1
        else list(zip(("layer 1", "layer 2"), a.layers, strict=True))
    )
    for label, layer in layers:
        checks = (("n", layer.n, ""), ("W", layer.W, " mm"), ("alpha", layer.alpha_deg, " deg"))
        said = []
        for name, value, unit in checks:
            lo, hi = VALIDATED[name]
            if not lo <= value <= hi:
                said.append(f"{name} = {value:g}{unit} ({lo:g}-{hi:g}{unit})")
        if said:
            out.append(
                ModelWarning(
                    "paper-bench-range",
                    f"{label}: {', '.join(said)} outside the range the paper tested on the "
                    "bench; the models are validated against FE over the ranges of "
                    "`corrugate docs validation/ranges`",
                )
            )
    return out


def shear_share(shear: float, factor: float) -> float:
    """The fraction (0-1) by which a 3-point test reads D below the pure-bending D when the shear
    compliance is ``factor`` times the Timoshenko estimate ``shear`` of the bending compliance:
    D_3pt = D / (1 + factor shear), so 1 - D_3pt / D = factor shear / (1 + factor shear)."""
    return factor * shear / (1.0 + factor * shear)


def _layer_warnings(label: str, layer: Layer) -> list[ModelWarning]:
    out: list[ModelWarning] = []
    err = crease_error_estimate(layer.t, layer.W, layer.alpha_deg)
    if err > CREASE_ERROR_LIMIT:
        out.append(
            ModelWarning(
                "thick-sheet",
                f"{label}: t/W = {layer.t / layer.W:.3g} at alpha = {layer.alpha_deg:g} deg is a thick "
                f"sheet; the thin-sheet formulas may be off by about {100 * err:.0f} % in Ecx and Ebx: "
                "choose a thinner sheet or wider facets (fabrication.max_t_over_W)",
            )
        )
    sold = layer.material.thicknesses
    if sold and min(abs(layer.t - x) for x in sold) > 1e-6 * layer.t:
        out.append(
            ModelWarning(
                "unusual-thickness",
                f"{label}: t = {layer.t:g} mm is not a thickness {layer.material.id} is sold in "
                f"({', '.join(f'{x:g}' for x in sold)} mm): choose one of those or check the "
                "supplier",
            )
        )
    shear = shear_estimate(layer.material.nu, layer.n, layer.alpha_deg)
    if shear > SHEAR_LIMIT:
        lo, hi = (100 * shear_share(shear, k) for k in SHEAR_FACTORS)
        out.append(
            ModelWarning(
                "short-panel-shear",
                f"{label}: a short panel (L/W = {(layer.n + 1) * layer.s:.3g}); D is a pure-bending "
                f"stiffness, and a 3-point bending test may measure about {lo:.0f}-{hi:.0f} % "
                "less, from shear (finite elements: `corrugate docs fea`, section 3): bound the "
                'test itself (test = "three-point" or a [[constraints.deflection]]) if the part '
                "is loaded so",
            )
        )
    springs = model_range("springs")
    lo_facets = springs.ranges["facets"][0]
    if layer.n + 1 < lo_facets:
        out.append(
            ModelWarning(
                "outside-model-range",
                f"{label}: {layer.n + 1} facets; {springs.sentence('facets', 'min')} "
                "(`corrugate docs validation/ranges`): the solver certifies only inside it; "
                "check this design with corrugate verify",
            )
        )
    return out


def group_warnings(warnings: Sequence[ModelWarning]) -> list[ModelWarning]:
    """One warning per code: the messages of a repeated code joined by '; ', in first-seen
    order."""
    by_code: dict[str, list[str]] = {}
    for w in warnings:
        by_code.setdefault(w.code, []).append(w.message)
    return [ModelWarning(code, "; ".join(dict.fromkeys(msgs))) for code, msgs in by_code.items()]


def _off_axis(
    eta_deg: Sequence[float], support: str, layout: str = DEFAULT_LAYOUT
) -> list[ModelWarning]:
    """The ``off-axis`` warning of ``support`` (its entry's text,
    :mod:`corrugate.mechanics.supports`) at the directions off the creases; a name that is not
    registered reads as the default support, as the text always did."""
    off = [e for e in eta_deg if crease_layer(e) is None]
    if not off:
        return []
    angles = ", ".join(f"{e:g}" for e in off)
    entry = get_support(support if support in support_names() else DEFAULT_SUPPORT)
    return [ModelWarning("off-axis", entry.off_axis(angles, layout))]


def design_warnings(
    a: Assembly, model: str, eta_deg: Sequence[float] = (), support: str = DEFAULT_SUPPORT
) -> list[ModelWarning]:
    """Every warning for assembly ``a`` analysed with moduli variant ``model`` in the directions
    ``eta_deg`` (deg) under ``support`` (a registered support condition:
    :mod:`corrugate.mechanics.behaviours`)."""
    out = _layer_warnings("layer 1", a.layer1)
    if a.layer2 != a.layer1:
        out += _layer_warnings("layer 2", a.layer2)
    else:
        out = [ModelWarning(w.code, w.message.replace("layer 1", "both layers", 1)) for w in out]
    if model == "paper":
        from corrugate.mechanics.moduli import moduli

        for label, layer in (("layer 1", a.layer1), ("layer 2", a.layer2)):
            m = layer.material
            values = moduli(m.E, m.nu, layer.t, layer.W, layer.alpha_deg, "paper").as_dict()
            bad = [k for k, v in values.items() if not v > 0]
            if bad:
                out.append(
                    ModelWarning(
                        "paper-model-negative",
                        f"{label}: the printed formulas give non-positive {', '.join(bad)} here "
                        f"(nu = {m.nu:g}); the results are meaningless, use 'xia' or 'refined'",
                    )
                )
        out.append(
            ModelWarning(
                "paper-model",
                "model 'paper' uses the formulas as printed, with known errors (Ecx 55-89 % too low, "
                "Ecy and Ebx slightly off); use 'refined' for design",
            )
        )
    return group_warnings(out + _off_axis(eta_deg, support, a.layout.name))


def wheel_warnings(a: Assembly) -> list[ModelWarning]:
    """The ``wheel-outside-validated-range`` warning of a design with a bound in the wheel test
    (docs/load_cases.md 9) for each of its layer 1's creases n, angle alpha (deg), facet width W
    (mm), t / W and the axle hole's diameter over the disc's that lies outside the FE sweep that
    gives the factor c(eta) (:data:`corrugate.mechanics.wheel.VALIDATED_WHEEL`; a circle's layers
    are identical). A disc without a central circular hole is outside it too."""
    from corrugate.mechanics.wheel import VALIDATED_WHEEL

    lay = a.layer1
    diameter = a.Lx
    hub = [
        h
        for h in a.layout.holes
        if h.shape == "circle"
        and math.hypot(*h.center) + h.radius < 0.5 * diameter
        and math.hypot(*h.center) <= h.radius
    ]
    values = {
        "n": (float(lay.n), ""),
        "alpha": (lay.alpha_deg, " deg"),
        "W": (lay.W, " mm"),
        "t/W": (lay.t / lay.W, ""),
    }
    out: list[ModelWarning] = []
    if hub:
        values["hole/diameter"] = (2.0 * hub[0].radius / diameter, "")
    else:
        out.append(
            ModelWarning(
                "wheel-outside-validated-range",
                "the wheel test's factor was measured on discs with a central circular axle "
                "hole; this disc has none (`corrugate docs load_cases`, section 9)",
            )
        )
    for name, (value, unit) in values.items():
        lo, hi = VALIDATED_WHEEL[name]
        if not lo - 1e-9 <= value <= hi + 1e-9:
            out.append(
                ModelWarning(
                    "wheel-outside-validated-range",
                    f"{name} = {value:.4g}{unit} is outside the designs whose FE gives the wheel "
                    f"test's factor ({lo:.4g}-{hi:.4g}{unit}): the wheel bound is not validated "
                    "there; check it with corrugate verify (`corrugate docs load_cases`, section 9)",
                )
            )
    return out
