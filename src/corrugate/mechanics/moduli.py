"""Equivalent plate moduli of one zig-zag (triangular) corrugated layer, in three named variants.

Each facet of a layer is replaced by a flat plate of thickness t and width p = W sin(alpha/2)
(docs/theory.md section 3.1). The four equivalent Young's moduli, all in the unit of ``E`` (MPa), are

* ``Ecx``: in-plane, chordwise (across the creases),
* ``Ecy``: in-plane, spanwise (along the creases),
* ``Ebx``: bending, chordwise,
* ``Eby``: bending, spanwise.

Variants (select by name everywhere a stiffness is computed):

``paper``
    The four formulas exactly as printed in Liu, Yan and Mehta (eqs. Ecx-Eby), kept to reproduce the
    paper's numbers. Known errors: Ecx 55-89 % too low, Ecy off by -4 % to +16 %, Ebx misses a
    factor 2 s on its t^2 term (docs/theory.md 3.1).
``xia``
    Xia, Friswell and Saavedra Flores (2012), Int. J. Solids Struct. 49:1453, specialised to the
    zig-zag and simplified: what the paper meant to print.
``refined`` (default)
    ``xia`` with the spanwise bending of Ye et al. (2014), Eby = E (s + W^2 c^2 / (t^2 s)): facets
    stretched along the creases contract freely, so their membrane stiffness is E t, not
    E t / (1 - nu^2).

How far ``refined`` is from the periodic unit-cell FE (:mod:`corrugate.fea.unitcell`, solid
mitred creases, mesh-converged by a refinement series extrapolated to zero element size; docs/fea.md
section 1.3, ``benchmarks/unitcell_range.py``), measured for nu = 0.43 over alpha = 40-115 deg and
t/W = 0.0067-0.02 (the paper's t = 0.125 mm with W = 8-18.75 mm, and t/W = 0.02): Ecy exact and
Eby within 0.4 % everywhere; Ecx and Ebx are **below** the FE, by a gap that grows with t/W and
with the depth of the fold (the FE's solid crease is stiffer than the closed forms' line crease):

    alpha (deg)   Ecx below FE   Ebx below FE
    40            3.3-10.5 %     1.1-3.6 %      (t = 0.125, W = 8-14 mm: 4.6-7.3 % and 1.6-2.5 %)
    65            1.3-3.9 %      0.5-1.3 %
    90            0.5-1.5 %      0.2-0.5 %
    115           0.1-0.5 %      0.04-0.2 %

So all four are within 1 % only at alpha = 115 deg (whole t/W range) and at alpha = 90 deg up to
t/W = 0.009; the errors are on the safe side (the closed forms understate what the FE cell carries).
At alpha = 40 deg these FE values are extrapolations of uniform meshes; the graded cell (docs/fea.md
1.3, converged within 0.1 %) differs from them by -1.2 to +0.2 % (t/W = 0.02 to 0.0156), so the
alpha = 40 deg gaps carry that much uncertainty.

All functions broadcast over NumPy arrays: a sweep over a million designs is one call. W, s and
c are the layer's cross-section, :class:`corrugate.geometry.profile.ZigZag`
(:meth:`ModuliModel.of_profile`); another profile's moduli come from Xia's general theory
(:func:`corrugate.mechanics.profiles.profile_moduli`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from corrugate.core.errors import InputError, UnknownNameError
from corrugate.geometry.profile import ZigZag
from corrugate.names import DEFAULT_MODEL

__all__ = ["DEFAULT_MODEL", "MODELS", "Moduli", "ModuliModel", "get_model", "moduli"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, slots=True)
class Moduli:
    """The four equivalent moduli (MPa); each is a float array broadcast over the inputs."""

    Ecx: FloatArray
    Ecy: FloatArray
    Ebx: FloatArray
    Eby: FloatArray

    def as_dict(self) -> dict[str, float]:
        """Scalar moduli as a dict (only for scalar inputs)."""
        return {k: float(getattr(self, k)) for k in ("Ecx", "Ecy", "Ebx", "Eby")}


ModuliFunction = Callable[[FloatArray, FloatArray, FloatArray, FloatArray, FloatArray], Moduli]
#: ``(E, nu, t, W, s, c) -> Moduli`` with s = sin(alpha/2), c = cos(alpha/2) already computed.
ModuliFromSC = Callable[
    [FloatArray, FloatArray, FloatArray, FloatArray, FloatArray, FloatArray], Moduli
]


@dataclass(frozen=True, slots=True)
class ModuliModel:
    """A named moduli variant: ``function(E, nu, t, W, alpha_rad) -> Moduli``, the same formulas
    as ``of_profile(E, nu, t, zigzag)`` for callers that hold the layer's
    :class:`~corrugate.geometry.profile.ZigZag` (the vectorised evaluator builds it once per
    layer), and ``from_sc(E, nu, t, W, s, c)`` with s = sin(alpha/2), c = cos(alpha/2)."""

    name: str
    from_sc: ModuliFromSC
    source: str
    #: Poisson's ratios at or below this give a negative modulus (None: any -1 < nu < 0.5).
    nu_min: float | None = None

    def check_nu(self, nu: float, field: str = "nu") -> None:
        """An :class:`~corrugate.core.errors.InputError` naming ``field`` when the variant's formulas
        are not positive at Poisson's ratio ``nu``."""
        if self.nu_min is not None and not nu > self.nu_min:
            raise InputError(
                field,
                f"{nu:g}",
                f"nu > {self.nu_min:.4f} for model '{self.name}' (its printed Ecx changes sign "
                "at nu = 1 - sqrt(2)); the 'refined' and 'xia' models take any -1 < nu < 0.5",
                reason="is outside the model's range",
            )

    def function(
        self, E: FloatArray, nu: FloatArray, t: FloatArray, W: FloatArray, alpha: FloatArray
    ) -> Moduli:
        """The moduli (unit of ``E``) at fold angle ``alpha`` (rad)."""
        return self.of_profile(E, nu, t, _zigzag(W, alpha))

    def of_profile(self, E: Any, nu: Any, t: Any, profile: ZigZag) -> Moduli:
        """The moduli (unit of ``E``) of a sheet (``E``, ``nu``, ``t`` mm) folded to the zig-zag
        ``profile`` (:class:`corrugate.geometry.profile.ZigZag`: its W, s and c); floats, arrays
        or intervals alike."""
        return self.from_sc(E, nu, t, profile.W, profile.s, profile.c)


