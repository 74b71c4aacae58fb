"""The cut plan of one design: the options of its output files (:class:`OutputOptions`), its parts
laid out on the cutter's sheets (:class:`CutPlan`, made once by :func:`cut_plan`) and the figures
drawn of them (:class:`Drawings`), so that the cut files, ``pattern.pdf`` and the report show the
very same sheets (the report embeds the fold maps themselves). Lengths in mm.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from corrugate.export.machines import Machine, get_machine
from corrugate.export.operations import FoldChoice, FoldOperations, check_operations
from corrugate.export.pdf import check_paper
from corrugate.fabrication.build import build_pattern
from corrugate.fabrication.linestyle import SOLID, LineStyle, check_style
from corrugate.fabrication.model import Pattern
from corrugate.fabrication.sheets import SheetPlan, plan_sheets
from corrugate.geometry.fabrication_options import DEFAULT_FABRICATION, FabricationOptions
from corrugate.geometry.layer import Assembly
from corrugate.names import DEFAULT_MARGIN_MM, DEFAULT_PAPER, DEFAULT_SPACING_MM

__all__ = ["CutPlan", "Drawings", "OutputOptions", "cut_plan"]


@dataclass(frozen=True, slots=True)
class OutputOptions:
    """Where and how to cut: the ``machine`` (its profile, :func:`corrugate.export.machines.get_machine`
    of a name of :data:`corrugate.fabrication.sheets.CUTTERS` or ``laser:WxH`` in mm; default
    :data:`~corrugate.names.DEFAULT_MACHINE`), fold-line ``style`` (the fold map and the
    PDF), the cut files' fold ``operations`` (None: the machine's default for the material,
    :func:`corrugate.export.operations.default_operations`), spacing and margin on the sheet
    (mm), connector sizes, and ``labels`` (``None``: on the fold map and the PDF, not in the cut
    files; ``True``: in the cut files too; ``False``: nowhere),
    and ``paper``: ``mat`` (``pattern.pdf`` only) or ``a4`` / ``letter`` (also the 1:1 tiles,
    ``pattern-a4.pdf`` / ``pattern-letter.pdf``)."""

    machine: Machine = field(default_factory=get_machine)
    style: LineStyle = SOLID
    operations: FoldOperations | FoldChoice | None = None
    spacing: float = DEFAULT_SPACING_MM
    margin: float = DEFAULT_MARGIN_MM
    fabrication: FabricationOptions = field(default_factory=lambda: DEFAULT_FABRICATION)
    labels: bool | None = None
    paper: str = DEFAULT_PAPER

    @property
    def cutter(self) -> str:
        """The machine's name (``cameo4-12x12``, ``laser:600x400``, ...)."""
        return self.machine.name


@dataclass(slots=True)
class Drawings:
    """What the files step drew, for the report to show instead of drawing it again:
    ``fold_maps``, the SVG texts of ``sheet-N.svg`` (one per sheet, empty before they are made)
    and ``assembly_png``, the bytes of ``assembly.png`` (None before)."""

    fold_maps: list[str] = field(default_factory=list)
    assembly_png: bytes | None = None


@dataclass(frozen=True, slots=True)
class CutPlan:
    """What one design's cut files are written from: the parts (``pattern``, mm), their
    arrangement on the cutter's sheets (``plan``), the fold-line ``style`` and the cut files' fold
    ``operations``; ``drawings`` collects what :func:`write_design_files` drew of them."""

    pattern: Pattern
    plan: SheetPlan
    style: LineStyle
    operations: FoldOperations = field(default_factory=FoldOperations)
    drawings: Drawings = field(default_factory=Drawings, compare=False)


def cut_plan(assembly: Assembly, options: OutputOptions | None = None) -> CutPlan:
    """Build the parts of ``assembly`` with ``options``' connector sizes and lay them out on its
    cutter's sheets; raises :class:`~corrugate.core.errors.InputError` subclasses for a bad option (an
    unknown cutter or paper, a part larger than the sheet, a perforation that does not fit)."""
    opts = options or OutputOptions()
    check_paper(opts.paper)
    pattern = build_pattern(assembly, opts.fabrication)
    plan = plan_sheets(pattern, opts.machine.cutter, spacing=opts.spacing, margin=opts.margin)
    check_style(pattern.parts, opts.style)
    ops = opts.operations
    if not isinstance(ops, FoldOperations):
        ops = (ops or FoldChoice()).resolve(opts.machine, pattern.material_id)
    check_operations(pattern.parts, ops)
    return CutPlan(pattern, plan, opts.style, ops)
