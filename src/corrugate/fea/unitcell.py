"""Periodic unit cell of one corrugation period: the four equivalent moduli by finite elements.

Model (CalculiX, :mod:`corrugate.fea.ccx`):

* **Geometry.** One period of the zig-zag, two facets of flat width W each: a valley crease at
  x = 0, a peak crease at x = p and a valley at x = 2 p (p = W sin(alpha/2), crease height
  h = W cos(alpha/2), mid-surface between z = -h/2 and z = +h/2). The sheet is a **solid** of
  thickness t; the creases are **mitred**: neighbouring facets meet on the vertical bisector plane,
  so the solid is the mid-surface zig-zag shifted vertically by +-t / (2 sin(alpha/2)). The same
  geometry as ``docs/data/unitcell_fe.csv``; it is stiffer than the zero-thickness crease of the
  closed forms by a margin that vanishes linearly with t/W.
* **Elements.** 20-node hexahedra with reduced integration (C3D20R), a structured mesh of
  ``mesh.along`` elements along each facet, ``mesh.through`` through the thickness and
  ``mesh.span`` along y. The cell is prismatic along y, so its depth is free: by default one
  element of the size of a facet element (the field is uniform along y).
* **Periodic boundary conditions.** Four macro strains carried as degrees of freedom of two
  dummy nodes: in-plane strains eps_x, eps_y and curvatures kappa_x, kappa_y. For every node on
  the faces x = 2 p and/or y = L_y, tied to its image on x = 0, y = 0 (``*EQUATION``), the jump of
  displacement is the Kirchhoff plate field u_x = x (eps_x - z kappa_x),
  u_y = y (eps_y - z kappa_y), u_z = (kappa_x x^2 + kappa_y y^2) / 2, the rest is periodic. In-plane
  shear and twist are held at zero; by the symmetry of the zig-zag they do not couple to the four.
  One node is held against rigid translation.
* **Loads.** Four steps, each a unit generalised force (conjugate of one macro strain) with the
  other three zero; the macro strains of the dummy nodes give the compliance matrix C (per unit
  plan area), and the moduli follow from its diagonal, so **each modulus has the other three
  generalised forces zero**, as the closed forms assume:

      Ecx = 1 / (t C_xx),  Ecy = 1 / (t C_yy),  Ebx = 12 / (t^3 C_kx),  Eby = 12 / (t^3 C_ky),

  moduli per plan width p of a facet, the convention of :mod:`corrugate.mechanics.moduli` (docs/theory.md 3.1).

Source of the method: periodic homogenisation of plates (e.g. Xia et al. 2012, Int. J. Solids
Struct. 49:1453, whose A and D this cell computes numerically).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from corrugate.core.errors import InputError
from corrugate.fea.ccx import SolverError, run_ccx, work_dir
from corrugate.geometry.layer import FacetGeometry
from corrugate.mechanics.moduli import Moduli

__all__ = ["UnitCell", "UnitCellMesh", "UnitCellResult", "solve_unit_cell", "unit_cell_deck"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, slots=True)
class UnitCellMesh:
    """Mesh of the unit cell: C3D20R elements along one facet, through t, and along y.

    The nodes are graded towards the creases along each facet, x = p (xi - g sin(2 pi xi) /
    (2 pi)) for xi uniform on [0, 1] with g = ``grading`` (the elements at a crease are 1 - g of
    the mean size), and towards both faces through t (``grading_t``); the mid-side nodes sit at
    the midpoints. ``grading = grading_t = 0`` is a uniform mesh.

    The default, 80 x 8 graded, gives Ecx within 0.7 % and Ebx within 0.2 % of the cell's
    converged values (where 320 x 8 and 160 x 16 agree within 0.1 %) at alpha = 40, 84 and
    115 deg, W = 8-18.75 mm, t = 0.125-0.16 mm (docs/fea.md 1.3, ``benchmarks/unitcell_graded.py``),
    in 9-13 s per ccx run on a shared core. The uniform 320 x 4 mesh used before was 1.2 % stiff at
    alpha = 40 deg, and a uniform mesh with 4 elements through t keeps drifting below the
    converged value as it is refined along the facet (too few elements through t at the crease).
    """

    along: int = 80
    through: int = 8
    span: int = 1
    grading: float = 0.98
    grading_t: float = 0.9

    def __post_init__(self) -> None:
        for name in ("along", "through", "span"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, int) or v < 1:
                raise InputError(f"cell-mesh.{name}", v, "an integer >= 1")
            from corrugate.core.limits import check_count

            check_count(
                "cell_mesh" if name == "along" else "cell_mesh_through", v, f"cell-mesh.{name}"
            )
        for name in ("grading", "grading_t"):
            g = getattr(self, name)
            if not (isinstance(g, int | float) and 0.0 <= g < 1.0):
                raise InputError(f"mesh.{name}", g, "a number 0 <= g < 1")

    def refined(self, factor: float = 2.0) -> UnitCellMesh:
        """The mesh with ``along`` and ``through`` scaled by ``factor`` (rounded, at least 1),
        graded alike."""
        return replace(
            self,
            along=max(1, round(self.along * factor)),
            through=max(1, round(self.through * factor)),
        )

    def label(self) -> str:
        """``along x through`` for the default grading (the notation of
        ``docs/data/unitcell_fe.csv`` for a uniform mesh, with its grading named)."""
        base = f"{self.along}x{self.through}"
        if (self.grading, self.grading_t) == (0.98, 0.9):
            return base
        if self.grading == 0 and self.grading_t == 0:
            return f"{base} uniform"
        return f"{base} graded {self.grading:g}/{self.grading_t:g}"


def _graded(n: int, g: float) -> FloatArray:
    """n + 1 points on [0, 1], clustered at both ends by ``g`` (0: uniform), and the mid-points
    between them: 2 n + 1 values, the corner and mid-side node positions of n quadratic elements."""
    xi = np.linspace(0.0, 1.0, n + 1)
    corners = xi - g / (2 * np.pi) * np.sin(2 * np.pi * xi)
    out = np.empty(2 * n + 1)
    out[0::2] = corners
    out[1::2] = 0.5 * (corners[:-1] + corners[1:])
    return out


@dataclass(frozen=True, slots=True)
class UnitCell(FacetGeometry):
    """One period of a zig-zag layer: E (MPa), nu, t (mm), W (mm), alpha (deg)."""

    E: float
    nu: float
    t: float
    W: float
    alpha_deg: float

    def __post_init__(self) -> None:
        if not self.E > 0:
            raise InputError("E", f"{self.E} MPa", "E > 0")
        if not -1 < self.nu < 0.5:
            raise InputError("nu", self.nu, "-1 < nu < 0.5")
        if not 0 < self.t < self.W:
            raise InputError("t", f"{self.t} mm", f"0 < t < W = {self.W} mm")
        if not 0 < self.alpha_deg < 180:
            raise InputError("alpha", f"{self.alpha_deg} deg", "0 < alpha < 180 deg")


@dataclass(frozen=True, slots=True)
class UnitCellResult:
    """Moduli (MPa, per plan width, docs/theory.md 3.1) and the compliance C (per unit plan area;
    order eps_x, eps_y, kappa_x, kappa_y; mm/N and 1/(N mm)) of one unit-cell run."""

    cell: UnitCell
    mesh: UnitCellMesh
    moduli: Moduli
    compliance: FloatArray
    nodes: int
    elements: int

    def as_dict(self) -> dict[str, float]:
        return self.moduli.as_dict()

    def normalised(self) -> dict[str, float]:
        """Moduli divided by the sheet's E (the form of ``docs/data/unitcell_fe.csv``)."""
        return {k: v / self.cell.E for k, v in self.moduli.as_dict().items()}


