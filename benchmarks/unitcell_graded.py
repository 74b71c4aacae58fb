"""Experiment (docs/fea.md, section 1.3): a unit-cell mesh graded towards the creases.

The uniform cell converges slowly at alpha = 40 deg (0.45-0.6 % per doubling up to 1280 along).
This script grades the nodes along each facet towards its two creases,
x = p (xi - beta sin(2 pi xi) / (2 pi)) for xi uniform in [0, 1] (the end elements are 1 - beta of
the mean size), and through the thickness towards both faces (the same law with beta_t), with the
mid-side nodes of the C3D20R elements at the midpoints, and prints Ecx and Ebx (MPa) per mesh:

    python benchmarks/unitcell_graded.py W T ALPHA BETA BETA_T MESH ...
    python benchmarks/unitcell_graded.py 8 0.125 40 0.98 0.9 80x4 160x4 320x4 640x4 160x8

Dura-Lar (E 2700 MPa, nu 0.43). The grading is the library's (:class:`UnitCellMesh` ``grading``,
``grading_t``; its default is 80x8 at 0.98 / 0.9); beta = beta_t = 0 is a uniform mesh. Needs ccx.
"""

from __future__ import annotations

import sys
import time

from corrugate.fea.unitcell import UnitCell, UnitCellMesh, solve_unit_cell

E, NU = 2700.0, 0.43


def main(argv: list[str]) -> None:
    W, t, alpha, beta, beta_t = (float(v) for v in argv[:5])
    cell = UnitCell(E, NU, t, W, alpha)
    print("W,t,alpha,beta,beta_t,mesh,Ecx_MPa,Ebx_MPa,seconds")
    for label in argv[5:]:
        along, through = (int(v) for v in label.split("x"))
        mesh = UnitCellMesh(along, through, grading=beta, grading_t=beta_t)
        t0 = time.perf_counter()
        m = solve_unit_cell(cell, mesh).moduli
        s = time.perf_counter() - t0
        print(f"{W:g},{t:g},{alpha:g},{beta:g},{beta_t:g},{label},{m.Ecx:.7g},{m.Ebx:.7g},{s:.1f}")


if __name__ == "__main__":
    if len(sys.argv) < 7:
        sys.exit(__doc__)
    main(sys.argv[1:])
