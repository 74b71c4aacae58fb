"""A homogenised Kirchhoff plate in the FE coupons' 3-point test, against those coupons.

    python benchmarks/plate_offaxis.py [M ...]          # default 8 16 32 (elements per half span)
    python benchmarks/plate_offaxis.py --shear [M ...]  # with transverse shear along the creases

An experiment towards a free-panel D(eta) model (issue: off-axis stiffness). Each layer is a
homogenised orthotropic Kirchhoff plate with its own springs as rigidities (a square coupon:
D_11 = D_S along the creases, D_22 = D_C across, D_66 = D_T twisting, D_12 = 0), rotated to
theta from the span. The fixture is the FE coupon's (docs/fea.md 2.1): w = 0 on the two end edges,
w = delta on the mid-span line (a rigid loading line), the sides free; the layers unconnected,
their forces added. D = P span^2 / (48 delta), as the FE reports it. Discretisation: conforming
bicubic Hermite (Bogner-Fox-Schmit) elements on a uniform 2M x 2M grid, so the supports and the
loading line are exact linear constraints; the energy converges from above (displacement method)
with order about 1 (a corner singularity), extrapolated with the observed order.

``--shear`` adds transverse shear along the creases by splitting w = w_b + w_s (bending and shear
deflections, exact for a statically determinate Timoshenko beam): w_b carries the Kirchhoff
energy, w_s the energy S_s (dw_s/ds)^2 / 2 with S_s = G t cos^2(alpha/2) / sin(alpha/2) per unit
width (the facets as inclined webs, derived, not fitted) and S_c = S_s / 100 across the creases.

Findings (run 2026-12-01, ``16 32 64``, 9 min): plate/FE at 0, 15, 30, 45, 60, 75 deg: case study
1.123, 1.044, 0.808, 1.950, 0.803, 1.039; alpha 40: 1.371, 1.216, 1.075, 3.039, 1.067, 1.206;
differing layers: 1.123, 1.044, 0.808, 2.856, 1.052, 1.189 (docs/offaxis.md, "Why no homogenised
model can meet the issue's targets"). Earlier run (2026-11-29). Kirchhoff (8 16 32): 1.04x
the FE at 15 deg and 0.80x at 30 deg for the case study, but 1.9x (case study), 2.3x (alpha 40,
still falling with the mesh) and 2.8x (differing layers) at 45 deg. With ``--shear 8 16``: 0.96,
0.76, 1.8 (case study at 15, 30, 45 deg), 1.02, 0.97, 3.5 (alpha 40), and 1.04 / 1.16 at 0 deg
(the FE's 3-point D includes shear the plate does not fully capture). So transverse shear is not
what is missing at 45 deg; the likely cause is that the plate's boundary layers there are narrower
than one corrugation wavelength, where a homogenised D_S does not exist. Neither variant is a
model to ship.
"""

from __future__ import annotations

import math
import sys
import time

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spl

from corrugate import analyze
from fea_offaxis import designs
from offaxis_table import _load, estimate


def hermite_1d(nodes: np.ndarray) -> dict[tuple[int, int], sp.csr_matrix]:
    """1-D cubic Hermite matrices A[a, b] = integral of d^a N_i d^b N_j (dofs: value, slope)."""
    nd = 2 * len(nodes)
    g, wg = np.polynomial.legendre.leggauss(4)
    s = (g + 1) / 2
    rows, cols = [], []
    vals: dict[tuple[int, int], list[np.ndarray]] = {(a, b): [] for a in range(3) for b in range(3)}
    for e in range(len(nodes) - 1):
        h = nodes[e + 1] - nodes[e]
        w = wg / 2 * h
        n0 = np.array(
            [
                1 - 3 * s**2 + 2 * s**3,
                h * (s - 2 * s**2 + s**3),
                3 * s**2 - 2 * s**3,
                h * (s**3 - s**2),
            ]
        )
        n1 = (
            np.array(
                [
                    6 * s**2 - 6 * s,
                    h * (1 - 4 * s + 3 * s**2),
                    6 * s - 6 * s**2,
                    h * (3 * s**2 - 2 * s),
                ]
            )
            / h
        )
        n2 = np.array([12 * s - 6, h * (6 * s - 4), 6 - 12 * s, h * (6 * s - 2)]) / h**2
        d = (n0, n1, n2)
        idx = np.arange(2 * e, 2 * e + 4)
        rows.append(np.repeat(idx, 4))
        cols.append(np.tile(idx, 4))
        for a, b in vals:
            vals[a, b].append(((d[a] * w) @ d[b].T).ravel())
    r, c = np.concatenate(rows), np.concatenate(cols)
    return {k: sp.csr_matrix((np.concatenate(v), (r, c)), shape=(nd, nd)) for k, v in vals.items()}