# C3D20R local node order on a (i, j, k) brick: i along the facet, j along y, k through t.
_CORNERS = [(0, 0, 0), (2, 0, 0), (2, 2, 0), (0, 2, 0), (0, 0, 2), (2, 0, 2), (2, 2, 2), (0, 2, 2)]
_MIDS = [
    (1, 0, 0),
    (2, 1, 0),
    (1, 2, 0),
    (0, 1, 0),
    (1, 0, 2),
    (2, 1, 2),
    (1, 2, 2),
    (0, 1, 2),
    (0, 0, 1),
    (2, 0, 1),
    (2, 2, 1),
    (0, 2, 1),
]
_LOCAL = _CORNERS + _MIDS


def _grid(cell: UnitCell, mesh: UnitCellMesh) -> tuple[FloatArray, FloatArray, FloatArray, float]:
    """Node coordinate functions on the doubled-resolution grid: x(I), z(I, K), y(J), and L_y."""
    p, h, t, s = cell.pitch, cell.height, cell.t, cell.s
    facet = _graded(mesh.along, mesh.grading)  # 0 ... 1 along one facet, crease to crease
    x = np.concatenate([p * facet, p + p * facet[1:]])
    zmid = np.interp(x, [0.0, p, 2 * p], [-h / 2, h / 2, -h / 2])
    d = -t / 2 + t * _graded(mesh.through, mesh.grading_t)
    z = zmid[:, None] + d[None, :] / s
    Ly = mesh.span * cell.W / mesh.along
    y = np.linspace(0.0, Ly, 2 * mesh.span + 1)
    return x, z, y, Ly


