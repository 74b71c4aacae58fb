"""A design's files: the output options a user types (:func:`output_options`), the machine and
fold operations a spec is made for (:func:`made_for`), and every file of an analysed design
written all or nothing into one folder (:func:`write_design_files`, :func:`write_design`).

* :func:`output_options`: the output options (machine, fold-line style, spacing, paper, ...) from
  the strings a user types (plain numbers in mm), for the command line and the web app alike;
* :func:`write_design_files`: every file a maker needs of an analysed design, written all or
  nothing into one folder: ``sheet-N.svg`` (the fold map, for people and Origami Simulator),
  ``cut-N.dxf`` / ``cut-N.svg`` (the machine's cut-ready files), ``pattern.pdf`` (and with
  ``paper`` a4 or letter its 1:1 tiles), ``layer1.fold`` / ``layer2.fold``, ``assembly.glb`` /
  ``assembly.stl``, ``ASSEMBLY.md`` + ``assembly.png``, ``report.html`` and ``design.json``
  (:mod:`corrugate.export.record`): the entries of the writers registry
  (:mod:`corrugate.export.writers`), written through it. Every option is checked and every
  document built before anything is written; the files are committed together as one set
  inside the folder (:mod:`corrugate.core.fileio`), so a bad option or a failure leaves the
  folder's earlier set, and a kill, once the next run (or :func:`~corrugate.core.fileio.recover`)
  has settled its journal, the earlier set or the new one whole, never a mix. The parts and their sheet plan are made once
  (:func:`corrugate.export.plan.cut_plan`); the report gets that very plan, and its sheet figures
  are the fold maps ``sheet-N.svg`` written beside it;
* :func:`write_design`: the files of a solved spec (``design.json`` only when it is infeasible).

The writers and the report are imported when a function runs, so the command line starts
without them.
"""

from __future__ import annotations

import threading
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from corrugate.core.errors import InputError
from corrugate.names import (
    DEFAULT_FOLD_STYLE,
    DEFAULT_MACHINE,
    DEFAULT_MARGIN_MM,
    DEFAULT_PAPER,
    DEFAULT_SPACING_MM,
    DEFAULT_TAB_DEPTH_MM,
)

if TYPE_CHECKING:
    from corrugate.analysis.evaluate import Analysis
    from corrugate.export.machines import Machine
    from corrugate.export.plan import CutPlan, OutputOptions
    from corrugate.spec.schema import Spec
    from corrugate.workflow.solve import DesignRun

__all__ = [
    "MadeFor",
    "made_for",
    "output_options",
    "prepare_design",
    "prepare_design_files",
    "write_design",
    "write_design_files",
]

#: matplotlib's pyplot (the assembly figure, the report's plots) keeps global state and is not
#: thread-safe: one design's files are written at a time in one process.
_FILES_LOCK = threading.Lock()


@dataclass(frozen=True, slots=True)
class MadeFor:
    """What a spec is solved and its files are written for (:func:`made_for`): the ``spec`` to
    solve, the ``cutter`` its files are for and the fold operations ``mountain``, ``valley`` and
    ``marks`` (None: the machine's)."""

    spec: Spec
    cutter: str
    mountain: str | None
    valley: str | None
    marks: str | None


def made_for(
    spec: Spec,
    cutter: str | None = None,
    *,
    mountain: str | None = None,
    valley: str | None = None,
    marks: str | None = None,
) -> MadeFor:
    """The spec with its ``[fabrication] machine`` set to ``cutter`` when one is given (a checked
    name: ``design --machine``, the web's ``cutter``), the machine its files are written for (that
    one, else the spec's, else :data:`~corrugate.names.DEFAULT_MACHINE` when it has none or
    ``"none"``) and the fold operations given, else the spec's (docs/fabrication.md, "What the
    solve asks of the making")."""
    from corrugate.spec.schema import with_machine

    spec = with_machine(spec, cutter)
    fab = spec.fabrication
    machine = DEFAULT_MACHINE if fab.machine in (None, "none") else fab.machine
    assert machine is not None
    return MadeFor(
        spec,
        machine,
        fab.mountain if mountain is None else mountain,
        fab.valley if valley is None else valley,
        fab.marks if marks is None else marks,
    )


