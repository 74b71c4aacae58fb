"""From facets to layers to the assembly: the spring model of the paper, vectorised.

Per layer, with p = W sin(alpha/2) and the sums over its n + 1 facets (DESIGN.md section 3.2; the
paper writes j = 1..n, but a layer with n creases has n + 1 facets and only that reproduces Table 1):

    K_C = 1 / sum_j p / (Ecx L_j t)          K_S = sum_j Ecy p t / L_j          [N/mm]
    D_C = 1 / sum_j 12 p / (Ebx L_j t^3)     D_S = sum_j Eby t^3 p / (12 L_j)   [N mm]

Every sum needs only q = sum_j 1/L_j, so a layer is fully described by (moduli, p, t, q). The
assembly along eta (the paper's rule for a panel in a rigid frame, DESIGN.md 3.3, or the free
panel) is :func:`corrugate.offaxis.assembly_directional`; EI(eta) = D(eta) x span(eta).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .moduli import Moduli
from .offaxis import shear_springs

__all__ = ["LayerSprings", "layer_springs"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, slots=True)
class LayerSprings:
    """Spring constants of one layer: K in N/mm, D in N mm (arrays)."""

    K_C: FloatArray
    K_S: FloatArray
    D_C: FloatArray
    D_S: FloatArray
    K_T: FloatArray  # in-plane shear (free-panel model, corrugate.offaxis)
    D_T: FloatArray  # twisting (free-panel model, corrugate.offaxis)


def layer_springs(
    m: Moduli,
    t: ArrayLike,
    pitch: ArrayLike,
    inv_length_sum: ArrayLike,
    E: ArrayLike,
    nu: ArrayLike,
    sin_half: ArrayLike,
    inv_length_sum_series: ArrayLike | None = None,
) -> LayerSprings:
    """Springs of a layer from its moduli (MPa), t (mm), pitch p (mm), q = sum_j 1/L_j (1/mm),
    and, for the shear and twisting springs of the free-panel model
    (:func:`corrugate.offaxis.shear_springs`), the sheet's E (MPa), nu and sin(alpha/2).

    With holes (:mod:`corrugate.holes`) the parallel sums (K_S, D_S, and the shear springs K_T,
    D_T) take ``inv_length_sum`` over the facets no hole touches and the series sums (K_C, D_C)
    ``inv_length_sum_series``, with the blocked lengths removed; without it both use
    ``inv_length_sum``."""
    t_ = np.asarray(t, dtype=np.float64)
    p = np.asarray(pitch, dtype=np.float64)
    q = np.asarray(inv_length_sum, dtype=np.float64)
    qs = q if inv_length_sum_series is None else np.asarray(inv_length_sum_series, np.float64)
    K_T, D_T = shear_springs(
        np.asarray(E, dtype=np.float64),
        np.asarray(nu, dtype=np.float64),
        t_,
        np.asarray(sin_half, dtype=np.float64),
        p * q,
    )
    with np.errstate(divide="ignore"):
        return LayerSprings(
            K_C=m.Ecx * t_ / (p * qs),
            K_S=m.Ecy * p * t_ * q,
            D_C=m.Ebx * t_**3 / (12 * p * qs),
            D_S=m.Eby * t_**3 * p * q / 12,
            K_T=np.asarray(K_T),
            D_T=np.asarray(D_T),
        )
