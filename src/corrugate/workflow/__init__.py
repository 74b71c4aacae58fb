"""Spec -> answer -> files: one design request, one run, behind ``corrugate design``,
``corrugate pattern``, ``POST /api/design`` (and its job) and the notebook's two calls.

* :mod:`~corrugate.workflow.request`: :class:`DesignRequest`, the typed request each boundary
  reads once (spec, problem, machine profile, budget, output, FE options, its names of the
  options);
* :mod:`~corrugate.workflow.steps`: :func:`run`, the one entry that solves, verifies and refines
  in FE and writes the files of a request, renaming the errors in one place (:class:`Run`);
* :mod:`~corrugate.workflow.solve`: :func:`solve_spec`, the certified answer of a spec (robust
  specs included) and the JSON object ``corrugate design --json`` prints (:class:`DesignRun`);
* :mod:`~corrugate.workflow.fe`: the FE step (``--verify fe``, ``--refine``: :class:`FeCheck`);
* :mod:`~corrugate.workflow.files`: :func:`output_options`, :func:`made_for`,
  :func:`write_design_files` and :func:`write_design`, every file of a design as one set;
* :mod:`~corrugate.workflow.notebook`: :func:`design` and :func:`write_files`.

The heavy modules (the solver, the FE, the writers, the report) are imported when a function
runs, so the command line starts without them.
"""

from corrugate.workflow.fe import FeCheck
from corrugate.workflow.files import (
    MadeFor,
    made_for,
    output_options,
    write_design,
    write_design_files,
)
from corrugate.workflow.notebook import DesignResult, design, write_files
from corrugate.workflow.request import DesignRequest, FeOptions, Names, Output, resolve_machine
from corrugate.workflow.solve import DesignRun, solve_spec
from corrugate.workflow.steps import Events, Run, json_safe, output_errors, run

__all__ = [
    "DesignRequest",
    "DesignResult",
    "DesignRun",
    "Events",
    "FeCheck",
    "FeOptions",
    "MadeFor",
    "Names",
    "Output",
    "Run",
    "design",
    "json_safe",
    "made_for",
    "output_errors",
    "output_options",
    "resolve_machine",
    "run",
    "solve_spec",
    "write_design",
    "write_design_files",
    "write_files",
]
