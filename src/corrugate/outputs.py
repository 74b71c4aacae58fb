"""Design -> every file a maker needs, written all or nothing into one folder.

``sheet-N.svg`` (the fold map, for people and Origami Simulator), ``cut-N.dxf`` / ``cut-N.svg``
(the cut-ready files of the machine: DXF for a Silhouette, SVG for a Cricut, both for a laser),
``pattern.pdf`` (the parts laid out on the machine's sheets, :mod:`corrugate.export.files`; with
``paper`` a4 or letter also ``pattern-a4.pdf`` / ``pattern-letter.pdf``, the sheets on 1:1 tiles),
``layer1.fold`` / ``layer2.fold`` (FOLD 1.2 with the folded frame), ``assembly.glb`` /
``assembly.stl`` (the folded part), ``ASSEMBLY.md`` + ``assembly.png`` (numbered steps and a figure),
``report.html`` (from ``corrugate design``) and ``design.json`` (:mod:`corrugate.record`: the analysis, the sheets, and the mass of the cut
parts). Every option is
checked and every document built before anything is written; the files are then committed
together as one set (:mod:`corrugate.fileio`), so a bad option, a failure or a kill leaves either the
folder's earlier set or the new one, never a mix.

The parts and their sheet plan are made once (:func:`cut_plan`); the report gets that very
:class:`CutPlan` (``report`` may be a function of it), so its sheet figures are the cut files'.
Each figure is drawn once: the report is made after the files, from the sheet figures of
``pattern.pdf`` and the PNG bytes of ``assembly.png`` (:class:`Drawings`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from .analysis import Analysis
from .export.files import write_files
from .export.machines import DEFAULT_MACHINE, get_machine
from .export.pdf import check_paper, sheet_figure
from .fileio import staged
from .geometry import Assembly
from .pattern.build import build_pattern
from .pattern.files3d import write_fold, write_mesh
from .pattern.instructions import instructions_png, write_instructions
from .pattern.linestyle import SOLID, LineStyle, check_style
from .pattern.model import Pattern
from .pattern.options import DEFAULT_FABRICATION, FabricationOptions
from .pattern.sheets import SheetPlan, plan_sheets
from .record import RECORD_NAME, write_record

__all__ = ["CutPlan", "Drawings", "OutputOptions", "cut_plan", "write_design_files"]


@dataclass(frozen=True, slots=True)
class OutputOptions:
    """Where and how to cut: the machine (``cutter``: a name of
    :data:`corrugate.pattern.sheets.CUTTERS` or ``laser:WxH`` in mm; its profile is
    :func:`corrugate.export.machines.get_machine`), fold-line style, spacing and margin on the sheet
    (mm), connector sizes, and ``labels`` (``None``: on the fold map and the PDF, not in the cut
    files; ``True``: in the cut files too; ``False``: nowhere),
    and ``paper``: ``mat`` (``pattern.pdf`` only) or ``a4`` / ``letter`` (also the 1:1 tiles,
    ``pattern-a4.pdf`` / ``pattern-letter.pdf``)."""

    cutter: str = DEFAULT_MACHINE
    style: LineStyle = SOLID
    spacing: float = 5.0
    margin: float = 5.0
    fabrication: FabricationOptions = field(default_factory=lambda: DEFAULT_FABRICATION)
    labels: bool | None = None
    paper: str = "mat"


@dataclass(slots=True)
class Drawings:
    """Figures the files step drew, for the report to show instead of drawing them again:
    ``sheets``, the matplotlib figures of ``pattern.pdf`` (one per sheet, labels on, empty when
    none were drawn so) and ``assembly_png``, the bytes of ``assembly.png`` (None before)."""

    sheets: list[Any] = field(default_factory=list)
    assembly_png: bytes | None = None


@dataclass(frozen=True, slots=True)
class CutPlan:
    """What one design's cut files are written from: the parts (``pattern``, mm), their
    arrangement on the cutter's sheets (``plan``) and the fold-line ``style``; ``drawings``
    collects what :func:`write_design_files` drew of them."""

    pattern: Pattern
    plan: SheetPlan
    style: LineStyle
    drawings: Drawings = field(default_factory=Drawings, compare=False)


def cut_plan(assembly: Assembly, options: OutputOptions | None = None) -> CutPlan:
    """Build the parts of ``assembly`` with ``options``' connector sizes and lay them out on its
    cutter's sheets; raises :class:`~corrugate.errors.InputError` subclasses for a bad option (an
    unknown cutter or paper, a part larger than the sheet, a perforation that does not fit)."""
    opts = options or OutputOptions()
    check_paper(opts.paper)
    pattern = build_pattern(assembly, opts.fabrication)
    plan = plan_sheets(pattern, opts.cutter, spacing=opts.spacing, margin=opts.margin)
    check_style(pattern.parts, opts.style)
    return CutPlan(pattern, plan, opts.style)


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
    opts = options or OutputOptions()
    a = analysis.assembly
    out = Path(out_dir)
    cut = cut_plan(a, opts)
    pattern, plan = cut.pattern, cut.plan
    record: dict[str, Any] = dict(analysis.to_dict())
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
    machine = get_machine(plan.cutter)
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
    if extra:
        record.update(extra)
    drawn = cut.drawings
    if opts.labels is not False:  # pattern.pdf shows the labels, as the report's sheets do
        drawn.sheets = [sheet_figure(plan, k, opts.style) for k in range(1, len(plan.sheets) + 1)]
    with staged(out, kind="design") as st:  # one set: the old files or the new ones, never a mix
        written = list(
            write_files(
                plan,
                out,
                opts.style,
                labels=opts.labels,
                paper=opts.paper,
                staging=st,
                sheet_figures=drawn.sheets or None,
            )
        )
        written += write_fold(a, pattern, out, st)
        written += write_mesh(a, pattern, out, st)
        drawn.assembly_png = instructions_png(a, pattern)
        written += write_instructions(a, pattern, out, st, png=drawn.assembly_png)
        # the report last, from the figures drawn above; nothing is committed before it is made
        report_text = report(cut) if callable(report) else report
        if report_text is not None:
            st.path(out / "report.html").write_text(report_text, encoding="utf-8")
            written.append(out / "report.html")
        record["files"] = [p.name for p in written] + [RECORD_NAME]
        written.append(write_record(record, out, st))
    return written
