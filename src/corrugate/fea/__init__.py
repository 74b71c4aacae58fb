"""Finite-element validation with CalculiX (optional: needs the ``ccx`` executable).

* :mod:`~corrugate.fea.ccx`: find and run ccx, parse its output;
* :mod:`~corrugate.fea.unitcell`: periodic solid unit cell giving the four equivalent moduli;
* :mod:`~corrugate.fea.assembly`: the whole two-layer assembly as shells: compression, 3-point
  bending and the 4-point (pure bending) diagnostic;
* :mod:`~corrugate.fea.validation`: FE beside every model variant for one design, mesh refinement;
* :mod:`~corrugate.fea.sweep`: sweeps through a ``concurrent.futures`` executor, tables;
* :mod:`~corrugate.fea.plots`: Fig. 7-style plots (matplotlib).

The core package never imports this subpackage (DESIGN.md section 9). See docs/fea.md.
"""

from .assembly import AssemblyMesh, AssemblyResult, solve_assembly
from .ccx import SolverError, SolverNotFoundError, find_ccx
from .unitcell import UnitCell, UnitCellMesh, UnitCellResult, solve_unit_cell
from .validation import Case, CaseResult, Refinement, run_case

__all__ = [
    "AssemblyMesh",
    "AssemblyResult",
    "Case",
    "CaseResult",
    "Refinement",
    "SolverError",
    "SolverNotFoundError",
    "UnitCell",
    "UnitCellMesh",
    "UnitCellResult",
    "find_ccx",
    "run_case",
    "solve_assembly",
    "solve_unit_cell",
]
