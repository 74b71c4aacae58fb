"""Spec -> solution -> files: the one chain behind ``corrugate design`` and ``POST /api/design``.

* :func:`output_options`: the output options (machine, fold-line style, spacing, paper, ...) from
  the strings a user types (plain numbers in mm), for the command line and the web app alike;
* :func:`solve_spec`: the certified design of a spec (:func:`corrugate.design.run.run_spec`,
  robust specs included) and the JSON object ``corrugate design --json`` prints;
* :func:`write_design`: every file of that design into a folder: the cut files, FOLD, GLB/STL,
  the assembly steps, ``report.html`` (drawn from the very sheet plan of the cut files) and
  ``design.json`` (:mod:`corrugate.record`); only ``design.json`` for an infeasible spec.

The heavy modules (the solver, the writers, the report) are imported when a function runs.
"""

from __future__ import annotations

import threading
from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING

from .errors import InputError

if TYPE_CHECKING:
    from .design.problem import Problem
    from .design.run import DesignRun
    from .outputs import CutPlan, OutputOptions
    from .spec import Spec

__all__ = ["output_options", "solve_spec", "write_design"]

#: matplotlib's pyplot (the assembly figure, the report's plots) keeps global state and is not
#: thread-safe: one design's files are written at a time in one process.
_FILES_LOCK = threading.Lock()


def output_options(
    cutter: str = "cameo4-12x12",
    fold_style: str = "solid",
    cut: str | float | None = None,
    gap: str | float | None = None,
    spacing: str | float = "5",
    margin: str | float = "5",
    tab_depth: str | float = "4",
    labels: bool | None = None,
    paper: str = "mat",
    *,
    names: Mapping[str, str] | None = None,
) -> OutputOptions:
    """Output options from user strings (plain numbers in mm, or with units: ``'0.04 in'``).

    ``cutter`` is the machine (``cameo4-12x12``, ``maker-12x24``, ``laser:WxH``, ...), ``labels``
    the ``--labels/--no-labels`` flag (``None`` when not given), ``paper`` is ``mat``, ``a4`` or
    ``letter`` (see :class:`~corrugate.outputs.OutputOptions`). A bad value raises an
    :class:`InputError` naming ``cutter``, ``fold-line style``, ``cut``, ``gap``, ``spacing``,
    ``margin``, ``tab-depth`` or ``paper``; ``names`` maps those to the caller's own names
    (the web app's ``fold_style``, ``tab_depth``). Without the ``fab`` extra it raises
    :class:`~corrugate.errors.MissingExtraError` first.
    """
    from .extras import require_extra

    require_extra("fab", "writing a design's files")  # before any work (or input check) is done
    from .export.machines import get_machine
    from .export.pdf import check_paper
    from .outputs import OutputOptions
    from .pattern.linestyle import line_style
    from .pattern.options import FabricationOptions
    from .units import parse_quantity

    def length(value: str | float | None, field: str) -> float | None:
        return None if value is None else parse_quantity(value, "mm", field)

    try:
        get_machine(cutter)  # an unknown machine is an error before anything else
        cut_mm, gap_mm = length(cut, "cut"), length(gap, "gap")
        if fold_style.strip().lower() == "perforated":
            for field, value in (("cut", cut_mm), ("gap", gap_mm)):
                if value is None:
                    raise InputError(
                        field,
                        None,
                        f"a {field} length (mm) for perforated fold lines",
                        reason="is missing",
                    )
        spacing_mm, margin_mm = length(spacing, "spacing"), length(margin, "margin")
        tab_mm = length(tab_depth, "tab-depth")
        assert spacing_mm is not None and margin_mm is not None and tab_mm is not None
        return OutputOptions(
            cutter=cutter,
            style=line_style(fold_style, cut_mm, gap_mm),
            spacing=spacing_mm,
            margin=margin_mm,
            fabrication=FabricationOptions(tab_depth=tab_mm),
            labels=labels,
            paper=check_paper(paper),
        )
    except InputError as exc:
        fields = {"perforation cut": "cut", "perforation gap": "gap", **(names or {})}
        if exc.field in fields:
            raise exc.renamed(fields[exc.field]) from None
        raise


def solve_spec(spec: Spec, problem: Problem | None = None) -> DesignRun:
    """The solution of ``spec`` (its ``problem`` may be given when already built) and the JSON
    object ``corrugate design --json`` prints for it."""
    from .design.run import run_spec

    return run_spec(spec, problem)


def write_design(
    run: DesignRun, out: str | Path, options: OutputOptions, spec_text: str
) -> list[Path]:
    """Write the files of a solved spec into ``out`` (created if missing), all or nothing; returns
    the paths written. ``spec_text`` is the spec as the user wrote it (shown in the report).

    A design gets every file of :func:`corrugate.outputs.write_design_files`, with the design
    answer merged into ``design.json``; an infeasible spec gets ``design.json`` only."""
    from .outputs import write_design_files
    from .record import write_record

    sol = run.solution
    analysis = sol.analysis
    if analysis is None:
        return [write_record(run.payload, out)]

    def report(cut: CutPlan) -> str:
        from .report import report_html

        return report_html(sol, spec_text, cut)

    with _FILES_LOCK:  # the report draws the very sheet plan the cut files are written from
        return write_design_files(analysis, out, options, extra=run.payload, report=report)