def _zigzag(W: FloatArray, alpha: FloatArray) -> ZigZag:
    """The zig-zag of facet width ``W`` at the fold angle ``alpha`` (rad): sin and cos of
    0.5 alpha."""
    return ZigZag.of_half(W, 0.5 * alpha)


def paper_moduli_sc(
    E: FloatArray, nu: FloatArray, t: FloatArray, W: FloatArray, s: FloatArray, c: FloatArray
) -> Moduli:
    """:func:`paper_moduli` from s = sin(alpha/2) and c = cos(alpha/2); cos(alpha) + 1 = 2 c^2.

    The nu polynomials enter with both the numerator's and the denominator's sign flipped
    (exact in floating point: the same numbers), so that for 0 <= nu < 0.5 every factor is
    positive, which keeps interval evaluations (:mod:`corrugate.solver.interval`) on their
    cheap non-negative path."""
    nu2 = nu * nu
    t2 = t * t
    W2 = W * W
    s2 = s * s
    c2 = c * c
    k = 1 - nu2
    Ecx = (
        E
        * t2
        * -(nu2 - 2 * nu - 1)
        * s
        / (
            -(3 * nu2 * nu2 + 2 * nu2 * nu - nu - 3) * t2 * s2
            + -(-nu2 * nu2 + 2 * nu2 * nu + 4 * nu2 - 2 * nu - 3) * W2 * c
        )
    )
    Ecy = E * -(nu2 - 2 * nu - 3) / (4 * -(nu2 - 1) * s)
    Ebx = E * (W2 * (2 * c2) * s + t2 * k * s2) / (2 * k * (W2 * c2 + t2 * s2))
    Eby = E * (s + W2 * c2 / (t2 * k * s))
    return Moduli(Ecx, Ecy, Ebx, Eby)


def paper_moduli(
    E: FloatArray, nu: FloatArray, t: FloatArray, W: FloatArray, alpha: FloatArray
) -> Moduli:
    """The moduli exactly as printed in Liu, Yan and Mehta, eqs. (Ecx), (Ecy), (Ebx), (Eby).

    Units follow ``E``; ``t`` and ``W`` in the same length unit; ``alpha`` in radians. The
    printed cos(alpha) + 1 of Ebx is evaluated as 2 cos^2(alpha/2) (the same number).
    """
    z = _zigzag(W, alpha)
    return paper_moduli_sc(E, nu, t, z.W, z.s, z.c)


def xia_moduli_sc(
    E: FloatArray, nu: FloatArray, t: FloatArray, W: FloatArray, s: FloatArray, c: FloatArray
) -> Moduli:
    """:func:`xia_moduli` from s = sin(alpha/2) and c = cos(alpha/2)."""
    k = 1 - nu * nu
    Wc2 = (W * c) ** 2
    ts2 = (t * s) ** 2
    Ecx = E * t**2 * s / (ts2 + k * Wc2)
    Ecy = E / s
    Ebx = E * s * (Wc2 + k * ts2) / (k * (Wc2 + ts2))
    Eby = E * (s + Wc2 / (t**2 * k * s))
    return Moduli(Ecx, Ecy, Ebx, Eby)


