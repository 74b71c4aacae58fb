"""Finite-element validation with CalculiX (optional: needs the ``ccx`` executable).

* :mod:`~corrugate.fea.ccx`: find and run ccx, parse its output;
* :mod:`~corrugate.fea.unitcell`: periodic solid unit cell giving the four equivalent moduli;
* :mod:`~corrugate.fea.assembly`: the whole two-layer assembly as shells, meshed by
  :mod:`~corrugate.fea.shells` (layers; coupons along any eta through
  :mod:`~corrugate.fea.planmesh`, gmsh) and :mod:`~corrugate.fea.connector_band` (the connector
  band), cut by :mod:`~corrugate.fea.cuts`; a deck is the mesh (:mod:`~corrugate.fea.deck`), one
  fixture of :mod:`~corrugate.fea.fixtures` (named as the spec names the tests: platens,
  three-point, four-point, cantilever, frame; wheel and corners for outlines) and one step of
  :mod:`~corrugate.fea.steps` (static, or linear buckling of any fixture);
* :mod:`~corrugate.fea.frame`: the panel in a rigid frame, the paper's cos^2 rule's own fixture;
* :mod:`~corrugate.fea.outline`: circles and polygons: the wheel between a ground patch and its
  hub, a plate bolted or clamped at its corners (docs/fea.md 2.8);
* :mod:`~corrugate.fea.validation`: FE beside every model variant for one design, mesh refinement;
* :mod:`~corrugate.fea.tasks`: FE runs as tasks of a ``concurrent.futures`` executor (a local
  process pool or a dask cluster), in rounds for a verification (docs/fea.md 4);
* :mod:`~corrugate.fea.series`: sweeps through that executor, tables;
* :mod:`~corrugate.fea.plots`: Fig. 7-style plots (matplotlib).

The core package never imports this subpackage (docs/architecture.md). See docs/fea.md.
"""

from corrugate.fea.assembly import AssemblyMesh, AssemblyResult, solve_assembly
from corrugate.fea.ccx import SolverError, SolverNotFoundError, find_ccx
from corrugate.fea.frame import FrameStiffness, solve_frame
from corrugate.fea.unitcell import UnitCell, UnitCellMesh, UnitCellResult, solve_unit_cell
from corrugate.fea.validation import Case, CaseResult, Refinement, run_case

__all__ = [
    "AssemblyMesh",
    "AssemblyResult",
    "Case",
    "CaseResult",
    "FrameStiffness",
    "Refinement",
    "SolverError",
    "SolverNotFoundError",
    "UnitCell",
    "UnitCellMesh",
    "UnitCellResult",
    "find_ccx",
    "run_case",
    "solve_assembly",
    "solve_frame",
    "solve_unit_cell",
]
