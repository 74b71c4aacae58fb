"""Finite-element validation with CalculiX (optional: needs the ``ccx`` executable).

* :mod:`~corrugate.fea.ccx`: find and run ccx, parse its output;
* :mod:`~corrugate.fea.unitcell`: periodic unit cell giving the four equivalent moduli;
* :mod:`~corrugate.fea.assembly`: the whole two-layer assembly as shells, compression and
  3-point bending.

The core package never imports this subpackage (DESIGN.md section 9).
"""

from .ccx import SolverError, SolverNotFoundError, find_ccx
from .unitcell import UnitCell, UnitCellMesh, UnitCellResult, solve_unit_cell

__all__ = [
    "SolverError",
    "SolverNotFoundError",
    "UnitCell",
    "UnitCellMesh",
    "UnitCellResult",
    "find_ccx",
    "solve_unit_cell",
]
