"""Experiment (docs/fea.md, section 1.3): a unit-cell mesh graded towards the creases.

The uniform cell converges slowly at alpha = 40 deg (0.45-0.6 % per doubling up to 1280 along).
This script grades the nodes along each facet towards its two creases,
x = p (xi - beta sin(2 pi xi) / (2 pi)) for xi uniform in [0, 1] (the end elements are 1 - beta of
the mean size), and through the thickness towards both faces (the same law with beta_t), with the
mid-side nodes of the C3D20R elements at the midpoints, and prints Ecx and Ebx (MPa) per mesh:

    python benchmarks/unitcell_graded.py W T ALPHA BETA BETA_T MESH ...
    python benchmarks/unitcell_graded.py 8 0.125 40 0.98 0.9 80x4 160x4 320x4 640x4 160x8

Dura-Lar (E 2700 MPa, nu 0.43). It swaps the node grid of
:func:`corrugate.fea.unitcell.unit_cell_deck` for the run (the library's mesh is unchanged).
beta = beta_t = 0 is the library's uniform mesh. Needs ccx.
"""

from __future__ import annotations

import sys
import time

import numpy as np

import corrugate.fea.unitcell as uc
from corrugate.fea.unitcell import UnitCell, UnitCellMesh, solve_unit_cell

E, NU = 2700.0, 0.43


def graded(n: int, beta: float) -> np.ndarray:
    """n + 1 points on [0, 1], clustered at both ends (beta = 0: uniform)."""
    xi = np.linspace(0.0, 1.0, n + 1)
    return np.asarray(xi - beta / (2 * np.pi) * np.sin(2 * np.pi * xi))


def with_mids(corners: np.ndarray) -> np.ndarray:
    out = np.empty(2 * len(corners) - 1)
    out[0::2] = corners
    out[1::2] = 0.5 * (corners[:-1] + corners[1:])
    return out


def make_grid(beta: float, beta_t: float):  # type: ignore[no-untyped-def]
    def grid(cell: UnitCell, mesh: UnitCellMesh):  # type: ignore[no-untyped-def]
        p, h, t, s = cell.pitch, cell.height, cell.t, cell.s
        g = graded(mesh.along, beta)
        x = with_mids(np.concatenate([p * g, p + p * g[1:]]))
        zmid = np.interp(x, [0.0, p, 2 * p], [-h / 2, h / 2, -h / 2])
        d = with_mids(-t / 2 + t * graded(mesh.through, beta_t))
        z = zmid[:, None] + d[None, :] / s
        Ly = mesh.span * cell.W / mesh.along
        y = np.linspace(0.0, Ly, 2 * mesh.span + 1)
        return x, z, y, Ly

    return grid


def main(argv: list[str]) -> None:
    W, t, alpha, beta, beta_t = (float(v) for v in argv[:5])
    uc._grid = make_grid(beta, beta_t)  # type: ignore[assignment]
    cell = UnitCell(E, NU, t, W, alpha)
    print("W,t,alpha,beta,beta_t,mesh,Ecx_MPa,Ebx_MPa,seconds")
    for label in argv[5:]:
        along, through = (int(v) for v in label.split("x"))
        t0 = time.perf_counter()
        m = solve_unit_cell(cell, UnitCellMesh(along, through)).moduli
        s = time.perf_counter() - t0
        print(f"{W:g},{t:g},{alpha:g},{beta:g},{beta_t:g},{label},{m.Ecx:.7g},{m.Ebx:.7g},{s:.1f}")


if __name__ == "__main__":
    if len(sys.argv) < 7:
        sys.exit(__doc__)
    main(sys.argv[1:])