def unit_cell_deck(cell: UnitCell, mesh: UnitCellMesh) -> tuple[str, dict[str, float]]:
    """The CalculiX deck of the periodic unit cell and its bookkeeping (area, load scales, ids)."""
    x, z, y, Ly = _grid(cell, mesh)
    ni, nk, nj = len(x), int(z.shape[1]), len(y)
    Lx = 2 * cell.pitch

    def nid(i: int, j: int, k: int) -> int:
        return 1 + i + ni * (k + nk * j)

    elements: list[list[int]] = []
    for ej in range(mesh.span):
        for ek in range(mesh.through):
            for ei in range(2 * mesh.along):
                elements.append([nid(2 * ei + a, 2 * ej + b, 2 * ek + c) for a, b, c in _LOCAL])
    used = sorted({n for e in elements for n in e})
    lines = ["*HEADING", "corrugate periodic unit cell (C3D20R, mitred creases)", "*NODE"]
    for n in used:
        r = n - 1
        i, r = r % ni, r // ni
        k, j = r % nk, r // nk
        lines.append(f"{n},{x[i]:.10g},{y[j]:.10g},{z[i, k]:.10g}")
    rx, ry = used[-1] + 1, used[-1] + 2
    lines += [f"{rx},0,0,0", f"{ry},0,0,0"]
    lines.append("*ELEMENT,TYPE=C3D20R,ELSET=EALL")
    for e_no, e in enumerate(elements, start=1):
        lines.append(f"{e_no}," + ",".join(map(str, e[:15])) + ",")
        lines.append(",".join(map(str, e[15:])))
    lines += [f"*NSET,NSET=NREF\n{rx},{ry}"]
    lines.append("*EQUATION")
    for n in used:
        r = n - 1
        i, r = r % ni, r // ni
        k, j = r % nk, r // nk
        on_x, on_y = i == ni - 1, j == nj - 1
        if not (on_x or on_y):
            continue
        master = nid(0 if on_x else i, 0 if on_y else j, k)
        dx = Lx if on_x else 0.0
        dy = Ly if on_y else 0.0
        zz = float(z[i, k])
        # u_B - u_A - jump(macro strains) = 0, one equation per displacement component
        rows = [
            [(n, 1, 1.0), (master, 1, -1.0), (rx, 1, -dx), (rx, 2, zz * dx)],
            [(n, 2, 1.0), (master, 2, -1.0), (ry, 1, -dy), (ry, 2, zz * dy)],
            [(n, 3, 1.0), (master, 3, -1.0), (rx, 2, -0.5 * dx * dx), (ry, 2, -0.5 * dy * dy)],
        ]
        for row in rows:
            terms = [tm for tm in row if tm[2] != 0.0]
            lines.append(str(len(terms)))
            lines.append(",".join(f"{a},{b},{c:.12g}" for a, b, c in terms))
    anchor = nid(0, 0, nk // 2)
    lines += [
        "*MATERIAL,NAME=SHEET",
        "*ELASTIC",
        f"{cell.E:.10g},{cell.nu:.10g}",
        "*SOLID SECTION,ELSET=EALL,MATERIAL=SHEET",
        "*BOUNDARY",
        f"{anchor},1,3",
    ]
    area = Lx * Ly
    # generalised forces scaled to strains of order 1e-3 (linear analysis: only for round-off)
    fm = 1e-3 * area * cell.E * cell.t
    fb = 1e-3 * area * cell.E * cell.t**3 / 12 / cell.W
    for node, dof, f in ((rx, 1, fm), (ry, 1, fm), (rx, 2, fb), (ry, 2, fb)):
        lines += [
            "*STEP",
            "*STATIC",
            "*CLOAD,OP=NEW",
            f"{node},{dof},{f:.12g}",
            "*NODE PRINT,NSET=NREF",
            "U",
            "*END STEP",
        ]
    info = {
        "area": area,
        "fm": fm,
        "fb": fb,
        "rx": rx,
        "ry": ry,
        "nodes": len(used),
        "elements": len(elements),
    }
    return "\n".join(lines) + "\n", info


def solve_unit_cell(
    cell: UnitCell,
    mesh: UnitCellMesh | None = None,
    *,
    folder: Path | None = None,
    keep: bool = False,
    timeout: float = 600.0,
) -> UnitCellResult:
    """Run the periodic unit cell in CalculiX and return its four moduli (MPa).

    ``folder``: parent of the work folder (a temporary folder by default), removed unless ``keep``.
    """
    mesh = mesh or UnitCellMesh()
    deck, info = unit_cell_deck(cell, mesh)
    with work_dir(folder, keep) as wd:
        run = run_ccx(deck, wd, job="unitcell", timeout=timeout)
    blocks = run.find("displacements", "NREF")
    if len(blocks) != 4:
        raise SolverError(f"ccx printed {len(blocks)} of 4 unit-cell load cases")
    rx, ry = int(info["rx"]), int(info["ry"])
    C = np.empty((4, 4))
    for col, (b, f) in enumerate(
        zip(blocks, (info["fm"], info["fm"], info["fb"], info["fb"]), strict=True)
    ):
        u = (b.rows[rx][0], b.rows[ry][0], b.rows[rx][1], b.rows[ry][1])
        C[:, col] = np.asarray(u) * info["area"] / f
    t = cell.t
    m = Moduli(
        Ecx=np.asarray(1 / (t * C[0, 0])),
        Ecy=np.asarray(1 / (t * C[1, 1])),
        Ebx=np.asarray(12 / (t**3 * C[2, 2])),
        Eby=np.asarray(12 / (t**3 * C[3, 3])),
    )
    return UnitCellResult(cell, mesh, m, C, int(info["nodes"]), int(info["elements"]))