def rotated(d1: float, d2: float, d66: float, phi_deg: float) -> tuple[float, ...]:
    """D11, D22, D12, D66, D16, D26 of an orthotropic plate (D12 = 0) whose axis 1 is at phi
    from x (the classical lamination transformation)."""
    m, n = math.cos(math.radians(phi_deg)), math.sin(math.radians(phi_deg))
    return (
        d1 * m**4 + 4 * d66 * m * m * n * n + d2 * n**4,
        d1 * n**4 + 4 * d66 * m * m * n * n + d2 * m**4,
        (d1 + d2 - 4 * d66) * m * m * n * n,
        (d1 + d2 - 2 * d66) * m * m * n * n + d66 * (m**4 + n**4),
        (d1 - 2 * d66) * m**3 * n - (d2 - 2 * d66) * m * n**3,
        (d1 - 2 * d66) * m * n**3 - (d2 - 2 * d66) * m**3 * n,
    )


def three_point(
    d1: float,
    d2: float,
    d66: float,
    theta_deg: float,
    m: int,
    shear: tuple[float, float, float] | None = None,
) -> float:
    """D (N mm) of a square plate (span along y, axis 1 at theta from y) in 3-point bending;
    ``shear`` = (S_s, S_c, side L mm) adds transverse shear (N/mm) along and across axis 1."""
    L = 1.0 if shear is None else shear[2]
    grid = np.linspace(0.0, L, 2 * m + 1)
    a = hermite_1d(grid)
    nd = len(a[0, 0].toarray())
    d11, d22, d12, d66_, d16, d26 = rotated(d1, d2, d66, 90.0 - theta_deg)
    k = sp.kron
    K = (
        d11 * k(a[2, 2], a[0, 0])
        + d12 * (k(a[2, 0], a[0, 2]) + k(a[0, 2], a[2, 0]))
        + d22 * k(a[0, 0], a[2, 2])
        + 4 * d66_ * k(a[1, 1], a[1, 1])
        + 2 * d16 * (k(a[2, 1], a[0, 1]) + k(a[1, 2], a[1, 0]))
        + 2 * d26 * (k(a[0, 1], a[2, 1]) + k(a[1, 0], a[1, 2]))
    ).tocsr()
    N = nd * nd
    if shear is not None:
        th = math.radians(theta_deg)
        e_s, e_c = np.array([math.sin(th), math.cos(th)]), np.array([math.cos(th), -math.sin(th)])
        S = shear[0] * np.outer(e_s, e_s) + shear[1] * np.outer(e_c, e_c)
        Ks = (
            S[0, 0] * k(a[1, 1], a[0, 0])
            + S[1, 1] * k(a[0, 0], a[1, 1])
            + S[0, 1] * (k(a[1, 0], a[0, 1]) + k(a[0, 1], a[1, 0]))
        )
        # unknowns (w, w_s): energy of w_b = w - w_s plus that of w_s
        K = sp.bmat([[K, -K], [-K, K + Ks]]).tocsr()
    u = np.zeros(K.shape[0])
    fixed = np.zeros(K.shape[0], dtype=bool)
    if shear is not None:
        fixed[N] = True  # the shear deflection's free constant
    for node, value in ((0, 0.0), (m, 1.0), (2 * m, 0.0)):  # w on the lines y = 0, 1/2, 1
        idx = np.arange(nd) * nd + 2 * node  # (the w dofs come first)
        fixed[idx] = True
        u[idx] = np.where(np.arange(nd) % 2 == 0, value, 0.0)  # w = value, dw/dx = 0 along x
    free = ~fixed
    u[free] = spl.spsolve(K[free][:, free].tocsc(), -(K[free][:, fixed] @ u[fixed]))
    return float(u @ (K @ u)) * L * L / 48.0  # P = 2 U / delta, D = P L^2 / 48 (delta = 1)


def main(ms: tuple[int, ...], with_shear: bool) -> None:
    fe = _load()
    for name, asm in designs().items():
        if asm.layout.name == "rectangle":  # the plate coupon here is a square
            continue
        an = analyze(asm, eta_deg=[0.0])
        s1, s2 = an.springs
        L = an.stiffness[0].span
        shears = []
        for layer in asm.layers:
            b = math.radians(layer.alpha_deg / 2)
            s_s = (
                layer.material.E
                / (2 * (1 + layer.material.nu))
                * layer.t
                * math.cos(b) ** 2
                / math.sin(b)
            )
            shears.append((s_s, s_s / 100, L) if with_shear else None)
        for eta in (0.0, 15.0, 30.0, 45.0, 60.0, 75.0):
            t0 = time.perf_counter()
            series = {
                m: sum(
                    three_point(float(s.D_S), float(s.D_C), float(s.D_T), th, m, sh)
                    for s, th, sh in ((s1, eta, shears[0]), (s2, eta - 90.0, shears[1]))
                )
                for m in ms
            }
            plate, how = estimate(series)
            key = (name, eta if (name, eta, "bending") in fe else 90.0 - eta, "bending")
            ref, _ = estimate(fe[key])
            print(
                f"{name[:24]:24s} eta {eta:4.0f}  plate {' / '.join(f'{v:.4g}' for v in series.values())}"
                f" -> {plate:.4g} ({how})  FE {ref:.4g}  plate/FE {plate / ref:.3f}"
                f"  {time.perf_counter() - t0:.1f} s",
                flush=True,
            )


if __name__ == "__main__":
    args = sys.argv[1:]
    main(tuple(int(v) for v in args if v != "--shear") or (8, 16, 32), "--shear" in args)