def output_options(
    cutter: str | Machine = DEFAULT_MACHINE,
    fold_style: str = DEFAULT_FOLD_STYLE,
    cut: str | float | None = None,
    gap: str | float | None = None,
    spacing: str | float = DEFAULT_SPACING_MM,
    margin: str | float = DEFAULT_MARGIN_MM,
    tab_depth: str | float = DEFAULT_TAB_DEPTH_MM,
    labels: bool | None = None,
    paper: str = DEFAULT_PAPER,
    *,
    mountain: str | None = None,
    valley: str | None = None,
    marks: str | None = None,
    names: Mapping[str, str] | None = None,
) -> OutputOptions:
    """Output options from user strings (plain numbers in mm, or with units: ``'0.04 in'``).

    ``cutter`` is the machine (``cameo4-12x12``, ``maker-12x24``, ``laser:WxH``, ...; or its
    profile, :class:`~corrugate.export.machines.Machine`, when already resolved), ``labels``
    the ``--labels/--no-labels`` flag (``None`` when not given), ``paper`` is ``mat``, ``a4`` or
    ``letter`` (see :class:`~corrugate.export.plan.OutputOptions`). ``fold_style`` (``machine``:
    the machine's default) and ``mountain``, ``valley``, ``marks`` (``cut-score``, ``perforate``,
    ``score``, ``pen``, ``none``; None: the style's) choose the cut files' fold operations
    (:func:`corrugate.export.operations.fold_operations`, resolved for the design's material when
    its files are written; checked here against a generic sheet). A bad value raises an
    :class:`InputError` naming ``cutter``, ``fold-line style``, ``cut``, ``gap``, ``mountain``,
    ``valley``, ``marks``, ``spacing``, ``margin``, ``tab-depth`` or ``paper``; ``names`` maps those to the caller's own names
    (the web app's ``fold_style``, ``tab_depth``). Without the ``fab`` extra it raises
    :class:`~corrugate.core.errors.MissingExtraError` first.
    """
    from corrugate.core.extras import require_extra

    require_extra("fab", "writing a design's files")  # before any work (or input check) is done
    from corrugate.core.units import parse_quantity
    from corrugate.export.machines import get_machine
    from corrugate.export.operations import FoldChoice
    from corrugate.export.pdf import check_paper
    from corrugate.export.plan import OutputOptions
    from corrugate.fabrication.linestyle import SOLID, StyleKind, line_style
    from corrugate.geometry.fabrication_options import FabricationOptions

    def length(value: str | float | None, field: str) -> float | None:
        return None if value is None else parse_quantity(value, "mm", field)

    try:
        machine = get_machine(cutter)  # an unknown machine is an error before anything else
        cut_mm, gap_mm = length(cut, "cut"), length(gap, "gap")
        if fold_style.strip().lower() == StyleKind.PERFORATED:
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
        machine_default = fold_style.strip().lower() == "machine"
        style = SOLID if machine_default else line_style(fold_style, cut_mm, gap_mm)
        choice = FoldChoice(
            "machine" if machine_default else style.kind.value,
            mountain,
            valley,
            marks,
            cut_mm,
            gap_mm,
        )
        choice.resolve(machine)  # an unknown or impossible operation: an error before solving
        return OutputOptions(
            machine=machine,
            style=style,
            operations=None if choice == FoldChoice() else choice,
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


def write_design_files(
    analysis: Analysis,
    out_dir: str | Path,
    options: OutputOptions | None = None,
    extra: dict[str, Any] | None = None,
    report: str | Callable[[CutPlan], str] | None = None,
) -> list[Path]:
    """Write every file of the analysed design into ``out_dir``; returns the paths written.

    ``extra`` is merged into ``design.json`` (the design command puts its spec and constraints
    there); ``report`` is the text of ``report.html`` (see :mod:`corrugate.report`), or a function
    that makes it from the :class:`CutPlan` the cut files are written from, or None.
    """
    return prepare_design_files(analysis, out_dir, options, extra, report)()


def prepare_design_files(
    analysis: Analysis,
    out_dir: str | Path,
    options: OutputOptions | None = None,
    extra: dict[str, Any] | None = None,
    report: str | Callable[[CutPlan], str] | None = None,
) -> Callable[[], list[Path]]:
    """What :func:`write_design_files` does in two parts: this one makes the parts and their
    sheet plan (:func:`corrugate.export.plan.cut_plan`: a part too large for the machine, or an
    impossible perforation, is its error) and the content of ``design.json`` but the list of
    files; the function it returns writes the files (the slow part: the figures, the PDF, the
    cut files; issue 39) and returns their paths. ``corrugate design`` prints its answer between
    the two."""
    from dataclasses import replace

    from corrugate.core.fileio import staged
    from corrugate.export.files import plan_job
    from corrugate.export.plan import OutputOptions, cut_plan
    from corrugate.export.record import VERIFY_KIND
    from corrugate.export.writers import WRITERS, write_job

    opts = options or OutputOptions()
    a = analysis.assembly
    out = Path(out_dir)
    cut = cut_plan(a, opts)
    pattern, plan = cut.pattern, cut.plan
    record: dict[str, Any] = dict(analysis.to_dict())
    # every property of each layer's material, so that the record reads back without the
    # library (an inline material; export.record reads them)
    record["layers"] = [
        {**entry, "material_properties": layer.material.as_dict()}
        for entry, layer in zip(record["layers"], a.layers, strict=True)
    ]
    record["cut_parts"] = [
        {
            "name": p.name,
            "kind": p.kind,
            "label": p.label,
            "size_mm": list(p.size),
            "area_mm2": p.area,
            "mass_g": pattern.part_mass(p),
        }
        for p in pattern.parts
    ]
    machine = opts.machine
    record["sheets"] = {
        "cutter": plan.cutter.name,
        "machine": machine.family.value,
        "cut_file_formats": list(machine.formats),
        "labels_in_cut_files": opts.labels is True,
        "size_mm": [plan.cutter.width, plan.cutter.height],
        "count": len(plan.sheets),
        "parts": [[pl.part.name for pl in sheet.placements] for sheet in plan.sheets],
    }
    record["fold_style"] = {
        "kind": str(opts.style.kind),
        "cut_mm": opts.style.cut,
        "gap_mm": opts.style.gap,
    }
    record["fold_operations"] = {**cut.operations.as_dict(), "layers": _layer_names(cut)}
    if extra:
        record.update(extra)
    drawn = cut.drawings

    def report_text() -> str | None:
        # written after the fold maps and the assembly steps, from what they drew (Drawings)
        return report(cut) if callable(report) else report

    def write() -> list[Path]:
        # one set: the old files or the new ones (fileio); a verification of another
        # design.json, or one that did not record which (an earlier version's), leaves in the
        # same commit
        with staged(out, kind="design", supersedes=(VERIFY_KIND,)) as st:
            job = replace(
                plan_job(
                    plan,
                    out,
                    opts.style,
                    machine=machine,
                    operations=cut.operations,
                    labels=opts.labels,
                    paper=opts.paper,
                ),
                assembly=a,
                pattern=pattern,
                drawings=drawn,
                report=report_text,
                record=record,
            )
            # every entry of the writers registry, in its order; nothing is committed before
            # the last
            return write_job(job, WRITERS, st)

    return write


def _layer_names(cut: CutPlan) -> dict[str, str]:
    """The cut files' layer of each kind of line (``mountain`` -> ``MOUNTAIN-PERFORATE``, ...;
    a kind made by ``none`` is in no cut file)."""
    from corrugate.export.machines import layer_name

    ops = cut.operations
    out = {"cut": "CUT"}
    for kind in ("mountain", "valley", "marks"):
        op = getattr(ops, kind)
        if op.value != "none":
            out[kind] = layer_name(kind, op.value)
    return out


def write_design(
    run: DesignRun, out: str | Path, options: OutputOptions, spec_text: str
) -> list[Path]:
    """Write the files of a solved spec into ``out`` (created if missing), all or nothing; returns
    the paths written. ``spec_text`` is the spec as the user wrote it (shown in the report).

    A design gets every file of :func:`write_design_files`, with the design
    answer merged into ``design.json``; an infeasible spec gets ``design.json`` only."""
    return prepare_design(run, out, options, spec_text)()


def prepare_design(
    run: DesignRun, out: str | Path, options: OutputOptions, spec_text: str
) -> Callable[[], list[Path]]:
    """:func:`write_design` in two parts (:func:`prepare_design_files`): the sheet plan and
    ``design.json``'s content now, its errors (a part too large, a perforation) raised here; the
    function returned writes the files and returns their paths."""
    from corrugate.export.record import write_record

    sol = run.solution
    analysis = sol.analysis
    if analysis is None:
        return lambda: [write_record(run.payload, out)]

    def report(cut: CutPlan) -> str:
        from corrugate.report import report_html

        return report_html(sol, spec_text, cut)

    write = prepare_design_files(analysis, out, options, extra=run.payload, report=report)

    def locked() -> list[Path]:
        with _FILES_LOCK:  # the report draws the very sheet plan the cut files are written from
            return write()

    return locked
