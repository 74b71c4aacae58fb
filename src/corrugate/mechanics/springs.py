"""From facets to layers to the assembly: the spring model of the paper, vectorised.

Per layer, with p = W sin(alpha/2) and the sums over its n + 1 facets (docs/theory.md section 3.2; the
paper writes j = 1..n, but a layer with n creases has n + 1 facets and only that reproduces Table 1):

    K_C = 1 / sum_j p / (Ecx L_j t)          K_S = sum_j Ecy p t / L_j          [N/mm]
    D_C = 1 / sum_j 12 p / (Ebx L_j t^3)     D_S = sum_j Eby t^3 p / (12 L_j)   [N mm]

Every sum needs only q = sum_j 1/L_j, so a layer is fully described by (moduli, p, t, q). The
assembly along eta (the paper's rule for a panel in a rigid frame, docs/theory.md 3.3, or the free
panel) is :func:`corrugate.mechanics.offaxis.assembly_directional`; EI(eta) = D(eta) x span(eta).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from corrugate.mechanics.moduli import Moduli
from corrugate.mechanics.offaxis import (
    facet_share,
    finite_panel_deficit,
    local_depth,
    shear_spring,
    shear_springs,
)

__all__ = ["LayerSprings", "layer_springs"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, slots=True)
class LayerSprings:
    """Spring constants of one layer: K in N/mm, D in N mm (arrays)."""

    K_C: FloatArray
    K_S: FloatArray
    D_C: FloatArray
    D_S: FloatArray
    K_T: FloatArray  # in-plane shear (free-panel model, corrugate.mechanics.offaxis)
    D_T: FloatArray  # twisting (free-panel model, corrugate.mechanics.offaxis)
    V_S: FloatArray  # transverse shear along the creases, per facet length (N/mm; load cases)
    h: FloatArray  # depth of the profile, W cos(alpha/2) for the zig-zag (mm; load cases)
    local: FloatArray  # the local term's length h sqrt(0.01 W / t) (mm; offaxis.local_depth)
    deficit: FloatArray  # finite-panel deficit of off-axis in-plane K (mechanics.offaxis)
    facet: FloatArray  # one facet's share 1 / (n + 1), the strip bound's loss (mechanics.offaxis)


def _num(x: ArrayLike) -> Any:
    """A 0-d input as a Python float (cheap scalar arithmetic), an array as float64."""
    a = np.asarray(x, dtype=np.float64)
    return float(a) if a.ndim == 0 else a


def layer_springs(
    m: Moduli,
    t: ArrayLike,
    pitch: ArrayLike,
    inv_length_sum: ArrayLike,
    E: ArrayLike,
    nu: ArrayLike,
    sin_half: ArrayLike,
    inv_length_sum_series: ArrayLike | None = None,
    *,
    web2: ArrayLike = 0.0,
    height: ArrayLike = 0.0,
    n: ArrayLike = 0.0,
) -> LayerSprings:
    """Springs of a layer from its moduli (MPa), t (mm), pitch p (mm), q = sum_j 1/L_j (1/mm),
    and, for the shear and twisting springs of the free-panel model
    (:func:`corrugate.mechanics.offaxis.shear_springs`), the sheet's E (MPa), nu and the profile's
    ``sin_half`` = pitch / developed (sin(alpha/2) for the zig-zag,
    :attr:`corrugate.geometry.profile.Profile.plan_ratio`).

    With holes (:mod:`corrugate.geometry.holes`) the parallel sums (K_S, D_S, and the shear springs K_T,
    D_T) take ``inv_length_sum`` over the facets no hole touches and the series sums (K_C, D_C)
    ``inv_length_sum_series``, with the blocked lengths removed; without it both use
    ``inv_length_sum``.

    For the load cases (:mod:`corrugate.mechanics.load_cases`), the profile's ``web2`` (its mean
    (dz/ds)^2, cos^2(alpha/2) for the zig-zag), ``height`` (mm, W cos(alpha/2) for the zig-zag)
    and ``n`` give the transverse shear spring V_S (:func:`corrugate.mechanics.offaxis.
    shear_spring`, on the parallel sum), the depth h (mm), the local term's length
    (:func:`corrugate.mechanics.offaxis.local_depth`, with W = pitch / ``sin_half``) and the
    finite-panel deficit of :func:`corrugate.mechanics.offaxis.finite_panel_deficit` and one
    facet's share of the layer (:func:`corrugate.mechanics.offaxis.facet_share`)."""
    t_ = _num(t)
    p = np.asarray(pitch, dtype=np.float64)
    pq = p * np.asarray(inv_length_sum, dtype=np.float64)
    series = inv_length_sum_series
    # without holes both sums are the same object (layouts.layer_inverse_sums): p q once
    pqs = pq if series is None or series is inv_length_sum else p * np.asarray(series, np.float64)
    K_T, D_T = shear_springs(_num(E), _num(nu), t_, np.asarray(sin_half, dtype=np.float64), pq)
    t3_12 = t_ * t_ * t_ / 12.0
    web = np.asarray(web2, dtype=np.float64)
    V_S = shear_spring(_num(E), _num(nu), t_, np.asarray(sin_half, dtype=np.float64), web, pq)
    height_ = np.asarray(height, dtype=np.float64)
    developed = p / np.asarray(sin_half, dtype=np.float64)  # the facet's developed width W
    with np.errstate(divide="ignore"):
        return LayerSprings(
            K_C=m.Ecx * t_ / pqs,
            K_S=m.Ecy * t_ * pq,
            D_C=m.Ebx * t3_12 / pqs,
            D_S=m.Eby * t3_12 * pq,
            K_T=K_T,
            D_T=D_T,
            V_S=V_S,
            h=height_,
            local=np.asarray(local_depth(height_, developed, t_), dtype=np.float64),
            deficit=finite_panel_deficit(np.asarray(n, dtype=np.float64)),
            facet=facet_share(np.asarray(n, dtype=np.float64)),
        )