def xia_moduli(
    E: FloatArray, nu: FloatArray, t: FloatArray, W: FloatArray, alpha: FloatArray
) -> Moduli:
    """Xia et al. (2012) A and D of the zig-zag, reduced to moduli (docs/theory.md 3.1, 'checked').

    Ecx = E t^2 s / (t^2 s^2 + (1 - nu^2) W^2 c^2), Ecy = E / s,
    Ebx = E s [W^2 c^2 + (1 - nu^2) t^2 s^2] / [(1 - nu^2)(W^2 c^2 + t^2 s^2)],
    Eby = E [s + W^2 c^2 / (t^2 (1 - nu^2) s)].
    """
    z = _zigzag(W, alpha)
    return xia_moduli_sc(E, nu, t, z.W, z.s, z.c)


def refined_moduli_sc(
    E: FloatArray, nu: FloatArray, t: FloatArray, W: FloatArray, s: FloatArray, c: FloatArray
) -> Moduli:
    """:func:`refined_moduli` from s = sin(alpha/2) and c = cos(alpha/2)."""
    k = 1 - nu * nu
    Wc2 = (W * c) ** 2
    t2 = t**2
    ts2 = t2 * s * s
    Ecx = E * t2 * s / (ts2 + k * Wc2)
    Ecy = E / s
    Ebx = E * s * (Wc2 + k * ts2) / (k * (Wc2 + ts2))
    Eby = E * (s + Wc2 / (t2 * s))
    return Moduli(Ecx, Ecy, Ebx, Eby)


def refined_moduli(
    E: FloatArray, nu: FloatArray, t: FloatArray, W: FloatArray, alpha: FloatArray
) -> Moduli:
    """``xia`` with the refined spanwise bending Eby = E [s + W^2 c^2 / (t^2 s)] (Ye et al. 2014).

    Default variant. Against the mesh-converged periodic unit-cell FE (module docstring): Ecy
    exact, Eby within 0.4 %, Ecx 0.1-10.5 % and Ebx 0.04-3.6 % below the FE over alpha = 40-115
    deg and t/W = 0.0067-0.02 (largest at alpha = 40 deg, t/W = 0.02; all within 1 % only at
    alpha = 115 deg, and at 90 deg up to t/W = 0.009).
    """
    z = _zigzag(W, alpha)
    return refined_moduli_sc(E, nu, t, z.W, z.s, z.c)


MODELS: dict[str, ModuliModel] = {
    "paper": ModuliModel(
        "paper",
        paper_moduli_sc,
        "Liu, Yan and Mehta, eqs. Ecx-Eby, as printed (reproduces Table 1)",
        # the printed Ecx's numerator nu^2 - 2 nu - 1 vanishes at nu = 1 - sqrt(2)
        nu_min=1.0 - math.sqrt(2.0),
    ),
    "xia": ModuliModel(
        "xia", xia_moduli_sc, "Xia, Friswell and Saavedra Flores (2012), zig-zag, corrected"
    ),
    "refined": ModuliModel(
        "refined",
        refined_moduli_sc,
        "Xia (2012) with the spanwise bending of Ye et al. (2014); agrees with unit-cell FE",
    ),
}


def get_model(name: str) -> ModuliModel:
    """The moduli variant called ``name``; :class:`UnknownNameError` if there is none."""
    key = name.strip().lower()
    if key not in MODELS:
        raise UnknownNameError("model", name, list(MODELS))
    return MODELS[key]


def moduli(
    E: ArrayLike,
    nu: ArrayLike,
    t: ArrayLike,
    W: ArrayLike,
    alpha_deg: ArrayLike,
    model: str = DEFAULT_MODEL,
) -> Moduli:
    """Equivalent moduli (unit of ``E``) of a zig-zag layer; ``alpha_deg`` in degrees.

    Inputs broadcast against each other; no validation is done here (the input limits are
    :mod:`corrugate.core.limits`, which the command line, spec and web API apply), so this is the
    fast path for sweeps.
    """
    arrays = np.broadcast_arrays(
        *(np.asarray(a, dtype=np.float64) for a in (E, nu, t, W, alpha_deg))
    )
    E_, nu_, t_, W_, a_ = arrays
    result = get_model(model).function(E_, nu_, t_, W_, np.radians(a_))
    return Moduli(
        *(np.broadcast_to(x, E_.shape) for x in (result.Ecx, result.Ecy, result.Ebx, result.Eby))
    )
