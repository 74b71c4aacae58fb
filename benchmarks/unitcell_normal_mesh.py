"""Experiment (docs/fea.md, section 1.3): is the slow convergence of the unit cell at alpha = 40
deg an artefact of its skewed elements?

The unit cell's through-thickness node lines are vertical everywhere (they must be at the mitred
crease), so at alpha = 40 deg its elements are parallelograms with a 20 deg corner. This script
builds the same geometry with node lines normal to the facet away from the creases, turning
smoothly (smoothstep over 2 t c / s of flat width, at most W / 2) to vertical at each crease, and
prints Ecx ... Eby (MPa) per mesh, as CSV like ``benchmarks/unitcell_range.py``:

    python benchmarks/unitcell_normal_mesh.py 8 0.125 40 40x2 80x2 160x4 320x4 640x4 320x8

Arguments: W (mm), t (mm), alpha (deg), then meshes. Dura-Lar (E 2700 MPa, nu 0.43). It swaps
the node grid of :func:`corrugate.fea.unitcell.unit_cell_deck` for the run (the library's mesh is
unchanged). Needs ccx.
"""

from __future__ import annotations

import inspect
import sys
import time
from typing import Any

import numpy as np

import corrugate.fea.unitcell as uc
from corrugate.fea.unitcell import UnitCell, UnitCellMesh, solve_unit_cell

E, NU = 2700.0, 0.43


def normal_grid(cell: UnitCell, mesh: UnitCellMesh) -> tuple[Any, Any, Any, float]:
    """Node coordinates X(I, K), Z(I, K), y(J) and L_y with node lines normal to the facets away
    from the creases (vertical at the creases)."""
    p, h, t, s = cell.pitch, cell.height, cell.t, cell.s
    c = float(np.cos(np.radians(cell.alpha_deg) / 2))
    ni, nk, nj = 4 * mesh.along + 1, 2 * mesh.through + 1, 2 * mesh.span + 1
    x = np.linspace(0.0, 2 * p, ni)
    zmid = np.interp(x, [0.0, p, 2 * p], [-h / 2, h / 2, -h / 2])
    d = np.linspace(-t / 2, t / 2, nk)
    xm = np.mod(x, p)
    u = np.clip(np.minimum(xm, p - xm) / s / min(cell.W / 2, 2 * c * t / s), 0.0, 1.0)
    w = u * u * (3 - 2 * u)  # 0 at a crease, 1 away from it
    rising = x < p
    sign = np.where(rising, 1.0, -1.0)
    # vertical offset (0, 1/s) = n + sign (c/s) tangent; blend the tangential part away
    vx = np.where(rising, -c, c) + (1 - w) * sign * (c / s) * s
    vz = s + (1 - w) * sign * (c / s) * np.where(rising, c, -c)
    X = x[:, None] + d[None, :] * vx[:, None]
    Z = zmid[:, None] + d[None, :] * vz[:, None]
    X[0, :], X[-1, :] = 0.0, 2 * p
    Ly = mesh.span * cell.W / mesh.along
    return X, Z, np.linspace(0.0, Ly, nj), Ly


def _patched_deck() -> Any:
    """unit_cell_deck with the node grid above: its source with ``_grid`` swapped, node x from
    X(I, K) (the periodic equations already use z(I, K), and X = 0, 2p on the periodic faces)."""
    src = inspect.getsource(uc.unit_cell_deck)
    src = src.replace("x, z, y, Ly = _grid(cell, mesh)", "X, z, y, Ly = normal_grid(cell, mesh)")
    src = src.replace("ni, nk, nj = len(x),", "x = X[:, 0]\n    ni, nk, nj = len(x),")
    src = src.replace("{x[i]:.10g},{y[j]", "{X[i, k]:.10g},{y[j]")
    if "X[i, k]" not in src or "normal_grid" not in src:
        raise RuntimeError("unit_cell_deck changed: update this experiment")
    namespace = dict(vars(uc), normal_grid=normal_grid)
    exec(src, namespace)
    return namespace["unit_cell_deck"]


if __name__ == "__main__":
    W, t, alpha = (float(v) for v in sys.argv[1:4])
    uc.unit_cell_deck = _patched_deck()  # solve_unit_cell looks it up in the module
    print("W,t,alpha,mesh,nodes,s,Ecx,Ecy,Ebx,Eby", flush=True)
    for label in sys.argv[4:]:
        along, through = (int(v) for v in label.split("x"))
        t0 = time.perf_counter()
        r = solve_unit_cell(
            UnitCell(E, NU, t, W, alpha), UnitCellMesh(along, through), timeout=1800
        )
        m = r.as_dict()
        print(
            f"{W},{t},{alpha},{label},{r.nodes},{time.perf_counter() - t0:.1f},"
            + ",".join(f"{m[k]:.8g}" for k in ("Ecx", "Ecy", "Ebx", "Eby")),
            flush=True,
        )
